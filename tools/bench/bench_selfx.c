/* `meshtopo-bench selfx`: mt_mesh_self_intersections against CGAL's
 * Polygon_mesh_processing::self_intersections (Sequential_tag, and
 * Parallel_tag when the peer has TBB) on the planted meshes of selfx_input.c,
 * each in its natural order and shuffled (mt_face_list_permute). Both sides
 * get the same triangles: CGAL through the raw file of bench_input.c, read
 * by its peer process (selfx_cgal.c). Building the meshes is not timed. Each
 * side runs once untimed, then the repetitions interleave meshtopo and CGAL
 * (the first of each round rotating); medians are printed. Every run of both
 * must give the same sorted pairs (count and hash); when they differ the
 * pairs only one side found are printed with their faces' coordinates and
 * the exit status is 1. Then the rate of mt_mesh_nonsimple_faces over every
 * face of a polygon mesh. */
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_selfx.h"
#include "meshtopo/mesh.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"

#define DEFAULT_FACES 1000000u
#define QUICK_FACES 20000u
#define DEFAULT_REPS 5u
#define QUICK_REPS 3u
#define MIN_FACES 2000u
#define MAX_FACES 100000000u
#define DEFAULT_SEED 0x6d657368746f706full
#define TARGET_RATIO 3.0
#define TARGET_MIN_FACES 100000u
#define PEER_NAME "meshtopo-bench-cgal-selfx"
#define MAX_DIFFERENCES_SHOWN 8

typedef struct options {
    uint64_t faces, seed;
    uint32_t reps;
    bool quick;
    int only; /* --mesh: the one planted mesh to measure (selfx_input.c's number), or -1 */
    const char *peer_dir, *tmp_parent;
} options;

/* The timed rows of a case. */
enum { ROW_MESHTOPO, ROW_CGAL, ROW_CGAL_PARALLEL, NUM_ROWS };
static const char *const row_names[NUM_ROWS] = {"meshtopo", "CGAL", "CGAL parallel"};

typedef enum row_state { ROW_NOT_RUN, ROW_OK, ROW_FAILED } row_state;

typedef struct row {
    row_state state;
    double ms[MT__BENCH_MAX_REPS];
    uint32_t num_ms;
    uint64_t pairs, hash;  /* of the warm-up run */
    bool consistent;       /* every timed run gave the warm-up's pairs */
    uint64_t cgal_written; /* CGAL: pairs it wrote in the warm-up (duplicates included) */
} row;

typedef struct selfx_case {
    char mesh[64];
    const char *order;
    uint32_t triangles;
    row rows[NUM_ROWS];
    bool agree; /* meshtopo and CGAL (each tag run) found the same pairs */
} selfx_case;

/* What the run learnt about the peer, for the notes under the table. */
typedef struct peer_info {
    bool found, parallel;
    char version[32];
} peer_info;

static void usage(FILE *out)
{
    fprintf(out,
            "usage: meshtopo-bench selfx [options]\n"
            "Times mt_mesh_self_intersections and CGAL's Polygon_mesh_processing::\n"
            "self_intersections (a peer process, Sequential_tag; Parallel_tag too when CGAL\n"
            "has TBB) on a grid and a closed torus of about --faces triangles each, with a few\n"
            "hundred self-intersections planted, in natural order and shuffled; checks that\n"
            "both find the same face pairs; then the rate of mt_mesh_nonsimple_faces on the\n"
            "dual of an icosphere (pentagons and hexagons).\n"
            "\n"
            "  --faces N       triangles per mesh (default %u)\n"
            "  --reps N        timed repetitions after one warm-up (default %u, at most %u)\n"
            "  --seed N        seed of the shuffle and of the planted offsets\n"
            "  --mesh NAME     only the grid or only the torus (default: both)\n"
            "  --quick         %u triangles, %u repetitions (a smoke test)\n"
            "  --peer-dir DIR  where %s is (default: next to this program)\n"
            "  --tmpdir DIR    where the input files for the peer go ($TMPDIR or /tmp)\n"
            "  --help          this text\n"
            "\n"
            "Exit status: 0 when every measurement ran and both libraries agree (a missed\n"
            "target included; a peer that was not built is skipped), 1 when one failed or\n"
            "they disagree, 2 on a usage error.\n",
            DEFAULT_FACES, DEFAULT_REPS, MT__BENCH_MAX_REPS, QUICK_FACES, QUICK_REPS, PEER_NAME);
}

