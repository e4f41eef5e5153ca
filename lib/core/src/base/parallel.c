/* Runs a piece of work split into parts on one thread per part: part 0 on
 * the calling thread, the others on threads of their own. A thread that
 * cannot be started leaves its part to the calling thread afterwards, so
 * the work always completes and gives the same result, only slower. The
 * build's phases, the self-intersection check and its flat fans use it.
 *
 * A part's thread starts on another CPU than the calling thread's. Left
 * to itself, the kernel may start it on the caller's own CPU when the
 * caller has been idle a while (in a long-lived process, between two
 * builds), and the two then share one CPU until a load balance moves one,
 * which a phase of a few milliseconds does not outlast. Once it runs, the
 * thread may go anywhere the caller may; the caller lets one that has not
 * started yet go anywhere too before waiting for it, so a busy other CPU
 * never holds the work up. */
#define _GNU_SOURCE /* cpu_set_t, sched_getcpu, pthread_attr_setaffinity_np */
#include <pthread.h>
#include <sched.h>

#include "base/base.h"

typedef struct part_job {
    pthread_t thread;
    bool started;
    mt__part_fn fn;
    void *ctx;
    uint32_t part, parts;
    const cpu_set_t *allowed; /* where the thread may go once it runs; NULL: anywhere */
} part_job;

static void *run_part(void *arg)
{
    part_job *j = arg;
    if (j->allowed) pthread_setaffinity_np(pthread_self(), sizeof *j->allowed, j->allowed);
    j->fn(j->ctx, j->part, j->parts);
    return NULL;
}

/* The CPUs the calling thread may use (*allowed) and those of them it is
 * not on (*elsewhere). false when there is no other, or they are not known. */
static bool cpus_elsewhere(cpu_set_t *allowed, cpu_set_t *elsewhere)
{
    if (sched_getaffinity(0, sizeof *allowed, allowed) != 0) return false;
    int here = sched_getcpu();
    if (here < 0 || here >= CPU_SETSIZE || !CPU_ISSET(here, allowed)) return false;
    *elsewhere = *allowed;
    CPU_CLR(here, elsewhere);
    return CPU_COUNT(elsewhere) > 0;
}

void mt__in_parallel(uint32_t parts, mt__part_fn fn, void *ctx)
{
    part_job jobs[MT__MAX_THREADS];
    if (parts > MT__MAX_THREADS) parts = MT__MAX_THREADS;
    cpu_set_t allowed, elsewhere;
    pthread_attr_t attr;
    bool spread =
        parts > 1 && cpus_elsewhere(&allowed, &elsewhere) && pthread_attr_init(&attr) == 0;
    if (spread && pthread_attr_setaffinity_np(&attr, sizeof elsewhere, &elsewhere) != 0) {
        pthread_attr_destroy(&attr);
        spread = false;
    }
    for (uint32_t t = 1; t < parts; t++) {
        jobs[t] = (part_job){.fn = fn, .ctx = ctx, .part = t, .parts = parts};
        jobs[t].allowed = spread ? &allowed : NULL;
        jobs[t].started =
            pthread_create(&jobs[t].thread, spread ? &attr : NULL, run_part, &jobs[t]) == 0;
    }
    if (spread) pthread_attr_destroy(&attr);
    fn(ctx, 0, parts);
    for (uint32_t t = 1; t < parts; t++) {
        if (!jobs[t].started) {
            fn(ctx, t, parts);
            continue;
        }
        /* one not running yet may now run anywhere; on one that has ended
         * the call changes nothing (its id is gone, and the call then sets
         * this thread's mask, which `allowed` already is) */
        if (spread) pthread_setaffinity_np(jobs[t].thread, sizeof allowed, &allowed);
        pthread_join(jobs[t].thread, NULL);
    }
}

void mt__part_range(uint32_t n, uint32_t part, uint32_t parts, uint32_t *first, uint32_t *end)
{
    *first = (uint32_t)((uint64_t)n * part / parts);
    *end = (uint32_t)((uint64_t)n * (part + 1) / parts);
}
