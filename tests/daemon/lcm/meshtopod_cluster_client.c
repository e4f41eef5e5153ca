/* meshtopod_cluster_client: the cluster tests' client (daemon.cluster_*),
 * run inside netns-run beside meshtopod members of one cluster sharing one
 * archive directory. It talks to them only through meshtopo::client, as any
 * node would, and reads their heartbeats to know the members.
 *
 *   submit PREFIX N MEMBERS [--second-answers-allowed]
 *     Waits until MEMBERS members beat and agree on one view (0: does not
 *     wait), then submits PREFIX-0 .. PREFIX-(N-1) once each: every one
 *     acknowledged (printed as "ID VERSION CONTENT_HASH") and queried back
 *     with its content hash, and, unless allowed, no request answered by two
 *     members (the script counts who built what).
 *
 *   chaos MESHTOPOD ARCHIVE_DIR LOG_DIR MEMBERS ROUNDS HEARTBEAT_MS
 *     Starts MEMBERS meshtopod (cluster "chaos", one build worker each),
 *     then, ROUNDS times, while a stream of submissions and queries runs:
 *     SIGKILLs one member (in odd rounds at a random instant, in even rounds
 *     the owner of a large mesh the stream is sending in chunks, once a
 *     quarter of it is confirmed: that submission must still complete),
 *     measures the time until the ids it owned answer again (failover),
 *     starts a new member (a join under load) and waits until every member
 *     sees the same view. Then it
 *     queries every acknowledged version and stops the members it started
 *     (by PID). Fails on a lost acknowledged version, a version number
 *     acknowledged for two contents, a query or submission never answered,
 *     or a latest version older than one already acknowledged.
 *
 *   versions ID...
 *     Prints "ID VERSION CONTENT_HASH" for every version of each id listed
 *     by the members (LIST_MESHES of that id, answered by its owner).
 *
 * Exit status 0 pass, 1 fail, 2 usage. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cluster.h"
#include "meshtopo/client.h"
#include "meshtopo/core.h"

#define HEARTBEAT_WAIT_MS 10000
#define MAX_MEMBERS 8
/* Mesh ids of the chaos stream; each gets versions all along. */
#define CHAOS_IDS 48
/* Large meshes sent in chunks, one per even round: "chaos-big-ROUND". */
#define MAX_ROUNDS 64
#define BIG_CELLS 300 /* a 300 x 300 grid of triangles: about 5 MB of content */
#define MAX_RECORDS 20000

static int64_t now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
    }
}

/* A small grid whose positions depend on seq: every submission has its own
 * content hash. */
static int make_mesh(uint64_t seq, mt_face_list *out)
{
    if (mt_gen_grid(4, 3, true, out) != MT_OK) return -1;
    for (uint32_t v = 0; v < out->num_verts; v++) out->positions[3 * v + 2] = (double)seq * 1e-3;
    return 0;
}

static mt_client *client_new(int timeout_ms, int retries, const char *source)
{
    mt_client_options o;
    memset(&o, 0, sizeof o);
    o.timeout_ms = timeout_ms;
    o.retries = retries;
    o.source = source;
    mt_client *c = NULL;
    mt_diag diag;
    if (mt_client_create(&o, &c, &diag) != MT_OK) {
        fprintf(stderr, "mt_client_create: %s\n", diag.message);
        return NULL;
    }
    if (mt_client_wait_daemon(c, HEARTBEAT_WAIT_MS, NULL, &diag) != MT_OK) {
        fprintf(stderr, "no member beats: %s\n", diag.message);
        mt_client_destroy(c);
        return NULL;
    }
    return c;
}

