/* `meshtopo-bench map`: an mt_map of about --faces triangles (map_surface.h:
 * a wavy height field in 4,050-triangle blocks, seams duplicated) built block
 * by block, then --steps steps each replacing 1 % of the blocks; timed against
 * a full mt_mesh_build of the welded union and against OpenMesh and CGAL
 * Surface_mesh doing the same steps (peer_map.cpp), with the map's memory.
 * At the end the map is compared with a rebuild of its union. */
#include <inttypes.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"
#include "bench_map.h"
#include "map_surface.h"
#include "meshtopo/map.h"
#include "meshtopo/mesh.h"
#include "meshtopo/report.h"

#define PROGRAM "meshtopo-bench map"
#define DEFAULT_FACES 4000000u
#define QUICK_FACES 40000u
#define MIN_FACES 4000u
#define MAX_FACES 100000000u
#define DEFAULT_STEPS 200u
#define QUICK_STEPS 20u
#define MAX_STEPS 100000u
#define BUILD_REPS 3u
#define QUICK_BUILD_REPS 1u
#define BLOCK_CELLS 45u /* 2 * 45^2 = 4,050 triangles a block */
#define VOXEL 0.05
#define DEFAULT_SEED 0x6d657368746f706full
#define TARGET_STEP_RATIO 0.05
#define TARGET_PUT_MS 2.0
#define TARGET_MEMORY_RATIO 1.1
#define TARGET_SPEEDUP 3.0

static const char *const peer_names[2] = {"meshtopo-bench-openmesh-map", "meshtopo-bench-cgal-map"};
static const char *const peer_labels[2] = {"OpenMesh", "CGAL Surface_mesh"};

typedef struct options {
    uint64_t faces, seed;
    uint32_t steps;
    bool quick, no_peers;
    const char *peer_dir;
} options;

/* What a peer measured. */
typedef struct peer_result {
    bool found, ok;
    double first_ms, step_ms, mean_ms; /* step_ms: median; mean_ms: garbage collections included */
    uint64_t faces, verts, collections;
} peer_result;

static void usage(FILE *out)
{
    fprintf(out,
            "usage: meshtopo-bench map [options]\n"
            "Builds an mt_map of a TSDF-like surface (a wavy height field) of about --faces\n"
            "triangles in blocks of %u triangles, seam vertices duplicated per block, then\n"
            "runs --steps steps each replacing 1 %% of the blocks with changed versions (their\n"
            "interior vertices moved along z). Times the first build, a full mt_mesh_build of\n"
            "the welded union, the steps and single block puts, the map's memory, and the\n"
            "same steps in OpenMesh and CGAL Surface_mesh (peer programs, when built). Ends\n"
            "by comparing the map with a rebuild of its union.\n"
            "\n"
            "  --faces N       triangles of the map (default %u)\n"
            "  --steps N       steps of 1 %% of the blocks each (default %u)\n"
            "  --seed N        seed of the changed versions and of the blocks each step picks\n"
            "  --quick         %u triangles, %u steps (a smoke test)\n"
            "  --no-peers      meshtopo alone\n"
            "  --peer-dir DIR  where the peers are (default: next to this program)\n"
            "  --help          this text\n"
            "\n"
            "Exit status: 0 when everything ran and the map equals the rebuild (a missed\n"
            "target included), 1 when something failed or they differ, 2 on a usage error.\n",
            2 * BLOCK_CELLS * BLOCK_CELLS, DEFAULT_FACES, DEFAULT_STEPS, QUICK_FACES, QUICK_STEPS);
}

/* The options usage() describes. */
static const mt__option option_table[] = {
    {"faces", "N", NULL},  {"steps", "N", NULL},     {"seed", "N", NULL},
    {"quick", NULL, NULL}, {"no-peers", NULL, NULL}, {"peer-dir", "DIR", NULL},
};

