/* meshtopod's lifecycle: creates its modules in dependency order and wires
 * them (config, error log, kept buffers, memory budget, store, worker pool,
 * replies, archive catalog and writer, submitter, transfers, queries, LCM
 * handlers, heartbeat), runs the periodic tick, stops and destroys them in
 * reverse. Each module owns its
 * state; this file owns only the modules. Called from the thread that runs
 * LCM (main.c, or a test's). */
#ifndef MESHTOPOD_DAEMON_H
#define MESHTOPOD_DAEMON_H

#include <lcm/lcm.h>
#include <stdint.h>

#include "cluster.h"
#include "config.h"
#include "content_pool.h"
#include "heartbeat.h"
#include "mesh_store.h"
#include "meshtopo/channels.h"
#include "peers.h"
#include "workspace_pool.h"

typedef struct mtd_daemon mtd_daemon;

/* Creates every module from config and subscribes to the request channels
 * on lcm (not owned). With config->cluster, `cluster` is the membership the
 * start-up probe filled (taken over, its instance is the daemon's; NULL:
 * the daemon makes its own, empty). MT_OK, MT_ERR_INVALID_ARG (prefix too
 * long for LCM channel names), MT_ERR_IO (the archive), MT_ERR_NOMEM; diag
 * says which (a given cluster is destroyed on failure). */
mt_status mtd_daemon_create(const mtd_config *config, lcm_t *lcm, mtd_cluster *cluster,
                            mtd_daemon **out_daemon, mt_diag *diag);

/* The membership of config's cluster for a daemon of this instance (*out
 * NULL without --cluster): what the start-up probe fills and
 * mtd_daemon_create takes over. MT_OK or MT_ERR_NOMEM. */
mt_status mtd_daemon_cluster_create(const mtd_config *config, const char *instance,
                                    mtd_cluster **out_cluster);

/* Formats the instance id a daemon started at start_utime has:
 * "host:pid:start_utime". */
void mtd_daemon_instance_name(int64_t start_utime, char *out, size_t size);

/* In a cluster, acts on changes of its view: drops members gone silent and,
 * when the view changed, catalogs what other members archived and drops
 * from memory the meshes this member no longer owns; rescans the archive
 * once more when the members have had time to agree. The main loop calls it
 * four times per heartbeat period; nothing without a cluster. */
void mtd_daemon_watch_cluster(mtd_daemon *daemon);

/* The periodic work, every heartbeat_ms: drops stalled transfers and old
 * remembered answers, gives freed heap memory back to the system, then
 * publishes the heartbeat. */
void mtd_daemon_tick(mtd_daemon *daemon);

/* Publishes one heartbeat now (the last one after mtd_daemon_stop). */
void mtd_daemon_heartbeat(mtd_daemon *daemon);

/* Stops taking work: unsubscribes, cancels queued builds and loads (each
 * gets a BUSY answer), waits for running builds, lets the async archive
 * writer finish. Idempotent. */
void mtd_daemon_stop(mtd_daemon *daemon);

/* mtd_daemon_stop, then frees everything (not the LCM handle). NULL-safe. */
void mtd_daemon_destroy(mtd_daemon *daemon);

/* Whether a live daemon that started earlier beats on the same prefix
 * (noted in the error log and logged when seen); `who` names it. */
bool mtd_daemon_other_seen(mtd_daemon *daemon, char *who, size_t who_size);

/* "host:pid:start-utime", as in the heartbeat. */
const char *mtd_daemon_instance(const mtd_daemon *daemon);

/* A channel's name, PREFIX + its suffix (meshtopo/channels.h). */
const char *mtd_daemon_channel(const mtd_daemon *daemon, mt_msgs_channel channel);

/* The counters the heartbeat and the last log line report. */
void mtd_daemon_get_counts(mtd_daemon *daemon, mtd_counters *out_counts);

/* The modules tests look into. */
mtd_store *mtd_daemon_store(mtd_daemon *daemon);
mtd_content_pool *mtd_daemon_content_pool(mtd_daemon *daemon);
mtd_workspace_pool *mtd_daemon_workspace_pool(mtd_daemon *daemon);
mtd_transfers *mtd_daemon_transfers(mtd_daemon *daemon);

#endif
