/* meshtopod's archive (archiver.h): the catalog of archived versions (a
 * sorted array by mesh id then version, one mutex), the writes (sync on the
 * build worker, async through one writer thread and a bounded queue), the
 * loads (preload at start; on demand through the store's backing, on the
 * worker that fetches) and the LRU eviction that keeps the store within
 * --memory-budget. Only archived versions are ever evicted, so an eviction
 * loses nothing: the next query loads the version again. Threads: the build
 * workers (stores, loads), the writer thread, the LCM thread (the backing's
 * catalog look-ups and listings, the heartbeat's stats). */
#include "archiver.h"

#include <inttypes.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "log.h"
#include "meshtopo/archive.h"

/* One archived version. */
typedef struct cat_entry {
    char *id;
    char *source;
    uint32_t version;
    int64_t utime;
    uint64_t content_hash;
    uint64_t file_bytes;
    int32_t num_verts, num_faces;
    int64_t num_defects;
    uint64_t last_used; /* the catalog's clock at the last query, 0 = never */
    bool resident;      /* believed to be in the store (eviction candidates) */
} cat_entry;

/* One built version waiting for the async writer. */
typedef struct write_job {
    struct write_job *next;
    mtd_mesh_entry *entry; /* a reference: the mesh, id, version, source */
    mt_face_list list;     /* a copy of the submitted face list */
} write_job;

struct mtd_archiver {
    mtd_store *store;         /* not owned */
    mtd_error_log *error_log; /* not owned */
    mt_archive *archive;      /* NULL without --archive */
    mtd_archive_mode mode;
    mt_archive_compression compression; /* --archive-compression, auto resolved */
    uint64_t budget;
    bool shared; /* --cluster: other members write the same directory */

    pthread_mutex_t lock; /* the catalog and the clock */
    cat_entry *entries;   /* [count], by id then version */
    size_t count, cap;
    uint64_t clock;
    uint64_t bytes; /* file_bytes of every entry */

    pthread_mutex_t queue_lock; /* the writer's queue */
    pthread_cond_t queue_filled, queue_drained;
    write_job *head, *tail;
    size_t queued, capacity;
    bool writer_started, writer_stop;
    pthread_t writer;

    atomic_int_fast64_t writes, errors, loads, evictions;
};

/* Logs and counts an archive error that a reply to its requester reports
 * (and notes in the error log). */
static void count_error(mtd_archiver *a, const char *what, const char *message)
{
    mtd_log(MTD_LOG_ERROR, what, "error=%s", message);
    atomic_fetch_add(&a->errors, 1);
}

/* count_error, for an archive error nobody is answered about: noted in the
 * error log for the heartbeat. */
static void note_error(mtd_archiver *a, const char *what, const char *message)
{
    count_error(a, what, message);
    char text[MTD_ERROR_MAX];
    snprintf(text, sizeof text, "%.40s: %.400s", what, message);
    mtd_error_log_note(a->error_log, text);
}

/* ---- the catalog (caller holds a->lock) ----------------------------------- */

static int cat_cmp(const cat_entry *e, const char *id, uint32_t version)
{
    int c = strcmp(e->id, id);
    if (c) return c;
    return e->version < version ? -1 : e->version > version;
}

