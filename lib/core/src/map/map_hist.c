/* Histograms the block map keeps current (face sizes, edge use counts): a
 * sorted array of non-empty bins. An operation first gathers its changes,
 * merges them by key and makes room for new bins (may fail), then applies
 * them (cannot fail), so a failed operation leaves the bins as they were. */
#include <stdlib.h>
#include <string.h>

#include "map/map_internal.h"

static int compare_change(const void *pa, const void *pb)
{
    const mt__hist_change *a = pa, *b = pb;
    return (a->key > b->key) - (a->key < b->key);
}

/* Index of the first bin with key >= key. */
static size_t lower_bound(const mt__hist *h, uint32_t key)
{
    size_t lo = 0, hi = h->len;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (h->bins[mid].key < key)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

mt_status mt__hist_note(mt__vec *changes, int64_t *small, uint32_t key, int64_t change)
{
    if (key < MT__HIST_SMALL) {
        small[key] += change;
        return MT_OK;
    }
    mt__hist_change c = {key, change};
    return mt__vec_push(changes, &c);
}

mt_status mt__hist_flush(mt__vec *changes, int64_t *small)
{
    for (uint32_t key = 0; key < MT__HIST_SMALL; key++) {
        if (small[key] == 0) continue;
        mt__hist_change c = {key, small[key]};
        if (mt__vec_push(changes, &c) != MT_OK) return MT_ERR_NOMEM;
        small[key] = 0;
    }
    return MT_OK;
}

mt_status mt__hist_prepare(mt__hist *h, mt__vec *changes)
{
    mt__hist_change *c = changes->data;
    size_t n = changes->len, out = 0;
    if (n) qsort(c, n, sizeof *c, compare_change);
    for (size_t i = 0; i < n;) {
        mt__hist_change merged = c[i++];
        while (i < n && c[i].key == merged.key) merged.change += c[i++].change;
        if (merged.change != 0) c[out++] = merged;
    }
    changes->len = out;
    size_t added = 0;
    for (size_t i = 0; i < out; i++) {
        size_t at = lower_bound(h, c[i].key);
        if (at == h->len || h->bins[at].key != c[i].key) added++;
    }
    if (h->len + added <= h->cap) return MT_OK;
    size_t cap = h->cap ? h->cap : 8, bytes;
    while (cap < h->len + added) cap *= 2;
    if (!mt__mul_size(cap, sizeof *h->bins, &bytes)) return MT_ERR_NOMEM;
    mt_histogram_bin *bins = mt__realloc(h->bins, bytes);
    if (!bins) return MT_ERR_NOMEM;
    h->bins = bins;
    h->cap = cap;
    return MT_OK;
}

void mt__hist_apply(mt__hist *h, const mt__vec *changes)
{
    const mt__hist_change *c = changes->data;
    for (size_t i = 0; i < changes->len; i++) {
        size_t at = lower_bound(h, c[i].key);
        if (at == h->len || h->bins[at].key != c[i].key) {
            memmove(&h->bins[at + 1], &h->bins[at], (h->len - at) * sizeof *h->bins);
            h->bins[at].key = c[i].key;
            h->bins[at].count = 0;
            h->len++;
        }
        h->bins[at].count = (uint64_t)((int64_t)h->bins[at].count + c[i].change);
        if (h->bins[at].count == 0) {
            memmove(&h->bins[at], &h->bins[at + 1], (h->len - at - 1) * sizeof *h->bins);
            h->len--;
        }
    }
}

void mt__hist_free(mt__hist *h)
{
    mt__free(h->bins);
    memset(h, 0, sizeof *h);
}
