/* meshtopo-bench's driver: parses the options, makes the cases, starts one
 * runner per library and case (meshtopo in process, OpenMesh and CGAL as
 * child processes when they were built), interleaves the repetitions across
 * libraries, checks that every library built the same V, E, F and boundary
 * loops, and prints the table. Exit status: 0 when every measurement ran and
 * agreed, 1 when one failed or the counts disagree, 2 on a usage error.
 * Missing peers are skipped, not failed; missed targets are only printed. */
#include <errno.h>
#include <inttypes.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bench.h"

#define MT__BENCH_DEFAULT_FACES 1000000u
#define MT__BENCH_DEFAULT_REPS 7u
#define MT__BENCH_QUICK_FACES 20000u
#define MT__BENCH_QUICK_REPS 3u
#define MT__BENCH_MAX_FACES 400000000u
#define MT__BENCH_SEED 0x6d657368746f706full

/* The peers: library name and executable name. */
static const char *const peer_names[][2] = {
    {"OpenMesh", "meshtopo-bench-openmesh"},
    {"CGAL", "meshtopo-bench-cgal"},
};

static void usage(FILE *out)
{
    fprintf(out,
            "usage: meshtopo-bench [options]\n"
            "Times building a half-edge mesh from a face list and a one-ring sweep over\n"
            "every vertex, for meshtopo and (when built) OpenMesh and CGAL, on a\n"
            "triangulated grid in natural order and with vertices and faces shuffled.\n"
            "\n"
            "  --faces N       triangles in the grid (default %u)\n"
            "  --reps N        timed repetitions after one warm-up (default %u, at most %u)\n"
            "  --threads N     meshtopo build threads, 0 = automatic (default 0)\n"
            "  --seed N        seed of the shuffled copy\n"
            "  --csv FILE      also write the results as CSV\n"
            "  --markdown FILE also write the results as a Markdown table\n"
            "  --quick         small mesh (%u triangles) and %u repetitions\n"
            "  --no-reserve    OpenMesh and CGAL do not reserve() the counts before a build\n"
            "  --peer-dir DIR  where the peer programs are (default: next to this program)\n"
            "  --tmpdir DIR    where the input files for the peers go (default $TMPDIR or /tmp)\n"
            "  --help          this text\n",
            MT__BENCH_DEFAULT_FACES, MT__BENCH_DEFAULT_REPS, MT__BENCH_MAX_REPS,
            MT__BENCH_QUICK_FACES, MT__BENCH_QUICK_REPS);
}

static bool parse_u64(const char *text, uint64_t min, uint64_t max, uint64_t *out)
{
    if (!text || !*text || *text == '-') return false;
    char *end;
    errno = 0;
    unsigned long long v = strtoull(text, &end, 0);
    if (errno || *end || v < min || v > max) return false;
    *out = v;
    return true;
}

/* Returns 0 when parsed, 1 for --help, 2 on error. */
static int parse_options(int argc, char **argv, mt__bench_options *o)
{
    memset(o, 0, sizeof *o);
    o->seed = MT__BENCH_SEED;
    bool have_faces = false, have_reps = false;
    uint64_t faces = MT__BENCH_DEFAULT_FACES, reps = MT__BENCH_DEFAULT_REPS, v;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) return 1;
        if (strcmp(a, "--quick") == 0) {
            o->quick = true;
            continue;
        }
        if (strcmp(a, "--no-reserve") == 0) {
            o->peer_no_reserve = true;
            continue;
        }
        if (!next) {
            fprintf(stderr, "meshtopo-bench: unknown option or missing value: %s\n", a);
            return 2;
        }
        i++;
        if (strcmp(a, "--faces") == 0 && parse_u64(next, 2, MT__BENCH_MAX_FACES, &faces)) {
            have_faces = true;
        } else if (strcmp(a, "--reps") == 0 && parse_u64(next, 1, MT__BENCH_MAX_REPS, &reps)) {
            have_reps = true;
        } else if (strcmp(a, "--threads") == 0 && parse_u64(next, 0, 1024, &v)) {
            o->threads = (uint32_t)v;
        } else if (strcmp(a, "--seed") == 0 && parse_u64(next, 0, UINT64_MAX, &v)) {
            o->seed = v;
        } else if (strcmp(a, "--csv") == 0) {
            o->csv_path = next;
        } else if (strcmp(a, "--markdown") == 0) {
            o->md_path = next;
        } else if (strcmp(a, "--peer-dir") == 0) {
            o->peer_dir = next;
        } else if (strcmp(a, "--tmpdir") == 0) {
            o->tmp_parent = next;
        } else {
            fprintf(stderr, "meshtopo-bench: bad option or value: %s %s\n", a, next);
            return 2;
        }
    }
    if (o->quick && !have_faces) faces = MT__BENCH_QUICK_FACES;
    if (o->quick && !have_reps) reps = MT__BENCH_QUICK_REPS;
    o->faces = faces;
    o->reps = (uint32_t)reps;
    return 0;
}

