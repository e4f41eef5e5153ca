/* The hash that identifies a large answer sent in reply_part_t pieces
 * (msgs/reply_part_t.lcm): 64-bit FNV-1a taken over 8-byte big-endian words
 * instead of bytes (eight times fewer multiplications, so the daemon can hash
 * a cached answer of megabytes on every pull). The daemon hashes what it
 * sends, the receiver what it reassembled; both call this. */
#ifndef MESHTOPO_ANSWER_HASH_H
#define MESHTOPO_ANSWER_HASH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The answer hash of n bytes: h = 0xcbf29ce484222325; for every group of 8
 * bytes read big-endian (the last group padded with zero bytes),
 * h = (h XOR word) * 0x100000001b3. */
uint64_t mt_msgs_answer_hash(const void *bytes, size_t n);

#ifdef __cplusplus
}
#endif

#endif
