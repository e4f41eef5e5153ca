/* The block map's layout (map.h), shared by the map*.c files only.
 * Per map vertex: position, the head of its face list (threaded through
 * the blocks' corners), one origin of a ring through its block vertices,
 * and status flags. Per map face: its block slot and local index. Every
 * operation is planned first (all allocation, nothing changed) and then
 * committed (no allocation, cannot fail): that is what makes it atomic. */
#ifndef MESHTOPO_MAP_INTERNAL_H
#define MESHTOPO_MAP_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mesh/mesh_internal.h"
#include "meshtopo/map.h"

#define MT__MAP_VALID 0x80000000u /* face_local bit: the face is valid */
#define MT__MAP_LOCAL_MASK 0x7fffffffu
#define MT__MAP_UNLINKED 0xfffffffeu /* corner_next of a corner in no vertex's list */
#define MT__MAP_OOR 0x80000000u      /* corners >= this are out-of-range entries */
#define MT__MAP_NO_ORIGIN UINT64_MAX

/* Vertex status flags (vert_flags). */
enum {
    MT__V_ALIVE = 1,
    MT__V_ANY = 2,   /* in some face record */
    MT__V_VALID = 4, /* in some valid face */
    MT__V_NONMANIFOLD = 8,
    MT__V_BOWTIE = 16,
    MT__V_NONFINITE = 32
};

/* The running counts, signed so that a plan can hold their changes. */
enum {
    MT__T_VERTS,
    MT__T_FACES,
    MT__T_FACES_VALID,
    MT__T_EDGES,
    MT__T_HALF_EDGES,
    MT__T_BOUNDARY,
    MT__T_NM_EDGES,
    MT__T_INCONSISTENT,
    MT__T_DUP_DIRECTED,
    MT__T_NM_VERTS,
    MT__T_BOWTIE,
    MT__T_ISOLATED,
    MT__T_UNREFERENCED,
    MT__T_DEGENERATE,
    MT__T_CLASSES, /* classes of valid faces with the same vertex cycle */
    MT__T_OOR_INDICES,
    MT__T_OOR_FACES,
    MT__T_NONFINITE,
    MT__T_COUNT
};

typedef struct mt__tally {
    int64_t n[MT__T_COUNT];
} mt__tally;

/* ---- Hash tables (map_table.c) ------------------------------------------ */

/* Open addressing over uint32 entries whose keys live elsewhere (a vertex's
 * position, a block's key): the caller hashes and compares. Linear probing,
 * deletion by backward shift, at most 3/4 full. */
typedef uint32_t (*mt__table_hash_fn)(const void *ctx, uint32_t entry);
typedef bool (*mt__table_eq_fn)(const void *ctx, uint32_t entry, const void *key);

typedef struct mt__table {
    uint32_t *slots; /* entries, MT_NONE for empty */
    uint32_t cap;    /* power of two, or 0 */
    uint32_t count;
} mt__table;

/* Makes room for `count` entries (rehashing: the content is unchanged).
 * MT_ERR_NOMEM leaves the table as it was. */
mt_status mt__table_reserve(mt__table *t, uint32_t count, mt__table_hash_fn hash, const void *ctx);
uint32_t mt__table_find(const mt__table *t, uint32_t hash, mt__table_eq_fn eq, const void *ctx,
                        const void *key);
/* Inserts an entry; room must have been reserved. */
void mt__table_insert(mt__table *t, uint32_t hash, uint32_t entry);
/* Calls visit(arg, entry) for every entry of the probe run that starts at
 * hash: every entry whose hash equals it, and others (the caller filters). */
void mt__table_scan(const mt__table *t, uint32_t hash, void (*visit)(void *arg, uint32_t entry),
                    void *arg);
void mt__table_remove(mt__table *t, uint32_t entry, mt__table_hash_fn hash, const void *ctx);
void mt__table_clear(mt__table *t);
void mt__table_free(mt__table *t);

/* A scratch map from uint64 keys to dense indices 0, 1, ... (insertion
 * order), sized once for at most max_entries. */
typedef struct mt__keymap {
    uint64_t *keys;
    uint32_t *vals; /* MT_NONE: empty */
    uint32_t mask;
    uint32_t count;
} mt__keymap;

mt_status mt__keymap_init(mt__keymap *m, uint32_t max_entries);
uint32_t mt__keymap_get(const mt__keymap *m, uint64_t key);
/* Index of key, inserted as the next index when absent (*out_added). */
uint32_t mt__keymap_put(mt__keymap *m, uint64_t key, bool *out_added);
void mt__keymap_free(mt__keymap *m);

/* Makes room for n elements in an mt__vec (length unchanged). */
mt_status mt__map_vec_reserve(mt__vec *v, size_t n);

static inline uint64_t mt__mix64(uint64_t x)
{
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdull;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ull;
    x ^= x >> 33;
    return x;
}

/* ---- Histograms (map_hist.c) -------------------------------------------- */

typedef struct mt__hist {
    mt_histogram_bin *bins; /* ascending keys, counts > 0 */
    size_t len, cap;
} mt__hist;

