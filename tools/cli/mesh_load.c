/* Reading a mesh file and building it, for every command that takes a
 * FILE: maps the library's failures onto the CLI exit codes (3 read/parse,
 * 4 build) and makes sure every message names the file. */
#include <string.h>
#include <time.h>

#include "cli.h"
#include "meshtopo/io.h"

double mt_cli_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

const char *mt_cli_basename(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

static bool format_parse(const char *name, mt_format *out)
{
    static const mt_format formats[] = {MT_FORMAT_AUTO,          MT_FORMAT_OFF,
                                        MT_FORMAT_OBJ,           MT_FORMAT_PLY_ASCII,
                                        MT_FORMAT_PLY_BINARY_LE, MT_FORMAT_PLY_BINARY_BE};
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++) {
        if (strcmp(mt_format_name(formats[i]), name) == 0) {
            *out = formats[i];
            return true;
        }
    }
    return false;
}

/* The diag's message, or the status text when the library left it empty. */
static const char *diag_text(const mt_diag *diag, mt_status status)
{
    return diag->message[0] ? diag->message : mt_strerror(status);
}

int mt_cli_face_list_read(const char *command, const char *path, const char *format_name,
                          mt_face_list *out_list)
{
    memset(out_list, 0, sizeof *out_list);
    mt_format format = MT_FORMAT_AUTO;
    if (format_name && !format_parse(format_name, &format)) {
        mt_cli_error(command, "unknown format '%s' (auto, off, obj, ply-ascii, ply-le, ply-be)",
                     format_name);
        return MT_CLI_EXIT_USAGE;
    }
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_read_file(path, format, out_list, &diag);
    if (st != MT_OK) {
        const char *text = diag_text(&diag, st);
        if (strstr(text, path))
            mt_cli_error(command, "%s", text);
        else
            mt_cli_error(command, "cannot read %s: %s", path, text);
        return MT_CLI_EXIT_READ;
    }
    return MT_CLI_EXIT_OK;
}

int mt_cli_mesh_load(const char *command, const char *path, const char *format_name,
                     const mt_build_options *options, mt_cli_mesh *out)
{
    memset(out, 0, sizeof *out);
    double t0 = mt_cli_now_ms();
    int code = mt_cli_face_list_read(command, path, format_name, &out->list);
    out->read_ms = mt_cli_now_ms() - t0;
    if (code != MT_CLI_EXIT_OK) return code;

    mt_diag diag;
    mt_diag_clear(&diag);
    t0 = mt_cli_now_ms();
    mt_status st = mt_mesh_build(&out->list, options, &out->mesh, &diag);
    out->build_ms = mt_cli_now_ms() - t0;
    if (st != MT_OK) {
        mt_cli_error(command, "cannot build a mesh from %s: %s", path, diag_text(&diag, st));
        out->mesh = NULL;
        mt_face_list_free(&out->list);
        return MT_CLI_EXIT_BUILD;
    }
    return MT_CLI_EXIT_OK;
}

void mt_cli_mesh_free(mt_cli_mesh *m)
{
    mt_mesh_destroy(m->mesh);
    m->mesh = NULL;
    mt_face_list_free(&m->list);
}
