/* `meshtopo replay DIR`: publishes archived meshes as submissions to
 * meshtopod (or any node answering the submission protocol), in utime order
 * with their original spacing divided by --rate, each from a client named
 * after the archived source. Prints one line (or JSON object) per mesh: the
 * archived and the newly assigned version and whether the daemon's content
 * hash equals the archived one (for archive formats 1 and 2, that of the
 * archived face list). On a terminal a progress line goes to stderr. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cmd_replay.h"
#include "remote.h"

static const cli_option options[] = {
    {"rate", "X", "speed factor 0.001..1e9: 2 = twice as fast, 0 = no waiting (default 1)"},
    {"as-fast-as-possible", NULL, "the same as --rate 0"},
    {"ids", "ID,...", "replay only these mesh ids (every archived version of each)"},
    {"since", "T", "only meshes with utime >= T (microseconds or 2026-11-22T08:00:00Z)"},
    {"until", "T", "only meshes with utime < T (microseconds or ISO 8601 UTC)"},
    {"channel", "CHANNEL", "submit on CHANNEL (\"XYZ_SUBMIT\") or with prefix \"XYZ_\""},
    {"json", NULL, "one JSON object per mesh and line, with send and ack times"},
    {"quiet", NULL, "no progress line (there is none either when stderr is not a terminal)"},
    CLI_REMOTE_OPTIONS,
};

/* Clients are kept per archived source (mt_client_options.source is the
 * mesh_t.source of every submission); at most this many at once. */
#define REPLAY_MAX_CLIENTS 16

typedef struct replay_client {
    char *source;
    mt_client *client;
} replay_client;

/* The whole run's state. */
typedef struct replay {
    cli_remote remote;
    bool json, progress;
    replay_client clients[REPLAY_MAX_CLIENTS];
    size_t num_clients, next_evict;
    double start_ms;
    size_t sent, total;
    bool progress_drawn;
    double last_offset_s;
} replay;

/* ---- options -------------------------------------------------------------- */

static bool parse_rate(const char *text, double *out)
{
    char *end = NULL;
    double v = strtod(text, &end);
    /* 0 = no waiting; below 1/1000 offsets would overflow any sensible wait */
    if (!text[0] || *end != '\0' || !isfinite(v) || (v != 0 && v < 0.001) || v > 1e9) return false;
    *out = v;
    return true;
}

/* --channel: a full submission channel "PREFIXSUBMIT" or a prefix. */
static const char *channel_prefix(const char *channel, char *buf, size_t size)
{
    size_t n = strlen(channel);
    const size_t suffix = strlen("SUBMIT");
    if (n > suffix && strcmp(channel + n - suffix, "SUBMIT") == 0 && n - suffix < size) {
        memcpy(buf, channel, n - suffix);
        buf[n - suffix] = '\0';
        return buf;
    }
    return channel;
}

static int parse_options(const cli_args *args, replay *r, double *rate, cli_replay_filter *filter,
                         char *prefix_buf, size_t prefix_size)
{
    int code = cli_remote_parse(args, &r->remote);
    if (code != CLI_EXIT_OK) return code;
    const char *channel = cli_arg(args, "channel");
    if (channel) {
        if (cli_arg(args, "prefix")) {
            cli_error("replay", "--channel and --prefix both name the channel: give one");
            return CLI_EXIT_USAGE;
        }
        r->remote.prefix = channel_prefix(channel, prefix_buf, prefix_size);
        if (!r->remote.prefix[0] || strlen(r->remote.prefix) > MT_CLIENT_MAX_PREFIX) {
            cli_error("replay",
                      "--channel: expected PREFIX or PREFIXSUBMIT with a prefix of "
                      "1 to %d characters, got '%s'",
                      MT_CLIENT_MAX_PREFIX, channel);
            return CLI_EXIT_USAGE;
        }
    }
    *rate = 1.0;
    const char *text = cli_arg(args, "rate");
    if (text && !parse_rate(text, rate)) {
        cli_error("replay", "--rate: expected 0 or a number from 0.001 to 1e9, got '%s'", text);
        return CLI_EXIT_USAGE;
    }
    if (cli_flag(args, "as-fast-as-possible")) {
        if (text && *rate != 0) {
            cli_error("replay", "--as-fast-as-possible contradicts --rate %s", text);
            return CLI_EXIT_USAGE;
        }
        *rate = 0;
    }
    memset(filter, 0, sizeof *filter);
    filter->ids = cli_arg(args, "ids");
    if (filter->ids && !filter->ids[0]) {
        cli_error("replay", "--ids: expected mesh ids separated by commas");
        return CLI_EXIT_USAGE;
    }
    const char *names[2] = {"since", "until"};
    int64_t *values[2] = {&filter->since, &filter->until};
    bool *given[2] = {&filter->has_since, &filter->has_until};
    for (int i = 0; i < 2; i++) {
        text = cli_arg(args, names[i]);
        if (!text) continue;
        if (!cli_replay_parse_time(text, values[i])) {
            cli_error("replay",
                      "--%s: expected microseconds since the epoch or an ISO 8601 UTC time "
                      "like 2026-11-22T08:00:00Z, got '%s'",
                      names[i], text);
            return CLI_EXIT_USAGE;
        }
        *given[i] = true;
    }
    if (filter->has_since && filter->has_until && filter->until <= filter->since) {
        cli_error("replay", "--until must be later than --since");
        return CLI_EXIT_USAGE;
    }
    r->json = cli_flag(args, "json");
    r->progress = !cli_flag(args, "quiet") && isatty(STDERR_FILENO);
    return CLI_EXIT_OK;
}