/* Returns 0, 1 (--help) or 2 (usage error, printed). */
static int parse_options(int argc, char **argv, options *o)
{
    /* The options usage() describes. */
    static const mt__option option_table[] = {
        {"quick", NULL, NULL},   {"faces", "N", NULL},   {"reps", "N", NULL},
        {"seed", "N", NULL},     {"mesh", "NAME", NULL}, {"peer-dir", "DIR", NULL},
        {"tmpdir", "DIR", NULL},
    };
    static const char program[] = "meshtopo-bench selfx";
    memset(o, 0, sizeof *o);
    o->faces = DEFAULT_FACES;
    o->reps = DEFAULT_REPS;
    o->seed = DEFAULT_SEED;
    o->only = -1;
    mt__args args;
    int read =
        mt__bench_args_read(program, option_table, sizeof option_table / sizeof option_table[0],
                            argc - 1, argv + 1, &args);
    if (read != 0) return read;
    bool faces_given = false, reps_given = false;
    bool ok =
        mt__bench_arg_u64(&args, program, "faces", MIN_FACES, MAX_FACES, &o->faces, &faces_given) &&
        mt__bench_arg_u32(&args, program, "reps", 1, MT__BENCH_MAX_REPS, &o->reps, &reps_given) &&
        mt__bench_arg_u64(&args, program, "seed", 0, UINT64_MAX, &o->seed, NULL);
    const char *mesh = mt__args_value(&args, "mesh");
    if (ok && mesh) {
        o->only = strcmp(mesh, "grid") == 0 ? 0 : strcmp(mesh, "torus") == 0 ? 1 : -1;
        if (o->only < 0) {
            fprintf(stderr, "%s: --mesh: bad value '%s' (grid or torus)\n", program, mesh);
            ok = false;
        }
    }
    o->quick = mt__args_flag(&args, "quick");
    o->peer_dir = mt__args_value(&args, "peer-dir");
    o->tmp_parent = mt__args_value(&args, "tmpdir");
    mt__args_free(&args);
    if (!ok) return 2;
    if (o->quick && !faces_given) o->faces = QUICK_FACES;
    if (o->quick && !reps_given) o->reps = QUICK_REPS;
    return 0;
}

uint64_t mt__selfx_pairs_hash(const mt_face_pair *pairs, size_t count)
{
    uint64_t h = 0;
    for (size_t i = 0; i < count; i++) {
        uint64_t x = h ^ ((uint64_t)pairs[i].a << 32 | pairs[i].b);
        /* splitmix64's finaliser */
        x += 0x9e3779b97f4a7c15ull;
        x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
        x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
        h = x ^ (x >> 31);
    }
    return h;
}

static double row_median(const row *r)
{
    double values[MT__BENCH_MAX_REPS];
    memcpy(values, r->ms, r->num_ms * sizeof *values);
    return mt__bench_median_of(values, r->num_ms);
}

/* ---- meshtopo ------------------------------------------------------------- */

/* meshtopo's side of a case: the built mesh and a buffer for its pairs,
 * sized by the warm-up so that a timed call fills it in one pass. */
typedef struct meshtopo_side {
    mt_mesh *mesh;
    mt_face_pair *pairs;
    size_t capacity, count;
} meshtopo_side;

/* One call. When the pairs did not fit (the warm-up: the first call has no
 * buffer and only counts them), the buffer grows to the count and the call
 * is made again. */
static bool meshtopo_run(meshtopo_side *s, double *out_ms, char *err, size_t err_size)
{
    for (int attempt = 0; attempt < 2; attempt++) {
        mt_diag diag;
        mt_diag_clear(&diag);
        double t0 = mt__bench_now_ms();
        mt_status st = mt_mesh_self_intersections(s->mesh, s->pairs, s->capacity, &s->count, &diag);
        *out_ms = mt__bench_now_ms() - t0;
        bool fits = s->count <= s->capacity;
        if (st == MT_OK && fits) return true;
        if ((st != MT_OK && st != MT_ERR_BUFFER_TOO_SMALL) || attempt > 0) {
            snprintf(err, err_size, "mt_mesh_self_intersections: %s %.400s", mt_strerror(st),
                     diag.message);
            return false;
        }
        mt_face_pair *grown = realloc(s->pairs, s->count * sizeof *grown);
        if (!grown) {
            snprintf(err, err_size, "out of memory for %zu pairs", s->count);
            return false;
        }
        s->pairs = grown;
        s->capacity = s->count;
    }
    return false;
}

