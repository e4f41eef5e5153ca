/* meshtopod's lifecycle (daemon.h): every module is created here, given the
 * modules below it, and destroyed here in reverse order once the workers
 * that use them have stopped. Runs on the thread that runs LCM. */
#include "daemon.h"

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "archive_catalog.h"
#include "archive_writer.h"
#include "clock.h"
#include "error_log.h"
#include "handlers.h"
#include "heartbeat.h"
#include "query_route.h"
#include "reply.h"
#include "submit.h"
#include "transfer.h"
#include "worker_pool.h"

/* Builds waiting for a worker before submissions are answered BUSY. */
#define BUILD_QUEUE_CAPACITY 256
/* Builds one reply channel may have admitted at once: a quarter of the queue. */
#define BUILDS_PER_SENDER (BUILD_QUEUE_CAPACITY / 4)

struct mtd_daemon {
    mtd_config config;
    lcm_t *lcm;                                                         /* not owned */
    char channels[MT_MSGS_CHANNEL_COUNT][MT_MSGS_CHANNEL_NAME_MAX + 1]; /* PREFIX + suffix */
    char instance[128];
    int64_t start_utime;
    bool stopped;

    mtd_error_log *errors;
    mtd_content_pool *contents;
    mtd_workspace_pool *workspaces;
    mtd_store *store;
    mtd_pool *pool;
    mtd_replies *replies;
    mtd_budget *budget;   /* --memory-budget (0: none) */
    mtd_catalog *catalog; /* NULL without --archive */
    mtd_writer *writer;   /* NULL without --archive */
    mtd_admission *admission;
    mtd_submitter *submitter;
    mtd_transfers *transfers;
    mtd_queries *queries;
    mtd_handlers *handlers;
    mtd_peers *peers;
    mtd_cluster *cluster;     /* NULL without --cluster */
    int64_t second_rescan_us; /* monotonic time of the rescan after a view change, 0 = none */
};

/* Names every channel; MT_ERR_INVALID_ARG when the prefix makes one too long. */
static mt_status name_channels(mtd_daemon *d, mt_diag *diag)
{
    const char *prefix = d->config.channel_prefix;
    for (int c = 0; c < MT_MSGS_CHANNEL_COUNT; c++) {
        if (mt_msgs_channel_name(prefix, (mt_msgs_channel)c, d->channels[c]) != MT_OK) {
            if (diag) {
                mt_diag_clear(diag);
                diag->status = MT_ERR_INVALID_ARG;
                snprintf(diag->message, sizeof diag->message,
                         "channel prefix '%s': %s%s is longer than LCM's %d bytes", prefix, prefix,
                         mt_msgs_channel_suffix((mt_msgs_channel)c), MT_MSGS_CHANNEL_NAME_MAX);
            }
            return MT_ERR_INVALID_ARG;
        }
    }
    return MT_OK;
}

/* Creates the modules, each after those it uses. */
/* Loads every version the catalog keeps through the store, until the
 * memory budget is reached (--preload). */
static void preload(mtd_daemon *d)
{
    mtd_store_listing *listing = NULL;
    if (mtd_store_list(d->store, &listing) != MT_OK) return;
    size_t loaded = 0, kept = mtd_catalog_count(d->catalog);
    const uint64_t budget = mtd_budget_bytes(d->budget);
    for (size_t i = 0; i < listing->num_ids; i++) {
        const mtd_listed_id *row = &listing->ids[i];
        for (uint32_t v = 0; v < row->num_versions; v++) {
            mtd_store_totals totals;
            mtd_store_get_totals(d->store, &totals);
            if (budget && totals.memory_bytes >= budget) goto done;
            mtd_mesh_entry *entry = NULL;
            mt_diag load_diag;
            mtd_fetch_result r = mtd_store_fetch(d->store, row->id, row->versions[v].version, true,
                                                 &entry, &load_diag);
            if (r == MTD_FETCH_LOAD_FAILED) {
                char text[MTD_ERROR_MAX];
                snprintf(text, sizeof text, "archive_load: %.400s", load_diag.message);
                mtd_error_log_note(d->errors, text);
            }
            if (r != MTD_FETCH_OK) continue;
            mtd_entry_release(entry);
            loaded++;
        }
    }
done:
    mtd_store_listing_free(listing);
    mtd_store_trim(d->store);
    mtd_log(MTD_LOG_INFO, "preload", "loaded=%zu of %zu", loaded, kept);
}

