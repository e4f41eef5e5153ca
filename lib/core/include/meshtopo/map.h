/* A map that grows: a mesh kept up to date block by block, as TSDF mappers
 * (voxblox, nvblox) publish it, with the counts of its topology report kept
 * current in time proportional to the change, never by rescanning the map.
 * The map always equals the full build of the welded union of its blocks
 * (exact weld: mt_face_list_weld with eps 0 of the blocks' face lists put
 * end to end; see MT_MAP_WELD_EPS for what a tolerance guarantees). */
#ifndef MESHTOPO_MAP_H
#define MESHTOPO_MAP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/face_list.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- What the map is -----------------------------------------------------
 *
 * A map holds blocks. A block is keyed by three int32 (the voxblox/nvblox
 * block index; an application with other keys packs them) and carries its
 * own face list: positions (required), face sizes and indices local to the
 * block, the polygon rules of mt_mesh_build. Every face record is kept, bad
 * ones too (an index past the block's vertices, fewer than 3 entries, a
 * vertex repeated, a NaN or infinite coordinate): they are counted exactly
 * as mt_mesh_build counts them, never refused and never a crash.
 *
 * Welding (mt_map_options.weld):
 *   MT_MAP_WELD_EXACT (default): vertices whose positions are equal as
 *     values (bitwise, except that -0.0 equals 0.0) are one map vertex,
 *     inside a block (per-triangle duplicates, as voxblox sends them) and
 *     across blocks (seam vertices duplicated per block, as nvblox sends
 *     them). A vertex with a NaN or infinite coordinate is never welded.
 *     This is exactly what mt_face_list_weld(list, 0, ...) does to the union
 *     of the blocks' face lists.
 *   MT_MAP_WELD_NONE: nothing is welded; the sender names the map vertex of
 *     every block vertex (mt_map_put's vertex_ids). Blocks that name the
 *     same id share that vertex; they must give it the same position (equal
 *     as values, as above; a NaN only equals the same bits), else the put is
 *     refused (MT_ERR_INVALID_ARG naming both). The one exception is a
 *     vertex held only by the block being replaced: the new version may
 *     move it.
 *   MT_MAP_WELD_EPS: a block vertex becomes the lowest-numbered live map
 *     vertex within Euclidean distance mt_map_options.eps of it (the
 *     distance test of mt_face_list_weld, bit for bit), else the
 *     lowest-numbered vertex the same put has already made within eps,
 *     else a new map vertex at its own position. A map vertex keeps the
 *     position of the block vertex that made it; the copies welded into it
 *     lie within eps of that position (not of each other: merging is not
 *     transitive, a chain of points eps/2 apart is not one vertex). NaN and
 *     infinite positions are never welded. Live finite map vertices are
 *     always more than eps apart (a vertex is made only when no live one is
 *     within eps), so a cell of the spatial hash (cells of side eps, the 27
 *     around a vertex searched) holds a bounded number: expected O(1) per
 *     block vertex, as in exact mode.
 *     Order matters, as it does for mt_face_list_weld ("each vertex merges
 *     into the lowest-numbered earlier survivor within eps"). While no block
 *     has been removed or replaced since the map was created or cleared,
 *     the map is exactly mt_face_list_weld(eps) of the blocks' face lists
 *     end to end in the order they were put (the same positions, vertex and
 *     face order; map ids are survivor ranks). After a removal or a
 *     replacement that no longer holds in general: a map vertex outlives
 *     the block that made it (with its position) while other blocks hold
 *     it, so re-welding the remaining blocks from scratch could pick other
 *     survivors. What always holds is the rule above, applied at each put
 *     against the live vertices of that moment, and the counts equal a full
 *     build of mt_map_face_list's union. A replacement keeps the id of
 *     every vertex its new version welds into (a seam that moved by less
 *     than eps keeps its vertices). mt_map_create refuses an eps that is
 *     not finite and positive (MT_ERR_INVALID_ARG).
 *
 * Ids. A map vertex and a map face keep their id for as long as they exist.
 * Face ids are given by the map in increasing order; vertex ids too, except
 * with MT_MAP_WELD_NONE where they are the sender's (below
 * MT_MAP_MAX_VERT_ID). The id of a removed element is not given again until
 * mt_map_compact (which renumbers densely and returns the old-to-new maps)
 * or mt_map_clear (which starts the ids again at 0). Replacing a block keeps
 * the id of every vertex the new version still uses (a welded vertex is
 * found by its position, or within eps of it); its faces are all new
 * records with new ids.
 * mt_map_id_ends tells how far ids have gone.
 *
 * The union. mt_map_face_list writes the map as a plain face list: the live
 * vertices in id order, the live faces in id order, each face's entries in
 * its block's order. An index that was out of range in its block is written
 * as MT_NONE - r (r = 0, 1, ...: the r-th distinct out-of-range value of
 * that face), so it stays out of range and two equal values stay equal.
 * mt_mesh_build of that list gives exactly the counts mt_map_counts holds.
 *
 * What is incremental. mt_map_put and mt_map_remove update every count of
 * mt_map_counts and both histograms in O(k + s) expected time for a block
 * of k face entries and vertices, where s is the size of its seam: the
 * faces of other blocks around the block's vertices (each touched vertex's
 * whole face list is walked once, each of its block origins once, and a
 * face is scanned for the vertex's corner, so a face's size counts, hence
 * MT_MAP_BLOCK_MAX_FACE_SIZE). That is independent of the map's size for
 * meshes whose vertices have bounded valence; a vertex shared by very many
 * faces (a fan of 10^5 triangles) makes every update at it cost its
 * valence. mt_map_clear, mt_map_compact and mt_map_face_list are linear in
 * the map. With exact and none welding, counts do not depend on the order
 * the blocks came in; with eps welding they may (see MT_MAP_WELD_EPS).
 * Not kept (a later slice): boundary loops, connected components,
 * orientability, genus, defect lists with ids, and the topology events of a
 * delta (loops opened or closed, components merged or split, defects by
 * kind). Queries (rings, neighbours, edge faces, loops), geometry and the
 * full mt_report are not answered by the map yet either: build
 * mt_map_face_list's list for them (linear in the map).
 *
 * Memory: the live elements' arrays and hash tables, plus, since removed
 * ids are not reused before mt_map_compact, a slot for every face and
 * vertex id given since the last compaction: a map whose blocks are
 * replaced again and again grows until it is compacted.
 * mt_map_memory_bytes tells; docs/performance/maps.md has the figures
 * (meshtopo-bench map).
 *
 * Threads: a map is not thread-safe; one call at a time. Memory: every
 * allocation goes through the core's allocator (and its test hook). */

