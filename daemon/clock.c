/* meshtopod's clocks (clock.h): clock_gettime, realtime and monotonic. Any
 * thread. */
#include "clock.h"

#include <time.h>

static int64_t microseconds(clockid_t clock)
{
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

int64_t mtd_now_utime(void)
{
    return microseconds(CLOCK_REALTIME);
}

int64_t mtd_monotonic_us(void)
{
    return microseconds(CLOCK_MONOTONIC);
}
