/* meshtopod's chunked submissions (transfer.h): reassembles the content of a
 * mesh_t sent in single-datagram pieces, per (reply channel, request id),
 * into one buffer that a content decoder (meshtopo/mesh_content.h) hashes and
 * turns into the mesh's arrays while the chunks arrive, so the complete mesh
 * goes to the submitter at once. The buffer is a mapping whose pages cost
 * memory once written; a transfer is charged for the pages up to the
 * highest byte it was sent, which the window (chunks start at most
 * WINDOW_BYTES past the first missing byte) keeps close to what it really
 * received, against --max-transfer-bytes and its reply channel's share of
 * it. Stalled transfers expire (--transfer-timeout-ms) and give their pages
 * back to the system; and
 * every chunk that contradicts its transfer is answered with BAD_REQUEST
 * without touching the transfer. The LCM thread runs all of it; one mutex
 * guards the table for the heartbeat's reads. */
#include "transfer.h"

#include <inttypes.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "byte_ranges.h"
#include "clock.h"
#include "log.h"
#include "meshtopo/mesh_content.h"

/* Bytes of mesh_t's four content counts, encoded with no arrays behind them. */
#define EMPTY_CONTENT_SIZE 16

/* Charges grow by whole steps of this (pages written, rounded up). */
#define CHARGE_STEP (64u << 10)

/* The protocol's numbers (msgs/mesh_chunk_t.lcm) as sizes. */
static const uint64_t window_bytes = MESHTOPO_MESH_CHUNK_T_WINDOW_BYTES;
static const size_t ranges_max = MESHTOPO_MESH_CHUNK_T_RECEIVED_RANGES_MAX;

typedef struct mtd_transfer mtd_transfer;

struct mtd_transfer {
    mtd_transfer *next;
    char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
    int64_t request_id;
    char *mesh_id, *source;
    bool strict;
    int64_t utime; /* the mesh's, from the first chunk */
    uint64_t total, hash;
    uint8_t *content; /* total bytes, being reassembled */
    size_t capacity;  /* of the content buffer (>= total) */
    mt_msgs_content_decoder *decoder;
    size_t charged; /* counted in transfer_bytes: the pages up to the highest byte sent */
    mtd_byte_ranges got;
    int64_t first_us, last_us; /* monotonic */
};

struct mtd_transfers {
    mtd_transfer_deps deps;
    pthread_mutex_t lock; /* the table and its totals */
    mtd_transfer *head;   /* keyed by (reply channel, request id) */
    size_t active;
    uint64_t bytes; /* charged against max_transfer_bytes */
    atomic_bool stopping;
    atomic_int_fast64_t chunks, completed, expired, refused, dropped;
};

/* Frees t. Its content buffer, if it still has one, is kept for the next
 * transfer when t was complete (the sender paid for every byte), else
 * unmapped. */
static void transfer_free(mtd_transfers *ts, mtd_transfer *t)
{
    if (!t) return;
    free(t->mesh_id);
    free(t->source);
    mt_msgs_content_decoder_free(t->decoder);
    if (t->content && t->got.covered == t->total)
        mtd_content_release(ts->deps.contents, t->content, t->capacity);
    else
        mtd_content_discard(t->content, t->capacity);
    mtd_byte_ranges_free(&t->got);
    free(t);
}

/* Unlinks t from the table and releases its charge (the lock held). */
static void unlink_transfer(mtd_transfers *ts, mtd_transfer *t)
{
    for (mtd_transfer **link = &ts->head; *link; link = &(*link)->next) {
        if (*link == t) {
            *link = t->next;
            t->next = NULL;
            ts->active--;
            ts->bytes -= t->charged;
            t->charged = 0;
            return;
        }
    }
}

static mtd_transfer *find_transfer(mtd_transfers *ts, const char *channel, int64_t request_id)
{
    for (mtd_transfer *t = ts->head; t; t = t->next)
        if (t->request_id == request_id && strcmp(t->channel, channel) == 0) return t;
    return NULL;
}

/* An unfinished transfer of the same content from the same source under
 * another key: what a restarted sender had already sent. */
static mtd_transfer *find_resumable(mtd_transfers *ts, const meshtopo_mesh_chunk_t *c)
{
    for (mtd_transfer *t = ts->head; t; t = t->next)
        if (t->total == (uint64_t)c->total_size && t->hash == (uint64_t)c->content_hash &&
            t->strict == (c->strict != 0) && strcmp(t->mesh_id, c->mesh_id) == 0 &&
            strcmp(t->source, c->source) == 0)
            return t;
    return NULL;
}