static bool is_executable(const char *dir, const char *name, char *out, size_t size)
{
    int n = snprintf(out, size, "%s/%s", dir, name);
    return n > 0 && (size_t)n < size && access(out, X_OK) == 0;
}

/* Looks for a peer program: --peer-dir, next to this program, in
 * ../libexec/meshtopo from it (installed), then in the build tree. */
static bool peer_find(const mt__bench_options *o, const char *name, char *out, size_t size)
{
    if (o->peer_dir) return is_executable(o->peer_dir, name, out, size);
    char self[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n > 0) {
        self[n] = '\0';
        char *slash = strrchr(self, '/');
        if (slash) {
            *slash = '\0';
            if (is_executable(self, name, out, size)) return true;
            char libexec[PATH_MAX];
            int m = snprintf(libexec, sizeof libexec, "%s/../libexec/meshtopo", self);
            if (m > 0 && (size_t)m < sizeof libexec && is_executable(libexec, name, out, size)) {
                return true;
            }
        }
    }
#ifdef MESHTOPO_BENCH_BUILD_PEER_DIR
    if (is_executable(MESHTOPO_BENCH_BUILD_PEER_DIR, name, out, size)) return true;
#endif
    return false;
}

static void result_fail(mt__bench_runner *runner, mt__bench_result *result)
{
    result->state = MT__BENCH_FAILED;
    fprintf(stderr, "meshtopo-bench: %s on %s: %s\n", result->library, result->bench_case->order,
            result->message);
    runner->stop(runner);
}

static bool topology_equal(const mt__bench_topology *a, const mt__bench_topology *b)
{
    return a->verts == b->verts && a->edges == b->edges && a->faces == b->faces &&
           a->boundary_loops == b->boundary_loops;
}

static void topology_print(FILE *out, const char *library, const mt__bench_topology *t)
{
    fprintf(out,
            "    %-9s V=%" PRIu64 " E=%" PRIu64 " F=%" PRIu64 " boundary_loops=%" PRIu64
            " rejected_faces=%" PRIu64 " neighbours=%" PRIu64 " checksum=%" PRIu64 "\n",
            library, t->verts, t->edges, t->faces, t->boundary_loops, t->rejected_faces,
            t->neighbours, t->checksum);
}

/* Checks one case: every measured library agrees with the first on V, E, F
 * and boundary loops, and every sweep (warm-up and timed) visited the same
 * neighbours with the same id sum. Prints the verdict; false on mismatch. */
