/* meshtopod's large answers (msgs/reply_part_t.lcm, reply_pull_t.lcm): an
 * encoded reply_t over one datagram goes out as reply_part_t pieces, the
 * first window at once and the rest when the receiver pulls them from the
 * request cache. Called by the reply module (reply.c); any thread. */
#ifndef MESHTOPOD_REPLY_PARTS_H
#define MESHTOPOD_REPLY_PARTS_H

#include <lcm/lcm.h>
#include <stddef.h>
#include <stdint.h>

#include "request_cache.h"

/* Publishes an encoded answer (ack_t, reply_t or mesh_transfer_t) for
 * request_id on the channel of its type under reply_channel
 * (meshtopo/channels.h): as it is, or, for a reply_t over
 * MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX bytes, as its first reply_part_t
 * pieces on the parts channel (the receiver pulls the rest from the request
 * cache). */
void mtd_parts_publish(lcm_t *lcm, const char *reply_channel, int64_t request_id, const void *data,
                       size_t size);

/* Handles one received reply_pull_t (bytes with their fingerprint): sends the
 * parts it asks for from `cache` (where replies are keyed by their reply_t
 * channel); unanswered when the cache holds no such answer (the receiver
 * then sends its query again). */
void mtd_parts_serve_pull(lcm_t *lcm, mtd_reqcache *cache, const void *data, size_t size);

#endif
