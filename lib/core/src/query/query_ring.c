/* Vertex one-ring and valence. A caller vertex has one fan per internal
 * vertex (itself, then its copies in ascending id), each one rotation
 * r(h) = next(twin(h)) from the stored outgoing half-edge (the boundary one
 * on an open fan). r turns clockwise around counter-clockwise faces, so fans
 * are written reversed. Linear in the ring (plus a binary search at copies
 * and bundled edges); no allocation. */
#include "meshtopo/attributes.h"
#include "meshtopo/query.h"
#include "query/query_internal.h"

/* The hidden flags a ring leaves out (mt_mesh_skip_hidden); all NULL when
 * nothing is skipped. */
typedef struct skipped {
    const uint8_t *vert, *edge, *half_edge, *face;
} skipped;

static skipped skipped_of(const mt_mesh *m)
{
    skipped s = {mt__skipped_flags(m, MT_ELEMENT_VERTEX), mt__skipped_flags(m, MT_ELEMENT_EDGE),
                 mt__skipped_flags(m, MT_ELEMENT_HALF_EDGE), mt__skipped_flags(m, MT_ELEMENT_FACE)};
    return s;
}

/* Whether the ring lists neighbour w reached by outgoing half-edge h. */
static bool neighbor_shown(const mt_mesh *m, const skipped *sk, uint32_t h, uint32_t w)
{
    return !mt__skipped(sk->vert, m->num_verts, w) &&
           !mt__skipped(sk->edge, m->num_half_edges / 2, h >> 1) &&
           !mt__skipped(sk->half_edge, m->num_half_edges, h);
}

/* Whether the ring lists face f (MT_NONE: no face). */
static bool face_shown(const mt_mesh *m, const skipped *sk, uint32_t f)
{
    return f != MT_NONE && !mt__skipped(sk->face, m->num_faces, f);
}

/* Sizes of the ring of caller vertex v; MT_ERR_CORRUPT on a broken fan. */
static mt_status ring_count(const mt_mesh *m, uint32_t v, const skipped *sk, mt_ring *ring)
{
    size_t nb = 0, nf = 0, fans = 0;
    mt__vert_walk w;
    mt__vert_walk_begin(&w, m, v);
    while (mt__vert_walk_fan(&w)) {
        const size_t fan_first = nb + nf;
        do {
            const uint32_t h = w.he;
            if (neighbor_shown(m, sk, h, mt__original_checked(m, m->he_head[h]))) nb++;
            if (face_shown(m, sk, m->he_face[h ^ 1u])) nf++;
        } while (mt__vert_walk_step(&w));
        if (w.status != MT_OK) return w.status;
        if (nb + nf > fan_first) fans++; /* a fan everything was left out of is not listed */
    }
    if (w.status != MT_OK) return w.status;
    ring->num_neighbors = nb;
    ring->num_faces = nf;
    ring->num_fans = fans;
    return MT_OK;
}

static void reverse_u32(uint32_t *a, size_t n)
{
    for (size_t i = 0, j = n; i + 1 < j; i++, j--) {
        uint32_t t = a[i];
        a[i] = a[j - 1];
        a[j - 1] = t;
    }
}

/* Writes the fans; the buffers are known to be large enough. Walking r from
 * the stored half-edge h_0: neighbour i is the head of h_i and the face
 * between neighbours i and i+1 is the face of twin(h_i) (the face r crosses
 * into); an open fan's last twin is the boundary, so it has one face fewer
 * than neighbours. Reversing both lists (an open fan whole, a closed one
 * after its first neighbour) keeps that pairing and turns the order
 * counter-clockwise. */
