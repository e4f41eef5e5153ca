/* Queries into buffers that grow (meshtopo/query.h): the one-ring, a face's
 * neighbours and its corners, for callers that ask about one element after
 * another, such as the inspect report's JSON and text. Each asks, grows
 * the arrays to the sizes the query reports and asks again. */
#include <string.h>

#include "meshtopo/query.h"
#include "query/query_internal.h"

/* Queries report their sizes either with MT_ERR_BUFFER_TOO_SMALL or, when
 * handed NULL buffers, with MT_OK and sizes above the capacities; both mean
 * "grow and ask again". Two rounds suffice for a fixed mesh; a third is
 * allowed in case the first answered with zero capacity. */
enum { QUERY_ROUNDS = 3 };

/* Grows *buf to hold `needed` elements of `size` bytes; false when out of memory. */
static bool grow(void **buf, size_t *capacity, size_t needed, size_t size)
{
    if (needed <= *capacity) return true;
    if (needed > SIZE_MAX / size) return false;
    void *p = mt__realloc(*buf, needed * size);
    if (!p) return false;
    *buf = p;
    *capacity = needed;
    return true;
}

mt_status mt_vert_ring_growing(const mt_mesh *mesh, uint32_t vert, mt_ring *ring)
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

void mt_ring_free(mt_ring *ring)
{
    mt__free(ring->neighbors);
    mt__free(ring->faces);
    mt__free(ring->fans);
    memset(ring, 0, sizeof *ring);
}

mt_status mt_face_neighbors_growing(const mt_mesh *mesh, uint32_t face, mt_face_adjacency *adj)
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

void mt_face_adjacency_free(mt_face_adjacency *adj)
{
    mt__free(adj->faces);
    mt__free(adj->offsets);
    memset(adj, 0, sizeof *adj);
}

mt_status mt_face_verts_growing(const mt_mesh *mesh, uint32_t face, mt_face_corners *corners)
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

void mt_face_corners_free(mt_face_corners *corners)
{
    mt__free(corners->verts);
    memset(corners, 0, sizeof *corners);
}
