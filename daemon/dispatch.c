/* meshtopod's dispatch: the raw LCM handlers of PREFIX+"SUBMIT" and
 * PREFIX+"QUERY". Received bytes are never given to lcm-gen's decoders
 * directly: mt_msgs_decode checks them first. A retried request (same reply
 * channel and request_id) is answered from the request cache, not run again.
 * Bytes that do not decode are still answered when their request header
 * (utime, request_id, reply_channel, common to mesh_t and query_t) can be
 * read, so a sender learns what was wrong. mesh_chunk_t, the pieces of a
 * large mesh on the same SUBMIT channel, goes to transfer.c; reply_pull_t on
 * the QUERY channel and answers too large for one datagram go to
 * reply_parts.c. Also the daemon's create/stop. */
#include "daemon.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "archiver.h"
#include "log.h"

/* LCM drops messages beyond this many waiting per subscription (default 30). */
#define QUEUE_CAPACITY 10000
/* Builds waiting for a worker before submissions are answered BUSY. */
#define BUILD_QUEUE_CAPACITY 256

int64_t mtd_now_utime(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static void note_error(mtd_daemon *d, const char *error)
{
    atomic_fetch_add(&d->errors, 1);
    pthread_mutex_lock(&d->error_lock);
    snprintf(d->last_error, sizeof d->last_error, "%s", error ? error : "");
    d->last_error_utime = mtd_now_utime();
    pthread_mutex_unlock(&d->error_lock);
}

void mtd_send_reply(mtd_daemon *d, const char *channel, int64_t request_id, bool remember,
                    const mt_msgs_type *type, const void *msg, int32_t status, const char *error)
{
    if (status != MESHTOPO_STATUS_CODE_T_OK) note_error(d, error);
    int size = type->encoded_size(msg);
    void *buf = size > 0 ? malloc((size_t)size) : NULL;
    if (!buf || type->encode(buf, 0, size, msg) != size) {
        free(buf);
        mtd_log(MTD_LOG_ERROR, "encode", "type=%s request_id=%" PRId64 " bytes=%d", type->name,
                request_id, size);
        if (remember) mtd_reqcache_abandon(d->cache, channel, request_id);
        return;
    }
    if (remember) {
        mt_status s = mtd_reqcache_finish(d->cache, channel, request_id, buf, (size_t)size);
        if (s != MT_OK)
            mtd_log(MTD_LOG_WARN, "reqcache", "request_id=%" PRId64 " not remembered: %s",
                    request_id, mt_strerror(s));
    }
    mtd_publish_answer(d, channel, request_id, buf, (size_t)size); /* in parts when large */
    free(buf);
}

void mtd_send_ack_error(mtd_daemon *d, const char *channel, int64_t request_id, const char *mesh_id,
                        bool remember, int32_t status, const char *error)
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
    mtd_send_reply(d, channel, request_id, remember, &mt_msgs_type_ack, &ack, status, error);
}

void mtd_send_reply_error(mtd_daemon *d, const char *channel, int64_t request_id,
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
    mtd_send_reply(d, channel, request_id, remember, &mt_msgs_type_reply, &reply, status, error);
}

/* A reply channel the daemon can publish on: 1..63 printable bytes. */
static bool reply_channel_ok(const char *channel)
{
    size_t n = strlen(channel);
    if (n == 0 || n > MTD_CHANNEL_MAX) return false;
    for (size_t i = 0; i < n; i++)
        if (channel[i] <= ' ' || channel[i] > '~') return false;
    return true;
}

static int64_t read_be64(const unsigned char *p)
{
    uint64_t v = 0;
    for (int i = 0; i < 8; i++) v = v << 8 | p[i];
    return (int64_t)v;
}

bool mtd_peek_request_header(const void *data, size_t size, int64_t *out_request_id, char *channel)
{
    const unsigned char *p = data;
    if (size < 8 + 8 + 8 + 4) return false;
    *out_request_id = read_be64(p + 16);
    uint32_t raw = (uint32_t)p[24] << 24 | (uint32_t)p[25] << 16 | (uint32_t)p[26] << 8 | p[27];
    int64_t len = (int32_t)raw;
    if (len < 2 || len > MTD_CHANNEL_MAX + 1 || (size_t)len > size - 28) return false;
    if (p[28 + len - 1] != 0) return false;
    memcpy(channel, p + 28, (size_t)len);
    return reply_channel_ok(channel);
}

