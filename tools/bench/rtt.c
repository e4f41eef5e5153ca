/* `meshtopo-bench rtt`: what a query to meshtopod costs on the wire. In one
 * run and one private network namespace: a raw LCM ping-pong of the query's
 * and the reply's encoded sizes, then single-id VERTEX_RING round trips
 * through the client library (repetitions alternate the two, medians shown,
 * ratio per repetition), then throughput from several client processes with
 * single-id queries and with batches. Every answer is checked against the
 * same grid built in this process. Missed targets are printed, not failed. */
#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"
#include "meshtopo/generate.h"
#include "meshtopo/report.h"
#include "rtt.h"

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

/* Targets of the daemon issue (round trips relative to the raw ping-pong). */
#define TARGET_P50_RATIO 1.5
#define TARGET_P99_RATIO 3.0
#define TARGET_SINGLE_PER_S 20000.0
#define TARGET_BATCH_PER_S 2000000.0

static void usage(FILE *out)
{
    fprintf(out,
            "usage: meshtopo-bench rtt [options]\n"
            "Query round trips to a meshtopod started for the run, against a raw LCM\n"
            "ping-pong of the same message sizes, and query throughput from several\n"
            "client processes; all inside a private network namespace made for the run.\n"
            "\n"
            "  --daemon PATH      meshtopod to start (default: next to this program, then\n"
            "                     the build tree)\n"
            "  --grid N           query a grid of N x N quads, 2 triangles each (default 100)\n"
            "  --round-trips N    timed round trips per repetition (default 2000)\n"
            "  --reps N           repetitions; medians are shown (default 5)\n"
            "  --seconds S        length of each throughput run (default 2)\n"
            "  --clients N        client processes in the throughput runs (default 4)\n"
            "  --batch N          vertex ids per batched query (default 1000)\n"
            "  --window N         queries in flight per client (default 16)\n"
            "  --seed N           seed of the queried vertex ids (default 1)\n"
            "  --csv FILE         also write the figures as CSV\n"
            "  --markdown FILE    also write the table as Markdown\n"
            "  --quick            small and short: a smoke test\n"
            "  --help             this text\n"
            "\n"
            "Exit status: 0 when every measurement ran and every answer was right, 1 when\n"
            "one failed, 2 on a usage error, 77 when no network namespace can be made here.\n");
}

/* Returns 0, 1 (--help) or 2 (usage error, printed). */
static int parse_options(int argc, char **argv, mt__rtt_options *o)
{
    /* The options usage() describes. */
    static const mt__option option_table[] = {
        {"quick", NULL, NULL},      {"daemon", "PATH", NULL}, {"grid", "N", NULL},
        {"round-trips", "N", NULL}, {"reps", "N", NULL},      {"seconds", "S", NULL},
        {"clients", "N", NULL},     {"batch", "N", NULL},     {"window", "N", NULL},
        {"seed", "N", NULL},        {"csv", "FILE", NULL},    {"markdown", "FILE", NULL},
    };
    static const char program[] = "meshtopo-bench rtt";
    memset(o, 0, sizeof *o);
    o->grid = 100;
    o->round_trips = 2000;
    o->reps = 5;
    o->clients = 4;
    o->batch = 1000;
    o->window = 16;
    o->seed = 1;
    uint32_t seconds = 2;
    mt__args args;
    int read =
        mt__bench_args_read(program, option_table, sizeof option_table / sizeof option_table[0],
                            argc - 1, argv + 1, &args);
    if (read != 0) return read;
    bool ok =
        mt__bench_arg_u32(&args, program, "grid", 2, 2000, &o->grid, NULL) &&
        mt__bench_arg_u32(&args, program, "round-trips", 10, 1000000, &o->round_trips, NULL) &&
        mt__bench_arg_u32(&args, program, "reps", 1, MT__RTT_MAX_REPS, &o->reps, NULL) &&
        mt__bench_arg_u32(&args, program, "seconds", 1, 600, &seconds, NULL) &&
        mt__bench_arg_u32(&args, program, "clients", 1, MT__RTT_MAX_CLIENTS, &o->clients, NULL) &&
        mt__bench_arg_u32(&args, program, "batch", 1, 4096, &o->batch, NULL) &&
        mt__bench_arg_u32(&args, program, "window", 1, 256, &o->window, NULL) &&
        mt__bench_arg_u64(&args, program, "seed", 0, UINT32_MAX, &o->seed, NULL);
    o->seconds = seconds;
    o->quick = mt__args_flag(&args, "quick");
    o->daemon_path = mt__args_value(&args, "daemon");
    o->csv_path = mt__args_value(&args, "csv");
    o->md_path = mt__args_value(&args, "markdown");
    mt__args_free(&args);
    if (!ok) return 2;
    if (o->quick) {
        o->grid = o->grid < 30 ? o->grid : 30;
        o->round_trips = 200;
        o->reps = 3;
        o->seconds = 1.0;
        o->batch = o->batch < 100 ? o->batch : 100;
    }
    return 0;
}

