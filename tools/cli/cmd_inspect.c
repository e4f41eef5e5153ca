/* `meshtopo inspect FILE`: read a mesh file (OFF, OBJ, PLY, gzip too), build
 * the half-edge mesh and print its topology report, readable or as JSON with
 * the corpus reference answers' keys, plus queried one-rings and face
 * neighbours. Exit codes as in `meshtopo --help`. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "inspect.h"

/* Most ids one --vertices/--faces list may expand to. */
#define MAX_QUERY_IDS ((size_t)1 << 24)

static const cli_option options[] = {
    {"json", NULL, "print one JSON object with the keys of the corpus answers (DEFINITIONS.md)"},
    {"json-defects", NULL, "with --json (implied): add a \"defects\" array listing every defect"},
    {"vertices", "LIST", "query these vertices (e.g. 0,78,100-110), in this order"},
    {"faces", "LIST", "query these faces (e.g. 0,158), in this order"},
    {"self-intersections", NULL,
     "also check the geometry: faces passing through each other (exact), self-crossing and "
     "warped faces, self-crossing boundary loops"},
    {"strict", NULL, "refuse any defect: the build fails (exit 4) and names the first one"},
    {"fail-on-defect", NULL, "exit 1 after printing when the report lists any defect"},
    {"format", "NAME",
     "file format: auto (default), off, obj, ply-ascii, ply-le, ply-be, stl-ascii, stl-binary"},
    {"weld", "MODE",
     "merge vertices before building: exact (identical coordinates) or EPS (within distance "
     "EPS, e.g. 1e-6)"},
    {"blocks", "SIZE",
     "split FILE into blocks on a grid of cell size SIZE (by face centroid, seam vertices "
     "duplicated per block, as a TSDF mapper sends them), put them one by one into a block "
     "map that welds exactly, and print the map's report (the keys of --weld exact)"},
    {"limit", "N", "items per list in the readable output (default 5, 0 = all)"},
    {"max-input-bytes", "N",
     "refuse FILE past N bytes inflated (e.g. 512M; default $" CLI_ENV_MAX_INPUT_BYTES " or 16G)"},
};

/* --max-input-bytes, else $MESHTOPO_MAX_INPUT_BYTES, else 0 (the library's
 * default). Returns false after printing the problem. */
static bool parse_max_input(const cli_args *args, uint64_t *out)
{
    *out = 0;
    const char *text = cli_arg(args, "max-input-bytes");
    const char *what = "--max-input-bytes";
    if (!text) {
        text = getenv(CLI_ENV_MAX_INPUT_BYTES);
        what = "$" CLI_ENV_MAX_INPUT_BYTES;
        if (!text || !text[0]) return true;
    }
    if (cli_byte_count_parse(text, out)) return true;
    cli_error("inspect", "%s: expected a byte count such as 1048576 or 512M, got '%s'", what, text);
    return false;
}

static bool parse_limit(const char *text, size_t *out)
{
    if (!text[0]) return false;
    char *end = NULL;
    unsigned long long v = strtoull(text, &end, 10);
    if (*end != '\0' || text[0] == '-' || v > SIZE_MAX) return false;
    *out = (size_t)v;
    return true;
}

/* A --blocks size: a whole number text, finite and above 0. */
static bool parse_block_size(const char *text, double *out)
{
    if (!text[0]) return false;
    char *end = NULL;
    const double v = strtod(text, &end);
    if (*end != '\0' || !(v > 0) || !isfinite(v)) return false;
    *out = v;
    return true;
}

static bool parse_ids(const char *option, const char *text, uint32_t limit, mt_id_list *out)
{
    char err[160];
    if (mt_id_list_parse(text, limit, MAX_QUERY_IDS, out, err, sizeof err)) return true;
    cli_error("inspect", "--%s: %s", option, err);
    return false;
}

