/* The content hash of a submitted mesh (see meshtopo/content_hash.h). FNV-1a
 * is written out here: it is four lines, and the protocol fixes it exactly,
 * so no library's variant or seed may change it. */
#include "meshtopo/content_hash.h"

uint64_t mt_msgs_fnv1a(uint64_t hash, const void *bytes, size_t n)
{
    const unsigned char *p = bytes;
    for (size_t i = 0; i < n; i++) {
        hash ^= p[i];
        hash *= 0x100000001b3ull;
    }
    return hash;
}

uint64_t mt_msgs_mesh_content_hash(const meshtopo_mesh_t *msg, const void *encoded,
                                   size_t encoded_size)
{
    /* num_verts, num_position_values, positions, num_faces, counts,
     * num_indices, indices: the last fields of the encoding. */
    const uint64_t tail = 4 + 4 + 8 * (uint64_t)(uint32_t)msg->num_position_values + 4 +
                          4 * (uint64_t)(uint32_t)msg->num_faces + 4 +
                          4 * (uint64_t)(uint32_t)msg->num_indices;
    if (tail > encoded_size) return 0;
    const unsigned char *p = encoded;
    return mt_msgs_fnv1a(MT_MSGS_FNV1A_BASIS, p + (encoded_size - (size_t)tail), (size_t)tail);
}
