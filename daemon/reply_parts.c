/* meshtopod's large answers (reply_parts.h): an encoded reply_t or ack_t
 * over one datagram goes out as reply_part_t pieces, the first window at once and the
 * rest when the receiver pulls them. The bytes come from the request cache,
 * so a pull (the next window, or parts lost on the way) never runs the query
 * again; a pull for an answer the cache no longer holds is left unanswered
 * (the receiver then sends its query again). Publishing runs on whichever
 * thread answers (the LCM thread or a build worker); pulls on the LCM
 * thread. */
#include "reply_parts.h"

#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "log.h"
#include "meshtopo/answer_hash.h"
#include "meshtopo/channels.h"
#include "meshtopo/msgs.h"

/* The protocol's numbers (msgs/reply_part_t.lcm, reply_pull_t.lcm) as sizes. */
static const size_t part_size = MESHTOPO_REPLY_PART_T_PART_SIZE;
static const size_t first_parts = MESHTOPO_REPLY_PART_T_FIRST_PARTS;
static const size_t parts_per_pull = MESHTOPO_REPLY_PULL_T_PARTS_PER_PULL_MAX;

/* Publishes parts first .. first + count - 1 of the answer (those that exist). */
static void publish_parts(lcm_t *lcm, const char *channel, int64_t request_id, const uint8_t *data,
                          size_t size, uint64_t hash, const uint8_t *wanted, size_t num_parts,
                          size_t max_parts)
{
    meshtopo_reply_part_t part;
    memset(&part, 0, sizeof part);
    part.request_id = request_id;
    part.total_size = (int64_t)size;
    part.answer_hash = (int64_t)hash;
    part.part_size = MESHTOPO_REPLY_PART_T_PART_SIZE;
    part.length = MESHTOPO_REPLY_PART_T_PART_SIZE;
    int capacity = meshtopo_reply_part_t_encoded_size(&part);
    uint8_t *buf = malloc((size_t)capacity);
    if (!buf) {
        mtd_log(MTD_LOG_ERROR, "reply_parts", "request_id=%" PRId64 " out of memory", request_id);
        return;
    }
    size_t sent = 0;
    for (size_t k = 0; k < num_parts && sent < max_parts; k++) {
        if (wanted && !wanted[k]) continue;
        size_t offset = k * part_size;
        size_t length = size - offset < part_size ? size - offset : part_size;
        part.utime = mtd_now_utime();
        part.offset = (int64_t)offset;
        part.length = (int32_t)length;
        part.data = (uint8_t *)(uintptr_t)(data + offset);
        int n = meshtopo_reply_part_t_encode(buf, 0, capacity, &part);
        if (n <= 0 || lcm_publish(lcm, channel, buf, (unsigned)n) != 0)
            mtd_log(MTD_LOG_ERROR, "publish", "channel=%s type=reply_part_t offset=%zu", channel,
                    offset);
        sent++;
    }
    free(buf);
}

void mtd_parts_publish(lcm_t *lcm, const char *reply_channel, int64_t request_id, const void *data,
                       size_t size)
{
    const mt_msgs_type *type = mt_msgs_type_of(data, size);
    bool in_parts = size > MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX &&
                    (type == &mt_msgs_type_reply || type == &mt_msgs_type_ack);
    char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
    if (mt_msgs_reply_channel_name(reply_channel, in_parts ? &mt_msgs_type_reply_part : type,
                                   channel) != MT_OK) {
        mtd_log(MTD_LOG_ERROR, "publish", "reply_channel=%.80s type=%s: no channel to answer on",
                reply_channel, type ? type->name : "?");
        return;
    }
    if (!in_parts) {
        if (lcm_publish(lcm, channel, data, (unsigned)size) != 0)
            mtd_log(MTD_LOG_ERROR, "publish", "channel=%s bytes=%zu", channel, size);
        return;
    }
    size_t num_parts = (size + part_size - 1) / part_size;
    uint64_t hash = mt_msgs_answer_hash(data, size);
    mtd_log(MTD_LOG_DEBUG, "reply_parts",
            "request_id=%" PRId64 " bytes=%zu parts=%zu first=%zu hash=%016" PRIx64, request_id,
            size, num_parts, first_parts, hash);
    publish_parts(lcm, channel, request_id, data, size, hash, NULL, num_parts, first_parts);
}

