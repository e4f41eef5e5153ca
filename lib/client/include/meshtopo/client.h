/* meshtopo::client: the C API a perception node uses to talk to meshtopod over
 * LCM: submit a mesh, query a built mesh, list held meshes. Calls are
 * synchronous with a timeout per attempt and retries (a retry reuses the
 * request id, so the daemon answers it again without executing it twice), or
 * asynchronous with a callback. One client is safe to use from many threads.
 * Replies are decoded only with mt_msgs_decode (meshtopo/msgs.h). */
#ifndef MESHTOPO_CLIENT_H
#define MESHTOPO_CLIENT_H

#include <stddef.h>
#include <stdint.h>

#include <lcm/lcm.h>

#include "meshtopo/channels.h"
#include "meshtopo/client_reply.h"
#include "meshtopo/face_list.h"
#include "meshtopo/msgs.h"
#include "meshtopo/protocol.h"
#include "meshtopo/query_kinds.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_client mt_client;

/* Defaults of the zeroed options. */
#define MT_CLIENT_DEFAULT_PREFIX "MESHTOPO_"
#define MT_CLIENT_DEFAULT_TIMEOUT_MS 1000
#define MT_CLIENT_DEFAULT_RETRIES 3
#define MT_CLIENT_BUSY_PAUSE_MS 100
#define MT_CLIENT_BUSY_PAUSE_MAX_MS 3200
/* Longest channel prefix accepted (the client's reply channel, PREFIX "REPLY_"
 * and a unique tail, must fit MESHTOPO_MESH_T_REPLY_CHANNEL_MAX). */
#define MT_CLIENT_MAX_PREFIX 24
/* Content bytes per chunk: the default and the largest allowed (a chunk then
 * encodes to under MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX bytes with the
 * longest ids). */
#define MT_CLIENT_DEFAULT_CHUNK_BYTES MESHTOPO_REPLY_PART_T_PART_SIZE /* a part's size */
#define MT_CLIENT_MAX_CHUNK_BYTES 59000
/* Chunks sent before waiting for the daemon's transfer status. */
#define MT_CLIENT_DEFAULT_WINDOW_CHUNKS 16
/* Bytes all partly received large answers (reply_part_t pieces) may hold
 * together, by default. */
#define MT_CLIENT_DEFAULT_MAX_REPLY_BYTES (256u << 20)

/* Progress of a chunked submission: bytes of the mesh's content the daemon
 * has confirmed, of `total`. Called on the submitting thread, after each
 * status from the daemon and once more with done == total when the ack
 * arrives. */
typedef void (*mt_client_progress_fn)(uint64_t done, uint64_t total, void *user);

