/* The daemons of a prefix from their heartbeats (members.h). */
#include "members.h"

#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

typedef struct heard {
    pthread_mutex_t lock;
    cli_members *members;
    int expected; /* the largest cluster_members a member reported */
} heard;

static void on_status(const meshtopo_status_t *st, void *user)
{
    heard *h = user;
    cli_members *m = h->members;
    pthread_mutex_lock(&h->lock);
    if (m->count == 0) snprintf(m->cluster, sizeof m->cluster, "%s", st->cluster);
    int i = 0;
    while (i < m->count && strcmp(m->instances[i], st->instance) != 0) i++;
    if (i == m->count && m->count < CLI_MAX_MEMBERS && strcmp(st->cluster, m->cluster) == 0 &&
        (m->cluster[0] || m->count == 0)) {
        snprintf(m->instances[i], sizeof m->instances[i], "%s", st->instance);
        snprintf(m->names[i], sizeof m->names[i], "%s", st->name);
        m->count++;
    }
    if (st->cluster_members > h->expected) h->expected = st->cluster_members;
    pthread_mutex_unlock(&h->lock);
}

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

void cli_members_find(mt_client *client, int wait_ms, cli_members *out)
{
    memset(out, 0, sizeof *out);
    heard h = {.members = out};
    pthread_mutex_init(&h.lock, NULL);
    mt_client_watch *watch = NULL;
    mt_client_watch_fns fns = {.on_status = on_status, .user = &h};
    mt_diag diag;
    if (mt_client_watch_start(client, &fns, &watch, &diag) == MT_OK) {
        bool done = false;
        for (int waited = 0; !done && waited < 2 * wait_ms; waited += 10) {
            sleep_ms(10);
            pthread_mutex_lock(&h.lock);
            done = (out->count > 0 && !out->cluster[0]) ||
                   (out->count > 0 && out->count >= h.expected);
            if (out->count == 0 && waited >= wait_ms) done = true;
            pthread_mutex_unlock(&h.lock);
        }
        mt_client_watch_stop(watch);
    }
    pthread_mutex_destroy(&h.lock);
}
