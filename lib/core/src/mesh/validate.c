/* mt_mesh_validate: checks every invariant of mesh_internal.h in linear time
 * and names the first one broken with its element. Indices are range-checked
 * before anything is dereferenced through them, and each later check relies
 * only on what the earlier ones established, so a corrupted mesh is reported,
 * never read out of bounds. One temporary allocation: a bitmap over the
 * half-edges, a counter per internal vertex and a stamp per caller vertex. */
#include <string.h>

#include "mesh/mesh_internal.h"
#include "meshtopo/validate.h"

typedef struct scratch {
    uint64_t *bits; /* [bit_words] one bit per half-edge (or edge) */
    size_t bit_words;
    uint32_t *counter; /* [num_verts_internal] out-degree per internal vertex */
    uint32_t *stamp;   /* [num_verts] marks per caller vertex */
} scratch;

static void bit_set(uint64_t *bits, uint32_t i)
{
    bits[i >> 6] |= (uint64_t)1 << (i & 63);
}

static void bit_clear(uint64_t *bits, uint32_t i)
{
    bits[i >> 6] &= ~((uint64_t)1 << (i & 63));
}

static bool bit_get(const uint64_t *bits, uint32_t i)
{
    return (bits[i >> 6] >> (i & 63)) & 1u;
}

static uint32_t bundled_total(const mt_mesh *m)
{
    return m->num_bundles ? m->bundle_offsets[m->num_bundles] : 0;
}

/* Counts, and every array present that a non-zero count needs. */
static mt_status check_sizes(const mt_mesh *m, mt_diag *diag)
{
    if (m->num_half_edges % 2 != 0)
        return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE,
                        "mesh has an odd number of half-edges (%u): they must come in twins",
                        m->num_half_edges);
    if (m->num_half_edges > 0x7fffffffu)
        return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE, "mesh has %u half-edges, more than 2^31 - 1",
                        m->num_half_edges);
    if (m->num_verts > m->num_verts_internal ||
        m->num_verts_internal - m->num_verts != m->num_copies)
        return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE,
                        "mesh has %u internal vertices but %u caller vertices and %u copies",
                        m->num_verts_internal, m->num_verts, m->num_copies);
    if (m->num_half_edges > 0 && (!m->he_head || !m->he_next || !m->he_face))
        return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE,
                        "mesh has %u half-edges but a half-edge array is missing",
                        m->num_half_edges);
    if (m->num_faces > 0 && !m->face_he)
        return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE, "mesh has %u faces but no face_he array",
                        m->num_faces);
    if (m->num_verts_internal > 0 && !m->vert_he)
        return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE,
                        "mesh has %u internal vertices but no vert_he array",
                        m->num_verts_internal);
    if (m->num_copies > 0 && (!m->copy_original || !m->copies_sorted))
        return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE,
                        "mesh has %u vertex copies but a copy array is missing", m->num_copies);
    if (m->num_bundles > 0) {
        if (!m->bundle_offsets)
            return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE,
                            "mesh has %u edge bundles but no bundle_offsets", m->num_bundles);
        uint32_t total = bundled_total(m);
        if (total > 0 && (!m->bundle_edges || !m->bundled_sorted || !m->bundled_bundle))
            return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE,
                            "mesh has %u bundled edges but a bundle array is missing", total);
    }
    const mt_report *r = &m->report;
    /* The report's V leaves out the vertices an edit deleted. */
    const uint32_t deleted = m->edit ? m->edit->num_deleted_verts : 0;
    if (deleted > m->num_verts)
        return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE, "%u vertices deleted of %u", deleted,
                        m->num_verts);
    if (r->num_verts != m->num_verts - deleted || r->num_faces != m->num_faces)
        return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE,
                        "report counts %u vertices and %u faces but the mesh has %u and %u",
                        r->num_verts, r->num_faces, m->num_verts - deleted, m->num_faces);
    return MT_OK;
}

/* An edge deleted by an edit (edit.h): both heads MT_NONE. */
static bool edge_deleted(const mt_mesh *m, uint32_t h)
{
    return m->he_head[h & ~1u] == MT_NONE && m->he_head[h | 1u] == MT_NONE;
}

