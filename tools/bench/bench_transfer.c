/* `meshtopo-bench transfer`: what a large submission costs end to end, in a
 * private network namespace (rtt_netns.c) with a meshtopod started for the
 * run (rtt_daemon.c): a grid's encoded bytes pushed raw (transfer_raw.c)
 * alternating with mt_client_submit of the same mesh, then the submission
 * again with a share of UDP packets dropped (transfer_loss.c). Medians are
 * shown with the targets; a missed target is printed, not failed. */
#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "bench_transfer.h"
#include "meshtopo/generate.h"
#include "rtt.h"

/* The raw push sends single-datagram LCM messages with the client's chunk
 * size and acknowledgement window and no protocol. A submission is timed
 * from send to ack (built and acked); its transfer part is that minus the
 * daemon's build time from the ack. */

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

#define MESH_ID "transfer-grid"
#define MAX_REPS 99
/* Targets of the chunked-submission issue. */
#define TARGET_RAW_RATIO 2.0  /* transfer part / raw push, 0 % loss */
#define TARGET_E2E_S 0.5      /* end to end for 1M triangles, 0 % loss */
#define TARGET_LOSS_RATIO 3.0 /* end to end at the loss / at 0 % */

typedef struct options {
    const char *daemon_path;
    uint32_t triangles, reps, window;
    int loss;
    const char *csv_path;
    bool quick;
} options;

static void usage(FILE *out)
{
    fprintf(out,
            "usage: meshtopo-bench transfer [options]\n"
            "End-to-end time of a chunked submission to a meshtopod started for the run\n"
            "(send -> built -> acked), at 0 %% and at a share of UDP packets dropped,\n"
            "next to pushing the same bytes as raw single-datagram LCM messages with the\n"
            "same acknowledgement window; all inside a private network namespace.\n"
            "\n"
            "  --daemon PATH      meshtopod to start (default: next to this program, then\n"
            "                     the build tree)\n"
            "  --triangles N      triangles of the submitted grid (default 1000000)\n"
            "  --reps N           repetitions; medians are shown (default 5)\n"
            "  --window N         chunks per acknowledgement, both ways (default %d)\n"
            "  --loss P           percent of UDP packets dropped in the lossy runs (default 5)\n"
            "  --csv FILE         also write the figures as CSV\n"
            "  --quick            a small grid and 2 repetitions: a smoke test\n"
            "  --help             this text\n"
            "\n"
            "Exit status: 0 when every measurement ran (missed targets included), 1 when\n"
            "one failed, 2 on a usage error, 77 when no network namespace can be made here.\n",
            MT_CLIENT_DEFAULT_WINDOW_CHUNKS);
}

/* Returns 0, 1 (--help) or 2 (usage error, printed). */
static int parse_options(int argc, char **argv, options *o)
{
    /* The options usage() describes. */
    static const mt__option option_table[] = {
        {"quick", NULL, NULL}, {"daemon", "PATH", NULL}, {"triangles", "N", NULL},
        {"reps", "N", NULL},   {"window", "N", NULL},    {"loss", "PERCENT", NULL},
        {"csv", "FILE", NULL},
    };
    static const char program[] = "meshtopo-bench transfer";
    memset(o, 0, sizeof *o);
    o->triangles = 1000000;
    o->reps = 5;
    o->window = MT_CLIENT_DEFAULT_WINDOW_CHUNKS;
    uint32_t loss = 5;
    mt__args args;
    int read =
        mt__bench_args_read(program, option_table, sizeof option_table / sizeof option_table[0],
                            argc - 1, argv + 1, &args);
    if (read != 0) return read;
    bool triangles_given = false;
    bool ok = mt__bench_arg_u32(&args, program, "triangles", 20000, 20000000, &o->triangles,
                                &triangles_given) &&
              mt__bench_arg_u32(&args, program, "reps", 1, MAX_REPS, &o->reps, NULL) &&
              mt__bench_arg_u32(&args, program, "window", 1, 4096, &o->window, NULL) &&
              mt__bench_arg_u32(&args, program, "loss", 1, 50, &loss, NULL);
    o->loss = (int)loss;
    o->quick = mt__args_flag(&args, "quick");
    o->daemon_path = mt__args_value(&args, "daemon");
    o->csv_path = mt__args_value(&args, "csv");
    mt__args_free(&args);
    if (!ok) return 2;
    if (o->quick) {
        if (!triangles_given) o->triangles = 40000;
        o->reps = o->reps < 2 ? o->reps : 2;
    }
    return 0;
}

