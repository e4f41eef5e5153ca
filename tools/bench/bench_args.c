/* Command-line values the benchmark subcommands share: a decimal count
 * within bounds. */
#include <errno.h>
#include <stdlib.h>

#include "bench.h"

bool mt__bench_parse_u64(const char *text, uint64_t min, uint64_t max, uint64_t *out)
{
    if (!text) return false;
    char *end;
    errno = 0;
    unsigned long long v = strtoull(text, &end, 10);
    if (errno || end == text || *end || text[0] == '-' || v < min || v > max) return false;
    *out = v;
    return true;
}

bool mt__bench_parse_u32(const char *text, uint32_t min, uint32_t max, uint32_t *out)
{
    uint64_t v;
    if (!mt__bench_parse_u64(text, min, max, &v)) return false;
    *out = (uint32_t)v;
    return true;
}