/* REPORT of (id, version): MT_OK with the answered version and hash. */
static mt_status report_of(mt_client *c, const char *id, int32_t version, int32_t *out_version,
                           uint64_t *out_hash, mt_diag *diag)
{
    meshtopo_reply_t r;
    mt_status st = mt_client_query(c, id, version, MESHTOPO_QUERY_T_REPORT, NULL, 0, &r, diag);
    if (st == MT_OK && r.num_reports == 1) {
        *out_version = r.version;
        *out_hash = (uint64_t)r.reports[0].content_hash;
    } else if (st == MT_OK) {
        st = MT_ERR_CORRUPT;
        snprintf(diag->message, sizeof diag->message, "REPORT answered without a report");
    }
    mt_client_reply_free(&r);
    return st;
}

/* ---- submit --------------------------------------------------------------- */

typedef struct beats {
    pthread_mutex_t lock;
    char instances[MAX_MEMBERS][128];
    int32_t members_seen[MAX_MEMBERS];
    int64_t views[MAX_MEMBERS];
    int count;
} beats;

static void on_beat(const meshtopo_status_t *st, void *user)
{
    beats *b = user;
    pthread_mutex_lock(&b->lock);
    int i = 0;
    while (i < b->count && strcmp(b->instances[i], st->instance) != 0) i++;
    if (i == b->count && b->count < MAX_MEMBERS)
        snprintf(b->instances[b->count++], sizeof b->instances[0], "%s", st->instance);
    if (i < b->count) {
        b->members_seen[i] = st->cluster_members;
        b->views[i] = st->cluster_view;
    }
    pthread_mutex_unlock(&b->lock);
}

/* Waits until `members` daemons beat, each seeing them all, with one view. */
static bool members_agree(mt_client *c, int members, int timeout_ms)
{
    static beats b = {.lock = PTHREAD_MUTEX_INITIALIZER};
    mt_client_watch *watch = NULL;
    mt_client_watch_fns fns = {.on_status = on_beat, .user = &b};
    mt_diag diag;
    if (mt_client_watch_start(c, &fns, &watch, &diag) != MT_OK) return false;
    bool agree = false;
    for (int64_t start = now_us(); !agree && now_us() - start < (int64_t)timeout_ms * 1000;) {
        sleep_ms(20);
        pthread_mutex_lock(&b.lock);
        agree = b.count == members;
        for (int i = 0; i < b.count; i++)
            agree = agree && b.members_seen[i] == members && b.views[i] == b.views[0];
        pthread_mutex_unlock(&b.lock);
    }
    mt_client_watch_stop(watch);
    return agree;
}

/* Submits PREFIX-0 .. PREFIX-(n-1) once each and queries each back; prints
 * "ID VERSION CONTENT_HASH" per acknowledgement. */
static int run_submit(const char *prefix, int n, int members, bool second_answers_allowed)
{
    mt_client *c = client_new(500, 20, "cluster-submit");
    if (!c) return 1;
    if (members > 0 && !members_agree(c, members, 15000)) {
        fprintf(stderr, "FAIL: %d members never agreed on one view\n", members);
        mt_client_destroy(c);
        return 1;
    }
    int failures = 0;
    uint64_t *hashes = calloc((size_t)n, sizeof *hashes);
    for (int k = 0; k < n && hashes; k++) {
        char id[64];
        snprintf(id, sizeof id, "%s-%d", prefix, k);
        mt_face_list list;
        mt_diag diag;
        mt_client_ack ack;
        if (make_mesh((uint64_t)k, &list) != 0) return 1;
        mt_status st = mt_client_submit(c, id, &list, 0, &ack, &diag);
        mt_face_list_free(&list);
        if (st != MT_OK) {
            fprintf(stderr, "FAIL: %s: %s\n", id, diag.message);
            failures++;
        } else {
            printf("%s %d %016" PRIx64 "\n", id, (int)ack.msg.version, ack.sent_content_hash);
        }
        hashes[k] = ack.sent_content_hash;
        mt_client_ack_free(&ack);
    }
    for (int k = 0; k < n && hashes; k++) {
        char id[64];
        snprintf(id, sizeof id, "%s-%d", prefix, k);
        int32_t version = 0;
        uint64_t hash = 0;
        mt_diag diag;
        if (report_of(c, id, 0, &version, &hash, &diag) != MT_OK || hash != hashes[k]) {
            fprintf(stderr, "FAIL: %s queried back: %s, version %d\n", id, diag.message,
                    (int)version);
            failures++;
        }
    }
    sleep_ms(500); /* a second member's late answers would arrive by now */
    mt_client_stats stats;
    mt_client_get_stats(c, &stats);
    fprintf(stderr,
            "submit: %d ids submitted and queried back, %d failures, %" PRIu64
            " requests answered twice, %" PRIu64 " attempts for %" PRIu64 " requests\n",
            n, failures, stats.conflicting_answers, stats.attempts, stats.requests);
    if (stats.conflicting_answers && !second_answers_allowed) {
        fprintf(stderr, "FAIL: %" PRIu64 " requests were answered by two members\n",
                stats.conflicting_answers);
        failures++;
    }
    free(hashes);
    mt_client_destroy(c);
    return failures ? 1 : 0;
}

