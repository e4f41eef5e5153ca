/* meshtopod's running state and the pieces that share it: the LCM handle, the
 * mesh store, the worker pool, the request cache and the heartbeat counters.
 * dispatch.c turns received bytes into calls of submit.c and query.c;
 * heartbeat.c reports the counters; main.c owns the loop. Everything here may
 * be used from the LCM thread and from build workers (LCM's publish is thread
 * safe; the counters are atomics and one mutex guards the last error). */
#ifndef MESHTOPOD_DAEMON_H
#define MESHTOPOD_DAEMON_H

#include <lcm/lcm.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "config.h"
#include "mesh_store.h"
#include "meshtopo/msgs.h"
#include "request_cache.h"
#include "worker_pool.h"

/* Longest channel name LCM publishes (its own limit). */
#define MTD_CHANNEL_MAX 63
/* A reply whose arrays would exceed this many bytes is refused (TOO_LARGE). */
#define MTD_REPLY_MAX_BYTES (64u << 20)
/* Entries listed per array in a topology_t published with a build; the
 * REPORT and DEFECTS queries give the complete lists. */
#define MTD_TOPOLOGY_LIST_MAX 65536u
/* Length of the error texts in replies (longer ones are cut). */
#define MTD_ERROR_MAX 512
/* Missing ranges listed in one mesh_transfer_t (16 bytes each). */
#define MTD_TRANSFER_GAPS_MAX 1024
/* An encoded reply_t larger than this goes out as reply_part_t pieces. */
#define MTD_SINGLE_MESSAGE_MAX 60000

/* One unfinished chunked submission (transfer.c). */
typedef struct mtd_transfer mtd_transfer;

/* The archive, its catalog and its writer (archiver.c); NULL without one. */
typedef struct mtd_archiver mtd_archiver;

typedef struct mtd_daemon {
    mtd_config config;
    lcm_t *lcm; /* not owned */
    mtd_store *store;
    mtd_pool *pool;
    mtd_reqcache *cache;
    mtd_archiver *archiver;
    lcm_subscription_t *submit_sub, *query_sub;
    char submit_channel[MTD_CHANNEL_MAX + 1];
    char query_channel[MTD_CHANNEL_MAX + 1];
    char topology_channel[MTD_CHANNEL_MAX + 1];
    char status_channel[MTD_CHANNEL_MAX + 1];
    char instance[128];
    int64_t start_utime;
    atomic_bool stopping; /* no new work once set */

    atomic_int_fast64_t submissions, builds, queries, errors, duplicates;

    /* Chunked submissions, keyed by (reply channel, request id); guarded by
     * transfer_lock. transfer_bytes counts against max_transfer_bytes. */
    pthread_mutex_t transfer_lock;
    mtd_transfer *transfers;
    size_t transfers_active;
    uint64_t transfer_bytes;
    atomic_int_fast64_t chunks, transfers_completed, transfers_expired, transfers_refused;
    /* The content buffer of the last finished transfer, kept for the next
     * one that fits in it (transfer.c); guarded by spare_lock. */
    pthread_mutex_t spare_lock;
    void *spare_content;
    size_t spare_capacity;
    /* The build workspace of the last build, kept for the next one
     * (submit.c): a build's scratch arrays are its largest allocations, and
     * fresh pages cost more than the build. Meshes the store drops are
     * recycled into it (mtd_mesh_recycle), so a mesh id resubmitted frame
     * after frame is built into the arrays of an earlier version. Guarded by
     * spare_lock; a build that finds it taken makes its own. */
    mt_build_workspace *spare_workspace;
    pthread_mutex_t error_lock;
    char last_error[MTD_ERROR_MAX];
    int64_t last_error_utime;
} mtd_daemon;

/* Creates the store, pool and cache from config and subscribes to
 * PREFIX+"SUBMIT" and PREFIX+"QUERY" on lcm (raw handlers, queue capacity
 * raised). MT_OK, MT_ERR_INVALID_ARG (prefix too long for LCM channel names),
 * MT_ERR_NOMEM; diag says which. */
mt_status mtd_daemon_create(const mtd_config *config, lcm_t *lcm, mtd_daemon **out_daemon,
                            mt_diag *diag);

/* Stops taking work: unsubscribes, cancels queued builds (each gets a BUSY
 * ack), waits for running builds. Idempotent. */
void mtd_daemon_stop(mtd_daemon *daemon);

/* mtd_daemon_stop, then frees everything (not the LCM handle). NULL-safe. */
void mtd_daemon_destroy(mtd_daemon *daemon);

/* Microseconds since the epoch. */
int64_t mtd_now_utime(void);

/* ---- replies (dispatch.c) ---- */

/* Encodes msg of `type`, stores it in the request cache under
 * (channel, request_id) when `remember` (a retry then gets the same bytes),
 * and publishes it on channel. Counts an error when status is not OK and
 * keeps its text for the heartbeat. */
void mtd_send_reply(mtd_daemon *daemon, const char *channel, int64_t request_id, bool remember,
                    const mt_msgs_type *type, const void *msg, int32_t status, const char *error);

