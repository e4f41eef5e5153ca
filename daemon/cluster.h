/* meshtopod's cluster membership (--cluster NAME): several daemons on one
 * prefix, sharing one archive directory, split the mesh ids between them.
 * Each member learns the others from their heartbeats (status_t naming the
 * same cluster; peers.c passes them here) and owns the ids that rendezvous
 * (highest-random-weight) hashing over the live members gives it: for each
 * id, the member whose hash of (its instance, the id) is highest. Ownership
 * is a pure function of the member set, so members that hear the same
 * heartbeats agree without talking to each other; a member joining takes
 * only the ids it wins, a member gone gives each of its ids to the member
 * that came second for it, and nothing else moves.
 *
 * The view members act on changes in two ways. A member heard for the first
 * time joins it at once (the others can only lose ids by that). A member not
 * heard for expiry_us leaves it only in mtd_cluster_refresh, which the
 * daemon calls on its LCM thread and follows, when the view changed, with
 * what a change needs (the archive rescanned for the ids it gains, the
 * meshes it no longer owns dropped from memory). Without a cluster the
 * daemon owns every id and none of this exists. Thread safe. */
#ifndef MESHTOPOD_CLUSTER_H
#define MESHTOPOD_CLUSTER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/status.h"

/* Members a view can hold; heartbeats of more are ignored (and logged). */
#define MTD_CLUSTER_MAX_MEMBERS 64

typedef struct mtd_cluster mtd_cluster;

typedef struct mtd_cluster_options {
    const char *name;        /* the cluster's name, not empty */
    const char *instance;    /* this daemon's instance (host:pid:start) */
    const char *member_name; /* this daemon's --name, for logs */
    int64_t expiry_us;       /* a member not heard for this long has left */
    /* Testing only: heartbeats of members whose daemon name is this are
     * ignored, so two members can be given views that disagree. NULL or ""
     * = none. */
    const char *ignored_name;
} mtd_cluster_options;

/* How long a member may stay silent before it has left: two heartbeat
 * periods (one lost or late heartbeat is not a departure). */
int64_t mtd_cluster_expiry_us(uint32_t heartbeat_ms);

/* MT_OK, MT_ERR_INVALID_ARG (no name or instance) or MT_ERR_NOMEM. */
mt_status mtd_cluster_create(const mtd_cluster_options *options, mtd_cluster **out_cluster);

/* NULL-safe. */
void mtd_cluster_destroy(mtd_cluster *cluster);

/* The cluster's name, and this daemon's instance. */
const char *mtd_cluster_name(const mtd_cluster *cluster);
const char *mtd_cluster_instance(const mtd_cluster *cluster);

/* A live daemon's heartbeat on this prefix, heard at now_us (monotonic):
 * its cluster name, instance and daemon name. Returns true when it is a
 * member of this cluster (this daemon's own heartbeats included), false
 * when it is another daemon (another cluster's, or one without a cluster),
 * which the caller treats as a second daemon on the prefix. */
bool mtd_cluster_heard(mtd_cluster *cluster, const char *cluster_name, const char *instance,
                       const char *daemon_name, int64_t now_us);

/* Drops from the view the members not heard for expiry_us. Returns true
 * when the view changed since the previous call that returned true (a
 * member joined or left). */
bool mtd_cluster_refresh(mtd_cluster *cluster, int64_t now_us);

/* Whether this daemon owns mesh_id in the current view. NULL cluster: true. */
bool mtd_cluster_owns(mtd_cluster *cluster, const char *mesh_id);

/* The member of `instances` (num of them, distinct) that owns mesh_id by
 * rendezvous hashing: its index. What every member computes; exposed so
 * tests and benchmarks can check the shares. */
size_t mtd_cluster_owner_of(const char *const *instances, size_t num, const char *mesh_id);

/* The current view, for the heartbeat and logs. */
typedef struct mtd_cluster_view {
    int32_t members; /* itself included */
    double share;    /* fraction of a fixed sample of 4096 ids it owns */
    uint64_t hash;   /* of the members' instances, sorted: equal on agreeing members */
    char names[512]; /* "name (instance), ..." of the members, cut to fit */
} mtd_cluster_view;

void mtd_cluster_get_view(mtd_cluster *cluster, mtd_cluster_view *out_view);

#endif