/* Returns 0, 1 (--help) or 2 (usage error, printed). */
static int parse_options(int argc, char **argv, options *o)
{
    memset(o, 0, sizeof *o);
    o->faces = DEFAULT_FACES;
    o->steps = DEFAULT_STEPS;
    o->seed = DEFAULT_SEED;
    mt__args args;
    int read =
        mt__bench_args_read(PROGRAM, option_table, sizeof option_table / sizeof option_table[0],
                            argc - 1, argv + 1, &args);
    if (read != 0) return read;
    bool faces_given = false, steps_given = false;
    bool ok =
        mt__bench_arg_u64(&args, PROGRAM, "faces", MIN_FACES, MAX_FACES, &o->faces, &faces_given) &&
        mt__bench_arg_u32(&args, PROGRAM, "steps", 1, MAX_STEPS, &o->steps, &steps_given) &&
        mt__bench_arg_u64(&args, PROGRAM, "seed", 0, UINT64_MAX, &o->seed, NULL);
    o->quick = mt__args_flag(&args, "quick");
    o->no_peers = mt__args_flag(&args, "no-peers");
    o->peer_dir = mt__args_value(&args, "peer-dir");
    mt__args_free(&args);
    if (!ok) return 2;
    if (o->quick && !faces_given) o->faces = QUICK_FACES;
    if (o->quick && !steps_given) o->steps = QUICK_STEPS;
    return 0;
}

/* The surface of about `faces` triangles: blocks of BLOCK_CELLS cells, as
 * square a grid of blocks as the count allows. */
static mt__map_surface surface_make(uint64_t faces)
{
    mt__map_surface s;
    s.cells = BLOCK_CELLS;
    s.voxel = VOXEL;
    uint64_t per_block = 2ull * BLOCK_CELLS * BLOCK_CELLS;
    uint64_t blocks = (faces + per_block / 2) / per_block;
    if (blocks < 1) blocks = 1;
    uint32_t tx = (uint32_t)ceil(sqrt((double)blocks));
    uint32_t ty = (uint32_t)((blocks + tx / 2) / tx);
    s.tiles_x = tx;
    s.tiles_y = ty ? ty : 1;
    return s;
}

/* One block's face list in caller-owned arrays (sizes all 3). */
typedef struct block_buf {
    mt_face_list list;
} block_buf;

static bool block_buf_init(block_buf *b, const mt__map_surface *s)
{
    memset(b, 0, sizeof *b);
    uint32_t nv = mt__map_block_verts(s), nf = mt__map_block_faces(s);
    b->list.num_verts = nv;
    b->list.num_faces = nf;
    b->list.num_indices = 3ull * nf;
    b->list.positions = malloc(3 * (size_t)nv * sizeof(double));
    b->list.face_sizes = malloc((size_t)nf * sizeof(uint32_t));
    b->list.face_indices = malloc(3 * (size_t)nf * sizeof(uint32_t));
    if (!b->list.positions || !b->list.face_sizes || !b->list.face_indices) return false;
    for (uint32_t f = 0; f < nf; f++) b->list.face_sizes[f] = 3;
    return true;
}

static void block_buf_free(block_buf *b)
{
    free(b->list.positions);
    free(b->list.face_sizes);
    free(b->list.face_indices);
    memset(b, 0, sizeof *b);
}

/* The welded union of version 0: the whole grid, vertex (i, j) numbered
 * i + j * (tiles_x * cells + 1), faces block by block in the blocks' order. */
static bool union_make(const mt__map_surface *s, mt_face_list *out)
{
    uint32_t gx = s->tiles_x * s->cells + 1, gy = s->tiles_y * s->cells + 1;
    uint32_t nb = s->tiles_x * s->tiles_y, bf = mt__map_block_faces(s);
    mt_diag diag;
    mt_diag_clear(&diag);
    if (mt_face_list_alloc(out, gx * gy, nb * bf, 3ull * nb * bf, &diag) != MT_OK) return false;
    for (uint32_t j = 0; j < gy; j++) {
        for (uint32_t i = 0; i < gx; i++) {
            double *p = out->positions + 3 * ((size_t)i + (size_t)j * gx);
            p[0] = i * s->voxel;
            p[1] = j * s->voxel;
            p[2] = mt__map_height(s, i, j);
        }
    }
    size_t at = 0;
    uint32_t n = s->cells;
    for (uint32_t by = 0; by < s->tiles_y; by++) {
        for (uint32_t bx = 0; bx < s->tiles_x; bx++) {
            for (uint32_t b = 0; b < n; b++) {
                for (uint32_t a = 0; a < n; a++) {
                    uint32_t i = bx * n + a, j = by * n + b;
                    uint32_t v00 = i + j * gx, v10 = v00 + 1, v01 = v00 + gx, v11 = v01 + 1;
                    uint32_t *t = out->face_indices + at;
                    t[0] = v00, t[1] = v10, t[2] = v11;
                    t[3] = v00, t[4] = v11, t[5] = v01;
                    at += 6;
                }
            }
        }
    }
    for (uint32_t f = 0; f < out->num_faces; f++) out->face_sizes[f] = 3;
    return true;
}

