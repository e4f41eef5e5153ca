/* meshtopo-bench's driver: parses the options, makes the cases, and for one
 * case after another starts one runner per library (meshtopo with 1 and 2
 * threads and the memcpy floors in process, OpenMesh, CGAL and CGAL's
 * polygon soup as child processes when they were built), interleaves the
 * repetitions across libraries, checks that every library built the same
 * V, E, F, boundary loops and components, and prints the table (`all`: also
 * Markdown, CSV and SVG files). Exit status: 0 when every measurement ran and
 * agreed, 1 when one failed or the counts disagree, 2 on a usage error.
 * Missing peers are skipped, not failed; missed targets are only printed. */
#include <errno.h>
#include <inttypes.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"

#define MT__BENCH_DEFAULT_FACES 1000000u
#define MT__BENCH_DEFAULT_TORUS_FACES 4000000u
#define MT__BENCH_DEFAULT_REPS 7u
#define MT__BENCH_ALL_REPS 5u
#define MT__BENCH_QUICK_FACES 20000u
#define MT__BENCH_QUICK_TORUS_FACES 40000u
#define MT__BENCH_QUICK_REPS 3u
#define MT__BENCH_MAX_FACES 400000000u
#define MT__BENCH_SEED 0x6d657368746f706full
#define MT__BENCH_DEFAULT_OUT "bench-results"
#ifndef MESHTOPO_BENCH_CORPUS_DIR
#define MESHTOPO_BENCH_CORPUS_DIR "tests/corpus"
#endif

/* The peers: row name, executable name, extra argument. */
static const char *const peer_names[][3] = {
    {"OpenMesh", "meshtopo-bench-openmesh", NULL},
    {"CGAL", "meshtopo-bench-cgal", NULL},
    {"CGAL-soup", "meshtopo-bench-cgal", "--soup"},
};
#define MT__BENCH_NUM_PEERS (sizeof peer_names / sizeof peer_names[0])

static void usage(FILE *out)
{
    fprintf(out,
            "usage: meshtopo-bench [build] [options]\n"
            "       meshtopo-bench all [options]\n"
            "Times building a half-edge mesh from a face list, a one-ring sweep over every\n"
            "vertex, a face-adjacency sweep over every face, boundary loops and connected\n"
            "components, for meshtopo (1 and 2 threads) and (when built) OpenMesh, CGAL and\n"
            "CGAL's polygon soup, next to a memcpy floor, on each mesh in natural order and\n"
            "with vertices and faces shuffled. build: a triangulated grid. all: the bunny,\n"
            "a closed corpus mesh, the grid and a closed torus, writing bench.md, bench.csv\n"
            "and build-time.svg into --out.\n"
            "\n"
            "  --faces N        triangles in the grid (default %u)\n"
            "  --torus-faces N  triangles in the torus, all only (default %u)\n"
            "  --reps N         timed repetitions after one warm-up (default %u, all %u,\n"
            "                   at most %u)\n"
            "  --threads N      one meshtopo row with N build threads, 0 = automatic\n"
            "                   (default: rows with 1 and 2 that recycle each mesh into\n"
            "                   the build workspace, and a row with 2 into new memory)\n"
            "  --seed N         seed of the shuffled copies\n"
            "  --out DIR        all: directory of the three files (default ./%s)\n"
            "  --corpus DIR     where npm_bunny.off and igl_fertility.off are\n"
            "                   (default %s)\n"
            "  --csv FILE       also write the results as CSV\n"
            "  --markdown FILE  also write the results as a Markdown table\n"
            "  --svg FILE       also write the build-time plot\n"
            "  --quick          small meshes (grid %u, torus %u triangles), %u repetitions\n"
            "  --no-reserve     OpenMesh and CGAL do not reserve() the counts before a build\n"
            "  --idle-ms N      idle N ms (at most 10000) before each timed repetition, as a\n"
            "                   long-lived program between two builds (default 0)\n"
            "  --peer-dir DIR   where the peer programs are (default: next to this program)\n"
            "  --tmpdir DIR     where the input files for the peers go ($TMPDIR or /tmp)\n"
            "  --help           this text\n",
            MT__BENCH_DEFAULT_FACES, MT__BENCH_DEFAULT_TORUS_FACES, MT__BENCH_DEFAULT_REPS,
            MT__BENCH_ALL_REPS, MT__BENCH_MAX_REPS, MT__BENCH_DEFAULT_OUT,
            MESHTOPO_BENCH_CORPUS_DIR, MT__BENCH_QUICK_FACES, MT__BENCH_QUICK_TORUS_FACES,
            MT__BENCH_QUICK_REPS);
}

