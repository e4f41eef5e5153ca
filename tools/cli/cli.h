/* The meshtopo command-line tool's shared pieces: the command table entry,
 * parsed arguments, exit codes, id lists and mesh loading. Every subcommand
 * is one cli_command defined in its own cmd_*.c and listed in main.c.
 * These names belong to the tool, not to the library API. */
#ifndef MESHTOPO_CLI_H
#define MESHTOPO_CLI_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "meshtopo/args.h"
#include "meshtopo/face_list.h"
#include "meshtopo/mesh.h"

/* Exit codes shared by every subcommand (documented in `meshtopo --help`). */
enum {
    CLI_EXIT_OK =
        0, /* success: the command did its job (a report is printed whatever its defects) */
    CLI_EXIT_DEFECT = 1,  /* --fail-on-defect and the report lists a defect */
    CLI_EXIT_USAGE = 2,   /* bad command line */
    CLI_EXIT_READ = 3,    /* a file could not be read or parsed */
    CLI_EXIT_BUILD = 4,   /* the mesh could not be built (strict mode refused it, too large, ...) */
    CLI_EXIT_REFUSED = 5, /* meshtopod answered with an error (unknown mesh, refused defect) */
    CLI_EXIT_NO_ANSWER = 6, /* no answer from meshtopod (timeout) or LCM could not be used */
    CLI_EXIT_MISSING = 7    /* a part of meshtopo could not be loaded (broken installation) */
};

/* One option of a command: `--name` (a flag) or `--name VALUE` / `--name=VALUE`
 * (meshtopo/args.h: name, value_name NULL for a flag, one line of help). */
typedef mt__option cli_option;

/* A command line after parsing against a command's options: values[i] is the
 * value of options[i] ("" for a flag that was given), NULL when absent. */
typedef struct cli_args {
    const char *command;
    const cli_option *options;
    size_t num_options;
    const char **values; /* [num_options] */
    char **positionals;  /* the non-option arguments, in order */
    size_t num_positionals;
} cli_args;

typedef struct cli_command {
    const char *name;        /* "inspect" */
    const char *summary;     /* one line for the command list */
    const char *synopsis;    /* after "meshtopo NAME ": "FILE [options]" */
    const char *description; /* paragraphs shown by `meshtopo help NAME` */
    const cli_option *options;
    size_t num_options;
    size_t min_positionals, max_positionals;
    int (*run)(const cli_args *args); /* returns an exit code */
    /* Set instead of `run` by a command that parses its own arguments (bench
     * hands them to another program): gets those after the command name. */
    int (*run_raw)(int argc, char **argv);
} cli_command;

/* The commands, each defined in its cmd_*.c; archive, replay and render in
 * the archive module (cli_module.c). */
extern const cli_command cli_cmd_inspect;
extern const cli_command cli_cmd_send;
extern const cli_command cli_cmd_query;
extern const cli_command cli_cmd_list;
extern const cli_command cli_cmd_watch;
extern const cli_command cli_cmd_spy;
extern const cli_command cli_cmd_bench;
extern const cli_command cli_cmd_archive;
extern const cli_command cli_cmd_replay;
extern const cli_command cli_cmd_render;

/* `relative` resolved from the directory of this program (/proc/self/exe)
 * into out; false without /proc or when it does not fit. */
bool cli_beside_program(const char *relative, char *out, size_t size);

/* The commands of the archive module: how many, and the name of the i-th. */
size_t cli_module_count(void);
const char *cli_module_name(size_t i);
/* The command `name` of the archive module, which is loaded the first time;
 * NULL with err filled when it cannot be loaded or has no such command. */
const cli_command *cli_module_command(const char *name, char *err, size_t err_size);

/* Parses argv[0..argc) (the arguments after the command name) against the
 * command's options into *out (arrays malloc'ed; free with cli_args_free).
 * Sets *out_help when --help or -h is given. Returns CLI_EXIT_OK, or
 * CLI_EXIT_USAGE after printing the problem to stderr. */
int cli_args_parse(const cli_command *cmd, int argc, char **argv, cli_args *out, bool *out_help);
void cli_args_free(cli_args *args);

/* Value of the option named `name` (NULL when absent, "" for a given flag). */
const char *cli_arg(const cli_args *args, const char *name);
bool cli_flag(const cli_args *args, const char *name);