typedef struct mt__hist_change {
    uint32_t key;
    int64_t change;
} mt__hist_change;

/* Keys below this are counted in a plan's arrays before they become
 * changes (one entry per key instead of one per face or edge). */
#define MT__HIST_SMALL 32

/* Adds `change` to key's count: into small[] for small keys, else as an
 * entry of changes. */
mt_status mt__hist_note(mt__vec *changes, int64_t *small, uint32_t key, int64_t change);
/* Moves the small keys' counts into changes. */
mt_status mt__hist_flush(mt__vec *changes, int64_t *small);

/* Sorts and merges the changes (an mt__vec of mt__hist_change) and makes
 * room in h for the keys they add. MT_ERR_NOMEM leaves h as it was. */
mt_status mt__hist_prepare(mt__hist *h, mt__vec *changes);
/* Applies prepared changes (no allocation). */
void mt__hist_apply(mt__hist *h, const mt__vec *changes);
void mt__hist_free(mt__hist *h);

/* ---- Blocks (map_blocks.c) ---------------------------------------------- */

typedef struct mt__map_block {
    mt_map_key key;
    uint32_t num_verts, num_faces, num_indices;
    uint32_t *vert_map;    /* [num_verts] map vertex of each block vertex */
    uint64_t *ring_next;   /* [num_verts] next origin of the same map vertex */
    uint32_t *face_first;  /* [num_faces + 1] corner offsets; NULL: all triangles */
    uint32_t *corners;     /* [num_indices] map vertex, or >= MT__MAP_OOR */
    uint32_t *corner_next; /* [num_indices] next face in the vertex's list */
    uint32_t *face_ids;    /* [num_faces] map face ids */
    /* What the block's faces add to the counts. */
    uint32_t valid_faces, degenerate_faces, oor_faces;
    uint64_t oor_indices;
} mt__map_block;

static inline uint32_t mt__blk_begin(const mt__map_block *b, uint32_t face)
{
    return b->face_first ? b->face_first[face] : 3 * face;
}
static inline uint32_t mt__blk_size(const mt__map_block *b, uint32_t face)
{
    return b->face_first ? b->face_first[face + 1] - b->face_first[face] : 3;
}

/* One allocation holding a block and its arrays (face_first only when some
 * face is not a triangle). NULL when out of memory. */
mt__map_block *mt__block_alloc(uint32_t num_verts, uint32_t num_faces, uint32_t num_indices,
                               bool all_triangles);
void mt__block_free(mt__map_block *b);
size_t mt__block_bytes(const mt__map_block *b);

static inline uint64_t mt__origin_pack(uint32_t slot, uint32_t local)
{
    return (uint64_t)slot << 32 | local;
}

/* ---- The map -------------------------------------------------------------- */

struct mt_map {
    mt_map_weld weld;
    double eps; /* MT_MAP_WELD_EPS: the weld distance; 0 otherwise */

    /* Blocks by slot (a slot is reused as soon as it is free). */
    mt__map_block **blocks;
    uint32_t num_slots, cap_slots;
    uint32_t *free_slots; /* [cap_slots] stack */
    uint32_t num_free;
    uint32_t num_blocks;
    mt__table block_table; /* slots by key */

    /* Vertices by id. */
    uint32_t vert_end, vert_cap;
    double *pos;           /* [3 * vert_cap] */
    uint32_t *vert_head;   /* [vert_cap] first face of its list, MT_NONE */
    uint64_t *vert_origin; /* [vert_cap] an origin (slot, local), MT__MAP_NO_ORIGIN */
    uint8_t *vert_flags;   /* [vert_cap] MT__V_* */
    mt__table weld_table;  /* finite live vertices by position (exact) or cell (eps) */

    /* Faces by id. */
    uint32_t face_end, face_cap;
    uint32_t *face_block; /* [face_cap] slot, MT_NONE for a removed face */
    uint32_t *face_local; /* [face_cap] local face | MT__MAP_VALID */

    mt__tally tally;
    mt__hist face_sizes, edge_uses;

    /* Delta lists of the last operation. */
    mt__vec faces_removed, verts_added, verts_removed;
};

/* Block and key hashing, for block_table (map_blocks.c). */
uint32_t mt__key_hash(mt_map_key key);
uint32_t mt__block_entry_hash(const void *map, uint32_t slot);
bool mt__block_entry_eq(const void *map, uint32_t slot, const void *key);
/* Slot of the block under key, MT_NONE when there is none. */
uint32_t mt__map_find_block(const mt_map *map, mt_map_key key);

/* Position hashing, for weld_table (map_weld.c). */
uint32_t mt__pos_hash(const double *p);
bool mt__pos_equal(const double *a, const double *b);
bool mt__pos_finite(const double *p);
uint32_t mt__weld_entry_hash(const void *map, uint32_t vert);

/* The linked corner of live vertex v in face f (its first occurrence):
 * the corner's index in the face's block. */