/* The documented order: a < b, ascending (a, b), each pair once. */
static bool pairs_in_order(const mt_face_pair *p, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (p[i].a >= p[i].b) return false;
        if (i && (p[i - 1].a > p[i].a || (p[i - 1].a == p[i].a && p[i - 1].b >= p[i].b))) {
            return false;
        }
    }
    return true;
}

/* ---- disagreement --------------------------------------------------------- */

static void face_print(FILE *out, const mt_face_list *list, uint32_t f)
{
    if (f >= list->num_faces || list->face_sizes[f] != 3) {
        fprintf(out, "      face %u: not a triangle of the input\n", f);
        return;
    }
    const uint32_t *fv = list->face_indices + 3 * (size_t)f;
    fprintf(out, "      face %u: vertices %u %u %u\n", f, fv[0], fv[1], fv[2]);
    for (int k = 0; k < 3; k++) {
        const double *p = list->positions + 3 * (size_t)fv[k];
        fprintf(out, "        v%u = (%.17g, %.17g, %.17g)\n", fv[k], p[0], p[1], p[2]);
    }
}

static int pair_compare(const mt_face_pair *x, const mt_face_pair *y)
{
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    if (x->b != y->b) return x->b < y->b ? -1 : 1;
    return 0;
}

/* Prints the pairs only one side found (both lists sorted), up to
 * MAX_DIFFERENCES_SHOWN of each, with the faces' corners. */
static void differences_print(FILE *out, const mt_face_list *list, const mt_face_pair *mine,
                              size_t num_mine, const mt_face_pair *theirs, size_t num_theirs,
                              const char *other)
{
    size_t i = 0, j = 0, only_mine = 0, only_theirs = 0;
    while (i < num_mine || j < num_theirs) {
        int c = i == num_mine ? 1 : j == num_theirs ? -1 : pair_compare(&mine[i], &theirs[j]);
        if (c == 0) {
            i++, j++;
            continue;
        }
        const mt_face_pair *p = c < 0 ? &mine[i++] : &theirs[j++];
        size_t *n = c < 0 ? &only_mine : &only_theirs;
        if (++*n <= MAX_DIFFERENCES_SHOWN) {
            fprintf(out, "    only %s: faces %u and %u\n", c < 0 ? "meshtopo" : other, p->a, p->b);
            face_print(out, list, p->a);
            face_print(out, list, p->b);
        }
    }
    fprintf(out, "    %zu pairs only meshtopo found, %zu only %s found\n", only_mine, only_theirs,
            other);
}

/* ---- one case ------------------------------------------------------------- */

/* Writes the raw file, starts the peer on it (when it was found) and
 * removes the file once the peer has read it. */
static bool peer_open(const options *o, const char *dir, const mt_face_list *list, peer_info *info,
                      mt__selfx_cgal *peer, char *err, size_t err_size)
{
    char exe[PATH_MAX], path[PATH_MAX];
    if (!mt__bench_peer_find(o->peer_dir, PEER_NAME, exe, sizeof exe)) return true;
    info->found = true;
    int n = snprintf(path, sizeof path, "%s/selfx.mtbench", dir);
    if (n < 0 || (size_t)n >= sizeof path) {
        snprintf(err, err_size, "temporary directory path too long: %.400s", dir);
        return false;
    }
    if (!mt__bench_input_write(list, path, err, err_size)) return false;
    bool ok = mt__selfx_cgal_start(peer, exe, path, err, err_size);
    remove(path);
    if (!ok) return false;
    info->parallel = peer->parallel;
    snprintf(info->version, sizeof info->version, "%s", peer->version);
    if (peer->failed_faces != 0 || peer->faces != list->num_faces) {
        snprintf(err, err_size, "the CGAL peer took %" PRIu64 " of %u faces", peer->faces,
                 list->num_faces);
        return false;
    }
    return true;
}

