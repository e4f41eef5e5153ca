/* A brute-force reference for the topology report, for tests only: every
 * quantity of tests/corpus/DEFINITIONS.md computed straight from the face
 * list by sorting and union-find, written for obvious correctness rather than
 * speed, and sharing no code with the library's builder. It also gives the
 * per-element sets (edge faces, vertex neighbours and faces, face adjacency,
 * vertex links) that the query tests compare against. */
#ifndef MESHTOPO_TEST_ORACLE_H
#define MESHTOPO_TEST_ORACLE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/face_list.h"
#include "meshtopo/report.h"

/* One undirected edge of the valid faces. */
typedef struct mt_oracle_edge {
    uint32_t a, b;      /* a < b */
    uint32_t uses;      /* valid faces with {a, b} as a side */
    uint32_t forward;   /* of them, how many have the side (a, b) */
    size_t face_begin;  /* its faces, ascending, are oracle.edge_faces[face_begin .. + uses) */
    uint32_t component; /* component of its faces */
} mt_oracle_edge;

/* A directed side (a, b) used by `count` >= 2 valid faces. */
typedef struct mt_oracle_side {
    uint32_t a, b, count;
} mt_oracle_side;

typedef struct mt_oracle {
    /* Every report field except the defect list (num_defects = 0). The
     * arrays are owned by the oracle. */
    mt_report report;

    /* Face records [num_faces]. */
    uint64_t *face_offset;       /* start of the record in face_indices */
    bool *face_valid;            /* not degenerate, no out-of-range entry */
    bool *face_degenerate;       /* fewer than 3 entries or a repeated value */
    uint32_t *face_distinct;     /* distinct values in the record */
    uint32_t *face_first_bad;    /* position of the first out-of-range entry, MT_NONE if none */
    uint32_t *face_duplicate_of; /* smallest earlier valid face with the same vertex cycle
                                    (either direction), MT_NONE if none */
    uint32_t *face_component;    /* index in report.components, MT_NONE for invalid records */

    /* Edges sorted by (a, b). */
    size_t num_edges;
    mt_oracle_edge *edges;
    uint32_t *edge_faces;

    /* Directed sides used by two or more valid faces, sorted by (a, b). */
    size_t num_dup_sides;
    mt_oracle_side *dup_sides;

    /* Per vertex [num_verts] CSR sets, ascending: neighbours across edges,
     * valid faces holding the vertex. */
    size_t *vert_nb_offsets; /* [num_verts + 1] */
    uint32_t *vert_nb;
    size_t *vert_face_offsets; /* [num_verts + 1] */
    uint32_t *vert_faces;

    /* Per face [num_faces] CSR set of valid faces sharing an edge, ascending. */
    size_t *face_adj_offsets; /* [num_faces + 1] */
    uint32_t *face_adj;

    /* Per vertex link: its connected parts (0 for a vertex in no valid face)
     * and whether some link node has degree > 2. */
    uint32_t *link_parts;
    bool *link_branch;
    uint32_t *nonmanifold_verts; /* [report.nonmanifold_vertices] ascending */

    /* Vertices in no valid face, ascending [report.isolated_vertices]. */
    uint32_t *isolated_verts;

    /* First non-finite axis of each vertex, MT_NONE when all are finite or
     * there are no positions [num_verts]. */
    uint32_t *nonfinite_axis;
} mt_oracle;

/* Computes everything for `list`. Returns false (and leaves *out zeroed)
 * when the sizes are inconsistent (see mt_face_list_check). Running out of
 * memory ends the test program with a message. */
bool mt_oracle_compute(const mt_face_list *list, mt_oracle *out);

void mt_oracle_free(mt_oracle *oracle);

/* The edge {a, b} (either order), or NULL when no valid face has it. */
const mt_oracle_edge *mt_oracle_find_edge(const mt_oracle *oracle, uint32_t a, uint32_t b);

/* Whether the oracle finds any defect that strict mode refuses. */
bool mt_oracle_has_defect(const mt_oracle *oracle);

#endif
