/* Mesh self-intersections (meshtopo/geometry.h). Every face becomes
 * triangles (polygons by polygon_ears.c); the triangles are sorted along a
 * Morton curve of their centroids so that neighbours in space are neighbours
 * in memory, and a bounding-volume hierarchy is laid over them as a complete
 * binary tree (node k has children 2k and 2k + 1, leaves hold LEAF_SIZE
 * consecutive triangles). The tree is then traversed against itself, pairs
 * of nodes whose boxes overlap down to pairs of leaves, so every pair of
 * triangles is met once. Pairs sharing a vertex whose fan is flat
 * (flat_fans.c) cannot cross and are passed over; the exact narrow phase
 * (mt__triangles_cross) decides the others. The pairs of subtrees a few
 * levels down are independent tasks that threads take from a shared
 * counter. Boxes are floats rounded outwards, so they never miss a pair. */
#include <float.h>
#include <inttypes.h>
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geometry/geometry_internal.h"

enum {
    LEAF_SIZE = 8,         /* triangles per leaf of the tree, a multiple of 4 (v4f) */
    TASKS_PER_THREAD = 64, /* pairs of subtrees the threads share, per thread */
    MIN_PARALLEL = 20000,  /* fewer triangles than this are checked on one thread */
    MORTON_BITS = 10,      /* bits per axis of a cell of the Morton curve (spread3 takes 10) */
    RADIX_BITS = 10,       /* bits per pass of the sort */
    TEST_BATCH = 1024      /* exact tests a thread counts before adding them to the total */
};

typedef struct box {
    float lo[3], hi[3];
} box;

/* The boxes of a leaf's triangles by axis, so that one box is tested
 * against all of them in a few vector operations (GCC and Clang vector
 * types: SSE on x86-64). Slots past the last triangle hold an empty box. */
typedef float v4f __attribute__((vector_size(4 * sizeof(float))));
typedef int32_t v4i __attribute__((vector_size(4 * sizeof(int32_t))));
typedef struct leaf_boxes {
    float lo[3][LEAF_SIZE], hi[3][LEAF_SIZE]; /* [axis][slot] */
} leaf_boxes;

typedef struct sorted_tri {
    uint32_t key; /* Morton code of the centroid */
    uint32_t index;
} sorted_tri;

/* Two nodes of the tree at the same depth whose triangles are to be
 * checked against each other (a == b: a node against itself). */
typedef struct node_pair {
    uint32_t a, b;
} node_pair;

typedef struct check {
    const mt_mesh *m;
    const uint8_t *flat;   /* [num_verts]: the vertex's fan is flat (mt__flat_fans) */
    mt__tri *tris;         /* in Morton order */
    uint8_t *flat_corners; /* bit k: corner k of the triangle has a flat fan */
    uint32_t num_tris;
    box *nodes;          /* [2 * num_leaves]; node 0 unused */
    leaf_boxes *leaves;  /* [num_leaves]: node num_leaves + l's triangles' boxes */
    uint32_t num_leaves; /* a power of two */
    node_pair *tasks;    /* pairs of subtrees to traverse, shared by the threads */
    uint32_t num_tasks;
    uint32_t threads;   /* how many share the work */
    size_t max_pairs;   /* more pairs than this end the search (MT_ERR_TOO_LARGE) */
    uint64_t max_tests; /* more exact tests than this end it too */
    atomic_uint next;   /* the next task to take */
    atomic_bool failed; /* a thread stopped: out of memory, too many pairs or tests */
    atomic_bool too_many;
    atomic_bool too_many_tests;
    _Atomic uint64_t tests; /* exact tests counted so far by all threads */
} check;

typedef struct worker {
    check *c;
    mt__vec pairs;      /* mt_face_pair, unsorted, possibly repeated */
    size_t compact_at;  /* pairs.len at which repeats are dropped and the count checked */
    uint32_t uncounted; /* exact tests not yet added to c->tests */
} worker;

/* The float next to finite f towards -infinity (step -1) or +infinity
 * (step +1), by its bits: nextafterf is a library call, and this runs six
 * times per triangle. */
