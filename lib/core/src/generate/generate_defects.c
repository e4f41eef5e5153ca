/* The classic defective shapes (generate.h), each the smallest face list that
 * shows one defect: the bowtie (two triangles meeting at a single vertex, a
 * non-manifold vertex) and the fin (three triangles on one edge, a
 * non-manifold edge). Both lie in or near the z = 0 plane. */
#include <string.h>

#include "meshtopo/generate.h"

/* Fills *out with 5 vertices and `num_faces` triangles from the tables. */
static mt_status small_make(const double pos[15], const uint32_t *tris, uint32_t num_faces,
                            mt_face_list *out)
{
    mt_status status = mt_face_list_alloc(out, 5, num_faces, 3 * (uint64_t)num_faces, NULL);
    if (status != MT_OK) return status;
    memcpy(out->positions, pos, 15 * sizeof(double));
    memcpy(out->face_indices, tris, 3 * num_faces * sizeof(uint32_t));
    for (uint32_t f = 0; f < num_faces; f++) out->face_sizes[f] = 3;
    return MT_OK;
}

/* Triangles (0, 1, 2) to the right of vertex 0 and (0, 3, 4) to its left,
 * both counter-clockwise seen from +z. */
mt_status mt_gen_bowtie(mt_face_list *out)
{
    if (!out) return MT_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    static const double pos[15] = {0, 0, 0, 1, -0.5, 0, 1, 0.5, 0, -1, 0.5, 0, -1, -0.5, 0};
    static const uint32_t tris[6] = {0, 1, 2, 0, 3, 4};
    return small_make(pos, tris, 2, out);
}

/* Edge 0-1 lies on the x axis; (0, 1, 2) and (1, 0, 3) form a flat, consistently
 * oriented pair in z = 0 and (0, 1, 4) stands up from it. No orientation of a
 * third face can be consistent with both: it runs 0 -> 1 like face 0. */
mt_status mt_gen_fin(mt_face_list *out)
{
    if (!out) return MT_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    static const double pos[15] = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1};
    static const uint32_t tris[9] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    return small_make(pos, tris, 3, out);
}