/* Publishes a mesh_transfer_t (never remembered: it describes the moment). */
static void send_status(mtd_transfers *ts, const char *channel, int64_t request_id, int32_t status,
                        const char *error, const mtd_transfer *t, uint64_t total, bool complete)
{
    static int64_t offsets[MESHTOPO_MESH_TRANSFER_T_MISSING_MAX],
        lengths[MESHTOPO_MESH_TRANSFER_T_MISSING_MAX];
    meshtopo_mesh_transfer_t msg;
    memset(&msg, 0, sizeof msg);
    msg.utime = mtd_now_utime();
    msg.request_id = request_id;
    msg.status = status;
    msg.error = (char *)(error ? error : "");
    msg.total_size = (int64_t)total;
    msg.complete = complete;
    msg.received_bytes = complete ? (int64_t)total : 0;
    msg.listed_until = (int64_t)total;
    if (t && !complete) {
        uint64_t until = 0;
        msg.num_missing = (int32_t)mtd_byte_ranges_gaps(
            &t->got, t->total, MESHTOPO_MESH_TRANSFER_T_MISSING_MAX, offsets, lengths, &until);
        msg.missing_offsets = offsets;
        msg.missing_lengths = lengths;
        msg.listed_until = (int64_t)until;
        msg.received_bytes = (int64_t)t->got.covered;
    }
    if (status != MESHTOPO_STATUS_CODE_T_OK)
        mtd_log(MTD_LOG_INFO, "chunk_error", "request_id=%" PRId64 " status=%d error=%s",
                request_id, (int)status, error);
    mtd_reply_send(ts->deps.replies, channel, request_id, false, &mt_msgs_type_mesh_transfer, &msg,
                   status, error);
}

/* The largest content the mesh limits allow (mesh_t's arrays at their maxima). */
static uint64_t content_limit(const mtd_config *config)
{
    return EMPTY_CONTENT_SIZE + 24ull * config->max_verts + 4ull * config->max_faces +
           4ull * config->max_indices;
}

/* Admits a new transfer for chunk c (the lock held), taking over a
 * resumable one. Returns it, or NULL after answering why not. */
static mtd_transfer *admit(mtd_transfers *ts, const meshtopo_mesh_chunk_t *c)
{
    char error[MTD_ERROR_MAX];
    const uint64_t total = (uint64_t)c->total_size;
    const uint64_t cap = ts->deps.config->max_transfer_bytes;
    int32_t status = MESHTOPO_STATUS_CODE_T_OK;
    mt_diag diag;
    if (mt_msgs_mesh_id_check(c->mesh_id, &diag) != MT_OK) {
        snprintf(error, sizeof error, "mesh_id: %.400s", diag.message);
        send_status(ts, c->reply_channel, c->request_id, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, error,
                    NULL, total, false);
        return NULL;
    }
    if (total > content_limit(ts->deps.config)) {
        status = MESHTOPO_STATUS_CODE_T_TOO_LARGE;
        snprintf(error, sizeof error,
                 "total_size: %" PRIu64
                 " bytes exceed the largest mesh the daemon accepts "
                 "(%" PRIu64 " bytes: --max-verts, --max-faces, --max-indices)",
                 total, content_limit(ts->deps.config));
    } else if (total > cap || total > (uint64_t)INT32_MAX - 4096) {
        status = MESHTOPO_STATUS_CODE_T_TOO_LARGE;
        snprintf(error, sizeof error, "total_size: %" PRIu64 " bytes exceed %s (%" PRIu64 " bytes)",
                 total, total > cap ? "--max-transfer-bytes" : "the largest LCM message",
                 total > cap ? cap : (uint64_t)INT32_MAX - 4096);
    }
    /* Nothing is charged yet: memory follows the bytes that arrive. */
    mtd_transfer *old = status == MESHTOPO_STATUS_CODE_T_OK ? find_resumable(ts, c) : NULL;
    mtd_transfer *t = NULL;
    if (status == MESHTOPO_STATUS_CODE_T_OK) {
        t = calloc(1, sizeof *t);
        if (t) {
            t->mesh_id = strdup(c->mesh_id);
            t->source = strdup(c->source);
            if (old) { /* its bytes, ranges and decoder carry over */
                t->content = old->content;
                t->decoder = old->decoder;
                t->capacity = old->capacity;
            } else {
                t->content = mtd_content_take(ts->deps.contents, total, &t->capacity);
                t->decoder = t->content ? mt_msgs_content_decoder_new(t->content, total) : NULL;
            }
        }
        if (!t || !t->mesh_id || !t->source || !t->content || !t->decoder) {
            if (t && old) { /* still old's */
                t->content = NULL;
                t->decoder = NULL;
            }
            transfer_free(ts, t);
            t = NULL;
            status = MESHTOPO_STATUS_CODE_T_BUSY;
            snprintf(error, sizeof error,
                     "out of memory for a %" PRIu64 "-byte transfer; retry later", total);
        }
    }
    if (status != MESHTOPO_STATUS_CODE_T_OK) {
        atomic_fetch_add(&ts->refused, 1);
        send_status(ts, c->reply_channel, c->request_id, status, error, NULL, total, false);
        return NULL;
    }
    snprintf(t->channel, sizeof t->channel, "%s", c->reply_channel);
    t->request_id = c->request_id;
    t->strict = c->strict != 0;
    t->utime = c->utime;
    t->total = total;
    t->hash = (uint64_t)c->content_hash;
    t->first_us = t->last_us = mtd_monotonic_us();
    t->charged = 0;
    if (old) {
        old->content = NULL;
        old->decoder = NULL;
        t->got = old->got;
        memset(&old->got, 0, sizeof old->got);
        size_t charged = old->charged;
        unlink_transfer(ts, old);
        t->charged = charged;
        mtd_log(MTD_LOG_INFO, "transfer_resumed",
                "mesh_id=%s request_id=%" PRId64 " from request_id=%" PRId64
                " channel=%s bytes_held=%" PRIu64,
                t->mesh_id, t->request_id, old->request_id, old->channel, t->got.covered);
        transfer_free(ts, old);
    }
    t->next = ts->head;
    ts->head = t;
    ts->active++;
    ts->bytes += t->charged;
    mtd_log(MTD_LOG_DEBUG, "transfer_begin",
            "mesh_id=%s request_id=%" PRId64 " channel=%s total=%" PRIu64, t->mesh_id,
            t->request_id, t->channel, total);
    return t;
}

