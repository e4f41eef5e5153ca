/* Applying a planned operation: the old version's faces leave their
 * vertices' lists and its vertices their origin rings, dying vertices leave
 * the weld table, the new version takes the slot, new vertices are born,
 * its faces join the lists, and the counts move by the planned change.
 * Every array was sized by the plan, so nothing here allocates or fails. */
#include <stdlib.h>
#include <string.h>

#include "map/map_internal.h"

static uint64_t ring_next(const mt_map *map, uint64_t e)
{
    return map->blocks[e >> 32]->ring_next[(uint32_t)e];
}

static void ring_set_next(mt_map *map, uint64_t e, uint64_t next)
{
    map->blocks[e >> 32]->ring_next[(uint32_t)e] = next;
}

/* Takes the origins in `slot` out of v's ring. */
static void ring_drop(mt_map *map, uint32_t v, uint32_t slot)
{
    const uint64_t start = map->vert_origin[v];
    uint64_t e = start, keep = MT__MAP_NO_ORIGIN;
    do {
        if ((uint32_t)(e >> 32) != slot) {
            keep = e;
            break;
        }
        e = ring_next(map, e);
    } while (e != start);
    map->vert_origin[v] = keep;
    if (keep == MT__MAP_NO_ORIGIN) return;
    uint64_t prev = keep;
    for (e = ring_next(map, keep); e != keep;) {
        const uint64_t next = ring_next(map, e);
        if ((uint32_t)(e >> 32) != slot) {
            ring_set_next(map, prev, e);
            prev = e;
        }
        e = next;
    }
    ring_set_next(map, prev, keep);
}

static void ring_add(mt_map *map, uint32_t v, uint64_t e)
{
    const uint64_t o = map->vert_origin[v];
    if (o == MT__MAP_NO_ORIGIN) {
        map->vert_origin[v] = e;
        ring_set_next(map, e, e);
    } else {
        ring_set_next(map, e, ring_next(map, o));
        ring_set_next(map, o, e);
    }
}

/* Unlinks the faces in `slot` from v's list. */
static void unlink_faces(mt_map *map, uint32_t v, uint32_t slot)
{
    uint32_t *link = &map->vert_head[v];
    while (*link != MT_NONE) {
        const uint32_t f = *link;
        const mt__map_block *cb;
        uint32_t local;
        const uint32_t c = mt__map_corner_of(map, f, v, &cb, &local);
        mt__map_block *b = map->blocks[map->face_block[f]];
        if (map->face_block[f] == slot)
            *link = b->corner_next[c];
        else
            link = &b->corner_next[c];
    }
}

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

static void remove_old(mt__map_plan *p)
{
    mt_map *map = p->map;
    const mt__map_block *old = p->old;
    if (old->num_faces)
        memcpy(map->faces_removed.data, old->face_ids, (size_t)old->num_faces * sizeof(uint32_t));
    map->faces_removed.len = old->num_faces;
    for (uint32_t t = 0; t < p->num_tv; t++) {
        const uint32_t v = p->tv_vert[t];
        if (p->tv_role[t] & MT__R_OLD_FACES) unlink_faces(map, v, p->old_slot);
        if (p->tv_role[t] & MT__R_IN_OLD) ring_drop(map, v, p->old_slot);
    }
    for (uint32_t i = 0; i < old->num_faces; i++) {
        map->face_block[old->face_ids[i]] = MT_NONE;
        map->face_local[old->face_ids[i]] = 0;
    }
}

static void place_block(mt__map_plan *p)
{
    mt_map *map = p->map;
    if (!p->block) {
        mt__table_remove(&map->block_table, p->old_slot, mt__block_entry_hash, map);
        map->blocks[p->old_slot] = NULL;
        map->free_slots[map->num_free++] = p->old_slot;
        map->num_blocks--;
    } else if (!p->old) {
        if (p->slot == map->num_slots)
            map->num_slots++;
        else
            map->num_free--; /* the plan took the top of the stack */
        map->blocks[p->slot] = p->block;
        mt__table_insert(&map->block_table, mt__key_hash(p->key), p->slot);
        map->num_blocks++;
    } else {
        map->blocks[p->slot] = p->block;
    }
    mt__block_free(p->old);
}

