/* mt_msgs_answer_hash: 64-bit FNV-1a over 8-byte big-endian words, the hash
 * of msgs/reply_part_t.lcm that ties the parts of one large answer together
 * and checks the reassembled bytes. */
#include "meshtopo/answer_hash.h"

#define FNV_BASIS 0xcbf29ce484222325ull
#define FNV_PRIME 0x100000001b3ull

uint64_t mt_msgs_answer_hash(const void *bytes, size_t n)
{
    const unsigned char *p = bytes;
    uint64_t h = FNV_BASIS;
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        uint64_t word = 0;
        for (int k = 0; k < 8; k++) word = word << 8 | p[i + k];
        h = (h ^ word) * FNV_PRIME;
    }
    if (i < n) {
        uint64_t word = 0;
        for (int k = 0; k < 8; k++) word = word << 8 | (i + (size_t)k < n ? p[i + k] : 0u);
        h = (h ^ word) * FNV_PRIME;
    }
    return h;
}
