/* meshtopod's replies (reply.h): encode, remember, publish. Every answer the
 * daemon sends to a requester goes through mtd_reply_send, so every error
 * answer is noted once, in one place, and every remembered answer is what a
 * retry gets. Any thread (LCM's publish is thread safe; the request cache
 * and the error log have their own locks). */
#include "reply.h"

#include <inttypes.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "log.h"
#include "reply_parts.h"

struct mtd_replies {
    lcm_t *lcm;            /* not owned */
    char prefix[64];       /* the daemon's channel prefix */
    mtd_error_log *errors; /* not owned */
    mtd_reqcache *cache;   /* owned */
    atomic_int_fast64_t duplicates;
};

mt_status mtd_replies_create(lcm_t *lcm, const char *prefix, mtd_error_log *errors,
                             mtd_replies **out_replies)
{
    *out_replies = NULL;
    mtd_replies *r = calloc(1, sizeof *r);
    if (!r) return MT_ERR_NOMEM;
    r->lcm = lcm;
    snprintf(r->prefix, sizeof r->prefix, "%s", prefix);
    r->errors = errors;
    if (mtd_reqcache_create(NULL, &r->cache) != MT_OK) {
        free(r);
        return MT_ERR_NOMEM;
    }
    *out_replies = r;
    return MT_OK;
}

void mtd_replies_destroy(mtd_replies *r)
{
    if (!r) return;
    mtd_reqcache_destroy(r->cache);
    free(r);
}

static int64_t read_be64(const unsigned char *p)
{
    uint64_t v = 0;
    for (int i = 0; i < 8; i++) v = v << 8 | p[i];
    return (int64_t)v;
}

bool mtd_reply_peek_header(const void *data, size_t size, int64_t *out_request_id, char *channel)
{
    const unsigned char *p = data;
    if (size < 8 + 8 + 8 + 4) return false;
    *out_request_id = read_be64(p + 16);
    uint32_t raw = (uint32_t)p[24] << 24 | (uint32_t)p[25] << 16 | (uint32_t)p[26] << 8 | p[27];
    int64_t len = (int32_t)raw;
    if (len < 2 || len > MT_MSGS_CHANNEL_NAME_MAX + 1 || (size_t)len > size - 28) return false;
    if (p[28 + len - 1] != 0) return false;
    memcpy(channel, p + 28, (size_t)len);
    return mt_msgs_reply_channel_ok(channel);
}

/* The request cache's key of a request: the channel of its answer type. */
static bool answer_channel(const char *reply_channel, const mt_msgs_type *answer, char *out)
{
    return mt_msgs_reply_channel_name(reply_channel, answer, out) == MT_OK;
}

bool mtd_reply_channel_check(mtd_replies *r, const char *reply_channel, int64_t request_id)
{
    if (mt_msgs_reply_channel_allowed(r->prefix, reply_channel)) return true;
    char error[MTD_ERROR_MAX];
    if (mt_msgs_reply_channel_ok(reply_channel))
        snprintf(error, sizeof error,
                 "reply_channel '%s': names a daemon channel of prefix '%s' (answers there "
                 "would reach daemons, not the requester)",
                 reply_channel, r->prefix);
    else
        snprintf(error, sizeof error, "reply_channel '%.80s': must be 1 to %d printable bytes",
                 reply_channel, MESHTOPO_MESH_T_REPLY_CHANNEL_MAX);
    mtd_error_log_note(r->errors, error);
    mtd_log(MTD_LOG_WARN, "bad_request", "request_id=%" PRId64 " error=%s (not answered)",
            request_id, error);
    return false;
}

void mtd_reply_send(mtd_replies *r, const char *reply_channel, int64_t request_id, bool remember,
                    const mt_msgs_type *type, const void *msg, int32_t status, const char *error)
{
    if (status != MESHTOPO_STATUS_CODE_T_OK) mtd_error_log_note(r->errors, error);
    char key[MT_MSGS_CHANNEL_NAME_MAX + 1];
    if (!answer_channel(reply_channel, type, key)) return; /* checked when it arrived */
    int size = type->encoded_size(msg);
    void *buf = size > 0 ? malloc((size_t)size) : NULL;
    if (!buf || type->encode(buf, 0, size, msg) != size) {
        free(buf);
        mtd_log(MTD_LOG_ERROR, "encode", "type=%s request_id=%" PRId64 " bytes=%d", type->name,
                request_id, size);
        if (remember) mtd_reqcache_abandon(r->cache, key, request_id);
        return;
    }
    if (remember) {
        mt_status s = mtd_reqcache_finish(r->cache, key, request_id, buf, (size_t)size);
        if (s != MT_OK)
            mtd_log(MTD_LOG_WARN, "reqcache", "request_id=%" PRId64 " not remembered: %s",
                    request_id, mt_strerror(s));
    }
    mtd_parts_publish(r->lcm, reply_channel, request_id, buf,
                      (size_t)size); /* in parts when large */
    free(buf);
}