static inline uint32_t mt__map_corner_of(const mt_map *map, uint32_t f, uint32_t v,
                                         const mt__map_block **out_block, uint32_t *out_local)
{
    const mt__map_block *b = map->blocks[map->face_block[f]];
    const uint32_t local = map->face_local[f] & MT__MAP_LOCAL_MASK;
    uint32_t c = mt__blk_begin(b, local);
    while (b->corners[c] != v) c++;
    *out_block = b;
    *out_local = local;
    return c;
}

/* Makes room in the per-vertex and per-face arrays for ids below the given
 * ends (map_store.c). MT_ERR_NOMEM leaves the content unchanged. */
mt_status mt__map_reserve_verts(mt_map *map, uint32_t end);
mt_status mt__map_reserve_faces(mt_map *map, uint32_t end);

/* ---- One operation: plan (map_plan.c and friends), then commit -------- */

typedef struct mt__map_plan {
    mt_map *map;
    mt_map_key key;
    mt__map_block *old;   /* the block the key holds, or NULL */
    mt__map_block *block; /* the new version, or NULL for a removal */
    uint32_t slot;        /* where the new version goes */
    const mt_face_list *input;
    const uint32_t *vertex_ids;
    uint32_t old_slot; /* slot of old, MT_NONE */

    /* Touched vertices: those of old's and the new block's vertices.
     * tv_* are indexed by touched index. */
    mt__keymap tv;
    uint32_t num_tv;
    uint32_t *tv_vert;     /* map vertex id */
    uint32_t *tv_pos;      /* block-local vertex giving its new position, or MT_NONE */
    uint8_t *tv_old;       /* flags before */
    uint8_t *tv_new;       /* flags after */
    uint8_t *tv_role;      /* MT__R_* */
    uint32_t *tv_bfirst;   /* [num_tv + 1] CSR: the new block's faces at each vertex */
    uint32_t *tv_bface;    /* local faces of the new block */
    uint8_t *b_valid;      /* [new block's faces] valid after welding */
    uint32_t new_vert_end; /* vert_end after the operation */

    /* Touched edges, keyed (min << 32 | max); fwd runs min -> max. */
    mt__keymap te;
    int32_t *te_dfwd, *te_dbwd;
    uint32_t *te_fwd, *te_bwd; /* counts before, from the walks */

    /* Touched vertex cycles of valid faces (duplicate faces). */
    mt__table tc;
    uint32_t num_tc;
    const uint32_t **tc_corners; /* representative face's corners */
    uint32_t *tc_size;
    uint32_t *tc_hash;
    int32_t *tc_delta;
    uint32_t *tc_old;

    /* Scratch for link analysis. */
    mt__vec link, link_scratch;

    mt__tally change;
    mt__vec size_changes, use_changes;                             /* mt__hist_change */
    int64_t size_small[MT__HIST_SMALL], use_small[MT__HIST_SMALL]; /* changes of small keys */
    mt_diag *diag;
} mt__map_plan;

enum {
    MT__R_IN_OLD = 1,  /* some vertex of the old version is this one */
    MT__R_IN_NEW = 2,  /* some vertex of the new version is this one */
    MT__R_OUTSIDE = 4, /* an origin outside the old version exists */
    MT__R_OLD_FACES = 8
};

/* "block (x, y, z)" for messages. */
#define MT__KEY_FMT "block (%d, %d, %d)"
#define MT__KEY_ARGS(k) (int)(k).x, (int)(k).y, (int)(k).z

/* map_plan.c: plans and commits a put (input set) or removal (input NULL). */
mt_status mt__map_update(mt_map *map, mt_map_key key, const mt_face_list *input,
                         const uint32_t *vertex_ids, mt_map_delta *out_delta, mt_diag *diag);
/* map_weld.c: fills block->vert_map for the new version and the touched
 * vertex table (positions, roles). */
mt_status mt__plan_verts(mt__map_plan *p);
/* map_faces.c: the new version's corners, validity, aggregates, face-size
 * changes; which corners get linked. */
mt_status mt__plan_faces(mt__map_plan *p);
/* map_edges.c: the touched edges and cycles with their changes. */
mt_status mt__plan_edges(mt__map_plan *p);
/* Counts one valid face at vertex a (walked before the change) into the
 * touched edges' and cycles' old counts. */
void mt__plan_edges_walk_face(mt__map_plan *p, uint32_t a, const uint32_t *corners, uint32_t n,
                              uint32_t at);
/* Turns old and new edge and cycle counts into count changes. */
mt_status mt__plan_edges_finish(mt__map_plan *p);
/* map_link.c: walks every touched vertex once: new status, old edge counts. */
mt_status mt__plan_walk(mt__map_plan *p);
/* map_commit.c: applies a plan. Cannot fail. */
void mt__plan_commit(mt__map_plan *p, mt_map_delta *out_delta);
void mt__plan_free(mt__map_plan *p);

/* Counts of a tally (map_store.c). */
void mt__tally_counts(const mt_map *map, const mt__tally *t, mt_map_counts *out);

#endif