/* Every stored index is in range for the array it points into; a deleted
 * edge's half-edges have no face and are their own next. */
static mt_status check_ranges(const mt_mesh *m, mt_diag *diag)
{
    const uint32_t nhe = m->num_half_edges, nvi = m->num_verts_internal;
    for (uint32_t h = 0; h < nhe; h++) {
        if (edge_deleted(m, h)) {
            if (m->he_next[h] == h && m->he_face[h] == MT_NONE) continue;
            return mt__fail(diag, MT_ERR_CORRUPT, h,
                            "half-edge %u of deleted edge %u still has a next (%u) or face", h,
                            h >> 1, m->he_next[h]);
        }
        if (m->he_head[h] >= nvi)
            return mt__fail(diag, MT_ERR_CORRUPT, h,
                            "half-edge %u: head %u is not a vertex (%u internal vertices)", h,
                            m->he_head[h], nvi);
        if (m->he_next[h] >= nhe)
            return mt__fail(diag, MT_ERR_CORRUPT, h,
                            "half-edge %u: next %u is not a half-edge (%u half-edges)", h,
                            m->he_next[h], nhe);
        if (m->he_face[h] != MT_NONE && m->he_face[h] >= m->num_faces)
            return mt__fail(diag, MT_ERR_CORRUPT, h,
                            "half-edge %u: face %u is not a face record (%u faces)", h,
                            m->he_face[h], m->num_faces);
    }
    for (uint32_t f = 0; f < m->num_faces; f++)
        if (m->face_he[f] != MT_NONE && m->face_he[f] >= nhe)
            return mt__fail(diag, MT_ERR_CORRUPT, f,
                            "face %u: face_he %u is not a half-edge (%u half-edges)", f,
                            m->face_he[f], nhe);
    for (uint32_t v = 0; v < nvi; v++)
        if (m->vert_he[v] != MT_NONE && m->vert_he[v] >= nhe)
            return mt__fail(diag, MT_ERR_CORRUPT, v,
                            "vertex %u: vert_he %u is not a half-edge (%u half-edges)", v,
                            m->vert_he[v], nhe);
    for (uint32_t i = 0; i < m->num_copies; i++) {
        if (m->copy_original[i] >= m->num_verts)
            return mt__fail(diag, MT_ERR_CORRUPT, m->num_verts + i,
                            "vertex copy %u: original %u is not a caller vertex (%u vertices)",
                            m->num_verts + i, m->copy_original[i], m->num_verts);
        if (m->copies_sorted[i] < m->num_verts || m->copies_sorted[i] >= nvi)
            return mt__fail(diag, MT_ERR_CORRUPT, m->copies_sorted[i],
                            "copies_sorted[%u] = %u is not a vertex copy (copies are %u..%u)", i,
                            m->copies_sorted[i], m->num_verts, nvi - 1);
    }
    if (m->num_bundles > 0) {
        if (m->bundle_offsets[0] != 0)
            return mt__fail(diag, MT_ERR_CORRUPT, 0, "bundle 0 starts at %u, not 0",
                            m->bundle_offsets[0]);
        for (uint32_t b = 0; b < m->num_bundles; b++)
            /* Written as a difference: offsets[b] + 2 could wrap around. */
            if (m->bundle_offsets[b + 1] < m->bundle_offsets[b] ||
                m->bundle_offsets[b + 1] - m->bundle_offsets[b] < 2)
                return mt__fail(diag, MT_ERR_CORRUPT, b,
                                "bundle %u: offsets %u..%u hold fewer than 2 edges", b,
                                m->bundle_offsets[b], m->bundle_offsets[b + 1]);
        const uint32_t total = bundled_total(m), num_edges = nhe / 2;
        for (uint32_t k = 0; k < total; k++) {
            if (m->bundle_edges[k] >= num_edges)
                return mt__fail(diag, MT_ERR_CORRUPT, k,
                                "bundle_edges[%u] = %u is not an edge (%u edges)", k,
                                m->bundle_edges[k], num_edges);
            if (m->bundled_sorted[k] >= num_edges)
                return mt__fail(diag, MT_ERR_CORRUPT, k,
                                "bundled_sorted[%u] = %u is not an edge (%u edges)", k,
                                m->bundled_sorted[k], num_edges);
            if (m->bundled_bundle[k] >= m->num_bundles)
                return mt__fail(diag, MT_ERR_CORRUPT, k,
                                "bundled_bundle[%u] = %u is not a bundle (%u bundles)", k,
                                m->bundled_bundle[k], m->num_bundles);
        }
    }
    if (m->vert_component) {
        const uint32_t cc = m->report.connected_components;
        for (uint32_t v = 0; v < nvi; v++) {
            uint32_t c = m->vert_component[v];
            if (c < cc || (c == MT_NONE && m->vert_he[v] == MT_NONE)) continue;
            return mt__fail(diag, MT_ERR_CORRUPT, v,
                            "vertex %u: component %u is not a component (%u components)", v, c, cc);
        }
    }
    return MT_OK;
}

