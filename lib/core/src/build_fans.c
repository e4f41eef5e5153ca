/* Build phase "fans": completes each vertex. For every vertex the outgoing
 * half-edges (its bucket from build_edges.c) are rotated with
 * r(h) = next(twin(h)). The usual vertex has one fan: a closed cycle, or an
 * open one from its boundary half-edge to the face half-edge whose twin is a
 * boundary half-edge; that boundary half-edge's next is then set, closing
 * the boundary ring through the vertex. A vertex with several fans (a
 * bowtie, or the sheets meeting at a non-manifold edge) keeps its first fan
 * and gets one new internal vertex, a copy, per further fan, so that every
 * internal vertex has exactly one fan (Botsch et al., "Polygon Mesh
 * Processing", 2010, section 2.2: non-manifold vertices split per fan). */
#include <stdlib.h>
#include <string.h>

#include "build_internal.h"

static int compare_u64(const void *pa, const void *pb)
{
    uint64_t a = *(const uint64_t *)pa, b = *(const uint64_t *)pb;
    return (a > b) - (a < b);
}

/* Position of half-edge h among the vertex's outgoing half-edges, from the
 * sorted (half-edge << 32 | position) keys. */
static uint32_t local_index(const uint64_t *keys, uint32_t n, uint32_t h)
{
    uint32_t lo = 0, hi = n;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if ((uint32_t)(keys[mid] >> 32) < h)
            lo = mid + 1;
        else
            hi = mid;
    }
    return (uint32_t)keys[lo];
}

/* A new internal vertex for a further fan of `original`. */
static mt_status new_copy(mt__build *b, uint32_t original, uint32_t *out_vert)
{
    mt_mesh *m = b->m;
    if (m->num_verts_internal >= UINT32_MAX - 1) return MT_ERR_TOO_LARGE;
    if (m->num_verts_internal == b->vert_capacity) {
        uint32_t cap = b->vert_capacity + b->vert_capacity / 4 + 16;
        if (cap < b->vert_capacity || cap >= UINT32_MAX) cap = UINT32_MAX - 1;
        uint32_t *grown = mt__realloc(m->vert_he, (size_t)cap * sizeof(uint32_t));
        if (!grown) return MT_ERR_NOMEM;
        m->vert_he = grown;
        b->vert_capacity = cap;
    }
    if (mt__vec_push(&b->copy_original, &original) != MT_OK) return MT_ERR_NOMEM;
    *out_vert = m->num_verts_internal++;
    m->vert_he[*out_vert] = MT_NONE;
    return MT_OK;
}

/* The general case: several fans at vertex v (or a fan that does not cover
 * all outgoing half-edges). hs[0..n) are its outgoing face half-edges. */
static mt_status split_fans(mt__build *b, uint32_t v, const uint32_t *hs, uint32_t n,
                            uint64_t *keys, uint8_t *flags)
{
    mt_mesh *m = b->m;
    uint32_t *he_next = m->he_next, *he_head = m->he_head;
    const uint32_t *he_face = m->he_face;
    enum { HAS_PRED = 1, USED = 2 };
    for (uint32_t i = 0; i < n; i++) {
        keys[i] = ((uint64_t)hs[i] << 32) | i;
        flags[i] = 0;
    }
    qsort(keys, n, sizeof *keys, compare_u64);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t t = hs[i] ^ 1u;
        if (he_face[t] != MT_NONE) flags[local_index(keys, n, he_next[t])] |= HAS_PRED;
    }
    if (mt__vec_push(&b->split_verts, &v) != MT_OK) return MT_ERR_NOMEM;
    uint32_t fans = 0;
    /* Open fans first (they start where no rotation leads), then cycles. */
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t i = 0; i < n; i++) {
            if ((flags[i] & USED) || (pass == 0 && (flags[i] & HAS_PRED))) continue;
            uint32_t vert = v;
            if (fans++ > 0 && new_copy(b, v, &vert) != MT_OK) return MT_ERR_NOMEM;
            uint32_t start_he = hs[i], count = 0;
            if (pass == 0) {
                uint32_t b_out = mt__he_prev(m, hs[i]) ^ 1u;
                he_head[b_out ^ 1u] = vert;
                start_he = b_out;
            }
            uint32_t j = i;
            for (;;) {
                flags[j] |= USED;
                count++;
                uint32_t t = hs[j] ^ 1u;
                he_head[t] = vert;
                if (he_face[t] == MT_NONE) {
                    he_next[t] = start_he; /* close the boundary ring */
                    break;
                }
                j = local_index(keys, n, he_next[t]);
                if (flags[j] & USED) break; /* back at the start of a cycle */
            }
            m->vert_he[vert] = start_he;
            if (pass == 1 && count == 2) {
                uint32_t pair[2] = {he_face[hs[i]], he_face[he_next[hs[i] ^ 1u]]};
                if (mt__vec_push(&b->dup_candidates, &pair[0]) != MT_OK ||
                    mt__vec_push(&b->dup_candidates, &pair[1]) != MT_OK)
                    return MT_ERR_NOMEM;
            }
        }
    }
    return MT_OK;
}

