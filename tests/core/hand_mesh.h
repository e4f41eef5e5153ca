/* Small half-edge meshes written out by hand, array by array, for the query
 * and validation tests: they do not go through mt_mesh_build, so the queries
 * and the validator are tested on structures whose every index is known, and
 * the corruption tests start from them. Each comes with its face list. */
#ifndef MESHTOPO_TEST_HAND_MESH_H
#define MESHTOPO_TEST_HAND_MESH_H

#include <stdint.h>

#include "mesh/mesh_internal.h"

/* Everything a hand mesh is made of; arrays are copied by hand_mesh_new. */
typedef struct hand_spec {
    uint32_t num_verts, num_faces, num_half_edges, num_copies, num_bundles;
    const uint32_t *he_head, *he_next, *he_face;   /* [num_half_edges] */
    const uint32_t *face_he;                       /* [num_faces] */
    const uint32_t *vert_he;                       /* [num_verts + num_copies] */
    const uint32_t *copy_original, *copies_sorted; /* [num_copies] */
    const uint32_t *bundle_offsets;                /* [num_bundles + 1] */
    const uint32_t *bundle_edges, *bundled_sorted, *bundled_bundle;
    const uint32_t *vert_component; /* [num_verts + num_copies] or NULL */
    uint32_t components;            /* report.connected_components */
} hand_spec;

/* A mesh owning malloc'd copies of the spec's arrays, with the report's
 * vertex, face, valid face and component counts filled in. Ends the test
 * program when out of memory. Free with hand_mesh_free. */
mt_mesh *hand_mesh_new(const hand_spec *spec);
void hand_mesh_free(mt_mesh *mesh);

/* The face list a hand mesh was written from (static storage). */
typedef struct hand_faces {
    uint32_t num_verts, num_faces;
    const uint32_t *sizes;
    const uint32_t *indices;
} hand_faces;

/* One triangle (0, 1, 2). */
mt_mesh *hand_triangle(hand_faces *out_faces);
/* The seed rectangle: (0, 1, 2), (0, 2, 3). */
mt_mesh *hand_rectangle(hand_faces *out_faces);
/* A closed tetrahedron: (0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2). */
mt_mesh *hand_tetrahedron(hand_faces *out_faces);
/* The triangle plus an isolated vertex 3 and a rejected face record 1. */
mt_mesh *hand_triangle_isolated(void);
/* Bowtie (0, 1, 2), (0, 3, 4): vertex 0 has a copy, 5, holding face 1's fan;
 * two components. */
mt_mesh *hand_bowtie(hand_faces *out_faces);
/* Fin (0, 1, 2), (1, 0, 3), (0, 1, 4): edges 0 and 5 form a bundle on 0-1,
 * face 2 sits on copies 5 (of 0) and 6 (of 1). */
mt_mesh *hand_fin(hand_faces *out_faces);

#endif
