/* The per-side use of a face (boundary, shared, non-manifold, same
 * direction) that both the default query choice and the readable output of
 * `meshtopo inspect` need, and the sorted sets of ids they print. */
#include <stdlib.h>

#include "inspect.h"

static int compare_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

size_t inspect_sort_unique(uint32_t *ids, size_t count)
{
    if (count == 0) return 0;
    qsort(ids, count, sizeof *ids, compare_u32);
    size_t out = 1;
    for (size_t i = 1; i < count; i++)
        if (ids[i] != ids[out - 1]) ids[out++] = ids[i];
    return out;
}

/* True when the corner list has the directed side a -> b. */
static bool has_directed_side(const mt_face_corners *c, uint32_t a, uint32_t b)
{
    for (size_t k = 0; k < c->count; k++)
        if (c->verts[k] == a && c->verts[(k + 1) % c->count] == b) return true;
    return false;
}

mt_status inspect_side_use(const mt_mesh *mesh, const mt_face_corners *corners,
                           const mt_face_adjacency *adj, size_t side, mt_face_corners *scratch,
                           mt_side_use *out)
{
    out->uses = 0;
    out->same_direction = false;
    if (side >= adj->num_edges || side >= corners->count) return MT_ERR_OUT_OF_RANGE;
    size_t across = adj->offsets[side + 1] - adj->offsets[side];
    out->uses = across + 1;
    if (across != 1) return MT_OK;
    uint32_t a = corners->verts[side];
    uint32_t b = corners->verts[(side + 1) % corners->count];
    mt_status st = mt_face_verts_growing(mesh, adj->faces[adj->offsets[side]], scratch);
    if (st != MT_OK) return st;
    out->same_direction = has_directed_side(scratch, a, b);
    return MT_OK;
}
