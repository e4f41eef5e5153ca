/* meshtopod's cluster membership (cluster.h): the members heard, in one
 * small array under a mutex (the member itself first, never dropped), and
 * rendezvous hashing over them (mt_msgs_cluster_owner, the protocol's rule:
 * a client reading the heartbeats computes the same). */
#include "cluster.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <xxhash.h>

#include "log.h"
#include "meshtopo/protocol.h"

/* Ids of the fixed sample the heartbeat's share is measured on. */
#define SHARE_SAMPLE 4096

typedef struct member {
    char instance[128];
    char name[64];
    uint64_t seed; /* mt_msgs_cluster_seed of instance */
    int64_t heard_us;
} member;

struct mtd_cluster {
    char name[64];
    char ignored_name[64];
    int64_t expiry_us;
    pthread_mutex_t lock;
    member members[MTD_CLUSTER_MAX_MEMBERS]; /* [0] is this daemon */
    size_t count;
    uint64_t generation, reported; /* view changes, and the last one refresh returned */
    bool full_logged;
    mtd_cluster_view view;    /* computed for generation view_generation - 1 */
    uint64_t view_generation; /* 0: none yet */
};

size_t mtd_cluster_owner_of(const char *const *instances, size_t num, const char *mesh_id)
{
    uint64_t seeds[MTD_CLUSTER_MAX_MEMBERS];
    if (num > MTD_CLUSTER_MAX_MEMBERS) num = MTD_CLUSTER_MAX_MEMBERS;
    for (size_t i = 0; i < num; i++) seeds[i] = mt_msgs_cluster_seed(instances[i]);
    return mt_msgs_cluster_owner(seeds, num, mesh_id);
}

int64_t mtd_cluster_expiry_us(uint32_t heartbeat_ms)
{
    return 2 * (int64_t)heartbeat_ms * 1000;
}

mt_status mtd_cluster_create(const mtd_cluster_options *o, mtd_cluster **out_cluster)
{
    *out_cluster = NULL;
    if (!o || !o->name || !o->name[0] || !o->instance || !o->instance[0]) return MT_ERR_INVALID_ARG;
    mtd_cluster *c = calloc(1, sizeof *c);
    if (!c) return MT_ERR_NOMEM;
    snprintf(c->name, sizeof c->name, "%s", o->name);
    snprintf(c->ignored_name, sizeof c->ignored_name, "%s", o->ignored_name ? o->ignored_name : "");
    c->expiry_us = o->expiry_us;
    pthread_mutex_init(&c->lock, NULL);
    member *self = &c->members[0];
    snprintf(self->instance, sizeof self->instance, "%s", o->instance);
    snprintf(self->name, sizeof self->name, "%s", o->member_name ? o->member_name : "");
    self->seed = mt_msgs_cluster_seed(self->instance);
    c->count = 1;
    *out_cluster = c;
    return MT_OK;
}

void mtd_cluster_destroy(mtd_cluster *c)
{
    if (!c) return;
    pthread_mutex_destroy(&c->lock);
    free(c);
}

const char *mtd_cluster_name(const mtd_cluster *c)
{
    return c->name;
}

const char *mtd_cluster_instance(const mtd_cluster *c)
{
    return c->members[0].instance; /* never changes */
}

bool mtd_cluster_heard(mtd_cluster *c, const char *cluster_name, const char *instance,
                       const char *daemon_name, int64_t now_us)
{
    if (strcmp(cluster_name, c->name) != 0) return false;
    if (c->ignored_name[0] && strcmp(daemon_name, c->ignored_name) == 0) return true;
    pthread_mutex_lock(&c->lock);
    size_t i = 0;
    while (i < c->count && strcmp(c->members[i].instance, instance) != 0) i++;
    bool joined = false, full = false;
    if (i < c->count) {
        c->members[i].heard_us = now_us;
    } else if (c->count < MTD_CLUSTER_MAX_MEMBERS) {
        member *m = &c->members[c->count++];
        snprintf(m->instance, sizeof m->instance, "%s", instance);
        snprintf(m->name, sizeof m->name, "%s", daemon_name);
        m->seed = mt_msgs_cluster_seed(m->instance);
        m->heard_us = now_us;
        c->generation++;
        joined = true;
    } else if (!c->full_logged) {
        c->full_logged = full = true;
    }
    size_t members = c->count;
    pthread_mutex_unlock(&c->lock);
    if (joined)
        mtd_log(MTD_LOG_INFO, "cluster_join", "cluster=%s member='%s' instance=%s members=%zu",
                c->name, daemon_name, instance, members);
    if (full)
        mtd_log(MTD_LOG_WARN, "cluster_full",
                "cluster=%s already has %d members: member '%s' (instance %s) is ignored", c->name,
                MTD_CLUSTER_MAX_MEMBERS, daemon_name, instance);
    return true;
}

