/* meshtopod's heartbeat (heartbeat.h): one status_t with what the store
 * holds, the worker pool's load, the unfinished chunked submissions, the
 * archive and the counters since the start, each read from the module that
 * owns it. LCM thread. */
#include "heartbeat.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "log.h"

void mtd_counters_get(mtd_handlers *handlers, mtd_transfers *transfers, mtd_submitter *submitter,
                      mtd_error_log *errors, mtd_replies *replies, mtd_counters *out)
{
    mtd_handler_counts received;
    mtd_handlers_get_counts(handlers, &received);
    mtd_transfer_stats transfer;
    mtd_transfers_get_stats(transfers, &transfer);
    mtd_error_summary error;
    mtd_error_log_get(errors, &error);
    out->submissions = received.submissions + transfer.completed;
    out->builds = mtd_submitter_builds(submitter);
    out->queries = received.queries;
    out->errors = error.count;
    out->duplicates = mtd_replies_duplicates(replies);
}

void mtd_heartbeat_publish(const mtd_heartbeat_sources *src)
{
    mtd_store_totals totals;
    mtd_store_get_totals(src->store, &totals);
    mtd_pool_stats pool;
    mtd_pool_get_stats(src->pool, &pool);
    mtd_error_summary errors;
    mtd_error_log_get(src->errors, &errors);
    mtd_counters counts;
    mtd_counters_get(src->handlers, src->transfers, src->submitter, src->errors, src->replies,
                     &counts);
    mtd_transfer_stats transfers;
    mtd_transfers_get_stats(src->transfers, &transfers);

    meshtopo_status_t st;
    memset(&st, 0, sizeof st);
    st.utime = mtd_now_utime();
    st.name = (char *)src->config->name;
    st.instance = (char *)src->instance;
    st.pid = (int32_t)getpid();
    st.uptime_us = st.utime - src->start_utime;
    st.channel_prefix = (char *)src->config->channel_prefix;
    st.meshes_held = (int32_t)totals.ids;
    st.versions_held = (int32_t)totals.versions;
    st.memory_bytes = (int64_t)totals.memory_bytes;
    st.submissions = counts.submissions;
    st.builds = counts.builds;
    st.queries = counts.queries;
    st.errors = counts.errors;
    st.duplicate_requests = counts.duplicates;
    st.worker_threads = (int32_t)pool.threads;
    st.builds_in_progress = (int32_t)pool.running;
    st.builds_queued = (int32_t)pool.queued;
    st.last_error = errors.last;
    st.last_error_utime = errors.last_utime;
    st.transfers_active = transfers.active;
    st.transfer_bytes = transfers.bytes;
    st.chunks = transfers.chunks;
    st.transfers_completed = transfers.completed;
    st.transfers_expired = transfers.expired;
    st.transfers_refused = transfers.refused;
    st.memory_budget = (int64_t)mtd_budget_bytes(src->budget);
    if (src->catalog) {
        st.archive_errors = 0;
        mtd_catalog_stats(src->catalog, &st);
        mtd_writer_stats(src->writer, &st);
        st.archive_evictions = mtd_budget_evictions(src->budget);
    }
    st.cluster = "";
    if (src->cluster) {
        mtd_cluster_view view;
        mtd_cluster_get_view(src->cluster, &view);
        st.cluster = (char *)mtd_cluster_name(src->cluster);
        st.cluster_members = view.members;
        st.cluster_share = view.share;
        st.cluster_view = (int64_t)view.hash;
    }

    int size = meshtopo_status_t_encoded_size(&st);
    void *buf = size > 0 ? malloc((size_t)size) : NULL;
    if (buf && meshtopo_status_t_encode(buf, 0, size, &st) == size)
        lcm_publish(src->lcm, src->status_channel, buf, (unsigned)size);
    else
        mtd_log(MTD_LOG_ERROR, "heartbeat", "cannot encode the status message");
    free(buf);
}
