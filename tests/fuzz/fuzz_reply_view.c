/* libFuzzer target for the client's reading of a reply (meshtopo/
 * client_reply.h): arbitrary bytes decoded as a reply_t; when the client's
 * check accepts its offsets, every item, group and value is read through
 * the accessors, which must stay inside the arrays (AddressSanitizer), give
 * each group inside its item and account for every value exactly once. A
 * refused reply must say why. Any disagreement calls abort(). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/client_reply.h"
#include "meshtopo/msgs.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void require(int ok, const char *what, int line)
{
    if (ok) return;
    fprintf(stderr, "fuzz_reply_view.c:%d: invariant violated: %s\n", line, what);
    abort();
}

#define REQUIRE(cond) require((cond), #cond, __LINE__)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* The fingerprint first, so the fuzzer reaches the fields. */
    uint8_t *buf = malloc(size + 8);
    REQUIRE(buf != NULL);
    uint64_t fingerprint = (uint64_t)mt_msgs_type_reply.fingerprint();
    for (int i = 0; i < 8; i++) buf[i] = (uint8_t)(fingerprint >> (56 - 8 * i));
    if (size) memcpy(buf + 8, data, size);
    meshtopo_reply_t reply;
    if (mt_msgs_decode(&mt_msgs_type_reply, buf, size + 8, &reply, NULL, 0) != 0) {
        free(buf);
        return 0;
    }
    mt_diag diag;
    if (mt_client_reply_check(&reply, &diag) != MT_OK) {
        REQUIRE(diag.status == MT_ERR_CORRUPT && diag.message[0] != '\0');
    } else {
        size_t groups = 0, values = 0, values2 = 0;
        int64_t sum = 0;
        for (size_t i = 0; i < mt_client_reply_num_items(&reply); i++) {
            mt_client_item item = mt_client_reply_item(&reply, i);
            REQUIRE(item.first_group == groups);
            for (size_t k = 0; k < item.num_groups; k++) {
                mt_client_group g = mt_client_item_group(&reply, &item, k);
                for (size_t v = 0; v < g.num_values; v++) sum += g.values[v];
                for (size_t v = 0; v < g.num_values2; v++) sum -= g.values2[v];
                values += g.num_values;
                values2 += g.num_values2;
            }
            groups += item.num_groups;
            double real = mt_client_reply_real(&reply, i);
            (void)real;
        }
        REQUIRE(groups == (size_t)reply.num_groups);
        REQUIRE(values == (size_t)reply.num_values);
        REQUIRE(values2 == (size_t)reply.num_values2);
        (void)sum;
    }
    meshtopo_reply_t_decode_cleanup(&reply);
    free(buf);
    return 0;
}
