/* Welding a block's vertices into the map. Exact mode: a vertex whose
 * position equals a live map vertex's (bitwise, -0.0 == 0.0; never a NaN
 * or infinity) becomes that vertex, else the block's first vertex at that
 * position makes a new one, as mt_face_list_weld(list, 0) does to the
 * union. Eps mode: the lowest-numbered live map vertex within eps (cells of
 * side eps, 27 searched, the distance test of mt_face_list_weld), else the
 * lowest-numbered new vertex of the block within eps, else a new one. None
 * mode: the sender's ids, with one position per id. Also gathers the
 * touched vertices of the operation and whether each lives on. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "map/map_internal.h"

/* The bits of a coordinate with -0.0 read as 0.0. */
static uint64_t coord_bits(double x)
{
    uint64_t bits;
    if (x == 0.0) x = 0.0;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

uint32_t mt__pos_hash(const double *p)
{
    uint64_t h = coord_bits(p[0]) * 0x9e3779b97f4a7c15ull;
    h = (h ^ coord_bits(p[1])) * 0xc2b2ae3d27d4eb4full;
    h = (h ^ coord_bits(p[2])) * 0x165667b19e3779f9ull;
    return (uint32_t)mt__mix64(h);
}

bool mt__pos_equal(const double *a, const double *b)
{
    return coord_bits(a[0]) == coord_bits(b[0]) && coord_bits(a[1]) == coord_bits(b[1]) &&
           coord_bits(a[2]) == coord_bits(b[2]);
}

bool mt__pos_finite(const double *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

/* ---- eps mode: cells of side eps ---- */

/* Cells past this many sides from the origin are clamped (as
 * mt_face_list_weld does): points that far share a clamped cell or lie in
 * neighbouring ones, so no pair within eps is missed. */
#define CELL_LIMIT 4611686018427387904.0 /* 2^62 */

static void cell_of(const double *p, double eps, int64_t *c)
{
    for (int k = 0; k < 3; k++) {
        double x = floor(p[k] / eps);
        if (x > CELL_LIMIT) x = CELL_LIMIT;
        if (x < -CELL_LIMIT) x = -CELL_LIMIT;
        c[k] = (int64_t)x;
    }
}

static uint32_t cell_hash(const int64_t *c)
{
    uint64_t h = (uint64_t)c[0] * 0x9e3779b97f4a7c15ull;
    h = (h ^ (uint64_t)c[1]) * 0xc2b2ae3d27d4eb4full;
    h = (h ^ (uint64_t)c[2]) * 0x165667b19e3779f9ull;
    return (uint32_t)mt__mix64(h);
}

static uint32_t pos_cell_hash(const double *p, double eps)
{
    int64_t c[3];
    cell_of(p, eps, c);
    return cell_hash(c);
}

/* Whether p and q are within eps, scaled so that neither overflow nor
 * underflow of the squares decides: mt_face_list_weld's test, bit for bit. */
static bool within(const double *p, const double *q, double eps)
{
    double d[3], m = 0;
    for (int k = 0; k < 3; k++) {
        d[k] = fabs(p[k] - q[k]);
        if (d[k] > m) m = d[k];
    }
    if (m > eps) return false;
    if (m == 0) return true;
    double s = 0;
    for (int k = 0; k < 3; k++) s += (d[k] / m) * (d[k] / m);
    return m * sqrt(s) <= eps;
}

typedef struct near_search {
    const double *x; /* the vertex welded */
    double eps;
    const double *positions; /* of the table's entries */
    const uint32_t *ids;     /* entry -> map id; NULL: entries are map ids */
    int64_t cell[3];         /* the cell scanned */
    uint32_t best;           /* lowest map id within eps so far */
} near_search;

static void near_visit(void *arg, uint32_t e)
{
    near_search *s = arg;
    const double *q = s->positions + 3 * (size_t)e;
    int64_t c[3];
    cell_of(q, s->eps, c);
    if (c[0] != s->cell[0] || c[1] != s->cell[1] || c[2] != s->cell[2]) return;
    const uint32_t id = s->ids ? s->ids[e] : e;
    if (id < s->best && within(s->x, q, s->eps)) s->best = id;
}

/* The lowest map id among the table's entries within eps of x (the 27
 * cells around x's), MT_NONE when none is. */
static uint32_t find_near(const mt__table *t, const double *positions, const uint32_t *ids,
                          const double *x, double eps)
{
    near_search s = {x, eps, positions, ids, {0, 0, 0}, MT_NONE};
    int64_t c[3];
    cell_of(x, eps, c);
    const int64_t lim = (int64_t)CELL_LIMIT;
    for (int dx = -1; dx <= 1; dx++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dz = -1; dz <= 1; dz++) {
                s.cell[0] = c[0] + dx;
                s.cell[1] = c[1] + dy;
                s.cell[2] = c[2] + dz;
                /* a clamped cell has no neighbour past the limit */
                if (s.cell[0] > lim || s.cell[0] < -lim || s.cell[1] > lim || s.cell[1] < -lim ||
                    s.cell[2] > lim || s.cell[2] < -lim)
                    continue;
                mt__table_scan(t, cell_hash(s.cell), near_visit, &s);
            }
    return s.best;
}

uint32_t mt__weld_entry_hash(const void *ctx, uint32_t vert)
{
    const mt_map *map = ctx;
    const double *p = &map->pos[3 * (size_t)vert];
    return map->weld == MT_MAP_WELD_EPS ? pos_cell_hash(p, map->eps) : mt__pos_hash(p);
}

static bool weld_entry_eq(const void *map, uint32_t vert, const void *key)
{
    return mt__pos_equal(&((const mt_map *)map)->pos[3 * (size_t)vert], key);
}

/* The scratch table of the block's own new positions: entries are block
 * vertices, ctx the block's positions. */
static uint32_t local_hash(const void *positions, uint32_t local)
{
    return mt__pos_hash((const double *)positions + 3 * (size_t)local);
}

static bool local_eq(const void *positions, uint32_t local, const void *key)
{
    return mt__pos_equal((const double *)positions + 3 * (size_t)local, key);
}

/* Enters v in the touched vertices (the table has room for every vertex
 * of both versions) with a role; returns its touched index. */
static uint32_t touch(mt__map_plan *p, uint32_t v, uint8_t role)
{
    bool added;
    uint32_t t = mt__keymap_put(&p->tv, v, &added);
    if (added) {
        const mt_map *map = p->map;
        p->tv_vert[t] = v;
        p->tv_pos[t] = MT_NONE;
        p->tv_old[t] = v < map->vert_end ? map->vert_flags[v] : 0;
        p->tv_new[t] = 0;
        p->tv_role[t] = 0;
        p->num_tv = t + 1;
    }
    p->tv_role[t] |= role;
    return t;
}

/* Exact and eps modes: the new block's map vertices (new ones numbered
 * from vert_end in block order). */
static mt_status weld_exact(mt__map_plan *p)
{
    mt_map *map = p->map;
    mt__map_block *b = p->block;
    const double *pos = p->input->positions;
    mt__table fresh = {NULL, 0, 0};
    if (mt__table_reserve(&fresh, b->num_verts, local_hash, pos) != MT_OK) return MT_ERR_NOMEM;
    uint32_t next = map->vert_end;
    const bool eps = map->weld == MT_MAP_WELD_EPS;
    for (uint32_t u = 0; u < b->num_verts; u++) {
        const double *x = pos + 3 * (size_t)u;
        uint32_t v = MT_NONE;
        if (eps && mt__pos_finite(x)) {
            /* Live map vertices have lower ids than the block's new ones. */
            v = find_near(&map->weld_table, map->pos, NULL, x, map->eps);
            if (v == MT_NONE) v = find_near(&fresh, pos, b->vert_map, x, map->eps);
            if (v == MT_NONE) mt__table_insert(&fresh, pos_cell_hash(x, map->eps), u);
        } else if (mt__pos_finite(x)) {
            const uint32_t h = mt__pos_hash(x);
            v = mt__table_find(&map->weld_table, h, weld_entry_eq, map, x);
            if (v == MT_NONE) {
                const uint32_t first = mt__table_find(&fresh, h, local_eq, pos, x);
                if (first != MT_NONE) {
                    v = b->vert_map[first];
                } else {
                    mt__table_insert(&fresh, h, u);
                }
            }
        }
        if (v == MT_NONE) {
            if (next >= MT_MAP_MAX_VERT_ID) {
                mt__table_free(&fresh);
                return mt__fail(p->diag, MT_ERR_TOO_LARGE, u,
                                MT__KEY_FMT ": the map has used all %u vertex ids; compact it",
                                MT__KEY_ARGS(p->key), MT_MAP_MAX_VERT_ID);
            }
            v = next++;
        }
        b->vert_map[u] = v;
        const uint32_t t = touch(p, v, MT__R_IN_NEW);
        if (v >= map->vert_end && p->tv_pos[t] == MT_NONE) p->tv_pos[t] = u;
    }
    mt__table_free(&fresh);
    p->new_vert_end = next;
    return MT_OK;
}

static mt_status refuse_position(mt__map_plan *p, uint32_t u, uint32_t v, const double *a,
                                 const double *b, const char *other)
{
    return mt__fail(p->diag, MT_ERR_INVALID_ARG, u,
                    MT__KEY_FMT
                    ": vertex %u gives map vertex %u the position (%.17g, %.17g, %.17g)"
                    " but %s has (%.17g, %.17g, %.17g)",
                    MT__KEY_ARGS(p->key), u, v, a[0], a[1], a[2], other, b[0], b[1], b[2]);
}

/* None mode: the sender's ids; one position per id. */
static mt_status weld_none(mt__map_plan *p)
{
    mt_map *map = p->map;
    mt__map_block *b = p->block;
    const double *pos = p->input->positions;
    uint32_t end = map->vert_end;
    for (uint32_t u = 0; u < b->num_verts; u++) {
        const uint32_t v = p->vertex_ids[u];
        if (v >= MT_MAP_MAX_VERT_ID)
            return mt__fail(p->diag, MT_ERR_TOO_LARGE, u,
                            MT__KEY_FMT ": vertex %u has map id %u; ids must be below %u",
                            MT__KEY_ARGS(p->key), u, v, MT_MAP_MAX_VERT_ID);
        const uint32_t t = touch(p, v, MT__R_IN_NEW);
        if (p->tv_pos[t] == MT_NONE) {
            p->tv_pos[t] = u;
        } else {
            const uint32_t w = p->tv_pos[t];
            if (!mt__pos_equal(pos + 3 * (size_t)u, pos + 3 * (size_t)w)) {
                char other[48];
                snprintf(other, sizeof other, "its vertex %u", w);
                return refuse_position(p, u, v, pos + 3 * (size_t)u, pos + 3 * (size_t)w, other);
            }
        }
        b->vert_map[u] = v;
        if (v >= end) end = v + 1;
    }
    p->new_vert_end = end;
    return MT_OK;
}

/* Whether live vertex v has an origin outside the old version (walks its
 * ring once). */
static bool has_outside_origin(const mt__map_plan *p, uint32_t v)
{
    const mt_map *map = p->map;
    const uint64_t start = map->vert_origin[v];
    uint64_t e = start;
    do {
        const uint32_t slot = (uint32_t)(e >> 32);
        if (slot != p->old_slot) return true;
        e = map->blocks[slot]->ring_next[(uint32_t)e];
    } while (e != start);
    return false;
}

mt_status mt__plan_verts(mt__map_plan *p)
{
    mt_map *map = p->map;
    const uint32_t n_old = p->old ? p->old->num_verts : 0;
    const uint32_t n_new = p->block ? p->block->num_verts : 0;
    const uint32_t max = n_old + n_new;
    if (mt__keymap_init(&p->tv, max) != MT_OK) return MT_ERR_NOMEM;
    p->tv_vert = mt__malloc((size_t)(max ? max : 1) * sizeof(uint32_t));
    p->tv_pos = mt__malloc((size_t)(max ? max : 1) * sizeof(uint32_t));
    p->tv_old = mt__malloc(max ? max : 1);
    p->tv_new = mt__malloc(max ? max : 1);
    p->tv_role = mt__malloc(max ? max : 1);
    if (!p->tv_vert || !p->tv_pos || !p->tv_old || !p->tv_new || !p->tv_role) return MT_ERR_NOMEM;
    for (uint32_t u = 0; u < n_old; u++) touch(p, p->old->vert_map[u], MT__R_IN_OLD);
    p->new_vert_end = map->vert_end;
    if (p->block) {
        mt_status s = map->weld == MT_MAP_WELD_NONE ? weld_none(p) : weld_exact(p);
        if (s != MT_OK) return s;
    }
    const double *pos = p->input ? p->input->positions : NULL;
    for (uint32_t t = 0; t < p->num_tv; t++) {
        const uint32_t v = p->tv_vert[t];
        if (!(p->tv_old[t] & MT__V_ALIVE)) continue;
        if (!(p->tv_role[t] & MT__R_IN_OLD) || has_outside_origin(p, v))
            p->tv_role[t] |= MT__R_OUTSIDE;
        if (map->weld != MT_MAP_WELD_NONE || !(p->tv_role[t] & MT__R_IN_NEW)) continue;
        /* None mode: a vertex another block holds keeps its position; one
         * only the old version held takes the new one. */
        const uint32_t u = p->tv_pos[t];
        const double *mine = pos + 3 * (size_t)u, *theirs = &map->pos[3 * (size_t)v];
        if (!(p->tv_role[t] & MT__R_OUTSIDE)) continue;
        if (!mt__pos_equal(mine, theirs))
            return refuse_position(p, u, v, mine, theirs, "another block");
        p->tv_pos[t] = MT_NONE;
    }
    return MT_OK;
}
