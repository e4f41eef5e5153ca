/* The mesh store: a sorted array of ids, each holding its versions in
 * ascending order; entries are reference counted with C11 atomics so they
 * outlive removal while a query holds them.
 *
 * Why a sorted array and not a hash table: a robot holds tens to a few
 * thousand mesh ids, lookup is a binary search over pointers (a few cache
 * misses), a new id costs one memmove of pointers, and `list` comes out in
 * order for free. libc has nothing better here: hsearch() keeps one global
 * table and cannot remove, and tsearch() allocates per node and its twalk()
 * takes no context pointer, so `list` would need a global.
 *
 * Why one mutex and not a rwlock: every critical section is pointer
 * bookkeeping (a binary search, a reference count increment, a memmove of a
 * few pointers, the occasional growth of a pointer array). Meshes are built
 * before mtd_store_add and queries run on an acquired entry after the lock is
 * dropped, so nobody holds the lock long enough for shared reading to pay;
 * glibc's rwlock costs more per acquisition and, preferring readers, lets a
 * steady stream of queries starve add and remove. Any thread: the LCM
 * thread fetches for queries, workers put built meshes and load kept ones,
 * the daemon's tick trims; the policy, the backing and the budget are called
 * outside the lock. */
#include "mesh_store.h"

#include <inttypes.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"
#include "meshtopo/report.h"

struct mtd_mesh_entry {
    atomic_size_t refs;
    mt_mesh *mesh;
    mtd_mesh_info info; /* info.id and info.source point into strings[] */
    mtd_entry_free_fn on_free;
    void *on_free_ctx;
    mtd_mesh_dispose_fn dispose;
    void *dispose_ctx;
    char strings[]; /* id NUL source NUL */
};

/* One mesh id. Kept after its last version is removed so that the id's
 * version numbers keep increasing (a client told "v3" never sees another
 * mesh as v3); that costs a few hundred bytes per id ever seen. */
typedef struct id_slot {
    char *id;
    uint32_t highest_version; /* highest version the id ever had */
    uint32_t num_versions;
    uint32_t cap_versions;
    mtd_mesh_entry **versions; /* [num_versions], ascending version */
} id_slot;

struct mtd_store {
    pthread_mutex_t lock;
    mtd_store_options options;
    id_slot **slots; /* [num_slots], ascending strcmp order of id */
    size_t num_slots;
    size_t cap_slots;
    mtd_store_totals totals;
    mtd_store_backing backing; /* all NULL without one */
    mtd_store_policy policy;   /* all NULL without one */
};

/* ---- mesh ids ------------------------------------------------------------ */

