/* State shared by the build phases (build.c orchestrates them):
 *   faces   (build_faces.c)  classify records, count corners per vertex
 *   edges   (build_edges.c)  counting sort by tail vertex, twin matching
 *   links   (build.c)        next/face/head of every half-edge
 *   fans    (build_fans.c)   boundary rings, one internal vertex per fan
 *   report  (report_*.c)     components, loops, links, genus, duplicates
 * Every phase is a fixed number of passes over flat arrays. */
#ifndef MESHTOPO_BUILD_INTERNAL_H
#define MESHTOPO_BUILD_INTERNAL_H

#include <stdint.h>

#include "mesh_internal.h"
#include "meshtopo/face_list.h"
#include "meshtopo/mesh.h"

/* Corners (sides of valid faces) a build accepts: half-edge ids then stay
 * below 2^31, which frees bit 31 for the flags below. */
#define MT__MAX_CORNERS 0x3fffffffu
#define MT__FLAG 0x80000000u /* in bucket entries: processed; in c2h: twin is boundary */

/* Face sizes counted in a flat histogram; larger ones are collected and sorted. */
#define MT__SMALL_SIZES 64
/* Edge use counts counted in a flat histogram; larger ones collected likewise. */
#define MT__SMALL_USES 16

typedef struct mt__build {
    const mt_face_list *in;
    mt_mesh *m;
    mt_diag *diag;
    uint32_t threads;

    /* faces */
    uint64_t num_corners; /* sides of valid faces */
    uint64_t size_hist[MT__SMALL_SIZES];
    mt__vec large_sizes;  /* uint32 sizes >= MT__SMALL_SIZES */
    mt__vec invalid_refs; /* uint32 in-range vertices of rejected records */
    mt__vec defects;      /* mt_defect, in discovery order (sorted at the end) */
    uint64_t out_of_range_entries;
    uint32_t out_of_range_faces, degenerate_faces, nonfinite_vertices;
    mt__vec scratch; /* uint32, sorting the indices of big faces */

    /* edges */
    uint32_t *bucket_start; /* [num_verts + 1] corners leaving each vertex */
    uint64_t *bucket;       /* [num_corners] (head << 32) | corner, later | half-edge */
    uint32_t *c2h;          /* [num_indices] half-edge of each corner (| MT__FLAG) */
    uint32_t max_degree;
    uint32_t num_internal_edges;
    uint64_t num_edges; /* distinct undirected edges */
    uint64_t use_hist[MT__SMALL_USES];
    mt__vec large_uses; /* uint32 use counts >= MT__SMALL_USES */
    uint64_t boundary_edges, nonmanifold_edges, inconsistent_edges, duplicate_directed_edges;
    mt__vec bundle_offsets; /* uint32, starts of bundles in bundle_edges */
    mt__vec bundle_edges;   /* uint32 internal edge ids, ascending */

    /* fans */
    uint32_t vert_capacity; /* allocated length of m->vert_he */
    mt__vec copy_original;  /* uint32 */
    mt__vec split_verts;    /* uint32 caller vertices with more than one fan */
    mt__vec dup_candidates; /* uint32 faces that may repeat another face */

    /* report */
    uint32_t *vert_comp; /* [num_verts_internal] component of each internal vertex */
    uint32_t num_components;
} mt__build;

mt_status mt__build_faces(mt__build *b);
mt_status mt__build_edges(mt__build *b);
mt_status mt__build_fans(mt__build *b);
mt_status mt__build_report(mt__build *b);

/* Parts of the report (report_*.c), called by mt__build_report in order. */
mt_status mt__report_components(mt__build *b);  /* components, per-component counts */
mt_status mt__report_boundary(mt__build *b);    /* boundary-edge graph: loops, lengths */
mt_status mt__report_links(mt__build *b);       /* vertex links: non-manifold, bowtie */
mt_status mt__report_orientation(mt__build *b); /* orientability per component */
mt_status mt__report_duplicates(mt__build *b);  /* duplicate faces */

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

/* 1 when internal edge e has a half-edge without a face and is alone (not
 * bundled): an edge used by exactly one face. */
int mt__is_boundary_edge(const mt_mesh *m, uint32_t e);

/* Adds a defect entry; MT_ERR_NOMEM on failure. */
mt_status mt__add_defect(mt__build *b, mt_defect_kind kind, uint32_t x, uint32_t y, uint32_t z);

#endif