/* The first field in which chunk c contradicts transfer t, described in
 * error; false when it agrees. */
static bool contradicts(const mtd_transfer *t, const meshtopo_mesh_chunk_t *c, char *error,
                        size_t size)
{
    if ((uint64_t)c->total_size != t->total)
        snprintf(error, size, "total_size: %" PRId64 " differs from the transfer's %" PRIu64,
                 c->total_size, t->total);
    else if ((uint64_t)c->content_hash != t->hash)
        snprintf(error, size,
                 "content_hash: %016" PRIx64 " differs from the transfer's %016" PRIx64,
                 (uint64_t)c->content_hash, t->hash);
    else if (strcmp(c->mesh_id, t->mesh_id) != 0)
        snprintf(error, size, "mesh_id: '%.100s' differs from the transfer's '%.100s'", c->mesh_id,
                 t->mesh_id);
    else if (strcmp(c->source, t->source) != 0)
        snprintf(error, size, "source: '%.100s' differs from the transfer's '%.100s'", c->source,
                 t->source);
    else if ((c->strict != 0) != t->strict)
        snprintf(error, size, "strict: %d differs from the transfer's %d", c->strict != 0,
                 (int)t->strict);
    else
        return false;
    return true;
}

/* A heap mesh_t for t's submission: t's header fields (copied) and the
 * decoded content's counts and arrays (pointing into t->content). NULL when
 * out of memory. */
static meshtopo_mesh_t *new_mesh_msg(const mtd_transfer *t, const meshtopo_mesh_t *content)
{
    meshtopo_mesh_t *msg = malloc(sizeof *msg);
    if (!msg) return NULL;
    *msg = *content;
    msg->utime = t->utime;
    msg->request_id = t->request_id;
    msg->strict = t->strict;
    msg->reply_channel = strdup(t->channel);
    msg->mesh_id = strdup(t->mesh_id);
    msg->source = strdup(t->source);
    if (!msg->reply_channel || !msg->mesh_id || !msg->source) {
        free(msg->reply_channel);
        free(msg->mesh_id);
        free(msg->source);
        free(msg);
        return NULL;
    }
    return msg;
}

/* Every byte of t is in (t is out of the table): check the hash and the
 * counts the decoder saw, submit once. Takes t. */
