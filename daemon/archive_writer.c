/* meshtopod's archive writer (archive_writer.h): writes built versions with
 * meshtopo::archive (temporary name, fsync, rename or link, directory
 * fsync), either inside the store's put (sync: admit, before the version is
 * visible) or from one writer thread fed by a bounded queue (async:
 * on_added, after). Every file written is catalogued; in async mode it then
 * becomes something the memory budget may drop (the daemon's tick and the
 * store's next put or load trim). Threads: build workers (admit, on_added),
 * the writer thread, the LCM thread (stats). */
#include "archive_writer.h"

#include <inttypes.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"
#include "meshtopo/archive.h"

/* One built version waiting for the async writer. */
typedef struct write_job {
    struct write_job *next;
    mtd_mesh_entry *entry; /* a reference: the mesh, id, version, source */
    mt_face_list list;     /* a copy of the submitted face list */
} write_job;

struct mtd_writer {
    mtd_catalog *catalog;     /* not owned */
    mt_archive *archive;      /* the catalog's */
    mtd_budget *budget;       /* not owned; NULL without one */
    mtd_error_log *error_log; /* not owned */
    mtd_archive_mode mode;
    mt_archive_compression compression; /* --archive-compression, auto resolved */
    bool shared;                        /* --cluster: other members write the same directory */

    pthread_mutex_t queue_lock; /* the writer's queue */
    pthread_cond_t queue_filled, queue_drained;
    write_job *head, *tail;
    size_t queued, capacity;
    bool writer_started, writer_stop;
    pthread_t writer;

    atomic_int_fast64_t writes, errors;
};

/* Logs and counts an archive error that a reply to its requester reports. */
static void count_error(mtd_writer *a, const char *what, const char *message)
{
    mtd_log(MTD_LOG_ERROR, what, "error=%s", message);
    atomic_fetch_add(&a->errors, 1);
}

/* count_error, for an archive error nobody is answered about: noted in the
 * error log for the heartbeat. */
static void note_error(mtd_writer *a, const char *what, const char *message)
{
    count_error(a, what, message);
    mtd_error_log_note_event(a->error_log, what, message);
}

/* Version numbers tried when the archive's names for them are taken. */
#define NAME_TAKEN_ATTEMPTS 8
/* In a shared directory: version numbers tried when other members take
 * them first (each loss means another member just wrote this id). */
#define SHARED_TAKEN_ATTEMPTS 64

/* Archives one version and adds it to the catalog. */
static mt_status write_version(mtd_writer *a, const mtd_mesh_info *info, const mt_face_list *list,
                               const mt_mesh *mesh, mt_diag *diag)
{
    mt_archive_meta meta = {.mesh_id = info->id,
                            .version = info->version,
                            .utime = info->utime,
                            .source = info->source,
                            .content_hash = info->content_hash};
    mt_archive_write_stats stats;
    memset(&stats, 0, sizeof stats);
    const mt_archive_write_options options = {.compression = a->compression};
    mt_status s = mt_archive_write_with(a->archive, &meta, list, mesh, &options, &stats, diag);
    if (s != MT_OK) return s;
    atomic_fetch_add(&a->writes, 1);
    mtd_log(MTD_LOG_DEBUG, "archived",
            "mesh_id=%s version=%" PRIu32 " bytes=%" PRIu64 " write_ms=%.2f fsync_ms=%.2f",
            info->id, info->version, stats.file_bytes, stats.write_ms, stats.fsync_ms);
    mtd_catalog_insert(a->catalog, info, mesh, stats.file_bytes);
    return MT_OK;
}

/* ---- async: the writer thread --------------------------------------------- */

