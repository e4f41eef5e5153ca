/* Hash tables of the block map: an open-addressing table of uint32 entries
 * whose keys live elsewhere (linear probing, at most 3/4 full, deletion by
 * backward shift so that no tombstones build up over a long-lived map), a
 * scratch map from uint64 keys to dense indices for one operation, and a
 * reserve for mt__vec. */
#include <string.h>

#include "map/map_internal.h"

static mt_status table_alloc(uint32_t cap, uint32_t **out)
{
    size_t bytes;
    if (!mt__mul_size(cap, sizeof(uint32_t), &bytes)) return MT_ERR_NOMEM;
    uint32_t *slots = mt__malloc(bytes);
    if (!slots) return MT_ERR_NOMEM;
    memset(slots, 0xff, bytes);
    *out = slots;
    return MT_OK;
}

mt_status mt__table_reserve(mt__table *t, uint32_t count, mt__table_hash_fn hash, const void *ctx)
{
    if ((uint64_t)count * 4 <= (uint64_t)t->cap * 3) return MT_OK;
    uint64_t cap = t->cap ? t->cap : 16;
    while ((uint64_t)count * 4 > cap * 3) cap *= 2;
    if (cap > 0x80000000ull) return MT_ERR_NOMEM;
    uint32_t *slots;
    if (table_alloc((uint32_t)cap, &slots) != MT_OK) return MT_ERR_NOMEM;
    const uint32_t mask = (uint32_t)cap - 1;
    for (uint32_t i = 0; i < t->cap; i++) {
        const uint32_t e = t->slots[i];
        if (e == MT_NONE) continue;
        uint32_t j = hash(ctx, e) & mask;
        while (slots[j] != MT_NONE) j = (j + 1) & mask;
        slots[j] = e;
    }
    mt__free(t->slots);
    t->slots = slots;
    t->cap = (uint32_t)cap;
    return MT_OK;
}

uint32_t mt__table_find(const mt__table *t, uint32_t hash, mt__table_eq_fn eq, const void *ctx,
                        const void *key)
{
    if (t->cap == 0) return MT_NONE;
    const uint32_t mask = t->cap - 1;
    for (uint32_t i = hash & mask;; i = (i + 1) & mask) {
        const uint32_t e = t->slots[i];
        if (e == MT_NONE) return MT_NONE;
        if (eq(ctx, e, key)) return e;
    }
}

void mt__table_insert(mt__table *t, uint32_t hash, uint32_t entry)
{
    const uint32_t mask = t->cap - 1;
    uint32_t i = hash & mask;
    while (t->slots[i] != MT_NONE) i = (i + 1) & mask;
    t->slots[i] = entry;
    t->count++;
}

void mt__table_scan(const mt__table *t, uint32_t hash, void (*visit)(void *arg, uint32_t entry),
                    void *arg)
{
    if (t->cap == 0) return;
    const uint32_t mask = t->cap - 1;
    for (uint32_t i = hash & mask; t->slots[i] != MT_NONE; i = (i + 1) & mask)
        visit(arg, t->slots[i]);
}

void mt__table_remove(mt__table *t, uint32_t entry, mt__table_hash_fn hash, const void *ctx)
{
    if (t->cap == 0) return;
    const uint32_t mask = t->cap - 1;
    uint32_t i = hash(ctx, entry) & mask;
    while (t->slots[i] != entry) {
        if (t->slots[i] == MT_NONE) return;
        i = (i + 1) & mask;
    }
    /* Backward shift: move up every later entry of the run whose home is
     * not between the hole and it. */
    for (uint32_t j = (i + 1) & mask; t->slots[j] != MT_NONE; j = (j + 1) & mask) {
        const uint32_t home = hash(ctx, t->slots[j]) & mask;
        const bool stays = i <= j ? (i < home && home <= j) : (i < home || home <= j);
        if (stays) continue;
        t->slots[i] = t->slots[j];
        i = j;
    }
    t->slots[i] = MT_NONE;
    t->count--;
}

void mt__table_clear(mt__table *t)
{
    if (t->slots) memset(t->slots, 0xff, (size_t)t->cap * sizeof *t->slots);
    t->count = 0;
}

void mt__table_free(mt__table *t)
{
    mt__free(t->slots);
    t->slots = NULL;
    t->cap = t->count = 0;
}

mt_status mt__keymap_init(mt__keymap *m, uint32_t max_entries)
{
    memset(m, 0, sizeof *m);
    uint64_t cap = 16;
    while (cap < 2 * (uint64_t)max_entries) cap *= 2;
    if (cap > 0x80000000ull) return MT_ERR_NOMEM;
    size_t key_bytes, val_bytes;
    if (!mt__mul_size((size_t)cap, sizeof(uint64_t), &key_bytes) ||
        !mt__mul_size((size_t)cap, sizeof(uint32_t), &val_bytes))
        return MT_ERR_NOMEM;
    m->keys = mt__malloc(key_bytes);
    m->vals = mt__malloc(val_bytes);
    if (!m->keys || !m->vals) {
        mt__keymap_free(m);
        return MT_ERR_NOMEM;
    }
    memset(m->vals, 0xff, val_bytes);
    m->mask = (uint32_t)cap - 1;
    return MT_OK;
}

uint32_t mt__keymap_get(const mt__keymap *m, uint64_t key)
{
    for (uint32_t i = (uint32_t)mt__mix64(key) & m->mask;; i = (i + 1) & m->mask) {
        if (m->vals[i] == MT_NONE) return MT_NONE;
        if (m->keys[i] == key) return m->vals[i];
    }
}

uint32_t mt__keymap_put(mt__keymap *m, uint64_t key, bool *out_added)
{
    uint32_t i = (uint32_t)mt__mix64(key) & m->mask;
    for (; m->vals[i] != MT_NONE; i = (i + 1) & m->mask) {
        if (m->keys[i] == key) {
            *out_added = false;
            return m->vals[i];
        }
    }
    m->keys[i] = key;
    m->vals[i] = m->count++;
    *out_added = true;
    return m->vals[i];
}

void mt__keymap_free(mt__keymap *m)
{
    mt__free(m->keys);
    mt__free(m->vals);
    memset(m, 0, sizeof *m);
}

mt_status mt__map_vec_reserve(mt__vec *v, size_t n)
{
    if (n <= v->cap) return MT_OK;
    size_t bytes;
    if (!mt__mul_size(n, v->elem_size, &bytes)) return MT_ERR_NOMEM;
    void *data = mt__realloc(v->data, bytes);
    if (!data) return MT_ERR_NOMEM;
    v->data = data;
    v->cap = n;
    return MT_OK;
}