static mt_status ring_fill(const mt_mesh *m, uint32_t v, const skipped *sk, mt_ring *ring)
{
    size_t nb = 0, nf = 0, fans = 0;
    mt__vert_walk w;
    mt__vert_walk_begin(&w, m, v);
    while (mt__vert_walk_fan(&w)) {
        mt_fan fan;
        fan.neighbor_begin = (uint32_t)nb;
        fan.face_begin = (uint32_t)nf;
        fan.boundary = m->he_face[w.start] == MT_NONE;
        do {
            const uint32_t h = w.he;
            const uint32_t nv = mt__original_checked(m, m->he_head[h]);
            if (nv == MT_NONE) return MT_ERR_CORRUPT;
            if (neighbor_shown(m, sk, h, nv)) ring->neighbors[nb++] = nv;
            uint32_t f = m->he_face[h ^ 1u];
            if (face_shown(m, sk, f)) ring->faces[nf++] = f;
        } while (mt__vert_walk_step(&w));
        if (w.status != MT_OK) return w.status;
        fan.neighbor_count = (uint32_t)(nb - fan.neighbor_begin);
        fan.face_count = (uint32_t)(nf - fan.face_begin);
        if (fan.neighbor_count == 0 && fan.face_count == 0) continue;
        uint32_t keep = fan.boundary || fan.neighbor_count == 0 ? 0 : 1;
        reverse_u32(ring->neighbors + fan.neighbor_begin + keep, fan.neighbor_count - keep);
        if (fan.face_count > 0) reverse_u32(ring->faces + fan.face_begin, fan.face_count);
        ring->fans[fans++] = fan;
    }
    return w.status;
}

mt_status mt_vert_ring(const mt_mesh *mesh, uint32_t vert, mt_ring *ring)
{
    if (!mesh || !ring) return MT_ERR_INVALID_ARG;
    if (vert >= mesh->num_verts) return MT_ERR_OUT_OF_RANGE;
    const skipped sk = skipped_of(mesh);
    mt_status s = ring_count(mesh, vert, &sk, ring);
    if (s != MT_OK) return s;
    if (mt__buffer_absent(ring->neighbors, ring->neighbors_capacity) &&
        mt__buffer_absent(ring->faces, ring->faces_capacity) &&
        mt__buffer_absent(ring->fans, ring->fans_capacity))
        return MT_OK;
    if (!mt__buffer_fits(ring->neighbors, ring->neighbors_capacity, ring->num_neighbors) ||
        !mt__buffer_fits(ring->faces, ring->faces_capacity, ring->num_faces) ||
        !mt__buffer_fits(ring->fans, ring->fans_capacity, ring->num_fans))
        return MT_ERR_BUFFER_TOO_SMALL;
    return ring_fill(mesh, vert, &sk, ring);
}

/* Every caller edge at the vertex is one internal edge, except a bundle,
 * whose edges all join the same two caller vertices and are all reached from
 * this vertex's fans: a bundle counts once, at its first listed edge. */
mt_status mt_vert_valence(const mt_mesh *mesh, uint32_t vert, uint32_t *out_valence)
{
    if (!mesh || !out_valence) return MT_ERR_INVALID_ARG;
    if (vert >= mesh->num_verts) return MT_ERR_OUT_OF_RANGE;
    const skipped sk = skipped_of(mesh);
    uint32_t valence = 0;
    mt__vert_walk w;
    mt__vert_walk_begin(&w, mesh, vert);
    while (mt__vert_walk_fan(&w)) {
        do {
            const uint32_t h = w.he;
            const uint32_t e = h >> 1, b = mt__edge_bundle(mesh, e);
            /* A neighbour the ring leaves out is not counted. */
            const bool shown =
                neighbor_shown(mesh, &sk, h, mt__original_checked(mesh, mesh->he_head[h]));
            if (shown && b == MT_NONE) {
                valence++;
            } else if (shown) {
                uint32_t begin, end;
                if (!mt__bundle_range(mesh, b, &begin, &end) || begin == end) return MT_ERR_CORRUPT;
                if (mesh->bundle_edges[begin] == e) valence++;
            }
        } while (mt__vert_walk_step(&w));
    }
    if (w.status != MT_OK) return w.status;
    *out_valence = valence;
    return MT_OK;
}