/* The median of n values, leaving them in their order. */
static double median(const double *values, uint32_t n)
{
    double sorted[MAX_REPS];
    memcpy(sorted, values, n * sizeof *values);
    return mt__bench_median_of(sorted, n);
}

static double seconds_since(const struct timespec *t0)
{
    struct timespec t1;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    return mt__bench_elapsed_us(t0, &t1) / 1e6;
}

/* One mt_client_submit of the grid: end-to-end seconds and the daemon's build
 * seconds (from the ack's report); checks the ack's content hash. The client
 * lives only for the call, so no thread is left when the acker forks. */
static bool submit_once(const options *o, const mt_face_list *list, double *out_e2e,
                        double *out_build, char *err, size_t err_size)
{
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm_url = MT__RTT_LCM_URL;
    opts.source = "meshtopo-bench-transfer";
    opts.window_chunks = (int)o->window;
    opts.timeout_ms = 2000;
    opts.retries = 5;
    mt_client *client = NULL;
    mt_diag diag;
    mt_diag_clear(&diag);
    if (mt_client_create(&opts, &client, &diag) != MT_OK) {
        snprintf(err, err_size, "cannot create a client: %.300s", diag.message);
        return false;
    }
    mt_client_ack ack;
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    mt_status st = mt_client_submit(client, MESH_ID, list, 0, &ack, &diag);
    *out_e2e = seconds_since(&t0);
    const meshtopo_topology_t *report = st == MT_OK ? mt_client_ack_report(&ack) : NULL;
    bool ok = false;
    if (st != MT_OK)
        snprintf(err, err_size, "submit: %s (%.300s)", mt_strerror(st), diag.message);
    else if ((uint64_t)ack.msg.content_hash != ack.sent_content_hash)
        snprintf(err, err_size, "the ack's content hash differs from the one sent");
    else if (!report || (uint64_t)report->num_faces != list->num_faces)
        snprintf(err, err_size, "the ack's report does not describe the grid");
    else
        ok = true;
    *out_build = report ? (double)report->build_duration_us / 1e6 : 0;
    mt_client_ack_free(&ack);
    mt_client_destroy(client);
    return ok;
}

/* The encoded mesh_t of the grid: the bytes the raw push sends. */
static uint8_t *encode_mesh(const mt_face_list *list, uint64_t *out_size)
{
    meshtopo_mesh_t m;
    memset(&m, 0, sizeof m);
    m.reply_channel = "MESHTOPO_REPLY_raw";
    m.mesh_id = MESH_ID;
    m.source = "meshtopo-bench-transfer";
    m.num_verts = (int32_t)list->num_verts;
    m.num_position_values = 3 * (int32_t)list->num_verts;
    m.positions = list->positions;
    m.num_faces = (int32_t)list->num_faces;
    m.face_vertex_counts = (int32_t *)list->face_sizes;
    m.num_indices = (int32_t)list->num_indices;
    m.face_vertex_indices = (int32_t *)list->face_indices;
    int size = meshtopo_mesh_t_encoded_size(&m);
    uint8_t *buf = size > 0 ? malloc((size_t)size) : NULL;
    if (!buf || meshtopo_mesh_t_encode(buf, 0, size, &m) != size) {
        free(buf);
        return NULL;
    }
    *out_size = (uint64_t)size;
    return buf;
}

typedef struct figures {
    double raw[MAX_REPS], e2e[MAX_REPS], build[MAX_REPS], part[MAX_REPS];
    double lossy[MAX_REPS], lossy_build[MAX_REPS];
    double local[MAX_REPS]; /* encoding and hashing the mesh in this process */
    bool have_loss;
    char loss_note[256];
} figures;

typedef struct row {
    char name[128];
    double value;
    const char *unit;
    char target[64];
    int met; /* -1: no target */
} row;