/* ---- clients per source ------------------------------------------------------ */

/* The client sending as `source`: a kept one, or a new one (the oldest is
 * destroyed when REPLAY_MAX_CLIENTS are kept). */
static int client_for(replay *r, const char *source, mt_client **out)
{
    for (size_t i = 0; i < r->num_clients; i++)
        if (strcmp(r->clients[i].source, source) == 0) {
            *out = r->clients[i].client;
            return CLI_EXIT_OK;
        }
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm_url = r->remote.lcm_url;
    opts.channel_prefix = r->remote.prefix;
    opts.timeout_ms = r->remote.timeout_ms;
    opts.retries = r->remote.retries > 0 ? r->remote.retries : -1; /* the client's 0 = default */
    opts.source = source;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_client *client = NULL;
    mt_status st = mt_client_create(&opts, &client, &diag);
    char *copy = st == MT_OK ? strdup(source) : NULL;
    if (st != MT_OK || !copy) {
        mt_client_destroy(client);
        const char *why = st != MT_OK && diag.message[0] ? diag.message : mt_strerror(st);
        if (st == MT_ERR_INVALID_ARG) {
            cli_error("replay", "source '%s': %s", source, why);
            return CLI_EXIT_USAGE;
        }
        cli_error("replay", "cannot talk LCM (%s): %s",
                  r->remote.lcm_url ? r->remote.lcm_url : "default URL", why);
        return CLI_EXIT_NO_ANSWER;
    }
    size_t slot = r->num_clients;
    if (slot == REPLAY_MAX_CLIENTS) {
        slot = r->next_evict;
        r->next_evict = (r->next_evict + 1) % REPLAY_MAX_CLIENTS;
        mt_client_destroy(r->clients[slot].client);
        free(r->clients[slot].source);
    } else {
        r->num_clients++;
    }
    r->clients[slot].source = copy;
    r->clients[slot].client = client;
    *out = client;
    return CLI_EXIT_OK;
}

static void clients_destroy(replay *r)
{
    for (size_t i = 0; i < r->num_clients; i++) {
        mt_client_destroy(r->clients[i].client);
        free(r->clients[i].source);
    }
    r->num_clients = 0;
}

/* ---- progress and output -------------------------------------------------- */

static double seconds_since_start(const replay *r)
{
    return (cli_now_ms() - r->start_ms) / 1e3;
}

/* "replay 3/10 meshes  elapsed 1.2 s  ETA 3.4 s" on stderr, redrawn in place. */
static void progress_draw(replay *r)
{
    if (!r->progress) return;
    double elapsed = r->start_ms > 0 ? seconds_since_start(r) : 0.0;
    char eta[32] = "ETA --";
    if (r->sent == r->total)
        snprintf(eta, sizeof eta, "done");
    else if (r->last_offset_s > 0)
        snprintf(eta, sizeof eta, "ETA %.1f s",
                 r->last_offset_s > elapsed ? r->last_offset_s - elapsed : 0.0);
    else if (r->sent > 0)
        snprintf(eta, sizeof eta, "ETA %.1f s",
                 elapsed / (double)r->sent * (double)(r->total - r->sent));
    fprintf(stderr, "\rreplay %zu/%zu meshes  elapsed %.1f s  %s   ", r->sent, r->total, elapsed,
            eta);
    fflush(stderr);
    r->progress_drawn = true;
}

