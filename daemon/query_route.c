/* meshtopod's query routing (query_route.h): a query_t is checked
 * (query_check.c), its mesh version fetched from the store, and its kind's
 * answerer (answer_*.c) fills one reply_t, every id of the batch in it as
 * two-level CSR; the query-kind table (meshtopo/query_kinds.h) says which
 * ids the kind takes, whether it needs a mesh and whether a worker answers
 * it. Runs on the LCM thread; it only reads immutable store entries, so a
 * build never holds it up, and a sender over its share of that thread's
 * time is answered BUSY (fair_share.h). A version that must first be loaded
 * from the store's backing is fetched, and the query answered, on a worker. */
#include "query_route.h"

#include <inttypes.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "fair_share.h"
#include "log.h"
#include "query_check.h"

struct mtd_queries {
    mtd_store *store;
    mtd_pool *pool;
    mtd_replies *replies;
    mtd_cluster *cluster;  /* NULL without --cluster */
    mtd_fair_share *share; /* the LCM thread's time, per reply channel */
    /* Queries of a kind a worker answers (on_worker) handed to a worker
     * and not yet answered: at most one, so that senders asking for them
     * (any node may) never hold more than one worker away from the builds. */
    atomic_uint worker_queries;
};

/* Every kind's answerer. */
static const struct {
    int32_t kind;
    mtd_answerer *answer;
} answerers[] = {
    {MESHTOPO_QUERY_T_VERTEX_RING, mtd_answer_rings},
    {MESHTOPO_QUERY_T_VALENCE, mtd_answer_valences},
    {MESHTOPO_QUERY_T_FACE_NEIGHBORS, mtd_answer_face_neighbors},
    {MESHTOPO_QUERY_T_EDGE_FACES, mtd_answer_edge_faces},
    {MESHTOPO_QUERY_T_BOUNDARY_LOOPS, mtd_answer_boundary_loops},
    {MESHTOPO_QUERY_T_COMPONENTS, mtd_answer_components},
    {MESHTOPO_QUERY_T_REPORT, mtd_answer_report},
    {MESHTOPO_QUERY_T_DEFECTS, mtd_answer_defects},
    {MESHTOPO_QUERY_T_LIST_MESHES, mtd_answer_list_meshes},
    {MESHTOPO_QUERY_T_DIHEDRAL_ANGLES, mtd_answer_dihedral_angles},
    {MESHTOPO_QUERY_T_ANGLE_DEFICITS, mtd_answer_angle_deficits},
    {MESHTOPO_QUERY_T_CONVEXITY, mtd_answer_convexity},
    {MESHTOPO_QUERY_T_SELF_INTERSECTIONS, mtd_answer_self_intersections},
};

mtd_answerer *mtd_query_answerer(int32_t kind)
{
    for (size_t i = 0; i < sizeof answerers / sizeof answerers[0]; i++)
        if (answerers[i].kind == kind) return answerers[i].answer;
    return NULL;
}

/* Whether a worker answers kind (the table's on_worker). */
static bool on_worker(int32_t kind)
{
    const mt_msgs_query_kind *k = mt_msgs_query_kind_of(kind);
    return k && k->on_worker;
}

/* Answers q with an error and no items. A remembered error is sent again
 * to a retry of q; a passing one (BUSY, INTERNAL) lets a retry run q again. */
static void send_error(mtd_replies *replies, const meshtopo_query_t *q, int32_t code,
                       const char *error, bool remember)
{
    if (!remember) mtd_reply_abandon(replies, q->reply_channel, q->request_id, &mt_msgs_type_reply);
    mtd_reply_query_error(replies, q->reply_channel, q->request_id, q->mesh_id, q->kind, remember,
                          code, error);
}

