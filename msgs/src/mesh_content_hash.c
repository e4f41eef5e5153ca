/* The content hash of a submitted mesh (see meshtopo/content_hash.h). XXH3
 * runs at memory speed, so hashing a 100 MB mesh costs a few milliseconds on
 * each side of a submission. */
#define XXH_STATIC_LINKING_ONLY /* XXH3_state_t on the stack */
#include "meshtopo/content_hash.h"

#include <xxhash.h>

#include "meshtopo/mesh_content.h"
#include "meshtopo/mesh_ident.h"

/* Bytes encoded and hashed at a time by mt_msgs_mesh_content_hash_of. */
#define HASH_BLOCK_BYTES 32768

uint64_t mt_msgs_content_hash_bytes(const void *bytes, size_t n)
{
    return mt_content_hash_bytes(bytes, n);
}

uint64_t mt_msgs_mesh_content_hash(const meshtopo_mesh_t *msg, const void *encoded,
                                   size_t encoded_size)
{
    /* num_verts .. face_vertex_indices: the last fields of the encoding. */
    const uint64_t tail = mt_msgs_mesh_content_size(msg);
    if (tail > encoded_size) return 0;
    const unsigned char *p = encoded;
    return mt_msgs_content_hash_bytes(p + (encoded_size - (size_t)tail), (size_t)tail);
}

uint64_t mt_msgs_mesh_content_hash_of(const meshtopo_mesh_t *msg)
{
    uint8_t block[HASH_BLOCK_BYTES];
    XXH3_state_t state;
    XXH3_INITSTATE(&state);
    XXH3_64bits_reset(&state);
    const uint64_t total = mt_msgs_mesh_content_size(msg);
    for (uint64_t at = 0; at < total; at += HASH_BLOCK_BYTES) {
        size_t n = total - at < HASH_BLOCK_BYTES ? (size_t)(total - at) : HASH_BLOCK_BYTES;
        mt_msgs_mesh_content_encode(msg, at, n, block);
        XXH3_64bits_update(&state, block, n);
    }
    return XXH3_64bits_digest(&state);
}