/* ---- versions ------------------------------------------------------------- */

static int run_versions(int argc, char **argv)
{
    mt_client *c = client_new(500, 20, "cluster-versions");
    if (!c) return 1;
    int failures = 0;
    for (int i = 0; i < argc; i++) {
        meshtopo_reply_t r;
        mt_diag diag;
        if (mt_client_list(c, argv[i], &r, &diag) != MT_OK) {
            fprintf(stderr, "FAIL: list %s: %s\n", argv[i], diag.message);
            failures++;
            continue;
        }
        for (int32_t k = 0; k < r.num_meshes; k++)
            printf("%s %d %016" PRIx64 "\n", r.list_mesh_ids[k], (int)r.list_versions[k],
                   (uint64_t)r.list_content_hashes[k]);
        mt_client_reply_free(&r);
    }
    mt_client_destroy(c);
    return failures ? 1 : 0;
}

/* ---- chaos ---------------------------------------------------------------- */

typedef struct member {
    pid_t pid;
    int number; /* member-NUMBER, its --name */
    char instance[128];
    int32_t members_seen;
    int64_t view;
    int64_t heard_us;
} member;

/* One acknowledged version. */
typedef struct record {
    int id;
    int32_t version;
    uint64_t hash;
} record;

typedef struct chaos {
    const char *meshtopod, *archive, *logs;
    int heartbeat_ms;
    pthread_mutex_t lock;
    member members[MAX_MEMBERS];
    int num_members, next_number;
    record records[MAX_RECORDS];
    int num_records;
    int32_t highest_acked[CHAOS_IDS + MAX_ROUNDS];
    atomic_int stop;
    /* The large submission of an even round: main asks for it (big_round),
     * the stream sends it and says when a quarter is confirmed (big_quarter)
     * and when it was acknowledged (big_done: 1 acknowledged, -1 failed). */
    atomic_int big_round, big_quarter, big_done;
    int64_t big_killed_us, big_acked_us;
    int64_t submitted, queried, failed_ops, stale_latest, wrong_hash, reused_versions;
} chaos;

static void on_status(const meshtopo_status_t *st, void *user)
{
    chaos *ch = user;
    pthread_mutex_lock(&ch->lock);
    for (int i = 0; i < ch->num_members; i++) {
        member *m = &ch->members[i];
        if (m->pid != st->pid) continue;
        snprintf(m->instance, sizeof m->instance, "%s", st->instance);
        m->members_seen = st->cluster_members;
        m->view = st->cluster_view;
        m->heard_us = now_us();
    }
    pthread_mutex_unlock(&ch->lock);
}