/* Latency figures of the run: per repetition, then medians. */
typedef struct latency_figures {
    double raw_p50[MT__RTT_MAX_REPS], raw_p99[MT__RTT_MAX_REPS];
    double query_p50[MT__RTT_MAX_REPS], query_p99[MT__RTT_MAX_REPS];
    double ratio_p50[MT__RTT_MAX_REPS], ratio_p99[MT__RTT_MAX_REPS];
    size_t query_bytes, reply_bytes;
} latency_figures;

static bool submit_grid(mt_client *client, const mt_face_list *list, const mt_mesh *local,
                        char *err, size_t err_size)
{
    mt_client_ack ack;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_client_submit(client, MT__RTT_MESH_ID, list, 0, &ack, &diag);
    const meshtopo_topology_t *t = st == MT_OK ? mt_client_ack_report(&ack) : NULL;
    const mt_report *r = mt_mesh_report(local);
    bool ok = t && (uint64_t)t->num_verts == r->num_verts && (uint64_t)t->num_faces == r->num_faces;
    if (st != MT_OK)
        snprintf(err, err_size, "submitting the grid: %s (%.300s)", mt_strerror(st), diag.message);
    else if (!ok)
        snprintf(err, err_size, "the daemon's report of the grid differs from the local one");
    mt_client_ack_free(&ack);
    return ok;
}

static bool measure_latency(const mt__rtt_options *o, const mt_mesh *local,
                            const mt_face_list *list, latency_figures *fig, char *err,
                            size_t err_size)
{
    mt_client *client = mt__rtt_client_new("meshtopo-bench-rtt");
    double *samples = calloc(o->round_trips, sizeof *samples);
    bool ok = client && samples && submit_grid(client, list, local, err, err_size);
    if (!client || !samples) snprintf(err, err_size, "cannot start a client");
    /* Untimed first queries: sizes for the ping-pong, warm caches. */
    ok = ok && mt__rtt_query_latency(client, local, o->round_trips < 200 ? o->round_trips : 200,
                                     o->seed + 1, samples, &fig->query_bytes, &fig->reply_bytes,
                                     err, err_size);
    for (uint32_t r = 0; ok && r < o->reps; r++) {
        /* Alternate which goes first, so drift on a shared machine hits both. */
        for (int half = 0; ok && half < 2; half++) {
            size_t unused_q, unused_r;
            if ((half == 0) == (r % 2 == 0)) {
                ok = mt__rtt_pingpong(fig->query_bytes, fig->reply_bytes, o->round_trips, samples,
                                      err, err_size);
                fig->raw_p50[r] = mt__bench_quantile(samples, o->round_trips, 0.50);
                fig->raw_p99[r] = mt__bench_quantile(samples, o->round_trips, 0.99);
            } else {
                ok = mt__rtt_query_latency(client, local, o->round_trips, o->seed + 100 + r,
                                           samples, &unused_q, &unused_r, err, err_size);
                fig->query_p50[r] = mt__bench_quantile(samples, o->round_trips, 0.50);
                fig->query_p99[r] = mt__bench_quantile(samples, o->round_trips, 0.99);
            }
        }
        fig->ratio_p50[r] = fig->query_p50[r] / fig->raw_p50[r];
        fig->ratio_p99[r] = fig->query_p99[r] / fig->raw_p99[r];
        if (ok)
            fprintf(stderr,
                    "meshtopo-bench rtt: rep %u: raw p50 %.1f p99 %.1f us, query p50 %.1f "
                    "p99 %.1f us\n",
                    r + 1, fig->raw_p50[r], fig->raw_p99[r], fig->query_p50[r], fig->query_p99[r]);
    }
    free(samples);
    mt_client_destroy(client); /* no thread may be left when the load processes fork */
    return ok;
}

typedef struct throughput_figures {
    double single[MT__RTT_MAX_REPS], batched[MT__RTT_MAX_REPS]; /* answers per second */
    uint64_t answers;
} throughput_figures;

