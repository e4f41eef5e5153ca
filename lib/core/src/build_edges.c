/* Build phase "edges": twin matching in linear time. The corners (face sides
 * a -> b) are counting-sorted by tail vertex a, each part scattering its own
 * faces into slots reserved for it, so the order does not depend on the
 * number of parts; a bucket repeating a head is sorted by head (see
 * sort_part). Then, vertex by vertex, each side's group {a, b} is gathered
 * from the buckets of a and b and paired: each a -> b side with one b -> a
 * side becomes an internal edge, every side left over gets an edge of its
 * own with a boundary twin. A group needing several internal edges (used
 * by more than two faces, or by two faces running the same way) is
 * recorded as a bundle.
 *
 * Ownership, which makes the parts independent: a group belongs to its
 * smaller vertex if that one has a side in it, otherwise to the larger one.
 * Only the owner's part touches the group's slots and corners. Part t
 * numbers its edges from t * corners and a final pass closes the gap, so the
 * ids equal those of a single pass in vertex order. */
#include <string.h>

#include "build_internal.h"

/* Bucket slots between a prefetch and its use in matching. */
#define MT__PREFETCH_DISTANCE 16

/* Sides up to which a bucket is scanned (and sorted only when it repeats a
 * head); larger buckets are sorted and searched. */
#define MT__SCAN_LIMIT 16

/* Exclusive prefix sum of the per-part counts: vertex v's bucket holds part
 * 0's sides of v, then part 1's; degree[] becomes each part's next slot. */
static void reserve_slots(mt__build *b)
{
    const uint32_t nv = b->in->num_verts;
    uint32_t *start = b->bucket_start;
    uint32_t sum = 0, max_degree = 0;
    for (uint32_t v = 0; v < nv; v++) {
        start[v] = sum;
        uint32_t first = sum;
        for (uint32_t t = 0; t < b->parts; t++) {
            uint32_t d = b->part[t].degree[v];
            b->part[t].degree[v] = sum;
            sum += d;
        }
        if (sum - first > max_degree) max_degree = sum - first;
    }
    start[nv] = sum;
    b->max_degree = max_degree;
}

static void scatter_part(mt__build *b, uint32_t t)
{
    mt__part *p = &b->part[t];
    const uint32_t *sizes = b->in->face_sizes;
    const uint32_t *indices = b->in->face_indices;
    const uint32_t *face_he = b->m->face_he;
    mt__side *bucket = b->bucket;
    uint32_t *slot = p->degree;
    uint32_t offset = p->index_begin;
    for (uint32_t f = p->face_begin; f < p->face_end; f++) {
        const uint32_t n = sizes[f];
        if (face_he[f] == MT_NONE) {
            offset += n;
            continue;
        }
        const uint32_t *idx = indices + offset;
        for (uint32_t i = 0; i < n; i++) {
            bucket[slot[idx[i]]++] = (mt__side){idx[i + 1 < n ? i + 1 : 0], offset + i};
        }
        offset += n;
    }
}

/* 1 when two sides of a small bucket share a head. Branch-free: the usual
 * bucket has none, and on a shuffled mesh a search that stops early
 * mispredicts. Heads distinct modulo 64 (most buckets) are told apart
 * with one pass over a bit mask; only a collision there compares pairs. */
static uint32_t repeats_head(const mt__side *s, uint32_t n)
{
    uint64_t seen = 0, collisions = 0;
    for (uint32_t i = 0; i < n; i++) {
        const uint64_t bit = (uint64_t)1 << (s[i].head & 63u);
        collisions |= seen & bit;
        seen |= bit;
    }
    if (!collisions) return 0;
    uint32_t repeats = 0;
    for (uint32_t i = 1; i < n; i++)
        for (uint32_t j = 0; j < i; j++) repeats |= s[i].head == s[j].head;
    return repeats;
}

/* Insertion sort of a bucket by head (stable: equal heads keep their
 * corner order). */
static void sort_bucket(mt__side *s, uint32_t n)
{
    for (uint32_t i = 1; i < n; i++) {
        mt__side x = s[i];
        uint32_t j = i;
        while (j > 0 && s[j - 1].head > x.head) {
            s[j] = s[j - 1];
            j--;
        }
        s[j] = x;
    }
}

/* Large buckets: a merge sort through a scratch buffer would need memory;
 * a heap sort on the pairs keeps it in place and O(n log n). */
static void sift_down(mt__side *s, uint32_t root, uint32_t n)
{
    for (;;) {
        uint32_t child = 2 * root + 1;
        if (child >= n) return;
        if (child + 1 < n && s[child + 1].head > s[child].head) child++;
        if (s[root].head >= s[child].head) return;
        mt__side x = s[root];
        s[root] = s[child];
        s[child] = x;
        root = child;
    }
}

static void heap_sort_bucket(mt__side *s, uint32_t n)
{
    for (uint32_t i = n / 2; i-- > 0;) sift_down(s, i, n);
    for (uint32_t end = n; end-- > 1;) {
        mt__side x = s[0];
        s[0] = s[end];
        s[end] = x;
        sift_down(s, 0, end);
    }
}

