/* Runs a piece of work split into parts on one thread per part: part 0 on
 * the calling thread, the others on threads of their own. A thread that
 * cannot be started leaves its part to the calling thread afterwards, so
 * the work always completes and gives the same result, only slower. The
 * build's phases, the self-intersection check and its flat fans use it. */
#include <pthread.h>

#include "mesh_internal.h"

typedef struct part_job {
    pthread_t thread;
    bool started;
    mt__part_fn fn;
    void *ctx;
    uint32_t part, parts;
} part_job;

static void *run_part(void *arg)
{
    part_job *j = arg;
    j->fn(j->ctx, j->part, j->parts);
    return NULL;
}

void mt__in_parallel(uint32_t parts, mt__part_fn fn, void *ctx)
{
    part_job jobs[MT__MAX_THREADS];
    if (parts > MT__MAX_THREADS) parts = MT__MAX_THREADS;
    for (uint32_t t = 1; t < parts; t++) {
        jobs[t] = (part_job){.fn = fn, .ctx = ctx, .part = t, .parts = parts};
        jobs[t].started = pthread_create(&jobs[t].thread, NULL, run_part, &jobs[t]) == 0;
    }
    fn(ctx, 0, parts);
    for (uint32_t t = 1; t < parts; t++) {
        if (jobs[t].started)
            pthread_join(jobs[t].thread, NULL);
        else
            fn(ctx, t, parts);
    }
}

void mt__part_range(uint32_t n, uint32_t part, uint32_t parts, uint32_t *first, uint32_t *end)
{
    *first = (uint32_t)((uint64_t)n * part / parts);
    *end = (uint32_t)((uint64_t)n * (part + 1) / parts);
}
