/* Runs one build phase on several threads: worker t gets part t of the
 * phase's range. Part 0 runs on the calling thread. If a thread cannot be
 * started its part runs on the calling thread afterwards, so a phase always
 * completes and gives the same result, only slower. */
#include <pthread.h>
#include <unistd.h>

#include "build_internal.h"

typedef struct worker {
    pthread_t thread;
    int started;
    void (*fn)(mt__build *, uint32_t);
    mt__build *b;
    uint32_t part;
} worker;

static void *worker_main(void *arg)
{
    worker *w = arg;
    w->fn(w->b, w->part);
    return NULL;
}

void mt__parallel_run(mt__build *b, void (*fn)(mt__build *, uint32_t))
{
    worker workers[MT__MAX_PARTS];
    for (uint32_t t = 1; t < b->parts; t++) {
        workers[t] = (worker){.fn = fn, .b = b, .part = t};
        workers[t].started =
            pthread_create(&workers[t].thread, NULL, worker_main, &workers[t]) == 0;
    }
    fn(b, 0);
    for (uint32_t t = 1; t < b->parts; t++) {
        if (workers[t].started)
            pthread_join(workers[t].thread, NULL);
        else
            fn(b, t);
    }
}

long mt__online_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? n : 1;
}
