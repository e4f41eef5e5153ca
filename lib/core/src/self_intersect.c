/* Mesh self-intersections (meshtopo/geometry.h). Every face becomes
 * triangles (polygons by polygon_ears.c); the triangles are sorted along a
 * Morton curve of their centroids so that neighbours in space are neighbours
 * in memory, and a bounding-volume hierarchy is laid over them as a complete
 * binary tree (node k has children 2k and 2k + 1, leaves hold LEAF_SIZE
 * consecutive triangles). Each triangle then looks in the tree for the later
 * triangles whose boxes overlap its own, so every pair is met once, and the
 * exact narrow phase (mt__triangles_cross) decides. The queries are
 * independent: threads take chunks of triangles from a shared counter.
 * Boxes are floats rounded outwards, so they never miss a pair. */
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geometry_internal.h"

enum {
    LEAF_SIZE = 4,        /* triangles per leaf of the tree */
    CHUNK = 1024,         /* triangles a thread takes at once */
    MAX_THREADS = 8,      /* the most threads the queries use */
    MIN_PARALLEL = 20000, /* fewer triangles than this are checked on one thread */
    MORTON_BITS = 10,     /* bits per axis of a centroid's cell */
    RADIX_BITS = 10       /* bits per pass of the sort */
};

typedef struct tri {
    uint32_t v[3]; /* caller vertex ids */
    uint32_t face;
} tri;

typedef struct box {
    float lo[3], hi[3];
} box;

typedef struct sorted_tri {
    uint32_t key; /* Morton code of the centroid */
    uint32_t index;
} sorted_tri;

typedef struct check {
    const mt_mesh *m;
    tri *tris; /* in Morton order */
    box *boxes;
    uint32_t num_tris;
    box *nodes;          /* [2 * num_leaves]; node 0 unused */
    uint32_t num_leaves; /* a power of two */
    atomic_uint next;    /* first triangle of the next chunk */
    atomic_bool failed;  /* a thread ran out of memory */
} check;

typedef struct worker {
    pthread_t thread;
    check *c;
    mt__vec pairs; /* mt_face_pair, unsorted, possibly repeated */
} worker;

