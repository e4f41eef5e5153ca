/* meshtopo/mesh_content.h and the content hash: every byte range the range
 * encoder writes equals the same bytes of LCM's own encoding of the mesh_t;
 * the hash is XXH3-64 of those bytes however it is computed (checked against
 * libxxhash directly); the in-place decoder, given the content in pieces of
 * any size in any order, yields the mesh's arrays and its hash, and refuses
 * counts that do not describe the bytes with an error naming the field.
 * meshtopo::ident's hash of a face list (the archive's, no LCM) is the same
 * hash, whole or piece by piece. */
#include <stdlib.h>
#include <string.h>
#include <xxhash.h>

#include "harness.h"
#include "meshtopo/content_hash.h"
#include "meshtopo/mesh_content.h"
#include "meshtopo/mesh_ident.h"

/* Deterministic xorshift64 so a failure reproduces. */
static uint64_t next_random(uint64_t *state)
{
    uint64_t x = *state;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    *state = x;
    return x;
}

/* A mesh_t with `faces` faces of 3 to 5 vertices over `verts` vertices, with
 * or without positions; its arrays are heap-allocated (free_mesh). */
static meshtopo_mesh_t make_mesh(int32_t verts, int32_t faces, int with_positions, uint64_t seed)
{
    meshtopo_mesh_t m;
    memset(&m, 0, sizeof m);
    m.reply_channel = "reply";
    m.mesh_id = "content";
    m.source = "test_mesh_content";
    m.num_verts = verts;
    m.num_position_values = with_positions ? 3 * verts : 0;
    m.positions = malloc(sizeof(double) * (size_t)(m.num_position_values + 1));
    for (int32_t i = 0; i < m.num_position_values; i++)
        m.positions[i] = (double)(int64_t)next_random(&seed) / 3.0e9;
    m.num_faces = faces;
    m.face_vertex_counts = malloc(sizeof(int32_t) * (size_t)(faces + 1));
    m.face_vertex_indices = malloc(sizeof(int32_t) * (size_t)(5 * faces + 1));
    for (int32_t f = 0; f < faces; f++) {
        m.face_vertex_counts[f] = 3 + (int32_t)(next_random(&seed) % 3);
        for (int32_t k = 0; k < m.face_vertex_counts[f]; k++)
            m.face_vertex_indices[m.num_indices++] =
                (int32_t)(next_random(&seed) % (uint64_t)(verts > 0 ? verts : 1));
    }
    return m;
}

static void free_mesh(meshtopo_mesh_t *m)
{
    free(m->positions);
    free(m->face_vertex_counts);
    free(m->face_vertex_indices);
}

/* LCM's encoding of m; *out_content points at its content (the tail). */
static uint8_t *lcm_encode(const meshtopo_mesh_t *m, size_t *out_size, const uint8_t **out_content)
{
    int size = meshtopo_mesh_t_encoded_size(m);
    uint8_t *buf = malloc((size_t)size);
    CHECK_EQ(meshtopo_mesh_t_encode(buf, 0, size, m), size);
    *out_size = (size_t)size;
    *out_content = buf + size - mt_msgs_mesh_content_size(m);
    return buf;
}

static void encoder_matches_lcm_for(const meshtopo_mesh_t *m, uint64_t *seed, int every_range)
{
    size_t size;
    const uint8_t *content;
    uint8_t *encoded = lcm_encode(m, &size, &content);
    const uint64_t total = mt_msgs_mesh_content_size(m);
    CHECK(total <= size);
    uint8_t *out = malloc(total + 1);
    int mismatches = 0;
    if (every_range) {
        for (uint64_t lo = 0; lo <= total; lo++)
            for (uint64_t hi = lo; hi <= total; hi++) {
                memset(out, 0xa5, total + 1);
                mt_msgs_mesh_content_encode(m, lo, (size_t)(hi - lo), out);
                if (memcmp(out, content + lo, (size_t)(hi - lo)) != 0) mismatches++;
                if (out[hi - lo] != 0xa5) mismatches++; /* nothing past the range */
            }
    } else {
        for (int k = 0; k < 2000; k++) {
            uint64_t lo = k == 0 ? 0 : next_random(seed) % (total + 1);
            uint64_t hi = k == 0 ? total : lo + next_random(seed) % (total - lo + 1);
            mt_msgs_mesh_content_encode(m, lo, (size_t)(hi - lo), out);
            if (memcmp(out, content + lo, (size_t)(hi - lo)) != 0) mismatches++;
        }
    }
    CHECK_EQ(mismatches, 0);
    free(out);
    free(encoded);
}