/* Clears the progress line so that a message or result line starts clean. */
static void progress_clear(replay *r)
{
    if (!r->progress_drawn) return;
    fprintf(stderr, "\r%70s\r", "");
    fflush(stderr);
    r->progress_drawn = false;
}

/* Sleeps until `offset_s` after the start, redrawing the progress line. */
static void wait_until(replay *r, double offset_s)
{
    for (;;) {
        double left = offset_s - seconds_since_start(r);
        if (left <= 0) return;
        double step = r->progress && left > 0.1 ? 0.1 : left;
        struct timespec ts = {(time_t)step, (long)((step - floor(step)) * 1e9)};
        nanosleep(&ts, NULL);
        progress_draw(r);
    }
}

/* What happened to one archived version. */
typedef struct replay_result {
    const mt_archive_entry *entry;
    const char *status; /* "OK", a status_code_t name, "UNREADABLE", "NO_ANSWER", "ERROR" */
    const char *error;
    bool acked;
    int32_t version;
    int64_t content_hash;
    /* What the ack's hash must equal: the archived hash, or for a file of
     * format 1 or 2 (whose hash is the former kind) the hash of what was
     * sent, computed here from the archived face list. */
    uint64_t expected_hash;
    double offset_s, sent_s, acked_s;
} replay_result;

static void result_print_json(const replay_result *res)
{
    const mt_archive_entry *e = res->entry;
    char hash[24];
    mt_json j;
    mt_json_init(&j, stdout);
    j.compact = true;
    mt_json_object_begin(&j);
    mt_json_key(&j, "mesh_id");
    mt_json_string(&j, e->mesh_id);
    mt_json_key(&j, "file");
    mt_json_string(&j, e->file_name);
    mt_json_key(&j, "source");
    mt_json_string(&j, e->source ? e->source : "");
    mt_json_key(&j, "utime");
    mt_json_int(&j, e->utime);
    mt_json_key(&j, "original_version");
    mt_json_uint(&j, e->version);
    mt_json_key(&j, "archived_content_hash");
    mt_json_string(&j, cli_hash_text((int64_t)e->content_hash, hash, sizeof hash));
    mt_json_key(&j, "status");
    mt_json_string(&j, res->status);
    mt_json_key(&j, "error");
    mt_json_string(&j, res->error ? res->error : "");
    mt_json_key(&j, "version");
    if (res->acked)
        mt_json_int(&j, res->version);
    else
        mt_json_null(&j);
    mt_json_key(&j, "content_hash");
    if (res->acked)
        mt_json_string(&j, cli_hash_text(res->content_hash, hash, sizeof hash));
    else
        mt_json_null(&j);
    mt_json_key(&j, "hash_match");
    mt_json_bool(&j, res->acked && (uint64_t)res->content_hash == res->expected_hash);
    /* Seconds after the first send: planned, actual send, ack received. */
    mt_json_key(&j, "scheduled_us");
    mt_json_int(&j, (int64_t)llround(res->offset_s * 1e6));
    mt_json_key(&j, "sent_us");
    mt_json_int(&j, (int64_t)llround(res->sent_s * 1e6));
    mt_json_key(&j, "acked_us");
    if (res->acked)
        mt_json_int(&j, (int64_t)llround(res->acked_s * 1e6));
    else
        mt_json_null(&j);
    mt_json_object_end(&j);
    mt_json_finish(&j);
}

static void result_print(replay *r, const replay_result *res)
{
    progress_clear(r);
    if (r->json) {
        result_print_json(res);
    } else if (res->acked && strcmp(res->status, "OK") == 0) {
        char got[24], want[24];
        cli_hash_text(res->content_hash, got, sizeof got);
        cli_hash_text((int64_t)res->expected_hash, want, sizeof want);
        bool same = strcmp(got, want) == 0;
        printf("%s version %u -> version %d  content hash %s %s%s\n", res->entry->mesh_id,
               res->entry->version, (int)res->version, got,
               same ? "matches the archive" : "DIFFERS from the archived ", same ? "" : want);
    } else {
        printf("%s version %u -> %s%s%s\n", res->entry->mesh_id, res->entry->version, res->status,
               res->error && res->error[0] ? ": " : "", res->error ? res->error : "");
    }
    fflush(stdout);
}

/* ---- the replay ----------------------------------------------------------------- */

