/* meshtopod's worker pool: a fixed set of threads and a bounded job queue, so
 * a large build runs on a worker while the LCM thread keeps answering.
 * Submitting never blocks: a full queue answers MTD_SUBMIT_BUSY and the
 * daemon replies "busy" (the client retries). Every accepted job's function
 * is called exactly once, either to run it or, on a cancelling shutdown, to
 * tell it that it will not run, so its argument is always freed. */
#ifndef MESHTOPOD_WORKER_POOL_H
#define MESHTOPOD_WORKER_POOL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A job. `cancelled` is false when it runs on a worker; true when a
 * cancelling shutdown dropped it from the queue (then it is called on the
 * thread calling mtd_pool_shutdown and should only free arg or send a
 * "shutting down" reply). */
typedef void (*mtd_job_fn)(void *arg, bool cancelled);

typedef struct mtd_pool mtd_pool;

/* Limits of mtd_pool_create. */
#define MTD_POOL_MAX_THREADS 256
#define MTD_POOL_MAX_QUEUE (1u << 20)

/* Starts `threads` workers (1 .. MTD_POOL_MAX_THREADS) sharing a queue of
 * `queue_capacity` waiting jobs (1 .. MTD_POOL_MAX_QUEUE). The workers block
 * every signal, so SIGINT and SIGTERM reach the daemon's main thread.
 * Returns MT_OK, MT_ERR_INVALID_ARG for counts out of range, MT_ERR_NOMEM
 * (also when a thread cannot be started); on failure *out_pool is NULL and no
 * thread is left running. */
mt_status mtd_pool_create(uint32_t threads, uint32_t queue_capacity, mtd_pool **out_pool);

/* Outcome of mtd_pool_submit. */
typedef enum mtd_submit_result {
    MTD_SUBMIT_OK = 0, /* queued; fn will be called exactly once */
    MTD_SUBMIT_BUSY,   /* the queue is full; nothing was queued */
    MTD_SUBMIT_STOPPED /* the pool is shutting down; nothing was queued */
} mtd_submit_result;

/* Queues fn(arg, false) to run on a worker. Never blocks on the queue; safe
 * from any thread, a job included. On BUSY or STOPPED the caller still owns arg. */
mtd_submit_result mtd_pool_submit(mtd_pool *pool, mtd_job_fn fn, void *arg);

typedef enum mtd_shutdown_mode {
    /* Refuse new jobs, run every queued job, then stop the workers. */
    MTD_SHUTDOWN_DRAIN,
    /* Refuse new jobs, call every queued job with cancelled = true (on the
     * calling thread), let the running jobs finish, then stop the workers. */
    MTD_SHUTDOWN_CANCEL
} mtd_shutdown_mode;

/* Stops the pool as `mode` says and joins every worker; when it returns, no
 * job is running or left. From the first call on, submissions (from jobs too)
 * get MTD_SUBMIT_STOPPED. A second call, concurrent or later, waits for the
 * first to finish and ignores its mode. Must not be called from a job. */
void mtd_pool_shutdown(mtd_pool *pool, mtd_shutdown_mode mode);

/* Shuts down with MTD_SHUTDOWN_DRAIN if that was not done yet, then frees
 * the pool. NULL-safe. */
void mtd_pool_destroy(mtd_pool *pool);

/* Counters for the heartbeat. */
typedef struct mtd_pool_stats {
    uint32_t threads;
    uint32_t queue_capacity;
    uint32_t queued;    /* waiting now */
    uint32_t running;   /* running now */
    uint64_t completed; /* ran to the end */
    uint64_t cancelled; /* dropped by a cancelling shutdown */
    uint64_t busy;      /* submissions refused because the queue was full */
} mtd_pool_stats;

void mtd_pool_get_stats(mtd_pool *pool, mtd_pool_stats *out_stats);

#ifdef __cplusplus
}
#endif

#endif
