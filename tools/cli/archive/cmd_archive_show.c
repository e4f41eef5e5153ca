/* `meshtopo archive show DIR ID [--version N] [--json]`: one archived
 * version's provenance and topology report. The mesh is restored from the
 * stored half-edge arrays (validated, and checked against the stored
 * report) as the daemon reloads it; a file without usable arrays is rebuilt
 * from its face list, which is said on stderr. */
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include "archive_common.h"
#include "cmd_archive.h"
#include "inspect.h"
#include "meshtopo/json_writer.h"
#include "meshtopo/report_json.h"
#include "remote.h"

static void json_report(mt_json *j, const mt_report *r)
{
    char text[256];
    mt_json_object_begin(j);
#define U(name)            \
    mt_json_key(j, #name); \
    mt_json_uint(j, (uint64_t)r->name)
#define B(name)            \
    mt_json_key(j, #name); \
    mt_json_bool(j, r->name)
    U(num_verts);
    U(num_faces);
    U(num_faces_valid);
    U(num_edges);
    U(num_half_edges);
    U(boundary_edges);
    U(boundary_loops);
    B(boundary_loops_ambiguous);
    U(nonmanifold_edges);
    U(inconsistent_orientation_edges);
    U(duplicate_directed_edges);
    U(nonmanifold_vertices);
    U(bowtie_vertices);
    U(isolated_vertices);
    U(unreferenced_vertices);
    U(degenerate_faces);
    U(duplicate_faces);
    U(out_of_range_indices);
    U(faces_with_out_of_range_indices);
    U(nonfinite_vertices);
    U(connected_components);
    U(vertex_connected_components);
    mt_json_key(j, "euler_characteristic");
    mt_json_int(j, r->euler_characteristic);
    B(closed);
    B(manifold);
    B(orientable);
    B(consistently_oriented);
#undef U
#undef B
    mt_json_key(j, "genus");
    if (r->genus < 0)
        mt_json_null(j);
    else
        mt_json_int(j, r->genus);
    mt_json_key(j, "boundary_loop_lengths");
    mt_json_array_begin(j);
    for (uint32_t i = 0; i < r->boundary_loops; i++) mt_json_uint(j, r->boundary_loop_lengths[i]);
    mt_json_array_end(j);
    mt_json_key(j, "face_size_histogram");
    mt_json_object_begin(j);
    for (size_t i = 0; i < r->num_face_size_bins; i++) {
        snprintf(text, sizeof text, "%" PRIu32, r->face_size_histogram[i].key);
        mt_json_key(j, text);
        mt_json_uint(j, r->face_size_histogram[i].count);
    }
    mt_json_object_end(j);
    mt_json_key(j, "defects");
    mt_report_json_write_defects(j, r->defects, r->num_defects);
    mt_json_object_end(j);
}

static void print_json(const char *dir, const mt_archive_record *rec)
{
    char hash[24];
    mt_json j;
    mt_json_init(&j, stdout);
    mt_json_object_begin(&j);
    mt_json_key(&j, "archive");
    mt_json_string(&j, dir);
    mt_json_key(&j, "file");
    mt_json_string(&j, rec->file_name);
    mt_json_key(&j, "mesh_id");
    mt_json_string(&j, rec->mesh_id);
    mt_json_key(&j, "version");
    mt_json_uint(&j, rec->version);
    mt_json_key(&j, "utime");
    mt_json_int(&j, rec->utime);
    mt_json_key(&j, "source");
    mt_json_string(&j, rec->source);
    mt_json_key(&j, "content_hash");
    mt_json_string(&j, cli_hash_text((int64_t)rec->content_hash, hash, sizeof hash));
    mt_json_key(&j, "format_version");
    mt_json_uint(&j, rec->format_version);
    mt_json_key(&j, "has_positions");
    mt_json_bool(&j, rec->faces.positions != NULL);
    mt_json_key(&j, "report");
    json_report(&j, &rec->report);
    mt_json_object_end(&j);
    mt_json_finish(&j);
}

int cli_archive_show(const cli_args *args)
{
    const char *dir = args->positionals[1], *id = args->positionals[2];
    uint32_t version = 0;
    int code = cli_archive_version(args, &version);
    if (code != CLI_EXIT_OK) return code;
    mt_archive *archive = NULL;
    code = cli_archive_open(dir, true, &archive);
    if (code != CLI_EXIT_OK) return code;
    mt_archive_record rec;
    mt_diag diag;
    mt_mesh *mesh = NULL;
    mt_archive_load_info info;
    /* Restored from the stored half-edge arrays (validated); rebuilt from
     * the face list only when a file lacks them or they are damaged. */
    mt_status st = mt_archive_load_mesh(archive, id, version, true, &rec, &mesh, &info, &diag);
    if (st == MT_OK && info.fallback.status != MT_OK)
        cli_error("archive", "note: rebuilt from the face list: %s", info.fallback.message);
    if (st != MT_OK) {
        cli_error("archive", "%s", diag.message);
        code = st == MT_ERR_INVALID_ARG ? CLI_EXIT_USAGE : CLI_EXIT_READ;
    } else if (cli_flag(args, "json")) {
        print_json(dir, &rec);
    } else {
        char hash[24];
        printf("mesh %s version %" PRIu32 " (source %s, utime %" PRId64 ", content hash %s)\n",
               rec.mesh_id, rec.version, rec.source[0] ? rec.source : "-", rec.utime,
               cli_hash_text((int64_t)rec.content_hash, hash, sizeof hash));
        cli_mesh shown;
        memset(&shown, 0, sizeof shown);
        shown.list = rec.faces;
        shown.mesh = mesh;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, rec.file_name);
        inspect_request req;
        memset(&req, 0, sizeof req);
        req.path = path;
        req.mesh = &shown;
        req.limit = 5;
        code = inspect_print_text(&req, stdout);
    }
    mt_mesh_destroy(mesh);
    mt_archive_record_free(&rec);
    mt_archive_close(archive);
    return cli_finish_output("archive", code, CLI_EXIT_READ);
}
