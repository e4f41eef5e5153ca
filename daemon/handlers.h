/* meshtopod's LCM handlers: the subscriptions to the four request channels
 * (meshtopo/channels.h: SUBMIT, SUBMIT_CHUNK, QUERY, QUERY_PULL, one type
 * each) and the raw handlers that check received bytes (mt_msgs_decode,
 * never lcm-gen's decoders) and route each message to the module that owns
 * it: whole meshes to the submitter, chunks to the transfers, queries to the
 * queries, pulls of large answers to the replies. In a cluster, a submission
 * or query of a mesh id another member owns is left to it (cluster.h), and
 * the TOPOLOGY broadcasts of the other members are read too: a version
 * announced for an id this member owns now goes to the archive's catalog.
 * Runs on the LCM thread. */
#ifndef MESHTOPOD_HANDLERS_H
#define MESHTOPOD_HANDLERS_H

#include <lcm/lcm.h>
#include <stdint.h>

#include "archive_catalog.h"
#include "cluster.h"
#include "query_route.h"
#include "reply.h"
#include "submit.h"
#include "transfer.h"

/* Where each message goes; not owned, all must outlive the handlers. */
typedef struct mtd_handler_deps {
    lcm_t *lcm;
    const char *prefix;   /* of the channel names */
    const char *instance; /* this daemon's, as in its heartbeat */
    mtd_replies *replies;
    mtd_submitter *submitter;
    mtd_transfers *transfers;
    mtd_queries *queries;
    mtd_cluster *cluster; /* NULL without --cluster */
    mtd_catalog *catalog; /* told of versions other members announce; NULL without */
} mtd_handler_deps;

typedef struct mtd_handlers mtd_handlers;

/* Subscribes (raw handlers, LCM's queue raised so bursts are not dropped).
 * MT_OK, MT_ERR_INVALID_ARG (the prefix makes a channel name longer than
 * LCM's 63 bytes) or MT_ERR_NOMEM. */
mt_status mtd_handlers_subscribe(const mtd_handler_deps *deps, mtd_handlers **out_handlers);

/* Unsubscribes: no message is handled after it returns. Idempotent. */
void mtd_handlers_unsubscribe(mtd_handlers *handlers);

/* Unsubscribes and frees. NULL-safe. */
void mtd_handlers_destroy(mtd_handlers *handlers);

/* Messages received on SUBMIT and on QUERY, undecodable ones included. */
typedef struct mtd_handler_counts {
    int64_t submissions;
    int64_t queries;
} mtd_handler_counts;

void mtd_handlers_get_counts(mtd_handlers *handlers, mtd_handler_counts *out_counts);

#endif
