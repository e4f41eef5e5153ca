/* meshtopod's heartbeat: one status_t on PREFIX+"STATUS" every heartbeat_ms
 * (and a last one when it stops), read from each module's stats. Clients
 * wait for the first one before sending anything. Runs on the LCM thread. */
#ifndef MESHTOPOD_HEARTBEAT_H
#define MESHTOPOD_HEARTBEAT_H

#include <lcm/lcm.h>
#include <stdint.h>

#include "archive_catalog.h"
#include "archive_writer.h"
#include "cluster.h"
#include "config.h"
#include "error_log.h"
#include "handlers.h"
#include "memory_budget.h"
#include "mesh_store.h"
#include "reply.h"
#include "submit.h"
#include "transfer.h"
#include "worker_pool.h"

/* The counters since the start. */
typedef struct mtd_counters {
    int64_t submissions; /* whole meshes received, and chunked ones once complete */
    int64_t builds, queries, errors, duplicates;
} mtd_counters;

/* Reads them from the modules that own them. */
void mtd_counters_get(mtd_handlers *handlers, mtd_transfers *transfers, mtd_submitter *submitter,
                      mtd_error_log *errors, mtd_replies *replies, mtd_counters *out_counters);

/* What the heartbeat reports on; nothing here is owned. */
typedef struct mtd_heartbeat_sources {
    const mtd_config *config;
    lcm_t *lcm;
    const char *status_channel;
    const char *instance;
    int64_t start_utime;
    mtd_store *store;
    mtd_pool *pool;
    mtd_error_log *errors;
    mtd_replies *replies;
    mtd_handlers *handlers;
    mtd_submitter *submitter;
    mtd_transfers *transfers;
    mtd_catalog *catalog; /* NULL without --archive */
    mtd_writer *writer;   /* NULL without --archive */
    mtd_budget *budget;
    mtd_cluster *cluster; /* NULL without --cluster */
} mtd_heartbeat_sources;

/* Publishes one status_t. */
void mtd_heartbeat_publish(const mtd_heartbeat_sources *sources);

#endif
