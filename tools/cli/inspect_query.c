/* Query wrappers for `meshtopo inspect`: call a query, grow its caller-owned
 * buffers to the sizes it reports, call again. Also the per-side use of a
 * face (boundary, shared, non-manifold, same direction) that both the
 * default query choice and the readable output need. */
#include <stdlib.h>
#include <string.h>

#include "inspect.h"

/* Grows *buf to hold `needed` elements of `size` bytes; false when out of memory. */
static bool grow(void **buf, size_t *capacity, size_t needed, size_t size)
{
    if (needed <= *capacity) return true;
    if (needed > SIZE_MAX / size) return false;
    void *p = realloc(*buf, needed * size);
    if (!p) return false;
    *buf = p;
    *capacity = needed;
    return true;
}

/* Queries report their needed sizes either with MT_ERR_BUFFER_TOO_SMALL or,
 * when handed NULL buffers, with MT_OK and sizes above the capacities; both
 * mean "grow and ask again". Two rounds always suffice for a fixed mesh;
 * a third is allowed in case the first answered with zero capacity. */
enum { QUERY_ROUNDS = 3 };

mt_status mt_inspect_ring(const mt_mesh *mesh, uint32_t vert, mt_ring *ring)
{
    for (int round = 0; round < QUERY_ROUNDS; round++) {
        mt_status st = mt_vert_ring(mesh, vert, ring);
        if (st != MT_OK && st != MT_ERR_BUFFER_TOO_SMALL) return st;
        bool fits = ring->num_neighbors <= ring->neighbors_capacity &&
                    ring->num_faces <= ring->faces_capacity &&
                    ring->num_fans <= ring->fans_capacity;
        if (st == MT_OK && fits) return MT_OK;
        if (!grow((void **)&ring->neighbors, &ring->neighbors_capacity, ring->num_neighbors,
                  sizeof *ring->neighbors) ||
            !grow((void **)&ring->faces, &ring->faces_capacity, ring->num_faces,
                  sizeof *ring->faces) ||
            !grow((void **)&ring->fans, &ring->fans_capacity, ring->num_fans, sizeof *ring->fans))
            return MT_ERR_NOMEM;
    }
    return MT_ERR_BUFFER_TOO_SMALL;
}

void mt_inspect_ring_free(mt_ring *ring)
{
    free(ring->neighbors);
    free(ring->faces);
    free(ring->fans);
    memset(ring, 0, sizeof *ring);
}

mt_status mt_inspect_face_adjacency(const mt_mesh *mesh, uint32_t face, mt_face_adjacency *adj)
{
    for (int round = 0; round < QUERY_ROUNDS; round++) {
        mt_status st = mt_face_neighbors(mesh, face, adj->faces, adj->faces_capacity, adj->offsets,
                                         adj->offsets_capacity, &adj->num_faces, &adj->num_edges);
        if (st != MT_OK && st != MT_ERR_BUFFER_TOO_SMALL) return st;
        bool fits =
            adj->num_faces <= adj->faces_capacity && adj->num_edges + 1 <= adj->offsets_capacity;
        if (st == MT_OK && fits) return MT_OK;
        if (!grow((void **)&adj->faces, &adj->faces_capacity, adj->num_faces, sizeof *adj->faces) ||
            !grow((void **)&adj->offsets, &adj->offsets_capacity, adj->num_edges + 1,
                  sizeof *adj->offsets))
            return MT_ERR_NOMEM;
    }
    return MT_ERR_BUFFER_TOO_SMALL;
}

void mt_inspect_face_adjacency_free(mt_face_adjacency *adj)
{
    free(adj->faces);
    free(adj->offsets);
    memset(adj, 0, sizeof *adj);
}

mt_status mt_inspect_face_corners(const mt_mesh *mesh, uint32_t face, mt_face_corners *corners)
{
    for (int round = 0; round < QUERY_ROUNDS; round++) {
        mt_status st =
            mt_face_verts(mesh, face, corners->verts, corners->capacity, &corners->count);
        if (st != MT_OK && st != MT_ERR_BUFFER_TOO_SMALL) return st;
        if (st == MT_OK && corners->count <= corners->capacity) return MT_OK;
        if (!grow((void **)&corners->verts, &corners->capacity, corners->count,
                  sizeof *corners->verts))
            return MT_ERR_NOMEM;
    }
    return MT_ERR_BUFFER_TOO_SMALL;
}

void mt_inspect_face_corners_free(mt_face_corners *corners)
{
    free(corners->verts);
    memset(corners, 0, sizeof *corners);
}

static int compare_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

size_t mt_inspect_sort_unique(uint32_t *ids, size_t count)
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

mt_status mt_inspect_side_use(const mt_mesh *mesh, const mt_face_corners *corners,
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
    mt_status st = mt_inspect_face_corners(mesh, adj->faces[adj->offsets[side]], scratch);
    if (st != MT_OK) return st;
    out->same_direction = has_directed_side(scratch, a, b);
    return MT_OK;
}
