/* core.self_intersections_oracle: mt_mesh_self_intersections,
 * mt_mesh_nonsimple_faces and mt_mesh_boundary_loop_crossings against an
 * exact brute force on every corpus mesh and on hand-made, generated and
 * random meshes (selfx_cases.c). Every pair of faces whose boxes overlap is
 * judged triangle by triangle in GMP integers (selfx_exact.c), over every
 * triangulation a polygon face may get (selfx_polygon.c): a pair whose
 * verdict depends on the triangulation is counted as undecided and left
 * out. Every pair of sides of every face and boundary loop is tried for the
 * shapes. Its own executable because it links GMP.
 *
 * With --meshtopo CLI, `CLI inspect FILE --self-intersections --json` must
 * give every corpus mesh the counts the oracle found.
 *
 * Usage: selfx_oracle [--no-filter] [--max-triangles N] [--only NAME] [--meshtopo CLI]
 * (--no-filter: no plane-side shortcut, to check that it changes nothing). */
#include <assert.h>
#include <dirent.h>
#include <gmp.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "harness.h"
#include "meshtopo/core.h"
#include "meshtopo/io.h"
#include "selfx_cases.h"
#include "selfx_exact.h"
#include "selfx_polygon.h"

/* Meshes with more candidate triangles than this get no pair check (the
 * brute force is quadratic); npm_snowden (109k triangles) is one. Their
 * faces and loops are still checked. */
#define DEFAULT_MAX_TRIANGLES 30000
/* Differences printed per mesh and kind. */
#define MAX_PRINTED 8

typedef struct options {
    bool filter;
    size_t max_triangles;
    const char *only;
} options;

typedef enum face_state {
    FACE_JUDGED,    /* its pairs are judged */
    FACE_LARGE,     /* more than SX_MAX_POLYGON corners: its pairs are left out */
    FACE_NONFINITE, /* a corner at NaN or infinity: not judged by either side */
    FACE_REJECTED   /* the build left it out */
} face_state;

typedef enum verdict { VERDICT_NO, VERDICT_YES, VERDICT_UNDECIDED } verdict;

/* A mesh under test and the oracle's view of it. */
typedef struct oracle_mesh {
    const char *name;
    const mt_face_list *list;
    mt_mesh *mesh;
    FILE *log; /* differences and notes, printed after the mesh's line */
    uint32_t num_verts, num_faces;
    face_state *state;
    uint32_t *face_n, *face_first; /* corners and where they start in corners[] */
    uint32_t *corners;             /* caller vertex ids, mt_face_verts order */
    uint32_t *face_tri;            /* first candidate triangle of each face */
    mpz_t *coord;                  /* 3 per vertex: position * 2^shift, an integer */
    mpz_t zero;
    uint32_t num_tris;
    uint32_t *tri_ids; /* 3 per candidate triangle */
    double *tri_box;   /* lo x, y, z, hi x, y, z per candidate triangle */
    mpz_t *tri_normal; /* 3 per candidate triangle */
} oracle_mesh;

/* What one mesh gave, for the summary line. */
typedef struct outcome {
    bool pairs_checked;
    size_t pairs, undecided, left_out, not_judged;
    size_t nonsimple, crossing, warped;
    size_t loops, crossing_loops;
    long differences;
} outcome;

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static sx_vec vertex_vec(const oracle_mesh *m, uint32_t v)
{
    sx_vec p = {
        {m->coord[3 * (size_t)v], m->coord[3 * (size_t)v + 1], m->coord[3 * (size_t)v + 2]}};
    return p;
}

static void triangle_vecs(const oracle_mesh *m, uint32_t t, sx_vec out[3])
{
    for (int i = 0; i < 3; i++) out[i] = vertex_vec(m, m->tri_ids[3 * (size_t)t + i]);
}

static const double *position(const oracle_mesh *m, uint32_t v)
{
    return m->list->positions + 3 * (size_t)v;
}

static void print_face(const oracle_mesh *m, uint32_t f)
{
    fprintf(m->log, "    face %u:", f);
    for (uint32_t i = 0; i < m->face_n[f]; i++) {
        uint32_t v = m->corners[m->face_first[f] + i];
        const double *p = position(m, v);
        fprintf(m->log, " %u (%.17g %.17g %.17g)", v, p[0], p[1], p[2]);
    }
    fprintf(m->log, "\n");
}

static void print_triangle(const oracle_mesh *m, uint32_t t)
{
    const uint32_t *ids = m->tri_ids + 3 * (size_t)t;
    fprintf(m->log, "(%u %u %u)", ids[0], ids[1], ids[2]);
}

/* ---- the mesh: faces, exact coordinates, candidate triangles ---------------------- */

static void free_mesh(oracle_mesh *m)
{
    if (m->coord) {
        for (size_t i = 0; i < 3 * (size_t)m->num_verts; i++) mpz_clear(m->coord[i]);
        mpz_clear(m->zero);
    }
    if (m->tri_normal)
        for (size_t i = 0; i < 3 * (size_t)m->num_tris; i++) mpz_clear(m->tri_normal[i]);
    free(m->coord);
    free(m->tri_normal);
    free(m->state);
    free(m->face_n);
    free(m->face_first);
    free(m->corners);
    free(m->face_tri);
    free(m->tri_ids);
    free(m->tri_box);
    mt_mesh_destroy(m->mesh);
    memset(m, 0, sizeof *m);
}

