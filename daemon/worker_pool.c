/* The worker pool: a ring buffer of jobs guarded by one mutex and a
 * condition variable the workers wait on. The lock is held only to move a job
 * in or out of the ring, never while a job runs; shutdown sets `stopping`,
 * wakes every worker and joins them once the queue is empty. Jobs are
 * submitted from the LCM thread; they run on the pool's own threads. */
#include "worker_pool.h"

#include <pthread.h>
#include <signal.h>
#include <stdlib.h>

typedef struct job {
    mtd_job_fn fn;
    void *arg;
} job;

struct mtd_pool {
    pthread_mutex_t lock;
    pthread_cond_t work;   /* a job was queued, or the pool is stopping */
    pthread_cond_t joined; /* the workers are gone (for a second shutdown caller) */
    job *ring;             /* [capacity] */
    uint32_t capacity;
    uint32_t head;  /* next job to take */
    uint32_t count; /* jobs waiting */
    uint32_t running;
    bool stopping;     /* no more submissions; set by the first shutdown */
    bool workers_gone; /* that shutdown has joined every worker */
    uint64_t completed;
    uint64_t cancelled;
    uint64_t busy;
    uint32_t num_threads; /* started; fixed after create */
    pthread_t *threads;   /* [num_threads] */
};

static void *worker_main(void *arg)
{
    mtd_pool *pool = arg;
    pthread_mutex_lock(&pool->lock);
    for (;;) {
        while (pool->count == 0 && !pool->stopping) pthread_cond_wait(&pool->work, &pool->lock);
        if (pool->count == 0) break; /* stopping and nothing left */
        job j = pool->ring[pool->head];
        pool->head = (pool->head + 1) % pool->capacity;
        pool->count--;
        pool->running++;
        pthread_mutex_unlock(&pool->lock);
        j.fn(j.arg, false);
        pthread_mutex_lock(&pool->lock);
        pool->running--;
        pool->completed++;
    }
    pthread_mutex_unlock(&pool->lock);
    return NULL;
}

/* Joins the started workers; they leave once stopping is set and the queue
 * is empty. */
static void join_workers(mtd_pool *pool)
{
    for (uint32_t i = 0; i < pool->num_threads; i++) pthread_join(pool->threads[i], NULL);
}

static void pool_free(mtd_pool *pool)
{
    pthread_cond_destroy(&pool->joined);
    pthread_cond_destroy(&pool->work);
    pthread_mutex_destroy(&pool->lock);
    free(pool->threads);
    free(pool->ring);
    free(pool);
}

mt_status mtd_pool_create(uint32_t threads, uint32_t queue_capacity, mtd_pool **out_pool)
{
    *out_pool = NULL;
    if (threads < 1 || threads > MTD_POOL_MAX_THREADS || queue_capacity < 1 ||
        queue_capacity > MTD_POOL_MAX_QUEUE)
        return MT_ERR_INVALID_ARG;
    mtd_pool *pool = calloc(1, sizeof *pool);
    if (!pool) return MT_ERR_NOMEM;
    /* Both counts are bounded above, so these products cannot overflow. */
    pool->ring = calloc(queue_capacity, sizeof(job));
    pool->threads = calloc(threads, sizeof(pthread_t));
    if (!pool->ring || !pool->threads) {
        free(pool->ring);
        free(pool->threads);
        free(pool);
        return MT_ERR_NOMEM;
    }
    pool->capacity = queue_capacity;
    if (pthread_mutex_init(&pool->lock, NULL) != 0) {
        free(pool->ring);
        free(pool->threads);
        free(pool);
        return MT_ERR_NOMEM;
    }
    pthread_cond_init(&pool->work, NULL);
    pthread_cond_init(&pool->joined, NULL);

    /* Workers inherit this thread's signal mask: block everything while
     * starting them so that signals go to the daemon's main thread. */
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    mt_status status = MT_OK;
    for (uint32_t i = 0; i < threads; i++) {
        if (pthread_create(&pool->threads[i], NULL, worker_main, pool) != 0) {
            status = MT_ERR_NOMEM;
            break;
        }
        pool->num_threads++;
    }
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (status != MT_OK) {
        pthread_mutex_lock(&pool->lock);
        pool->stopping = true;
        pthread_cond_broadcast(&pool->work);
        pthread_mutex_unlock(&pool->lock);
        join_workers(pool);
        pool_free(pool);
        return status;
    }
    *out_pool = pool;
    return MT_OK;
}

mtd_submit_result mtd_pool_submit(mtd_pool *pool, mtd_job_fn fn, void *arg)
{
    pthread_mutex_lock(&pool->lock);
    mtd_submit_result result = MTD_SUBMIT_OK;
    if (pool->stopping) {
        result = MTD_SUBMIT_STOPPED;
    } else if (pool->count == pool->capacity) {
        pool->busy++;
        result = MTD_SUBMIT_BUSY;
    } else {
        uint32_t tail = (pool->head + pool->count) % pool->capacity;
        pool->ring[tail].fn = fn;
        pool->ring[tail].arg = arg;
        pool->count++;
        pthread_cond_signal(&pool->work);
    }
    pthread_mutex_unlock(&pool->lock);
    return result;
}

void mtd_pool_shutdown(mtd_pool *pool, mtd_shutdown_mode mode)
{
    pthread_mutex_lock(&pool->lock);
    if (pool->stopping) {
        /* Another call got here first: wait until it has joined the workers. */
        while (!pool->workers_gone) pthread_cond_wait(&pool->joined, &pool->lock);
        pthread_mutex_unlock(&pool->lock);
        return;
    }
    pool->stopping = true;
    job *dropped = NULL;
    uint32_t num_dropped = 0;
    if (mode == MTD_SHUTDOWN_CANCEL && pool->count > 0) {
        /* Take the queued jobs out under the lock and call them outside it.
         * Out of memory, they stay queued and are drained instead, which
         * still calls each exactly once. */
        dropped = malloc((size_t)pool->count * sizeof(job));
        if (dropped) {
            num_dropped = pool->count;
            for (uint32_t i = 0; i < num_dropped; i++)
                dropped[i] = pool->ring[(pool->head + i) % pool->capacity];
            pool->head = (pool->head + num_dropped) % pool->capacity;
            pool->count = 0;
            pool->cancelled += num_dropped;
        }
    }
    pthread_cond_broadcast(&pool->work);
    pthread_mutex_unlock(&pool->lock);

    for (uint32_t i = 0; i < num_dropped; i++) dropped[i].fn(dropped[i].arg, true);
    free(dropped);
    join_workers(pool);

    pthread_mutex_lock(&pool->lock);
    pool->workers_gone = true;
    pthread_cond_broadcast(&pool->joined);
    pthread_mutex_unlock(&pool->lock);
}

void mtd_pool_destroy(mtd_pool *pool)
{
    if (!pool) return;
    mtd_pool_shutdown(pool, MTD_SHUTDOWN_DRAIN);
    pool_free(pool);
}

void mtd_pool_get_stats(mtd_pool *pool, mtd_pool_stats *out_stats)
{
    pthread_mutex_lock(&pool->lock);
    out_stats->threads = pool->num_threads;
    out_stats->queue_capacity = pool->capacity;
    out_stats->queued = pool->count;
    out_stats->running = pool->running;
    out_stats->completed = pool->completed;
    out_stats->cancelled = pool->cancelled;
    out_stats->busy = pool->busy;
    pthread_mutex_unlock(&pool->lock);
}
