/* mesh_t's content as bytes (see meshtopo/mesh_content.h): range encoding
 * from host-order arrays and in-place decoding with hashing. The content is
 * seven runs of big-endian values: num_verts and num_position_values (4
 * bytes each), the positions (8 bytes: a double's IEEE-754 bits), num_faces,
 * the face counts, num_indices, the indices (4 bytes each). A range may start
 * or end inside a value; only the values it cuts are handled one byte at a
 * time. */
#define _DEFAULT_SOURCE /* endian.h's htobe64 and friends under -std=c11 */
#include "meshtopo/mesh_content.h"

#include <endian.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <xxhash.h>

/* Bytes of the four counts: two before the positions, two after. */
#define COUNTS_BEFORE_POSITIONS 8
#define COUNTS_SIZE 16

/* One run of values of the content. */
typedef struct value_run {
    uint64_t start;     /* content offset of its first byte */
    uint64_t count;     /* values */
    unsigned width;     /* bytes per value: 4 or 8 */
    const void *values; /* host-order array of count values */
} value_run;

static uint64_t unsigned_count(int32_t count)
{
    return (uint64_t)(uint32_t)count;
}

uint64_t mt_msgs_mesh_content_size(const meshtopo_mesh_t *m)
{
    return COUNTS_SIZE + 8 * unsigned_count(m->num_position_values) +
           4 * unsigned_count(m->num_faces) + 4 * unsigned_count(m->num_indices);
}

/* m's content as its seven runs, in order. */
static void runs_of(const meshtopo_mesh_t *m, value_run runs[7])
{
    const uint64_t npos = unsigned_count(m->num_position_values);
    const uint64_t nfaces = unsigned_count(m->num_faces);
    const uint64_t nindices = unsigned_count(m->num_indices);
    const uint64_t faces_at = COUNTS_BEFORE_POSITIONS + 8 * npos;
    const uint64_t indices_at = faces_at + 4 + 4 * nfaces;
    runs[0] = (value_run){0, 1, 4, &m->num_verts};
    runs[1] = (value_run){4, 1, 4, &m->num_position_values};
    runs[2] = (value_run){COUNTS_BEFORE_POSITIONS, npos, 8, m->positions};
    runs[3] = (value_run){faces_at, 1, 4, &m->num_faces};
    runs[4] = (value_run){faces_at + 4, nfaces, 4, m->face_vertex_counts};
    runs[5] = (value_run){indices_at, 1, 4, &m->num_indices};
    runs[6] = (value_run){indices_at + 4, nindices, 4, m->face_vertex_indices};
}

/* Value `index` of run r, big-endian, into out[0 .. r->width). */
static void encode_value(const value_run *r, uint64_t index, uint8_t *out)
{
    const uint8_t *src = (const uint8_t *)r->values + index * r->width;
    if (r->width == 8) {
        uint64_t v;
        memcpy(&v, src, 8);
        v = htobe64(v);
        memcpy(out, &v, 8);
    } else {
        uint32_t v;
        memcpy(&v, src, 4);
        v = htobe32(v);
        memcpy(out, &v, 4);
    }
}

/* Values [first, first + n) of run r, big-endian, to out. */
static void encode_values(const value_run *r, uint64_t first, uint64_t n, uint8_t *out)
{
    const uint8_t *src = (const uint8_t *)r->values + first * r->width;
    if (r->width == 8) {
        for (uint64_t i = 0; i < n; i++) {
            uint64_t v;
            memcpy(&v, src + 8 * i, 8);
            v = htobe64(v);
            memcpy(out + 8 * i, &v, 8);
        }
    } else {
        for (uint64_t i = 0; i < n; i++) {
            uint32_t v;
            memcpy(&v, src + 4 * i, 4);
            v = htobe32(v);
            memcpy(out + 4 * i, &v, 4);
        }
    }
}

