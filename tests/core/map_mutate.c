/* Changed versions of a block for the map tests (map_mutate.h): each change
 * appends to or edits a growable copy of the block's face list. */
#include "map_mutate.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct growing {
    double *pos;
    uint32_t nv, cap_v;
    uint32_t *sizes;
    uint32_t nf, cap_f;
    uint32_t *idx;
    uint64_t ni, cap_i;
} growing;

static void *xrealloc(void *p, size_t bytes)
{
    p = realloc(p, bytes ? bytes : 1);
    if (!p) {
        fprintf(stderr, "map_mutate: out of memory\n");
        abort();
    }
    return p;
}

static uint32_t add_vert(growing *g, const double *at)
{
    double x[3]; /* at may point into g->pos, which may move */
    memcpy(x, at, sizeof x);
    if (g->nv == g->cap_v) {
        g->cap_v = g->cap_v * 2 + 8;
        g->pos = xrealloc(g->pos, (size_t)g->cap_v * 3 * sizeof(double));
    }
    memcpy(&g->pos[3 * (size_t)g->nv], x, 3 * sizeof(double));
    return g->nv++;
}

static void add_face(growing *g, const uint32_t *v, uint32_t n)
{
    if (g->nf == g->cap_f) {
        g->cap_f = g->cap_f * 2 + 8;
        g->sizes = xrealloc(g->sizes, (size_t)g->cap_f * sizeof(uint32_t));
    }
    while (g->ni + n > g->cap_i) {
        g->cap_i = g->cap_i * 2 + 16;
        g->idx = xrealloc(g->idx, (size_t)g->cap_i * sizeof(uint32_t));
    }
    g->sizes[g->nf++] = n;
    if (n) memcpy(&g->idx[g->ni], v, (size_t)n * sizeof(uint32_t));
    g->ni += n;
}

static void from_list(growing *g, const mt_face_list *l)
{
    memset(g, 0, sizeof *g);
    for (uint32_t v = 0; v < l->num_verts; v++) add_vert(g, &l->positions[3 * (size_t)v]);
    uint64_t at = 0;
    for (uint32_t f = 0; f < l->num_faces; f++) {
        add_face(g, l->face_indices + at, l->face_sizes[f]);
        at += l->face_sizes[f];
    }
}

static void to_list(growing *g, mt_face_list *l)
{
    mt_face_list_free(l);
    l->num_verts = g->nv;
    l->num_faces = g->nf;
    l->num_indices = g->ni;
    l->positions = g->pos ? g->pos : xrealloc(NULL, 1);
    l->face_sizes = g->sizes ? g->sizes : xrealloc(NULL, 1);
    l->face_indices = g->idx ? g->idx : xrealloc(NULL, 1);
}

static uint64_t face_start(const growing *g, uint32_t f)
{
    uint64_t at = 0;
    for (uint32_t i = 0; i < f; i++) at += g->sizes[i];
    return at;
}

/* A random in-range vertex of a random face of size >= 2, or MT_NONE. */
static bool random_side(const growing *g, uint64_t *rng, uint32_t *a, uint32_t *b)
{
    if (g->nf == 0) return false;
    const uint32_t f = map_rng_below(rng, g->nf), n = g->sizes[f];
    if (n < 2) return false;
    const uint64_t at = face_start(g, f);
    const uint32_t i = map_rng_below(rng, n);
    *a = g->idx[at + i];
    *b = g->idx[at + (i + 1) % n];
    return *a < g->nv && *b < g->nv && *a != *b;
}

static void drop_faces(growing *g, uint64_t *rng)
{
    uint64_t in = 0, out = 0;
    uint32_t kept = 0;
    const uint32_t keep_one_in = 2 + map_rng_below(rng, 6);
    for (uint32_t f = 0; f < g->nf; f++) {
        const uint32_t n = g->sizes[f];
        if (map_rng_below(rng, keep_one_in) != 0) {
            memmove(&g->idx[out], &g->idx[in], (size_t)n * sizeof(uint32_t));
            g->sizes[kept++] = n;
            out += n;
        }
        in += n;
    }
    g->nf = kept;
    g->ni = out;
}