/* Prints a command's full help (synopsis, description, options). */
void cli_print_command_help(const cli_command *cmd, FILE *out);

/* Prints "meshtopo CMD: " and the message to stderr, with a newline. */
void cli_error(const char *command, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Flushes stdout at the end of a command. When that fails and the command
 * had succeeded so far, reports it and returns failure_code; otherwise
 * returns code unchanged. */
int cli_finish_output(const char *command, int code, int failure_code);

/* An ordered list of element ids as given on the command line. */
typedef struct mt_id_list {
    uint32_t *ids;
    size_t count;
} mt_id_list;

/* Parses "0,78,157" or ranges "10-20" (inclusive), separated by commas, into
 * *out (malloc'ed; free with mt_id_list_free). Order and repeats are kept;
 * an empty string gives an empty list. Each id must be below `limit`; at
 * most `max_count` ids in all. On error writes a one-line reason into err
 * and returns false, leaving *out empty. */
bool mt_id_list_parse(const char *text, uint32_t limit, size_t max_count, mt_id_list *out,
                      char *err, size_t err_size);
void mt_id_list_free(mt_id_list *list);

/* What `--weld` did to a mesh file before it was built (mt_face_list_weld). */
typedef struct cli_weld {
    bool enabled;
    double eps; /* 0: exact */
    uint32_t vertices_before, vertices_after, merged;
    /* Vertices (welded ids, ascending) that are non-manifold in the welded
     * mesh although no vertex merged into them was in the unwelded one:
     * those the weld made non-manifold. malloc'd. */
    uint32_t *nonmanifold;
    size_t num_nonmanifold;
    /* inspect --blocks: the blocks the file was split into (0 otherwise),
     * their size, and vertices_before counts the blocks' vertices. */
    size_t blocks;
    double block_size;
} cli_weld;

/* Parses a --weld value: "exact" (eps 0) or a positive finite distance. */
bool cli_weld_parse(const char *text, double *out_eps);

/* A mesh file read (welded with --weld) and built, with the timings. */
typedef struct cli_mesh {
    mt_face_list list;
    mt_mesh *mesh;
    double read_ms, build_ms;
    cli_weld weld;
} cli_mesh;

/* Reads `path` (format auto-detected unless `format_name` names one) into
 * *out_list without building it. Returns CLI_EXIT_OK, CLI_EXIT_USAGE
 * (unknown format name) or CLI_EXIT_READ after printing the reason, naming
 * the file, to stderr; *out_list is then empty. */
int cli_face_list_read(const char *command, const char *path, const char *format_name,
                       mt_face_list *out_list);
/* The same with an input limit after gzip inflation (0: the library's
 * default), as --max-input-bytes sets it. */
int cli_face_list_read_bounded(const char *command, const char *path, const char *format_name,
                               uint64_t max_input_bytes, mt_face_list *out_list);

/* Reads `path` (format auto-detected unless `format_name` names one) and
 * builds it. max_input_bytes: the largest input read, after gzip inflation
 * (0: the library's default; set by --max-input-bytes). weld_eps (NULL: no
 * weld): the vertices are welded before the build (0: exact), and the
 * unwelded list is built first, without options, to tell which vertices
 * the weld made non-manifold (out->weld). Returns CLI_EXIT_OK,
 * CLI_EXIT_USAGE (unknown format name), CLI_EXIT_READ or
 * CLI_EXIT_BUILD after printing the reason, naming the file, to stderr.
 * Unless keep_positions, the mesh takes the positions of out->list
 * (mt_mesh_build_taking_positions) rather than a copy: out->list then holds
 * the faces only. */
int cli_mesh_load(const char *command, const char *path, const char *format_name,
                  uint64_t max_input_bytes, const double *weld_eps, const mt_build_options *options,
                  bool keep_positions, cli_mesh *out);
void cli_mesh_free(cli_mesh *m);

/* Environment variable giving the default of --max-input-bytes. */
#define CLI_ENV_MAX_INPUT_BYTES "MESHTOPO_MAX_INPUT_BYTES"

/* Parses a byte count of at least 1: decimal digits, optionally followed
 * by K, M, G or T (any case; powers of 1024). */
bool cli_byte_count_parse(const char *text, uint64_t *out);

/* Milliseconds on a monotonic clock. */
double cli_now_ms(void);

/* The last path component ("dir/a.off.gz" -> "a.off.gz"). */
const char *cli_basename(const char *path);

#endif
