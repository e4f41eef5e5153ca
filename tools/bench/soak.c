/* `meshtopo-bench soak` (soak.h): the run. In a private network namespace
 * it starts meshtopod with an archive, submits the grid everyone queries,
 * then runs the normal clients (threads, each its own meshtopo::client)
 * through three phases: a baseline alone, an attack beside the hostile
 * sender, and a quiet end in which transfers expire and remembered answers
 * age out. A sampler reads the daemon's resident memory from /proc every
 * 100 ms. At the end every acknowledged normal mesh is queried again. */
#define _XOPEN_SOURCE 700 /* nftw */
#define _DEFAULT_SOURCE   /* mkdtemp */
#include <dirent.h>
#include <fcntl.h>
#include <ftw.h>
#include <inttypes.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bench.h"
#include "meshtopo/generate.h"
#include "rtt.h"
#include "soak.h"

#define GRID_ID "soak-grid"
#define GRID_SIZE 150 /* 22,801 vertices: room for 20,000-id floods */
#define FLOOD_IDS 20000
#define QUERY_PAUSE_MS 10 /* between one client's queries */
#define SUBMIT_EVERY_MS 2000
#define MAX_CLIENTS 16

/* Targets (issue "meshtopod under hostile and buggy traffic"). */
#define TARGET_P99_RATIO 3.0
#define TARGET_RSS_RATIO 1.5

enum { BASELINE, ATTACK, QUIET, STOPPED, PHASES = 3 };

typedef struct options {
    double seconds;
    uint32_t clients;
    const char *daemon_path;
} options;

typedef struct samples {
    double *v;
    size_t n, cap;
} samples;

typedef struct acked_mesh {
    char id[64];
    int32_t version;
} acked_mesh;

typedef struct soak soak;

typedef struct worker {
    soak *run;
    int index;
    pthread_t thread;
    samples latency[PHASES]; /* us, answered queries */
    uint64_t failed[PHASES]; /* queries without an answer */
    uint64_t submitted, unacked;
    acked_mesh *acked;
    size_t num_acked, cap_acked;
} worker;

struct soak {
    atomic_int phase;
    pid_t daemon_pid;
    atomic_long rss_kb, peak_kb; /* the daemon's, peak since the attack began */
    pthread_t sampler;
    worker workers[MAX_CLIENTS];
};

static void usage(FILE *to)
{
    fprintf(to,
            "usage: meshtopo-bench soak [--seconds S] [--clients N] [--daemon PATH]\n"
            "meshtopod under normal and hostile traffic for S seconds (default 600; a\n"
            "quarter baseline, half attack, a quarter (at least 25 s) quiet), N normal\n"
            "clients (default 3), in a private network namespace made for the run.\n"
            "Prints lost acknowledged meshes, the normal clients' latency under attack\n"
            "against the baseline, the daemon's memory at start, peak and end, and the\n"
            "archive bytes the hostile sender got written. Exit 0 when every target is\n"
            "met, 1 otherwise, 77 without network namespaces.\n");
}

static int parse_options(int argc, char **argv, options *o)
{
    /* The options usage() describes. */
    static const mt__option option_table[] = {
        {"seconds", "S", NULL},
        {"clients", "N", NULL},
        {"daemon", "PATH", NULL},
    };
    static const char program[] = "meshtopo-bench soak";
    o->seconds = 600;
    o->clients = 3;
    mt__args args;
    int read =
        mt__bench_args_read(program, option_table, sizeof option_table / sizeof option_table[0],
                            argc - 1, argv + 1, &args);
    if (read != 0) return read;
    bool ok = mt__bench_arg_u32(&args, program, "clients", 1, MAX_CLIENTS, &o->clients, NULL);
    const char *seconds = mt__args_value(&args, "seconds");
    if (ok && seconds) {
        char *end = NULL;
        o->seconds = strtod(seconds, &end);
        ok = end != seconds && *end == '\0' && o->seconds >= 20 && o->seconds <= 86400;
        if (!ok)
            fprintf(stderr, "%s: --seconds: bad value '%s' (from 20 to 86400)\n", program, seconds);
    }
    o->daemon_path = mt__args_value(&args, "daemon");
    mt__args_free(&args);
    return ok ? 0 : 2;
}

static void push(samples *s, double v)
{
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 1024;
        double *grown = realloc(s->v, cap * sizeof *grown);
        if (!grown) return;
        s->v = grown;
        s->cap = cap;
    }
    s->v[s->n++] = v;
}

static long read_rss_kb(pid_t pid)
{
    char path[64], line[256];
    snprintf(path, sizeof path, "/proc/%d/status", (int)pid);
    FILE *f = fopen(path, "r");
    long kb = -1;
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, "VmRSS: %ld kB", &kb) == 1) break;
    if (f) fclose(f);
    return kb;
}

