/* meshtopod's chunked submissions (msgs/mesh_chunk_t.lcm): the unfinished
 * transfers, opaque behind mtd_transfers, reassembled per (reply channel,
 * request id) and handed to the submitter once complete. It owns their
 * admission (the mesh limits), the memory they hold (pages of what they were
 * sent, within --max-transfer-bytes and a share per reply channel), their expiry
 * (--transfer-timeout-ms) and their counters. Runs on the LCM thread (chunks,
 * expiry); the heartbeat reads its stats. */
#ifndef MESHTOPOD_TRANSFER_H
#define MESHTOPOD_TRANSFER_H

#include <stddef.h>
#include <stdint.h>

#include "cluster.h"
#include "config.h"
#include "content_pool.h"
#include "reply.h"
#include "submit.h"

typedef struct mtd_transfers mtd_transfers;

/* What transfers use; not owned, all must outlive them. */
typedef struct mtd_transfer_deps {
    const mtd_config *config;
    mtd_replies *replies;
    mtd_submitter *submitter;
    mtd_content_pool *contents;
    mtd_cluster *cluster; /* NULL without --cluster */
} mtd_transfer_deps;

/* MT_OK or MT_ERR_NOMEM. */
mt_status mtd_transfers_create(const mtd_transfer_deps *deps, mtd_transfers **out_transfers);

/* Frees every unfinished transfer (their buffers go back to the content
 * pool). NULL-safe. */
void mtd_transfers_destroy(mtd_transfers *transfers);

/* Handles one received mesh_chunk_t (bytes with its fingerprint, not yet
 * decoded): decodes it, adds it to its transfer (admitting a new one within
 * the limits), answers with mesh_transfer_t when asked or wrong, and hands a
 * complete mesh to the submitter. Expires stalled transfers first. In a
 * cluster, a chunk opens a transfer only on the member owning its mesh id;
 * a transfer already open is finished by its member whoever owns the id
 * now. */
void mtd_transfers_chunk(mtd_transfers *transfers, const void *data, size_t size);

/* Drops every transfer that received nothing for transfer_timeout_ms and
 * releases its memory. Returns how many were dropped. */
size_t mtd_transfers_expire(mtd_transfers *transfers);

/* New transfers are refused with BUSY from now on (the daemon is stopping). */
void mtd_transfers_stop(mtd_transfers *transfers);

/* For the heartbeat. */
typedef struct mtd_transfer_stats {
    int32_t active;    /* unfinished transfers */
    int64_t bytes;     /* memory they hold, counted against the limit */
    int64_t chunks;    /* chunks received */
    int64_t completed; /* transfers complete (each one submission) */
    int64_t expired;
    int64_t refused; /* transfers refused, and chunks refused BUSY */
    int64_t dropped; /* chunks beyond the window or the ranges a transfer may hold */
} mtd_transfer_stats;

void mtd_transfers_get_stats(mtd_transfers *transfers, mtd_transfer_stats *out_stats);

#endif