static int run_inspect(const cli_args *args)
{
    const char *path = args->positionals[0];
    bool json = cli_flag(args, "json") || cli_flag(args, "json-defects");
    size_t limit = 5;
    const char *limit_text = cli_arg(args, "limit");
    if (limit_text && !parse_limit(limit_text, &limit)) {
        cli_error("inspect", "--limit: expected a count, got '%s'", limit_text);
        return CLI_EXIT_USAGE;
    }

    uint64_t max_input;
    if (!parse_max_input(args, &max_input)) return CLI_EXIT_USAGE;

    double block_size = 0;
    const char *blocks_text = cli_arg(args, "blocks");
    if (blocks_text && !parse_block_size(blocks_text, &block_size)) {
        cli_error("inspect",
                  "--blocks: expected a block size, a finite number above 0 such as 0.5, "
                  "got '%s'",
                  blocks_text);
        return CLI_EXIT_USAGE;
    }
    if (blocks_text && (cli_arg(args, "weld") || cli_flag(args, "strict"))) {
        cli_error("inspect",
                  "--blocks welds exactly and builds leniently: it takes neither "
                  "--weld nor --strict");
        return CLI_EXIT_USAGE;
    }

    double weld_eps = 0;
    const char *weld_text = cli_arg(args, "weld");
    if (weld_text && !cli_weld_parse(weld_text, &weld_eps)) {
        cli_error("inspect",
                  "--weld: expected 'exact' or a positive distance such as 1e-6, "
                  "got '%s'",
                  weld_text);
        return CLI_EXIT_USAGE;
    }

    mt_build_options build;
    memset(&build, 0, sizeof build);
    build.strict = cli_flag(args, "strict");
    cli_mesh mesh;
    /* --blocks: the map keeps counts only so far; the rest of the report
     * comes from a build of its union, checked against the map's counts. */
    int code = blocks_text ? inspect_blocks_load(path, cli_arg(args, "format"), max_input,
                                                 block_size, &mesh)
                           : cli_mesh_load("inspect", path, cli_arg(args, "format"), max_input,
                                           weld_text ? &weld_eps : NULL, &build, false, &mesh);
    if (code != CLI_EXIT_OK) return code;

    inspect_request req;
    memset(&req, 0, sizeof req);
    req.path = path;
    req.mesh = &mesh;
    req.json_defects = cli_flag(args, "json-defects");
    req.limit = limit;
    inspect_geometry geometry = {0};
    if (cli_flag(args, "self-intersections")) {
        mt_diag diag;
        mt_status st = inspect_geometry_compute(mesh.mesh, &geometry, &diag);
        if (st != MT_OK) {
            cli_error("inspect", "--self-intersections: %s", diag.message);
            cli_mesh_free(&mesh);
            return CLI_EXIT_BUILD;
        }
        req.geometry = &geometry;
    }
    const char *verts_text = cli_arg(args, "vertices");
    const char *faces_text = cli_arg(args, "faces");
    if ((verts_text &&
         !parse_ids("vertices", verts_text, mt_mesh_num_verts(mesh.mesh), &req.vertices)) ||
        (faces_text && !parse_ids("faces", faces_text, mt_mesh_num_faces(mesh.mesh), &req.faces))) {
        code = CLI_EXIT_USAGE;
    } else if (json) {
        /* Elements not named on the command line are chosen as the corpus answers choose them. */
        mt_status st =
            inspect_default_queries(mesh.mesh, !verts_text, &req.vertices, !faces_text, &req.faces);
        if (st != MT_OK) {
            cli_error("inspect", "choosing the queried elements failed: %s", mt_strerror(st));
            code = CLI_EXIT_BUILD;
        } else {
            code = inspect_print_json(&req, stdout);
        }
    } else {
        code = inspect_print_text(&req, stdout);
    }
    if (code == CLI_EXIT_OK && cli_flag(args, "fail-on-defect") &&
        (mt_mesh_report(mesh.mesh)->num_defects > 0 || inspect_geometry_findings(&geometry) > 0))
        code = CLI_EXIT_DEFECT;
    code = cli_finish_output("inspect", code, CLI_EXIT_BUILD);
    mt_id_list_free(&req.vertices);
    mt_id_list_free(&req.faces);
    inspect_geometry_free(&geometry);
    cli_mesh_free(&mesh);
    return code;
}

