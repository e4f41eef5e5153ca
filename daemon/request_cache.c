/* The request cache: a chained hash table over (reply channel, request id)
 * plus a doubly linked list in arrival order for eviction, all under one
 * mutex; every operation is O(1) expected apart from copying a reply, which
 * happens outside the lock.
 *
 * Written by hand because libc has no fitting table: hsearch() is one global
 * table without removal, and tsearch() would still need the arrival list
 * beside it. The bucket array is sized once from max_entries (a power of two
 * at least that large), so the table never rehashes. Any thread (the reply
 * module calls it from the LCM thread and from build workers). */
#include "request_cache.h"

#include "clock.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

struct mtd_reply {
    atomic_size_t refs;
    size_t size;
    unsigned char data[];
};

typedef struct centry {
    struct centry *chain; /* next in the bucket */
    struct centry *older; /* arrival list */
    struct centry *newer;
    uint64_t hash;
    int64_t request_id;
    int64_t arrived_us; /* monotonic */
    mtd_reply *reply;   /* NULL while pending */
    size_t bytes;       /* counted against max_bytes */
    size_t channel_len;
    char channel[];
} centry;

struct mtd_reqcache {
    pthread_mutex_t lock;
    size_t max_entries;
    size_t max_bytes;
    centry **buckets; /* [mask + 1] */
    size_t mask;
    centry *oldest;
    centry *newest;
    mtd_reqcache_stats stats;
};

/* ---- replies --------------------------------------------------------------- */

const void *mtd_reply_data(const mtd_reply *reply)
{
    return reply->data;
}

size_t mtd_reply_size(const mtd_reply *reply)
{
    return reply->size;
}

static mtd_reply *reply_retain(mtd_reply *reply)
{
    atomic_fetch_add_explicit(&reply->refs, 1, memory_order_relaxed);
    return reply;
}

void mtd_reply_release(mtd_reply *reply)
{
    if (!reply) return;
    if (atomic_fetch_sub_explicit(&reply->refs, 1, memory_order_acq_rel) == 1) free(reply);
}

/* ---- keys ---------------------------------------------------------------- */

/* FNV-1a over the channel, then the id folded in and mixed (splitmix64's
 * finalizer), so ids differing in one bit land in different buckets. */
static uint64_t key_hash(const char *channel, size_t len, int64_t request_id)
{
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < len; i++) h = (h ^ (unsigned char)channel[i]) * 1099511628211ull;
    h ^= (uint64_t)request_id;
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
    return h ^ (h >> 31);
}

/* Length of a valid channel, or 0 when it is not one. */
static size_t channel_length(const char *channel)
{
    if (!channel) return 0;
    size_t len = strnlen(channel, MTD_REPLY_CHANNEL_MAX + 1);
    return len > MTD_REPLY_CHANNEL_MAX ? 0 : len;
}

static centry **find_link(mtd_reqcache *cache, uint64_t hash, const char *channel, size_t len,
                          int64_t request_id)
{
    centry **link = &cache->buckets[hash & cache->mask];
    while (*link) {
        centry *e = *link;
        if (e->hash == hash && e->request_id == request_id && e->channel_len == len &&
            memcmp(e->channel, channel, len) == 0)
            return link;
        link = &e->chain;
    }
    return link;
}

/* ---- entries ------------------------------------------------------------- */

static centry *entry_new(uint64_t hash, const char *channel, size_t len, int64_t request_id)
{
    centry *e = malloc(sizeof(centry) + len + 1); /* len <= MTD_REPLY_CHANNEL_MAX */
    if (!e) return NULL;
    memset(e, 0, sizeof *e);
    e->hash = hash;
    e->request_id = request_id;
    e->arrived_us = mtd_monotonic_us();
    e->channel_len = len;
    memcpy(e->channel, channel, len);
    e->channel[len] = '\0';
    e->bytes = sizeof(centry) + len + 1;
    return e;
}

/* Links e in as the newest entry at *link (the end of its bucket chain). */
static void entry_link(mtd_reqcache *cache, centry **link, centry *e)
{
    *link = e;
    e->older = cache->newest;
    if (cache->newest)
        cache->newest->newer = e;
    else
        cache->oldest = e;
    cache->newest = e;
    cache->stats.entries++;
    cache->stats.bytes += e->bytes;
    if (!e->reply) cache->stats.pending++;
}