/* x rounded to a float not above it (not below it: up). */
static float down(double x)
{
    if (x >= FLT_MAX) return FLT_MAX;
    if (x < -FLT_MAX) return -INFINITY;
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

static float up(double x)
{
    if (x <= -FLT_MAX) return -FLT_MAX;
    if (x > FLT_MAX) return INFINITY;
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
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
        b->lo[k] = fminf(b->lo[k], o->lo[k]);
        b->hi[k] = fmaxf(b->hi[k], o->hi[k]);
    }
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
        if (v == MT_NONE) {
            *status = MT_ERR_CORRUPT;
            return 0;
        }
        if (mt__vec_push(verts, &v) != MT_OK) {
            *status = MT_ERR_NOMEM;
            return 0;
        }
        if (!mt__ring_step(m, &h, &steps)) {
            *status = MT_ERR_CORRUPT;
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

/* Appends the triangles of face f (corners verts[0..n)) to tris. */
static mt_status add_face(const mt_mesh *m, uint32_t f, const uint32_t *verts, uint32_t n,
                          mt__vec *tris)
{
    if (n == 3) {
        const tri t = {{verts[0], verts[1], verts[2]}, f};
        return mt__vec_push(tris, &t);
    }
    const double **pos = mt__malloc(n * sizeof *pos);
    uint32_t *scratch = mt__malloc((size_t)(n + 3 * (n - 2)) * sizeof *scratch);
    mt_status s = pos && scratch ? MT_OK : MT_ERR_NOMEM;
    if (s == MT_OK) {
        for (uint32_t i = 0; i < n; i++) pos[i] = m->positions + 3 * (size_t)verts[i];
        uint32_t *corners = scratch + n;
        mt__ear_clip(pos, n, NULL, NULL, scratch, corners);
        for (uint32_t t = 0; t < n - 2 && s == MT_OK; t++) {
            const uint32_t *c = corners + 3 * t;
            const tri one = {{verts[c[0]], verts[c[1]], verts[c[2]]}, f};
            s = mt__vec_push(tris, &one);
        }
    }
    mt__free(pos);
    mt__free(scratch);
    return s;
}

/* Every judged face's triangles into tris. */
static mt_status collect(const mt_mesh *m, mt__vec *tris, mt_diag *diag, const char *what)
{
    mt__vec verts = {.elem_size = sizeof(uint32_t)};
    mt_status s = MT_OK;
    for (uint32_t f = 0; f < m->num_faces && s == MT_OK; f++) {
        if (m->face_he[f] == MT_NONE) continue; /* rejected or deleted */
        const uint32_t n = face_corners(m, f, &verts, &s);
        if (n == 0) {
            mt__fail(diag, s, f, "%s: %s face %u", what,
                     s == MT_ERR_NOMEM ? "no memory for" : "broken ring of", f);
            break;
        }
        if (n < 3 || !finite_corners(m, verts.data, n)) continue;
        s = add_face(m, f, verts.data, n, tris);
        if (s != MT_OK) mt__fail(diag, s, f, "%s: no memory for the triangles of face %u", what, f);
    }
    mt__vec_free(&verts);
    return s;
}

/* Spreads the low MORTON_BITS bits of x to every third bit. */
static uint32_t spread3(uint32_t x)
{
    uint32_t r = 0;
    for (int b = 0; b < MORTON_BITS; b++) r |= ((x >> b) & 1u) << (3 * b);
    return r;
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

static void tri_box(const mt_mesh *m, const tri *t, box *b)
{
    for (int k = 0; k < 3; k++) {
        double lo = INFINITY, hi = -INFINITY;
        for (int i = 0; i < 3; i++) {
            const double x = m->positions[3 * (size_t)t->v[i] + k];
            lo = fmin(lo, x);
            hi = fmax(hi, x);
        }
        b->lo[k] = down(lo);
        b->hi[k] = up(hi);
    }
}

/* Sorts the triangles along the Morton curve and computes their boxes. */
static mt_status order_triangles(check *c, tri *unsorted)
{
    const uint32_t n = c->num_tris;
    sorted_tri *order = mt__malloc((size_t)n * sizeof *order);
    if (!order) return MT_ERR_NOMEM;
    /* The cells span the first corners' bounds; centroids beyond go to the edge cells. */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            const double x = c->m->positions[3 * (size_t)unsorted[i].v[0] + k];
            lo[k] = fmin(lo[k], x);
            hi[k] = fmax(hi[k], x);
        }
    const double cells = (double)((1u << MORTON_BITS) - 1);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t key = 0;
        for (int k = 0; k < 3; k++) {
            double centroid = 0;
            for (int j = 0; j < 3; j++)
                centroid += c->m->positions[3 * (size_t)unsorted[i].v[j] + k] / 3;
            const double extent = hi[k] - lo[k];
            double cell = extent > 0 ? (centroid - lo[k]) / extent * cells : 0;
            cell = cell >= 0 ? (cell <= cells ? cell : cells) : 0; /* NaN too */
            key |= spread3((uint32_t)cell) << k;
        }
        order[i] = (sorted_tri){key, i};
    }
    mt_status s = radix_sort(order, n);
    if (s == MT_OK)
        for (uint32_t i = 0; i < n; i++) {
            c->tris[i] = unsorted[order[i].index];
            tri_box(c->m, &c->tris[i], &c->boxes[i]);
        }
    mt__free(order);
    return s;
}

/* The tree's node boxes, leaves up. */
static void build_tree(check *c)
{
    const uint32_t leaves = c->num_leaves;
    for (uint32_t l = 0; l < leaves; l++) {
        box *b = &c->nodes[leaves + l];
        box_empty(b);
        for (uint32_t i = l * LEAF_SIZE; i < (l + 1) * LEAF_SIZE && i < c->num_tris; i++)
            box_add(b, &c->boxes[i]);
    }
    for (uint32_t k = leaves - 1; k >= 1; k--) {
        c->nodes[k] = c->nodes[2 * k];
        box_add(&c->nodes[k], &c->nodes[2 * k + 1]);
    }
}

/* A node of the tree to visit, with the range of leaves it covers. */
typedef struct frame {
    uint32_t node, first, end;
} frame;

/* Narrow phase of triangles i and j (different faces). */
static mt_status test_pair(const check *c, uint32_t i, uint32_t j, mt__vec *pairs)
{
    const tri *a = &c->tris[i], *b = &c->tris[j];
    const double *const pa[3] = {c->m->positions + 3 * (size_t)a->v[0],
                                 c->m->positions + 3 * (size_t)a->v[1],
                                 c->m->positions + 3 * (size_t)a->v[2]};
    const double *const pb[3] = {c->m->positions + 3 * (size_t)b->v[0],
                                 c->m->positions + 3 * (size_t)b->v[1],
                                 c->m->positions + 3 * (size_t)b->v[2]};
    if (!mt__triangles_cross(a->v, pa, b->v, pb)) return MT_OK;
    const mt_face_pair p = {a->face < b->face ? a->face : b->face,
                            a->face < b->face ? b->face : a->face};
    return mt__vec_push(pairs, &p);
}

/* Triangle i against every later triangle whose box overlaps its own. */
static mt_status query(const check *c, uint32_t i, mt__vec *pairs)
{
    frame stack[64]; /* two per level of at most 31 */
    int top = 0;
    stack[top++] = (frame){1, 0, c->num_leaves};
    const box *mine = &c->boxes[i];
    while (top > 0) {
        const uint32_t k = stack[top - 1].node, first = stack[top - 1].first,
                       end = stack[top - 1].end;
        top--;
        const uint64_t stop =
            (uint64_t)end * LEAF_SIZE < c->num_tris ? (uint64_t)end * LEAF_SIZE : c->num_tris;
        if (stop <= (uint64_t)i + 1) continue; /* no later triangle */
        if (!overlap(&c->nodes[k], mine)) continue;
        if (k >= c->num_leaves) {
            const uint32_t from = first * LEAF_SIZE > i ? first * LEAF_SIZE : i + 1;
            for (uint32_t j = from; j < stop; j++) {
                if (c->tris[j].face == c->tris[i].face || !overlap(&c->boxes[j], mine)) continue;
                mt_status s = test_pair(c, i, j, pairs);
                if (s != MT_OK) return s;
            }
            continue;
        }
        const uint32_t mid = first + (end - first) / 2;
        stack[top++] = (frame){2 * k + 1, mid, end};
        stack[top++] = (frame){2 * k, first, mid};
    }
    return MT_OK;
}

static void *run_queries(void *arg)
{
    worker *w = arg;
    check *c = w->c;
    for (;;) {
        const uint32_t first = atomic_fetch_add(&c->next, CHUNK);
        if (first >= c->num_tris || atomic_load(&c->failed)) break;
        const uint32_t end = c->num_tris - first < CHUNK ? c->num_tris : first + CHUNK;
        for (uint32_t i = first; i < end; i++)
            if (query(c, i, &w->pairs) != MT_OK) {
                atomic_store(&c->failed, true);
                return NULL;
            }
    }
    return NULL;
}

static int compare_pairs(const void *pa, const void *pb)
{
    const mt_face_pair *a = pa, *b = pb;
    if (a->a != b->a) return a->a < b->a ? -1 : 1;
    return (a->b > b->b) - (a->b < b->b);
}

/* Runs the queries on up to MAX_THREADS threads and gathers their pairs,
 * sorted and without repeats, into out. */
static mt_status run_all(check *c, mt__vec *out)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    uint32_t threads = c->num_tris < MIN_PARALLEL || cores < 2 ? 1 : (uint32_t)cores;
    if (threads > MAX_THREADS) threads = MAX_THREADS;
    worker workers[MAX_THREADS];
    bool started[MAX_THREADS] = {false};
    for (uint32_t t = 0; t < threads; t++)
        workers[t] = (worker){.c = c, .pairs = {.elem_size = sizeof(mt_face_pair)}};
    for (uint32_t t = 1; t < threads; t++)
        started[t] = pthread_create(&workers[t].thread, NULL, run_queries, &workers[t]) == 0;
    run_queries(&workers[0]); /* a thread that did not start leaves its share to this one */
    mt_status s = MT_OK;
    for (uint32_t t = 0; t < threads; t++) {
        if (started[t]) pthread_join(workers[t].thread, NULL);
        if (s == MT_OK && !atomic_load(&c->failed)) s = mt__vec_append(out, &workers[t].pairs);
        mt__vec_free(&workers[t].pairs);
    }
    if (s == MT_OK && atomic_load(&c->failed)) s = MT_ERR_NOMEM;
    if (s != MT_OK) return s;
    mt_face_pair *p = out->data;
    if (out->len > 1) qsort(p, out->len, sizeof *p, compare_pairs);
    size_t kept = 0;
    for (size_t i = 0; i < out->len; i++)
        if (kept == 0 || compare_pairs(&p[kept - 1], &p[i]) != 0) p[kept++] = p[i];
    out->len = kept;
    return MT_OK;
}

