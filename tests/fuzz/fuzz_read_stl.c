/* libFuzzer target: the STL readers (ASCII and binary, told apart as
 * mt_read_* tells them, and each forced) on arbitrary bytes, gzip included
 * (checks in fuzz_reader.h); then what was read is welded, exactly or
 * within a distance taken from the input, and the weld checked: a
 * consistent list, no index moved out of or into range, every merged
 * vertex within the distance of its survivor. */
#include <math.h>

#include "fuzz_reader.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void fuzz_weld(const uint8_t *data, size_t size)
{
    mt_face_list list;
    mt_diag diag;
    if (mt_read_memory(data, size, MT_FORMAT_AUTO, "fuzz.stl", &list, &diag) != MT_OK) return;
    /* the last byte picks the distance: 0 exact, else 2^-(b % 64) */
    uint8_t b = size ? data[size - 1] : 0;
    double eps = b < 32 ? 0 : ldexp(1.0, -(int)(b % 64));
    uint32_t n = list.num_verts;
    double *before = malloc(3 * sizeof(double) * (n ? n : 1));
    uint32_t *old_indices = malloc(sizeof(uint32_t) * (list.num_indices ? list.num_indices : 1));
    uint32_t *map = malloc(sizeof(uint32_t) * (n ? n : 1));
    if (before && old_indices && map) {
        memcpy(before, list.positions, 3 * sizeof(double) * n);
        memcpy(old_indices, list.face_indices, sizeof(uint32_t) * list.num_indices);
        mt_weld_stats stats;
        if (mt_face_list_weld(&list, eps, map, &stats, &diag) != MT_OK) __builtin_trap();
        if (mt_face_list_check(&list, NULL) != MT_OK || stats.vertices_before != n ||
            stats.vertices_after != list.num_verts || stats.merged != n - list.num_verts)
            __builtin_trap();
        for (uint32_t v = 0; v < n; v++) {
            if (map[v] >= list.num_verts) __builtin_trap();
            const double *p = before + 3 * (size_t)v, *q = list.positions + 3 * (size_t)map[v];
            double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                            (p[2] - q[2]) * (p[2] - q[2]));
            int same = p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
            if (eps == 0 ? !same && memcmp(p, q, 3 * sizeof(double)) != 0
                         : !same && !(d <= eps * (1 + 1e-9)) && isfinite(d))
                __builtin_trap();
        }
        for (uint64_t k = 0; k < list.num_indices; k++) {
            uint32_t i = old_indices[k];
            if (list.face_indices[k] != (i < n ? map[i] : i)) __builtin_trap();
        }
    }
    free(before);
    free(old_indices);
    free(map);
    mt_face_list_free(&list);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    mt_fuzz_reader(data, size, MT_FORMAT_AUTO, "fuzz.stl");
    mt_fuzz_reader(data, size, MT_FORMAT_STL_ASCII, "fuzz");
    mt_fuzz_reader(data, size, MT_FORMAT_STL_BINARY, "fuzz");
    fuzz_weld(data, size);
    return 0;
}
