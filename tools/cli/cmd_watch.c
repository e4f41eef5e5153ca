/* `meshtopo watch`: print every report meshtopod publishes on PREFIX TOPOLOGY
 * (one per build) and every heartbeat on PREFIX STATUS as it arrives, one
 * line each (JSON Lines with --json), through the client's watch
 * (mt_client_watch_start). The callbacks print on the client's thread under
 * one lock; the main thread waits for --count, --timeout-ms, SIGINT or SIGTERM. */
#include <inttypes.h>
#include <pthread.h>
#include <signal.h>
#include <string.h>
#include <time.h>

#include "remote.h"

static const cli_option options[] = {
    {"json", NULL, "print each message as one line of JSON: {channel, type, message}"},
    {"count", "N", "stop after N messages (default: run until SIGINT)"},
    CLI_REMOTE_OPTIONS,
};

static volatile sig_atomic_t interrupted;

static void on_sigint(int sig)
{
    (void)sig;
    interrupted = 1;
}

/* Shared by the callbacks (client's thread) and the waiting main thread. */
typedef struct watch_state {
    pthread_mutex_t lock;
    pthread_cond_t printed_one;
    bool json;
    long count;     /* stop after this many messages; 0 = never */
    long printed;   /* messages printed */
    double last_ms; /* when the last one was printed (or the watch started) */
    char topology_channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
    char status_channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
} watch_state;