/* Unlinks e and returns it; the caller frees it (outside the lock). */
static centry *entry_unlink(mtd_reqcache *cache, centry *e)
{
    centry **link = find_link(cache, e->hash, e->channel, e->channel_len, e->request_id);
    *link = e->chain;
    if (e->older)
        e->older->newer = e->newer;
    else
        cache->oldest = e->newer;
    if (e->newer)
        e->newer->older = e->older;
    else
        cache->newest = e->older;
    e->chain = e->older = e->newer = NULL;
    cache->stats.entries--;
    cache->stats.bytes -= e->bytes;
    if (!e->reply) cache->stats.pending--;
    return e;
}

static void entry_free(centry *e)
{
    if (!e) return;
    mtd_reply_release(e->reply);
    free(e);
}

/* Evicts the oldest answered requests (never `keep`, never a pending one)
 * until there is room for `extra_entries` more entries and `extra_bytes`
 * more bytes, or nothing is left to evict. Evicted entries are chained
 * through `older` onto *freed for freeing outside the lock. */
static void evict(mtd_reqcache *cache, size_t extra_entries, size_t extra_bytes, const centry *keep,
                  centry **freed)
{
    centry *e = cache->oldest;
    while (e && (cache->stats.entries + extra_entries > cache->max_entries ||
                 extra_bytes > cache->max_bytes ||
                 cache->stats.bytes > cache->max_bytes - extra_bytes)) {
        centry *next = e->newer;
        if (e != keep && e->reply) {
            entry_unlink(cache, e);
            e->older = *freed;
            *freed = e;
            cache->stats.evictions++;
        }
        e = next;
    }
}

static void free_chain(centry *freed)
{
    while (freed) {
        centry *older = freed->older;
        entry_free(freed);
        freed = older;
    }
}

/* ---- the cache ----------------------------------------------------------- */

mt_status mtd_reqcache_create(const mtd_reqcache_options *options, mtd_reqcache **out_cache)
{
    *out_cache = NULL;
    size_t max_entries = options && options->max_entries ? options->max_entries : 4096;
    size_t max_bytes = options && options->max_bytes ? options->max_bytes : (size_t)64 << 20;
    if (max_entries > MTD_REQCACHE_MAX_ENTRIES) return MT_ERR_INVALID_ARG;
    size_t buckets = 16;
    while (buckets < max_entries) buckets *= 2; /* <= 2^24: no overflow */
    mtd_reqcache *cache = calloc(1, sizeof *cache);
    if (!cache) return MT_ERR_NOMEM;
    cache->buckets = calloc(buckets, sizeof(centry *));
    if (!cache->buckets || pthread_mutex_init(&cache->lock, NULL) != 0) {
        free(cache->buckets);
        free(cache);
        return MT_ERR_NOMEM;
    }
    cache->mask = buckets - 1;
    cache->max_entries = max_entries;
    cache->max_bytes = max_bytes;
    *out_cache = cache;
    return MT_OK;
}

void mtd_reqcache_destroy(mtd_reqcache *cache)
{
    if (!cache) return;
    centry *e = cache->oldest;
    while (e) {
        centry *newer = e->newer;
        entry_free(e);
        e = newer;
    }
    free(cache->buckets);
    pthread_mutex_destroy(&cache->lock);
    free(cache);
}

mt_status mtd_reqcache_begin(mtd_reqcache *cache, const char *reply_channel, int64_t request_id,
                             mtd_request_state *out_state, mtd_reply **out_reply)
{
    *out_reply = NULL;
    *out_state = MTD_REQUEST_NEW;
    size_t len = channel_length(reply_channel);
    if (len == 0) return MT_ERR_INVALID_ARG;
    uint64_t hash = key_hash(reply_channel, len, request_id);
    /* Allocated before the lock in case the request is new; freed if not. */
    centry *fresh = entry_new(hash, reply_channel, len, request_id);
    centry *freed = NULL;
    mt_status status = MT_OK;

    pthread_mutex_lock(&cache->lock);
    centry **link = find_link(cache, hash, reply_channel, len, request_id);
    centry *e = *link;
    if (e && e->reply) {
        *out_state = MTD_REQUEST_DONE;
        *out_reply = reply_retain(e->reply);
        cache->stats.done_hits++;
    } else if (e) {
        *out_state = MTD_REQUEST_PENDING;
        cache->stats.pending_hits++;
    } else if (!fresh) {
        status = MT_ERR_NOMEM;
    } else {
        /* Room first: eviction may unlink from this very bucket, so the link
         * is looked up again afterwards. */
        evict(cache, 1, fresh->bytes, NULL, &freed);
        link = find_link(cache, hash, reply_channel, len, request_id);
        entry_link(cache, link, fresh);
        cache->stats.new_requests++;
        fresh = NULL;
    }
    pthread_mutex_unlock(&cache->lock);

    free(fresh);
    free_chain(freed);
    return status;
}

