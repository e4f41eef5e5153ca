/* Build phase "edges": twin matching in linear time, without random reads.
 * Every side a -> b of a valid face is filed under its smaller vertex
 * lo = min(a, b), in blocks of 2^block_shift consecutive lo (the faces
 * phase counted the sides of each block): each part streams its faces'
 * sides into its own slots of every block, a few thousand sequential write
 * streams instead of one random write per side. Then each block, small
 * enough to stay in the core's cache, is counting-sorted by lo, each lo's
 * sides are sorted by hi, and each run of sides on {lo, hi} is paired: each
 * lo -> hi side with one hi -> lo side becomes an internal edge, every side
 * left over gets an edge of its own with a boundary twin. A run needing
 * several internal edges (used by more than two faces, or by two faces
 * running the same way) is recorded as a bundle.
 *
 * Edges are numbered in (lo, hi) order and half-edge 2e runs lo -> hi, so
 * the head and face of every half-edge come out in id order: they are kept
 * in the block's own slots, which the sort has emptied, and moved into the
 * mesh once the number of edges is known (mt__build_edges_publish). The
 * half-edge of each corner goes to c2h for the links phase. Part t numbers
 * its edges from t * corners; the gap is closed afterwards, so the ids equal
 * those of a single pass. */
#include <string.h>

#include "build/build_phases.h"

/* Sides of one smaller vertex up to which they are sorted by insertion;
 * more are heap-sorted. */
#define MT__INSERTION_LIMIT 32

/* Exclusive prefix sum of the per-part counts: block k holds part 0's
 * sides, then part 1's, each in face order; block_sides becomes each
 * part's next free slot. */
static void reserve_slots(mt__build *b)
{
    uint32_t sum = 0;
    for (uint32_t k = 0; k < b->num_blocks; k++) {
        b->block_start[k] = sum;
        for (uint32_t t = 0; t < b->parts; t++) {
            const uint32_t count = b->part[t].block_sides[k];
            b->part[t].block_sides[k] = sum;
            sum += count;
        }
    }
    b->block_start[b->num_blocks] = sum;
}

static void scatter_part(mt__build *b, uint32_t t)
{
    mt__part *p = &b->part[t];
    const uint32_t *sizes = b->in->face_sizes, *indices = b->in->face_indices;
    const uint32_t *face_he = b->m->face_he;
    mt__side *sides = b->sides;
    uint32_t *slot = p->block_sides;
    uint32_t offset = p->index_begin;
    for (uint32_t f = p->face_begin; f < p->face_end; f++) {
        const uint32_t n = sizes[f];
        if (face_he[f] == MT_NONE) {
            offset += n;
            continue;
        }
        const uint32_t *idx = indices + offset;
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t tail = idx[i], head = idx[i + 1 < n ? i + 1 : 0];
            const uint32_t down = tail > head;
            const uint32_t lo = down ? head : tail, hi = down ? tail : head;
            sides[slot[mt__block_of(b, lo)]++] =
                (mt__side){lo, hi, (offset + i) | (down ? MT__SIDE_DOWN : 0u), f};
        }
        offset += n;
    }
}

/* Insertion sort by hi (stable: equal his keep their face order). */
static void sort_by_hi(mt__side *s, uint32_t n)
{
    for (uint32_t i = 1; i < n; i++) {
        mt__side x = s[i];
        uint32_t j = i;
        while (j > 0 && s[j - 1].hi > x.hi) {
            s[j] = s[j - 1];
            j--;
        }
        s[j] = x;
    }
}

/* Many sides on one vertex: a merge sort through a scratch buffer would
 * need memory; a heap sort keeps it in place and O(n log n). It orders by
 * (hi, face), which is the order the stable insertion sort gives. */
static uint64_t heap_key(const mt__side *s)
{
    return (uint64_t)s->hi << 32 | s->face;
}

static void sift_down(mt__side *s, uint32_t root, uint32_t n)
{
    for (;;) {
        uint32_t child = 2 * root + 1;
        if (child >= n) return;
        if (child + 1 < n && heap_key(&s[child + 1]) > heap_key(&s[child])) child++;
        if (heap_key(&s[root]) >= heap_key(&s[child])) return;
        mt__side x = s[root];
        s[root] = s[child];
        s[child] = x;
        root = child;
    }
}