/* Publishes the finished answer (or its error). */
static void send_answer(mtd_replies *replies, const meshtopo_query_t *q, mtd_answer *a,
                        int32_t version)
{
    if (!mtd_answer_ok(a)) {
        send_error(replies, q, a->status, a->error, a->status != MESHTOPO_STATUS_CODE_T_INTERNAL);
        return;
    }
    meshtopo_reply_t reply;
    if (a->have_list)
        reply = a->list;
    else
        memset(&reply, 0, sizeof reply);
    int8_t *item_status = malloc(a->item_status.n + 1);
    int8_t *boundary = malloc(a->group_boundary.n + 1);
    if (!item_status || !boundary) {
        free(item_status);
        free(boundary);
        send_error(replies, q, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory sending the answer",
                   false);
        return;
    }
    for (size_t i = 0; i < a->item_status.n; i++) item_status[i] = (int8_t)a->item_status.v[i];
    for (size_t i = 0; i < a->group_boundary.n; i++) boundary[i] = (int8_t)a->group_boundary.v[i];
    reply.utime = mtd_now_utime();
    reply.request_id = q->request_id;
    reply.status = MESHTOPO_STATUS_CODE_T_OK;
    reply.error = "";
    reply.mesh_id = q->mesh_id;
    reply.version = version;
    reply.kind = q->kind;
    reply.num_items = (int32_t)a->item_status.n;
    reply.item_status = item_status;
    reply.num_item_offsets = (int32_t)a->item_offsets.n;
    reply.item_offsets = a->item_offsets.v;
    reply.num_groups = (int32_t)a->group_boundary.n;
    reply.group_boundary = boundary;
    reply.num_value_offsets = (int32_t)a->value_offsets.n;
    reply.value_offsets = a->value_offsets.v;
    reply.value2_offsets = a->value2_offsets.v;
    reply.num_values = (int32_t)a->values.n;
    reply.values = a->values.v;
    reply.num_values2 = (int32_t)a->values2.n;
    reply.values2 = a->values2.v;
    reply.num_reals = (int32_t)a->num_reals;
    reply.reals = a->reals;
    reply.num_reports = a->have_report ? 1 : 0;
    reply.reports = a->have_report ? &a->report : NULL;
    mtd_reply_send(replies, q->reply_channel, q->request_id, true, &mt_msgs_type_reply, &reply,
                   MESHTOPO_STATUS_CODE_T_OK, "");
    free(item_status);
    free(boundary);
}

/* Answers q from the store; on the LCM thread (may_load false) a version to
 * load first sends q to a worker. */
static void answer_query(mtd_queries *qs, const meshtopo_query_t *q, bool may_load);

typedef struct load_job {
    mtd_queries *queries;
    meshtopo_query_t *query; /* a copy */
} load_job;

static void load_job_run(void *arg, bool cancelled)
{
    load_job *job = arg;
    const meshtopo_query_t *q = job->query;
    if (cancelled) {
        /* A worker query's turn ends before its answer goes out, so that
         * asking again on the answer is not told it runs. */
        if (on_worker(q->kind)) atomic_fetch_sub(&job->queries->worker_queries, 1);
        send_error(job->queries->replies, q, MESHTOPO_STATUS_CODE_T_BUSY,
                   "the daemon is shutting down; the mesh was not loaded", false);
    } else {
        answer_query(job->queries, q, true);
    }
    meshtopo_query_t_destroy(job->query);
    free(job);
}

/* Hands q to a worker that loads its version and answers. false when it
 * cannot (out of memory, the pool full or stopping). */
static bool defer_to_worker(mtd_queries *qs, const meshtopo_query_t *q)
{
    load_job *job = calloc(1, sizeof *job);
    meshtopo_query_t *copy = job ? meshtopo_query_t_copy(q) : NULL;
    if (!copy) {
        free(job);
        return false;
    }
    job->queries = qs;
    job->query = copy;
    if (mtd_pool_submit(qs->pool, load_job_run, job) != MTD_SUBMIT_OK) {
        meshtopo_query_t_destroy(copy);
        free(job);
        return false;
    }
    return true;
}

