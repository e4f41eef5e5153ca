/* Worker pool tests: every job runs exactly once on a worker, a full queue
 * answers BUSY without queueing, a draining shutdown runs what is queued, a
 * cancelling shutdown hands each queued job back once with cancelled = true
 * while the running job finishes, and concurrent shutdowns are safe. A real
 * build runs on the pool into the mesh store. */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "daemon_test_util.h"
#include "harness.h"
#include "mesh_store.h"
#include "worker_pool.h"

/* Polls cond (an expression) for up to 10 s; records a failure on timeout. */
#define WAIT_FOR(cond)                                                                    \
    do {                                                                                  \
        int mt__ms = 0;                                                                   \
        while (!(cond) && mt__ms < 10000) {                                               \
            dt_sleep_ms(1);                                                               \
            mt__ms++;                                                                     \
        }                                                                                 \
        if (!(cond)) mt_test_fail(__FILE__, __LINE__, "timed out waiting for %s", #cond); \
    } while (0)

typedef struct counters {
    atomic_int ran;       /* called with cancelled = false */
    atomic_int cancelled; /* called with cancelled = true */
    atomic_int on_submitter;
    pthread_t submitter;
} counters;

static void count_job(void *arg, bool cancelled)
{
    counters *c = arg;
    if (cancelled) {
        atomic_fetch_add(&c->cancelled, 1);
        return;
    }
    if (pthread_equal(pthread_self(), c->submitter)) atomic_fetch_add(&c->on_submitter, 1);
    atomic_fetch_add(&c->ran, 1);
}

/* A job that signals it started, then waits at a gate. */
typedef struct blocker {
    dt_gate gate;
    atomic_int started;
    atomic_int finished;
    atomic_int cancelled;
} blocker;

static void blocker_job(void *arg, bool cancelled)
{
    blocker *b = arg;
    if (cancelled) {
        atomic_fetch_add(&b->cancelled, 1);
        return;
    }
    atomic_fetch_add(&b->started, 1);
    dt_gate_wait(&b->gate);
    atomic_fetch_add(&b->finished, 1);
}

/* A job owning heap memory: freed whether it runs or is cancelled (ASan's
 * leak check catches a job that is never called). */
typedef struct owned {
    counters *c;
    char *payload;
} owned;

static void owned_job(void *arg, bool cancelled)
{
    owned *o = arg;
    count_job(o->c, cancelled);
    free(o->payload);
    free(o);
}

static owned *owned_new(counters *c)
{
    owned *o = malloc(sizeof *o);
    if (!o) return NULL;
    o->c = c;
    o->payload = malloc(64);
    return o;
}

/* Queues count owned jobs; each must be accepted (a refused one is freed). */
static void submit_owned_jobs(mtd_pool *pool, counters *c, int count)
{
    for (int i = 0; i < count; i++) {
        owned *o = owned_new(c);
        if (o && mtd_pool_submit(pool, owned_job, o) != MTD_SUBMIT_OK) {
            mt_test_fail(__FILE__, __LINE__, "submit %d refused", i);
            owned_job(o, true);
        }
    }
}

static void test_pool_runs_all_jobs(void)
{
    counters c;
    memset(&c, 0, sizeof c);
    c.submitter = pthread_self();
    mtd_pool *pool = NULL;
    CHECK_OK(mtd_pool_create(4, 16, &pool));
    if (!pool) return;
    int submitted = 0, busy = 0;
    while (submitted < 2000) {
        mtd_submit_result r = mtd_pool_submit(pool, count_job, &c);
        if (r == MTD_SUBMIT_OK)
            submitted++;
        else if (r == MTD_SUBMIT_BUSY)
            busy++; /* the queue holds 16: try again */
        else
            break;
    }
    CHECK_EQ(submitted, 2000);
    mtd_pool_destroy(pool); /* drains */
    CHECK_EQ(atomic_load(&c.ran), 2000);
    CHECK_EQ(atomic_load(&c.cancelled), 0);
    CHECK_EQ(atomic_load(&c.on_submitter), 0);
}

static void test_pool_busy_when_full(void)
{
    counters c;
    memset(&c, 0, sizeof c);
    c.submitter = pthread_self();
    blocker b;
    memset(&b, 0, sizeof b);
    dt_gate_init(&b.gate);
    mtd_pool *pool = NULL;
    CHECK_OK(mtd_pool_create(1, 2, &pool));
    if (!pool) return;

    CHECK_EQ(mtd_pool_submit(pool, blocker_job, &b), MTD_SUBMIT_OK);
    WAIT_FOR(atomic_load(&b.started) == 1); /* the only worker is busy */
    CHECK_EQ(mtd_pool_submit(pool, count_job, &c), MTD_SUBMIT_OK);
    CHECK_EQ(mtd_pool_submit(pool, count_job, &c), MTD_SUBMIT_OK);
    CHECK_EQ(mtd_pool_submit(pool, count_job, &c), MTD_SUBMIT_BUSY);
    CHECK_EQ(mtd_pool_submit(pool, count_job, &c), MTD_SUBMIT_BUSY);
    mtd_pool_stats st;
    mtd_pool_get_stats(pool, &st);
    CHECK_EQ(st.threads, 1);
    CHECK_EQ(st.queue_capacity, 2);
    CHECK_EQ(st.queued, 2);
    CHECK_EQ(st.running, 1);
    CHECK_EQ(st.busy, 2);
    CHECK_EQ(atomic_load(&c.ran), 0);

    dt_gate_open(&b.gate);
    WAIT_FOR(atomic_load(&c.ran) == 2);
    CHECK_EQ(mtd_pool_submit(pool, count_job, &c), MTD_SUBMIT_OK); /* room again */
    mtd_pool_shutdown(pool, MTD_SHUTDOWN_DRAIN);
    CHECK_EQ(atomic_load(&c.ran), 3); /* the refused ones never ran */
    mtd_pool_get_stats(pool, &st);
    CHECK_EQ(st.completed, 4);
    CHECK_EQ(st.queued, 0);
    CHECK_EQ(st.running, 0);
    mtd_pool_destroy(pool);
    dt_gate_destroy(&b.gate);
}

typedef struct shutdown_call {
    mtd_pool *pool;
    mtd_shutdown_mode mode;
    atomic_int returned;
} shutdown_call;

static void *call_shutdown(void *arg)
{
    shutdown_call *call = arg;
    mtd_pool_shutdown(call->pool, call->mode);
    atomic_store(&call->returned, 1);
    return NULL;
}

static void test_pool_shutdown_drain(void)
{
    counters c;
    memset(&c, 0, sizeof c);
    c.submitter = pthread_self();
    blocker b;
    memset(&b, 0, sizeof b);
    dt_gate_init(&b.gate);
    mtd_pool *pool = NULL;
    CHECK_OK(mtd_pool_create(2, 64, &pool));
    if (!pool) return;
    CHECK_EQ(mtd_pool_submit(pool, blocker_job, &b), MTD_SUBMIT_OK);
    CHECK_EQ(mtd_pool_submit(pool, blocker_job, &b), MTD_SUBMIT_OK);
    WAIT_FOR(atomic_load(&b.started) == 2);
    submit_owned_jobs(pool, &c, 20);

    shutdown_call call = {pool, MTD_SHUTDOWN_DRAIN, 0};
    pthread_t t;
    CHECK_EQ(pthread_create(&t, NULL, call_shutdown, &call), 0);
    /* Once shutdown has begun, new jobs are refused, but the queued ones wait.
     * Probes accepted before that count on their own. */
    counters probe;
    memset(&probe, 0, sizeof probe);
    int probes_accepted = 0;
    mtd_submit_result r;
    for (int tries = 0; tries < 10000; tries++) {
        r = mtd_pool_submit(pool, count_job, &probe);
        if (r == MTD_SUBMIT_STOPPED) break;
        if (r == MTD_SUBMIT_OK) probes_accepted++;
        dt_sleep_ms(1);
    }
    CHECK_EQ(r, MTD_SUBMIT_STOPPED);
    dt_sleep_ms(20);
    CHECK_EQ(atomic_load(&call.returned), 0); /* both workers are still blocked */
    CHECK_EQ(atomic_load(&c.ran), 0);
    dt_gate_open(&b.gate);
    pthread_join(t, NULL);
    CHECK_EQ(atomic_load(&call.returned), 1);
    CHECK_EQ(atomic_load(&b.finished), 2);
    CHECK_EQ(atomic_load(&c.ran), 20);
    CHECK_EQ(atomic_load(&c.cancelled), 0);
    CHECK_EQ(atomic_load(&probe.ran), probes_accepted);
    mtd_pool_stats st;
    mtd_pool_get_stats(pool, &st);
    CHECK_EQ(st.completed, 22 + (uint64_t)probes_accepted);
    CHECK_EQ(st.cancelled, 0);
    mtd_pool_destroy(pool);
    dt_gate_destroy(&b.gate);
}

static void test_pool_shutdown_cancel(void)
{
    counters c;
    memset(&c, 0, sizeof c);
    c.submitter = pthread_self();
    blocker b;
    memset(&b, 0, sizeof b);
    dt_gate_init(&b.gate);
    mtd_pool *pool = NULL;
    CHECK_OK(mtd_pool_create(1, 64, &pool));
    if (!pool) return;
    CHECK_EQ(mtd_pool_submit(pool, blocker_job, &b), MTD_SUBMIT_OK);
    WAIT_FOR(atomic_load(&b.started) == 1);
    submit_owned_jobs(pool, &c, 10);

    shutdown_call call = {pool, MTD_SHUTDOWN_CANCEL, 0};
    pthread_t t;
    CHECK_EQ(pthread_create(&t, NULL, call_shutdown, &call), 0);
    /* The queued jobs are handed back at once, while the running job goes on
     * and the shutdown waits for it. */
    WAIT_FOR(atomic_load(&c.cancelled) == 10);
    CHECK_EQ(mtd_pool_submit(pool, count_job, &c), MTD_SUBMIT_STOPPED);
    dt_sleep_ms(20);
    CHECK_EQ(atomic_load(&b.finished), 0);
    CHECK_EQ(atomic_load(&call.returned), 0);
    dt_gate_open(&b.gate);
    pthread_join(t, NULL);
    CHECK_EQ(atomic_load(&b.finished), 1);
    CHECK_EQ(atomic_load(&b.cancelled), 0);
    CHECK_EQ(atomic_load(&c.ran), 0);
    CHECK_EQ(atomic_load(&c.cancelled), 10);
    mtd_pool_stats st;
    mtd_pool_get_stats(pool, &st);
    CHECK_EQ(st.completed, 1);
    CHECK_EQ(st.cancelled, 10);
    CHECK_EQ(st.queued, 0);
    mtd_pool_shutdown(pool, MTD_SHUTDOWN_DRAIN); /* again: nothing happens */
    mtd_pool_destroy(pool);
    CHECK_EQ(atomic_load(&c.ran), 0);
    dt_gate_destroy(&b.gate);
}

static void test_pool_concurrent_shutdown(void)
{
    blocker b;
    memset(&b, 0, sizeof b);
    dt_gate_init(&b.gate);
    mtd_pool *pool = NULL;
    CHECK_OK(mtd_pool_create(3, 8, &pool));
    if (!pool) return;
    CHECK_EQ(mtd_pool_submit(pool, blocker_job, &b), MTD_SUBMIT_OK);
    WAIT_FOR(atomic_load(&b.started) == 1);
    shutdown_call calls[3] = {{pool, MTD_SHUTDOWN_DRAIN, 0},
                              {pool, MTD_SHUTDOWN_CANCEL, 0},
                              {pool, MTD_SHUTDOWN_DRAIN, 0}};
    pthread_t t[3];
    for (int i = 0; i < 3; i++) CHECK_EQ(pthread_create(&t[i], NULL, call_shutdown, &calls[i]), 0);
    dt_sleep_ms(20);
    for (int i = 0; i < 3; i++) CHECK_EQ(atomic_load(&calls[i].returned), 0); /* all wait */
    dt_gate_open(&b.gate);
    for (int i = 0; i < 3; i++) pthread_join(t[i], NULL);
    CHECK_EQ(atomic_load(&b.finished), 1);
    mtd_pool_destroy(pool);
    dt_gate_destroy(&b.gate);
}

/* A job that submits the next one: submission works from a worker. */
typedef struct chain {
    mtd_pool *pool;
    atomic_int left;
    atomic_int refused;
} chain;

static void chain_job(void *arg, bool cancelled)
{
    chain *ch = arg;
    if (cancelled) return;
    if (atomic_fetch_sub(&ch->left, 1) > 1 &&
        mtd_pool_submit(ch->pool, chain_job, ch) != MTD_SUBMIT_OK)
        atomic_fetch_add(&ch->refused, 1);
}

static void test_pool_submit_from_job(void)
{
    chain ch;
    memset(&ch, 0, sizeof ch);
    atomic_init(&ch.left, 100);
    CHECK_OK(mtd_pool_create(2, 4, &ch.pool));
    if (!ch.pool) return;
    CHECK_EQ(mtd_pool_submit(ch.pool, chain_job, &ch), MTD_SUBMIT_OK);
    WAIT_FOR(atomic_load(&ch.left) == 0);
    mtd_pool_destroy(ch.pool);
    CHECK_EQ(atomic_load(&ch.refused), 0);
    CHECK_EQ(atomic_load(&ch.left), 0);
}

static void test_pool_bad_args(void)
{
    mtd_pool *pool = (mtd_pool *)(void *)&pool;
    CHECK_STATUS(mtd_pool_create(0, 4, &pool), MT_ERR_INVALID_ARG);
    CHECK(pool == NULL);
    CHECK_STATUS(mtd_pool_create(1, 0, &pool), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mtd_pool_create(MTD_POOL_MAX_THREADS + 1, 4, &pool), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mtd_pool_create(1, MTD_POOL_MAX_QUEUE + 1, &pool), MT_ERR_INVALID_ARG);
    mtd_pool_destroy(NULL);

    counters c;
    memset(&c, 0, sizeof c);
    CHECK_OK(mtd_pool_create(1, 1, &pool));
    if (!pool) return;
    mtd_pool_shutdown(pool, MTD_SHUTDOWN_DRAIN);
    CHECK_EQ(mtd_pool_submit(pool, count_job, &c), MTD_SUBMIT_STOPPED);
    mtd_pool_destroy(pool);
    CHECK_EQ(atomic_load(&c.ran), 0);
    CHECK_EQ(atomic_load(&c.cancelled), 0);
}

/* A build job: builds a mesh on a worker and adds it to the store, while this
 * thread keeps acquiring another mesh from the same store. The job holds its
 * worker until this thread has answered BUILD_JOB_LOOKUPS lookups, so the
 * lookups provably happen while a job is running (a fast build could
 * otherwise finish before the first one). */
#define BUILD_JOB_LOOKUPS 100

typedef struct build_job {
    mtd_store *store;
    uint32_t level;
    atomic_int status;    /* -1 until done */
    atomic_long answered; /* lookups answered by the test thread */
} build_job;

static void run_build(void *arg, bool cancelled)
{
    build_job *job = arg;
    if (cancelled) return;
    for (int waited_ms = 0; atomic_load(&job->answered) < BUILD_JOB_LOOKUPS && waited_ms < 10000;
         waited_ms++)
        dt_sleep_ms(1);
    mt_face_list fl;
    mt_mesh *mesh = NULL;
    mt_status s = mt_gen_icosphere(job->level, &fl);
    if (s == MT_OK) {
        s = mt_mesh_build(&fl, NULL, &mesh, NULL);
        mt_face_list_free(&fl);
    }
    if (s == MT_OK) s = mt_mesh_validate(mesh, NULL);
    if (s == MT_OK) s = mtd_store_add(job->store, "sphere", mesh, NULL, NULL, NULL, NULL);
    if (s != MT_OK) mt_mesh_destroy(mesh);
    atomic_store(&job->status, (int)s);
}

static void test_pool_build_into_store(void)
{
    mtd_store *store = NULL;
    CHECK_OK(mtd_store_create(NULL, &store));
    if (!store) return;
    mt_mesh *small = dt_build_platonic(MT_CUBE);
    if (small) CHECK_OK(mtd_store_add(store, "cube", small, NULL, NULL, NULL, NULL));
    mtd_pool *pool = NULL;
    CHECK_OK(mtd_pool_create(2, 4, &pool));
    if (!pool) {
        mtd_store_destroy(store);
        return;
    }
    build_job job = {store, 5, -1, 0};
    CHECK_EQ(mtd_pool_submit(pool, run_build, &job), MTD_SUBMIT_OK);
    while (atomic_load(&job.status) == -1) {
        mtd_mesh_entry *e = NULL;
        if (mtd_store_acquire(store, "cube", 0, &e, NULL) == MT_OK) {
            if (mt_mesh_num_verts(mtd_entry_mesh(e)) == 8) atomic_fetch_add(&job.answered, 1);
            mtd_entry_release(e);
        }
    }
    mtd_pool_destroy(pool);
    CHECK_OK(atomic_load(&job.status));
    CHECK(atomic_load(&job.answered) >= BUILD_JOB_LOOKUPS);
    mtd_mesh_entry *e = NULL;
    CHECK_OK(mtd_store_acquire(store, "sphere", 1, &e, NULL));
    if (e) {
        CHECK_EQ(mt_mesh_num_faces(mtd_entry_mesh(e)), 20 * 1024);
        DT_CHECK_VALID(mtd_entry_mesh(e));
        mtd_entry_release(e);
    }
    mtd_store_destroy(store);
}

static const mt_test_case cases[] = {
    {"pool_runs_all_jobs", test_pool_runs_all_jobs},
    {"pool_busy_when_full", test_pool_busy_when_full},
    {"pool_shutdown_drain", test_pool_shutdown_drain},
    {"pool_shutdown_cancel", test_pool_shutdown_cancel},
    {"pool_concurrent_shutdown", test_pool_concurrent_shutdown},
    {"pool_submit_from_job", test_pool_submit_from_job},
    {"pool_bad_args", test_pool_bad_args},
    {"pool_build_into_store", test_pool_build_into_store},
};
const mt_test_table mt_tests_worker_pool = {cases, sizeof cases / sizeof cases[0]};
