/* Reading a mesh file and building it, for every command that takes a
 * FILE: maps the library's failures onto the CLI exit codes (3 read/parse,
 * 4 build), makes sure every message names the file, reads the byte
 * counts of input limits (--max-input-bytes), and welds (--weld) with the
 * report of the vertices the weld made non-manifold. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "meshtopo/io.h"
#include "meshtopo/report.h"

double cli_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

const char *cli_basename(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

static bool format_parse(const char *name, mt_format *out)
{
    static const mt_format formats[] = {MT_FORMAT_AUTO,          MT_FORMAT_OFF,
                                        MT_FORMAT_OBJ,           MT_FORMAT_PLY_ASCII,
                                        MT_FORMAT_PLY_BINARY_LE, MT_FORMAT_PLY_BINARY_BE,
                                        MT_FORMAT_STL_ASCII,     MT_FORMAT_STL_BINARY};
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

/* cli_face_list_read with an input limit (0: the library's default);
 * `limit_option` names the option that sets it, for the message of an
 * input over the limit (NULL: none). */
static int face_list_read(const char *command, const char *path, const char *format_name,
                          uint64_t max_input_bytes, const char *limit_option,
                          mt_face_list *out_list)
{
    memset(out_list, 0, sizeof *out_list);
    mt_format format = MT_FORMAT_AUTO;
    if (format_name && !format_parse(format_name, &format)) {
        cli_error(command,
                  "unknown format '%s' (auto, off, obj, ply-ascii, ply-le, ply-be, "
                  "stl-ascii, stl-binary)",
                  format_name);
        return CLI_EXIT_USAGE;
    }
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_read_options options;
    memset(&options, 0, sizeof options);
    options.max_input_bytes = max_input_bytes;
    /* "-" is standard input (a pipe: read once, bounded by the limit). */
    const bool from_stdin = strcmp(path, "-") == 0;
    mt_status st = from_stdin ? mt_read_fd_with(STDIN_FILENO, "standard input", format, &options,
                                                out_list, &diag)
                              : mt_read_file_with(path, format, &options, out_list, &diag);
    if (st != MT_OK) {
        const char *text = diag_text(&diag, st);
        char hint[64] = "";
        if (st == MT_ERR_TOO_LARGE && limit_option && strstr(text, "input limit"))
            snprintf(hint, sizeof hint, " (%s raises it)", limit_option);
        if (strstr(text, from_stdin ? "standard input" : path))
            cli_error(command, "%s%s", text, hint);
        else
            cli_error(command, "cannot read %s: %s%s", path, text, hint);
        return CLI_EXIT_READ;
    }
    return CLI_EXIT_OK;
}

int cli_face_list_read(const char *command, const char *path, const char *format_name,
                       mt_face_list *out_list)
{
    return face_list_read(command, path, format_name, 0, NULL, out_list);
}

int cli_face_list_read_bounded(const char *command, const char *path, const char *format_name,
                               uint64_t max_input_bytes, mt_face_list *out_list)
{
    return face_list_read(command, path, format_name, max_input_bytes, "--max-input-bytes",
                          out_list);
}

bool cli_byte_count_parse(const char *text, uint64_t *out)
{
    uint64_t v = 0;
    const char *p = text;
    if (*p < '0' || *p > '9') return false;
    for (; *p >= '0' && *p <= '9'; p++) {
        if (v > (UINT64_MAX - (uint64_t)(*p - '0')) / 10) return false;
        v = v * 10 + (uint64_t)(*p - '0');
    }
    static const char units[] = "KMGT";
    const char *unit = *p ? strchr(units, *p >= 'a' ? *p - 'a' + 'A' : *p) : NULL;
    if (*p && (!unit || p[1] != '\0')) return false;
    for (int k = unit ? (int)(unit - units) + 1 : 0; k > 0; k--) {
        if (v > UINT64_MAX / 1024) return false;
        v *= 1024;
    }
    if (v == 0) return false;
    *out = v;
    return true;
}

bool cli_weld_parse(const char *text, double *out_eps)
{
    if (strcmp(text, "exact") == 0) {
        *out_eps = 0;
        return true;
    }
    if (!text[0]) return false;
    char *end = NULL;
    double eps = strtod(text, &end);
    if (*end != '\0' || !(eps > 0) || !isfinite(eps)) return false;
    *out_eps = eps;
    return true;
}

/* Marks the vertices with a non-manifold-vertex defect in `flags`
 * (num_verts entries): bit `bit` set. */
static void mark_nonmanifold(const mt_mesh *mesh, unsigned char *flags, uint32_t num_verts,
                             unsigned char bit)
{
    const mt_report *r = mt_mesh_report(mesh);
    for (size_t i = 0; i < r->num_defects; i++) {
        const mt_defect *d = &r->defects[i];
        if (d->kind == MT_DEFECT_NONMANIFOLD_VERTEX && d->a < num_verts) flags[d->a] |= bit;
    }
}

