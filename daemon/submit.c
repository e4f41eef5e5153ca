/* meshtopod's submissions (submit.h): a decoded mesh_t is checked field by
 * field (mesh id, counts against each other and against the configured
 * limits) on the LCM thread, then built on a worker with the kept build
 * workspace, put into the store (which has it archived as its policy says),
 * and only then acknowledged (ack_t
 * with the topology report) and announced on PREFIX+"TOPOLOGY", from the
 * worker. Defects (bad indices, NaN positions, non-manifold spots) are not
 * errors: the core build reports them, and a strict submission is refused
 * with DEFECT_REFUSED and the full report. */
#include "submit.h"

#include <inttypes.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "log.h"
#include "meshtopo/content_hash.h"
#include "meshtopo/mesh.h"
#include "meshtopo/protocol.h"
#include "meshtopo/report.h"
#include "topology.h"

struct mtd_submitter {
    mtd_submit_deps deps;
    atomic_int_fast64_t builds;
};

typedef struct submit_job {
    mtd_submitter *submitter;
    meshtopo_mesh_t *msg;
    void *content; /* NULL, or the buffer msg's arrays point into */
    size_t content_capacity;
    uint64_t content_hash;
    mtd_cost cost; /* reserved in admission until the job ends */
} submit_job;

/* Frees msg: its strings, and its arrays or gives back the buffer they
 * point into. */
static void free_msg(mtd_submitter *s, meshtopo_mesh_t *msg, void *content, size_t capacity)
{
    if (content) {
        msg->positions = NULL;
        msg->face_vertex_counts = NULL;
        msg->face_vertex_indices = NULL;
        mtd_content_release(s->deps.contents, content, capacity);
    }
    meshtopo_mesh_t_decode_cleanup(msg);
    free(msg);
}

/* Ends a job: gives back its admission and frees it. */
static void free_job(submit_job *job)
{
    mtd_admission_give_back(job->submitter->deps.admission, job->msg->reply_channel, &job->cost);
    free_msg(job->submitter, job->msg, job->content, job->content_capacity);
    free(job);
}

/* Checks everything the build does not: the mesh id, the counts against each
 * other and the limits. Returns OK or a status with the reason in error. */
static int32_t check_mesh(const mtd_config *config, const meshtopo_mesh_t *m, char *error,
                          size_t size)
{
    mt_diag diag;
    if (mt_msgs_mesh_id_check(m->mesh_id, &diag) != MT_OK) {
        snprintf(error, size, "mesh_id: %.400s", diag.message);
        return MESHTOPO_STATUS_CODE_T_BAD_REQUEST;
    }
    if (m->num_verts < 0) {
        snprintf(error, size, "num_verts: %" PRId32 " is negative", m->num_verts);
        return MESHTOPO_STATUS_CODE_T_BAD_REQUEST;
    }
    if (m->num_position_values != 0 && m->num_position_values != 3 * (int64_t)m->num_verts) {
        snprintf(error, size,
                 "num_position_values: %" PRId32 " is neither 0 nor 3 * num_verts (%" PRId64 ")",
                 m->num_position_values, 3 * (int64_t)m->num_verts);
        return MESHTOPO_STATUS_CODE_T_BAD_REQUEST;
    }
    if ((uint32_t)m->num_verts > config->max_verts) {
        snprintf(error, size,
                 "num_verts: %" PRId32 " exceeds the limit of %" PRIu32 " (--max-verts)",
                 m->num_verts, config->max_verts);
        return MESHTOPO_STATUS_CODE_T_TOO_LARGE;
    }
    if ((uint32_t)m->num_faces > config->max_faces) {
        snprintf(error, size,
                 "num_faces: %" PRId32 " exceeds the limit of %" PRIu32 " (--max-faces)",
                 m->num_faces, config->max_faces);
        return MESHTOPO_STATUS_CODE_T_TOO_LARGE;
    }
    if ((uint64_t)m->num_indices > config->max_indices) {
        snprintf(error, size,
                 "num_indices: %" PRId32 " exceeds the limit of %" PRIu64 " (--max-indices)",
                 m->num_indices, config->max_indices);
        return MESHTOPO_STATUS_CODE_T_TOO_LARGE;
    }
    int64_t sum = 0;
    for (int32_t i = 0; i < m->num_faces; i++) {
        if (m->face_vertex_counts[i] < 0) {
            snprintf(error, size, "face_vertex_counts[%" PRId32 "]: %" PRId32 " is negative", i,
                     m->face_vertex_counts[i]);
            return MESHTOPO_STATUS_CODE_T_BAD_REQUEST;
        }
        sum += m->face_vertex_counts[i];
    }
    if (sum != m->num_indices) {
        snprintf(error, size, "num_indices: %" PRId32 " but face_vertex_counts add up to %" PRId64,
                 m->num_indices, sum);
        return MESHTOPO_STATUS_CODE_T_BAD_REQUEST;
    }
    return MESHTOPO_STATUS_CODE_T_OK;
}