const cli_command cli_cmd_inspect = {
    .name = "inspect",
    .summary = "read a mesh file, build it and print its topology report",
    .synopsis =
        "FILE [--json] [--self-intersections] [--vertices LIST] [--faces LIST] "
        "[--weld exact|EPS] [--blocks SIZE] [--strict] [--fail-on-defect]",
    .description =
        "Reads FILE (OFF, OBJ, PLY or STL, gzip-compressed too; the format is detected from\n"
        "the content; - reads standard input), builds the half-edge mesh and prints counts,\n"
        "boundary loops, components, Euler characteristic, genus, the closed/manifold/\n"
        "orientable flags and every defect with the ids of the elements involved. Nothing\n"
        "is welded or dropped silently.\n"
        "FILE is parsed as it is read and inflated, so memory follows the mesh, not the\n"
        "file: data past what an OFF or PLY header declares is refused, and so is a FILE\n"
        "longer than --max-input-bytes once inflated.\n"
        "\n"
        "--vertices prints each vertex's one-ring fan by fan; --faces prints each face's\n"
        "neighbours edge by edge. With --json the output is one JSON object with the keys\n"
        "of the corpus reference answers (tests/corpus/DEFINITIONS.md); vertices and faces\n"
        "not named with --vertices/--faces are then chosen as DEFINITIONS.md \"Queries\"\n"
        "says. A queried face that was left out of the mesh has \"adjacent_faces\": null.\n"
        "\n"
        "An STL file gives a soup (3 new vertices per triangle). --weld merges vertices\n"
        "before the build, in any format: `exact` those with identical coordinates, EPS those\n"
        "within distance EPS of an earlier kept vertex (ids then refer to the welded mesh).\n"
        "The report adds how many vertices were merged and the vertices the weld made\n"
        "non-manifold: non-manifold in the welded mesh, while no vertex merged into them was\n"
        "in the unwelded one (JSON key \"weld\").\n"
        "\n"
        "--blocks SIZE builds the mesh as a robot's mapper would send it: FILE is split into\n"
        "blocks on a grid of cell size SIZE by face centroid (seam vertices duplicated per\n"
        "block; faces without a finite centroid in one block of their own; unreferenced\n"
        "vertices in the block of their cell), the blocks are put one by one into a block\n"
        "map (meshtopo/map.h) welding exactly, and the map's report is printed with the\n"
        "keys of --weld exact (\"weld\" counts the blocks' vertices as the ones before the\n"
        "weld); ids are the map's. The map keeps its counts incrementally but not yet loops,\n"
        "components or defect ids, so the full report comes from a build of the map's\n"
        "welded union; the command checks that the map's counts equal that build's and\n"
        "fails (exit 4) if they do not.\n"
        "\n"
        "--self-intersections adds the geometric checks: pairs of faces that pass through\n"
        "or touch each other other than at the vertices and edges they share (exact\n"
        "arithmetic, polygons by their triangulation), faces whose sides cross in their\n"
        "plane or whose corners leave it (warped), and boundary loops that cross\n"
        "themselves. --fail-on-defect counts what they find.\n"
        "\n"
        "exit codes: 0 report printed (whatever its defects), 1 --fail-on-defect and a\n"
        "defect was found, 2 usage error (also an id out of range), 3 FILE could not be\n"
        "read or parsed, 4 the mesh could not be built (e.g. --strict refused it, or\n"
        "--blocks found the map's counts differ from a full build).\n",
    .options = options,
    .num_options = sizeof options / sizeof options[0],
    .min_positionals = 1,
    .max_positionals = 1,
    .run = run_inspect,
};
