/* The document `meshtopo inspect --json` prints (report_json.h): the
 * summary with the corpus answers' keys, the queried one-rings and face
 * neighbours, and "file", so it diffs cleanly against NAME.expected.json
 * (which adds only "oracle_version"). mt_report_json_inspect writes it
 * whole into memory, never half a document, for the Python binding. */
#include <stdio.h>
#include <stdlib.h>

#include "meshtopo/report_json.h"

mt_status mt_report_json_write_inspect(mt_json *j, const mt_mesh *mesh, const uint32_t *verts,
                                       size_t num_verts, const uint32_t *faces, size_t num_faces,
                                       const char *file_name, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!j || !mesh)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "report JSON: NULL mesh or writer");
    const mt_report *r = mt_mesh_report(mesh);
    if (!mt_report_json_write_summary(j, r, r->boundary_loops, r->connected_components,
                                      MT_REPORT_JSON_KEYS_CORPUS))
        return mt_diag_set(diag, MT_ERR_NOMEM, "out of memory while writing the report");
    mt_status st = mt_report_json_write_queries(j, mesh, verts, num_verts, faces, num_faces, diag);
    if (st != MT_OK) return st;
    mt_json_key(j, "file");
    if (file_name)
        mt_json_string(j, file_name);
    else
        mt_json_null(j);
    return MT_OK;
}

mt_status mt_report_json_inspect(const mt_mesh *mesh, const char *file_name, char **out_text,
                                 size_t *out_size, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (out_text) *out_text = NULL;
    if (out_size) *out_size = 0;
    if (!mesh || !out_text)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "report JSON: NULL mesh or output");
    uint32_t verts[MT_REPORT_JSON_MAX_QUERIES], faces[MT_REPORT_JSON_MAX_QUERIES];
    size_t num_verts = 0, num_faces = 0;
    mt_status st = mt_report_json_default_queries(mesh, verts, &num_verts, faces, &num_faces);
    if (st != MT_OK)
        return mt_diag_set(diag, st, "choosing the queried elements failed: %s", mt_strerror(st));

    char *doc = NULL;
    size_t doc_size = 0;
    FILE *mem = open_memstream(&doc, &doc_size);
    if (!mem) return mt_diag_set(diag, MT_ERR_NOMEM, "out of memory while writing the report");
    mt_json j;
    mt_json_init(&j, mem);
    mt_json_object_begin(&j);
    st =
        mt_report_json_write_inspect(&j, mesh, verts, num_verts, faces, num_faces, file_name, diag);
    if (st == MT_OK) mt_json_object_end(&j);
    bool complete = st == MT_OK && mt_json_finish(&j);
    bool flushed = fclose(mem) == 0;
    if (st == MT_OK && !flushed)
        st = mt_diag_set(diag, MT_ERR_NOMEM, "out of memory while writing the report");
    else if (st == MT_OK && !complete)
        st = mt_diag_set(diag, MT_ERR_CORRUPT, "internal error: malformed JSON document");
    if (st != MT_OK) {
        free(doc);
        return st;
    }
    *out_text = doc;
    if (out_size) *out_size = doc_size;
    return MT_OK;
}

void mt_report_json_free(char *text)
{
    free(text);
}