static void status_json(mt_json *j, const meshtopo_status_t *s)
{
    mt_json_object_begin(j);
#define FIELD_INT(name)    \
    mt_json_key(j, #name); \
    mt_json_int(j, s->name)
#define FIELD_STR(name)    \
    mt_json_key(j, #name); \
    mt_json_string(j, s->name)
    FIELD_INT(utime);
    FIELD_STR(name);
    FIELD_STR(instance);
    FIELD_INT(pid);
    FIELD_INT(uptime_us);
    FIELD_STR(channel_prefix);
    FIELD_INT(meshes_held);
    FIELD_INT(versions_held);
    FIELD_INT(memory_bytes);
    FIELD_INT(submissions);
    FIELD_INT(builds);
    FIELD_INT(queries);
    FIELD_INT(errors);
    FIELD_INT(duplicate_requests);
    FIELD_INT(worker_threads);
    FIELD_INT(builds_in_progress);
    FIELD_INT(builds_queued);
    FIELD_STR(last_error);
    FIELD_INT(last_error_utime);
    FIELD_INT(archive_versions);
    FIELD_INT(archive_writes);
    FIELD_INT(archive_errors);
    FIELD_INT(archive_loads);
    FIELD_INT(archive_evictions);
    FIELD_INT(archive_backlog);
    FIELD_INT(archive_bytes);
    FIELD_INT(memory_budget);
    FIELD_STR(cluster);
    FIELD_INT(cluster_members);
    mt_json_key(j, "cluster_share");
    mt_json_double(j, s->cluster_share);
    FIELD_INT(cluster_view);
#undef FIELD_INT
#undef FIELD_STR
    mt_json_object_end(j);
}

static void status_text(const char *channel, const meshtopo_status_t *s)
{
    printf("%s %s pid %" PRId32 " up %.1f s: %" PRId32 " meshes (%" PRId32 " versions), %" PRId64
           " bytes; %" PRId64 " submissions, %" PRId64 " builds, %" PRId64 " queries, %" PRId64
           " errors; %" PRId32 " workers (%" PRId32 " building, %" PRId32 " queued)",
           channel, s->name, s->pid, (double)s->uptime_us / 1e6, s->meshes_held, s->versions_held,
           s->memory_bytes, s->submissions, s->builds, s->queries, s->errors, s->worker_threads,
           s->builds_in_progress, s->builds_queued);
    if (s->archive_versions || s->archive_writes || s->archive_errors || s->memory_budget)
        printf("; archive: %" PRId32 " versions (%" PRId64 " bytes), %" PRId64 " written, %" PRId64
               " loaded, %" PRId64 " evicted, %" PRId32 " waiting, %" PRId64 " errors",
               s->archive_versions, s->archive_bytes, s->archive_writes, s->archive_loads,
               s->archive_evictions, s->archive_backlog, s->archive_errors);
    if (s->cluster[0])
        printf("; cluster %s: %" PRId32 " members, owns %.1f %% of mesh ids (view %016" PRIx64 ")",
               s->cluster, s->cluster_members, 100.0 * s->cluster_share, (uint64_t)s->cluster_view);
    if (s->last_error[0]) printf("; last error: %s", s->last_error);
    putchar('\n');
}

/* One JSON line {channel, type, message}; the message written by the caller's
 * writer. */
static void json_line_begin(mt_json *j, const char *channel, const mt_msgs_type *type)
{
    mt_json_init(j, stdout);
    j->compact = true;
    mt_json_object_begin(j);
    mt_json_key(j, "channel");
    mt_json_string(j, channel);
    mt_json_key(j, "type");
    mt_json_string(j, type->name);
    mt_json_key(j, "message");
}

static void json_line_end(mt_json *j)
{
    mt_json_object_end(j);
    mt_json_finish(j);
}

/* Whether another message may be printed; call with the lock held. */
static bool wants_more(const watch_state *w)
{
    return w->count == 0 || w->printed < w->count;
}

/* After printing one message; call with the lock held. */
static void message_printed(watch_state *w)
{
    fflush(stdout);
    w->printed++;
    w->last_ms = cli_now_ms();
    pthread_cond_signal(&w->printed_one);
}

static void on_status(const meshtopo_status_t *status, void *user)
{
    watch_state *w = user;
    pthread_mutex_lock(&w->lock);
    if (wants_more(w)) {
        if (w->json) {
            mt_json j;
            json_line_begin(&j, w->status_channel, &mt_msgs_type_status);
            status_json(&j, status);
            json_line_end(&j);
        } else {
            status_text(w->status_channel, status);
        }
        message_printed(w);
    }
    pthread_mutex_unlock(&w->lock);
}

static void on_topology(const meshtopo_topology_t *topology, void *user)
{
    watch_state *w = user;
    cli_report report;
    mt_diag diag;
    mt_status st = cli_report_from_topology(topology, &report, &diag);
    pthread_mutex_lock(&w->lock);
    if (st != MT_OK) {
        cli_error("watch", "%s: undecodable %s: %s", w->topology_channel,
                  mt_msgs_type_topology.name, diag.message);
    } else if (wants_more(w)) {
        if (w->json) {
            mt_json j;
            json_line_begin(&j, w->topology_channel, &mt_msgs_type_topology);
            cli_report_write_json(&j, &report);
            json_line_end(&j);
        } else {
            cli_report_print_line(&report, w->topology_channel, stdout);
        }
        message_printed(w);
    }
    pthread_mutex_unlock(&w->lock);
    cli_report_free(&report);
}

/* Waits until --count messages were printed, a signal came or (with
 * --timeout-ms) nothing came for that long; reports messages the client
 * could not decode. Returns the exit code. */
static int wait_for_end(watch_state *w, mt_client *client, const cli_remote *remote)
{
    int code = CLI_EXIT_OK;
    uint64_t undecodable = 0;
    pthread_mutex_lock(&w->lock);
    while (!interrupted && wants_more(w)) {
        if (remote->timeout_given && cli_now_ms() - w->last_ms > remote->timeout_ms) {
            cli_error("watch", "no message on %s or %s for %d ms", w->topology_channel,
                      w->status_channel, remote->timeout_ms);
            code = CLI_EXIT_NO_ANSWER;
            break;
        }
        struct timespec wake;
        clock_gettime(CLOCK_MONOTONIC, &wake);
        wake.tv_nsec += 100 * 1000 * 1000;
        if (wake.tv_nsec >= 1000000000L) {
            wake.tv_sec++;
            wake.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&w->printed_one, &w->lock, &wake);
        mt_client_stats stats;
        mt_client_get_stats(client, &stats);
        if (stats.undecodable > undecodable)
            cli_error("watch", "%s or %s: %" PRIu64 " undecodable message(s)", w->topology_channel,
                      w->status_channel, stats.undecodable - undecodable);
        undecodable = stats.undecodable;
    }
    pthread_mutex_unlock(&w->lock);
    return code;
}

static int run_watch(const cli_args *args)
{
    cli_remote remote;
    int code = cli_remote_parse(args, &remote);
    if (code != CLI_EXIT_OK) return code;
    int count = 0;
    const char *count_text = cli_arg(args, "count");
    if (count_text && (!cli_parse_int(count_text, &count) || count == 0)) {
        cli_error("watch", "--count: expected a positive count, got '%s'", count_text);
        return CLI_EXIT_USAGE;
    }
    watch_state w;
    memset(&w, 0, sizeof w);
    w.json = cli_flag(args, "json");
    w.count = count;
    /* The prefix is checked when the client is created; the names are only
     * printed. */
    mt_msgs_channel_name(remote.prefix, MT_MSGS_CHANNEL_TOPOLOGY, w.topology_channel);
    mt_msgs_channel_name(remote.prefix, MT_MSGS_CHANNEL_STATUS, w.status_channel);

    /* SIGINT and SIGTERM go to this thread only: the client's thread starts
     * with them blocked. */
    sigset_t stop_signals, old_mask;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT);
    sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, &old_mask);
    mt_client *client = NULL;
    code = cli_client_create("watch", &remote, &client);
    if (code != CLI_EXIT_OK) {
        pthread_sigmask(SIG_SETMASK, &old_mask, NULL);
        return code;
    }
    struct sigaction sa, old_int, old_term;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    pthread_sigmask(SIG_SETMASK, &old_mask, NULL);

    pthread_mutex_init(&w.lock, NULL);
    pthread_condattr_t attr;
    pthread_condattr_init(&attr);
    pthread_condattr_setclock(&attr, CLOCK_MONOTONIC);
    pthread_cond_init(&w.printed_one, &attr);
    pthread_condattr_destroy(&attr);
    w.last_ms = cli_now_ms();
    mt_client_watch_fns fns = {on_status, on_topology, &w};
    mt_client_watch *watch = NULL;
    mt_diag diag;
    mt_status st = mt_client_watch_start(client, &fns, &watch, &diag);
    if (st != MT_OK) {
        cli_error("watch", "cannot watch %s and %s: %s", w.topology_channel, w.status_channel,
                  diag.message[0] ? diag.message : mt_strerror(st));
        code = CLI_EXIT_NO_ANSWER;
    } else {
        code = wait_for_end(&w, client, &remote);
    }
    mt_client_watch_stop(watch); /* no callback runs past here */
    mt_client_destroy(client);
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    pthread_cond_destroy(&w.printed_one);
    pthread_mutex_destroy(&w.lock);
    return code;
}

const cli_command cli_cmd_watch = {
    .name = "watch",
    .summary = "print meshtopod's topology reports and heartbeats as they arrive",
    .synopsis = "[--json] [--count N] [--timeout-ms MS] [--lcm-url URL] [--prefix PREFIX]",
    .description =
        "Subscribes to PREFIX TOPOLOGY (the report of every build) and PREFIX STATUS (the\n"
        "daemon's heartbeat, once a second) and prints each message decoded on one line;\n"
        "with --json one JSON object per line: {channel, type, message}. Stops after\n"
        "--count messages, on SIGINT or SIGTERM, or (with --timeout-ms) when nothing arrives\n"
        "for that long. --retries is accepted and ignored.\n"
        "\n"
        "exit codes: 0 stopped (count reached or interrupted), 2 usage error, 6 nothing\n"
        "arrived within --timeout-ms, or LCM could not be used.\n",
    .options = options,
    .num_options = sizeof options / sizeof options[0],
    .min_positionals = 0,
    .max_positionals = 0,
    .run = run_watch,
};
