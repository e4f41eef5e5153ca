/* meshtopod's watch for other daemons on its channel prefix, from their
 * heartbeats (status_t on PREFIX "STATUS"). Several daemons answering one
 * prefix would each build every submission and number versions on their
 * own, so one prefix has one daemon: before serving, meshtopod listens for
 * a while and refuses to start when a live daemon beats (main.c); while
 * serving, another daemon's heartbeat is logged and noted in the error log
 * (the heartbeat's last_error) but never stops it, since anyone on the
 * network can forge a heartbeat. With --cluster, daemons of the same
 * cluster are members, not second daemons: their heartbeats go to the
 * cluster's membership (cluster.h); a daemon of another cluster or of none
 * is still refused and warned about. Messages arrive on the LCM thread; the
 * verdict is read on the main thread, under a mutex. */
#ifndef MESHTOPOD_PEERS_H
#define MESHTOPOD_PEERS_H

#include <lcm/lcm.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cluster.h"
#include "error_log.h"
#include "meshtopo/status.h"

typedef struct mtd_peers mtd_peers;

/* Watches status_channel on lcm (not owned) for live daemons other than
 * `instance` (its own heartbeats, ignored; "" before it has one); those that
 * started before start_utime (INT64_MAX: any) count as older. With `errors`
 * (not owned), each other daemon is noted there and logged once. With
 * `cluster` (not owned; NULL = none), live heartbeats of its members are
 * passed to mtd_cluster_heard and are not other daemons. MT_OK or
 * MT_ERR_NOMEM. */
mt_status mtd_peers_create(lcm_t *lcm, const char *status_channel, const char *instance,
                           int64_t start_utime, mtd_error_log *errors, mtd_cluster *cluster,
                           mtd_peers **out_peers);

/* Unsubscribes and frees. NULL-safe; on the thread that handles lcm. */
void mtd_peers_destroy(mtd_peers *peers);

/* Whether an older daemon serves the prefix; when so, `who` gets its name,
 * instance (host:pid:start) and pid. */
bool mtd_peers_older_seen(mtd_peers *peers, char *who, size_t who_size);

#endif
