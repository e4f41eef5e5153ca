/* Editing a built half-edge mesh in place: split, flip and collapse edges,
 * split and triangulate faces, add faces and vertices, delete faces, edges and
 * vertices, and compact away what was deleted. Each edit costs time linear in
 * the neighbourhood it touches and keeps every invariant mt_mesh_validate
 * checks. Edges are named by their two caller vertex ids, as in query.h.
 *
 * Contract shared by every edit:
 *  - Manifold meshes only. A mesh whose build made vertex copies or edge
 *    bundles (non-manifold vertices or edges, see mesh.h) gets
 *    MT_ERR_UNSUPPORTED from every edit ("mesh has 3 non-manifold vertices;
 *    edits need a manifold mesh"): the copies' internal ids would collide with
 *    new vertex ids. mt_mesh_compact works on any mesh.
 *  - Atomic. A refused or failed edit leaves every array and count of the mesh
 *    byte-identical (arrays may have been moved to a larger allocation). It
 *    returns MT_ERR_REFUSED with diag naming the elements and the reason, or
 *    MT_ERR_OUT_OF_RANGE for an id past the counts, MT_ERR_NOT_FOUND for a
 *    deleted (or rejected) element or a missing edge, MT_ERR_NOMEM when an
 *    allocation fails. Every edit writes an undo log and replays it on failure.
 *  - New elements get the next ids: vertices num_verts, num_verts + 1, ...,
 *    faces num_faces, ...; positions grow with the vertices (a mesh without
 *    geometry stays without). Arrays grow geometrically.
 *  - Deleting marks: a deleted face has face_he[f] == MT_NONE, a deleted
 *    vertex vert_he[v] == MT_NONE (mt_vert_is_deleted tells it from an
 *    isolated one), a deleted internal edge e has he_head[2e] == he_head[2e+1]
 *    == MT_NONE (and he_face MT_NONE, he_next pointing at itself). Read-only
 *    code skips them; the queries of query.h do. Faces and vertices left
 *    without faces by a deletion stay as isolated vertices, not deleted ones.
 *    mt_mesh_compact removes the marked elements and renumbers.
 *  - The report: mt_mesh_report keeps describing the last build or compaction,
 *    except for these counts, which every edit keeps current: num_verts,
 *    num_faces, num_faces_valid, num_edges and euler_characteristic (deleted
 *    vertices left out of V). Everything else (boundary loops, components,
 *    genus, defects) is brought up to date by mt_mesh_compact, which rebuilds
 *    the report; mt_mesh_edit_count says how many edits the report lags. The
 *    component of a face (mt_face_component) is that of the last report for
 *    old faces and of the touched neighbourhood for new ones.
 *  - Surfaces stay manifold: an edit that would leave a vertex with two
 *    separate boundary gaps (a bowtie), an edge joining two vertices twice,
 *    a face with a repeated vertex or an interior vertex left between just
 *    two triangles (which then close up on their own, a "pillow") is
 *    refused. */
#ifndef MESHTOPO_EDIT_H
#define MESHTOPO_EDIT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/mesh.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Splits edge a-b by a new vertex m (id num_verts; *out_vert gets it when not
 * NULL) at `position` (3 doubles) or, when position is NULL, at the edge's
 * midpoint. A triangle on the edge is split in two by a new edge from m to
 * its opposite vertex (the old face keeps its id and the part holding its
 * first vertex, the other part gets a new id); a polygon face with more than
 * three sides is not split: m is inserted as one more corner. An interior edge
 * between two triangles gives +1 vertex, +3 edges, +2 faces; a boundary edge
 * +1 vertex, +2 edges, +1 face.
 *
 *         c                     c
 *        / \                   /|\
 *       /   \                 / | \
 *      a-----b      ->       a--m--b
 *       \   /                 \ | /
 *        \ /                   \|/
 *         d                     d
 */
mt_status mt_edge_split(mt_mesh *mesh, uint32_t a, uint32_t b, const double *position,
                        uint32_t *out_vert, mt_diag *diag);