static void heap_sort_by_hi(mt__side *s, uint32_t n)
{
    for (uint32_t i = n / 2; i-- > 0;) sift_down(s, i, n);
    for (uint32_t end = n; end-- > 1;) {
        mt__side x = s[0];
        s[0] = s[end];
        s[end] = x;
        sift_down(s, 0, end);
    }
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

/* A matched block's output: (head, face) of each half-edge it made, in id
 * order, written over the block's slots (4 words per side, at most 4 per
 * edge, and every edge takes at least one side). */
typedef struct block_output {
    uint32_t *pairs;
    uint32_t half_edges;
} block_output;

static void put_edge(block_output *out, uint32_t lo, uint32_t hi, uint32_t face_up,
                     uint32_t face_down)
{
    uint32_t *pair = out->pairs + 2 * (size_t)out->half_edges;
    pair[0] = hi; /* 2e runs lo -> hi */
    pair[1] = face_up;
    pair[2] = lo;
    pair[3] = face_down;
    out->half_edges += 2;
}

/* Pairs a run of n sides on {lo, hi} that is not one side each way: the
 * k-th lo -> hi side with the k-th hi -> lo side, in face order. */
static mt_status pair_run(mt__build *b, mt__part *p, const mt__side *run, uint32_t n,
                          block_output *out)
{
    const uint32_t lo = run[0].lo, hi = run[0].hi;
    uint32_t up = 0;
    for (uint32_t i = 0; i < n; i++) up += !(run[i].corner_down & MT__SIDE_DOWN);
    const uint32_t down = n - up, count = up > down ? up : down;
    const uint32_t first_edge = p->edge_base + p->edges_made;
    uint32_t next_up = 0, next_down = 0;
    for (uint32_t k = 0; k < count; k++) {
        const uint32_t e = p->edge_base + p->edges_made++;
        uint32_t face_up = MT_NONE, face_down = MT_NONE, h_up = 2 * e, h_down = 2 * e + 1;
        while (next_up < n && (run[next_up].corner_down & MT__SIDE_DOWN)) next_up++;
        while (next_down < n && !(run[next_down].corner_down & MT__SIDE_DOWN)) next_down++;
        if (next_up < n) {
            face_up = run[next_up].face;
            b->c2h[run[next_up++].corner_down] = h_up;
        } else if (mt__vec_push(&p->boundary_halves, &h_up) != MT_OK) {
            return MT_ERR_NOMEM;
        }
        if (next_down < n) {
            face_down = run[next_down].face;
            b->c2h[run[next_down++].corner_down & ~MT__SIDE_DOWN] = h_down;
        } else if (mt__vec_push(&p->boundary_halves, &h_down) != MT_OK) {
            return MT_ERR_NOMEM;
        }
        put_edge(out, lo, hi, face_up, face_down);
    }
    return record_group(p, lo, hi, up, down, first_edge);
}

/* Sorts block k's sides into `sorted` by lo (counting sort, count has
 * 2^block_shift + 1 entries), then by hi, and pairs every run. */
static mt_status match_block(mt__build *b, mt__part *p, uint32_t k, mt__side *sorted,
                             uint32_t *count)
{
    const uint32_t first = b->block_start[k], n = b->block_start[k + 1] - first;
    const mt__side *s = b->sides + first;
    const uint32_t base = k << b->block_shift;
    uint32_t width = b->in->num_verts - base;
    if (width > 1u << b->block_shift) width = 1u << b->block_shift;
    memset(count, 0, ((size_t)width + 1) * sizeof *count);
    for (uint32_t i = 0; i < n; i++) count[s[i].lo - base + 1]++;
    for (uint32_t v = 1; v <= width; v++) count[v] += count[v - 1];
    for (uint32_t i = 0; i < n; i++) sorted[count[s[i].lo - base]++] = s[i];
    /* count[v] is now the end of lo = base + v's sides. */
    block_output out = {(uint32_t *)(b->sides + first), 0};
    uint32_t *c2h = b->c2h;
    for (uint32_t v = 0, begin = 0; v < width; begin = count[v++]) {
        const uint32_t end = count[v];
        if (end - begin <= MT__INSERTION_LIMIT)
            sort_by_hi(sorted + begin, end - begin);
        else
            heap_sort_by_hi(sorted + begin, end - begin);
        for (uint32_t i = begin; i < end;) {
            if (i + MT__PREFETCH_DISTANCE < n) {
                const uint32_t ahead = sorted[i + MT__PREFETCH_DISTANCE].corner_down;
                __builtin_prefetch(&c2h[ahead & ~MT__SIDE_DOWN], 1);
            }
            const mt__side *run = sorted + i;
            uint32_t len = 1;
            while (i + len < end && run[len].hi == run[0].hi) len++;
            const uint32_t flip = (run[0].corner_down ^ run[len > 1].corner_down) & MT__SIDE_DOWN;
            if (len == 2 && flip) { /* the manifold case, inline */
                const mt__side *up = run[0].corner_down & MT__SIDE_DOWN ? run + 1 : run;
                const mt__side *down = up == run ? run + 1 : run;
                const uint32_t e = p->edge_base + p->edges_made++;
                c2h[up->corner_down] = 2 * e;
                c2h[down->corner_down & ~MT__SIDE_DOWN] = 2 * e + 1;
                put_edge(&out, run[0].lo, run[0].hi, up->face, down->face);
                p->num_edges++;
                p->use_hist[2]++;
            } else if (pair_run(b, p, run, len, &out) != MT_OK) {
                return MT_ERR_NOMEM;
            }
            i += len;
        }
    }
    b->block_half_edges[k] = out.half_edges;
    return MT_OK;
}

static void match_part(mt__build *b, uint32_t t)
{
    mt__part *p = &b->part[t];
    p->edge_base = t * (uint32_t)b->num_corners;
    uint32_t largest = 0;
    for (uint32_t k = p->block_begin; k < p->block_end; k++) {
        const uint32_t n = b->block_start[k + 1] - b->block_start[k];
        if (n > largest) largest = n;
    }
    mt__side *sorted = mt__scratch_get(b, MT__SCRATCH_SORTED + t, largest, sizeof *sorted, 0);
    uint32_t *count = mt__malloc(((size_t)1 << b->block_shift) * sizeof *count + sizeof *count);
    if (!sorted || !count) p->status = MT_ERR_NOMEM;
    for (uint32_t k = p->block_begin; k < p->block_end && p->status == MT_OK; k++)
        p->status = match_block(b, p, k, sorted, count);
    mt__scratch_put(b, sorted);
    mt__free(count);
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
        uint32_t *halves = p->boundary_halves.data;
        for (size_t i = 0; t > 0 && i < p->bundle_edges.len; i++) edges[i] -= shift;
        for (size_t i = 0; t > 0 && i < p->boundary_halves.len; i++) halves[i] -= 2 * shift;
        for (size_t i = 0; i < p->bundle_offsets.len; i++)
            offsets[i] += (uint32_t)b->bundle_edges.len;
        if (mt__vec_append(&b->large_uses, &p->large_uses) != MT_OK ||
            mt__vec_append(&b->defects, &p->defects) != MT_OK ||
            mt__vec_append(&b->bundle_offsets, &p->bundle_offsets) != MT_OK ||
            mt__vec_append(&b->bundle_edges, &p->bundle_edges) != MT_OK ||
            mt__vec_append(&b->boundary_halves, &p->boundary_halves) != MT_OK)
            return MT_ERR_NOMEM;
    }
    return MT_OK;
}

