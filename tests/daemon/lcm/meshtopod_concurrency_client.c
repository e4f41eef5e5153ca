/* meshtopod_concurrency_client: daemon.concurrency's client, run inside
 * netns-run next to a real meshtopod. CHILDREN processes send single-vertex
 * VERTEX_RING queries through meshtopo::client to three small generated
 * meshes, each answer checked against the core's mt_vert_ring, while this
 * process submits versions of a large grid so builds run during the queries;
 * it fails on a wrong or lost answer, or when a build held up the queries. */
#define _GNU_SOURCE
#include <inttypes.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "meshtopo/client.h"
#include "meshtopo/core.h"

/* The parent forks the children while it has no thread yet, waits for the
 * daemon and submits the small meshes; then each child sends
 * QUERIES_PER_CHILD queries (random mesh, random vertex). The parent prints
 * p50/p99 latency of the queries outside the big submissions, during their
 * transfer and ack only, and during the builds themselves (the daemon's
 * build_duration_us before each ack), and fails when p99 during the builds is
 * above P99_RATIO_LIMIT times p99 outside AND above half the shortest big
 * build (a query held up by a build waits for a good part of it; noise on a
 * shared machine alone rarely reaches that).
 *
 * usage: meshtopod_concurrency_client
 * Exit status: 0 pass, 1 fail, SKIP_STATUS (ctest's skip) when the big mesh
 * cannot fit the UDP receive buffer udpm gets here. */
#define SKIP_STATUS 77
#define CHILDREN 8
#define QUERIES_PER_CHILD 5000
#define NUM_SMALL 3
/* The big mesh: a grid of BIG_NX x BIG_NY cells split into triangles. */
#define BIG_NX 280u
#define BIG_NY 220u
/* Its submissions (new versions) start when this share of the queries is
 * done: 20 %, 40 %, 60 %, so every phase has queries before, during and after. */
#define BIG_SUBMITS 3
/* Bytes of a mesh_t besides its content (header, strings), with room to spare. */
#define MESH_MSG_OVERHEAD 4096
/* The receive buffer both ends ask for (recv_buf_size in the URL). */
#define RECV_BUF_BYTES (4u << 20)
#define HEARTBEAT_WAIT_MS 10000
#define QUERY_TIMEOUT_MS 300
#define QUERY_RETRIES 10
#define P99_RATIO_LIMIT 10.0
#define RING_CAPACITY 64

static const char *const small_ids[NUM_SMALL] = {"conc_grid", "conc_torus", "conc_icosphere"};
static const char *const big_id = "conc_big_grid";

/* One query as a child recorded it. */
typedef struct query_record {
    int64_t start_ns; /* CLOCK_MONOTONIC (shared by every process) */
    int64_t latency_ns;
} query_record;

/* Shared between the parent and the children (MAP_SHARED before fork). */
typedef struct shared_state {
    atomic_int go;   /* 1: the small meshes are held, start querying; -1: give up */
    atomic_int done; /* queries answered so far, every child */
    struct {
        uint64_t requests, attempts, timeouts;
        uint64_t wrong, failed; /* wrong answers, calls that did not return MT_OK */
        int finished;
    } child[CHILDREN];
    /* Each big submission: sent .. acked, and its build inside (the ack's
     * arrival minus the daemon's build_duration_us). */
    int64_t window_begin_ns[BIG_SUBMITS], window_end_ns[BIG_SUBMITS];
    int64_t build_begin_ns[BIG_SUBMITS];
    query_record records[CHILDREN][QUERIES_PER_CHILD];
} shared_state;

static int64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000};
    nanosleep(&ts, NULL);
}

/* xorshift64*: a child's random stream. */
static uint64_t rng_next(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * 0x2545F4914F6CDD1Dull;
}

/* ---- the meshes ---------------------------------------------------------- */

static mt_status small_mesh(int which, mt_face_list *out)
{
    switch (which) {
        case 0:
            return mt_gen_grid(24, 18, true, out);
        case 1:
            return mt_gen_torus(30, 16, out);
        default:
            return mt_gen_icosphere(3, out);
    }
}

