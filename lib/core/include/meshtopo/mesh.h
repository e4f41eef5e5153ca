/* The half-edge mesh: building it from a face list, freeing it, and raw
 * read-only access to its arrays for fast traversal.
 *
 * Structure (see DESIGN.md): half-edges come in pairs, the twin of h is h ^ 1
 * and its edge is h >> 1. Each half-edge stores its head (the vertex it points
 * to), its face (MT_NONE on a boundary) and next. Boundary half-edges are
 * linked by next into one ring around every hole; a boundary vertex keeps a
 * boundary half-edge as its outgoing half-edge. There is no prev array: the
 * previous half-edge is found by walking the face ring (two steps for a
 * triangle), which keeps the structure at 12 bytes per half-edge.
 *
 * Messy input is kept: an edge used by more than two faces, or by two faces
 * running the same way, becomes several internal edges (one per pairing, the
 * rest with boundary twins) grouped in an "edge bundle"; a vertex whose faces
 * form several fans becomes one internal vertex per fan ("vertex copies").
 * The public queries (query.h) hide this and answer in the caller's ids. */
#ifndef MESHTOPO_MESH_H
#define MESHTOPO_MESH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/face_list.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_mesh mt_mesh;
typedef struct mt_report mt_report;

/* Memory that builds keep for the next build. A build's largest
 * allocations are its scratch arrays (about 70 bytes per triangle), and
 * fresh pages cost the kernel's zeroing on first touch (and, in a virtual
 * machine whose host takes freed memory back, the host's too); a program
 * that builds mesh after mesh (meshtopod, a loop over a scan) passes the
 * same workspace each time and skips that. It grows to the largest build it
 * has served and keeps that memory until destroyed. A mesh that is no longer
 * needed can also be handed to it (mt_build_workspace_recycle) so that the
 * next build's mesh reuses its arrays. One build or recycle at a time may
 * use a workspace; it never changes the result. */
typedef struct mt_build_workspace mt_build_workspace;

/* A new, empty workspace; NULL when out of memory. */
mt_build_workspace *mt_build_workspace_create(void);

/* Frees a workspace and the memory it holds. NULL-safe. */
void mt_build_workspace_destroy(mt_build_workspace *workspace);

/* Bytes a workspace holds, kept mesh arrays included. */
size_t mt_build_workspace_bytes(const mt_build_workspace *workspace);

/* Destroys a mesh like mt_mesh_destroy, but keeps its large arrays (half-
 * edges, faces, vertices, positions) in the workspace: the next build using
 * the workspace takes each one that fits instead of new memory, the
 * smallest that holds what it needs and no more than twice that. A workspace
 * keeps at most eight such arrays, the largest ones. For a loop that builds
 * a new mesh each frame and drops the last. A NULL workspace destroys the
 * mesh; a NULL mesh does nothing. Any mesh may be recycled, built, restored
 * or edited. */
void mt_build_workspace_recycle(mt_build_workspace *workspace, mt_mesh *mesh);

/* Build options; a zeroed struct (or NULL) gives the defaults. */
typedef struct mt_build_options {
    /* Refuse any defect (bad index, degenerate or duplicate face, non-manifold
     * edge or vertex, inconsistent orientation, isolated vertex, non-finite
     * coordinate): the build fails with MT_ERR_DEFECT and diag names the first. */
    bool strict;
    /* Worker threads for the build: 0 = as many as pay off (one for small
     * meshes, else up to two, never more than the online cores), 1 = build on
     * the calling thread, 2 or more = two threads. The result is the same
     * whatever the count. */
    uint32_t threads;
    /* Scratch memory kept between builds (see mt_build_workspace); NULL:
     * the build allocates its scratch and frees it before returning. */
    mt_build_workspace *workspace;
} mt_build_options;

/* Builds a half-edge mesh and its topology report from a face list.
 * Expected linear time; a fixed number of allocations whatever the size.
 * Faces that cannot be represented (an index >= num_verts, fewer than three
 * entries or a vertex repeated anywhere in the face) are left out and listed
 * in the report; every other face is kept under its own id. Vertex ids and
 * face ids are the caller's. Positions are copied (NULL positions give a
 * mesh without geometry). On success *out_mesh owns everything; free it with
 * mt_mesh_destroy. On failure *out_mesh is NULL and diag says why
 * (MT_ERR_INVALID_ARG for inconsistent sizes, MT_ERR_TOO_LARGE past 2^31 - 1
 * vertices or indices or 2^30 - 1 sides of valid faces, MT_ERR_NOMEM,
 * MT_ERR_DEFECT in strict mode). */
mt_status mt_mesh_build(const mt_face_list *input, const mt_build_options *options,
                        mt_mesh **out_mesh, mt_diag *diag);

