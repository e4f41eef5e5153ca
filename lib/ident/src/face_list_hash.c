/* The content hash of a face list (see meshtopo/mesh_ident.h): the bytes
 * LCM would encode for mesh_t's content fields, made a block at a time from
 * the host-order arrays (never the whole encoding at once) and fed to
 * XXH3-64. */
#define _DEFAULT_SOURCE         /* endian.h's htobe32 and htobe64 under -std=c11 */
#define XXH_STATIC_LINKING_ONLY /* XXH3_state_t on the stack */
#include <endian.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <xxhash.h>

#include "meshtopo/mesh_ident.h"

/* Bytes encoded and hashed at a time. */
#define BLOCK_BYTES 32768

struct mt_content_hasher {
    XXH3_state_t *state; /* XXH3_createState's: aligned as XXH3 wants */
    uint64_t block[BLOCK_BYTES / 8];
};

static void add_count(XXH3_state_t *state, uint32_t count)
{
    uint32_t be = htobe32(count);
    XXH3_64bits_update(state, &be, 4);
}

static void add_int32s(XXH3_state_t *state, uint64_t *block, const uint32_t *values, size_t n)
{
    uint32_t *out = (uint32_t *)(void *)block;
    while (n > 0) {
        size_t k = n < BLOCK_BYTES / 4 ? n : BLOCK_BYTES / 4;
        for (size_t i = 0; i < k; i++) out[i] = htobe32(values[i]);
        XXH3_64bits_update(state, out, 4 * k);
        values += k;
        n -= k;
    }
}

static void add_doubles(XXH3_state_t *state, uint64_t *block, const double *values, size_t n)
{
    while (n > 0) {
        size_t k = n < BLOCK_BYTES / 8 ? n : BLOCK_BYTES / 8;
        memcpy(block, values, 8 * k);
        for (size_t i = 0; i < k; i++) block[i] = htobe64(block[i]);
        XXH3_64bits_update(state, block, 8 * k);
        values += k;
        n -= k;
    }
}

uint64_t mt_content_hash_bytes(const void *bytes, size_t n)
{
    return XXH3_64bits(bytes, n);
}

mt_status mt_face_list_content_hash(const mt_face_list *faces, uint64_t *out_hash, mt_diag *diag)
{
    if (!faces || !out_hash)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG,
                           "mt_face_list_content_hash: faces or out_hash is NULL");
    if (faces->num_verts > INT32_MAX / 3 || faces->num_faces > INT32_MAX ||
        faces->num_indices > INT32_MAX)
        return mt_diag_set(diag, MT_ERR_TOO_LARGE,
                           "a face list of %u vertices, %u faces and %llu indices does not "
                           "fit mesh_t: its content hash is not defined",
                           faces->num_verts, faces->num_faces,
                           (unsigned long long)faces->num_indices);
    uint64_t block[BLOCK_BYTES / 8];
    XXH3_state_t state;
    XXH3_INITSTATE(&state);
    XXH3_64bits_reset(&state);
    const uint32_t npos = faces->positions ? 3 * faces->num_verts : 0;
    add_count(&state, faces->num_verts);
    add_count(&state, npos);
    add_doubles(&state, block, faces->positions, npos);
    add_count(&state, faces->num_faces);
    add_int32s(&state, block, faces->face_sizes, faces->num_faces);
    add_count(&state, (uint32_t)faces->num_indices);
    add_int32s(&state, block, faces->face_indices, (size_t)faces->num_indices);
    *out_hash = XXH3_64bits_digest(&state);
    mt_diag_clear(diag);
    return MT_OK;
}

mt_content_hasher *mt_content_hasher_new(void)
{
    mt_content_hasher *h = malloc(sizeof *h);
    if (!h) return NULL;
    h->state = XXH3_createState();
    if (!h->state || XXH3_64bits_reset(h->state) != XXH_OK) {
        mt_content_hasher_free(h);
        return NULL;
    }
    return h;
}

void mt_content_hasher_count(mt_content_hasher *h, uint32_t count)
{
    add_count(h->state, count);
}

void mt_content_hasher_int32s(mt_content_hasher *h, const uint32_t *values, size_t n)
{
    add_int32s(h->state, h->block, values, n);
}

void mt_content_hasher_doubles(mt_content_hasher *h, const double *values, size_t n)
{
    add_doubles(h->state, h->block, values, n);
}

uint64_t mt_content_hasher_digest(const mt_content_hasher *h)
{
    return XXH3_64bits_digest(h->state);
}

void mt_content_hasher_free(mt_content_hasher *h)
{
    if (!h) return;
    XXH3_freeState(h->state);
    free(h);
}
