/* Build phase "fans": completes each vertex. The outgoing half-edges of a
 * vertex are rotated with r(h) = next(twin(h)). The usual vertex has one
 * fan: a closed cycle, or an open one from the face half-edge after its
 * boundary half-edge to the face half-edge whose twin is a boundary
 * half-edge; that boundary half-edge's next is then set, closing the
 * boundary ring through the vertex. Both are checked by walking the fan once
 * and counting its half-edges against the vertex's corners. A vertex with
 * several fans (a bowtie, or the sheets meeting at a non-manifold edge)
 * keeps its first fan and gets one new internal vertex, a copy, per further
 * fan, so that every internal vertex has exactly one fan (Botsch et al.,
 * "Polygon Mesh Processing", 2010, section 2.2: non-manifold vertices split
 * per fan). */
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "build/build_phases.h"

/* vert_he of a vertex that several boundary half-edges leave, and of one
 * waiting for the general case, while the fans are made. Half-edge ids stay
 * below 2^31. */
#define MT__SEVERAL_BOUNDARY (MT_NONE - 1)
#define MT__NEEDS_SPLIT (MT_NONE - 2)

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

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

/* Corners leaving v in valid faces: as many as its outgoing face half-edges. */
static uint32_t out_degree(const mt__build *b, uint32_t v)
{
    uint32_t n = 0;
    for (uint32_t t = 0; t < b->parts; t++) n += b->part[t].degree[v];
    return n;
}

/* Puts into vert_he the boundary half-edge leaving each vertex, or
 * MT__SEVERAL_BOUNDARY. On one thread: any part may have made them. */
static void mark_boundary_out(mt__build *b)
{
    mt_mesh *m = b->m;
    const uint32_t *halves = b->boundary_halves.data;
    for (size_t i = 0; i < b->boundary_halves.len; i++) {
        const uint32_t h = halves[i], tail = m->he_head[h ^ 1u];
        m->vert_he[tail] = m->vert_he[tail] == MT_NONE ? h : MT__SEVERAL_BOUNDARY;
    }
}

/* The usual vertex has one fan, checked by walking it and counting its n
 * outgoing face half-edges. A closed fan is walked from the half-edge the
 * links phase offered and starts at its smallest half-edge, whichever was
 * offered. An open one is walked from the face half-edge after the boundary
 * half-edge leaving v to the face half-edge whose twin, the boundary
 * half-edge entering v, has no next yet: that one gets the boundary
 * half-edge leaving v, closing the ring. (Until this phase half-edges
 * without a face have next MT_NONE, and only v's own fan sets the next of
 * one entering v.) A vertex whose walk fails goes to split_fans.
 *
 * Each step of a walk waits for the load of the step before, so several
 * vertices are walked at once, each step fetching ahead what its walk's
 * next step reads: MT__FAN_WALKS loads in flight instead of one. On a mesh
 * larger than the cache that is most of this phase's time. A round over
 * the walks must take longer than a load from memory, or the step waits
 * for its own prefetch: on a shuffled mesh of millions of triangles the
 * phase ran about three times as fast with 128 walks as with 16, and no
 * faster with more. */
#define MT__FAN_WALKS 128

typedef struct fan_walk {
    uint32_t v, n, steps;
    uint32_t start;    /* closed: where the walk began; open: the boundary half-edge leaving v */
    uint32_t h;        /* the outgoing half-edge reached */
    uint32_t smallest; /* closed: smallest outgoing half-edge seen */
    int open;
} fan_walk;

static void needs_split(mt__part *p, uint32_t v)
{
    if (mt__vec_push(&p->split_verts, &v) != MT_OK) p->status = MT_ERR_NOMEM;
}

/* Starts v's walk: 0 when there is nothing to walk (no corners, or several
 * boundary half-edges leaving v, which goes straight to split_fans). */
static int walk_begin(mt__build *b, mt__part *p, uint32_t v, fan_walk *w)
{
    const mt_mesh *m = b->m;
    const uint32_t n = out_degree(b, v), b_out = m->vert_he[v];
    if (n == 0) return 0;
    if (b_out == MT__SEVERAL_BOUNDARY) {
        needs_split(p, v);
        return 0;
    }
    w->v = v;
    w->n = n;
    w->open = b_out != MT_NONE;
    if (w->open) {
        w->start = b_out;
        w->h = m->he_next[b_out ^ 1u];
        w->steps = 1;
    } else {
        w->start = w->h = w->smallest =
            atomic_load_explicit(&b->fan_start[v], memory_order_relaxed);
        w->steps = 0;
    }
    __builtin_prefetch(&m->he_next[w->h ^ 1u]);
    return 1;
}

static void closed_fan_done(mt__build *b, mt__part *p, const fan_walk *w)
{
    mt_mesh *m = b->m;
    m->vert_he[w->v] = w->smallest;
    if (w->n != 2) return;
    const uint32_t faces[2] = {m->he_face[w->start], m->he_face[m->he_next[w->start ^ 1u]]};
    if (mt__vec_push(&p->dup_candidates, &faces[0]) != MT_OK ||
        mt__vec_push(&p->dup_candidates, &faces[1]) != MT_OK)
        p->status = MT_ERR_NOMEM;
}