static bool case_check(FILE *out, const mt__bench_result *row, uint32_t num_runners)
{
    const mt__bench_result *first = NULL;
    bool counts_agree = true, sweeps_agree = true;
    uint32_t measured = 0;
    for (uint32_t k = 0; k < num_runners; k++) {
        const mt__bench_result *r = &row[k];
        if (r->state != MT__BENCH_OK) continue;
        measured++;
        if (!first) first = r;
        if (!topology_equal(&r->topology, &first->topology)) counts_agree = false;
        if (r->topology.neighbours != first->topology.neighbours ||
            r->topology.checksum != first->topology.checksum) {
            sweeps_agree = false;
        }
        for (uint32_t i = 0; i < r->num_samples; i++) {
            if (r->samples[i].neighbours != r->topology.neighbours ||
                r->samples[i].checksum != r->topology.checksum) {
                sweeps_agree = false;
            }
        }
    }
    const char *order = row[0].bench_case->order;
    if (!first) {
        fprintf(out, "check %s: nothing measured\n", order);
        return true;
    }
    if (counts_agree && sweeps_agree) {
        const mt__bench_topology *t = &first->topology;
        fprintf(out,
                "check %s: %s: V=%" PRIu64 " E=%" PRIu64 " F=%" PRIu64 " boundary loops=%" PRIu64
                "; each sweep visits %" PRIu64 " neighbours\n",
                order, measured == 1 ? "only one library measured" : "all libraries agree",
                t->verts, t->edges, t->faces, t->boundary_loops, t->neighbours);
        return true;
    }
    fprintf(out, "check %s: DISAGREEMENT (%s)\n", order,
            counts_agree ? "one-ring sweeps differ" : "V, E, F or boundary loops differ");
    for (uint32_t k = 0; k < num_runners; k++) {
        if (row[k].state == MT__BENCH_OK) topology_print(out, row[k].library, &row[k].topology);
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

int mt__bench_command(int argc, char **argv)
{
    mt__bench_options options;
    int parsed = parse_options(argc, argv, &options);
    if (parsed == 1) {
        usage(stdout);
        return 0;
    }
    if (parsed != 0) {
        usage(stderr);
        return 2;
    }
    signal(SIGPIPE, SIG_IGN); /* a dead peer is reported through its pipe */

    char dir[PATH_MAX];
    if (!tmpdir_make(&options, dir, sizeof dir)) return 1;

    int exit_code = 0;
    mt__bench_case cases[MT__BENCH_MAX_CASES];
    uint32_t num_cases = 0;
    char err[512];
    fprintf(stderr, "meshtopo-bench: making the input (%" PRIu64 " triangles) in %s\n",
            options.faces, dir);
    if (!mt__bench_cases_make(&options, dir, cases, &num_cases, err, sizeof err)) {
        fprintf(stderr, "meshtopo-bench: %s\n", err);
        mt__bench_cases_free(cases, num_cases);
        rmdir(dir);
        return 1;
    }

    /* One runner per case and library: runners[c * num_runners + k]. */
    uint32_t num_runners = 1 + (uint32_t)(sizeof peer_names / sizeof peer_names[0]);
    size_t num_slots = (size_t)num_cases * num_runners;
    mt__bench_runner *runners = calloc(num_slots, sizeof *runners);
    mt__bench_result *results = calloc(num_slots, sizeof *results);
    if (!runners || !results) {
        fprintf(stderr, "meshtopo-bench: out of memory\n");
        free(runners);
        free(results);
        mt__bench_cases_free(cases, num_cases);
        rmdir(dir);
        return 1;
    }

    for (uint32_t c = 0; c < num_cases; c++) {
        for (uint32_t k = 0; k < num_runners; k++) {
            mt__bench_runner *runner = &runners[c * num_runners + k];
            mt__bench_result *result = &results[c * num_runners + k];
            result->bench_case = &cases[c];
            if (k == 0) {
                mt__bench_runner_meshtopo(runner);
                result->library = runner->library;
            } else {
                char exe[PATH_MAX];
                result->library = peer_names[k - 1][0];
                mt__bench_runner_peer(runner, peer_names[k - 1][0], "");
                if (!peer_find(&options, peer_names[k - 1][1], exe, sizeof exe)) {
                    result->state = MT__BENCH_SKIPPED;
                    snprintf(result->message, sizeof result->message,
                             "%s not found (built only when the library is installed)",
                             peer_names[k - 1][1]);
                    continue;
                }
                snprintf(runner->exe, sizeof runner->exe, "%s", exe);
            }
            fprintf(stderr, "meshtopo-bench: warming up %s on %s\n", result->library,
                    cases[c].order);
            if (!runner->start(runner, &cases[c], &options, result)) result_fail(runner, result);
        }
    }

    /* Every peer has read its input by now: a crash from here on leaves
     * nothing behind in the temporary directory. */
    mt__bench_cases_remove_files(cases, num_cases);
    rmdir(dir);

    /* Repetitions interleaved across libraries and cases; the first library
     * of each round rotates so none always runs right after another. */
    for (uint32_t rep = 0; rep < options.reps; rep++) {
        fprintf(stderr, "meshtopo-bench: repetition %u of %u\n", rep + 1, options.reps);
        for (uint32_t c = 0; c < num_cases; c++) {
            for (uint32_t j = 0; j < num_runners; j++) {
                uint32_t k = (j + rep) % num_runners;
                mt__bench_runner *runner = &runners[c * num_runners + k];
                mt__bench_result *result = &results[c * num_runners + k];
                if (result->state != MT__BENCH_OK) continue;
                if (!runner->rep(runner, &result->samples[result->num_samples], result)) {
                    result_fail(runner, result);
                    continue;
                }
                result->num_samples++;
            }
        }
    }
    for (size_t i = 0; i < num_slots; i++) {
        if (results[i].state == MT__BENCH_OK) runners[i].stop(&runners[i]);
        if (results[i].state == MT__BENCH_FAILED) exit_code = 1;
    }

    printf("\n");
    mt__bench_table_print(stdout, &options, results, num_cases, num_runners);
    mt__bench_targets_print(stdout, results, num_cases, num_runners);
    printf("\n");
    for (uint32_t c = 0; c < num_cases; c++) {
        if (!case_check(stdout, &results[c * num_runners], num_runners)) exit_code = 1;
    }
    if (options.csv_path &&
        !mt__bench_csv_write(options.csv_path, &options, results, num_cases, num_runners)) {
        fprintf(stderr, "meshtopo-bench: cannot write %s\n", options.csv_path);
        exit_code = 1;
    }
    if (options.md_path &&
        !mt__bench_markdown_write(options.md_path, &options, results, num_cases, num_runners)) {
        fprintf(stderr, "meshtopo-bench: cannot write %s\n", options.md_path);
        exit_code = 1;
    }

    free(runners);
    free(results);
    mt__bench_cases_free(cases, num_cases);
    return exit_code;
}