void mt_msgs_mesh_content_encode(const meshtopo_mesh_t *m, uint64_t offset, size_t length,
                                 uint8_t *out)
{
    value_run runs[7];
    runs_of(m, runs);
    const uint64_t lo = offset, hi = offset + length;
    for (int k = 0; k < 7; k++) {
        const value_run *r = &runs[k];
        const uint64_t end = r->start + r->count * r->width;
        uint64_t pos = lo > r->start ? lo : r->start;
        const uint64_t to = hi < end ? hi : end;
        uint64_t index = pos < to ? (pos - r->start) / r->width : 0;
        while (pos < to) {
            const uint64_t value_at = r->start + index * r->width;
            if (value_at == pos && value_at + r->width <= to) { /* whole values */
                uint64_t n = (to - pos) / r->width;
                encode_values(r, index, n, out + (pos - lo));
                pos += n * r->width;
                index += n;
            } else { /* a value the range cuts */
                uint8_t bytes[8];
                encode_value(r, index, bytes);
                uint64_t first = pos - value_at;
                uint64_t last = to - value_at < r->width ? to - value_at : r->width;
                memcpy(out + (pos - lo), bytes + first, (size_t)(last - first));
                pos = value_at + last;
                index++;
            }
        }
    }
}

/* ---- in-place decoding ----------------------------------------------------- */

struct mt_msgs_content_decoder {
    uint8_t *bytes;
    uint64_t total;
    uint64_t hashed;        /* bytes [0, hashed) went into the hash */
    uint64_t converted;     /* bytes [0, converted) are whole values in host order */
    uint64_t positions_end; /* 8 + 8 * num_position_values, once known (else 0) */
    char layout_error[200]; /* the counts cannot describe `total` bytes: converting stopped */
    XXH3_state_t *hash;
};

mt_msgs_content_decoder *mt_msgs_content_decoder_new(uint8_t *bytes, uint64_t total)
{
    mt_msgs_content_decoder *d = calloc(1, sizeof *d);
    if (!d) return NULL;
    d->hash = XXH3_createState();
    if (!d->hash || XXH3_64bits_reset(d->hash) != XXH_OK) {
        mt_msgs_content_decoder_free(d);
        return NULL;
    }
    d->bytes = bytes;
    d->total = total;
    return d;
}

void mt_msgs_content_decoder_free(mt_msgs_content_decoder *d)
{
    if (!d) return;
    XXH3_freeState(d->hash);
    free(d);
}

static int32_t read_count(const mt_msgs_content_decoder *d, uint64_t at)
{
    int32_t v;
    memcpy(&v, d->bytes + at, 4);
    return v;
}

/* Values [at, at + 4n) from big-endian to host order. */
static void convert_32(uint8_t *at, uint64_t n)
{
    for (uint64_t i = 0; i < n; i++) {
        uint32_t v;
        memcpy(&v, at + 4 * i, 4);
        v = be32toh(v);
        memcpy(at + 4 * i, &v, 4);
    }
}

static void convert_64(uint8_t *at, uint64_t n)
{
    for (uint64_t i = 0; i < n; i++) {
        uint64_t v;
        memcpy(&v, at + 8 * i, 8);
        v = be64toh(v);
        memcpy(at + 8 * i, &v, 8);
    }
}

/* num_position_values is in host order: where the positions end, or why
 * they cannot. */
static void learn_positions(mt_msgs_content_decoder *d)
{
    const int32_t npos = read_count(d, 4);
    const uint64_t end = COUNTS_BEFORE_POSITIONS + 8 * unsigned_count(npos);
    if (npos < 0)
        snprintf(d->layout_error, sizeof d->layout_error,
                 "num_position_values: %" PRId32 " is negative", npos);
    else if (end + 8 > d->total)
        snprintf(d->layout_error, sizeof d->layout_error,
                 "num_position_values: %" PRId32 " positions (%" PRIu64
                 " bytes) leave no room for num_faces and num_indices in %" PRIu64
                 " bytes of content",
                 npos, 8 * unsigned_count(npos), d->total);
    else if ((d->total - end) % 4 != 0)
        snprintf(d->layout_error, sizeof d->layout_error,
                 "content: %" PRIu64 " bytes after %" PRId32
                 " positions are not a whole number of 4-byte values",
                 d->total - end, npos);
    else
        d->positions_end = end;
}