/* Matching needs the sides of each group next to one another. A small
 * bucket whose heads are all distinct already has that and stays in corner
 * order; only one that repeats a head is sorted. Larger buckets are always
 * sorted, for binary search. */
static void sort_part(mt__build *b, uint32_t t)
{
    mt__part *p = &b->part[t];
    const uint32_t *start = b->bucket_start;
    for (uint32_t v = p->vert_begin; v < p->vert_end; v++) {
        mt__side *s = b->bucket + start[v];
        const uint32_t n = start[v + 1] - start[v];
        if (n <= MT__SCAN_LIMIT) {
            if (repeats_head(s, n)) sort_bucket(s, n);
        } else if (n <= 32) {
            sort_bucket(s, n);
        } else {
            heap_sort_bucket(s, n);
        }
    }
}

/* The sides with head v in bucket [lo, hi): first slot and count. A small
 * bucket is scanned whole (its sides with head v are adjacent if there are
 * several, see sort_part); a large one is searched. */
static uint32_t find_head(const mt__side *s, uint32_t lo, uint32_t hi, uint32_t v,
                          uint32_t *out_count)
{
    const uint32_t end = hi;
    uint32_t first = hi, count = 0;
    if (hi - lo <= MT__SCAN_LIMIT) {
        for (uint32_t j = hi; j-- > lo;) {
            const uint32_t hit = s[j].head == v;
            count += hit;
            first = hit ? j : first;
        }
        *out_count = count;
        return first;
    }
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (s[mid].head < v)
            lo = mid + 1;
        else
            hi = mid;
    }
    while (lo + count < end && s[lo + count].head == v) count++;
    *out_count = count;
    return lo;
}

static mt_status record_group(mt__part *p, uint32_t a, uint32_t bv, uint32_t na, uint32_t nb,
                              uint32_t first_edge)
{
    const uint32_t uses = na + nb;
    p->num_edges++;
    if (uses < MT__SMALL_USES)
        p->use_hist[uses]++;
    else if (mt__vec_push(&p->large_uses, &uses) != MT_OK)
        return MT_ERR_NOMEM;
    if (uses == 1) {
        p->boundary_edges++;
        return MT_OK;
    }
    if (uses == 2 && na == 1) return MT_OK; /* the common manifold case */
    uint32_t lo = a < bv ? a : bv, hi = a < bv ? bv : a;
    if (uses > 2) {
        p->nonmanifold_edges++;
        if (mt__push_defect(&p->defects, MT_DEFECT_NONMANIFOLD_EDGE, lo, hi, uses) != MT_OK)
            return MT_ERR_NOMEM;
    }
    if (na >= 2 || nb >= 2) {
        p->duplicate_directed_edges++;
        if (uses == 2) p->inconsistent_edges++;
        if (na >= 2 &&
            mt__push_defect(&p->defects, MT_DEFECT_SAME_DIRECTION_EDGE, a, bv, na) != MT_OK)
            return MT_ERR_NOMEM;
        if (nb >= 2 &&
            mt__push_defect(&p->defects, MT_DEFECT_SAME_DIRECTION_EDGE, bv, a, nb) != MT_OK)
            return MT_ERR_NOMEM;
    }
    uint32_t count = na > nb ? na : nb;
    if (count > 1) {
        uint32_t start = (uint32_t)p->bundle_edges.len;
        if (mt__vec_push(&p->bundle_offsets, &start) != MT_OK) return MT_ERR_NOMEM;
        for (uint32_t e = first_edge; e < first_edge + count; e++)
            if (mt__vec_push(&p->bundle_edges, &e) != MT_OK) return MT_ERR_NOMEM;
    }
    return MT_OK;
}

/* Pairs the sides of group {a, b}: slots [sa, sa + na) of a's bucket hold
 * the a -> b sides, [sb, sb + nb) of b's the b -> a sides. Half-edge 2e
 * points from the smaller vertex id. */
static void pair_group(mt__build *b, mt__part *p, uint32_t a, uint32_t bv, uint32_t sa, uint32_t na,
                       uint32_t sb, uint32_t nb)
{
    mt__side *bucket = b->bucket;
    uint32_t *c2h = b->c2h;
    const uint32_t count = na > nb ? na : nb;
    const uint32_t a_low = a < bv ? 0u : 1u;
    for (uint32_t k = 0; k < count; k++) {
        const uint32_t e = p->edge_base + p->edges_made++;
        if (k < na) {
            uint32_t h = 2 * e + a_low;
            c2h[bucket[sa + k].item] = h;
            bucket[sa + k].item = h;
        }
        if (k < nb) {
            uint32_t h = 2 * e + (1u - a_low);
            c2h[bucket[sb + k].item] = h;
            bucket[sb + k].item = h;
        }
    }
}

