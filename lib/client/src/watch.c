/* The daemon's broadcasts for the client's users (meshtopo/client.h):
 * watches over PREFIX STATUS and PREFIX TOPOLOGY whose handlers decode with
 * mt_msgs_decode and call the user's functions on the client's thread, and
 * mt_client_wait_daemon, a watch that waits for the first heartbeat. A
 * watch is started and stopped on the thread that handles LCM, between two
 * lcm_handle calls (mt__client_run_on_thread): LCM 1.3 runs a handler with
 * its lock released, so an unsubscribe from another thread could neither
 * wait for a running callback nor, racing a dispatch, be sure LCM frees the
 * subscription; every field of a watch is then that thread's alone. */
#include <errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "client_internal.h"

struct mt_client_watch {
    mt_client *client;
    mt_client_watch_fns fns;
    lcm_subscription_t *status_sub, *topology_sub;
    bool stopped;     /* no callback runs any more */
    bool in_callback; /* one runs now: it frees the watch when stopped in it */
};

/* Whether a callback may run now (the watch is not stopped); it then runs
 * between begin_call and end_call. */
static bool begin_call(mt_client_watch *w)
{
    if (w->stopped) return false;
    w->in_callback = true;
    return true;
}

/* Frees a watch that its own callback stopped: unsubscribed, LCM will not
 * call it again. w must not be used after. */
static void end_call(mt_client_watch *w)
{
    w->in_callback = false;
    if (w->stopped) free(w);
}

static void count_undecodable(mt_client *client)
{
    pthread_mutex_lock(&client->mutex);
    client->stats.undecodable++;
    pthread_mutex_unlock(&client->mutex);
}

static void on_status(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mt_client_watch *w = user;
    meshtopo_status_t msg;
    if (mt_msgs_decode(&mt_msgs_type_status, rbuf->data, rbuf->data_size, &msg, NULL, 0) != 0) {
        count_undecodable(w->client);
        return;
    }
    if (w->fns.on_status && begin_call(w)) {
        w->fns.on_status(&msg, w->fns.user);
        end_call(w);
    }
    meshtopo_status_t_decode_cleanup(&msg);
}

static void on_topology(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mt_client_watch *w = user;
    meshtopo_topology_t msg;
    if (mt_msgs_decode(&mt_msgs_type_topology, rbuf->data, rbuf->data_size, &msg, NULL, 0) != 0) {
        count_undecodable(w->client);
        return;
    }
    if (w->fns.on_topology && begin_call(w)) {
        w->fns.on_topology(&msg, w->fns.user);
        end_call(w);
    }
    meshtopo_topology_t_decode_cleanup(&msg);
}

/* A watch to subscribe, and whether both subscriptions were made. */
typedef struct start_call {
    mt_client_watch *w;
    bool subscribed;
} start_call;

/* Subscribes w, on the thread that handles LCM; when LCM refuses either
 * subscription, undoes the other and frees w (no callback can have run: this
 * thread has not handled a message since). Once it returns, a callback may
 * run (and stop and free w): the caller reads only the start_call. */
static void start_on_lcm_thread(void *arg)
{
    start_call *call = arg;
    mt_client_watch *w = call->w;
    lcm_t *lcm = w->client->lcm;
    w->status_sub = lcm_subscribe(lcm, w->client->status_channel, on_status, w);
    w->topology_sub = lcm_subscribe(lcm, w->client->topology_channel, on_topology, w);
    call->subscribed = w->status_sub && w->topology_sub;
    if (call->subscribed) return;
    if (w->status_sub) lcm_unsubscribe(lcm, w->status_sub);
    if (w->topology_sub) lcm_unsubscribe(lcm, w->topology_sub);
    free(w);
}

mt_status mt_client_watch_start(mt_client *client, const mt_client_watch_fns *fns,
                                mt_client_watch **out_watch, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!client || !fns || !out_watch)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG,
                               "mt_client_watch_start: client, fns and out_watch are needed");
    *out_watch = NULL;
    mt_client_watch *w = calloc(1, sizeof *w);
    if (!w) return mt__client_fail(diag, MT_ERR_NOMEM, "no memory for a watch");
    w->client = client;
    w->fns = *fns;
    *out_watch = w; /* before any callback: one may stop its own watch */
    start_call call = {.w = w};
    mt__client_run_on_thread(client, start_on_lcm_thread, &call);
    if (!call.subscribed) { /* w is freed */
        *out_watch = NULL;
        return mt__client_fail(diag, MT_ERR_IO, "lcm_subscribe(%s, %s) failed",
                               client->status_channel, client->topology_channel);
    }
    return MT_OK;
}