static int start_member(chaos *ch)
{
    int number = ch->next_number++;
    char name[32], log[512], heartbeat[16];
    snprintf(name, sizeof name, "member-%d", number);
    snprintf(log, sizeof log, "%s/%s.log", ch->logs, name);
    snprintf(heartbeat, sizeof heartbeat, "%d", ch->heartbeat_ms);
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        int fd = open(log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
        if (fd >= 0) dup2(fd, 2);
        execl(ch->meshtopod, ch->meshtopod, "--cluster", "chaos", "--archive", ch->archive,
              "--heartbeat-ms", heartbeat, "--name", name, "--workers", "1", (char *)NULL);
        _exit(127);
    }
    pthread_mutex_lock(&ch->lock);
    member *m = &ch->members[ch->num_members++];
    memset(m, 0, sizeof *m);
    m->pid = pid;
    m->number = number;
    pthread_mutex_unlock(&ch->lock);
    printf("started member-%d (pid %d)\n", number, (int)pid);
    return 0;
}

/* Waits until every member beats, sees all of them and all see one view.
 * Returns the time it took in ms, -1 after timeout_ms. */
static int wait_settled(chaos *ch, int timeout_ms)
{
    int64_t start = now_us();
    while (now_us() - start < (int64_t)timeout_ms * 1000) {
        pthread_mutex_lock(&ch->lock);
        bool settled = true;
        for (int i = 0; i < ch->num_members; i++) {
            const member *m = &ch->members[i];
            settled = settled && m->heard_us > 0 && m->members_seen == ch->num_members &&
                      m->view == ch->members[0].view;
        }
        pthread_mutex_unlock(&ch->lock);
        if (settled) return (int)((now_us() - start) / 1000);
        sleep_ms(20);
    }
    return -1;
}

/* Ids 0 .. CHAOS_IDS - 1 are the stream's small meshes, the ones above the
 * large meshes of the even rounds. */
static void chaos_id(int k, char *id, size_t size)
{
    if (k < CHAOS_IDS)
        snprintf(id, size, "chaos-%d", k);
    else
        snprintf(id, size, "chaos-big-%d", k - CHAOS_IDS);
}

static chaos *progress_chaos;

static void on_progress(uint64_t done, uint64_t total, void *user)
{
    (void)user;
    if (done >= total / 4) atomic_store(&progress_chaos->big_quarter, 1);
}

/* Records an ack; a version acknowledged before for another content is a
 * number used twice. */
static void record_ack(chaos *ch, int k, int32_t version, uint64_t hash)
{
    pthread_mutex_lock(&ch->lock);
    for (int i = 0; i < ch->num_records; i++)
        if (ch->records[i].id == k && ch->records[i].version == version &&
            ch->records[i].hash != hash) {
            ch->reused_versions++;
            fprintf(stderr, "FAIL: chaos-%d version %d acknowledged for two contents\n", k,
                    (int)version);
        }
    if (ch->num_records < MAX_RECORDS) ch->records[ch->num_records++] = (record){k, version, hash};
    if (version > ch->highest_acked[k]) ch->highest_acked[k] = version;
    pthread_mutex_unlock(&ch->lock);
}

/* Submits one new version of chaos-k; 0 when acknowledged. */
static int submit_one(chaos *ch, mt_client *c, int k, uint64_t seq)
{
    char id[32];
    chaos_id(k, id, sizeof id);
    mt_face_list list;
    if (k >= CHAOS_IDS ? mt_gen_grid(BIG_CELLS, BIG_CELLS, true, &list) != MT_OK
                       : make_mesh(seq, &list) != 0)
        return -1;
    mt_client_ack ack;
    mt_diag diag;
    mt_status st = mt_client_submit(c, id, &list, 0, &ack, &diag);
    mt_face_list_free(&list);
    int rc = 0;
    if (st == MT_OK) {
        record_ack(ch, k, ack.msg.version, ack.sent_content_hash);
    } else {
        fprintf(stderr, "FAIL: submit %s: %s\n", id, diag.message);
        rc = -1;
    }
    mt_client_ack_free(&ack);
    return rc;
}

/* Queries the latest version of chaos-k: it must be at least the highest
 * acknowledged before the query and, when acknowledged, have its hash. */
