/* meshtopod's submissions: a decoded mesh_t is checked field by field (mesh
 * id, counts against each other and against the configured limits), then
 * built on the worker pool so the LCM thread keeps answering queries, added
 * to the store, and only then acknowledged (ack_t with the topology report)
 * and announced on PREFIX+"TOPOLOGY". Defects (bad indices, NaN positions,
 * non-manifold spots) are not errors: the core build reports them, and a
 * strict submission is refused with DEFECT_REFUSED and the full report. */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "archiver.h"
#include "daemon.h"
#include "log.h"
#include "meshtopo/content_hash.h"
#include "meshtopo/mesh.h"
#include "meshtopo/report.h"

typedef struct submit_job {
    mtd_daemon *daemon;
    meshtopo_mesh_t *msg;
    void *content; /* NULL, or the buffer msg's arrays point into */
    size_t content_capacity;
    uint64_t content_hash;
} submit_job;

/* Frees msg: its strings, and its arrays or gives back the buffer they
 * point into. */
static void free_msg(mtd_daemon *d, meshtopo_mesh_t *msg, void *content, size_t capacity)
{
    if (content) {
        msg->positions = NULL;
        msg->face_vertex_counts = NULL;
        msg->face_vertex_indices = NULL;
        mtd_content_release(d, content, capacity);
    }
    meshtopo_mesh_t_decode_cleanup(msg);
    free(msg);
}

static void free_job(submit_job *job)
{
    free_msg(job->daemon, job->msg, job->content, job->content_capacity);
    free(job);
}

/* Checks everything the build does not: the mesh id, the counts against each
 * other and the limits. Returns OK or a status with the reason in error. */