mt_status mtd_reqcache_peek(mtd_reqcache *cache, const char *reply_channel, int64_t request_id,
                            mtd_request_state *out_state, mtd_reply **out_reply)
{
    *out_reply = NULL;
    *out_state = MTD_REQUEST_NEW;
    size_t len = channel_length(reply_channel);
    if (len == 0) return MT_ERR_INVALID_ARG;
    uint64_t hash = key_hash(reply_channel, len, request_id);
    pthread_mutex_lock(&cache->lock);
    centry *e = *find_link(cache, hash, reply_channel, len, request_id);
    if (e && e->reply) {
        *out_state = MTD_REQUEST_DONE;
        *out_reply = reply_retain(e->reply);
    } else if (e) {
        *out_state = MTD_REQUEST_PENDING;
    }
    pthread_mutex_unlock(&cache->lock);
    return MT_OK;
}

mt_status mtd_reqcache_finish(mtd_reqcache *cache, const char *reply_channel, int64_t request_id,
                              const void *data, size_t size)
{
    size_t len = channel_length(reply_channel);
    if (len == 0 || (!data && size > 0)) return MT_ERR_INVALID_ARG;
    uint64_t hash = key_hash(reply_channel, len, request_id);

    /* Copy the reply and make a possible new entry before taking the lock. */
    mt_status status = MT_OK;
    mtd_reply *reply = NULL;
    centry *fresh = NULL;
    size_t overhead = sizeof(centry) + len + 1 + sizeof(mtd_reply);
    if (size > cache->max_bytes || overhead > cache->max_bytes - size) {
        status = MT_ERR_TOO_LARGE;
    } else {
        reply = malloc(sizeof(mtd_reply) + size);
        fresh = entry_new(hash, reply_channel, len, request_id);
        if (!reply || !fresh) {
            status = MT_ERR_NOMEM;
            free(reply);
            free(fresh);
            reply = NULL;
            fresh = NULL;
        } else {
            atomic_init(&reply->refs, 1);
            reply->size = size;
            if (size) memcpy(reply->data, data, size);
        }
    }

    centry *freed = NULL;
    pthread_mutex_lock(&cache->lock);
    centry **link = find_link(cache, hash, reply_channel, len, request_id);
    centry *e = *link;
    if (status != MT_OK) {
        /* Not storable: drop the pending mark so a retry runs it again. */
        if (e && !e->reply) {
            entry_unlink(cache, e);
            e->older = freed;
            freed = e;
        }
    } else if (e && e->reply) {
        /* Already answered: keep the reply that was sent first. */
    } else {
        if (!e) {
            e = fresh;
            fresh = NULL;
            entry_link(cache, link, e);
        }
        cache->stats.pending--;
        e->reply = reply;
        reply = NULL;
        e->bytes += sizeof(mtd_reply) + size;
        cache->stats.bytes += sizeof(mtd_reply) + size;
        evict(cache, 0, 0, e, &freed);
    }
    pthread_mutex_unlock(&cache->lock);

    free(fresh);
    mtd_reply_release(reply);
    free_chain(freed);
    return status;
}

void mtd_reqcache_abandon(mtd_reqcache *cache, const char *reply_channel, int64_t request_id)
{
    size_t len = channel_length(reply_channel);
    if (len == 0) return;
    uint64_t hash = key_hash(reply_channel, len, request_id);
    centry *gone = NULL;
    pthread_mutex_lock(&cache->lock);
    centry *e = *find_link(cache, hash, reply_channel, len, request_id);
    if (e && !e->reply) gone = entry_unlink(cache, e);
    pthread_mutex_unlock(&cache->lock);
    entry_free(gone);
}

void mtd_reqcache_get_stats(mtd_reqcache *cache, mtd_reqcache_stats *out_stats)
{
    pthread_mutex_lock(&cache->lock);
    *out_stats = cache->stats;
    pthread_mutex_unlock(&cache->lock);
}

size_t mtd_reqcache_expire(mtd_reqcache *cache, int64_t now_us, int64_t max_age_us)
{
    centry *freed = NULL;
    size_t n = 0;
    pthread_mutex_lock(&cache->lock);
    for (centry *e = cache->oldest; e && now_us - e->arrived_us > max_age_us;) {
        centry *next = e->newer;
        if (e->reply) {
            entry_unlink(cache, e);
            e->older = freed;
            freed = e;
            n++;
        }
        e = next;
    }
    cache->stats.evictions += n;
    pthread_mutex_unlock(&cache->lock);
    free_chain(freed);
    return n;
}