static void *sample_rss(void *arg)
{
    soak *s = arg;
    while (atomic_load(&s->phase) != STOPPED) {
        long kb = read_rss_kb(s->daemon_pid);
        if (kb > 0) {
            atomic_store(&s->rss_kb, kb);
            if (atomic_load(&s->phase) != BASELINE && kb > atomic_load(&s->peak_kb))
                atomic_store(&s->peak_kb, kb);
        }
        mt__bench_sleep_ms(100);
    }
    return NULL;
}

/* A normal client: a query every QUERY_PAUSE_MS (the valence of a random
 * vertex of the grid, timed), a small mesh of its own every
 * SUBMIT_EVERY_MS (its acknowledged version remembered). */
static void *run_worker(void *arg)
{
    worker *w = arg;
    char source[64];
    snprintf(source, sizeof source, "soak-normal-%d", w->index);
    mt_client *client = mt__rtt_client_new(source);
    if (!client) return NULL;
    mt_face_list small;
    if (mt_gen_grid(8, 8, true, &small) != MT_OK) {
        mt_client_destroy(client);
        return NULL;
    }
    uint64_t rng = 0x50a4 + (uint64_t)w->index;
    double next_submit = mt__bench_now_ms();
    int phase;
    while ((phase = atomic_load(&w->run->phase)) != STOPPED) {
        mt_diag diag;
        if (mt__bench_now_ms() >= next_submit) {
            next_submit = mt__bench_now_ms() + SUBMIT_EVERY_MS;
            char id[64];
            snprintf(id, sizeof id, "normal-%d-%" PRIu64, w->index, w->submitted++);
            mt_client_ack ack;
            if (mt_client_submit(client, id, &small, 0, &ack, &diag) == MT_OK &&
                w->num_acked < w->cap_acked) {
                acked_mesh *a = &w->acked[w->num_acked++];
                snprintf(a->id, sizeof a->id, "%s", id);
                a->version = ack.msg.version;
            } else {
                w->unacked++;
            }
            mt_client_ack_free(&ack);
            continue;
        }
        uint32_t vertex =
            (uint32_t)(mt__bench_rand_u64(&rng) % ((GRID_SIZE + 1) * (GRID_SIZE + 1)));
        meshtopo_reply_t reply;
        double start = mt__bench_now_ms();
        mt_status st = mt_client_query(client, GRID_ID, 0, MESHTOPO_QUERY_T_VALENCE, &vertex, 1,
                                       &reply, &diag);
        double took_us = (mt__bench_now_ms() - start) * 1000;
        if (st == MT_OK && reply.num_items == 1)
            push(&w->latency[phase], took_us);
        else
            w->failed[phase]++;
        mt_client_reply_free(&reply);
        mt__bench_sleep_ms(QUERY_PAUSE_MS);
    }
    mt_face_list_free(&small);
    mt_client_destroy(client);
    return NULL;
}

/* Every acknowledged normal mesh, queried again: how many are gone. */
static uint64_t count_lost(soak *s, uint32_t clients, uint64_t *out_checked)
{
    mt_client *client = mt__rtt_client_new("soak-check");
    uint64_t lost = 0, checked = 0;
    for (uint32_t c = 0; c < clients; c++) {
        worker *w = &s->workers[c];
        for (size_t i = 0; i < w->num_acked; i++) {
            meshtopo_reply_t reply;
            mt_diag diag;
            checked++;
            if (!client ||
                mt_client_query(client, w->acked[i].id, w->acked[i].version,
                                MESHTOPO_QUERY_T_REPORT, NULL, 0, &reply, &diag) != MT_OK) {
                lost++;
                fprintf(stderr, "meshtopo-bench soak: lost %s version %d\n", w->acked[i].id,
                        (int)w->acked[i].version);
            }
            mt_client_reply_free(&reply);
        }
    }
    if (client) mt_client_destroy(client);
    *out_checked = checked;
    return lost;
}

/* Bytes of the archive's files, and of those the hostile sender's ids name. */
static void archive_bytes(const char *dir, uint64_t *out_total, uint64_t *out_hostile)
{
    *out_total = *out_hostile = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d))) {
        struct stat st;
        if (fstatat(dirfd(d), e->d_name, &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode))
            continue;
        *out_total += (uint64_t)st.st_size;
        if (strstr(e->d_name, "hostile")) *out_hostile += (uint64_t)st.st_size;
    }
    if (d) closedir(d);
}

static void merge(soak *s, uint32_t clients, int phase, samples *out, uint64_t *out_failed)
{
    memset(out, 0, sizeof *out);
    *out_failed = 0;
    for (uint32_t c = 0; c < clients; c++) {
        samples *l = &s->workers[c].latency[phase];
        for (size_t i = 0; i < l->n; i++) push(out, l->v[i]);
        *out_failed += s->workers[c].failed[phase];
    }
}

