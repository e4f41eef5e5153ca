/* `meshtopo inspect --json`: one JSON object with exactly the keys of the
 * corpus answers (tests/corpus/DEFINITIONS.md) in their order, so it diffs
 * cleanly against NAME.expected.json (which adds only "oracle_version"):
 * meshtopo::json writes them (the same document the Python binding reads);
 * --weld appends "weld", --self-intersections the geometry, --json-defects
 * "defects" (defect records, README.md "Defect records"). Built in memory and written only when
 * every query succeeded: never half a document. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "inspect.h"
#include "meshtopo/json_writer.h"
#include "meshtopo/report_json.h"

static void write_ids(mt_json *j, const uint32_t *ids, size_t count)
{
    mt_json_array_begin(j);
    for (size_t i = 0; i < count; i++) mt_json_uint(j, ids[i]);
    mt_json_array_end(j);
}

/* One list of default queries as an mt_id_list (malloc'ed). */
static mt_status store_ids(const uint32_t *ids, size_t count, mt_id_list *out)
{
    memset(out, 0, sizeof *out);
    if (count == 0) return MT_OK;
    out->ids = malloc(count * sizeof *out->ids);
    if (!out->ids) return MT_ERR_NOMEM;
    memcpy(out->ids, ids, count * sizeof *out->ids);
    out->count = count;
    return MT_OK;
}

mt_status inspect_default_queries(const mt_mesh *mesh, bool want_vertices, mt_id_list *out_vertices,
                                  bool want_faces, mt_id_list *out_faces)
{
    uint32_t verts[MT_REPORT_JSON_MAX_QUERIES], faces[MT_REPORT_JSON_MAX_QUERIES];
    size_t num_verts = 0, num_faces = 0;
    mt_status st = mt_report_json_default_queries(mesh, want_vertices ? verts : NULL, &num_verts,
                                                  want_faces ? faces : NULL, &num_faces);
    if (st == MT_OK && want_vertices) st = store_ids(verts, num_verts, out_vertices);
    if (st == MT_OK && want_faces) {
        st = store_ids(faces, num_faces, out_faces);
        if (st != MT_OK && want_vertices) mt_id_list_free(out_vertices);
    }
    return st;
}

/* "weld": what --weld did (README, inspect's JSON keys). */
static void write_weld(mt_json *j, const cli_weld *w)
{
    mt_json_object_begin(j);
    mt_json_key(j, "mode");
    mt_json_string(j, w->eps == 0 ? "exact" : "distance");
    mt_json_key(j, "eps");
    mt_json_double(j, w->eps);
    mt_json_key(j, "vertices_before");
    mt_json_uint(j, w->vertices_before);
    mt_json_key(j, "vertices_after");
    mt_json_uint(j, w->vertices_after);
    mt_json_key(j, "merged");
    mt_json_uint(j, w->merged);
    mt_json_key(j, "nonmanifold_after_weld");
    write_ids(j, w->nonmanifold, w->num_nonmanifold);
    mt_json_object_end(j);
}

int inspect_print_json(const inspect_request *req, FILE *out)
{
    const mt_mesh *mesh = req->mesh->mesh;
    const mt_report *r = mt_mesh_report(mesh);
    char *doc = NULL;
    size_t doc_size = 0;
    FILE *mem = open_memstream(&doc, &doc_size);
    if (!mem) {
        cli_error("inspect", "out of memory");
        return CLI_EXIT_BUILD;
    }
    mt_json j;
    mt_json_init(&j, mem);
    mt_json_object_begin(&j);
    mt_diag diag;
    mt_status st = mt_report_json_write_inspect(&j, mesh, req->vertices.ids, req->vertices.count,
                                                req->faces.ids, req->faces.count,
                                                cli_basename(req->path), &diag);
    if (st == MT_OK) {
        if (req->mesh->weld.enabled) {
            mt_json_key(&j, "weld");
            write_weld(&j, &req->mesh->weld);
        }
        if (req->geometry) inspect_geometry_json(&j, req->geometry);
        if (req->json_defects) {
            mt_json_key(&j, "defects");
            mt_report_json_write_defects(&j, r->defects, r->num_defects);
        }
        mt_json_object_end(&j);
    }
    bool complete = st == MT_OK && mt_json_finish(&j);
    bool flushed = fclose(mem) == 0;
    int code = CLI_EXIT_OK;
    if (st != MT_OK) {
        cli_error("inspect", "%s", diag.message);
        code = CLI_EXIT_BUILD;
    } else if (!flushed) {
        cli_error("inspect", "out of memory while writing JSON");
        code = CLI_EXIT_BUILD;
    } else if (!complete) {
        cli_error("inspect", "internal error: malformed JSON document");
        code = CLI_EXIT_BUILD;
    } else if (fwrite(doc, 1, doc_size, out) != doc_size) {
        cli_error("inspect", "cannot write the output");
        code = CLI_EXIT_BUILD;
    }
    free(doc);
    return code;
}
