/* Compaction of the map: the point where ids of removed elements come back.
 * Live vertices (exact mode; none mode keeps the sender's ids) and live
 * faces are renumbered densely in id order, every reference is rewritten
 * (block vertex maps, corners, face links, list heads, the weld table), and
 * the per-element arrays shrink to fit. Linear in the map. */
#include <string.h>

#include "map/map_internal.h"

/* Shrinks an array to `bytes` if realloc allows; keeps it otherwise. */
static void shrink(void **arr, size_t bytes)
{
    void *p = mt__realloc(*arr, bytes ? bytes : 1);
    if (p) *arr = p;
}

static void renumber_blocks(mt_map *map, const uint32_t *vmap, const uint32_t *fmap)
{
    for (uint32_t s = 0; s < map->num_slots; s++) {
        mt__map_block *b = map->blocks[s];
        if (!b) continue;
        for (uint32_t u = 0; u < b->num_verts; u++) b->vert_map[u] = vmap[b->vert_map[u]];
        for (uint32_t c = 0; c < b->num_indices; c++) {
            if (b->corners[c] < MT__MAP_OOR) b->corners[c] = vmap[b->corners[c]];
            const uint32_t next = b->corner_next[c];
            if (next != MT_NONE && next != MT__MAP_UNLINKED) b->corner_next[c] = fmap[next];
        }
        for (uint32_t i = 0; i < b->num_faces; i++) b->face_ids[i] = fmap[b->face_ids[i]];
    }
}

static void rebuild_weld_table(mt_map *map)
{
    if (map->weld == MT_MAP_WELD_NONE) return;
    const uint32_t live = map->weld_table.count;
    mt__table smaller = {NULL, 0, 0};
    if (map->weld_table.cap > 64 && (uint64_t)live * 8 < map->weld_table.cap &&
        mt__table_reserve(&smaller, live, mt__weld_entry_hash, map) == MT_OK) {
        mt__table_free(&map->weld_table);
        map->weld_table = smaller;
    }
    mt__table_clear(&map->weld_table);
    for (uint32_t v = 0; v < map->vert_end; v++)
        if ((map->vert_flags[v] & (MT__V_ALIVE | MT__V_NONFINITE)) == MT__V_ALIVE)
            mt__table_insert(&map->weld_table, mt__weld_entry_hash(map, v), v);
}

mt_status mt_map_compact(mt_map *map, uint32_t *out_vert_map, size_t vert_map_capacity,
                         uint32_t *out_face_map, size_t face_map_capacity, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!map) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "map compact: NULL map");
    if ((out_vert_map && vert_map_capacity < map->vert_end) ||
        (out_face_map && face_map_capacity < map->face_end))
        return mt__fail(diag, MT_ERR_BUFFER_TOO_SMALL, MT_NONE,
                        "map compact: the maps need %u vertex and %u face entries", map->vert_end,
                        map->face_end);
    uint32_t *vmap = out_vert_map, *fmap = out_face_map;
    if (!vmap) vmap = mt__malloc((size_t)(map->vert_end ? map->vert_end : 1) * sizeof *vmap);
    if (!fmap) fmap = mt__malloc((size_t)(map->face_end ? map->face_end : 1) * sizeof *fmap);
    if (!vmap || !fmap) {
        if (vmap != out_vert_map) mt__free(vmap);
        if (fmap != out_face_map) mt__free(fmap);
        return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "map compact: out of memory; unchanged");
    }
    const bool renumber = map->weld != MT_MAP_WELD_NONE;
    uint32_t vend = 0, fend = 0;
    for (uint32_t v = 0; v < map->vert_end; v++) {
        vmap[v] = MT_NONE;
        if (!(map->vert_flags[v] & MT__V_ALIVE)) continue;
        vmap[v] = renumber ? vend : v;
        vend = vmap[v] + 1;
    }
    for (uint32_t f = 0; f < map->face_end; f++)
        fmap[f] = map->face_block[f] == MT_NONE ? MT_NONE : fend++;

    for (uint32_t v = 0; v < map->vert_end; v++) {
        const uint32_t w = vmap[v];
        if (w == MT_NONE) {
            if (!renumber) map->vert_head[v] = MT_NONE, map->vert_flags[v] = 0;
            continue;
        }
        memmove(&map->pos[3 * (size_t)w], &map->pos[3 * (size_t)v], 3 * sizeof(double));
        map->vert_head[w] = map->vert_head[v] == MT_NONE ? MT_NONE : fmap[map->vert_head[v]];
        map->vert_origin[w] = map->vert_origin[v];
        map->vert_flags[w] = map->vert_flags[v];
    }
    for (uint32_t f = 0; f < map->face_end; f++) {
        const uint32_t g = fmap[f];
        if (g == MT_NONE) continue;
        map->face_block[g] = map->face_block[f];
        map->face_local[g] = map->face_local[f];
    }
    renumber_blocks(map, vmap, fmap);
    map->vert_end = vend;
    map->face_end = fend;
    rebuild_weld_table(map);

    shrink((void **)&map->pos, (size_t)vend * 3 * sizeof(double));
    shrink((void **)&map->vert_head, (size_t)vend * sizeof(uint32_t));
    shrink((void **)&map->vert_origin, (size_t)vend * sizeof(uint64_t));
    shrink((void **)&map->vert_flags, vend);
    map->vert_cap = vend; /* each array holds at least vend entries */
    shrink((void **)&map->face_block, (size_t)fend * sizeof(uint32_t));
    shrink((void **)&map->face_local, (size_t)fend * sizeof(uint32_t));
    map->face_cap = fend;
    mt__vec_free(&map->faces_removed);
    mt__vec_free(&map->verts_added);
    mt__vec_free(&map->verts_removed);

    if (vmap != out_vert_map) mt__free(vmap);
    if (fmap != out_face_map) mt__free(fmap);
    return MT_OK;
}
