/* `meshtopo archive SUBCOMMAND DIR ...`: offline inspection and management
 * of a meshtopod archive directory (one VTKHDF file per mesh version). This
 * file holds the command's table entry, its help and the dispatch to the
 * cmd_archive_*.c subcommands (which share archive_common.c, not this
 * file). */
#include <stdbool.h>
#include <string.h>

#include "cmd_archive.h"

static const cli_option options[] = {
    {"json", NULL, "ls, show, verify: print one JSON object"},
    {"version", "N", "show, export, rm: this version (default: the highest archived)"},
    {"all", NULL, "rm: remove every version of the mesh"},
    {"self-intersections", NULL,
     "export to .ply, .vtu, .hdf, .vtkhdf: find the faces passing through each other"},
};

typedef struct subcommand {
    const char *name;
    size_t min_args, max_args; /* after the subcommand's name */
    int (*run)(const cli_args *args);
    bool json, version, all, self_intersections; /* which options apply */
} subcommand;

static const subcommand subcommands[] = {
    {"ls", 1, 1, cli_archive_ls, true, false, false, false},
    {"show", 2, 2, cli_archive_show, true, true, false, false},
    {"verify", 1, 1, cli_archive_verify, true, false, false, false},
    {"export", 3, 3, cli_archive_export, false, true, false, true},
    {"rm", 2, 2, cli_archive_rm, false, true, true, false},
};

static int run_archive(const cli_args *args)
{
    const char *name = args->positionals[0];
    const subcommand *sub = NULL;
    for (size_t i = 0; i < sizeof subcommands / sizeof subcommands[0]; i++)
        if (strcmp(subcommands[i].name, name) == 0) sub = &subcommands[i];
    if (!sub) {
        cli_error("archive", "unknown subcommand '%s' (ls, show, verify, export, rm)", name);
        return CLI_EXIT_USAGE;
    }
    size_t given = args->num_positionals - 1;
    if (given < sub->min_args || given > sub->max_args) {
        cli_error("archive", "%s takes %zu argument%s, got %zu (see meshtopo help archive)",
                  sub->name, sub->min_args, sub->min_args == 1 ? "" : "s", given);
        return CLI_EXIT_USAGE;
    }
    const char *bad = (!sub->json && cli_flag(args, "json"))        ? "--json"
                      : (!sub->version && cli_arg(args, "version")) ? "--version"
                      : (!sub->all && cli_flag(args, "all"))        ? "--all"
                      : (!sub->self_intersections && cli_flag(args, "self-intersections"))
                          ? "--self-intersections"
                          : NULL;
    if (bad) {
        cli_error("archive", "%s does not apply to '%s'", bad, sub->name);
        return CLI_EXIT_USAGE;
    }
    return sub->run(args);
}

const cli_command cli_cmd_archive = {
    .name = "archive",
    .summary = "list, show, verify, export or remove archived mesh versions (offline)",
    .synopsis =
        "ls|show|verify|export|rm DIR [ID] [OUT] [--version N] [--all] [--json] "
        "[--self-intersections]",
    .description =
        "Works on a meshtopod archive directory without the daemon: one HDF5 file per mesh\n"
        "version, also a VTKHDF file that ParaView and VTK open (NAME.vN.hdf, the mesh id\n"
        "percent-encoded in NAME; files named NAME.vN.vtkhdf by earlier versions are read\n"
        "too).\n"
        "\n"
        "  archive ls DIR [--json]\n"
        "      every archived version: mesh id, version, time, source, file size, vertices,\n"
        "      faces, defects, components, genus; unreadable files are listed with the reason.\n"
        "  archive show DIR ID [--version N] [--json]\n"
        "      one version's provenance and topology report (rebuilt from the stored face\n"
        "      list and checked against the stored report).\n"
        "  archive verify DIR [--json]\n"
        "      checks every file as meshtopod's loads do: a regular file of this user\n"
        "      (links are never followed), shapes and types consistent, name matching its\n"
        "      mesh id and version, content hash matching the face list, stored half-edge\n"
        "      arrays matching their digest (or a rebuild), VTKHDF cells matching the face\n"
        "      list. One line per file; a bad one names its fault: derived (rebuilt on\n"
        "      load), vtk, content (set aside by the daemon), newer, unsafe, system.\n"
        "  archive export DIR ID [--version N] [--self-intersections] OUT\n"
        "      OUT.off, OUT.obj: the face list exactly as submitted (rejected faces too);\n"
        "      OUT.ply: the same with red, green, blue per vertex and per face marking the\n"
        "      defects in the colours of meshtopo render (help render);\n"
        "      OUT.hdf, OUT.vtkhdf: a VTKHDF archive file of the version with this\n"
        "      meshtopo's topology arrays; OUT.vtu: the same as a VTK XML unstructured grid\n"
        "      (written by VTK: Debian's python3-vtk9). --self-intersections adds\n"
        "      CellData/self_intersecting (.ply: yellow faces).\n"
        "  archive rm DIR ID [--version N | --all]\n"
        "      removes one version (default the highest) or every version of ID.\n"
        "\n"
        "ls, show, verify and export open the archive read-only (safe while meshtopod\n"
        "writes to it); rm also removes leftovers of interrupted writes.\n"
        "\n"
        "exit codes: 0 success, 2 usage error, 3 the directory, a file or a version could\n"
        "not be read, found or written (verify: at least one bad file; export: OUT could\n"
        "not be written).\n",
    .options = options,
    .num_options = sizeof options / sizeof options[0],
    .min_positionals = 2,
    .max_positionals = 4,
    .run = run_archive,
};
