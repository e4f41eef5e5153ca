/* Report part "orientation": a component is orientable when its faces can be
 * flipped so that every edge used by exactly two faces is crossed in opposite
 * directions (DEFINITIONS.md). Union-find with parity over faces: a paired
 * internal edge says "same flip", a two-face bundle (both faces running the
 * same way) says "opposite flip"; a contradiction makes the component
 * non-orientable. Without any same-direction pair every constraint is "same
 * flip", so the pass is skipped. */
#include "report/report_internal.h"

/* Root of x; *out_parity gets x's flip relative to the root. */
static uint32_t find_parity(uint32_t *parent, uint8_t *parity, uint32_t x, uint8_t *out_parity)
{
    uint8_t acc = 0;
    while (parent[x] != x) {
        uint32_t p = parent[x];
        if (parent[p] != p) {
            parity[x] ^= parity[p];
            parent[x] = parent[p];
        }
        acc ^= parity[x];
        x = parent[x];
    }
    *out_parity = acc;
    return x;
}

/* Records that faces f and g flip alike (differ = 0) or oppositely (1);
 * returns 0 on a contradiction. */
static int constrain(uint32_t *parent, uint8_t *parity, uint32_t f, uint32_t g, uint8_t differ)
{
    uint8_t pf, pg;
    uint32_t rf = find_parity(parent, parity, f, &pf), rg = find_parity(parent, parity, g, &pg);
    if (rf == rg) return (uint8_t)(pf ^ pg) == differ;
    parent[rg] = rf;
    parity[rg] = pf ^ pg ^ differ;
    return 1;
}

mt_status mt__report_orientation(mt__build *b)
{
    mt_mesh *m = b->m;
    if (b->inconsistent_edges == 0) return MT_OK;
    uint32_t *parent = mt__malloc((size_t)m->num_faces * sizeof(uint32_t));
    uint8_t *parity = mt__calloc(m->num_faces ? m->num_faces : 1, 1);
    if (!parent || !parity) {
        mt__free(parent);
        mt__free(parity);
        return MT_ERR_NOMEM;
    }
    for (uint32_t f = 0; f < m->num_faces; f++) parent[f] = f;
    mt_component_info *ci = m->report.components;
    const uint32_t num_edges = m->num_half_edges / 2;
    for (uint32_t e = 0; e < num_edges; e++) {
        uint32_t f = m->he_face[2 * e], g = m->he_face[2 * e + 1];
        if (f == MT_NONE || g == MT_NONE) continue;
        if (m->num_bundles && mt__edge_bundle(m, e) != MT_NONE) continue;
        if (!constrain(parent, parity, f, g, 0))
            ci[b->vert_comp[m->he_head[2 * e]]].orientable = false;
    }
    for (uint32_t k = 0; k < m->num_bundles; k++) {
        uint32_t faces[2], uses = 0;
        for (uint32_t i = m->bundle_offsets[k]; i < m->bundle_offsets[k + 1]; i++) {
            uint32_t e = m->bundle_edges[i];
            for (uint32_t h = 2 * e; h <= 2 * e + 1; h++)
                if (m->he_face[h] != MT_NONE && uses++ < 2) faces[uses - 1] = m->he_face[h];
        }
        if (uses != 2) continue;
        if (!constrain(parent, parity, faces[0], faces[1], 1))
            ci[b->vert_comp[m->he_head[m->face_he[faces[0]]]]].orientable = false;
    }
    mt__free(parent);
    mt__free(parity);
    return MT_OK;
}
