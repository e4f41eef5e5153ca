/* The map's per-element storage and running counts: growing the arrays
 * indexed by vertex and face id (geometrically, content kept, so a failed
 * growth changes nothing observable), and turning the signed tallies into
 * the public mt_map_counts. Used by every stage of an operation. */
#include <string.h>

#include "map/map_internal.h"

/* Grows *arr to hold cap elements of elem bytes; the old content stays. */
static mt_status grow(void **arr, size_t cap, size_t elem)
{
    size_t bytes;
    if (!mt__mul_size(cap, elem, &bytes)) return MT_ERR_NOMEM;
    void *p = mt__realloc(*arr, bytes);
    if (!p) return MT_ERR_NOMEM;
    *arr = p;
    return MT_OK;
}

static uint32_t grown_cap(uint32_t cap, uint32_t end)
{
    uint64_t want = (uint64_t)cap + cap / 2;
    if (want < end) want = end;
    if (want < 64) want = 64;
    return want > UINT32_MAX ? UINT32_MAX : (uint32_t)want;
}

mt_status mt__map_reserve_verts(mt_map *map, uint32_t end)
{
    if (end <= map->vert_cap) return MT_OK;
    const uint32_t cap = grown_cap(map->vert_cap, end);
    if (grow((void **)&map->pos, cap, 3 * sizeof(double)) != MT_OK ||
        grow((void **)&map->vert_head, cap, sizeof(uint32_t)) != MT_OK ||
        grow((void **)&map->vert_origin, cap, sizeof(uint64_t)) != MT_OK ||
        grow((void **)&map->vert_flags, cap, 1) != MT_OK)
        return MT_ERR_NOMEM;
    map->vert_cap = cap;
    return MT_OK;
}

mt_status mt__map_reserve_faces(mt_map *map, uint32_t end)
{
    if (end <= map->face_cap) return MT_OK;
    const uint32_t cap = grown_cap(map->face_cap, end);
    if (grow((void **)&map->face_block, cap, sizeof(uint32_t)) != MT_OK ||
        grow((void **)&map->face_local, cap, sizeof(uint32_t)) != MT_OK)
        return MT_ERR_NOMEM;
    map->face_cap = cap;
    return MT_OK;
}

void mt__tally_counts(const mt_map *map, const mt__tally *t, mt_map_counts *out)
{
    memset(out, 0, sizeof *out);
    const int64_t *n = t->n;
    out->num_blocks = map->num_blocks;
    out->num_verts = (uint32_t)n[MT__T_VERTS];
    out->num_faces = (uint32_t)n[MT__T_FACES];
    out->num_faces_valid = (uint32_t)n[MT__T_FACES_VALID];
    out->num_edges = (uint64_t)n[MT__T_EDGES];
    out->num_half_edges = (uint64_t)n[MT__T_HALF_EDGES];
    out->boundary_edges = (uint64_t)n[MT__T_BOUNDARY];
    out->nonmanifold_edges = (uint64_t)n[MT__T_NM_EDGES];
    out->inconsistent_orientation_edges = (uint64_t)n[MT__T_INCONSISTENT];
    out->duplicate_directed_edges = (uint64_t)n[MT__T_DUP_DIRECTED];
    out->nonmanifold_vertices = (uint32_t)n[MT__T_NM_VERTS];
    out->bowtie_vertices = (uint32_t)n[MT__T_BOWTIE];
    out->isolated_vertices = (uint32_t)n[MT__T_ISOLATED];
    out->unreferenced_vertices = (uint32_t)n[MT__T_UNREFERENCED];
    out->degenerate_faces = (uint32_t)n[MT__T_DEGENERATE];
    out->duplicate_faces = (uint32_t)(n[MT__T_FACES_VALID] - n[MT__T_CLASSES]);
    out->out_of_range_indices = (uint64_t)n[MT__T_OOR_INDICES];
    out->faces_with_out_of_range_indices = (uint32_t)n[MT__T_OOR_FACES];
    out->nonfinite_vertices = (uint32_t)n[MT__T_NONFINITE];
    out->euler_characteristic = n[MT__T_VERTS] - n[MT__T_EDGES] + n[MT__T_FACES_VALID];
    out->closed = n[MT__T_BOUNDARY] == 0 && n[MT__T_FACES_VALID] > 0;
    out->manifold = n[MT__T_NM_EDGES] == 0 && n[MT__T_NM_VERTS] == 0;
    out->consistently_oriented = n[MT__T_INCONSISTENT] == 0 && n[MT__T_DUP_DIRECTED] == 0;
}