/* The remembered answer a pull names: the reply_t or ack_t of its request
 * under its reply channel whose size and hash are the pull's, large enough
 * to have gone in parts. NULL when the cache holds none (release the one
 * returned with mtd_reply_release). */
static mtd_reply *pulled_answer(mtd_reqcache *cache, const meshtopo_reply_pull_t *pull)
{
    const mt_msgs_type *answers[] = {&mt_msgs_type_reply, &mt_msgs_type_ack};
    for (size_t i = 0; i < sizeof answers / sizeof answers[0]; i++) {
        char key[MT_MSGS_CHANNEL_NAME_MAX + 1];
        mtd_request_state state = MTD_REQUEST_NEW;
        mtd_reply *stored = NULL;
        if (mt_msgs_reply_channel_name(pull->reply_channel, answers[i], key) != MT_OK ||
            mtd_reqcache_peek(cache, key, pull->request_id, &state, &stored) != MT_OK)
            continue;
        if (state == MTD_REQUEST_DONE) {
            const uint8_t *bytes = mtd_reply_data(stored);
            size_t total = mtd_reply_size(stored);
            if (pull->total_size == (int64_t)total &&
                total > MESHTOPO_MESH_CHUNK_T_SINGLE_MESSAGE_MAX &&
                (uint64_t)pull->answer_hash == mt_msgs_answer_hash(bytes, total))
                return stored;
        }
        mtd_reply_release(stored);
    }
    return NULL;
}

void mtd_parts_serve_pull(lcm_t *lcm, mtd_reqcache *cache, const void *data, size_t size)
{
    meshtopo_reply_pull_t pull;
    char why[MT_MSGS_ERROR_SIZE];
    if (mt_msgs_decode(&mt_msgs_type_reply_pull, data, size, &pull, why, sizeof why) != 0) {
        mtd_log(MTD_LOG_WARN, "undecodable", "bytes=%zu error=undecodable reply_pull_t: %s", size,
                why);
        return;
    }
    char parts[MT_MSGS_CHANNEL_NAME_MAX + 1];
    mtd_reply *stored = NULL;
    if (pull.num_ranges > MESHTOPO_REPLY_PULL_T_RANGES_MAX) {
        mtd_log(MTD_LOG_WARN, "reply_pull",
                "request_id=%" PRId64 " %d ranges (at most %d): ignored", pull.request_id,
                (int)pull.num_ranges, MESHTOPO_REPLY_PULL_T_RANGES_MAX);
    } else if (mt_msgs_reply_channel_name(pull.reply_channel, &mt_msgs_type_reply_part, parts) !=
                   MT_OK ||
               !(stored = pulled_answer(cache, &pull))) {
        mtd_log(MTD_LOG_DEBUG, "reply_pull",
                "request_id=%" PRId64 " channel=%s: no answer of %" PRId64
                " bytes held, not answered",
                pull.request_id, pull.reply_channel, pull.total_size);
    } else {
        const uint8_t *bytes = mtd_reply_data(stored);
        size_t total = mtd_reply_size(stored);
        size_t num_parts = (total + part_size - 1) / part_size;
        uint8_t *wanted = calloc(num_parts, 1);
        for (int32_t i = 0; wanted && i < pull.num_ranges; i++) {
            int64_t start = pull.offsets[i], length = pull.lengths[i];
            if (start < 0 || length <= 0 || (uint64_t)start >= total) continue;
            uint64_t end = (uint64_t)length > total - (uint64_t)start
                               ? total
                               : (uint64_t)start + (uint64_t)length;
            for (uint64_t k = (uint64_t)start / part_size; k * part_size < end; k++) wanted[k] = 1;
        }
        if (wanted)
            publish_parts(lcm, parts, pull.request_id, bytes, total,
                          mt_msgs_answer_hash(bytes, total), wanted, num_parts, parts_per_pull);
        free(wanted);
    }
    mtd_reply_release(stored);
    meshtopo_reply_pull_t_decode_cleanup(&pull);
}