/* Index of the first entry >= (id, version); *out_found when equal. */
static size_t cat_lower_bound(const mtd_archiver *a, const char *id, uint32_t version,
                              bool *out_found)
{
    size_t lo = 0, hi = a->count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (cat_cmp(&a->entries[mid], id, version) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    *out_found = lo < a->count && cat_cmp(&a->entries[lo], id, version) == 0;
    return lo;
}

static cat_entry *cat_find(mtd_archiver *a, const char *id, uint32_t version)
{
    bool found;
    size_t at = cat_lower_bound(a, id, version, &found);
    return found ? &a->entries[at] : NULL;
}

/* The highest archived version of id, 0 if none. */
/* Drops version `version` of id from the catalog, if there (takes the lock). */
static void cat_remove(mtd_archiver *a, const char *id, uint32_t version)
{
    pthread_mutex_lock(&a->lock);
    bool found;
    size_t at = cat_lower_bound(a, id, version, &found);
    if (found) {
        a->bytes -= a->entries[at].file_bytes;
        free(a->entries[at].id);
        free(a->entries[at].source);
        memmove(&a->entries[at], &a->entries[at + 1], (a->count - at - 1) * sizeof(cat_entry));
        a->count--;
    }
    pthread_mutex_unlock(&a->lock);
}

static uint32_t cat_highest(const mtd_archiver *a, const char *id)
{
    bool found;
    size_t at = cat_lower_bound(a, id, UINT32_MAX, &found);
    if (found) return UINT32_MAX;
    return at > 0 && strcmp(a->entries[at - 1].id, id) == 0 ? a->entries[at - 1].version : 0;
}

/* Inserts a copy of *e (strings duplicated). false when out of memory. */
static bool cat_insert(mtd_archiver *a, const cat_entry *e)
{
    bool found;
    size_t at = cat_lower_bound(a, e->id, e->version, &found);
    if (found) return true;
    if (a->count == a->cap) {
        size_t cap = a->cap ? 2 * a->cap : 64;
        if (cap > SIZE_MAX / sizeof(cat_entry)) return false;
        cat_entry *grown = realloc(a->entries, cap * sizeof *grown);
        if (!grown) return false;
        a->entries = grown;
        a->cap = cap;
    }
    cat_entry copy = *e;
    copy.id = strdup(e->id);
    copy.source = strdup(e->source ? e->source : "");
    if (!copy.id || !copy.source) {
        free(copy.id);
        free(copy.source);
        return false;
    }
    memmove(&a->entries[at + 1], &a->entries[at], (a->count - at) * sizeof(cat_entry));
    a->entries[at] = copy;
    a->count++;
    a->bytes += e->file_bytes;
    return true;
}

/* ---- eviction ------------------------------------------------------------ */

/* Drops the least recently used resident archived versions from the store
 * until it holds no more than the budget. */
static void enforce_budget(mtd_archiver *a)
{
    if (!a->budget) return;
    for (;;) {
        mtd_store_totals totals;
        mtd_store_get_totals(a->store, &totals);
        if (totals.memory_bytes <= a->budget) return;
        char id[MESHTOPO_MESH_T_MESH_ID_MAX + 1];
        uint32_t version = 0;
        pthread_mutex_lock(&a->lock);
        cat_entry *victim = NULL;
        for (size_t i = 0; i < a->count; i++)
            if (a->entries[i].resident && (!victim || a->entries[i].last_used < victim->last_used))
                victim = &a->entries[i];
        if (victim) {
            victim->resident = false;
            snprintf(id, sizeof id, "%s", victim->id);
            version = victim->version;
        }
        pthread_mutex_unlock(&a->lock);
        if (!victim) return; /* nothing archived is in memory: the rest stays */
        if (mtd_store_remove(a->store, id, version, NULL) == MT_OK) {
            atomic_fetch_add(&a->evictions, 1);
            mtd_log(MTD_LOG_DEBUG, "evicted", "mesh_id=%s version=%" PRIu32, id, version);
        }
    }
}

/* Marks (id, version) as just used and in memory. */
static void touch(mtd_archiver *a, const char *id, uint32_t version)
{
    pthread_mutex_lock(&a->lock);
    cat_entry *e = cat_find(a, id, version);
    if (e) {
        e->last_used = ++a->clock;
        e->resident = true;
    }
    pthread_mutex_unlock(&a->lock);
}

/* ---- writing ------------------------------------------------------------- */

/* Version numbers tried when the archive's names for them are taken. */
#define NAME_TAKEN_ATTEMPTS 8
/* In a shared directory: version numbers tried when other members take
 * them first (each loss means another member just wrote this id). */
#define SHARED_TAKEN_ATTEMPTS 64

/* Archives one stored version and adds it to the catalog. */
static mt_status write_version(mtd_archiver *a, const mtd_mesh_info *info, const mt_face_list *list,
                               const mt_mesh *mesh, bool resident, mt_diag *diag)
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
    cat_entry e = {.id = (char *)info->id,
                   .source = (char *)info->source,
                   .version = info->version,
                   .utime = info->utime,
                   .content_hash = info->content_hash,
                   .file_bytes = stats.file_bytes,
                   .num_verts = (int32_t)mt_mesh_num_verts(mesh),
                   .num_faces = (int32_t)mt_mesh_num_faces(mesh),
                   .num_defects = (int64_t)mt_mesh_report(mesh)->num_defects,
                   .resident = resident};
    pthread_mutex_lock(&a->lock);
    e.last_used = ++a->clock;
    bool ok = cat_insert(a, &e);
    pthread_mutex_unlock(&a->lock);
    if (!ok) mtd_log(MTD_LOG_WARN, "archived", "out of memory cataloguing %s", info->id);
    return MT_OK;
}