/* mesh_t's content: 3 float64 per vertex, an int32 per face and per index. */
static uint64_t mesh_bytes(const mt_face_list *list)
{
    return 24ull * list->num_verts + 4ull * list->num_faces + 4ull * list->num_indices;
}

static mt_client *client_new(const char *source)
{
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.timeout_ms = QUERY_TIMEOUT_MS;
    opts.retries = QUERY_RETRIES;
    opts.source = source;
    mt_client *client = NULL;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_client_create(&opts, &client, &diag);
    if (st != MT_OK)
        fprintf(stderr, "%s: mt_client_create: %s (%s)\n", source, mt_strerror(st), diag.message);
    return client;
}

/* ---- a child: queries and checks ---------------------------------------- */

/* 1 when the reply's one item equals the local ring of `vert`, fan by fan,
 * the fans' values in the ring's order (read with the reply accessors). */
static int ring_matches(const meshtopo_reply_t *rep, const mt_mesh *mesh, uint32_t vert)
{
    uint32_t nb[RING_CAPACITY], faces[RING_CAPACITY];
    mt_fan fans[RING_CAPACITY];
    mt_ring ring = {nb, RING_CAPACITY, faces, RING_CAPACITY, fans, RING_CAPACITY, 0, 0, 0};
    if (mt_vert_ring(mesh, vert, &ring) != MT_OK) return 0;
    if (rep->status != MESHTOPO_STATUS_CODE_T_OK || mt_client_reply_num_items(rep) != 1 ||
        rep->num_groups != (int32_t)ring.num_fans ||
        rep->num_values != (int32_t)ring.num_neighbors ||
        rep->num_values2 != (int32_t)ring.num_faces)
        return 0;
    mt_client_item item = mt_client_reply_item(rep, 0);
    if (item.status != MESHTOPO_STATUS_CODE_T_OK || item.first_group != 0 ||
        item.num_groups != ring.num_fans)
        return 0;
    /* The groups' values are consecutive (the client checked the offsets):
     * each fan's starts where the previous one's ended. */
    size_t at = 0, at2 = 0;
    for (size_t g = 0; g < ring.num_fans; g++) {
        const mt_fan *f = &fans[g];
        mt_client_group grp = mt_client_item_group(rep, &item, g);
        if (grp.boundary != f->boundary || at != f->neighbor_begin ||
            grp.num_values != f->neighbor_count || at2 != f->face_begin ||
            grp.num_values2 != f->face_count)
            return 0;
        for (size_t k = 0; k < grp.num_values; k++)
            if ((uint32_t)grp.values[k] != nb[at + k]) return 0;
        for (size_t k = 0; k < grp.num_values2; k++)
            if ((uint32_t)grp.values2[k] != faces[at2 + k]) return 0;
        at += grp.num_values;
        at2 += grp.num_values2;
    }
    return at == ring.num_neighbors && at2 == ring.num_faces;
}

