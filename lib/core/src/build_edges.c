/* Build phase "edges": twin matching in linear time. The corners (face sides
 * a -> b) are counting-sorted by tail vertex a; then, vertex by vertex, each
 * side's group {a, b} is gathered from the buckets of a and b, and paired:
 * each a -> b side with one b -> a side becomes an internal edge, every side
 * left over gets an edge of its own with a boundary twin. A group that needs
 * more than one internal edge (used by more than two faces, or by two faces
 * running the same way) is recorded as a bundle. Edge ids are handed out in
 * tail-vertex order, so half-edges of nearby vertices sit nearby in memory. */
#include <string.h>

#include "build_internal.h"

/* Bucket entries between a prefetch and its use. */
#define MT__PREFETCH_DISTANCE 16

/* Exclusive prefix sum of the per-vertex counts, then the scatter. */
static void sort_corners_by_tail(mt__build *b)
{
    const mt_face_list *in = b->in;
    const uint32_t nv = in->num_verts;
    uint32_t *start = b->bucket_start;
    uint32_t sum = 0, max_degree = 0;
    for (uint32_t v = 0; v < nv; v++) {
        uint32_t d = start[v];
        if (d > max_degree) max_degree = d;
        start[v] = sum;
        sum += d;
    }
    start[nv] = sum;
    b->max_degree = max_degree;

    const uint32_t *sizes = in->face_sizes;
    const uint32_t *indices = in->face_indices;
    const uint32_t *face_he = b->m->face_he;
    uint64_t *bucket = b->bucket;
    uint32_t offset = 0;
    for (uint32_t f = 0; f < in->num_faces; f++) {
        const uint32_t n = sizes[f];
        if (face_he[f] == MT_NONE) {
            offset += n;
            continue;
        }
        const uint32_t *idx = indices + offset;
        for (uint32_t i = 0; i + 1 < n; i++)
            bucket[start[idx[i]]++] = ((uint64_t)idx[i + 1] << 32) | (offset + i);
        bucket[start[idx[n - 1]]++] = ((uint64_t)idx[0] << 32) | (offset + n - 1);
        offset += n;
    }
    /* start[v] now holds the end of v's bucket: shift back to starts. */
    for (uint32_t v = nv; v > 0; v--) start[v] = start[v - 1];
    start[0] = 0;
}

static mt_status record_group(mt__build *b, uint32_t a, uint32_t bv, uint32_t na, uint32_t nb,
                              uint32_t first_edge)
{
    const uint32_t uses = na + nb;
    b->num_edges++;
    if (uses < MT__SMALL_USES)
        b->use_hist[uses]++;
    else if (mt__vec_push(&b->large_uses, &uses) != MT_OK)
        return MT_ERR_NOMEM;
    if (uses == 1) {
        b->boundary_edges++;
        return MT_OK;
    }
    if (uses == 2 && na == 1) return MT_OK; /* the common manifold case */
    uint32_t lo = a < bv ? a : bv, hi = a < bv ? bv : a;
    if (uses > 2) {
        b->nonmanifold_edges++;
        if (mt__add_defect(b, MT_DEFECT_NONMANIFOLD_EDGE, lo, hi, uses) != MT_OK)
            return MT_ERR_NOMEM;
    }
    if (na >= 2 || nb >= 2) {
        b->duplicate_directed_edges++;
        if (uses == 2) b->inconsistent_edges++;
        if (na >= 2 && mt__add_defect(b, MT_DEFECT_SAME_DIRECTION_EDGE, a, bv, na) != MT_OK)
            return MT_ERR_NOMEM;
        if (nb >= 2 && mt__add_defect(b, MT_DEFECT_SAME_DIRECTION_EDGE, bv, a, nb) != MT_OK)
            return MT_ERR_NOMEM;
    }
    uint32_t count = na > nb ? na : nb;
    if (count > 1) {
        uint32_t start = (uint32_t)b->bundle_edges.len;
        if (mt__vec_push(&b->bundle_offsets, &start) != MT_OK) return MT_ERR_NOMEM;
        for (uint32_t e = first_edge; e < first_edge + count; e++)
            if (mt__vec_push(&b->bundle_edges, &e) != MT_OK) return MT_ERR_NOMEM;
    }
    return MT_OK;
}