static void finish(mtd_transfers *ts, mtd_transfer *t)
{
    atomic_fetch_add(&ts->completed, 1);
    mtd_log(MTD_LOG_INFO, "transfer_complete",
            "mesh_id=%s request_id=%" PRId64 " bytes=%" PRIu64 " transfer_us=%" PRId64, t->mesh_id,
            t->request_id, t->total, mtd_monotonic_us() - t->first_us);
    meshtopo_mesh_t content;
    memset(&content, 0, sizeof content);
    uint64_t hash = 0;
    char why[MTD_ERROR_MAX / 2];
    int decoded = mt_msgs_content_decoder_finish(t->decoder, &content, &hash, why, sizeof why);
    char error[MTD_ERROR_MAX];
    int32_t status = MESHTOPO_STATUS_CODE_T_OK;
    meshtopo_mesh_t *msg = NULL;
    if (hash != t->hash) {
        status = MESHTOPO_STATUS_CODE_T_BAD_REQUEST;
        snprintf(error, sizeof error,
                 "content_hash: the reassembled %" PRIu64 " bytes hash to %016" PRIx64
                 ", the chunks said %016" PRIx64,
                 t->total, hash, t->hash);
    } else if (decoded != 0) {
        status = MESHTOPO_STATUS_CODE_T_UNDECODABLE;
        snprintf(error, sizeof error, "undecodable mesh_t from the chunks' content: %s", why);
    } else if (atomic_load(&ts->stopping)) {
        status = MESHTOPO_STATUS_CODE_T_BUSY;
        snprintf(error, sizeof error, "the daemon is shutting down");
    } else if (!(msg = new_mesh_msg(t, &content))) {
        status = MESHTOPO_STATUS_CODE_T_INTERNAL;
        snprintf(error, sizeof error, "out of memory");
    }
    if (status != MESHTOPO_STATUS_CODE_T_OK) {
        mtd_reply_ack_error(ts->deps.replies, t->channel, t->request_id, t->mesh_id, false, status,
                            error);
    } else if (mtd_reply_begin(ts->deps.replies, t->channel, t->request_id, &mt_msgs_type_ack)) {
        mtd_submit_content(ts->deps.submitter, msg, t->content, t->capacity, hash); /* takes both */
        t->content = NULL;
    } else {
        free(msg->reply_channel);
        free(msg->mesh_id);
        free(msg->source);
        free(msg);
    }
    transfer_free(ts, t);
}

/* The bytes t holds from offset 0 on, without a gap: what its decoder has
 * been given. */
static uint64_t held_from_start(const mtd_transfer *t)
{
    return t->got.count > 0 && t->got.items[0].start == 0 ? t->got.items[0].end : 0;
}

/* Bytes charged to the transfers of `channel`, and whether other reply
 * channels have transfers (the lock held). */
static uint64_t sender_bytes(const mtd_transfers *ts, const char *channel, bool *out_others)
{
    uint64_t bytes = 0;
    *out_others = false;
    for (const mtd_transfer *t = ts->head; t; t = t->next) {
        if (strcmp(t->channel, channel) == 0)
            bytes += t->charged;
        else
            *out_others = true;
    }
    return bytes;
}

/* Whether chunk c of t is kept (the lock held): it starts within the window
 * after the first missing byte, it does not split the received bytes into
 * more than ranges_max pieces, and the pages it adds fit the memory limit
 * and the sender's share (charged now). A chunk not kept is answered (BUSY
 * for memory; the missing list when asked) and dropped. */
static bool keep_chunk(mtd_transfers *ts, mtd_transfer *t, const meshtopo_mesh_chunk_t *c)
{
    const uint64_t start = (uint64_t)c->offset, end = start + (uint64_t)c->length;
    if (start >= held_from_start(t) + window_bytes ||
        (t->got.count >= ranges_max && !mtd_byte_ranges_touches(&t->got, start, end))) {
        atomic_fetch_add(&ts->dropped, 1);
        if (c->want_status)
            send_status(ts, t->channel, t->request_id, MESHTOPO_STATUS_CODE_T_OK, "", t, t->total,
                        false);
        return false;
    }
    uint64_t high = (end + CHARGE_STEP - 1) / CHARGE_STEP * CHARGE_STEP;
    if (high > t->total) high = t->total;
    if (high <= t->charged) return true;
    const uint64_t growth = high - t->charged, cap = ts->deps.config->max_transfer_bytes;
    bool others = false;
    const uint64_t mine = sender_bytes(ts, t->channel, &others);
    const uint64_t share = others ? cap / 4 : cap;
    if (ts->bytes + growth <= cap && mine + growth <= share) {
        t->charged = (size_t)high;
        ts->bytes += growth;
        return true;
    }
    char error[MTD_ERROR_MAX];
    if (ts->bytes + growth > cap)
        snprintf(error, sizeof error,
                 "%zu unfinished transfer(s) hold %" PRIu64 " of --max-transfer-bytes %" PRIu64
                 " bytes: chunk at %" PRIu64 " dropped, retry later",
                 ts->active, ts->bytes, cap, start);
    else
        snprintf(error, sizeof error,
                 "reply channel '%s' holds %" PRIu64
                 " bytes of transfers, its share of "
                 "--max-transfer-bytes %" PRIu64 " while others send: chunk at %" PRIu64
                 " dropped, retry later",
                 t->channel, mine, cap, start);
    atomic_fetch_add(&ts->refused, 1);
    send_status(ts, t->channel, t->request_id, MESHTOPO_STATUS_CODE_T_BUSY, error, t, t->total,
                false);
    return false;
}

