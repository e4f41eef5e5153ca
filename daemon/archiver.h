/* meshtopod's archive (--archive DIR): writes built meshes with
 * meshtopo::archive (sync: before the ack, on the build worker; async: after
 * it, by one background writer with a bounded queue), keeps a catalog of what
 * the archive holds and serves it as the store's backing (mtd_store_backing:
 * restarts serve every archived version by id and version, loaded on the
 * worker that fetches it, or all at start with --preload), and keeps the
 * store within --memory-budget by dropping the least recently queried
 * archived versions. In a cluster the directory is shared: a version's
 * number is one above the highest there, and the atomic link of the
 * archive decides between members that pick the same (the loser takes the
 * next); rescans catalog what the other members wrote. Without --archive it only adds built meshes
 * to the store. Calls down into the store only; nothing here answers requests. Threads: build
 * workers (stores, loads), the async writer, the LCM thread (catalog look-ups through the backing,
 * stats for the heartbeat). */
#ifndef MESHTOPOD_ARCHIVER_H
#define MESHTOPOD_ARCHIVER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "config.h"
#include "error_log.h"
#include "mesh_store.h"
#include "meshtopo/face_list.h"
#include "meshtopo/msgs.h"

typedef struct mtd_archiver mtd_archiver;

/* Opens config.archive_dir (nothing to open when it is ""): lists the archive
 * (unreadable files are logged and noted in `errors`, not fatal), reserves
 * every archived version number in `store` so new versions continue after
 * them, installs itself as the store's backing, preloads when asked and
 * starts the async writer. store and errors are not owned and must outlive
 * it. MT_ERR_IO when the directory cannot be opened or listed, with diag
 * naming it; MT_ERR_NOMEM. */
mt_status mtd_archiver_open(const mtd_config *config, mtd_store *store, mtd_error_log *errors,
                            mtd_archiver **out_archiver, mt_diag *diag);

/* Lets the async writer empty its queue, then stops it. Call after the
 * worker pool has stopped (no build adds to the queue any more). Idempotent,
 * NULL-safe. */
void mtd_archiver_stop(mtd_archiver *archiver);

/* Stops and frees the archiver. NULL-safe. */
void mtd_archiver_destroy(mtd_archiver *archiver);

/* Stores a freshly built mesh (of submission m, face list `list`, content
 * hash) as the next version of m->mesh_id, archiving it as the mode says.
 * Returns a status_code_t: OK (the store owns mesh; *out_version and
 * *out_entry, a reference to release, are set), or TOO_LARGE, INTERNAL or
 * ARCHIVE_FAILED with the reason in error[size] (the caller still owns mesh;
 * nothing is stored and, in sync mode, nothing stays archived). Build
 * workers. */
int32_t mtd_archiver_store(mtd_archiver *archiver, const meshtopo_mesh_t *m,
                           const mt_face_list *list, mt_mesh *mesh, uint64_t content_hash,
                           uint32_t *out_version, mtd_mesh_entry **out_entry, char *error,
                           size_t size);

/* Catalogs the archive's files it does not know yet: versions other members
 * of a cluster wrote into the shared directory, so that they are served
 * (loaded on their first query) and numbered after. Reads the directory's
 * names and the attributes of the new files only. Returns how many
 * versions were added. The daemon calls it when the cluster's view changes. */
size_t mtd_archiver_rescan(mtd_archiver *archiver);

/* Another member of the cluster announced version `version` of id (its
 * topology broadcast): catalogs that file when it is not known yet, so a
 * query of the id's latest version here sees it. Reads the one file's
 * attributes. Returns whether it was added (false also when the file is
 * not there or not that version: the next rescan looks again). */
bool mtd_archiver_learn(mtd_archiver *archiver, const char *id, uint32_t version);

/* Fills the heartbeat's archive_* fields and memory_budget. */
void mtd_archiver_stats(mtd_archiver *archiver, meshtopo_status_t *st);

/* Bytes of the archive's files (0 without an archive). */
uint64_t mtd_archiver_bytes(mtd_archiver *archiver);

#endif