static float float_step(float f, int step)
{
    if (f == 0) return step < 0 ? -FLT_TRUE_MIN : FLT_TRUE_MIN;
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    bits = (f > 0) == (step > 0) ? bits + 1 : bits - 1; /* away from zero, or towards it */
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* x rounded to a float not above it (not below it: up). */
static float down(double x)
{
    if (x >= FLT_MAX) return FLT_MAX;
    if (x < -FLT_MAX) return -INFINITY;
    float f = (float)x;
    return (double)f > x ? float_step(f, -1) : f;
}

static float up(double x)
{
    if (x <= -FLT_MAX) return -FLT_MAX;
    if (x > FLT_MAX) return INFINITY;
    float f = (float)x;
    return (double)f < x ? float_step(f, +1) : f;
}

static bool overlap(const box *a, const box *b)
{
    return a->lo[0] <= b->hi[0] && b->lo[0] <= a->hi[0] && a->lo[1] <= b->hi[1] &&
           b->lo[1] <= a->hi[1] && a->lo[2] <= b->hi[2] && b->lo[2] <= a->hi[2];
}

static void box_empty(box *b)
{
    for (int k = 0; k < 3; k++) {
        b->lo[k] = INFINITY;
        b->hi[k] = -INFINITY;
    }
}

static void box_add(box *b, const box *o)
{
    for (int k = 0; k < 3; k++) {
        b->lo[k] = o->lo[k] < b->lo[k] ? o->lo[k] : b->lo[k];
        b->hi[k] = o->hi[k] > b->hi[k] ? o->hi[k] : b->hi[k];
    }
}

/* Appends x to a vector of uint32_t, in place while it has room. */
static mt_status push_u32(mt__vec *v, uint32_t x)
{
    if (v->len == v->cap) return mt__vec_push(v, &x);
    ((uint32_t *)v->data)[v->len++] = x;
    return MT_OK;
}

/* The corners of valid face f as caller ids into verts (grown as needed);
 * their count, or 0 on a broken ring (MT_ERR_CORRUPT) or no memory. */
static uint32_t face_corners(const mt_mesh *m, uint32_t f, mt__vec *verts, mt_status *status)
{
    verts->len = 0;
    uint32_t h = m->face_he[f], steps = 0;
    const uint32_t start = h;
    if (!mt__he_ok(m, h)) {
        *status = MT_ERR_CORRUPT;
        return 0;
    }
    do {
        const uint32_t v = mt__original_checked(m, m->he_head[h ^ 1u]);
        if (v == MT_NONE || !mt__ring_step(m, &h, &steps)) {
            *status = MT_ERR_CORRUPT;
            return 0;
        }
        if (push_u32(verts, v) != MT_OK) {
            *status = MT_ERR_NOMEM;
            return 0;
        }
    } while (h != start);
    return (uint32_t)verts->len;
}

static bool finite_corners(const mt_mesh *m, const uint32_t *verts, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        const double *p = m->positions + 3 * (size_t)verts[i];
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) return false;
    }
    return true;
}

/* Triangles with their boxes. */
typedef struct tri_set {
    mt__tri *tris;
    box *boxes;
    size_t len, cap;
    box bounds; /* of every box */
} tri_set;

static void tri_set_free(tri_set *t)
{
    mt__free(t->tris);
    mt__free(t->boxes);
    *t = (tri_set){0};
}

/* Room for `cap` triangles (the arrays that could grow keep their room). */
static mt_status tri_set_reserve(tri_set *t, size_t cap)
{
    if (cap <= t->cap) return MT_OK;
    mt__tri *tris = mt__realloc(t->tris, cap * sizeof *tris);
    if (tris) t->tris = tris;
    box *boxes = tris ? mt__realloc(t->boxes, cap * sizeof *boxes) : NULL;
    if (!boxes) return MT_ERR_NOMEM;
    t->boxes = boxes;
    t->cap = cap;
    return MT_OK;
}

/* Appends triangle (a, b, c) of face f with its box. */
static mt_status tri_set_add(tri_set *t, const mt_mesh *m, uint32_t a, uint32_t b, uint32_t c,
                             uint32_t f)
{
    if (t->len == t->cap && tri_set_reserve(t, t->cap ? 2 * t->cap : 64) != MT_OK)
        return MT_ERR_NOMEM;
    const mt__tri one = {{a, b, c}, f};
    const double *pa = m->positions + 3 * (size_t)a, *pb = m->positions + 3 * (size_t)b,
                 *pc = m->positions + 3 * (size_t)c;
    box *bx = &t->boxes[t->len];
    for (int k = 0; k < 3; k++) {
        const double x0 = pa[k], x1 = pb[k], x2 = pc[k];
        const double lo = x0 < x1 ? (x0 < x2 ? x0 : x2) : (x1 < x2 ? x1 : x2);
        const double hi = x0 > x1 ? (x0 > x2 ? x0 : x2) : (x1 > x2 ? x1 : x2);
        bx->lo[k] = down(lo);
        bx->hi[k] = up(hi);
    }
    box_add(&t->bounds, bx);
    t->tris[t->len++] = one;
    return MT_OK;
}