/* Flips edge a-b between two triangles (a, b, c) and (b, a, d) to c-d; the
 * two faces keep their ids. Refused when the edge is on the boundary, either
 * face is not a triangle, or c and d are already joined by an edge.
 *
 *         c                     c
 *        / \                   /|\
 *       /   \                 / | \
 *      a-----b      ->       a  |  b
 *       \   /                 \ | /
 *        \ /                   \|/
 *         d                     d
 */
mt_status mt_edge_flip(mt_mesh *mesh, uint32_t a, uint32_t b, mt_diag *diag);

/* Collapses edge a-b into vertex b: a is deleted, its edges move to b, a
 * triangle on the edge disappears (its face id is deleted, its two other
 * edges become one), a polygon on the edge loses corner a. b moves to
 * `position` when given, else keeps its position. Refused when the link
 * condition fails (a and b have a common neighbour other than the third
 * corner of a triangle on the edge), when a and b are both on the boundary
 * but the edge is not, or when the result would be degenerate (an interior
 * vertex left between just two triangles, as any collapse of a tetrahedron
 * gives, or a triangle on the edge whose two other sides are both boundary). Interior edge between
 * two triangles: -1 vertex, -3 edges, -2 faces.
 *
 *         c                     c
 *        / \                    |
 *       /   \                   |
 *      a-----b      ->          b
 *       \   /                   |
 *        \ /                    |
 *         d                     d
 */
mt_status mt_edge_collapse(mt_mesh *mesh, uint32_t a, uint32_t b, const double *position,
                           mt_diag *diag);

/* Splits a face by the diagonal a-b between two of its corners that are not
 * neighbours in it. The face keeps its id and the part holding its first
 * vertex; the other part gets a new id (*out_face when not NULL). Refused
 * when a and b are neighbours in the face or already joined by an edge.
 *
 *      d-----c               d-----c
 *      |     |               |   / |
 *      |     |      ->       |  /  |
 *      |     |               | /   |
 *      a-----b               a-----b      (split by a-c)
 */
mt_status mt_face_split(mt_mesh *mesh, uint32_t face, uint32_t a, uint32_t b, uint32_t *out_face,
                        mt_diag *diag);

/* Triangulates one polygon face by ear clipping: with positions, an ear is a
 * convex corner (in the plane of the face's Newell normal) whose triangle
 * holds no other corner, so non-convex planar polygons get triangles that
 * do not overlap, which a fan from one corner would not give; without
 * positions (or when no such ear is left, as in a degenerate polygon) any
 * corner is an ear. A corner is never used as an ear when its diagonal is
 * already an edge of the mesh. The face keeps its id for its first triangle,
 * the others get new ids; *out_new_faces (when not NULL) gets how many.
 * A triangle is left alone. Refused when every remaining diagonal is already
 * an edge, and, with positions, when the face crosses itself in its
 * best-fit plane (a pentagram, a crossed quad: mt_face_shape_of), naming the
 * two sides; its triangles would fold over each other.
 *
 *      d-----c               d-----c
 *      |     |               | \   |
 *      |     |      ->       |   \ |
 *      a-----b               a-----b      (quad: one diagonal, two triangles)
 */
mt_status mt_face_triangulate(mt_mesh *mesh, uint32_t face, uint32_t *out_new_faces, mt_diag *diag);

/* Joins the two faces on either side of edge a-b into one polygon (the
 * face merge of the proof of Euler's formula): the face holding a -> b keeps
 * its id (*out_face, when not NULL) and gets the corners of both around the
 * edge, the other face's record is deleted, and the edge disappears, so V -
 * E + F is unchanged.
 *
 *      d-----c               d-----c
 *      |  f1 |               |     |
 *      a-----b      ->       a     b      (a quad: f1 and f2 become a hexagon)
 *      |  f2 |               |     |
 *      f-----e               f-----e
 *
 * Refused (MT_ERR_REFUSED, nothing changed) with the reason when the edge is
 * on a boundary (used by other than two faces), when one face is on both
 * sides, and when the faces share more than that edge (the joined face would
 * repeat a vertex); like every edit, MT_ERR_UNSUPPORTED on a non-manifold
 * mesh. */
mt_status mt_face_join(mt_mesh *mesh, uint32_t a, uint32_t b, uint32_t *out_face, mt_diag *diag);

/* Triangulates every face with more than three sides (as mt_face_triangulate),
 * all or nothing: a refusal on any face leaves the whole mesh unchanged. */
