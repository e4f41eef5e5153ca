/* Shared declarations of meshtopo-bench: the benchmark cases (one mesh in one
 * vertex/face order), the runners that measure one library on one case (in
 * process for meshtopo, a child process for each C++ peer), and the result
 * records the tables are printed from. Times are CLOCK_MONOTONIC, heap bytes
 * come from mallinfo2() where glibc has it. */
#ifndef MESHTOPO_BENCH_H
#define MESHTOPO_BENCH_H

#include <limits.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/types.h>
#include <time.h>

#include "meshtopo/args.h"
#include "meshtopo/face_list.h"

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

#define MT__BENCH_MAX_REPS 99
#define MT__BENCH_MAX_CASES 16
#define MT__BENCH_MAX_RUNNERS 9

/* Command-line options (see usage in bench.c). */
typedef struct mt__bench_options {
    bool all;               /* `meshtopo-bench all`: every mesh, files into out_dir */
    uint64_t faces;         /* target triangle count of the grid */
    uint64_t torus_faces;   /* target triangle count of the closed torus (all) */
    uint32_t reps;          /* timed repetitions per library and case */
    bool threads_given;     /* --threads: one meshtopo row, else rows for 1 and 2 threads */
    uint32_t threads;       /* mt_build_options.threads of that row (0 = automatic) */
    uint64_t seed;          /* seed of the permuted copies */
    bool quick;             /* small meshes, few repetitions (smoke test) */
    bool peer_no_reserve;   /* peers time the plain add loop, without reserve() */
    uint32_t idle_ms;       /* this process idles that long before each repetition */
    const char *csv_path;   /* NULL: no CSV (all: out_dir/bench.csv) */
    const char *md_path;    /* NULL: no Markdown (all: out_dir/bench.md) */
    const char *svg_path;   /* NULL: no plot (all: out_dir/build-time.svg) */
    const char *out_dir;    /* all: where the three files go */
    const char *corpus_dir; /* where npm_bunny.off and igl_fertility.off are */
    const char *peer_dir;   /* NULL: look next to the executable */
    const char *tmp_parent; /* NULL: $TMPDIR or /tmp */
    char command[512];      /* the command line, for the Markdown file */
    char machine[256];      /* CPU model, cores, kernel: where it was measured */
} mt__bench_options;

/* One mesh in one order: the face list meshtopo builds from in process and
 * the raw file (bench_input.c) the peers read the same bytes from. */
typedef struct mt__bench_case {
    char mesh[48];  /* "grid 707x707", "npm_bunny" */
    char order[16]; /* "ordered" or "permuted" */
    mt_face_list list;
    char path[PATH_MAX];
} mt__bench_case;

/* Bytes of a face list (positions, face sizes, indices): what a build reads. */
uint64_t mt__bench_case_input_bytes(const mt__bench_case *bench_case);

/* What a library built: counts checked across libraries, and one run's
 * totals of each sweep (elements visited, sum of their ids) as a
 * cross-check. components is MT__BENCH_UNKNOWN when the library does not
 * compute them. */
#define MT__BENCH_UNKNOWN UINT64_MAX
typedef struct mt__bench_topology {
    uint64_t verts, edges, faces, boundary_loops, components;
    uint64_t rejected_faces;            /* faces the library refused or left out */
    uint64_t loop_verts;                /* vertices over all extracted boundary loops */
    uint64_t ring_neighbours, ring_sum; /* one-ring sweep: neighbours, sum of vertex ids */
    uint64_t adj_neighbours, adj_sum;   /* face-adjacency sweep: neighbours, sum of face ids */
} mt__bench_topology;

/* One timed repetition: build, one-ring sweep over every vertex, face
 * adjacency sweep over every face, boundary-loop extraction, connected
 * components (each timed on its own; the mesh is freed untimed). */
typedef struct mt__bench_sample {
    double build_ms, ring_ms, adj_ms, loops_ms, components_ms; /* NAN when not measured */
    mt__bench_topology seen; /* what this repetition's queries found */
    int64_t heap_bytes;      /* heap growth over the build (mallinfo2), -1 if unknown */
} mt__bench_sample;

typedef enum mt__bench_state {
    MT__BENCH_OK,
    MT__BENCH_SKIPPED, /* library not available: not an error */
    MT__BENCH_FAILED
} mt__bench_state;

/* What a runner measures: a library building a mesh, or the memcpy floor
 * (no mesh, no queries: only its time is in build_ms). */
typedef enum mt__bench_kind { MT__BENCH_LIBRARY, MT__BENCH_FLOOR } mt__bench_kind;