/* next is a permutation: no half-edge is the next of two. With as many
 * targets as half-edges, that makes every half-edge some next exactly once.
 * Leaves every bit set. */
static mt_status check_next_permutation(const mt_mesh *m, scratch *s, mt_diag *diag)
{
    memset(s->bits, 0, s->bit_words * sizeof *s->bits);
    for (uint32_t h = 0; h < m->num_half_edges; h++) {
        uint32_t n = m->he_next[h];
        if (!bit_get(s->bits, n)) {
            bit_set(s->bits, n);
            continue;
        }
        uint32_t first = 0;
        while (first < h && m->he_next[first] != n) first++;
        return mt__fail(diag, MT_ERR_CORRUPT, n,
                        "half-edge %u is the next of both %u and %u: next is not a permutation", n,
                        first, h);
    }
    return MT_OK;
}

/* Per half-edge: rings are continuous (next(h) starts where h ends) and
 * uniform (one face, or none, all the way round); edges join two caller
 * vertices, first half-edge from the smaller id to the larger; both ends of
 * an edge lie in one component. */
static mt_status check_half_edges(const mt_mesh *m, mt_diag *diag)
{
    for (uint32_t h = 0; h < m->num_half_edges; h++) {
        if (edge_deleted(m, h)) continue;
        const uint32_t n = m->he_next[h];
        const uint32_t head = m->he_head[h], next_tail = m->he_head[n ^ 1u];
        if (next_tail != head)
            return mt__fail(diag, MT_ERR_CORRUPT, h,
                            "half-edge %u: next(%u)=%u starts at vertex %u but %u ends at "
                            "vertex %u",
                            h, h, n, next_tail, h, head);
        if (m->he_face[n] != m->he_face[h])
            return mt__fail(diag, MT_ERR_CORRUPT, h,
                            "half-edge %u: face %lld but its next %u has face %lld: a ring "
                            "must have one face (or none) all the way round",
                            h, m->he_face[h] == MT_NONE ? -1ll : (long long)m->he_face[h], n,
                            m->he_face[n] == MT_NONE ? -1ll : (long long)m->he_face[n]);
        if (h & 1u) continue;
        const uint32_t e = h >> 1, tail = m->he_head[h ^ 1u];
        const uint32_t from = mt__original(m, tail), to = mt__original(m, head);
        if (from == to)
            return mt__fail(diag, MT_ERR_CORRUPT, e,
                            "edge %u: both half-edges point at caller vertex %u (vertices %u "
                            "and %u); an edge must join two vertices",
                            e, from, tail, head);
        if (from > to)
            return mt__fail(diag, MT_ERR_CORRUPT, e,
                            "edge %u: half-edge %u runs from caller vertex %u to %u; the first "
                            "half-edge of an edge must run from the smaller id to the larger",
                            e, h, from, to);
        if (m->he_face[h] == MT_NONE && m->he_face[h ^ 1u] == MT_NONE)
            return mt__fail(diag, MT_ERR_CORRUPT, e, "edge %u has no face on either side", e);
        if (m->vert_component && m->vert_component[tail] != m->vert_component[head])
            return mt__fail(diag, MT_ERR_CORRUPT, e,
                            "edge %u joins vertex %u (component %u) and vertex %u "
                            "(component %u)",
                            e, tail, m->vert_component[tail], head, m->vert_component[head]);
    }
    return MT_OK;
}

