/* Helpers of the restore tests: whether two meshes answer every query the
 * same way (rings, valences, face vertices and neighbours, edge faces,
 * components, boundary loops, positions, report), so that a restored mesh
 * can be checked against the mesh built from the same face list. */
#ifndef MESHTOPO_TEST_RESTORE_CHECK_H
#define MESHTOPO_TEST_RESTORE_CHECK_H

#include <stdbool.h>

#include "meshtopo/mesh.h"

/* True when a and b answer every query identically; otherwise prints the
 * first difference (prefixed by what) and returns false. */
bool rc_same_answers(const mt_mesh *a, const mt_mesh *b, const char *what);

#endif
