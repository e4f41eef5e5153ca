/* meshtopod's request-id deduplication. A request is keyed by its reply
 * channel and request_id. The first arrival marks it pending and runs it;
 * a retry while it runs is told so (and must not start it again); a retry
 * after it finished gets the encoded reply bytes stored by then, to publish
 * again without re-executing. Bounded by entry count and bytes, oldest
 * request evicted first; pending requests are never evicted. Thread safe. */
#ifndef MESHTOPOD_REQUEST_CACHE_H
#define MESHTOPOD_REQUEST_CACHE_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Longest reply channel accepted as a key, in bytes (LCM itself allows 63). */
#define MTD_REPLY_CHANNEL_MAX 255
/* Upper limit of max_entries. */
#define MTD_REQCACHE_MAX_ENTRIES (1u << 24)

/* An immutable stored reply (opaque encoded bytes), reference counted so it
 * can be published after the cache has evicted it. */
typedef struct mtd_reply mtd_reply;

const void *mtd_reply_data(const mtd_reply *reply);
size_t mtd_reply_size(const mtd_reply *reply);
/* Drops one reference; the last frees the bytes. NULL-safe. */
void mtd_reply_release(mtd_reply *reply);

/* Limits; a zeroed struct (or NULL) gives the defaults. */
typedef struct mtd_reqcache_options {
    /* Requests remembered (0 = 4096; at most MTD_REQCACHE_MAX_ENTRIES). */
    size_t max_entries;
    /* Bytes of stored replies plus keys and bookkeeping (0 = 64 MiB). A reply
     * larger than this on its own is not stored. */
    size_t max_bytes;
} mtd_reqcache_options;

typedef struct mtd_reqcache mtd_reqcache;

/* MT_OK, MT_ERR_INVALID_ARG (max_entries too large), MT_ERR_NOMEM. */
mt_status mtd_reqcache_create(const mtd_reqcache_options *options, mtd_reqcache **out_cache);

/* Frees the cache; replies still held by callers stay valid. NULL-safe. */
void mtd_reqcache_destroy(mtd_reqcache *cache);

/* What mtd_reqcache_begin found. */
typedef enum mtd_request_state {
    /* First arrival: it is now marked pending. The caller runs it, then calls
     * mtd_reqcache_finish with the reply (or mtd_reqcache_abandon). */
    MTD_REQUEST_NEW,
    /* Already running: do not start it again (its reply will be sent when it
     * finishes). */
    MTD_REQUEST_PENDING,
    /* Answered before: *out_reply holds the reply to publish again. */
    MTD_REQUEST_DONE
} mtd_request_state;

/* Looks the request up and, when it is new, marks it pending, in one atomic
 * step: of two copies arriving together exactly one is NEW. On MTD_REQUEST_DONE
 * *out_reply is a reference the caller must release; otherwise it is NULL.
 * Returns MT_OK, MT_ERR_INVALID_ARG (channel NULL, empty or longer than
 * MTD_REPLY_CHANNEL_MAX), MT_ERR_NOMEM (nothing marked). */
mt_status mtd_reqcache_begin(mtd_reqcache *cache, const char *reply_channel, int64_t request_id,
                             mtd_request_state *out_state, mtd_reply **out_reply);

/* mtd_reqcache_begin without marking anything: MTD_REQUEST_NEW means the
 * cache does not know the request. Counts no hit. */
mt_status mtd_reqcache_peek(mtd_reqcache *cache, const char *reply_channel, int64_t request_id,
                            mtd_request_state *out_state, mtd_reply **out_reply);

/* Stores the encoded reply of a request (copying `size` bytes of `data`), so
 * retries get it; the request stops being pending. Works without a begin too
 * (the reply is remembered as a new request). If the request already has a
 * reply, that first one is kept. Older requests are evicted to stay within
 * the limits. Returns MT_OK; MT_ERR_TOO_LARGE when the reply alone exceeds
 * max_bytes (it is not stored and the pending mark is removed, so a retry
 * runs the request again); MT_ERR_INVALID_ARG; MT_ERR_NOMEM (pending mark
 * removed too). */
mt_status mtd_reqcache_finish(mtd_reqcache *cache, const char *reply_channel, int64_t request_id,
                              const void *data, size_t size);

/* Removes the pending mark of a request that will not be answered (for
 * example cancelled at shutdown), so a retry runs it. A request that is not
 * pending is left alone. */
void mtd_reqcache_abandon(mtd_reqcache *cache, const char *reply_channel, int64_t request_id);

/* Forgets the answered requests that arrived more than max_age_us before
 * now_us (monotonic; pending ones stay), so what a burst left behind does
 * not stay in memory once retries are no longer to be expected. Returns how
 * many were dropped (counted as evictions). */
size_t mtd_reqcache_expire(mtd_reqcache *cache, int64_t now_us, int64_t max_age_us);

typedef struct mtd_reqcache_stats {
    size_t entries; /* requests remembered, pending ones included */
    size_t pending; /* of which pending */
    size_t bytes;   /* counted against max_bytes */
    uint64_t new_requests;
    uint64_t pending_hits; /* begin found the request running */
    uint64_t done_hits;    /* begin found a stored reply */
    uint64_t evictions;
} mtd_reqcache_stats;

void mtd_reqcache_get_stats(mtd_reqcache *cache, mtd_reqcache_stats *out_stats);

#ifdef __cplusplus
}
#endif

#endif
