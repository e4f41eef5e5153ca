/* meshtopod's watch for other daemons (peers.h): each heartbeat on the
 * status channel is decoded and, when it comes from a live daemon other than
 * this one, compared with our start time. A heartbeat is not taken for a
 * live daemon when it was sent more than STALE_US from now, or names a
 * process of this host that no longer exists: what lcm-logplayer replays
 * from a recorded session. With a cluster, the live heartbeats of its
 * members go to it (cluster.h) instead. */
#define _DEFAULT_SOURCE /* gethostname */
#include "peers.h"

#include <errno.h>
#include <inttypes.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "cluster.h"
#include "log.h"
#include "meshtopo/msgs.h"

#define STALE_US (10 * 1000000LL)

struct mtd_peers {
    lcm_t *lcm;
    lcm_subscription_t *subscription;
    mtd_error_log *errors; /* not owned; NULL in the probe */
    mtd_cluster *cluster;  /* not owned; NULL without --cluster */
    char instance[128];
    char host[64];
    int64_t start_utime;
    pthread_mutex_t lock;
    bool older_seen;
    char older[256];
    char warned[128]; /* the last instance warned about */
};

/* Whether st looks like the heartbeat of a daemon running now. */
static bool alive(const mtd_peers *p, const meshtopo_status_t *st)
{
    int64_t age = mtd_now_utime() - st->utime;
    if (age > STALE_US || age < -STALE_US) return false;
    size_t host_len = strlen(p->host);
    bool same_host = host_len > 0 && strncmp(st->instance, p->host, host_len) == 0 &&
                     st->instance[host_len] == ':';
    if (same_host && st->pid > 0 && kill((pid_t)st->pid, 0) != 0 && errno == ESRCH) return false;
    return true;
}

static void on_status(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mtd_peers *p = user;
    meshtopo_status_t st;
    if (mt_msgs_decode(&mt_msgs_type_status, rbuf->data, rbuf->data_size, &st, NULL, 0) != 0)
        return;
    /* A member of our cluster is no second daemon: the cluster takes it. */
    bool member =
        p->cluster && alive(p, &st) &&
        mtd_cluster_heard(p->cluster, st.cluster, st.instance, st.name, mtd_monotonic_us());
    if (!member && strcmp(st.instance, p->instance) != 0 && alive(p, &st)) {
        int64_t started = st.utime - st.uptime_us;
        bool older = started < p->start_utime ||
                     (started == p->start_utime && strcmp(st.instance, p->instance) < 0);
        char who[256];
        snprintf(who, sizeof who, "'%.60s' (instance %.120s, pid %" PRId32 ")", st.name,
                 st.instance, st.pid);
        pthread_mutex_lock(&p->lock);
        if (older && !p->older_seen) {
            p->older_seen = true;
            snprintf(p->older, sizeof p->older, "%s", who);
        }
        bool warn = p->errors && strcmp(p->warned, st.instance) != 0;
        if (warn) snprintf(p->warned, sizeof p->warned, "%s", st.instance);
        pthread_mutex_unlock(&p->lock);
        if (warn) {
            char error[512];
            snprintf(error, sizeof error,
                     "another meshtopod %s beats on this prefix%s%.60s%s: both would build every "
                     "submission; give each its own --prefix, or both one --cluster",
                     who, st.cluster[0] ? " (cluster '" : "", st.cluster,
                     st.cluster[0] ? "')" : "");
            mtd_error_log_note(p->errors, error);
            mtd_log(MTD_LOG_WARN, "second_daemon", "%s", error);
        }
    }
    meshtopo_status_t_decode_cleanup(&st);
}

mt_status mtd_peers_create(lcm_t *lcm, const char *status_channel, const char *instance,
                           int64_t start_utime, mtd_error_log *errors, mtd_cluster *cluster,
                           mtd_peers **out_peers)
{
    *out_peers = NULL;
    mtd_peers *p = calloc(1, sizeof *p);
    if (!p) return MT_ERR_NOMEM;
    p->lcm = lcm;
    p->errors = errors;
    p->cluster = cluster;
    snprintf(p->instance, sizeof p->instance, "%s", instance);
    gethostname(p->host, sizeof p->host - 1);
    p->start_utime = start_utime;
    pthread_mutex_init(&p->lock, NULL);
    p->subscription = lcm_subscribe(lcm, status_channel, on_status, p);
    if (!p->subscription) {
        pthread_mutex_destroy(&p->lock);
        free(p);
        return MT_ERR_NOMEM;
    }
    *out_peers = p;
    return MT_OK;
}

void mtd_peers_destroy(mtd_peers *p)
{
    if (!p) return;
    lcm_unsubscribe(p->lcm, p->subscription);
    pthread_mutex_destroy(&p->lock);
    free(p);
}

bool mtd_peers_older_seen(mtd_peers *p, char *who, size_t who_size)
{
    pthread_mutex_lock(&p->lock);
    bool seen = p->older_seen;
    if (seen && who) snprintf(who, who_size, "%s", p->older);
    pthread_mutex_unlock(&p->lock);
    return seen;
}
