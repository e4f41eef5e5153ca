/* Face queries: vertices in stored order, faces across each side, and the
 * face's component. A face is the ring of next pointers from its stored
 * half-edge (first vertex to second), so the caller's vertex order comes back
 * unchanged. Across a bundled side every other face of the bundle is listed.
 * Time linear in the output (plus a binary search per side when the mesh has
 * bundles); no allocation. */
#include "meshtopo/attributes.h"
#include "meshtopo/query.h"
#include "query/query_internal.h"

/* First half-edge of a face record, or the status to return (a hidden face
 * the queries skip is not found). */
static mt_status face_start(const mt_mesh *m, uint32_t face, uint32_t *out_he)
{
    if (face >= m->num_faces) return MT_ERR_OUT_OF_RANGE;
    uint32_t h = m->face_he[face];
    if (h == MT_NONE) return MT_ERR_NOT_FOUND;
    if (mt__skipped(mt__skipped_flags(m, MT_ELEMENT_FACE), m->num_faces, face))
        return MT_ERR_NOT_FOUND;
    if (!mt__he_ok(m, h)) return MT_ERR_CORRUPT;
    *out_he = h;
    return MT_OK;
}

mt_status mt_face_verts(const mt_mesh *mesh, uint32_t face, uint32_t *out_verts, size_t capacity,
                        size_t *out_count)
{
    if (!mesh || !out_count) return MT_ERR_INVALID_ARG;
    uint32_t start;
    mt_status s = face_start(mesh, face, &start);
    if (s != MT_OK) return s;
    size_t n = 0;
    uint32_t h = start, steps = 0;
    do {
        n++;
        if (!mt__ring_step(mesh, &h, &steps)) return MT_ERR_CORRUPT;
    } while (h != start);
    *out_count = n;
    if (mt__buffer_absent(out_verts, capacity)) return MT_OK;
    if (capacity < n) return MT_ERR_BUFFER_TOO_SMALL;
    size_t i = 0;
    h = start;
    steps = 0;
    do {
        uint32_t v = mt__original_checked(mesh, mesh->he_head[h ^ 1u]);
        if (v == MT_NONE) return MT_ERR_CORRUPT;
        out_verts[i++] = v;
        if (!mt__ring_step(mesh, &h, &steps)) return MT_ERR_CORRUPT;
    } while (h != start && i < n);
    return MT_OK;
}

/* Faces across the side of `face` held by half-edge h: every face of the
 * bundle but `face` when the side is bundled, else the twin's face; none
 * that `hidden` (the skipped flags, or NULL) marks. Writes them to out
 * (when not NULL) and returns how many, or SIZE_MAX on a corrupt bundle
 * table. */
static size_t side_neighbors(const mt_mesh *m, uint32_t face, uint32_t h, const uint8_t *hidden,
                             uint32_t *out)
{
    size_t n = 0;
    uint32_t b = mt__edge_bundle(m, h >> 1);
    if (b == MT_NONE) {
        uint32_t g = m->he_face[h ^ 1u];
        if (g != MT_NONE && g != face && !mt__skipped(hidden, m->num_faces, g)) {
            if (out) out[n] = g;
            n++;
        }
        return n;
    }
    uint32_t begin, end;
    if (!mt__bundle_range(m, b, &begin, &end)) return SIZE_MAX;
    for (uint32_t k = begin; k < end; k++) {
        uint32_t e = m->bundle_edges[k];
        if (e >= m->num_half_edges / 2) return SIZE_MAX;
        for (uint32_t side = 0; side < 2; side++) {
            uint32_t g = m->he_face[2 * e + side];
            if (g == MT_NONE || g == face || mt__skipped(hidden, m->num_faces, g)) continue;
            if (out) out[n] = g;
            n++;
        }
    }
    return n;
}

mt_status mt_face_neighbors(const mt_mesh *mesh, uint32_t face, uint32_t *out_faces,
                            size_t faces_capacity, uint32_t *out_offsets, size_t offsets_capacity,
                            size_t *out_num_faces, size_t *out_num_edges)
{
    if (!mesh || !out_num_faces || !out_num_edges) return MT_ERR_INVALID_ARG;
    uint32_t start;
    mt_status s = face_start(mesh, face, &start);
    if (s != MT_OK) return s;

    const uint8_t *hidden = mt__skipped_flags(mesh, MT_ELEMENT_FACE);
    size_t edges = 0, total = 0;
    uint32_t h = start, steps = 0;
    do {
        size_t n = side_neighbors(mesh, face, h, hidden, NULL);
        if (n == SIZE_MAX) return MT_ERR_CORRUPT;
        total += n;
        edges++;
        if (!mt__ring_step(mesh, &h, &steps)) return MT_ERR_CORRUPT;
    } while (h != start);
    /* Offsets are 32-bit: a face's neighbours are distinct face sides of the
     * mesh, so more than 2^32 - 1 of them means a corrupted table. */
    if (total > UINT32_MAX) return MT_ERR_CORRUPT;
    *out_num_faces = total;
    *out_num_edges = edges;

    if (mt__buffer_absent(out_faces, faces_capacity) &&
        mt__buffer_absent(out_offsets, offsets_capacity))
        return MT_OK;
    if (!mt__buffer_fits(out_faces, faces_capacity, total) ||
        !mt__buffer_fits(out_offsets, offsets_capacity, edges + 1))
        return MT_ERR_BUFFER_TOO_SMALL;

    size_t written = 0, i = 0;
    out_offsets[0] = 0;
    h = start;
    steps = 0;
    do {
        /* Same walk as the counting pass over a mesh that cannot change in
         * between, so the sides add up to `total` again. */
        written += side_neighbors(mesh, face, h, hidden, out_faces ? out_faces + written : NULL);
        out_offsets[++i] = (uint32_t)written;
        if (!mt__ring_step(mesh, &h, &steps)) return MT_ERR_CORRUPT;
    } while (h != start && i < edges);
    return MT_OK;
}

mt_status mt_face_component(const mt_mesh *mesh, uint32_t face, uint32_t *out_component)
{
    if (!mesh || !out_component) return MT_ERR_INVALID_ARG;
    uint32_t start;
    mt_status s = face_start(mesh, face, &start);
    if (s != MT_OK) return s;
    if (!mesh->vert_component) {
        *out_component = 0;
        return MT_OK;
    }
    uint32_t v = mesh->he_head[start];
    if (v >= mesh->num_verts_internal) return MT_ERR_CORRUPT;
    *out_component = mesh->vert_component[v];
    return MT_OK;
}
