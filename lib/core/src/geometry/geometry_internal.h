/* Steps shared by the geometry files (geometry_*.c): positions of internal
 * vertices, the vector area of a face ring and corner angles. Every walk is
 * bounded and every index range-checked as in the queries (query_internal.h),
 * so a corrupted mesh gives MT_ERR_CORRUPT, never a bad read. Conventions are
 * stated once, in meshtopo/geometry.h. */
#ifndef MESHTOPO_GEOMETRY_INTERNAL_H
#define MESHTOPO_GEOMETRY_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "meshtopo/geometry.h"
#include "query/query_internal.h"

#define MT__PI 3.14159265358979323846

/* MT_OK when mesh is non-NULL and has positions, else the status (with diag
 * naming `what`, the calling function). */
mt_status mt__geom_ready(const mt_mesh *m, const char *what, mt_diag *diag);

/* Position of internal vertex v (its caller vertex's), NULL when v is out of range. */
static inline const double *mt__geom_pos(const mt_mesh *m, uint32_t v)
{
    uint32_t o = mt__original_checked(m, v);
    return o == MT_NONE ? NULL : m->positions + 3 * (size_t)o;
}

static inline void mt__v3_sub(const double *a, const double *b, double *out)
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

static inline void mt__v3_cross(const double *a, const double *b, double *out)
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

static inline double mt__v3_dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Twice the vector area of the face ring through half-edge h (Newell's
 * normal, summed over the fan from the ring's first vertex) into out, and the
 * ring's length into *out_size. MT_ERR_CORRUPT on a broken ring. */
mt_status mt__face_ring_area2(const mt_mesh *m, uint32_t h, double out[3], uint32_t *out_size);

/* Unit normal from twice the vector area: false (and the zero vector) when
 * the vector area is zero or not finite. */
bool mt__unit(const double area2[3], double out[3]);

/* Corner angle at the head of half-edge h_in in its face, whose unit normal
 * is unit_normal (the zero vector for a degenerate face) and size face_size.
 * h_in's next must be valid (checked by the caller's ring walk). */
double mt__corner_angle(const mt_mesh *m, uint32_t h_in, const double unit_normal[3],
                        uint32_t face_size);

/* Unit normal of face f (zero vector when degenerate) and its size; false
 * in *out_ok when degenerate. MT_ERR_CORRUPT on a broken ring. The face must
 * be valid (face_he[f] != MT_NONE). */
mt_status mt__face_unit_normal(const mt_mesh *m, uint32_t f, double out[3], uint32_t *out_size,
                               bool *out_ok);

/* Called by mt__edge_sweep once per undirected caller edge {a, b} (a < b)
 * with its shape and interior angle (0 when it has none). */
typedef void (*mt__edge_visit)(void *user, uint32_t a, uint32_t b, mt_edge_shape shape,
                               double angle);

/* Visits every edge of the mesh (deleted ones skipped, a split edge once) in
 * internal edge order, shapes judged under tol. Allocates one normal per face
 * (MT_ERR_NOMEM); MT_ERR_CORRUPT on a broken structure. `what` names the
 * public call in diag. The mesh must have positions. */
mt_status mt__edge_sweep(const mt_mesh *m, double tol, const char *what, mt__edge_visit visit,
                         void *user, mt_diag *diag);

/* The plane a polygon's shape is judged in (geometry_simple.c): the axis
 * to drop to project onto its least-squares plane (the normal's largest;
 * for corners on one line, the bounding box's smallest), and how far the
 * corners leave that plane over the diagonal of their bounding box. n >= 3. */
void mt__polygon_plane(const double *const *corner, uint32_t n, int *out_drop, double *out_warp);

/* The orientations of points q[0..n) against the plane through a, b, c,
 * as mt_orient3d(a, b, c, q[i]) gives them (predicates.c), the plane's
 * share of the work done once. */
void mt__orient3d_points(const double a[3], const double b[3], const double c[3],
                         const double *const *q, int n, int *out);

/* Whether the diagonal between corners i and j of a polygon may be cut. */
typedef bool (*mt__diagonal_ok)(void *user, uint32_t i, uint32_t j);

/* Cuts the polygon with corner positions pos[0..n) (n >= 3) into n - 2
 * triangles by ear clipping in the plane of its Newell normal: out_tris gets
 * 3 (n - 2) corner indices, each triangle in the polygon's orientation. A
 * corner that is no geometric ear is cut only when none is (a self-crossing
 * polygon); pos NULL makes every corner an ear. diagonal_ok (NULL: any) may
 * forbid diagonals; false when every diagonal left to cut is forbidden.
 * rem is scratch for n indices. */
bool mt__ear_clip(const double *const *pos, uint32_t n, mt__diagonal_ok diagonal_ok, void *user,
                  uint32_t *rem, uint32_t *out_tris);

/* A triangle of a face (polygons give several): its corners' caller ids,
 * in the face's orientation. */
typedef struct mt__tri {
    uint32_t v[3];
    uint32_t face;
} mt__tri;

/* Which caller vertices have flat fans (flat_fans.c): flat[v] stays 1 when
 * v's faces are one closed fan of triangles that projects one-to-one onto a
 * coordinate plane, so that two of them meet only at v and along the sides
 * they share (exact tests), and becomes 0 otherwise. On entry flat[v] is 0
 * for vertices already known not to qualify (corners of polygon faces and
 * of faces left out), 1 for the others. tris are every triangle of the
 * mesh's faces, read in the order given; `threads` share the vertices. */
mt_status mt__flat_fans(const mt_mesh *m, const mt__tri *tris, uint32_t num_tris, uint32_t threads,
                        uint8_t *flat);

/* Whether triangles a and b of two different faces (caller corner ids ia,
 * ib; corner positions pa, pb) meet other than at the corners they share and
 * along a side they share: the rules of mt_mesh_self_intersections, decided
 * by exact predicates (intersect.c). */
bool mt__triangles_cross(const uint32_t ia[3], const double *const pa[3], const uint32_t ib[3],
                         const double *const pb[3]);

#endif