static void *writer_main(void *arg)
{
    mtd_writer *a = arg;
    for (;;) {
        pthread_mutex_lock(&a->queue_lock);
        while (!a->head && !a->writer_stop) pthread_cond_wait(&a->queue_filled, &a->queue_lock);
        write_job *job = a->head;
        if (job) {
            a->head = job->next;
            if (!a->head) a->tail = NULL;
        }
        pthread_mutex_unlock(&a->queue_lock);
        if (!job) return NULL; /* stopping and the queue is empty */
        const mtd_mesh_info *info = mtd_entry_info(job->entry);
        mt_diag diag;
        if (write_version(a, info, &job->list, mtd_entry_mesh(job->entry), &diag) != MT_OK) {
            char text[MTD_ERROR_MAX];
            snprintf(text, sizeof text, "mesh '%.255s' version %" PRIu32 ": %.200s", info->id,
                     info->version, diag.message);
            note_error(a, "archive_write", text);
        } else {
            /* Archived now: the budget may drop it from memory. */
            mtd_budget_track(a->budget, info->id, info->version);
        }
        mtd_entry_release(job->entry);
        mt_face_list_free(&job->list);
        free(job);
        pthread_mutex_lock(&a->queue_lock);
        a->queued--;
        pthread_cond_broadcast(&a->queue_drained);
        pthread_mutex_unlock(&a->queue_lock);
    }
}

/* Queues a stored version for the writer, waiting for room. */
static mt_status enqueue_write(mtd_writer *a, mtd_mesh_entry *entry, const mt_face_list *list,
                               mt_diag *diag)
{
    write_job *job = calloc(1, sizeof *job);
    if (!job) return MT_ERR_NOMEM;
    mt_status s =
        mt_face_list_alloc(&job->list, list->num_verts, list->num_faces, list->num_indices, diag);
    if (s != MT_OK) {
        free(job);
        return s;
    }
    if (list->positions)
        memcpy(job->list.positions, list->positions, 3 * sizeof(double) * list->num_verts);
    else {
        free(job->list.positions);
        job->list.positions = NULL;
    }
    memcpy(job->list.face_sizes, list->face_sizes, sizeof(uint32_t) * list->num_faces);
    memcpy(job->list.face_indices, list->face_indices, sizeof(uint32_t) * list->num_indices);
    job->entry = mtd_entry_retain(entry);
    pthread_mutex_lock(&a->queue_lock);
    while (a->queued >= a->capacity && !a->writer_stop)
        pthread_cond_wait(&a->queue_drained, &a->queue_lock);
    a->queued++;
    if (a->tail)
        a->tail->next = job;
    else
        a->head = job;
    a->tail = job;
    pthread_cond_signal(&a->queue_filled);
    pthread_mutex_unlock(&a->queue_lock);
    return MT_OK;
}

static void policy_on_added(void *ctx, mtd_mesh_entry *entry, const mt_face_list *list)
{
    mtd_writer *a = ctx;
    mt_diag diag;
    if (enqueue_write(a, entry, list, &diag) != MT_OK) {
        const mtd_mesh_info *info = mtd_entry_info(entry);
        char text[MTD_ERROR_MAX];
        snprintf(text, sizeof text, "mesh '%.255s' version %" PRIu32 " not queued: out of memory",
                 info->id, info->version);
        note_error(a, "archive_write", text);
    }
}

/* ---- sync: before the version is visible ----------------------------------- */

/* The next version number of id in a directory other members write too:
 * one above every version there and every one catalogued (the archive's
 * link decides between members that pick the same). */
static mt_status shared_next_version(mtd_writer *a, const char *id, uint32_t *out_version,
                                     mt_diag *diag)
{
    uint32_t highest = 0;
    mt_status s = mt_archive_highest_version(a->archive, id, &highest, diag);
    if (s != MT_OK) return s;
    uint32_t catalogued = mtd_catalog_highest(a->catalog, id);
    if (catalogued > highest) highest = catalogued;
    if (highest == UINT32_MAX)
        return mt_diag_set(diag, MT_ERR_TOO_LARGE, "mesh '%s' has used every version number", id);
    *out_version = highest + 1;
    return MT_OK;
}

