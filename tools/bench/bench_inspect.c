/* `meshtopo-bench inspect`: `meshtopo inspect FILE` timed from outside as a
 * whole process, with --json and without, next to an OpenMesh program that
 * reads the same file and computes the same counts, boundary loops and
 * components (peer_openmesh_inspect.cpp), in paired runs (the three take
 * turns going first, so drift on a shared machine hits each alike); then
 * reading alone: meshtopo's reader in a fresh process (the read time the
 * text run prints) and in this process (mt_read_file), `cat FILE >
 * /dev/null` as a process, and OpenMesh's reader alone (timed inside the
 * peer, a fresh process too). The targets are judged on the fresh
 * processes: a long-lived process such as this one reads faster or slower
 * with what it did before (its allocator's free lists, where its threads
 * last ran), which OpenMesh's reader is not timed with. Files: a grid and
 * a closed torus, in natural and shuffled order, as OFF, binary PLY and
 * OBJ, written to a temporary directory.
 * Medians; a Markdown table on stdout (and into --markdown FILE). */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "bench_inspect.h"
#include "meshtopo/generate.h"
#include "meshtopo/io.h"
#include "meshtopo/mesh.h"
#include "meshtopo/report.h"

#define PEER_NAME "meshtopo-bench-openmesh-inspect"
#define DEFAULT_FACES 1000000u
#define DEFAULT_TORUS_FACES 4000000u
#define DEFAULT_REPS 5u
#define QUICK_FACES 20000u
#define QUICK_TORUS_FACES 40000u
#define QUICK_REPS 3u
#define NUM_FILES 12u

/* Targets of the issue this benchmark judges. */
#define TARGET_VS_OPENMESH 6.0
#define TARGET_JSON_OVER_TEXT 1.1
#define TARGET_TEXT_MB_S 1000.0
#define TARGET_READ_VS_OPENMESH 5.0

typedef struct options {
    uint64_t faces, torus_faces, seed;
    uint32_t reps;
    bool quick;
    const char *tmp_parent, *meshtopo, *peer_dir, *md_path;
} options;

/* One file and its figures. */
typedef struct file_case {
    char mesh[48], order[12], format[12];
    char path[PATH_MAX];
    uint64_t bytes;
    /* in-process counts, checked against the peer's */
    uint64_t verts, edges, faces, loops, components;
    double json_ms[MT__BENCH_MAX_REPS], text_ms[MT__BENCH_MAX_REPS], om_ms[MT__BENCH_MAX_REPS];
    double fresh_read_ms[MT__BENCH_MAX_REPS]; /* printed by the text run */
    double read_ms[MT__BENCH_MAX_REPS], cat_ms[MT__BENCH_MAX_REPS], om_read_ms[MT__BENCH_MAX_REPS];
    bool om_ok; /* the peer ran and agreed */
    char om_note[160];
} file_case;

static void usage(FILE *out)
{
    fprintf(out,
            "usage: meshtopo-bench inspect [options]\n"
            "Times `meshtopo inspect FILE --json` and `meshtopo inspect FILE` as whole processes\n"
            "next to an OpenMesh program (%s) that reads FILE and computes the\n"
            "same counts, boundary loops and components, in paired runs; then reading alone:\n"
            "meshtopo's reader (in a fresh process and in this one), `cat FILE > /dev/null`\n"
            "and OpenMesh's reader.\n"
            "Files: a grid of --faces triangles and a closed torus of --torus-faces, in natural\n"
            "and shuffled order, as OFF, binary PLY and OBJ.\n"
            "  --faces N        grid triangles (default %u)\n"
            "  --torus-faces N  torus triangles (default %u)\n"
            "  --reps N         paired runs per file (default %u, at most %u)\n"
            "  --quick          grid %u and torus %u triangles, %u runs (a smoke test)\n"
            "  --seed N         shuffle seed\n"
            "  --meshtopo PATH  the meshtopo program (default: beside this one, or the build's)\n"
            "  --peer-dir DIR   where the OpenMesh peer is\n"
            "  --tmpdir DIR     where the files are written (default $TMPDIR or /tmp)\n"
            "  --markdown FILE  also write the tables there\n"
            "Exit 0 when every run succeeded and the counts agree (missed targets are\n"
            "printed, not failed), 1 otherwise, 2 on a usage error.\n",
            PEER_NAME, DEFAULT_FACES, DEFAULT_TORUS_FACES, DEFAULT_REPS, MT__BENCH_MAX_REPS,
            QUICK_FACES, QUICK_TORUS_FACES, QUICK_REPS);
}

