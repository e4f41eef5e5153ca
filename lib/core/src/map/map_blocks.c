/* Blocks of the map: one allocation per block holding its arrays (block
 * vertex -> map vertex, the origin ring, corners as map vertex ids, the
 * corner links of the vertices' face lists, its map face ids), and the
 * table that finds a block's slot by its key. */
#include <string.h>

#include "map/map_internal.h"

/* Rounds n up to a multiple of 8. */
static size_t align8(size_t n)
{
    return (n + 7) & ~(size_t)7;
}

mt__map_block *mt__block_alloc(uint32_t num_verts, uint32_t num_faces, uint32_t num_indices,
                               bool all_triangles)
{
    /* The limits keep every product far below SIZE_MAX on 64 bits; the
     * checks keep it so on 32. */
    size_t ring, verts, first = 0, corners, faces, total;
    if (!mt__mul_size(num_verts, sizeof(uint64_t), &ring) ||
        !mt__mul_size(num_verts, sizeof(uint32_t), &verts) ||
        (!all_triangles && !mt__mul_size((size_t)num_faces + 1, sizeof(uint32_t), &first)) ||
        !mt__mul_size(num_indices, 2 * sizeof(uint32_t), &corners) ||
        !mt__mul_size(num_faces, sizeof(uint32_t), &faces))
        return NULL;
    total = align8(sizeof(mt__map_block)) + ring + align8(verts) + align8(first) + align8(corners) +
            align8(faces);
    char *mem = mt__malloc(total);
    if (!mem) return NULL;
    mt__map_block *b = (mt__map_block *)mem;
    memset(b, 0, sizeof *b);
    char *at = mem + align8(sizeof *b);
    b->ring_next = (uint64_t *)at;
    at += ring;
    b->vert_map = (uint32_t *)at;
    at += align8(verts);
    if (!all_triangles) {
        b->face_first = (uint32_t *)at;
        at += align8(first);
    }
    b->corners = (uint32_t *)at;
    b->corner_next = b->corners + num_indices;
    at += align8(corners);
    b->face_ids = (uint32_t *)at;
    b->num_verts = num_verts;
    b->num_faces = num_faces;
    b->num_indices = num_indices;
    return b;
}

void mt__block_free(mt__map_block *b)
{
    mt__free(b);
}

size_t mt__block_bytes(const mt__map_block *b)
{
    if (!b) return 0;
    size_t first = b->face_first ? ((size_t)b->num_faces + 1) * 4 : 0;
    return align8(sizeof *b) + (size_t)b->num_verts * 8 + align8((size_t)b->num_verts * 4) +
           align8(first) + align8((size_t)b->num_indices * 8) + align8((size_t)b->num_faces * 4);
}

uint32_t mt__key_hash(mt_map_key key)
{
    uint64_t x = (uint64_t)(uint32_t)key.x * 0x9e3779b97f4a7c15ull;
    x ^= (uint64_t)(uint32_t)key.y * 0xc2b2ae3d27d4eb4full;
    x ^= (uint64_t)(uint32_t)key.z * 0x165667b19e3779f9ull;
    return (uint32_t)mt__mix64(x);
}

uint32_t mt__block_entry_hash(const void *map, uint32_t slot)
{
    return mt__key_hash(((const mt_map *)map)->blocks[slot]->key);
}

bool mt__block_entry_eq(const void *map, uint32_t slot, const void *key)
{
    const mt_map_key *a = &((const mt_map *)map)->blocks[slot]->key;
    const mt_map_key *b = key;
    return a->x == b->x && a->y == b->y && a->z == b->z;
}

uint32_t mt__map_find_block(const mt_map *map, mt_map_key key)
{
    return mt__table_find(&map->block_table, mt__key_hash(key), mt__block_entry_eq, map, &key);
}
