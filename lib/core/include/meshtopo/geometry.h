/* Geometry of a built mesh with positions: face normals, areas and centroids,
 * angle-weighted vertex normals, angle deficits (discrete Gaussian curvature),
 * dihedral angles and convexity of edges, and whether the mesh bounds a
 * convex polytope. Answers are in the caller's vertex and face ids; outputs
 * are caller-owned (pass NULL or capacity 0 to learn the size, then fill).
 * Every function takes an mt_diag (NULL allowed) naming what is wrong and where.
 *
 * Conventions, shared by every function here:
 * - A polygon face is taken as given. Its vector area is Newell's
 *   (sum of (p[i] - p[0]) x (p[i+1] - p[0]) over the fan from its first
 *   vertex, halved); its normal is the vector area normalised, its area the
 *   vector area's length. For a planar polygon these are exact; for a
 *   non-planar one they describe its projection onto the best-fitting plane.
 * - A face is degenerate when its vector area is exactly zero (all vertices
 *   on one line, or a polygon whose signed pieces cancel). Its normal is the
 *   zero vector and its area 0; it never yields NaN. It adds nothing to vertex
 *   normals, and an edge on it has no dihedral angle (MT_EDGE_DEGENERATE).
 * - Corner angles: in a triangle the unsigned angle between its two sides; in
 *   a larger polygon the interior angle of the polygon projected onto the
 *   plane of its normal (so a reflex corner of a planar polygon counts more
 *   than pi, and a face of n sides has angles adding up to (n - 2) pi unless
 *   its projection winds around more than once). A degenerate polygon's
 *   corners get unsigned angles. Nothing yields NaN: a side of zero length
 *   counts as no turn (angle 0 in a triangle, pi in a polygon).
 * - Deleted elements (an edit sets face_he[f], vert_he[v] or both he_head of
 *   an edge to MT_NONE) and face records the build rejected are skipped by
 *   whole-mesh sweeps.
 * - A mesh built without positions gives MT_ERR_NO_GEOMETRY everywhere. */
#ifndef MESHTOPO_GEOMETRY_H
#define MESHTOPO_GEOMETRY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/mesh.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- faces ---------------------------------------------------------------- */

/* Unit normal of a face (3 doubles; the zero vector for a degenerate face).
 * Counter-clockwise faces seen from outside get outward normals.
 * MT_ERR_OUT_OF_RANGE for face >= mt_mesh_num_faces, MT_ERR_NOT_FOUND for a
 * face record the build rejected (or an edit deleted). */
mt_status mt_face_normal(const mt_mesh *mesh, uint32_t face, double out_normal[3], mt_diag *diag);

/* Area of a face: the length of its vector area (0 for a degenerate face). */
mt_status mt_face_area(const mt_mesh *mesh, uint32_t face, double *out_area, mt_diag *diag);

/* Centroid of a face's region: the area-weighted mean of the centroids of the
 * fan triangles (p[0], p[i], p[i+1]), each weighted by its signed area along
 * the face normal (so it is exact for any planar polygon, convex or not). A
 * degenerate face gets the mean of its vertices instead. */
mt_status mt_face_centroid(const mt_mesh *mesh, uint32_t face, double out_centroid[3],
                           mt_diag *diag);

/* Every face at once: out_normals gets 3 doubles per face record, out_areas
 * one (either may be NULL). capacity counts faces and must be at least
 * mt_mesh_num_faces; *out_count gets that number. Rejected and deleted face
 * records get a zero normal and area 0. */
mt_status mt_mesh_face_normals(const mt_mesh *mesh, double *out_normals, double *out_areas,
                               size_t capacity, size_t *out_count, mt_diag *diag);

/* ---- face shape ----------------------------------------------------------- */

/* What a polygon face's boundary looks like in its best-fit plane (the
 * least-squares plane of its corners; Newell's normal would be zero for a
 * bowtie). A triangle is always simple. */
typedef enum mt_face_shape_kind {
    MT_FACE_SIMPLE = 0,        /* its sides neither cross nor touch, its corners are on the plane */
    MT_FACE_SELF_CROSSING = 1, /* two sides cross or touch (a pentagram, a crossed quad); sides
                                  that fold back over each other count; corners at one position
                                  count as touching */
    MT_FACE_WARPED = 2,        /* simple, but a corner lies off the plane by more than
                                  MT_FACE_WARP_TOLERANCE of the face's size (a warped quad) */
} mt_face_shape_kind;

/* Corners farther from the best-fit plane than this fraction of the
 * diagonal of the corners' bounding box make a face warped. */
#define MT_FACE_WARP_TOLERANCE 1e-3