/* Each kept face's half-edge names it, its ring has at least three
 * half-edges with distinct caller vertices, and every half-edge naming a face
 * lies on that face's ring. Expects every bit set; clears the face rings. */
static mt_status check_faces(const mt_mesh *m, scratch *s, mt_diag *diag)
{
    uint32_t *stamp = s->stamp; /* stamp[caller vertex] = face + 1 */
    memset(stamp, 0, (size_t)m->num_verts * sizeof *stamp);
    uint32_t kept = 0;
    for (uint32_t f = 0; f < m->num_faces; f++) {
        const uint32_t start = m->face_he[f];
        if (start == MT_NONE) continue;
        kept++;
        if (m->he_face[start] != f)
            return mt__fail(diag, MT_ERR_CORRUPT, f,
                            "face %u: face_he[%u]=%u but half-edge %u names face %lld", f, f, start,
                            start,
                            m->he_face[start] == MT_NONE ? -1ll : (long long)m->he_face[start]);
        uint32_t h = start, len = 0;
        do {
            const uint32_t v = mt__original(m, m->he_head[h ^ 1u]);
            if (stamp[v] == f + 1)
                return mt__fail(diag, MT_ERR_CORRUPT, f,
                                "face %u: caller vertex %u appears twice in its ring", f, v);
            stamp[v] = f + 1;
            bit_clear(s->bits, h);
            h = m->he_next[h];
            len++;
        } while (h != start && len <= m->num_half_edges);
        if (len < 3)
            return mt__fail(diag, MT_ERR_CORRUPT, f,
                            "face %u: its ring has %u half-edge%s, fewer than 3", f, len,
                            len == 1 ? "" : "s");
    }
    if (kept != m->report.num_faces_valid)
        return mt__fail(diag, MT_ERR_CORRUPT, MT_NONE,
                        "mesh keeps %u faces but the report counts %u valid faces", kept,
                        m->report.num_faces_valid);
    for (uint32_t h = 0; h < m->num_half_edges; h++) {
        const uint32_t f = m->he_face[h];
        if (f == MT_NONE || !bit_get(s->bits, h)) continue;
        if (m->face_he[f] == MT_NONE)
            return mt__fail(diag, MT_ERR_CORRUPT, h,
                            "half-edge %u names face %u, a rejected face record", h, f);
        return mt__fail(diag, MT_ERR_CORRUPT, h,
                        "half-edge %u names face %u but is not on the ring of face_he[%u]=%u", h, f,
                        f, m->face_he[f]);
    }
    return MT_OK;
}

/* copies_sorted is strictly ascending by (original, id): with every entry a
 * copy id (checked earlier) that makes it a permutation of the copies, and
 * mt__vert_copies finds every copy under its original. */
static mt_status check_copies(const mt_mesh *m, mt_diag *diag)
{
    for (uint32_t k = 1; k < m->num_copies; k++) {
        const uint32_t a = m->copies_sorted[k - 1], b = m->copies_sorted[k];
        const uint32_t oa = mt__original(m, a), ob = mt__original(m, b);
        if (oa < ob || (oa == ob && a < b)) continue;
        return mt__fail(diag, MT_ERR_CORRUPT, b,
                        "copies_sorted[%u]=%u (copy of %u) does not follow copies_sorted[%u]=%u "
                        "(copy of %u) in (original, id) order",
                        k, b, ob, k - 1, a, oa);
    }
    return MT_OK;
}

/* Each bundle's edges are distinct and join the same two caller vertices,
 * bundled_sorted is strictly ascending and maps each of them back to its
 * bundle (same size as bundle_edges, so it lists exactly those edges). */
