/* Planning one operation (put a block, replace it, remove it): checks the
 * input, builds the new version, welds it, walks the touched vertices and
 * computes every count change, then reserves all the room the commit will
 * use. Everything allocated here is scratch or the new block; a failure at
 * any point frees it and leaves the map as it was (a table may have been
 * rehashed larger, with the same content). */
#include <string.h>

#include "map/map_internal.h"

void mt__plan_free(mt__map_plan *p)
{
    mt__keymap_free(&p->tv);
    mt__free(p->tv_vert);
    mt__free(p->tv_pos);
    mt__free(p->tv_old);
    mt__free(p->tv_new);
    mt__free(p->tv_role);
    mt__free(p->tv_bfirst);
    mt__free(p->tv_bface);
    mt__free(p->b_valid);
    mt__keymap_free(&p->te);
    mt__free(p->te_dfwd);
    mt__free(p->te_dbwd);
    mt__free(p->te_fwd);
    mt__free(p->te_bwd);
    mt__table_free(&p->tc);
    mt__free((void *)p->tc_corners);
    mt__free(p->tc_size);
    mt__free(p->tc_hash);
    mt__free(p->tc_delta);
    mt__free(p->tc_old);
    mt__vec_free(&p->link);
    mt__vec_free(&p->link_scratch);
    mt__vec_free(&p->size_changes);
    mt__vec_free(&p->use_changes);
}

/* Room for the block table and slot arrays to take one more block. */
static mt_status reserve_slot(mt__map_plan *p)
{
    mt_map *map = p->map;
    if (mt__table_reserve(&map->block_table, map->num_blocks + 1, mt__block_entry_hash, map) !=
        MT_OK)
        return MT_ERR_NOMEM;
    if (map->num_free > 0) {
        p->slot = map->free_slots[map->num_free - 1];
        return MT_OK;
    }
    p->slot = map->num_slots;
    if (map->num_slots < map->cap_slots) return MT_OK;
    const uint32_t cap = map->cap_slots ? map->cap_slots * 2 : 16;
    if (cap < map->cap_slots) return MT_ERR_NOMEM;
    mt__map_block **blocks = mt__realloc(map->blocks, (size_t)cap * sizeof *blocks);
    if (!blocks) return MT_ERR_NOMEM;
    map->blocks = blocks;
    uint32_t *free_slots = mt__realloc(map->free_slots, (size_t)cap * sizeof *free_slots);
    if (!free_slots) return MT_ERR_NOMEM;
    map->free_slots = free_slots;
    for (uint32_t s = map->cap_slots; s < cap; s++) blocks[s] = NULL;
    map->cap_slots = cap;
    return MT_OK;
}

/* Room for everything the commit writes. */
static mt_status reserve_all(mt__map_plan *p)
{
    mt_map *map = p->map;
    uint32_t births = 0, deaths = 0;
    for (uint32_t t = 0; t < p->num_tv; t++) {
        const bool before = p->tv_old[t] & MT__V_ALIVE, after = p->tv_new[t] & MT__V_ALIVE;
        births += !before && after;
        deaths += before && !after;
    }
    const uint32_t faces = p->block ? p->block->num_faces : 0;
    if (mt__map_reserve_verts(map, p->new_vert_end) != MT_OK ||
        mt__map_reserve_faces(map, map->face_end + faces) != MT_OK ||
        (map->weld != MT_MAP_WELD_NONE &&
         mt__table_reserve(&map->weld_table, map->weld_table.count + births, mt__weld_entry_hash,
                           map) != MT_OK) ||
        (p->block && !p->old && reserve_slot(p) != MT_OK) ||
        mt__hist_flush(&p->size_changes, p->size_small) != MT_OK ||
        mt__hist_flush(&p->use_changes, p->use_small) != MT_OK ||
        mt__hist_prepare(&map->face_sizes, &p->size_changes) != MT_OK ||
        mt__hist_prepare(&map->edge_uses, &p->use_changes) != MT_OK ||
        mt__map_vec_reserve(&map->faces_removed, p->old ? p->old->num_faces : 0) != MT_OK ||
        mt__map_vec_reserve(&map->verts_added, births) != MT_OK ||
        mt__map_vec_reserve(&map->verts_removed, deaths) != MT_OK)
        return MT_ERR_NOMEM;
    return MT_OK;
}

/* The new version's block, sized for its input. */
static mt_status alloc_block(mt__map_plan *p)
{
    const mt_face_list *in = p->input;
    bool triangles = true;
    for (uint32_t i = 0; i < in->num_faces && triangles; i++) triangles = in->face_sizes[i] == 3;
    p->block = mt__block_alloc(in->num_verts, in->num_faces, (uint32_t)in->num_indices, triangles);
    return p->block ? MT_OK : MT_ERR_NOMEM;
}

mt_status mt__map_update(mt_map *map, mt_map_key key, const mt_face_list *input,
                         const uint32_t *vertex_ids, mt_map_delta *out_delta, mt_diag *diag)
{
    mt__map_plan p;
    memset(&p, 0, sizeof p);
    p.map = map;
    p.key = key;
    p.input = input;
    p.vertex_ids = vertex_ids;
    p.diag = diag;
    p.old_slot = mt__map_find_block(map, key);
    p.old = p.old_slot != MT_NONE ? map->blocks[p.old_slot] : NULL;
    p.slot = p.old_slot;
    p.link.elem_size = p.link_scratch.elem_size = sizeof(uint32_t);
    p.size_changes.elem_size = p.use_changes.elem_size = sizeof(mt__hist_change);
    if (!input && !p.old)
        return mt__fail(diag, MT_ERR_NOT_FOUND, MT_NONE, MT__KEY_FMT ": no such block in the map",
                        MT__KEY_ARGS(key));
    mt_status s = input ? alloc_block(&p) : MT_OK;
    if (s == MT_OK) s = mt__plan_verts(&p);
    if (s == MT_OK) s = mt__plan_faces(&p);
    if (s == MT_OK) s = mt__plan_edges(&p);
    if (s == MT_OK) s = mt__plan_walk(&p);
    if (s == MT_OK) s = mt__plan_edges_finish(&p);
    if (s == MT_OK) s = reserve_all(&p);
    if (s != MT_OK) {
        if (s == MT_ERR_NOMEM)
            mt__fail(diag, MT_ERR_NOMEM, MT_NONE,
                     MT__KEY_FMT ": out of memory while %s it; the map is unchanged",
                     MT__KEY_ARGS(key), input ? "putting" : "removing");
        mt__block_free(p.block);
        mt__plan_free(&p);
        return s;
    }
    mt__plan_commit(&p, out_delta);
    mt__plan_free(&p);
    return MT_OK;
}
