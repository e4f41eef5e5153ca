/* State shared by the build phases; build.c orchestrates them and is the
 * only file that includes their entry points (build_phases.h and
 * report/report_internal.h):
 *   faces   (build_faces.c)  classify records, count corners per vertex and
 *                            sides per block of smaller vertices
 *   edges   (build_edges.c)  twin matching block by block: heads and faces
 *                            of all half-edges, the half-edge of each corner
 *   links   (build_links.c)  next of every face half-edge
 *   fans    (build_fans.c)   boundary rings, one internal vertex per fan
 *   report  (report/)        components, loops, links, genus, duplicates
 * Every phase is a fixed number of passes over flat arrays. The first four
 * run on up to MT__MAX_PARTS threads, each owning a range of faces, blocks or
 * vertices and writing only elements its range owns (except the fan starts
 * of the links phase, see build_links.c); the result does not depend on the
 * number of threads. This header is below every phase: it holds the state,
 * the scratch arrays (build_workspace.c), and the helpers each phase uses to
 * run on its parts and record defects. */
#ifndef MESHTOPO_BUILD_STATE_H
#define MESHTOPO_BUILD_STATE_H

#include <stdint.h>

#include "mesh/mesh_internal.h"
#include "meshtopo/face_list.h"
#include "meshtopo/mesh.h"

/* Corners (sides of valid faces) a build accepts: with two parts numbering
 * half-edges from 0 and from 2 * corners, ids stay below 2^32 - 4. */
#define MT__MAX_CORNERS 0x3fffffffu

/* Face sizes counted in a flat histogram; larger ones are collected and sorted. */
#define MT__SMALL_SIZES 64
/* Edge use counts counted in a flat histogram; larger ones collected likewise. */
#define MT__SMALL_USES 16
/* Sides are filed in blocks of 2^shift consecutive smaller vertices: at
 * least 2^MT__BLOCK_MIN_SHIFT (a block's sides then stay in a core's cache
 * while they are matched: about 6 sides of 16 bytes per vertex, twice with
 * the sorted copy, so 2^11 vertices leave room in a core's L2 where 2^12
 * filled it), and few enough blocks to keep one write stream per block
 * cheap. */
#define MT__BLOCK_MIN_SHIFT 11
#define MT__MAX_BLOCKS 4096u
/* Face sides ahead of the one at hand whose random accesses are fetched
 * early (vertex counts, half-edges of a shuffled mesh): far enough that
 * the load has arrived when its side comes up (64 counted a shuffled mesh's
 * corners a third faster than 16; further ahead gained nothing). */
#define MT__PREFETCH_DISTANCE 64
/* Threads a build uses at most (the machines it targets have two cores). */
#define MT__MAX_PARTS 2
/* Below this many face sides one thread is faster than starting another. */
#define MT__PARALLEL_MIN_CORNERS 200000u

/* A face side a -> b, filed under its smaller vertex. */
typedef struct mt__side {
    uint32_t lo, hi;      /* min(a, b), max(a, b) */
    uint32_t corner_down; /* the tail corner's flat index, | MT__SIDE_DOWN when a > b */
    uint32_t face;
} mt__side;

#define MT__SIDE_DOWN 0x80000000u

/* The scratch arrays a workspace keeps (build_workspace.c); the last two
 * kinds have one array per part. */
typedef enum mt__scratch {
    MT__SCRATCH_SIDES,
    MT__SCRATCH_C2H,
    MT__SCRATCH_FAN_START,
    MT__SCRATCH_DEGREE,
    MT__SCRATCH_SORTED = MT__SCRATCH_DEGREE + MT__MAX_PARTS,
    MT__SCRATCH_KINDS = MT__SCRATCH_SORTED + MT__MAX_PARTS
} mt__scratch;

/* How many arrays of recycled meshes a workspace keeps at most: the four
 * large arrays of one mesh (half-edges, faces, vertices, positions), twice. */