/* Returns 0 when parsed, 1 for --help, 2 on error (printed). */
static int parse_options(int argc, char **argv, mt__bench_options *o)
{
    /* The options usage() describes. */
    static const mt__option option_table[] = {
        {"quick", NULL, NULL},      {"no-reserve", NULL, NULL}, {"faces", "N", NULL},
        {"torus-faces", "N", NULL}, {"reps", "N", NULL},        {"threads", "N", NULL},
        {"idle-ms", "N", NULL},     {"seed", "N", NULL},        {"csv", "FILE", NULL},
        {"markdown", "FILE", NULL}, {"svg", "FILE", NULL},      {"out", "DIR", NULL},
        {"corpus", "DIR", NULL},    {"peer-dir", "DIR", NULL},  {"tmpdir", "DIR", NULL},
    };
    static const char program[] = "meshtopo-bench";
    memset(o, 0, sizeof *o);
    o->seed = MT__BENCH_SEED;
    o->corpus_dir = MESHTOPO_BENCH_CORPUS_DIR;
    uint64_t faces = MT__BENCH_DEFAULT_FACES, torus = MT__BENCH_DEFAULT_TORUS_FACES;
    uint64_t reps = MT__BENCH_DEFAULT_REPS;
    /* argv[0] is the program or "build"; "all" may follow it. */
    int first = 1;
    if (argc > 1 && strcmp(argv[1], "all") == 0) {
        o->all = true;
        first = 2;
    }
    mt__args args;
    int read =
        mt__bench_args_read(program, option_table, sizeof option_table / sizeof option_table[0],
                            argc - first, argv + first, &args);
    if (read != 0) return read;
    bool have_faces = false, have_torus = false, have_reps = false;
    bool ok =
        mt__bench_arg_u64(&args, program, "faces", 2, MT__BENCH_MAX_FACES, &faces, &have_faces) &&
        mt__bench_arg_u64(&args, program, "torus-faces", 18, MT__BENCH_MAX_FACES, &torus,
                          &have_torus) &&
        mt__bench_arg_u64(&args, program, "reps", 1, MT__BENCH_MAX_REPS, &reps, &have_reps) &&
        mt__bench_arg_u32(&args, program, "threads", 0, 1024, &o->threads, &o->threads_given) &&
        mt__bench_arg_u32(&args, program, "idle-ms", 0, 10000, &o->idle_ms, NULL) &&
        mt__bench_arg_u64(&args, program, "seed", 0, UINT64_MAX, &o->seed, NULL);
    o->quick = mt__args_flag(&args, "quick");
    o->peer_no_reserve = mt__args_flag(&args, "no-reserve");
    o->csv_path = mt__args_value(&args, "csv");
    o->md_path = mt__args_value(&args, "markdown");
    o->svg_path = mt__args_value(&args, "svg");
    o->out_dir = mt__args_value(&args, "out");
    if (mt__args_value(&args, "corpus")) o->corpus_dir = mt__args_value(&args, "corpus");
    o->peer_dir = mt__args_value(&args, "peer-dir");
    o->tmp_parent = mt__args_value(&args, "tmpdir");
    mt__args_free(&args);
    if (!ok) return 2;
    if (o->all && !have_reps) reps = MT__BENCH_ALL_REPS;
    if (o->quick && !have_faces) faces = MT__BENCH_QUICK_FACES;
    if (o->quick && !have_torus) torus = MT__BENCH_QUICK_TORUS_FACES;
    if (o->quick && !have_reps) reps = MT__BENCH_QUICK_REPS;
    if (o->all && !o->out_dir) o->out_dir = MT__BENCH_DEFAULT_OUT;
    o->faces = faces;
    o->torus_faces = torus;
    o->reps = (uint32_t)reps;
    return 0;
}