/* Archives a built version under the next number free in a shared
 * directory: numbers other members took meanwhile are skipped. MT_OK with
 * *io_version set, or the last write's failure. */
static mt_status write_shared(mtd_writer *a, const mtd_mesh_info *proposed,
                              const mt_face_list *list, const mt_mesh *mesh, uint32_t *io_version,
                              mt_diag *diag)
{
    mt_status s = MT_OK;
    mtd_mesh_info info = *proposed;
    for (int attempt = 0; attempt < SHARED_TAKEN_ATTEMPTS; attempt++) {
        s = shared_next_version(a, info.id, &info.version, diag);
        if (s != MT_OK) return s;
        *io_version = info.version;
        s = write_version(a, &info, list, mesh, diag);
        if (s != MT_ERR_INVALID_ARG) return s;
        mtd_log(MTD_LOG_INFO, "archive_version_taken", "mesh_id=%s version=%" PRIu32 ": %s",
                info.id, info.version, diag->message);
    }
    return s;
}

/* Writes a version under the number the store reserved; a number whose name
 * is taken in the directory (a file the catalog could not read, or
 * something planted there) is skipped for the next one. */
static mt_status write_numbered(mtd_writer *a, const mtd_mesh_info *proposed,
                                const mt_face_list *list, const mt_mesh *mesh, uint32_t *io_version,
                                mt_diag *diag)
{
    mt_status s = MT_OK;
    mtd_mesh_info info = *proposed;
    for (int attempt = 0; attempt < NAME_TAKEN_ATTEMPTS; attempt++) {
        *io_version = info.version;
        s = write_version(a, &info, list, mesh, diag);
        if (s != MT_ERR_INVALID_ARG) break;
        note_error(a, "archive_name_taken", diag->message);
        if (info.version == UINT32_MAX) break;
        info.version++;
    }
    return s;
}

/* The store's admit: durable before visible. A refusal is MT_ERR_TOO_LARGE
 * (a cluster's id out of version numbers) or MT_ERR_IO (ARCHIVE_FAILED),
 * with diag's message as the archive gave it. */
static mt_status policy_admit(void *ctx, const mtd_mesh_info *info, const mt_face_list *list,
                              const mt_mesh *mesh, uint32_t *io_version, mt_diag *diag)
{
    mtd_writer *a = ctx;
    mt_status s = a->shared ? write_shared(a, info, list, mesh, io_version, diag)
                            : write_numbered(a, info, list, mesh, io_version, diag);
    if (s == MT_OK) return MT_OK;
    char error[MTD_ERROR_MAX];
    snprintf(error, sizeof error, "not archived, so not stored: %.400s", diag->message);
    count_error(a, "archive_write", error);
    s = a->shared && s == MT_ERR_TOO_LARGE ? MT_ERR_TOO_LARGE : MT_ERR_IO;
    diag->status = s;
    return s;
}

/* An admitted version the store refused: not acknowledged, so not kept (a
 * restart must not serve it). */
static void policy_withdraw(void *ctx, const char *id, uint32_t version)
{
    mtd_writer *a = ctx;
    mt_diag ignored;
    mt_archive_remove(a->archive, id, version, &ignored);
    mtd_catalog_remove(a->catalog, id, version);
}

void mtd_writer_policy(mtd_writer *a, mtd_store_policy *out)
{
    memset(out, 0, sizeof *out);
    out->ctx = a;
    if (a->mode == MTD_ARCHIVE_SYNC) {
        out->admit = policy_admit;
        out->withdraw = policy_withdraw;
    } else if (a->mode == MTD_ARCHIVE_ASYNC) {
        out->on_added = policy_on_added;
    }
}

/* ---- create and stop ------------------------------------------------------- */

/* The archive files' compression (--archive-compression). LZ4 without
 * the Blosc filter plugin is an error: the daemon does not start rather
 * than write something other than asked. */