static bool measure_throughput(const mt__rtt_options *o, const mt_mesh *local,
                               throughput_figures *fig, char *err, size_t err_size)
{
    bool ok = true;
    for (uint32_t r = 0; ok && r < o->reps; r++) {
        mt__rtt_throughput t;
        ok = mt__rtt_query_throughput(local, o->clients, 1, o->window, o->seconds,
                                      o->seed + 1000 * (r + 1), &t, err, err_size);
        fig->single[r] = (double)t.answers / t.seconds;
        fig->answers += t.answers;
        if (!ok) break;
        ok = mt__rtt_query_throughput(local, o->clients, o->batch, o->window, o->seconds,
                                      o->seed + 1000 * (r + 1) + 500, &t, err, err_size);
        fig->batched[r] = (double)t.answers / t.seconds;
        fig->answers += t.answers;
        if (ok)
            fprintf(stderr,
                    "meshtopo-bench rtt: rep %u: %.0f answers/s single-id, %.0f answers/s in "
                    "batches of %u\n",
                    r + 1, fig->single[r], fig->batched[r], o->batch);
    }
    return ok;
}

typedef struct table_row {
    const char *name;
    double value;
    const char *unit;
    const char *target_text;
    bool met;
} table_row;

static void write_outputs(const mt__rtt_options *o, const table_row *rows, size_t n,
                          const char *title)
{
    printf("%s\n\n", title);
    printf("| measurement | median | target | met |\n|---|---:|---|---|\n");
    for (size_t i = 0; i < n; i++)
        printf("| %s | %.2f %s | %s | %s |\n", rows[i].name, rows[i].value, rows[i].unit,
               rows[i].target_text, rows[i].target_text[0] ? (rows[i].met ? "yes" : "NO") : "");
    if (o->md_path) {
        FILE *f = fopen(o->md_path, "w");
        if (f) {
            fprintf(f, "%s\n\n| measurement | median | target | met |\n|---|---:|---|---|\n",
                    title);
            for (size_t i = 0; i < n; i++)
                fprintf(f, "| %s | %.2f %s | %s | %s |\n", rows[i].name, rows[i].value,
                        rows[i].unit, rows[i].target_text,
                        rows[i].target_text[0] ? (rows[i].met ? "yes" : "NO") : "");
            if (fclose(f) != 0)
                fprintf(stderr, "meshtopo-bench rtt: cannot write %s\n", o->md_path);
        } else {
            fprintf(stderr, "meshtopo-bench rtt: cannot write %s: %s\n", o->md_path,
                    strerror(errno));
        }
    }
    if (o->csv_path) {
        FILE *f = fopen(o->csv_path, "w");
        if (f) {
            fprintf(f, "measurement,median,unit,target,met\n");
            for (size_t i = 0; i < n; i++)
                fprintf(f, "\"%s\",%.4f,%s,\"%s\",%s\n", rows[i].name, rows[i].value, rows[i].unit,
                        rows[i].target_text,
                        rows[i].target_text[0] ? (rows[i].met ? "yes" : "no") : "");
            if (fclose(f) != 0)
                fprintf(stderr, "meshtopo-bench rtt: cannot write %s\n", o->csv_path);
        } else {
            fprintf(stderr, "meshtopo-bench rtt: cannot write %s: %s\n", o->csv_path,
                    strerror(errno));
        }
    }
}