static void result_fail(mt__bench_runner *runner, mt__bench_result *result)
{
    result->state = MT__BENCH_FAILED;
    fprintf(stderr, "meshtopo-bench: %s on %s, %s: %s\n", result->library, result->bench_case->mesh,
            result->bench_case->order, result->message);
    runner->stop(runner);
}

static bool counts_equal(const mt__bench_topology *a, const mt__bench_topology *b)
{
    return a->verts == b->verts && a->edges == b->edges && a->faces == b->faces &&
           a->boundary_loops == b->boundary_loops;
}

/* What every query of a run saw: the same in every repetition and library. */
static bool seen_equal(const mt__bench_topology *a, const mt__bench_topology *b)
{
    return a->boundary_loops == b->boundary_loops && a->loop_verts == b->loop_verts &&
           a->ring_neighbours == b->ring_neighbours && a->ring_sum == b->ring_sum &&
           a->adj_neighbours == b->adj_neighbours && a->adj_sum == b->adj_sum;
}

static void topology_print(FILE *out, const char *library, const mt__bench_topology *t)
{
    fprintf(out,
            "    %-13s V=%" PRIu64 " E=%" PRIu64 " F=%" PRIu64 " boundary_loops=%" PRIu64
            " components=%s%.0f rejected_faces=%" PRIu64 " loop_verts=%" PRIu64 " ring=%" PRIu64
            "/%" PRIu64 " adjacency=%" PRIu64 "/%" PRIu64 "\n",
            library, t->verts, t->edges, t->faces, t->boundary_loops,
            t->components == MT__BENCH_UNKNOWN ? "-" : "",
            t->components == MT__BENCH_UNKNOWN ? 0.0 : (double)t->components, t->rejected_faces,
            t->loop_verts, t->ring_neighbours, t->ring_sum, t->adj_neighbours, t->adj_sum);
}

/* Checks one case: every measured library agrees with the first on V, E, F,
 * boundary loops and (where computed) components, and every repetition's
 * queries (warm-up and timed) saw the same loops, neighbours and id sums.
 * Prints the verdict; false on mismatch. */