typedef struct mt_map mt_map;

/* A block's key: the block's index on the mapper's grid. */
typedef struct mt_map_key {
    int32_t x, y, z;
} mt_map_key;

typedef enum mt_map_weld {
    MT_MAP_WELD_EXACT = 0, /* weld bitwise-equal positions (-0.0 == 0.0), never NaN */
    MT_MAP_WELD_NONE = 1,  /* the sender gives map-wide vertex ids */
    MT_MAP_WELD_EPS = 2    /* weld within eps, lowest-numbered live vertex first (above) */
} mt_map_weld;

/* Options; a zeroed struct (or NULL) gives the defaults. */
typedef struct mt_map_options {
    mt_map_weld weld;
    double eps; /* MT_MAP_WELD_EPS only: the weld distance, finite and > 0 */
} mt_map_options;

/* Limits. A block with more vertices, faces or indices than these, or a
 * face record longer than MT_MAP_BLOCK_MAX_FACE_SIZE (an update walks each
 * touched face once per corner, so a face's cost grows with its size
 * squared), is refused with MT_ERR_TOO_LARGE naming the block and the
 * limit; so is a put that would need a vertex or face id past
 * MT_MAP_MAX_*_ID (call mt_map_compact: ids of removed elements then come
 * back). */
#define MT_MAP_BLOCK_MAX_VERTS (1u << 24)
#define MT_MAP_BLOCK_MAX_FACES (1u << 24)
#define MT_MAP_BLOCK_MAX_INDICES (1u << 26)
#define MT_MAP_BLOCK_MAX_FACE_SIZE 256u
#define MT_MAP_MAX_VERT_ID 0x7ffffffeu /* vertex ids are below it */
#define MT_MAP_MAX_FACE_ID 0x7ffffffeu /* face ids are below it */

/* The counts of a full build's mt_report that the map keeps current, with
 * the same definitions (tests/corpus/DEFINITIONS.md, report.h) over the
 * welded union. */
