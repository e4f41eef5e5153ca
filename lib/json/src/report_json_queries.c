/* "vertex_queries" and "face_queries" of the inspect document
 * (report_json.h): each queried vertex's neighbours and valid faces, each
 * queried face's adjacent faces, as the sorted sets DEFINITIONS.md
 * "Queries" defines. The caller-owned query buffers grow to the sizes the
 * queries report and are reused from one element to the next. */
#include <stdlib.h>
#include <string.h>

#include "meshtopo/query.h"
#include "meshtopo/report_json.h"
#include "report_json_internal.h"

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

/* Queries report their sizes either with MT_ERR_BUFFER_TOO_SMALL or, when
 * handed NULL buffers, with MT_OK and sizes above the capacities; both mean
 * "grow and ask again". Two rounds suffice for a fixed mesh; a third is
 * allowed in case the first answered with zero capacity. */
enum { QUERY_ROUNDS = 3 };

static mt_status ring_of(const mt_mesh *mesh, uint32_t vert, mt_ring *ring)
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

/* Buffers of mt_face_neighbors. */
typedef struct adjacency {
    uint32_t *faces;
    size_t faces_capacity;
    uint32_t *offsets;
    size_t offsets_capacity;
    size_t num_faces, num_edges;
} adjacency;

static mt_status adjacency_of(const mt_mesh *mesh, uint32_t face, adjacency *adj)
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

static mt_status write_vertex_queries(mt_json *j, const mt_mesh *mesh, const uint32_t *verts,
                                      size_t num_verts, mt_diag *diag)
{
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    mt_status st = MT_OK;
    mt_json_array_begin(j);
    for (size_t i = 0; i < num_verts; i++) {
        uint32_t v = verts[i];
        st = ring_of(mesh, v, &ring);
        if (st != MT_OK) {
            mt_diag_set(diag, st, "query of vertex %u failed: %s", (unsigned)v, mt_strerror(st));
            break;
        }
        size_t nn = mt__json_sort_unique(ring.neighbors, ring.num_neighbors);
        size_t nf = mt__json_sort_unique(ring.faces, ring.num_faces);
        mt_json_object_begin(j);
        mt_json_key(j, "vertex");
        mt_json_uint(j, v);
        mt_json_key(j, "neighbors");
        mt__json_write_ids(j, ring.neighbors, nn);
        mt_json_key(j, "faces");
        mt__json_write_ids(j, ring.faces, nf);
        mt_json_object_end(j);
    }
    mt_json_array_end(j);
    free(ring.neighbors);
    free(ring.faces);
    free(ring.fans);
    return st;
}

static mt_status write_face_queries(mt_json *j, const mt_mesh *mesh, const uint32_t *faces,
                                    size_t num_faces, mt_diag *diag)
{
    adjacency adj;
    memset(&adj, 0, sizeof adj);
    mt_status st = MT_OK;
    mt_json_array_begin(j);
    for (size_t i = 0; i < num_faces; i++) {
        uint32_t f = faces[i];
        st = adjacency_of(mesh, f, &adj);
        if (st != MT_OK && st != MT_ERR_NOT_FOUND) {
            mt_diag_set(diag, st, "query of face %u failed: %s", (unsigned)f, mt_strerror(st));
            break;
        }
        mt_json_object_begin(j);
        mt_json_key(j, "face");
        mt_json_uint(j, f);
        mt_json_key(j, "adjacent_faces");
        if (st == MT_ERR_NOT_FOUND) {
            mt_json_null(j); /* a rejected record has no adjacency */
            st = MT_OK;
        } else {
            size_t n = mt__json_sort_unique(adj.faces, adj.num_faces);
            size_t kept = 0;
            for (size_t k = 0; k < n; k++)
                if (adj.faces[k] != f) adj.faces[kept++] = adj.faces[k];
            mt__json_write_ids(j, adj.faces, kept);
        }
        mt_json_object_end(j);
    }
    mt_json_array_end(j);
    free(adj.faces);
    free(adj.offsets);
    return st;
}

mt_status mt_report_json_write_queries(mt_json *j, const mt_mesh *mesh, const uint32_t *verts,
                                       size_t num_verts, const uint32_t *faces, size_t num_faces,
                                       mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!j || !mesh || (num_verts && !verts) || (num_faces && !faces))
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "report JSON: NULL mesh, writer or id list");
    mt_json_key(j, "vertex_queries");
    mt_status st = write_vertex_queries(j, mesh, verts, num_verts, diag);
    if (st != MT_OK) return st;
    mt_json_key(j, "face_queries");
    return write_face_queries(j, mesh, faces, num_faces, diag);
}