/* Returns 0, 1 (--help) or 2 (usage error, printed). */
static int parse_options(int argc, char **argv, options *o)
{
    /* The options usage() describes. */
    static const mt__option option_table[] = {
        {"quick", NULL, NULL},     {"faces", "N", NULL},    {"torus-faces", "N", NULL},
        {"reps", "N", NULL},       {"seed", "N", NULL},     {"meshtopo", "PATH", NULL},
        {"peer-dir", "DIR", NULL}, {"tmpdir", "DIR", NULL}, {"markdown", "FILE", NULL},
    };
    static const char program[] = "meshtopo-bench inspect";
    memset(o, 0, sizeof *o);
    o->faces = DEFAULT_FACES;
    o->torus_faces = DEFAULT_TORUS_FACES;
    o->reps = DEFAULT_REPS;
    o->seed = 12345;
    mt__args args;
    int read =
        mt__bench_args_read(program, option_table, sizeof option_table / sizeof option_table[0],
                            argc - 1, argv + 1, &args);
    if (read != 0) return read;
    bool faces_given = false, torus_given = false, reps_given = false;
    bool ok =
        mt__bench_arg_u64(&args, program, "faces", 2, (uint64_t)1 << 31, &o->faces, &faces_given) &&
        mt__bench_arg_u64(&args, program, "torus-faces", 18, (uint64_t)1 << 31, &o->torus_faces,
                          &torus_given) &&
        mt__bench_arg_u32(&args, program, "reps", 1, MT__BENCH_MAX_REPS, &o->reps, &reps_given) &&
        mt__bench_arg_u64(&args, program, "seed", 0, UINT64_MAX, &o->seed, NULL);
    o->quick = mt__args_flag(&args, "quick");
    o->meshtopo = mt__args_value(&args, "meshtopo");
    o->peer_dir = mt__args_value(&args, "peer-dir");
    o->tmp_parent = mt__args_value(&args, "tmpdir");
    o->md_path = mt__args_value(&args, "markdown");
    mt__args_free(&args);
    if (!ok) return 2;
    if (o->quick) {
        if (!faces_given) o->faces = QUICK_FACES;
        if (!torus_given) o->torus_faces = QUICK_TORUS_FACES;
        if (!reps_given) o->reps = QUICK_REPS;
    }
    return 0;
}

/* ---- Processes ----------------------------------------------------------- */

/* Runs argv as a process, standard output into `capture` (size bytes, NUL
 * terminated; NULL: /dev/null), standard error kept. Returns its exit status
 * (-1 when it could not run or was killed) and the wall time from fork to
 * its end in *ms. */