/* Sends an ack carrying a report (OK or DEFECT_REFUSED). */
static void send_ack_with_report(mtd_submitter *s, const meshtopo_mesh_t *m, int32_t status,
                                 const char *error, int32_t version, uint64_t hash,
                                 meshtopo_topology_t *report)
{
    meshtopo_ack_t ack;
    memset(&ack, 0, sizeof ack);
    ack.utime = mtd_now_utime();
    ack.request_id = m->request_id;
    ack.status = status;
    ack.error = (char *)error;
    ack.mesh_id = m->mesh_id;
    ack.version = version;
    ack.content_hash = (int64_t)hash;
    ack.num_reports = 1;
    ack.reports = report;
    mtd_reply_send(s->deps.replies, m->reply_channel, m->request_id, true, &mt_msgs_type_ack, &ack,
                   status, error);
}

/* Publishes the report of a stored version on PREFIX "TOPOLOGY" as one
 * datagram: every subscriber gets it, so it cannot travel in pulled parts.
 * When the full report (`full`, what the ack carried) is larger, its lists
 * are cut (a quarter at a time) until it fits; the counts stay whole and the
 * BOUNDARY_LOOPS and DEFECTS queries give the full lists. */
static void broadcast_topology(mtd_submitter *s, const mt_mesh *mesh, const mtd_mesh_info *info,
                               int64_t duration, const meshtopo_topology_t *full)
{
    meshtopo_topology_t cut;
    const meshtopo_topology_t *t = full;
    int size = meshtopo_topology_t_encoded_size(t);
    for (size_t list_max = MTD_TOPOLOGY_LIST_MAX / 4;
         size > MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX; list_max /= 4) {
        if (t == &cut) mtd_topology_free(&cut);
        if (mtd_topology_fill(mesh, info, duration, list_max, &cut) != 0) {
            mtd_log(MTD_LOG_ERROR, "publish", "channel=%s out of memory for the report",
                    s->deps.topology_channel);
            return;
        }
        t = &cut;
        size = meshtopo_topology_t_encoded_size(t);
        if (list_max == 0) break;
    }
    void *buf = size > 0 ? malloc((size_t)size) : NULL;
    if (buf && meshtopo_topology_t_encode(buf, 0, size, t) == size &&
        lcm_publish(s->deps.lcm, s->deps.topology_channel, buf, (unsigned)size) == 0) {
        if (t == &cut)
            mtd_log(MTD_LOG_DEBUG, "topology_cut",
                    "mesh_id=%s bytes=%d lists cut to fit one datagram", info->id, size);
    } else {
        mtd_log(MTD_LOG_ERROR, "publish", "channel=%s type=topology_t bytes=%d",
                s->deps.topology_channel, size);
    }
    free(buf);
    if (t == &cut) mtd_topology_free(&cut);
}