mt_status mt_mesh_triangulate(mt_mesh *mesh, mt_diag *diag);

/* Adds an isolated vertex (id num_verts, *out_vert) at `position` (ignored by
 * a mesh without geometry; NULL gives the origin). */
mt_status mt_mesh_add_vert(mt_mesh *mesh, const double *position, uint32_t *out_vert,
                           mt_diag *diag);

/* Adds face (verts[0], ..., verts[count-1]) with id num_faces (*out_face).
 * Refused when it would make the mesh non-manifold: a side already used by
 * two faces or by a face running the same direction, a corner at a vertex
 * whose fan is closed, or a corner at a boundary vertex that is not next to
 * the vertex's boundary gap (the fans would not join). Repeated or deleted
 * vertices and count < 3 give MT_ERR_INVALID_ARG / MT_ERR_NOT_FOUND.
 * Euler characteristic: +1 face, + the new edges, so it changes by
 * 1 - (new edges) + (new vertices = 0).
 *
 *      c                     c
 *      | \                   | \
 *      |  \         ->       |  \
 *      a---b   d             a---b
 *                             \ /
 *                              d          (add (a, d, b))
 */
mt_status mt_mesh_add_face(mt_mesh *mesh, const uint32_t *verts, uint32_t count, uint32_t *out_face,
                           mt_diag *diag);

/* Deletes a face: it is marked, its sides become boundary, an edge with no
 * face left is deleted, a vertex with no face left becomes isolated.
 * Refused when a corner of the face is a boundary vertex whose boundary gap
 * is not next to the face (deleting it would make a bowtie).
 *
 *      c---d                 c---d
 *      | / |        ->       | /
 *      a---b                 a   b        (face (a, b, d) deleted; b isolated)
 */
mt_status mt_face_delete(mt_mesh *mesh, uint32_t face, mt_diag *diag);

/* Deletes edge a-b with the faces on it (as mt_face_delete on each).
 *
 *      c---d                 c---d
 *      | / |        ->       |   |  (edge a-d and both triangles deleted:
 *      a---b                 a   b   a-c, c-d, d-b stay only if other faces hold them)
 */
mt_status mt_edge_delete(mt_mesh *mesh, uint32_t a, uint32_t b, mt_diag *diag);

/* Deletes a vertex with every face around it; the vertex is marked deleted
 * (not merely isolated). Refused when a neighbour would be left with two
 * boundary gaps.
 *
 *      c---d                 c---d
 *      |\ /|                 |   |
 *      | v |        ->       |   |        (the hole's border is the old link)
 *      |/ \|                 |   |
 *      a---b                 a---b
 */
mt_status mt_vert_delete(mt_mesh *mesh, uint32_t vert, mt_diag *diag);

/* True when `vert` was deleted by an edit (false for an isolated vertex or an
 * id out of range). */
bool mt_vert_is_deleted(const mt_mesh *mesh, uint32_t vert);

/* Edits applied since the report was made (0 right after a build or a
 * compaction: the whole report describes the mesh). */
uint64_t mt_mesh_edit_count(const mt_mesh *mesh);

/* Removes deleted vertices, deleted faces, face records the build rejected
 * and deleted edges, renumbers what is left in the same order, and rebuilds
 * the report (so every field of mt_mesh_report is current again). The mesh
 * pointer stays valid. The maps are caller-owned and optional (NULL skips
 * one): out_vert_map needs mt_mesh_num_verts(mesh) entries and out_face_map
 * mt_mesh_num_faces(mesh), both read before the call; each old id gets its
 * new id or MT_NONE when removed. A map with a smaller capacity gives
 * MT_ERR_BUFFER_TOO_SMALL and nothing changes. Linear time (it runs the
 * build on the compacted face list). Internal half-edge and edge ids change.
 *
 *   verts 0 1 2 3 4 (2 deleted)     ->   verts 0 1 2 3   map {0, 1, N, 2, 3}
 */
mt_status mt_mesh_compact(mt_mesh *mesh, uint32_t *out_vert_map, size_t vert_map_capacity,
                          uint32_t *out_face_map, size_t face_map_capacity, mt_diag *diag);

#ifdef __cplusplus
}
#endif

#endif