static int child_main(int index, shared_state *sh, mt_mesh *const meshes[NUM_SMALL])
{
    while (atomic_load(&sh->go) == 0) sleep_ms(5);
    if (atomic_load(&sh->go) < 0) return 1;
    char source[32];
    snprintf(source, sizeof source, "conc_child_%d", index);
    mt_client *client = client_new(source);
    if (!client) return 1;
    uint64_t seed = 0x9E3779B97F4A7C15ull * (uint64_t)(index + 1);
    uint64_t wrong = 0, failed = 0;
    for (int q = 0; q < QUERIES_PER_CHILD; q++) {
        int which = (int)(rng_next(&seed) % NUM_SMALL);
        uint32_t vert = (uint32_t)(rng_next(&seed) % mt_mesh_num_verts(meshes[which]));
        meshtopo_reply_t rep;
        mt_diag diag;
        mt_diag_clear(&diag);
        int64_t start = now_ns();
        mt_status st = mt_client_query(client, small_ids[which], 0, MESHTOPO_QUERY_T_VERTEX_RING,
                                       &vert, 1, &rep, &diag);
        int64_t end = now_ns();
        sh->records[index][q].start_ns = start;
        sh->records[index][q].latency_ns = end - start;
        if (st != MT_OK) {
            if (failed++ < 5)
                fprintf(stderr, "child %d: query %s vertex %u: %s (%s)\n", index, small_ids[which],
                        vert, mt_strerror(st), diag.message);
        } else if (!ring_matches(&rep, meshes[which], vert)) {
            if (wrong++ < 5)
                fprintf(stderr,
                        "child %d: %s vertex %u: the ring over LCM differs from the core's\n",
                        index, small_ids[which], vert);
        }
        mt_client_reply_free(&rep);
        atomic_fetch_add(&sh->done, 1);
    }
    mt_client_stats stats;
    mt_client_get_stats(client, &stats);
    sh->child[index].requests = stats.requests;
    sh->child[index].attempts = stats.attempts;
    sh->child[index].timeouts = stats.timeouts;
    sh->child[index].wrong = wrong;
    sh->child[index].failed = failed;
    sh->child[index].finished = 1;
    mt_client_destroy(client);
    return 0;
}

/* ---- the parent ----------------------------------------------------------- */

/* Submits and checks the ack; 1 and the daemon's build time, else 0. */
static int submit(mt_client *client, const char *id, const mt_face_list *list,
                  int64_t *out_build_us)
{
    mt_client_ack ack;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_client_submit(client, id, list, 0, &ack, &diag);
    const meshtopo_topology_t *t = mt_client_ack_report(&ack);
    int ok = st == MT_OK && t && t->num_faces == (int32_t)list->num_faces;
    if (!ok)
        fprintf(stderr, "submit %s: %s (%s)\n", id, mt_strerror(st), diag.message);
    else
        printf("submitted %s: version %d, %u vertices, %u faces, daemon build %" PRId64 " us\n", id,
               (int)ack.msg.version, list->num_verts, list->num_faces, t->build_duration_us);
    if (ok && out_build_us) *out_build_us = t->build_duration_us;
    mt_client_ack_free(&ack);
    return ok;
}

static int compare_i64(const void *a, const void *b)
{
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return (x > y) - (x < y);
}

/* Nearest-rank percentile (p in 0..100) of a sorted array, in microseconds. */
static double percentile_us(const int64_t *sorted, size_t n, double p)
{
    if (n == 0) return 0;
    size_t rank = (size_t)(p / 100.0 * (double)n + 0.999999);
    if (rank < 1) rank = 1;
    if (rank > n) rank = n;
    return (double)sorted[rank - 1] / 1000.0;
}

/* Where a query ran, by overlap of [start, start + latency]: */
enum { PHASE_OUTSIDE, PHASE_TRANSFER, PHASE_BUILD, NUM_PHASES };
static const char *const phase_names[NUM_PHASES] = {
    "outside the big submissions", "during a big submission's transfer and ack only",
    "during a big build"};

static int query_phase(const shared_state *sh, const query_record *r)
{
    int64_t begin = r->start_ns, end = r->start_ns + r->latency_ns;
    int phase = PHASE_OUTSIDE;
    for (int w = 0; w < BIG_SUBMITS; w++) {
        if (begin <= sh->window_end_ns[w] && end >= sh->build_begin_ns[w]) return PHASE_BUILD;
        if (begin <= sh->window_end_ns[w] && end >= sh->window_begin_ns[w]) phase = PHASE_TRANSFER;
    }
    return phase;
}