static bool case_check(FILE *out, const mt__bench_result *row, uint32_t num_runners)
{
    const mt__bench_result *first = NULL;
    uint64_t components = MT__BENCH_UNKNOWN;
    bool counts_agree = true, queries_agree = true;
    uint32_t measured = 0;
    for (uint32_t k = 0; k < num_runners; k++) {
        const mt__bench_result *r = &row[k];
        if (r->state != MT__BENCH_OK || r->kind != MT__BENCH_LIBRARY) continue;
        measured++;
        if (!first) first = r;
        if (!counts_equal(&r->topology, &first->topology)) counts_agree = false;
        if (r->topology.components != MT__BENCH_UNKNOWN) {
            if (components == MT__BENCH_UNKNOWN) components = r->topology.components;
            if (r->topology.components != components) counts_agree = false;
        }
        if (!seen_equal(&r->topology, &first->topology)) queries_agree = false;
        for (uint32_t i = 0; i < r->num_samples; i++) {
            if (!seen_equal(&r->samples[i].seen, &r->topology) ||
                r->samples[i].seen.components != r->topology.components) {
                queries_agree = false;
            }
        }
    }
    const mt__bench_case *c = row[0].bench_case;
    if (!first) {
        fprintf(out, "check %s, %s: nothing measured\n", c->mesh, c->order);
        return true;
    }
    if (counts_agree && queries_agree) {
        const mt__bench_topology *t = &first->topology;
        fprintf(out,
                "check %s, %s: %s: V=%" PRIu64 " E=%" PRIu64 " F=%" PRIu64
                " boundary loops=%" PRIu64 " components=%" PRIu64 "; sweeps visit %" PRIu64
                " vertex and %" PRIu64 " face neighbours\n",
                c->mesh, c->order,
                measured == 1 ? "only one library measured" : "all libraries agree", t->verts,
                t->edges, t->faces, t->boundary_loops, components, t->ring_neighbours,
                t->adj_neighbours);
        return true;
    }
    fprintf(out, "check %s, %s: DISAGREEMENT (%s)\n", c->mesh, c->order,
            counts_agree ? "sweeps or boundary loops differ"
                         : "V, E, F, boundary loops or components differ");
    for (uint32_t k = 0; k < num_runners; k++) {
        if (row[k].state == MT__BENCH_OK && row[k].kind == MT__BENCH_LIBRARY) {
            topology_print(out, row[k].library, &row[k].topology);
        }
    }
    return false;
}

static bool tmpdir_make(const mt__bench_options *o, char *dir, size_t size)
{
    const char *parent = o->tmp_parent;
    if (!parent) parent = getenv("TMPDIR");
    if (!parent || !*parent) parent = "/tmp";
    int n = snprintf(dir, size, "%s/meshtopo-bench-XXXXXX", parent);
    if (n < 0 || (size_t)n >= size) {
        fprintf(stderr, "meshtopo-bench: temporary directory path too long\n");
        return false;
    }
    if (!mkdtemp(dir)) {
        fprintf(stderr, "meshtopo-bench: cannot create %s: %s\n", dir, strerror(errno));
        return false;
    }
    return true;
}

/* The command line and the machine, for the Markdown file. */
static void provenance_fill(mt__bench_options *o, int argc, char **argv)
{
    size_t at = 0;
    o->command[0] = '\0';
    for (int i = 0; i < argc && at < sizeof o->command; i++) {
        const char *word = i == 0 ? "meshtopo-bench" : argv[i];
        int n = snprintf(o->command + at, sizeof o->command - at, "%s%s", i ? " " : "", word);
        if (n < 0) break;
        at += (size_t)n;
    }
    char model[160] = "unknown CPU";
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f) {
        char line[256];
        while (fgets(line, sizeof line, f)) {
            const char *colon = strchr(line, ':');
            if (strncmp(line, "model name", 10) == 0 && colon) {
                colon++;
                while (*colon == ' ' || *colon == '\t') colon++;
                snprintf(model, sizeof model, "%.*s", (int)strcspn(colon, "\n"), colon);
                break;
            }
        }
        fclose(f);
    }
    struct utsname u;
    bool have_uname = uname(&u) == 0;
    snprintf(o->machine, sizeof o->machine, "%s, %ld cores online, %s %s", model,
             sysconf(_SC_NPROCESSORS_ONLN), have_uname ? u.sysname : "?",
             have_uname ? u.release : "?");
}

/* The rows of every case: meshtopo (1 and 2 threads recycling each mesh
 * into the workspace and 1 and 2 threads building into new memory, or one
 * row of --threads), the peers, the two memcpy floors. Returns the count. */
static uint32_t runners_make(const mt__bench_options *o, mt__bench_runner *out)
{
    uint32_t n = 0;
    if (o->threads_given) {
        mt__bench_runner_meshtopo(&out[n++], o->threads, true);
    } else {
        mt__bench_runner_meshtopo(&out[n++], 1, true);
        mt__bench_runner_meshtopo(&out[n++], 2, true);
        mt__bench_runner_meshtopo(&out[n++], 1, false);
        mt__bench_runner_meshtopo(&out[n++], 2, false);
    }
    for (size_t p = 0; p < MT__BENCH_NUM_PEERS; p++) {
        mt__bench_runner_peer(&out[n++], peer_names[p][0], peer_names[p][2]);
    }
    mt__bench_runner_floor(&out[n++], true);
    mt__bench_runner_floor(&out[n++], false);
    return n;
}