static void encode_ranges_match_lcm(void)
{
    uint64_t seed = 0x9e3779b97f4a7c15ull;
    meshtopo_mesh_t small = make_mesh(5, 4, 1, 1);
    encoder_matches_lcm_for(&small, &seed, 1); /* every range of a ~200-byte content */
    free_mesh(&small);
    meshtopo_mesh_t bare = make_mesh(7, 3, 0, 2);
    encoder_matches_lcm_for(&bare, &seed, 1);
    free_mesh(&bare);
    meshtopo_mesh_t empty = make_mesh(0, 0, 1, 3);
    encoder_matches_lcm_for(&empty, &seed, 1);
    free_mesh(&empty);
    meshtopo_mesh_t large = make_mesh(20000, 30000, 1, 4);
    encoder_matches_lcm_for(&large, &seed, 0);
    free_mesh(&large);
}

static void content_hash_is_xxh3_of_the_encoding(void)
{
    const int32_t sizes[][3] = {
        {0, 0, 1}, {4, 2, 1}, {4, 2, 0}, {3000, 5000, 1}, {50000, 90000, 1}};
    uint64_t previous = 0;
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        meshtopo_mesh_t m = make_mesh(sizes[i][0], sizes[i][1], sizes[i][2], 10 + i);
        size_t size;
        const uint8_t *content;
        uint8_t *encoded = lcm_encode(&m, &size, &content);
        const uint64_t total = mt_msgs_mesh_content_size(&m);
        const uint64_t expected = XXH3_64bits(content, (size_t)total);
        CHECK_EQ(mt_msgs_content_hash_bytes(content, (size_t)total), expected);
        CHECK_EQ(mt_msgs_mesh_content_hash(&m, encoded, size), expected);
        CHECK_EQ(mt_msgs_mesh_content_hash_of(&m), expected); /* blocks of 32 KiB */
        CHECK(expected != previous);
        previous = expected;
        /* One changed index changes it. */
        if (m.num_indices > 0) {
            m.face_vertex_indices[m.num_indices / 2] ^= 1;
            CHECK(mt_msgs_mesh_content_hash_of(&m) != expected);
        }
        CHECK_EQ(mt_msgs_mesh_content_hash(&m, encoded, (size_t)total - 1), 0);
        free(encoded);
        free_mesh(&m);
    }
}

/* Gives decoder the content in `pieces` pieces of random sizes, in random
 * order, as the daemon does: each piece is copied except what lies below the
 * bytes already given (those were turned into values), then the decoder
 * advances over the bytes held from 0 on. */
