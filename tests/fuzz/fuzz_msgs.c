/* libFuzzer target for the safe decoder of meshtopo's LCM messages
 * (mt_msgs_decode): arbitrary bytes decoded as each type either give an
 * error with a message and a zeroed struct, or a message that encodes back to
 * exactly the same bytes and whose fingerprint names its type; never a crash,
 * a leak or a read out of bounds. Any disagreement calls abort().
 *
 * Input layout: byte 0 picks the mode. With byte 0 < number of types, the
 * rest is decoded as that type after its fingerprint (so the fuzzer reaches
 * the fields without guessing 8 bytes); otherwise the rest is decoded, as it
 * is, as every type. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/msgs.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void require(int ok, const char *what, int line)
{
    if (ok) return;
    fprintf(stderr, "fuzz_msgs.c:%d: invariant violated: %s\n", line, what);
    abort();
}

#define REQUIRE(cond) require((cond), #cond, __LINE__)

/* Room for any meshtopo_*_t struct, aligned for any member. */
typedef union any_msg {
    meshtopo_mesh_t mesh;
    meshtopo_ack_t ack;
    meshtopo_topology_t topology;
    meshtopo_query_t query;
    meshtopo_reply_t reply;
    meshtopo_status_t status;
    meshtopo_status_code_t status_code;
    uint8_t bytes[1024];
} any_msg;

static void decode_as(const mt_msgs_type *type, const uint8_t *buf, size_t size)
{
    any_msg msg;
    char error[MT_MSGS_ERROR_SIZE];
    REQUIRE(type->struct_size <= sizeof msg.bytes);
    memset(&msg, 0x5a, sizeof msg);
    int status = mt_msgs_decode(type, buf, size, &msg, error, sizeof error);
    REQUIRE(status == 0 || status == -1);
    REQUIRE((mt_msgs_check(type, buf, size, NULL, 0) == 0) == (status == 0));
    if (status != 0) {
        REQUIRE(error[0] != '\0' && memchr(error, '\0', sizeof error) != NULL);
        for (size_t i = 0; i < type->struct_size; i++) REQUIRE(msg.bytes[i] == 0);
        return;
    }
    REQUIRE(mt_msgs_type_of(buf, size) == type);
    int encoded_size = type->encoded_size(&msg);
    REQUIRE(encoded_size >= 0 && (size_t)encoded_size == size);
    uint8_t *again = malloc(size);
    REQUIRE(again != NULL);
    REQUIRE(type->encode(again, 0, (int)size, &msg) == (int)size);
    REQUIRE(memcmp(again, buf, size) == 0);
    free(again);
    type->decode_cleanup(&msg);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0) return 0;
    size_t mode = data[0];
    const uint8_t *rest = data + 1;
    size_t rest_size = size - 1;
    if (mode < mt_msgs_num_types) {
        const mt_msgs_type *type = mt_msgs_types[mode];
        uint8_t *buf = malloc(rest_size + 8);
        REQUIRE(buf != NULL);
        uint64_t fingerprint = (uint64_t)type->fingerprint();
        for (int i = 0; i < 8; i++) buf[i] = (uint8_t)(fingerprint >> (56 - 8 * i));
        if (rest_size) memcpy(buf + 8, rest, rest_size);
        decode_as(type, buf, rest_size + 8);
        free(buf);
    } else {
        for (size_t t = 0; t < mt_msgs_num_types; t++) decode_as(mt_msgs_types[t], rest, rest_size);
    }
    return 0;
}