void mtd_reply_ack_error(mtd_replies *r, const char *reply_channel, int64_t request_id,
                         const char *mesh_id, bool remember, int32_t status, const char *error)
{
    meshtopo_ack_t ack;
    memset(&ack, 0, sizeof ack);
    ack.utime = mtd_now_utime();
    ack.request_id = request_id;
    ack.status = status;
    ack.error = (char *)error;
    ack.mesh_id = (char *)(mesh_id ? mesh_id : "");
    mtd_log(MTD_LOG_INFO, "submit_error", "request_id=%" PRId64 " status=%d error=%s", request_id,
            (int)status, error);
    mtd_reply_send(r, reply_channel, request_id, remember, &mt_msgs_type_ack, &ack, status, error);
}

void mtd_reply_query_error(mtd_replies *r, const char *reply_channel, int64_t request_id,
                           const char *mesh_id, int32_t kind, bool remember, int32_t status,
                           const char *error)
{
    int32_t zero[1] = {0};
    meshtopo_reply_t reply;
    memset(&reply, 0, sizeof reply);
    reply.utime = mtd_now_utime();
    reply.request_id = request_id;
    reply.status = status;
    reply.error = (char *)error;
    reply.mesh_id = (char *)(mesh_id ? mesh_id : "");
    reply.kind = kind;
    reply.num_item_offsets = 1;
    reply.item_offsets = zero;
    reply.num_value_offsets = 1;
    reply.value_offsets = zero;
    reply.value2_offsets = zero;
    mtd_log(MTD_LOG_INFO, "query_error", "request_id=%" PRId64 " status=%d error=%s", request_id,
            (int)status, error);
    mtd_reply_send(r, reply_channel, request_id, remember, &mt_msgs_type_reply, &reply, status,
                   error);
}

void mtd_reply_undecodable(mtd_replies *r, const mt_msgs_type *type, const void *data, size_t size,
                           const char *why)
{
    int64_t request_id = 0;
    char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
    char error[MTD_ERROR_MAX];
    snprintf(error, sizeof error, "undecodable %s: %s", type->name, why);
    if (!mtd_reply_peek_header(data, size, &request_id, channel)) {
        mtd_error_log_note(r->errors, error);
        mtd_log(MTD_LOG_WARN, "undecodable", "bytes=%zu error=%s (no reply channel to answer on)",
                size, error);
        return;
    }
    if (!mtd_reply_channel_check(r, channel, request_id)) return;
    if (type == &mt_msgs_type_mesh)
        mtd_reply_ack_error(r, channel, request_id, "", false, MESHTOPO_STATUS_CODE_T_UNDECODABLE,
                            error);
    else
        mtd_reply_query_error(r, channel, request_id, "", 0, false,
                              MESHTOPO_STATUS_CODE_T_UNDECODABLE, error);
}

bool mtd_reply_begin(mtd_replies *r, const char *reply_channel, int64_t request_id,
                     const mt_msgs_type *answer)
{
    char key[MT_MSGS_CHANNEL_NAME_MAX + 1];
    if (!mtd_reply_channel_check(r, reply_channel, request_id) ||
        !answer_channel(reply_channel, answer, key))
        return false;
    mtd_request_state state = MTD_REQUEST_NEW;
    mtd_reply *stored = NULL;
    if (mtd_reqcache_begin(r->cache, key, request_id, &state, &stored) != MT_OK)
        return true; /* out of memory for the mark: run it unremembered */
    if (state == MTD_REQUEST_NEW) return true;
    atomic_fetch_add(&r->duplicates, 1);
    if (state == MTD_REQUEST_DONE) {
        mtd_log(MTD_LOG_DEBUG, "duplicate", "request_id=%" PRId64 " channel=%s answered again",
                request_id, key);
        mtd_parts_publish(r->lcm, reply_channel, request_id, mtd_reply_data(stored),
                          mtd_reply_size(stored));
        mtd_reply_release(stored);
    }
    return false;
}

mtd_request_state mtd_reply_state(mtd_replies *r, const char *reply_channel, int64_t request_id,
                                  const mt_msgs_type *answer, bool resend)
{
    char key[MT_MSGS_CHANNEL_NAME_MAX + 1];
    mtd_request_state state = MTD_REQUEST_NEW;
    mtd_reply *stored = NULL;
    if (!answer_channel(reply_channel, answer, key) ||
        mtd_reqcache_peek(r->cache, key, request_id, &state, &stored) != MT_OK)
        return MTD_REQUEST_NEW;
    if (state == MTD_REQUEST_DONE && resend) {
        atomic_fetch_add(&r->duplicates, 1);
        mtd_parts_publish(r->lcm, reply_channel, request_id, mtd_reply_data(stored),
                          mtd_reply_size(stored));
    }
    mtd_reply_release(stored);
    return state;
}

void mtd_reply_abandon(mtd_replies *r, const char *reply_channel, int64_t request_id,
                       const mt_msgs_type *answer)
{
    char key[MT_MSGS_CHANNEL_NAME_MAX + 1];
    if (answer_channel(reply_channel, answer, key)) mtd_reqcache_abandon(r->cache, key, request_id);
}

void mtd_reply_serve_pull(mtd_replies *r, const void *data, size_t size)
{
    mtd_parts_serve_pull(r->lcm, r->cache, data, size);
}

void mtd_replies_expire(mtd_replies *r)
{
    mtd_reqcache_expire(r->cache, mtd_monotonic_us(), MTD_REPLY_KEEP_US);
}

int64_t mtd_replies_duplicates(mtd_replies *r)
{
    return atomic_load(&r->duplicates);
}