/* Options of mt_client_create. A zeroed struct (or NULL) gives the defaults. */
typedef struct mt_client_options {
    /* LCM provider URL; NULL = LCM's default (LCM_DEFAULT_URL or udpm). Ignored with `lcm`. */
    const char *lcm_url;
    /* Use this lcm_t instead of creating one; the caller keeps ownership and
     * destroys it after the client. Unless external_handle is set, the
     * client's thread then calls lcm_handle on it, so every handler
     * subscribed on it (the caller's too) runs on the client's thread, and
     * nothing else may call lcm_handle on it. */
    lcm_t *lcm;
    /* With `lcm`: the caller's own loop calls lcm_handle, and the client's
     * thread only runs timeouts and retries. Replies (and async callbacks
     * with a reply) are then handled on the caller's loop thread, which must
     * never make a synchronous client call itself (it would wait forever). */
    int external_handle;
    /* Channel prefix: 1..MT_CLIENT_MAX_PREFIX of [A-Za-z0-9_-]; NULL = "MESHTOPO_".
     * Requests go to PREFIX "SUBMIT", "SUBMIT_CHUNK", "QUERY" and
     * "QUERY_PULL", one type each (meshtopo/channels.h). */
    const char *channel_prefix;
    /* Time to wait for a reply to one attempt; 0 = MT_CLIENT_DEFAULT_TIMEOUT_MS. */
    int timeout_ms;
    /* Attempts after the first; 0 = MT_CLIENT_DEFAULT_RETRIES, negative = none.
     * A BUSY answer uses one: the request is sent again after a pause that
     * doubles each time (MT_CLIENT_BUSY_PAUSE_MS, at most
     * MT_CLIENT_BUSY_PAUSE_MAX_MS, spread by +-25 %); BUSY after the last
     * attempt fails the call with the daemon's answer ("BUSY: ..."). */
    int retries;
    /* Name of the node, sent as mesh_t.source; NULL = "meshtopo-client". */
    const char *source;
    /* Chunked submission (large meshes): content bytes per chunk, 0 =
     * MT_CLIENT_DEFAULT_CHUNK_BYTES, 64..MT_CLIENT_MAX_CHUNK_BYTES. */
    int chunk_bytes;
    /* Chunks sent per round trip to the daemon, 0 =
     * MT_CLIENT_DEFAULT_WINDOW_CHUNKS, 1..4096. Larger windows go faster
     * until the daemon's socket receive buffer overflows and chunks are lost. */
    int window_chunks;
    /* Called with the progress of chunked submissions; NULL = none. */
    mt_client_progress_fn progress;
    void *progress_user;
    /* Large answers arrive as reply_part_t pieces (msgs/reply_part_t.lcm),
     * reassembled here and pulled a window (window_chunks parts) at a time:
     * the bytes all partly received answers may hold together; 0 =
     * MT_CLIENT_DEFAULT_MAX_REPLY_BYTES. An answer that does not fit fails its
     * call with MT_ERR_TOO_LARGE. */
    uint64_t max_reply_bytes;
} mt_client_options;

/* Counters of one client (mt_client_get_stats). */
typedef struct mt_client_stats {
    uint64_t requests;        /* calls sent (each with a fresh request id) */
    uint64_t attempts;        /* messages published, retries included */
    uint64_t replies;         /* replies matched to a waiting request */
    uint64_t timeouts;        /* requests that ran out of attempts */
    uint64_t unknown_replies; /* well-formed replies for no waiting request */
    uint64_t undecodable;     /* bytes on the reply channel that did not decode */
    uint64_t publish_errors;  /* lcm_publish failures (the attempt then times out) */
    uint64_t reply_parts;     /* reply_part_t pieces kept (duplicates not counted) */
    uint64_t bad_parts;       /* pieces refused: layout broken, another answer, bad hash */
    uint64_t reply_pulls;     /* reply_pull_t sent (next windows and lost parts) */
    uint64_t busy_retries;    /* requests sent again after a pause because the daemon said BUSY */
    uint64_t conflicting_answers; /* a second, different answer to a completed call: two
                                     daemons answer this prefix (meshtopod refuses to start
                                     beside another; this catches two started at once) */
} mt_client_stats;

/* Creates a client: its own lcm_t (or opts->lcm), a private reply channel
 * PREFIX "REPLY_" host_pid_random, and a thread handling LCM, timeouts and
 * retries. Returns MT_OK and *out, or MT_ERR_INVALID_ARG (bad options, with
 * the reason in diag), MT_ERR_IO (LCM or thread could not start),
 * MT_ERR_NOMEM; *out is then NULL. */
mt_status mt_client_create(const mt_client_options *opts, mt_client **out, mt_diag *diag);

/* Stops the thread, unsubscribes and frees the client. Asynchronous calls
 * still waiting get their callback with MT_ERR_IO ("client destroyed").
 * No call on this client may run or start meanwhile. NULL-safe. */
void mt_client_destroy(mt_client *client);

/* The client's private reply channel R, named in its requests (valid until
 * destroy); answers come on R "_ACK", R "_REPLY", R "_PART" and
 * R "_TRANSFER" (mt_msgs_reply_channel_name). */
const char *mt_client_reply_channel(const mt_client *client);

/* A snapshot of the client's counters. */
void mt_client_get_stats(mt_client *client, mt_client_stats *out_stats);

/* ---- Results ----------------------------------------------------------- */