/* --archive DIR: the catalog (the store's backing) and the writer (its
 * archiving policy), then --preload. */
static mt_status open_archive(mtd_daemon *d, mt_diag *diag)
{
    const mtd_config *c = &d->config;
    if (!c->archive_dir[0]) {
        if (c->memory_budget)
            mtd_log(MTD_LOG_WARN, "archive",
                    "--memory-budget without --archive: nothing can be evicted");
        return MT_OK;
    }
    mt_status s = mtd_writer_check_compression(c->archive_compression, diag);
    if (s == MT_OK) s = mtd_catalog_open(c, d->errors, &d->catalog, diag);
    if (s == MT_OK) s = mtd_writer_create(c, d->catalog, d->budget, d->errors, &d->writer, diag);
    if (s != MT_OK) return s;
    mtd_store_backing backing;
    mtd_catalog_backing(d->catalog, &backing);
    mtd_store_set_backing(d->store, &backing);
    mtd_store_policy policy;
    mtd_writer_policy(d->writer, &policy);
    mtd_store_set_policy(d->store, &policy);
    if (c->preload) preload(d);
    return MT_OK;
}

static mt_status create_modules(mtd_daemon *d, mt_diag *diag)
{
    const mtd_config *c = &d->config;
    if (mtd_error_log_create(&d->errors) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "error log");
    if (mtd_content_pool_create(&d->contents) != MT_OK ||
        mtd_workspace_pool_create(&d->workspaces) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "kept buffers");
    if (c->prepare_faces) {
        const int64_t start = mtd_now_utime();
        if (mtd_workspace_pool_prepare(d->workspaces, c->prepare_faces, diag) != MT_OK)
            return diag ? diag->status : MT_ERR_NOMEM;
        mtd_log(MTD_LOG_INFO, "prepared", "faces=%u bytes=%zu ms=%.1f", c->prepare_faces,
                mtd_workspace_pool_bytes(d->workspaces), (double)(mtd_now_utime() - start) / 1e3);
    }
    if (mtd_budget_create(c->memory_budget, &d->budget) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "memory budget");
    mtd_store_options store_options = {
        .max_versions_per_id = c->max_versions,
        .max_bytes = (size_t)c->max_store_bytes,
        .dispose_mesh = mtd_workspace_recycle_mesh,
        .dispose_mesh_ctx = d->workspaces,
        .budget = d->budget,
    };
    if (mtd_store_create(&store_options, &d->store) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "mesh store");
    if (mtd_pool_create(c->workers, BUILD_QUEUE_CAPACITY, &d->pool) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "worker pool");
    if (mtd_replies_create(d->lcm, c->channel_prefix, d->errors, &d->replies) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "request cache");
    mt_status s = open_archive(d, diag);
    if (s != MT_OK) return s;
    mtd_admission_limits limits = {
        .max_store_bytes = c->max_store_bytes,
        .max_archive_bytes = c->archive_dir[0] ? c->max_archive_bytes : 0,
        .max_claim_ratio = c->max_claim_ratio,
        .builds_per_sender = BUILDS_PER_SENDER};
    if (mtd_admission_create(&limits, &d->admission) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "admission");
    mtd_submit_deps submit = {.config = c,
                              .lcm = d->lcm,
                              .topology_channel = d->channels[MT_MSGS_CHANNEL_TOPOLOGY],
                              .pool = d->pool,
                              .replies = d->replies,
                              .catalog = d->catalog,
                              .store = d->store,
                              .admission = d->admission,
                              .workspaces = d->workspaces,
                              .contents = d->contents};
    if (mtd_submitter_create(&submit, &d->submitter) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "submitter");
    mtd_transfer_deps transfer = {.config = c,
                                  .replies = d->replies,
                                  .submitter = d->submitter,
                                  .contents = d->contents,
                                  .cluster = d->cluster};
    if (mtd_transfers_create(&transfer, &d->transfers) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "transfer table");
    if (mtd_queries_create(d->store, d->pool, d->replies, d->cluster, &d->queries) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "query handler");
    mtd_handler_deps handlers = {.lcm = d->lcm,
                                 .prefix = c->channel_prefix,
                                 .instance = d->instance,
                                 .replies = d->replies,
                                 .submitter = d->submitter,
                                 .transfers = d->transfers,
                                 .queries = d->queries,
                                 .cluster = d->cluster,
                                 .catalog = d->catalog};
    if (mtd_handlers_subscribe(&handlers, &d->handlers) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "LCM subscriptions");
    if (mtd_peers_create(d->lcm, d->channels[MT_MSGS_CHANNEL_STATUS], d->instance, d->start_utime,
                         d->errors, d->cluster, &d->peers) != MT_OK)
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "watch for other daemons");
    return MT_OK;
}

