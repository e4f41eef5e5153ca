/* Message helpers of the Python package (python_api.h): received bytes decoded
 * by mt_msgs_decode (meshtopo/msgs.h), then held to the rules the client
 * library applies to what it decodes (reply offsets, report counts) and to the
 * layout of reply_t pieces (msgs/reply_part_t.lcm); the decoded struct is read
 * field by field through lcm-gen's typeinfo. Nothing here trusts a length
 * before mt_msgs_decode has checked it against the bytes. */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/channels.h"
#include "meshtopo/client_reply.h"
#include "meshtopo/client_report.h"
#include "python_api.h"

const mt_msgs_type *mt_py_msgs_type(const char *name)
{
    static const char package[] = "meshtopo.";
    if (!name) return NULL;
    if (strncmp(name, package, sizeof package - 1) == 0) name += sizeof package - 1;
    for (size_t i = 0; i < mt_msgs_num_types; i++)
        if (strcmp(mt_msgs_types[i]->name, name) == 0) return mt_msgs_types[i];
    return NULL;
}

const char *mt_py_msgs_type_name(const mt_msgs_type *type)
{
    return type ? type->name : NULL;
}

size_t mt_py_msgs_struct_size(const mt_msgs_type *type)
{
    return type ? type->struct_size : 0;
}

int mt_py_msgs_num_fields(const mt_msgs_type *type)
{
    return type ? type->num_fields() : 0;
}

int mt_py_msgs_field(const mt_msgs_type *type, const void *msg, int index, lcm_field_t *out_field)
{
    memset(out_field, 0, sizeof *out_field);
    return type && msg ? type->get_field(msg, index, out_field) : -1;
}

const mt_msgs_type *mt_py_msgs_channel_type(const char *prefix, const char *channel)
{
    if (!prefix || !channel) return NULL;
    for (int c = 0; c < MT_MSGS_CHANNEL_COUNT; c++) {
        char name[MT_MSGS_CHANNEL_NAME_MAX + 1];
        if (mt_msgs_channel_name(prefix, (mt_msgs_channel)c, name) == MT_OK &&
            strcmp(name, channel) == 0)
            return mt_msgs_channel_type((mt_msgs_channel)c);
    }
    /* An answer: a reply channel (1 to REPLY_CHANNEL_MAX printable bytes) and
     * the suffix of its type. */
    size_t n = strlen(channel);
    for (size_t i = 0; i < mt_msgs_num_types; i++) {
        const char *suffix = mt_msgs_reply_suffix(mt_msgs_types[i]);
        size_t k = suffix ? strlen(suffix) : 0;
        if (!suffix || n <= k || strcmp(channel + n - k, suffix) != 0) continue;
        char reply_channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
        if (n - k > MT_MSGS_CHANNEL_NAME_MAX) continue;
        memcpy(reply_channel, channel, n - k);
        reply_channel[n - k] = '\0';
        if (mt_msgs_reply_channel_ok(reply_channel)) return mt_msgs_types[i];
    }
    return NULL;
}

/* The client's checks of a topology_t: counts non-negative, lists no longer
 * than their counts (mt_client_report_from_topology). */
static mt_status check_topology(const meshtopo_topology_t *t, const char *where, mt_diag *diag)
{
    mt_client_report report;
    mt_diag inner;
    mt_diag_clear(&inner);
    mt_status s = mt_client_report_from_topology(t, &report, &inner);
    mt_client_report_free(&report);
    if (s != MT_OK) return mt_diag_set(diag, s, "%s: %s", where, inner.message);
    return MT_OK;
}

static mt_status check_reports(const char *type, const meshtopo_topology_t *reports, int32_t n,
                               mt_diag *diag)
{
    for (int32_t i = 0; i < n; i++) {
        char where[64];
        snprintf(where, sizeof where, "%s.reports[%" PRId32 "]", type, i);
        mt_status s = check_topology(&reports[i], where, diag);
        if (s != MT_OK) return s;
    }
    return MT_OK;
}