/* Exit codes seen so far: the final code is the most serious one. */
static int code_worse(int a, int b)
{
    static const int rank[] = {
        [CLI_EXIT_OK] = 0,    [CLI_EXIT_DEFECT] = 1,  [CLI_EXIT_USAGE] = 5,    [CLI_EXIT_READ] = 2,
        [CLI_EXIT_BUILD] = 3, [CLI_EXIT_REFUSED] = 4, [CLI_EXIT_NO_ANSWER] = 6};
    return rank[b] > rank[a] ? b : a;
}

/* Loads, waits for and submits one planned version; returns its exit code
 * (CLI_EXIT_NO_ANSWER stops the replay). */
static int replay_one(replay *r, const mt_archive *archive, const cli_replay_item *item)
{
    const mt_archive_entry *e = item->entry;
    replay_result res = {.entry = e, .offset_s = item->offset_s};
    mt_archive_record rec;
    mt_diag diag;
    mt_diag_clear(&diag);
    if (mt_archive_load_file(archive, e->file_name, &rec, &diag) != MT_OK) {
        progress_clear(r);
        cli_error("replay", "%s", diag.message);
        res.status = "UNREADABLE";
        res.error = diag.message;
        if (r->json) result_print(r, &res);
        return CLI_EXIT_READ;
    }
    mt_client *client = NULL;
    int code = client_for(r, rec.source ? rec.source : "", &client);
    if (code != CLI_EXIT_OK) {
        mt_archive_record_free(&rec);
        return code;
    }
    if (r->start_ms == 0) r->start_ms = cli_now_ms() - item->offset_s * 1e3;
    wait_until(r, item->offset_s);
    res.sent_s = seconds_since_start(r);
    mt_client_ack ack;
    mt_status st = mt_client_submit(client, rec.mesh_id, &rec.faces, 0, &ack, &diag);
    res.acked_s = seconds_since_start(r);
    res.acked = ack.msg.mesh_id != NULL;
    res.version = ack.msg.version;
    res.content_hash = ack.msg.content_hash;
    res.expected_hash = rec.format_version >= MT_ARCHIVE_FORMAT_VERSION_HASHED
                            ? e->content_hash
                            : ack.sent_content_hash;
    if (st == MT_OK) {
        res.status = "OK";
        code = (uint64_t)res.content_hash == res.expected_hash ? CLI_EXIT_OK : CLI_EXIT_READ;
    } else {
        progress_clear(r);
        code = cli_call_failed("replay", rec.mesh_id, &r->remote, st, res.acked, &diag);
        res.status = res.acked                    ? mt_msgs_code_name(ack.msg.status)
                     : code == CLI_EXIT_NO_ANSWER ? "NO_ANSWER"
                                                  : "ERROR";
        res.error = diag.message;
    }
    result_print(r, &res);
    if (code == CLI_EXIT_READ) {
        char want[24];
        cli_error("replay", "%s: meshtopod computed another content hash than the archived %s",
                  e->file_name, cli_hash_text((int64_t)res.expected_hash, want, sizeof want));
    }
    mt_client_ack_free(&ack);
    mt_archive_record_free(&rec);
    return code;
}

static int replay_run(replay *r, const mt_archive *archive, const mt_archive_listing *listing,
                      const cli_replay_plan *plan)
{
    int code = CLI_EXIT_OK;
    for (size_t i = 0; i < listing->count; i++) {
        const mt_archive_entry *e = &listing->entries[i];
        if (e->status == MT_OK) continue;
        cli_error("replay", "%s", e->diag.message);
        if (r->json) {
            mt_json j;
            mt_json_init(&j, stdout);
            j.compact = true;
            mt_json_object_begin(&j);
            mt_json_key(&j, "file");
            mt_json_string(&j, e->file_name);
            mt_json_key(&j, "status");
            mt_json_string(&j, "UNREADABLE");
            mt_json_key(&j, "error");
            mt_json_string(&j, e->diag.message);
            mt_json_object_end(&j);
            mt_json_finish(&j);
        }
        code = CLI_EXIT_READ;
    }
    if (plan->count == 0) cli_error("replay", "no archived mesh matches: nothing to replay");
    r->total = plan->count;
    r->last_offset_s = plan->count ? plan->items[plan->count - 1].offset_s : 0.0;
    progress_draw(r);
    for (size_t i = 0; i < plan->count; i++) {
        int one = replay_one(r, archive, &plan->items[i]);
        code = code_worse(code, one);
        r->sent++;
        progress_draw(r);
        if (one == CLI_EXIT_NO_ANSWER || one == CLI_EXIT_USAGE) break;
    }
    if (r->progress_drawn) {
        fputc('\n', stderr);
        r->progress_drawn = false;
    }
    return code;
}

