/* Edge query: the faces on an undirected caller edge {a, b}. The internal
 * edge is found by one rotation around a's fans (its copies included); a
 * non-bundled edge is the only internal edge joining a and b and has at most
 * two faces, a bundled one brings the faces of its whole bundle. Time
 * O(valence of a + faces on the edge * log); no allocation. */
#include <stdlib.h>

#include "meshtopo/attributes.h"
#include "meshtopo/query.h"
#include "query/query_internal.h"

/* Outgoing half-edge of caller vertex a (any of its fans) whose head is
 * caller vertex b, MT_NONE in *out_he when there is none; MT_ERR_CORRUPT on a
 * broken rotation. */
static mt_status find_side(const mt_mesh *m, uint32_t a, uint32_t b, uint32_t *out_he)
{
    *out_he = MT_NONE;
    mt__vert_walk w;
    mt__vert_walk_begin(&w, m, a);
    while (mt__vert_walk_fan(&w)) {
        do {
            if (mt__original_checked(m, m->he_head[w.he]) == b) {
                *out_he = w.he;
                return MT_OK;
            }
        } while (mt__vert_walk_step(&w));
    }
    return w.status;
}

/* Faces on the edge of half-edge h (its bundle's when bundled), but none
 * that `hidden` (the skipped flags, or NULL) marks, written to out when not
 * NULL; returns how many, SIZE_MAX on a corrupt bundle table. */
static size_t edge_faces(const mt_mesh *m, uint32_t h, const uint8_t *hidden, uint32_t *out)
{
    uint32_t b = mt__edge_bundle(m, h >> 1);
    uint32_t first_edge = h >> 1, begin = 0, end = 1;
    if (b != MT_NONE && !mt__bundle_range(m, b, &begin, &end)) return SIZE_MAX;
    size_t n = 0;
    for (uint32_t k = begin; k < end; k++) {
        uint32_t e = b == MT_NONE ? first_edge : m->bundle_edges[k];
        if (e >= m->num_half_edges / 2) return SIZE_MAX;
        for (uint32_t side = 0; side < 2; side++) {
            uint32_t f = m->he_face[2 * e + side];
            if (f == MT_NONE || mt__skipped(hidden, m->num_faces, f)) continue;
            if (out) out[n] = f;
            n++;
        }
    }
    return n;
}

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

mt_status mt_edge_faces(const mt_mesh *mesh, uint32_t a, uint32_t b, uint32_t *out_faces,
                        size_t capacity, size_t *out_count)
{
    if (!mesh || !out_count) return MT_ERR_INVALID_ARG;
    if (a >= mesh->num_verts || b >= mesh->num_verts) return MT_ERR_OUT_OF_RANGE;
    if (a == b) return MT_ERR_NOT_FOUND;
    uint32_t h;
    mt_status s = find_side(mesh, a, b, &h);
    if (s != MT_OK) return s;
    if (h == MT_NONE) return MT_ERR_NOT_FOUND;
    if (mt__skipped(mt__skipped_flags(mesh, MT_ELEMENT_EDGE), mesh->num_half_edges / 2, h >> 1))
        return MT_ERR_NOT_FOUND;
    const uint8_t *hidden = mt__skipped_flags(mesh, MT_ELEMENT_FACE);
    size_t n = edge_faces(mesh, h, hidden, NULL);
    if (n == SIZE_MAX) return MT_ERR_CORRUPT;
    if (n == 0) return MT_ERR_NOT_FOUND;
    *out_count = n;
    if (mt__buffer_absent(out_faces, capacity)) return MT_OK;
    if (capacity < n) return MT_ERR_BUFFER_TOO_SMALL;
    edge_faces(mesh, h, hidden, out_faces);
    if (n == 2) {
        if (out_faces[0] > out_faces[1]) {
            uint32_t t = out_faces[0];
            out_faces[0] = out_faces[1];
            out_faces[1] = t;
        }
    } else if (n > 2) {
        qsort(out_faces, n, sizeof *out_faces, compare_u32);
    }
    /* A face has one side on an edge, so repeats only come from a corrupted
     * mesh; drop them all the same so the output is a set. */
    size_t unique = 1;
    for (size_t i = 1; i < n; i++)
        if (out_faces[i] != out_faces[unique - 1]) out_faces[unique++] = out_faces[i];
    *out_count = unique;
    return MT_OK;
}
