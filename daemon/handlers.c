/* meshtopod's LCM handlers (handlers.h): a retried request (same reply
 * channel and request_id) is answered from the request cache, not run again
 * (mtd_reply_begin). Bytes that do not decode are still answered when their
 * request header (utime, request_id, reply_channel, common to mesh_t and
 * query_t) can be read, so a sender learns what was wrong. mesh_chunk_t, the
 * pieces of a large mesh on the same SUBMIT channel, goes to the transfers;
 * reply_pull_t on the QUERY channel to the replies. LCM thread only. */
#include "handlers.h"

#include <stdatomic.h>
#include <stdlib.h>

/* LCM drops messages beyond this many waiting per subscription (default 30). */
#define QUEUE_CAPACITY 10000

struct mtd_handlers {
    mtd_handler_deps deps;
    lcm_subscription_t *submit_sub, *query_sub;
    atomic_int_fast64_t submissions, queries;
};

static void on_submit(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mtd_handlers *h = user;
    size_t size = rbuf->data_size;
    const mt_msgs_type *type = mt_msgs_type_of(rbuf->data, size);
    if (type == &mt_msgs_type_mesh_chunk) {
        mtd_transfers_chunk(h->deps.transfers, rbuf->data, size); /* counted once complete */
        return;
    }
    atomic_fetch_add(&h->submissions, 1);
    if (type != &mt_msgs_type_mesh) {
        mtd_reply_undecodable(h->deps.replies, &mt_msgs_type_mesh, rbuf->data, size,
                              size < 8 ? "shorter than a fingerprint"
                                       : "wrong fingerprint (not a meshtopo.mesh_t nor "
                                         "mesh_chunk_t)");
        return;
    }
    meshtopo_mesh_t *msg = calloc(1, sizeof *msg);
    char why[MT_MSGS_ERROR_SIZE];
    if (!msg) return;
    if (mt_msgs_decode(&mt_msgs_type_mesh, rbuf->data, size, msg, why, sizeof why) != 0) {
        free(msg);
        mtd_reply_undecodable(h->deps.replies, &mt_msgs_type_mesh, rbuf->data, size, why);
        return;
    }
    if (mtd_reply_begin(h->deps.replies, msg->reply_channel, msg->request_id)) {
        mtd_submit_handle(h->deps.submitter, msg, rbuf->data, size); /* takes msg */
        return;
    }
    meshtopo_mesh_t_decode_cleanup(msg);
    free(msg);
}

static void on_query(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mtd_handlers *h = user;
    size_t size = rbuf->data_size;
    const mt_msgs_type *type = mt_msgs_type_of(rbuf->data, size);
    if (type == &mt_msgs_type_reply_pull) {
        mtd_reply_serve_pull(h->deps.replies, rbuf->data, size); /* not a query */
        return;
    }
    atomic_fetch_add(&h->queries, 1);
    if (type != &mt_msgs_type_query) {
        mtd_reply_undecodable(
            h->deps.replies, &mt_msgs_type_query, rbuf->data, size,
            size < 8 ? "shorter than a fingerprint" : "wrong fingerprint (not a meshtopo.query_t)");
        return;
    }
    meshtopo_query_t msg;
    char why[MT_MSGS_ERROR_SIZE];
    if (mt_msgs_decode(&mt_msgs_type_query, rbuf->data, size, &msg, why, sizeof why) != 0) {
        mtd_reply_undecodable(h->deps.replies, &mt_msgs_type_query, rbuf->data, size, why);
        return;
    }
    if (mtd_reply_begin(h->deps.replies, msg.reply_channel, msg.request_id))
        mtd_query_handle(h->deps.queries, &msg);
    meshtopo_query_t_decode_cleanup(&msg);
}

mt_status mtd_handlers_subscribe(const mtd_handler_deps *deps, mtd_handlers **out_handlers)
{
    *out_handlers = NULL;
    mtd_handlers *h = calloc(1, sizeof *h);
    if (!h) return MT_ERR_NOMEM;
    h->deps = *deps;
    h->submit_sub = lcm_subscribe(deps->lcm, deps->submit_channel, on_submit, h);
    h->query_sub = lcm_subscribe(deps->lcm, deps->query_channel, on_query, h);
    if (!h->submit_sub || !h->query_sub) {
        mtd_handlers_destroy(h);
        return MT_ERR_NOMEM;
    }
    lcm_subscription_set_queue_capacity(h->submit_sub, QUEUE_CAPACITY);
    lcm_subscription_set_queue_capacity(h->query_sub, QUEUE_CAPACITY);
    *out_handlers = h;
    return MT_OK;
}

void mtd_handlers_unsubscribe(mtd_handlers *h)
{
    if (h->submit_sub) lcm_unsubscribe(h->deps.lcm, h->submit_sub);
    if (h->query_sub) lcm_unsubscribe(h->deps.lcm, h->query_sub);
    h->submit_sub = h->query_sub = NULL;
}

void mtd_handlers_destroy(mtd_handlers *h)
{
    if (!h) return;
    mtd_handlers_unsubscribe(h);
    free(h);
}

void mtd_handlers_get_counts(mtd_handlers *h, mtd_handler_counts *out_counts)
{
    out_counts->submissions = atomic_load(&h->submissions);
    out_counts->queries = atomic_load(&h->queries);
}