/* Appends the triangles of face f (corners verts[0..n)). */
static mt_status add_face(const mt_mesh *m, uint32_t f, const uint32_t *verts, uint32_t n,
                          tri_set *out)
{
    if (n == 3) return tri_set_add(out, m, verts[0], verts[1], verts[2], f);
    const double **pos = mt__malloc(n * sizeof *pos);
    uint32_t *scratch = mt__malloc((size_t)(n + 3 * (n - 2)) * sizeof *scratch);
    mt_status s = pos && scratch ? MT_OK : MT_ERR_NOMEM;
    if (s == MT_OK) {
        for (uint32_t i = 0; i < n; i++) pos[i] = m->positions + 3 * (size_t)verts[i];
        uint32_t *corners = scratch + n;
        mt__ear_clip(pos, n, NULL, NULL, scratch, corners);
        for (uint32_t t = 0; t < n - 2 && s == MT_OK; t++) {
            const uint32_t *c = corners + 3 * t;
            s = tri_set_add(out, m, verts[c[0]], verts[c[1]], verts[c[2]], f);
        }
    }
    mt__free(pos);
    mt__free(scratch);
    return s;
}

/* The triangles of the judged faces among [first, end). Faces are read in
 * parallel ranges: their half-edges and corners are scattered in memory
 * when the mesh came shuffled, and waiting on memory is what two threads
 * overlap best. */
typedef struct collector {
    const mt_mesh *m;
    uint32_t first, end;
    mt__vec unflat; /* corners of polygon faces and of faces left out (mt__flat_fans) */
    tri_set out;
    mt_status status;
    uint32_t failed_face;
} collector;

/* Part t: the triangles of collector t's faces. */
static void collect_range(void *ctx, uint32_t t, uint32_t threads)
{
    (void)threads;
    collector *c = &((collector *)ctx)[t];
    mt__vec verts = {.elem_size = sizeof(uint32_t)};
    box_empty(&c->out.bounds);
    c->status = tri_set_reserve(&c->out, c->end - c->first); /* one per triangle face */
    for (uint32_t f = c->first; f < c->end && c->status == MT_OK; f++) {
        if (c->m->face_he[f] == MT_NONE) continue; /* rejected or deleted */
        const uint32_t n = face_corners(c->m, f, &verts, &c->status);
        const bool judged = n >= 3 && finite_corners(c->m, verts.data, n);
        if (judged) c->status = add_face(c->m, f, verts.data, n, &c->out);
        for (uint32_t k = 0; k < n && (n > 3 || !judged) && c->status == MT_OK; k++)
            c->status = push_u32(&c->unflat, ((const uint32_t *)verts.data)[k]);
        if (c->status != MT_OK) c->failed_face = f;
    }
    mt__vec_free(&verts);
}

/* Threads for a mesh of `faces` faces: one below MIN_PARALLEL, else one
 * per core up to MT__MAX_THREADS. */
static uint32_t threads_for(uint32_t faces)
{
    const long cores = sysconf(_SC_NPROCESSORS_ONLN);
    if (faces < MIN_PARALLEL || cores < 2) return 1;
    return cores < MT__MAX_THREADS ? (uint32_t)cores : MT__MAX_THREADS;
}

/* Every judged face's triangles, in face order: those of parts[0], then
 * parts[1], ... (one per thread; left in place, not copied together), and
 * flat[] as mt__flat_fans takes it. */
static mt_status collect(const mt_mesh *m, uint32_t threads, collector *parts, uint8_t *flat,
                         mt_diag *diag, const char *what)
{
    for (uint32_t t = 0; t < threads; t++)
        parts[t] = (collector){.m = m,
                               .first = (uint32_t)((uint64_t)m->num_faces * t / threads),
                               .end = (uint32_t)((uint64_t)m->num_faces * (t + 1) / threads),
                               .unflat = {.elem_size = sizeof(uint32_t)}};
    mt__in_parallel(threads, collect_range, parts);
    memset(flat, 1, m->num_verts);
    for (uint32_t t = 0; t < threads; t++) {
        for (size_t i = 0; i < parts[t].unflat.len; i++)
            flat[((const uint32_t *)parts[t].unflat.data)[i]] = 0;
        mt__vec_free(&parts[t].unflat);
    }
    for (uint32_t t = 0; t < threads; t++)
        if (parts[t].status != MT_OK)
            return mt__fail(diag, parts[t].status, parts[t].failed_face, "%s: %s face %u", what,
                            parts[t].status == MT_ERR_NOMEM ? "no memory for the triangles of"
                                                            : "broken ring of",
                            parts[t].failed_face);
    return MT_OK;
}