/* Starts every runner of one case, runs the interleaved repetitions, stops
 * them. The first runner of each round rotates so none always runs right
 * after another. */
static void case_run(const mt__bench_options *o, mt__bench_case *bench_case,
                     mt__bench_runner *runners, mt__bench_result *results, uint32_t num_runners)
{
    for (uint32_t k = 0; k < num_runners; k++) {
        mt__bench_runner *runner = &runners[k];
        mt__bench_result *result = &results[k];
        result->bench_case = bench_case;
        result->library = runner->library;
        result->kind = runner->kind;
        result->is_meshtopo = runner->is_meshtopo;
        result->threads = runner->is_meshtopo ? runner->threads : 1;
        if (runner->kind == MT__BENCH_LIBRARY && !runner->is_meshtopo) {
            const char *exe_name = NULL;
            for (size_t p = 0; p < MT__BENCH_NUM_PEERS; p++) {
                if (strcmp(peer_names[p][0], runner->library) == 0) exe_name = peer_names[p][1];
            }
            if (!exe_name ||
                !mt__bench_peer_find(o->peer_dir, exe_name, runner->exe, sizeof runner->exe)) {
                runner->exe[0] = '\0';
                result->state = MT__BENCH_SKIPPED;
                snprintf(result->message, sizeof result->message,
                         "%s not found (built only when the library is installed)",
                         exe_name ? exe_name : runner->library);
                continue;
            }
        }
        fprintf(stderr, "meshtopo-bench: warming up %s on %s, %s\n", result->library,
                bench_case->mesh, bench_case->order);
        if (!runner->start(runner, bench_case, o, result)) result_fail(runner, result);
    }
    /* Every peer has read its input by now. */
    mt__bench_case_remove_file(bench_case);

    for (uint32_t rep = 0; rep < o->reps; rep++) {
        fprintf(stderr, "meshtopo-bench: %s, %s: repetition %u of %u\n", bench_case->mesh,
                bench_case->order, rep + 1, o->reps);
        for (uint32_t j = 0; j < num_runners; j++) {
            uint32_t k = (j + rep) % num_runners;
            mt__bench_result *result = &results[k];
            if (result->state != MT__BENCH_OK) continue;
            if (o->idle_ms) {
                struct timespec idle = {o->idle_ms / 1000, (long)(o->idle_ms % 1000) * 1000000L};
                nanosleep(&idle, NULL);
            }
            if (!runners[k].rep(&runners[k], &result->samples[result->num_samples], result)) {
                result_fail(&runners[k], result);
                continue;
            }
            result->num_samples++;
        }
    }
    for (uint32_t k = 0; k < num_runners; k++) {
        if (results[k].state == MT__BENCH_OK) runners[k].stop(&runners[k]);
    }
}

/* out_dir/name into buf, creating out_dir (one level) when needed. */
static const char *out_path(const char *dir, const char *name, char *buf, size_t size)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "meshtopo-bench: cannot create %s: %s\n", dir, strerror(errno));
        return NULL;
    }
    int n = snprintf(buf, size, "%s/%s", dir, name);
    return n > 0 && (size_t)n < size ? buf : NULL;
}

static bool file_written(bool ok, const char *path)
{
    if (ok) {
        fprintf(stderr, "meshtopo-bench: wrote %s\n", path);
    } else {
        fprintf(stderr, "meshtopo-bench: cannot write %s\n", path);
    }
    return ok;
}