static bool run_phases(soak *s, const options *o, const char *archive, char *err, size_t err_size,
                       mt__soak_hostile_counts *hostile_counts, long *rss_start, long *rss_end)
{
    double baseline_s = o->seconds / 4 < 10 ? 10 : o->seconds / 4;
    double attack_s = o->seconds / 2;
    double quiet_s = o->seconds / 4 < 25 ? 25 : o->seconds / 4;
    (void)archive;
    atomic_store(&s->phase, BASELINE);
    pthread_create(&s->sampler, NULL, sample_rss, s);
    for (uint32_t c = 0; c < o->clients; c++) {
        worker *w = &s->workers[c];
        w->run = s;
        w->index = (int)c;
        w->cap_acked = (size_t)(o->seconds * 1000 / SUBMIT_EVERY_MS) + 16;
        w->acked = calloc(w->cap_acked, sizeof *w->acked);
        pthread_create(&w->thread, NULL, run_worker, w);
    }
    fprintf(stderr, "meshtopo-bench soak: baseline %.0f s, attack %.0f s, quiet %.0f s\n",
            baseline_s, attack_s, quiet_s);
    mt__bench_sleep_ms(baseline_s * 1000);
    *rss_start = atomic_load(&s->rss_kb);
    atomic_store(&s->peak_kb, *rss_start);
    atomic_store(&s->phase, ATTACK);
    mt__soak_hostile *h =
        mt__soak_hostile_start(MT__RTT_LCM_URL, GRID_ID, FLOOD_IDS, err, err_size);
    if (h) {
        mt__bench_sleep_ms(attack_s * 1000);
        mt__soak_hostile_stop(h, hostile_counts);
    }
    atomic_store(&s->phase, QUIET);
    mt__bench_sleep_ms(quiet_s * 1000);
    *rss_end = atomic_load(&s->rss_kb);
    atomic_store(&s->phase, STOPPED);
    for (uint32_t c = 0; c < o->clients; c++) pthread_join(s->workers[c].thread, NULL);
    pthread_join(s->sampler, NULL);
    return h != NULL;
}

static bool report(soak *s, const options *o, const mt__soak_hostile_counts *h, long rss_start,
                   long rss_end, uint64_t lost, uint64_t checked, uint64_t archive_total,
                   uint64_t archive_hostile)
{
    samples base, attack;
    uint64_t base_failed, attack_failed, unacked = 0, submitted = 0;
    merge(s, o->clients, BASELINE, &base, &base_failed);
    merge(s, o->clients, ATTACK, &attack, &attack_failed);
    for (uint32_t c = 0; c < o->clients; c++) {
        unacked += s->workers[c].unacked;
        submitted += s->workers[c].submitted;
    }
    double b50 = mt__bench_quantile(base.v, (uint32_t)base.n, 0.5);
    double b99 = mt__bench_quantile(base.v, (uint32_t)base.n, 0.99);
    double a50 = mt__bench_quantile(attack.v, (uint32_t)attack.n, 0.5);
    double a99 = mt__bench_quantile(attack.v, (uint32_t)attack.n, 0.99);
    long peak = atomic_load(&s->peak_kb);
    double p99_ratio = a99 / b99, rss_ratio = (double)rss_end / (double)rss_start;
    bool ok_lost = lost == 0, ok_p99 = p99_ratio <= TARGET_P99_RATIO,
         ok_rss = rss_ratio <= TARGET_RSS_RATIO, ok_archive = archive_hostile == 0,
         ok_claims = h->claims_accepted == 0, ok_channels = h->on_own_channels == 0;
    printf("meshtopo-bench soak: %.0f s, %u normal clients, private network namespace\n\n",
           o->seconds, o->clients);
    printf("| figure | value | target |\n|---|---|---|\n");
    printf("| lost acknowledged meshes | %" PRIu64 " of %" PRIu64 " | 0 %s |\n", lost, checked,
           ok_lost ? "met" : "MISSED");
    printf("| normal submissions not acknowledged | %" PRIu64 " of %" PRIu64 " | |\n", unacked,
           submitted);
    printf("| query p50 baseline / attack | %.0f / %.0f us | |\n", b50, a50);
    printf("| query p99 baseline / attack | %.0f / %.0f us (%.2fx) | <= %.0fx %s |\n", b99, a99,
           p99_ratio, TARGET_P99_RATIO, ok_p99 ? "met" : "MISSED");
    printf("| normal queries answered / failed, baseline | %zu / %" PRIu64 " | |\n", base.n,
           base_failed);
    printf("| normal queries answered / failed, attack | %zu / %" PRIu64 " | |\n", attack.n,
           attack_failed);
    printf(
        "| daemon RSS start / peak / end | %ld / %ld / %ld kB (end %.2fx start) | <= %.1fx "
        "%s |\n",
        rss_start, peak, rss_end, rss_ratio, TARGET_RSS_RATIO, ok_rss ? "met" : "MISSED");
    printf("| archive bytes, all / hostile | %" PRIu64 " / %" PRIu64 " | hostile 0 %s |\n",
           archive_total, archive_hostile, ok_archive ? "met" : "MISSED");
    printf("| hostile claims sent / refused TOO_LARGE / accepted | %" PRIu64 " / %" PRIu64
           " / %" PRIu64 " | accepted 0 %s |\n",
           h->claims, h->claims_refused, h->claims_accepted, ok_claims ? "met" : "MISSED");
    printf("| hostile 1 GiB transfers opened / bytes trickled / bytes scattered | %" PRIu64
           " / %" PRIu64 " / %" PRIu64 " | |\n",
           h->claim_polls, h->trickle_bytes, h->scatter_bytes);
    printf("| hostile 20,000-id queries sent / BUSY / parts served | %" PRIu64 " / %" PRIu64
           " / %" PRIu64 " | |\n",
           h->floods, h->flood_busy, h->flood_parts);
    printf("| requests naming daemon channels / answers seen there | %" PRIu64 " / %" PRIu64
           " | 0 seen %s |\n",
           h->own_channels, h->on_own_channels, ok_channels ? "met" : "MISSED");
    printf("| garbage messages | %" PRIu64 " | |\n", h->garbage);
    free(base.v);
    free(attack.v);
    return ok_lost && ok_p99 && ok_rss && ok_archive && ok_claims && ok_channels;
}

