/* meshtopod's archive catalog (archive_catalog.h): a sorted array of the
 * archived versions by mesh id then version, behind one mutex, listed from
 * the directory at start and by rescans (names first, then the attributes of
 * the new files only). As the store's backing it answers look-ups from the
 * array and reads a version with meshtopo::archive (verified before it is
 * handed over; a file whose content fails its hash is set aside), counting
 * loads and errors for the heartbeat. Calls the archive library, the log and
 * the error log; never the store. */
#include "archive_catalog.h"

#include <inttypes.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"

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
} cat_entry;

struct mtd_catalog {
    mtd_error_log *error_log; /* not owned */
    mt_archive *archive;

    pthread_mutex_t lock; /* the catalog */
    cat_entry *entries;   /* [count], by id then version */
    size_t count, cap;
    uint64_t bytes; /* file_bytes of every entry */

    atomic_int_fast64_t errors, loads;
};

/* Logs and counts an archive error that a reply to its requester reports. */
static void count_error(mtd_catalog *a, const char *what, const char *message)
{
    mtd_log(MTD_LOG_ERROR, what, "error=%s", message);
    atomic_fetch_add(&a->errors, 1);
}

/* count_error, for an archive error nobody is answered about: noted in the
 * error log for the heartbeat. */
static void note_error(mtd_catalog *a, const char *what, const char *message)
{
    count_error(a, what, message);
    mtd_error_log_note_event(a->error_log, what, message);
}

/* ---- the catalog (caller holds a->lock unless said) ----------------------- */

static int cat_cmp(const cat_entry *e, const char *id, uint32_t version)
{
    int c = strcmp(e->id, id);
    if (c) return c;
    return e->version < version ? -1 : e->version > version;
}