static double median_of(double *values, uint32_t n)
{
    return n ? mt__bench_median_of(values, n) : NAN;
}

/* Starts peer k (when built) on the same surface and steps and reads its
 * result line. The peer generates the blocks itself from map_surface.h. */
static void peer_run(const options *o, const mt__map_surface *s, int k, peer_result *out)
{
    memset(out, 0, sizeof *out);
    char exe[PATH_MAX];
    if (o->no_peers || !mt__bench_peer_find(o->peer_dir, peer_names[k], exe, sizeof exe)) return;
    out->found = true;
    char tx[16], ty[16], cells[16], voxel[40], seed[32], steps[16];
    snprintf(tx, sizeof tx, "%u", s->tiles_x);
    snprintf(ty, sizeof ty, "%u", s->tiles_y);
    snprintf(cells, sizeof cells, "%u", s->cells);
    snprintf(voxel, sizeof voxel, "%.17g", s->voxel);
    snprintf(seed, sizeof seed, "%" PRIu64, o->seed);
    snprintf(steps, sizeof steps, "%u", o->steps);
    char *argv[] = {exe,       "--tiles-x", tx,       "--tiles-y", ty,        "--cells", cells,
                    "--voxel", voxel,       "--seed", seed,        "--steps", steps,     NULL};
    mt__bench_child child;
    memset(&child, 0, sizeof child);
    char err[512], line[512];
    fprintf(stderr, "meshtopo-bench map: %s: running the steps\n", peer_labels[k]);
    if (!mt__bench_child_start(&child, argv, err, sizeof err) ||
        !mt__bench_child_read_line(&child, line, sizeof line, err, sizeof err)) {
        fprintf(stderr, "meshtopo-bench map: %s: %s\n", peer_names[k], err);
    } else if (!mt__bench_field_double(line, "first_ms", &out->first_ms) ||
               !mt__bench_field_double(line, "step_ms", &out->step_ms) ||
               !mt__bench_field_double(line, "mean_ms", &out->mean_ms) ||
               !mt__bench_field_u64(line, "faces", &out->faces) ||
               !mt__bench_field_u64(line, "verts", &out->verts) ||
               !mt__bench_field_u64(line, "collections", &out->collections)) {
        fprintf(stderr, "meshtopo-bench map: %s: unexpected line: %.400s\n", peer_names[k], line);
    } else {
        out->ok = true;
    }
    mt__bench_child_stop(&child, peer_names[k]);
}

/* The meshtopo side's figures. */
typedef struct map_result {
    double first_ms, full_ms, step_ms, mean_ms, put_ms;
    size_t bytes_first, bytes_last, bytes_compact, mesh_bytes;
    double compact_ms;
    uint32_t faces, verts;
} map_result;

static const char *ms_text(char *buf, size_t size, double x)
{
    return mt__bench_ms(buf, size, x);
}

static const char *verdict(bool met)
{
    return met ? "met" : "MISSED";
}