typedef struct mt_face_shape {
    uint32_t face;
    mt_face_shape_kind kind;
    /* MT_FACE_SELF_CROSSING: two sides that cross or touch, side_a < side_b;
     * side i runs from the face's vertex i to vertex i+1 (mt_face_verts
     * order). MT_NONE otherwise. */
    uint32_t side_a, side_b;
    /* The largest distance of a corner from the best-fit plane over the
     * diagonal of the corners' bounding box (0 for a triangle). */
    double warp;
} mt_face_shape;

/* The shape of one face, found by a sweep line over its sides (Shamos and
 * Hoey) in its best-fit plane: O(n log n) for n sides. A face with a corner
 * at NaN or infinity is not judged (reported simple; the report lists the
 * vertex as a nonfinite_coordinate). MT_ERR_OUT_OF_RANGE,
 * MT_ERR_NOT_FOUND (a rejected or deleted face), MT_ERR_NO_GEOMETRY. */
mt_status mt_face_shape_of(const mt_mesh *mesh, uint32_t face, mt_face_shape *out, mt_diag *diag);

/* Every face that is not simple (self-crossing or warped), in face order:
 * out gets up to capacity of them (NULL or 0 to learn how many), *out_count
 * how many there are; MT_ERR_BUFFER_TOO_SMALL when they do not fit. Rejected
 * and deleted face records are skipped. */
mt_status mt_mesh_nonsimple_faces(const mt_mesh *mesh, mt_face_shape *out, size_t capacity,
                                  size_t *out_count, mt_diag *diag);

/* A boundary loop (mt_boundary_loops) that crosses or touches itself in its
 * best-fit plane, and two of its edges that do (caller vertex pairs, in
 * the loop's order; edge_a comes first along the loop). */
typedef struct mt_loop_crossing {
    uint32_t loop; /* its index in mt_boundary_loops' order */
    uint32_t edge_a[2], edge_b[2];
} mt_loop_crossing;

/* Every boundary loop of four or more edges that crosses itself in its
 * best-fit plane (the sweep of mt_face_shape_of over the loop), in loop
 * order: out gets up to capacity (NULL or 0 to learn how many), *out_count
 * how many; MT_ERR_BUFFER_TOO_SMALL when they do not fit. A loop with a
 * corner at NaN or infinity is not judged. */
mt_status mt_mesh_boundary_loop_crossings(const mt_mesh *mesh, mt_loop_crossing *out,
                                          size_t capacity, size_t *out_count, mt_diag *diag);

/* ---- self-intersections --------------------------------------------------- */

/* Two faces, a < b. */
typedef struct mt_face_pair {
    uint32_t a, b;
} mt_face_pair;

/* Every pair of faces that meet other than at the vertices and along the
 * edges they share: faces that pass through each other, touch at a point
 * that is not a shared vertex, or fold onto each other across a shared
 * edge (coplanar, on the same side of it). Faces sharing all their corners
 * (duplicates) are reported too. Polygon faces are checked as the triangles
 * of their ear-clipping triangulation in their best-fit plane; the triangles
 * of one face are not checked against each other (mt_face_shape_of judges a
 * face on its own). Closed triangles; one whose corners are on a line (or
 * coincide) is the union of its sides, judged by the same rules (so such a
 * triangle whose side opposite a shared corner passes through that corner
 * counts as meeting the other face).
 *
 * Exact: every decision is an exact orientation test (meshtopo/predicates.h)
 * on the double coordinates, so the answer does not depend on rounding.
 * Pairs are candidates from a bounding-volume hierarchy over the triangles'
 * boxes (O(n log n) for n triangles, plus the pairs of triangles whose boxes
 * overlap), checked on every core for large meshes. A face with a corner at
 * NaN or infinity is not judged (the report lists the vertex as a
 * nonfinite_coordinate). Rejected and deleted face records are skipped.
 *
 * out gets up to capacity pairs in ascending (a, b) order (NULL or 0 to
 * learn how many), *out_count how many there are; MT_ERR_BUFFER_TOO_SMALL
 * when they do not fit. MT_ERR_NO_GEOMETRY without positions,
 * MT_ERR_NOMEM, MT_ERR_CORRUPT on a broken face ring. */
mt_status mt_mesh_self_intersections(const mt_mesh *mesh, mt_face_pair *out, size_t capacity,
                                     size_t *out_count, mt_diag *diag);

