/* mt_mesh_compact: drops what the edits marked deleted (and face records the
 * build rejected), renumbers the rest in order and rebuilds the mesh and its
 * report from the compacted face list with mt_mesh_build, then moves the
 * result into the caller's mesh object. Linear time; all or nothing (a failed
 * build leaves the mesh as it was). */
#include <stdlib.h>
#include <string.h>

#include "edit/edit_internal.h"
#include "meshtopo/edit.h"

/* The half-edge of fresh from caller vertex a to b, looked for in every
 * fan of a (a non-manifold vertex has copies); MT_NONE when there is none. */
static uint32_t find_half_edge(const mt_mesh *fresh, uint32_t a, uint32_t b)
{
    const uint32_t *copies = NULL;
    const uint32_t num_copies = mt__vert_copies(fresh, a, &copies);
    for (uint32_t i = 0; i <= num_copies; i++) {
        const uint32_t start = fresh->vert_he[i == 0 ? a : copies[i - 1]];
        if (start == MT_NONE) continue;
        uint32_t h = start, steps = 0;
        do {
            if (mt__original(fresh, fresh->he_head[h]) == b) return h;
            h = fresh->he_next[h ^ 1u];
        } while (h != start && ++steps < fresh->num_half_edges);
    }
    return MT_NONE;
}

/* The attributes of m carried to fresh, its compaction: each live
 * half-edge of m goes to the half-edge joining its mapped ends in fresh. */
static mt_status carry_attributes(const mt_mesh *m, mt_mesh *fresh, const uint32_t *vmap,
                                  const uint32_t *fmap)
{
    if (!m->attributes) return MT_OK;
    uint32_t *hemap = mt__malloc(((size_t)m->num_half_edges + 1) * sizeof *hemap);
    if (!hemap) return MT_ERR_NOMEM;
    for (uint32_t h = 0; h < m->num_half_edges; h++) {
        hemap[h] = MT_NONE;
        if (m->he_head[h] == MT_NONE) continue; /* deleted */
        const uint32_t a = vmap[mt__original(m, m->he_head[h ^ 1u])];
        const uint32_t b = vmap[mt__original(m, m->he_head[h])];
        if (a != MT_NONE && b != MT_NONE) hemap[h] = find_half_edge(fresh, a, b);
    }
    mt_status s = mt__attributes_remap(m, fresh, vmap, fmap, hemap);
    mt__free(hemap);
    return s;
}

/* Face list of the live faces in new ids; fills the maps. */
static mt_status export_faces(const mt_mesh *m, uint32_t *vmap, uint32_t *fmap, mt_face_list *out,
                              mt_diag *diag)
{
    uint32_t nv = 0, nf = 0;
    uint64_t ni = 0;
    for (uint32_t v = 0; v < m->num_verts; v++) vmap[v] = mt_vert_is_deleted(m, v) ? MT_NONE : nv++;
    for (uint32_t f = 0; f < m->num_faces; f++) {
        fmap[f] = MT_NONE;
        const uint32_t start = m->face_he[f];
        if (start == MT_NONE) continue;
        fmap[f] = nf++;
        uint32_t h = start, steps = 0;
        do {
            ni++;
            h = m->he_next[h];
        } while (h != start && ++steps < m->num_half_edges);
    }
    mt_status s = mt_face_list_alloc(out, nv, nf, ni, diag);
    if (s != MT_OK) return s;
    if (!m->positions) {
        free(out->positions); /* mt_face_list_alloc allocates with calloc */
        out->positions = NULL;
    }
    uint64_t k = 0;
    for (uint32_t v = 0; v < m->num_verts; v++)
        if (vmap[v] != MT_NONE && m->positions)
            memcpy(out->positions + 3 * (size_t)vmap[v], m->positions + 3 * (size_t)v,
                   3 * sizeof(double));
    for (uint32_t f = 0; f < m->num_faces; f++) {
        if (fmap[f] == MT_NONE) continue;
        const uint32_t start = m->face_he[f];
        uint32_t h = start, n = 0;
        do {
            out->face_indices[k++] = vmap[mt__original(m, m->he_head[h ^ 1u])];
            n++;
            h = m->he_next[h];
        } while (h != start && n < m->num_half_edges);
        out->face_sizes[fmap[f]] = n;
    }
    return MT_OK;
}

mt_status mt_mesh_compact(mt_mesh *mesh, uint32_t *out_vert_map, size_t vert_map_capacity,
                          uint32_t *out_face_map, size_t face_map_capacity, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!mesh) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "compact: mesh is NULL");
    if ((out_vert_map && vert_map_capacity < mesh->num_verts) ||
        (out_face_map && face_map_capacity < mesh->num_faces))
        return mt__fail(diag, MT_ERR_BUFFER_TOO_SMALL, MT_NONE,
                        "compact: the maps need %u vertex and %u face entries (capacities %zu "
                        "and %zu)",
                        mesh->num_verts, mesh->num_faces, out_vert_map ? vert_map_capacity : 0,
                        out_face_map ? face_map_capacity : 0);
    uint32_t *vmap = mt__malloc(((size_t)mesh->num_verts + mesh->num_faces) * sizeof(uint32_t));
    if (!vmap) return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "compact: out of memory");
    uint32_t *fmap = vmap + mesh->num_verts;
    mt_face_list list;
    memset(&list, 0, sizeof list);
    mt_status s = export_faces(mesh, vmap, fmap, &list, diag);
    mt_mesh *fresh = NULL;
    if (s == MT_OK) s = mt_mesh_build(&list, NULL, &fresh, diag);
    mt_face_list_free(&list);
    if (s == MT_OK && carry_attributes(mesh, fresh, vmap, fmap) != MT_OK)
        s = mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "compact: no memory for the attributes");
    if (s != MT_OK) {
        mt_mesh_destroy(fresh);
        mt__free(vmap);
        return s;
    }
    if (out_vert_map) memcpy(out_vert_map, vmap, (size_t)mesh->num_verts * sizeof(uint32_t));
    if (out_face_map) memcpy(out_face_map, fmap, (size_t)mesh->num_faces * sizeof(uint32_t));
    mt__free(vmap);
    fresh->skip_hidden = mesh->skip_hidden;
    /* The caller keeps its pointer: swap the contents and free the old ones. */
    mt_mesh old = *mesh;
    *mesh = *fresh;
    *fresh = old;
    mt_mesh_destroy(fresh);
    return MT_OK;
}