void mtd_daemon_instance_name(int64_t start_utime, char *out, size_t size)
{
    char host[64] = "";
    gethostname(host, sizeof host - 1);
    snprintf(out, size, "%s:%d:%" PRId64, host, (int)getpid(), start_utime);
}

mt_status mtd_daemon_cluster_create(const mtd_config *config, const char *instance,
                                    mtd_cluster **out_cluster)
{
    *out_cluster = NULL;
    if (!config->cluster[0]) return MT_OK;
    mtd_cluster_options members = {.name = config->cluster,
                                   .instance = instance,
                                   .member_name = config->name,
                                   .expiry_us = mtd_cluster_expiry_us(config->heartbeat_ms),
                                   .ignored_name = config->test_ignore_member};
    return mtd_cluster_create(&members, out_cluster);
}

mt_status mtd_daemon_create(const mtd_config *config, lcm_t *lcm, mtd_cluster *cluster,
                            mtd_daemon **out_daemon, mt_diag *diag)
{
    *out_daemon = NULL;
    mtd_daemon *d = calloc(1, sizeof *d);
    if (!d) {
        mtd_cluster_destroy(cluster);
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "daemon");
    }
    d->config = *config;
    d->lcm = lcm;
    d->start_utime = mtd_now_utime();
    d->cluster = config->cluster[0] ? cluster : NULL;
    if (cluster && !d->cluster) mtd_cluster_destroy(cluster);
    if (d->cluster)
        snprintf(d->instance, sizeof d->instance, "%s", mtd_cluster_instance(d->cluster));
    else
        mtd_daemon_instance_name(d->start_utime, d->instance, sizeof d->instance);
    if (!d->cluster && mtd_daemon_cluster_create(config, d->instance, &d->cluster) != MT_OK) {
        free(d);
        return mt_diag_set(diag, MT_ERR_NOMEM, "cannot create the %s", "cluster membership");
    }
    /* lcm-gen's fingerprints are computed lazily without a lock: do it now,
     * before any worker thread encodes. */
    mt_msgs_type_of(NULL, 0);

    mt_status s;
    if ((s = name_channels(d, diag)) != MT_OK || (s = create_modules(d, diag)) != MT_OK) {
        mtd_daemon_destroy(d);
        return s;
    }
    *out_daemon = d;
    return MT_OK;
}

void mtd_daemon_heartbeat(mtd_daemon *d)
{
    mtd_heartbeat_sources sources = {.config = &d->config,
                                     .lcm = d->lcm,
                                     .status_channel = d->channels[MT_MSGS_CHANNEL_STATUS],
                                     .instance = d->instance,
                                     .start_utime = d->start_utime,
                                     .store = d->store,
                                     .pool = d->pool,
                                     .errors = d->errors,
                                     .replies = d->replies,
                                     .handlers = d->handlers,
                                     .submitter = d->submitter,
                                     .transfers = d->transfers,
                                     .catalog = d->catalog,
                                     .writer = d->writer,
                                     .budget = d->budget,
                                     .cluster = d->cluster};
    mtd_heartbeat_publish(&sources);
}

static bool owned(void *cluster, const char *id)
{
    return mtd_cluster_owns(cluster, id);
}