static void feed_in_pieces(mt_msgs_content_decoder *decoder, uint8_t *buffer,
                           const uint8_t *content, uint64_t total, size_t pieces, uint64_t *seed)
{
    uint64_t *cuts = malloc(sizeof(uint64_t) * (pieces + 1));
    cuts[0] = 0;
    for (size_t i = 1; i < pieces; i++) cuts[i] = next_random(seed) % (total + 1);
    cuts[pieces] = total;
    for (size_t i = 1; i < pieces; i++) /* insertion sort: the cut points in order */
        for (size_t j = i; j > 0 && cuts[j] < cuts[j - 1]; j--) {
            uint64_t t = cuts[j];
            cuts[j] = cuts[j - 1];
            cuts[j - 1] = t;
        }
    size_t *order = malloc(sizeof(size_t) * pieces);
    for (size_t i = 0; i < pieces; i++) order[i] = i;
    for (size_t i = pieces; i > 1; i--) {
        size_t j = next_random(seed) % i;
        size_t t = order[i - 1];
        order[i - 1] = order[j];
        order[j] = t;
    }
    uint8_t *have = calloc(total + 1, 1);
    uint64_t ready = 0;
    for (size_t k = 0; k < pieces; k++) {
        uint64_t lo = cuts[order[k]], hi = cuts[order[k] + 1];
        for (uint64_t b = lo; b < hi; b++) {
            if (b >= ready) buffer[b] = content[b];
            have[b] = 1;
        }
        while (ready < total && have[ready]) ready++;
        mt_msgs_content_decoder_advance(decoder, ready);
    }
    free(have);
    free(order);
    free(cuts);
}

static void decoder_takes_pieces_in_any_order(void)
{
    uint64_t seed = 0x243f6a8885a308d3ull;
    const int32_t sizes[][3] = {{4, 2, 1}, {4, 2, 0}, {0, 0, 1}, {300, 500, 1}, {2000, 3000, 1}};
    const size_t piece_counts[] = {1, 2, 7, 64, 1000};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        for (size_t p = 0; p < sizeof piece_counts / sizeof piece_counts[0]; p++) {
            meshtopo_mesh_t m = make_mesh(sizes[i][0], sizes[i][1], sizes[i][2], 20 + i);
            size_t size;
            const uint8_t *content;
            uint8_t *encoded = lcm_encode(&m, &size, &content);
            const uint64_t total = mt_msgs_mesh_content_size(&m);
            uint8_t *buffer = malloc(total);
            mt_msgs_content_decoder *decoder = mt_msgs_content_decoder_new(buffer, total);
            CHECK(decoder != NULL);
            feed_in_pieces(decoder, buffer, content, total, piece_counts[p], &seed);
            meshtopo_mesh_t out;
            memset(&out, 0, sizeof out);
            uint64_t hash = 0;
            char error[256] = "";
            CHECK_EQ(mt_msgs_content_decoder_finish(decoder, &out, &hash, error, sizeof error), 0);
            CHECK_EQ(hash, XXH3_64bits(content, (size_t)total));
            CHECK_EQ(out.num_verts, m.num_verts);
            CHECK_EQ(out.num_position_values, m.num_position_values);
            CHECK_EQ(out.num_faces, m.num_faces);
            CHECK_EQ(out.num_indices, m.num_indices);
            if (m.num_position_values)
                CHECK(memcmp(out.positions, m.positions,
                             sizeof(double) * (size_t)m.num_position_values) == 0);
            else
                CHECK(out.positions == NULL);
            if (m.num_faces)
                CHECK(memcmp(out.face_vertex_counts, m.face_vertex_counts,
                             sizeof(int32_t) * (size_t)m.num_faces) == 0);
            if (m.num_indices)
                CHECK(memcmp(out.face_vertex_indices, m.face_vertex_indices,
                             sizeof(int32_t) * (size_t)m.num_indices) == 0);
            mt_msgs_content_decoder_free(decoder);
            free(buffer);
            free(encoded);
            free_mesh(&m);
        }
    }
    mt_msgs_content_decoder_free(NULL);
}

/* Big-endian 32-bit value v at content[at]. */
static void put_be32(uint8_t *content, size_t at, int32_t v)
{
    uint32_t u = (uint32_t)v;
    for (int k = 0; k < 4; k++) content[at + (size_t)k] = (uint8_t)(u >> (24 - 8 * k));
}

/* Decodes `total` bytes of content given all at once; returns finish's
 * result and checks the error names `field` when it fails. */