static void row_fail(selfx_case *c, int k, const char *err)
{
    c->rows[k].state = ROW_FAILED;
    fprintf(stderr, "meshtopo-bench selfx: %s on %s, %s: %s\n", row_names[k], c->mesh, c->order,
            err);
}

/* One run of row k: its time and whether it found the warm-up's pairs. */
static bool row_run(selfx_case *c, int k, meshtopo_side *mine, mt__selfx_cgal *peer, bool warm_up)
{
    row *r = &c->rows[k];
    char err[512];
    double ms;
    uint64_t pairs, hash;
    if (k == ROW_MESHTOPO) {
        if (!meshtopo_run(mine, &ms, err, sizeof err)) {
            row_fail(c, k, err);
            return false;
        }
        if (!pairs_in_order(mine->pairs, mine->count)) {
            row_fail(c, k, "its pairs are not in ascending (a, b) order with a < b");
            return false;
        }
        pairs = mine->count;
        hash = mt__selfx_pairs_hash(mine->pairs, mine->count);
    } else {
        mt__selfx_answer answer;
        if (!mt__selfx_cgal_run(peer, k == ROW_CGAL_PARALLEL, &answer, err, sizeof err)) {
            row_fail(c, k, err);
            return false;
        }
        ms = answer.ms;
        pairs = answer.pairs;
        hash = answer.hash;
        if (warm_up) r->cgal_written = answer.reported;
    }
    if (warm_up) {
        r->state = ROW_OK;
        r->pairs = pairs;
        r->hash = hash;
        r->consistent = true;
    } else {
        r->ms[r->num_ms++] = ms;
        if (pairs != r->pairs || hash != r->hash) r->consistent = false;
    }
    return true;
}

/* Compares the rows' pairs; on a difference fetches CGAL's list of its
 * last run and prints what differs. */
static void case_compare(selfx_case *c, const mt_face_list *list, const meshtopo_side *mine,
                         mt__selfx_cgal *peer)
{
    const row *m = &c->rows[ROW_MESHTOPO];
    c->agree = m->state == ROW_OK && m->consistent;
    for (int k = ROW_CGAL; k < NUM_ROWS; k++) {
        const row *r = &c->rows[k];
        if (r->state != ROW_OK) continue;
        if (r->consistent && m->state == ROW_OK && r->pairs == m->pairs && r->hash == m->hash) {
            continue;
        }
        c->agree = false;
        printf("check %s, %s: DISAGREEMENT: meshtopo %" PRIu64 " pairs (hash %016" PRIx64
               ")%s, %s %" PRIu64 " pairs (hash %016" PRIx64 ")%s\n",
               c->mesh, c->order, m->pairs, m->hash,
               m->consistent ? "" : " (differing between runs)", row_names[k], r->pairs, r->hash,
               r->consistent ? "" : " (differing between runs)");
        mt_face_pair *theirs = NULL;
        size_t num_theirs = 0;
        char err[512];
        if (m->state != ROW_OK) continue;
        /* One more run of this row, so that the listed pairs are its own. */
        mt__selfx_answer again;
        if (!mt__selfx_cgal_run(peer, k == ROW_CGAL_PARALLEL, &again, err, sizeof err) ||
            !mt__selfx_cgal_list(peer, &theirs, &num_theirs, err, sizeof err)) {
            printf("    cannot fetch CGAL's pairs: %s\n", err);
            continue;
        }
        differences_print(stdout, list, mine->pairs, mine->count, theirs, num_theirs, row_names[k]);
        free(theirs);
    }
    const row *cgal = &c->rows[ROW_CGAL];
    if (c->agree && cgal->state == ROW_OK) {
        printf("check %s, %s: meshtopo and CGAL agree: %" PRIu64 " pairs (hash %016" PRIx64 ")\n",
               c->mesh, c->order, m->pairs, m->hash);
        if (cgal->cgal_written != cgal->pairs) {
            printf("    (CGAL wrote %" PRIu64 " pairs, some of them more than once)\n",
                   cgal->cgal_written);
        }
    } else if (c->agree) {
        printf("check %s, %s: only meshtopo measured: %" PRIu64 " pairs, the same in every run\n",
               c->mesh, c->order, m->pairs);
    } else if (m->state == ROW_OK && !m->consistent) {
        printf("check %s, %s: meshtopo's runs gave different pairs\n", c->mesh, c->order);
    }
}