int mt__bench_map_command(int argc, char **argv)
{
    options o;
    int parsed = parse_options(argc, argv, &o);
    if (parsed != 0) return mt__bench_usage_exit(parsed, usage);
    signal(SIGPIPE, SIG_IGN); /* a dead peer is reported through its pipe */
    mt__map_surface s = surface_make(o.faces);
    uint32_t nb = s.tiles_x * s.tiles_y, per_step = mt__map_step_count(&s);
    uint32_t build_reps = o.quick ? QUICK_BUILD_REPS : BUILD_REPS;
    map_result r;
    memset(&r, 0, sizeof r);
    int exit_code = 0;
    mt_diag diag;
    mt_diag_clear(&diag);

    /* The full build of the welded union (median of build_reps). */
    mt_face_list whole;
    memset(&whole, 0, sizeof whole);
    if (!union_make(&s, &whole)) {
        fprintf(stderr, "meshtopo-bench map: out of memory for the union\n");
        return 1;
    }
    fprintf(stderr, "meshtopo-bench map: %u blocks of %u triangles, %u triangles: full builds\n",
            nb, mt__map_block_faces(&s), whole.num_faces);
    double full[BUILD_REPS];
    for (uint32_t rep = 0; rep < build_reps; rep++) {
        mt_mesh *mesh = NULL;
        double t0 = mt__bench_now_ms();
        mt_status st = mt_mesh_build(&whole, NULL, &mesh, &diag);
        full[rep] = mt__bench_now_ms() - t0;
        if (st != MT_OK) {
            fprintf(stderr, "meshtopo-bench map: mt_mesh_build: %s %s\n", mt_strerror(st),
                    diag.message);
            mt_face_list_free(&whole);
            return 1;
        }
        r.mesh_bytes = mt_mesh_memory_bytes(mesh);
        mt_mesh_destroy(mesh);
    }
    r.full_ms = median_of(full, build_reps);
    mt_face_list_free(&whole);

    /* The first build, block by block. */
    block_buf *bufs = calloc(per_step, sizeof *bufs);
    uint32_t *picks = calloc(per_step, sizeof *picks);
    uint64_t num_puts = (uint64_t)o.steps * per_step;
    double *step_ms = calloc(o.steps, sizeof *step_ms);
    double *put_ms = calloc(num_puts, sizeof *put_ms);
    mt_map *map = NULL;
    bool ok = bufs && picks && step_ms && put_ms && num_puts <= UINT32_MAX;
    for (uint32_t k = 0; ok && k < per_step; k++) ok = block_buf_init(&bufs[k], &s);
    if (!ok) fprintf(stderr, "meshtopo-bench map: out of memory for the blocks\n");
    if (ok && mt_map_create(NULL, &map, &diag) != MT_OK) {
        fprintf(stderr, "meshtopo-bench map: mt_map_create: %s\n", diag.message);
        ok = false;
    }
    if (ok) fprintf(stderr, "meshtopo-bench map: first build, block by block\n");
    double first = 0;
    for (uint32_t b = 0; ok && b < nb; b++) {
        uint32_t bx = b % s.tiles_x, by = b / s.tiles_x;
        mt__map_block_fill(&s, bx, by, 0, o.seed, bufs[0].list.positions,
                           bufs[0].list.face_indices);
        mt_map_key key = {(int32_t)bx, (int32_t)by, 0};
        double t0 = mt__bench_now_ms();
        mt_status st = mt_map_put(map, key, &bufs[0].list, NULL, NULL, &diag);
        first += mt__bench_now_ms() - t0;
        if (st != MT_OK) {
            fprintf(stderr, "meshtopo-bench map: mt_map_put: %s %s\n", mt_strerror(st),
                    diag.message);
            ok = false;
        }
    }
    r.first_ms = first;
    if (ok) r.bytes_first = mt_map_memory_bytes(map);

    /* The steps: the changed versions are made before each step's clock
     * starts; a step is its puts, each also timed alone. */
    uint32_t puts_done = 0;
    for (uint32_t step = 0; ok && step < o.steps; step++) {
        if (step % 20 == 0) {
            fprintf(stderr, "meshtopo-bench map: step %u of %u\n", step + 1, o.steps);
        }
        mt__map_step_blocks(&s, o.seed, step, per_step, picks);
        for (uint32_t k = 0; k < per_step; k++) {
            mt__map_block_fill(&s, picks[k] % s.tiles_x, picks[k] / s.tiles_x, step + 1, o.seed,
                               bufs[k].list.positions, bufs[k].list.face_indices);
        }
        double t_step = mt__bench_now_ms();
        for (uint32_t k = 0; ok && k < per_step; k++) {
            mt_map_key key = {(int32_t)(picks[k] % s.tiles_x), (int32_t)(picks[k] / s.tiles_x), 0};
            double t0 = mt__bench_now_ms();
            mt_status st = mt_map_put(map, key, &bufs[k].list, NULL, NULL, &diag);
            put_ms[puts_done++] = mt__bench_now_ms() - t0;
            if (st != MT_OK) {
                fprintf(stderr, "meshtopo-bench map: mt_map_put: %s %s\n", mt_strerror(st),
                        diag.message);
                ok = false;
            }
        }
        step_ms[step] = mt__bench_now_ms() - t_step;
    }
    if (ok) {
        r.bytes_last = mt_map_memory_bytes(map);
        mt_map_counts counts;
        mt_map_get_counts(map, &counts);
        r.faces = counts.num_faces;
        r.verts = counts.num_verts;
        for (uint32_t i = 0; i < o.steps; i++) r.mean_ms += step_ms[i] / o.steps;
        r.step_ms = median_of(step_ms, o.steps);
        r.put_ms = median_of(put_ms, puts_done);
        /* Not part of the targets: what mt_map_compact gives back (removed
         * ids are kept until it runs). */
        double t0 = mt__bench_now_ms();
        mt_status st = mt_map_compact(map, NULL, 0, NULL, 0, &diag);
        r.compact_ms = mt__bench_now_ms() - t0;
        if (st != MT_OK) {
            fprintf(stderr, "meshtopo-bench map: mt_map_compact: %s %s\n", mt_strerror(st),
                    diag.message);
            ok = false;
        }
        r.bytes_compact = mt_map_memory_bytes(map);
    }
    for (uint32_t k = 0; bufs && k < per_step; k++) block_buf_free(&bufs[k]);
    free(bufs);
    free(picks);
    free(step_ms);
    free(put_ms);

    /* The check: the map against a rebuild of its union. */
    bool agree = false;
    if (ok) {
        fprintf(stderr, "meshtopo-bench map: comparing with a rebuild of the union\n");
        mt_face_list list;
        mt_mesh *mesh = NULL;
        mt_status st = mt_map_face_list(map, &list, NULL, 0, NULL, 0, &diag);
        if (st == MT_OK) {
            st = mt_mesh_build(&list, NULL, &mesh, &diag);
            mt_face_list_free(&list);
        }
        if (st == MT_OK) st = mt_map_compare_report(map, mt_mesh_report(mesh), &diag);
        mt_mesh_destroy(mesh);
        agree = st == MT_OK;
        if (!agree) {
            printf("check: the map DIFFERS from a rebuild of its union: %s %s\n", mt_strerror(st),
                   diag.message);
        }
    }
    mt_map_destroy(map);
    if (!ok || !agree) exit_code = 1;

    if (!ok) return 1;
    peer_result peers[2];
    for (int k = 0; k < 2; k++) {
        peer_run(&o, &s, k, &peers[k]);
        if (peers[k].found && !peers[k].ok) exit_code = 1;
        if (peers[k].ok && (peers[k].faces != r.faces || peers[k].verts != r.verts)) {
            printf("check: %s ends with %" PRIu64 " faces, %" PRIu64
                   " vertices; meshtopo with %u, %u\n",
                   peer_labels[k], peers[k].faces, peers[k].verts, r.faces, r.verts);
            exit_code = 1;
        }
    }

    /* The table. */
    char a[32], b[32], c[32];
    double step_ratio = r.step_ms / r.full_ms;
    double bpf_first = (double)r.bytes_first / r.faces, bpf_last = (double)r.bytes_last / r.faces;
    double mem_ratio = (double)r.bytes_last / (double)r.bytes_first;
    printf(
        "\nmeshtopo-bench map: %u blocks (%u x %u) of %u triangles, %u triangles, %u vertices; "
        "%u steps of %u blocks (1 %%); medians; full build with mt_mesh_build's defaults "
        "(%ld cores online), the map on one thread\n\n",
        nb, s.tiles_x, s.tiles_y, mt__map_block_faces(&s), r.faces, r.verts, o.steps, per_step,
        sysconf(_SC_NPROCESSORS_ONLN));
    printf("| measure | value |\n|---|--:|\n");
    printf("| first build, block by block (total ms) | %s |\n", ms_text(a, sizeof a, r.first_ms));
    printf("| full mt_mesh_build of the welded union (ms, median of %u) | %s |\n", build_reps,
           ms_text(a, sizeof a, r.full_ms));
    printf("| step: %u blocks replaced (ms) | %s |\n", per_step, ms_text(a, sizeof a, r.step_ms));
    printf("| step, mean (ms) | %s |\n", ms_text(a, sizeof a, r.mean_ms));
    printf("| step / full build | %.2f %% |\n", 100 * step_ratio);
    printf("| one block put (ms) | %s |\n", ms_text(a, sizeof a, r.put_ms));
    printf("| map bytes per face after the first build | %.1f |\n", bpf_first);
    printf("| map bytes per face after the last step | %.1f |\n", bpf_last);
    printf("| last / first | %.3fx |\n", mem_ratio);
    printf("| mt_map_compact after the last step (ms) | %s |\n",
           ms_text(a, sizeof a, r.compact_ms));
    printf("| map bytes per face after mt_map_compact | %.1f |\n",
           (double)r.bytes_compact / r.faces);
    printf("| built mesh bytes per face (reference) | %.1f |\n", (double)r.mesh_bytes / r.faces);
    double best_peer = INFINITY;
    int best = -1;
    for (int k = 0; k < 2; k++) {
        if (!peers[k].ok) continue;
        printf("| %s: first build (ms) | %s |\n", peer_labels[k],
               ms_text(a, sizeof a, peers[k].first_ms));
        printf("| %s: step (ms) | %s |\n", peer_labels[k], ms_text(a, sizeof a, peers[k].step_ms));
        printf("| %s: step, mean with %" PRIu64 " garbage collections (ms) | %s |\n",
               peer_labels[k], peers[k].collections, ms_text(b, sizeof b, peers[k].mean_ms));
        if (peers[k].mean_ms < best_peer) best_peer = peers[k].mean_ms, best = k;
    }
    printf("\n");
    printf("target: step at most %.0f %% of a full build: %s (%.2f %%)\n", 100 * TARGET_STEP_RATIO,
           verdict(step_ratio <= TARGET_STEP_RATIO), 100 * step_ratio);
    printf("target: one block put at most %.0f ms: %s (%s ms)\n", TARGET_PUT_MS,
           verdict(r.put_ms <= TARGET_PUT_MS), ms_text(a, sizeof a, r.put_ms));
    printf("target: memory after the last step at most %.1fx the first build's: %s (%.3fx)\n",
           TARGET_MEMORY_RATIO, verdict(mem_ratio <= TARGET_MEMORY_RATIO), mem_ratio);
    if (isinf(best_peer)) {
        printf(
            "target: at least %.0fx the faster of OpenMesh and CGAL: not judged (no peer ran: "
            "%s)\n",
            TARGET_SPEEDUP,
            o.no_peers ? "--no-peers" : "meshtopo-bench-openmesh-map and -cgal-map not built");
    } else {
        double speedup = best_peer / r.mean_ms;
        printf(
            "target: at least %.0fx the faster of OpenMesh and CGAL (mean steps, garbage "
            "collection amortised): %s (%.1fx: %s ms against %s's %s ms; medians %.1fx)\n",
            TARGET_SPEEDUP, verdict(speedup >= TARGET_SPEEDUP), speedup,
            ms_text(b, sizeof b, r.mean_ms), peer_labels[best], ms_text(c, sizeof c, best_peer),
            peers[best].step_ms / r.step_ms);
    }
    if (agree) {
        printf("check: the map equals a rebuild of its union (mt_map_compare_report)\n");
    }
    return exit_code;
}