static void report(const options *o, const figures *f, uint64_t bytes, uint32_t faces)
{
    uint32_t n = o->reps;
    double raw = median(f->raw, n), e2e = median(f->e2e, n), build = median(f->build, n);
    double part = median(f->part, n);
    double ratio_raw[MAX_REPS], ratio_loss[MAX_REPS];
    for (uint32_t r = 0; r < n; r++) {
        ratio_raw[r] = f->part[r] / f->raw[r];
        ratio_loss[r] = f->have_loss ? f->lossy[r] / f->e2e[r] : 0;
    }
    /* The end-to-end target is for 1M triangles: scaled to the grid's size. */
    double e2e_target = TARGET_E2E_S * (double)faces / 1e6;
    row rows[12];
    size_t k = 0;
    rows[k] = (row){"", raw, "s", "", -1};
    snprintf(rows[k++].name, sizeof rows[0].name, "raw LCM push, 0%% loss (%.0f MB/s)",
             (double)bytes / raw / 1e6);
    rows[k] = (row){"", e2e, "s", "", -1};
    snprintf(rows[k].target, sizeof rows[k].target, "< %.2f s", e2e_target);
    rows[k].met = e2e < e2e_target;
    snprintf(rows[k++].name, sizeof rows[0].name, "submit end to end, 0%% loss");
    rows[k] = (row){"", build, "s", "", -1};
    snprintf(rows[k++].name, sizeof rows[0].name, "  of which the daemon's build");
    rows[k] = (row){"", part, "s", "", -1};
    snprintf(rows[k++].name, sizeof rows[0].name, "  transfer part (end to end - build)");
    rows[k] = (row){"", median(f->local, n), "s", "", -1};
    snprintf(rows[k++].name, sizeof rows[0].name,
             "  of which the content hash, in-process (client side)");
    rows[k] = (row){"", median(ratio_raw, n), "x", "<= 2x", -1};
    rows[k].met = rows[k].value <= TARGET_RAW_RATIO;
    snprintf(rows[k++].name, sizeof rows[0].name, "ratio transfer part / raw push");
    if (f->have_loss) {
        rows[k] = (row){"", median(f->lossy, n), "s", "", -1};
        snprintf(rows[k++].name, sizeof rows[0].name, "submit end to end, %d%% loss", o->loss);
        rows[k] = (row){"", median(ratio_loss, n), "x", "< 3x", -1};
        rows[k].met = rows[k].value < TARGET_LOSS_RATIO;
        snprintf(rows[k++].name, sizeof rows[0].name, "ratio %d%% loss / 0%% loss", o->loss);
    }
    printf(
        "meshtopo-bench transfer: grid of %u triangles (%.1f MB encoded), chunks of %d B, "
        "window %u, median of %u reps, private network namespace\n\n",
        faces, (double)bytes / 1e6, MT_CLIENT_DEFAULT_CHUNK_BYTES, o->window, n);
    printf("| measurement | median | target | met |\n|---|---:|---|---|\n");
    for (size_t i = 0; i < k; i++)
        printf("| %s | %.3f %s | %s | %s |\n", rows[i].name, rows[i].value, rows[i].unit,
               rows[i].target,
               rows[i].met < 0 ? ""
               : rows[i].met   ? "met"
                               : "MISS");
    if (!f->have_loss) printf("\n%d%% loss row skipped: %s\n", o->loss, f->loss_note);
    for (size_t i = 0; i < k; i++)
        if (rows[i].met == 0)
            printf("target missed: %s = %.3f %s (target %s)\n", rows[i].name, rows[i].value,
                   rows[i].unit, rows[i].target);
    if (o->csv_path) {
        FILE *out = fopen(o->csv_path, "w");
        if (!out) {
            fprintf(stderr, "meshtopo-bench transfer: cannot write %s: %s\n", o->csv_path,
                    strerror(errno));
            return;
        }
        fprintf(out, "measurement,median,unit,target,met\n");
        for (size_t i = 0; i < k; i++)
            fprintf(out, "\"%s\",%.6f,%s,\"%s\",%s\n", rows[i].name, rows[i].value, rows[i].unit,
                    rows[i].target,
                    rows[i].met < 0 ? ""
                    : rows[i].met   ? "yes"
                                    : "no");
        if (fclose(out) != 0)
            fprintf(stderr, "meshtopo-bench transfer: cannot write %s\n", o->csv_path);
    }
}

