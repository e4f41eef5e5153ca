/* Deterministic shuffling of a face list (face_list.h): vertex ids and face
 * order are permuted by Fisher-Yates driven by splitmix64 seeded with the
 * caller's seed, so the same seed always gives the same list. Face i of the
 * result is some input face with its ids renamed, starting at the same corner.
 * Linear time, a fixed number of allocations; on failure the list is unchanged. */
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_internal.h"
#include "meshtopo/face_list.h"

static uint64_t splitmix64_next(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Uniform in [0, bound), bound >= 1: draws above the last whole multiple of
 * bound are rejected so that no value is favoured. */
static uint32_t random_below(uint64_t *state, uint32_t bound)
{
    const uint64_t limit = UINT64_MAX - UINT64_MAX % bound;
    uint64_t r;
    do r = splitmix64_next(state);
    while (r >= limit);
    return (uint32_t)(r % bound);
}

/* Fills perm with a uniformly random permutation of 0 .. n-1. */
static void permutation_fill(uint32_t *perm, uint32_t n, uint64_t *state)
{
    for (uint32_t i = 0; i < n; i++) perm[i] = i;
    for (uint32_t i = n; i > 1; i--) {
        uint32_t j = random_below(state, i);
        uint32_t t = perm[i - 1];
        perm[i - 1] = perm[j];
        perm[j] = t;
    }
}

mt_status mt_face_list_permute(mt_face_list *list, uint64_t seed, mt_diag *diag)
{
    mt_status status = mt_face_list_check(list, diag);
    if (status != MT_OK) return status;
    const uint32_t nv = list->num_verts, nf = list->num_faces;
    const bool has_positions = list->positions != NULL;
    /* new_id[v]: new id of vertex v; order[i]: input face placed at i;
     * start[f]: first index of input face f; the rest are the new arrays. */
    size_t id_bytes, order_bytes, start_bytes, size_bytes, index_bytes, pos_bytes = 0;
    if (list->num_indices > SIZE_MAX / sizeof(uint32_t) ||
        !mt__mul_size((size_t)nv, sizeof(uint32_t), &id_bytes) ||
        !mt__mul_size((size_t)nf, sizeof(uint32_t), &order_bytes) ||
        !mt__mul_size((size_t)nf, sizeof(uint64_t), &start_bytes) ||
        !mt__mul_size((size_t)nf, sizeof(uint32_t), &size_bytes) ||
        !mt__mul_size((size_t)list->num_indices, sizeof(uint32_t), &index_bytes) ||
        (has_positions && !mt__mul_size((size_t)nv, 3 * sizeof(double), &pos_bytes)))
        return mt__fail(diag, MT_ERR_TOO_LARGE, MT_NONE,
                        "permute: %u vertices, %u faces and %llu indices do not fit in memory", nv,
                        nf, (unsigned long long)list->num_indices);
    uint32_t *new_id = malloc(id_bytes ? id_bytes : 1);
    uint32_t *order = malloc(order_bytes ? order_bytes : 1);
    uint64_t *start = malloc(start_bytes ? start_bytes : 1);
    uint32_t *sizes = malloc(size_bytes ? size_bytes : 1);
    uint32_t *indices = malloc(index_bytes ? index_bytes : 1);
    double *positions = has_positions ? malloc(pos_bytes ? pos_bytes : 1) : NULL;
    if (!new_id || !order || !start || !sizes || !indices || (has_positions && !positions)) {
        free(new_id);
        free(order);
        free(start);
        free(sizes);
        free(indices);
        free(positions);
        return mt__fail(diag, MT_ERR_NOMEM, MT_NONE,
                        "permute: cannot allocate scratch for %u vertices, %u faces and %llu "
                        "indices",
                        nv, nf, (unsigned long long)list->num_indices);
    }

    uint64_t state = seed;
    permutation_fill(new_id, nv, &state);
    permutation_fill(order, nf, &state);

    uint64_t offset = 0;
    for (uint32_t f = 0; f < nf; f++) {
        start[f] = offset;
        offset += list->face_sizes[f];
    }
    uint64_t out = 0;
    for (uint32_t i = 0; i < nf; i++) {
        uint32_t f = order[i];
        sizes[i] = list->face_sizes[f];
        for (uint32_t k = 0; k < sizes[i]; k++) {
            uint32_t v = list->face_indices[start[f] + k];
            indices[out++] = v < nv ? new_id[v] : v; /* out-of-range ids stay as they are */
        }
    }
    if (has_positions) {
        for (uint32_t v = 0; v < nv; v++)
            memcpy(positions + 3 * (size_t)new_id[v], list->positions + 3 * (size_t)v,
                   3 * sizeof(double));
        memcpy(list->positions, positions, pos_bytes);
    }
    if (size_bytes > 0) memcpy(list->face_sizes, sizes, size_bytes);
    if (index_bytes > 0) memcpy(list->face_indices, indices, index_bytes);

    free(new_id);
    free(order);
    free(start);
    free(sizes);
    free(indices);
    free(positions);
    return MT_OK;
}
