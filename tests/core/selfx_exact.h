/* Exact geometry for the self-intersection oracle (selfx_oracle.c): closed
 * segments and triangles tested in GMP integers, on coordinates that are
 * the mesh's doubles converted exactly (mpq_set_d) and scaled by one power
 * of two so that every one is an integer. Written apart from
 * lib/core/src/geometry/intersect.c on purpose: Cramer's rule and parameter ranges
 * instead of orientation signs, no projections, every case spelled out. */
#ifndef MESHTOPO_TESTS_SELFX_EXACT_H
#define MESHTOPO_TESTS_SELFX_EXACT_H

#include <gmp.h>
#include <stdbool.h>
#include <stdint.h>

/* A point or vector of three integers (views into caller-owned mpz_t). */
typedef struct sx_vec {
    mpz_ptr c[3];
} sx_vec;

/* Temporaries, taken and given back in stack order so that no test
 * allocates once the pool is warm. */
#define SX_POOL_SIZE 160
typedef struct sx_pool {
    mpz_t z[SX_POOL_SIZE];
    int top;
} sx_pool;

void sx_pool_init(sx_pool *pool);
void sx_pool_clear(sx_pool *pool);

/* Whether the closed segments [s, e] and [p, q] share a point (either may
 * be a single point). */
bool sx_segments_meet(sx_pool *pool, sx_vec s, sx_vec e, sx_vec p, sx_vec q);

/* Whether the closed segment [s, e] and the closed triangle t share a point;
 * a triangle whose corners are on one line is the union of its sides. */
bool sx_segment_meets_triangle(sx_pool *pool, sx_vec s, sx_vec e, const sx_vec t[3]);

/* Whether two closed triangles share a point: an edge of one meets the other. */
bool sx_triangles_meet(sx_pool *pool, const sx_vec a[3], const sx_vec b[3]);

/* Whether two triangles of different faces, with corners ids_a and ids_b
 * (caller vertex ids), meet other than where they should:
 *   no shared id: they share any point;
 *   one shared id v: the side opposite v in either meets the other;
 *   two shared ids u, w: they share a point off the segment uw. For two
 *     proper triangles: the four corners are coplanar and the third
 *     corners lie strictly on the same side of the line uw. A triangle
 *     with its corners on a line is a segment: next to a proper triangle
 *     it never counts; two segments along the line uw count when both
 *     third corners lie past the same end of uw; with u and w at one
 *     point, when the segments from it to x and to y point the same way;
 *   three: always (a duplicate). */
bool sx_triangles_clash(sx_pool *pool, const uint32_t ids_a[3], const sx_vec a[3],
                        const uint32_t ids_b[3], const sx_vec b[3]);

/* The normal (b - a) x (c - a) of triangle t into out (zero when its
 * corners are on one line). */
void sx_triangle_normal(const sx_vec t[3], sx_vec out);

/* Whether every corner of b whose id is not a corner of a lies strictly on
 * one side of the plane of a (normal_a its sx_triangle_normal, non-zero).
 * Then neither the no-shared-id nor the one-shared-id rule reports the
 * pair: a sound shortcut, which selfx_oracle --no-filter switches off. */
bool sx_plane_separates(sx_pool *pool, const uint32_t ids_a[3], const sx_vec a[3], sx_vec normal_a,
                        const uint32_t ids_b[3], const sx_vec b[3]);

/* Whether two consecutive sides [a, q] and [q, b] of a polygon share more
 * than their corner q (they fold back over each other). */
bool sx_sides_fold(sx_pool *pool, sx_vec a, sx_vec q, sx_vec b);

#endif