/* Measures one case: the peer reads the list, meshtopo builds it, one
 * untimed run each, then the interleaved repetitions. */
static void case_run(const options *o, const char *dir, const mt_face_list *list, selfx_case *c,
                     peer_info *info)
{
    c->triangles = list->num_faces;
    mt__selfx_cgal peer;
    memset(&peer, 0, sizeof peer);
    char err[512];
    fprintf(stderr, "meshtopo-bench selfx: %s, %s: building\n", c->mesh, c->order);
    if (!peer_open(o, dir, list, info, &peer, err, sizeof err)) row_fail(c, ROW_CGAL, err);
    meshtopo_side mine;
    memset(&mine, 0, sizeof mine);
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_mesh_build(list, NULL, &mine.mesh, &diag);
    if (st != MT_OK) {
        snprintf(err, sizeof err, "mt_mesh_build: %s %.400s", mt_strerror(st), diag.message);
        row_fail(c, ROW_MESHTOPO, err);
    } else if (mt_mesh_report(mine.mesh)->num_faces_valid != list->num_faces) {
        row_fail(c, ROW_MESHTOPO, "the build rejected faces");
    }

    bool active[NUM_ROWS] = {
        c->rows[ROW_MESHTOPO].state != ROW_FAILED,
        peer.started && c->rows[ROW_CGAL].state != ROW_FAILED,
        peer.started && peer.parallel && c->rows[ROW_CGAL].state != ROW_FAILED};
    fprintf(stderr, "meshtopo-bench selfx: %s, %s: warming up\n", c->mesh, c->order);
    for (int k = 0; k < NUM_ROWS; k++) {
        if (active[k]) active[k] = row_run(c, k, &mine, &peer, true);
    }
    for (uint32_t rep = 0; rep < o->reps; rep++) {
        fprintf(stderr, "meshtopo-bench selfx: %s, %s: repetition %u of %u\n", c->mesh, c->order,
                rep + 1, o->reps);
        for (int j = 0; j < NUM_ROWS; j++) {
            int k = (int)((j + rep) % NUM_ROWS);
            if (active[k]) active[k] = row_run(c, k, &mine, &peer, false);
        }
    }
    case_compare(c, list, &mine, &peer);
    mt__selfx_cgal_stop(&peer);
    mt_mesh_destroy(mine.mesh);
    free(mine.pairs);
}

/* ---- the table ------------------------------------------------------------ */

static const char *count_text(char *buf, size_t size, uint64_t x)
{
    char digits[32];
    int n = snprintf(digits, sizeof digits, "%" PRIu64, x);
    size_t at = 0;
    for (int i = 0; i < n && at + 2 < size; i++) {
        if (i && (n - i) % 3 == 0) buf[at++] = ',';
        buf[at++] = digits[i];
    }
    buf[at] = '\0';
    return buf;
}

static double row_ms(const selfx_case *c, int k)
{
    const row *r = &c->rows[k];
    return r->state == ROW_OK && r->num_ms ? row_median(r) : NAN;
}

/* Prints the table and the target line; true when the target was met on
 * every case it applies to. */