/* One piece of a large answer (msgs/reply_part_t.lcm): part_size within
 * 1..PART_SIZE, an answer over one message, offset a multiple of part_size
 * below total_size, length the size of that range. */
static mt_status check_part(const meshtopo_reply_part_t *p, mt_diag *diag)
{
    if (p->part_size <= 0 || p->part_size > MESHTOPO_REPLY_PART_T_PART_SIZE)
        return mt_diag_set(diag, MT_ERR_CORRUPT,
                           "reply_part_t.part_size: %" PRId32 " is not within 1..%d", p->part_size,
                           MESHTOPO_REPLY_PART_T_PART_SIZE);
    if (p->total_size <= MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX)
        return mt_diag_set(diag, MT_ERR_CORRUPT,
                           "reply_part_t.total_size: %" PRId64
                           ", an answer in parts has more than %d bytes",
                           p->total_size, MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX);
    if (p->offset < 0 || p->offset >= p->total_size || p->offset % p->part_size != 0)
        return mt_diag_set(diag, MT_ERR_CORRUPT,
                           "reply_part_t.offset: %" PRId64 " is not a multiple of %" PRId32
                           " below %" PRId64,
                           p->offset, p->part_size, p->total_size);
    int64_t expected =
        p->total_size - p->offset < p->part_size ? p->total_size - p->offset : p->part_size;
    if (p->length != expected)
        return mt_diag_set(diag, MT_ERR_CORRUPT,
                           "reply_part_t.length: %" PRId32 " bytes at offset %" PRId64
                           ", expected %" PRId64,
                           p->length, p->offset, expected);
    return MT_OK;
}

/* The rules of each type beyond its encoding. */
static mt_status check_rules(const mt_msgs_type *type, const void *msg, mt_diag *diag)
{
    if (type == &mt_msgs_type_reply) {
        const meshtopo_reply_t *r = msg;
        mt_status s = mt_client_reply_check(r, diag);
        return s != MT_OK ? s : check_reports("reply_t", r->reports, r->num_reports, diag);
    }
    if (type == &mt_msgs_type_ack) {
        const meshtopo_ack_t *a = msg;
        return check_reports("ack_t", a->reports, a->num_reports, diag);
    }
    if (type == &mt_msgs_type_topology) return check_topology(msg, "topology_t", diag);
    if (type == &mt_msgs_type_reply_part) return check_part(msg, diag);
    if (type == &mt_msgs_type_mesh_transfer) {
        const meshtopo_mesh_transfer_t *t = msg;
        if (t->num_missing > MESHTOPO_MESH_TRANSFER_T_MISSING_MAX)
            return mt_diag_set(diag, MT_ERR_CORRUPT,
                               "mesh_transfer_t.num_missing: %" PRId32 " ranges, at most %d",
                               t->num_missing, MESHTOPO_MESH_TRANSFER_T_MISSING_MAX);
    }
    return MT_OK;
}

mt_status mt_py_msgs_decode(const mt_msgs_type *type, const void *buf, size_t size, void **out_msg,
                            mt_diag *diag)
{
    mt_diag_clear(diag);
    *out_msg = NULL;
    if (!type) return mt_diag_set(diag, MT_ERR_INVALID_ARG, "no message type given");
    void *msg = calloc(1, type->struct_size);
    if (!msg) return mt_diag_set(diag, MT_ERR_NOMEM, "out of memory");
    char error[MT_MSGS_ERROR_SIZE];
    if (mt_msgs_decode(type, buf, size, msg, error, sizeof error) != 0) {
        free(msg);
        return mt_diag_set(diag, MT_ERR_CORRUPT, "%s", error);
    }
    mt_status s = check_rules(type, msg, diag);
    if (s != MT_OK) {
        if (s != MT_ERR_NOMEM) s = MT_ERR_CORRUPT;
        mt_py_msgs_free(type, msg);
        return s;
    }
    *out_msg = msg;
    return MT_OK;
}

void mt_py_msgs_free(const mt_msgs_type *type, void *msg)
{
    if (!type || !msg) return;
    type->decode_cleanup(msg);
    free(msg);
}
