/* `meshtopo-bench cluster`: what a second meshtopod of a cluster adds, in a
 * private network namespace (rtt_netns.c) with members started for the run
 * (rtt_daemon.c). Aggregate build throughput of 1 and of 2 members with one
 * build worker each, submitting large meshes under distinct ids (chosen so
 * that each member owns as many, by the protocol's rule
 * mt_msgs_cluster_owner), paired runs, the ratio per pair and its median;
 * then the failover time of a member killed with SIGKILL: from the kill
 * until every id it owned answers again from the survivors. The archive is
 * on /dev/shm unless --archive says otherwise: the build is measured, not
 * the disk (a member's archive write is part of every submission). */
#define _GNU_SOURCE
#include <errno.h>
#include <inttypes.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "bench_cluster.h"
#include "meshtopo/generate.h"
#include "meshtopo/protocol.h"
#include "rtt.h"

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

#define MAX_MEMBERS 3
#define MAX_REPS 99
#define MAX_MESHES 256
#define TARGET_RATIO 1.8
#define HEARTBEAT_MS "200"
#define FAILOVER_HEARTBEAT_MS 1000

typedef struct options {
    const char *daemon_path, *archive;
    uint32_t triangles, meshes, reps;
    bool quick;
} options;

static void usage(FILE *out)
{
    fprintf(out,
            "usage: meshtopo-bench cluster [options]\n"
            "Aggregate build throughput of a meshtopod cluster of 1 and 2 members (one build\n"
            "worker each), submitting large meshes under distinct ids, paired runs; then\n"
            "the failover time of a member killed with SIGKILL (3 members, 1 s heartbeat).\n"
            "All inside a private network namespace.\n"
            "\n"
            "  --daemon PATH      meshtopod to start (default: next to this program, then\n"
            "                     the build tree)\n"
            "  --triangles N      triangles of each submitted grid (default 1000000)\n"
            "  --meshes N         meshes submitted per run (default 16)\n"
            "  --reps N           paired runs and kills; medians are shown (default 3)\n"
            "  --archive DIR      the members' shared archive goes under DIR (default: a\n"
            "                     directory under /dev/shm, else $TMPDIR)\n"
            "  --quick            small grids, 2 repetitions: a smoke test\n"
            "  --help             this text\n"
            "\n"
            "Exit status: 0 when every measurement ran (missed targets included), 1 when\n"
            "one failed, 2 on a usage error, 77 when no network namespace can be made here.\n");
}

