/* meshtopod's LCM handlers (handlers.h): each request channel carries one
 * type; bytes of another type or that do not decode are still answered when
 * their request header (utime, request_id, reply_channel, common to every
 * request) can be read, so a sender learns what was wrong. A retried request
 * (same reply channel and request_id) is answered from the request cache,
 * not run again (mtd_reply_begin). LCM thread only. */
#include "handlers.h"

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* LCM drops messages beyond this many waiting per subscription (default 30). */
#define QUEUE_CAPACITY 10000

/* The request channels, in the order of mtd_handlers.subs, then the
 * cluster's TOPOLOGY. */
enum { SUB_SUBMIT, SUB_CHUNK, SUB_QUERY, SUB_PULL, SUB_TOPOLOGY, SUB_COUNT };

struct mtd_handlers {
    mtd_handler_deps deps;
    lcm_subscription_t *subs[SUB_COUNT];
    atomic_int_fast64_t submissions, queries;
};

/* Why bytes on a channel of `type` are not a message of it, before decoding. */
static const char *wrong_type(const mt_msgs_type *type, const lcm_recv_buf_t *rbuf, char *why,
                              size_t size)
{
    if (rbuf->data_size < 8) return "shorter than a fingerprint";
    if (mt_msgs_type_of(rbuf->data, rbuf->data_size) == type) return NULL;
    snprintf(why, size, "wrong fingerprint (not a meshtopo.%s)", type->name);
    return why;
}

static void on_submit(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mtd_handlers *h = user;
    size_t size = rbuf->data_size;
    atomic_fetch_add(&h->submissions, 1);
    char why[MT_MSGS_ERROR_SIZE];
    const char *wrong = wrong_type(&mt_msgs_type_mesh, rbuf, why, sizeof why);
    if (wrong) {
        mtd_reply_undecodable(h->deps.replies, &mt_msgs_type_mesh, rbuf->data, size, wrong);
        return;
    }
    meshtopo_mesh_t *msg = calloc(1, sizeof *msg);
    if (!msg) return;
    if (mt_msgs_decode(&mt_msgs_type_mesh, rbuf->data, size, msg, why, sizeof why) != 0) {
        free(msg);
        mtd_reply_undecodable(h->deps.replies, &mt_msgs_type_mesh, rbuf->data, size, why);
        return;
    }
    if (!mtd_cluster_owns(h->deps.cluster, msg->mesh_id)) {
        meshtopo_mesh_t_decode_cleanup(msg);
        free(msg);
        return;
    }
    if (mtd_reply_begin(h->deps.replies, msg->reply_channel, msg->request_id, &mt_msgs_type_ack)) {
        mtd_submit_handle(h->deps.submitter, msg, rbuf->data, size); /* takes msg */
        return;
    }
    meshtopo_mesh_t_decode_cleanup(msg);
    free(msg);
}

static void on_chunk(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mtd_handlers *h = user;
    mtd_transfers_chunk(h->deps.transfers, rbuf->data, rbuf->data_size); /* counted once complete */
}

static void on_query(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mtd_handlers *h = user;
    size_t size = rbuf->data_size;
    atomic_fetch_add(&h->queries, 1);
    char why[MT_MSGS_ERROR_SIZE];
    const char *wrong = wrong_type(&mt_msgs_type_query, rbuf, why, sizeof why);
    if (wrong) {
        mtd_reply_undecodable(h->deps.replies, &mt_msgs_type_query, rbuf->data, size, wrong);
        return;
    }
    meshtopo_query_t msg;
    if (mt_msgs_decode(&mt_msgs_type_query, rbuf->data, size, &msg, why, sizeof why) != 0) {
        mtd_reply_undecodable(h->deps.replies, &mt_msgs_type_query, rbuf->data, size, why);
        return;
    }
    /* A listing of every mesh is answered by each member for what it owns;
     * a query naming another daemon's instance is that daemon's. */
    bool every_mesh = msg.kind == MESHTOPO_QUERY_T_LIST_MESHES && !msg.mesh_id[0];
    bool other_daemon = msg.instance[0] && strcmp(msg.instance, h->deps.instance) != 0;
    if (other_daemon || (!every_mesh && !mtd_cluster_owns(h->deps.cluster, msg.mesh_id))) {
        meshtopo_query_t_decode_cleanup(&msg);
        return;
    }
    if (mtd_reply_begin(h->deps.replies, msg.reply_channel, msg.request_id, &mt_msgs_type_reply))
        mtd_query_handle(h->deps.queries, &msg);
    meshtopo_query_t_decode_cleanup(&msg);
}

/* A member's announcement of a version it built: one of an id owned here
 * (its builder lost it meanwhile) is catalogued before anyone asks. */
static void on_topology(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mtd_handlers *h = user;
    meshtopo_topology_t t;
    if (mt_msgs_decode(&mt_msgs_type_topology, rbuf->data, rbuf->data_size, &t, NULL, 0) != 0)
        return;
    if (t.version > 0 && mt_msgs_mesh_id_check(t.mesh_id, NULL) == MT_OK &&
        mtd_cluster_owns(h->deps.cluster, t.mesh_id))
        mtd_catalog_learn(h->deps.catalog, t.mesh_id, (uint32_t)t.version);
    meshtopo_topology_t_decode_cleanup(&t);
}

static void on_pull(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mtd_handlers *h = user;
    mtd_reply_serve_pull(h->deps.replies, rbuf->data, rbuf->data_size); /* not a query */
}

mt_status mtd_handlers_subscribe(const mtd_handler_deps *deps, mtd_handlers **out_handlers)
{
    static const struct {
        mt_msgs_channel channel;
        lcm_msg_handler_t handler;
    } routes[SUB_COUNT] = {
        [SUB_SUBMIT] = {MT_MSGS_CHANNEL_SUBMIT, on_submit},
        [SUB_CHUNK] = {MT_MSGS_CHANNEL_SUBMIT_CHUNK, on_chunk},
        [SUB_QUERY] = {MT_MSGS_CHANNEL_QUERY, on_query},
        [SUB_PULL] = {MT_MSGS_CHANNEL_QUERY_PULL, on_pull},
        [SUB_TOPOLOGY] = {MT_MSGS_CHANNEL_TOPOLOGY, on_topology},
    };
    *out_handlers = NULL;
    mtd_handlers *h = calloc(1, sizeof *h);
    if (!h) return MT_ERR_NOMEM;
    h->deps = *deps;
    for (int i = 0; i < SUB_COUNT; i++) {
        if (i == SUB_TOPOLOGY && !deps->cluster) continue;
        char name[MT_MSGS_CHANNEL_NAME_MAX + 1];
        if (mt_msgs_channel_name(deps->prefix, routes[i].channel, name) != MT_OK) {
            mtd_handlers_destroy(h);
            return MT_ERR_INVALID_ARG;
        }
        h->subs[i] = lcm_subscribe(deps->lcm, name, routes[i].handler, h);
        if (!h->subs[i]) {
            mtd_handlers_destroy(h);
            return MT_ERR_NOMEM;
        }
        lcm_subscription_set_queue_capacity(h->subs[i], QUEUE_CAPACITY);
    }
    *out_handlers = h;
    return MT_OK;
}

void mtd_handlers_unsubscribe(mtd_handlers *h)
{
    for (int i = 0; i < SUB_COUNT; i++) {
        if (h->subs[i]) lcm_unsubscribe(h->deps.lcm, h->subs[i]);
        h->subs[i] = NULL;
    }
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