/* Splits the blocks into parts holding about the same number of sides. */
static void split_blocks(mt__build *b)
{
    uint32_t k = 0;
    for (uint32_t t = 0; t < b->parts; t++) {
        const uint64_t goal = b->num_corners * (t + 1) / b->parts;
        b->part[t].block_begin = k;
        while (k < b->num_blocks && (t + 1 == b->parts || b->block_start[k] < goal)) k++;
        b->part[t].block_end = k;
    }
}

mt_status mt__build_edges(mt__build *b)
{
    reserve_slots(b);
    mt__parallel_run(b, scatter_part);
    split_blocks(b);
    mt__parallel_run(b, match_part);
    if (b->parts > 1) {
        b->gap_first_he = 2 * b->part[1].edge_base;
        b->gap_shift = 2 * (b->part[1].edge_base - b->part[0].edges_made);
    }
    return merge_parts(b);
}

static void publish_part(mt__build *b, uint32_t t)
{
    mt_mesh *m = b->m;
    uint32_t h = 0;
    for (uint32_t earlier = 0; earlier < t; earlier++) h += 2 * b->part[earlier].edges_made;
    for (uint32_t k = b->part[t].block_begin; k < b->part[t].block_end; k++) {
        const uint32_t *pairs = (const uint32_t *)(b->sides + b->block_start[k]);
        for (uint32_t j = 0; j < b->block_half_edges[k]; j++, h++) {
            m->he_head[h] = pairs[2 * j];
            m->he_face[h] = pairs[2 * j + 1];
            m->he_next[h] = MT_NONE; /* set by the links phase, or by the fans if no face */
        }
    }
}

void mt__build_edges_publish(mt__build *b)
{
    mt__parallel_run(b, publish_part);
}