static int run_process(char *const argv[], const char *stdout_path, char *capture, size_t size,
                       double *ms)
{
    int fds[2] = {-1, -1};
    if (capture && pipe(fds) != 0) return -1;
    double t0 = mt__bench_now_ms();
    pid_t pid = fork();
    if (pid < 0) {
        if (capture) {
            close(fds[0]);
            close(fds[1]);
        }
        return -1;
    }
    if (pid == 0) {
        int out = capture ? fds[1] : open(stdout_path ? stdout_path : "/dev/null", O_WRONLY);
        if (out < 0 || dup2(out, STDOUT_FILENO) < 0) _exit(127);
        if (capture) close(fds[0]);
        execv(argv[0], argv);
        _exit(127);
    }
    size_t used = 0;
    if (capture) {
        close(fds[1]);
        for (;;) {
            char sink[4096];
            char *dst = used + 1 < size ? capture + used : sink;
            size_t room = used + 1 < size ? size - 1 - used : sizeof sink;
            ssize_t k = read(fds[0], dst, room);
            if (k < 0 && errno == EINTR) continue;
            if (k <= 0) break;
            if (dst != sink) used += (size_t)k;
        }
        close(fds[0]);
        capture[used] = '\0';
    }
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return -1;
    *ms = mt__bench_now_ms() - t0;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* ---- The files --------------------------------------------------------- */

static bool files_make(const options *o, const char *dir, file_case *files, char *err,
                       size_t err_size)
{
    uint32_t n = 0;
    for (int m = 0; m < 2; m++) {
        uint64_t target = m == 0 ? o->faces : o->torus_faces;
        mt_face_list list;
        mt_status st;
        char name[48];
        if (m == 0) {
            uint32_t side = (uint32_t)floor(sqrt((double)target / 2.0));
            if (side < 1) side = 1;
            st = mt_gen_grid(side, side, true, &list);
            snprintf(name, sizeof name, "grid %ux%u", side, side);
        } else {
            uint32_t nv = (uint32_t)floor(sqrt((double)target / 8.0));
            if (nv < 3) nv = 3;
            st = mt_gen_torus(4 * nv, nv, &list);
            snprintf(name, sizeof name, "torus %ux%u", 4 * nv, nv);
        }
        if (st != MT_OK) {
            snprintf(err, err_size, "generating %s: %s", name, mt_strerror(st));
            return false;
        }
        for (int shuffled = 0; shuffled < 2; shuffled++) {
            mt_diag diag;
            if (shuffled && mt_face_list_permute(&list, o->seed, &diag) != MT_OK) {
                snprintf(err, err_size, "shuffling %s: %.200s", name, diag.message);
                mt_face_list_free(&list);
                return false;
            }
            static const struct {
                const char *name, *ext;
                mt_format format;
            } formats[] = {{"OFF", "off", MT_FORMAT_OFF},
                           {"PLY binary", "ply", MT_FORMAT_PLY_BINARY_LE},
                           {"OBJ", "obj", MT_FORMAT_OBJ}};
            for (size_t f = 0; f < sizeof formats / sizeof formats[0]; f++) {
                file_case *c = &files[n++];
                memset(c, 0, sizeof *c);
                snprintf(c->mesh, sizeof c->mesh, "%s", name);
                snprintf(c->order, sizeof c->order, "%s", shuffled ? "shuffled" : "natural");
                snprintf(c->format, sizeof c->format, "%s", formats[f].name);
                int k = snprintf(c->path, sizeof c->path, "%s/%s-%s.%s", dir,
                                 m == 0 ? "grid" : "torus", c->order, formats[f].ext);
                if (k < 0 || (size_t)k >= sizeof c->path) {
                    snprintf(err, err_size, "the directory name is too long");
                    mt_face_list_free(&list);
                    return false;
                }
                st = mt_write_file(c->path, formats[f].format, &list, &diag);
                struct stat sb;
                if (st != MT_OK || stat(c->path, &sb) != 0) {
                    snprintf(err, err_size, "writing %.200s: %.200s", c->path,
                             st != MT_OK ? diag.message : strerror(errno));
                    mt_face_list_free(&list);
                    return false;
                }
                c->bytes = (uint64_t)sb.st_size;
            }
        }
        mt_face_list_free(&list);
    }
    return true;
}

/* meshtopo's answer in this process: the counts the peer must match. */
static bool counts_make(file_case *c, char *err, size_t err_size)
{
    mt_face_list list;
    mt_diag diag;
    mt_status st = mt_read_file(c->path, MT_FORMAT_AUTO, &list, &diag);
    if (st != MT_OK) {
        snprintf(err, err_size, "%.400s", diag.message);
        return false;
    }
    mt_mesh *mesh = NULL;
    st = mt_mesh_build(&list, NULL, &mesh, &diag);
    mt_face_list_free(&list);
    if (st != MT_OK) {
        snprintf(err, err_size, "building %.200s: %.200s", c->path, diag.message);
        return false;
    }
    const mt_report *r = mt_mesh_report(mesh);
    c->verts = r->num_verts;
    c->edges = r->num_edges;
    c->faces = r->num_faces;
    c->loops = r->boundary_loops;
    c->components = r->connected_components;
    mt_mesh_destroy(mesh);
    return true;
}

/* ---- Measuring ----------------------------------------------------------- */

static double median(const double *values, uint32_t n)
{
    double copy[MT__BENCH_MAX_REPS];
    memcpy(copy, values, n * sizeof *copy);
    return mt__bench_median_of(copy, n);
}

/* The read time `meshtopo inspect FILE` prints first: "file: FILE (read in
 * X ms, ...". */
static bool printed_read_ms(const char *out, const char *path, double *ms)
{
    char head[PATH_MAX + 32];
    int n = snprintf(head, sizeof head, "file: %s (read in ", path);
    if (n < 0 || (size_t)n >= sizeof head || strncmp(out, head, (size_t)n) != 0) return false;
    char *end;
    *ms = strtod(out + n, &end);
    return end != out + n && strncmp(end, " ms", 3) == 0;
}

static bool measure(const options *o, const char *meshtopo, const char *peer, file_case *c,
                    char *err, size_t err_size)
{
    char *json_argv[] = {(char *)meshtopo, "inspect", c->path, "--json", NULL};
    char *text_argv[] = {(char *)meshtopo, "inspect", c->path, NULL};
    char *om_argv[] = {(char *)peer, c->path, NULL};
    char *om_read_argv[] = {(char *)peer, c->path, "--read-only", NULL};
    char *cat_argv[] = {"/bin/cat", c->path, NULL};
    char line[512], text_out[PATH_MAX + 512];
    double ms;
    /* warm-up, and the peer's counts against meshtopo's */
    if (run_process(json_argv, NULL, NULL, 0, &ms) != 0 ||
        run_process(text_argv, NULL, NULL, 0, &ms) != 0) {
        snprintf(err, err_size, "meshtopo inspect %.400s failed", c->path);
        return false;
    }
    c->om_ok = false;
    if (peer) {
        uint64_t v = 0, e = 0, f = 0, l = 0, k = 0;
        if (run_process(om_argv, NULL, line, sizeof line, &ms) != 0) {
            snprintf(c->om_note, sizeof c->om_note, "the OpenMesh peer failed");
        } else if (!mt__bench_field_u64(line, "verts", &v) ||
                   !mt__bench_field_u64(line, "edges", &e) ||
                   !mt__bench_field_u64(line, "faces", &f) ||
                   !mt__bench_field_u64(line, "boundary_loops", &l) ||
                   !mt__bench_field_u64(line, "components", &k)) {
            snprintf(c->om_note, sizeof c->om_note, "unexpected peer output: %.100s", line);
        } else if (v != c->verts || e != c->edges || f != c->faces || l != c->loops ||
                   k != c->components) {
            snprintf(err, err_size,
                     "%.200s: OpenMesh counts V=%llu E=%llu F=%llu loops=%llu components=%llu, "
                     "meshtopo %llu %llu %llu %llu %llu",
                     c->path, (unsigned long long)v, (unsigned long long)e, (unsigned long long)f,
                     (unsigned long long)l, (unsigned long long)k, (unsigned long long)c->verts,
                     (unsigned long long)c->edges, (unsigned long long)c->faces,
                     (unsigned long long)c->loops, (unsigned long long)c->components);
            return false;
        } else {
            c->om_ok = true;
        }
    } else {
        snprintf(c->om_note, sizeof c->om_note, "OpenMesh peer not built");
    }
    for (uint32_t r = 0; r < o->reps; r++) {
        /* whole processes: the three take turns going first */
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t which = (r + k) % 3;
            if (which == 0 && run_process(json_argv, NULL, NULL, 0, &c->json_ms[r]) != 0) {
                snprintf(err, err_size, "meshtopo inspect %.400s --json failed", c->path);
                return false;
            }
            if (which == 1 &&
                (run_process(text_argv, NULL, text_out, sizeof text_out, &c->text_ms[r]) != 0 ||
                 !printed_read_ms(text_out, c->path, &c->fresh_read_ms[r]))) {
                snprintf(err, err_size, "meshtopo inspect %.400s failed or printed no read time",
                         c->path);
                return false;
            }
            if (which == 2 && c->om_ok &&
                run_process(om_argv, NULL, line, sizeof line, &c->om_ms[r]) != 0) {
                snprintf(err, err_size, "the OpenMesh peer failed on %.400s", c->path);
                return false;
            }
        }
        /* reading alone */
        if (run_process(cat_argv, NULL, NULL, 0, &c->cat_ms[r]) != 0) {
            snprintf(err, err_size, "cat %.400s failed", c->path);
            return false;
        }
        mt_face_list list;
        mt_diag diag;
        double t0 = mt__bench_now_ms();
        mt_status st = mt_read_file(c->path, MT_FORMAT_AUTO, &list, &diag);
        c->read_ms[r] = mt__bench_now_ms() - t0;
        if (st != MT_OK) {
            snprintf(err, err_size, "%.400s", diag.message);
            return false;
        }
        mt_face_list_free(&list);
        if (c->om_ok) {
            if (run_process(om_read_argv, NULL, line, sizeof line, &ms) != 0 ||
                !mt__bench_field_double(line, "read_ms", &c->om_read_ms[r])) {
                snprintf(err, err_size, "the OpenMesh peer failed reading %.400s", c->path);
                return false;
            }
        }
    }
    return true;
}

