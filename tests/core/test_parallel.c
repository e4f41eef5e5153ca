/* mt__in_parallel (lib/core/src/base/parallel.c): every part runs once, and a
 * part's thread starts on another CPU than the caller's, even after the
 * caller has been idle, then may run anywhere the caller may. */
#define _GNU_SOURCE /* cpu_set_t, sched_getcpu */
#include <sched.h>
#include <stdatomic.h>
#include <string.h>
#include <time.h>

#include "harness.h"
#include "mesh/mesh_internal.h"

typedef struct parts_seen {
    atomic_int runs[MT__MAX_THREADS];
    uint32_t parts_told[MT__MAX_THREADS];
} parts_seen;

static void count_part(void *ctx, uint32_t part, uint32_t parts)
{
    parts_seen *s = ctx;
    atomic_fetch_add(&s->runs[part], 1);
    s->parts_told[part] = parts;
}

static void parallel_runs_every_part_once(void)
{
    for (uint32_t parts = 1; parts <= MT__MAX_THREADS + 2; parts++) {
        parts_seen s;
        memset(&s, 0, sizeof s);
        mt__in_parallel(parts, count_part, &s);
        uint32_t ran = parts < MT__MAX_THREADS ? parts : MT__MAX_THREADS;
        for (uint32_t p = 0; p < MT__MAX_THREADS; p++) {
            CHECK_EQ(atomic_load(&s.runs[p]), p < ran ? 1 : 0);
            if (p < ran) CHECK_EQ(s.parts_told[p], ran);
        }
    }
}

/* Where part 1 ran and what it was allowed. */
typedef struct placement {
    int cpu;
    cpu_set_t allowed;
} placement;

static void note_placement(void *ctx, uint32_t part, uint32_t parts)
{
    (void)parts;
    placement *p = ctx;
    if (part != 1) return;
    p->cpu = sched_getcpu();
    CPU_ZERO(&p->allowed);
    sched_getaffinity(0, sizeof p->allowed, &p->allowed);
}

static void parallel_part_starts_elsewhere(void)
{
    cpu_set_t mine;
    CHECK(sched_getaffinity(0, sizeof mine, &mine) == 0);
    if (CPU_COUNT(&mine) < 2) {
        printf("skip: this thread may use one CPU only\n");
        return;
    }
    int elsewhere = 0;
    for (int attempt = 0; attempt < 5; attempt++) {
        /* idle a while first, as a long-lived process between two builds */
        struct timespec pause = {0, 50 * 1000 * 1000};
        nanosleep(&pause, NULL);
        placement p = {.cpu = -1};
        int here = sched_getcpu();
        mt__in_parallel(2, note_placement, &p);
        CHECK(p.cpu >= 0);
        CHECK(CPU_EQUAL(&p.allowed, &mine)); /* once running, anywhere the caller may */
        elsewhere += p.cpu != here;
    }
    CHECK(elsewhere > 0);
}

static const mt_test_case cases[] = {
    {"parallel_runs_every_part_once", parallel_runs_every_part_once},
    {"parallel_part_starts_elsewhere", parallel_part_starts_elsewhere},
};
const mt_test_table mt_tests_parallel = {cases, sizeof cases / sizeof cases[0]};