/* Status of every call: MT_OK, a local error (MT_ERR_INVALID_ARG,
 * MT_ERR_TOO_LARGE, MT_ERR_NOMEM), the daemon's status code mapped by
 * mt_msgs_status_of_code (meshtopo/protocol.h), or MT_ERR_IO when no reply
 * came after every attempt: diag->message then starts with "timeout:". With
 * a reply whose status is not OK, diag->message is "CODE_NAME: the daemon's
 * error text" (mt_msgs_code_name). */

/* The answer to a submission. The decoded ack_t is kept as received, with its
 * topology_t report: it is the wire type lcm-spy shows and mirrors the core's
 * mt_report field for field, so callers read one schema, and no copy or
 * second conversion of the report is needed. */
typedef struct mt_client_ack {
    uint64_t sent_content_hash; /* computed by the client before sending */
    meshtopo_ack_t msg;         /* version, content_hash, reports[0] if num_reports */
} mt_client_ack;

/* The report of an ack, or NULL when it carries none. */
static inline const meshtopo_topology_t *mt_client_ack_report(const mt_client_ack *ack)
{
    return ack->msg.num_reports == 1 ? &ack->msg.reports[0] : (const meshtopo_topology_t *)0;
}

/* Releases what an ack owns and zeroes it. NULL-safe; fine on a zeroed ack. */
void mt_client_ack_free(mt_client_ack *ack);

/* Releases what a reply filled by mt_client_query / mt_client_list owns and
 * zeroes it. NULL-safe; fine on a zeroed reply. */
void mt_client_reply_free(meshtopo_reply_t *reply);

/* ---- Content hash ------------------------------------------------------ */

/* The content hash of msgs/mesh_t.lcm (XXH3-64 over the encoded
 * num_verts .. face_vertex_indices fields) of a face list, without encoding
 * it whole. Returns MT_ERR_INVALID_ARG for an inconsistent list and
 * MT_ERR_TOO_LARGE when a count does not fit mesh_t's int32 fields. */
mt_status mt_client_content_hash(const mt_face_list *list, uint64_t *out_hash, mt_diag *diag);

/* ---- Calls ------------------------------------------------------------- */

/* Mesh ids: 1..255 bytes of printable ASCII, no '/' and no ".." (the
 * daemon's rule); anything else gives MT_ERR_INVALID_ARG before sending. A synchronous call made
 * from the client's own thread (an async callback) gives MT_ERR_INVALID_ARG. */

/* Submits a face list as mesh `mesh_id` (a new version of it) and waits for
 * the ack. A mesh larger than one datagram (MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX)
 * goes as chunks: sent a window at a time, the daemon's missing ranges sent
 * again, a poll when no status comes; the call fails with MT_ERR_IO
 * ("timeout:") only after `retries` + 1 timeouts in a row without any word
 * from the daemon, or with the daemon's refusal (TOO_LARGE, BUSY). strict: the daemon refuses a
 * mesh with any defect (MT_ERR_DEFECT, with the report). out_ack is always initialised: filled
 * whenever an ack arrived (even with an error status), zeroed otherwise;
 * release it with mt_client_ack_free. */
mt_status mt_client_submit(mt_client *client, const char *mesh_id, const mt_face_list *list,
                           int strict, mt_client_ack *out_ack, mt_diag *diag);

/* Sends one query (kind: MESHTOPO_QUERY_T_VERTEX_RING, ..., any kind of the
 * query-kind table, meshtopo/query_kinds.h, which also says what ids it
 * takes and what its reply holds, e.g. mt_msgs_query_kind_named("ring");
 * version 0 = the latest) with a batch of element ids and waits for the
 * reply. ids may be
 * NULL when num_ids is 0; ids are sent as the int32 of the same bits.
 * A reply too large for one datagram arrives in parts that the client pulls,
 * recovers when lost and reassembles (any size up to max_reply_bytes).
 * out_reply is always initialised: filled whenever a reply arrived (even with
 * an error status), zeroed otherwise; release it with mt_client_reply_free. */
mt_status mt_client_query(mt_client *client, const char *mesh_id, int32_t version, int32_t kind,
                          const uint32_t *ids, size_t num_ids, meshtopo_reply_t *out_reply,
                          mt_diag *diag);

