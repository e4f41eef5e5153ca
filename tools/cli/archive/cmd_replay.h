/* `meshtopo replay`: the pieces its files share. The plan says which archived
 * mesh versions are replayed, in which order (utime, then mesh id, then
 * version) and when, as seconds after the first send (original spacing
 * divided by the rate); times on the command line are parsed here too. */
#ifndef MESHTOPO_CLI_CMD_REPLAY_H
#define MESHTOPO_CLI_CMD_REPLAY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/archive.h"

/* Which archived versions to replay; a zeroed struct selects all of them. */
typedef struct cli_replay_filter {
    const char *ids; /* "a,b,c": only these mesh ids (every version); NULL = all */
    bool has_since;  /* utime >= since */
    int64_t since;
    bool has_until; /* utime < until */
    int64_t until;
} cli_replay_filter;

/* One mesh version to send. */
typedef struct cli_replay_item {
    const mt_archive_entry *entry; /* points into the listing */
    double offset_s;               /* send this long after the first one */
} cli_replay_item;

typedef struct cli_replay_plan {
    cli_replay_item *items; /* in sending order */
    size_t count;
} cli_replay_plan;

/* Parses a time given as microseconds since the epoch ("1795334400000000")
 * or as ISO 8601 UTC ("2026-11-22T08:00:00Z", up to 6 fraction digits,
 * "Z" or "+00:00"). False when it is neither or out of range. */
bool cli_replay_parse_time(const char *text, int64_t *out_utime);

/* Builds the plan from the readable entries of `listing` that pass the
 * filter, ordered by utime (ties by mesh id, then version), offsets scaled
 * by 1/rate (rate 0: every offset 0). Returns CLI_EXIT_OK,
 * CLI_EXIT_USAGE when an id of filter->ids has no archived version
 * (reported on stderr) or CLI_EXIT_READ when memory runs out. Free with
 * cli_replay_plan_free. */
int cli_replay_plan_make(const mt_archive_listing *listing, const cli_replay_filter *filter,
                         double rate, cli_replay_plan *out);
void cli_replay_plan_free(cli_replay_plan *plan);

#endif