static void *writer_main(void *arg)
{
    mtd_archiver *a = arg;
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
        if (write_version(a, info, &job->list, mtd_entry_mesh(job->entry), true, &diag) != MT_OK) {
            char text[MTD_ERROR_MAX];
            snprintf(text, sizeof text, "mesh '%.255s' version %" PRIu32 ": %.200s", info->id,
                     info->version, diag.message);
            note_error(a, "archive_write", text);
        }
        mtd_entry_release(job->entry);
        mt_face_list_free(&job->list);
        free(job);
        pthread_mutex_lock(&a->queue_lock);
        a->queued--;
        pthread_cond_broadcast(&a->queue_drained);
        pthread_mutex_unlock(&a->queue_lock);
        enforce_budget(a);
    }
}

/* Queues a stored version for the writer, waiting for room. */
static mt_status enqueue_write(mtd_archiver *a, mtd_mesh_entry *entry, const mt_face_list *list,
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

/* The next version number of id in a directory other members write too:
 * one above every version there and every one catalogued (the archive's
 * link decides between members that pick the same). */
static mt_status shared_next_version(mtd_archiver *a, const char *id, uint32_t *out_version,
                                     mt_diag *diag)
{
    uint32_t highest = 0;
    mt_status s = mt_archive_highest_version(a->archive, id, &highest, diag);
    if (s != MT_OK) return s;
    pthread_mutex_lock(&a->lock);
    uint32_t catalogued = cat_highest(a, id);
    pthread_mutex_unlock(&a->lock);
    if (catalogued > highest) highest = catalogued;
    if (highest == UINT32_MAX)
        return mt_diag_set(diag, MT_ERR_TOO_LARGE, "mesh '%s' has used every version number", id);
    *out_version = highest + 1;
    return mtd_store_reserve_version(a->store, id, *out_version, NULL, diag);
}

/* Archives a built version under the next number free in a shared
 * directory: numbers other members took meanwhile are skipped. MT_OK with
 * meta->version set, or the last write's failure. */
static mt_status write_shared(mtd_archiver *a, const meshtopo_mesh_t *m, const mt_face_list *list,
                              const mt_mesh *mesh, mtd_mesh_meta *meta, mt_diag *diag)
{
    mt_status s = MT_OK;
    for (int attempt = 0; attempt < SHARED_TAKEN_ATTEMPTS; attempt++) {
        s = shared_next_version(a, m->mesh_id, &meta->version, diag);
        if (s != MT_OK) return s;
        mtd_mesh_info info = {.id = m->mesh_id,
                              .version = meta->version,
                              .source = m->source,
                              .utime = m->utime,
                              .content_hash = meta->content_hash};
        s = write_version(a, &info, list, mesh, false, diag);
        if (s != MT_ERR_INVALID_ARG) return s;
        mtd_log(MTD_LOG_INFO, "archive_version_taken", "mesh_id=%s version=%" PRIu32 ": %s",
                m->mesh_id, meta->version, diag->message);
    }
    return s;
}

int32_t mtd_archiver_store(mtd_archiver *a, const meshtopo_mesh_t *m, const mt_face_list *list,
                           mt_mesh *mesh, uint64_t content_hash, uint32_t *out_version,
                           mtd_mesh_entry **out_entry, char *error, size_t size)
{
    mtd_mesh_meta meta = {.source = m->source, .utime = m->utime, .content_hash = content_hash};
    mt_diag diag;
    bool sync = a->archive && a->mode == MTD_ARCHIVE_SYNC;
    if (sync && a->shared) {
        mt_status s = write_shared(a, m, list, mesh, &meta, &diag);
        meta.reserved = true;
        if (s != MT_OK) {
            snprintf(error, size, "not archived, so not stored: %.400s", diag.message);
            count_error(a, "archive_write", error);
            return s == MT_ERR_TOO_LARGE ? MESHTOPO_STATUS_CODE_T_TOO_LARGE
                                         : MESHTOPO_STATUS_CODE_T_ARCHIVE_FAILED;
        }
    } else if (sync) {
        /* Write first, under a reserved number: the store sees the version
         * only once it is durable. A failed write leaves a gap; a number
         * whose name is taken in the directory (a file the catalog could
         * not read, or something planted there) is skipped. */
        mt_status s = MT_OK;
        for (int attempt = 0; attempt < NAME_TAKEN_ATTEMPTS; attempt++) {
            s = mtd_store_reserve_version(a->store, m->mesh_id, 0, &meta.version, &diag);
            if (s != MT_OK) {
                snprintf(error, size, "not stored: %.400s", diag.message);
                return s == MT_ERR_TOO_LARGE ? MESHTOPO_STATUS_CODE_T_TOO_LARGE
                                             : MESHTOPO_STATUS_CODE_T_INTERNAL;
            }
            mtd_mesh_info info = {.id = m->mesh_id,
                                  .version = meta.version,
                                  .source = m->source,
                                  .utime = m->utime,
                                  .content_hash = content_hash};
            s = write_version(a, &info, list, mesh, false, &diag);
            if (s != MT_ERR_INVALID_ARG) break;
            note_error(a, "archive_name_taken", diag.message);
        }
        meta.reserved = true;
        if (s != MT_OK) {
            snprintf(error, size, "not archived, so not stored: %.400s", diag.message);
            count_error(a, "archive_write", error);
            return MESHTOPO_STATUS_CODE_T_ARCHIVE_FAILED;
        }
    }
    mt_status s = mtd_store_add(a->store, m->mesh_id, mesh, &meta, out_version, out_entry, &diag);
    if (s != MT_OK) {
        snprintf(error, size, "not stored: %.400s", diag.message);
        if (sync) {
            /* Not acknowledged, so not kept: a restart must not serve it. */
            mt_diag ignored;
            mt_archive_remove(a->archive, m->mesh_id, meta.version, &ignored);
            cat_remove(a, m->mesh_id, meta.version);
        }
        return s == MT_ERR_TOO_LARGE ? MESHTOPO_STATUS_CODE_T_TOO_LARGE
                                     : MESHTOPO_STATUS_CODE_T_INTERNAL;
    }
    if (sync) touch(a, m->mesh_id, *out_version);
    if (a->archive && a->mode == MTD_ARCHIVE_ASYNC &&
        enqueue_write(a, *out_entry, list, &diag) != MT_OK) {
        char text[MTD_ERROR_MAX];
        snprintf(text, sizeof text, "mesh '%.255s' version %" PRIu32 " not queued: out of memory",
                 m->mesh_id, *out_version);
        note_error(a, "archive_write", text);
    }
    enforce_budget(a);
    return MESHTOPO_STATUS_CODE_T_OK;
}

/* ---- loading ------------------------------------------------------------- */

/* A file that can serve nothing (its face list does not match its content
 * hash, or cannot be read): renamed out of the way, kept for inspection,
 * and no longer catalogued, so that the daemon and `archive verify` agree
 * and nobody is served it. diag (the load's) gets the new name added. */
static void set_aside(mtd_archiver *a, const char *id, uint32_t version, mt_diag *diag)
{
    char file[MT_ARCHIVE_FILE_NAME_MAX + 1], aside[MT_ARCHIVE_FILE_NAME_MAX + 64];
    mt_diag aside_diag;
    if (mt_archive_file_find(a->archive, id, version, file, sizeof file, NULL) != MT_OK) return;
    if (mt_archive_set_aside(a->archive, file, aside, sizeof aside, &aside_diag) != MT_OK) {
        note_error(a, "archive_set_aside", aside_diag.message);
        return;
    }
    cat_remove(a, id, version);
    size_t n = strlen(diag->message);
    snprintf(diag->message + n, sizeof diag->message - n, " (set aside as %s)", aside);
}

/* Loads version `version` of id into the store (reserved: its number was
 * handed out before). MT_OK also when it is there already. */
static mt_status load_version(mtd_archiver *a, const char *id, uint32_t version, mt_diag *diag)
{
    mtd_mesh_entry *held = NULL;
    if (mtd_store_acquire(a->store, id, version, &held, NULL) == MT_OK) {
        mtd_entry_release(held);
        return MT_OK;
    }
    /* The stored half-edge arrays, validated, without a rebuild; a file
     * without them (or with damaged ones) is rebuilt from its face list. */
    mt_archive_record record;
    mt_mesh *mesh = NULL;
    mt_archive_load_info info;
    mt_status s = mt_archive_load_mesh(a->archive, id, version, false, &record, &mesh, &info, diag);
    if (s != MT_OK) {
        if (info.fault == MT_ARCHIVE_FAULT_CONTENT) set_aside(a, id, version, diag);
        return s;
    }
    if (info.fault == MT_ARCHIVE_FAULT_DERIVED) {
        char text[MTD_ERROR_MAX];
        snprintf(text, sizeof text,
                 "mesh '%.200s' version %" PRIu32
                 ": stored arrays damaged, rebuilt from its "
                 "intact face list: %.200s",
                 id, version, info.fallback.message);
        note_error(a, "archive_rebuilt", text);
    }
    mtd_mesh_meta meta = {.source = record.source,
                          .utime = record.utime,
                          .content_hash = record.content_hash,
                          .version = version,
                          .reserved = true};
    s = mtd_store_add(a->store, id, mesh, &meta, NULL, NULL, diag);
    if (s != MT_OK) {
        mt_mesh_destroy(mesh);
        /* A concurrent load of the same version got there first. */
        if (mtd_store_acquire(a->store, id, version, &held, NULL) == MT_OK) {
            mtd_entry_release(held);
            s = MT_OK;
        }
    } else {
        atomic_fetch_add(&a->loads, 1);
        mtd_log(MTD_LOG_DEBUG, "loaded", "mesh_id=%s version=%" PRIu32, id, version);
    }
    mt_archive_record_free(&record);
    return s;
}

/* ---- the store's backing ------------------------------------------------ */

static uint32_t backing_highest(void *ctx, const char *id)
{
    mtd_archiver *a = ctx;
    pthread_mutex_lock(&a->lock);
    uint32_t highest = cat_highest(a, id);
    pthread_mutex_unlock(&a->lock);
    return highest;
}

static bool backing_keeps(void *ctx, const char *id, uint32_t version)
{
    mtd_archiver *a = ctx;
    pthread_mutex_lock(&a->lock);
    bool archived = cat_find(a, id, version) != NULL;
    pthread_mutex_unlock(&a->lock);
    return archived;
}

static mt_status backing_load(void *ctx, const char *id, uint32_t version, mt_diag *diag)
{
    mtd_archiver *a = ctx;
    mt_status s = load_version(a, id, version, diag);
    if (s != MT_OK) {
        /* The query that asked is answered with this text (ARCHIVE_FAILED). */
        char text[MTD_ERROR_MAX];
        snprintf(text, sizeof text, "mesh '%.200s' version %" PRIu32 " cannot be loaded: %.250s",
                 id, version, diag->message);
        count_error(a, "archive_load", text);
        snprintf(diag->message, sizeof diag->message, "%s", text);
        return s;
    }
    enforce_budget(a);
    return MT_OK;
}

static void backing_fetched(void *ctx, const char *id, uint32_t version)
{
    touch(ctx, id, version);
}

/* ---- listing and stats --------------------------------------------------- */

/* One row of the merged listing. */
typedef struct list_row {
    const char *id;
    mtd_mesh_info info;
} list_row;

static int row_cmp(const void *pa, const void *pb)
{
    const list_row *x = pa, *y = pb;
    int c = strcmp(x->id, y->id);
    if (c) return c;
    return x->info.version < y->info.version ? -1 : x->info.version > y->info.version;
}

static mt_status backing_list(void *ctx, const mtd_store_listing *held,
                              mtd_store_listing **out_listing)
{
    mtd_archiver *a = ctx;
    *out_listing = NULL;
    pthread_mutex_lock(&a->lock);
    size_t n = held->totals.versions + a->count;
    list_row *rows = calloc(n + 1, sizeof *rows);
    if (!rows) {
        pthread_mutex_unlock(&a->lock);
        return MT_ERR_NOMEM;
    }
    size_t k = 0;
    for (size_t i = 0; i < held->num_ids; i++)
        for (uint32_t v = 0; v < held->ids[i].num_versions; v++)
            rows[k++] = (list_row){held->ids[i].id, held->ids[i].versions[v]};
    for (size_t i = 0; i < a->count; i++) {
        const cat_entry *e = &a->entries[i];
        rows[k++] = (list_row){e->id,
                               {.id = e->id,
                                .version = e->version,
                                .source = e->source,
                                .utime = e->utime,
                                .content_hash = e->content_hash,
                                .num_verts = (uint32_t)e->num_verts,
                                .num_faces = (uint32_t)e->num_faces,
                                .num_defects = (uint64_t)e->num_defects}};
    }
    /* Stable order with held rows first among equals is not needed: keep the
     * held row (it has memory_bytes) by preferring a non-zero memory_bytes. */
    qsort(rows, k, sizeof *rows, row_cmp);
    size_t m = 0, ids = 0, bytes = sizeof(mtd_store_listing);
    for (size_t i = 0; i < k; i++) {
        if (m > 0 && row_cmp(&rows[m - 1], &rows[i]) == 0) {
            if (rows[i].info.memory_bytes) rows[m - 1] = rows[i];
            continue;
        }
        if (m == 0 || strcmp(rows[m - 1].id, rows[i].id) != 0) {
            ids++;
            bytes += strlen(rows[i].id) + 1;
        }
        bytes += strlen(rows[i].info.source) + 1;
        rows[m++] = rows[i];
    }
    bytes += ids * sizeof(mtd_listed_id) + m * sizeof(mtd_mesh_info);
    mtd_store_listing *out = malloc(bytes);
    if (out) {
        out->num_ids = ids;
        out->ids = (mtd_listed_id *)(out + 1);
        out->totals = held->totals;
        mtd_mesh_info *info = (mtd_mesh_info *)(out->ids + ids);
        char *text = (char *)(info + m);
        size_t row = SIZE_MAX;
        const char *id = NULL;
        for (size_t i = 0; i < m; i++) {
            if (!id || strcmp(id, rows[i].id) != 0) {
                size_t len = strlen(rows[i].id) + 1;
                memcpy(text, rows[i].id, len);
                id = text;
                text += len;
                row = row == SIZE_MAX ? 0 : row + 1;
                out->ids[row] = (mtd_listed_id){id, 0, info};
            }
            *info = rows[i].info;
            info->id = id;
            size_t len = strlen(rows[i].info.source) + 1;
            memcpy(text, rows[i].info.source, len);
            info->source = text;
            text += len;
            info++;
            out->ids[row].num_versions++;
        }
    }
    pthread_mutex_unlock(&a->lock);
    free(rows);
    if (!out) return MT_ERR_NOMEM;
    *out_listing = out;
    return MT_OK;
}

uint64_t mtd_archiver_bytes(mtd_archiver *a)
{
    if (!a->archive) return 0;
    pthread_mutex_lock(&a->lock);
    uint64_t bytes = a->bytes;
    pthread_mutex_unlock(&a->lock);
    return bytes;
}

void mtd_archiver_stats(mtd_archiver *a, meshtopo_status_t *st)
{
    st->memory_budget = (int64_t)a->budget;
    if (!a->archive) return;
    pthread_mutex_lock(&a->lock);
    st->archive_versions = (int32_t)a->count;
    st->archive_bytes = (int64_t)a->bytes;
    pthread_mutex_unlock(&a->lock);
    pthread_mutex_lock(&a->queue_lock);
    st->archive_backlog = (int32_t)a->queued;
    pthread_mutex_unlock(&a->queue_lock);
    st->archive_writes = atomic_load(&a->writes);
    st->archive_errors = atomic_load(&a->errors);
    st->archive_loads = atomic_load(&a->loads);
    st->archive_evictions = atomic_load(&a->evictions);
}

/* ---- what other members wrote --------------------------------------------- */

/* The file names of the catalog without their suffix ("<stem>.v<N>"),
 * sorted, for the rescan's filter: a file is known whichever suffix it has
 * (".hdf", or ".vtkhdf" as earlier versions wrote). */
typedef struct known_names {
    char (*names)[MT_ARCHIVE_FILE_NAME_MAX + 1];
    size_t count;
} known_names;

static int name_cmp(const void *x, const void *y)
{
    return strcmp(x, y);
}

/* name without its last ".suffix", into out (MT_ARCHIVE_FILE_NAME_MAX + 1 bytes). */
static void name_stem(const char *name, char *out)
{
    const char *dot = strrchr(name, '.');
    size_t len = dot ? (size_t)(dot - name) : strlen(name);
    if (len > MT_ARCHIVE_FILE_NAME_MAX) len = MT_ARCHIVE_FILE_NAME_MAX;
    memcpy(out, name, len);
    out[len] = '\0';
}

static bool not_known(void *ctx, const char *file_name)
{
    const known_names *k = ctx;
    char stem[MT_ARCHIVE_FILE_NAME_MAX + 1];
    name_stem(file_name, stem);
    return !k->count || !bsearch(stem, k->names, k->count, sizeof *k->names, name_cmp);
}

/* Adds a readable listed file to the catalog and reserves its number in
 * the store. false when out of memory. */
static bool catalog_entry(mtd_archiver *a, const mt_archive_entry *e)
{
    cat_entry ce = {.id = e->mesh_id,
                    .source = e->source,
                    .version = e->version,
                    .utime = e->utime,
                    .content_hash = e->content_hash,
                    .file_bytes = e->file_bytes,
                    .num_verts = (int32_t)e->summary.num_verts,
                    .num_faces = (int32_t)e->summary.num_faces,
                    .num_defects = (int64_t)e->summary.num_defects};
    pthread_mutex_lock(&a->lock);
    bool ok = cat_insert(a, &ce);
    pthread_mutex_unlock(&a->lock);
    return ok && mtd_store_reserve_version(a->store, e->mesh_id, e->version, NULL, NULL) == MT_OK;
}

/* Adds readable entries of a listing to the catalog; returns how many were
 * added. Unreadable ones are counted in *out_bad and noted when `note` is
 * set. */
static size_t catalog_listing(mtd_archiver *a, const mt_archive_listing *listing, bool note,
                              size_t *out_bad)
{
    size_t added = 0;
    for (size_t i = 0; i < listing->count; i++) {
        const mt_archive_entry *e = &listing->entries[i];
        if (e->status != MT_OK) {
            (*out_bad)++;
            if (note) {
                char text[MTD_ERROR_MAX];
                snprintf(text, sizeof text, "%.440s (%s)", e->diag.message,
                         mt_archive_fault_name(e->fault));
                note_error(a, "archive_list", text);
            }
            continue;
        }
        if (!catalog_entry(a, e)) break; /* out of memory: the next rescan tries again */
        added++;
    }
    return added;
}

bool mtd_archiver_learn(mtd_archiver *a, const char *id, uint32_t version)
{
    if (!a->archive) return false;
    pthread_mutex_lock(&a->lock);
    bool known = cat_find(a, id, version) != NULL;
    pthread_mutex_unlock(&a->lock);
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    if (known || mt_archive_file_find(a->archive, id, version, name, sizeof name, NULL) != MT_OK)
        return false;
    mt_archive_entry e;
    mt_diag diag;
    bool added = mt_archive_list_file(a->archive, name, &e, &diag) == MT_OK &&
                 strcmp(e.mesh_id, id) == 0 && e.version == version && catalog_entry(a, &e);
    mt_archive_entry_free(&e);
    if (added)
        mtd_log(MTD_LOG_DEBUG, "archive_learned", "mesh_id=%s version=%" PRIu32, id, version);
    return added;
}

size_t mtd_archiver_rescan(mtd_archiver *a)
{
    if (!a->archive) return 0;
    known_names known = {NULL, 0};
    pthread_mutex_lock(&a->lock);
    const size_t catalogued = a->count;
    known.names = catalogued ? malloc(catalogued * sizeof *known.names) : NULL;
    for (size_t i = 0; known.names && i < catalogued; i++) {
        char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
        mt_archive_file_name(a->entries[i].id, a->entries[i].version, name, sizeof name);
        name_stem(name, known.names[known.count++]);
    }
    pthread_mutex_unlock(&a->lock);
    if (catalogued && !known.names) return 0;
    if (known.count) qsort(known.names, known.count, sizeof *known.names, name_cmp);
    mt_archive_listing listing;
    mt_diag diag;
    size_t added = 0, bad = 0;
    if (mt_archive_list_filtered(a->archive, not_known, &known, &listing, &diag) != MT_OK) {
        note_error(a, "archive_rescan", diag.message);
    } else {
        added = catalog_listing(a, &listing, false, &bad);
        mt_archive_listing_free(&listing);
    }
    free(known.names);
    mtd_log(MTD_LOG_INFO, "archive_rescan", "new_versions=%zu unreadable=%zu", added, bad);
    return added;
}

/* ---- open and close ------------------------------------------------------ */

/* Lists the archive into the catalog, reserves every archived version number
 * in the store, preloads when asked and starts the async writer. */
static mt_status open_archive(mtd_archiver *a, const mtd_config *c, mt_diag *diag)
{
    mt_archive_options options = {.create = a->mode != MTD_ARCHIVE_OFF,
                                  .read_only = a->mode == MTD_ARCHIVE_OFF};
    mt_status s = mt_archive_open(c->archive_dir, &options, &a->archive, diag);
    if (s != MT_OK) return s;
    /* Loads check each face list against the hash it was acknowledged with. */
    mt_archive_set_content_hash(a->archive, mt_archive_content_hash, NULL);
    mt_archive_listing listing;
    s = mt_archive_list(a->archive, &listing, diag);
    if (s != MT_OK) return s;
    size_t bad = 0, listed = listing.count;
    size_t added = catalog_listing(a, &listing, true, &bad);
    mt_archive_listing_free(&listing);
    if (added + bad < listed)
        return mt_diag_set(diag, MT_ERR_NOMEM, "out of memory cataloguing %s", c->archive_dir);
    mtd_log(MTD_LOG_INFO, "archive",
            "dir=%s mode=%s versions=%zu unreadable=%zu leftovers_removed=%zu bytes=%" PRIu64,
            c->archive_dir, mtd_archive_mode_name(a->mode), a->count, bad,
            mt_archive_leftovers_removed(a->archive), a->bytes);
    if (c->preload) {
        size_t loaded = 0;
        for (size_t i = 0; i < a->count; i++) {
            mtd_store_totals totals;
            mtd_store_get_totals(a->store, &totals);
            if (a->budget && totals.memory_bytes >= a->budget) break;
            mt_diag load_diag;
            if (load_version(a, a->entries[i].id, a->entries[i].version, &load_diag) != MT_OK) {
                note_error(a, "archive_load", load_diag.message);
                continue;
            }
            touch(a, a->entries[i].id, a->entries[i].version);
            loaded++;
        }
        enforce_budget(a);
        mtd_log(MTD_LOG_INFO, "preload", "loaded=%zu of %zu", loaded, a->count);
    }
    mtd_store_backing backing = {.ctx = a,
                                 .highest = backing_highest,
                                 .keeps = backing_keeps,
                                 .load = backing_load,
                                 .fetched = backing_fetched,
                                 .list = backing_list};
    mtd_store_set_backing(a->store, &backing);
    if (a->mode == MTD_ARCHIVE_ASYNC) {
        if (pthread_create(&a->writer, NULL, writer_main, a) != 0) return MT_ERR_NOMEM;
        a->writer_started = true;
    }
    return MT_OK;
}

/* The archive files' compression (--archive-compression). LZ4 without
 * the Blosc filter plugin is an error: the daemon does not start rather
 * than write something other than asked. */
static mt_status choose_compression(mtd_archiver *a, mtd_archive_compression asked, mt_diag *diag)
{
    static const mt_archive_compression stored[] = {
        MT_ARCHIVE_COMPRESSION_NONE, MT_ARCHIVE_COMPRESSION_DEFLATE, MT_ARCHIVE_COMPRESSION_LZ4};
    if ((unsigned)asked > MTD_COMPRESSION_LZ4)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "unknown archive compression %d", (int)asked);
    if (asked == MTD_COMPRESSION_LZ4 && !mt_archive_lz4_available())
        return mt_diag_set(diag, MT_ERR_UNSUPPORTED,
                           "--archive-compression lz4: HDF5 finds no Blosc filter plugin "
                           "(Debian: hdf5-filter-plugin-blosc-serial; or HDF5_PLUGIN_PATH)");
    a->compression = stored[asked];
    return MT_OK;
}