static int query_latest(chaos *ch, mt_client *c, int k)
{
    char id[32];
    chaos_id(k, id, sizeof id);
    pthread_mutex_lock(&ch->lock);
    int32_t floor = ch->highest_acked[k];
    pthread_mutex_unlock(&ch->lock);
    int32_t version = 0;
    uint64_t hash = 0;
    mt_diag diag;
    if (report_of(c, id, 0, &version, &hash, &diag) != MT_OK) {
        fprintf(stderr, "FAIL: query %s: %s\n", id, diag.message);
        return -1;
    }
    int rc = 0;
    pthread_mutex_lock(&ch->lock);
    if (version < floor) {
        ch->stale_latest++;
        fprintf(stderr, "FAIL: %s latest is version %d, version %d was acknowledged before\n", id,
                (int)version, (int)floor);
        rc = -1;
    }
    for (int i = 0; i < ch->num_records; i++)
        if (ch->records[i].id == k && ch->records[i].version == version &&
            ch->records[i].hash != hash) {
            ch->wrong_hash++;
            rc = -1;
        }
    pthread_mutex_unlock(&ch->lock);
    return rc;
}

static void *stream_main(void *arg)
{
    chaos *ch = arg;
    /* Attempts of 100 ms, retried for 20 s: a member's death costs a few. */
    mt_client_options o;
    memset(&o, 0, sizeof o);
    o.timeout_ms = 100;
    o.retries = 200;
    o.source = "cluster-stream";
    o.progress = on_progress;
    progress_chaos = ch;
    mt_client *c = NULL;
    mt_diag diag;
    if (mt_client_create(&o, &c, &diag) != MT_OK) {
        ch->failed_ops++;
        return NULL;
    }
    uint64_t seq = 1000;
    unsigned rng = 12345;
    while (!atomic_load(&ch->stop)) {
        int big = atomic_exchange(&ch->big_round, 0);
        if (big) {
            int rc = submit_one(ch, c, CHAOS_IDS + big, seq++);
            ch->big_acked_us = now_us();
            atomic_store(&ch->big_done, rc == 0 ? 1 : -1);
            continue;
        }
        int k = (int)(rand_r(&rng) % CHAOS_IDS);
        if (submit_one(ch, c, k, seq++) != 0) ch->failed_ops++;
        ch->submitted++;
        for (int q = 0; q < 3; q++) {
            if (query_latest(ch, c, (int)(rand_r(&rng) % CHAOS_IDS)) != 0) ch->failed_ops++;
            ch->queried++;
        }
    }
    mt_client_destroy(c);
    return NULL;
}

/* Kills one member: the owner of id `target` (an index for chaos_id), or a
 * random one when target < 0. Returns the failover time in ms (the last of
 * its ids to answer again), -1 when one never did. */
static int kill_and_measure(chaos *ch, mt_client *probe, unsigned *rng, int target)
{
    pthread_mutex_lock(&ch->lock);
    const char *instances[MAX_MEMBERS];
    for (int i = 0; i < ch->num_members; i++) instances[i] = ch->members[i].instance;
    int victim = (int)(rand_r(rng) % (unsigned)ch->num_members);
    if (target >= 0) {
        char id[32];
        chaos_id(target, id, sizeof id);
        victim = (int)mtd_cluster_owner_of(instances, (size_t)ch->num_members, id);
    }
    bool owned[CHAOS_IDS];
    int dead_ids = 0;
    for (int k = 0; k < CHAOS_IDS; k++) {
        char id[32];
        chaos_id(k, id, sizeof id);
        owned[k] = mtd_cluster_owner_of(instances, (size_t)ch->num_members, id) == (size_t)victim;
        dead_ids += owned[k];
    }
    member dead = ch->members[victim];
    ch->members[victim] = ch->members[--ch->num_members];
    pthread_mutex_unlock(&ch->lock);

    int64_t killed = now_us();
    ch->big_killed_us = killed;
    kill(dead.pid, SIGKILL);
    waitpid(dead.pid, NULL, 0);
    int64_t last = killed;
    int unanswered = 0;
    for (int k = 0; k < CHAOS_IDS; k++) {
        if (!owned[k]) continue;
        if (query_latest(ch, probe, k) != 0) unanswered++;
        int64_t t = now_us();
        if (t > last) last = t;
    }
    int ms = (int)((last - killed) / 1000);
    printf("killed member-%d (pid %d, %d of %d ids): they answered again after %d ms%s\n",
           dead.number, (int)dead.pid, dead_ids, CHAOS_IDS, ms,
           unanswered ? " (some never did)" : "");
    return unanswered ? -1 : ms;
}

