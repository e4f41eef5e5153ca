/* meshtopod's archive (--archive DIR): writes built meshes with
 * meshtopo::archive (sync: before the ack, on the build worker; async: after
 * it, by one background writer with a bounded queue), keeps a catalog of what
 * the archive holds so that restarts serve every archived version by id and
 * version (loaded on a worker on first query, or all at start with
 * --preload), and keeps the store within --memory-budget by dropping the
 * least recently queried archived versions. */
#ifndef MESHTOPOD_ARCHIVER_H
#define MESHTOPOD_ARCHIVER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "daemon.h"
#include "meshtopo/face_list.h"

/* Opens config.archive_dir into d->archiver (nothing when it is ""): lists
 * the archive (unreadable files are logged and counted, not fatal), reserves
 * every archived version number in the store so new versions continue after
 * them, preloads when asked and starts the async writer. MT_ERR_IO when the
 * directory cannot be opened or listed, with diag naming it. */
mt_status mtd_archiver_start(mtd_daemon *daemon, mt_diag *diag);

/* Lets the async writer empty its queue, then stops it. Call after the
 * worker pool has stopped (no build adds to the queue any more). Idempotent,
 * NULL-safe. */
void mtd_archiver_stop(mtd_daemon *daemon);

/* Stops and frees d->archiver. NULL-safe. */
void mtd_archiver_free(mtd_daemon *daemon);

/* Stores a freshly built mesh (of submission m, face list `list`, content
 * hash) as the next version of m->mesh_id, archiving it as the mode says.
 * Returns a status_code_t: OK (the store owns mesh; *out_version and
 * *out_entry, a reference to release, are set), or TOO_LARGE, INTERNAL or
 * ARCHIVE_FAILED with the reason in error[size] (the caller still owns mesh;
 * nothing is stored and, in sync mode, nothing stays archived). */
int32_t mtd_archiver_store(mtd_daemon *daemon, const meshtopo_mesh_t *m, const mt_face_list *list,
                           mt_mesh *mesh, uint64_t content_hash, uint32_t *out_version,
                           mtd_mesh_entry **out_entry, char *error, size_t size);

/* mtd_store_acquire for a query, archive aware: version 0 means the highest
 * version held or archived; a version archived but not in memory is loaded
 * on a worker, which then answers q by calling mtd_query_handle again:
 * *out_deferred is then true, nothing is acquired and the caller must not
 * answer. Marks the acquired version as recently used. Errors as
 * mtd_store_acquire. */
mt_status mtd_archiver_acquire(mtd_daemon *daemon, const meshtopo_query_t *q,
                               mtd_mesh_entry **out_entry, bool *out_deferred, mt_diag *diag);

/* mtd_store_list plus every archived version that is not in memory (with
 * memory_bytes 0). Free with mtd_store_listing_free. */
mt_status mtd_archiver_list(mtd_daemon *daemon, mtd_store_listing **out_listing);

/* Vertex, face and defect counts of an archived version from the catalog
 * (for LIST_MESHES rows not in memory). false when it is not archived. */
bool mtd_archiver_counts(mtd_daemon *daemon, const char *mesh_id, uint32_t version,
                         int32_t *out_verts, int32_t *out_faces, int64_t *out_defects);

/* Fills the heartbeat's archive_* fields and memory_budget. */
void mtd_archiver_stats(mtd_daemon *daemon, meshtopo_status_t *st);

#endif