/* Publishes an ack_t carrying only a status and an error. */
void mtd_send_ack_error(mtd_daemon *daemon, const char *channel, int64_t request_id,
                        const char *mesh_id, bool remember, int32_t status, const char *error);

/* Publishes a reply_t carrying only a status and an error. */
void mtd_send_reply_error(mtd_daemon *daemon, const char *channel, int64_t request_id,
                          const char *mesh_id, int32_t kind, bool remember, int32_t status,
                          const char *error);

/* Reads the header every request starts with: fingerprint, utime,
 * request_id, reply_channel (int32 length with its NUL, then the bytes).
 * Returns true with the channel copied into channel[MTD_CHANNEL_MAX + 1]. */
bool mtd_peek_request_header(const void *data, size_t size, int64_t *out_request_id, char *channel);

/* Checks the reply channel and the request cache. Returns true when the
 * request is new (now marked pending) and must be run; a finished one has
 * had its reply published again. */
bool mtd_begin_request(mtd_daemon *daemon, const char *channel, int64_t request_id);

/* ---- large answers (reply_parts.c) ---- */

/* Publishes an encoded answer for request_id on channel: as it is, or, for a
 * reply_t over MTD_SINGLE_MESSAGE_MAX bytes, as its first reply_part_t pieces
 * (msgs/reply_part_t.lcm; the receiver pulls the rest from the request
 * cache). Any thread. */
void mtd_publish_answer(mtd_daemon *daemon, const char *channel, int64_t request_id,
                        const void *data, size_t size);

/* Handles one received reply_pull_t (bytes with its fingerprint): sends the
 * parts it asks for from the request cache; unanswered when the cache holds
 * no such answer. Runs on the LCM thread. */
void mtd_reply_pull_handle(mtd_daemon *daemon, const void *data, size_t size);

/* ---- submissions (submit.c) ---- */

/* Handles one decoded mesh_t whose request was new in the request cache.
 * `encoded` is the received message (for the content hash). Takes ownership
 * of msg (heap-allocated, decoded by mt_msgs_decode). */
void mtd_submit_handle(mtd_daemon *daemon, meshtopo_mesh_t *msg, const void *encoded,
                       size_t encoded_size);

/* A chunked submission, reassembled: msg's strings are heap copies it owns,
 * its arrays point into `content` (the decoded chunks, mesh_content.h, a
 * buffer of content_capacity bytes), whose hash the decoder computed. Takes
 * msg and content (given back with mtd_content_release). */
void mtd_submit_handle_content(mtd_daemon *daemon, meshtopo_mesh_t *msg, void *content,
                               size_t content_capacity, uint64_t content_hash);

/* Disposes of a mesh nobody holds any more (the store's dispose_mesh, with
 * the daemon as ctx): its arrays go to the kept build workspace for the next
 * build, or it is destroyed while a build has the workspace. */
void mtd_mesh_recycle(void *daemon, mt_mesh *mesh);

/* ---- chunked submissions (transfer.c) ---- */

/* Handles one received mesh_chunk_t (bytes with its fingerprint, not yet
 * decoded): decodes it, adds it to its transfer (admitting a new one within
 * the limits), answers with mesh_transfer_t when asked or wrong, and hands a
 * complete mesh to mtd_submit_handle. Runs on the LCM thread. */
void mtd_chunk_handle(mtd_daemon *daemon, const void *data, size_t size);

/* Drops every transfer that received nothing for transfer_timeout_ms and
 * releases its memory. Returns how many were dropped. */
size_t mtd_transfers_expire(mtd_daemon *daemon);

/* Frees every transfer and the kept content buffer (at destroy). */
void mtd_transfers_free(mtd_daemon *daemon);

/* Gives back a transfer's content buffer of `capacity` bytes: it is kept for
 * the next transfer that fits in it (the one kept before is freed), so that
 * a stream of similar meshes does not make the kernel map and zero fresh
 * pages for each one, which costs more than the network does. NULL-safe. */
void mtd_content_release(mtd_daemon *daemon, void *content, size_t capacity);

/* ---- queries (query.c) ---- */

/* Answers one decoded query_t whose request was new in the request cache. */
void mtd_query_handle(mtd_daemon *daemon, const meshtopo_query_t *msg);

/* ---- topology reports (topology.c) ---- */

/* Fills out (zeroed first) from a built mesh's report; at most list_max
 * entries per list (SIZE_MAX for all). Returns 0, or -1 when out of memory
 * (out then owns nothing). Free with mtd_topology_free. */
int mtd_topology_fill(const mt_mesh *mesh, const mtd_mesh_info *info, int64_t build_duration_us,
                      size_t list_max, meshtopo_topology_t *out);

/* Frees what mtd_topology_fill allocated. NULL-safe. */
void mtd_topology_free(meshtopo_topology_t *topology);

/* ---- heartbeat (heartbeat.c) ---- */

/* Expires stalled transfers, then publishes one status_t on PREFIX+"STATUS". */
void mtd_heartbeat_publish(mtd_daemon *daemon);

#endif
