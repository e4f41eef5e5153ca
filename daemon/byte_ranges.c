/* meshtopod's byte-range set (byte_ranges.h): insertion finds the first
 * range ending at or after the new start by binary search, merges every
 * range the new one touches or overlaps, and shifts the tail once. One
 * owner, no lock: the LCM thread, for its transfer. */
#include "byte_ranges.h"

#include <stdlib.h>
#include <string.h>

/* Index of the first range with end >= start (ranges touching start merge). */
static size_t first_touching(const mtd_byte_ranges *r, uint64_t start)
{
    size_t lo = 0, hi = r->count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (r->items[mid].end < start)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

bool mtd_byte_ranges_touches(const mtd_byte_ranges *r, uint64_t start, uint64_t end)
{
    size_t i = first_touching(r, start);
    return i < r->count && r->items[i].start <= end;
}

mt_status mtd_byte_ranges_add(mtd_byte_ranges *r, uint64_t start, uint64_t end, uint64_t *out_added)
{
    if (out_added) *out_added = 0;
    if (start >= end) return MT_OK;
    size_t i = first_touching(r, start);
    size_t j = i; /* ranges [i, j) merge with the new one */
    uint64_t merged_start = start, merged_end = end, already = 0;
    while (j < r->count && r->items[j].start <= end) {
        const mtd_byte_range *x = &r->items[j];
        uint64_t lo = x->start > start ? x->start : start;
        uint64_t hi = x->end < end ? x->end : end;
        if (hi > lo) already += hi - lo;
        if (x->start < merged_start) merged_start = x->start;
        if (x->end > merged_end) merged_end = x->end;
        j++;
    }
    if (i == j) { /* no overlap: insert one range at i */
        if (r->count == r->capacity) {
            size_t cap = r->capacity ? 2 * r->capacity : 8;
            if (cap > SIZE_MAX / sizeof *r->items) return MT_ERR_NOMEM;
            mtd_byte_range *grown = realloc(r->items, cap * sizeof *grown);
            if (!grown) return MT_ERR_NOMEM;
            r->items = grown;
            r->capacity = cap;
        }
        memmove(&r->items[i + 1], &r->items[i], (r->count - i) * sizeof *r->items);
        r->count++;
    } else if (j - i > 1) { /* several merge into item i */
        memmove(&r->items[i + 1], &r->items[j], (r->count - j) * sizeof *r->items);
        r->count -= j - i - 1;
    }
    r->items[i].start = merged_start;
    r->items[i].end = merged_end;
    uint64_t added = (end - start) - already;
    r->covered += added;
    if (out_added) *out_added = added;
    return MT_OK;
}

size_t mtd_byte_ranges_gaps(const mtd_byte_ranges *r, uint64_t total, size_t max_gaps,
                            int64_t *out_offsets, int64_t *out_lengths, uint64_t *out_listed_until)
{
    size_t n = 0;
    uint64_t at = 0;
    for (size_t i = 0; i <= r->count; i++) {
        uint64_t next = i < r->count ? r->items[i].start : total;
        if (next > total) next = total;
        if (next > at) {
            if (n == max_gaps) {
                if (out_listed_until) *out_listed_until = at;
                return n;
            }
            out_offsets[n] = (int64_t)at;
            out_lengths[n] = (int64_t)(next - at);
            n++;
        }
        if (i < r->count && r->items[i].end > at) at = r->items[i].end;
        if (at >= total) break;
    }
    if (out_listed_until) *out_listed_until = total;
    return n;
}

size_t mtd_byte_ranges_memory(const mtd_byte_ranges *r)
{
    return r->capacity * sizeof *r->items;
}

void mtd_byte_ranges_free(mtd_byte_ranges *r)
{
    if (!r) return;
    free(r->items);
    memset(r, 0, sizeof *r);
}