/* Spreads the low 10 bits of x to every third bit (bit i to bit 3i), by
 * the usual shifts and masks of Morton codes. */
static uint32_t spread3(uint32_t x)
{
    x &= 0x3ffu;
    x = (x | x << 16) & 0x030000ffu;
    x = (x | x << 8) & 0x0300f00fu;
    x = (x | x << 4) & 0x030c30c3u;
    x = (x | x << 2) & 0x09249249u;
    return x;
}

/* LSD radix sort of items by key. Written by hand: the C library's qsort
 * is several times slower on a million keys and this is a hot step. */
static mt_status radix_sort(sorted_tri *items, uint32_t n)
{
    sorted_tri *tmp = mt__malloc((size_t)n * sizeof *tmp);
    if (!tmp) return MT_ERR_NOMEM;
    sorted_tri *src = items, *dst = tmp;
    for (int shift = 0; shift < 3 * MORTON_BITS; shift += RADIX_BITS) {
        uint32_t count[(1u << RADIX_BITS) + 1];
        memset(count, 0, sizeof count);
        for (uint32_t i = 0; i < n; i++)
            count[((src[i].key >> shift) & ((1u << RADIX_BITS) - 1)) + 1]++;
        for (uint32_t d = 0; d < (1u << RADIX_BITS); d++) count[d + 1] += count[d];
        for (uint32_t i = 0; i < n; i++)
            dst[count[(src[i].key >> shift) & ((1u << RADIX_BITS) - 1)]++] = src[i];
        sorted_tri *t = src;
        src = dst;
        dst = t;
    }
    if (src != items) memcpy(items, src, (size_t)n * sizeof *items);
    mt__free(tmp);
    return MT_OK;
}

typedef struct ordering {
    check *c;
    const collector *parts; /* one per share */
    sorted_tri *order;
    box all;
} ordering;

/* Share t: the Morton keys of part t's triangles. */
static void morton_keys(void *ctx, uint32_t t, uint32_t threads)
{
    (void)threads;
    ordering *o = ctx;
    const double cells = (double)((1u << MORTON_BITS) - 1);
    uint32_t next = 0;
    for (uint32_t p = 0; p < t; p++) next += (uint32_t)o->parts[p].out.len;
    const tri_set *part = &o->parts[t].out;
    for (size_t i = 0; i < part->len; i++, next++) {
        const box *b = &part->boxes[i];
        uint32_t key = 0;
        for (int k = 0; k < 3; k++) {
            const double centre = 0.5 * ((double)b->lo[k] + (double)b->hi[k]);
            const double extent = (double)o->all.hi[k] - (double)o->all.lo[k];
            double cell = extent > 0 ? (centre - o->all.lo[k]) / extent * cells : 0;
            cell = cell >= 0 ? (cell <= cells ? cell : cells) : 0; /* NaN and overflow too */
            key |= spread3((uint32_t)cell) << k;
        }
        o->order[next] = (sorted_tri){key, next};
    }
}

/* Share t of the sorted triangles copied into place, their boxes into
 * their leaves' slots. */
static void gather(void *ctx, uint32_t t, uint32_t threads)
{
    ordering *o = ctx;
    uint32_t first, end;
    mt__part_range(o->c->num_tris, t, threads, &first, &end);
    for (uint32_t i = first; i < end; i++) {
        uint32_t from = o->order[i].index, p = 0;
        while (from >= o->parts[p].out.len) from -= (uint32_t)o->parts[p++].out.len;
        o->c->tris[i] = o->parts[p].out.tris[from];
        const box *b = &o->parts[p].out.boxes[from];
        leaf_boxes *leaf = &o->c->leaves[i / LEAF_SIZE];
        for (int k = 0; k < 3; k++) {
            leaf->lo[k][i % LEAF_SIZE] = b->lo[k];
            leaf->hi[k][i % LEAF_SIZE] = b->hi[k];
        }
    }
}

/* Sorts the triangles of the parts (one per thread) along the Morton curve
 * of their boxes' centres into c's arrays. */
static mt_status order_triangles(check *c, const collector *parts)
{
    ordering o = {
        .c = c, .parts = parts, .order = mt__malloc((size_t)c->num_tris * sizeof *o.order)};
    if (!o.order) return MT_ERR_NOMEM;
    box_empty(&o.all);
    for (uint32_t p = 0; p < c->threads; p++) box_add(&o.all, &parts[p].out.bounds);
    mt__in_parallel(c->threads, morton_keys, &o);
    mt_status s = radix_sort(o.order, c->num_tris);
    if (s == MT_OK) mt__in_parallel(c->threads, gather, &o);
    mt__free(o.order);
    return s;
}

