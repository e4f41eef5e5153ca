/* The pieces shared by the commands that talk to meshtopod over LCM (send,
 * query, list, watch): the common connection options and their environment
 * defaults, creating the client, and turning a call's outcome into an exit
 * code and a message. Reports are printed through cli_report.h. */
#ifndef MESHTOPO_CLI_REMOTE_H
#define MESHTOPO_CLI_REMOTE_H

#include <stdbool.h>
#include <stdio.h>

#include "cli.h"
#include "cli_report.h"
#include "meshtopo/client.h"
#include "meshtopo/json_writer.h"
#include "meshtopo/msgs.h"

/* Environment variables giving the defaults of --lcm-url and --prefix. */
#define CLI_ENV_LCM_URL "MESHTOPO_LCM_URL"
#define CLI_ENV_PREFIX "MESHTOPO_PREFIX"

/* The option rows every remote command lists (look them up with
 * cli_remote_parse). */
#define CLI_REMOTE_OPTIONS                                                                     \
    {"lcm-url", "URL", "LCM provider URL (default: $" CLI_ENV_LCM_URL ", else LCM's own)"},    \
        {"prefix", "PREFIX", "channel prefix (default: $" CLI_ENV_PREFIX ", else MESHTOPO_)"}, \
        {"timeout-ms", "MS", "wait this long for a reply to each attempt (default 1000)"},     \
    {                                                                                          \
        "retries", "N", "attempts after the first one (default 3)"                             \
    }

/* The connection settings after parsing (strings point into argv/environ). */
typedef struct cli_remote {
    const char *lcm_url; /* NULL = LCM's default */
    const char *prefix;  /* never NULL */
    int timeout_ms;      /* > 0 */
    int retries;         /* >= 0 */
    bool timeout_given;  /* --timeout-ms was on the command line */
} cli_remote;

/* Reads --lcm-url, --prefix, --timeout-ms and --retries (with the
 * environment defaults). Returns CLI_EXIT_OK or CLI_EXIT_USAGE after
 * printing the problem. */
int cli_remote_parse(const cli_args *args, cli_remote *out);

/* Creates a client with these settings. Returns CLI_EXIT_OK and *out, or
 * CLI_EXIT_USAGE (bad prefix) / CLI_EXIT_NO_ANSWER (LCM could not
 * start) after printing the reason. */
int cli_client_create(const char *command, const cli_remote *remote, mt_client **out);

/* cli_client_create with a progress callback for chunked submissions. */
int cli_client_create_progress(const char *command, const cli_remote *remote,
                               mt_client_progress_fn progress, void *progress_user,
                               mt_client **out);

/* Destroys a client after saying, when it saw two different answers to one
 * request, that two meshtopod answer the prefix. */
void cli_client_destroy(const char *command, const cli_remote *remote, mt_client *client);

/* The exit code of a failed client call, after printing one line naming the
 * mesh (unless mesh_id is NULL): CLI_EXIT_REFUSED when the daemon answered with an error
 * (`answered`), CLI_EXIT_NO_ANSWER after a timeout, CLI_EXIT_USAGE for
 * arguments the client refused before sending, CLI_EXIT_BUILD for a mesh
 * too large for the message. */
int cli_call_failed(const char *command, const char *mesh_id, const cli_remote *remote,
                    mt_status status, bool answered, const mt_diag *diag);

/* Parses a non-negative decimal that fits an int; false otherwise. */
bool cli_parse_int(const char *text, int *out);

/* A 64-bit content hash as 16 hex digits (buf of at least 17 bytes). */
const char *cli_hash_text(int64_t hash, char *buf, size_t size);

#endif
