/* `meshtopo render FILE|ARCHIVE-FILE --out PNG [--view V] [--size WxH]`:
 * a picture of a mesh with its defects marked. The mesh is built here (a
 * mesh file) or loaded with the archive's checks (an archive file, by its
 * .hdf or .vtkhdf name), archived alone into a temporary directory with
 * its topology arrays and self-intersections, and drawn from that file by
 * tools/vtk/render.py with VTK's offscreen rendering (vtk_script.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/archive.h"
#include "temp_archive.h"
#include "vtk_script.h"

static const cli_option options[] = {
    {"out", "PNG", "the picture to write (required)"},
    {"view", "VIEW", "iso (default), front, back, left, right, top or bottom; +Y is up"},
    {"size", "WxH", "the picture's size in pixels (default 800x600; 16 to 8192 a side)"},
    {"no-self-intersections", NULL, "do not look for faces passing through each other"},
    {"weld", "exact|EPS", "a mesh file: merge vertices closer than EPS (or identical) first"},
};

static const char *const views[] = {"iso", "front", "back", "left", "right", "top", "bottom"};

static bool size_parse(const char *text, unsigned *w, unsigned *h)
{
    char *end = NULL;
    unsigned long a = text[0] >= '0' && text[0] <= '9' ? strtoul(text, &end, 10) : 0;
    if (!end || (*end != 'x' && *end != 'X') || end[1] < '0' || end[1] > '9') return false;
    unsigned long b = strtoul(end + 1, &end, 10);
    if (*end != '\0' || a < 16 || a > 8192 || b < 16 || b > 8192) return false;
    *w = (unsigned)a;
    *h = (unsigned)b;
    return true;
}

/* The mesh of an archive file: its directory opened read-only, the file
 * loaded and checked as meshtopod loads it. */
static int load_archive_file(const char *path, mt_archive_record *rec, mt_mesh **mesh)
{
    char dir[4096];
    const char *name = cli_basename(path);
    int n = name == path ? snprintf(dir, sizeof dir, ".")
                         : snprintf(dir, sizeof dir, "%.*s", (int)(name - path), path);
    if (n < 0 || (size_t)n >= sizeof dir) {
        cli_error("render", "%s: name too long", path);
        return CLI_EXIT_USAGE;
    }
    mt_archive *archive = NULL;
    mt_archive_options open_options = {.read_only = true};
    mt_diag diag;
    mt_status st = mt_archive_open(dir, &open_options, &archive, &diag);
    if (st == MT_OK) {
        mt_archive_set_content_hash(archive, mt_archive_content_hash, NULL);
        st = mt_archive_load_mesh_file(archive, name, true, rec, mesh, NULL, &diag);
    }
    mt_archive_close(archive);
    if (st != MT_OK) {
        cli_error("render", "%s", diag.message);
        return CLI_EXIT_READ;
    }
    return CLI_EXIT_OK;
}

static int run_render(const cli_args *args)
{
    const char *path = args->positionals[0];
    const char *out = cli_arg(args, "out"), *view = cli_arg(args, "view");
    const char *size = cli_arg(args, "size"), *weld = cli_arg(args, "weld");
    if (!out || !out[0]) {
        cli_error("render", "--out PNG is required");
        return CLI_EXIT_USAGE;
    }
    if (!view) view = "iso";
    bool view_known = false;
    for (size_t i = 0; i < sizeof views / sizeof views[0]; i++)
        view_known = view_known || strcmp(views[i], view) == 0;
    if (!view_known) {
        cli_error("render",
                  "--view: '%s' is not one of iso, front, back, left, right, top, "
                  "bottom",
                  view);
        return CLI_EXIT_USAGE;
    }
    unsigned width = 800, height = 600;
    if (size && !size_parse(size, &width, &height)) {
        cli_error("render", "--size: expected WxH, each 16 to 8192 (800x600), got '%s'", size);
        return CLI_EXIT_USAGE;
    }
    double eps = 0;
    const bool archived = cli_is_archive_path(path);
    if (weld && (archived || !cli_weld_parse(weld, &eps))) {
        cli_error("render",
                  archived ? "--weld applies to mesh files, not archive files"
                           : "--weld: expected 'exact' or a positive distance, got '%s'",
                  weld);
        return CLI_EXIT_USAGE;
    }

    cli_mesh loaded;
    memset(&loaded, 0, sizeof loaded);
    mt_archive_record rec;
    memset(&rec, 0, sizeof rec);
    mt_mesh *mesh = NULL;
    const mt_face_list *list = NULL;
    int code;
    if (archived) {
        code = load_archive_file(path, &rec, &mesh);
        list = &rec.faces;
    } else {
        code = cli_mesh_load("render", path, NULL, 0, weld ? &eps : NULL, NULL, true, &loaded);
        mesh = loaded.mesh;
        list = &loaded.list;
    }
    cli_temp_archive temp;
    memset(&temp, 0, sizeof temp);
    if (code == CLI_EXIT_OK)
        code = cli_temp_archive_write("render", list, mesh, NULL,
                                      !cli_flag(args, "no-self-intersections"), &temp);
    if (archived) {
        mt_mesh_destroy(mesh);
        mt_archive_record_free(&rec);
    } else {
        cli_mesh_free(&loaded);
    }
    if (code != CLI_EXIT_OK) return code;

    char size_text[32];
    snprintf(size_text, sizeof size_text, "%ux%u", width, height);
    const char *script_args[] = {"--out",   out,       "--view",           view,      "--size",
                                 size_text, "--title", cli_basename(path), temp.path, NULL};
    code = cli_vtk_script_run("render", "render.py", script_args);
    cli_temp_archive_remove(&temp);
    if (code == CLI_EXIT_OK)
        printf("rendered %s to %s (%s, %s view)\n", path, out, size_text, view);
    return cli_finish_output("render", code, CLI_EXIT_READ);
}

const cli_command cli_cmd_render = {
    .name = "render",
    .summary = "draw a mesh with its defects marked into a PNG (VTK, offscreen)",
    .synopsis = "FILE|ARCHIVE-FILE --out PNG [--view VIEW] [--size WxH] [options]",
    .description =
        "Draws a mesh file (OFF, OBJ, PLY, STL, .gz too) or an archive file (a name ending\n"
        "in .hdf or .vtkhdf; loaded with the checks meshtopod makes) on a grey surface with\n"
        "its defects marked in fixed colours:\n"
        "  red lines        boundary edges (used by one face)\n"
        "  magenta lines    non-manifold edges (used by three or more faces)\n"
        "  magenta points   non-manifold vertices\n"
        "  orange points    corners of rejected faces (out-of-range index, degenerate)\n"
        "  yellow faces     self-intersecting faces\n"
        "  blue faces       faces oriented against a neighbour\n"
        "and a legend with the counts. Drawn with VTK's offscreen rendering by render.py\n"
        "(share/meshtopo) under Debian's /usr/bin/python3 with python3-vtk9; without a\n"
        "display (DISPLAY unset) it runs its own Xvfb (Debian: xvfb), as VTK 9.1 renders\n"
        "through X. $MESHTOPO_PYTHON and $MESHTOPO_VTK_SCRIPTS choose another python or\n"
        "script directory.\n"
        "\n"
        "exit codes: 0 written, 2 usage error, 3 the input could not be read, or python3,\n"
        "python3-vtk9 or Xvfb is missing, or the picture could not be written (the\n"
        "message says which), 4 the mesh could not be built.\n",
    .options = options,
    .num_options = sizeof options / sizeof options[0],
    .min_positionals = 1,
    .max_positionals = 1,
    .run = run_render,
};