/* Share t of the leaves: their node boxes, empty boxes in their slots past
 * the last triangle (gather filled the others) and which of their
 * triangles' corners have flat fans. */
static void build_leaves(void *ctx, uint32_t t, uint32_t threads)
{
    check *c = ctx;
    uint32_t first, end;
    mt__part_range(c->num_leaves, t, threads, &first, &end);
    for (uint32_t i = first * LEAF_SIZE; i < end * LEAF_SIZE && i < c->num_tris; i++) {
        const uint32_t *v = c->tris[i].v;
        c->flat_corners[i] = (uint8_t)(c->flat[v[0]] | c->flat[v[1]] << 1 | c->flat[v[2]] << 2);
    }
    const uint32_t leaves = c->num_leaves;
    for (uint32_t l = first; l < end; l++) {
        box *b = &c->nodes[leaves + l];
        leaf_boxes *lb = &c->leaves[l];
        box_empty(b);
        for (uint32_t slot = 0; slot < LEAF_SIZE; slot++) {
            const bool empty = l * LEAF_SIZE + slot >= c->num_tris; /* past the last */
            box one;
            for (int k = 0; k < 3; k++) {
                if (empty) {
                    lb->lo[k][slot] = INFINITY;
                    lb->hi[k][slot] = -INFINITY;
                }
                one.lo[k] = lb->lo[k][slot];
                one.hi[k] = lb->hi[k][slot];
            }
            box_add(b, &one);
        }
    }
}

/* The tree's node boxes, leaves up, the leaves' triangle boxes and the
 * triangles' flat corners. */
static void build_tree(check *c)
{
    mt__in_parallel(c->threads, build_leaves, c);
    for (uint32_t k = c->num_leaves - 1; k >= 1; k--) {
        c->nodes[k] = c->nodes[2 * k];
        box_add(&c->nodes[k], &c->nodes[2 * k + 1]);
    }
}

static int compare_pairs(const void *pa, const void *pb)
{
    const mt_face_pair *a = pa, *b = pb;
    if (a->a != b->a) return a->a < b->a ? -1 : 1;
    return (a->b > b->b) - (a->b < b->b);
}

/* Sorts the pairs and drops repeats (a pair of polygons meets once per
 * pair of their triangles that cross). */
static void sort_unique(mt__vec *pairs)
{
    mt_face_pair *p = pairs->data;
    if (pairs->len > 1) qsort(p, pairs->len, sizeof *p, compare_pairs);
    size_t kept = 0;
    for (size_t i = 0; i < pairs->len; i++)
        if (kept == 0 || compare_pairs(&p[kept - 1], &p[i]) != 0) p[kept++] = p[i];
    pairs->len = kept;
}

/* Adds a pair to a worker's list. Once the list doubles past max_pairs,
 * its repeats are dropped: more than max_pairs left then is more than the
 * caller takes, and the search ends, so memory stays within about twice
 * max_pairs per thread however many faces are piled on one another. */
static mt_status add_pair(worker *w, const mt_face_pair *p)
{
    mt_status s = mt__vec_push(&w->pairs, p);
    if (s != MT_OK || w->pairs.len < w->compact_at) return s;
    sort_unique(&w->pairs);
    if (w->pairs.len > w->c->max_pairs) {
        atomic_store(&w->c->too_many, true);
        return MT_ERR_TOO_LARGE;
    }
    return MT_OK;
}

/* Adds a worker's uncounted tests to the total: MT_ERR_TOO_LARGE once it
 * passes max_tests. The total only grows, so whether it passes does not
 * depend on how the threads shared the work. */
static mt_status count_tests(worker *w)
{
    check *c = w->c;
    const uint64_t total = atomic_fetch_add(&c->tests, w->uncounted) + w->uncounted;
    w->uncounted = 0;
    if (total <= c->max_tests) return MT_OK;
    atomic_store(&c->too_many_tests, true);
    return MT_ERR_TOO_LARGE;
}

/* Narrow phase of triangles i and j (different faces). */
static mt_status test_pair(const check *c, uint32_t i, uint32_t j, worker *w)
{
    if (++w->uncounted == TEST_BATCH) {
        mt_status s = count_tests(w);
        if (s != MT_OK) return s;
    }
    const mt__tri *a = &c->tris[i], *b = &c->tris[j];
    const double *pos = c->m->positions;
    const double *const pa[3] = {pos + 3 * (size_t)a->v[0], pos + 3 * (size_t)a->v[1],
                                 pos + 3 * (size_t)a->v[2]};
    const double *const pb[3] = {pos + 3 * (size_t)b->v[0], pos + 3 * (size_t)b->v[1],
                                 pos + 3 * (size_t)b->v[2]};
    if (!mt__triangles_cross(a->v, pa, b->v, pb)) return MT_OK;
    const mt_face_pair p = {a->face < b->face ? a->face : b->face,
                            a->face < b->face ? b->face : a->face};
    return add_pair(w, &p);
}

