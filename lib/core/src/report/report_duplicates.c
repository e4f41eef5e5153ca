/* Report part "duplicates": valid faces that repeat an earlier face's vertex
 * cycle (same cyclic order, either direction). Two such faces share every
 * edge, so they can only be the two faces of a size-2 closed fan (opposite
 * directions; found by build_fans.c) or faces on an edge bundle (same
 * direction, or a third face on an edge): only those candidates are hashed
 * and compared. */
#include <stdlib.h>
#include <string.h>

#include "report/report_internal.h"

typedef struct keyed_face {
    uint64_t hash;
    uint32_t face;
} keyed_face;

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

static int compare_keyed(const void *pa, const void *pb)
{
    const keyed_face *a = pa, *b = pb;
    if (a->hash != b->hash) return (a->hash > b->hash) - (a->hash < b->hash);
    return (a->face > b->face) - (a->face < b->face);
}

/* Caller vertex ids of face f into out (at most cap); returns the size. */
static uint32_t face_verts(const mt_mesh *m, uint32_t f, uint32_t *out, uint32_t cap)
{
    uint32_t h = m->face_he[f], n = 0;
    do {
        if (n < cap) out[n] = mt__original(m, m->he_head[h ^ 1u]);
        n++;
        h = m->he_next[h];
    } while (h != m->face_he[f] && n < m->num_half_edges);
    return n;
}

/* Order-independent hash of a face's vertex set (sum and xor of mixed ids). */
static uint64_t face_hash(const mt_mesh *m, uint32_t f)
{
    uint64_t sum = 0, mix = 0, n = 0;
    uint32_t h = m->face_he[f];
    do {
        uint64_t x = mt__original(m, m->he_head[h ^ 1u]) * 0x9e3779b97f4a7c15ull;
        x ^= x >> 29;
        sum += x;
        mix ^= x * 0xbf58476d1ce4e5b9ull;
        n++;
        h = m->he_next[h];
    } while (h != m->face_he[f] && n < m->num_half_edges);
    return sum ^ (mix << 1) ^ n;
}

static int same_cycle(const uint32_t *a, const uint32_t *b, uint32_t n)
{
    uint32_t j = 0;
    while (j < n && b[j] != a[0]) j++;
    if (j == n) return 0;
    int forward = 1, backward = 1;
    for (uint32_t i = 0; i < n; i++) {
        forward &= a[i] == b[(j + i) % n];
        backward &= a[i] == b[(j + n - i) % n];
    }
    return forward || backward;
}

static mt_status compare_run(mt__build *b, const keyed_face *run, size_t n, mt__vec *va,
                             mt__vec *vb)
{
    const mt_mesh *m = b->m;
    for (size_t i = 1; i < n; i++) {
        uint32_t size_i = face_verts(m, run[i].face, NULL, 0);
        va->len = vb->len = 0;
        uint32_t zero = 0;
        for (uint32_t k = 0; k < size_i; k++)
            if (mt__vec_push(va, &zero) != MT_OK || mt__vec_push(vb, &zero) != MT_OK)
                return MT_ERR_NOMEM;
        face_verts(m, run[i].face, va->data, size_i);
        for (size_t j = 0; j < i; j++) {
            if (face_verts(m, run[j].face, NULL, 0) != size_i) continue;
            face_verts(m, run[j].face, vb->data, size_i);
            if (!same_cycle(va->data, vb->data, size_i)) continue;
            b->m->report.duplicate_faces++;
            if (mt__add_defect(b, MT_DEFECT_DUPLICATE_FACE, run[i].face, run[j].face, 0) != MT_OK)
                return MT_ERR_NOMEM;
            break;
        }
    }
    return MT_OK;
}

mt_status mt__report_duplicates(mt__build *b)
{
    mt_mesh *m = b->m;
    mt__vec *cand = &b->dup_candidates;
    for (uint32_t i = 0; m->bundle_offsets && i < m->bundle_offsets[m->num_bundles]; i++) {
        uint32_t e = m->bundle_edges[i];
        for (uint32_t h = 2 * e; h <= 2 * e + 1; h++)
            if (m->he_face[h] != MT_NONE && mt__vec_push(cand, &m->he_face[h]) != MT_OK)
                return MT_ERR_NOMEM;
    }
    if (cand->len < 2) return MT_OK;
    uint32_t *faces = cand->data;
    qsort(faces, cand->len, sizeof *faces, compare_u32);
    size_t unique = 0;
    for (size_t i = 0; i < cand->len; i++)
        if (unique == 0 || faces[unique - 1] != faces[i]) faces[unique++] = faces[i];
    keyed_face *keyed = mt__malloc(unique * sizeof *keyed);
    if (!keyed) return MT_ERR_NOMEM;
    for (size_t i = 0; i < unique; i++) keyed[i] = (keyed_face){face_hash(m, faces[i]), faces[i]};
    qsort(keyed, unique, sizeof *keyed, compare_keyed);
    mt__vec va = {NULL, 0, 0, sizeof(uint32_t)}, vb = {NULL, 0, 0, sizeof(uint32_t)};
    mt_status s = MT_OK;
    for (size_t i = 0; i < unique && s == MT_OK;) {
        size_t j = i;
        while (j < unique && keyed[j].hash == keyed[i].hash) j++;
        if (j - i > 1) s = compare_run(b, keyed + i, j - i, &va, &vb);
        i = j;
    }
    mt__vec_free(&va);
    mt__vec_free(&vb);
    mt__free(keyed);
    return s;
}
