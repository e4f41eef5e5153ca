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

#include "meshtopo/face_list.h"

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

#define MT__BENCH_MAX_REPS 99
#define MT__BENCH_MAX_CASES 8
#define MT__BENCH_MAX_RUNNERS 4

/* Command-line options (see mt__bench_usage in bench.c). */
typedef struct mt__bench_options {
    uint64_t faces;         /* target triangle count of the grid */
    uint32_t reps;          /* timed repetitions per library and case */
    uint32_t threads;       /* mt_build_options.threads (0 = automatic) */
    uint64_t seed;          /* seed of the permuted copy */
    bool quick;             /* small mesh, few repetitions (smoke test) */
    bool peer_no_reserve;   /* peers time the plain add loop, without reserve() */
    const char *csv_path;   /* NULL: no CSV */
    const char *md_path;    /* NULL: no Markdown */
    const char *peer_dir;   /* NULL: look next to the executable */
    const char *tmp_parent; /* NULL: $TMPDIR or /tmp */
} mt__bench_options;

/* One mesh in one order: the face list meshtopo builds from in process and
 * the raw file (bench_input.c) the peers read the same bytes from. */
typedef struct mt__bench_case {
    char mesh[48];  /* "grid 707x707" */
    char order[16]; /* "ordered" or "permuted" */
    mt_face_list list;
    char path[PATH_MAX];
} mt__bench_case;

/* What a library built: counts checked across libraries, and one sweep's
 * totals (neighbours visited, sum of their vertex ids) as a cross-check. */
typedef struct mt__bench_topology {
    uint64_t verts, edges, faces, boundary_loops;
    uint64_t rejected_faces; /* faces the library refused or left out */
    uint64_t neighbours, checksum;
} mt__bench_topology;

/* One timed repetition: build, then one-ring sweep over every vertex. */
typedef struct mt__bench_sample {
    double build_ms;
    double sweep_ms;
    uint64_t neighbours, checksum;
    int64_t heap_bytes; /* heap growth over the build (mallinfo2), -1 if unknown */
} mt__bench_sample;

typedef enum mt__bench_state {
    MT__BENCH_OK,
    MT__BENCH_SKIPPED, /* library not available: not an error */
    MT__BENCH_FAILED
} mt__bench_state;

/* One library on one case. */
typedef struct mt__bench_result {
    const char *library;
    const mt__bench_case *bench_case;
    mt__bench_state state;
    char message[512]; /* why it was skipped or failed */
    char version[32];
    mt__bench_topology topology;
    uint64_t structure_bytes; /* meshtopo: mt_mesh_memory_bytes; 0 for peers */
    uint64_t report_bytes;    /* meshtopo: mt_mesh_report_memory_bytes */
    uint32_t num_samples;
    mt__bench_sample samples[MT__BENCH_MAX_REPS];
} mt__bench_result;

/* A way to measure one library: start loads a case and warms up (filling
 * version and topology in the result), rep runs one timed repetition, stop
 * releases everything. start and rep return false after writing the reason
 * into result->message. */
typedef struct mt__bench_runner mt__bench_runner;
struct mt__bench_runner {
    const char *library;
    bool (*start)(mt__bench_runner *runner, const mt__bench_case *bench_case,
                  const mt__bench_options *options, mt__bench_result *result);
    bool (*rep)(mt__bench_runner *runner, mt__bench_sample *out, mt__bench_result *result);
    void (*stop)(mt__bench_runner *runner);
    void *state;
    char exe[PATH_MAX]; /* peer executable, empty for in-process runners */
};

/* Entry point shared by the meshtopo-bench executable (and later the
 * `meshtopo bench` subcommand). Returns the process exit code. */
int mt__bench_command(int argc, char **argv);

/* bench_clock.c */
double mt__bench_now_ms(void);
int64_t mt__bench_heap_bytes(void);

/* bench_input.c: builds the cases and writes their raw files into dir. */
bool mt__bench_cases_make(const mt__bench_options *options, const char *dir, mt__bench_case *cases,
                          uint32_t *out_num_cases, char *err, size_t err_size);
/* Removes the raw files (the peers have read them once started); free
 * removes them too and releases the face lists. */
void mt__bench_cases_remove_files(mt__bench_case *cases, uint32_t num_cases);
void mt__bench_cases_free(mt__bench_case *cases, uint32_t num_cases);
bool mt__bench_input_write(const mt_face_list *list, const char *path, char *err, size_t err_size);

/* bench_meshtopo.c and bench_peer.c */
void mt__bench_runner_meshtopo(mt__bench_runner *out);
void mt__bench_runner_peer(mt__bench_runner *out, const char *library, const char *exe);

/* bench_table.c: medians, the console table, CSV and Markdown. results is
 * [num_cases][num_runners], row-major. */
double mt__bench_median(const mt__bench_result *result, bool sweep);
void mt__bench_table_print(FILE *out, const mt__bench_options *options,
                           const mt__bench_result *results, uint32_t num_cases,
                           uint32_t num_runners);
bool mt__bench_targets_print(FILE *out, const mt__bench_result *results, uint32_t num_cases,
                             uint32_t num_runners);
bool mt__bench_csv_write(const char *path, const mt__bench_options *options,
                         const mt__bench_result *results, uint32_t num_cases, uint32_t num_runners);
bool mt__bench_markdown_write(const char *path, const mt__bench_options *options,
                              const mt__bench_result *results, uint32_t num_cases,
                              uint32_t num_runners);

#endif