#define MT__KEPT_ARRAYS 8

struct mt_build_workspace {
    void *array[MT__SCRATCH_KINDS];
    size_t bytes[MT__SCRATCH_KINDS];
    void *kept[MT__KEPT_ARRAYS]; /* arrays of recycled meshes, NULL when free */
    size_t kept_bytes[MT__KEPT_ARRAYS];
};

/* What one thread of a parallel phase owns: its range of faces or vertices
 * and everything it counts or collects; merged by the calling thread. */
typedef struct mt__part {
    mt_status status;
    uint32_t face_begin, face_end; /* faces of this part */
    uint32_t index_begin;          /* flat index of face_begin's first corner */
    uint32_t vert_begin, vert_end; /* vertices of this part */

    /* faces */
    uint32_t *degree;      /* [num_verts] corners leaving each vertex in this part's faces */
    uint32_t *block_sides; /* [num_blocks] sides of this part's faces per block, then
                              the part's next free slot in each block */
    uint64_t num_corners;
    uint64_t size_hist[MT__SMALL_SIZES];
    mt__vec large_sizes;  /* uint32 */
    mt__vec invalid_refs; /* uint32 */
    mt__vec defects;      /* mt_defect */
    mt__vec scratch;      /* uint32 */
    uint64_t out_of_range_entries;
    uint32_t out_of_range_faces, degenerate_faces, nonfinite_vertices;

    /* edges */
    uint32_t block_begin, block_end; /* blocks this part matches */
    uint32_t edge_base, edges_made;  /* internal edge ids edge_base .. edge_base + edges_made */
    uint64_t num_edges;
    uint64_t use_hist[MT__SMALL_USES];
    mt__vec large_uses; /* uint32 */
    uint64_t boundary_edges, nonmanifold_edges, inconsistent_edges, duplicate_directed_edges;
    mt__vec bundle_offsets;  /* uint32 */
    mt__vec bundle_edges;    /* uint32 */
    mt__vec boundary_halves; /* uint32 half-edges without a face */

    /* fans */
    mt__vec split_verts;    /* uint32 vertices needing the general fan split */
    mt__vec dup_candidates; /* uint32 faces */
} mt__part;

typedef struct mt__build {
    const mt_face_list *in;
    mt_mesh *m;
    mt_diag *diag;
    mt_build_workspace *workspace; /* NULL: scratch is the build's own */
    bool positions_taken;          /* m->positions is in->positions, not a copy */
    uint32_t parts;
    mt__part part[MT__MAX_PARTS];

    /* faces (merged) */
    uint64_t num_corners;
    uint64_t size_hist[MT__SMALL_SIZES];
    mt__vec large_sizes;  /* uint32 sizes >= MT__SMALL_SIZES */
    mt__vec invalid_refs; /* uint32 in-range vertices of rejected records */
    mt__vec defects;      /* mt_defect, in discovery order (sorted at the end) */
    uint64_t out_of_range_entries;
    uint32_t out_of_range_faces, degenerate_faces, nonfinite_vertices;

    /* edges */
    uint32_t block_shift, num_blocks;
    uint32_t *block_start;            /* [num_blocks + 1] first slot of each block */
    mt__side *sides;                  /* [num_corners] the sides, by block; a matched block's
                                         slots then hold (head, face) of its half-edges */
    uint32_t *block_half_edges;       /* [num_blocks] half-edges each block made */
    uint32_t *c2h;                    /* [num_indices] half-edge of each corner */
    uint32_t gap_first_he, gap_shift; /* see mt__edge_gap */
    uint32_t num_internal_edges;
    uint64_t num_edges; /* distinct undirected edges */
    uint64_t use_hist[MT__SMALL_USES];
    mt__vec large_uses; /* uint32 use counts >= MT__SMALL_USES */
    uint64_t boundary_edges, nonmanifold_edges, inconsistent_edges, duplicate_directed_edges;
    mt__vec bundle_offsets; /* uint32, starts of bundles in bundle_edges */
    mt__vec bundle_edges;   /* uint32 internal edge ids, ascending */

    /* links and fans */
    _Atomic uint32_t *fan_start; /* [num_verts] some face half-edge leaving each vertex */
    uint32_t vert_capacity;      /* allocated length of m->vert_he */
    mt__vec boundary_halves;     /* uint32 every half-edge without a face; in the
                                    report, the boundary edges (used by one face) */
    mt__vec copy_original;       /* uint32 */
    mt__vec split_verts;         /* uint32 caller vertices with more than one fan */
    mt__vec dup_candidates;      /* uint32 faces that may repeat another face */

    /* report */
    _Atomic uint32_t *shared_parent; /* union-find shared by the parts */
    uint32_t *vert_comp;             /* [num_verts_internal] component of each internal vertex */
    uint32_t num_components;
} mt__build;

