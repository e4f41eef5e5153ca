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

/* Outgoing half-edges up to which an open fan is checked in place; a larger
 * boundary vertex goes through split_fans, which sorts. */
#define MT__FAN_SCAN_LIMIT 16

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
                            uint64_t *keys, uint8_t *flags, uint32_t *out_fans)
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
    *out_fans = fans;
    return MT_OK;
}

/* Start of v's single open fan among hs[0..n): the half-edge no rotation
 * leads to. MT_NONE when there is none (several fans or a corrupt ring). */
static uint32_t open_fan_start(const mt_mesh *m, const uint32_t *hs, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        uint32_t j = 0;
        for (; j < n; j++) {
            uint32_t t = hs[j] ^ 1u;
            if (m->he_face[t] != MT_NONE && m->he_next[t] == hs[i]) break;
        }
        if (j == n) return hs[i];
    }
    return MT_NONE;
}

/* The usual vertex: one fan. Returns 0 when v needs split_fans. */
static int single_fan(mt__build *b, mt__part *p, uint32_t v, const uint32_t *hs, uint32_t n,
                      uint32_t boundary_in)
{
    mt_mesh *m = b->m;
    uint32_t *he_next = m->he_next;
    const uint32_t *he_face = m->he_face;
    if (boundary_in == 0) {
        uint32_t h = he_next[hs[0] ^ 1u], steps = 1;
        while (h != hs[0] && steps < n) h = he_next[h ^ 1u], steps++;
        if (h != hs[0] || steps != n) return 0;
        m->vert_he[v] = hs[0];
        if (n == 2 && (mt__vec_push(&p->dup_candidates, &he_face[hs[0]]) != MT_OK ||
                       mt__vec_push(&p->dup_candidates, &he_face[hs[1]]) != MT_OK))
            p->status = MT_ERR_NOMEM;
        return 1;
    }
    if (boundary_in != 1 || n > MT__FAN_SCAN_LIMIT) return 0;
    const uint32_t first = open_fan_start(m, hs, n);
    if (first == MT_NONE) return 0;
    uint32_t h = first, steps = 1;
    while (he_face[h ^ 1u] != MT_NONE && steps < n) h = he_next[h ^ 1u], steps++;
    if (he_face[h ^ 1u] != MT_NONE || steps != n) return 0;
    const uint32_t b_out = mt__he_prev(m, first) ^ 1u;
    he_next[h ^ 1u] = b_out; /* close the boundary ring through v */
    m->vert_he[v] = b_out;
    return 1;
}

/* Copies the half-edges of v's bucket into hs; returns how many. */
static uint32_t outgoing(const mt__build *b, uint32_t v, uint32_t *hs)
{
    const mt__side *side = b->bucket + b->bucket_start[v];
    const uint32_t n = b->bucket_start[v + 1] - b->bucket_start[v];
    for (uint32_t i = 0; i < n; i++) hs[i] = side[i].item;
    return n;
}

static void fans_part(mt__build *b, uint32_t t)
{
    mt__part *p = &b->part[t];
    mt_mesh *m = b->m;
    uint32_t *he_head = m->he_head;
    const uint32_t *he_face = m->he_face;
    uint32_t *hs = mt__malloc(((size_t)b->max_degree + 1) * sizeof(uint32_t));
    if (!hs) {
        p->status = MT_ERR_NOMEM;
        return;
    }
    for (uint32_t v = p->vert_begin; v < p->vert_end && p->status == MT_OK; v++) {
        const uint32_t n = outgoing(b, v, hs);
        if (n == 0) continue;
        uint32_t boundary_in = 0;
        for (uint32_t i = 0; i < n; i++) {
            uint32_t twin = hs[i] ^ 1u;
            if (he_face[twin] != MT_NONE) continue;
            he_head[twin] = v; /* a boundary half-edge into v: v's to set */
            boundary_in++;
            if (mt__vec_push(&p->boundary_halves, &twin) != MT_OK) p->status = MT_ERR_NOMEM;
        }
        if (!single_fan(b, p, v, hs, n, boundary_in) && mt__vec_push(&p->split_verts, &v) != MT_OK)
            p->status = MT_ERR_NOMEM;
    }
    mt__free(hs);
}

mt_status mt__build_fans(mt__build *b)
{
    mt__parallel_run(b, fans_part);
    for (uint32_t t = 0; t < b->parts; t++) {
        mt__part *p = &b->part[t];
        if (p->status != MT_OK) return p->status;
        if (mt__vec_append(&b->boundary_halves, &p->boundary_halves) != MT_OK ||
            mt__vec_append(&b->split_verts, &p->split_verts) != MT_OK ||
            mt__vec_append(&b->dup_candidates, &p->dup_candidates) != MT_OK)
            return MT_ERR_NOMEM;
    }
    /* The general case, rare and done on one thread: it makes new vertices. */
    mt_status status = MT_OK;
    if (b->split_verts.len) {
        size_t scratch_bytes;
        const size_t per = sizeof(uint64_t) + sizeof(uint32_t) + 1;
        if (!mt__mul_size((size_t)b->max_degree + 1, per, &scratch_bytes)) return MT_ERR_NOMEM;
        uint64_t *keys = mt__malloc(scratch_bytes);
        if (!keys) return MT_ERR_NOMEM;
        uint32_t *hs = (uint32_t *)(keys + b->max_degree + 1);
        uint8_t *flags = (uint8_t *)(hs + b->max_degree + 1);
        mt__vec candidates = b->split_verts;
        b->split_verts = (mt__vec){NULL, 0, 0, sizeof(uint32_t)};
        const uint32_t *verts = candidates.data;
        for (size_t i = 0; i < candidates.len && status == MT_OK; i++) {
            uint32_t v = verts[i], fans = 0;
            const uint32_t n = outgoing(b, v, hs);
            status = split_fans(b, v, hs, n, keys, flags, &fans);
            if (status == MT_OK && fans > 1 && mt__vec_push(&b->split_verts, &v) != MT_OK)
                status = MT_ERR_NOMEM;
        }
        mt__vec_free(&candidates);
        mt__free(keys);
    }
    if (status != MT_OK) return status;

    /* Publish the copies: originals plus the order used to look them up. */
    mt_mesh *m = b->m;
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
