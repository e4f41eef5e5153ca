/* meshtopod's clocks: wall time for message utimes and logs, monotonic time
 * for timeouts. Any thread. */
#ifndef MESHTOPOD_CLOCK_H
#define MESHTOPOD_CLOCK_H

#include <stdint.h>

/* Microseconds since the epoch (LCM's utime). */
int64_t mtd_now_utime(void);

/* Microseconds of CLOCK_MONOTONIC: for durations and timeouts. */
int64_t mtd_monotonic_us(void);

#endif