/* ---- Printing ------------------------------------------------------------ */

static double mb_per_s(uint64_t bytes, double ms)
{
    return ms > 0 ? (double)bytes / 1e6 / (ms / 1e3) : NAN;
}

static void load_text(char *buf, size_t size)
{
    FILE *f = fopen("/proc/loadavg", "r");
    double a = 0, b = 0, c = 0;
    if (!f || fscanf(f, "%lf %lf %lf", &a, &b, &c) != 3)
        snprintf(buf, size, "unknown");
    else
        snprintf(buf, size, "%.2f %.2f %.2f (1, 5, 15 min)", a, b, c);
    if (f) fclose(f);
}

/* Both tables, and the targets missed, to out. */
static void print_tables(FILE *out, const options *o, const file_case *files, const char *load0,
                         const char *load1)
{
    char machine[256] = "unknown";
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f) {
        char line[256];
        while (fgets(line, sizeof line, f)) {
            const char *colon = strchr(line, ':');
            if (strncmp(line, "model name", 10) == 0 && colon) {
                colon++;
                while (*colon == ' ') colon++;
                snprintf(machine, sizeof machine, "%.*s", (int)strcspn(colon, "\n"), colon);
                break;
            }
        }
        fclose(f);
    }
    time_t now = time(NULL);
    char date[64];
    strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", gmtime(&now));
    fprintf(out, "- machine: %s, %ld cores online\n- date: %s\n", machine,
            sysconf(_SC_NPROCESSORS_ONLN), date);
    fprintf(out, "- load average: %s before, %s after\n- runs: %u paired, medians\n\n", load0,
            load1, o->reps);
    fprintf(out,
            "Whole processes (`meshtopo inspect FILE [--json]` against the OpenMesh peer, "
            "reading, counts, boundary loops, components):\n\n");
    fprintf(out,
            "| mesh | order | format | MB | --json ms | text ms | OpenMesh ms | OpenMesh / "
            "--json | --json / text |\n|---|---|---|--:|--:|--:|--:|--:|--:|\n");
    for (uint32_t i = 0; i < NUM_FILES; i++) {
        const file_case *c = &files[i];
        double json = median(c->json_ms, o->reps), text = median(c->text_ms, o->reps);
        fprintf(out, "| %s | %s | %s | %.1f | %.1f | %.1f | ", c->mesh, c->order, c->format,
                (double)c->bytes / 1e6, json, text);
        if (c->om_ok) {
            double om = median(c->om_ms, o->reps);
            fprintf(out, "%.1f | %.2fx | %.2f |\n", om, om / json, json / text);
        } else {
            fprintf(out, "- | - | %.2f |\n", json / text);
        }
    }
    fprintf(out,
            "\nReading alone (meshtopo, fresh: the read time `meshtopo inspect FILE` prints; "
            "meshtopo, here: mt_read_file in the benchmark's process; cat: `cat FILE > "
            "/dev/null`, a whole process; OpenMesh: IO::read_mesh timed in its process). "
            "The targets are judged on the fresh processes:\n\n");
    fprintf(out,
            "| mesh | order | format | MB | cat ms (MB/s) | meshtopo, fresh ms (MB/s) | "
            "meshtopo, here ms (MB/s) | OpenMesh ms (MB/s) | OpenMesh / meshtopo, fresh "
            "|\n|---|---|---|--:|--:|--:|--:|--:|--:|\n");
    for (uint32_t i = 0; i < NUM_FILES; i++) {
        const file_case *c = &files[i];
        double cat = median(c->cat_ms, o->reps), rd = median(c->fresh_read_ms, o->reps);
        double here = median(c->read_ms, o->reps);
        fprintf(out, "| %s | %s | %s | %.1f | %.1f (%.0f) | %.1f (%.0f) | %.1f (%.0f) | ", c->mesh,
                c->order, c->format, (double)c->bytes / 1e6, cat, mb_per_s(c->bytes, cat), rd,
                mb_per_s(c->bytes, rd), here, mb_per_s(c->bytes, here));
        if (c->om_ok) {
            double om = median(c->om_read_ms, o->reps);
            fprintf(out, "%.1f (%.0f) | %.2fx |\n", om, mb_per_s(c->bytes, om), om / rd);
        } else {
            fprintf(out, "- | - |\n");
        }
    }
    fprintf(out,
            "\nTargets: OpenMesh / --json >= %.0fx, --json / text <= %.1f, text (OFF, OBJ) read "
            ">= %.0f MB/s, OpenMesh's reader / meshtopo's >= %.0fx.\n",
            TARGET_VS_OPENMESH, TARGET_JSON_OVER_TEXT, TARGET_TEXT_MB_S, TARGET_READ_VS_OPENMESH);
    for (uint32_t i = 0; i < NUM_FILES; i++) {
        const file_case *c = &files[i];
        double json = median(c->json_ms, o->reps), text = median(c->text_ms, o->reps);
        double rd = median(c->fresh_read_ms, o->reps);
        char what[128];
        snprintf(what, sizeof what, "%s %s %s", c->mesh, c->order, c->format);
        if (json / text > TARGET_JSON_OVER_TEXT)
            fprintf(out, "- missed: %s: --json / text %.2f\n", what, json / text);
        if (strcmp(c->format, "PLY binary") != 0 && mb_per_s(c->bytes, rd) < TARGET_TEXT_MB_S)
            fprintf(out, "- missed: %s: read at %.0f MB/s\n", what, mb_per_s(c->bytes, rd));
        if (!c->om_ok) continue;
        double om = median(c->om_ms, o->reps), om_read = median(c->om_read_ms, o->reps);
        if (om / json < TARGET_VS_OPENMESH)
            fprintf(out, "- missed: %s: OpenMesh / --json %.2fx\n", what, om / json);
        if (om_read / rd < TARGET_READ_VS_OPENMESH)
            fprintf(out, "- missed: %s: OpenMesh's reader / meshtopo's %.2fx\n", what,
                    om_read / rd);
    }
    for (uint32_t i = 0; i < NUM_FILES; i++)
        if (!files[i].om_ok && files[i].om_note[0])
            fprintf(out, "- %s %s %s: %s\n", files[i].mesh, files[i].order, files[i].format,
                    files[i].om_note);
}