static bool finite_vertex(const oracle_mesh *m, uint32_t v)
{
    const double *p = position(m, v);
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

/* Every finite coordinate x is m 2^e with 0.5 <= |m| < 1, so x 2^(53 - e)
 * is an integer: one shift that serves them all, converted exactly. */
static bool exact_coordinates(oracle_mesh *m)
{
    long shift = 0;
    for (uint32_t v = 0; v < m->num_verts; v++) {
        if (!finite_vertex(m, v)) continue;
        for (int k = 0; k < 3; k++) {
            int e = 0;
            if (position(m, v)[k] != 0) frexp(position(m, v)[k], &e);
            if (53 - e > shift) shift = 53 - e;
        }
    }
    m->coord = malloc(3 * ((size_t)m->num_verts + 1) * sizeof *m->coord);
    if (!m->coord) return false;
    mpz_init(m->zero);
    mpq_t q;
    mpq_init(q);
    bool ok = true;
    for (uint32_t v = 0; v < m->num_verts; v++) {
        for (int k = 0; k < 3; k++) {
            mpz_ptr c = m->coord[3 * (size_t)v + k];
            mpz_init(c);
            if (!finite_vertex(m, v)) continue; /* never used */
            mpq_set_d(q, position(m, v)[k]);
            mpq_mul_2exp(q, q, (mp_bitcnt_t)shift);
            ok = ok && mpz_cmp_ui(mpq_denref(q), 1) == 0;
            mpz_set(c, mpq_numref(q));
        }
    }
    mpq_clear(q);
    return ok;
}

/* Faces as the build keeps them (mt_face_verts) and their states. */
static bool read_faces(oracle_mesh *m)
{
    m->state = calloc(m->num_faces + 1, sizeof *m->state);
    m->face_n = calloc(m->num_faces + 1, sizeof *m->face_n);
    m->face_first = calloc(m->num_faces + 1, sizeof *m->face_first);
    m->corners = malloc((m->list->num_indices + 1) * sizeof *m->corners);
    if (!m->state || !m->face_n || !m->face_first || !m->corners) return false;
    uint32_t at = 0;
    for (uint32_t f = 0; f < m->num_faces; f++) {
        size_t n = 0;
        mt_status s = mt_face_verts(m->mesh, f, NULL, 0, &n);
        m->face_first[f] = at;
        if (s == MT_ERR_NOT_FOUND) {
            m->state[f] = FACE_REJECTED;
            continue;
        }
        if ((s != MT_OK && s != MT_ERR_BUFFER_TOO_SMALL) || at + n > m->list->num_indices ||
            mt_face_verts(m->mesh, f, m->corners + at, n, &n) != MT_OK) {
            fprintf(m->log, "  mt_face_verts(%u) failed\n", f);
            return false;
        }
        m->face_n[f] = (uint32_t)n;
        at += (uint32_t)n;
        bool finite = true;
        for (uint32_t i = 0; i < n; i++)
            finite = finite && finite_vertex(m, m->corners[m->face_first[f] + i]);
        m->state[f] = !finite ? FACE_NONFINITE : n > SX_MAX_POLYGON ? FACE_LARGE : FACE_JUDGED;
    }
    return true;
}

/* Candidate triangles of the judged faces: a triangle itself, every
 * corner triple of a polygon (selfx_polygon.h numbering). */
static bool make_triangles(oracle_mesh *m)
{
    size_t total = 0;
    for (uint32_t f = 0; f < m->num_faces; f++)
        if (m->state[f] == FACE_JUDGED) total += sx_num_candidates(m->face_n[f]);
    m->num_tris = (uint32_t)total;
    m->face_tri = calloc(m->num_faces + 1, sizeof *m->face_tri);
    m->tri_ids = malloc(3 * (total + 1) * sizeof *m->tri_ids);
    m->tri_box = malloc(6 * (total + 1) * sizeof *m->tri_box);
    m->tri_normal = malloc(3 * (total + 1) * sizeof *m->tri_normal);
    if (!m->face_tri || !m->tri_ids || !m->tri_box || !m->tri_normal) return false;
    for (size_t i = 0; i < 3 * total; i++) mpz_init(m->tri_normal[i]);
    uint32_t t = 0;
    for (uint32_t f = 0; f < m->num_faces; f++) {
        m->face_tri[f] = t;
        if (m->state[f] != FACE_JUDGED) continue;
        const uint32_t *c = m->corners + m->face_first[f];
        for (uint32_t k = 2; k < m->face_n[f]; k++)
            for (uint32_t j = 1; j < k; j++)
                for (uint32_t i = 0; i < j; i++, t++) {
                    assert(t - m->face_tri[f] == sx_candidate_index(i, j, k));
                    uint32_t *ids = m->tri_ids + 3 * (size_t)t;
                    ids[0] = c[i];
                    ids[1] = c[j];
                    ids[2] = c[k];
                    double *box = m->tri_box + 6 * (size_t)t;
                    for (int d = 0; d < 3; d++) {
                        box[d] = box[d + 3] = position(m, ids[0])[d];
                        for (int r = 1; r < 3; r++) {
                            box[d] = fmin(box[d], position(m, ids[r])[d]);
                            box[d + 3] = fmax(box[d + 3], position(m, ids[r])[d]);
                        }
                    }
                    sx_vec tv[3];
                    triangle_vecs(m, t, tv);
                    mpz_t *nz = m->tri_normal + 3 * (size_t)t;
                    sx_vec normal = {{nz[0], nz[1], nz[2]}};
                    sx_triangle_normal(tv, normal);
                }
    }
    return true;
}

/* ---- pairs of faces ---------------------------------------------------------------- */

static bool boxes_overlap(const double *a, const double *b)
{
    for (int d = 0; d < 3; d++)
        if (a[d + 3] < b[d] || b[d + 3] < a[d]) return false;
    return true;
}

/* Scratch of decide_pair, grown as needed. */
typedef struct pair_work {
    bool *bad;    /* bad[a * candidates of g + b]: candidates a of f and b of g clash */
    bool *marked; /* per candidate of the face whose triangulations are searched */
    size_t bad_capacity, marked_capacity;
    uint32_t witness[2]; /* the first clashing pair of candidate triangles */
} pair_work;

/* The search, for each triangulation of one face (the enumerated one), for
 * a triangulation of the other (the searched one) with no clash between
 * them. */
typedef struct clean_search {
    const bool *bad;
    uint32_t row;        /* candidates of g: the length of a row of bad */
    bool searched_is_f;  /* the searched face is f (bad's rows) */
    uint32_t n_searched; /* its corners */
    uint32_t num_searched, num_enumerated_tris;
    bool *marked;
    bool found_clean;
} clean_search;

static bool visit_triangulation(const uint32_t *tris, void *ctx)
{
    clean_search *s = ctx;
    for (uint32_t a = 0; a < s->num_searched; a++) {
        bool hit = false;
        for (uint32_t i = 0; i < s->num_enumerated_tris && !hit; i++)
            hit = s->searched_is_f ? s->bad[(size_t)a * s->row + tris[i]]
                                   : s->bad[(size_t)tris[i] * s->row + a];
        s->marked[a] = hit;
    }
    s->found_clean = sx_has_unmarked_triangulation(s->n_searched, s->marked);
    return !s->found_clean;
}

/* buffer with room for at least `needed` elements of `size` bytes
 * (*capacity of them); aborts when out of memory. */
static void *grow(void *buffer, size_t *capacity, size_t needed, size_t size)
{
    if (needed <= *capacity) return buffer;
    void *p = realloc(buffer, needed * size);
    if (!p) abort();
    *capacity = needed;
    return p;
}

/* Whether faces f and g (both judged) meet where they should not: every
 * candidate triangle of one against every one of the other, by the rules
 * of sx_triangles_clash; then YES when every pair of triangulations has a
 * clashing pair, NO when none has, UNDECIDED otherwise. */
static verdict decide_pair(const oracle_mesh *m, sx_pool *pool, const options *opt, pair_work *w,
                           uint32_t f, uint32_t g)
{
    const uint32_t nf = sx_num_candidates(m->face_n[f]), ng = sx_num_candidates(m->face_n[g]);
    w->bad = grow(w->bad, &w->bad_capacity, (size_t)nf * ng, sizeof *w->bad);
    bool any = false;
    for (uint32_t a = 0; a < nf; a++) {
        const uint32_t ta = m->face_tri[f] + a;
        sx_vec va[3], na = {{m->tri_normal[3 * (size_t)ta], m->tri_normal[3 * (size_t)ta + 1],
                             m->tri_normal[3 * (size_t)ta + 2]}};
        triangle_vecs(m, ta, va);
        for (uint32_t b = 0; b < ng; b++) {
            const uint32_t tb = m->face_tri[g] + b;
            bool *bad = &w->bad[(size_t)a * ng + b];
            *bad = false;
            if (!boxes_overlap(m->tri_box + 6 * (size_t)ta, m->tri_box + 6 * (size_t)tb)) continue;
            sx_vec vb[3], nb = {{m->tri_normal[3 * (size_t)tb], m->tri_normal[3 * (size_t)tb + 1],
                                 m->tri_normal[3 * (size_t)tb + 2]}};
            triangle_vecs(m, tb, vb);
            const uint32_t *ia = m->tri_ids + 3 * (size_t)ta, *ib = m->tri_ids + 3 * (size_t)tb;
            if (opt->filter && (sx_plane_separates(pool, ia, va, na, ib, vb) ||
                                sx_plane_separates(pool, ib, vb, nb, ia, va)))
                continue;
            *bad = sx_triangles_clash(pool, ia, va, ib, vb);
            if (*bad && !any) {
                w->witness[0] = ta;
                w->witness[1] = tb;
            }
            any = any || *bad;
        }
    }
    if (!any) return VERDICT_NO;
    /* Enumerate the triangulations of the face with fewer corners. */
    const bool enumerate_g = m->face_n[g] <= m->face_n[f];
    const uint32_t searched = enumerate_g ? f : g, enumerated = enumerate_g ? g : f;
    w->marked = grow(w->marked, &w->marked_capacity, enumerate_g ? nf : ng, sizeof *w->marked);
    clean_search s = {.bad = w->bad,
                      .row = ng,
                      .searched_is_f = enumerate_g,
                      .n_searched = m->face_n[searched],
                      .num_searched = enumerate_g ? nf : ng,
                      .num_enumerated_tris = m->face_n[enumerated] - 2,
                      .marked = w->marked,
                      .found_clean = false};
    sx_each_triangulation(m->face_n[enumerated], visit_triangulation, &s);
    return s.found_clean ? VERDICT_UNDECIDED : VERDICT_YES;
}

typedef struct pair_list {
    mt_face_pair *pairs;
    size_t count, capacity;
} pair_list;

static void pair_list_add(pair_list *l, uint32_t a, uint32_t b)
{
    if (l->count == l->capacity)
        l->pairs =
            grow(l->pairs, &l->capacity, l->capacity < 32 ? 64 : 2 * l->capacity, sizeof *l->pairs);
    l->pairs[l->count++] = (mt_face_pair){a, b};
}

static int compare_pairs(const void *pa, const void *pb)
{
    const mt_face_pair *a = pa, *b = pb;
    if (a->a != b->a) return a->a < b->a ? -1 : 1;
    if (a->b != b->b) return a->b < b->b ? -1 : 1;
    return 0;
}

static bool pair_listed(const pair_list *l, uint32_t a, uint32_t b)
{
    mt_face_pair key = {a, b};
    return l->count > 0 && bsearch(&key, l->pairs, l->count, sizeof key, compare_pairs) != NULL;
}

/* The library's pairs, checked to be ascending with a < b. */
static bool library_pairs(const oracle_mesh *m, pair_list *out, long *differences)
{
    size_t count = 0;
    mt_diag diag;
    mt_status s = mt_mesh_self_intersections(m->mesh, NULL, 0, &count, &diag);
    if (s != MT_OK && s != MT_ERR_BUFFER_TOO_SMALL) {
        fprintf(m->log, "  mt_mesh_self_intersections: %s (%s)\n", mt_strerror(s), diag.message);
        (*differences)++;
        return false;
    }
    out->pairs = grow(out->pairs, &out->capacity, count + 1, sizeof *out->pairs);
    s = mt_mesh_self_intersections(m->mesh, out->pairs, count, &out->count, &diag);
    if (s != MT_OK || out->count != count) {
        fprintf(m->log, "  mt_mesh_self_intersections (filling %zu): %s (%s), %zu pairs\n", count,
                mt_strerror(s), diag.message, out->count);
        (*differences)++;
        return false;
    }
    for (size_t i = 0; i < count; i++) {
        const mt_face_pair *p = &out->pairs[i];
        if (p->a >= p->b || p->b >= m->num_faces ||
            (i > 0 && compare_pairs(&out->pairs[i - 1], p) >= 0)) {
            fprintf(m->log,
                    "  mt_mesh_self_intersections: pair %zu (%u, %u) is out of order or range\n", i,
                    p->a, p->b);
            (*differences)++;
            return false;
        }
    }
    return true;
}

/* Brute force over the pairs of judged faces, compared with the library. */
static void check_pairs(const oracle_mesh *m, sx_pool *pool, const options *opt, outcome *out)
{
    pair_list yes = {0}, undecided = {0}, lib = {0};
    pair_work w = {0};
    double *box = malloc(6 * ((size_t)m->num_faces + 1) * sizeof *box);
    uint32_t *judged = malloc(((size_t)m->num_faces + 1) * sizeof *judged);
    if (!box || !judged) abort();
    uint32_t num_judged = 0;
    for (uint32_t f = 0; f < m->num_faces; f++) {
        if (m->state[f] == FACE_LARGE) out->left_out++;
        if (m->state[f] == FACE_NONFINITE) out->not_judged++;
        if (m->state[f] != FACE_JUDGED) continue;
        judged[num_judged++] = f;
        double *b = box + 6 * (size_t)f;
        for (int d = 0; d < 3; d++) {
            b[d] = b[d + 3] = position(m, m->corners[m->face_first[f]])[d];
            for (uint32_t i = 1; i < m->face_n[f]; i++) {
                b[d] = fmin(b[d], position(m, m->corners[m->face_first[f] + i])[d]);
                b[d + 3] = fmax(b[d + 3], position(m, m->corners[m->face_first[f] + i])[d]);
            }
        }
    }
    long printed = 0;
    for (uint32_t i = 0; i < num_judged; i++) {
        const uint32_t f = judged[i];
        const double *bf = box + 6 * (size_t)f;
        for (uint32_t j = i + 1; j < num_judged; j++) {
            const uint32_t g = judged[j];
            if (!boxes_overlap(bf, box + 6 * (size_t)g)) continue;
            verdict v = decide_pair(m, pool, opt, &w, f, g);
            if (v == VERDICT_YES) pair_list_add(&yes, f, g);
            if (v == VERDICT_UNDECIDED) {
                pair_list_add(&undecided, f, g);
                if (printed++ < MAX_PRINTED) {
                    fprintf(m->log,
                            "  undecided: faces %u and %u clash or not by the triangulation, e.g. ",
                            f, g);
                    print_triangle(m, w.witness[0]);
                    fprintf(m->log, " with ");
                    print_triangle(m, w.witness[1]);
                    fprintf(m->log, "\n");
                }
            }
        }
    }
    out->pairs = yes.count;
    out->undecided = undecided.count;
    if (library_pairs(m, &lib, &out->differences)) {
        long missing = 0, extra = 0;
        for (size_t i = 0; i < lib.count; i++) {
            const mt_face_pair p = lib.pairs[i];
            if (m->state[p.a] == FACE_LARGE || m->state[p.b] == FACE_LARGE) continue;
            if (pair_listed(&undecided, p.a, p.b) || pair_listed(&yes, p.a, p.b)) continue;
            if (extra++ < MAX_PRINTED) {
                fprintf(m->log, "  meshtopo reports faces %u and %u; the oracle finds no clash:\n",
                        p.a, p.b);
                print_face(m, p.a);
                print_face(m, p.b);
            }
        }
        for (size_t i = 0; i < yes.count; i++) {
            const mt_face_pair p = yes.pairs[i];
            if (pair_listed(&lib, p.a, p.b)) continue;
            if (missing++ < MAX_PRINTED) {
                decide_pair(m, pool, opt, &w, p.a, p.b); /* again, for its witness */
                fprintf(m->log, "  the oracle finds faces %u and %u clash (triangles ", p.a, p.b);
                print_triangle(m, w.witness[0]);
                fprintf(m->log, " and ");
                print_triangle(m, w.witness[1]);
                fprintf(m->log, "); meshtopo does not report them:\n");
                print_face(m, p.a);
                print_face(m, p.b);
            }
        }
        if (extra || missing)
            fprintf(m->log,
                    "  pairs: %ld reported by meshtopo only, %ld found by the oracle only\n", extra,
                    missing);
        out->differences += extra + missing;
    }
    free(yes.pairs);
    free(undecided.pairs);
    free(lib.pairs);
    free(w.bad);
    free(w.marked);
    free(box);
    free(judged);
}

/* ---- faces and loops that cross themselves --------------------------------------- */

/* The exact shape of the closed polyline through verts[0..n) (n >= 4,
 * finite corners) in the library's plane: MT_FACE_SELF_CROSSING with two
 * sides that meet, else MT_FACE_WARPED or MT_FACE_SIMPLE. pts and xy have
 * room for n points. */
static mt_face_shape_kind polyline_kind(const oracle_mesh *m, sx_pool *pool, const uint32_t *verts,
                                        uint32_t n, sx_vec *pts, double (*xy)[2],
                                        const double **corner)
{
    for (uint32_t i = 0; i < n; i++) corner[i] = position(m, verts[i]);
    int drop = 0;
    double warp = 0;
    sx_polygon_plane(corner, n, &drop, &warp);
    const int x = drop == 0 ? 1 : 0, y = drop == 2 ? 1 : 2;
    for (uint32_t i = 0; i < n; i++) {
        pts[i].c[0] = m->coord[3 * (size_t)verts[i] + x];
        pts[i].c[1] = m->coord[3 * (size_t)verts[i] + y];
        pts[i].c[2] = (mpz_ptr)m->zero;
        xy[i][0] = corner[i][x];
        xy[i][1] = corner[i][y];
    }
    uint32_t a = 0, b = 0;
    if (sx_polyline_crosses(pool, pts, xy, n, &a, &b)) return MT_FACE_SELF_CROSSING;
    return warp > MT_FACE_WARP_TOLERANCE ? MT_FACE_WARPED : MT_FACE_SIMPLE;
}

typedef struct polyline_work {
    sx_vec *pts;
    double (*xy)[2];
    const double **corner;
    size_t capacity;
} polyline_work;

static void polyline_work_reserve(polyline_work *w, size_t n)
{
    if (n <= w->capacity) return;
    free(w->pts);
    free(w->xy);
    free(w->corner);
    w->pts = malloc(n * sizeof *w->pts);
    w->xy = malloc(n * sizeof *w->xy);
    w->corner = malloc(n * sizeof *w->corner);
    if (!w->pts || !w->xy || !w->corner) abort();
    w->capacity = n;
}

static const char *kind_name(mt_face_shape_kind kind)
{
    return kind == MT_FACE_SELF_CROSSING ? "self-crossing"
           : kind == MT_FACE_WARPED      ? "warped"
                                         : "simple";
}

static void check_faces(const oracle_mesh *m, sx_pool *pool, polyline_work *pw, outcome *out)
{
    size_t count = 0;
    mt_diag diag;
    mt_status s = mt_mesh_nonsimple_faces(m->mesh, NULL, 0, &count, &diag);
    mt_face_shape *lib = calloc(count + 1, sizeof *lib);
    mt_face_shape_kind *lib_kind = calloc((size_t)m->num_faces + 1, sizeof *lib_kind);
    if (!lib || !lib_kind) abort();
    if (s == MT_OK || s == MT_ERR_BUFFER_TOO_SMALL)
        s = mt_mesh_nonsimple_faces(m->mesh, lib, count, &count, &diag);
    if (s != MT_OK) {
        fprintf(m->log, "  mt_mesh_nonsimple_faces: %s (%s)\n", mt_strerror(s), diag.message);
        out->differences++;
        count = 0;
    }
    long printed = 0;
    for (size_t i = 0; i < count; i++) {
        const mt_face_shape *shape = &lib[i];
        if (shape->face >= m->num_faces) {
            fprintf(m->log, "  mt_mesh_nonsimple_faces: face %u out of range\n", shape->face);
            out->differences++;
            continue;
        }
        lib_kind[shape->face] = shape->kind;
        /* The two sides it names must meet. */
        const uint32_t f = shape->face, n = m->face_n[f];
        if (shape->kind != MT_FACE_SELF_CROSSING || m->state[f] == FACE_REJECTED ||
            m->state[f] == FACE_NONFINITE)
            continue;
        polyline_work_reserve(pw, n);
        polyline_kind(m, pool, m->corners + m->face_first[f], n, pw->pts, pw->xy, pw->corner);
        if (shape->side_a >= n || shape->side_b >= n || shape->side_a >= shape->side_b ||
            !sx_polyline_sides_meet(pool, pw->pts, n, shape->side_a, shape->side_b)) {
            out->differences++;
            if (printed++ < MAX_PRINTED) {
                fprintf(m->log, "  meshtopo names sides %u and %u of face %u, which do not meet:\n",
                        shape->side_a, shape->side_b, f);
                print_face(m, f);
            }
        }
    }
    for (uint32_t f = 0; f < m->num_faces; f++) {
        mt_face_shape_kind kind = MT_FACE_SIMPLE;
        const uint32_t n = m->face_n[f];
        if (m->state[f] != FACE_REJECTED && m->state[f] != FACE_NONFINITE && n >= 4) {
            polyline_work_reserve(pw, n);
            kind = polyline_kind(m, pool, m->corners + m->face_first[f], n, pw->pts, pw->xy,
                                 pw->corner);
        }
        out->crossing += kind == MT_FACE_SELF_CROSSING;
        out->warped += kind == MT_FACE_WARPED;
        out->nonsimple += kind != MT_FACE_SIMPLE;
        if (kind == lib_kind[f]) continue;
        out->differences++;
        if (printed++ < MAX_PRINTED) {
            fprintf(m->log, "  face %u: meshtopo says %s, the oracle %s\n", f,
                    kind_name(lib_kind[f]), kind_name(kind));
            print_face(m, f);
        }
    }
    free(lib);
    free(lib_kind);
}

static void print_loop(const oracle_mesh *m, const uint32_t *loop, uint32_t n)
{
    fprintf(m->log, "    loop:");
    for (uint32_t i = 0; i < n && i < 40; i++) {
        const double *p = position(m, loop[i]);
        fprintf(m->log, " %u (%.17g %.17g %.17g)", loop[i], p[0], p[1], p[2]);
    }
    fprintf(m->log, n > 40 ? " ...\n" : "\n");
}

/* Side i of the loop with the given corners, or n. */
static uint32_t loop_side(const uint32_t *loop, uint32_t n, const uint32_t edge[2])
{
    for (uint32_t i = 0; i < n; i++)
        if (loop[i] == edge[0] && loop[(i + 1) % n] == edge[1]) return i;
    return n;
}

static void check_loops(const oracle_mesh *m, sx_pool *pool, polyline_work *pw, outcome *out)
{
    size_t num_verts = 0, num_loops = 0, count = 0;
    mt_status s = mt_boundary_loops(m->mesh, NULL, 0, NULL, 0, &num_verts, &num_loops);
    uint32_t *verts = malloc((num_verts + 1) * sizeof *verts);
    uint32_t *offsets = malloc((num_loops + 2) * sizeof *offsets);
    bool *lib_crossing = calloc(num_loops + 1, sizeof *lib_crossing);
    if (!verts || !offsets || !lib_crossing) abort();
    if (s == MT_OK || s == MT_ERR_BUFFER_TOO_SMALL)
        s = mt_boundary_loops(m->mesh, verts, num_verts, offsets, num_loops + 1, &num_verts,
                              &num_loops);
    mt_diag diag;
    mt_status s2 = mt_mesh_boundary_loop_crossings(m->mesh, NULL, 0, &count, &diag);
    mt_loop_crossing *lib = calloc(count + 1, sizeof *lib);
    if (!lib) abort();
    if (s2 == MT_OK || s2 == MT_ERR_BUFFER_TOO_SMALL)
        s2 = mt_mesh_boundary_loop_crossings(m->mesh, lib, count, &count, &diag);
    if (s != MT_OK || s2 != MT_OK) {
        fprintf(m->log, "  boundary loops: %s, crossings: %s (%s)\n", mt_strerror(s),
                mt_strerror(s2), diag.message);
        out->differences++;
        num_loops = count = 0;
    }
    out->loops = num_loops;
    long printed = 0;
    for (size_t i = 0; i < count; i++) {
        const mt_loop_crossing *c = &lib[i];
        if (c->loop >= num_loops) {
            fprintf(m->log, "  mt_mesh_boundary_loop_crossings: loop %u out of range\n", c->loop);
            out->differences++;
            continue;
        }
        lib_crossing[c->loop] = true;
        const uint32_t *loop = verts + offsets[c->loop];
        const uint32_t n = offsets[c->loop + 1] - offsets[c->loop];
        polyline_work_reserve(pw, n);
        polyline_kind(m, pool, loop, n, pw->pts, pw->xy, pw->corner);
        uint32_t a = loop_side(loop, n, c->edge_a), b = loop_side(loop, n, c->edge_b);
        if (a == n || b == n || a == b || !sx_polyline_sides_meet(pool, pw->pts, n, a, b)) {
            out->differences++;
            if (printed++ < MAX_PRINTED) {
                fprintf(m->log,
                        "  meshtopo names edges %u-%u and %u-%u of loop %u, which do not meet:\n",
                        c->edge_a[0], c->edge_a[1], c->edge_b[0], c->edge_b[1], c->loop);
                print_loop(m, loop, n);
            }
        }
    }
    for (size_t l = 0; l < num_loops; l++) {
        const uint32_t *loop = verts + offsets[l];
        const uint32_t n = offsets[l + 1] - offsets[l];
        bool finite = true;
        for (uint32_t i = 0; i < n; i++) finite = finite && finite_vertex(m, loop[i]);
        bool crossing = false;
        if (n >= 4 && finite) {
            polyline_work_reserve(pw, n);
            crossing = polyline_kind(m, pool, loop, n, pw->pts, pw->xy, pw->corner) ==
                       MT_FACE_SELF_CROSSING;
        }
        out->crossing_loops += crossing;
        if (crossing == lib_crossing[l]) continue;
        out->differences++;
        if (printed++ < MAX_PRINTED) {
            fprintf(m->log, "  loop %zu (%u edges): meshtopo says %s, the oracle %s\n", l, n,
                    lib_crossing[l] ? "crossing" : "not crossing",
                    crossing ? "crossing" : "not crossing");
            print_loop(m, loop, n);
        }
    }
    free(verts);
    free(offsets);
    free(lib_crossing);
    free(lib);
}

/* ---- one mesh ------------------------------------------------------------------------ */

/* Builds and checks one face list; prints its line. Returns the number of
 * differences (-1 when it could not be checked at all). */
static long check_mesh(const char *name, const mt_face_list *list, const options *opt,
                       sx_pool *pool, outcome *out)
{
    const double start = seconds_now();
    memset(out, 0, sizeof *out);
    oracle_mesh m;
    memset(&m, 0, sizeof m);
    m.name = name;
    m.list = list;
    m.num_verts = list->num_verts;
    m.num_faces = list->num_faces;
    char *log_text = NULL;
    size_t log_size = 0;
    m.log = open_memstream(&log_text, &log_size);
    if (!m.log) abort();
    mt_diag diag;
    mt_status s = mt_mesh_build(list, NULL, &m.mesh, &diag);
    if (s != MT_OK || !read_faces(&m) || !exact_coordinates(&m)) {
        fclose(m.log);
        printf("%s: %s%s\n%s", name, s != MT_OK ? "mt_mesh_build: " : "",
               s != MT_OK ? diag.message : "could not read its faces or convert its coordinates",
               log_text);
        free(log_text);
        free_mesh(&m);
        return -1;
    }
    size_t candidates = 0;
    for (uint32_t f = 0; f < m.num_faces; f++)
        if (m.state[f] == FACE_JUDGED) candidates += sx_num_candidates(m.face_n[f]);
    out->pairs_checked = candidates <= opt->max_triangles;
    if (out->pairs_checked) {
        if (!make_triangles(&m)) abort();
        check_pairs(&m, pool, opt, out);
    }
    polyline_work pw = {0};
    check_faces(&m, pool, &pw, out);
    check_loops(&m, pool, &pw, out);
    free(pw.pts);
    free(pw.xy);
    free(pw.corner);
    if (out->pairs_checked)
        printf("%s: %u faces, %zu pairs", name, m.num_faces, out->pairs);
    else
        printf("%s: %u faces, pairs not checked (%zu candidate triangles, more than %zu)", name,
               m.num_faces, candidates, opt->max_triangles);
    if (out->undecided || out->left_out || out->not_judged)
        printf(" (%zu undecided, %zu faces left out, %zu faces not judged)", out->undecided,
               out->left_out, out->not_judged);
    printf(
        ", %zu non-simple faces (%zu crossing, %zu warped), %zu of %zu loops crossing: %s "
        "(%.2f s)\n",
        out->nonsimple, out->crossing, out->warped, out->crossing_loops, out->loops,
        out->differences ? "DISAGREE" : "agree", seconds_now() - start);
    fclose(m.log);
    fputs(log_text, stdout);
    free(log_text);
    free_mesh(&m);
    return out->differences;
}

/* ---- main ---------------------------------------------------------------------------- */

/* The search over triangulations checks itself: for n = 3 .. 9 corners it
 * finds Catalan(n - 2) triangulations, and for random marked candidates the
 * dynamic program agrees with trying them all. */
typedef struct triangulation_count {
    uint32_t n;
    const bool *marked;
    long count, unmarked;
} triangulation_count;

static bool count_triangulation(const uint32_t *tris, void *ctx)
{
    triangulation_count *c = ctx;
    bool clean = true;
    for (uint32_t i = 0; i + 2 < c->n; i++) clean = clean && !c->marked[tris[i]];
    c->count++;
    c->unmarked += clean;
    return true;
}

static long check_triangulation_search(void)
{
    static const long catalan[] = {1, 1, 2, 5, 14, 42, 132, 429};
    bool marked[84];
    uint64_t state = 12345;
    long wrong = 0;
    for (uint32_t n = 3; n <= 9; n++) {
        for (int round = 0; round < 50; round++) {
            const uint32_t num = sx_num_candidates(n);
            for (uint32_t i = 0; i < num; i++) {
                state = state * 6364136223846793005ull + 1442695040888963407ull;
                marked[i] = round > 0 && (state >> 33) % 5 == 0;
            }
            triangulation_count c = {n, marked, 0, 0};
            sx_each_triangulation(n, count_triangulation, &c);
            if (c.count != catalan[n - 2] ||
                (c.unmarked > 0) != sx_has_unmarked_triangulation(n, marked))
                wrong++;
        }
    }
    if (wrong)
        printf("the triangulation search fails its own check %ld times\n", wrong);
    else
        printf(
            "triangulation search: Catalan counts and the dynamic program agree for 3 to 9 "
            "corners\n");
    return wrong;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static bool is_corpus_mesh(const char *name)
{
    size_t n = strlen(name);
    return (n > 4 && strcmp(name + n - 4, ".off") == 0) ||
           (n > 7 && strcmp(name + n - 7, ".off.gz") == 0);
}

/* The oracle's own answers against what a hand-made case states. */
static long check_expected(const sx_case *c, const outcome *out)
{
    const long want[4] = {c->pairs, c->undecided, c->nonsimple, c->loops};
    const long got[4] = {(long)out->pairs, (long)out->undecided, (long)out->nonsimple,
                         (long)out->crossing_loops};
    static const char *const what[4] = {"pairs", "undecided pairs", "non-simple faces",
                                        "crossing loops"};
    long wrong = 0;
    for (int i = 0; i < 4; i++) {
        if (want[i] < 0 || want[i] == got[i]) continue;
        printf("  %s: the oracle finds %ld %s, the case states %ld\n", c->name, got[i], what[i],
               want[i]);
        wrong++;
    }
    return wrong;
}

/* The number after "key": in a JSON document, or -1. */
static long json_count(const char *doc, const char *key)
{
    char quoted[96];
    snprintf(quoted, sizeof quoted, "\"%s\":", key);
    const char *at = strstr(doc, quoted);
    return at ? strtol(at + strlen(quoted), NULL, 10) : -1;
}

/* `meshtopo inspect FILE --self-intersections --json` gives the counts the
 * oracle found (pairs only when it checked them). Returns the number of
 * counts that differ (1 when the command fails). */
static long check_cli(const char *meshtopo, const char *path, const outcome *out)
{
    char command[8192];
    snprintf(command, sizeof command, "'%s' inspect '%s' --self-intersections --json", meshtopo,
             path);
    FILE *p = popen(command, "r");
    char *doc = NULL;
    size_t size = 0;
    FILE *mem = open_memstream(&doc, &size);
    if (!p || !mem) abort();
    char buf[65536];
    for (size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) fwrite(buf, 1, n, mem);
    const int status = pclose(p);
    fclose(mem);
    const long got[3] = {json_count(doc, "self_intersecting_pairs"),
                         json_count(doc, "non_simple_faces"),
                         json_count(doc, "self_intersecting_boundary_loops")};
    const long want[3] = {out->pairs_checked ? (long)out->pairs : got[0], (long)out->nonsimple,
                          (long)out->crossing_loops};
    static const char *const key[3] = {"self_intersecting_pairs", "non_simple_faces",
                                       "self_intersecting_boundary_loops"};
    long wrong = status != 0;
    if (status != 0) printf("  %s: exits with status %d\n", command, status);
    for (int i = 0; i < 3; i++) {
        if (got[i] == want[i]) continue;
        printf("  inspect --json says %s %ld, the oracle %ld\n", key[i], got[i], want[i]);
        wrong++;
    }
    free(doc);
    return wrong;
}

int main(int argc, char **argv)
{
    options opt = {true, DEFAULT_MAX_TRIANGLES, NULL};
    const char *meshtopo = NULL; /* the CLI whose inspect --json is checked too */
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--no-filter") == 0) {
            opt.filter = false;
        } else if (strcmp(argv[i], "--max-triangles") == 0 && i + 1 < argc) {
            opt.max_triangles = (size_t)strtoull(argv[++i], NULL, 10);
        } else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc) {
            opt.only = argv[++i];
        } else if (strcmp(argv[i], "--meshtopo") == 0 && i + 1 < argc) {
            meshtopo = argv[++i];
        } else {
            fprintf(stderr,
                    "usage: %s [--no-filter] [--max-triangles N] [--only NAME] [--meshtopo CLI]\n",
                    argv[0]);
            return 2;
        }
    }
    const double start = seconds_now();
    sx_pool pool;
    sx_pool_init(&pool);
    long failures = check_triangulation_search() != 0;
    size_t meshes = 0;

    static sx_case cases[64];
    const size_t num_cases = sx_make_cases(cases, sizeof cases / sizeof cases[0]);
    if (num_cases == 0) {
        printf("could not make the hand-made cases\n");
        failures++;
    }
    for (size_t i = 0; i < num_cases; i++) {
        if (opt.only && strcmp(opt.only, cases[i].name) != 0) continue;
        outcome out;
        long d = check_mesh(cases[i].name, &cases[i].list, &opt, &pool, &out);
        failures += d != 0;
        failures += d >= 0 && check_expected(&cases[i], &out) != 0;
        meshes++;
    }
    for (size_t i = 0; i < num_cases; i++) mt_face_list_free(&cases[i].list);

    const char *dir = mt_test_corpus_dir();
    DIR *d = opendir(dir);
    char *names[256];
    size_t num_names = 0;
    if (!d) {
        printf("cannot open the corpus directory %s\n", dir);
        failures++;
    } else {
        for (struct dirent *e; (e = readdir(d)) != NULL && num_names < 256;)
            if (is_corpus_mesh(e->d_name)) names[num_names++] = strdup(e->d_name);
        closedir(d);
    }
    qsort(names, num_names, sizeof *names, compare_names);
    if (d && num_names == 0) {
        printf("no meshes in the corpus directory %s\n", dir);
        failures++;
    }
    for (size_t i = 0; i < num_names; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        if (!opt.only || strcmp(opt.only, names[i]) == 0) {
            mt_face_list list;
            mt_diag diag;
            if (mt_read_file(path, MT_FORMAT_AUTO, &list, &diag) != MT_OK) {
                printf("%s: cannot read: %s\n", names[i], diag.message);
                failures++;
            } else {
                outcome out;
                const long diffs = check_mesh(names[i], &list, &opt, &pool, &out);
                failures += diffs != 0;
                if (meshtopo && diffs >= 0) failures += check_cli(meshtopo, path, &out) != 0;
                mt_face_list_free(&list);
                meshes++;
            }
        }
        free(names[i]);
    }
    sx_pool_clear(&pool);
    printf("core.self_intersections_oracle: %zu meshes, %ld with differences (%.1f s)\n", meshes,
           failures, seconds_now() - start);
    return failures ? 1 : 0;
}