/* Every intersecting pair into pairs (sorted, no repeats). */
static mt_status find_pairs(const mt_mesh *m, mt__vec *pairs, mt_diag *diag, const char *what)
{
    mt__vec unsorted = {.elem_size = sizeof(tri)};
    mt_status s = collect(m, &unsorted, diag, what);
    if (s != MT_OK || unsorted.len < 2) {
        mt__vec_free(&unsorted);
        return s;
    }
    check c = {.m = m, .num_tris = (uint32_t)unsorted.len, .num_leaves = 1};
    const uint64_t blocks = ((uint64_t)c.num_tris + LEAF_SIZE - 1) / LEAF_SIZE;
    while (c.num_leaves < blocks) c.num_leaves *= 2;
    atomic_init(&c.next, 0);
    atomic_init(&c.failed, false);
    c.tris = mt__malloc((size_t)c.num_tris * sizeof *c.tris);
    c.boxes = mt__malloc((size_t)c.num_tris * sizeof *c.boxes);
    c.nodes = mt__malloc(2 * (size_t)c.num_leaves * sizeof *c.nodes);
    s = c.tris && c.boxes && c.nodes ? order_triangles(&c, unsorted.data) : MT_ERR_NOMEM;
    mt__vec_free(&unsorted);
    if (s == MT_OK) {
        build_tree(&c);
        s = run_all(&c, pairs);
    }
    if (s == MT_ERR_NOMEM)
        mt__fail(diag, s, MT_NONE, "%s: no memory for %u triangles and their pairs", what,
                 c.num_tris);
    mt__free(c.tris);
    mt__free(c.boxes);
    mt__free(c.nodes);
    return s;
}

mt_status mt_mesh_self_intersections(const mt_mesh *mesh, mt_face_pair *out, size_t capacity,
                                     size_t *out_count, mt_diag *diag)
{
    static const char what[] = "mt_mesh_self_intersections";
    mt_diag_clear(diag);
    if (out_count) *out_count = 0;
    if (!out_count) return mt_diag_set(diag, MT_ERR_INVALID_ARG, "%s: out_count is NULL", what);
    mt_status s = mt__geom_ready(mesh, what, diag);
    if (s != MT_OK) return s;
    mt__vec pairs = {.elem_size = sizeof(mt_face_pair)};
    s = find_pairs(mesh, &pairs, diag, what);
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