static void answer_query(mtd_queries *qs, const meshtopo_query_t *q, bool may_load)
{
    mtd_answer a;
    mtd_answer_init(&a);
    const mt_msgs_query_kind *k = mtd_query_check(&a, q);
    mtd_answerer *answer = k ? mtd_query_answerer(k->kind) : NULL;
    if (k && !answer)
        mtd_answer_fail(&a, MESHTOPO_STATUS_CODE_T_INTERNAL,
                        "kind: %" PRId32 " has no answerer in this daemon", q->kind);
    mtd_answer_input in = {.query = q, .store = qs->store, .cluster = qs->cluster};
    if (mtd_answer_ok(&a) && k->reply == MT_MSGS_REPLY_LIST) {
        answer(&a, &in); /* about the store, not one mesh */
        send_answer(qs->replies, q, &a, 0);
        mtd_answer_free(&a);
        return;
    }
    /* A worker's kind (a self-intersection check) takes long enough on a
     * large mesh to hold up every other request on the LCM thread: a worker
     * answers it, one such query at a time, or nobody when that one or every
     * worker is taken. */
    const bool worker_kind = on_worker(q->kind);
    if (mtd_answer_ok(&a) && !may_load && worker_kind) {
        if (atomic_fetch_add(&qs->worker_queries, 1) == 0 && defer_to_worker(qs, q)) {
            mtd_answer_free(&a);
            return;
        }
        atomic_fetch_sub(&qs->worker_queries, 1);
        mtd_answer_fail(&a, MESHTOPO_STATUS_CODE_T_BUSY,
                        "a self-intersection check is running or every worker is busy; ask "
                        "again later");
    }
    mtd_mesh_entry *entry = NULL;
    if (mtd_answer_ok(&a)) {
        mt_diag diag;
        mtd_fetch_result r =
            mtd_store_fetch(qs->store, q->mesh_id, (uint32_t)q->version, may_load, &entry, &diag);
        if (r == MTD_FETCH_NEEDS_LOAD && defer_to_worker(qs, q)) {
            mtd_answer_free(&a); /* a worker answers */
            return;
        }
        if (r == MTD_FETCH_BAD_ID)
            mtd_answer_fail(&a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "mesh_id: %.400s",
                            diag.message);
        else if (r == MTD_FETCH_LOAD_FAILED)
            mtd_answer_fail(&a, MESHTOPO_STATUS_CODE_T_ARCHIVE_FAILED, "%s", diag.message);
        else if (r != MTD_FETCH_OK && q->version)
            mtd_answer_fail(&a, MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH,
                            "mesh_id '%s' version %" PRId32 ": not held", q->mesh_id, q->version);
        else if (r != MTD_FETCH_OK)
            mtd_answer_fail(&a, MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH, "mesh_id '%s': no such mesh",
                            q->mesh_id);
    }
    int32_t version = 0;
    if (entry) {
        in.mesh = mtd_entry_mesh(entry);
        in.info = mtd_entry_info(entry);
        version = (int32_t)in.info->version;
        mtd_query_check_ids(&a, k, q, in.mesh);
        if (mtd_answer_ok(&a)) answer(&a, &in);
    }
    if (may_load && worker_kind)
        atomic_fetch_sub(&qs->worker_queries, 1); /* its turn ends before its answer goes out */
    send_answer(qs->replies, q, &a, version);
    mtd_entry_release(entry);
    mtd_answer_free(&a);
}

void mtd_query_handle(mtd_queries *qs, const meshtopo_query_t *q)
{
    mtd_log(MTD_LOG_DEBUG, "query",
            "mesh_id=%.64s version=%" PRId32 " kind=%" PRId32 " ids=%" PRId32, q->mesh_id,
            q->version, q->kind, q->num_ids);
    int64_t start = mtd_monotonic_us();
    char why[MTD_ERROR_MAX];
    if (!mtd_fair_share_allowed(qs->share, q->reply_channel, start, why, sizeof why)) {
        send_error(qs->replies, q, MESHTOPO_STATUS_CODE_T_BUSY, why, false);
        return;
    }
    answer_query(qs, q, false);
    int64_t end = mtd_monotonic_us();
    mtd_fair_share_charge(qs->share, q->reply_channel, end, end - start);
}

mt_status mtd_queries_create(mtd_store *store, mtd_pool *pool, mtd_replies *replies,
                             mtd_cluster *cluster, mtd_queries **out_queries)
{
    mtd_queries *qs = calloc(1, sizeof *qs);
    *out_queries = qs;
    if (!qs) return MT_ERR_NOMEM;
    qs->store = store;
    qs->pool = pool;
    qs->replies = replies;
    qs->cluster = cluster;
    atomic_init(&qs->worker_queries, 0);
    if (mtd_fair_share_create(&qs->share) != MT_OK) {
        free(qs);
        *out_queries = NULL;
        return MT_ERR_NOMEM;
    }
    return MT_OK;
}

void mtd_queries_destroy(mtd_queries *qs)
{
    if (!qs) return;
    mtd_fair_share_destroy(qs->share);
    free(qs);
}
