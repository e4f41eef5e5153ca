/* Structural self-check of a built (or edited) half-edge mesh. */
#ifndef MESHTOPO_VALIDATE_H
#define MESHTOPO_VALIDATE_H

#include "meshtopo/mesh.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Checks every invariant of the structure: array bounds of every stored
 * index, twin of twin, next is a permutation whose cycles are the face and
 * boundary rings, every half-edge of a face ring names that face and every
 * boundary ring has no face, next(h) starts where h ends, each face's
 * half-edge lies on its ring, each vertex's outgoing half-edge starts at it and
 * is a boundary half-edge when the vertex has one, one rotation around each
 * vertex visits all its outgoing half-edges, and vertex copies and edge
 * bundles are consistent. Returns MT_OK or MT_ERR_CORRUPT with diag naming
 * the first broken invariant and the element. Linear time. */
mt_status mt_mesh_validate(const mt_mesh *mesh, mt_diag *diag);

#ifdef __cplusplus
}
#endif

#endif
