/* meshtopo::json: a built mesh's topology report as JSON, with the keys of
 * the corpus reference answers (tests/corpus/DEFINITIONS.md) in their
 * order. `meshtopo inspect --json` prints this document and the Python
 * binding reads it, so the two can never disagree on a key; the CLI's
 * reports from meshtopod share the summary. Depends on meshtopo::core only. */
#ifndef MESHTOPO_REPORT_JSON_H
#define MESHTOPO_REPORT_JSON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/json_writer.h"
#include "meshtopo/mesh.h"
#include "meshtopo/report.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most vertices, and most faces, chosen by mt_report_json_default_queries. */
#define MT_REPORT_JSON_MAX_QUERIES 5

/* Which keys the summary carries besides the ones both forms share. */
typedef enum mt_report_json_keys {
    /* The corpus reference answers' (inspect --json, DEFINITIONS.md):
     * nonmanifold_vertices_list_head and component_genera. */
    MT_REPORT_JSON_KEYS_CORPUS,
    /* Every count meshtopod sends: duplicate_faces and nonfinite_vertices. */
    MT_REPORT_JSON_KEYS_DAEMON
} mt_report_json_keys;

/* Writes the report's members (V, F, ... components) into the JSON object
 * being written, in the corpus answers' order; undefined genera are null.
 * A report from meshtopod may list fewer boundary loop lengths and
 * components than it counts: num_loop_lengths and num_components say how
 * many of r's entries are present (r->boundary_loops and
 * r->connected_components for a local report). false when out of memory
 * (the document is then incomplete). */
bool mt_report_json_write_summary(mt_json *j, const mt_report *r, size_t num_loop_lengths,
                                  size_t num_components, mt_report_json_keys keys);

/* The vertices and faces `inspect --json` queries when none are named, as
 * DEFINITIONS.md "Queries" chooses them: first the interesting spots
 * (non-manifold, isolated, boundary, flipped), then evenly spread ids, up
 * to MT_REPORT_JSON_MAX_QUERIES of each, no repeats. Either output pair may
 * be NULL to skip that choice. MT_OK or MT_ERR_NOMEM. */
mt_status mt_report_json_default_queries(const mt_mesh *mesh,
                                         uint32_t out_verts[MT_REPORT_JSON_MAX_QUERIES],
                                         size_t *out_num_verts,
                                         uint32_t out_faces[MT_REPORT_JSON_MAX_QUERIES],
                                         size_t *out_num_faces);

/* Writes the members "vertex_queries" (each vertex's sorted neighbours and
 * valid faces) and "face_queries" (each face's sorted adjacent faces, null
 * for a face the build rejected) into the open object, in the given order.
 * A failed query (an id out of range, out of memory) returns its status
 * with diag naming the element; the document is then incomplete. */
mt_status mt_report_json_write_queries(mt_json *j, const mt_mesh *mesh, const uint32_t *verts,
                                       size_t num_verts, const uint32_t *faces, size_t num_faces,
                                       mt_diag *diag);

/* The members of `inspect --json` up to "file": the summary with
 * MT_REPORT_JSON_KEYS_CORPUS, the queries of the given elements, and
 * "file" (file_name, or null when NULL). The caller opens the object and
 * may add its own members before closing it. Fails as
 * mt_report_json_write_queries does, or with MT_ERR_NOMEM. */
mt_status mt_report_json_write_inspect(mt_json *j, const mt_mesh *mesh, const uint32_t *verts,
                                       size_t num_verts, const uint32_t *faces, size_t num_faces,
                                       const char *file_name, mt_diag *diag);

/* Writes one defect as its record (meshtopo/defect_record.h; README.md
 * "Defect records"): an object with "kind" (the key), "vertices" and
 * "faces" (arrays of ids, maybe empty), "edge" ([u, v] or null),
 * "face_count", "index", "position", "face_size", "distinct_vertices",
 * "fans", "on_nonmanifold_edge" (a boolean) and "axis" (null where they do
 * not apply to the kind), then "description" (mt_defect_describe). */
void mt_report_json_write_defect(mt_json *j, const mt_defect *defect);

/* Writes an array of the records of defects[0 .. count). */
void mt_report_json_write_defects(mt_json *j, const mt_defect *defects, size_t count);

/* The whole document `meshtopo inspect FILE --json` prints for this mesh
 * (no options: the default queries, "file" = file_name or null), as
 * NUL-terminated text in *out_text (out_size, NULL-safe, gets its length).
 * Release it with mt_report_json_free. On failure *out_text is NULL and
 * diag says why (MT_ERR_NOMEM, MT_ERR_INVALID_ARG for a NULL argument). */
mt_status mt_report_json_inspect(const mt_mesh *mesh, const char *file_name, char **out_text,
                                 size_t *out_size, mt_diag *diag);

/* Frees a text from mt_report_json_inspect. NULL-safe. */
void mt_report_json_free(char *text);

#ifdef __cplusplus
}
#endif

#endif
