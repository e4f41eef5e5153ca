/* meshtopod's record of which bytes of a chunked submission have arrived: a
 * sorted array of disjoint, non-touching [start, end) ranges. Adding a range
 * merges it with its neighbours, so chunks arriving in order keep one range
 * and each loss adds at most one. LCM-free; one owner, no locking (the LCM
 * thread, which owns the transfers). */
#ifndef MESHTOPOD_BYTE_RANGES_H
#define MESHTOPOD_BYTE_RANGES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/status.h"

typedef struct mtd_byte_range {
    uint64_t start, end; /* start < end */
} mtd_byte_range;

typedef struct mtd_byte_ranges {
    mtd_byte_range *items;
    size_t count, capacity;
    uint64_t covered; /* bytes in all ranges */
} mtd_byte_ranges;

/* Adds [start, end) (nothing when start >= end). *out_added (may be NULL)
 * gets the bytes that were not covered before. MT_OK or MT_ERR_NOMEM (the
 * set is then unchanged). */
mt_status mtd_byte_ranges_add(mtd_byte_ranges *ranges, uint64_t start, uint64_t end,
                              uint64_t *out_added);

/* Whether [start, end) overlaps or touches a range of the set, so that
 * adding it would not make one more range. */
bool mtd_byte_ranges_touches(const mtd_byte_ranges *ranges, uint64_t start, uint64_t end);

/* The gaps of [0, total) not covered, in order: at most max_gaps of them into
 * out_offsets / out_lengths (may be NULL when max_gaps is 0). Returns how
 * many were written; *out_listed_until (may be NULL) gets the offset below
 * which the list is complete (total when every gap was written). */
size_t mtd_byte_ranges_gaps(const mtd_byte_ranges *ranges, uint64_t total, size_t max_gaps,
                            int64_t *out_offsets, int64_t *out_lengths, uint64_t *out_listed_until);

/* Bytes the array itself holds (for memory accounting). */
size_t mtd_byte_ranges_memory(const mtd_byte_ranges *ranges);

/* Frees the array and empties the set. NULL-safe. */
void mtd_byte_ranges_free(mtd_byte_ranges *ranges);

#endif