/* Unsubscribes and frees w, or leaves the freeing to its running callback.
 * On the thread that handles LCM, between two lcm_handle calls or inside a
 * callback. */
static void stop_on_lcm_thread(void *arg)
{
    mt_client_watch *w = arg;
    w->stopped = true;
    if (w->status_sub) lcm_unsubscribe(w->client->lcm, w->status_sub);
    if (w->topology_sub) lcm_unsubscribe(w->client->lcm, w->topology_sub);
    if (!w->in_callback) free(w);
}

void mt_client_watch_stop(mt_client_watch *w)
{
    if (!w) return;
    mt__client_run_on_thread(w->client, stop_on_lcm_thread, w);
}

/* The first heartbeat, handed from the client's thread to the waiter. */
typedef struct heartbeat_wait {
    pthread_mutex_t lock;
    pthread_cond_t cond;
    meshtopo_status_t *first; /* a copy, NULL until one came */
    int copy_failed;
} heartbeat_wait;

static void on_first_heartbeat(const meshtopo_status_t *status, void *user)
{
    heartbeat_wait *hw = user;
    pthread_mutex_lock(&hw->lock);
    if (!hw->first && !hw->copy_failed) {
        hw->first = meshtopo_status_t_copy(status);
        if (!hw->first) hw->copy_failed = 1;
        pthread_cond_signal(&hw->cond);
    }
    pthread_mutex_unlock(&hw->lock);
}

mt_status mt_client_wait_daemon(mt_client *client, int timeout_ms, meshtopo_status_t **out_status,
                                mt_diag *diag)
{
    mt_diag_clear(diag);
    if (out_status) *out_status = NULL;
    if (!client) return mt__client_fail(diag, MT_ERR_INVALID_ARG, "mt_client_wait_daemon: NULL");
    if (client->thread_started && pthread_equal(pthread_self(), client->thread))
        return mt__client_fail(diag, MT_ERR_INVALID_ARG,
                               "mt_client_wait_daemon from the client's own thread would never "
                               "see the heartbeat");
    if (timeout_ms <= 0) timeout_ms = client->timeout_ms * client->attempts;
    heartbeat_wait hw = {.first = NULL};
    pthread_mutex_init(&hw.lock, NULL);
    pthread_condattr_t attr;
    pthread_condattr_init(&attr);
    pthread_condattr_setclock(&attr, CLOCK_MONOTONIC);
    pthread_cond_init(&hw.cond, &attr);
    pthread_condattr_destroy(&attr);
    mt_client_watch_fns fns = {.on_status = on_first_heartbeat, .user = &hw};
    mt_client_watch *w = NULL;
    mt_status st = mt_client_watch_start(client, &fns, &w, diag);
    if (st == MT_OK) {
        struct timespec until;
        clock_gettime(CLOCK_MONOTONIC, &until);
        until.tv_sec += timeout_ms / 1000;
        until.tv_nsec += (long)(timeout_ms % 1000) * 1000000L;
        if (until.tv_nsec >= 1000000000L) {
            until.tv_sec++;
            until.tv_nsec -= 1000000000L;
        }
        pthread_mutex_lock(&hw.lock);
        while (!hw.first && !hw.copy_failed &&
               pthread_cond_timedwait(&hw.cond, &hw.lock, &until) != ETIMEDOUT) {
        }
        pthread_mutex_unlock(&hw.lock);
        mt_client_watch_stop(w); /* no callback runs past here */
        if (hw.copy_failed)
            st = mt__client_fail(diag, MT_ERR_NOMEM, "no memory to copy the heartbeat");
        else if (!hw.first)
            st = mt__client_fail(diag, MT_ERR_IO,
                                 "timeout: no heartbeat from meshtopod on %s within %d ms",
                                 client->status_channel, timeout_ms);
    }
    if (st == MT_OK && out_status)
        *out_status = hw.first;
    else if (hw.first) /* lcm-gen's destroy is not NULL-safe */
        meshtopo_status_t_destroy(hw.first);
    pthread_cond_destroy(&hw.cond);
    pthread_mutex_destroy(&hw.lock);
    return st;
}