static bool measure(const options *o, const mt_face_list *list, const uint8_t *bytes, uint64_t size,
                    figures *f, char *err, size_t err_size)
{
    bool ok = true;
    for (uint32_t r = 0; ok && r < o->reps; r++) {
        /* Alternate which goes first, so drift on a shared machine hits both. */
        for (int half = 0; ok && half < 2; half++) {
            if ((half == 0) == (r % 2 == 0)) {
                mt__raw_acker acker = {0};
                ok = mt__raw_acker_start(&acker, err, err_size) &&
                     mt__raw_push(bytes, size, MT_CLIENT_DEFAULT_CHUNK_BYTES, o->window, &f->raw[r],
                                  err, err_size);
                mt__raw_acker_stop(&acker);
            } else {
                ok = submit_once(o, list, &f->e2e[r], &f->build[r], err, err_size);
                f->part[r] = f->e2e[r] - f->build[r];
                /* What the client does before its first chunk: the content
                 * hash (chunks are encoded as they are sent). */
                struct timespec t0;
                clock_gettime(CLOCK_MONOTONIC, &t0);
                uint64_t hash = 0;
                mt_client_content_hash(list, &hash, NULL);
                f->local[r] = seconds_since(&t0);
            }
        }
        if (ok)
            fprintf(stderr,
                    "meshtopo-bench transfer: rep %u: raw %.3f s, submit %.3f s (build %.3f s)\n",
                    r + 1, f->raw[r], f->e2e[r], f->build[r]);
    }
    if (!ok) return false;
    char loss_err[256] = "";
    f->have_loss = mt__transfer_set_loss(o->loss, loss_err, sizeof loss_err);
    if (!f->have_loss) {
        snprintf(f->loss_note, sizeof f->loss_note, "%s", loss_err);
        fprintf(stderr, "meshtopo-bench transfer: no %d%% loss runs: %s\n", o->loss, loss_err);
        return true;
    }
    for (uint32_t r = 0; ok && r < o->reps; r++) {
        ok = submit_once(o, list, &f->lossy[r], &f->lossy_build[r], err, err_size);
        if (ok)
            fprintf(stderr, "meshtopo-bench transfer: rep %u: submit at %d%% loss %.3f s\n", r + 1,
                    o->loss, f->lossy[r]);
    }
    char unused[256];
    if (!mt__transfer_set_loss(0, unused, sizeof unused))
        fprintf(stderr, "meshtopo-bench transfer: could not remove the loss rule: %s\n", unused);
    return ok;
}

int mt__bench_transfer_command(int argc, char **argv)
{
    options o;
    int parsed = parse_options(argc, argv, &o);
    if (parsed != 0) return mt__bench_usage_exit(parsed, usage);
    char err[512] = "";
    /* First, before any thread exists: the private network. */
    int net = mt__rtt_enter_private_network(err, sizeof err);
    if (net != 0) {
        fprintf(stderr, "meshtopo-bench transfer: %s%s\n", err,
                net == 77 ? " (skipped: needs root or user namespaces)" : "");
        return net;
    }
    signal(SIGPIPE, SIG_IGN);

    /* A grid of nx x ny cells, 2 triangles each, about o.triangles of them. */
    uint32_t nx = (uint32_t)ceil(sqrt((double)o.triangles / 2.0));
    uint32_t ny = (uint32_t)((o.triangles + 2 * nx - 1) / (2 * nx));
    mt_face_list list;
    if (mt_gen_grid(nx, ny, true, &list) != MT_OK) {
        fprintf(stderr, "meshtopo-bench transfer: cannot make a %ux%u grid\n", nx, ny);
        return 1;
    }
    uint64_t size = 0;
    uint8_t *bytes = encode_mesh(&list, &size);
    if (!bytes) {
        fprintf(stderr, "meshtopo-bench transfer: cannot encode the grid\n");
        mt_face_list_free(&list);
        return 1;
    }
    char daemon_buf[PATH_MAX];
    const char *daemon_path = mt__rtt_daemon_find(o.daemon_path, daemon_buf, sizeof daemon_buf);
    fprintf(stderr, "meshtopo-bench transfer: starting %s in a private network namespace\n",
            daemon_path);
    figures f;
    memset(&f, 0, sizeof f);
    mt__rtt_daemon daemon;
    bool ok = mt__rtt_daemon_start(daemon_path, NULL, &daemon, err, sizeof err) &&
              measure(&o, &list, bytes, size, &f, err, sizeof err);
    if (!ok) fprintf(stderr, "meshtopo-bench transfer: %s\n", err);
    char stop_err[512] = "";
    if (!mt__rtt_daemon_stop(&daemon, stop_err, sizeof stop_err)) {
        if (stop_err[0]) fprintf(stderr, "meshtopo-bench transfer: %s\n", stop_err);
        ok = false;
    }
    if (ok) report(&o, &f, size, list.num_faces);
    free(bytes);
    mt_face_list_free(&list);
    return ok ? 0 : 1;
}
