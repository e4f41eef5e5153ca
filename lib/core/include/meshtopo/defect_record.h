/* The defect record: one defect in named fields whose meaning does not
 * depend on its kind. It is the one schema of defects in meshtopo's outputs
 * (`inspect --json --json-defects`, `query defects --json`, the archive's
 * /meshtopo/report/defects, Python's Mesh.defects); README.md "Defect
 * records" documents it. mt_defect (report.h) keeps the report's compact
 * form; the two convert both ways without loss. */
#ifndef MESHTOPO_DEFECT_RECORD_H
#define MESHTOPO_DEFECT_RECORD_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/report.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Every field of a record, in order, with what it holds. A field that does
 * not apply to the record's kind holds MT_NONE (4294967295; null in JSON),
 * and so does the unused end of a two-id list. */
#define MT_DEFECT_RECORD_FIELDS(X)                                                             \
    X(kind, "the defect kind (its key, e.g. nonmanifold_edge)")                                \
    X(vertices,                                                                                \
      "vertex ids it is at: the vertex (vertex kinds) or the edge's two ends "                 \
      "(edge kinds)")                                                                          \
    X(faces,                                                                                   \
      "face ids it is at: the face (face kinds), then for duplicate_face the earlier "         \
      "face it repeats")                                                                       \
    X(edge,                                                                                    \
      "edge kinds: the edge as [u, v], u < v for nonmanifold_edge, the direction "             \
      "u -> v the faces cross for same_direction_edge")                                        \
    X(face_count,                                                                              \
      "edge kinds: faces using the edge (in that direction for "                               \
      "same_direction_edge)")                                                                  \
    X(index, "out_of_range_index: the bad entry's value, signed as read (-1 for an OBJ 0)")    \
    X(position, "out_of_range_index: the entry's position in its face, from 0")                \
    X(face_size, "degenerate_face: entries of the face")                                       \
    X(distinct_vertices, "degenerate_face: distinct vertices among them")                      \
    X(fans, "nonmanifold_vertex: connected parts (fans) of its link; more than 1 is a bowtie") \
    X(on_nonmanifold_edge,                                                                     \
      "nonmanifold_vertex: 1 (true) when it lies on a non-manifold edge, "                     \
      "else 0")                                                                                \
    X(axis, "nonfinite_coordinate: the first bad coordinate, 0 x, 1 y, 2 z")

/* One defect in named fields (MT_DEFECT_RECORD_FIELDS says what each holds,
 * in this order). 64 bytes without padding: index falls on offset 32. */
typedef struct mt_defect_record {
    uint32_t kind; /* mt_defect_kind */
    uint32_t vertices[2];
    uint32_t faces[2];
    uint32_t edge[2];
    uint32_t face_count;
    int64_t index; /* MT_NONE (no value an entry reads as) when it does not apply */
    uint32_t position;
    uint32_t face_size;
    uint32_t distinct_vertices;
    uint32_t fans;
    uint32_t on_nonmanifold_edge;
    uint32_t axis;
} mt_defect_record;

/* The record of one defect. A kind outside the table gives a record with
 * that kind and every other field MT_NONE. */
mt_defect_record mt_defect_to_record(const mt_defect *defect);

/* The records of defects[0 .. count) into out[0 .. count) (caller-owned, at
 * least count entries). */
void mt_defect_to_records(const mt_defect *defects, size_t count, mt_defect_record *out);

/* The defect a record stands for, into *out. MT_ERR_INVALID_ARG (and *out
 * zeroed) when the record is not one mt_defect_to_record gives: an unknown
 * kind, a field that does not apply holding a value, ids disagreeing
 * between vertices and edge, an index no face-list entry reads as. */
mt_status mt_defect_from_record(const mt_defect_record *record, mt_defect *out);

#ifdef __cplusplus
}
#endif

#endif