/* As mt_mesh_self_intersections, for callers that must bound what one
 * mesh may cost them (a service any node may send meshes to), with
 * MT_ERR_TOO_LARGE (*out_count 0) past either bound, whichever is passed
 * first:
 * - max_count pairs (a reply limit). The memory held stays within about
 *   twice max_count pairs per thread and the search stops soon after
 *   passing it; without the bound, n faces at one place make n^2/2 pairs.
 * - max_tests exact tests of two triangles whose boxes overlap, the work
 *   of the search (the boxes cost O(n log n) besides). A surface needs a
 *   few per triangle; n triangles piled closely on one another need
 *   n^2/2 whether or not they cross. Whether the bound is passed does not
 *   depend on the threads: the tests are counted, not timed.
 * SIZE_MAX and UINT64_MAX leave a bound out. */
mt_status mt_mesh_self_intersections_at_most(const mt_mesh *mesh, size_t max_count,
                                             uint64_t max_tests, mt_face_pair *out, size_t capacity,
                                             size_t *out_count, mt_diag *diag);

/* ---- vertices ------------------------------------------------------------- */

/* Angle-weighted vertex normal (Thuermer and Wuethrich 1998): the sum of the
 * unit normals of the faces around the vertex, each weighted by the face's
 * corner angle at the vertex, normalised. A non-manifold vertex sums over all
 * its fans. The zero vector when nothing contributes (a vertex in no face, or
 * only in degenerate faces, or whose weighted normals cancel). */
mt_status mt_vert_normal(const mt_mesh *mesh, uint32_t vert, double out_normal[3], mt_diag *diag);

/* Angle deficit of a vertex: 2 pi minus the sum of its corner angles in every
 * face around it (all fans of a non-manifold vertex). On the boundary (some
 * edge at the vertex is used by exactly one face) the deficit is pi minus the
 * sum instead: the turning (geodesic curvature) of the boundary there, so that
 * Gauss-Bonnet reads sum of deficits = 2 pi chi for any manifold mesh, open or
 * closed. Sides split only by a non-manifold or same-direction edge are not
 * boundary. A vertex in no face (isolated, or deleted) gets 0 and is not on
 * the boundary: it is not part of the surface, so over a mesh with isolated
 * vertices the deficits add up to 2 pi (chi - isolated vertices).
 * out_boundary may be NULL. */
mt_status mt_vert_angle_deficit(const mt_mesh *mesh, uint32_t vert, double *out_deficit,
                                bool *out_boundary, mt_diag *diag);

/* Every vertex at once, indexed by caller vertex id: out_normals gets 3
 * doubles per vertex (or NULL), out_deficits one (or NULL), out_boundary one
 * flag (or NULL). capacity counts vertices and must be at least
 * mt_mesh_num_verts; *out_count gets that number. Linear time. */
mt_status mt_mesh_vert_curvature(const mt_mesh *mesh, double *out_normals, double *out_deficits,
                                 bool *out_boundary, size_t capacity, size_t *out_count,
                                 mt_diag *diag);

/* ---- edges ---------------------------------------------------------------- */

/* How an edge bends. The first three are for an edge with exactly two faces
 * crossing it in opposite directions, both non-degenerate; the others say
 * why an edge has no single dihedral angle. */
typedef enum mt_edge_shape {
    MT_EDGE_CONVEX,       /* interior dihedral angle below pi - tolerance (a ridge) */
    MT_EDGE_FLAT,         /* within tolerance of pi */
    MT_EDGE_REFLEX,       /* above pi + tolerance (a valley) */
    MT_EDGE_BOUNDARY,     /* used by one face */
    MT_EDGE_NONMANIFOLD,  /* used by more than two faces */
    MT_EDGE_INCONSISTENT, /* two faces crossing it in the same direction */
    MT_EDGE_DEGENERATE    /* a face on it is degenerate: no normal */
} mt_edge_shape;

/* Short English name of a shape ("convex", "reflex", ...); never NULL. */
const char *mt_edge_shape_name(mt_edge_shape shape);

/* Interior dihedral angle of edge {a, b} (either order), in [0, 2 pi): the
 * angle between its two faces measured inside the surface, where the inside
 * is the side the face normals point away from. pi is flat, pi/2 a cube
 * edge, acos(1/3) a regular tetrahedron's, above pi a reflex (valley) edge.
 * It is pi minus the signed angle between the two face normals, the sign
 * positive when the edge bends away from the normals (a ridge).
 * MT_ERR_OUT_OF_RANGE for a bad vertex id, MT_ERR_NOT_FOUND when no face has
 * {a, b} as a side, MT_ERR_UNSUPPORTED when the edge has no single dihedral
 * angle: a boundary edge, an edge used by more than two faces or by two faces
 * running the same way, or one with a degenerate face (mt_edge_convexity
 * says which). */
mt_status mt_edge_dihedral_angle(const mt_mesh *mesh, uint32_t a, uint32_t b, double *out_angle,
                                 mt_diag *diag);

