/* `meshtopo-bench soak`: meshtopod under normal and hostile traffic at once,
 * for minutes, in a private network namespace made for the run. Normal
 * clients submit meshes and query (through meshtopo::client) first alone,
 * for a baseline, then beside a hostile sender (soak_hostile.c) that sends
 * what the daemon must survive: tiny meshes claiming millions of vertices,
 * transfers claiming a gigabyte fed a byte at a time, one-byte chunks spread
 * over a gigabyte, an open-loop flood of 20,000-id queries, requests naming
 * the daemon's own channels as reply channel, and garbage. Prints lost
 * acknowledged meshes, the normal clients' latency against the baseline,
 * the daemon's memory (from /proc) at start, peak and end, and the archive
 * bytes the hostile sender got written. */
#ifndef MESHTOPO_BENCH_SOAK_H
#define MESHTOPO_BENCH_SOAK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Entry point: `meshtopo-bench soak [options]` (argv[0] is "soak"). Exit
 * status 0 when every target was met, 1 when one was missed or the run
 * failed, 2 on a usage error, 77 without private network namespaces. */
int mt__bench_soak_command(int argc, char **argv);

/* ---- soak_hostile.c ------------------------------------------------------ */

/* What the hostile sender sent and what came back to it. */
typedef struct mt__soak_hostile_counts {
    uint64_t claims;          /* tiny mesh_t claiming 16M vertices */
    uint64_t claims_refused;  /* answered TOO_LARGE */
    uint64_t claims_accepted; /* answered OK (must stay 0) */
    uint64_t claim_polls;     /* transfers claiming 1 GiB, opened */
    uint64_t trickle_bytes;   /* one-byte chunks feeding those slowly */
    uint64_t scatter_bytes;   /* one-byte chunks spread over a 1 GiB transfer */
    uint64_t floods;          /* 20,000-id queries, never waited for */
    uint64_t flood_busy;      /* answered BUSY */
    uint64_t flood_parts;     /* reply_part_t pieces of served floods */
    uint64_t own_channels;    /* requests naming a daemon channel as reply channel */
    uint64_t on_own_channels; /* messages seen on answer channels beside the daemon's (must be 0) */
    uint64_t garbage;         /* random bytes on every request channel */
} mt__soak_hostile_counts;

typedef struct mt__soak_hostile mt__soak_hostile;

/* Starts the hostile sender's thread on lcm_url, flooding queries on
 * `mesh_id` (a mesh with at least `flood_ids` vertices). NULL with err on
 * failure. */
mt__soak_hostile *mt__soak_hostile_start(const char *lcm_url, const char *mesh_id,
                                         uint32_t flood_ids, char *err, size_t err_size);

/* Stops it and returns its counts. */
void mt__soak_hostile_stop(mt__soak_hostile *hostile, mt__soak_hostile_counts *out);

#endif