/* The block a side with smaller vertex lo is filed in. */
static inline uint32_t mt__block_of(const mt__build *b, uint32_t lo)
{
    return lo >> b->block_shift;
}

/* Final id of a half-edge numbered by edge matching: ids from part 1's base
 * on move down by the gap left after part 0's edges (branch-free). */
static inline uint32_t mt__edge_gap(const mt__build *b, uint32_t he)
{
    return he - (he >= b->gap_first_he ? b->gap_shift : 0u);
}

/* A scratch array of count * size bytes, zeroed if asked: the workspace's
 * (grown when too small), or a fresh allocation when the build has none.
 * NULL when out of memory or when the size overflows. */
void *mt__scratch_get(mt__build *b, mt__scratch which, size_t count, size_t size, int zero);

/* Gives a scratch array back: kept by the workspace, or freed. NULL-safe. */
void mt__scratch_put(mt__build *b, void *array);

/* An array of at least `bytes` kept from a recycled mesh, now the caller's:
 * the smallest that fits, if it is no more than twice the size (a small mesh
 * does not hold on to a large one's memory). NULL when none fits or the
 * workspace is NULL. Contents are undefined. */
void *mt__kept_array_take(mt_build_workspace *workspace, size_t bytes);

/* A phase function and its build, for mt__parallel_run. */
typedef struct mt__phase {
    void (*fn)(mt__build *, uint32_t);
    mt__build *b;
} mt__phase;

static inline void mt__phase_part(void *ctx, uint32_t part, uint32_t parts)
{
    (void)parts;
    const mt__phase *p = ctx;
    p->fn(p->b, part);
}

/* Runs fn(b, t) for every part t, part 0 on the calling thread (base/parallel.c). */
static inline void mt__parallel_run(mt__build *b, void (*fn)(mt__build *, uint32_t))
{
    mt__phase p = {fn, b};
    mt__in_parallel(b->parts, mt__phase_part, &p);
}

/* Union-find with path halving over a parent array. */
static inline uint32_t mt__uf_find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

static inline void mt__uf_union(uint32_t *parent, uint32_t x, uint32_t y)
{
    x = mt__uf_find(parent, x);
    y = mt__uf_find(parent, y);
    if (x < y)
        parent[y] = x;
    else if (y < x)
        parent[x] = y;
}

/* Adds a defect entry to a list (a part's own, in the parallel phases);
 * MT_ERR_NOMEM on failure. */
static inline mt_status mt__push_defect(mt__vec *defects, mt_defect_kind kind, uint32_t x,
                                        uint32_t y, uint32_t z)
{
    mt_defect d = {(uint32_t)kind, x, y, z};
    return mt__vec_push(defects, &d);
}

/* The same into the build's merged list (sequential phases, the report). */
static inline mt_status mt__add_defect(mt__build *b, mt_defect_kind kind, uint32_t x, uint32_t y,
                                       uint32_t z)
{
    return mt__push_defect(&b->defects, kind, x, y, z);
}

#endif