static void diag_set(mt_diag *diag, mt_status status, uint64_t byte_offset, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static void diag_set(mt_diag *diag, mt_status status, uint64_t byte_offset, const char *fmt, ...)
{
    if (!diag) return;
    mt_diag_clear(diag);
    diag->status = status;
    diag->byte_offset = byte_offset;
    va_list args;
    va_start(args, fmt);
    vsnprintf(diag->message, sizeof diag->message, fmt, args);
    va_end(args);
}

/* ---- entries ------------------------------------------------------------- */

mtd_mesh_entry *mtd_entry_retain(mtd_mesh_entry *entry)
{
    /* Relaxed is enough: the caller already holds a reference, so the entry
     * cannot be freed concurrently (the classic shared_ptr argument). */
    atomic_fetch_add_explicit(&entry->refs, 1, memory_order_relaxed);
    return entry;
}

void mtd_entry_release(mtd_mesh_entry *entry)
{
    if (!entry) return;
    /* acq_rel: every earlier use of the entry happens before the free. */
    if (atomic_fetch_sub_explicit(&entry->refs, 1, memory_order_acq_rel) != 1) return;
    if (entry->on_free) entry->on_free(entry->on_free_ctx, entry->mesh, &entry->info);
    if (entry->dispose)
        entry->dispose(entry->dispose_ctx, entry->mesh);
    else
        mt_mesh_destroy(entry->mesh);
    free(entry);
}

const mt_mesh *mtd_entry_mesh(const mtd_mesh_entry *entry)
{
    return entry->mesh;
}

const mtd_mesh_info *mtd_entry_info(const mtd_mesh_entry *entry)
{
    return &entry->info;
}

/* A new entry with one reference; the version is set when it is stored. */
static mtd_mesh_entry *entry_new(const mtd_store *store, const char *id, mt_mesh *mesh,
                                 const mtd_mesh_meta *meta)
{
    const char *source = meta->source ? meta->source : "";
    size_t id_len = strlen(id); /* <= MESHTOPO_MESH_T_MESH_ID_MAX, checked */
    size_t source_len = strlen(source);
    size_t strings = id_len + 1;
    if (source_len > SIZE_MAX - sizeof(mtd_mesh_entry) - strings - 1) return NULL;
    strings += source_len + 1;
    size_t bytes = sizeof(mtd_mesh_entry) + strings;
    mtd_mesh_entry *e = malloc(bytes);
    if (!e) return NULL;
    atomic_init(&e->refs, 1);
    e->mesh = mesh;
    memcpy(e->strings, id, id_len + 1);
    memcpy(e->strings + id_len + 1, source, source_len + 1);
    e->info.id = e->strings;
    e->info.source = e->strings + id_len + 1;
    e->info.version = 0;
    e->info.utime = meta->utime;
    e->info.content_hash = meta->content_hash;
    size_t mesh_bytes = mt_mesh_memory_bytes(mesh);
    size_t report_bytes = mt_mesh_report_memory_bytes(mesh);
    size_t total = bytes;
    total = mesh_bytes > SIZE_MAX - total ? SIZE_MAX : total + mesh_bytes;
    total = report_bytes > SIZE_MAX - total ? SIZE_MAX : total + report_bytes;
    e->info.memory_bytes = total;
    e->info.num_verts = mt_mesh_num_verts(mesh);
    e->info.num_faces = mt_mesh_num_faces(mesh);
    e->info.num_defects = mt_mesh_report(mesh)->num_defects;
    e->on_free = store->options.on_entry_free;
    e->on_free_ctx = store->options.on_entry_free_ctx;
    e->dispose = store->options.dispose_mesh;
    e->dispose_ctx = store->options.dispose_mesh_ctx;
    return e;
}

/* ---- the store ----------------------------------------------------------- */

mt_status mtd_store_create(const mtd_store_options *options, mtd_store **out_store)
{
    *out_store = NULL;
    mtd_store *s = calloc(1, sizeof *s);
    if (!s) return MT_ERR_NOMEM;
    if (options) s->options = *options;
    if (pthread_mutex_init(&s->lock, NULL) != 0) {
        free(s);
        return MT_ERR_NOMEM;
    }
    *out_store = s;
    return MT_OK;
}

void mtd_store_destroy(mtd_store *store)
{
    if (!store) return;
    for (size_t i = 0; i < store->num_slots; i++) {
        id_slot *slot = store->slots[i];
        for (uint32_t v = 0; v < slot->num_versions; v++) mtd_entry_release(slot->versions[v]);
        free(slot->versions);
        free(slot->id);
        free(slot);
    }
    free(store->slots);
    pthread_mutex_destroy(&store->lock);
    free(store);
}

/* Index of the first slot whose id is >= id; *out_found when equal. */
static size_t slot_lower_bound(const mtd_store *store, const char *id, int *out_found)
{
    size_t lo = 0, hi = store->num_slots;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (strcmp(store->slots[mid]->id, id) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    *out_found = lo < store->num_slots && strcmp(store->slots[lo]->id, id) == 0;
    return lo;
}

static id_slot *slot_find(const mtd_store *store, const char *id)
{
    int found;
    size_t at = slot_lower_bound(store, id, &found);
    return found ? store->slots[at] : NULL;
}

/* Index of `version` in slot->versions, or UINT32_MAX. */
static uint32_t version_index(const id_slot *slot, uint32_t version)
{
    uint32_t lo = 0, hi = slot->num_versions;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        uint32_t v = slot->versions[mid]->info.version;
        if (v == version) return mid;
        if (v < version)
            lo = mid + 1;
        else
            hi = mid;
    }
    return UINT32_MAX;
}

/* Makes room for one more version; MT_OK, MT_ERR_TOO_LARGE or MT_ERR_NOMEM
 * (slot unchanged). */
static mt_status slot_reserve(id_slot *slot)
{
    if (slot->num_versions < slot->cap_versions) return MT_OK;
    if (slot->cap_versions > UINT32_MAX / 2) return MT_ERR_TOO_LARGE;
    uint32_t cap = slot->cap_versions ? slot->cap_versions * 2 : 4;
#if SIZE_MAX / 8 < UINT32_MAX /* only where size_t is narrower than 35 bits */
    if ((size_t)cap > SIZE_MAX / sizeof(mtd_mesh_entry *)) return MT_ERR_TOO_LARGE;
#endif
    mtd_mesh_entry **grown = realloc(slot->versions, (size_t)cap * sizeof *grown);
    if (!grown) return MT_ERR_NOMEM;
    slot->versions = grown;
    slot->cap_versions = cap;
    return MT_OK;
}

/* A new empty slot inserted at index `at`; NULL when out of memory. */
static id_slot *slot_insert(mtd_store *store, size_t at, const char *id)
{
    if (store->num_slots == store->cap_slots) {
        size_t cap = store->cap_slots ? store->cap_slots * 2 : 16;
        if (cap > SIZE_MAX / sizeof(id_slot *)) return NULL;
        id_slot **grown = realloc(store->slots, cap * sizeof *grown);
        if (!grown) return NULL;
        store->slots = grown;
        store->cap_slots = cap;
    }
    id_slot *slot = calloc(1, sizeof *slot);
    if (!slot) return NULL;
    size_t len = strlen(id);
    slot->id = malloc(len + 1);
    if (!slot->id || slot_reserve(slot) != MT_OK) {
        free(slot->id);
        free(slot);
        return NULL;
    }
    memcpy(slot->id, id, len + 1);
    memmove(&store->slots[at + 1], &store->slots[at], (store->num_slots - at) * sizeof(id_slot *));
    store->slots[at] = slot;
    store->num_slots++;
    return slot;
}

mt_status mtd_store_add(mtd_store *store, const char *id, mt_mesh *mesh, const mtd_mesh_meta *meta,
                        uint32_t *out_version, mtd_mesh_entry **out_entry, mt_diag *diag)
{
    if (out_version) *out_version = 0;
    if (out_entry) *out_entry = NULL;
    mt_status status = mt_msgs_mesh_id_check(id, diag);
    if (status != MT_OK) return status;
    if (!mesh) {
        diag_set(diag, MT_ERR_INVALID_ARG, UINT64_MAX, "no mesh to add under id '%s'", id);
        return MT_ERR_INVALID_ARG;
    }
    static const mtd_mesh_meta no_meta;
    if (!meta) meta = &no_meta;

    /* Everything that copies bytes happens before the lock. */
    mtd_mesh_entry *entry = entry_new(store, id, mesh, meta);
    if (!entry) {
        diag_set(diag, MT_ERR_NOMEM, UINT64_MAX, "out of memory storing mesh '%s'", id);
        return MT_ERR_NOMEM;
    }
    if (out_entry) atomic_init(&entry->refs, 2);

    mtd_mesh_entry *dropped = NULL;
    pthread_mutex_lock(&store->lock);
    int found;
    size_t at = slot_lower_bound(store, id, &found);
    id_slot *slot = found ? store->slots[at] : NULL;
    uint32_t highest = slot ? slot->highest_version : 0;
    uint32_t held = slot ? slot->num_versions : 0;
    uint32_t version = meta->version;
    if (version == 0 && highest == UINT32_MAX) {
        status = MT_ERR_TOO_LARGE;
        diag_set(diag, status, UINT64_MAX, "mesh '%s' has used every version number", id);
        goto fail;
    }
    bool reserved = meta->reserved && meta->version != 0;
    if (version == 0) version = highest + 1;
    if (reserved) {
        if (slot && version_index(slot, version) != UINT32_MAX) {
            status = MT_ERR_INVALID_ARG;
            diag_set(diag, status, UINT64_MAX, "version %u of mesh '%s' is already held",
                     (unsigned)version, id);
            goto fail;
        }
    } else if (version <= highest) {
        status = MT_ERR_INVALID_ARG;
        diag_set(diag, status, UINT64_MAX,
                 "version %u of mesh '%s' requested, but the id already had version %u",
                 (unsigned)version, id, (unsigned)highest);
        goto fail;
    }
    /* Versions held never exceed the limit (a reserved add of an old version
     * aside), so one add drops at most one: the oldest, when it is older. */
    uint32_t limit = store->options.max_versions_per_id;
    bool drop = limit && held >= limit && slot->versions[0]->info.version < version;
    size_t freed_bytes = 0;
    if (drop) freed_bytes = slot->versions[0]->info.memory_bytes;
    size_t after = store->totals.memory_bytes - freed_bytes;
    if (store->options.max_bytes && (entry->info.memory_bytes > store->options.max_bytes ||
                                     after > store->options.max_bytes - entry->info.memory_bytes)) {
        status = MT_ERR_TOO_LARGE;
        diag_set(diag, status, UINT64_MAX,
                 "mesh '%s' needs %zu bytes; the store holds %zu of its %zu-byte limit", id,
                 entry->info.memory_bytes, after, store->options.max_bytes);
        goto fail;
    }
    if (!slot) {
        slot = slot_insert(store, at, id);
        if (!slot) {
            status = MT_ERR_NOMEM;
            diag_set(diag, status, UINT64_MAX, "out of memory storing mesh '%s'", id);
            goto fail;
        }
    }
    if (!drop) {
        status = slot_reserve(slot);
        if (status != MT_OK) {
            /* Only an existing slot gets here (slot_insert reserves room), so
             * the store is unchanged. */
            diag_set(diag, status, UINT64_MAX, "cannot hold another version of mesh '%s'", id);
            goto fail;
        }
    }

    /* Commit: nothing below fails. */
    if (drop) {
        dropped = slot->versions[0];
        memmove(&slot->versions[0], &slot->versions[1],
                (slot->num_versions - 1) * sizeof(mtd_mesh_entry *));
        slot->num_versions--;
        store->totals.versions--;
        store->totals.memory_bytes -= dropped->info.memory_bytes;
    }
    entry->info.version = version;
    uint32_t pos = slot->num_versions;
    while (pos > 0 && slot->versions[pos - 1]->info.version > version) pos--;
    memmove(&slot->versions[pos + 1], &slot->versions[pos],
            (slot->num_versions - pos) * sizeof(mtd_mesh_entry *));
    slot->versions[pos] = entry;
    slot->num_versions++;
    if (version > slot->highest_version) slot->highest_version = version;
    if (slot->num_versions == 1) store->totals.ids++;
    store->totals.versions++;
    store->totals.memory_bytes += entry->info.memory_bytes;
    pthread_mutex_unlock(&store->lock);

    if (dropped) mtd_budget_forget(store->options.budget, dropped->info.id, dropped->info.version);
    mtd_entry_release(dropped);
    if (out_version) *out_version = version;
    if (out_entry) *out_entry = entry;
    if (diag) mt_diag_clear(diag);
    return MT_OK;

fail:
    pthread_mutex_unlock(&store->lock);
    entry->mesh = NULL; /* the caller keeps the mesh */
    free(entry);
    return status;
}

mt_status mtd_store_reserve_version(mtd_store *store, const char *id, uint32_t version,
                                    uint32_t *out_version, mt_diag *diag)
{
    if (out_version) *out_version = 0;
    mt_status status = mt_msgs_mesh_id_check(id, diag);
    if (status != MT_OK) return status;
    pthread_mutex_lock(&store->lock);
    int found;
    size_t at = slot_lower_bound(store, id, &found);
    id_slot *slot = found ? store->slots[at] : slot_insert(store, at, id);
    if (!slot) {
        pthread_mutex_unlock(&store->lock);
        diag_set(diag, MT_ERR_NOMEM, UINT64_MAX, "out of memory reserving a version of '%s'", id);
        return MT_ERR_NOMEM;
    }
    if (version == 0 && slot->highest_version == UINT32_MAX) {
        pthread_mutex_unlock(&store->lock);
        diag_set(diag, MT_ERR_TOO_LARGE, UINT64_MAX, "mesh '%s' has used every version number", id);
        return MT_ERR_TOO_LARGE;
    }
    if (version == 0) version = slot->highest_version + 1;
    if (version > slot->highest_version) slot->highest_version = version;
    uint32_t highest = slot->highest_version;
    pthread_mutex_unlock(&store->lock);
    if (out_version) *out_version = version == 0 ? highest : version;
    if (diag) mt_diag_clear(diag);
    return MT_OK;
}

mt_status mtd_store_acquire(mtd_store *store, const char *id, uint32_t version,
                            mtd_mesh_entry **out_entry, mt_diag *diag)
{
    *out_entry = NULL;
    mt_status status = mt_msgs_mesh_id_check(id, diag);
    if (status != MT_OK) return status;
    mtd_mesh_entry *entry = NULL;
    pthread_mutex_lock(&store->lock);
    id_slot *slot = slot_find(store, id);
    if (slot && slot->num_versions > 0) {
        if (version == 0) {
            entry = slot->versions[slot->num_versions - 1];
        } else {
            uint32_t i = version_index(slot, version);
            if (i != UINT32_MAX) entry = slot->versions[i];
        }
        if (entry) mtd_entry_retain(entry);
    }
    pthread_mutex_unlock(&store->lock);
    if (!entry) {
        if (version == 0)
            diag_set(diag, MT_ERR_NOT_FOUND, UINT64_MAX, "no mesh '%s'", id);
        else
            diag_set(diag, MT_ERR_NOT_FOUND, UINT64_MAX, "no version %u of mesh '%s'",
                     (unsigned)version, id);
        return MT_ERR_NOT_FOUND;
    }
    *out_entry = entry;
    return MT_OK;
}

mt_status mtd_store_remove(mtd_store *store, const char *id, uint32_t version, mt_diag *diag)
{
    mt_status status = mt_msgs_mesh_id_check(id, diag);
    if (status != MT_OK) return status;
    if (version == 0) {
        diag_set(diag, MT_ERR_INVALID_ARG, UINT64_MAX,
                 "removing mesh '%s' needs a version (1 or more), not 0", id);
        return MT_ERR_INVALID_ARG;
    }
    mtd_mesh_entry *entry = NULL;
    pthread_mutex_lock(&store->lock);
    id_slot *slot = slot_find(store, id);
    uint32_t i = slot ? version_index(slot, version) : UINT32_MAX;
    if (i != UINT32_MAX) {
        entry = slot->versions[i];
        memmove(&slot->versions[i], &slot->versions[i + 1],
                (slot->num_versions - i - 1) * sizeof(mtd_mesh_entry *));
        slot->num_versions--;
        if (slot->num_versions == 0) store->totals.ids--;
        store->totals.versions--;
        store->totals.memory_bytes -= entry->info.memory_bytes;
    }
    pthread_mutex_unlock(&store->lock);
    if (!entry) {
        diag_set(diag, MT_ERR_NOT_FOUND, UINT64_MAX, "no version %u of mesh '%s'",
                 (unsigned)version, id);
        return MT_ERR_NOT_FOUND;
    }
    mtd_budget_forget(store->options.budget, id, version);
    mtd_entry_release(entry); /* the store's reference; the mesh lives on while held */
    if (diag) mt_diag_clear(diag);
    return MT_OK;
}

size_t mtd_store_remove_unless(mtd_store *store, bool (*keep)(void *ctx, const char *id), void *ctx)
{
    pthread_mutex_lock(&store->lock);
    size_t count = 0;
    for (size_t s = 0; s < store->num_slots; s++)
        if (store->slots[s]->num_versions && !keep(ctx, store->slots[s]->id))
            count += store->slots[s]->num_versions;
    mtd_mesh_entry **dropped = count ? malloc(count * sizeof *dropped) : NULL;
    size_t n = 0;
    for (size_t s = 0; dropped && s < store->num_slots; s++) {
        id_slot *slot = store->slots[s];
        /* keep may answer otherwise than in the count (a view changed):
         * never past what was counted. */
        if (!slot->num_versions || n + slot->num_versions > count || keep(ctx, slot->id)) continue;
        for (uint32_t v = 0; v < slot->num_versions; v++) {
            dropped[n++] = slot->versions[v];
            store->totals.versions--;
            store->totals.memory_bytes -= slot->versions[v]->info.memory_bytes;
        }
        slot->num_versions = 0;
        store->totals.ids--;
    }
    pthread_mutex_unlock(&store->lock);
    /* The store's references; queries holding an entry keep it. */
    for (size_t i = 0; i < n; i++) {
        mtd_budget_forget(store->options.budget, dropped[i]->info.id, dropped[i]->info.version);
        mtd_entry_release(dropped[i]);
    }
    free(dropped);
    return n;
}

void mtd_store_get_totals(mtd_store *store, mtd_store_totals *out_totals)
{
    pthread_mutex_lock(&store->lock);
    *out_totals = store->totals;
    pthread_mutex_unlock(&store->lock);
}

/* ---- listing ------------------------------------------------------------- */

/* Adds b to *a; 0 on overflow. */
static int add_size(size_t *a, size_t b)
{
    if (b > SIZE_MAX - *a) return 0;
    *a += b;
    return 1;
}

static mt_status list_held(mtd_store *store, mtd_store_listing **out_listing)
{
    *out_listing = NULL;
    pthread_mutex_lock(&store->lock);
    /* One block: the listing, the id rows, the info rows, then the strings. */
    size_t ids = store->totals.ids, versions = store->totals.versions;
    size_t bytes = sizeof(mtd_store_listing);
    int ok = ids <= SIZE_MAX / sizeof(mtd_listed_id) &&
             versions <= SIZE_MAX / sizeof(mtd_mesh_info) &&
             add_size(&bytes, ids * sizeof(mtd_listed_id)) &&
             add_size(&bytes, versions * sizeof(mtd_mesh_info));
    size_t head = bytes;
    for (size_t i = 0; ok && i < store->num_slots; i++) {
        const id_slot *slot = store->slots[i];
        if (slot->num_versions == 0) continue;
        ok = add_size(&bytes, strlen(slot->id) + 1);
        for (uint32_t v = 0; ok && v < slot->num_versions; v++)
            ok = add_size(&bytes, strlen(slot->versions[v]->info.source) + 1);
    }
    mtd_store_listing *listing = ok ? malloc(bytes) : NULL;
    if (!listing) {
        pthread_mutex_unlock(&store->lock);
        return MT_ERR_NOMEM;
    }
    listing->num_ids = ids;
    listing->ids = (mtd_listed_id *)(listing + 1);
    listing->totals = store->totals;
    mtd_mesh_info *info = (mtd_mesh_info *)(listing->ids + ids);
    char *text = (char *)listing + head;
    size_t row = 0;
    for (size_t i = 0; i < store->num_slots; i++) {
        const id_slot *slot = store->slots[i];
        if (slot->num_versions == 0) continue;
        size_t len = strlen(slot->id) + 1;
        memcpy(text, slot->id, len);
        const char *id = text;
        text += len;
        listing->ids[row].id = id;
        listing->ids[row].num_versions = slot->num_versions;
        listing->ids[row].versions = info;
        for (uint32_t v = 0; v < slot->num_versions; v++) {
            *info = slot->versions[v]->info;
            info->id = id;
            len = strlen(info->source) + 1;
            memcpy(text, info->source, len);
            info->source = text;
            text += len;
            info++;
        }
        row++;
    }
    pthread_mutex_unlock(&store->lock);
    *out_listing = listing;
    return MT_OK;
}

mt_status mtd_store_list(mtd_store *store, mtd_store_listing **out_listing)
{
    mt_status s = list_held(store, out_listing);
    if (s != MT_OK || !store->backing.list) return s;
    mtd_store_listing *held = *out_listing;
    *out_listing = NULL;
    s = store->backing.list(store->backing.ctx, held, out_listing);
    mtd_store_listing_free(held);
    return s;
}

void mtd_store_listing_free(mtd_store_listing *listing)
{
    free(listing);
}

/* ---- the policy and the budget ----------------------------------------- */

void mtd_store_set_policy(mtd_store *store, const mtd_store_policy *policy)
{
    store->policy = *policy;
}

size_t mtd_store_trim(mtd_store *store)
{
    mtd_budget *budget = store->options.budget;
    size_t dropped = 0;
    if (!mtd_budget_bytes(budget)) return 0;
    for (;;) {
        mtd_store_totals totals;
        mtd_store_get_totals(store, &totals);
        if (!mtd_budget_over(budget, totals.memory_bytes)) return dropped;
        char id[MESHTOPO_MESH_T_MESH_ID_MAX + 1];
        uint32_t version;
        if (!mtd_budget_pick(budget, id, sizeof id, &version))
            return dropped; /* nothing kept is in memory: the rest stays */
        if (mtd_store_remove(store, id, version, NULL) == MT_OK) {
            mtd_budget_count_eviction(budget);
            dropped++;
            mtd_log(MTD_LOG_DEBUG, "evicted", "mesh_id=%s version=%" PRIu32, id, version);
        }
    }
}

mt_status mtd_store_put(mtd_store *store, const char *id, mt_mesh *mesh, const mtd_mesh_meta *meta,
                        const mt_face_list *list, uint32_t *out_version, mtd_mesh_entry **out_entry,
                        bool *out_by_policy, mt_diag *diag)
{
    if (out_by_policy) *out_by_policy = false;
    if (out_version) *out_version = 0;
    if (out_entry) *out_entry = NULL;
    static const mtd_mesh_meta no_meta;
    if (!meta) meta = &no_meta;
    mt_status s = mt_msgs_mesh_id_check(id, diag);
    if (s != MT_OK) return s;
    mtd_mesh_meta m = *meta;
    m.version = 0;
    m.reserved = false;
    /* Numbered after what the backing keeps (an archive listed at start,
     * versions other members of a cluster wrote). */
    uint32_t kept = store->backing.highest ? store->backing.highest(store->backing.ctx, id) : 0;
    if (kept) {
        s = mtd_store_reserve_version(store, id, kept, NULL, diag);
        if (s != MT_OK) return s;
    }
    bool admitted = false;
    if (store->policy.admit) {
        /* Durable first, under a reserved number: nobody sees the version
         * before the policy kept it. A refusal leaves a gap. */
        s = mtd_store_reserve_version(store, id, 0, &m.version, diag);
        if (s != MT_OK) return s;
        mtd_mesh_info info = {.id = id,
                              .version = m.version,
                              .source = m.source ? m.source : "",
                              .utime = m.utime,
                              .content_hash = m.content_hash};
        s = store->policy.admit(store->policy.ctx, &info, list, mesh, &m.version, diag);
        if (s != MT_OK) {
            if (out_by_policy) *out_by_policy = true;
            return s;
        }
        m.reserved = true;
        admitted = true;
    }
    mtd_mesh_entry *entry = NULL;
    uint32_t version = 0;
    s = mtd_store_add(store, id, mesh, &m, &version, &entry, diag);
    if (s != MT_OK) {
        /* Not acknowledged, so not kept: a restart must not serve it. */
        if (admitted && store->policy.withdraw)
            store->policy.withdraw(store->policy.ctx, id, m.version);
        return s;
    }
    if (admitted) mtd_budget_track(store->options.budget, id, version);
    if (store->policy.on_added) store->policy.on_added(store->policy.ctx, entry, list);
    mtd_store_trim(store);
    if (out_version) *out_version = version;
    if (out_entry)
        *out_entry = entry;
    else
        mtd_entry_release(entry);
    return MT_OK;
}

/* ---- the backing --------------------------------------------------------- */

void mtd_store_set_backing(mtd_store *store, const mtd_store_backing *backing)
{
    store->backing = *backing;
}

/* mtd_store_acquire, noting the use for the budget. */
static mtd_fetch_result acquire_held(mtd_store *store, const char *id, uint32_t version,
                                     mtd_mesh_entry **out_entry, mt_diag *diag)
{
    mt_status s = mtd_store_acquire(store, id, version, out_entry, diag);
    if (s == MT_ERR_INVALID_ARG) return MTD_FETCH_BAD_ID;
    if (s != MT_OK) return MTD_FETCH_NOT_HELD;
    mtd_budget_touch(store->options.budget, id, mtd_entry_info(*out_entry)->version);
    return MTD_FETCH_OK;
}

/* Adds (id, version) as the backing reads it. MT_OK also when it is held
 * already (a concurrent load got there first). */
static mt_status load_kept(mtd_store *store, const char *id, uint32_t version, mt_diag *diag)
{
    const mtd_store_backing *b = &store->backing;
    mtd_mesh_entry *held = NULL;
    if (mtd_store_acquire(store, id, version, &held, NULL) == MT_OK) {
        mtd_entry_release(held);
        return MT_OK;
    }
    /* Its number was handed out: never again, even when the backing then
     * stops keeping it (a file that fails its checks is set aside). */
    mt_status s = mtd_store_reserve_version(store, id, version, NULL, diag);
    if (s != MT_OK) return s;
    mt_mesh *mesh = NULL;
    mtd_mesh_meta meta;
    memset(&meta, 0, sizeof meta);
    s = b->load(b->ctx, id, version, &mesh, &meta, diag);
    if (s != MT_OK) return s;
    /* Reserved: its number was handed out before. */
    meta.version = version;
    meta.reserved = true;
    s = mtd_store_add(store, id, mesh, &meta, NULL, NULL, diag);
    free((char *)meta.source);
    if (s != MT_OK) {
        mt_mesh_destroy(mesh);
        if (mtd_store_acquire(store, id, version, &held, NULL) == MT_OK) {
            mtd_entry_release(held);
            return MT_OK;
        }
    }
    if (b->loaded) b->loaded(b->ctx, id, version, s, diag);
    return s;
}

mtd_fetch_result mtd_store_fetch(mtd_store *store, const char *id, uint32_t version, bool may_load,
                                 mtd_mesh_entry **out_entry, mt_diag *diag)
{
    *out_entry = NULL;
    const mtd_store_backing *b = &store->backing;
    if (!b->keeps) return acquire_held(store, id, version, out_entry, diag);
    if (mt_msgs_mesh_id_check(id, diag) != MT_OK) return MTD_FETCH_BAD_ID;
    if (version == 0) {
        uint32_t kept = b->highest(b->ctx, id);
        mtd_mesh_entry *latest = NULL;
        if (mtd_store_acquire(store, id, 0, &latest, NULL) == MT_OK &&
            mtd_entry_info(latest)->version >= kept) {
            mtd_budget_touch(store->options.budget, id, mtd_entry_info(latest)->version);
            *out_entry = latest;
            if (diag) mt_diag_clear(diag);
            return MTD_FETCH_OK;
        }
        mtd_entry_release(latest);
        version = kept; /* still 0 when the backing keeps none either */
    }
    /* Twice: a version loaded can be dropped again (a memory budget) before
     * it is acquired. */
    for (int attempt = 0; attempt < 2; attempt++) {
        mtd_fetch_result r = acquire_held(store, id, version, out_entry, diag);
        if (r != MTD_FETCH_NOT_HELD || version == 0 || !b->keeps(b->ctx, id, version)) return r;
        if (!may_load) return MTD_FETCH_NEEDS_LOAD;
        if (load_kept(store, id, version, diag) != MT_OK) return MTD_FETCH_LOAD_FAILED;
        r = acquire_held(store, id, version, out_entry, diag);
        if (r == MTD_FETCH_OK) {
            /* Held by this query first, so a budget smaller than the mesh
             * still answers it. */
            mtd_budget_track(store->options.budget, id, version);
            mtd_store_trim(store);
            return r;
        }
    }
    return acquire_held(store, id, version, out_entry, diag);
}
