/* The block map's lifetime and entry points (map.h): create and destroy,
 * the checks of put / remove before they are planned (map_plan.c), clear,
 * and the O(1) readers of the counts and histograms kept current. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "map/map_internal.h"

mt_status mt_map_create(const mt_map_options *opts, mt_map **out, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!out) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "map: NULL output");
    *out = NULL;
    const mt_map_weld weld = opts ? opts->weld : MT_MAP_WELD_EXACT;
    if (weld != MT_MAP_WELD_EXACT && weld != MT_MAP_WELD_NONE && weld != MT_MAP_WELD_EPS)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "map: unknown weld mode %d", (int)weld);
    const double eps = weld == MT_MAP_WELD_EPS ? opts->eps : 0;
    if (weld == MT_MAP_WELD_EPS && !(eps > 0 && isfinite(eps)))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "map: MT_MAP_WELD_EPS needs a finite distance eps > 0, got %g", eps);
    mt_map *map = mt__calloc(1, sizeof *map);
    if (!map) return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "map: out of memory");
    map->weld = weld;
    map->eps = eps;
    map->faces_removed.elem_size = map->verts_added.elem_size = map->verts_removed.elem_size =
        sizeof(uint32_t);
    *out = map;
    return MT_OK;
}

static void free_blocks(mt_map *map)
{
    for (uint32_t s = 0; s < map->num_slots; s++) {
        mt__block_free(map->blocks[s]);
        map->blocks[s] = NULL;
    }
}

void mt_map_destroy(mt_map *map)
{
    if (!map) return;
    free_blocks(map);
    mt__free(map->blocks);
    mt__free(map->free_slots);
    mt__table_free(&map->block_table);
    mt__free(map->pos);
    mt__free(map->vert_head);
    mt__free(map->vert_origin);
    mt__free(map->vert_flags);
    mt__table_free(&map->weld_table);
    mt__free(map->face_block);
    mt__free(map->face_local);
    mt__hist_free(&map->face_sizes);
    mt__hist_free(&map->edge_uses);
    mt__vec_free(&map->faces_removed);
    mt__vec_free(&map->verts_added);
    mt__vec_free(&map->verts_removed);
    mt__free(map);
}

mt_status mt_map_put(mt_map *map, mt_map_key key, const mt_face_list *block,
                     const uint32_t *vertex_ids, mt_map_delta *out_delta, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!map || !block)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, MT__KEY_FMT ": NULL %s",
                        MT__KEY_ARGS(key), map ? "face list" : "map");
    /* The limits first: they read only the counts. */
    if (block->num_verts > MT_MAP_BLOCK_MAX_VERTS || block->num_faces > MT_MAP_BLOCK_MAX_FACES ||
        block->num_indices > MT_MAP_BLOCK_MAX_INDICES)
        return mt__fail(diag, MT_ERR_TOO_LARGE, MT_NONE,
                        MT__KEY_FMT
                        ": %u vertices, %u faces, %llu indices; a block holds at "
                        "most %u, %u and %u",
                        MT__KEY_ARGS(key), block->num_verts, block->num_faces,
                        (unsigned long long)block->num_indices, MT_MAP_BLOCK_MAX_VERTS,
                        MT_MAP_BLOCK_MAX_FACES, MT_MAP_BLOCK_MAX_INDICES);
    mt_diag inner;
    mt_status s = mt_face_list_check(block, &inner);
    if (s != MT_OK)
        return mt__fail(diag, s, inner.element, MT__KEY_FMT ": %s", MT__KEY_ARGS(key),
                        inner.message);
    for (uint32_t f = 0; f < block->num_faces; f++)
        if (block->face_sizes[f] > MT_MAP_BLOCK_MAX_FACE_SIZE)
            return mt__fail(diag, MT_ERR_TOO_LARGE, f,
                            MT__KEY_FMT ": face %u has %u entries; a face has at most %u",
                            MT__KEY_ARGS(key), f, block->face_sizes[f], MT_MAP_BLOCK_MAX_FACE_SIZE);
    if (block->num_verts > 0 && !block->positions)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        MT__KEY_FMT ": %u vertices but no positions; a map needs them",
                        MT__KEY_ARGS(key), block->num_verts);
    if (map->weld != MT_MAP_WELD_NONE && vertex_ids)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        MT__KEY_FMT ": vertex ids given, but the map welds by position",
                        MT__KEY_ARGS(key));
    if (map->weld == MT_MAP_WELD_NONE && !vertex_ids && block->num_verts > 0)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        MT__KEY_FMT
                        ": the map does not weld (MT_MAP_WELD_NONE), so each block "
                        "vertex needs a map vertex id",
                        MT__KEY_ARGS(key));
    return mt__map_update(map, key, block, vertex_ids, out_delta, diag);
}

