/* Report part "components": edge-connected components of the valid faces
 * (union-find over internal vertices along internal edges and across edge
 * bundles: each fan's faces share its internal vertex, so this joins exactly
 * the faces that share an edge), numbered by smallest face id, with their
 * face, vertex and edge counts; and the vertex-connected count. */
#include <stdatomic.h>
#include <string.h>

#include "report/report_internal.h"

/* Vertex-connected components: components joined through vertex copies. */
static mt_status count_vertex_components(mt__build *b)
{
    mt_mesh *m = b->m;
    mt_report *r = &m->report;
    if (b->num_components == 0 || m->num_copies == 0) {
        r->vertex_connected_components = b->num_components;
        return MT_OK;
    }
    uint32_t *parent = mt__malloc((size_t)b->num_components * sizeof(uint32_t));
    if (!parent) return MT_ERR_NOMEM;
    for (uint32_t c = 0; c < b->num_components; c++) parent[c] = c;
    for (uint32_t i = 0; i < m->num_copies; i++) {
        uint32_t copy = m->num_verts + i;
        mt__uf_union(parent, b->vert_comp[copy], b->vert_comp[m->copy_original[i]]);
    }
    uint32_t count = 0;
    for (uint32_t c = 0; c < b->num_components; c++) count += parent[c] == c;
    r->vertex_connected_components = count;
    mt__free(parent);
    return MT_OK;
}

/* One component: its counts are the mesh's. */
static void count_single_component(mt__build *b)
{
    mt_report *r = &b->m->report;
    mt_component_info *c = &r->components[0];
    c->min_face = 0;
    while (b->m->face_he[c->min_face] == MT_NONE) c->min_face++;
    c->faces = r->num_faces_valid;
    c->vertices = r->num_verts; /* every vertex with a face: all copies share it */
    for (uint32_t v = 0; v < b->m->num_verts; v++) c->vertices -= b->m->vert_he[v] == MT_NONE;
    c->edges = r->num_edges;
    c->boundary_edges = r->boundary_edges;
}

/* Several components: faces, vertices, edges and boundary edges of each. */
static void count_per_component(mt__build *b)
{
    mt_mesh *m = b->m;
    const uint32_t *comp = b->vert_comp;
    mt_component_info *ci = m->report.components;
    for (uint32_t c = 0; c < b->num_components; c++) ci[c].min_face = MT_NONE;
    for (uint32_t f = 0; f < m->num_faces; f++) {
        if (m->face_he[f] == MT_NONE) continue;
        mt_component_info *c = &ci[comp[m->he_head[m->face_he[f]]]];
        if (c->min_face == MT_NONE) c->min_face = f;
        c->faces++;
    }
    /* Vertices: a caller vertex counts once per component it touches. Its
     * copies come right after one another in id order per original. */
    for (uint32_t v = 0; v < m->num_verts; v++)
        if (comp[v] != MT_NONE) ci[comp[v]].vertices++;
    for (uint32_t i = 0; i < m->num_copies; i++) {
        uint32_t copy = m->num_verts + i, original = m->copy_original[i];
        int seen = comp[original] == comp[copy];
        for (uint32_t j = i; j > 0 && !seen && m->copy_original[j - 1] == original; j--)
            seen = comp[m->num_verts + j - 1] == comp[copy];
        if (!seen) ci[comp[copy]].vertices++;
    }
    const uint32_t num_edges = m->num_half_edges / 2;
    for (uint32_t e = 0; e < num_edges; e++) ci[comp[m->he_head[2 * e]]].edges++;
    for (uint32_t k = 0; k < m->num_bundles; k++) {
        uint32_t first = m->bundle_edges[m->bundle_offsets[k]];
        ci[comp[m->he_head[2 * first]]].edges -=
            m->bundle_offsets[k + 1] - m->bundle_offsets[k] - 1;
    }
    const uint32_t *boundary = b->boundary_halves.data;
    for (size_t i = 0; i < b->boundary_halves.len; i++)
        ci[comp[m->he_head[2 * boundary[i]]]].boundary_edges++;
}

/* Concurrent union-find over atomics (the parts join edges of their own
 * ranges at the same time). A root is only ever linked below a smaller id by
 * compare-and-swap, so every set ends with its smallest vertex as root
 * whatever the interleaving; path halving only ever skips to an ancestor. */
static uint32_t shared_find(_Atomic uint32_t *parent, uint32_t x)
{
    for (;;) {
        uint32_t p = atomic_load_explicit(&parent[x], memory_order_relaxed);
        if (p == x) return x;
        uint32_t gp = atomic_load_explicit(&parent[p], memory_order_relaxed);
        /* x is not a root, so its parent only ever moves up its own tree: a
         * plain store of an ancestor cannot lose a link. */
        if (gp != p) atomic_store_explicit(&parent[x], gp, memory_order_relaxed);
        x = gp;
    }
}

