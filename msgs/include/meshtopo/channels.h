/* meshtopo's channels: LCM's convention of one message type per channel, so
 * lcm-spy and lcm-logger decode every channel by one type. Requests go to
 * PREFIX + a fixed suffix; the answers to a request go to the reply_channel
 * it names + one suffix per answer type. This table is the one place both
 * sides read the names from. Pure functions, any thread. */
#ifndef MESHTOPO_CHANNELS_H
#define MESHTOPO_CHANNELS_H

#include <stdbool.h>
#include <stddef.h>

#include "meshtopo/msgs.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Longest channel name LCM publishes (its own limit). */
#define MT_MSGS_CHANNEL_NAME_MAX 63

/* The channels under the prefix (default "MESHTOPO_"). */
typedef enum mt_msgs_channel {
    MT_MSGS_CHANNEL_SUBMIT,       /* PREFIX "SUBMIT": mesh_t, node -> daemon */
    MT_MSGS_CHANNEL_SUBMIT_CHUNK, /* PREFIX "SUBMIT_CHUNK": mesh_chunk_t, node -> daemon */
    MT_MSGS_CHANNEL_QUERY,        /* PREFIX "QUERY": query_t, node -> daemon */
    MT_MSGS_CHANNEL_QUERY_PULL,   /* PREFIX "QUERY_PULL": reply_pull_t, node -> daemon */
    MT_MSGS_CHANNEL_TOPOLOGY,     /* PREFIX "TOPOLOGY": topology_t, daemon -> all */
    MT_MSGS_CHANNEL_STATUS,       /* PREFIX "STATUS": status_t, daemon -> all */
    MT_MSGS_CHANNEL_COUNT
} mt_msgs_channel;

/* The suffix after the prefix ("SUBMIT"), or NULL for a value out of range. */
const char *mt_msgs_channel_suffix(mt_msgs_channel channel);

/* The one type the channel carries, or NULL for a value out of range. */
const mt_msgs_type *mt_msgs_channel_type(mt_msgs_channel channel);

/* Writes prefix + the channel's suffix to out[MT_MSGS_CHANNEL_NAME_MAX + 1].
 * MT_OK, or MT_ERR_INVALID_ARG when the name would exceed LCM's 63 bytes or
 * the channel is out of range (out is then ""). */
mt_status mt_msgs_channel_name(const char *prefix, mt_msgs_channel channel, char *out);

/* The suffix that answers of `type` add to a request's reply_channel: "_ACK"
 * (ack_t), "_REPLY" (reply_t), "_PART" (reply_part_t), "_TRANSFER"
 * (mesh_transfer_t); NULL for a type that is not an answer. */
const char *mt_msgs_reply_suffix(const mt_msgs_type *type);

/* Whether a request's reply_channel can be answered: 1 to
 * MESHTOPO_MESH_T_REPLY_CHANNEL_MAX printable ASCII bytes (0x21 to 0x7e), so
 * that it and its longest suffix fit LCM's limit. */
bool mt_msgs_reply_channel_ok(const char *reply_channel);

/* Whether the daemons of `prefix` may answer on reply_channel:
 * mt_msgs_reply_channel_ok, and the name neither is nor starts with one of
 * their own channel names (PREFIX "SUBMIT" ... PREFIX "STATUS"), so that no
 * answer lands on a daemon channel or on a name a subscriber to its pattern
 * (PREFIX "STATUS.*", say) would take for one. The client library's reply
 * channels (PREFIX "REPLY_" ...) always pass. */
bool mt_msgs_reply_channel_allowed(const char *prefix, const char *reply_channel);

/* Writes reply_channel + the suffix of `type` to
 * out[MT_MSGS_CHANNEL_NAME_MAX + 1]. MT_OK, or MT_ERR_INVALID_ARG when the
 * reply channel breaks mt_msgs_reply_channel_ok or the type is not an
 * answer (out is then ""). */
mt_status mt_msgs_reply_channel_name(const char *reply_channel, const mt_msgs_type *type,
                                     char *out);

#ifdef __cplusplus
}
#endif

#endif
