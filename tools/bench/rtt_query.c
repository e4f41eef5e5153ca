/* The meshtopo side of `meshtopo-bench rtt`: single-id VERTEX_RING round
 * trips through mt_client_query, and throughput runs in which several client
 * processes keep queries in flight with mt_client_query_async. Every answer
 * is checked (status, one item per id), and the one-rings are compared with
 * mt_vert_ring on the same grid built in this process (read through the
 * client's reply accessors), so a fast wrong answer never counts. */
#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "meshtopo/query.h"
#include "rtt.h"

#define RING_CAPACITY 64

static bool range_equals(const int32_t *wire, const uint32_t *local, size_t count)
{
    for (size_t i = 0; i < count; i++)
        if ((uint32_t)wire[i] != local[i]) return false;
    return true;
}

bool mt__rtt_ring_matches(const mt_mesh *local, const meshtopo_reply_t *reply, uint32_t item,
                          uint32_t vert, char *err, size_t err_size)
{
    uint32_t neighbors[RING_CAPACITY], faces[RING_CAPACITY];
    mt_fan fans[RING_CAPACITY];
    mt_ring ring = {neighbors, RING_CAPACITY, faces, RING_CAPACITY, fans, RING_CAPACITY, 0, 0, 0};
    mt_status st = mt_vert_ring(local, vert, &ring);
    if (st != MT_OK) {
        snprintf(err, err_size, "local one-ring of vertex %u: %s", vert, mt_strerror(st));
        return false;
    }
    bool answered = item < mt_client_reply_num_items(reply);
    mt_client_item answer = answered ? mt_client_reply_item(reply, item) : (mt_client_item){0};
    if (!answered || answer.status != MESHTOPO_STATUS_CODE_T_OK) {
        snprintf(err, err_size, "vertex %u: no answer in the reply", vert);
        return false;
    }
    if (answer.num_groups != ring.num_fans) {
        snprintf(err, err_size, "vertex %u: %zu fans over the wire, %zu locally", vert,
                 answer.num_groups, ring.num_fans);
        return false;
    }
    for (size_t f = 0; f < ring.num_fans; f++) {
        mt_client_group g = mt_client_item_group(reply, &answer, f);
        const mt_fan *fan = &fans[f];
        bool same = g.num_values == fan->neighbor_count && g.num_values2 == fan->face_count &&
                    g.boundary == fan->boundary &&
                    range_equals(g.values, neighbors + fan->neighbor_begin, fan->neighbor_count) &&
                    range_equals(g.values2, faces + fan->face_begin, fan->face_count);
        if (!same) {
            snprintf(err, err_size, "vertex %u: fan %zu differs from the local one-ring", vert, f);
            return false;
        }
    }
    return true;
}

bool mt__rtt_query_latency(mt_client *client, const mt_mesh *local, uint32_t count, uint64_t seed,
                           double *out_us, size_t *out_query_bytes, size_t *out_reply_bytes,
                           char *err, size_t err_size)
{
    uint64_t rng = seed;
    uint32_t num_verts = mt_mesh_num_verts(local);
    for (uint32_t i = 0; i < count; i++) {
        uint32_t vert = (uint32_t)(mt__bench_rand_u64(&rng) % num_verts);
        meshtopo_reply_t reply;
        mt_diag diag;
        mt_diag_clear(&diag);
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        mt_status st = mt_client_query(client, MT__RTT_MESH_ID, 0, MESHTOPO_QUERY_T_VERTEX_RING,
                                       &vert, 1, &reply, &diag);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        out_us[i] = mt__bench_elapsed_us(&t0, &t1);
        bool ok = st == MT_OK && mt__rtt_ring_matches(local, &reply, 0, vert, err, err_size);
        if (st != MT_OK)
            snprintf(err, err_size, "query %u (vertex %u): %s (%s)", i, vert, mt_strerror(st),
                     diag.message);
        if (ok) *out_reply_bytes = (size_t)meshtopo_reply_t_encoded_size(&reply);
        mt_client_reply_free(&reply);
        if (!ok) return false;
    }
    /* query_t of one id, as the client encodes it (its request fields set). */
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    int32_t id = 0;
    q.mesh_id = (char *)MT__RTT_MESH_ID;
    q.reply_channel = (char *)mt_client_reply_channel(client);
    q.instance = "";
    q.kind = MESHTOPO_QUERY_T_VERTEX_RING;
    q.num_ids = 1;
    q.ids = &id;
    *out_query_bytes = (size_t)meshtopo_query_t_encoded_size(&q);
    return true;
}