static void flip_face(growing *g, uint64_t *rng)
{
    if (g->nf == 0) return;
    const uint32_t f = map_rng_below(rng, g->nf), n = g->sizes[f];
    uint32_t *v = &g->idx[face_start(g, f)];
    for (uint32_t i = 0; i < n / 2; i++) {
        uint32_t t = v[i];
        v[i] = v[n - 1 - i];
        v[n - 1 - i] = t;
    }
}

static void duplicate_face(growing *g, uint64_t *rng)
{
    if (g->nf == 0) return;
    const uint32_t f = map_rng_below(rng, g->nf), n = g->sizes[f];
    uint32_t v[64];
    if (n > 64) return;
    memcpy(v, &g->idx[face_start(g, f)], (size_t)n * sizeof(uint32_t));
    if (map_rng_below(rng, 2)) { /* the reverse, or a rotation */
        for (uint32_t i = 0; i < n / 2; i++) {
            uint32_t t = v[i];
            v[i] = v[n - 1 - i];
            v[n - 1 - i] = t;
        }
    } else if (n > 0) {
        uint32_t t = v[0];
        memmove(v, v + 1, (size_t)(n - 1) * sizeof(uint32_t));
        v[n - 1] = t;
    }
    add_face(g, v, n);
}

/* A third (or fourth) face on a side: a fin, non-manifold where the side
 * already had two faces, a seam one when the side is on the block's border. */
static void add_fin(growing *g, uint64_t *rng)
{
    uint32_t a, b;
    if (!random_side(g, rng, &a, &b)) return;
    double x[3];
    for (int k = 0; k < 3; k++)
        x[k] = 0.5 * (g->pos[3 * (size_t)a + k] + g->pos[3 * (size_t)b + k]);
    x[2] += 0.75;
    const uint32_t c = add_vert(g, x);
    const uint32_t tri[3] = {a, b, c}, rev[3] = {b, a, c};
    add_face(g, map_rng_below(rng, 2) ? tri : rev, 3);
}

static void add_bowtie(growing *g, uint64_t *rng)
{
    if (g->nv == 0) return;
    const uint32_t a = map_rng_below(rng, g->nv);
    double x[3], y[3];
    for (int k = 0; k < 3; k++) x[k] = y[k] = g->pos[3 * (size_t)a + k];
    x[2] += 2.5;
    y[2] += 2.5;
    y[0] += 0.5;
    const uint32_t tri[3] = {a, add_vert(g, x), add_vert(g, y)};
    add_face(g, tri, 3);
}

static void add_degenerate(growing *g, uint64_t *rng)
{
    uint32_t a, b;
    if (!random_side(g, rng, &a, &b)) return;
    switch (map_rng_below(rng, 5)) {
        case 0: {
            const uint32_t v[3] = {a, a, b};
            add_face(g, v, 3);
            break;
        }
        case 1: {
            const uint32_t v[2] = {a, b};
            add_face(g, v, 2);
            break;
        }
        case 2:
            add_face(g, NULL, 0);
            break;
        case 3: { /* a new vertex on a's position: the face collapses when welded */
            const uint32_t c = add_vert(g, &g->pos[3 * (size_t)a]);
            const uint32_t v[3] = {a, b, c};
            add_face(g, v, 3);
            break;
        }
        default: { /* a long face repeating a vertex far apart (the sorted check) */
            uint32_t v[11];
            for (uint32_t i = 0; i < 11; i++) {
                double x[3] = {g->pos[3 * (size_t)a] + cos(i), g->pos[3 * (size_t)a + 1] + sin(i),
                               g->pos[3 * (size_t)a + 2] + 3.0};
                v[i] = add_vert(g, x);
            }
            if (map_rng_below(rng, 2)) v[9] = v[1];
            add_face(g, v, 11);
            break;
        }
    }
}