/* Handles one decoded chunk (the lock held). Returns a transfer that
 * became complete (out of the table) for the caller to finish. */
static mtd_transfer *take_chunk(mtd_transfers *ts, const meshtopo_mesh_chunk_t *c)
{
    char error[MTD_ERROR_MAX];
    const char *channel = c->reply_channel;
    error[0] = '\0';
    if (c->total_size <= 0)
        snprintf(error, sizeof error, "total_size: %" PRId64 " must be positive", c->total_size);
    else if (c->offset < 0)
        snprintf(error, sizeof error, "offset: %" PRId64 " is negative", c->offset);
    else if (c->offset > c->total_size || c->length > c->total_size - c->offset)
        snprintf(error, sizeof error,
                 "offset %" PRId64 " + length %" PRId32 " reaches past total_size %" PRId64,
                 c->offset, c->length, c->total_size);
    if (error[0]) {
        send_status(ts, channel, c->request_id, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, error, NULL,
                    c->total_size > 0 ? (uint64_t)c->total_size : 0, false);
        return NULL;
    }
    mtd_transfer *t = find_transfer(ts, channel, c->request_id);
    if (!t && !mtd_cluster_owns(ts->deps.cluster, c->mesh_id)) return NULL; /* its owner's */
    if (!t) {
        /* Finished already (building or acked), or new. */
        mtd_request_state state = mtd_reply_state(ts->deps.replies, channel, c->request_id,
                                                  &mt_msgs_type_ack, c->want_status);
        if (state != MTD_REQUEST_NEW) {
            if (state == MTD_REQUEST_PENDING && c->want_status)
                send_status(ts, channel, c->request_id, MESHTOPO_STATUS_CODE_T_OK, "", NULL,
                            (uint64_t)c->total_size, true);
            return NULL;
        }
        if (atomic_load(&ts->stopping)) {
            send_status(ts, channel, c->request_id, MESHTOPO_STATUS_CODE_T_BUSY,
                        "the daemon is shutting down", NULL, (uint64_t)c->total_size, false);
            return NULL;
        }
        if (!(t = admit(ts, c))) return NULL;
    } else if (contradicts(t, c, error, sizeof error)) {
        send_status(ts, channel, c->request_id, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, error, NULL,
                    t->total, false);
        return NULL;
    }
    t->last_us = mtd_monotonic_us();
    if (c->length > 0 && !keep_chunk(ts, t, c)) return NULL;
    if (c->length > 0) {
        const uint64_t start = (uint64_t)c->offset, end = start + (uint64_t)c->length;
        /* Bytes below `decoded` were turned into values in place already:
         * a chunk sent again must not overwrite them. */
        const uint64_t decoded = held_from_start(t);
        const uint64_t copy_from = start > decoded ? start : decoded;
        /* Copy first: a failed add only forgets that these bytes arrived. */
        if (copy_from < end)
            memcpy(t->content + copy_from, c->data + (copy_from - start),
                   (size_t)(end - copy_from));
        if (mtd_byte_ranges_add(&t->got, start, end, NULL) != MT_OK)
            mtd_log(MTD_LOG_WARN, "chunk", "request_id=%" PRId64 " out of memory for its ranges",
                    c->request_id);
        mt_msgs_content_decoder_advance(t->decoder, held_from_start(t));
    }
    if (t->got.covered == t->total) {
        send_status(ts, channel, c->request_id, MESHTOPO_STATUS_CODE_T_OK, "", NULL, t->total,
                    true);
        unlink_transfer(ts, t);
        return t;
    }
    if (c->want_status)
        send_status(ts, channel, c->request_id, MESHTOPO_STATUS_CODE_T_OK, "", t, t->total, false);
    return NULL;
}

