/* `meshtopo inspect --json`: one JSON object with exactly the keys of the
 * corpus answers (shared/corpus/DEFINITIONS.md) in their order, so it diffs
 * cleanly against NAME.expected.json (which adds only "oracle_version");
 * undefined genera are null (the summary is cli_report_json.c's, shared with
 * the daemon's reports); --weld appends "weld", --json-defects "defects". Built in memory and
 * written only when every query succeeded: never half a document. */
#include <stdlib.h>
#include <string.h>

#include "cli_report.h"
#include "inspect.h"
#include "json_writer.h"

static void write_ids(mt_json *j, const uint32_t *ids, size_t count)
{
    mt_json_array_begin(j);
    for (size_t i = 0; i < count; i++) mt_json_uint(j, ids[i]);
    mt_json_array_end(j);
}

static mt_status write_vertex_queries(mt_json *j, const mt_mesh *mesh, const mt_id_list *verts,
                                      uint32_t *failed)
{
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    mt_status st = MT_OK;
    mt_json_array_begin(j);
    for (size_t i = 0; i < verts->count && st == MT_OK; i++) {
        uint32_t v = verts->ids[i];
        st = mt_inspect_ring(mesh, v, &ring);
        if (st != MT_OK) {
            *failed = v;
            break;
        }
        size_t nn = mt_inspect_sort_unique(ring.neighbors, ring.num_neighbors);
        size_t nf = mt_inspect_sort_unique(ring.faces, ring.num_faces);
        mt_json_object_begin(j);
        mt_json_key(j, "vertex");
        mt_json_uint(j, v);
        mt_json_key(j, "neighbors");
        write_ids(j, ring.neighbors, nn);
        mt_json_key(j, "faces");
        write_ids(j, ring.faces, nf);
        mt_json_object_end(j);
    }
    mt_json_array_end(j);
    mt_inspect_ring_free(&ring);
    return st;
}

static mt_status write_face_queries(mt_json *j, const mt_mesh *mesh, const mt_id_list *faces,
                                    uint32_t *failed)
{
    mt_face_adjacency adj;
    memset(&adj, 0, sizeof adj);
    mt_status st = MT_OK;
    mt_json_array_begin(j);
    for (size_t i = 0; i < faces->count; i++) {
        uint32_t f = faces->ids[i];
        st = mt_inspect_face_adjacency(mesh, f, &adj);
        mt_json_object_begin(j);
        mt_json_key(j, "face");
        mt_json_uint(j, f);
        mt_json_key(j, "adjacent_faces");
        if (st == MT_ERR_NOT_FOUND) {
            mt_json_null(j); /* a rejected record has no adjacency */
            st = MT_OK;
        } else if (st == MT_OK) {
            size_t n = mt_inspect_sort_unique(adj.faces, adj.num_faces);
            size_t kept = 0;
            for (size_t k = 0; k < n; k++)
                if (adj.faces[k] != f) adj.faces[kept++] = adj.faces[k];
            write_ids(j, adj.faces, kept);
        } else {
            *failed = f;
            mt_json_null(j);
            mt_json_object_end(j);
            break;
        }
        mt_json_object_end(j);
    }
    mt_json_array_end(j);
    mt_inspect_face_adjacency_free(&adj);
    return st;
}

/* "weld": what --weld did (README, inspect's JSON keys). */
static void write_weld(mt_json *j, const mt_cli_weld *w)
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