static void shared_union(_Atomic uint32_t *parent, uint32_t x, uint32_t y)
{
    for (;;) {
        x = shared_find(parent, x);
        y = shared_find(parent, y);
        if (x == y) return;
        if (x > y) {
            uint32_t swap = x;
            x = y;
            y = swap;
        }
        uint32_t expected = y;
        if (atomic_compare_exchange_strong_explicit(&parent[y], &expected, x, memory_order_acq_rel,
                                                    memory_order_relaxed))
            return;
    }
}

/* Edges ahead of the one joined whose vertices are fetched (they are
 * anywhere in the parent array on a shuffled mesh). */
#define MT__JOIN_PREFETCH 16

static void join_edges_part(mt__build *b, uint32_t t)
{
    const mt_mesh *m = b->m;
    const uint32_t *head = m->he_head;
    _Atomic uint32_t *parent = b->shared_parent;
    const uint64_t num_edges = m->num_half_edges / 2;
    const uint64_t end = num_edges * (t + 1) / b->parts;
    for (uint64_t e = num_edges * t / b->parts; e < end; e++) {
        if (e + MT__JOIN_PREFETCH < end) {
            __builtin_prefetch(&parent[head[2 * (e + MT__JOIN_PREFETCH)]]);
            __builtin_prefetch(&parent[head[2 * (e + MT__JOIN_PREFETCH) + 1]]);
        }
        shared_union(parent, head[2 * e], head[2 * e + 1]);
    }
}

mt_status mt__report_components(mt__build *b)
{
    mt_mesh *m = b->m;
    mt_report *r = &m->report;
    const uint32_t nvi = m->num_verts_internal;
    _Atomic uint32_t *parent = mt__malloc((size_t)nvi * sizeof *parent);
    if (!parent) return MT_ERR_NOMEM;
    for (uint32_t v = 0; v < nvi; v++) atomic_init(&parent[v], v);
    b->shared_parent = parent;
    mt__parallel_run(b, join_edges_part);
    b->shared_parent = NULL;
    for (uint32_t k = 0; k < m->num_bundles; k++) {
        uint32_t first = m->bundle_edges[m->bundle_offsets[k]];
        for (uint32_t i = m->bundle_offsets[k] + 1; i < m->bundle_offsets[k + 1]; i++) {
            uint32_t e = m->bundle_edges[i];
            shared_union(parent, m->he_head[2 * first], m->he_head[2 * e]);
            shared_union(parent, m->he_head[2 * first + 1], m->he_head[2 * e + 1]);
        }
    }
    /* Number components by smallest face. Roots are counted first so that
     * the walk over the faces stops once every component has its number. */
    uint32_t *comp = mt__malloc((size_t)nvi * sizeof(uint32_t));
    if (!comp) {
        mt__free((void *)parent);
        return MT_ERR_NOMEM;
    }
    uint32_t roots = 0;
    for (uint32_t v = 0; v < nvi; v++) {
        comp[v] = MT_NONE;
        roots += m->vert_he[v] != MT_NONE && shared_find(parent, v) == v;
    }
    uint32_t count = 0;
    for (uint32_t f = 0; f < m->num_faces && count < roots; f++) {
        if (m->face_he[f] == MT_NONE) continue;
        uint32_t root = shared_find(parent, m->he_head[m->face_he[f]]);
        if (comp[root] == MT_NONE) comp[root] = count++;
    }
    for (uint32_t v = 0; v < nvi; v++)
        if (m->vert_he[v] != MT_NONE) comp[v] = comp[shared_find(parent, v)];
    mt__free((void *)parent);
    b->vert_comp = comp;
    b->num_components = count;
    r->connected_components = count;

    r->components = mt__calloc(count ? count : 1, sizeof(mt_component_info));
    if (!r->components) return MT_ERR_NOMEM;
    if (count == 1)
        count_single_component(b);
    else
        count_per_component(b);
    mt_component_info *ci = r->components;
    for (uint32_t c = 0; c < count; c++) {
        ci[c].euler_characteristic = (int64_t)ci[c].vertices - (int64_t)ci[c].edges + ci[c].faces;
        ci[c].closed = ci[c].boundary_edges == 0;
        ci[c].manifold = true;   /* until report_links.c or a bundle says otherwise */
        ci[c].orientable = true; /* until report_orientation.c says otherwise */
    }
    for (uint32_t k = 0; k < m->num_bundles; k++) {
        uint32_t first = m->bundle_edges[m->bundle_offsets[k]];
        uint32_t uses = 0;
        for (uint32_t i = m->bundle_offsets[k]; i < m->bundle_offsets[k + 1]; i++) {
            uint32_t e = m->bundle_edges[i];
            uses += (m->he_face[2 * e] != MT_NONE) + (m->he_face[2 * e + 1] != MT_NONE);
        }
        if (uses > 2) ci[comp[m->he_head[2 * first]]].manifold = false;
    }
    return count_vertex_components(b);
}
