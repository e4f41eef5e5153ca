/* `meshtopo archive export DIR ID [--version N] OUT` and `meshtopo archive
 * rm DIR ID [--version N | --all]`: writing an archived version to a file
 * and removing versions. OFF, OBJ and PLY get the face list exactly as
 * submitted (meshtopo::io; PLY with defect colours, defect_colors.h);
 * .hdf / .vtkhdf a VTKHDF archive file of the version rewritten with this
 * meshtopo's topology arrays; .vtu the same converted by
 * tools/vtk/export_vtu.py. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "archive_common.h"
#include "cmd_archive.h"
#include "defect_colors.h"
#include "meshtopo/geometry.h"
#include "meshtopo/io.h"
#include "meshtopo/mesh_ident.h"
#include "temp_archive.h"
#include "vtk_script.h"

/* What OUT's name asks for. */
typedef enum export_kind { EXPORT_MESH, EXPORT_PLY, EXPORT_HDF, EXPORT_VTU } export_kind;

static bool has_suffix(const char *path, const char *suffix)
{
    size_t len = strlen(path), n = strlen(suffix);
    return len > n && strcmp(path + len - n, suffix) == 0;
}

static bool export_kind_of(const char *out, export_kind *kind)
{
    mt_format format = mt_format_from_path(out);
    if (has_suffix(out, ".vtu"))
        *kind = EXPORT_VTU;
    else if (cli_is_archive_path(out))
        *kind = EXPORT_HDF;
    else if (format == MT_FORMAT_PLY_BINARY_LE || format == MT_FORMAT_PLY_ASCII ||
             format == MT_FORMAT_PLY_BINARY_BE)
        *kind = EXPORT_PLY;
    else if (format == MT_FORMAT_OFF || format == MT_FORMAT_OBJ)
        *kind = EXPORT_MESH;
    else
        return false;
    return true;
}

/* The face list with a colour per vertex and per face record. */
static mt_status write_colored_ply(const char *out, const mt_face_list *list, const mt_mesh *mesh,
                                   bool self_intersections, mt_diag *diag)
{
    mt_face_pair *pairs = NULL;
    size_t num_pairs = 0;
    mt_status st = MT_OK;
    if (self_intersections && list->positions) {
        st = mt_mesh_self_intersections(mesh, NULL, 0, &num_pairs, diag);
        if (st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL) {
            pairs = malloc((num_pairs + 1) * sizeof *pairs);
            st = pairs ? mt_mesh_self_intersections(mesh, pairs, num_pairs, &num_pairs, diag)
                       : MT_ERR_NOMEM;
        }
    }
    uint8_t *vertex = malloc(3 * (size_t)list->num_verts + 1);
    uint8_t *face = malloc(3 * (size_t)list->num_faces + 1);
    if (st == MT_OK &&
        (!vertex || !face || !cli_defect_colors(list, mesh, pairs, num_pairs, vertex, face)))
        st = MT_ERR_NOMEM;
    if (st == MT_OK) {
        mt_write_options options = {.vertex_colors = vertex, .face_colors = face};
        st = mt_write_file_with(out, MT_FORMAT_AUTO, list, &options, diag);
    } else if (st == MT_ERR_NOMEM) {
        snprintf(diag->message, sizeof diag->message, "%s: out of memory", out);
    }
    free(pairs);
    free(vertex);
    free(face);
    return st;
}

/* The version rewritten as an archive file (OUT.hdf, OUT.vtkhdf) or
 * converted from one (OUT.vtu). */
static int write_vtk(const char *out, export_kind kind, const mt_archive_record *rec,
                     const mt_mesh *mesh, bool self_intersections)
{
    mt_archive_meta meta = {rec->mesh_id, rec->version, rec->utime, rec->source, rec->content_hash};
    cli_temp_archive temp;
    int code =
        cli_temp_archive_write("archive", &rec->faces, mesh, &meta, self_intersections, &temp);
    if (code != CLI_EXIT_OK) return code;
    if (kind == EXPORT_HDF) {
        code = cli_temp_archive_copy("archive", &temp, out);
    } else {
        const char *script_args[] = {temp.path, out, NULL};
        code = cli_vtk_script_run("archive", "export_vtu.py", script_args);
    }
    cli_temp_archive_remove(&temp);
    return code;
}