/* Answers bytes that are not a well-formed message of the expected type. */
static void answer_undecodable(mtd_daemon *d, bool submit, const void *data, size_t size,
                               const char *why)
{
    int64_t request_id = 0;
    char channel[MTD_CHANNEL_MAX + 1];
    char error[MTD_ERROR_MAX];
    snprintf(error, sizeof error, "undecodable %s: %s", submit ? "mesh_t" : "query_t", why);
    if (!mtd_peek_request_header(data, size, &request_id, channel)) {
        note_error(d, error);
        mtd_log(MTD_LOG_WARN, "undecodable", "bytes=%zu error=%s (no reply channel to answer on)",
                size, error);
        return;
    }
    if (submit)
        mtd_send_ack_error(d, channel, request_id, "", false, MESHTOPO_STATUS_CODE_T_UNDECODABLE,
                           error);
    else
        mtd_send_reply_error(d, channel, request_id, "", 0, false,
                             MESHTOPO_STATUS_CODE_T_UNDECODABLE, error);
}

bool mtd_begin_request(mtd_daemon *d, const char *channel, int64_t request_id)
{
    if (!reply_channel_ok(channel)) {
        char error[MTD_ERROR_MAX];
        snprintf(error, sizeof error, "reply_channel '%.80s': must be 1 to %d printable bytes",
                 channel, MTD_CHANNEL_MAX);
        note_error(d, error);
        mtd_log(MTD_LOG_WARN, "bad_request", "request_id=%" PRId64 " error=%s (not answered)",
                request_id, error);
        return false;
    }
    mtd_request_state state = MTD_REQUEST_NEW;
    mtd_reply *stored = NULL;
    if (mtd_reqcache_begin(d->cache, channel, request_id, &state, &stored) != MT_OK)
        return true; /* out of memory for the mark: run it unremembered */
    if (state == MTD_REQUEST_NEW) return true;
    atomic_fetch_add(&d->duplicates, 1);
    if (state == MTD_REQUEST_DONE) {
        mtd_log(MTD_LOG_DEBUG, "duplicate", "request_id=%" PRId64 " channel=%s answered again",
                request_id, channel);
        mtd_publish_answer(d, channel, request_id, mtd_reply_data(stored), mtd_reply_size(stored));
        mtd_reply_release(stored);
    }
    return false;
}

static void on_submit(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mtd_daemon *d = user;
    size_t size = rbuf->data_size;
    const mt_msgs_type *type = mt_msgs_type_of(rbuf->data, size);
    if (type == &mt_msgs_type_mesh_chunk) {
        mtd_chunk_handle(d, rbuf->data, size); /* counts the mesh once it is complete */
        return;
    }
    atomic_fetch_add(&d->submissions, 1);
    if (type != &mt_msgs_type_mesh) {
        answer_undecodable(d, true, rbuf->data, size,
                           size < 8 ? "shorter than a fingerprint"
                                    : "wrong fingerprint (not a meshtopo.mesh_t nor mesh_chunk_t)");
        return;
    }
    meshtopo_mesh_t *msg = calloc(1, sizeof *msg);
    char why[MT_MSGS_ERROR_SIZE];
    if (!msg) return;
    if (mt_msgs_decode(&mt_msgs_type_mesh, rbuf->data, size, msg, why, sizeof why) != 0) {
        free(msg);
        answer_undecodable(d, true, rbuf->data, size, why);
        return;
    }
    if (atomic_load(&d->stopping)) {
        mtd_send_ack_error(d, msg->reply_channel, msg->request_id, msg->mesh_id, false,
                           MESHTOPO_STATUS_CODE_T_BUSY, "the daemon is shutting down");
    } else if (mtd_begin_request(d, msg->reply_channel, msg->request_id)) {
        mtd_submit_handle(d, msg, rbuf->data, size); /* takes msg */
        return;
    }
    meshtopo_mesh_t_decode_cleanup(msg);
    free(msg);
}

static void on_query(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mtd_daemon *d = user;
    size_t size = rbuf->data_size;
    if (mt_msgs_type_of(rbuf->data, size) == &mt_msgs_type_reply_pull) {
        mtd_reply_pull_handle(d, rbuf->data, size); /* parts of a large answer, not a query */
        return;
    }
    atomic_fetch_add(&d->queries, 1);
    if (mt_msgs_type_of(rbuf->data, size) != &mt_msgs_type_query) {
        answer_undecodable(
            d, false, rbuf->data, size,
            size < 8 ? "shorter than a fingerprint" : "wrong fingerprint (not a meshtopo.query_t)");
        return;
    }
    meshtopo_query_t msg;
    char why[MT_MSGS_ERROR_SIZE];
    if (mt_msgs_decode(&mt_msgs_type_query, rbuf->data, size, &msg, why, sizeof why) != 0) {
        answer_undecodable(d, false, rbuf->data, size, why);
        return;
    }
    if (mtd_begin_request(d, msg.reply_channel, msg.request_id)) mtd_query_handle(d, &msg);
    meshtopo_query_t_decode_cleanup(&msg);
}