static void match_part(mt__build *b, uint32_t t)
{
    mt__part *p = &b->part[t];
    const uint32_t *start = b->bucket_start;
    mt__side *bucket = b->bucket;
    uint32_t *c2h = b->c2h;
    const uint64_t num_corners = b->num_corners;
    p->edge_base = t * (uint32_t)num_corners;
    for (uint32_t a = p->vert_begin; a < p->vert_end; a++) {
        const uint32_t end_a = start[a + 1];
        for (uint32_t i = start[a]; i < end_a;) {
            /* The twin sides sit in another vertex's bucket, at random in a
             * scan-ordered mesh: fetch those ahead of use. (Heads do not
             * change during matching; items may be written by another part,
             * so they are not read ahead.) */
            if (i + MT__PREFETCH_DISTANCE < num_corners) {
                __builtin_prefetch(&start[bucket[i + MT__PREFETCH_DISTANCE].head]);
                __builtin_prefetch(&bucket[start[bucket[i + MT__PREFETCH_DISTANCE / 2].head]]);
            }
            const uint32_t bv = bucket[i].head;
            uint32_t na = 1;
            while (i + na < end_a && bucket[i + na].head == bv) na++;
            uint32_t nb;
            const uint32_t sb = find_head(bucket, start[bv], start[bv + 1], a, &nb);
            /* Owned by a unless b is smaller and has a side in the group. */
            if (bv < a && nb > 0) {
                i += na;
                continue;
            }
            if (na == 1 && nb == 1) { /* the manifold case, inline */
                const uint32_t e = p->edge_base + p->edges_made++;
                const uint32_t ha = 2 * e + (a < bv ? 0u : 1u);
                c2h[bucket[i].item] = ha;
                bucket[i].item = ha;
                c2h[bucket[sb].item] = ha ^ 1u;
                bucket[sb].item = ha ^ 1u;
                p->num_edges++;
                p->use_hist[2]++;
            } else {
                const uint32_t first_edge = p->edge_base + p->edges_made;
                pair_group(b, p, a, bv, i, na, sb, nb);
                if (record_group(p, a, bv, na, nb, first_edge) != MT_OK) {
                    p->status = MT_ERR_NOMEM;
                    return;
                }
            }
            i += na;
        }
    }
}

/* Part 1 numbered its edges from `corners`; move the half-edges in the
 * buckets down to follow part 0's edges directly (c2h is moved as it is
 * read, by mt__edge_gap). */
static void close_gap_part(mt__build *b, uint32_t t)
{
    const uint64_t n = b->num_corners;
    mt__side *bucket = b->bucket;
    for (uint64_t i = n * t / b->parts, hi = n * (t + 1) / b->parts; i < hi; i++)
        bucket[i].item = mt__edge_gap(b, bucket[i].item);
}

static mt_status merge_parts(mt__build *b)
{
    const uint32_t shift = b->parts > 1 ? b->part[1].edge_base - b->part[0].edges_made : 0;
    for (uint32_t t = 0; t < b->parts; t++) {
        mt__part *p = &b->part[t];
        if (p->status != MT_OK) return p->status;
        b->num_internal_edges += p->edges_made;
        b->num_edges += p->num_edges;
        for (uint32_t k = 0; k < MT__SMALL_USES; k++) b->use_hist[k] += p->use_hist[k];
        b->boundary_edges += p->boundary_edges;
        b->nonmanifold_edges += p->nonmanifold_edges;
        b->inconsistent_edges += p->inconsistent_edges;
        b->duplicate_directed_edges += p->duplicate_directed_edges;
        uint32_t *edges = p->bundle_edges.data, *offsets = p->bundle_offsets.data;
        for (size_t i = 0; t > 0 && i < p->bundle_edges.len; i++) edges[i] -= shift;
        for (size_t i = 0; i < p->bundle_offsets.len; i++)
            offsets[i] += (uint32_t)b->bundle_edges.len;
        if (mt__vec_append(&b->large_uses, &p->large_uses) != MT_OK ||
            mt__vec_append(&b->defects, &p->defects) != MT_OK ||
            mt__vec_append(&b->bundle_offsets, &p->bundle_offsets) != MT_OK ||
            mt__vec_append(&b->bundle_edges, &p->bundle_edges) != MT_OK)
            return MT_ERR_NOMEM;
    }
    return MT_OK;
}

/* Splits the vertices into parts holding about the same number of sides. */
static void split_vertices(mt__build *b)
{
    const uint32_t nv = b->in->num_verts;
    uint32_t v = 0;
    for (uint32_t t = 0; t < b->parts; t++) {
        uint64_t goal = b->num_corners * (t + 1) / b->parts;
        b->part[t].vert_begin = v;
        while (v < nv && (t + 1 == b->parts || b->bucket_start[v] < goal)) v++;
        b->part[t].vert_end = v;
    }
}

mt_status mt__build_edges(mt__build *b)
{
    reserve_slots(b);
    mt__parallel_run(b, scatter_part);
    split_vertices(b);
    mt__parallel_run(b, sort_part);
    mt__parallel_run(b, match_part);
    if (b->parts > 1) {
        b->gap_first_he = 2 * b->part[1].edge_base;
        b->gap_shift = 2 * (b->part[1].edge_base - b->part[0].edges_made);
        mt__parallel_run(b, close_gap_part);
    }
    return merge_parts(b);
}