/* The triangles of leaf node k: [*first, *end). */
static void leaf_range(const check *c, uint32_t k, uint32_t *first, uint32_t *end)
{
    const uint64_t lo = (uint64_t)(k - c->num_leaves) * LEAF_SIZE, hi = lo + LEAF_SIZE;
    *first = lo < c->num_tris ? (uint32_t)lo : c->num_tris;
    *end = hi < c->num_tris ? (uint32_t)hi : c->num_tris;
}

/* Whether triangles i and j share a corner with a flat fan: then they
 * meet only at their shared corners and sides. */
static bool share_flat_corner(const check *c, uint32_t i, uint32_t j)
{
    const uint32_t *a = c->tris[i].v, *b = c->tris[j].v;
    for (int k = 0; k < 3; k++)
        if ((c->flat_corners[i] >> k & 1u) && (a[k] == b[0] || a[k] == b[1] || a[k] == b[2]))
            return true;
    return false;
}

/* Bit s set: the box of slot s of `leaf` overlaps box (lo, hi). */
static unsigned overlapping_slots(const leaf_boxes *leaf, const float lo[3], const float hi[3])
{
    unsigned bits = 0;
    for (int first = 0; first < LEAF_SIZE; first += 4) {
        v4i meet = {-1, -1, -1, -1};
        for (int k = 0; k < 3; k++) {
            v4f leaf_lo, leaf_hi;
            memcpy(&leaf_lo, &leaf->lo[k][first], sizeof leaf_lo);
            memcpy(&leaf_hi, &leaf->hi[k][first], sizeof leaf_hi);
            const v4f box_lo = {lo[k], lo[k], lo[k], lo[k]};
            const v4f box_hi = {hi[k], hi[k], hi[k], hi[k]};
            meet &= (leaf_lo <= box_hi) & (box_lo <= leaf_hi);
        }
        bits |= ((unsigned)(meet[0] != 0) | (unsigned)(meet[1] != 0) << 1 |
                 (unsigned)(meet[2] != 0) << 2 | (unsigned)(meet[3] != 0) << 3)
                << first;
    }
    return bits;
}

/* Every triangle of leaf a against every one of leaf b (each pair once
 * when a == b) whose boxes overlap: those of different faces that share no
 * corner with a flat fan go to the narrow phase. */
static mt_status leaf_pairs(const check *c, uint32_t a, uint32_t b, worker *w)
{
    uint32_t a0, a1;
    leaf_range(c, a, &a0, &a1);
    uint32_t b0, b1;
    leaf_range(c, b, &b0, &b1);
    /* An empty slot's box (+inf to -inf) still meets a box that spans
     * every axis from -inf to +inf: only the slots holding triangles count. */
    const unsigned filled = (1u << (b1 - b0)) - 1;
    const leaf_boxes *la = &c->leaves[a - c->num_leaves], *lb = &c->leaves[b - c->num_leaves];
    for (uint32_t i = a0; i < a1; i++) {
        const uint32_t slot = i - a0;
        const float lo[3] = {la->lo[0][slot], la->lo[1][slot], la->lo[2][slot]};
        const float hi[3] = {la->hi[0][slot], la->hi[1][slot], la->hi[2][slot]};
        unsigned hits = overlapping_slots(lb, lo, hi) & filled;
        if (a == b) hits &= ~((2u << slot) - 1); /* the later triangles only */
        for (; hits; hits &= hits - 1) {
            const uint32_t j = b0 + (uint32_t)__builtin_ctz(hits);
            if (c->tris[i].face == c->tris[j].face || share_flat_corner(c, i, j)) continue;
            mt_status s = test_pair(c, i, j, w);
            if (s != MT_OK) return s;
        }
    }
    return MT_OK;
}

/* The pairs of children of p whose boxes overlap, into out; their count. */
static int children(const check *c, node_pair p, node_pair out[4])
{
    int n = 0;
    const uint32_t a = 2 * p.a, b = 2 * p.b;
    if (p.a == p.b) { /* a node with itself: each child with itself unless empty, and the two */
        for (uint32_t k = a; k <= a + 1; k++)
            if (c->nodes[k].lo[0] <= c->nodes[k].hi[0]) out[n++] = (node_pair){k, k};
        if (overlap(&c->nodes[a], &c->nodes[a + 1])) out[n++] = (node_pair){a, a + 1};
        return n;
    }
    const node_pair all[4] = {{a, b}, {a, b + 1}, {a + 1, b + 1}, {a + 1, b}};
    for (int i = 0; i < 4; i++)
        if (overlap(&c->nodes[all[i].a], &c->nodes[all[i].b])) out[n++] = all[i];
    return n;
}