mt_status mt_map_remove(mt_map *map, mt_map_key key, mt_map_delta *out_delta, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!map)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, MT__KEY_FMT ": NULL map",
                        MT__KEY_ARGS(key));
    return mt__map_update(map, key, NULL, NULL, out_delta, diag);
}

mt_status mt_map_clear(mt_map *map, mt_map_delta *out_delta, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!map) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "map clear: NULL map");
    mt_map_counts before;
    mt__tally_counts(map, &map->tally, &before);
    free_blocks(map);
    map->num_slots = map->num_free = map->num_blocks = 0;
    mt__table_clear(&map->block_table);
    mt__table_clear(&map->weld_table);
    map->vert_end = map->face_end = 0;
    memset(&map->tally, 0, sizeof map->tally);
    map->face_sizes.len = map->edge_uses.len = 0;
    map->faces_removed.len = map->verts_added.len = map->verts_removed.len = 0;
    if (out_delta) {
        memset(out_delta, 0, sizeof *out_delta);
        out_delta->op = MT_MAP_OP_CLEAR;
        out_delta->all_removed = true;
        out_delta->before = before;
        mt__tally_counts(map, &map->tally, &out_delta->after);
    }
    return MT_OK;
}

void mt_map_get_counts(const mt_map *map, mt_map_counts *out)
{
    if (!out) return;
    if (!map) {
        memset(out, 0, sizeof *out);
        return;
    }
    mt__tally_counts(map, &map->tally, out);
}

static mt_status copy_hist(const mt__hist *h, mt_histogram_bin *out, size_t capacity,
                           size_t *out_count)
{
    if (out_count) *out_count = h->len;
    if (!out && capacity == 0) return MT_OK;
    if (!out || capacity < h->len) return MT_ERR_BUFFER_TOO_SMALL;
    if (h->len) memcpy(out, h->bins, h->len * sizeof *out);
    return MT_OK;
}

mt_status mt_map_face_size_histogram(const mt_map *map, mt_histogram_bin *out_bins, size_t capacity,
                                     size_t *out_count)
{
    if (!map) return MT_ERR_INVALID_ARG;
    return copy_hist(&map->face_sizes, out_bins, capacity, out_count);
}

mt_status mt_map_edge_use_histogram(const mt_map *map, mt_histogram_bin *out_bins, size_t capacity,
                                    size_t *out_count)
{
    if (!map) return MT_ERR_INVALID_ARG;
    return copy_hist(&map->edge_uses, out_bins, capacity, out_count);
}

void mt_map_id_ends(const mt_map *map, uint32_t *out_vert_end, uint32_t *out_face_end)
{
    if (out_vert_end) *out_vert_end = map ? map->vert_end : 0;
    if (out_face_end) *out_face_end = map ? map->face_end : 0;
}

mt_status mt_map_blocks(const mt_map *map, mt_map_key *out_keys, size_t capacity, size_t *out_count)
{
    if (!map) return MT_ERR_INVALID_ARG;
    if (out_count) *out_count = map->num_blocks;
    if (!out_keys && capacity == 0) return MT_OK;
    if (!out_keys || capacity < map->num_blocks) return MT_ERR_BUFFER_TOO_SMALL;
    size_t n = 0;
    for (uint32_t s = 0; s < map->num_slots; s++)
        if (map->blocks[s]) out_keys[n++] = map->blocks[s]->key;
    return MT_OK;
}

bool mt_map_has_block(const mt_map *map, mt_map_key key)
{
    return map && mt__map_find_block(map, key) != MT_NONE;
}

size_t mt_map_memory_bytes(const mt_map *map)
{
    if (!map) return 0;
    size_t bytes = sizeof *map;
    for (uint32_t s = 0; s < map->num_slots; s++) bytes += mt__block_bytes(map->blocks[s]);
    bytes += (size_t)map->cap_slots * (sizeof(mt__map_block *) + sizeof(uint32_t));
    bytes += ((size_t)map->block_table.cap + map->weld_table.cap) * sizeof(uint32_t);
    bytes += (size_t)map->vert_cap * (3 * sizeof(double) + sizeof(uint32_t) + sizeof(uint64_t) + 1);
    bytes += (size_t)map->face_cap * 2 * sizeof(uint32_t);
    bytes += (map->face_sizes.cap + map->edge_uses.cap) * sizeof(mt_histogram_bin);
    bytes +=
        (map->faces_removed.cap + map->verts_added.cap + map->verts_removed.cap) * sizeof(uint32_t);
    return bytes;
}
