/* Boundary loops: every ring of boundary half-edges (no face), each once, in
 * ascending order of its smallest half-edge id, listed from that half-edge's
 * tail with the faces on the left (the ring walked backwards: a boundary
 * half-edge has its face on the twin side). Linear in the number of
 * half-edges with one temporary bitmap of visited half-edges. */
#include <string.h>

#include "meshtopo/query.h"
#include "query/query_internal.h"

typedef struct loop_out {
    uint32_t *verts;   /* NULL in the counting pass */
    uint32_t *offsets; /* NULL in the counting pass */
    size_t num_verts, num_loops;
} loop_out;

static void mark(uint64_t *bits, uint32_t h)
{
    bits[h >> 6] |= (uint64_t)1 << (h & 63);
}

static bool marked(const uint64_t *bits, uint32_t h)
{
    return (bits[h >> 6] >> (h & 63)) & 1u;
}

/* Walks the ring of boundary half-edge `start`, marking it; in the filling
 * pass writes its vertices. MT_ERR_CORRUPT when the ring leaves the boundary
 * or never closes. */
static mt_status walk_loop(const mt_mesh *m, uint32_t start, uint64_t *bits, loop_out *out)
{
    size_t first = out->num_verts;
    uint32_t h = start, steps = 0;
    do {
        if (m->he_face[h] != MT_NONE || marked(bits, h)) return MT_ERR_CORRUPT;
        mark(bits, h);
        if (out->verts) {
            uint32_t v = mt__original_checked(m, m->he_head[h ^ 1u]);
            if (v == MT_NONE) return MT_ERR_CORRUPT;
            out->verts[out->num_verts] = v;
        }
        out->num_verts++;
        if (!mt__ring_step(m, &h, &steps)) return MT_ERR_CORRUPT;
    } while (h != start);
    if (out->verts) {
        /* Ring order has the faces on the right: keep the first vertex and
         * reverse the rest. */
        uint32_t *loop = out->verts + first;
        size_t n = out->num_verts - first;
        for (size_t i = 1, j = n - 1; i < j; i++, j--) {
            uint32_t t = loop[i];
            loop[i] = loop[j];
            loop[j] = t;
        }
        out->offsets[out->num_loops + 1] = (uint32_t)out->num_verts;
    }
    out->num_loops++;
    return MT_OK;
}

static mt_status walk_all(const mt_mesh *m, uint64_t *bits, size_t bitmap_words, loop_out *out)
{
    memset(bits, 0, bitmap_words * sizeof *bits);
    const uint32_t nhe = m->num_half_edges & ~1u;
    if (out->offsets) out->offsets[0] = 0;
    for (uint32_t h = 0; h < nhe; h++) {
        if (m->he_face[h] != MT_NONE || marked(bits, h)) continue;
        if (m->he_head[h] == MT_NONE && m->he_head[h ^ 1u] == MT_NONE) continue; /* deleted */
        mt_status s = walk_loop(m, h, bits, out);
        if (s != MT_OK) return s;
    }
    return MT_OK;
}

mt_status mt_boundary_loops(const mt_mesh *mesh, uint32_t *out_verts, size_t verts_capacity,
                            uint32_t *out_offsets, size_t offsets_capacity, size_t *out_num_verts,
                            size_t *out_num_loops)
{
    if (!mesh || !out_num_verts || !out_num_loops) return MT_ERR_INVALID_ARG;
    size_t words = ((size_t)mesh->num_half_edges + 63) / 64;
    uint64_t *bits = mt__calloc(words ? words : 1, sizeof *bits);
    if (!bits) return MT_ERR_NOMEM;

    loop_out count = {NULL, NULL, 0, 0};
    mt_status s = walk_all(mesh, bits, words, &count);
    if (s == MT_OK) {
        *out_num_verts = count.num_verts;
        *out_num_loops = count.num_loops;
        if (mt__buffer_absent(out_verts, verts_capacity) &&
            mt__buffer_absent(out_offsets, offsets_capacity)) {
            s = MT_OK;
        } else if (!mt__buffer_fits(out_verts, verts_capacity, count.num_verts) ||
                   !mt__buffer_fits(out_offsets, offsets_capacity, count.num_loops + 1)) {
            s = MT_ERR_BUFFER_TOO_SMALL;
        } else {
            loop_out fill = {out_verts, out_offsets, 0, 0};
            s = walk_all(mesh, bits, words, &fill);
        }
    }
    mt__free(bits);
    return s;
}