static void add_out_of_range(growing *g, uint64_t *rng)
{
    uint32_t a, b;
    if (!random_side(g, rng, &a, &b)) return;
    const uint32_t big = g->nv + 5 + map_rng_below(rng, 100);
    switch (map_rng_below(rng, 4)) {
        case 0: {
            const uint32_t v[3] = {a, b, big};
            add_face(g, v, 3);
            break;
        }
        case 1: {
            const uint32_t v[3] = {a, big, big};
            add_face(g, v, 3);
            break;
        }
        case 2: {
            const uint32_t v[4] = {a, big, b, MT_NONE};
            add_face(g, v, 4);
            break;
        }
        default: {
            uint32_t v[10];
            for (uint32_t i = 0; i < 10; i++) v[i] = i == 0 ? a : big + (i % 4);
            add_face(g, v, 10);
            break;
        }
    }
}

static void nonfinite(growing *g, uint64_t *rng)
{
    if (g->nv == 0) return;
    const uint32_t v = map_rng_below(rng, g->nv);
    g->pos[3 * (size_t)v + map_rng_below(rng, 3)] = map_rng_below(rng, 3) ? NAN : INFINITY;
}

static void negative_zeros(growing *g, uint64_t *rng)
{
    for (uint32_t v = 0; v < g->nv; v++)
        for (int k = 0; k < 3; k++)
            if (g->pos[3 * (size_t)v + k] == 0.0 && map_rng_below(rng, 2))
                g->pos[3 * (size_t)v + k] = -g->pos[3 * (size_t)v + k];
}

static void isolated(growing *g, const map_block_set *set, uint64_t *rng)
{
    double x[3] = {100.0 + map_rng_below(rng, 4), 50.0, -3.0};
    if (set->count && map_rng_below(rng, 2)) {
        const map_block_src *o = &set->blocks[map_rng_below(rng, (uint32_t)set->count)];
        if (o->list.num_verts)
            memcpy(x, &o->list.positions[3 * (size_t)map_rng_below(rng, o->list.num_verts)],
                   sizeof x);
    }
    add_vert(g, x);
}

/* A face from one of this block's sides to a vertex of another block. */
static void reach_across(growing *g, const map_block_set *set, uint64_t *rng)
{
    uint32_t a, b;
    if (!set->count || !random_side(g, rng, &a, &b)) return;
    const map_block_src *o = &set->blocks[map_rng_below(rng, (uint32_t)set->count)];
    if (!o->list.num_verts) return;
    const uint32_t c =
        add_vert(g, &o->list.positions[3 * (size_t)map_rng_below(rng, o->list.num_verts)]);
    const uint32_t v[3] = {b, a, c};
    add_face(g, v, 3);
}

void map_mutate(mt_face_list *list, const map_block_set *set, uint64_t *rng)
{
    growing g;
    from_list(&g, list);
    const uint32_t changes = 1 + map_rng_below(rng, 3);
    for (uint32_t i = 0; i < changes; i++) {
        switch (map_rng_below(rng, 12)) {
            case 0:
                drop_faces(&g, rng);
                break;
            case 1:
                flip_face(&g, rng);
                break;
            case 2:
                duplicate_face(&g, rng);
                break;
            case 3:
            case 4:
                add_fin(&g, rng);
                break;
            case 5:
                add_bowtie(&g, rng);
                break;
            case 6:
                add_degenerate(&g, rng);
                break;
            case 7:
                add_out_of_range(&g, rng);
                break;
            case 8:
                nonfinite(&g, rng);
                break;
            case 9:
                negative_zeros(&g, rng);
                break;
            case 10:
                isolated(&g, set, rng);
                break;
            default:
                reach_across(&g, set, rng);
                break;
        }
    }
    to_list(&g, list);
}