static mt_status check_bundles(const mt_mesh *m, scratch *s, mt_diag *diag)
{
    const uint32_t total = bundled_total(m);
    for (uint32_t k = 1; k < total; k++)
        if (m->bundled_sorted[k] <= m->bundled_sorted[k - 1])
            return mt__fail(diag, MT_ERR_CORRUPT, k,
                            "bundled_sorted[%u]=%u does not follow bundled_sorted[%u]=%u in "
                            "ascending order",
                            k, m->bundled_sorted[k], k - 1, m->bundled_sorted[k - 1]);
    memset(s->bits, 0, s->bit_words * sizeof *s->bits);
    for (uint32_t b = 0; b < m->num_bundles; b++) {
        const uint32_t e0 = m->bundle_edges[m->bundle_offsets[b]];
        const uint32_t a = mt__original(m, m->he_head[2 * e0 + 1]);
        const uint32_t c = mt__original(m, m->he_head[2 * e0]);
        for (uint32_t k = m->bundle_offsets[b]; k < m->bundle_offsets[b + 1]; k++) {
            const uint32_t e = m->bundle_edges[k];
            if (bit_get(s->bits, e))
                return mt__fail(diag, MT_ERR_CORRUPT, e, "edge %u is listed twice in bundles", e);
            bit_set(s->bits, e);
            const uint32_t ea = mt__original(m, m->he_head[2 * e + 1]);
            const uint32_t ec = mt__original(m, m->he_head[2 * e]);
            if (ea != a || ec != c)
                return mt__fail(diag, MT_ERR_CORRUPT, e,
                                "bundle %u: edge %u joins caller vertices %u-%u but edge %u "
                                "joins %u-%u",
                                b, e, ea, ec, e0, a, c);
            if (mt__edge_bundle(m, e) != b)
                return mt__fail(diag, MT_ERR_CORRUPT, e,
                                "bundle %u: edge %u is not found under that bundle in "
                                "bundled_sorted",
                                b, e);
        }
    }
    return MT_OK;
}

/* The fan of internal vertex u (a fan of caller vertex v): its outgoing
 * half-edge starts at it, one rotation from there visits all `degree`
 * half-edges leaving u, the first being u's only boundary half-edge when it
 * has one; a copy holds a fan. Stamps the caller vertices reached by
 * non-bundled edges with v + 1, failing on one reached twice (a caller edge
 * outside a bundle has one internal edge), and notes bundled edges. */
static mt_status check_fan(const mt_mesh *m, uint32_t u, uint32_t v, uint32_t degree,
                           uint32_t *stamp, bool *out_bundled, mt_diag *diag)
{
    const uint32_t start = m->vert_he[u];
    if (start == MT_NONE) {
        if (degree != 0)
            return mt__fail(diag, MT_ERR_CORRUPT, u,
                            "vertex %u has %u outgoing half-edges but no vert_he", u, degree);
        if (u >= m->num_verts)
            return mt__fail(diag, MT_ERR_CORRUPT, u,
                            "vertex copy %u (of caller vertex %u) holds no fan", u, v);
        return MT_OK;
    }
    const uint32_t tail = m->he_head[start ^ 1u];
    if (tail != u)
        return mt__fail(diag, MT_ERR_CORRUPT, u,
                        "vertex %u: vert_he[%u]=%u starts at vertex %u, not at %u", u, u, start,
                        tail, u);
    const bool start_boundary = m->he_face[start] == MT_NONE;
    uint32_t h = start, len = 0;
    do {
        if (h != start && m->he_face[h] == MT_NONE) {
            if (!start_boundary)
                return mt__fail(diag, MT_ERR_CORRUPT, u,
                                "vertex %u has boundary half-edge %u but vert_he[%u]=%u is not "
                                "a boundary half-edge",
                                u, h, u, start);
            return mt__fail(diag, MT_ERR_CORRUPT, u,
                            "vertex %u: its fan holds two boundary half-edges, %u and %u", u, start,
                            h);
        }
        if (mt__edge_bundle(m, h >> 1) != MT_NONE) {
            *out_bundled = true;
        } else {
            const uint32_t w = mt__original(m, m->he_head[h]);
            if (stamp[w] == v + 1)
                return mt__fail(diag, MT_ERR_CORRUPT, h >> 1,
                                "caller edge %u-%u is held by several internal edges (%u "
                                "among them) but not by a bundle",
                                v, w, h >> 1);
            stamp[w] = v + 1;
        }
        len++;
        h = m->he_next[h ^ 1u];
    } while (h != start && len <= degree);
    if (len != degree)
        return mt__fail(diag, MT_ERR_CORRUPT, u,
                        "vertex %u: one rotation from vert_he[%u]=%u visits %u of its %u "
                        "outgoing half-edges",
                        u, u, start, len, degree);
    return MT_OK;
}