mt_status mt__build_fans(mt__build *b)
{
    mt_mesh *m = b->m;
    const uint64_t *bucket = b->bucket;
    uint32_t *he_next = m->he_next;
    const uint32_t *he_face = m->he_face;
    size_t scratch_bytes;
    const size_t per = 2 * sizeof(uint32_t) + sizeof(uint64_t) + 1;
    if (!mt__mul_size((size_t)b->max_degree + 1, per, &scratch_bytes)) return MT_ERR_NOMEM;
    uint32_t *hs = mt__malloc(scratch_bytes);
    if (!hs) return MT_ERR_NOMEM;
    uint64_t *keys = (uint64_t *)(hs + 2 * ((size_t)b->max_degree + 1));
    uint8_t *flags = (uint8_t *)(keys + b->max_degree + 1);

    /* bucket_start was freed; walk the buckets by counting: the bucket is
     * sorted by tail, and each entry's tail is the twin's head. */
    mt_status status = MT_OK;
    uint64_t pos = 0;
    const uint64_t total = b->num_corners;
    const uint32_t *he_head = m->he_head;
    while (pos < total && status == MT_OK) {
        const uint32_t first = (uint32_t)bucket[pos] & ~MT__FLAG;
        const uint32_t v = he_head[first ^ 1u];
        uint32_t n = 0, boundary_in = 0;
        while (pos < total) {
            uint32_t h = (uint32_t)bucket[pos] & ~MT__FLAG;
            if (he_head[h ^ 1u] != v) break;
            hs[n++] = h;
            boundary_in += he_face[h ^ 1u] == MT_NONE;
            pos++;
        }
        int single = 0;
        if (boundary_in == 0) {
            uint32_t h = he_next[hs[0] ^ 1u], steps = 1;
            while (h != hs[0] && steps < n) h = he_next[h ^ 1u], steps++;
            single = h == hs[0] && steps == n;
            if (single) {
                m->vert_he[v] = hs[0];
                if (n == 2 && (mt__vec_push(&b->dup_candidates, &he_face[hs[0]]) != MT_OK ||
                               mt__vec_push(&b->dup_candidates, &he_face[hs[1]]) != MT_OK))
                    status = MT_ERR_NOMEM;
            }
        } else if (boundary_in == 1) {
            const uint32_t b_out = m->vert_he[v];
            uint32_t h = he_next[b_out ^ 1u], steps = 1;
            while (he_face[h ^ 1u] != MT_NONE && steps < n) h = he_next[h ^ 1u], steps++;
            single = he_face[h ^ 1u] == MT_NONE && steps == n;
            if (single) he_next[h ^ 1u] = b_out;
        }
        if (!single && status == MT_OK) status = split_fans(b, v, hs, n, keys, flags);
    }
    mt__free(hs);
    if (status != MT_OK) return status;

    /* Publish the copies: originals plus the order used to look them up. */
    m->num_copies = (uint32_t)b->copy_original.len;
    if (m->num_copies) {
        m->copy_original = b->copy_original.data;
        b->copy_original.data = NULL;
        b->copy_original.len = b->copy_original.cap = 0;
        m->copies_sorted = mt__malloc((size_t)m->num_copies * sizeof(uint32_t));
        if (!m->copies_sorted) return MT_ERR_NOMEM;
        /* Copies are made vertex by vertex in ascending order, so they are
         * already sorted by (original, id). */
        for (uint32_t i = 0; i < m->num_copies; i++) m->copies_sorted[i] = m->num_verts + i;
    }
    return MT_OK;
}
