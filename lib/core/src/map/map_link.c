/* The walk of an operation: each touched vertex's face list is read once.
 * It gives the vertex's status after the change (alive, in some record, in
 * some valid face, and from its link, as report_links.c judges it:
 * non-manifold unless one simple path or cycle, a bowtie when disconnected)
 * and feeds the edges' and cycles' counts before the change. Nothing else
 * of the map is read, so an update costs the touched vertices' valences. */
#include <stdlib.h>
#include <string.h>

#include "map/map_internal.h"

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

static uint32_t uf_find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

/* Index of v among the sorted nodes (it is there). */
static uint32_t node_of(const uint32_t *nodes, uint32_t n, uint32_t v)
{
    uint32_t lo = 0, hi = n;
    while (hi - lo > 8) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (nodes[mid] <= v)
            lo = mid;
        else
            hi = mid;
    }
    while (nodes[lo] != v) lo++;
    return lo;
}

/* Sorts a few uint32 in place (insertion sort below 17, else qsort). */
static void sort_u32(uint32_t *a, uint32_t n)
{
    if (n > 16) {
        qsort(a, n, sizeof *a, compare_u32);
        return;
    }
    for (uint32_t i = 1; i < n; i++) {
        const uint32_t x = a[i];
        uint32_t j = i;
        while (j > 0 && a[j - 1] > x) a[j] = a[j - 1], j--;
        a[j] = x;
    }
}

/* Status flags from the link edges (pairs in link[0 .. 2n)). */
static mt_status link_flags(mt__map_plan *p, uint8_t *out_flags)
{
    const uint32_t *pairs = p->link.data;
    const uint32_t n = (uint32_t)(p->link.len / 2);
    *out_flags = 0;
    if (n == 0) return MT_OK;
    if (mt__map_vec_reserve(&p->link_scratch, 6 * (size_t)n) != MT_OK) return MT_ERR_NOMEM;
    uint32_t *nodes = p->link_scratch.data, *degree = nodes + 2 * n, *parent = nodes + 4 * n;
    memcpy(nodes, pairs, 2 * (size_t)n * sizeof *nodes);
    sort_u32(nodes, 2 * n);
    uint32_t unique = 0;
    for (uint32_t i = 0; i < 2 * n; i++)
        if (unique == 0 || nodes[unique - 1] != nodes[i]) nodes[unique++] = nodes[i];
    for (uint32_t i = 0; i < unique; i++) degree[i] = 0, parent[i] = i;
    bool high = false;
    uint32_t parts = unique;
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t a = node_of(nodes, unique, pairs[2 * i]),
                       b = node_of(nodes, unique, pairs[2 * i + 1]);
        if (++degree[a] > 2 || ++degree[b] > 2) high = true;
        const uint32_t ra = uf_find(parent, a), rb = uf_find(parent, b);
        if (ra != rb) {
            parent[ra > rb ? ra : rb] = ra < rb ? ra : rb;
            parts--;
        }
    }
    if (parts > 1 || high) *out_flags |= MT__V_NONMANIFOLD;
    if (parts > 1) *out_flags |= MT__V_BOWTIE;
    return MT_OK;
}

/* Adds the link edge of a valid face at corner `at` (corners c[0..n)). */
static mt_status push_link(mt__map_plan *p, const uint32_t *c, uint32_t n, uint32_t at)
{
    mt__vec *link = &p->link;
    if (link->len + 2 > link->cap &&
        mt__map_vec_reserve(link, link->cap ? 2 * link->cap : 64) != MT_OK)
        return MT_ERR_NOMEM;
    uint32_t *pq = (uint32_t *)link->data + link->len;
    pq[0] = c[at ? at - 1 : n - 1];
    pq[1] = c[at + 1 < n ? at + 1 : 0];
    link->len += 2;
    return MT_OK;
}

static void add_contribution(mt__tally *t, uint8_t flags, int64_t sign)
{
    const bool alive = flags & MT__V_ALIVE;
    t->n[MT__T_VERTS] += sign * alive;
    t->n[MT__T_ISOLATED] += sign * (alive && !(flags & MT__V_VALID));
    t->n[MT__T_UNREFERENCED] += sign * (alive && !(flags & MT__V_ANY));
    t->n[MT__T_NM_VERTS] += sign * !!(flags & MT__V_NONMANIFOLD);
    t->n[MT__T_BOWTIE] += sign * !!(flags & MT__V_BOWTIE);
    t->n[MT__T_NONFINITE] += sign * (alive && (flags & MT__V_NONFINITE));
}

/* Walks vertex t's list (the state before) and the new block's faces at it. */
static mt_status walk_vertex(mt__map_plan *p, uint32_t t)
{
    const mt_map *map = p->map;
    const uint32_t v = p->tv_vert[t];
    uint8_t role = p->tv_role[t], flags = 0;
    p->link.len = 0;
    if (p->tv_old[t] & MT__V_ALIVE) {
        for (uint32_t f = map->vert_head[v]; f != MT_NONE;) {
            const mt__map_block *b;
            uint32_t local;
            const uint32_t c = mt__map_corner_of(map, f, v, &b, &local);
            const uint32_t c0 = mt__blk_begin(b, local), n = mt__blk_size(b, local);
            const bool valid = map->face_local[f] & MT__MAP_VALID;
            if (valid) mt__plan_edges_walk_face(p, v, b->corners + c0, n, c - c0);
            if (map->face_block[f] == p->old_slot) {
                role |= MT__R_OLD_FACES;
            } else {
                flags |= MT__V_ANY;
                if (valid) {
                    flags |= MT__V_VALID;
                    if (push_link(p, b->corners + c0, n, c - c0) != MT_OK) return MT_ERR_NOMEM;
                }
            }
            f = b->corner_next[c];
        }
    }
    if (p->block && (role & MT__R_IN_NEW)) {
        const mt__map_block *b = p->block;
        for (uint32_t i = p->tv_bfirst[t]; i < p->tv_bfirst[t + 1]; i++) {
            const uint32_t face = p->tv_bface[i];
            flags |= MT__V_ANY;
            if (!p->b_valid[face]) continue;
            flags |= MT__V_VALID;
            const uint32_t c0 = mt__blk_begin(b, face), n = mt__blk_size(b, face);
            uint32_t at = 0;
            while (b->corners[c0 + at] != v) at++;
            if (push_link(p, b->corners + c0, n, at) != MT_OK) return MT_ERR_NOMEM;
        }
    }
    p->tv_role[t] = role;
    if (!(role & (MT__R_IN_NEW | MT__R_OUTSIDE))) {
        p->tv_new[t] = 0; /* the vertex goes with the old version */
    } else {
        uint8_t link;
        if (link_flags(p, &link) != MT_OK) return MT_ERR_NOMEM;
        const double *x = p->tv_pos[t] != MT_NONE ? p->input->positions + 3 * (size_t)p->tv_pos[t]
                                                  : &map->pos[3 * (size_t)v];
        p->tv_new[t] = MT__V_ALIVE | flags | link | (mt__pos_finite(x) ? 0 : MT__V_NONFINITE);
    }
    add_contribution(&p->change, p->tv_old[t], -1);
    add_contribution(&p->change, p->tv_new[t], 1);
    return MT_OK;
}

mt_status mt__plan_walk(mt__map_plan *p)
{
    for (uint32_t t = 0; t < p->num_tv; t++)
        if (walk_vertex(p, t) != MT_OK) return MT_ERR_NOMEM;
    return MT_OK;
}