/* ---- throughput ---------------------------------------------------------- */

/* One client process's run; shared with its reply callback. */
typedef struct load_state {
    mt_client *client;
    const mt_mesh *local;
    uint32_t batch;
    struct timespec deadline;
    uint64_t rng;
    pthread_mutex_t lock;
    pthread_cond_t idle;
    uint32_t in_flight;
    uint64_t queries, answers, failures;
    char error[640]; /* holds an mt_diag message and a prefix */
} load_state;

static bool past(const struct timespec *deadline)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return mt__bench_elapsed_us(deadline, &now) >= 0;
}

static void on_reply(mt_status status, const meshtopo_reply_t *reply, const mt_diag *diag,
                     void *user);

/* Sends one query of `batch` random ids; call with the lock held. */
static void send_query(load_state *s)
{
    uint32_t ids[4096];
    uint32_t n = s->batch;
    uint32_t num_verts = mt_mesh_num_verts(s->local);
    for (uint32_t i = 0; i < n; i++) ids[i] = (uint32_t)(mt__bench_rand_u64(&s->rng) % num_verts);
    mt_diag diag;
    mt_diag_clear(&diag);
    s->in_flight++;
    mt_status st = mt_client_query_async(s->client, MT__RTT_MESH_ID, 0,
                                         MESHTOPO_QUERY_T_VERTEX_RING, ids, n, on_reply, s, &diag);
    if (st != MT_OK) {
        s->in_flight--;
        s->failures++;
        snprintf(s->error, sizeof s->error, "send: %s (%s)", mt_strerror(st), diag.message);
    }
}

static void on_reply(mt_status status, const meshtopo_reply_t *reply, const mt_diag *diag,
                     void *user)
{
    load_state *s = user;
    pthread_mutex_lock(&s->lock);
    s->in_flight--;
    bool ok = status == MT_OK && reply && reply->status == MESHTOPO_STATUS_CODE_T_OK &&
              mt_client_reply_num_items(reply) == s->batch;
    for (size_t i = 0; ok && i < s->batch; i++)
        ok = mt_client_reply_item(reply, i).status == MESHTOPO_STATUS_CODE_T_OK;
    if (!ok && !s->error[0])
        snprintf(s->error, sizeof s->error, "reply: %s (%s)", mt_strerror(status),
                 diag ? diag->message : "wrong shape");
    if (ok) {
        s->queries++;
        s->answers += s->batch;
    } else {
        s->failures++;
    }
    if (!past(&s->deadline))
        send_query(s);
    else if (s->in_flight == 0)
        pthread_cond_signal(&s->idle);
    pthread_mutex_unlock(&s->lock);
}

/* Checks a synchronous query of `batch` known ids against the local mesh:
 * replies do not echo their ids, so the timed replies are checked for shape
 * only and this one, before the start, for content. */
static bool check_batch(load_state *s)
{
    uint32_t ids[4096];
    uint32_t num_verts = mt_mesh_num_verts(s->local);
    for (uint32_t i = 0; i < s->batch; i++)
        ids[i] = (uint32_t)(mt__bench_rand_u64(&s->rng) % num_verts);
    meshtopo_reply_t reply;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_client_query(s->client, MT__RTT_MESH_ID, 0, MESHTOPO_QUERY_T_VERTEX_RING, ids,
                                   s->batch, &reply, &diag);
    bool ok = st == MT_OK;
    if (!ok)
        snprintf(s->error, sizeof s->error, "check query: %s (%s)", mt_strerror(st), diag.message);
    for (uint32_t i = 0; ok && i < s->batch; i++)
        ok = mt__rtt_ring_matches(s->local, &reply, i, ids[i], s->error, sizeof s->error);
    mt_client_reply_free(&reply);
    return ok;
}

typedef struct load_result {
    uint64_t queries, answers, failures;
    char error[640]; /* holds an mt_diag message and a prefix */
} load_result;

