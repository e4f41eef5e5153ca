/* Reassembly of a large answer sent in reply_part_t pieces
 * (msgs/reply_part_t.lcm): one buffer of the announced size, a flag per
 * part, and the list of missing byte ranges the next reply_pull_t asks for.
 * A part that breaks the layout (offset not on a part boundary, past the
 * total, wrong length) or belongs to another answer is refused without
 * touching what is held. No locking: the client's mutex guards it. */
#include <stdlib.h>
#include <string.h>

#include "client_internal.h"

/* Largest part_size accepted (the daemon uses 57,344; a datagram holds less
 * than 64 KiB). */
#define MT__PART_SIZE_MAX 65536

mt_status mt__parts_create(const meshtopo_reply_part_t *part, mt__parts **out_parts)
{
    *out_parts = NULL;
    if (part->total_size <= 0 || part->part_size <= 0 || part->part_size > MT__PART_SIZE_MAX ||
        (uint64_t)part->total_size > (uint64_t)SIZE_MAX / 2)
        return MT_ERR_INVALID_ARG;
    mt__parts *p = calloc(1, sizeof *p);
    if (!p) return MT_ERR_NOMEM;
    p->total = (uint64_t)part->total_size;
    p->hash = (uint64_t)part->answer_hash;
    p->part_size = (uint32_t)part->part_size;
    p->num_parts = (size_t)((p->total + p->part_size - 1) / p->part_size);
    p->have = calloc(p->num_parts, 1);
    p->data = malloc((size_t)p->total);
    if (!p->have || !p->data) {
        mt__parts_free(p);
        return MT_ERR_NOMEM;
    }
    *out_parts = p;
    return MT_OK;
}

void mt__parts_free(mt__parts *parts)
{
    if (!parts) return;
    free(parts->have);
    free(parts->data);
    free(parts);
}

mt__part_result mt__parts_add(mt__parts *parts, const meshtopo_reply_part_t *part)
{
    if ((uint64_t)part->total_size != parts->total || (uint64_t)part->answer_hash != parts->hash ||
        part->part_size != (int32_t)parts->part_size)
        return MT__PART_OTHER;
    if (part->offset < 0 || (uint64_t)part->offset >= parts->total ||
        (uint64_t)part->offset % parts->part_size != 0)
        return MT__PART_BAD;
    uint64_t offset = (uint64_t)part->offset;
    uint64_t expected =
        parts->total - offset < parts->part_size ? parts->total - offset : parts->part_size;
    if (part->length < 0 || (uint64_t)part->length != expected) return MT__PART_BAD;
    size_t k = (size_t)(offset / parts->part_size);
    if (parts->have[k]) return MT__PART_DUPLICATE;
    memcpy(parts->data + offset, part->data, (size_t)expected);
    parts->have[k] = 1;
    parts->num_have++;
    return MT__PART_ADDED;
}

int mt__parts_complete(const mt__parts *parts)
{
    return parts->num_have == parts->num_parts;
}

size_t mt__parts_missing(const mt__parts *parts, size_t max_parts, size_t max_ranges,
                         int64_t *out_offsets, int64_t *out_lengths, size_t *out_num_parts)
{
    size_t ranges = 0, listed = 0;
    for (size_t k = 0; k < parts->num_parts && listed < max_parts; k++) {
        if (parts->have[k]) continue;
        uint64_t start = (uint64_t)k * parts->part_size;
        uint64_t end =
            start + parts->part_size > parts->total ? parts->total : start + parts->part_size;
        if (ranges > 0 && (uint64_t)(out_offsets[ranges - 1] + out_lengths[ranges - 1]) == start) {
            out_lengths[ranges - 1] += (int64_t)(end - start);
        } else {
            if (ranges == max_ranges) break;
            out_offsets[ranges] = (int64_t)start;
            out_lengths[ranges] = (int64_t)(end - start);
            ranges++;
        }
        listed++;
    }
    if (out_num_parts) *out_num_parts = listed;
    return ranges;
}