static int compare_int(const void *a, const void *b)
{
    return *(const int *)a - *(const int *)b;
}

static int run_chaos(chaos *ch, int members, int rounds)
{
    pthread_mutex_init(&ch->lock, NULL);
    for (int i = 0; i < members; i++)
        if (start_member(ch) != 0) return 1;
    mt_client *probe = client_new(50, 400, "cluster-probe");
    if (!probe) return 1;
    mt_client_watch *watch = NULL;
    mt_client_watch_fns fns = {.on_status = on_status, .user = ch};
    mt_diag diag;
    if (mt_client_watch_start(probe, &fns, &watch, &diag) != MT_OK) return 1;
    int failures = 0;
    int settle_ms = wait_settled(ch, 15000);
    printf("%d members agree on one view after %d ms\n", members, settle_ms);
    if (settle_ms < 0) failures++;
    /* Every id gets a first version before anything is killed. */
    for (int k = 0; k < CHAOS_IDS; k++)
        if (submit_one(ch, probe, k, (uint64_t)k) != 0) failures++;

    pthread_t stream;
    pthread_create(&stream, NULL, stream_main, ch);
    unsigned rng = (unsigned)getpid();
    int failover[MAX_ROUNDS], num_failover = 0;
    for (int round = 0; round < rounds && round < MAX_ROUNDS; round++) {
        int big = round % 2 ? round : 0; /* the second, fourth, ... round */
        int ms;
        if (big) {
            /* The owner of a large mesh in flight, a quarter of it confirmed. */
            atomic_store(&ch->big_quarter, 0);
            atomic_store(&ch->big_done, 0);
            atomic_store(&ch->big_round, big);
            int64_t asked = now_us();
            while (!atomic_load(&ch->big_quarter) && !atomic_load(&ch->big_done) &&
                   now_us() - asked < 20000000)
                sleep_ms(1);
            bool in_flight = atomic_load(&ch->big_quarter) && !atomic_load(&ch->big_done);
            ms = kill_and_measure(ch, probe, &rng, CHAOS_IDS + big);
            while (!atomic_load(&ch->big_done) && now_us() - asked < 30000000) sleep_ms(5);
            int done = atomic_load(&ch->big_done);
            printf("round %d: the owner of chaos-big-%d was killed %s; the submission %s",
                   round + 1, big,
                   in_flight ? "with a quarter of its chunks confirmed" : "(not in flight: FAIL)",
                   done == 1 ? "was acknowledged" : "FAILED");
            if (done == 1)
                printf(" %.0f ms after the kill\n",
                       (double)(ch->big_acked_us - ch->big_killed_us) / 1e3);
            else
                printf("\n");
            if (!in_flight || done != 1) failures++;
        } else {
            sleep_ms(300 + (int)(rand_r(&rng) % 1200)); /* a random instant of the stream */
            ms = kill_and_measure(ch, probe, &rng, -1);
        }
        if (ms < 0)
            failures++;
        else
            failover[num_failover++] = ms;
        sleep_ms(200);
        if (start_member(ch) != 0) return 1;
        int settled = wait_settled(ch, 30000);
        printf("round %d: a new member joined under load; views agree after %d ms\n", round + 1,
               settled);
        if (settled < 0) failures++;
    }
    sleep_ms(500);
    atomic_store(&ch->stop, 1);
    pthread_join(stream, NULL);

    /* Every acknowledged version, queried by number. */
    int lost = 0;
    for (int i = 0; i < ch->num_records; i++) {
        char id[32];
        chaos_id(ch->records[i].id, id, sizeof id);
        int32_t version = 0;
        uint64_t hash = 0;
        if (report_of(probe, id, ch->records[i].version, &version, &hash, &diag) != MT_OK ||
            version != ch->records[i].version || hash != ch->records[i].hash) {
            fprintf(stderr, "FAIL: acknowledged %s version %d lost: %s\n", id,
                    (int)ch->records[i].version, diag.message);
            lost++;
        }
    }
    mt_client_watch_stop(watch);
    mt_client_stats stats;
    mt_client_get_stats(probe, &stats);
    mt_client_destroy(probe);
    for (int i = 0; i < ch->num_members; i++) {
        kill(ch->members[i].pid, SIGTERM);
        int status = 0;
        waitpid(ch->members[i].pid, &status, 0);
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            fprintf(stderr, "FAIL: member-%d did not stop cleanly\n", ch->members[i].number);
            failures++;
        }
    }
    qsort(failover, (size_t)num_failover, sizeof *failover, compare_int);
    printf("chaos: %d rounds, %" PRId64 " submissions and %" PRId64
           " queries in the stream, %d versions acknowledged, %d lost, %" PRId64
           " failed operations, %" PRId64 " stale latest versions, %" PRId64
           " wrong hashes, %" PRId64 " numbers acknowledged twice\n",
           rounds, ch->submitted, ch->queried, ch->num_records, lost, ch->failed_ops,
           ch->stale_latest, ch->wrong_hash, ch->reused_versions);
    if (num_failover)
        printf(
            "failover (kill to the dead member's ids answering): median %d ms, max %d ms, "
            "%.1f and %.1f heartbeat periods of %d ms\n",
            failover[num_failover / 2], failover[num_failover - 1],
            (double)failover[num_failover / 2] / ch->heartbeat_ms,
            (double)failover[num_failover - 1] / ch->heartbeat_ms, ch->heartbeat_ms);
    return failures || lost || ch->failed_ops || ch->stale_latest || ch->wrong_hash ||
                   ch->reused_versions
               ? 1
               : 0;
}

