/* Test and demo meshes as face lists: the Platonic solids, the seed
 * rectangle (also closed into a sphere, as a built mesh with hidden
 * elements), grids, tori, spheres, a genus-2 surface, the classic defective
 * shapes, and the dual of a built mesh. Every generator allocates *out (free it with
 * mt_face_list_free) and returns MT_OK, MT_ERR_INVALID_ARG for sizes out of
 * its documented range, MT_ERR_TOO_LARGE when the counts would not fit in
 * 32 bits, or MT_ERR_NOMEM; on failure *out is zeroed. All faces are consistently oriented
 * (counter-clockwise seen from outside) unless the shape cannot be. */
#ifndef MESHTOPO_GENERATE_H
#define MESHTOPO_GENERATE_H

#include <stdbool.h>
#include <stdint.h>

#include "meshtopo/face_list.h"
#include "meshtopo/mesh.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mt_platonic {
    MT_TETRAHEDRON,  /* 4 vertices, 4 triangles */
    MT_CUBE,         /* 8 vertices, 6 quads */
    MT_OCTAHEDRON,   /* 6 vertices, 8 triangles */
    MT_DODECAHEDRON, /* 20 vertices, 12 pentagons */
    MT_ICOSAHEDRON   /* 12 vertices, 20 triangles */
} mt_platonic;

/* A Platonic solid centred at the origin with circumradius 1. */
mt_status mt_gen_platonic(mt_platonic kind, mt_face_list *out);

/* The seed article's rectangle: vertices (0,0,0), (w,0,0), (w,h,0), (0,h,0)
 * and two triangles (0,1,2), (0,2,3) sharing the diagonal v0-v2. */
mt_status mt_gen_rectangle(double width, double height, mt_face_list *out);

/* The seed's rectangle closed into a sphere, built: its two triangles
 * (0, 1, 2), (0, 2, 3) in front and two more, (1, 0, 3), (3, 2, 1), behind on
 * the same four corners (4 faces, 6 edges, Euler characteristic 2), with the
 * two faces behind and the front diagonal 0-2 hidden (meshtopo/attributes.h),
 * so that what is shown is the rectangle. On MT_OK *out_mesh is the
 * caller's (mt_mesh_destroy). MT_ERR_INVALID_ARG for sizes that are not
 * finite and positive, MT_ERR_NOMEM. */
mt_status mt_gen_closed_rectangle(double width, double height, mt_mesh **out_mesh, mt_diag *diag);

/* A flat grid of nx by ny unit cells in the z = 0 plane with one boundary loop.
 * triangles: each cell split into two triangles (2*nx*ny faces); otherwise
 * nx*ny quads. Vertex (i, j) has id j*(nx+1)+i. nx, ny >= 1. */
mt_status mt_gen_grid(uint32_t nx, uint32_t ny, bool triangles, mt_face_list *out);

/* A closed torus (genus 1) of nu by nv cells split into triangles
 * (2*nu*nv faces), major radius 1, minor radius 0.25. nu, nv >= 3. */
mt_status mt_gen_torus(uint32_t nu, uint32_t nv, mt_face_list *out);

/* An icosahedron subdivided `level` times (20 * 4^level triangles) and
 * projected onto the unit sphere. level <= 10. */
mt_status mt_gen_icosphere(uint32_t level, mt_face_list *out);

/* A closed orientable genus-2 surface (a "double torus"): two tori joined
 * through a tube, all triangles. segments >= 4 controls its resolution. */
mt_status mt_gen_double_torus(uint32_t segments, mt_face_list *out);

/* A Moebius strip of `segments` quads (segments >= 3): non-orientable, one
 * boundary loop. */
mt_status mt_gen_moebius(uint32_t segments, mt_face_list *out);

/* Two triangles sharing only vertex 0: a bowtie (non-manifold vertex). */
mt_status mt_gen_bowtie(mt_face_list *out);

/* Three triangles sharing edge 0-1: a fin (non-manifold edge). */
mt_status mt_gen_fin(mt_face_list *out);

/* The dual of a built mesh (Platonic duality): dual vertex f for each face
 * record f, at the face's centroid (mt_face_centroid; the origin for a
 * record the build rejected, or without positions when the mesh has none);
 * a dual face for each closed fan of faces around a vertex, its corners the
 * fan's faces in ring order (counter-clockwise: orientation is kept), in
 * vertex order, a non-manifold vertex giving one per closed fan. On a
 * boundary the rule is: an open fan gives no face, so the dual of a mesh
 * with boundary covers only its interior vertices. For a closed manifold
 * mesh dual face v is vertex v, and the dual of the dual has the original's
 * faces (each face's corners up to rotation). MT_ERR_INVALID_ARG,
 * MT_ERR_NOMEM. */
mt_status mt_gen_dual(const mt_mesh *mesh, mt_face_list *out, mt_diag *diag);

#ifdef __cplusplus
}
#endif

#endif