static bool table_print(const options *o, const selfx_case *cases, uint32_t num_cases,
                        const peer_info *info)
{
    char cgal[64] = "no CGAL";
    if (info->found)
        snprintf(cgal, sizeof cgal, "CGAL %s Sequential_tag on one core", info->version);
    printf(
        "\nmedian of %u repetitions after one warm-up, building excluded; meshtopo on its "
        "automatic thread count (%ld cores online), %s; ratio: CGAL's median over "
        "meshtopo's (above 1: meshtopo is faster)\n\n",
        o->reps, sysconf(_SC_NPROCESSORS_ONLN), cgal);
    bool parallel = info->parallel;
    printf("| input | order | triangles | pairs | meshtopo ms | CGAL ms | ratio |%s\n",
           parallel ? " CGAL parallel ms | ratio |" : "");
    printf("|---|---|--:|--:|--:|--:|--:|%s\n", parallel ? "--:|--:|" : "");
    bool met = true, judged = false;
    double lowest = INFINITY;
    for (uint32_t i = 0; i < num_cases; i++) {
        const selfx_case *c = &cases[i];
        char tri[32], pairs[32], a[32], b[32], ratio[32], pa[32], pratio[32];
        double mt_ms = row_ms(c, ROW_MESHTOPO), cg_ms = row_ms(c, ROW_CGAL);
        double r = cg_ms / mt_ms;
        const row *m = &c->rows[ROW_MESHTOPO];
        printf("| %s | %s | %s | %s | %s | %s | %s |", c->mesh, c->order,
               count_text(tri, sizeof tri, c->triangles),
               m->state == ROW_OK ? count_text(pairs, sizeof pairs, m->pairs) : "-",
               mt__bench_ms(a, sizeof a, mt_ms), mt__bench_ms(b, sizeof b, cg_ms),
               isnan(r) ? "-" : (snprintf(ratio, sizeof ratio, "%.1fx", r), ratio));
        if (parallel) {
            double p_ms = row_ms(c, ROW_CGAL_PARALLEL), pr = p_ms / mt_ms;
            printf(" %s | %s |", mt__bench_ms(pa, sizeof pa, p_ms),
                   isnan(pr) ? "-" : (snprintf(pratio, sizeof pratio, "%.1fx", pr), pratio));
        }
        printf("\n");
        if (c->triangles >= TARGET_MIN_FACES) {
            judged = true;
            if (isnan(r) || r < TARGET_RATIO) met = false;
            if (!isnan(r) && r < lowest) lowest = r;
        }
    }
    printf("\n");
    if (!info->found) {
        printf("CGAL: %s not found (built only when CGAL is installed): meshtopo alone\n",
               PEER_NAME);
    } else if (!parallel) {
        printf(
            "CGAL Parallel_tag: not measured, the CGAL peer was built without TBB "
            "(CGAL_LINKED_WITH_TBB unset: no TBB development files found)\n");
    }
    if (!judged || !info->found) {
        printf("target: meshtopo at least %.0fx faster than CGAL sequential: not judged (%s)\n",
               TARGET_RATIO, info->found ? "every input under 100,000 triangles" : "no CGAL");
        return true;
    }
    char low[32];
    printf(
        "target: meshtopo at least %.0fx faster than CGAL sequential on every input of "
        "100,000 triangles or more: %s (lowest ratio %s)\n",
        TARGET_RATIO, met ? "met" : "MISSED",
        isinf(lowest) ? "-" : (snprintf(low, sizeof low, "%.1fx", lowest), low));
    return met;
}

/* ---- mt_mesh_nonsimple_faces ---------------------------------------------- */

static bool nonsimple_rate(const options *o)
{
    mt_mesh *mesh = NULL;
    char name[64], err[512];
    if (!mt__selfx_polygon_mesh_make(o->faces, &mesh, name, sizeof name, err, sizeof err)) {
        fprintf(stderr, "meshtopo-bench selfx: %s\n", err);
        return false;
    }
    /* Sides: the sum of the face sizes (every face of the dual is kept). */
    uint32_t faces = mt_mesh_num_faces(mesh);
    uint64_t sides = 0;
    for (uint32_t f = 0; f < faces; f++) {
        size_t n = 0;
        if (mt_face_verts(mesh, f, NULL, 0, &n) == MT_OK) sides += n;
    }
    mt_face_shape *shapes = malloc(((size_t)faces + 1) * sizeof *shapes);
    double ms[MT__BENCH_MAX_REPS];
    size_t found = 0;
    bool ok = shapes != NULL;
    for (uint32_t rep = 0; ok && rep <= o->reps; rep++) {
        mt_diag diag;
        mt_diag_clear(&diag);
        size_t count = 0;
        double t0 = mt__bench_now_ms();
        mt_status st = mt_mesh_nonsimple_faces(mesh, shapes, (size_t)faces + 1, &count, &diag);
        double t = mt__bench_now_ms() - t0;
        if (st != MT_OK) {
            fprintf(stderr, "meshtopo-bench selfx: mt_mesh_nonsimple_faces: %s %s\n",
                    mt_strerror(st), diag.message);
            ok = false;
        } else if (rep == 0) {
            found = count;
        } else {
            ms[rep - 1] = t;
            if (count != found) {
                fprintf(stderr,
                        "meshtopo-bench selfx: mt_mesh_nonsimple_faces found %zu, then "
                        "%zu faces\n",
                        found, count);
                ok = false;
            }
        }
    }
    if (ok) {
        double median = mt__bench_median_of(ms, o->reps);
        char f[32], s[32], m[32], fr[32], sr[32];
        printf(
            "mt_mesh_nonsimple_faces over every face of the %s: %s faces, %s sides, median "
            "%s ms of %u: %s faces/s, %s sides/s (%zu not simple)\n",
            name, count_text(f, sizeof f, faces), count_text(s, sizeof s, sides),
            mt__bench_ms(m, sizeof m, median), o->reps,
            mt__bench_rate(fr, sizeof fr, faces / (median * 1e-3)),
            mt__bench_rate(sr, sizeof sr, (double)sides / (median * 1e-3)), found);
    }
    free(shapes);
    mt_mesh_destroy(mesh);
    return ok;
}

