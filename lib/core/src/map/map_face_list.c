/* The map written out as a plain face list (the welded union of its
 * blocks): live vertices in id order, live faces in id order, out-of-range
 * entries as MT_NONE - r. What a full mt_mesh_build is compared with, and
 * the way to run whole-mesh queries on a map until the map answers them. */
#include <string.h>

#include "map/map_internal.h"

mt_status mt_map_face_list(const mt_map *map, mt_face_list *out, uint32_t *out_vert_ids,
                           size_t vert_ids_capacity, uint32_t *out_face_ids,
                           size_t face_ids_capacity, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!map || !out) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "map face list: NULL");
    memset(out, 0, sizeof *out);
    const uint32_t nv = (uint32_t)map->tally.n[MT__T_VERTS];
    const uint32_t nf = (uint32_t)map->tally.n[MT__T_FACES];
    const uint64_t ni = (uint64_t)map->tally.n[MT__T_HALF_EDGES];
    if ((out_vert_ids && vert_ids_capacity < nv) || (out_face_ids && face_ids_capacity < nf))
        return mt__fail(diag, MT_ERR_BUFFER_TOO_SMALL, MT_NONE,
                        "map face list: id arrays need %u vertex and %u face entries", nv, nf);
    uint32_t *dense = mt__malloc((size_t)(map->vert_end ? map->vert_end : 1) * sizeof(uint32_t));
    if (!dense) return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "map face list: out of memory");
    mt_status s = mt_face_list_alloc(out, nv, nf, ni, diag);
    if (s != MT_OK) {
        mt__free(dense);
        return s;
    }
    uint32_t k = 0;
    for (uint32_t v = 0; v < map->vert_end; v++) {
        if (!(map->vert_flags[v] & MT__V_ALIVE)) continue;
        dense[v] = k;
        memcpy(&out->positions[3 * (size_t)k], &map->pos[3 * (size_t)v], 3 * sizeof(double));
        if (out_vert_ids) out_vert_ids[k] = v;
        k++;
    }
    uint64_t at = 0;
    uint32_t j = 0;
    for (uint32_t f = 0; f < map->face_end; f++) {
        if (map->face_block[f] == MT_NONE) continue;
        const mt__map_block *b = map->blocks[map->face_block[f]];
        const uint32_t local = map->face_local[f] & MT__MAP_LOCAL_MASK;
        const uint32_t c0 = mt__blk_begin(b, local), n = mt__blk_size(b, local);
        out->face_sizes[j] = n;
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t c = b->corners[c0 + i];
            out->face_indices[at++] = c >= MT__MAP_OOR ? c : dense[c];
        }
        if (out_face_ids) out_face_ids[j] = f;
        j++;
    }
    mt__free(dense);
    return MT_OK;
}