static int decode_whole(const uint8_t *content, uint64_t total, const char *field)
{
    uint8_t *buffer = malloc(total + 1);
    memcpy(buffer, content, (size_t)total);
    mt_msgs_content_decoder *decoder = mt_msgs_content_decoder_new(buffer, total);
    mt_msgs_content_decoder_advance(decoder, total);
    meshtopo_mesh_t out;
    memset(&out, 0, sizeof out);
    uint64_t hash = 0;
    char error[256] = "";
    int result = mt_msgs_content_decoder_finish(decoder, &out, &hash, error, sizeof error);
    CHECK_EQ(hash, XXH3_64bits(content, (size_t)total)); /* the hash is set in any case */
    if (field) {
        CHECK_EQ(result, -1);
        if (!strstr(error, field))
            mt_test_fail(__FILE__, __LINE__, "error '%s' does not name '%s'", error, field);
    }
    mt_msgs_content_decoder_free(decoder);
    free(buffer);
    return result;
}

static void decoder_refuses_counts_that_do_not_fit(void)
{
    /* A triangle without positions: 3, 0, 1, [3], 3, [0 1 2] = 36 bytes. */
    uint8_t c[64];
    memset(c, 0, sizeof c);
    put_be32(c, 0, 3);
    put_be32(c, 4, 0);
    put_be32(c, 8, 1);
    put_be32(c, 12, 3);
    put_be32(c, 16, 3);
    put_be32(c, 20, 0);
    put_be32(c, 24, 1);
    put_be32(c, 28, 2);
    CHECK_EQ(decode_whole(c, 32, NULL), 0);

    put_be32(c, 4, -3);
    decode_whole(c, 32, "num_position_values");
    put_be32(c, 4, 3); /* 24 bytes of positions leave no room for the two counts */
    decode_whole(c, 32, "num_position_values");
    put_be32(c, 4, 0);
    decode_whole(c, 33, "not a whole number");
    put_be32(c, 8, -1);
    decode_whole(c, 32, "num_faces");
    put_be32(c, 8, 40);
    decode_whole(c, 32, "num_faces");
    put_be32(c, 8, 1);
    put_be32(c, 16, 4); /* one index more than the bytes hold */
    decode_whole(c, 32, "num_indices");
    put_be32(c, 16, -2);
    decode_whole(c, 32, "num_indices");
    put_be32(c, 16, 3);
    decode_whole(c, 36, "num_indices"); /* 4 bytes too many */
    decode_whole(c, 12, "fewer than its four counts");
    decode_whole(c, 0, "fewer than its four counts");

    /* Finishing before every byte was advanced over says so. */
    uint8_t buffer[32];
    memcpy(buffer, c, sizeof buffer);
    mt_msgs_content_decoder *decoder = mt_msgs_content_decoder_new(buffer, 32);
    mt_msgs_content_decoder_advance(decoder, 20);
    mt_msgs_content_decoder_advance(decoder, 10); /* smaller: nothing */
    meshtopo_mesh_t out;
    uint64_t hash;
    char error[128];
    CHECK_EQ(mt_msgs_content_decoder_finish(decoder, &out, &hash, error, sizeof error), -1);
    CHECK(strstr(error, "only 20 of 32 bytes") != NULL);
    mt_msgs_content_decoder_advance(decoder, 99); /* past the end: up to the end */
    CHECK_EQ(mt_msgs_content_decoder_finish(decoder, &out, &hash, error, sizeof error), 0);
    CHECK_EQ(out.num_indices, 3);
    CHECK_EQ(out.face_vertex_indices[2], 2);
    mt_msgs_content_decoder_free(decoder);
}

/* The content hash of make_mesh(4, 2, 1, 11): the XXH3-64 of its LCM
 * encoding's content fields. */
#define PINNED_HASH 0xe8b2a48eca49ce7aULL

/* m's content as a face list view (not owned). */
static mt_face_list face_list_of(const meshtopo_mesh_t *m)
{
    mt_face_list list = {(uint32_t)m->num_verts,
                         (uint32_t)m->num_faces,
                         (uint64_t)m->num_indices,
                         m->num_position_values ? m->positions : NULL,
                         (uint32_t *)m->face_vertex_counts,
                         (uint32_t *)m->face_vertex_indices};
    return list;
}