/* One library on one case. */
typedef struct mt__bench_result {
    const char *library;
    mt__bench_kind kind;
    bool is_meshtopo;
    uint32_t threads; /* build threads (0 = automatic) */
    const mt__bench_case *bench_case;
    mt__bench_state state;
    char message[512]; /* why it was skipped or failed */
    char version[32];
    mt__bench_topology topology;
    uint64_t structure_bytes; /* meshtopo: mt_mesh_memory_bytes; floors: bytes written */
    uint64_t report_bytes;    /* meshtopo: mt_mesh_report_memory_bytes */
    uint32_t num_samples;
    mt__bench_sample samples[MT__BENCH_MAX_REPS];
} mt__bench_result;

/* A way to measure one library: start loads a case and warms up (filling
 * version and topology in the result), rep runs one timed repetition, stop
 * releases everything. start and rep return false after writing the reason
 * into result->message. The make functions fill everything but exe. */
typedef struct mt__bench_runner mt__bench_runner;
struct mt__bench_runner {
    char library[32]; /* row name: "meshtopo-1t", "OpenMesh", "memcpy-fresh" */
    mt__bench_kind kind;
    bool is_meshtopo;
    uint32_t threads;      /* meshtopo: mt_build_options.threads */
    bool fresh;            /* floor, meshtopo: into freshly allocated memory each repetition */
    const char *peer_flag; /* peer: extra argument ("--soup") or NULL */
    bool (*start)(mt__bench_runner *runner, const mt__bench_case *bench_case,
                  const mt__bench_options *options, mt__bench_result *result);
    bool (*rep)(mt__bench_runner *runner, mt__bench_sample *out, mt__bench_result *result);
    void (*stop)(mt__bench_runner *runner);
    void *state;
    char exe[PATH_MAX]; /* peer executable, empty for in-process runners */
};

/* Entry point of the meshtopo-bench executable (also `meshtopo bench`):
 * `[build] [options]` or `all [options]`. Returns the process exit code. */
int mt__bench_command(int argc, char **argv);

/* bench_args.c: a decimal count in [min, max] (no sign, no suffix); false
 * when text is not one. */
bool mt__bench_parse_u32(const char *text, uint32_t min, uint32_t max, uint32_t *out);
/* The same for 64 bits (NULL text: false). */
bool mt__bench_parse_u64(const char *text, uint64_t min, uint64_t max, uint64_t *out);

/* Reads a subcommand's arguments (argv without the program or subcommand
 * name) against its options. Returns 0 when read, 1 for -h/--help, 2 when
 * refused (the reason printed on stderr, prefixed with `program`; *out is
 * then freed). After 0 or 1, free *out with mt__args_free. */
int mt__bench_args_read(const char *program, const mt__option *options, size_t num_options,
                        int argc, char **argv, mt__args *out);
/* Option `name`'s value as a count in [min, max] into *out when it was
 * given (*given, when not NULL, says whether); false, with a message on
 * stderr naming program, option and value, when it is not such a count. */
bool mt__bench_arg_u64(const mt__args *args, const char *program, const char *name, uint64_t min,
                       uint64_t max, uint64_t *out, bool *given);
bool mt__bench_arg_u32(const mt__args *args, const char *program, const char *name, uint32_t min,
                       uint32_t max, uint32_t *out, bool *given);
/* The exit code after a subcommand's options were not run with (parsed 1:
 * --help, usage on stdout, 0; parsed 2: refused, usage on stderr, 2). */
int mt__bench_usage_exit(int parsed, void (*usage)(FILE *out));

/* bench_stats.c: both sort `values` in place; NaN for n == 0. */
double mt__bench_median_of(double *values, uint32_t n);
double mt__bench_quantile(double *values, uint32_t n, double q); /* nearest rank, q in [0, 1] */

/* bench_stats.c: splitmix64, a fixed, seedable sequence (vertex ids, bytes). */
uint64_t mt__bench_rand_u64(uint64_t *state);

/* bench_clock.c; mt__bench_elapsed_us: microseconds from a to b
 * (CLOCK_MONOTONIC readings). */
double mt__bench_now_ms(void);
void mt__bench_sleep_ms(double ms);
double mt__bench_elapsed_us(const struct timespec *a, const struct timespec *b);
int64_t mt__bench_heap_bytes(void);

/* bench_input.c: the meshes of a run (all: bunny, a closed corpus mesh,
 * the grid and the torus; otherwise the grid), each measured ordered and
 * permuted. A mesh's two cases are made (and their raw files written into
 * dir) just before they run, into cases[0] and cases[1], and released
 * after, so that one mesh's input never sits beside another's. */
uint32_t mt__bench_num_meshes(const mt__bench_options *options);
bool mt__bench_mesh_cases_make(const mt__bench_options *options, const char *dir, uint32_t m,
                               mt__bench_case *cases, char *err, size_t err_size);
/* Removes the raw file of a case (its peers have read it once started). */
void mt__bench_case_remove_file(mt__bench_case *bench_case);
/* Frees a case's arrays and file, keeping its names and counts for the
 * tables. */
