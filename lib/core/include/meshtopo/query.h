/* Topology queries on a built mesh, in the caller's vertex and face ids.
 * Each costs time linear in its output (plus a logarithmic look-up where the
 * element touches a non-manifold spot). Outputs are caller-owned: pass NULL
 * buffers (or capacity 0) to learn the sizes, then call again to fill; a call
 * whose buffers are too small returns MT_ERR_BUFFER_TOO_SMALL, writes the
 * needed sizes and nothing else. An id past the caller's counts gives
 * MT_ERR_OUT_OF_RANGE; a face record the build rejected gives
 * MT_ERR_NOT_FOUND. A fan's boundary flag means the half-edge structure
 * opens there: a real boundary, or a seam where an edge is non-manifold or
 * crossed twice in the same direction (see the report for which). */
#ifndef MESHTOPO_QUERY_H
#define MESHTOPO_QUERY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/mesh.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One fan of faces around a vertex, as ranges into the ring buffers. A
 * manifold vertex has one fan; a bowtie has several. An open fan (boundary
 * true) lists face_count + 1 neighbours, a closed one face_count. */
typedef struct mt_fan {
    uint32_t neighbor_begin, neighbor_count; /* range in mt_ring.neighbors */
    uint32_t face_begin, face_count;         /* range in mt_ring.faces */
    bool boundary;                           /* the fan starts and ends on a boundary edge */
} mt_fan;

/* Buffers for mt_vert_ring; the capacities are in elements. */
typedef struct mt_ring {
    uint32_t *neighbors;
    size_t neighbors_capacity;
    uint32_t *faces;
    size_t faces_capacity;
    mt_fan *fans;
    size_t fans_capacity;
    /* written by the call: */
    size_t num_neighbors, num_faces, num_fans;
} mt_ring;

/* One-ring of caller vertex `vert`: neighbour vertices and incident faces in
 * rotational order (counter-clockwise for consistently oriented faces), one
 * fan after another. Within an open fan, neighbors[i] and neighbors[i+1]
 * bound faces[i]; in a closed fan neighbors[i] and neighbors[i+1 mod n] do.
 * A neighbour reached through two fans (a non-manifold edge) appears in
 * each. An edge two faces cross in the same direction (a flipped face) is a
 * seam: the half-edge structure opens there, so the vertex's faces on either
 * side of it fall in separate fans (or one open fan), each with that
 * neighbour at an end. An isolated vertex has no fans. MT_ERR_OUT_OF_RANGE
 * for a bad id. */
mt_status mt_vert_ring(const mt_mesh *mesh, uint32_t vert, mt_ring *ring);

/* Number of distinct neighbours (edges at the vertex). */
mt_status mt_vert_valence(const mt_mesh *mesh, uint32_t vert, uint32_t *out_valence);

/* Caller vertex ids of a face in its stored order. MT_ERR_NOT_FOUND for a
 * rejected face record. */
mt_status mt_face_verts(const mt_mesh *mesh, uint32_t face, uint32_t *out_verts, size_t capacity,
                        size_t *out_count);

/* Faces across each edge of `face`: edge i runs from the face's vertex i to
 * vertex i+1. out_offsets gets face size + 1 entries (CSR): the faces across
 * edge i are out_faces[out_offsets[i] .. out_offsets[i+1]). Across a
 * non-manifold edge every other face on that edge is listed; a boundary edge
 * has none. out_num_edges gets the face size, out_num_faces the total. */
mt_status mt_face_neighbors(const mt_mesh *mesh, uint32_t face, uint32_t *out_faces,
                            size_t faces_capacity, uint32_t *out_offsets, size_t offsets_capacity,
                            size_t *out_num_faces, size_t *out_num_edges);

/* ---- The same into buffers that grow ------------------------------------ */

/* mt_vert_ring, mt_face_neighbors and mt_face_verts for callers that ask
 * about one element after another and do not know how large the answers
 * are: each grows the arrays of its struct (malloc'd by the library; NULL
 * and capacity 0 at first, reused from one call to the next) to what the
 * answer needs and asks again. Statuses are those of the query
 * (MT_ERR_NOT_FOUND for a rejected face, MT_ERR_OUT_OF_RANGE for a bad
 * id), or MT_ERR_NOMEM. The _free functions free the arrays and zero the
 * struct. */

typedef struct mt_face_adjacency {
    uint32_t *faces; /* the faces across each side, CSR by offsets */
    size_t faces_capacity;
    uint32_t *offsets; /* num_edges + 1 */
    size_t offsets_capacity;
    size_t num_faces, num_edges;
} mt_face_adjacency;

typedef struct mt_face_corners {
    uint32_t *verts;
    size_t capacity, count;
} mt_face_corners;

mt_status mt_vert_ring_growing(const mt_mesh *mesh, uint32_t vert, mt_ring *ring);
void mt_ring_free(mt_ring *ring);
mt_status mt_face_neighbors_growing(const mt_mesh *mesh, uint32_t face, mt_face_adjacency *adj);
void mt_face_adjacency_free(mt_face_adjacency *adj);
mt_status mt_face_verts_growing(const mt_mesh *mesh, uint32_t face, mt_face_corners *corners);
void mt_face_corners_free(mt_face_corners *corners);

/* Faces (ascending ids) that have {a, b} as a side. MT_ERR_NOT_FOUND when no
 * valid face does. */
mt_status mt_edge_faces(const mt_mesh *mesh, uint32_t a, uint32_t b, uint32_t *out_faces,
                        size_t capacity, size_t *out_count);

/* Boundary loops as ordered caller vertex lists (CSR): loop i is
 * out_verts[out_offsets[i] .. out_offsets[i+1]), walked with the faces on the
 * left. These are the half-edge boundary rings: around a non-manifold edge or
 * a flipped face a ring also runs along that edge, and a pinched boundary
 * gives one ring per fan. out_offsets needs num_loops + 1 entries. */
mt_status mt_boundary_loops(const mt_mesh *mesh, uint32_t *out_verts, size_t verts_capacity,
                            uint32_t *out_offsets, size_t offsets_capacity, size_t *out_num_verts,
                            size_t *out_num_loops);

/* Edge-connected component of a face, numbered as report->components.
 * MT_ERR_NOT_FOUND for a rejected face record. */
mt_status mt_face_component(const mt_mesh *mesh, uint32_t face, uint32_t *out_component);

#ifdef __cplusplus
}
#endif

#endif