static void face_list_hash_is_the_content_hash(void)
{
    const int32_t sizes[][3] = {{0, 0, 1},       {4, 2, 1},         {4, 2, 0},
                                {3000, 5000, 1}, {50000, 90000, 1}, {9000, 20000, 0}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        meshtopo_mesh_t m = make_mesh(sizes[i][0], sizes[i][1], sizes[i][2], 30 + i);
        size_t size;
        const uint8_t *content;
        uint8_t *encoded = lcm_encode(&m, &size, &content);
        const uint64_t expected = mt_msgs_mesh_content_hash(&m, encoded, size);
        CHECK_EQ(mt_content_hash_bytes(content, (size_t)mt_msgs_mesh_content_size(&m)), expected);
        mt_face_list list = face_list_of(&m);
        uint64_t hash = 0;
        mt_diag diag;
        CHECK_EQ(mt_face_list_content_hash(&list, &hash, &diag), MT_OK);
        CHECK_EQ(hash, expected);
        /* Piece by piece, the arrays cut anywhere (as an archive file is read). */
        mt_content_hasher *h = mt_content_hasher_new();
        CHECK(h != NULL);
        const size_t npos = (size_t)m.num_position_values, cut = npos / 3;
        mt_content_hasher_count(h, list.num_verts);
        mt_content_hasher_count(h, (uint32_t)npos);
        mt_content_hasher_doubles(h, m.positions, cut);
        mt_content_hasher_doubles(h, m.positions + cut, npos - cut);
        mt_content_hasher_count(h, list.num_faces);
        mt_content_hasher_int32s(h, list.face_sizes, list.num_faces);
        mt_content_hasher_count(h, (uint32_t)list.num_indices);
        for (uint64_t at = 0; at < list.num_indices; at += 7777) {
            uint64_t n = list.num_indices - at < 7777 ? list.num_indices - at : 7777;
            mt_content_hasher_int32s(h, list.face_indices + at, (size_t)n);
        }
        CHECK_EQ(mt_content_hasher_digest(h), expected);
        mt_content_hasher_free(h);
        free(encoded);
        free_mesh(&m);
    }
    /* Pinned: the hash is stored in archive files and compared on the wire. */
    meshtopo_mesh_t m = make_mesh(4, 2, 1, 11);
    mt_face_list list = face_list_of(&m);
    uint64_t hash = 0;
    CHECK_EQ(mt_face_list_content_hash(&list, &hash, NULL), MT_OK);
    CHECK_EQ(hash, PINNED_HASH);
    free_mesh(&m);
    /* Counts past mesh_t's int32 fields have no content hash. */
    mt_face_list big = {UINT32_MAX / 3 + 1, 0, 0, NULL, NULL, NULL};
    mt_diag diag;
    CHECK_EQ(mt_face_list_content_hash(&big, &hash, &diag), MT_ERR_TOO_LARGE);
    CHECK(strstr(diag.message, "does not fit mesh_t") != NULL);
    CHECK_EQ(mt_face_list_content_hash(NULL, &hash, &diag), MT_ERR_INVALID_ARG);
}

static const mt_test_case cases[] = {
    {"encode_ranges_match_lcm", encode_ranges_match_lcm},
    {"content_hash_is_xxh3_of_the_encoding", content_hash_is_xxh3_of_the_encoding},
    {"decoder_takes_pieces_in_any_order", decoder_takes_pieces_in_any_order},
    {"decoder_refuses_counts_that_do_not_fit", decoder_refuses_counts_that_do_not_fit},
    {"face_list_hash_is_the_content_hash", face_list_hash_is_the_content_hash},
};
const mt_test_table mt_tests_mesh_content = {cases, sizeof cases / sizeof cases[0]};