void mtd_daemon_watch_cluster(mtd_daemon *d)
{
    if (!d->cluster || d->stopped) return;
    const int64_t now = mtd_monotonic_us();
    if (mtd_cluster_refresh(d->cluster, now)) {
        /* Ids gained are served from what their former owner archived; the
         * rescan runs before this thread handles another request. */
        size_t found = mtd_catalog_rescan(d->catalog);
        size_t dropped = mtd_store_remove_unless(d->store, owned, d->cluster);
        mtd_cluster_view view;
        mtd_cluster_get_view(d->cluster, &view);
        mtd_log(MTD_LOG_INFO, "cluster_view",
                "cluster=%s members=%" PRId32 " share=%.3f view=%016" PRIx64
                " archived_versions_found=%zu dropped_from_memory=%zu members_seen=[%s]",
                mtd_cluster_name(d->cluster), view.members, view.share, view.hash, found, dropped,
                view.names);
        /* Versions the former owners wrote before they too saw the change. */
        d->second_rescan_us = now + mtd_cluster_expiry_us(d->config.heartbeat_ms);
    } else if (d->second_rescan_us && now >= d->second_rescan_us) {
        d->second_rescan_us = 0;
        mtd_catalog_rescan(d->catalog);
    }
}

void mtd_daemon_tick(mtd_daemon *d)
{
    mtd_transfers_expire(d->transfers);
    mtd_replies_expire(d->replies);
    /* Versions the async writer archived since may now be dropped. */
    mtd_store_trim(d->store);
#ifdef __GLIBC__
    /* Memory freed after a burst (answers of a query flood, decoded
     * messages) stays in malloc's arenas otherwise: give it back. */
    malloc_trim(0);
#endif
    mtd_daemon_heartbeat(d);
}

void mtd_daemon_stop(mtd_daemon *d)
{
    if (!d || d->stopped) return;
    d->stopped = true;
    if (d->handlers) mtd_handlers_unsubscribe(d->handlers);
    mtd_peers_destroy(d->peers);
    d->peers = NULL;
    if (d->transfers) mtd_transfers_stop(d->transfers);
    if (d->pool) mtd_pool_shutdown(d->pool, MTD_SHUTDOWN_CANCEL);
    mtd_writer_stop(d->writer);
}

void mtd_daemon_destroy(mtd_daemon *d)
{
    if (!d) return;
    mtd_daemon_stop(d);
    mtd_handlers_destroy(d->handlers);
    mtd_pool_destroy(d->pool); /* no worker runs past here */
    mtd_queries_destroy(d->queries);
    mtd_transfers_destroy(d->transfers);
    mtd_submitter_destroy(d->submitter);
    mtd_admission_destroy(d->admission);
    mtd_writer_destroy(d->writer);
    mtd_replies_destroy(d->replies);
    mtd_store_destroy(d->store);     /* its meshes go to the workspace pool: destroyed next */
    mtd_catalog_destroy(d->catalog); /* the store's backing: after the store */
    mtd_budget_destroy(d->budget);
    mtd_workspace_pool_destroy(d->workspaces);
    mtd_content_pool_destroy(d->contents);
    mtd_error_log_destroy(d->errors);
    mtd_cluster_destroy(d->cluster);
    free(d);
}

bool mtd_daemon_other_seen(mtd_daemon *d, char *who, size_t who_size)
{
    return d->peers && mtd_peers_older_seen(d->peers, who, who_size);
}

const char *mtd_daemon_instance(const mtd_daemon *d)
{
    return d->instance;
}

const char *mtd_daemon_channel(const mtd_daemon *d, mt_msgs_channel channel)
{
    return (unsigned)channel < MT_MSGS_CHANNEL_COUNT ? d->channels[channel] : "";
}

void mtd_daemon_get_counts(mtd_daemon *d, mtd_counters *out)
{
    mtd_counters_get(d->handlers, d->transfers, d->submitter, d->errors, d->replies, out);
}

mtd_store *mtd_daemon_store(mtd_daemon *d)
{
    return d->store;
}

mtd_content_pool *mtd_daemon_content_pool(mtd_daemon *d)
{
    return d->contents;
}

mtd_workspace_pool *mtd_daemon_workspace_pool(mtd_daemon *d)
{
    return d->workspaces;
}

mtd_transfers *mtd_daemon_transfers(mtd_daemon *d)
{
    return d->transfers;
}