/* Lists the held mesh versions (LIST_MESHES): every mesh when mesh_id is NULL
 * or "", else the versions of that id. Like mt_client_query otherwise. */
mt_status mt_client_list(mt_client *client, const char *mesh_id, meshtopo_reply_t *out_reply,
                         mt_diag *diag);

/* Longest daemon instance mt_client_list_from accepts (status_t.instance). */
#define MT_CLIENT_MAX_INSTANCE 127

/* mt_client_list answered only by the daemon whose heartbeat carries
 * `instance` (status_t.instance; NULL or "": any daemon). In a cluster each
 * member lists the ids it owns: ask each member seen in the heartbeats and
 * merge (meshtopo list does). */
mt_status mt_client_list_from(mt_client *client, const char *instance, const char *mesh_id,
                              meshtopo_reply_t *out_reply, mt_diag *diag);

/* Called once per asynchronous query: with MT_OK or the daemon's mapped
 * status and the reply, or with MT_ERR_IO and reply NULL after the last
 * attempt timed out (or the client was destroyed). diag says why when status
 * is not MT_OK. reply and diag are valid only during the call; the callback
 * must not free the reply. It runs on the client's thread (see
 * mt_client_options.external_handle) and must not make synchronous calls on
 * the same client; asynchronous ones are fine. */
typedef void (*mt_client_reply_fn)(mt_status status, const meshtopo_reply_t *reply,
                                   const mt_diag *diag, void *user);

/* mt_client_query without waiting. Returns MT_OK once the first attempt is
 * sent (the callback then runs exactly once, later, on the client's thread);
 * any other status means nothing was sent and the callback will not run. */
mt_status mt_client_query_async(mt_client *client, const char *mesh_id, int32_t version,
                                int32_t kind, const uint32_t *ids, size_t num_ids,
                                mt_client_reply_fn callback, void *user, mt_diag *diag);

/* ---- The daemon's broadcasts ------------------------------------------- */

/* What mt_client_watch_start calls for each message on PREFIX "STATUS"
 * (heartbeats) and PREFIX "TOPOLOGY" (the report of every build), decoded
 * with mt_msgs_decode (undecodable ones are counted in stats.undecodable).
 * Either function may be NULL. They run on the client's thread, like the
 * asynchronous callbacks; the message is valid only during the call. */
typedef struct mt_client_watch_fns {
    void (*on_status)(const meshtopo_status_t *status, void *user);
    void (*on_topology)(const meshtopo_topology_t *report, void *user);
    void *user;
} mt_client_watch_fns;

typedef struct mt_client_watch mt_client_watch;

/* Starts calling fns for the daemon's broadcasts; *out_watch is set before
 * the first callback can run (a callback may stop its own watch). MT_OK,
 * MT_ERR_NOMEM or MT_ERR_IO (LCM refused the subscription). Stop every watch
 * before destroying the client. */
mt_status mt_client_watch_start(mt_client *client, const mt_client_watch_fns *fns,
                                mt_client_watch **out_watch, mt_diag *diag);

/* Stops a watch: once it returns, no callback of it runs (called from one of
 * its own callbacks, none runs after that callback). It waits for the
 * client's thread to be between two messages; with external_handle, call it
 * from the thread that runs lcm_handle. NULL-safe. */
void mt_client_watch_stop(mt_client_watch *watch);

/* Waits until a heartbeat of a daemon on the client's prefix arrives, at
 * most timeout_ms (0: the client's timeout times its attempts). Wait for the
 * daemon before the first request: a fresh LCM socket may miss its first
 * messages. On MT_OK, *out_status (when out_status is not NULL) is a copy of
 * the heartbeat, to release with meshtopo_status_t_destroy. MT_ERR_IO with
 * "timeout: no heartbeat ..." when none came; MT_ERR_INVALID_ARG from the
 * client's own thread. */
mt_status mt_client_wait_daemon(mt_client *client, int timeout_ms, meshtopo_status_t **out_status,
                                mt_diag *diag);

#ifdef __cplusplus
}
#endif

#endif
