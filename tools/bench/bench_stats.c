/* Order statistics every benchmark program reports: the median of its
 * repetitions and, for round trips, nearest-rank quantiles (both sort the
 * values in place); and the benchmarks' one random sequence. */
#include <math.h>
#include <stdlib.h>

#include "bench.h"

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double mt__bench_median_of(double *values, uint32_t n)
{
    if (n == 0) return NAN;
    qsort(values, n, sizeof *values, compare_double);
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double mt__bench_quantile(double *values, uint32_t n, double q)
{
    if (n == 0) return NAN;
    qsort(values, n, sizeof *values, compare_double);
    uint32_t rank = (uint32_t)(q * (double)n + 0.999999);
    if (rank < 1) rank = 1;
    if (rank > n) rank = n;
    return values[rank - 1];
}

uint64_t mt__bench_rand_u64(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}