typedef struct mt_map_counts {
    uint32_t num_blocks;
    uint32_t num_verts;       /* live map vertices (every listed one, isolated too) */
    uint32_t num_faces;       /* live face records, invalid ones included */
    uint32_t num_faces_valid; /* not degenerate, no out-of-range index */
    uint64_t num_edges;       /* distinct undirected edges of valid faces */
    uint64_t num_half_edges;  /* sum of the record sizes */
    uint64_t boundary_edges;  /* used by one valid face */
    uint64_t nonmanifold_edges;
    uint64_t inconsistent_orientation_edges;
    uint64_t duplicate_directed_edges;
    uint32_t nonmanifold_vertices;
    uint32_t bowtie_vertices;
    uint32_t isolated_vertices;
    uint32_t unreferenced_vertices;
    uint32_t degenerate_faces; /* after welding: a face whose corners weld is degenerate */
    uint32_t duplicate_faces;
    uint64_t out_of_range_indices;
    uint32_t faces_with_out_of_range_indices;
    uint32_t nonfinite_vertices;
    int64_t euler_characteristic; /* num_verts - num_edges + num_faces_valid */
    bool closed;                  /* no boundary edge and at least one valid face */
    bool manifold;                /* no non-manifold edge or vertex */
    bool consistently_oriented;   /* no inconsistent nor duplicate directed edge */
} mt_map_counts;

/* What one operation did. The arrays belong to the map and stay valid
 * until the next call that changes or tries to change it (put, remove,
 * clear, compact) or its destruction. */
typedef enum mt_map_op {
    MT_MAP_OP_PUT_NEW = 0, /* a block under a new key */
    MT_MAP_OP_REPLACE = 1, /* a block replaced another under its key */
    MT_MAP_OP_REMOVE = 2,
    MT_MAP_OP_CLEAR = 3
} mt_map_op;

typedef struct mt_map_delta {
    mt_map_op op;
    mt_map_key key; /* zero for a clear */
    const uint32_t *faces_added;
    size_t num_faces_added; /* the block's faces: added[i] is its face i */
    const uint32_t *faces_removed;
    size_t num_faces_removed; /* the old version's faces, in its order */
    const uint32_t *verts_added;
    size_t num_verts_added; /* vertices that did not exist before, ascending */
    const uint32_t *verts_removed;
    size_t num_verts_removed; /* vertices that no longer exist, ascending */
    bool all_removed;         /* a clear: everything went, the lists are empty */
    /* (MT_MAP_WELD_NONE: a vertex a new version moved is in neither list.) */
    mt_map_counts before, after;
    /* Topology events (loops, components, defects by kind) come in a later
     * slice. */
} mt_map_delta;

/* Creates an empty map. MT_ERR_INVALID_ARG for a NULL out, an unknown
 * weld mode, or MT_MAP_WELD_EPS with an eps not finite and positive;
 * MT_ERR_NOMEM; *out is NULL on failure. Free the map with mt_map_destroy. */
mt_status mt_map_create(const mt_map_options *opts, mt_map **out, mt_diag *diag);

/* Frees a map and everything it holds. NULL-safe. */
void mt_map_destroy(mt_map *map);

/* Puts a block under `key`: adds it, or replaces the block the key holds
 * (atomically: the map goes from the old version to the new one, and the
 * delta says what changed). The face list is copied (the map keeps its
 * topology, the positions of new vertices, and per block vertex its map
 * vertex; not the caller's arrays). vertex_ids: NULL with
 * MT_MAP_WELD_EXACT and MT_MAP_WELD_EPS; with MT_MAP_WELD_NONE, block->num_verts map vertex ids
 * (each below MT_MAP_MAX_VERT_ID). out_delta may be NULL.
 *
 * Errors, each leaving the map unchanged, diag naming the block ("block
 * (3, 1, 0): ...") and the reason: MT_ERR_INVALID_ARG (NULL map or block,
 * inconsistent face list as mt_face_list_check says, vertices without
 * positions, vertex_ids given or missing against the weld mode, two
 * positions for one vertex id), MT_ERR_TOO_LARGE (a block past the limits
 * above, ids exhausted), MT_ERR_NOMEM. */
mt_status mt_map_put(mt_map *map, mt_map_key key, const mt_face_list *block,
                     const uint32_t *vertex_ids, mt_map_delta *out_delta, mt_diag *diag);

/* Removes the block under `key` with its faces, and the vertices no other
 * block holds. MT_ERR_NOT_FOUND when no block has that key,
 * MT_ERR_INVALID_ARG for a NULL map, MT_ERR_NOMEM; the map is then
 * unchanged. out_delta may be NULL. */
