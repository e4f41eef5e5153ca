/* The topology report every build produces: counts, flags, per-component
 * figures and every defect with its element ids. Quantities follow the corpus
 * definitions (tests/corpus/DEFINITIONS.md): topology uses valid faces only,
 * edges are unordered vertex pairs in the caller's ids, manifoldness of a
 * vertex is judged on its link. */
#ifndef MESHTOPO_REPORT_H
#define MESHTOPO_REPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a defect entry means; a, b, c are per kind. Generated from one table
 * so names and descriptions stay together. Outside the library a defect
 * travels as its record of named fields (meshtopo/defect_record.h). */
#define MT_DEFECT_TABLE(X)                                                                         \
    /* a = face, b = first bad index value (as stored), c = its position in the face */            \
    X(MT_DEFECT_OUT_OF_RANGE_INDEX, "out_of_range_index", "face uses a vertex index out of range") \
    /* a = face, b = number of distinct vertices, c = face size */                                 \
    X(MT_DEFECT_DEGENERATE_FACE, "degenerate_face",                                                \
      "face has fewer than 3 entries or repeats a vertex")                                         \
    /* a = face, b = earlier face with the same vertex cycle (either direction) */                 \
    X(MT_DEFECT_DUPLICATE_FACE, "duplicate_face", "face repeats an earlier face")                  \
    /* a, b = edge vertices (a < b), c = number of faces using the edge (> 2) */                   \
    X(MT_DEFECT_NONMANIFOLD_EDGE, "nonmanifold_edge", "edge used by more than two faces")          \
    /* a -> b = a directed side used by c >= 2 faces; one entry per such direction */              \
    X(MT_DEFECT_SAME_DIRECTION_EDGE, "same_direction_edge",                                        \
      "two faces cross an edge in the same direction")                                             \
    /* a = vertex, b = connected parts (fans) of its link, c = 1 if a link vertex                  \
       has degree > 2 (the vertex is on a non-manifold edge). b > 1 is a bowtie. */                \
    X(MT_DEFECT_NONMANIFOLD_VERTEX, "nonmanifold_vertex",                                          \
      "vertex whose faces do not form a single fan")                                               \
    /* a = vertex */                                                                               \
    X(MT_DEFECT_ISOLATED_VERTEX, "isolated_vertex", "vertex used by no valid face")                \
    /* a = vertex, b = coordinate axis (0, 1, 2) */                                                \
    X(MT_DEFECT_NONFINITE_COORD, "nonfinite_coordinate", "vertex has a NaN or infinite coordinate")

typedef enum mt_defect_kind {
#define MT__DEFECT_ENUM(name, key, text) name,
    MT_DEFECT_TABLE(MT__DEFECT_ENUM)
#undef MT__DEFECT_ENUM
        MT_DEFECT_KIND_COUNT
} mt_defect_kind;

/* Machine-friendly key ("nonmanifold_edge") and English description. */
const char *mt_defect_key(mt_defect_kind kind);
const char *mt_defect_description(mt_defect_kind kind);

typedef struct mt_defect {
    uint32_t kind; /* mt_defect_kind */
    uint32_t a, b, c;
} mt_defect;

typedef struct mt_histogram_bin {
    uint32_t key;   /* face size or edge use count */
    uint64_t count; /* how many faces / edges */
} mt_histogram_bin;

/* One edge-connected component of valid faces. */
typedef struct mt_component_info {
    uint32_t min_face; /* smallest face id in it; components are ordered by it */
    uint32_t faces;
    uint32_t vertices; /* distinct caller vertices of its faces */
    uint64_t edges;    /* distinct undirected edges */
    int64_t euler_characteristic;
    uint64_t boundary_edges; /* edges used by exactly one face */
    uint32_t boundary_loops; /* connected parts of its boundary-edge graph */
    bool closed, manifold, orientable;
    int32_t genus;               /* -1 unless closed, manifold and orientable */
    int32_t genus_with_boundary; /* -1 unless manifold and orientable */
} mt_component_info;

typedef struct mt_report {
    uint32_t num_verts;       /* V: every listed vertex, less those an edit deleted (so
                                 V - E + F_valid is the Euler characteristic before
                                 compaction too; mt_mesh_num_verts keeps the id range) */
    uint32_t num_faces;       /* F: every face record */
    uint32_t num_faces_valid; /* records kept in the mesh */
    uint64_t num_edges;       /* distinct undirected edges of valid faces */
    uint64_t num_half_edges;  /* sum of all record sizes (degenerate ones too) */

    uint64_t boundary_edges;
    uint32_t boundary_loops;         /* parts of the boundary-edge graph */
    bool boundary_loops_ambiguous;   /* some vertex has boundary degree other than 2 */
    uint32_t *boundary_loop_lengths; /* [boundary_loops] edge counts, ascending */

    uint64_t nonmanifold_edges;              /* used by more than two faces */
    uint64_t inconsistent_orientation_edges; /* used by exactly two faces, same direction */
    uint64_t duplicate_directed_edges;       /* some directed side used by two or more faces */
    uint32_t nonmanifold_vertices;           /* link not a single simple path or cycle */
    uint32_t bowtie_vertices;                /* link disconnected */
    uint32_t isolated_vertices;              /* in no valid face */
    uint32_t unreferenced_vertices;          /* in no face record at all */
    uint32_t degenerate_faces;               /* fewer than 3 entries or a repeated vertex */
    uint32_t duplicate_faces;                /* valid faces repeating an earlier one */
    uint64_t out_of_range_indices;           /* entries, with repeats */
    uint32_t faces_with_out_of_range_indices;
    uint32_t nonfinite_vertices;

    uint32_t connected_components;        /* classes of faces sharing edges */
    uint32_t vertex_connected_components; /* classes of faces sharing vertices */
    int64_t euler_characteristic;         /* V - E + F_valid */
    bool closed, manifold, orientable, consistently_oriented;
    int32_t genus; /* of the single component, -1 when undefined or several */

    mt_component_info *components; /* [connected_components], by min_face */

    size_t num_face_size_bins;
    mt_histogram_bin *face_size_histogram; /* ascending key, over all records */
    size_t num_edge_use_bins;
    mt_histogram_bin *edge_use_histogram; /* ascending key */

    /* Every defect, grouped by kind in table order, then by first id. */
    size_t num_defects;
    mt_defect *defects;
} mt_report;

/* Number of defect entries of one kind in the report. */
size_t mt_report_count_defects(const mt_report *report, mt_defect_kind kind);

/* Writes one line describing a defect ("non-manifold edge 7-8 is used by 3
 * faces") into buf (always NUL-terminated when size > 0). Returns the length
 * the full text needs, like snprintf. */
size_t mt_defect_describe(const mt_defect *defect, char *buf, size_t size);

#ifdef __cplusplus
}
#endif

#endif