int main(int argc, char **argv)
{
    if ((argc == 5 || argc == 6) && strcmp(argv[1], "submit") == 0)
        return run_submit(argv[2], atoi(argv[3]), atoi(argv[4]),
                          argc == 6 && strcmp(argv[5], "--second-answers-allowed") == 0);
    if (argc >= 3 && strcmp(argv[1], "versions") == 0) return run_versions(argc - 2, argv + 2);
    if (argc == 8 && strcmp(argv[1], "chaos") == 0) {
        static chaos ch;
        ch.meshtopod = argv[2];
        ch.archive = argv[3];
        ch.logs = argv[4];
        ch.heartbeat_ms = atoi(argv[7]);
        int members = atoi(argv[5]), rounds = atoi(argv[6]);
        if (members < 2 || members > MAX_MEMBERS - 1 || rounds < 1 || ch.heartbeat_ms < 10) {
            fprintf(stderr, "chaos: 2..%d members, 1 or more rounds, heartbeat >= 10 ms\n",
                    MAX_MEMBERS - 1);
            return 2;
        }
        return run_chaos(&ch, members, rounds);
    }
    fprintf(stderr,
            "usage: meshtopod_cluster_client submit PREFIX N MEMBERS [--second-answers-allowed]\n"
            "       meshtopod_cluster_client versions ID...\n"
            "       meshtopod_cluster_client chaos MESHTOPOD ARCHIVE_DIR LOG_DIR MEMBERS ROUNDS "
            "HEARTBEAT_MS\n");
    return 2;
}