/* Depth first from one pair of nodes down to pairs of leaves. */
static mt_status traverse(const check *c, node_pair start, worker *w)
{
    node_pair stack[4 * 32]; /* up to 3 more per level, 31 levels at most */
    int top = 0;
    stack[top++] = start;
    while (top > 0) {
        const node_pair p = stack[--top];
        if (p.a >= c->num_leaves) {
            mt_status s = leaf_pairs(c, p.a, p.b, w);
            if (s != MT_OK) return s;
            continue;
        }
        top += children(c, p, stack + top);
    }
    return MT_OK;
}

/* Part t: tasks taken from the shared counter until none is left. */
static void run_tasks(void *ctx, uint32_t t, uint32_t threads)
{
    (void)threads;
    worker *w = &((worker *)ctx)[t];
    check *c = w->c;
    for (;;) {
        const uint32_t task = atomic_fetch_add(&c->next, 1);
        if (task >= c->num_tasks || atomic_load(&c->failed)) break;
        if (traverse(c, c->tasks[task], w) != MT_OK) {
            atomic_store(&c->failed, true);
            return;
        }
    }
    if (count_tests(w) != MT_OK) atomic_store(&c->failed, true);
}

/* The pairs of nodes at the first depth with at least `want` of them (or
 * the leaves' depth), for the threads to share. */
static mt_status make_tasks(check *c, uint32_t want)
{
    mt__vec level = {.elem_size = sizeof(node_pair)}, next = {.elem_size = sizeof(node_pair)};
    const node_pair root = {1, 1};
    mt_status s = overlap(&c->nodes[1], &c->nodes[1]) ? mt__vec_push(&level, &root) : MT_OK;
    uint32_t depth_first = 1; /* first node id of the current depth */
    while (s == MT_OK && level.len > 0 && level.len < want && depth_first < c->num_leaves) {
        next.len = 0;
        for (size_t i = 0; i < level.len && s == MT_OK; i++) {
            node_pair kids[4];
            const int n = children(c, ((const node_pair *)level.data)[i], kids);
            for (int k = 0; k < n && s == MT_OK; k++) s = mt__vec_push(&next, &kids[k]);
        }
        mt__vec t = level;
        level = next;
        next = t;
        depth_first *= 2;
    }
    mt__vec_free(&next);
    if (s != MT_OK) {
        mt__vec_free(&level);
        return s;
    }
    c->tasks = level.data;
    c->num_tasks = (uint32_t)level.len;
    return MT_OK;
}

/* Runs the queries on up to MT__MAX_THREADS threads and gathers their pairs,
 * sorted and without repeats, into out (MT_ERR_TOO_LARGE past max_pairs). */
static mt_status run_all(check *c, mt__vec *out)
{
    const uint32_t threads = c->threads;
    mt_status made = make_tasks(c, TASKS_PER_THREAD * threads);
    if (made != MT_OK) return made;
    const size_t compact_at = c->max_pairs < (SIZE_MAX - 64) / 2 ? 2 * c->max_pairs + 64 : SIZE_MAX;
    worker workers[MT__MAX_THREADS];
    for (uint32_t t = 0; t < threads; t++)
        workers[t] = (worker){
            .c = c, .pairs = {.elem_size = sizeof(mt_face_pair)}, .compact_at = compact_at};
    mt__in_parallel(threads, run_tasks, workers);
    mt_status s = MT_OK;
    for (uint32_t t = 0; t < threads; t++) {
        if (s == MT_OK && !atomic_load(&c->failed)) s = mt__vec_append(out, &workers[t].pairs);
        mt__vec_free(&workers[t].pairs);
    }
    if (s == MT_OK && atomic_load(&c->failed))
        s = atomic_load(&c->too_many) || atomic_load(&c->too_many_tests) ? MT_ERR_TOO_LARGE
                                                                         : MT_ERR_NOMEM;
    if (s != MT_OK) return s;
    sort_unique(out);
    return out->len > c->max_pairs ? MT_ERR_TOO_LARGE : MT_OK;
}

/* Every intersecting pair into pairs (sorted, no repeats), or
 * MT_ERR_TOO_LARGE once more than max_pairs are found or more than
 * max_tests exact tests are needed. */
