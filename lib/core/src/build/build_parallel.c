/* Runs one build phase on several threads (parallel.c): worker t gets
 * part t of the phase's range; and how many cores there are. */
#include <unistd.h>

#include "build/build_state.h"

typedef struct phase {
    void (*fn)(mt__build *, uint32_t);
    mt__build *b;
} phase;

static void run_phase_part(void *ctx, uint32_t part, uint32_t parts)
{
    (void)parts;
    const phase *p = ctx;
    p->fn(p->b, part);
}

void mt__parallel_run(mt__build *b, void (*fn)(mt__build *, uint32_t))
{
    phase p = {fn, b};
    mt__in_parallel(b->parts, run_phase_part, &p);
}

long mt__online_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? n : 1;
}