/* Index of the first entry >= (id, version); *out_found when equal. */
static size_t cat_lower_bound(const mtd_catalog *a, const char *id, uint32_t version,
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

static cat_entry *cat_find(mtd_catalog *a, const char *id, uint32_t version)
{
    bool found;
    size_t at = cat_lower_bound(a, id, version, &found);
    return found ? &a->entries[at] : NULL;
}

/* Drops version `version` of id from the catalog, if there (takes the lock). */
static void cat_remove(mtd_catalog *a, const char *id, uint32_t version)
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

static uint32_t cat_highest(const mtd_catalog *a, const char *id)
{
    bool found;
    size_t at = cat_lower_bound(a, id, UINT32_MAX, &found);
    if (found) return UINT32_MAX;
    return at > 0 && strcmp(a->entries[at - 1].id, id) == 0 ? a->entries[at - 1].version : 0;
}

/* Inserts a copy of *e (strings duplicated). false when out of memory. */
static bool cat_insert(mtd_catalog *a, const cat_entry *e)
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

bool mtd_catalog_insert(mtd_catalog *a, const mtd_mesh_info *info, const mt_mesh *mesh,
                        uint64_t file_bytes)
{
    cat_entry e = {.id = (char *)info->id,
                   .source = (char *)info->source,
                   .version = info->version,
                   .utime = info->utime,
                   .content_hash = info->content_hash,
                   .file_bytes = file_bytes,
                   .num_verts = (int32_t)mt_mesh_num_verts(mesh),
                   .num_faces = (int32_t)mt_mesh_num_faces(mesh),
                   .num_defects = (int64_t)mt_mesh_report(mesh)->num_defects};
    pthread_mutex_lock(&a->lock);
    bool ok = cat_insert(a, &e);
    pthread_mutex_unlock(&a->lock);
    if (!ok) mtd_log(MTD_LOG_WARN, "archived", "out of memory cataloguing %s", info->id);
    return ok;
}

void mtd_catalog_remove(mtd_catalog *a, const char *id, uint32_t version)
{
    cat_remove(a, id, version);
}

uint32_t mtd_catalog_highest(mtd_catalog *a, const char *id)
{
    pthread_mutex_lock(&a->lock);
    uint32_t highest = cat_highest(a, id);
    pthread_mutex_unlock(&a->lock);
    return highest;
}

size_t mtd_catalog_count(mtd_catalog *a)
{
    pthread_mutex_lock(&a->lock);
    size_t n = a->count;
    pthread_mutex_unlock(&a->lock);
    return n;
}

mt_archive *mtd_catalog_archive(mtd_catalog *a)
{
    return a->archive;
}

/* ---- loading ------------------------------------------------------------- */

/* A file that can serve nothing (its face list does not match its content
 * hash, or cannot be read): renamed out of the way, kept for inspection,
 * and no longer catalogued, so that the daemon and `archive verify` agree
 * and nobody is served it. diag (the load's) gets the new name added. */
static void set_aside(mtd_catalog *a, const char *id, uint32_t version, mt_diag *diag)
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

/* A load that failed: the query that asked is answered with this text
 * (ARCHIVE_FAILED). */
static void load_failed(mtd_catalog *a, const char *id, uint32_t version, mt_diag *diag)
{
    char text[MTD_ERROR_MAX];
    snprintf(text, sizeof text, "mesh '%.200s' version %" PRIu32 " cannot be loaded: %.250s", id,
             version, diag->message);
    count_error(a, "archive_load", text);
    snprintf(diag->message, sizeof diag->message, "%s", text);
}

/* ---- the store's backing ------------------------------------------------ */

static uint32_t backing_highest(void *ctx, const char *id)
{
    return mtd_catalog_highest(ctx, id);
}

static bool backing_keeps(void *ctx, const char *id, uint32_t version)
{
    mtd_catalog *a = ctx;
    pthread_mutex_lock(&a->lock);
    bool archived = cat_find(a, id, version) != NULL;
    pthread_mutex_unlock(&a->lock);
    return archived;
}

/* Reads version `version` of id: the stored half-edge arrays, validated,
 * without a rebuild; a file without them (or with damaged ones) is rebuilt
 * from its face list. */
static mt_status backing_load(void *ctx, const char *id, uint32_t version, mt_mesh **out_mesh,
                              mtd_mesh_meta *out_meta, mt_diag *diag)
{
    mtd_catalog *a = ctx;
    *out_mesh = NULL;
    mt_archive_record record;
    mt_archive_load_info info;
    mt_mesh *mesh = NULL;
    mt_status s = mt_archive_load_mesh(a->archive, id, version, false, &record, &mesh, &info, diag);
    if (s != MT_OK) {
        if (info.fault == MT_ARCHIVE_FAULT_CONTENT) set_aside(a, id, version, diag);
        load_failed(a, id, version, diag);
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
    char *source = strdup(record.source ? record.source : "");
    if (!source) {
        mt_mesh_destroy(mesh);
        mt_archive_record_free(&record);
        mt_diag_set(diag, MT_ERR_NOMEM, "out of memory loading mesh '%s'", id);
        load_failed(a, id, version, diag);
        return MT_ERR_NOMEM;
    }
    out_meta->source = source;
    out_meta->utime = record.utime;
    out_meta->content_hash = record.content_hash;
    mt_archive_record_free(&record);
    *out_mesh = mesh;
    return MT_OK;
}

static void backing_loaded(void *ctx, const char *id, uint32_t version, mt_status status,
                           mt_diag *diag)
{
    mtd_catalog *a = ctx;
    if (status != MT_OK) {
        load_failed(a, id, version, diag);
        return;
    }
    atomic_fetch_add(&a->loads, 1);
    mtd_log(MTD_LOG_DEBUG, "loaded", "mesh_id=%s version=%" PRIu32, id, version);
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
    mtd_catalog *a = ctx;
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

void mtd_catalog_backing(mtd_catalog *a, mtd_store_backing *out)
{
    *out = (mtd_store_backing){.ctx = a,
                               .highest = backing_highest,
                               .keeps = backing_keeps,
                               .load = backing_load,
                               .loaded = backing_loaded,
                               .list = backing_list};
}

uint64_t mtd_catalog_bytes(mtd_catalog *a)
{
    if (!a) return 0;
    pthread_mutex_lock(&a->lock);
    uint64_t bytes = a->bytes;
    pthread_mutex_unlock(&a->lock);
    return bytes;
}

void mtd_catalog_stats(mtd_catalog *a, meshtopo_status_t *st)
{
    if (!a) return;
    pthread_mutex_lock(&a->lock);
    st->archive_versions = (int32_t)a->count;
    st->archive_bytes = (int64_t)a->bytes;
    pthread_mutex_unlock(&a->lock);
    st->archive_errors += atomic_load(&a->errors);
    st->archive_loads = atomic_load(&a->loads);
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

/* Adds a readable listed file to the catalog (the store numbers new
 * versions after it through the backing). false when out of memory. */
static bool catalog_entry(mtd_catalog *a, const mt_archive_entry *e)
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
    return ok;
}

/* Adds readable entries of a listing to the catalog; returns how many were
 * added. Unreadable ones are counted in *out_bad and noted when `note` is
 * set. */
static size_t catalog_listing(mtd_catalog *a, const mt_archive_listing *listing, bool note,
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

bool mtd_catalog_learn(mtd_catalog *a, const char *id, uint32_t version)
{
    if (!a) return false;
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

size_t mtd_catalog_rescan(mtd_catalog *a)
{
    if (!a) return 0;
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

mt_status mtd_catalog_open(const mtd_config *c, mtd_error_log *errors, mtd_catalog **out_catalog,
                           mt_diag *diag)
{
    *out_catalog = NULL;
    mtd_catalog *a = calloc(1, sizeof *a);
    if (!a) return MT_ERR_NOMEM;
    a->error_log = errors;
    pthread_mutex_init(&a->lock, NULL);
    atomic_init(&a->errors, 0);
    atomic_init(&a->loads, 0);
    mt_archive_options options = {.create = c->archive_mode != MTD_ARCHIVE_OFF,
                                  .read_only = c->archive_mode == MTD_ARCHIVE_OFF};
    mt_status s = mt_archive_open(c->archive_dir, &options, &a->archive, diag);
    if (s != MT_OK) {
        mtd_catalog_destroy(a);
        return s;
    }
    /* Loads check each face list against the hash it was acknowledged with. */
    mt_archive_set_content_hash(a->archive, mt_archive_content_hash, NULL);
    mt_archive_listing listing;
    s = mt_archive_list(a->archive, &listing, diag);
    if (s != MT_OK) {
        mtd_catalog_destroy(a);
        return s;
    }
    size_t bad = 0, listed = listing.count;
    size_t added = catalog_listing(a, &listing, true, &bad);
    mt_archive_listing_free(&listing);
    if (added + bad < listed) {
        mtd_catalog_destroy(a);
        return mt_diag_set(diag, MT_ERR_NOMEM, "out of memory cataloguing %s", c->archive_dir);
    }
    mtd_log(MTD_LOG_INFO, "archive",
            "dir=%s mode=%s versions=%zu unreadable=%zu leftovers_removed=%zu bytes=%" PRIu64,
            c->archive_dir, mtd_archive_mode_name(c->archive_mode), a->count, bad,
            mt_archive_leftovers_removed(a->archive), a->bytes);
    *out_catalog = a;
    return MT_OK;
}

void mtd_catalog_destroy(mtd_catalog *a)
{
    if (!a) return;
    for (size_t i = 0; i < a->count; i++) {
        free(a->entries[i].id);
        free(a->entries[i].source);
    }
    free(a->entries);
    mt_archive_close(a->archive);
    pthread_mutex_destroy(&a->lock);
    free(a);
}
