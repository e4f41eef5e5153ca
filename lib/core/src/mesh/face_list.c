/* Face lists: allocation, release and the size check every consumer runs
 * before trusting the counts. */
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_internal.h"
#include "meshtopo/face_list.h"

mt_status mt_face_list_alloc(mt_face_list *out, uint32_t num_verts, uint32_t num_faces,
                             uint64_t num_indices, mt_diag *diag)
{
    if (!out) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "face list: NULL output");
    memset(out, 0, sizeof *out);
    size_t pos_bytes, size_bytes, index_bytes;
    if (num_indices > SIZE_MAX / sizeof(uint32_t) ||
        !mt__mul_size((size_t)num_verts, 3 * sizeof(double), &pos_bytes) ||
        !mt__mul_size((size_t)num_faces, sizeof(uint32_t), &size_bytes) ||
        !mt__mul_size((size_t)num_indices, sizeof(uint32_t), &index_bytes))
        return mt__fail(diag, MT_ERR_TOO_LARGE, MT_NONE,
                        "face list: %u vertices, %u faces, %llu indices do not fit in memory",
                        num_verts, num_faces, (unsigned long long)num_indices);
    double *positions = calloc(pos_bytes ? pos_bytes : 1, 1);
    uint32_t *sizes = calloc(size_bytes ? size_bytes : 1, 1);
    uint32_t *indices = calloc(index_bytes ? index_bytes : 1, 1);
    if (!positions || !sizes || !indices) {
        free(positions);
        free(sizes);
        free(indices);
        return mt__fail(diag, MT_ERR_NOMEM, MT_NONE,
                        "face list: cannot allocate %zu bytes for %u vertices, %u faces",
                        pos_bytes + size_bytes + index_bytes, num_verts, num_faces);
    }
    out->num_verts = num_verts;
    out->num_faces = num_faces;
    out->num_indices = num_indices;
    out->positions = positions;
    out->face_sizes = sizes;
    out->face_indices = indices;
    return MT_OK;
}

void mt_face_list_free(mt_face_list *list)
{
    if (!list) return;
    free(list->positions);
    free(list->face_sizes);
    free(list->face_indices);
    memset(list, 0, sizeof *list);
}

mt_status mt_face_list_check(const mt_face_list *list, mt_diag *diag)
{
    if (!list) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "face list is NULL");
    if (list->num_faces > 0 && !list->face_sizes)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "face list: %u faces but face_sizes is NULL", list->num_faces);
    if (list->num_indices > 0 && !list->face_indices)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "face list: %llu indices but face_indices is NULL",
                        (unsigned long long)list->num_indices);
    uint64_t sum = 0;
    for (uint32_t f = 0; f < list->num_faces; f++) {
        sum += list->face_sizes[f]; /* at most 2^32 * 2^32: cannot wrap a uint64 */
        if (sum > list->num_indices)
            return mt__fail(diag, MT_ERR_INVALID_ARG, f,
                            "face list: face %u (size %u) runs past the %llu indices given", f,
                            list->face_sizes[f], (unsigned long long)list->num_indices);
    }
    if (sum != list->num_indices)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "face list: face sizes add up to %llu but %llu indices are given",
                        (unsigned long long)sum, (unsigned long long)list->num_indices);
    return MT_OK;
}
