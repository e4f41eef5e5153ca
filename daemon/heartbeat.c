/* meshtopod's heartbeat: one status_t on PREFIX+"STATUS" every heartbeat_ms
 * (and a last one when it stops), with what the store holds, the worker
 * pool's load, the unfinished chunked submissions (stalled ones expire
 * here first) and the counters since the start. Clients wait for the first
 * one before sending anything. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "archiver.h"
#include "daemon.h"
#include "log.h"

void mtd_heartbeat_publish(mtd_daemon *d)
{
    mtd_transfers_expire(d);
    mtd_store_totals totals;
    mtd_store_get_totals(d->store, &totals);
    mtd_pool_stats pool;
    mtd_pool_get_stats(d->pool, &pool);

    char last_error[MTD_ERROR_MAX];
    meshtopo_status_t st;
    memset(&st, 0, sizeof st);
    pthread_mutex_lock(&d->error_lock);
    memcpy(last_error, d->last_error, sizeof last_error);
    st.last_error_utime = d->last_error_utime;
    pthread_mutex_unlock(&d->error_lock);

    st.utime = mtd_now_utime();
    st.name = d->config.name;
    st.instance = d->instance;
    st.pid = (int32_t)getpid();
    st.uptime_us = st.utime - d->start_utime;
    st.channel_prefix = d->config.channel_prefix;
    st.meshes_held = (int32_t)totals.ids;
    st.versions_held = (int32_t)totals.versions;
    st.memory_bytes = (int64_t)totals.memory_bytes;
    st.submissions = atomic_load(&d->submissions);
    st.builds = atomic_load(&d->builds);
    st.queries = atomic_load(&d->queries);
    st.errors = atomic_load(&d->errors);
    st.duplicate_requests = atomic_load(&d->duplicates);
    st.worker_threads = (int32_t)pool.threads;
    st.builds_in_progress = (int32_t)pool.running;
    st.builds_queued = (int32_t)pool.queued;
    st.last_error = last_error;
    pthread_mutex_lock(&d->transfer_lock);
    st.transfers_active = (int32_t)d->transfers_active;
    st.transfer_bytes = (int64_t)d->transfer_bytes;
    pthread_mutex_unlock(&d->transfer_lock);
    st.chunks = atomic_load(&d->chunks);
    st.transfers_completed = atomic_load(&d->transfers_completed);
    st.transfers_expired = atomic_load(&d->transfers_expired);
    st.transfers_refused = atomic_load(&d->transfers_refused);
    mtd_archiver_stats(d, &st);

    int size = meshtopo_status_t_encoded_size(&st);
    void *buf = size > 0 ? malloc((size_t)size) : NULL;
    if (buf && meshtopo_status_t_encode(buf, 0, size, &st) == size)
        lcm_publish(d->lcm, d->status_channel, buf, (unsigned)size);
    else
        mtd_log(MTD_LOG_ERROR, "heartbeat", "cannot encode the status message");
    free(buf);
}
