/* Connection options, client creation and error reporting shared by the
 * commands that talk to meshtopod (see remote.h). A failed call always ends
 * in one stderr line naming the mesh and one of the documented exit codes:
 * 5 when meshtopod answered with an error, 6 when it did not answer. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "remote.h"

bool cli_parse_int(const char *text, int *out)
{
    if (!text[0] || text[0] == '-' || text[0] == '+') return false;
    char *end = NULL;
    unsigned long long v = strtoull(text, &end, 10);
    if (*end != '\0' || v > INT_MAX) return false;
    *out = (int)v;
    return true;
}

int cli_remote_parse(const cli_args *args, cli_remote *out)
{
    memset(out, 0, sizeof *out);
    out->lcm_url = cli_arg(args, "lcm-url");
    if (!out->lcm_url) out->lcm_url = getenv(CLI_ENV_LCM_URL);
    if (out->lcm_url && !out->lcm_url[0]) out->lcm_url = NULL;
    out->prefix = cli_arg(args, "prefix");
    if (!out->prefix) out->prefix = getenv(CLI_ENV_PREFIX);
    if (!out->prefix || !out->prefix[0]) out->prefix = MT_CLIENT_DEFAULT_PREFIX;
    if (strlen(out->prefix) > MT_CLIENT_MAX_PREFIX) {
        cli_error(args->command, "--prefix: at most %d characters, got '%s'", MT_CLIENT_MAX_PREFIX,
                  out->prefix);
        return CLI_EXIT_USAGE;
    }
    out->timeout_ms = MT_CLIENT_DEFAULT_TIMEOUT_MS;
    out->retries = MT_CLIENT_DEFAULT_RETRIES;
    const char *text = cli_arg(args, "timeout-ms");
    if (text) {
        if (!cli_parse_int(text, &out->timeout_ms) || out->timeout_ms == 0) {
            cli_error(args->command, "--timeout-ms: expected a positive count, got '%s'", text);
            return CLI_EXIT_USAGE;
        }
        out->timeout_given = true;
    }
    text = cli_arg(args, "retries");
    if (text && !cli_parse_int(text, &out->retries)) {
        cli_error(args->command, "--retries: expected a count, got '%s'", text);
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

int cli_client_create(const char *command, const cli_remote *remote, mt_client **out)
{
    return cli_client_create_progress(command, remote, NULL, NULL, out);
}

int cli_client_create_progress(const char *command, const cli_remote *remote,
                               mt_client_progress_fn progress, void *progress_user, mt_client **out)
{
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.progress = progress;
    opts.progress_user = progress_user;
    opts.lcm_url = remote->lcm_url;
    opts.channel_prefix = remote->prefix;
    opts.timeout_ms = remote->timeout_ms;
    opts.retries = remote->retries > 0 ? remote->retries : -1; /* the client's 0 = default */
    opts.source = "meshtopo-cli";
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_client_create(&opts, out, &diag);
    if (st == MT_OK) return CLI_EXIT_OK;
    const char *why = diag.message[0] ? diag.message : mt_strerror(st);
    if (st == MT_ERR_INVALID_ARG) {
        cli_error(command, "%s", why);
        return CLI_EXIT_USAGE;
    }
    cli_error(command, "cannot talk LCM (%s): %s",
              remote->lcm_url ? remote->lcm_url : "default URL", why);
    return CLI_EXIT_NO_ANSWER;
}

void cli_client_destroy(const char *command, const cli_remote *remote, mt_client *client)
{
    if (!client) return;
    mt_client_stats stats;
    mt_client_get_stats(client, &stats);
    if (stats.conflicting_answers > 0)
        cli_error(command,
                  "warning: %llu request(s) got two different answers: two meshtopod answer "
                  "prefix %s (meshtopo watch shows their heartbeats; give each its own "
                  "--prefix)",
                  (unsigned long long)stats.conflicting_answers, remote->prefix);
    mt_client_destroy(client);
}

int cli_call_failed(const char *command, const char *mesh_id, const cli_remote *remote,
                    mt_status status, bool answered, const mt_diag *diag)
{
    const char *why = diag->message[0] ? diag->message : mt_strerror(status);
    char subject[300] = "";
    if (mesh_id) snprintf(subject, sizeof subject, "mesh '%s': ", mesh_id);
    if (answered) {
        cli_error(command, "%smeshtopod refused: %s", subject, why);
        return CLI_EXIT_REFUSED;
    }
    if (strncmp(diag->message, "timeout:", 8) == 0) {
        cli_error(command,
                  "%sno answer from meshtopod on %s* after %d attempt(s) of %d ms "
                  "(is it running with this --prefix and --lcm-url?)",
                  subject, remote->prefix, remote->retries + 1, remote->timeout_ms);
        return CLI_EXIT_NO_ANSWER;
    }
    cli_error(command, "%s%s", subject, why);
    if (status == MT_ERR_INVALID_ARG) return CLI_EXIT_USAGE;
    if (status == MT_ERR_TOO_LARGE) return CLI_EXIT_BUILD;
    return CLI_EXIT_NO_ANSWER;
}

const char *cli_hash_text(int64_t hash, char *buf, size_t size)
{
    snprintf(buf, size, "%016llx", (unsigned long long)(uint64_t)hash);
    return buf;
}
