/* The seed's planar rectangle closed into a sphere (generate.h): the
 * rectangle's two triangles in front, two more behind on the same four
 * corners, and hidden flags (meshtopo/attributes.h) on what is not the
 * rectangle: the two faces behind and the front diagonal. The only
 * generator that returns a built mesh, since the flags live on one. */
#include <math.h>
#include <string.h>

#include "meshtopo/attributes.h"
#include "meshtopo/generate.h"

/* Front (0, 1, 2), (0, 2, 3) as mt_gen_rectangle; behind (1, 0, 3),
 * (3, 2, 1), across the other diagonal: every edge once each way. */
static const uint32_t closed_faces[12] = {0, 1, 2, 0, 2, 3, 1, 0, 3, 3, 2, 1};

mt_status mt_gen_closed_rectangle(double width, double height, mt_mesh **out_mesh, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!out_mesh)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "mt_gen_closed_rectangle: out_mesh is NULL");
    *out_mesh = NULL;
    if (!isfinite(width) || !isfinite(height) || !(width > 0) || !(height > 0))
        return mt_diag_set(diag, MT_ERR_INVALID_ARG,
                           "mt_gen_closed_rectangle: width %g and height %g must be finite and > 0",
                           width, height);
    double positions[12] = {0, 0, 0, width, 0, 0, width, height, 0, 0, height, 0};
    uint32_t sizes[4] = {3, 3, 3, 3}, indices[12];
    memcpy(indices, closed_faces, sizeof indices);
    mt_face_list list = {4, 4, 12, positions, sizes, indices};
    mt_mesh *mesh = NULL;
    mt_status s = mt_mesh_build(&list, NULL, &mesh, diag);
    if (s != MT_OK) return s;
    /* The front diagonal 0-2: the edge of face 0's third side (2 -> 0). */
    mt_mesh_view view;
    mt_mesh_get_view(mesh, &view);
    const uint32_t side_1_2 = view.he_next[view.face_he[0]];
    const uint32_t diagonal = mt_he_edge(view.he_next[side_1_2]);
    s = mt_set_hidden(mesh, MT_ELEMENT_FACE, 2, true, diag);
    if (s == MT_OK) s = mt_set_hidden(mesh, MT_ELEMENT_FACE, 3, true, diag);
    if (s == MT_OK) s = mt_set_hidden(mesh, MT_ELEMENT_EDGE, diagonal, true, diag);
    if (s != MT_OK) {
        mt_mesh_destroy(mesh);
        return s;
    }
    *out_mesh = mesh;
    return MT_OK;
}
