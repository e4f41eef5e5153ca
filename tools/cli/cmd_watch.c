/* `meshtopo watch`: subscribe to PREFIX TOPOLOGY (a report per build) and
 * PREFIX STATUS (the daemon's heartbeat) and print every message decoded,
 * one line each (JSON Lines with --json). Bytes from the network are decoded
 * only with mt_msgs_decode; the loop waits with lcm_get_fileno + poll so
 * SIGINT, --count and --timeout-ms stop it cleanly. */
#include <errno.h>
#include <inttypes.h>
#include <lcm/lcm.h>
#include <poll.h>
#include <signal.h>
#include <string.h>

#include "remote.h"

static const mt_cli_option options[] = {
    {"json", NULL, "print each message as one line of JSON: {channel, type, message}"},
    {"count", "N", "stop after N messages (default: run until SIGINT)"},
    MT_CLI_REMOTE_OPTIONS,
};

static volatile sig_atomic_t interrupted;

static void on_sigint(int sig)
{
    (void)sig;
    interrupted = 1;
}

typedef struct watch_state {
    bool json;
    long printed;
    char topology_channel[64];
    char status_channel[64];
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
    if (s->last_error[0]) printf("; last error: %s", s->last_error);
    putchar('\n');
}

static void topology_text(const char *channel, const meshtopo_topology_t *t)
{
    printf("%s %s version %" PRId32 ": V %" PRId32 ", F %" PRId32 " (%" PRId32 " valid), E %" PRId64
           "; %" PRId64 " boundary edges in %" PRId32 " loops; %" PRId32
           " components; Euler characteristic %" PRId64 "; %s, %s, %s; %" PRId64
           " defects; built in %.3f ms\n",
           channel, t->mesh_id, t->version, t->num_verts, t->num_faces, t->num_faces_valid,
           t->num_edges, t->boundary_edges, t->boundary_loops, t->connected_components,
           t->euler_characteristic, t->closed ? "closed" : "open",
           t->manifold ? "manifold" : "non-manifold",
           t->orientable ? "orientable" : "non-orientable", t->num_defects,
           (double)t->build_duration_us / 1000.0);
}

static void on_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    watch_state *w = user;
    bool is_status = strcmp(channel, w->status_channel) == 0;
    const mt_msgs_type *type = is_status ? &mt_msgs_type_status : &mt_msgs_type_topology;
    union {
        meshtopo_status_t status;
        meshtopo_topology_t topology;
    } msg;
    char error[MT_MSGS_ERROR_SIZE];
    if (mt_msgs_decode(type, rbuf->data, rbuf->data_size, &msg, error, sizeof error) != 0) {
        mt_cli_error("watch", "%s: undecodable %s: %s", channel, type->name, error);
        return;
    }
    if (w->json) {
        mt_json j;
        mt_json_init(&j, stdout);
        j.compact = true;
        mt_json_object_begin(&j);
        mt_json_key(&j, "channel");
        mt_json_string(&j, channel);
        mt_json_key(&j, "type");
        mt_json_string(&j, type->name);
        mt_json_key(&j, "message");
        if (is_status)
            status_json(&j, &msg.status);
        else
            mt_cli_topology_write_json(&j, &msg.topology);
        mt_json_object_end(&j);
        mt_json_finish(&j);
    } else if (is_status) {
        status_text(channel, &msg.status);
    } else {
        topology_text(channel, &msg.topology);
    }
    fflush(stdout);
    type->decode_cleanup(&msg);
    w->printed++;
}

static int run_watch(const mt_cli_args *args)
{
    mt_cli_remote remote;
    int code = mt_cli_remote_parse(args, &remote);
    if (code != MT_CLI_EXIT_OK) return code;
    int count = 0;
    const char *count_text = mt_cli_arg(args, "count");
    if (count_text && (!mt_cli_parse_int(count_text, &count) || count == 0)) {
        mt_cli_error("watch", "--count: expected a positive count, got '%s'", count_text);
        return MT_CLI_EXIT_USAGE;
    }
    watch_state w;
    memset(&w, 0, sizeof w);
    w.json = mt_cli_flag(args, "json");
    snprintf(w.topology_channel, sizeof w.topology_channel, "%sTOPOLOGY", remote.prefix);
    snprintf(w.status_channel, sizeof w.status_channel, "%sSTATUS", remote.prefix);

    /* Compute every fingerprint once (msgs.h, Threads). */
    (void)mt_msgs_type_of(NULL, 0);
    lcm_t *lcm = lcm_create(remote.lcm_url);
    if (!lcm) {
        mt_cli_error("watch", "cannot talk LCM (%s)",
                     remote.lcm_url ? remote.lcm_url : "default URL");
        return MT_CLI_EXIT_NO_ANSWER;
    }
    lcm_subscription_t *subs[2] = {lcm_subscribe(lcm, w.topology_channel, on_message, &w),
                                   lcm_subscribe(lcm, w.status_channel, on_message, &w)};
    struct sigaction sa, old_int, old_term;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);

    double last = mt_cli_now_ms();
    while (!interrupted && (count == 0 || w.printed < count)) {
        struct pollfd pfd = {lcm_get_fileno(lcm), POLLIN, 0};
        int ready = poll(&pfd, 1, 100);
        if (ready < 0 && errno != EINTR) {
            mt_cli_error("watch", "poll: %s", strerror(errno));
            code = MT_CLI_EXIT_NO_ANSWER;
            break;
        }
        if (ready > 0) {
            long before = w.printed;
            if (lcm_handle(lcm) != 0) {
                mt_cli_error("watch", "LCM stopped receiving");
                code = MT_CLI_EXIT_NO_ANSWER;
                break;
            }
            if (w.printed != before) last = mt_cli_now_ms();
        }
        if (remote.timeout_given && mt_cli_now_ms() - last > remote.timeout_ms) {
            mt_cli_error("watch", "no message on %s or %s for %d ms", w.topology_channel,
                         w.status_channel, remote.timeout_ms);
            code = MT_CLI_EXIT_NO_ANSWER;
            break;
        }
    }
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    for (int i = 0; i < 2; i++)
        if (subs[i]) lcm_unsubscribe(lcm, subs[i]);
    lcm_destroy(lcm);
    return code;
}

const mt_cli_command mt_cli_cmd_watch = {
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