int mt__bench_command(int argc, char **argv)
{
    mt__bench_options options;
    int parsed = parse_options(argc, argv, &options);
    if (parsed != 0) return mt__bench_usage_exit(parsed, usage);
    provenance_fill(&options, argc, argv);
    char md_buf[PATH_MAX], csv_buf[PATH_MAX], svg_buf[PATH_MAX];
    if (options.out_dir) {
        if (!options.md_path)
            options.md_path = out_path(options.out_dir, "bench.md", md_buf, sizeof md_buf);
        if (!options.csv_path)
            options.csv_path = out_path(options.out_dir, "bench.csv", csv_buf, sizeof csv_buf);
        if (!options.svg_path)
            options.svg_path = out_path(options.out_dir, "build-time.svg", svg_buf, sizeof svg_buf);
        if (!options.md_path || !options.csv_path || !options.svg_path) return 1;
    }
    signal(SIGPIPE, SIG_IGN); /* a dead peer is reported through its pipe */

    char dir[PATH_MAX];
    if (!tmpdir_make(&options, dir, sizeof dir)) return 1;

    int exit_code = 0;
    mt__bench_case cases[MT__BENCH_MAX_CASES];
    const uint32_t num_cases = 2 * mt__bench_num_meshes(&options);
    memset(cases, 0, sizeof cases);
    char err[512];
    fprintf(stderr, "meshtopo-bench: the input goes to %s\n", dir);

    /* One runner per case and library: runners[c * num_runners + k]. */
    mt__bench_runner prototype[MT__BENCH_MAX_RUNNERS];
    uint32_t num_runners = runners_make(&options, prototype);
    size_t num_slots = (size_t)num_cases * num_runners;
    mt__bench_runner *runners = calloc(num_slots, sizeof *runners);
    mt__bench_result *results = calloc(num_slots, sizeof *results);
    if (!runners || !results) {
        fprintf(stderr, "meshtopo-bench: out of memory\n");
        free(runners);
        free(results);
        rmdir(dir);
        return 1;
    }
    for (uint32_t c = 0; c < num_cases; c += 2) {
        if (!mt__bench_mesh_cases_make(&options, dir, c / 2, &cases[c], err, sizeof err)) {
            fprintf(stderr, "meshtopo-bench: %s\n", err);
            mt__bench_case_release(&cases[c]);
            mt__bench_case_release(&cases[c + 1]);
            free(runners);
            free(results);
            rmdir(dir);
            return 1;
        }
        for (uint32_t k = c; k < c + 2; k++) {
            memcpy(&runners[(size_t)k * num_runners], prototype, sizeof prototype[0] * num_runners);
            case_run(&options, &cases[k], &runners[(size_t)k * num_runners],
                     &results[(size_t)k * num_runners], num_runners);
        }
        mt__bench_case_release(&cases[c]);
        mt__bench_case_release(&cases[c + 1]);
    }
    rmdir(dir);
    for (size_t i = 0; i < num_slots; i++) {
        if (results[i].state == MT__BENCH_FAILED) exit_code = 1;
    }

    printf("\n");
    mt__bench_table_print(stdout, &options, results, num_cases, num_runners);
    mt__bench_targets_print(stdout, results, num_cases, num_runners);
    printf("\n");
    for (uint32_t c = 0; c < num_cases; c++) {
        if (!case_check(stdout, &results[c * num_runners], num_runners)) exit_code = 1;
    }
    if (options.csv_path && !file_written(mt__bench_csv_write(options.csv_path, &options, results,
                                                              num_cases, num_runners),
                                          options.csv_path)) {
        exit_code = 1;
    }
    if (options.md_path && !file_written(mt__bench_markdown_write(options.md_path, &options,
                                                                  results, num_cases, num_runners),
                                         options.md_path)) {
        exit_code = 1;
    }
    if (options.svg_path &&
        !file_written(mt__bench_svg_write(options.svg_path, results, num_cases, num_runners),
                      options.svg_path)) {
        exit_code = 1;
    }

    free(runners);
    free(results);
    return exit_code;
}