/* Shape of edge {a, b}: convex, flat or reflex when its interior dihedral
 * angle is below, within `tolerance` (radians, >= 0) of, or above pi; else
 * why it has no dihedral angle. Errors as mt_edge_dihedral_angle, except that
 * an edge without a dihedral angle gives MT_OK and its shape. */
mt_status mt_edge_convexity(const mt_mesh *mesh, uint32_t a, uint32_t b, double tolerance,
                            mt_edge_shape *out_shape, mt_diag *diag);

/* Every edge at once, each undirected caller edge once (an edge the build
 * split among several internal edges included), in internal edge order.
 * out_edges gets 2 vertex ids per edge (smaller first), out_angles the
 * interior dihedral angle (0 where there is none: see out_shapes),
 * out_shapes the shape under `tolerance`; any of the three may be NULL.
 * capacity counts edges; *out_count gets the number of edges (the report's
 * num_edges on a freshly built mesh). Deleted edges are skipped. */
mt_status mt_mesh_dihedral_angles(const mt_mesh *mesh, double tolerance, uint32_t *out_edges,
                                  double *out_angles, mt_edge_shape *out_shapes, size_t capacity,
                                  size_t *out_count, mt_diag *diag);

/* ---- the whole mesh ------------------------------------------------------- */

/* Why a mesh does not bound a convex polytope: bits of mt_convexity.reasons. */
typedef enum mt_convexity_reason {
    MT_NONCONVEX_EMPTY = 1u << 0,           /* no valid face */
    MT_NONCONVEX_OPEN = 1u << 1,            /* has boundary edges */
    MT_NONCONVEX_NONMANIFOLD = 1u << 2,     /* a non-manifold edge or vertex */
    MT_NONCONVEX_INCONSISTENT = 1u << 3,    /* not orientable, or faces not consistently oriented */
    MT_NONCONVEX_COMPONENTS = 1u << 4,      /* more than one connected component */
    MT_NONCONVEX_NOT_SPHERE = 1u << 5,      /* Euler characteristic of the surface is not 2 */
    MT_NONCONVEX_DEGENERATE_FACE = 1u << 6, /* a degenerate face */
    MT_NONCONVEX_REFLEX_EDGE = 1u << 7,     /* some edge is reflex (listed) */
    MT_NONCONVEX_SADDLE_VERTEX = 1u << 8,   /* a vertex's angle deficit is below -tolerance */
    MT_NONCONVEX_INWARD = 1u << 9           /* enclosed volume is not positive: faces turn inward */
} mt_convexity_reason;

typedef struct mt_convexity {
    bool convex;           /* reasons == 0 */
    uint32_t reasons;      /* mt_convexity_reason bits */
    size_t num_reflex;     /* reflex edges (listed in out_reflex_edges) */
    size_t num_degenerate; /* degenerate faces */
    double volume;         /* signed enclosed volume (divergence theorem); 0 unless closed */
} mt_convexity;

/* Whether the mesh bounds a convex polytope: closed, one component, the
 * surface's Euler characteristic 2 (isolated vertices do not count),
 * orientable, manifold and consistently oriented (from the build's report),
 * no degenerate face, no reflex edge and no vertex with negative angle
 * deficit (both under `tolerance`, radians >= 0), and positive volume, so
 * the faces run counter-clockwise seen from outside. A closed surface that
 * is locally convex at every edge and vertex bounds a convex body (van
 * Heijenoort 1952). Non-planar polygons are judged by their normals only.
 * The geometric checks run whatever the topology, so an open or non-manifold
 * mesh still gets its reflex edges listed; INWARD is judged on closed,
 * consistently oriented meshes only. Boundary, non-manifold and
 * same-direction edges are found on the current structure; components,
 * Euler characteristic, orientability and non-manifold vertices come from
 * the report (after edits, as current as edit.h keeps it). Linear time; allocates one normal per
 * face and two values per vertex (MT_ERR_NOMEM). out_reflex_edges gets 2 caller vertex ids (smaller
 * first) per reflex edge, in internal edge order; capacity counts edges and may be 0 (with NULL) to
 * learn out->num_reflex. MT_ERR_BUFFER_TOO_SMALL when the list does not fit:
 * *out is still filled. */
mt_status mt_mesh_convexity(const mt_mesh *mesh, double tolerance, mt_convexity *out,
                            uint32_t *out_reflex_edges, size_t capacity, mt_diag *diag);

/* Writes the names of the reason bits ("open, reflex_edge") into buf (always
 * NUL-terminated when size > 0); "convex" for 0. Returns the length the full
 * text needs, like snprintf. */
size_t mt_convexity_describe(uint32_t reasons, char *buf, size_t size);

#ifdef __cplusplus
}
#endif

#endif