/* Returns 0, 1 (--help) or 2 (usage error, printed). */
static int parse_options(int argc, char **argv, options *o)
{
    /* The options usage() describes. */
    static const mt__option option_table[] = {
        {"quick", NULL, NULL},    {"daemon", "PATH", NULL}, {"archive", "DIR", NULL},
        {"triangles", "N", NULL}, {"meshes", "N", NULL},    {"reps", "N", NULL},
    };
    static const char program[] = "meshtopo-bench cluster";
    memset(o, 0, sizeof *o);
    o->triangles = 1000000;
    o->meshes = 16;
    o->reps = 3;
    mt__args args;
    int read =
        mt__bench_args_read(program, option_table, sizeof option_table / sizeof option_table[0],
                            argc - 1, argv + 1, &args);
    if (read != 0) return read;
    bool triangles_given = false, reps_given = false;
    bool ok = mt__bench_arg_u32(&args, program, "triangles", 2000, 20000000, &o->triangles,
                                &triangles_given) &&
              mt__bench_arg_u32(&args, program, "meshes", 2, MAX_MESHES, &o->meshes, NULL) &&
              mt__bench_arg_u32(&args, program, "reps", 1, MAX_REPS, &o->reps, &reps_given);
    o->quick = mt__args_flag(&args, "quick");
    o->daemon_path = mt__args_value(&args, "daemon");
    o->archive = mt__args_value(&args, "archive");
    mt__args_free(&args);
    if (!ok) return 2;
    if (o->quick) {
        if (!triangles_given) o->triangles = 40000;
        if (!reps_given) o->reps = 2;
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

/* ---- the members of one run ---------------------------------------------- */

typedef struct members {
    mt__rtt_daemon daemons[MAX_MEMBERS];
    char instances[MAX_MEMBERS][MT_CLIENT_MAX_INSTANCE + 1];
    int count;
} members;

typedef struct heard {
    pthread_mutex_t lock;
    members *m;
    int agreeing; /* members whose last heartbeat counted them all */
    int32_t seen[MAX_MEMBERS];
} heard;

static void on_status(const meshtopo_status_t *st, void *user)
{
    heard *h = user;
    pthread_mutex_lock(&h->lock);
    for (int i = 0; i < h->m->count; i++)
        if (h->m->daemons[i].pid == st->pid) {
            snprintf(h->m->instances[i], sizeof h->m->instances[i], "%s", st->instance);
            h->seen[i] = st->cluster_members;
        }
    h->agreeing = 0;
    for (int i = 0; i < h->m->count; i++) h->agreeing += h->seen[i] == h->m->count;
    pthread_mutex_unlock(&h->lock);
}

/* Waits until every member beats and counts them all. */
static bool members_agree(members *m, char *err, size_t err_size)
{
    mt_client *c = mt__rtt_client_new("meshtopo-bench-cluster-watch");
    if (!c) return false;
    static heard h = {.lock = PTHREAD_MUTEX_INITIALIZER};
    memset(h.seen, 0, sizeof h.seen);
    h.m = m;
    h.agreeing = 0;
    mt_client_watch *watch = NULL;
    mt_client_watch_fns fns = {.on_status = on_status, .user = &h};
    mt_diag diag;
    bool agree = false;
    if (mt_client_watch_start(c, &fns, &watch, &diag) == MT_OK) {
        double deadline = mt__bench_now_ms() + 15000;
        while (!agree && mt__bench_now_ms() < deadline) {
            struct timespec pause = {0, 20 * 1000 * 1000};
            nanosleep(&pause, NULL);
            pthread_mutex_lock(&h.lock);
            agree = h.agreeing == m->count;
            pthread_mutex_unlock(&h.lock);
        }
        mt_client_watch_stop(watch);
    }
    mt_client_destroy(c);
    if (!agree) snprintf(err, err_size, "the %d members never agreed on the cluster", m->count);
    return agree;
}

static bool start_members(const char *daemon, const char *archive, int count, int heartbeat_ms,
                          members *out, char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    char heartbeat[16];
    snprintf(heartbeat, sizeof heartbeat, "%d", heartbeat_ms);
    for (int i = 0; i < count; i++) {
        char name[32];
        snprintf(name, sizeof name, "bench-%d", i);
        const char *args[] = {
            "--cluster",       "bench",     "--archive", archive,  "--heartbeat-ms",
            heartbeat,         "--workers", "1",         "--name", name,
            "--memory-budget", "512M",      NULL};
        if (!mt__rtt_daemon_start_with(daemon, args, &out->daemons[i], err, err_size)) return false;
        out->count++;
    }
    return members_agree(out, err, err_size);
}

static bool stop_members(members *m, char *err, size_t err_size)
{
    bool ok = true;
    for (int i = 0; i < m->count; i++)
        if (m->daemons[i].pid > 0) ok = mt__rtt_daemon_stop(&m->daemons[i], err, err_size) && ok;
    return ok;
}

/* ids[0 .. n-1] named PREFIX-k, as many owned by each member. */
static void balanced_ids(const members *m, const char *prefix, uint32_t n, char (*ids)[64])
{
    uint64_t seeds[MAX_MEMBERS];
    for (int i = 0; i < m->count; i++) seeds[i] = mt_msgs_cluster_seed(m->instances[i]);
    uint32_t per_member[MAX_MEMBERS] = {0}, chosen = 0;
    const uint32_t share = (n + (uint32_t)m->count - 1) / (uint32_t)m->count;
    for (uint32_t k = 0; chosen < n; k++) {
        char id[64];
        snprintf(id, sizeof id, "%s-%" PRIu32, prefix, k);
        size_t owner = mt_msgs_cluster_owner(seeds, (size_t)m->count, id);
        if (per_member[owner] >= share) continue;
        per_member[owner]++;
        memcpy(ids[chosen++], id, sizeof id);
    }
}

/* ---- throughput ------------------------------------------------------------ */

typedef struct submitter {
    const mt_face_list *list;
    char (*ids)[64];
    uint32_t count;
    atomic_uint next;
    atomic_int failed;
    char err[256];
} submitter;

static void *submit_main(void *arg)
{
    submitter *s = arg;
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm_url = MT__RTT_LCM_URL;
    opts.source = "meshtopo-bench-cluster";
    opts.timeout_ms = 5000;
    opts.retries = 5;
    mt_client *client = NULL;
    mt_diag diag;
    if (mt_client_create(&opts, &client, &diag) != MT_OK) {
        atomic_store(&s->failed, 1);
        return NULL;
    }
    for (unsigned k = atomic_fetch_add(&s->next, 1); k < s->count;
         k = atomic_fetch_add(&s->next, 1)) {
        mt_client_ack ack;
        if (mt_client_submit(client, s->ids[k], s->list, 0, &ack, &diag) != MT_OK ||
            (uint64_t)ack.msg.content_hash != ack.sent_content_hash) {
            snprintf(s->err, sizeof s->err, "submit %s: %.200s", s->ids[k], diag.message);
            atomic_store(&s->failed, 1);
        }
        mt_client_ack_free(&ack);
    }
    mt_client_destroy(client);
    return NULL;
}

/* CPU seconds (user + system) used so far by this process (the clients)
 * and by the running members, from /proc/PID/stat. */
static double cpu_seconds(const members *m)
{
    struct rusage self;
    getrusage(RUSAGE_SELF, &self);
    double s = (double)self.ru_utime.tv_sec + (double)self.ru_utime.tv_usec / 1e6 +
               (double)self.ru_stime.tv_sec + (double)self.ru_stime.tv_usec / 1e6;
    const double tick = (double)sysconf(_SC_CLK_TCK);
    for (int i = 0; i < m->count; i++) {
        char path[64], line[1024];
        snprintf(path, sizeof path, "/proc/%d/stat", (int)m->daemons[i].pid);
        FILE *f = fopen(path, "r");
        if (!f) continue;
        size_t n = fread(line, 1, sizeof line - 1, f);
        fclose(f);
        line[n] = '\0';
        /* utime and stime are fields 14 and 15, counted after the ")" that
         * ends the command name (field 2). */
        const char *p = strrchr(line, ')');
        unsigned long long utime = 0, stime = 0;
        if (p && sscanf(p + 2, "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %llu %llu", &utime,
                        &stime) == 2)
            s += (double)(utime + stime) / tick;
    }
    return s;
}

/* Meshes per second of one run with `count` members; <0 on failure.
 * *out_cores: the CPU time the members and the submitting clients used
 * while the meshes were submitted, over that time. */
static double run_throughput(const options *o, const char *daemon, const char *archive_root,
                             const mt_face_list *list, uint32_t rep, int count, double *out_cores,
                             char *err, size_t err_size)
{
    char archive[PATH_MAX + 32];
    snprintf(archive, sizeof archive, "%s/run-%" PRIu32 "-%d", archive_root, rep, count);
    members m;
    if (!start_members(daemon, archive, count, atoi(HEARTBEAT_MS), &m, err, err_size)) {
        stop_members(&m, err, err_size);
        return -1;
    }
    static char ids[MAX_MESHES][64];
    char prefix[32];
    snprintf(prefix, sizeof prefix, "grid-%" PRIu32 "-%d", rep, count);
    balanced_ids(&m, prefix, o->meshes, ids);
    submitter s = {.list = list, .ids = ids, .count = o->meshes};
    /* Two meshes in flight per member: one built while the next arrives. */
    pthread_t threads[2 * MAX_MEMBERS];
    const int num_threads = 2 * count;
    const double cpu0 = cpu_seconds(&m), t0 = mt__bench_now_ms();
    for (int t = 0; t < num_threads; t++) pthread_create(&threads[t], NULL, submit_main, &s);
    for (int t = 0; t < num_threads; t++) pthread_join(threads[t], NULL);
    double seconds = (mt__bench_now_ms() - t0) / 1e3;
    *out_cores = (cpu_seconds(&m) - cpu0) / seconds;
    bool stopped = stop_members(&m, err, err_size);
    mt__rtt_daemon_remove_archive(archive);
    if (atomic_load(&s.failed)) {
        snprintf(err, err_size, "%s", s.err[0] ? s.err : "a submission failed");
        return -1;
    }
    return stopped ? o->meshes / seconds : -1;
}

/* ---- failover ----------------------------------------------------------- */

/* Three members with the default heartbeat; one id per member submitted,
 * one member killed: ms until its id answers from a survivor. */
static double run_failover(const char *daemon, const char *archive_root, uint32_t rep,
                           const mt_face_list *small, char *err, size_t err_size)
{
    char archive[PATH_MAX + 32];
    snprintf(archive, sizeof archive, "%s/failover-%" PRIu32, archive_root, rep);
    members m;
    double ms = -1;
    if (!start_members(daemon, archive, 3, FAILOVER_HEARTBEAT_MS, &m, err, err_size)) {
        stop_members(&m, err, err_size);
        return -1;
    }
    char ids[3][64];
    balanced_ids(&m, "failover", 3, ids);
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm_url = MT__RTT_LCM_URL;
    opts.source = "meshtopo-bench-failover";
    opts.timeout_ms = 50;
    opts.retries = 400;
    mt_client *client = NULL;
    mt_diag diag;
    if (mt_client_create(&opts, &client, &diag) == MT_OK) {
        bool ok = true;
        for (int i = 0; i < 3 && ok; i++) {
            mt_client_ack ack;
            ok = mt_client_submit(client, ids[i], small, 0, &ack, &diag) == MT_OK;
            mt_client_ack_free(&ack);
        }
        /* The victim: the owner of ids[0] (balanced_ids gives each member one). */
        uint64_t seeds[3];
        for (int i = 0; i < 3; i++) seeds[i] = mt_msgs_cluster_seed(m.instances[i]);
        size_t victim = mt_msgs_cluster_owner(seeds, 3, ids[0]);
        double killed = mt__bench_now_ms();
        kill(m.daemons[victim].pid, SIGKILL);
        waitpid(m.daemons[victim].pid, NULL, 0);
        m.daemons[victim].pid = 0;
        meshtopo_reply_t r;
        if (ok && mt_client_query(client, ids[0], 0, MESHTOPO_QUERY_T_REPORT, NULL, 0, &r, &diag) ==
                      MT_OK)
            ms = mt__bench_now_ms() - killed;
        else
            snprintf(err, err_size, "failover: %.200s", diag.message);
        mt_client_reply_free(&r);
        mt_client_destroy(client);
    }
    stop_members(&m, err, err_size);
    mt__rtt_daemon_remove_archive(archive);
    return ms;
}

int mt__bench_cluster_command(int argc, char **argv)
{
    options o;
    int parsed = parse_options(argc, argv, &o);
    if (parsed == 1) {
        usage(stdout);
        return 0;
    }
    if (parsed) return 2;
    char err[512] = "";
    int code = mt__rtt_enter_private_network(err, sizeof err);
    if (code) {
        fprintf(stderr, "meshtopo-bench cluster: %s\n", err);
        return code;
    }
    char daemon_buf[PATH_MAX];
    const char *daemon = mt__rtt_daemon_find(o.daemon_path, daemon_buf, sizeof daemon_buf);
    char root[PATH_MAX];
    struct stat shm;
    const char *tmp = getenv("TMPDIR");
    snprintf(root, sizeof root, "%s/meshtopo-bench-cluster-XXXXXX",
             o.archive                                             ? o.archive
             : stat("/dev/shm", &shm) == 0 && S_ISDIR(shm.st_mode) ? "/dev/shm"
             : tmp && *tmp                                         ? tmp
                                                                   : "/tmp");
    if (!mkdtemp(root)) {
        fprintf(stderr, "meshtopo-bench cluster: cannot make %s: %s\n", root, strerror(errno));
        return 1;
    }
    uint32_t side = 1;
    while (2ull * (side + 1) * (side + 1) <= o.triangles) side++;
    mt_face_list grid, small;
    if (mt_gen_grid(side, side, true, &grid) != MT_OK || mt_gen_grid(4, 4, true, &small) != MT_OK) {
        fprintf(stderr, "meshtopo-bench cluster: cannot generate the grids\n");
        return 1;
    }
    printf("meshtopo-bench cluster: %" PRIu32 " meshes of %" PRIu32
           " triangles per run, members with one build worker each, archive under %s\n",
           o.meshes, grid.num_faces, root);
    double one[MAX_REPS], two[MAX_REPS], ratio[MAX_REPS], failover[MAX_REPS];
    double cores_one[MAX_REPS], cores_two[MAX_REPS];
    int failed = 0;
    for (uint32_t rep = 0; rep < o.reps && !failed; rep++) {
        one[rep] =
            run_throughput(&o, daemon, root, &grid, rep, 1, &cores_one[rep], err, sizeof err);
        two[rep] = one[rep] > 0 ? run_throughput(&o, daemon, root, &grid, rep, 2, &cores_two[rep],
                                                 err, sizeof err)
                                : -1;
        if (one[rep] <= 0 || two[rep] <= 0) {
            fprintf(stderr, "meshtopo-bench cluster: run %" PRIu32 ": %s\n", rep + 1, err);
            failed = 1;
            break;
        }
        ratio[rep] = two[rep] / one[rep];
        printf("  pair %" PRIu32
               ": 1 member %.2f meshes/s (%.2f cores busy), 2 members %.2f "
               "meshes/s (%.2f cores busy): %.2fx\n",
               rep + 1, one[rep], cores_one[rep], two[rep], cores_two[rep], ratio[rep]);
    }
    for (uint32_t rep = 0; rep < o.reps && !failed; rep++) {
        failover[rep] = run_failover(daemon, root, rep, &small, err, sizeof err);
        if (failover[rep] < 0) {
            fprintf(stderr, "meshtopo-bench cluster: failover %" PRIu32 ": %s\n", rep + 1, err);
            failed = 1;
        }
    }
    rmdir(root);
    mt_face_list_free(&grid);
    mt_face_list_free(&small);
    if (failed) return 1;
    double r = median(ratio, o.reps);
    long online = sysconf(_SC_NPROCESSORS_ONLN);
    printf("\n| members | meshes/s (median of %" PRIu32
           ") | cores busy (median) |\n|---|---|---|\n"
           "| 1 | %.2f | %.2f |\n| 2 | %.2f | %.2f |\n\n",
           o.reps, median(one, o.reps), median(cores_one, o.reps), median(two, o.reps),
           median(cores_two, o.reps));
    printf(
        "this machine has %ld cores: with one member already keeping %.2f of them busy "
        "(clients included), 2 members can gain at most %.2fx here\n",
        online, median(cores_one, o.reps), (double)online / median(cores_one, o.reps));
    printf("2 members / 1 member, median of the paired ratios: %.2fx (target >= %.1fx: %s)\n", r,
           TARGET_RATIO, r >= TARGET_RATIO ? "met" : "MISSED");
    double f = median(failover, o.reps);
    printf(
        "failover, SIGKILL to the dead member's id answering (3 members, %d ms heartbeat): "
        "median %.0f ms = %.2f heartbeat periods (target <= 3: %s)\n",
        FAILOVER_HEARTBEAT_MS, f, f / FAILOVER_HEARTBEAT_MS,
        f <= 3.0 * FAILOVER_HEARTBEAT_MS ? "met" : "MISSED");
    return 0;
}
