/* Colours marking a built mesh's defects, per vertex and per face record,
 * in the palette `meshtopo render` draws with (tools/vtk/render.py): what
 * `meshtopo archive export OUT.ply` writes as PLY colours. */
#ifndef MESHTOPO_CLI_DEFECT_COLORS_H
#define MESHTOPO_CLI_DEFECT_COLORS_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/face_list.h"
#include "meshtopo/geometry.h"
#include "meshtopo/mesh.h"

/* Fills out_vertex (3 x list->num_verts bytes) and out_face (3 x
 * list->num_faces bytes) with red, green, blue; mesh is list's build. A
 * vertex is magenta when it is a nonmanifold_vertex, else orange when it
 * is a corner of a rejected face, else red when it ends a boundary edge
 * (an edge of one face), else grey. A face is orange when the build
 * rejected it, else yellow when it is in one of the `pairs` (its
 * self-intersections; none when not computed), else magenta when it has a
 * side used by three or more faces, else blue when the other face of one
 * of its two-face sides runs that side the same way, else grey. false when
 * memory runs out. */
bool cli_defect_colors(const mt_face_list *list, const mt_mesh *mesh, const mt_face_pair *pairs,
                       size_t num_pairs, uint8_t *out_vertex, uint8_t *out_face);

#endif