/* ---- the command ---------------------------------------------------------- */

static bool tmpdir_make(const options *o, char *dir, size_t size)
{
    const char *parent = o->tmp_parent;
    if (!parent) parent = getenv("TMPDIR");
    if (!parent || !*parent) parent = "/tmp";
    int n = snprintf(dir, size, "%s/meshtopo-bench-selfx-XXXXXX", parent);
    if (n < 0 || (size_t)n >= size || !mkdtemp(dir)) {
        fprintf(stderr, "meshtopo-bench selfx: cannot create a directory in %s: %s\n", parent,
                n < 0 || (size_t)n >= size ? "path too long" : strerror(errno));
        return false;
    }
    return true;
}

int mt__bench_selfx_command(int argc, char **argv)
{
    options o;
    int parsed = parse_options(argc, argv, &o);
    if (parsed != 0) return mt__bench_usage_exit(parsed, usage);
    signal(SIGPIPE, SIG_IGN); /* a dead peer is reported through its pipe */
    char dir[PATH_MAX];
    if (!tmpdir_make(&o, dir, sizeof dir)) return 1;

    selfx_case cases[2 * MT__SELFX_NUM_MESHES];
    memset(cases, 0, sizeof cases);
    peer_info info;
    memset(&info, 0, sizeof info);
    uint32_t num_cases = 0;
    int exit_code = 0;
    for (uint32_t m = 0; m < MT__SELFX_NUM_MESHES; m++) {
        if (o.only >= 0 && m != (uint32_t)o.only) continue;
        mt_face_list list;
        char name[64], err[512];
        if (!mt__selfx_mesh_make(m, o.faces, o.seed, &list, name, sizeof name, err, sizeof err)) {
            fprintf(stderr, "meshtopo-bench selfx: %s\n", err);
            exit_code = 1;
            continue;
        }
        /* The natural order, then the same list shuffled in place. */
        for (int order = 0; order < 2; order++) {
            selfx_case *c = &cases[num_cases++];
            snprintf(c->mesh, sizeof c->mesh, "%s", name);
            c->order = order ? "shuffled" : "natural";
            if (order) {
                mt_diag diag;
                mt_diag_clear(&diag);
                if (mt_face_list_permute(&list, o.seed, &diag) != MT_OK) {
                    fprintf(stderr, "meshtopo-bench selfx: mt_face_list_permute: %s\n",
                            diag.message);
                    row_fail(c, ROW_MESHTOPO, "cannot shuffle");
                    continue;
                }
            }
            case_run(&o, dir, &list, c, &info);
        }
        mt_face_list_free(&list);
    }
    rmdir(dir);
    for (uint32_t i = 0; i < num_cases; i++) {
        for (int k = 0; k < NUM_ROWS; k++) {
            if (cases[i].rows[k].state == ROW_FAILED) exit_code = 1;
        }
        if (!cases[i].agree) exit_code = 1;
    }
    table_print(&o, cases, num_cases, &info);
    printf("\n");
    if (!nonsimple_rate(&o)) exit_code = 1;
    return exit_code;
}
