/* meshtopod's memory budget (memory_budget.h): a sorted array of the
 * versions that may be dropped (by id, then version), each with the use
 * clock at its last use, behind one mutex. Picking scans for the oldest
 * use: evictions are rare next to fetches, which are a binary search. */
#include "memory_budget.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct candidate {
    char *id;
    uint32_t version;
    uint64_t last_used; /* the clock at its last use */
} candidate;

struct mtd_budget {
    uint64_t bytes;
    pthread_mutex_t lock;
    candidate *items; /* [count], by id then version */
    size_t count, cap;
    uint64_t clock;
    atomic_int_fast64_t evictions;
};

mt_status mtd_budget_create(uint64_t bytes, mtd_budget **out_budget)
{
    *out_budget = NULL;
    mtd_budget *b = calloc(1, sizeof *b);
    if (!b) return MT_ERR_NOMEM;
    b->bytes = bytes;
    pthread_mutex_init(&b->lock, NULL);
    atomic_init(&b->evictions, 0);
    *out_budget = b;
    return MT_OK;
}

void mtd_budget_destroy(mtd_budget *b)
{
    if (!b) return;
    for (size_t i = 0; i < b->count; i++) free(b->items[i].id);
    free(b->items);
    pthread_mutex_destroy(&b->lock);
    free(b);
}

uint64_t mtd_budget_bytes(const mtd_budget *b)
{
    return b ? b->bytes : 0;
}

bool mtd_budget_over(const mtd_budget *b, size_t held)
{
    return b && b->bytes && held > b->bytes;
}

/* Index of the first candidate >= (id, version); *out_found when equal.
 * Caller holds the lock. */
static size_t lower_bound(const mtd_budget *b, const char *id, uint32_t version, bool *out_found)
{
    size_t lo = 0, hi = b->count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        int c = strcmp(b->items[mid].id, id);
        if (c < 0 || (c == 0 && b->items[mid].version < version))
            lo = mid + 1;
        else
            hi = mid;
    }
    *out_found =
        lo < b->count && b->items[lo].version == version && strcmp(b->items[lo].id, id) == 0;
    return lo;
}

void mtd_budget_track(mtd_budget *b, const char *id, uint32_t version)
{
    if (!b || !b->bytes) return;
    pthread_mutex_lock(&b->lock);
    bool found;
    size_t at = lower_bound(b, id, version, &found);
    if (!found) {
        char *copy = strdup(id);
        if (b->count == b->cap) {
            size_t cap = b->cap ? 2 * b->cap : 64;
            candidate *grown =
                cap <= SIZE_MAX / sizeof *grown ? realloc(b->items, cap * sizeof *grown) : NULL;
            if (grown) {
                b->items = grown;
                b->cap = cap;
            }
        }
        if (!copy || b->count == b->cap) {
            free(copy);
            pthread_mutex_unlock(&b->lock);
            return;
        }
        memmove(&b->items[at + 1], &b->items[at], (b->count - at) * sizeof *b->items);
        b->items[at] = (candidate){copy, version, 0};
        b->count++;
    }
    b->items[at].last_used = ++b->clock;
    pthread_mutex_unlock(&b->lock);
}

void mtd_budget_touch(mtd_budget *b, const char *id, uint32_t version)
{
    if (!b || !b->bytes) return;
    pthread_mutex_lock(&b->lock);
    bool found;
    size_t at = lower_bound(b, id, version, &found);
    if (found) b->items[at].last_used = ++b->clock;
    pthread_mutex_unlock(&b->lock);
}

/* Removes items[at]. Caller holds the lock. */
static void remove_at(mtd_budget *b, size_t at)
{
    free(b->items[at].id);
    memmove(&b->items[at], &b->items[at + 1], (b->count - at - 1) * sizeof *b->items);
    b->count--;
}

void mtd_budget_forget(mtd_budget *b, const char *id, uint32_t version)
{
    if (!b || !b->bytes) return;
    pthread_mutex_lock(&b->lock);
    bool found;
    size_t at = lower_bound(b, id, version, &found);
    if (found) remove_at(b, at);
    pthread_mutex_unlock(&b->lock);
}

bool mtd_budget_pick(mtd_budget *b, char *id, size_t id_size, uint32_t *out_version)
{
    if (!b || !b->bytes) return false;
    pthread_mutex_lock(&b->lock);
    size_t victim = SIZE_MAX;
    for (size_t i = 0; i < b->count; i++)
        if (victim == SIZE_MAX || b->items[i].last_used < b->items[victim].last_used) victim = i;
    if (victim != SIZE_MAX) {
        snprintf(id, id_size, "%s", b->items[victim].id);
        *out_version = b->items[victim].version;
        remove_at(b, victim);
    }
    pthread_mutex_unlock(&b->lock);
    return victim != SIZE_MAX;
}

void mtd_budget_count_eviction(mtd_budget *b)
{
    if (b) atomic_fetch_add(&b->evictions, 1);
}

int64_t mtd_budget_evictions(mtd_budget *b)
{
    return b ? (int64_t)atomic_load(&b->evictions) : 0;
}

size_t mtd_budget_tracked(mtd_budget *b)
{
    if (!b) return 0;
    pthread_mutex_lock(&b->lock);
    size_t n = b->count;
    pthread_mutex_unlock(&b->lock);
    return n;
}
