/* The two meters of meshtopo-bench: a monotonic clock (milliseconds, the
 * microseconds between two readings, and a pause) and the bytes the heap has handed out
 * (mallinfo2: all arenas plus mmapped blocks, so a difference taken around a
 * build is the memory the build keeps). Without glibc 2.33+ the heap meter
 * answers -1 (unknown). */
#include <time.h>

#include "bench.h"

#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
#include <malloc.h>
#define MT__BENCH_HAVE_MALLINFO2 1
#endif

double mt__bench_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

double mt__bench_elapsed_us(const struct timespec *a, const struct timespec *b)
{
    return (double)(b->tv_sec - a->tv_sec) * 1e6 + (double)(b->tv_nsec - a->tv_nsec) / 1e3;
}

int64_t mt__bench_heap_bytes(void)
{
#ifdef MT__BENCH_HAVE_MALLINFO2
    struct mallinfo2 info = mallinfo2();
    return (int64_t)(info.uordblks + info.hblkhd);
#else
    return -1;
#endif
}

void mt__bench_sleep_ms(double ms)
{
    struct timespec ts = {(time_t)(ms / 1000), (long)((ms - 1000.0 * (time_t)(ms / 1000)) * 1e6)};
    nanosleep(&ts, NULL);
}
