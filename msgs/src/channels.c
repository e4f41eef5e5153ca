/* meshtopo's channel names (meshtopo/channels.h): the suffixes of the
 * request and broadcast channels and of the answers, with the type each
 * carries, as two tables. */
#include "meshtopo/channels.h"

#include <stdio.h>
#include <string.h>

typedef struct channel_entry {
    const char *suffix;
    const mt_msgs_type *type;
} channel_entry;

static const channel_entry channels[MT_MSGS_CHANNEL_COUNT] = {
    [MT_MSGS_CHANNEL_SUBMIT] = {"SUBMIT", &mt_msgs_type_mesh},
    [MT_MSGS_CHANNEL_SUBMIT_CHUNK] = {"SUBMIT_CHUNK", &mt_msgs_type_mesh_chunk},
    [MT_MSGS_CHANNEL_QUERY] = {"QUERY", &mt_msgs_type_query},
    [MT_MSGS_CHANNEL_QUERY_PULL] = {"QUERY_PULL", &mt_msgs_type_reply_pull},
    [MT_MSGS_CHANNEL_TOPOLOGY] = {"TOPOLOGY", &mt_msgs_type_topology},
    [MT_MSGS_CHANNEL_STATUS] = {"STATUS", &mt_msgs_type_status},
};

static const channel_entry answers[] = {
    {"_ACK", &mt_msgs_type_ack},
    {"_REPLY", &mt_msgs_type_reply},
    {"_PART", &mt_msgs_type_reply_part},
    {"_TRANSFER", &mt_msgs_type_mesh_transfer},
};

const char *mt_msgs_channel_suffix(mt_msgs_channel channel)
{
    return (unsigned)channel < MT_MSGS_CHANNEL_COUNT ? channels[channel].suffix : NULL;
}

const mt_msgs_type *mt_msgs_channel_type(mt_msgs_channel channel)
{
    return (unsigned)channel < MT_MSGS_CHANNEL_COUNT ? channels[channel].type : NULL;
}

/* a + b into out[MT_MSGS_CHANNEL_NAME_MAX + 1], or "" when it does not fit. */
static mt_status join(const char *a, const char *b, char *out)
{
    int n = snprintf(out, MT_MSGS_CHANNEL_NAME_MAX + 1, "%s%s", a, b);
    if (n < 0 || n > MT_MSGS_CHANNEL_NAME_MAX) {
        out[0] = '\0';
        return MT_ERR_INVALID_ARG;
    }
    return MT_OK;
}

mt_status mt_msgs_channel_name(const char *prefix, mt_msgs_channel channel, char *out)
{
    const char *suffix = mt_msgs_channel_suffix(channel);
    if (!prefix || !suffix) {
        out[0] = '\0';
        return MT_ERR_INVALID_ARG;
    }
    return join(prefix, suffix, out);
}

const char *mt_msgs_reply_suffix(const mt_msgs_type *type)
{
    for (size_t i = 0; i < sizeof answers / sizeof answers[0]; i++)
        if (answers[i].type == type) return answers[i].suffix;
    return NULL;
}

bool mt_msgs_reply_channel_ok(const char *reply_channel)
{
    if (!reply_channel) return false;
    size_t n = strnlen(reply_channel, MESHTOPO_MESH_T_REPLY_CHANNEL_MAX + 1);
    if (n == 0 || n > MESHTOPO_MESH_T_REPLY_CHANNEL_MAX) return false;
    for (size_t i = 0; i < n; i++)
        if (reply_channel[i] <= ' ' || reply_channel[i] > '~') return false;
    return true;
}

bool mt_msgs_reply_channel_allowed(const char *prefix, const char *reply_channel)
{
    if (!prefix || !mt_msgs_reply_channel_ok(reply_channel)) return false;
    for (int c = 0; c < MT_MSGS_CHANNEL_COUNT; c++) {
        char name[MT_MSGS_CHANNEL_NAME_MAX + 1];
        if (mt_msgs_channel_name(prefix, (mt_msgs_channel)c, name) != MT_OK) continue;
        if (strncmp(reply_channel, name, strlen(name)) == 0) return false;
    }
    return true;
}

mt_status mt_msgs_reply_channel_name(const char *reply_channel, const mt_msgs_type *type, char *out)
{
    const char *suffix = mt_msgs_reply_suffix(type);
    if (!suffix || !mt_msgs_reply_channel_ok(reply_channel)) {
        out[0] = '\0';
        return MT_ERR_INVALID_ARG;
    }
    return join(reply_channel, suffix, out);
}