static void write_defect(mt_json *j, const mt_defect *d)
{
    char text[512];
    mt_defect_describe(d, text, sizeof text);
    mt_json_object_begin(j);
    mt_json_key(j, "kind");
    mt_json_string(
        j, d->kind < MT_DEFECT_KIND_COUNT ? mt_defect_key((mt_defect_kind)d->kind) : "unknown");
    switch (d->kind) {
        case MT_DEFECT_OUT_OF_RANGE_INDEX:
            mt_json_key(j, "face");
            mt_json_uint(j, d->a);
            mt_json_key(j, "index");
            mt_json_int(j, mt_index_as_signed(d->b));
            mt_json_key(j, "position");
            mt_json_uint(j, d->c);
            break;
        case MT_DEFECT_DEGENERATE_FACE:
            mt_json_key(j, "face");
            mt_json_uint(j, d->a);
            mt_json_key(j, "distinct_vertices");
            mt_json_uint(j, d->b);
            mt_json_key(j, "size");
            mt_json_uint(j, d->c);
            break;
        case MT_DEFECT_DUPLICATE_FACE:
            mt_json_key(j, "face");
            mt_json_uint(j, d->a);
            mt_json_key(j, "duplicate_of");
            mt_json_uint(j, d->b);
            break;
        case MT_DEFECT_NONMANIFOLD_EDGE:
            mt_json_key(j, "edge");
            mt_json_array_begin(j);
            mt_json_uint(j, d->a);
            mt_json_uint(j, d->b);
            mt_json_array_end(j);
            mt_json_key(j, "faces");
            mt_json_uint(j, d->c);
            break;
        case MT_DEFECT_SAME_DIRECTION_EDGE:
            mt_json_key(j, "from");
            mt_json_uint(j, d->a);
            mt_json_key(j, "to");
            mt_json_uint(j, d->b);
            mt_json_key(j, "faces");
            mt_json_uint(j, d->c);
            break;
        case MT_DEFECT_NONMANIFOLD_VERTEX:
            mt_json_key(j, "vertex");
            mt_json_uint(j, d->a);
            mt_json_key(j, "fans");
            mt_json_uint(j, d->b);
            mt_json_key(j, "on_nonmanifold_edge");
            mt_json_bool(j, d->c != 0);
            break;
        case MT_DEFECT_ISOLATED_VERTEX:
            mt_json_key(j, "vertex");
            mt_json_uint(j, d->a);
            break;
        case MT_DEFECT_NONFINITE_COORD:
            mt_json_key(j, "vertex");
            mt_json_uint(j, d->a);
            mt_json_key(j, "axis");
            mt_json_uint(j, d->b);
            break;
        default:
            mt_json_key(j, "a");
            mt_json_uint(j, d->a);
            mt_json_key(j, "b");
            mt_json_uint(j, d->b);
            mt_json_key(j, "c");
            mt_json_uint(j, d->c);
            break;
    }
    mt_json_key(j, "text");
    mt_json_string(j, text);
    mt_json_object_end(j);
}

int mt_inspect_print_json(const mt_inspect_request *req, FILE *out)
{
    const mt_mesh *mesh = req->mesh->mesh;
    const mt_report *r = mt_mesh_report(mesh);
    char *doc = NULL;
    size_t doc_size = 0;
    FILE *mem = open_memstream(&doc, &doc_size);
    if (!mem) {
        mt_cli_error("inspect", "out of memory");
        return MT_CLI_EXIT_BUILD;
    }
    mt_json j;
    mt_json_init(&j, mem);
    mt_json_object_begin(&j);
    mt_cli_report summary = mt_cli_report_local(r);
    bool ok = mt_cli_report_write_summary(&j, &summary, MT_CLI_REPORT_KEYS_CORPUS);
    uint32_t failed = MT_NONE;
    mt_status st = MT_OK;
    const char *what = "vertex";
    if (ok) {
        mt_json_key(&j, "vertex_queries");
        st = write_vertex_queries(&j, mesh, &req->vertices, &failed);
    }
    if (ok && st == MT_OK) {
        what = "face";
        mt_json_key(&j, "face_queries");
        st = write_face_queries(&j, mesh, &req->faces, &failed);
    }
    if (ok && st == MT_OK) {
        mt_json_key(&j, "file");
        mt_json_string(&j, mt_cli_basename(req->path));
        if (req->mesh->weld.enabled) {
            mt_json_key(&j, "weld");
            write_weld(&j, &req->mesh->weld);
        }
        if (req->geometry) mt_inspect_geometry_json(&j, req->geometry);
        if (req->json_defects) {
            mt_json_key(&j, "defects");
            mt_json_array_begin(&j);
            for (size_t i = 0; i < r->num_defects; i++) write_defect(&j, &r->defects[i]);
            mt_json_array_end(&j);
        }
        mt_json_object_end(&j);
    }
    bool complete = ok && st == MT_OK && mt_json_finish(&j);
    bool flushed = fclose(mem) == 0;
    int code = MT_CLI_EXIT_OK;
    if (!ok || !flushed) {
        mt_cli_error("inspect", "out of memory while writing JSON");
        code = MT_CLI_EXIT_BUILD;
    } else if (st != MT_OK) {
        mt_cli_error("inspect", "query of %s %u failed: %s", what, (unsigned)failed,
                     mt_strerror(st));
        code = MT_CLI_EXIT_BUILD;
    } else if (!complete) {
        mt_cli_error("inspect", "internal error: malformed JSON document");
        code = MT_CLI_EXIT_BUILD;
    } else if (fwrite(doc, 1, doc_size, out) != doc_size) {
        mt_cli_error("inspect", "cannot write the output");
        code = MT_CLI_EXIT_BUILD;
    }
    free(doc);
    return code;
}
