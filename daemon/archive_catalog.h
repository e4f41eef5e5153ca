/* meshtopod's archive catalog (--archive DIR): what the archive directory
 * holds (ids, versions, sources, counts, file sizes), listed at start,
 * extended by the writer's files and, in a cluster, by rescans and the
 * versions other members announce. It is the store's backing
 * (mtd_store_backing): the highest kept version of an id, whether a version
 * is kept, the listing merged with the store's, and the read of a version
 * (verified: content hash, half-edge arrays; a file that serves nothing is
 * set aside) that the store then adds. It never calls the store. Threads:
 * workers (loads), the writer, the LCM thread (look-ups, rescans, stats). */
#ifndef MESHTOPOD_ARCHIVE_CATALOG_H
#define MESHTOPOD_ARCHIVE_CATALOG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "config.h"
#include "error_log.h"
#include "mesh_store.h"
#include "meshtopo/archive.h"
#include "meshtopo/msgs.h"

typedef struct mtd_catalog mtd_catalog;

/* Opens config->archive_dir (created when missing unless --archive-mode
 * off, which opens it read-only) and lists it: unreadable files are logged
 * and noted in `errors` (not owned, must outlive it), not fatal. MT_ERR_IO
 * when the directory cannot be opened or listed, with diag naming it;
 * MT_ERR_NOMEM. */
mt_status mtd_catalog_open(const mtd_config *config, mtd_error_log *errors,
                           mtd_catalog **out_catalog, mt_diag *diag);

/* Closes the archive and frees the catalog. NULL-safe. */
void mtd_catalog_destroy(mtd_catalog *catalog);

/* The open archive (owned by the catalog), for the writer. */
mt_archive *mtd_catalog_archive(mtd_catalog *catalog);

/* The catalog as the store's backing (*out, its ctx the catalog). */
void mtd_catalog_backing(mtd_catalog *catalog, mtd_store_backing *out_backing);

/* Catalogs a version just written to a file of file_bytes bytes. false when
 * out of memory (logged; the file stays, the next start lists it). */
bool mtd_catalog_insert(mtd_catalog *catalog, const mtd_mesh_info *info, const mt_mesh *mesh,
                        uint64_t file_bytes);

/* Drops (id, version) from the catalog, if there. */
void mtd_catalog_remove(mtd_catalog *catalog, const char *id, uint32_t version);

/* The highest catalogued version of id, 0 if none. */
uint32_t mtd_catalog_highest(mtd_catalog *catalog, const char *id);

/* Catalogs the archive's files it does not know yet: versions other members
 * of a cluster wrote into the shared directory, so that they are served
 * (loaded on their first query) and numbered after. Reads the directory's
 * names and the attributes of the new files only. Returns how many
 * versions were added (0 for a NULL catalog). The daemon calls it when the
 * cluster's view changes. */
size_t mtd_catalog_rescan(mtd_catalog *catalog);

/* Another member of the cluster announced version `version` of id (its
 * topology broadcast): catalogs that file when it is not known yet, so a
 * query of the id's latest version here sees it. Reads the one file's
 * attributes. Returns whether it was added (false also when the file is
 * not there or not that version, or without a catalog: the next rescan
 * looks again). */
bool mtd_catalog_learn(mtd_catalog *catalog, const char *id, uint32_t version);

/* Versions catalogued. */
size_t mtd_catalog_count(mtd_catalog *catalog);

/* Bytes of the archive's files (0 for a NULL catalog). */
uint64_t mtd_catalog_bytes(mtd_catalog *catalog);

/* Fills the heartbeat's archive_versions, archive_bytes, archive_loads and
 * adds the catalog's errors to archive_errors. Nothing for NULL. */
void mtd_catalog_stats(mtd_catalog *catalog, meshtopo_status_t *st);

#endif
