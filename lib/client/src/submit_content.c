/* A submission's content (msgs/mesh_t.lcm): its encoded size, mesh_t's fields
 * over a face list's arrays, and its content hash: XXH3-64 over the
 * bytes LCM encodes for mesh_t's content fields, num_verts to
 * face_vertex_indices. mt_client_content_hash gives it straight from a face
 * list, encoding a block at a time instead of the whole mesh. */
#include <limits.h>
#include <string.h>

#include "client_internal.h"
#include "meshtopo/content_hash.h"

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

void mt__mesh_content_of(const mt_face_list *list, meshtopo_mesh_t *m)
{
    m->num_verts = (int32_t)list->num_verts;
    m->num_position_values = list->positions ? (int32_t)(3 * list->num_verts) : 0;
    m->positions = list->positions;
    m->num_faces = (int32_t)list->num_faces;
    /* uint32_t and int32_t may alias; the encoding is the same bits. */
    m->face_vertex_counts = (int32_t *)list->face_sizes;
    m->num_indices = (int32_t)list->num_indices;
    m->face_vertex_indices = (int32_t *)list->face_indices;
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
    meshtopo_mesh_t m;
    memset(&m, 0, sizeof m);
    mt__mesh_content_of(list, &m);
    uint64_t h = mt_msgs_mesh_content_hash_of(&m);
    *out_hash = h;
    return MT_OK;
}
