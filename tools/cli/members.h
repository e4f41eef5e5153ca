/* The daemons that answer a prefix, as the CLI learns them from their
 * heartbeats: one meshtopod, or the members of a cluster (status_t.cluster),
 * each of which answers for the mesh ids it owns. */
#ifndef MESHTOPO_CLI_MEMBERS_H
#define MESHTOPO_CLI_MEMBERS_H

#include "meshtopo/client.h"

#define CLI_MAX_MEMBERS 64

typedef struct cli_members {
    char cluster[64]; /* "" for a daemon without a cluster */
    int count;        /* 0 when no heartbeat came */
    char instances[CLI_MAX_MEMBERS][MT_CLIENT_MAX_INSTANCE + 1];
    char names[CLI_MAX_MEMBERS][64];
} cli_members;

/* Waits for a heartbeat (at most wait_ms); when it names a cluster, goes on
 * listening until as many members beat as the heartbeats say the cluster
 * has (at most wait_ms more). */
void cli_members_find(mt_client *client, int wait_ms, cli_members *out);

#endif
