/* Translation between map ids and (block, local) ids, each O(1): a block
 * vertex or face to its map id through the block's arrays, a map face to
 * its block through face_block / face_local, a map vertex to one of its
 * origins (the head of its origin ring). */
#include <string.h>

#include "map/map_internal.h"

static const mt__map_block *block_of(const mt_map *map, mt_map_key key)
{
    if (!map) return NULL;
    const uint32_t slot = mt__map_find_block(map, key);
    return slot == MT_NONE ? NULL : map->blocks[slot];
}

mt_status mt_map_block_vert(const mt_map *map, mt_map_key key, uint32_t local, uint32_t *out_vert)
{
    if (!map || !out_vert) return MT_ERR_INVALID_ARG;
    const mt__map_block *b = block_of(map, key);
    if (!b) return MT_ERR_NOT_FOUND;
    if (local >= b->num_verts) return MT_ERR_OUT_OF_RANGE;
    *out_vert = b->vert_map[local];
    return MT_OK;
}

mt_status mt_map_block_face(const mt_map *map, mt_map_key key, uint32_t local, uint32_t *out_face)
{
    if (!map || !out_face) return MT_ERR_INVALID_ARG;
    const mt__map_block *b = block_of(map, key);
    if (!b) return MT_ERR_NOT_FOUND;
    if (local >= b->num_faces) return MT_ERR_OUT_OF_RANGE;
    *out_face = b->face_ids[local];
    return MT_OK;
}

mt_status mt_map_face_origin(const mt_map *map, uint32_t face, mt_map_key *out_key,
                             uint32_t *out_local)
{
    if (!map) return MT_ERR_INVALID_ARG;
    if (face >= map->face_end) return MT_ERR_OUT_OF_RANGE;
    if (map->face_block[face] == MT_NONE) return MT_ERR_NOT_FOUND;
    if (out_key) *out_key = map->blocks[map->face_block[face]]->key;
    if (out_local) *out_local = map->face_local[face] & MT__MAP_LOCAL_MASK;
    return MT_OK;
}

mt_status mt_map_vert_origin(const mt_map *map, uint32_t vert, mt_map_key *out_key,
                             uint32_t *out_local)
{
    if (!map) return MT_ERR_INVALID_ARG;
    if (vert >= map->vert_end) return MT_ERR_OUT_OF_RANGE;
    if (!(map->vert_flags[vert] & MT__V_ALIVE)) return MT_ERR_NOT_FOUND;
    const uint64_t o = map->vert_origin[vert];
    if (out_key) *out_key = map->blocks[o >> 32]->key;
    if (out_local) *out_local = (uint32_t)o;
    return MT_OK;
}

const double *mt_map_vert_position(const mt_map *map, uint32_t vert)
{
    if (!map || vert >= map->vert_end || !(map->vert_flags[vert] & MT__V_ALIVE)) return NULL;
    return &map->pos[3 * (size_t)vert];
}

mt_status mt_map_face_verts(const mt_map *map, uint32_t face, uint32_t *out_verts, size_t capacity,
                            size_t *out_count)
{
    mt_status s = mt_map_face_origin(map, face, NULL, NULL);
    if (s != MT_OK) return s;
    const mt__map_block *b = map->blocks[map->face_block[face]];
    const uint32_t local = map->face_local[face] & MT__MAP_LOCAL_MASK;
    const uint32_t c0 = mt__blk_begin(b, local), n = mt__blk_size(b, local);
    if (out_count) *out_count = n;
    if (!out_verts && capacity == 0) return MT_OK;
    if (!out_verts || capacity < n) return MT_ERR_BUFFER_TOO_SMALL;
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t c = b->corners[c0 + i];
        out_verts[i] = c >= MT__MAP_OOR ? MT_NONE : c;
    }
    return MT_OK;
}
