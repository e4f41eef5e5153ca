/* Changed versions of a block for the map tests: the defects a mapper's
 * blocks can carry (holes, flipped and duplicated faces, fins that make a
 * seam non-manifold, bowties, degenerate and out-of-range records, NaN and
 * -0.0 coordinates, isolated vertices, faces reaching into other blocks). */
#ifndef MESHTOPO_TEST_MAP_MUTATE_H
#define MESHTOPO_TEST_MAP_MUTATE_H

#include <stdint.h>

#include "map_split.h"
#include "meshtopo/face_list.h"

static inline uint64_t map_rng_next(uint64_t *state)
{
    uint64_t x = *state;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return *state = x;
}

static inline uint32_t map_rng_below(uint64_t *state, uint32_t n)
{
    return n ? (uint32_t)(map_rng_next(state) % n) : 0;
}

/* Replaces *list (malloc'd) with a changed copy: one to three random
 * changes; `set` gives positions of other blocks for faces that reach
 * across seams. */
void map_mutate(mt_face_list *list, const map_block_set *set, uint64_t *rng);

#endif