static int32_t check_mesh(const mtd_config *config, const meshtopo_mesh_t *m, char *error,
                          size_t size)
{
    mt_diag diag;
    if (mtd_mesh_id_check(m->mesh_id, &diag) != MT_OK) {
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

static int32_t status_of_build(mt_status s)
{
    switch (s) {
        case MT_ERR_TOO_LARGE:
            return MESHTOPO_STATUS_CODE_T_TOO_LARGE;
        case MT_ERR_INVALID_ARG:
            return MESHTOPO_STATUS_CODE_T_BAD_REQUEST;
        case MT_ERR_NOMEM:
            return MESHTOPO_STATUS_CODE_T_INTERNAL;
        default:
            return MESHTOPO_STATUS_CODE_T_BUILD_FAILED;
    }
}

/* Sends an ack carrying a report (OK or DEFECT_REFUSED). */
static void send_ack_with_report(mtd_daemon *d, const meshtopo_mesh_t *m, int32_t status,
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
    mtd_send_reply(d, m->reply_channel, m->request_id, true, &mt_msgs_type_ack, &ack, status,
                   error);
}

/* The kept build workspace, or a new one (NULL when out of memory: the
 * build then allocates its own scratch). */
static mt_build_workspace *workspace_take(mtd_daemon *d)
{
    pthread_mutex_lock(&d->spare_lock);
    mt_build_workspace *w = d->spare_workspace;
    d->spare_workspace = NULL;
    pthread_mutex_unlock(&d->spare_lock);
    return w ? w : mt_build_workspace_create();
}

/* Keeps a workspace for the next build; of two, the larger. */
static void workspace_release(mtd_daemon *d, mt_build_workspace *w)
{
    pthread_mutex_lock(&d->spare_lock);
    mt_build_workspace *other = d->spare_workspace;
    if (other && mt_build_workspace_bytes(other) > mt_build_workspace_bytes(w)) {
        mt_build_workspace *swap = w;
        w = other;
        other = swap;
    }
    d->spare_workspace = w;
    pthread_mutex_unlock(&d->spare_lock);
    mt_build_workspace_destroy(other);
}

void mtd_mesh_recycle(void *daemon, mt_mesh *mesh)
{
    mtd_daemon *d = daemon;
    pthread_mutex_lock(&d->spare_lock);
    if (d->spare_workspace) {
        mt_build_workspace_recycle(d->spare_workspace, mesh);
        mesh = NULL;
    }
    pthread_mutex_unlock(&d->spare_lock);
    mt_mesh_destroy(mesh);
}

static void build_job(void *arg, bool cancelled)
{
    submit_job *job = arg;
    mtd_daemon *d = job->daemon;
    const meshtopo_mesh_t *m = job->msg;
    if (cancelled) {
        mtd_reqcache_abandon(d->cache, m->reply_channel, m->request_id);
        mtd_send_ack_error(d, m->reply_channel, m->request_id, m->mesh_id, false,
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
    mt_build_options options = {.strict = false, .threads = 1, .workspace = workspace_take(d)};
    mt_mesh *mesh = NULL;
    mt_diag diag;
    char error[MTD_ERROR_MAX];
    int64_t start = mtd_now_utime();
    mt_status s = mt_mesh_build(&list, &options, &mesh, &diag);
    int64_t duration = mtd_now_utime() - start;
    if (options.workspace) workspace_release(d, options.workspace);
    atomic_fetch_add(&d->builds, 1);
    if (s != MT_OK) {
        snprintf(error, sizeof error, "build failed: %.400s", diag.message);
        mtd_send_ack_error(d, m->reply_channel, m->request_id, m->mesh_id, true, status_of_build(s),
                           error);
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
            send_ack_with_report(d, m, MESHTOPO_STATUS_CODE_T_DEFECT_REFUSED, error, 0,
                                 job->content_hash, &topology);
            mtd_topology_free(&topology);
        } else {
            mtd_send_ack_error(d, m->reply_channel, m->request_id, m->mesh_id, true,
                               MESHTOPO_STATUS_CODE_T_DEFECT_REFUSED, error);
        }
        mtd_mesh_recycle(d, mesh);
        free_job(job);
        return;
    }
    /* Stored, and in sync archive mode archived, before it is acknowledged. */
    uint32_t version = 0;
    mtd_mesh_entry *entry = NULL;
    int32_t code = mtd_archiver_store(d, m, &list, mesh, job->content_hash, &version, &entry, error,
                                      sizeof error);
    if (code != MESHTOPO_STATUS_CODE_T_OK) {
        mtd_mesh_recycle(d, mesh);
        mtd_send_ack_error(d, m->reply_channel, m->request_id, m->mesh_id, true, code, error);
        free_job(job);
        return;
    }
    const mt_mesh *held = mtd_entry_mesh(entry);
    mtd_log(MTD_LOG_INFO, "built",
            "mesh_id=%s version=%" PRIu32 " source=%s verts=%" PRIu32 " faces=%" PRIu32
            " defects=%zu build_us=%" PRId64,
            m->mesh_id, version, m->source, mt_mesh_num_verts(held), mt_mesh_num_faces(held),
            mt_mesh_report(held)->num_defects, duration);
    if (mtd_topology_fill(held, mtd_entry_info(entry), duration, MTD_TOPOLOGY_LIST_MAX,
                          &topology) == 0) {
        send_ack_with_report(d, m, MESHTOPO_STATUS_CODE_T_OK, "", (int32_t)version,
                             job->content_hash, &topology);
        int size = meshtopo_topology_t_encoded_size(&topology);
        void *buf = size > 0 ? malloc((size_t)size) : NULL;
        if (buf && meshtopo_topology_t_encode(buf, 0, size, &topology) == size)
            lcm_publish(d->lcm, d->topology_channel, buf, (unsigned)size);
        free(buf);
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
        mtd_send_reply(d, m->reply_channel, m->request_id, true, &mt_msgs_type_ack, &ack,
                       MESHTOPO_STATUS_CODE_T_OK, "");
    }
    mtd_entry_release(entry);
    free_job(job);
}

static void submit(mtd_daemon *d, meshtopo_mesh_t *msg, void *content, size_t capacity,
                   uint64_t content_hash)
{
    char error[MTD_ERROR_MAX];
    int32_t status = check_mesh(&d->config, msg, error, sizeof error);
    if (status != MESHTOPO_STATUS_CODE_T_OK) {
        mtd_send_ack_error(d, msg->reply_channel, msg->request_id, msg->mesh_id, true, status,
                           error);
        free_msg(d, msg, content, capacity);
        return;
    }
    submit_job *job = malloc(sizeof *job);
    if (!job) {
        mtd_reqcache_abandon(d->cache, msg->reply_channel, msg->request_id);
        mtd_send_ack_error(d, msg->reply_channel, msg->request_id, msg->mesh_id, false,
                           MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory");
        free_msg(d, msg, content, capacity);
        return;
    }
    job->daemon = d;
    job->msg = msg;
    job->content = content;
    job->content_capacity = capacity;
    job->content_hash = content_hash;
    mtd_log(MTD_LOG_DEBUG, "submit",
            "mesh_id=%s request_id=%" PRId64 " verts=%" PRId32 " faces=%" PRId32, msg->mesh_id,
            msg->request_id, msg->num_verts, msg->num_faces);
    mtd_submit_result r = mtd_pool_submit(d->pool, build_job, job);
    if (r != MTD_SUBMIT_OK) {
        mtd_reqcache_abandon(d->cache, msg->reply_channel, msg->request_id);
        mtd_send_ack_error(d, msg->reply_channel, msg->request_id, msg->mesh_id, false,
                           MESHTOPO_STATUS_CODE_T_BUSY,
                           r == MTD_SUBMIT_BUSY ? "every build worker is busy; retry later"
                                                : "the daemon is shutting down");
        free_job(job);
    }
}

void mtd_submit_handle(mtd_daemon *d, meshtopo_mesh_t *msg, const void *encoded,
                       size_t encoded_size)
{
    submit(d, msg, NULL, 0, mt_msgs_mesh_content_hash(msg, encoded, encoded_size));
}

void mtd_submit_handle_content(mtd_daemon *d, meshtopo_mesh_t *msg, void *content,
                               size_t content_capacity, uint64_t content_hash)
{
    submit(d, msg, content, content_capacity, content_hash);
}
