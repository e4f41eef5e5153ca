/* Exact orientation predicates: the sign of a determinant of double
 * coordinates as if it were computed in exact arithmetic, so that a test
 * never misclassifies a point because of rounding (collinear and coplanar
 * inputs give exactly 0). A fast floating-point evaluation decides whenever
 * its error bound allows; otherwise the determinant is summed exactly as an
 * expansion of doubles. Geometric checks of meshtopo (self-intersections)
 * are built on these.
 *
 * Exactness holds while no intermediate product overflows or underflows:
 * for coordinates and their differences that are zero or between 2^-250
 * and 2^250 in magnitude (any mesh in metres, millimetres or kilometres).
 * A NaN or infinite coordinate gives 0 (the intersection tests then treat
 * the point as on every line and plane). Pure functions, any thread. */
#ifndef MESHTOPO_PREDICATES_H
#define MESHTOPO_PREDICATES_H

#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The sign of (b - a) x (c - a): +1 when a, b, c turn counterclockwise
 * (c left of the line from a to b), -1 clockwise, 0 when collinear. */
int mt_orient2d(const double a[2], const double b[2], const double c[2]);

/* The sign of ((b - a) x (c - a)) . (d - a): +1 when d lies on the side of
 * the plane through a, b, c that its right-hand normal points to (a, b, c
 * counterclockwise seen from d), -1 on the other side, 0 when the four
 * points are coplanar. */
int mt_orient3d(const double a[3], const double b[3], const double c[3], const double d[3]);

/* Exact intersection tests built on the two predicates above, for closed
 * sets (touching counts). A triangle whose corners lie on one line, or
 * coincide, counts as the union of its sides. Same range of exactness. */

/* Whether the segment from s to e and the triangle t[0], t[1], t[2] share
 * a point. */
bool mt_segment_hits_triangle(const double s[3], const double e[3], const double t[3][3]);

/* Whether triangles a and b share a point. */
bool mt_triangles_intersect(const double a[3][3], const double b[3][3]);

#ifdef __cplusplus
}
#endif

#endif
