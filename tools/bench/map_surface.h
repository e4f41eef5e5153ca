/* The input of `meshtopo-bench map`, shared by the driver (C) and its peers
 * (C++): a TSDF-like wavy height field cut into square blocks of cells on a
 * regular grid, each block with its own copies of its seam vertices (as
 * nvblox sends them), its changed versions, and the blocks each step
 * replaces. Everything is a pure function of the parameters: deterministic. */
#ifndef MESHTOPO_BENCH_MAP_SURFACE_H
#define MESHTOPO_BENCH_MAP_SURFACE_H

#include <math.h>
#include <stdint.h>

typedef struct mt__map_surface {
    uint32_t tiles_x, tiles_y; /* blocks along x and y (block keys (bx, by, 0)) */
    uint32_t cells;            /* cells along a block's side: 2 * cells^2 triangles */
    double voxel;              /* a cell's side in metres */
} mt__map_surface;

static inline uint64_t mt__map_mix(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

static inline uint32_t mt__map_block_verts(const mt__map_surface *s)
{
    return (s->cells + 1) * (s->cells + 1);
}

static inline uint32_t mt__map_block_faces(const mt__map_surface *s)
{
    return 2 * s->cells * s->cells;
}

/* Height of grid vertex (i, j) of the whole surface, version 0. */
static inline double mt__map_height(const mt__map_surface *s, uint32_t i, uint32_t j)
{
    double x = i * s->voxel, y = j * s->voxel;
    return 0.3 * sin(0.9 * x) * cos(0.7 * y) + 0.1 * sin(2.3 * x + 1.1 * y);
}

/* Fills block (bx, by) in version `version`: pos gets 3 * block_verts
 * doubles, idx 3 * block_faces indices (triangles, counter-clockwise seen
 * from +z). Local vertex (a, b) is a + b * (cells + 1), at global grid
 * vertex (bx * cells + a, by * cells + b). What a changed version changes:
 * version 0 is the surface itself; a version v > 0 moves each interior
 * vertex (0 < a, b < cells) along z by a pseudo-random offset in
 * [-0.1, 0.1) voxel drawn from (seed, bx, by, v, a, b). Seam vertices never
 * move, so every version welds to its neighbours exactly. */
static inline void mt__map_block_fill(const mt__map_surface *s, uint32_t bx, uint32_t by,
                                      uint32_t version, uint64_t seed, double *pos, uint32_t *idx)
{
    uint32_t n = s->cells, row = n + 1;
    for (uint32_t b = 0; b <= n; b++) {
        for (uint32_t a = 0; a <= n; a++) {
            uint32_t i = bx * n + a, j = by * n + b;
            double *p = pos + 3 * (size_t)(a + b * row);
            p[0] = i * s->voxel;
            p[1] = j * s->voxel;
            p[2] = mt__map_height(s, i, j);
            if (version > 0 && a > 0 && b > 0 && a < n && b < n) {
                uint64_t h = mt__map_mix(
                    seed ^ mt__map_mix(((uint64_t)bx << 40) ^ ((uint64_t)by << 20) ^ version) ^
                    ((uint64_t)a << 32 | b));
                p[2] += 0.2 * s->voxel * ((double)(h >> 11) * 0x1.0p-53 - 0.5);
            }
        }
    }
    for (uint32_t b = 0; b < n; b++) {
        for (uint32_t a = 0; a < n; a++) {
            uint32_t v00 = a + b * row, v10 = v00 + 1, v01 = v00 + row, v11 = v01 + 1;
            uint32_t *t = idx + 6 * (size_t)(a + b * n);
            t[0] = v00, t[1] = v10, t[2] = v11;
            t[3] = v00, t[4] = v11, t[5] = v01;
        }
    }
}

/* The blocks step `step` replaces: `count` distinct block numbers
 * (bx + by * tiles_x) into out, drawn from (seed, step). */
static inline void mt__map_step_blocks(const mt__map_surface *s, uint64_t seed, uint32_t step,
                                       uint32_t count, uint32_t *out)
{
    uint32_t total = s->tiles_x * s->tiles_y;
    uint64_t state = mt__map_mix(seed ^ 0x5354455053ull ^ ((uint64_t)step << 24));
    for (uint32_t k = 0; k < count;) {
        state = mt__map_mix(state);
        uint32_t pick = (uint32_t)(state % total);
        int seen = 0;
        for (uint32_t m = 0; m < k; m++) seen |= out[m] == pick;
        if (!seen) out[k++] = pick;
    }
}

/* Blocks a step replaces: 1 % of the map, at least one. */
static inline uint32_t mt__map_step_count(const mt__map_surface *s)
{
    uint32_t total = s->tiles_x * s->tiles_y;
    uint32_t count = (total + 50) / 100;
    return count ? count : 1;
}

#endif