/* Converts the whole values among bytes [converted, ready). */
static void convert(mt_msgs_content_decoder *d, uint64_t ready)
{
    while (!d->layout_error[0]) {
        const uint64_t at = d->converted;
        uint64_t n;
        if (at < COUNTS_BEFORE_POSITIONS) {
            if (ready < at + 4) return;
            convert_32(d->bytes + at, 1);
            d->converted += 4;
            if (d->converted == COUNTS_BEFORE_POSITIONS) learn_positions(d);
        } else if (at < d->positions_end) {
            n = ((ready < d->positions_end ? ready : d->positions_end) - at) / 8;
            if (n == 0) return;
            convert_64(d->bytes + at, n);
            d->converted += 8 * n;
        } else {
            n = (ready - at) / 4;
            if (n == 0) return;
            convert_32(d->bytes + at, n);
            d->converted += 4 * n;
        }
    }
}

void mt_msgs_content_decoder_advance(mt_msgs_content_decoder *d, uint64_t ready)
{
    if (ready > d->total) ready = d->total;
    if (ready <= d->hashed) return;
    /* Hashed as received (big-endian), then converted. */
    XXH3_64bits_update(d->hash, d->bytes + d->hashed, (size_t)(ready - d->hashed));
    d->hashed = ready;
    convert(d, ready);
}

int mt_msgs_content_decoder_finish(mt_msgs_content_decoder *d, meshtopo_mesh_t *out,
                                   uint64_t *out_hash, char *error, size_t error_size)
{
    *out_hash = XXH3_64bits_digest(d->hash);
    if (d->hashed < d->total) {
        snprintf(error, error_size,
                 "content: only %" PRIu64 " of %" PRIu64 " bytes have arrived in order", d->hashed,
                 d->total);
        return -1;
    }
    if (d->total < COUNTS_SIZE) {
        snprintf(error, error_size,
                 "content: %" PRIu64 " bytes are fewer than its four counts take (16)", d->total);
        return -1;
    }
    if (d->layout_error[0]) {
        snprintf(error, error_size, "%s", d->layout_error);
        return -1;
    }
    const int32_t nfaces = read_count(d, d->positions_end);
    const uint64_t counts_end = d->positions_end + 4 + 4 * unsigned_count(nfaces);
    if (nfaces < 0) {
        snprintf(error, error_size, "num_faces: %" PRId32 " is negative", nfaces);
        return -1;
    }
    if (counts_end + 4 > d->total) {
        snprintf(error, error_size,
                 "num_faces: %" PRId32 " face counts end at byte %" PRIu64 ", past the %" PRIu64
                 " bytes of content",
                 nfaces, counts_end, d->total);
        return -1;
    }
    const int32_t nindices = read_count(d, counts_end);
    if (nindices < 0) {
        snprintf(error, error_size, "num_indices: %" PRId32 " is negative", nindices);
        return -1;
    }
    if (counts_end + 4 + 4 * unsigned_count(nindices) != d->total) {
        snprintf(error, error_size,
                 "num_indices: %" PRId32 " indices end at byte %" PRIu64
                 ", but the content has %" PRIu64 " bytes",
                 nindices, counts_end + 4 + 4 * unsigned_count(nindices), d->total);
        return -1;
    }
    const int32_t npos = read_count(d, 4);
    out->num_verts = read_count(d, 0);
    out->num_position_values = npos;
    out->positions = npos ? (double *)(void *)(d->bytes + COUNTS_BEFORE_POSITIONS) : NULL;
    out->num_faces = nfaces;
    out->face_vertex_counts = nfaces ? (int32_t *)(void *)(d->bytes + d->positions_end + 4) : NULL;
    out->num_indices = nindices;
    out->face_vertex_indices = nindices ? (int32_t *)(void *)(d->bytes + counts_end + 4) : NULL;
    return 0;
}
