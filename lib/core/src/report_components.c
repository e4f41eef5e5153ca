/* Report part "components": edge-connected components of the valid faces
 * (union-find over internal vertices along internal edges and across edge
 * bundles: each fan's faces share its internal vertex, so this joins exactly
 * the faces that share an edge), numbered by smallest face id, with their
 * face, vertex and edge counts; and the vertex-connected count. */
#include <string.h>

#include "build_internal.h"

int mt__is_boundary_edge(const mt_mesh *m, uint32_t e)
{
    if (m->he_face[2 * e] != MT_NONE && m->he_face[2 * e + 1] != MT_NONE) return 0;
    return m->num_bundles == 0 || mt__edge_bundle(m, e) == MT_NONE;
}

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

mt_status mt__report_components(mt__build *b)
{
    mt_mesh *m = b->m;
    mt_report *r = &m->report;
    const uint32_t nvi = m->num_verts_internal;
    uint32_t *parent = mt__malloc((size_t)nvi * sizeof(uint32_t));
    if (!parent) return MT_ERR_NOMEM;
    for (uint32_t v = 0; v < nvi; v++) parent[v] = v;
    const uint32_t num_edges = m->num_half_edges / 2;
    for (uint32_t e = 0; e < num_edges; e++)
        mt__uf_union(parent, m->he_head[2 * e], m->he_head[2 * e + 1]);
    for (uint32_t k = 0; k < m->num_bundles; k++) {
        uint32_t first = m->bundle_edges[m->bundle_offsets[k]];
        for (uint32_t i = m->bundle_offsets[k] + 1; i < m->bundle_offsets[k + 1]; i++) {
            uint32_t e = m->bundle_edges[i];
            mt__uf_union(parent, m->he_head[2 * first], m->he_head[2 * e]);
            mt__uf_union(parent, m->he_head[2 * first + 1], m->he_head[2 * e + 1]);
        }
    }
    /* Number components by smallest face: reuse parent roots as "unnumbered"
     * marks through a second array. */
    uint32_t *comp = mt__malloc((size_t)nvi * sizeof(uint32_t));
    if (!comp) {
        mt__free(parent);
        return MT_ERR_NOMEM;
    }
    memset(comp, 0xff, (size_t)nvi * sizeof(uint32_t));
    uint32_t count = 0;
    for (uint32_t f = 0; f < m->num_faces; f++) {
        if (m->face_he[f] == MT_NONE) continue;
        uint32_t root = mt__uf_find(parent, m->he_head[m->face_he[f]]);
        if (comp[root] == MT_NONE) comp[root] = count++;
    }
    for (uint32_t v = 0; v < nvi; v++)
        comp[v] = m->vert_he[v] == MT_NONE ? MT_NONE : comp[mt__uf_find(parent, v)];
    mt__free(parent);
    b->vert_comp = comp;
    b->num_components = count;
    r->connected_components = count;

    r->components = mt__calloc(count ? count : 1, sizeof(mt_component_info));
    if (!r->components) return MT_ERR_NOMEM;
    mt_component_info *ci = r->components;
    for (uint32_t c = 0; c < count; c++) ci[c].min_face = MT_NONE;
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
    for (uint32_t e = 0; e < num_edges; e++) {
        mt_component_info *c = &ci[comp[m->he_head[2 * e]]];
        c->edges++;
        if (mt__is_boundary_edge(m, e)) c->boundary_edges++;
    }
    for (uint32_t k = 0; k < m->num_bundles; k++) {
        uint32_t first = m->bundle_edges[m->bundle_offsets[k]];
        ci[comp[m->he_head[2 * first]]].edges -=
            m->bundle_offsets[k + 1] - m->bundle_offsets[k] - 1;
    }
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