/* Pairs the sides of one group. pos_a / pos_b are bucket positions of the
 * a -> b and b -> a sides. Half-edge 2e points from the smaller vertex id. */
static void pair_group(mt__build *b, uint32_t a, uint32_t bv, const uint32_t *pos_a, uint32_t na,
                       const uint32_t *pos_b, uint32_t nb)
{
    uint64_t *bucket = b->bucket;
    uint32_t *c2h = b->c2h;
    const uint32_t count = na > nb ? na : nb;
    const uint32_t a_low = a < bv ? 0u : 1u;
    for (uint32_t k = 0; k < count; k++) {
        const uint32_t e = b->num_internal_edges++;
        if (k < na) {
            uint32_t h = 2 * e + a_low;
            uint64_t entry = bucket[pos_a[k]];
            c2h[(uint32_t)entry] = h | (k >= nb ? MT__FLAG : 0u);
            bucket[pos_a[k]] = (entry & 0xffffffff00000000ull) | h | MT__FLAG;
        }
        if (k < nb) {
            uint32_t h = 2 * e + (1u - a_low);
            uint64_t entry = bucket[pos_b[k]];
            c2h[(uint32_t)entry] = h | (k >= na ? MT__FLAG : 0u);
            bucket[pos_b[k]] = (entry & 0xffffffff00000000ull) | h | MT__FLAG;
        }
    }
}

mt_status mt__build_edges(mt__build *b)
{
    sort_corners_by_tail(b);
    const uint32_t nv = b->in->num_verts;
    const uint32_t *start = b->bucket_start;
    uint64_t *bucket = b->bucket;
    size_t scratch_bytes;
    if (!mt__mul_size((size_t)b->max_degree + 1, 2 * sizeof(uint32_t), &scratch_bytes))
        return MT_ERR_NOMEM;
    uint32_t *pos_a = mt__malloc(scratch_bytes);
    if (!pos_a) return MT_ERR_NOMEM;
    uint32_t *pos_b = pos_a + b->max_degree + 1;
    mt_status status = MT_OK;
    for (uint32_t a = 0; a < nv && status == MT_OK; a++) {
        const uint32_t end_a = start[a + 1];
        for (uint32_t i = start[a]; i < end_a; i++) {
            /* The twin sides sit in another vertex's bucket, at random in a
             * scan-ordered mesh: fetch those ahead of use. */
            if (i + MT__PREFETCH_DISTANCE < b->num_corners) {
                uint32_t ahead = (uint32_t)(bucket[i + MT__PREFETCH_DISTANCE] >> 32);
                __builtin_prefetch(&start[ahead]);
                uint32_t near = (uint32_t)(bucket[i + MT__PREFETCH_DISTANCE / 2] >> 32);
                __builtin_prefetch(&bucket[start[near]]);
            }
            const uint64_t entry = bucket[i];
            if ((uint32_t)entry & MT__FLAG) continue;
            const uint32_t bv = (uint32_t)(entry >> 32);
            uint32_t na = 0, nb = 0;
            pos_a[na++] = i;
            for (uint32_t j = i + 1; j < end_a; j++)
                if ((uint32_t)(bucket[j] >> 32) == bv) pos_a[na++] = j;
            const uint32_t end_b = start[bv + 1];
            for (uint32_t j = start[bv]; j < end_b; j++)
                if ((uint32_t)(bucket[j] >> 32) == a) pos_b[nb++] = j;
            const uint32_t first_edge = b->num_internal_edges;
            pair_group(b, a, bv, pos_a, na, pos_b, nb);
            status = record_group(b, a, bv, na, nb, first_edge);
            if (status != MT_OK) break;
        }
    }
    mt__free(pos_a);
    return status;
}