/* Welds out->list in place: builds the unwelded list first, welds, keeps
 * the counts in out->weld and sets *out_was (malloc'd, one byte per welded
 * vertex) to 2 where a vertex merged into it was non-manifold unwelded:
 * that is no news. The welded mesh is built by the caller (weld_news). */
static int weld_list(const char *command, const char *path, double eps, cli_mesh *out,
                     unsigned char **out_was)
{
    cli_weld *w = &out->weld;
    w->enabled = true;
    w->eps = eps;
    uint32_t n = out->list.num_verts;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_build_options plain;
    memset(&plain, 0, sizeof plain);
    mt_mesh *before = NULL;
    mt_status st = mt_mesh_build(&out->list, &plain, &before, &diag);
    if (st != MT_OK) {
        cli_error(command, "cannot build the unwelded mesh from %s: %s", path,
                  diag_text(&diag, st));
        return CLI_EXIT_BUILD;
    }
    unsigned char *was = calloc(n ? n : 1, 1);
    uint32_t *map = malloc((n ? n : 1) * sizeof(uint32_t));
    if (!was || !map) {
        mt_mesh_destroy(before);
        free(was);
        free(map);
        cli_error(command, "out of memory welding %s", path);
        return CLI_EXIT_BUILD;
    }
    mark_nonmanifold(before, was, n, 1);
    mt_mesh_destroy(before);
    mt_weld_stats stats;
    st = mt_face_list_weld(&out->list, eps, map, &stats, &diag);
    if (st != MT_OK) {
        free(was);
        free(map);
        cli_error(command, "cannot weld %s: %s", path, diag_text(&diag, st));
        return CLI_EXIT_BUILD;
    }
    w->vertices_before = stats.vertices_before;
    w->vertices_after = stats.vertices_after;
    w->merged = stats.merged;
    /* was[new id] bit 2: some vertex merged into it was non-manifold before */
    for (uint32_t v = 0; v < n; v++)
        if (was[v] & 1) was[map[v]] |= 2;
    for (uint32_t v = 0; v < stats.vertices_after; v++) was[v] = (unsigned char)(was[v] & 2);
    free(map);
    *out_was = was;
    return CLI_EXIT_OK;
}

/* The welded mesh's non-manifold vertices that were not before (`was`, as
 * weld_list left it); frees `was`. */
static bool weld_news(cli_mesh *out, unsigned char *was)
{
    uint32_t n = out->weld.vertices_after;
    mark_nonmanifold(out->mesh, was, n, 1);
    size_t count = 0;
    for (uint32_t v = 0; v < n; v++) count += was[v] == 1;
    uint32_t *ids = malloc((count ? count : 1) * sizeof(uint32_t));
    if (!ids) {
        free(was);
        return false;
    }
    count = 0;
    for (uint32_t v = 0; v < n; v++)
        if (was[v] == 1) ids[count++] = v;
    free(was);
    out->weld.nonmanifold = ids;
    out->weld.num_nonmanifold = count;
    return true;
}

int cli_mesh_load(const char *command, const char *path, const char *format_name,
                  uint64_t max_input_bytes, const double *weld_eps, const mt_build_options *options,
                  bool keep_positions, cli_mesh *out)
{
    memset(out, 0, sizeof *out);
    double t0 = cli_now_ms();
    int code = face_list_read(command, path, format_name, max_input_bytes, "--max-input-bytes",
                              &out->list);
    out->read_ms = cli_now_ms() - t0;
    if (code != CLI_EXIT_OK) return code;
    unsigned char *was = NULL;
    if (weld_eps) {
        code = weld_list(command, path, *weld_eps, out, &was);
        if (code != CLI_EXIT_OK) {
            mt_face_list_free(&out->list);
            return code;
        }
    }

    mt_diag diag;
    mt_diag_clear(&diag);
    t0 = cli_now_ms();
    mt_status st = keep_positions
                       ? mt_mesh_build(&out->list, options, &out->mesh, &diag)
                       : mt_mesh_build_taking_positions(&out->list, options, &out->mesh, &diag);
    out->build_ms = cli_now_ms() - t0;
    if (st != MT_OK) {
        cli_error(command, "cannot build a mesh from %s%s: %s", weld_eps ? "the welded " : "", path,
                  diag_text(&diag, st));
        out->mesh = NULL;
        free(was);
        mt_face_list_free(&out->list);
        return CLI_EXIT_BUILD;
    }
    if (was && !weld_news(out, was)) {
        cli_error(command, "out of memory welding %s", path);
        cli_mesh_free(out);
        return CLI_EXIT_BUILD;
    }
    return CLI_EXIT_OK;
}

void cli_mesh_free(cli_mesh *m)
{
    mt_mesh_destroy(m->mesh);
    m->mesh = NULL;
    mt_face_list_free(&m->list);
    free(m->weld.nonmanifold);
    memset(&m->weld, 0, sizeof m->weld);
}