/* ---- The command --------------------------------------------------------- */

static bool find_meshtopo(const options *o, char *out, size_t size)
{
    if (o->meshtopo) {
        snprintf(out, size, "%s", o->meshtopo);
        return access(out, X_OK) == 0;
    }
    if (mt__bench_peer_find(NULL, "meshtopo", out, size)) return true;
#ifdef MESHTOPO_BENCH_MESHTOPO_BUILD_PATH
    snprintf(out, size, "%s", MESHTOPO_BENCH_MESHTOPO_BUILD_PATH);
    if (access(out, X_OK) == 0) return true;
#endif
    return false;
}

int mt__bench_inspect_command(int argc, char **argv)
{
    options o;
    int parsed = parse_options(argc, argv, &o);
    if (parsed != 0) return mt__bench_usage_exit(parsed, usage);
    signal(SIGPIPE, SIG_IGN);
    char meshtopo[PATH_MAX], peer[PATH_MAX];
    if (!find_meshtopo(&o, meshtopo, sizeof meshtopo)) {
        fprintf(stderr, "meshtopo-bench inspect: cannot find the meshtopo program (--meshtopo)\n");
        return 1;
    }
    bool have_peer = mt__bench_peer_find(o.peer_dir, PEER_NAME, peer, sizeof peer);
    const char *parent = o.tmp_parent ? o.tmp_parent : getenv("TMPDIR");
    char dir[PATH_MAX];
    int k = snprintf(dir, sizeof dir, "%s/meshtopo-bench-inspect-XXXXXX",
                     parent && *parent ? parent : "/tmp");
    if (k < 0 || (size_t)k >= sizeof dir || !mkdtemp(dir)) {
        fprintf(stderr, "meshtopo-bench inspect: cannot create a directory in %s: %s\n",
                parent ? parent : "/tmp", strerror(errno));
        return 1;
    }
    file_case *files = calloc(NUM_FILES, sizeof *files);
    char err[512] = "";
    char load0[64], load1[64];
    load_text(load0, sizeof load0);
    bool ok = files && files_make(&o, dir, files, err, sizeof err);
    for (uint32_t i = 0; ok && i < NUM_FILES; i++) {
        fprintf(stderr, "meshtopo-bench inspect: %s %s %s (%.1f MB)\n", files[i].mesh,
                files[i].order, files[i].format, (double)files[i].bytes / 1e6);
        ok = counts_make(&files[i], err, sizeof err) &&
             measure(&o, meshtopo, have_peer ? peer : NULL, &files[i], err, sizeof err);
    }
    load_text(load1, sizeof load1);
    if (ok) {
        print_tables(stdout, &o, files, load0, load1);
        if (o.md_path) {
            FILE *md = fopen(o.md_path, "w");
            if (!md) {
                snprintf(err, sizeof err, "cannot write %.300s: %s", o.md_path, strerror(errno));
                ok = false;
            } else {
                print_tables(md, &o, files, load0, load1);
                if (fclose(md) != 0) ok = false;
            }
        }
    }
    if (!ok) fprintf(stderr, "meshtopo-bench inspect: %s\n", err[0] ? err : "out of memory");
    for (uint32_t i = 0; files && i < NUM_FILES; i++)
        if (files[i].path[0]) unlink(files[i].path);
    rmdir(dir);
    free(files);
    return ok ? 0 : 1;
}