bool mtd_cluster_refresh(mtd_cluster *c, int64_t now_us)
{
    pthread_mutex_lock(&c->lock);
    for (size_t i = 1; i < c->count;) {
        member *m = &c->members[i];
        if (now_us - m->heard_us <= c->expiry_us) {
            i++;
            continue;
        }
        mtd_log(MTD_LOG_INFO, "cluster_leave",
                "cluster=%s member='%s' instance=%s silent for %.0f ms, members=%zu", c->name,
                m->name, m->instance, (double)(now_us - m->heard_us) / 1e3, c->count - 1);
        c->members[i] = c->members[--c->count];
        c->generation++;
    }
    bool changed = c->generation != c->reported;
    c->reported = c->generation;
    pthread_mutex_unlock(&c->lock);
    return changed;
}

bool mtd_cluster_owns(mtd_cluster *c, const char *mesh_id)
{
    if (!c) return true;
    uint64_t seeds[MTD_CLUSTER_MAX_MEMBERS];
    pthread_mutex_lock(&c->lock);
    size_t n = c->count;
    for (size_t i = 0; i < n; i++) seeds[i] = c->members[i].seed;
    pthread_mutex_unlock(&c->lock);
    return mt_msgs_cluster_owner(seeds, n, mesh_id) == 0;
}

static int compare_text(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* The view of members[0 .. n-1] (members[0] this daemon). */
static void compute_view(const member *members, size_t n, mtd_cluster_view *out)
{
    memset(out, 0, sizeof *out);
    out->members = (int32_t)n;
    uint64_t seeds[MTD_CLUSTER_MAX_MEMBERS];
    const char *sorted[MTD_CLUSTER_MAX_MEMBERS];
    for (size_t i = 0; i < n; i++) {
        seeds[i] = members[i].seed;
        sorted[i] = members[i].instance;
    }
    size_t owned = 0;
    for (int k = 0; k < SHARE_SAMPLE; k++) {
        char id[16];
        snprintf(id, sizeof id, "%d", k);
        owned += mt_msgs_cluster_owner(seeds, n, id) == 0;
    }
    out->share = (double)owned / SHARE_SAMPLE;
    qsort(sorted, n, sizeof *sorted, compare_text);
    XXH3_state_t *state = XXH3_createState();
    if (state) {
        XXH3_64bits_reset(state);
        for (size_t i = 0; i < n; i++) XXH3_64bits_update(state, sorted[i], strlen(sorted[i]) + 1);
        out->hash = XXH3_64bits_digest(state);
        XXH3_freeState(state);
    }
    size_t used = 0;
    for (size_t i = 0; i < n && used < sizeof out->names; i++) {
        int w = snprintf(out->names + used, sizeof out->names - used, "%s%s (%s)", i ? ", " : "",
                         members[i].name, members[i].instance);
        if (w < 0) break;
        used += (size_t)w;
    }
}

void mtd_cluster_get_view(mtd_cluster *c, mtd_cluster_view *out)
{
    member members[MTD_CLUSTER_MAX_MEMBERS];
    pthread_mutex_lock(&c->lock);
    bool fresh = c->view_generation == c->generation + 1;
    if (fresh) *out = c->view;
    const uint64_t generation = c->generation;
    size_t n = c->count;
    memcpy(members, c->members, n * sizeof *members);
    pthread_mutex_unlock(&c->lock);
    if (fresh) return;
    /* Every heartbeat reports the view: it is computed once per change. */
    compute_view(members, n, out);
    pthread_mutex_lock(&c->lock);
    if (c->generation == generation) {
        c->view = *out;
        c->view_generation = generation + 1;
    }
    pthread_mutex_unlock(&c->lock);
}