static void report(const mt__rtt_options *o, latency_figures *lat, throughput_figures *tp,
                   uint64_t num_faces)
{
    uint32_t n = o->reps;
    char raw_name[96], query_name[96], single_name[96], batch_name[96], title[256];
    snprintf(raw_name, sizeof raw_name, "raw LCM ping-pong (%zu B out, %zu B back)",
             lat->query_bytes, lat->reply_bytes);
    snprintf(query_name, sizeof query_name, "one-ring query round trip (1 id)");
    snprintf(single_name, sizeof single_name,
             "one-ring answers/s, single-id queries, %u clients x %u in flight", o->clients,
             o->window);
    snprintf(batch_name, sizeof batch_name,
             "one-ring answers/s, batches of %u, %u clients x %u in flight", o->batch, o->clients,
             o->window);
    snprintf(title, sizeof title,
             "meshtopo-bench rtt: grid %ux%u (%" PRIu64
             " triangles), %u round trips x %u reps, "
             "%.0f s throughput runs, private network namespace",
             o->grid, o->grid, num_faces, o->round_trips, n, o->seconds);
    double ratio50 = mt__bench_median_of(lat->ratio_p50, n),
           ratio99 = mt__bench_median_of(lat->ratio_p99, n);
    double single = mt__bench_median_of(tp->single, n),
           batched = mt__bench_median_of(tp->batched, n);
    table_row rows[] = {
        {"p50 raw LCM ping-pong", mt__bench_median_of(lat->raw_p50, n), "us", "", false},
        {"p50 one-ring query", mt__bench_median_of(lat->query_p50, n), "us", "", false},
        {"p50 ratio query / raw", ratio50, "x", "<= 1.5x", ratio50 <= TARGET_P50_RATIO},
        {"p99 raw LCM ping-pong", mt__bench_median_of(lat->raw_p99, n), "us", "", false},
        {"p99 one-ring query", mt__bench_median_of(lat->query_p99, n), "us", "", false},
        {"p99 ratio query / raw", ratio99, "x", "<= 3x", ratio99 <= TARGET_P99_RATIO},
        {single_name, single, "/s", ">= 20,000/s", single >= TARGET_SINGLE_PER_S},
        {batch_name, batched, "/s", ">= 2,000,000/s", batched >= TARGET_BATCH_PER_S},
    };
    fprintf(stderr, "meshtopo-bench rtt: baseline is %s\n", raw_name);
    write_outputs(o, rows, sizeof rows / sizeof rows[0], title);
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++)
        if (rows[i].target_text[0] && !rows[i].met)
            printf("target missed: %s = %.2f %s (target %s)\n", rows[i].name, rows[i].value,
                   rows[i].unit, rows[i].target_text);
}

int mt__bench_rtt_command(int argc, char **argv)
{
    mt__rtt_options o;
    int parsed = parse_options(argc, argv, &o);
    if (parsed != 0) return mt__bench_usage_exit(parsed, usage);
    char err[512] = "";
    /* First, before any thread exists: the private network. */
    int net = mt__rtt_enter_private_network(err, sizeof err);
    if (net != 0) {
        fprintf(stderr, "meshtopo-bench rtt: %s%s\n", err,
                net == 77 ? " (skipped: needs root or user namespaces)" : "");
        return net;
    }
    signal(SIGPIPE, SIG_IGN);

    mt_face_list list;
    mt_mesh *local = NULL;
    mt_diag diag;
    mt_diag_clear(&diag);
    if (mt_gen_grid(o.grid, o.grid, true, &list) != MT_OK) {
        fprintf(stderr, "meshtopo-bench rtt: cannot make the grid\n");
        return 1;
    }
    if (mt_mesh_build(&list, NULL, &local, &diag) != MT_OK) {
        fprintf(stderr, "meshtopo-bench rtt: building the grid: %s\n", diag.message);
        mt_face_list_free(&list);
        return 1;
    }

    char daemon_buf[PATH_MAX];
    const char *daemon_path = mt__rtt_daemon_find(o.daemon_path, daemon_buf, sizeof daemon_buf);
    mt__rtt_daemon daemon;
    mt__rtt_echo echo = {0};
    latency_figures lat;
    throughput_figures tp;
    memset(&lat, 0, sizeof lat);
    memset(&tp, 0, sizeof tp);
    fprintf(stderr, "meshtopo-bench rtt: starting %s in a private network namespace\n",
            daemon_path);
    bool ok = mt__rtt_daemon_start(daemon_path, NULL, &daemon, err, sizeof err) &&
              mt__rtt_echo_start(&echo, err, sizeof err) &&
              measure_latency(&o, local, &list, &lat, err, sizeof err);
    /* Every LCM socket on the group receives every message: the echo goes
     * before the throughput runs so that it does not slow them. */
    mt__rtt_echo_stop(&echo);
    ok = ok && measure_throughput(&o, local, &tp, err, sizeof err);
    if (!ok) fprintf(stderr, "meshtopo-bench rtt: %s\n", err);
    char stop_err[512] = "";
    if (!mt__rtt_daemon_stop(&daemon, stop_err, sizeof stop_err)) {
        if (stop_err[0]) fprintf(stderr, "meshtopo-bench rtt: %s\n", stop_err);
        ok = false;
    }
    if (ok) report(&o, &lat, &tp, list.num_faces);
    mt_mesh_destroy(local);
    mt_face_list_free(&list);
    return ok ? 0 : 1;
}