static void update_verts(mt__map_plan *p)
{
    mt_map *map = p->map;
    for (uint32_t v = map->vert_end; v < p->new_vert_end; v++) {
        map->vert_flags[v] = 0;
        map->vert_head[v] = MT_NONE;
        map->vert_origin[v] = MT__MAP_NO_ORIGIN;
    }
    map->vert_end = p->new_vert_end;
    const bool exact = map->weld != MT_MAP_WELD_NONE; /* a weld table is kept */
    map->verts_added.len = map->verts_removed.len = 0;
    uint32_t *added = map->verts_added.data, *removed = map->verts_removed.data;
    for (uint32_t t = 0; t < p->num_tv; t++) {
        const uint32_t v = p->tv_vert[t];
        const uint8_t before = p->tv_old[t], after = p->tv_new[t];
        if ((before & MT__V_ALIVE) && !(after & MT__V_ALIVE)) {
            if (exact && !(before & MT__V_NONFINITE))
                mt__table_remove(&map->weld_table, v, mt__weld_entry_hash, map);
            map->vert_head[v] = MT_NONE;
            map->vert_origin[v] = MT__MAP_NO_ORIGIN;
            removed[map->verts_removed.len++] = v;
        }
        if (p->tv_pos[t] != MT_NONE)
            memcpy(&map->pos[3 * (size_t)v], p->input->positions + 3 * (size_t)p->tv_pos[t],
                   3 * sizeof(double));
        if (!(before & MT__V_ALIVE) && (after & MT__V_ALIVE)) {
            map->vert_head[v] = MT_NONE;
            map->vert_origin[v] = MT__MAP_NO_ORIGIN;
            if (exact && !(after & MT__V_NONFINITE))
                mt__table_insert(&map->weld_table, mt__weld_entry_hash(map, v), v);
            added[map->verts_added.len++] = v;
        }
        map->vert_flags[v] = after;
    }
    if (map->verts_added.len > 1) qsort(added, map->verts_added.len, sizeof *added, compare_u32);
    if (map->verts_removed.len > 1)
        qsort(removed, map->verts_removed.len, sizeof *removed, compare_u32);
}

static void add_new(mt__map_plan *p)
{
    mt_map *map = p->map;
    mt__map_block *b = p->block;
    b->key = p->key;
    for (uint32_t u = 0; u < b->num_verts; u++)
        ring_add(map, b->vert_map[u], mt__origin_pack(p->slot, u));
    for (uint32_t i = 0; i < b->num_faces; i++) {
        const uint32_t f = b->face_ids[i];
        map->face_block[f] = p->slot;
        map->face_local[f] = i | (p->b_valid[i] ? MT__MAP_VALID : 0);
        const uint32_t c0 = mt__blk_begin(b, i), n = mt__blk_size(b, i);
        for (uint32_t c = c0; c < c0 + n; c++) {
            if (b->corner_next[c] == MT__MAP_UNLINKED) continue;
            b->corner_next[c] = map->vert_head[b->corners[c]];
            map->vert_head[b->corners[c]] = f;
        }
    }
    map->face_end += b->num_faces;
}

void mt__plan_commit(mt__map_plan *p, mt_map_delta *out)
{
    mt_map *map = p->map;
    mt_map_counts before;
    mt__tally_counts(map, &map->tally, &before);
    map->faces_removed.len = 0;
    if (p->old) remove_old(p);
    update_verts(p);
    place_block(p);
    if (p->block) add_new(p);
    for (int k = 0; k < MT__T_COUNT; k++) map->tally.n[k] += p->change.n[k];
    mt__hist_apply(&map->face_sizes, &p->size_changes);
    mt__hist_apply(&map->edge_uses, &p->use_changes);
    if (!out) return;
    memset(out, 0, sizeof *out);
    out->op = !p->block ? MT_MAP_OP_REMOVE : p->old ? MT_MAP_OP_REPLACE : MT_MAP_OP_PUT_NEW;
    out->key = p->key;
    out->faces_added = p->block ? p->block->face_ids : NULL;
    out->num_faces_added = p->block ? p->block->num_faces : 0;
    out->faces_removed = map->faces_removed.data;
    out->num_faces_removed = map->faces_removed.len;
    out->verts_added = map->verts_added.data;
    out->num_verts_added = map->verts_added.len;
    out->verts_removed = map->verts_removed.data;
    out->num_verts_removed = map->verts_removed.len;
    out->before = before;
    mt__tally_counts(map, &map->tally, &out->after);
}
