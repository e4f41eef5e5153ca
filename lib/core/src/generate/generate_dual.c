/* The dual of a built mesh (meshtopo/generate.h): one vertex per face record
 * (at the face's centroid), one face per closed fan of faces around a
 * vertex, its corners the fan's faces in ring order. Written over the ring
 * query, so it follows the same fans a non-manifold vertex has. */
#include <stdlib.h>
#include <string.h>

#include "meshtopo/generate.h"
#include "meshtopo/geometry.h"
#include "meshtopo/mesh.h"
#include "meshtopo/query.h"

/* Grows *buf to hold n elements of `size` bytes. */
static bool reserve(void **buf, size_t *capacity, size_t n, size_t size)
{
    if (n <= *capacity) return true;
    size_t cap = *capacity ? *capacity : 16;
    while (cap < n) cap *= 2;
    void *grown = realloc(*buf, cap * size);
    if (!grown) return false;
    *buf = grown;
    *capacity = cap;
    return true;
}

/* The ring of v into ring, growing its buffers (a call without buffers
 * only counts). */
static mt_status ring_of(const mt_mesh *m, uint32_t v, mt_ring *ring)
{
    for (;;) {
        mt_status s = mt_vert_ring(m, v, ring);
        if (s != MT_OK && s != MT_ERR_BUFFER_TOO_SMALL) return s;
        if (s == MT_OK && (ring->num_fans == 0 || ring->fans)) return MT_OK;
        if (!reserve((void **)&ring->neighbors, &ring->neighbors_capacity, ring->num_neighbors,
                     sizeof *ring->neighbors) ||
            !reserve((void **)&ring->faces, &ring->faces_capacity, ring->num_faces,
                     sizeof *ring->faces) ||
            !reserve((void **)&ring->fans, &ring->fans_capacity, ring->num_fans,
                     sizeof *ring->fans))
            return MT_ERR_NOMEM;
    }
}

mt_status mt_gen_dual(const mt_mesh *mesh, mt_face_list *out, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (out) memset(out, 0, sizeof *out);
    if (!mesh || !out)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "mt_gen_dual: %s is NULL",
                           mesh ? "out" : "mesh");
    const uint32_t num_faces = mt_mesh_num_faces(mesh), num_verts = mt_mesh_num_verts(mesh);
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    size_t sizes_cap = 0, indices_cap = 0;
    uint32_t *sizes = NULL, *indices = NULL;
    size_t num_dual_faces = 0, num_indices = 0;
    mt_status s = MT_OK;
    for (uint32_t v = 0; v < num_verts && s == MT_OK; v++) {
        s = ring_of(mesh, v, &ring);
        if (s == MT_ERR_NOT_FOUND) { /* a vertex an edit deleted */
            s = MT_OK;
            continue;
        }
        for (size_t k = 0; s == MT_OK && k < ring.num_fans; k++) {
            const mt_fan *fan = &ring.fans[k];
            if (fan->boundary || fan->face_count < 3) continue;
            if (!reserve((void **)&sizes, &sizes_cap, num_dual_faces + 1, sizeof *sizes) ||
                !reserve((void **)&indices, &indices_cap, num_indices + fan->face_count,
                         sizeof *indices)) {
                s = MT_ERR_NOMEM;
                break;
            }
            sizes[num_dual_faces++] = fan->face_count;
            memcpy(indices + num_indices, ring.faces + fan->face_begin,
                   fan->face_count * sizeof *indices);
            num_indices += fan->face_count;
        }
    }
    free(ring.neighbors);
    free(ring.faces);
    free(ring.fans);
    double *positions = NULL;
    if (s == MT_OK && num_verts > 0 && mt_mesh_position(mesh, 0)) {
        positions = calloc(3 * (size_t)num_faces + 1, sizeof *positions);
        if (!positions) s = MT_ERR_NOMEM;
        for (uint32_t f = 0; s == MT_OK && f < num_faces; f++) {
            mt_status c = mt_face_centroid(mesh, f, positions + 3 * (size_t)f, NULL);
            if (c != MT_OK && c != MT_ERR_NOT_FOUND) s = c; /* rejected: the origin */
        }
    }
    if (s != MT_OK) {
        free(sizes);
        free(indices);
        free(positions);
        return mt_diag_set(diag, s, "mt_gen_dual: %s", mt_strerror(s));
    }
    out->num_verts = num_faces;
    out->num_faces = (uint32_t)num_dual_faces;
    out->num_indices = num_indices;
    out->positions = positions;
    out->face_sizes = sizes;
    out->face_indices = indices;
    return MT_OK;
}
