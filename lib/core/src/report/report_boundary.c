/* Report part "boundary": the graph of boundary edges (edges used by exactly
 * one face). Its connected parts are the boundary loops, counted over caller
 * vertices for the whole mesh (with their edge counts) and over (vertex,
 * component) pairs for each component. A vertex with boundary degree other
 * than 2 makes the loops ambiguous (a pinched boundary is a figure eight). */
#include <stdlib.h>
#include <string.h>

#include "report/report_internal.h"

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

/* Loops of the whole mesh, over caller vertices. */
static mt_status global_loops(mt__build *b, uint32_t *parent, uint32_t *degree)
{
    mt_mesh *m = b->m;
    mt_report *r = &m->report;
    const uint32_t nv = m->num_verts;
    const uint32_t *edges = b->boundary_halves.data;
    const size_t num_edges = b->boundary_halves.len;
    for (uint32_t v = 0; v < nv; v++) parent[v] = v, degree[v] = 0;
    for (size_t i = 0; i < num_edges; i++) {
        const uint32_t e = edges[i];
        uint32_t x = mt__original(m, m->he_head[2 * e]), y = mt__original(m, m->he_head[2 * e + 1]);
        mt__uf_union(parent, x, y);
        degree[x]++;
        degree[y]++;
    }
    uint32_t loops = 0;
    for (uint32_t v = 0; v < nv; v++) {
        if (degree[v] != 0 && degree[v] != 2) r->boundary_loops_ambiguous = true;
        if (degree[v] && parent[v] == v) loops++;
    }
    r->boundary_loops = loops;
    r->boundary_loop_lengths = mt__calloc(loops ? loops : 1, sizeof(uint32_t));
    if (!r->boundary_loop_lengths) return MT_ERR_NOMEM;
    /* Number the roots, then count edges per root (degree[] reused as ids). */
    uint32_t next = 0;
    for (uint32_t v = 0; v < nv; v++) degree[v] = (degree[v] && parent[v] == v) ? next++ : MT_NONE;
    for (size_t i = 0; i < num_edges; i++) {
        uint32_t x = mt__original(m, m->he_head[2 * edges[i]]);
        r->boundary_loop_lengths[degree[mt__uf_find(parent, x)]]++;
    }
    qsort(r->boundary_loop_lengths, loops, sizeof(uint32_t), compare_u32);
    return MT_OK;
}

/* Loops per component, over internal vertices with the copies of a vertex
 * that fall into the same component joined back together. */
static void component_loops(mt__build *b, uint32_t *parent, uint8_t *touched)
{
    mt_mesh *m = b->m;
    const uint32_t nvi = m->num_verts_internal;
    const uint32_t *edges = b->boundary_halves.data;
    const size_t num_edges = b->boundary_halves.len;
    const uint32_t *comp = b->vert_comp;
    for (uint32_t v = 0; v < nvi; v++) parent[v] = v, touched[v] = 0;
    for (uint32_t i = 0; i < m->num_copies; i++) {
        uint32_t copy = m->num_verts + i, original = m->copy_original[i];
        if (comp[copy] == comp[original]) mt__uf_union(parent, copy, original);
        for (uint32_t j = i; j > 0 && m->copy_original[j - 1] == original; j--)
            if (comp[m->num_verts + j - 1] == comp[copy])
                mt__uf_union(parent, copy, m->num_verts + j - 1);
    }
    for (size_t i = 0; i < num_edges; i++) {
        uint32_t x = m->he_head[2 * edges[i]], y = m->he_head[2 * edges[i] + 1];
        mt__uf_union(parent, x, y);
        touched[x] = touched[y] = 1;
    }
    /* A root may be a vertex the boundary does not touch (a copy joined to
     * its original): count each touched vertex's root once. */
    for (uint32_t v = 0; v < nvi; v++) {
        if (!(touched[v] & 1)) continue;
        uint32_t root = mt__uf_find(parent, v);
        if (touched[root] & 2) continue;
        touched[root] |= 2;
        m->report.components[comp[v]].boundary_loops++;
    }
}

mt_status mt__report_boundary(mt__build *b)
{
    mt_mesh *m = b->m;
    mt_report *r = &m->report;
    if (r->boundary_edges == 0) {
        r->boundary_loop_lengths = mt__calloc(1, sizeof(uint32_t));
        return r->boundary_loop_lengths ? MT_OK : MT_ERR_NOMEM;
    }
    const uint32_t nvi = m->num_verts_internal;
    uint32_t *parent = mt__malloc((size_t)nvi * sizeof(uint32_t));
    uint32_t *degree = mt__malloc((size_t)nvi * sizeof(uint32_t));
    mt_status s = MT_ERR_NOMEM;
    if (parent && degree) {
        s = global_loops(b, parent, degree);
        if (s == MT_OK) component_loops(b, parent, (uint8_t *)degree);
    }
    mt__free(parent);
    mt__free(degree);
    return s;
}
