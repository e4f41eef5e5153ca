/* Polygons for the self-intersection oracle (selfx_oracle.c): the triangles
 * any triangulation of a face may use and which triangulations avoid a set
 * of them (so that a verdict is known not to depend on the library's ear
 * clipping), and the exact brute-force shape test of a closed polyline in
 * the library's best-fit plane (geometry.h, mt_face_shape_kind). */
#ifndef MESHTOPO_TESTS_SELFX_POLYGON_H
#define MESHTOPO_TESTS_SELFX_POLYGON_H

#include <stdbool.h>
#include <stdint.h>

#include "selfx_exact.h"

/* Faces with more corners are not judged by the oracle (C(n, 3) candidate
 * triangles and Catalan(n - 2) triangulations each). */
#define SX_MAX_POLYGON 12

/* Candidate triangles of an n-gon: every (i, j, k), i < j < k, of its
 * corners (each is in some triangulation), numbered C(k,3) + C(j,2) + i,
 * the same number whatever n. */
uint32_t sx_num_candidates(uint32_t n);
uint32_t sx_candidate_index(uint32_t i, uint32_t j, uint32_t k);

/* Whether some triangulation of an n-gon (3 <= n <= SX_MAX_POLYGON) uses no
 * candidate marked in `marked` (indexed by candidate number); a dynamic
 * program over the sub-polygons i..j. */
bool sx_has_unmarked_triangulation(uint32_t n, const bool *marked);

/* Calls visit(tris, ctx) with the n - 2 candidate numbers of every
 * triangulation of an n-gon; stops early and returns false when visit
 * does. */
bool sx_each_triangulation(uint32_t n, bool (*visit)(const uint32_t *tris, void *ctx), void *ctx);

/* The coordinate the library drops to project a polygon onto its best-fit
 * plane, and its warp: the library's own choice (mt__polygon_plane), so
 * that only the crossing decisions below are re-derived, exactly. */
void sx_polygon_plane(const double *const *corner, uint32_t n, int *out_drop, double *out_warp);

/* Whether sides i and j (side i runs from corner i to corner i + 1) of the
 * closed polyline pts[0..n) meet: consecutive sides only when they fold
 * back over each other, others when they share any point. pts are
 * projected points (third coordinate zero). */
bool sx_polyline_sides_meet(sx_pool *pool, const sx_vec *pts, uint32_t n, uint32_t i, uint32_t j);

/* Whether any two sides meet, by trying every pair; the first pair found
 * goes to *out_a < *out_b. xy holds the same points as doubles, for an
 * exact comparison of the sides' boxes first. */
bool sx_polyline_crosses(sx_pool *pool, const sx_vec *pts, const double (*xy)[2], uint32_t n,
                         uint32_t *out_a, uint32_t *out_b);

#endif
