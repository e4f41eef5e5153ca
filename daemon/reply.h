/* meshtopod's replies: the one way out to a requester. Encodes and publishes
 * replies, acks, transfer statuses and error answers on the channel of their
 * type under the reply channel a request names (meshtopo/channels.h: R_ACK,
 * R_REPLY, R_PART, R_TRANSFER; large replies in parts), remembers them in
 * the request cache so a retry with the same request id gets the same bytes
 * instead of running again, and notes every error answer in the error log.
 * Owns the request cache, keyed by (answer channel, request id): the key
 * includes the kind of request, so a query_t reusing the id of an earlier
 * mesh_t is a new request. Any thread: the LCM thread answers queries and
 * refusals, build workers answer submissions. */
#ifndef MESHTOPOD_REPLY_H
#define MESHTOPOD_REPLY_H

#include <lcm/lcm.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "error_log.h"
#include "meshtopo/channels.h"
#include "meshtopo/msgs.h"
#include "request_cache.h"

typedef struct mtd_replies mtd_replies;

/* Publishes on lcm (not owned) and notes errors in `errors` (not owned);
 * refuses reply channels that name a daemon channel of `prefix`
 * (mt_msgs_reply_channel_allowed). MT_OK or MT_ERR_NOMEM. */
mt_status mtd_replies_create(lcm_t *lcm, const char *prefix, mtd_error_log *errors,
                             mtd_replies **out_replies);

/* Frees the request cache (replies still held stay valid). NULL-safe. */
void mtd_replies_destroy(mtd_replies *replies);

/* Reads the header every request starts with (fingerprint, utime,
 * request_id, reply_channel as int32 length with its NUL, then the bytes),
 * for answering bytes that do not decode. Returns true with the reply
 * channel copied into channel[MT_MSGS_CHANNEL_NAME_MAX + 1] when it is one
 * to answer on (mt_msgs_reply_channel_ok). */
bool mtd_reply_peek_header(const void *data, size_t size, int64_t *out_request_id, char *channel);

/* Whether a request's reply channel may be answered on
 * (mt_msgs_reply_channel_allowed for the daemon's prefix); when not, the
 * request is noted in the error log, logged and must not be answered. */
bool mtd_reply_channel_check(mtd_replies *replies, const char *reply_channel, int64_t request_id);

/* Starts a request whose answer is of type `answer` (ack_t for submissions,
 * reply_t for queries): checks its reply channel (a bad one, or one naming a
 * daemon channel, is noted, logged and not answered) and the request cache. Returns true when the
 * request is new (now marked pending) and must be run; a finished one has had its answer published
 * again, a running one is left to finish (both counted as duplicates). */
bool mtd_reply_begin(mtd_replies *replies, const char *reply_channel, int64_t request_id,
                     const mt_msgs_type *answer);

/* What the request cache knows of a request, without marking it. A finished
 * one is published again when `resend` (and counted as a duplicate). */
mtd_request_state mtd_reply_state(mtd_replies *replies, const char *reply_channel,
                                  int64_t request_id, const mt_msgs_type *answer, bool resend);

/* Removes the pending mark of a request that will not be answered with a
 * remembered answer, so a retry runs it again. */
void mtd_reply_abandon(mtd_replies *replies, const char *reply_channel, int64_t request_id,
                       const mt_msgs_type *answer);

/* Encodes msg of `type` (an answer type) and publishes it on reply_channel +
 * the type's suffix; when `remember`, stores it in the request cache first.
 * A status other than OK is noted in the error log with `error`. */
void mtd_reply_send(mtd_replies *replies, const char *reply_channel, int64_t request_id,
                    bool remember, const mt_msgs_type *type, const void *msg, int32_t status,
                    const char *error);

/* An ack_t carrying only a status and an error. */
void mtd_reply_ack_error(mtd_replies *replies, const char *reply_channel, int64_t request_id,
                         const char *mesh_id, bool remember, int32_t status, const char *error);

/* A reply_t carrying only a status and an error. */
void mtd_reply_query_error(mtd_replies *replies, const char *reply_channel, int64_t request_id,
                           const char *mesh_id, int32_t kind, bool remember, int32_t status,
                           const char *error);

/* Answers bytes received on a request channel that are not a well-formed
 * message of `type` (mesh_t or query_t), with UNDECODABLE and `why` in an
 * ack_t or reply_t, when their request header names a reply channel; notes
 * the error either way. */
void mtd_reply_undecodable(mtd_replies *replies, const mt_msgs_type *type, const void *data,
                           size_t size, const char *why);

/* Serves one received reply_pull_t (parts of a large answer) from the
 * request cache. */
void mtd_reply_serve_pull(mtd_replies *replies, const void *data, size_t size);

/* How long an answer stays remembered for retries: longer than any client
 * keeps retrying (the client library's attempts and BUSY pauses end within
 * a few seconds). */
#define MTD_REPLY_KEEP_US (20 * 1000000LL)

/* Forgets answers older than MTD_REPLY_KEEP_US (the periodic tick). */
void mtd_replies_expire(mtd_replies *replies);

/* Requests answered again from the cache, or found still running. */
int64_t mtd_replies_duplicates(mtd_replies *replies);

#endif
