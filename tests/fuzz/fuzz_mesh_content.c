/* libFuzzer target for the in-place content decoder (meshtopo/
 * mesh_content.h), against LCM's own decoder: arbitrary bytes, given to the
 * decoder in pieces of fuzzer-chosen sizes and order (as meshtopod gives it
 * chunks), are accepted exactly when mt_msgs_decode accepts them behind a
 * mesh_t header, with the same counts and array values, and hash to the
 * content hash of the bytes; the range encoder gives the bytes back. Never a
 * crash or a read out of bounds. Any disagreement calls abort().
 *
 * Input layout: byte 0 is the piece size (1..256), byte 1 seeds the order of
 * the pieces; the rest is the content. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/content_hash.h"
#include "meshtopo/mesh_content.h"
#include "meshtopo/msgs.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void require(int ok, const char *what, int line)
{
    if (ok) return;
    fprintf(stderr, "fuzz_mesh_content.c:%d: invariant violated: %s\n", line, what);
    abort();
}

#define REQUIRE(cond) require((cond), #cond, __LINE__)

/* LCM's decoding of header + content as a mesh_t (0 on success). */
static int lcm_decode(const uint8_t *content, size_t total, meshtopo_mesh_t *out)
{
    meshtopo_mesh_t empty;
    memset(&empty, 0, sizeof empty);
    empty.reply_channel = "R";
    empty.mesh_id = "m";
    empty.source = "s";
    int size = meshtopo_mesh_t_encoded_size(&empty);
    size_t header = (size_t)size - 16; /* without the four zero counts */
    uint8_t *whole = malloc(header + (total > 16 ? total : 16));
    REQUIRE(whole != NULL);
    REQUIRE(meshtopo_mesh_t_encode(whole, 0, size, &empty) == size);
    if (total) memcpy(whole + header, content, total);
    int result = mt_msgs_decode(&mt_msgs_type_mesh, whole, header + total, out, NULL, 0);
    free(whole);
    return result;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 2) return 0;
    const size_t piece = (size_t)data[0] + 1;
    uint32_t order_state = (uint32_t)data[1] * 2654435761u + 1;
    const uint8_t *content = data + 2;
    const size_t total = size - 2;

    uint8_t *buffer = malloc(total + 1);
    uint8_t *have = calloc(total + 1, 1);
    REQUIRE(buffer && have);
    mt_msgs_content_decoder *decoder = mt_msgs_content_decoder_new(buffer, total);
    REQUIRE(decoder != NULL);
    /* Pieces in a shuffled order; copies never go below the bytes given. */
    const size_t pieces = (total + piece - 1) / piece;
    size_t *order = malloc(sizeof(size_t) * (pieces + 1));
    REQUIRE(order != NULL);
    for (size_t i = 0; i < pieces; i++) order[i] = i;
    for (size_t i = pieces; i > 1; i--) {
        order_state = order_state * 1103515245u + 12345u;
        size_t j = (order_state >> 8) % i;
        size_t t = order[i - 1];
        order[i - 1] = order[j];
        order[j] = t;
    }
    size_t ready = 0;
    for (size_t k = 0; k < pieces; k++) {
        size_t lo = order[k] * piece, hi = lo + piece < total ? lo + piece : total;
        for (size_t b = lo; b < hi; b++) {
            if (b >= ready) buffer[b] = content[b];
            have[b] = 1;
        }
        while (ready < total && have[ready]) ready++;
        mt_msgs_content_decoder_advance(decoder, ready);
    }
    meshtopo_mesh_t ours;
    memset(&ours, 0, sizeof ours);
    uint64_t hash = 0;
    char error[200];
    int result = mt_msgs_content_decoder_finish(decoder, &ours, &hash, error, sizeof error);
    REQUIRE(hash == mt_msgs_content_hash_bytes(content, total));

    meshtopo_mesh_t lcm;
    int lcm_result = lcm_decode(content, total, &lcm);
    REQUIRE((result == 0) == (lcm_result == 0));
    if (result != 0) REQUIRE(error[0] != '\0' && memchr(error, '\0', sizeof error) != NULL);
    if (result == 0) {
        REQUIRE(ours.num_verts == lcm.num_verts);
        REQUIRE(ours.num_position_values == lcm.num_position_values);
        REQUIRE(ours.num_faces == lcm.num_faces);
        REQUIRE(ours.num_indices == lcm.num_indices);
        REQUIRE(ours.num_position_values == 0 ||
                memcmp(ours.positions, lcm.positions,
                       sizeof(double) * (size_t)ours.num_position_values) == 0);
        REQUIRE(ours.num_faces == 0 || memcmp(ours.face_vertex_counts, lcm.face_vertex_counts,
                                              sizeof(int32_t) * (size_t)ours.num_faces) == 0);
        REQUIRE(ours.num_indices == 0 || memcmp(ours.face_vertex_indices, lcm.face_vertex_indices,
                                                sizeof(int32_t) * (size_t)ours.num_indices) == 0);
        REQUIRE(mt_msgs_mesh_content_size(&ours) == total);
        /* The range encoder gives the received bytes back. */
        uint8_t *again = malloc(total + 1);
        REQUIRE(again != NULL);
        mt_msgs_mesh_content_encode(&ours, 0, total, again);
        REQUIRE(memcmp(again, content, total) == 0);
        free(again);
        meshtopo_mesh_t_decode_cleanup(&lcm);
    }
    mt_msgs_content_decoder_free(decoder);
    free(order);
    free(have);
    free(buffer);
    return 0;
}