static mt_status find_pairs(const mt_mesh *m, size_t max_pairs, uint64_t max_tests, mt__vec *pairs,
                            mt_diag *diag, const char *what)
{
    collector parts[MT__MAX_THREADS];
    const uint32_t threads = threads_for(m->num_faces);
    uint8_t *flat = mt__malloc(m->num_verts);
    if (!flat)
        return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "%s: no memory for %u vertices", what,
                        m->num_verts);
    mt_status s = collect(m, threads, parts, flat, diag, what);
    size_t total = 0;
    for (uint32_t t = 0; t < threads; t++) total += parts[t].out.len;
    check c = {.m = m,
               .num_tris = (uint32_t)total,
               .num_leaves = 1,
               .threads = threads,
               .max_pairs = max_pairs,
               .max_tests = max_tests};
    if (s == MT_OK && total >= 2) {
        const uint64_t blocks = ((uint64_t)c.num_tris + LEAF_SIZE - 1) / LEAF_SIZE;
        while (c.num_leaves < blocks) c.num_leaves *= 2;
        atomic_init(&c.next, 0);
        atomic_init(&c.failed, false);
        atomic_init(&c.too_many, false);
        atomic_init(&c.too_many_tests, false);
        atomic_init(&c.tests, 0);
        c.tris = mt__malloc((size_t)c.num_tris * sizeof *c.tris);
        c.nodes = mt__malloc(2 * (size_t)c.num_leaves * sizeof *c.nodes);
        c.leaves = mt__malloc((size_t)c.num_leaves * sizeof *c.leaves);
        c.flat_corners = mt__malloc(c.num_tris);
        s = c.tris && c.nodes && c.leaves && c.flat_corners ? order_triangles(&c, parts)
                                                            : MT_ERR_NOMEM;
        for (uint32_t t = 0; t < threads; t++) tri_set_free(&parts[t].out);
        if (s == MT_OK) s = mt__flat_fans(m, c.tris, c.num_tris, threads, flat);
        if (s == MT_OK) {
            c.flat = flat;
            build_tree(&c);
            s = run_all(&c, pairs);
        }
        if (s == MT_ERR_NOMEM)
            mt__fail(diag, s, MT_NONE, "%s: no memory for %u triangles and their pairs", what,
                     c.num_tris);
        if (s == MT_ERR_TOO_LARGE && atomic_load(&c.too_many_tests))
            mt__fail(diag, s, MT_NONE,
                     "%s: more than %" PRIu64
                     " pairs of triangles whose boxes overlap "
                     "to test (faces piled on one another)",
                     what, max_tests);
        else if (s == MT_ERR_TOO_LARGE)
            mt__fail(diag, s, MT_NONE, "%s: more than %zu self-intersecting face pairs", what,
                     max_pairs);
    }
    for (uint32_t t = 0; t < threads; t++) tri_set_free(&parts[t].out);
    mt__free(c.tris);
    mt__free(c.nodes);
    mt__free(c.leaves);
    mt__free(c.flat_corners);
    mt__free(c.tasks);
    mt__free(flat);
    return s;
}

mt_status mt_mesh_self_intersections_at_most(const mt_mesh *mesh, size_t max_count,
                                             uint64_t max_tests, mt_face_pair *out, size_t capacity,
                                             size_t *out_count, mt_diag *diag)
{
    static const char what[] = "mt_mesh_self_intersections";
    mt_diag_clear(diag);
    if (out_count) *out_count = 0;
    if (!out_count) return mt_diag_set(diag, MT_ERR_INVALID_ARG, "%s: out_count is NULL", what);
    mt_status s = mt__geom_ready(mesh, what, diag);
    if (s != MT_OK) return s;
    mt__vec pairs = {.elem_size = sizeof(mt_face_pair)};
    s = find_pairs(mesh, max_count, max_tests, &pairs, diag, what);
    if (s == MT_OK) {
        *out_count = pairs.len;
        if (out && capacity > 0 && pairs.len > 0)
            memcpy(out, pairs.data, (pairs.len < capacity ? pairs.len : capacity) * sizeof *out);
        if (out && capacity > 0 && pairs.len > capacity)
            s = mt_diag_set(diag, MT_ERR_BUFFER_TOO_SMALL, "%s: %zu pairs, room for %zu", what,
                            pairs.len, capacity);
    }
    mt__vec_free(&pairs);
    return s;
}

mt_status mt_mesh_self_intersections(const mt_mesh *mesh, mt_face_pair *out, size_t capacity,
                                     size_t *out_count, mt_diag *diag)
{
    return mt_mesh_self_intersections_at_most(mesh, SIZE_MAX, UINT64_MAX, out, capacity, out_count,
                                              diag);
}