static mt_status channel_name(char *out, const char *prefix, const char *suffix, mt_diag *diag)
{
    int n = snprintf(out, MTD_CHANNEL_MAX + 1, "%s%s", prefix, suffix);
    if (n < 0 || n > MTD_CHANNEL_MAX) {
        if (diag) {
            mt_diag_clear(diag);
            diag->status = MT_ERR_INVALID_ARG;
            snprintf(diag->message, sizeof diag->message,
                     "channel prefix '%s': %s%s is longer than LCM's %d bytes", prefix, prefix,
                     suffix, MTD_CHANNEL_MAX);
        }
        return MT_ERR_INVALID_ARG;
    }
    return MT_OK;
}

static mt_status fail_nomem(mt_diag *diag, const char *what)
{
    if (diag) {
        mt_diag_clear(diag);
        diag->status = MT_ERR_NOMEM;
        snprintf(diag->message, sizeof diag->message, "cannot create the %s", what);
    }
    return MT_ERR_NOMEM;
}

mt_status mtd_daemon_create(const mtd_config *config, lcm_t *lcm, mtd_daemon **out_daemon,
                            mt_diag *diag)
{
    *out_daemon = NULL;
    mtd_daemon *d = calloc(1, sizeof *d);
    if (!d) return fail_nomem(diag, "daemon");
    d->config = *config;
    d->lcm = lcm;
    d->start_utime = mtd_now_utime();
    pthread_mutex_init(&d->error_lock, NULL);
    pthread_mutex_init(&d->transfer_lock, NULL);
    pthread_mutex_init(&d->spare_lock, NULL);
    char host[64] = "";
    gethostname(host, sizeof host - 1);
    snprintf(d->instance, sizeof d->instance, "%s:%d:%" PRId64, host, (int)getpid(),
             d->start_utime);
    /* lcm-gen's fingerprints are computed lazily without a lock: do it now,
     * before any worker thread encodes. */
    mt_msgs_type_of(NULL, 0);

    const char *prefix = config->channel_prefix;
    mt_status s;
    if ((s = channel_name(d->submit_channel, prefix, "SUBMIT", diag)) != MT_OK ||
        (s = channel_name(d->query_channel, prefix, "QUERY", diag)) != MT_OK ||
        (s = channel_name(d->topology_channel, prefix, "TOPOLOGY", diag)) != MT_OK ||
        (s = channel_name(d->status_channel, prefix, "STATUS", diag)) != MT_OK) {
        mtd_daemon_destroy(d);
        return s;
    }
    mtd_store_options store_options = {
        .max_versions_per_id = config->max_versions,
        .max_bytes = (size_t)config->max_store_bytes,
        .dispose_mesh = mtd_mesh_recycle,
        .dispose_mesh_ctx = d,
    };
    if (mtd_store_create(&store_options, &d->store) != MT_OK) {
        mtd_daemon_destroy(d);
        return fail_nomem(diag, "mesh store");
    }
    if (mtd_reqcache_create(NULL, &d->cache) != MT_OK) {
        mtd_daemon_destroy(d);
        return fail_nomem(diag, "request cache");
    }
    if (mtd_pool_create(config->workers, BUILD_QUEUE_CAPACITY, &d->pool) != MT_OK) {
        mtd_daemon_destroy(d);
        return fail_nomem(diag, "worker pool");
    }
    if ((s = mtd_archiver_start(d, diag)) != MT_OK) {
        mtd_daemon_destroy(d);
        return s;
    }
    d->submit_sub = lcm_subscribe(lcm, d->submit_channel, on_submit, d);
    d->query_sub = lcm_subscribe(lcm, d->query_channel, on_query, d);
    if (!d->submit_sub || !d->query_sub) {
        mtd_daemon_destroy(d);
        return fail_nomem(diag, "LCM subscriptions");
    }
    lcm_subscription_set_queue_capacity(d->submit_sub, QUEUE_CAPACITY);
    lcm_subscription_set_queue_capacity(d->query_sub, QUEUE_CAPACITY);
    *out_daemon = d;
    return MT_OK;
}

void mtd_daemon_stop(mtd_daemon *d)
{
    if (!d || atomic_exchange(&d->stopping, true)) return;
    if (d->submit_sub) lcm_unsubscribe(d->lcm, d->submit_sub);
    if (d->query_sub) lcm_unsubscribe(d->lcm, d->query_sub);
    d->submit_sub = d->query_sub = NULL;
    if (d->pool) mtd_pool_shutdown(d->pool, MTD_SHUTDOWN_CANCEL);
    mtd_archiver_stop(d);
}

void mtd_daemon_destroy(mtd_daemon *d)
{
    if (!d) return;
    mtd_daemon_stop(d);
    mtd_pool_destroy(d->pool);
    mtd_archiver_free(d);
    mtd_transfers_free(d);
    mtd_store_destroy(d->store); /* its meshes go to the workspace: destroyed next */
    mt_build_workspace_destroy(d->spare_workspace);
    pthread_mutex_destroy(&d->transfer_lock);
    pthread_mutex_destroy(&d->spare_lock);
    mtd_reqcache_destroy(d->cache);
    pthread_mutex_destroy(&d->error_lock);
    free(d);
}
