/* Helpers for the geometry tests (test_geometry*.c): building a mesh from
 * arrays or a generator and validating it, a deterministic random source, a
 * small incremental convex hull for random point sets, and angle
 * comparisons that print both values. */
#ifndef MESHTOPO_TEST_GEOMETRY_MESH_H
#define MESHTOPO_TEST_GEOMETRY_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/core.h"

/* Builds (non-strict) and validates; records a failure and returns NULL when
 * either fails. `what` names the mesh in messages. */
mt_mesh *geom_build(const mt_face_list *list, const char *what);

/* The same from plain arrays (positions may be NULL). */
mt_mesh *geom_build_arrays(uint32_t num_verts, const double *positions, uint32_t num_faces,
                           const uint32_t *sizes, const uint32_t *indices, const char *what);

/* A generator's mesh: kind is an mt_platonic. */
mt_mesh *geom_build_platonic(int kind);

/* Checks |got - want| <= tol, printing both. */
#define CHECK_NEAR(got, want, tol) geom_check_near((got), (want), (tol), #got, __FILE__, __LINE__)
void geom_check_near(double got, double want, double tol, const char *expr, const char *file,
                     int line);

/* Deterministic uniform doubles in [0, 1) (splitmix64). */
double geom_random(uint64_t *state);

/* Convex hull of n points (3 doubles each, in general position) as a closed
 * triangle mesh with counter-clockwise faces seen from outside, by the
 * incremental algorithm (O(n^2)). Only hull points are kept as vertices;
 * *out is allocated (mt_face_list_free). Returns false when the points are
 * all coplanar or memory runs out. */
int geom_convex_hull(const double *points, uint32_t n, mt_face_list *out);

#endif
