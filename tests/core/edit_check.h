/* Helpers for the edit tests (test_edit*.c): building generated meshes,
 * byte-exact snapshots of a mesh's arrays and counts (to prove that a refused
 * or failed edit changed nothing), and counts of live elements. */
#ifndef MESHTOPO_TEST_EDIT_CHECK_H
#define MESHTOPO_TEST_EDIT_CHECK_H

#include <stdbool.h>
#include <stdint.h>

#include "mesh/mesh_internal.h"
#include "meshtopo/face_list.h"

/* Builds a mesh from a face list (and frees the list); ends the test program
 * when the build fails. */
mt_mesh *edit_build(mt_face_list *list);

/* Copies of every array (up to its count) and every count of a mesh. */
typedef struct edit_snapshot {
    mt_mesh counts; /* the struct, pointers cleared */
    uint32_t *he_head, *he_next, *he_face, *face_he, *vert_he, *vert_component;
    double *positions;
    uint8_t *deleted; /* mt_vert_is_deleted per vertex */
    uint64_t edits;   /* mt_mesh_edit_count */
} edit_snapshot;

void edit_snapshot_take(const mt_mesh *m, edit_snapshot *out);
/* True when the mesh holds exactly what the snapshot saw. */
bool edit_snapshot_same(const mt_mesh *m, const edit_snapshot *snap);
void edit_snapshot_free(edit_snapshot *snap);

/* Live elements: faces with a ring, vertices not deleted, edges not deleted. */
typedef struct edit_counts {
    uint32_t verts, edges, faces;
    int64_t euler;
} edit_counts;
edit_counts edit_count(const mt_mesh *m);

#endif