mt_status mt_map_remove(mt_map *map, mt_map_key key, mt_map_delta *out_delta, mt_diag *diag);

/* Removes every block (nvblox's `clear`: the whole map follows). Ids start
 * again at 0. Allocates nothing, so it fails only for a NULL map. The
 * delta's lists are empty and all_removed is set. Linear in the map. */
mt_status mt_map_clear(mt_map *map, mt_map_delta *out_delta, mt_diag *diag);

/* Renumbers the live vertices (not with MT_MAP_WELD_NONE, whose ids are
 * the sender's) and faces densely in id order, so removed ids come back,
 * and gives memory back. out_vert_map and out_face_map (each may be NULL)
 * receive, for every old id below the ends of mt_map_id_ends, its new id or
 * MT_NONE; capacities are in entries and must reach those ends
 * (MT_ERR_BUFFER_TOO_SMALL otherwise, nothing changed). Linear in the map;
 * MT_ERR_NOMEM leaves it unchanged. */
mt_status mt_map_compact(mt_map *map, uint32_t *out_vert_map, size_t vert_map_capacity,
                         uint32_t *out_face_map, size_t face_map_capacity, mt_diag *diag);

/* ---- Reading the map ---------------------------------------------------- */

/* The counts, O(1). A NULL map gives zeros. */
void mt_map_get_counts(const mt_map *map, mt_map_counts *out);

/* The face-size histogram over all face records and the edge-use histogram
 * over the edges of valid faces, ascending keys, as mt_report has them.
 * Pass NULL / 0 to learn *out_count; MT_ERR_BUFFER_TOO_SMALL writes the
 * count and nothing else. O(bins). */
mt_status mt_map_face_size_histogram(const mt_map *map, mt_histogram_bin *out_bins, size_t capacity,
                                     size_t *out_count);
mt_status mt_map_edge_use_histogram(const mt_map *map, mt_histogram_bin *out_bins, size_t capacity,
                                    size_t *out_count);

/* One past the largest vertex and face id given since the last compaction
 * or clear: the sizes of mt_map_compact's maps. */
void mt_map_id_ends(const mt_map *map, uint32_t *out_vert_end, uint32_t *out_face_end);

/* The keys of the blocks, in no particular order (pass NULL / 0 to learn
 * the count). MT_ERR_BUFFER_TOO_SMALL writes the count and nothing else. */
mt_status mt_map_blocks(const mt_map *map, mt_map_key *out_keys, size_t capacity,
                        size_t *out_count);

/* Whether a block has that key. */
bool mt_map_has_block(const mt_map *map, mt_map_key key);

/* Translation, block to map: the map vertex of local vertex `local` of
 * block `key`, the map face of its local face. MT_ERR_NOT_FOUND for an
 * unknown key, MT_ERR_OUT_OF_RANGE for a local id past the block's. O(1). */
mt_status mt_map_block_vert(const mt_map *map, mt_map_key key, uint32_t local, uint32_t *out_vert);
mt_status mt_map_block_face(const mt_map *map, mt_map_key key, uint32_t local, uint32_t *out_face);

/* Translation, map to block: the block and local face of a map face; one of
 * the block vertices a map vertex was welded from (any; it changes when
 * that block goes). MT_ERR_OUT_OF_RANGE for an id past mt_map_id_ends,
 * MT_ERR_NOT_FOUND for a removed one. O(1). */
mt_status mt_map_face_origin(const mt_map *map, uint32_t face, mt_map_key *out_key,
                             uint32_t *out_local);
mt_status mt_map_vert_origin(const mt_map *map, uint32_t vert, mt_map_key *out_key,
                             uint32_t *out_local);

/* Position of a live map vertex (3 doubles: the coordinates it was created
 * with; welded copies are equal as values), NULL for a dead or unknown id.
 * The pointer is valid until the next change of the map. */
const double *mt_map_vert_position(const mt_map *map, uint32_t vert);

/* The corners of a live map face as map vertex ids in its block's order,
 * an out-of-range entry as MT_NONE. Pass NULL / 0 to learn *out_count;
 * MT_ERR_BUFFER_TOO_SMALL writes the count only. MT_ERR_OUT_OF_RANGE /
 * MT_ERR_NOT_FOUND as mt_map_face_origin. */