mt_status mtd_archiver_open(const mtd_config *config, mtd_store *store, mtd_error_log *errors,
                            mtd_archiver **out_archiver, mt_diag *diag)
{
    *out_archiver = NULL;
    mtd_archiver *a = calloc(1, sizeof *a);
    if (!a) return MT_ERR_NOMEM;
    a->store = store;
    a->error_log = errors;
    a->mode = config->archive_mode;
    a->budget = config->memory_budget;
    a->shared = config->cluster[0] != '\0';
    a->capacity = config->archive_queue ? config->archive_queue : 1;
    pthread_mutex_init(&a->lock, NULL);
    pthread_mutex_init(&a->queue_lock, NULL);
    pthread_cond_init(&a->queue_filled, NULL);
    pthread_cond_init(&a->queue_drained, NULL);
    if (!config->archive_dir[0]) {
        if (config->memory_budget)
            mtd_log(MTD_LOG_WARN, "archive",
                    "--memory-budget without --archive: nothing can be evicted");
    } else {
        mt_status s = choose_compression(a, config->archive_compression, diag);
        if (s == MT_OK) s = open_archive(a, config, diag);
        if (s != MT_OK) {
            mtd_archiver_destroy(a);
            return s;
        }
    }
    *out_archiver = a;
    return MT_OK;
}

void mtd_archiver_stop(mtd_archiver *a)
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

void mtd_archiver_destroy(mtd_archiver *a)
{
    if (!a) return;
    mtd_archiver_stop(a);
    for (write_job *job = a->head, *next; job; job = next) {
        next = job->next;
        mtd_entry_release(job->entry);
        mt_face_list_free(&job->list);
        free(job);
    }
    for (size_t i = 0; i < a->count; i++) {
        free(a->entries[i].id);
        free(a->entries[i].source);
    }
    free(a->entries);
    mt_archive_close(a->archive);
    pthread_cond_destroy(&a->queue_filled);
    pthread_cond_destroy(&a->queue_drained);
    pthread_mutex_destroy(&a->queue_lock);
    pthread_mutex_destroy(&a->lock);
    free(a);
}