void mtd_transfers_chunk(mtd_transfers *ts, const void *data, size_t size)
{
    atomic_fetch_add(&ts->chunks, 1);
    mtd_transfers_expire(ts);
    meshtopo_mesh_chunk_t c;
    char why[MT_MSGS_ERROR_SIZE];
    if (mt_msgs_decode(&mt_msgs_type_mesh_chunk, data, size, &c, why, sizeof why) != 0) {
        char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
        char error[MTD_ERROR_MAX];
        int64_t request_id = 0;
        snprintf(error, sizeof error, "undecodable mesh_chunk_t: %s", why);
        if (mtd_reply_peek_header(data, size, &request_id, channel) &&
            mtd_reply_channel_check(ts->deps.replies, channel, request_id))
            send_status(ts, channel, request_id, MESHTOPO_STATUS_CODE_T_UNDECODABLE, error, NULL, 0,
                        false);
        else
            mtd_log(MTD_LOG_WARN, "undecodable", "bytes=%zu error=%s (no reply channel)", size,
                    error);
        return;
    }
    if (!mtd_reply_channel_check(ts->deps.replies, c.reply_channel, c.request_id)) {
        meshtopo_mesh_chunk_t_decode_cleanup(&c);
        return;
    }
    pthread_mutex_lock(&ts->lock);
    mtd_transfer *complete = take_chunk(ts, &c);
    pthread_mutex_unlock(&ts->lock);
    meshtopo_mesh_chunk_t_decode_cleanup(&c);
    if (complete) finish(ts, complete);
}

size_t mtd_transfers_expire(mtd_transfers *ts)
{
    const int64_t now = mtd_monotonic_us();
    const int64_t timeout = (int64_t)ts->deps.config->transfer_timeout_ms * 1000;
    mtd_transfer *expired = NULL;
    size_t n = 0;
    pthread_mutex_lock(&ts->lock);
    mtd_transfer *t = ts->head;
    while (t) {
        mtd_transfer *next = t->next;
        if (now - t->last_us > timeout) {
            unlink_transfer(ts, t);
            t->next = expired;
            expired = t;
            n++;
        }
        t = next;
    }
    pthread_mutex_unlock(&ts->lock);
    while (expired) {
        mtd_transfer *e = expired;
        expired = e->next;
        atomic_fetch_add(&ts->expired, 1);
        mtd_log(MTD_LOG_INFO, "transfer_expired",
                "mesh_id=%s request_id=%" PRId64 " channel=%s received=%" PRIu64 "/%" PRIu64
                " idle_ms=%" PRId64,
                e->mesh_id, e->request_id, e->channel, e->got.covered, e->total,
                (now - e->last_us) / 1000);
        transfer_free(ts, e);
    }
    return n;
}

mt_status mtd_transfers_create(const mtd_transfer_deps *deps, mtd_transfers **out_transfers)
{
    mtd_transfers *ts = calloc(1, sizeof *ts);
    *out_transfers = ts;
    if (!ts) return MT_ERR_NOMEM;
    ts->deps = *deps;
    pthread_mutex_init(&ts->lock, NULL);
    return MT_OK;
}

void mtd_transfers_destroy(mtd_transfers *ts)
{
    if (!ts) return;
    while (ts->head) {
        mtd_transfer *t = ts->head;
        unlink_transfer(ts, t);
        transfer_free(ts, t);
    }
    pthread_mutex_destroy(&ts->lock);
    free(ts);
}

void mtd_transfers_stop(mtd_transfers *ts)
{
    atomic_store(&ts->stopping, true);
}

void mtd_transfers_get_stats(mtd_transfers *ts, mtd_transfer_stats *out_stats)
{
    pthread_mutex_lock(&ts->lock);
    out_stats->active = (int32_t)ts->active;
    out_stats->bytes = (int64_t)ts->bytes;
    pthread_mutex_unlock(&ts->lock);
    out_stats->chunks = atomic_load(&ts->chunks);
    out_stats->completed = atomic_load(&ts->completed);
    out_stats->expired = atomic_load(&ts->expired);
    out_stats->refused = atomic_load(&ts->refused);
    out_stats->dropped = atomic_load(&ts->dropped);
}