static void build_job(void *arg, bool cancelled)
{
    submit_job *job = arg;
    mtd_submitter *sub = job->submitter;
    mtd_replies *replies = sub->deps.replies;
    const meshtopo_mesh_t *m = job->msg;
    if (cancelled) {
        mtd_reply_abandon(replies, m->reply_channel, m->request_id, &mt_msgs_type_ack);
        mtd_reply_ack_error(replies, m->reply_channel, m->request_id, m->mesh_id, false,
                            MESHTOPO_STATUS_CODE_T_BUSY,
                            "the daemon is shutting down; the mesh was not built");
        free_job(job);
        return;
    }
    mt_face_list list = {
        .num_verts = (uint32_t)m->num_verts,
        .num_faces = (uint32_t)m->num_faces,
        .num_indices = (uint64_t)m->num_indices,
        .positions = m->num_position_values ? m->positions : NULL,
        /* int32_t and uint32_t may alias; negative indices read as out of range. */
        .face_sizes = (uint32_t *)m->face_vertex_counts,
        .face_indices = (uint32_t *)m->face_vertex_indices,
    };
    mt_build_options options = {
        .strict = false, .threads = 1, .workspace = mtd_workspace_take(sub->deps.workspaces)};
    mt_mesh *mesh = NULL;
    mt_diag diag;
    char error[MTD_ERROR_MAX];
    int64_t start = mtd_now_utime();
    mt_status s = mt_mesh_build(&list, &options, &mesh, &diag);
    int64_t duration = mtd_now_utime() - start;
    mtd_workspace_release(sub->deps.workspaces, options.workspace);
    atomic_fetch_add(&sub->builds, 1);
    if (s != MT_OK) {
        snprintf(error, sizeof error, "build failed: %.400s", diag.message);
        mtd_reply_ack_error(replies, m->reply_channel, m->request_id, m->mesh_id, true,
                            mt_msgs_code_of_status(s, MESHTOPO_STATUS_CODE_T_BUILD_FAILED), error);
        free_job(job);
        return;
    }
    const mt_report *report = mt_mesh_report(mesh);
    meshtopo_topology_t topology;
    if (m->strict && report->num_defects > 0) {
        char first[256];
        mt_defect_describe(&report->defects[0], first, sizeof first);
        snprintf(error, sizeof error, "strict: %zu defect(s), the first: %s", report->num_defects,
                 first);
        mtd_mesh_info info = {.id = m->mesh_id,
                              .source = m->source,
                              .utime = m->utime,
                              .content_hash = job->content_hash};
        if (mtd_topology_fill(mesh, &info, duration, MTD_TOPOLOGY_LIST_MAX, &topology) == 0) {
            send_ack_with_report(sub, m, MESHTOPO_STATUS_CODE_T_DEFECT_REFUSED, error, 0,
                                 job->content_hash, &topology);
            mtd_topology_free(&topology);
        } else {
            mtd_reply_ack_error(replies, m->reply_channel, m->request_id, m->mesh_id, true,
                                MESHTOPO_STATUS_CODE_T_DEFECT_REFUSED, error);
        }
        mtd_workspace_recycle_mesh(sub->deps.workspaces, mesh);
        free_job(job);
        return;
    }
    /* Stored, and in sync archive mode archived, before it is acknowledged. */
    uint32_t version = 0;
    mtd_mesh_entry *entry = NULL;
    mtd_mesh_meta meta = {
        .source = m->source, .utime = m->utime, .content_hash = job->content_hash};
    bool by_policy = false;
    s = mtd_store_put(sub->deps.store, m->mesh_id, mesh, &meta, &list, &version, &entry, &by_policy,
                      &diag);
    if (s != MT_OK) {
        int32_t code;
        if (by_policy) {
            snprintf(error, sizeof error, "not archived, so not stored: %.400s", diag.message);
            code = s == MT_ERR_TOO_LARGE ? MESHTOPO_STATUS_CODE_T_TOO_LARGE
                                         : MESHTOPO_STATUS_CODE_T_ARCHIVE_FAILED;
        } else {
            snprintf(error, sizeof error, "not stored: %.400s", diag.message);
            code = s == MT_ERR_TOO_LARGE ? MESHTOPO_STATUS_CODE_T_TOO_LARGE
                                         : MESHTOPO_STATUS_CODE_T_INTERNAL;
        }
        mtd_workspace_recycle_mesh(sub->deps.workspaces, mesh);
        mtd_reply_ack_error(replies, m->reply_channel, m->request_id, m->mesh_id, true, code,
                            error);
        free_job(job);
        return;
    }
    const mt_mesh *held = mtd_entry_mesh(entry);
    mtd_log(MTD_LOG_INFO, "built",
            "mesh_id=%s version=%" PRIu32 " source=%s verts=%" PRIu32 " faces=%" PRIu32
            " defects=%zu build_us=%" PRId64,
            m->mesh_id, version, m->source, mt_mesh_num_verts(held), mt_mesh_num_faces(held),
            mt_mesh_report(held)->num_defects, duration);
    /* The report is a copy: nothing below needs the entry. */
    const bool have_report = mtd_topology_fill(held, mtd_entry_info(entry), duration,
                                               MTD_TOPOLOGY_LIST_MAX, &topology) == 0;
    /* Announced before it is acknowledged: another member of a cluster that
     * owns the id now hears of the version before the sender can ask it for
     * the version (handlers.c). */
    if (have_report) broadcast_topology(sub, held, mtd_entry_info(entry), duration, &topology);
    /* This worker's reference goes before the ack: once the sender hears of
     * the version, only the store (queries, the async writer's queue) holds
     * it, so when the store drops it for a later version, that put frees it
     * and its arrays are back in the kept workspace before the later
     * version is acknowledged. Released after the ack, a worker preempted
     * between the two freed it on its own time, after the next ack. */
    mtd_entry_release(entry);
    entry = NULL;
    held = NULL;
    if (have_report) {
        send_ack_with_report(sub, m, MESHTOPO_STATUS_CODE_T_OK, "", (int32_t)version,
                             job->content_hash, &topology);
        mtd_topology_free(&topology);
    } else {
        /* The mesh is held; the client learns its version without the report. */
        meshtopo_ack_t ack;
        memset(&ack, 0, sizeof ack);
        ack.utime = mtd_now_utime();
        ack.request_id = m->request_id;
        ack.error = "";
        ack.mesh_id = m->mesh_id;
        ack.version = (int32_t)version;
        ack.content_hash = (int64_t)job->content_hash;
        mtd_reply_send(replies, m->reply_channel, m->request_id, true, &mt_msgs_type_ack, &ack,
                       MESHTOPO_STATUS_CODE_T_OK, "");
    }
    free_job(job);
}