mt_status mt_map_face_verts(const mt_map *map, uint32_t face, uint32_t *out_verts, size_t capacity,
                            size_t *out_count);

/* The welded union as a plain face list (see "The union" above): *out is
 * allocated like mt_face_list_alloc (free it with mt_face_list_free).
 * out_vert_ids (counts.num_verts entries) and out_face_ids (counts.num_faces
 * entries), each may be NULL, receive the map id of each list vertex and
 * face; capacities in entries (MT_ERR_BUFFER_TOO_SMALL, nothing allocated).
 * Linear in the map. MT_ERR_NOMEM leaves *out zeroed. */
mt_status mt_map_face_list(const mt_map *map, mt_face_list *out, uint32_t *out_vert_ids,
                           size_t vert_ids_capacity, uint32_t *out_face_ids,
                           size_t face_ids_capacity, mt_diag *diag);

/* Bytes the map holds (blocks, per-element arrays, hash tables, delta
 * buffers), capacity included. */
size_t mt_map_memory_bytes(const mt_map *map);

/* ---- Adjacency queries ------------------------------------------------------ */

/* The queries of meshtopo/query.h on the map, in map ids: each gives what
 * that query gives on a full mt_mesh_build of mt_map_face_list's union,
 * translated to map ids (neighbours, faces and fans in the same order, the
 * same statuses). Each builds the map's faces at the element's vertices on
 * the calling thread: O(the size of those faces) expected time and memory,
 * independent of the map's size, allocated and freed by the call. The map is not changed; calls may
 * run concurrently with each other, not with an update. Besides the statuses of the mesh query:
 * MT_ERR_INVALID_ARG for NULL arguments, MT_ERR_OUT_OF_RANGE for an id that is not a live vertex
 * (face), MT_ERR_NOMEM; diag (NULL-safe) says which. */

/* mt_vert_ring of map vertex `vert` (a live vertex in no face has no fans). */
mt_status mt_map_vert_ring(const mt_map *map, uint32_t vert, mt_ring *ring, mt_diag *diag);

/* mt_face_neighbors of map face `face`; a face the map keeps but a build
 * rejects (an out-of-range entry, a repeated vertex) gives MT_ERR_NOT_FOUND. */
mt_status mt_map_face_neighbors(const mt_map *map, uint32_t face, uint32_t *out_faces,
                                size_t faces_capacity, uint32_t *out_offsets,
                                size_t offsets_capacity, size_t *out_num_faces,
                                size_t *out_num_edges, mt_diag *diag);

/* mt_edge_faces of map vertices a and b (MT_ERR_NOT_FOUND: no valid face
 * has the side {a, b}). */
mt_status mt_map_edge_faces(const mt_map *map, uint32_t a, uint32_t b, uint32_t *out_faces,
                            size_t capacity, size_t *out_count, mt_diag *diag);

/* ---- Checking the map --------------------------------------------------- */

/* Compares the map's incremental counts with `report`, the mt_report of a
 * full build of what the map holds (mt_mesh_build of mt_map_face_list's
 * list, or of a list map.h says the map equals). Compared: every field of
 * mt_map_counts except num_blocks (a report has no blocks), that is every
 * count, euler_characteristic and the flags closed, manifold and
 * consistently_oriented, and both histograms bin by bin (keys and counts).
 * Nothing else of the report (loops, components, defect lists) is looked at.
 *
 * Returns MT_OK when everything is equal. MT_ERR_CORRUPT when anything
 * differs (the map's bookkeeping disagrees with the build: a bug in
 * meshtopo, or a report of some other mesh); diag's message then names
 * every differing field with both values, in the order of mt_map_counts,
 * the histograms last, e.g. "nonmanifold_edges map 0, build 1;
 * edge_use_histogram map {1:4 2:5}, build {1:4 2:4 3:1}" (flags as 0 or 1),
 * cut to the message's size and then ending in "...".
 * MT_ERR_INVALID_ARG for a NULL map or report. The map is not changed;
 * nothing is allocated. Linear in the number of histogram bins (O(1) for
 * the counts). Meant for tests, fuzzers and tools that check the map
 * against a build (meshtopo inspect --blocks); it costs nothing on its own,
 * but the build it needs is linear in the map. */
mt_status mt_map_compare_report(const mt_map *map, const mt_report *report, mt_diag *diag);

#ifdef __cplusplus
}
#endif

#endif