/* One step of a walk; 0 once it has ended (and its vertex is done). */
static int walk_step(mt__build *b, mt__part *p, fan_walk *w)
{
    uint32_t *he_next = b->m->he_next;
    const uint32_t next = he_next[w->h ^ 1u];
    if (w->open) {
        if (next == MT_NONE) {
            if (w->steps == w->n)
                he_next[w->h ^ 1u] = w->start; /* close the boundary ring through v */
            else
                needs_split(p, w->v);
            return 0;
        }
        if (w->steps == w->n) {
            needs_split(p, w->v);
            return 0;
        }
        w->h = next;
        w->steps++;
        __builtin_prefetch(&he_next[next ^ 1u]);
        return 1;
    }
    if (next == MT_NONE) { /* a half-edge without a face enters v */
        needs_split(p, w->v);
        return 0;
    }
    w->h = next;
    w->steps++;
    w->smallest = next < w->smallest ? next : w->smallest;
    if (next != w->start && w->steps < w->n) {
        __builtin_prefetch(&he_next[next ^ 1u]);
        return 1;
    }
    if (next == w->start && w->steps == w->n)
        closed_fan_done(b, p, w);
    else
        needs_split(p, w->v);
    return 0;
}

static void fans_part(mt__build *b, uint32_t t)
{
    mt__part *p = &b->part[t];
    fan_walk walks[MT__FAN_WALKS];
    uint32_t active = 0, v = p->vert_begin;
    while (p->status == MT_OK) {
        for (; active < MT__FAN_WALKS && v < p->vert_end; v++)
            active += (uint32_t)walk_begin(b, p, v, &walks[active]);
        if (active == 0) break;
        for (uint32_t i = 0; i < active;) {
            if (walk_step(b, p, &walks[i]))
                i++;
            else
                walks[i] = walks[--active];
        }
    }
}

/* The outgoing face half-edges of the vertices left for the general case,
 * in id order, found in one pass over all half-edges: verts[i]'s are
 * hs[first[i] .. first[i + 1]). */
typedef struct outgoing_lists {
    uint32_t *hs, *first, *cursor;
    uint32_t largest;
} outgoing_lists;

static mt_status gather_outgoing(mt__build *b, const uint32_t *verts, size_t count,
                                 outgoing_lists *out)
{
    mt_mesh *m = b->m;
    out->first = mt__malloc((count + 1) * sizeof(uint32_t));
    out->cursor = mt__malloc((count + 1) * sizeof(uint32_t));
    if (!out->first || !out->cursor) return MT_ERR_NOMEM;
    uint32_t total = 0;
    out->largest = 0;
    for (size_t i = 0; i < count; i++) {
        const uint32_t v = verts[i], n = out_degree(b, v);
        out->first[i] = out->cursor[i] = total;
        total += n;
        out->largest = n > out->largest ? n : out->largest;
        m->vert_he[v] = MT__NEEDS_SPLIT;
        atomic_store_explicit(&b->fan_start[v], (uint32_t)i, memory_order_relaxed);
    }
    out->first[count] = total;
    out->hs = mt__malloc((size_t)total * sizeof(uint32_t) + 1);
    if (!out->hs) return MT_ERR_NOMEM;
    for (uint32_t h = 0; h < m->num_half_edges; h++) {
        if (m->he_face[h] == MT_NONE) continue;
        const uint32_t tail = m->he_head[h ^ 1u];
        if (m->vert_he[tail] != MT__NEEDS_SPLIT) continue;
        const uint32_t i = atomic_load_explicit(&b->fan_start[tail], memory_order_relaxed);
        out->hs[out->cursor[i]++] = h;
    }
    return MT_OK;
}

/* The general case, rare and done on one thread: it makes new vertices. */
static mt_status split_vertices(mt__build *b)
{
    mt__vec candidates = b->split_verts;
    b->split_verts = (mt__vec){NULL, 0, 0, sizeof(uint32_t)};
    const uint32_t *verts = candidates.data;
    outgoing_lists lists = {NULL, NULL, NULL, 0};
    uint64_t *keys = NULL;
    mt_status status = gather_outgoing(b, verts, candidates.len, &lists);
    if (status == MT_OK) {
        size_t scratch_bytes;
        const size_t per = sizeof(uint64_t) + 1;
        if (mt__mul_size((size_t)lists.largest + 1, per, &scratch_bytes))
            keys = mt__malloc(scratch_bytes);
        if (!keys) status = MT_ERR_NOMEM;
    }
    uint8_t *flags = keys ? (uint8_t *)(keys + lists.largest + 1) : NULL;
    for (size_t i = 0; i < candidates.len && status == MT_OK; i++) {
        uint32_t v = verts[i], fans = 0;
        const uint32_t *hs = lists.hs + lists.first[i];
        status = split_fans(b, v, hs, lists.first[i + 1] - lists.first[i], keys, flags, &fans);
        if (status == MT_OK && fans > 1 && mt__vec_push(&b->split_verts, &v) != MT_OK)
            status = MT_ERR_NOMEM;
    }
    mt__vec_free(&candidates);
    mt__free(keys);
    mt__free(lists.hs);
    mt__free(lists.first);
    mt__free(lists.cursor);
    return status;
}

mt_status mt__build_fans(mt__build *b)
{
    mark_boundary_out(b);
    mt__parallel_run(b, fans_part);
    for (uint32_t t = 0; t < b->parts; t++) {
        mt__part *p = &b->part[t];
        if (p->status != MT_OK) return p->status;
        if (mt__vec_append(&b->split_verts, &p->split_verts) != MT_OK ||
            mt__vec_append(&b->dup_candidates, &p->dup_candidates) != MT_OK)
            return MT_ERR_NOMEM;
    }
    if (b->split_verts.len) {
        /* Walks end in any order; copies are made in vertex order. */
        qsort(b->split_verts.data, b->split_verts.len, sizeof(uint32_t), compare_u32);
        mt_status status = split_vertices(b);
        if (status != MT_OK) return status;
    }

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