/* mt_mesh_build for a caller done with the positions once the mesh is
 * built (a program that reads a file to report on it): instead of a copy,
 * the mesh takes input->positions, which must come from malloc (as the
 * readers' and generators' face lists do), and input->positions is NULL
 * after a successful build. The faces stay the caller's. A failed build
 * leaves input as it was. Saves a copy and 24 bytes per vertex of new
 * memory. */
mt_status mt_mesh_build_taking_positions(mt_face_list *input, const mt_build_options *options,
                                         mt_mesh **out_mesh, mt_diag *diag);

/* Frees a mesh. NULL-safe. */
void mt_mesh_destroy(mt_mesh *mesh);

/* The topology report made by the build; owned by the mesh. */
const mt_report *mt_mesh_report(const mt_mesh *mesh);

/* The caller's counts: vertices and face records as given to mt_mesh_build. */
uint32_t mt_mesh_num_verts(const mt_mesh *mesh);
uint32_t mt_mesh_num_faces(const mt_mesh *mesh);

/* Position of a caller vertex (3 doubles), or NULL when out of range or the
 * mesh has no geometry. */
const double *mt_mesh_position(const mt_mesh *mesh, uint32_t vert);

/* Bytes held by the half-edge structure and positions (not the report). */
size_t mt_mesh_memory_bytes(const mt_mesh *mesh);

/* Bytes held by the report (defect lists, components, histograms). */
size_t mt_mesh_report_memory_bytes(const mt_mesh *mesh);

/* Read-only raw view of the arrays, for fast sweeps. Internal vertex ids
 * 0 .. num_verts-1 are the caller's; ids num_verts .. num_verts_internal-1 are
 * vertex copies (one per extra fan of a non-manifold vertex), mapped back
 * with mt_vert_original(). Internal edge e has half-edges 2e and 2e+1; the
 * first points from the smaller caller vertex id to the larger. */
typedef struct mt_mesh_view {
    uint32_t num_verts;          /* caller's vertex count */
    uint32_t num_verts_internal; /* num_verts + vertex copies */
    uint32_t num_faces;          /* caller's face records (rejected ones have face_he MT_NONE) */
    uint32_t num_half_edges;     /* 2 * internal edges */
    const uint32_t *he_head;     /* [num_half_edges] internal vertex the half-edge points to */
    const uint32_t *he_next;     /* [num_half_edges] next half-edge in its face or boundary ring */
    const uint32_t *he_face;     /* [num_half_edges] face, MT_NONE on a boundary */
    const uint32_t *face_he; /* [num_faces] half-edge from the face's first to its second vertex */
    const uint32_t *vert_he; /* [num_verts_internal] outgoing half-edge, boundary one on a
                                boundary vertex, MT_NONE for an isolated vertex */
    const double *positions; /* [3 * num_verts] or NULL */
} mt_mesh_view;

void mt_mesh_get_view(const mt_mesh *mesh, mt_mesh_view *out_view);

/* Caller's id of an internal vertex id (identity below num_verts). */
uint32_t mt_vert_original(const mt_mesh *mesh, uint32_t internal_vert);

static inline uint32_t mt_he_twin(uint32_t he)
{
    return he ^ 1u;
}
static inline uint32_t mt_he_edge(uint32_t he)
{
    return he >> 1;
}
static inline uint32_t mt_he_tail(const mt_mesh_view *v, uint32_t he)
{
    return v->he_head[he ^ 1u];
}
/* Next outgoing half-edge around the tail of he (one rotation step). Starting
 * from a vertex's vert_he it visits the whole fan; on a boundary vertex it
 * starts at the boundary half-edge and returns to it. */
static inline uint32_t mt_he_rotate(const mt_mesh_view *v, uint32_t he)
{
    return v->he_next[he ^ 1u];
}

/* Steps a traversal may take before it is treated as a corrupted ring. */
#define MT_RING_STEP_LIMIT 0x7fffffffu

/* Iterates the outgoing half-edges `he` of internal vertex `vert` in
 * rotational order: `for` over an mt_ring_iter, ends after one turn. */
typedef struct mt_ring_iter {
    uint32_t start;
    uint32_t current;
    uint32_t steps;
} mt_ring_iter;

static inline mt_ring_iter mt_ring_begin(const mt_mesh_view *v, uint32_t internal_vert)
{
    mt_ring_iter it;
    it.start = v->vert_he[internal_vert];
    it.current = it.start;
    it.steps = 0;
    return it;
}

static inline bool mt_ring_valid(const mt_ring_iter *it)
{
    return it->current != MT_NONE && it->steps < MT_RING_STEP_LIMIT;
}

static inline void mt_ring_step(const mt_mesh_view *v, mt_ring_iter *it)
{
    it->current = mt_he_rotate(v, it->current);
    it->steps++;
    if (it->current == it->start) it->current = MT_NONE;
}

#define MT_FOR_VERT_OUT(view, vert, it)                                       \
    for (mt_ring_iter it = mt_ring_begin((view), (vert)); mt_ring_valid(&it); \
         mt_ring_step((view), &it))

#ifdef __cplusplus
}
#endif

#endif