/* A bundled edge of caller vertex v must not join it to a vertex that a
 * non-bundled edge already reaches (stamped by check_fan). */
static mt_status check_bundled_fan(const mt_mesh *m, uint32_t u, uint32_t v, const uint32_t *stamp,
                                   mt_diag *diag)
{
    const uint32_t start = m->vert_he[u];
    if (start == MT_NONE) return MT_OK;
    uint32_t h = start, steps = 0;
    do {
        const uint32_t w = mt__original(m, m->he_head[h]);
        if (stamp[w] == v + 1 && mt__edge_bundle(m, h >> 1) != MT_NONE)
            return mt__fail(diag, MT_ERR_CORRUPT, h >> 1,
                            "caller edge %u-%u is held by bundled edge %u and by an edge "
                            "outside the bundle",
                            v, w, h >> 1);
        h = m->he_next[h ^ 1u];
    } while (h != start && ++steps < m->num_half_edges);
    return MT_OK;
}

/* Every internal vertex, visited as one of the fans of its caller vertex
 * (the copies come from copies_sorted, checked before). */
static mt_status check_vertices(const mt_mesh *m, scratch *s, mt_diag *diag)
{
    uint32_t *out_degree = s->counter;
    memset(out_degree, 0, (size_t)m->num_verts_internal * sizeof *out_degree);
    memset(s->stamp, 0, (size_t)m->num_verts * sizeof *s->stamp);
    for (uint32_t h = 0; h < m->num_half_edges; h++)
        if (!edge_deleted(m, h)) out_degree[m->he_head[h ^ 1u]]++;
    for (uint32_t v = 0; v < m->num_verts; v++) {
        const uint32_t *copies;
        const uint32_t num_copies = mt__vert_copies(m, v, &copies);
        bool bundled = false;
        for (uint32_t i = 0; i <= num_copies; i++) {
            const uint32_t u = i == 0 ? v : copies[i - 1];
            mt_status st = check_fan(m, u, v, out_degree[u], s->stamp, &bundled, diag);
            if (st != MT_OK) return st;
        }
        for (uint32_t i = 0; bundled && i <= num_copies; i++) {
            mt_status st = check_bundled_fan(m, i == 0 ? v : copies[i - 1], v, s->stamp, diag);
            if (st != MT_OK) return st;
        }
    }
    return MT_OK;
}

mt_status mt_mesh_validate(const mt_mesh *mesh, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!mesh) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "validate: mesh is NULL");
    mt_status st = check_sizes(mesh, diag);
    if (st == MT_OK) st = check_ranges(mesh, diag);
    if (st != MT_OK) return st;

    scratch s;
    s.bit_words = ((size_t)mesh->num_half_edges + 63) / 64;
    const size_t bit_bytes = s.bit_words * sizeof(uint64_t);
    const size_t counter_bytes = (size_t)mesh->num_verts_internal * sizeof(uint32_t);
    const size_t stamp_bytes = (size_t)mesh->num_verts * sizeof(uint32_t);
    unsigned char *block = mt__malloc(bit_bytes + counter_bytes + stamp_bytes);
    if (!block)
        return mt__fail(diag, MT_ERR_NOMEM, MT_NONE,
                        "validate: cannot allocate %zu bytes of scratch",
                        bit_bytes + counter_bytes + stamp_bytes);
    s.bits = (uint64_t *)block;
    s.counter = (uint32_t *)(block + bit_bytes);
    s.stamp = (uint32_t *)(block + bit_bytes + counter_bytes);

    st = check_next_permutation(mesh, &s, diag);
    if (st == MT_OK) st = check_half_edges(mesh, diag);
    if (st == MT_OK) st = check_faces(mesh, &s, diag);
    if (st == MT_OK) st = check_copies(mesh, diag);
    if (st == MT_OK) st = check_bundles(mesh, &s, diag);
    if (st == MT_OK) st = check_vertices(mesh, &s, diag);
    mt__free(block);
    return st;
}