int mt__bench_soak_command(int argc, char **argv)
{
    options o;
    int parsed = parse_options(argc, argv, &o);
    if (parsed != 0) return mt__bench_usage_exit(parsed, usage);
    char err[512] = "";
    int net = mt__rtt_enter_private_network(err, sizeof err);
    if (net != 0) {
        fprintf(stderr, "meshtopo-bench soak: %s%s\n", err,
                net == 77 ? " (skipped: needs root or user namespaces)" : "");
        return net;
    }
    signal(SIGPIPE, SIG_IGN);
    const char *tmp = getenv("TMPDIR");
    char archive[PATH_MAX];
    snprintf(archive, sizeof archive, "%s/meshtopo-soak-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(archive)) {
        fprintf(stderr, "meshtopo-bench soak: cannot make the archive directory\n");
        return 1;
    }
    char daemon_buf[PATH_MAX];
    const char *daemon_path = mt__rtt_daemon_find(o.daemon_path, daemon_buf, sizeof daemon_buf);
    mt__rtt_daemon daemon;
    soak *s = calloc(1, sizeof *s);
    mt__soak_hostile_counts counts;
    memset(&counts, 0, sizeof counts);
    long rss_start = 0, rss_end = 0;
    uint64_t lost = 0, checked = 0, archive_total = 0, archive_hostile = 0;
    bool ok = s && mt__rtt_daemon_start(daemon_path, archive, &daemon, err, sizeof err);
    if (ok) {
        s->daemon_pid = daemon.pid;
        mt_face_list grid;
        mt_client *setup = mt__rtt_client_new("soak-setup");
        mt_client_ack ack;
        mt_diag diag;
        ok = setup && mt_gen_grid(GRID_SIZE, GRID_SIZE, true, &grid) == MT_OK;
        if (ok) {
            ok = mt_client_submit(setup, GRID_ID, &grid, 0, &ack, &diag) == MT_OK;
            if (!ok) snprintf(err, sizeof err, "submitting the grid: %.400s", diag.message);
            mt_client_ack_free(&ack);
            mt_face_list_free(&grid);
        }
        if (setup) mt_client_destroy(setup);
        ok = ok && run_phases(s, &o, archive, err, sizeof err, &counts, &rss_start, &rss_end);
        if (ok) {
            lost = count_lost(s, o.clients, &checked);
            archive_bytes(archive, &archive_total, &archive_hostile);
        }
        char stop_err[512] = "";
        if (!mt__rtt_daemon_stop(&daemon, stop_err, sizeof stop_err) && stop_err[0])
            fprintf(stderr, "meshtopo-bench soak: %s\n", stop_err);
    }
    if (!ok) fprintf(stderr, "meshtopo-bench soak: %s\n", err);
    bool met = ok && report(s, &o, &counts, rss_start, rss_end, lost, checked, archive_total,
                            archive_hostile);
    if (ok && !met) printf("\ntarget missed (see the table)\n");
    mt__rtt_daemon_remove_archive(archive);
    if (s)
        for (uint32_t c = 0; c < MAX_CLIENTS; c++) {
            for (int p = 0; p < PHASES; p++) free(s->workers[c].latency[p].v);
            free(s->workers[c].acked);
        }
    free(s);
    return met ? 0 : 1;
}