int cli_archive_export(const cli_args *args)
{
    const char *dir = args->positionals[1], *id = args->positionals[2];
    const char *out = args->positionals[3];
    const bool self_intersections = cli_flag(args, "self-intersections");
    uint32_t version = 0;
    int code = cli_archive_version(args, &version);
    if (code != CLI_EXIT_OK) return code;
    export_kind kind;
    if (!export_kind_of(out, &kind)) {
        cli_error("archive",
                  "%s: the output name must end in .off, .obj, .ply (.gz too), .vtu, .hdf or "
                  ".vtkhdf",
                  out);
        return CLI_EXIT_USAGE;
    }
    if (self_intersections && kind == EXPORT_MESH) {
        cli_error("archive", "--self-intersections applies to .ply, .vtu, .hdf and .vtkhdf");
        return CLI_EXIT_USAGE;
    }
    mt_archive *archive = NULL;
    code = cli_archive_open(dir, true, &archive);
    if (code != CLI_EXIT_OK) return code;
    mt_archive_record rec;
    mt_mesh *mesh = NULL;
    mt_diag diag;
    mt_status st = kind == EXPORT_MESH
                       ? mt_archive_load(archive, id, version, &rec, &diag)
                       : mt_archive_load_mesh(archive, id, version, true, &rec, &mesh, NULL, &diag);
    if (st == MT_OK && kind == EXPORT_MESH)
        st = mt_write_file(out, MT_FORMAT_AUTO, &rec.faces, &diag);
    if (st == MT_OK && kind == EXPORT_PLY)
        st = write_colored_ply(out, &rec.faces, mesh, self_intersections, &diag);
    if (st != MT_OK) {
        cli_error("archive", "%s", diag.message);
        code = st == MT_ERR_INVALID_ARG ? CLI_EXIT_USAGE : CLI_EXIT_READ;
    } else if (kind == EXPORT_HDF || kind == EXPORT_VTU) {
        code = write_vtk(out, kind, &rec, mesh, self_intersections);
    }
    if (code == CLI_EXIT_OK)
        printf("exported mesh %s version %u (%u vertices, %u faces) to %s\n", rec.mesh_id,
               rec.version, rec.faces.num_verts, rec.faces.num_faces, out);
    mt_mesh_destroy(mesh);
    mt_archive_record_free(&rec);
    mt_archive_close(archive);
    return cli_finish_output("archive", code, CLI_EXIT_READ);
}

/* Versions of id present in the archive, ascending (malloc'ed). */
static size_t versions_of(const mt_archive *archive, const char *id, uint32_t **out)
{
    *out = NULL;
    mt_archive_listing l;
    if (mt_archive_list(archive, &l, NULL) != MT_OK) return 0;
    size_t n = 0;
    *out = malloc((l.count + 1) * sizeof **out);
    for (size_t i = 0; *out && i < l.count; i++)
        if (l.entries[i].status == MT_OK && strcmp(l.entries[i].mesh_id, id) == 0)
            (*out)[n++] = l.entries[i].version;
    mt_archive_listing_free(&l);
    return n;
}

int cli_archive_rm(const cli_args *args)
{
    const char *dir = args->positionals[1], *id = args->positionals[2];
    uint32_t version = 0;
    int code = cli_archive_version(args, &version);
    if (code != CLI_EXIT_OK) return code;
    bool all = cli_flag(args, "all");
    if (all && version) {
        cli_error("archive", "rm: give --version or --all, not both");
        return CLI_EXIT_USAGE;
    }
    mt_diag diag;
    if (mt_mesh_id_check(id, &diag) != MT_OK) {
        cli_error("archive", "rm: %s", diag.message);
        return CLI_EXIT_USAGE;
    }
    mt_archive *archive = NULL;
    code = cli_archive_open(dir, false, &archive);
    if (code != CLI_EXIT_OK) return code;
    uint32_t *versions = NULL;
    size_t n = versions_of(archive, id, &versions);
    if (version) {
        n = 1;
        free(versions);
        versions = malloc(sizeof *versions);
        if (versions) versions[0] = version;
    } else if (!all && n > 0) {
        versions[0] = versions[n - 1]; /* the highest */
        n = 1;
    }
    if (n == 0 || !versions) {
        cli_error("archive", "rm: mesh '%s' is not archived in %s", id, dir);
        code = CLI_EXIT_READ;
    }
    for (size_t i = 0; code == CLI_EXIT_OK && i < n; i++) {
        if (mt_archive_remove(archive, id, versions[i], &diag) != MT_OK) {
            cli_error("archive", "rm: %s", diag.message);
            code = CLI_EXIT_READ;
        } else {
            printf("removed mesh %s version %u\n", id, versions[i]);
        }
    }
    free(versions);
    mt_archive_close(archive);
    return cli_finish_output("archive", code, CLI_EXIT_READ);
}
