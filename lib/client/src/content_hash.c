/* The content hash of a submitted mesh (msgs/mesh_t.lcm): 64-bit FNV-1a over
 * the bytes LCM encodes for mesh_t's content fields, num_verts to
 * face_vertex_indices (big-endian, doubles as their IEEE-754 bits). The client
 * hashes the tail of the encoded message it sends; mt_client_content_hash
 * gives the same value straight from a face list, without encoding it. */
#include <limits.h>
#include <string.h>

#include "client_internal.h"
#include "meshtopo/content_hash.h"

/* Continues the hash over value as LCM encodes it: `bytes` bytes, big-endian. */
static uint64_t hash_big_endian(uint64_t hash, uint64_t value, int bytes)
{
    uint8_t encoded[8];
    for (int k = 0; k < bytes; k++) encoded[k] = (uint8_t)(value >> (8 * (bytes - 1 - k)));
    return mt_msgs_fnv1a(hash, encoded, (size_t)bytes);
}

/* Bytes of mesh_t's content fields (num_verts .. face_vertex_indices) once
 * encoded; 0 when a count does not fit its int32 field or the whole mesh_t
 * would not fit the int sizes of LCM's encoders (chunked submissions carry
 * more than one LCM message could). */
uint64_t mt__content_size(const mt_face_list *list)
{
    if (list->num_verts > INT32_MAX / 3 || list->num_faces > INT32_MAX ||
        list->num_indices > INT32_MAX)
        return 0;
    uint64_t npos = list->positions ? 3ull * list->num_verts : 0;
    uint64_t size = 8 + 8 * npos + 4 + 4ull * list->num_faces + 4 + 4 * list->num_indices;
    return size > (uint64_t)INT32_MAX - 65536 ? 0 : size;
}

mt_status mt_client_content_hash(const mt_face_list *list, uint64_t *out_hash, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!list || !out_hash)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG,
                               "mt_client_content_hash: list or out_hash is NULL");
    mt_status st = mt_face_list_check(list, diag);
    if (st != MT_OK) return st;
    if (mt__content_size(list) == 0)
        return mt__client_fail(diag, MT_ERR_TOO_LARGE, "face list does not fit mesh_t");
    /* The fields as LCM encodes them: big-endian, doubles as their bits. */
    uint64_t h = MT_MSGS_FNV1A_BASIS;
    uint32_t npos = list->positions ? 3 * list->num_verts : 0;
    h = hash_big_endian(h, list->num_verts, 4);
    h = hash_big_endian(h, npos, 4);
    for (uint32_t i = 0; i < npos; i++) {
        uint64_t bits;
        memcpy(&bits, &list->positions[i], sizeof bits);
        h = hash_big_endian(h, bits, 8);
    }
    h = hash_big_endian(h, list->num_faces, 4);
    for (uint32_t i = 0; i < list->num_faces; i++) h = hash_big_endian(h, list->face_sizes[i], 4);
    h = hash_big_endian(h, (uint32_t)list->num_indices, 4);
    for (uint64_t i = 0; i < list->num_indices; i++)
        h = hash_big_endian(h, list->face_indices[i], 4);
    *out_hash = h;
    return MT_OK;
}