static void submit(mtd_submitter *sub, meshtopo_mesh_t *msg, void *content, size_t capacity,
                   uint64_t content_hash)
{
    mtd_replies *replies = sub->deps.replies;
    char error[MTD_ERROR_MAX];
    int32_t status = check_mesh(sub->deps.config, msg, error, sizeof error);
    if (status != MESHTOPO_STATUS_CODE_T_OK) {
        mtd_reply_ack_error(replies, msg->reply_channel, msg->request_id, msg->mesh_id, true,
                            status, error);
        free_msg(sub, msg, content, capacity);
        return;
    }
    mtd_cost cost = mtd_cost_estimate((uint32_t)msg->num_verts, msg->num_position_values != 0,
                                      (uint32_t)msg->num_faces, (uint64_t)msg->num_indices);
    mtd_store_totals held;
    mtd_store_get_totals(sub->deps.store, &held);
    status = mtd_admission_take(sub->deps.admission, msg->reply_channel, &cost, held.memory_bytes,
                                mtd_catalog_bytes(sub->deps.catalog), error, sizeof error);
    if (status != MESHTOPO_STATUS_CODE_T_OK) {
        /* TOO_LARGE stays true for this request; BUSY may pass on a retry. */
        bool lasting = status == MESHTOPO_STATUS_CODE_T_TOO_LARGE;
        if (!lasting)
            mtd_reply_abandon(replies, msg->reply_channel, msg->request_id, &mt_msgs_type_ack);
        mtd_reply_ack_error(replies, msg->reply_channel, msg->request_id, msg->mesh_id, lasting,
                            status, error);
        free_msg(sub, msg, content, capacity);
        return;
    }
    submit_job *job = malloc(sizeof *job);
    if (!job) {
        mtd_admission_give_back(sub->deps.admission, msg->reply_channel, &cost);
        mtd_reply_abandon(replies, msg->reply_channel, msg->request_id, &mt_msgs_type_ack);
        mtd_reply_ack_error(replies, msg->reply_channel, msg->request_id, msg->mesh_id, false,
                            MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory");
        free_msg(sub, msg, content, capacity);
        return;
    }
    job->submitter = sub;
    job->msg = msg;
    job->content = content;
    job->content_capacity = capacity;
    job->content_hash = content_hash;
    job->cost = cost;
    mtd_log(MTD_LOG_DEBUG, "submit",
            "mesh_id=%s request_id=%" PRId64 " verts=%" PRId32 " faces=%" PRId32, msg->mesh_id,
            msg->request_id, msg->num_verts, msg->num_faces);
    mtd_submit_result r = mtd_pool_submit(sub->deps.pool, build_job, job);
    if (r != MTD_SUBMIT_OK) {
        mtd_reply_abandon(replies, msg->reply_channel, msg->request_id, &mt_msgs_type_ack);
        mtd_reply_ack_error(replies, msg->reply_channel, msg->request_id, msg->mesh_id, false,
                            MESHTOPO_STATUS_CODE_T_BUSY,
                            r == MTD_SUBMIT_BUSY ? "every build worker is busy; retry later"
                                                 : "the daemon is shutting down");
        free_job(job);
    }
}

void mtd_submit_handle(mtd_submitter *sub, meshtopo_mesh_t *msg, const void *encoded,
                       size_t encoded_size)
{
    submit(sub, msg, NULL, 0, mt_msgs_mesh_content_hash(msg, encoded, encoded_size));
}

void mtd_submit_content(mtd_submitter *sub, meshtopo_mesh_t *msg, void *content,
                        size_t content_capacity, uint64_t content_hash)
{
    submit(sub, msg, content, content_capacity, content_hash);
}

mt_status mtd_submitter_create(const mtd_submit_deps *deps, mtd_submitter **out_submitter)
{
    *out_submitter = calloc(1, sizeof **out_submitter);
    if (!*out_submitter) return MT_ERR_NOMEM;
    (*out_submitter)->deps = *deps;
    return MT_OK;
}

void mtd_submitter_destroy(mtd_submitter *sub)
{
    free(sub);
}

int64_t mtd_submitter_builds(mtd_submitter *sub)
{
    return atomic_load(&sub->builds);
}