static int run_replay(const cli_args *args)
{
    replay r;
    memset(&r, 0, sizeof r);
    double rate = 1.0;
    cli_replay_filter filter;
    char prefix[MT_CLIENT_MAX_PREFIX + 8];
    int code = parse_options(args, &r, &rate, &filter, prefix, sizeof prefix);
    if (code != CLI_EXIT_OK) return code;

    const char *dir = args->positionals[0];
    mt_archive_options open_options = {.read_only = true};
    mt_archive *archive = NULL;
    mt_diag diag;
    mt_diag_clear(&diag);
    if (mt_archive_open(dir, &open_options, &archive, &diag) != MT_OK) {
        cli_error("replay", "%s", diag.message);
        return CLI_EXIT_READ;
    }
    mt_archive_listing listing;
    if (mt_archive_list(archive, &listing, &diag) != MT_OK) {
        cli_error("replay", "%s", diag.message);
        mt_archive_close(archive);
        return CLI_EXIT_READ;
    }
    cli_replay_plan plan;
    code = cli_replay_plan_make(&listing, &filter, rate, &plan);
    if (code == CLI_EXIT_OK) code = replay_run(&r, archive, &listing, &plan);
    clients_destroy(&r);
    cli_replay_plan_free(&plan);
    mt_archive_listing_free(&listing);
    mt_archive_close(archive);
    return cli_finish_output("replay", code, CLI_EXIT_READ);
}

const cli_command cli_cmd_replay = {
    .name = "replay",
    .summary = "publish archived meshes to meshtopod again, with their original timing",
    .synopsis =
        "DIR [--rate X | --as-fast-as-possible] [--ids ID,...] [--since T] [--until T] "
        "[--channel CHANNEL] [--json] [--quiet] [--lcm-url URL] [--prefix PREFIX]",
    .description =
        "Submits the meshes archived in DIR (by meshtopod --archive) again, in the order of\n"
        "their utime (ties by mesh id, then version), each with the source it was archived\n"
        "with, keeping their original spacing in time divided by --rate: --rate 2 replays\n"
        "twice as fast, --rate 0 (or --as-fast-as-possible) sends each mesh as soon as the\n"
        "previous one is acknowledged. Every submission waits for its acknowledgement; the\n"
        "schedule is absolute, so a slow acknowledgement delays only the meshes due before\n"
        "it arrives. The daemon assigns new versions and the submission's utime is the time\n"
        "of sending.\n"
        "\n"
        "Prints one line per mesh: id, archived version -> new version, and whether the\n"
        "daemon's content hash equals the archived one (for files of archive formats 1\n"
        "and 2, whose hash is of a former kind, the hash of the archived face list).\n"
        "--json prints one JSON object per\n"
        "line instead: {mesh_id, file, source, utime, original_version,\n"
        "archived_content_hash, status, error, version, content_hash, hash_match,\n"
        "scheduled_us, sent_us, acked_us} (the last three in microseconds after the first\n"
        "send), and {file, status: \"UNREADABLE\", error} for a file that cannot be read.\n"
        "\n"
        "--ids selects mesh ids (every archived version of each; an id with no archived\n"
        "version is a usage error; an id containing ',' cannot be named). --since T and\n"
        "--until T select utime >= T and < T; T is microseconds since the epoch\n"
        "(1795334400000000) or ISO 8601 UTC (2026-11-22T08:00:00Z, 2026-11-22T08:00:00.25Z,\n"
        "or +00:00 for Z).\n"
        "--channel XYZ_SUBMIT (or the prefix XYZ_) submits to that channel; replies come\n"
        "back on XYZ_REPLY_..., as with --prefix XYZ_. On a terminal, stderr shows one\n"
        "progress line (meshes sent / total, elapsed, ETA).\n"
        "\n"
        "exit codes: 0 every mesh acknowledged with the archived content hash, 2 usage error,\n"
        "3 DIR or a file in it could not be read, or an acknowledged content hash differs\n"
        "(the other meshes are still replayed), 5 meshtopod refused a mesh (the others are\n"
        "still replayed), 6 no answer from meshtopod (the replay stops there).\n",
    .options = options,
    .num_options = sizeof options / sizeof options[0],
    .min_positionals = 1,
    .max_positionals = 1,
    .run = run_replay,
};
