/* meshtopod's archive writer: the store's archiving policy
 * (mtd_store_policy). In sync mode (the default with --archive) it writes a
 * new version before the store shows it, so it is durable before its ack (a
 * failed write: the version is not stored); in async mode the store hands it
 * each version once visible and one background writer writes them from a
 * bounded queue (a build waits for room). Each file written goes into the
 * catalog; in a cluster a version's number is one above the highest in the
 * shared directory, and the archive's atomic link decides between members
 * that pick the same (the loser takes the next). Calls the catalog, the
 * memory budget (a version written may be dropped from memory) and the
 * entries it is handed; never the store. */
#ifndef MESHTOPOD_ARCHIVE_WRITER_H
#define MESHTOPOD_ARCHIVE_WRITER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "archive_catalog.h"
#include "config.h"
#include "error_log.h"
#include "memory_budget.h"
#include "mesh_store.h"
#include "meshtopo/msgs.h"

typedef struct mtd_writer mtd_writer;

/* Checks --archive-compression (LZ4 without HDF5's Blosc plugin is refused:
 * the daemon does not start rather than write something other than asked).
 * MT_OK, MT_ERR_INVALID_ARG or MT_ERR_UNSUPPORTED with diag. */
mt_status mtd_writer_check_compression(mtd_archive_compression asked, mt_diag *diag);

/* A writer into catalog's archive for config's mode (sync, async; off
 * writes nothing), starting the async writer thread. catalog, budget (may
 * be NULL) and errors are not owned and must outlive it. MT_OK,
 * MT_ERR_NOMEM, or the compression's error. */
mt_status mtd_writer_create(const mtd_config *config, mtd_catalog *catalog, mtd_budget *budget,
                            mtd_error_log *errors, mtd_writer **out_writer, mt_diag *diag);

/* The writer as the store's archiving policy (*out, its ctx the writer):
 * admit and withdraw in sync mode, on_added in async mode, nothing off. */
void mtd_writer_policy(mtd_writer *writer, mtd_store_policy *out_policy);

/* Lets the async writer empty its queue, then stops it. Call after the
 * worker pool has stopped (no build adds to the queue any more). Idempotent,
 * NULL-safe. */
void mtd_writer_stop(mtd_writer *writer);

/* Stops and frees the writer (versions still queued are dropped).
 * NULL-safe. */
void mtd_writer_destroy(mtd_writer *writer);

/* Adds the heartbeat's archive_writes, archive_backlog and its errors to
 * archive_errors. Nothing for NULL. */
void mtd_writer_stats(mtd_writer *writer, meshtopo_status_t *st);

#endif
