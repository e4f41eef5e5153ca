/* Report part "links": decides which vertices are non-manifold, by their
 * link (DEFINITIONS.md): each face at v adds the link edge {p, q} between the
 * vertices before and after v. v is manifold when that multigraph is one
 * simple path or cycle; a bowtie when it is disconnected. Only vertices that
 * can fail are examined: those split into several fans and the ends of edge
 * bundles; every other vertex has one fan and no bundled edge, so its link
 * is the fan's own path or cycle. Each component is also judged on the link
 * restricted to its faces. */
#include <stdlib.h>
#include <string.h>

#include "report/report_internal.h"

typedef struct link_edge {
    uint32_t p, q, comp;
} link_edge;

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

static int compare_comp(const void *pa, const void *pb)
{
    const link_edge *a = pa, *b = pb;
    return (a->comp > b->comp) - (a->comp < b->comp);
}

static uint32_t node_index(const uint32_t *nodes, uint32_t n, uint32_t v)
{
    const uint32_t *hit = bsearch(&v, nodes, n, sizeof *nodes, compare_u32);
    return (uint32_t)(hit - nodes);
}

typedef struct link_shape {
    uint32_t parts;  /* connected parts */
    int high_degree; /* some node has degree > 2 */
} link_shape;

/* Shape of the link made of edges[0..n). scratch holds 4 * 2n uint32. */
static link_shape analyze(const link_edge *edges, uint32_t n, uint32_t *scratch)
{
    uint32_t *nodes = scratch, *degree = scratch + 2 * n, *parent = scratch + 4 * n;
    uint32_t num_nodes = 0;
    for (uint32_t i = 0; i < n; i++)
        nodes[num_nodes++] = edges[i].p, nodes[num_nodes++] = edges[i].q;
    qsort(nodes, num_nodes, sizeof *nodes, compare_u32);
    uint32_t unique = 0;
    for (uint32_t i = 0; i < num_nodes; i++)
        if (unique == 0 || nodes[unique - 1] != nodes[i]) nodes[unique++] = nodes[i];
    for (uint32_t i = 0; i < unique; i++) degree[i] = 0, parent[i] = i;
    link_shape shape = {0, 0};
    for (uint32_t i = 0; i < n; i++) {
        uint32_t a = node_index(nodes, unique, edges[i].p),
                 b = node_index(nodes, unique, edges[i].q);
        if (++degree[a] > 2 || ++degree[b] > 2) shape.high_degree = 1;
        mt__uf_union(parent, a, b);
    }
    for (uint32_t i = 0; i < unique; i++) shape.parts += parent[i] == i;
    return shape;
}

/* Link edges of caller vertex v over all its fans. */
static mt_status gather_link(mt__build *b, uint32_t v, mt__vec *edges)
{
    const mt_mesh *m = b->m;
    const uint32_t *copies = NULL;
    uint32_t num_copies = mt__vert_copies(m, v, &copies);
    edges->len = 0;
    for (uint32_t k = 0; k <= num_copies; k++) {
        uint32_t u = k == 0 ? v : copies[k - 1];
        uint32_t start = m->vert_he[u], h = start, steps = 0;
        if (start == MT_NONE) continue;
        do {
            if (m->he_face[h] != MT_NONE) {
                uint32_t prev = mt__he_prev(m, h);
                link_edge e = {mt__original(m, m->he_head[prev ^ 1u]),
                               mt__original(m, m->he_head[h]), b->vert_comp[u]};
                if (mt__vec_push(edges, &e) != MT_OK) return MT_ERR_NOMEM;
            }
            h = m->he_next[h ^ 1u];
        } while (h != start && ++steps < m->num_half_edges);
    }
    return MT_OK;
}

static mt_status examine_vertex(mt__build *b, uint32_t v, mt__vec *edges, mt__vec *scratch)
{
    mt_report *r = &b->m->report;
    if (gather_link(b, v, edges) != MT_OK) return MT_ERR_NOMEM;
    uint32_t n = (uint32_t)edges->len;
    if (n == 0) return MT_OK;
    scratch->len = 0;
    uint32_t zero = 0;
    for (uint32_t i = 0; i < 8 * n; i++)
        if (mt__vec_push(scratch, &zero) != MT_OK) return MT_ERR_NOMEM;
    link_edge *le = edges->data;
    link_shape whole = analyze(le, n, scratch->data);
    if (whole.parts > 1 || whole.high_degree) {
        r->nonmanifold_vertices++;
        if (whole.parts > 1) r->bowtie_vertices++;
        if (mt__add_defect(b, MT_DEFECT_NONMANIFOLD_VERTEX, v, whole.parts,
                           (uint32_t)whole.high_degree) != MT_OK)
            return MT_ERR_NOMEM;
    }
    qsort(le, n, sizeof *le, compare_comp);
    for (uint32_t i = 0; i < n;) {
        uint32_t j = i;
        while (j < n && le[j].comp == le[i].comp) j++;
        link_shape part = analyze(le + i, j - i, scratch->data);
        if (part.parts > 1 || part.high_degree) r->components[le[i].comp].manifold = false;
        i = j;
    }
    return MT_OK;
}

mt_status mt__report_links(mt__build *b)
{
    mt_mesh *m = b->m;
    mt__vec *candidates = &b->split_verts;
    for (uint32_t k = 0; k < m->num_bundles; k++) {
        for (uint32_t i = m->bundle_offsets[k]; i < m->bundle_offsets[k + 1]; i++) {
            uint32_t e = m->bundle_edges[i];
            uint32_t ends[2] = {mt__original(m, m->he_head[2 * e]),
                                mt__original(m, m->he_head[2 * e + 1])};
            if (mt__vec_push(candidates, &ends[0]) != MT_OK ||
                mt__vec_push(candidates, &ends[1]) != MT_OK)
                return MT_ERR_NOMEM;
        }
    }
    uint32_t *verts = candidates->data;
    size_t n = candidates->len;
    if (n == 0) return MT_OK;
    qsort(verts, n, sizeof *verts, compare_u32);
    mt__vec edges = {NULL, 0, 0, sizeof(link_edge)};
    mt__vec scratch = {NULL, 0, 0, sizeof(uint32_t)};
    mt_status s = MT_OK;
    for (size_t i = 0; i < n && s == MT_OK; i++)
        if (i == 0 || verts[i] != verts[i - 1]) s = examine_vertex(b, verts[i], &edges, &scratch);
    mt__vec_free(&edges);
    mt__vec_free(&scratch);
    return s;
}