void mt__bench_case_release(mt__bench_case *bench_case);
bool mt__bench_input_write(const mt_face_list *list, const char *path, char *err, size_t err_size);

/* bench_child.c: a peer program as a child process speaking one line at a
 * time over its stdin and stdout. */
typedef struct mt__bench_child {
    pid_t pid;
    FILE *to_child;   /* its stdin */
    FILE *from_child; /* its stdout */
} mt__bench_child;

/* Finds the peer program `name`: in peer_dir when given, else next to this
 * program, in ../libexec/meshtopo from it (installed), then in the build
 * tree. Its path goes to out. */
bool mt__bench_peer_find(const char *peer_dir, const char *name, char *out, size_t size);
/* Starts argv[0] with argv (NULL-terminated) on two pipes. */
bool mt__bench_child_start(mt__bench_child *child, char *const argv[], char *err, size_t err_size);
/* Sends one line (the newline is added). */
bool mt__bench_child_send(mt__bench_child *child, const char *line, char *err, size_t err_size);
/* Reads one line into buf, newline removed; false at the end of its output
 * or on an "error ..." line (err says which). */
bool mt__bench_child_read_line(mt__bench_child *child, char *buf, size_t size, char *err,
                               size_t err_size);
/* Sends "quit", closes both pipes, waits for this child only and reports
 * (under `name`) a non-zero exit or a signal. Safe on a child never started. */
void mt__bench_child_stop(mt__bench_child *child, const char *name);
/* key=value in a protocol line (keys are whole words): the value, or NULL. */
const char *mt__bench_field(const char *line, const char *key);
bool mt__bench_field_u64(const char *line, const char *key, uint64_t *out);
bool mt__bench_field_i64(const char *line, const char *key, int64_t *out);
bool mt__bench_field_double(const char *line, const char *key, double *out);

/* bench_meshtopo.c, bench_peer.c and bench_floor.c */
void mt__bench_runner_meshtopo(mt__bench_runner *out, uint32_t threads, bool recycle);
void mt__bench_runner_peer(mt__bench_runner *out, const char *library, const char *peer_flag);
void mt__bench_runner_floor(mt__bench_runner *out, bool fresh);

/* bench_table.c: medians and the figures of one row, shared by every
 * printer. results is [num_cases][num_runners], row-major. */
typedef enum mt__bench_metric {
    MT__BENCH_BUILD,
    MT__BENCH_RING,
    MT__BENCH_ADJ,
    MT__BENCH_LOOPS,
    MT__BENCH_COMPONENTS
} mt__bench_metric;

typedef struct mt__bench_row {
    const mt__bench_result *r;
    bool ok;
    double faces; /* of the case's input */
    double build_ms, build_min, build_max, build_ratio, ns_per_face;
    double ring_ms, ring_ratio, ring_per_s;
    double adj_ms, adj_ratio, adj_per_s;
    double loops_ms, components_ms;
    double heap_per_face;      /* mallinfo2 growth / F */
    double structure_per_face; /* meshtopo only: mt_mesh_memory_bytes / F */
} mt__bench_row;

double mt__bench_median(const mt__bench_result *result, mt__bench_metric metric);
/* The meshtopo row the ratios of a case are taken against: its fastest
 * build (NULL when meshtopo has no measurement). */
const mt__bench_result *mt__bench_base(const mt__bench_result *row, uint32_t num_runners);
mt__bench_row mt__bench_row_compute(const mt__bench_result *r, const mt__bench_result *base);
/* "%.*f" of x, or "-" when x is not a number. */
const char *mt__bench_num(char *buf, size_t size, double x, int decimals);
const char *mt__bench_ms(char *buf, size_t size, double x);
const char *mt__bench_rate(char *buf, size_t size, double x);
const char *mt__bench_threads_text(const mt__bench_result *r, char *buf, size_t size);

void mt__bench_table_print(FILE *out, const mt__bench_options *options,
                           const mt__bench_result *results, uint32_t num_cases,
                           uint32_t num_runners);
/* Targets of the benchmark issue for every case of 100k faces or more;
 * returns true when all were met (the exit status does not depend on it). */
bool mt__bench_targets_print(FILE *out, const mt__bench_result *results, uint32_t num_cases,
                             uint32_t num_runners);

/* bench_files.c: the same rows as CSV and Markdown; bench_svg.c: build time
 * against faces, log-log, one line per library and order. */
bool mt__bench_csv_write(const char *path, const mt__bench_options *options,
                         const mt__bench_result *results, uint32_t num_cases, uint32_t num_runners);
bool mt__bench_markdown_write(const char *path, const mt__bench_options *options,
                              const mt__bench_result *results, uint32_t num_cases,
                              uint32_t num_runners);
bool mt__bench_svg_write(const char *path, const mt__bench_result *results, uint32_t num_cases,
                         uint32_t num_runners);

#endif