static mt_status resolve_compression(mtd_archive_compression asked, mt_archive_compression *out,
                                     mt_diag *diag)
{
    static const mt_archive_compression stored[] = {
        MT_ARCHIVE_COMPRESSION_NONE, MT_ARCHIVE_COMPRESSION_DEFLATE, MT_ARCHIVE_COMPRESSION_LZ4};
    if ((unsigned)asked > MTD_COMPRESSION_LZ4)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "unknown archive compression %d", (int)asked);
    if (asked == MTD_COMPRESSION_LZ4 && !mt_archive_lz4_available())
        return mt_diag_set(diag, MT_ERR_UNSUPPORTED,
                           "--archive-compression lz4: HDF5 finds no Blosc filter plugin "
                           "(Debian: hdf5-filter-plugin-blosc-serial; or HDF5_PLUGIN_PATH)");
    *out = stored[asked];
    return MT_OK;
}

mt_status mtd_writer_check_compression(mtd_archive_compression asked, mt_diag *diag)
{
    mt_archive_compression ignored;
    return resolve_compression(asked, &ignored, diag);
}

mt_status mtd_writer_create(const mtd_config *config, mtd_catalog *catalog, mtd_budget *budget,
                            mtd_error_log *errors, mtd_writer **out_writer, mt_diag *diag)
{
    *out_writer = NULL;
    mtd_writer *a = calloc(1, sizeof *a);
    if (!a) return MT_ERR_NOMEM;
    a->catalog = catalog;
    a->archive = mtd_catalog_archive(catalog);
    a->budget = budget;
    a->error_log = errors;
    a->mode = config->archive_mode;
    a->shared = config->cluster[0] != '\0';
    a->capacity = config->archive_queue ? config->archive_queue : 1;
    atomic_init(&a->writes, 0);
    atomic_init(&a->errors, 0);
    pthread_mutex_init(&a->queue_lock, NULL);
    pthread_cond_init(&a->queue_filled, NULL);
    pthread_cond_init(&a->queue_drained, NULL);
    mt_status s = resolve_compression(config->archive_compression, &a->compression, diag);
    if (s == MT_OK && a->mode == MTD_ARCHIVE_ASYNC) {
        if (pthread_create(&a->writer, NULL, writer_main, a) != 0)
            s = MT_ERR_NOMEM;
        else
            a->writer_started = true;
    }
    if (s != MT_OK) {
        mtd_writer_destroy(a);
        return s;
    }
    *out_writer = a;
    return MT_OK;
}

void mtd_writer_stop(mtd_writer *a)
{
    if (!a) return;
    pthread_mutex_lock(&a->queue_lock);
    bool join = a->writer_started && !a->writer_stop;
    a->writer_stop = true;
    pthread_cond_broadcast(&a->queue_filled);
    pthread_cond_broadcast(&a->queue_drained);
    pthread_mutex_unlock(&a->queue_lock);
    if (join) pthread_join(a->writer, NULL);
}

void mtd_writer_destroy(mtd_writer *a)
{
    if (!a) return;
    mtd_writer_stop(a);
    for (write_job *job = a->head, *next; job; job = next) {
        next = job->next;
        mtd_entry_release(job->entry);
        mt_face_list_free(&job->list);
        free(job);
    }
    pthread_cond_destroy(&a->queue_filled);
    pthread_cond_destroy(&a->queue_drained);
    pthread_mutex_destroy(&a->queue_lock);
    free(a);
}

void mtd_writer_stats(mtd_writer *a, meshtopo_status_t *st)
{
    if (!a) return;
    pthread_mutex_lock(&a->queue_lock);
    st->archive_backlog = (int32_t)a->queued;
    pthread_mutex_unlock(&a->queue_lock);
    st->archive_writes = atomic_load(&a->writes);
    st->archive_errors += atomic_load(&a->errors);
}