static void load_main(const mt_mesh *local, uint32_t batch, uint32_t window, double seconds,
                      uint64_t seed, int start_fd, int result_fd)
{
    load_state s;
    memset(&s, 0, sizeof s);
    s.local = local;
    s.batch = batch;
    s.rng = seed;
    pthread_mutex_init(&s.lock, NULL);
    pthread_cond_init(&s.idle, NULL);
    load_result r;
    memset(&r, 0, sizeof r);
    s.client = mt__rtt_client_new("meshtopo-bench-rtt-load");
    bool ok = s.client && check_batch(&s);
    char go = 0;
    if (read(start_fd, &go, 1) != 1) ok = false; /* everyone starts together */
    if (ok) {
        clock_gettime(CLOCK_MONOTONIC, &s.deadline);
        s.deadline.tv_sec += (time_t)seconds;
        s.deadline.tv_nsec += (long)((seconds - (double)(time_t)seconds) * 1e9);
        if (s.deadline.tv_nsec >= 1000000000L) {
            s.deadline.tv_sec++;
            s.deadline.tv_nsec -= 1000000000L;
        }
        pthread_mutex_lock(&s.lock);
        for (uint32_t i = 0; i < window; i++) send_query(&s);
        while (s.in_flight > 0 || !past(&s.deadline)) {
            struct timespec wake;
            clock_gettime(CLOCK_REALTIME, &wake);
            wake.tv_sec += 1;
            pthread_cond_timedwait(&s.idle, &s.lock, &wake);
            if (s.in_flight == 0) break;
        }
        pthread_mutex_unlock(&s.lock);
    } else if (!s.error[0]) {
        snprintf(s.error, sizeof s.error, "client did not start");
    }
    mt_client_destroy(s.client);
    r.queries = s.queries;
    r.answers = s.answers;
    r.failures = s.failures + (ok ? 0 : 1);
    snprintf(r.error, sizeof r.error, "%s", s.error);
    ssize_t written = write(result_fd, &r, sizeof r);
    _exit(written == (ssize_t)sizeof r ? 0 : 1);
}

bool mt__rtt_query_throughput(const mt_mesh *local, uint32_t clients, uint32_t batch,
                              uint32_t window, double seconds, uint64_t seed,
                              mt__rtt_throughput *out, char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    if (clients == 0 || clients > MT__RTT_MAX_CLIENTS || batch == 0 || batch > 4096 ||
        window == 0) {
        snprintf(err, err_size, "bad throughput settings");
        return false;
    }
    int start_pipe[2], result_pipe[2];
    if (pipe(start_pipe) != 0 || pipe(result_pipe) != 0) {
        snprintf(err, err_size, "pipe: %s", strerror(errno));
        return false;
    }
    pid_t pids[MT__RTT_MAX_CLIENTS];
    uint32_t started = 0;
    for (; started < clients; started++) {
        pid_t pid = fork();
        if (pid < 0) break;
        if (pid == 0) {
            close(start_pipe[1]);
            close(result_pipe[0]);
            load_main(local, batch, window, seconds, seed + 7919u * (started + 1), start_pipe[0],
                      result_pipe[1]);
        }
        pids[started] = pid;
    }
    close(start_pipe[0]);
    close(result_pipe[1]);
    /* Let every client create its LCM socket and check one answer. */
    struct timespec settle = {1, 0};
    nanosleep(&settle, NULL);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    char go[MT__RTT_MAX_CLIENTS] = {0};
    bool ok = write(start_pipe[1], go, started) == (ssize_t)started && started == clients;
    close(start_pipe[1]);
    for (uint32_t i = 0; i < started; i++) {
        load_result r;
        if (read(result_pipe[0], &r, sizeof r) != (ssize_t)sizeof r) {
            ok = false;
            snprintf(err, err_size, "a client process ended without a result");
            continue;
        }
        out->queries += r.queries;
        out->answers += r.answers;
        out->failures += r.failures;
        if (r.failures) {
            ok = false;
            snprintf(err, err_size, "%s", r.error);
        }
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    out->seconds = mt__bench_elapsed_us(&t0, &t1) / 1e6;
    close(result_pipe[0]);
    for (uint32_t i = 0; i < started; i++) {
        int status = 0;
        waitpid(pids[i], &status, 0);
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) ok = false;
    }
    if (started < clients) snprintf(err, err_size, "fork: %s", strerror(errno));
    return ok;
}
