/* `meshtopo archive export DIR ID [--version N] OUT` and `meshtopo archive
 * rm DIR ID [--version N | --all]`: writing an archived face list to a mesh
 * file exactly as submitted (meshtopo::io), and removing versions. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd_archive.h"
#include "meshtopo/io.h"
#include "meshtopo/msgs.h"
#include "meshtopo/protocol.h"

int mt_cli_archive_export(const mt_cli_args *args)
{
    const char *dir = args->positionals[1], *id = args->positionals[2];
    const char *out = args->positionals[3];
    uint32_t version = 0;
    int code = mt_cli_archive_version(args, &version);
    if (code != MT_CLI_EXIT_OK) return code;
    if (mt_format_from_path(out) == MT_FORMAT_AUTO) {
        mt_cli_error("archive", "%s: the output name must end in .off, .obj or .ply (.gz too)",
                     out);
        return MT_CLI_EXIT_USAGE;
    }
    mt_archive *archive = NULL;
    code = mt_cli_archive_open(dir, true, &archive);
    if (code != MT_CLI_EXIT_OK) return code;
    mt_archive_record rec;
    mt_diag diag;
    mt_status st = mt_archive_load(archive, id, version, &rec, &diag);
    if (st == MT_OK) st = mt_write_file(out, MT_FORMAT_AUTO, &rec.faces, &diag);
    if (st != MT_OK) {
        mt_cli_error("archive", "%s", diag.message);
        code = st == MT_ERR_INVALID_ARG ? MT_CLI_EXIT_USAGE : MT_CLI_EXIT_READ;
    } else {
        printf("exported mesh %s version %u (%u vertices, %u faces) to %s\n", rec.mesh_id,
               rec.version, rec.faces.num_verts, rec.faces.num_faces, out);
    }
    mt_archive_record_free(&rec);
    mt_archive_close(archive);
    return mt_cli_finish_output("archive", code, MT_CLI_EXIT_READ);
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

int mt_cli_archive_rm(const mt_cli_args *args)
{
    const char *dir = args->positionals[1], *id = args->positionals[2];
    uint32_t version = 0;
    int code = mt_cli_archive_version(args, &version);
    if (code != MT_CLI_EXIT_OK) return code;
    bool all = mt_cli_flag(args, "all");
    if (all && version) {
        mt_cli_error("archive", "rm: give --version or --all, not both");
        return MT_CLI_EXIT_USAGE;
    }
    mt_diag diag;
    if (mt_msgs_mesh_id_check(id, &diag) != MT_OK) {
        mt_cli_error("archive", "rm: %s", diag.message);
        return MT_CLI_EXIT_USAGE;
    }
    mt_archive *archive = NULL;
    code = mt_cli_archive_open(dir, false, &archive);
    if (code != MT_CLI_EXIT_OK) return code;
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
        mt_cli_error("archive", "rm: mesh '%s' is not archived in %s", id, dir);
        code = MT_CLI_EXIT_READ;
    }
    for (size_t i = 0; code == MT_CLI_EXIT_OK && i < n; i++) {
        if (mt_archive_remove(archive, id, versions[i], &diag) != MT_OK) {
            mt_cli_error("archive", "rm: %s", diag.message);
            code = MT_CLI_EXIT_READ;
        } else {
            printf("removed mesh %s version %u\n", id, versions[i]);
        }
    }
    free(versions);
    mt_archive_close(archive);
    return mt_cli_finish_output("archive", code, MT_CLI_EXIT_READ);
}