int main(void)
{
    mt_face_list small[NUM_SMALL], big;
    mt_mesh *meshes[NUM_SMALL] = {NULL, NULL, NULL};
    memset(small, 0, sizeof small);
    memset(&big, 0, sizeof big);
    mt_build_options build = {.strict = false, .threads = 1}; /* no threads before fork */
    for (int i = 0; i < NUM_SMALL; i++) {
        mt_diag diag;
        mt_diag_clear(&diag);
        if (small_mesh(i, &small[i]) != MT_OK ||
            mt_mesh_build(&small[i], &build, &meshes[i], &diag) != MT_OK) {
            fprintf(stderr, "%s: cannot generate or build (%s)\n", small_ids[i], diag.message);
            return 1;
        }
    }
    if (mt_gen_grid(BIG_NX, BIG_NY, true, &big) != MT_OK) {
        fprintf(stderr, "%s: cannot generate\n", big_id);
        return 1;
    }
    uint64_t big_bytes = mesh_bytes(&big) + MESH_MSG_OVERHEAD;
    printf("%s: %ux%u grid, %u vertices, %u triangles, %llu bytes of mesh_t\n", big_id, BIG_NX,
           BIG_NY, big.num_verts, big.num_faces, (unsigned long long)big_bytes);
    /* Queries share the daemon's receive buffer with the big message: keep it
     * within the recv_buf_size asked for, not the doubled figure the kernel grants. */
    if (big_bytes > RECV_BUF_BYTES) {
        printf("SKIP: %s (%llu bytes) does not fit the %u-byte receive buffer\n", big_id,
               (unsigned long long)big_bytes, RECV_BUF_BYTES);
        return SKIP_STATUS;
    }

    shared_state *sh =
        mmap(NULL, sizeof *sh, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (sh == MAP_FAILED) {
        perror("mmap");
        return 1;
    }
    memset(sh, 0, sizeof *sh);
    atomic_init(&sh->go, 0);
    atomic_init(&sh->done, 0);

    /* Fork while this process has no threads (no LCM, no client yet). */
    fflush(stdout);
    pid_t pids[CHILDREN];
    for (int i = 0; i < CHILDREN; i++) {
        pids[i] = fork();
        if (pids[i] < 0) {
            perror("fork");
            atomic_store(&sh->go, -1);
            for (int k = 0; k < i; k++) waitpid(pids[k], NULL, 0);
            return 1;
        }
        if (pids[i] == 0) _exit(child_main(i, sh, meshes));
    }

    int ok = 0;
    mt_client *client = client_new("conc_parent");
    meshtopo_status_t *heartbeat = NULL;
    mt_diag diag;
    mt_diag_clear(&diag);
    if (client && mt_client_wait_daemon(client, HEARTBEAT_WAIT_MS, &heartbeat, &diag) != MT_OK) {
        fprintf(stderr, "conc_parent: %s\n", diag.message);
    } else if (client) {
        printf("heartbeat from meshtopod pid %d\n", (int)heartbeat->pid);
        meshtopo_status_t_destroy(heartbeat);
        ok = 1;
        for (int i = 0; ok && i < NUM_SMALL; i++)
            ok = submit(client, small_ids[i], &small[i], NULL);
    }
    atomic_store(&sh->go, ok ? 1 : -1);

    /* The big submissions, each while the children are querying. */
    const int total = CHILDREN * QUERIES_PER_CHILD;
    int64_t run_begin = now_ns();
    int64_t shortest_build_us = INT64_MAX;
    for (int w = 0; ok && w < BIG_SUBMITS; w++) {
        int threshold = total / 5 * (w + 1);
        while (atomic_load(&sh->done) < threshold) sleep_ms(1);
        sh->window_begin_ns[w] = now_ns();
        int64_t build_us = 0;
        ok = submit(client, big_id, &big, &build_us);
        sh->window_end_ns[w] = now_ns();
        sh->build_begin_ns[w] = sh->window_end_ns[w] - build_us * 1000;
        if (build_us < shortest_build_us) shortest_build_us = build_us;
        if (ok)
            printf("  big submission %d: %.1f ms (send, build, ack) at %d of %d queries\n", w + 1,
                   (double)(sh->window_end_ns[w] - sh->window_begin_ns[w]) / 1e6, threshold, total);
    }
    if (!ok) atomic_store(&sh->go, -1);

    int children_ok = 1;
    for (int i = 0; i < CHILDREN; i++) {
        int wstatus = 0;
        if (waitpid(pids[i], &wstatus, 0) < 0 || !WIFEXITED(wstatus) || WEXITSTATUS(wstatus) != 0 ||
            !sh->child[i].finished) {
            fprintf(stderr, "child %d did not finish cleanly\n", i);
            children_ok = 0;
        }
    }
    int64_t run_end = now_ns();
    mt_client_destroy(client);

    if (ok && children_ok) {
        uint64_t requests = 0, attempts = 0, timeouts = 0, wrong = 0, failed = 0;
        for (int i = 0; i < CHILDREN; i++) {
            requests += sh->child[i].requests;
            attempts += sh->child[i].attempts;
            timeouts += sh->child[i].timeouts;
            wrong += sh->child[i].wrong;
            failed += sh->child[i].failed;
        }
        double secs = (double)(run_end - run_begin) / 1e9;
        printf("queries: %d by %d processes in %.2f s (%.0f/s), %" PRIu64 " requests, %" PRIu64
               " retries, %" PRIu64 " timed out, %" PRIu64 " failed, %" PRIu64 " wrong\n",
               total, CHILDREN, secs, total / secs, requests, attempts - requests, timeouts, failed,
               wrong);
        if (requests != (uint64_t)total || failed || wrong || timeouts) {
            fprintf(stderr, "FAIL: %" PRIu64 " of %d queries were lost or wrong\n", failed + wrong,
                    total);
            ok = 0;
        }
        int64_t *lat[NUM_PHASES];
        size_t n[NUM_PHASES] = {0, 0, 0};
        double p99[NUM_PHASES] = {0, 0, 0};
        int have = 1;
        for (int p = 0; p < NUM_PHASES; p++) {
            lat[p] = malloc(sizeof(int64_t) * (size_t)total);
            have = have && lat[p];
        }
        for (int i = 0; have && i < CHILDREN; i++)
            for (int q = 0; q < QUERIES_PER_CHILD; q++) {
                const query_record *r = &sh->records[i][q];
                int p = query_phase(sh, r);
                lat[p][n[p]++] = r->latency_ns;
            }
        for (int p = 0; have && p < NUM_PHASES; p++) {
            qsort(lat[p], n[p], sizeof *lat[p], compare_i64);
            p99[p] = percentile_us(lat[p], n[p], 99);
            printf("latency %s: %zu queries, p50 %.0f us, p99 %.0f us, max %.0f us\n",
                   phase_names[p], n[p], percentile_us(lat[p], n[p], 50), p99[p],
                   n[p] ? (double)lat[p][n[p] - 1] / 1000.0 : 0.0);
        }
        if (!have) {
            fprintf(stderr, "out of memory\n");
            ok = 0;
        } else if (n[PHASE_BUILD] == 0) {
            fprintf(stderr, "FAIL: no query overlapped a big build\n");
            ok = 0;
        } else if (p99[PHASE_BUILD] > P99_RATIO_LIMIT * p99[PHASE_OUTSIDE] &&
                   p99[PHASE_BUILD] > (double)shortest_build_us / 2) {
            fprintf(stderr,
                    "FAIL: p99 during the big builds (%.0f us) is more than %.0fx p99 "
                    "outside the big submissions (%.0f us) and more than half the shortest "
                    "build (%" PRId64 " us): a build held up queries\n",
                    p99[PHASE_BUILD], P99_RATIO_LIMIT, p99[PHASE_OUTSIDE], shortest_build_us);
            ok = 0;
        }
        for (int p = 0; p < NUM_PHASES; p++) free(lat[p]);
    } else {
        ok = 0;
    }
    printf("%s\n", ok ? "PASS" : "FAIL");

    munmap(sh, sizeof *sh);
    for (int i = 0; i < NUM_SMALL; i++) {
        mt_mesh_destroy(meshes[i]);
        mt_face_list_free(&small[i]);
    }
    mt_face_list_free(&big);
    return ok ? 0 : 1;
}
