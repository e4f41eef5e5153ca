/* Tests of the exact predicates (meshtopo/predicates.h). The orientations
 * against
 * an exact oracle: points with integer coordinates (exact doubles), whose
 * determinants __int128 holds exactly. Nearly collinear points are points
 * of a line rounded to integers; nearly coplanar ones lie on a plane whose
 * normal has a small component, moved by one unit along it, or exactly on
 * it. Their determinants are far below the rounding error of a plain double
 * evaluation, which often gets the sign wrong; the same points moved by
 * 2^20 (still exact doubles) make the differences cancel too. The
 * predicates must agree with the oracle on every one, and flip sign exactly
 * under an odd permutation. The intersection tests are checked on touching,
 * crossing, coplanar and degenerate triangles and near misses by one
 * representable step; tests/core/cgal_intersect_check.cpp compares them
 * with CGAL on random triangles. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "harness.h"
#include "meshtopo/predicates.h"

#define OFFSET 0x1p20

typedef __int128 i128;

static int sign128(i128 x)
{
    return x > 0 ? 1 : x < 0 ? -1 : 0;
}

static uint64_t next_random(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* An integer in (-2^bits, 2^bits). */
static int64_t random_k(uint64_t *state, int bits)
{
    uint64_t span = 1ull << bits;
    return (int64_t)(next_random(state) % (2 * span - 1)) - (int64_t)(span - 1);
}

static int oracle2d(const int64_t *a, const int64_t *b, const int64_t *c)
{
    return sign128((i128)(b[0] - a[0]) * (c[1] - a[1]) - (i128)(b[1] - a[1]) * (c[0] - a[0]));
}

static int oracle3d(const int64_t *a, const int64_t *b, const int64_t *c, const int64_t *d)
{
    i128 u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = d[k] - a[k];
    }
    return sign128(u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
                   u[2] * (v[0] * w[1] - v[1] * w[0]));
}

static void to_doubles(const int64_t *k, int dims, double offset, double *out)
{
    for (int i = 0; i < dims; i++) out[i] = (double)k[i] + offset;
}

/* The naive double determinant, to show the cases are hard. */
static int naive2d(const double *a, const double *b, const double *c)
{
    double det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    return det > 0 ? 1 : det < 0 ? -1 : 0;
}

static void orient2d_exact_near_lines(void)
{
    uint64_t state = 2026;
    int wrong_naive = 0, zeros = 0;
    for (int round = 0; round < 20000; round++) {
        int64_t a[2] = {random_k(&state, 50), random_k(&state, 50)};
        int64_t b[2] = {random_k(&state, 50), random_k(&state, 50)};
        double t = (double)(next_random(&state) >> 11) * 0x1p-53;
        int64_t c[2];
        /* On the line through a and b, rounded; every fourth one exactly on it. */
        for (int i = 0; i < 2; i++)
            c[i] = round % 4 ? llround((double)a[i] + t * (double)(b[i] - a[i])) : 2 * b[i] - a[i];
        int want = oracle2d(a, b, c);
        zeros += want == 0;
        for (int shifted = 0; shifted < 2; shifted++) {
            double pa[2], pb[2], pc[2];
            double offset = shifted ? OFFSET : 0;
            to_doubles(a, 2, offset, pa);
            to_doubles(b, 2, offset, pb);
            to_doubles(c, 2, offset, pc);
            int got = mt_orient2d(pa, pb, pc);
            if (got != want) {
                mt_test_fail(__FILE__, __LINE__, "round %d offset %g: orient2d %d, exact %d", round,
                             offset, got, want);
                return;
            }
            CHECK_EQ(mt_orient2d(pb, pa, pc), -want);
            CHECK_EQ(mt_orient2d(pb, pc, pa), want);
            wrong_naive += naive2d(pa, pb, pc) != want;
        }
    }
    printf(
        "orient2d: 40000 near-collinear cases exact (%d collinear); the naive formula got %d "
        "wrong\n",
        zeros, wrong_naive);
    CHECK(wrong_naive > 100);
    CHECK(zeros > 10);
}

static int naive3d(const double *a, const double *b, const double *c, const double *d)
{
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = d[k] - a[k];
    }
    double det = u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
                 u[2] * (v[0] * w[1] - v[1] * w[0]);
    return det > 0 ? 1 : det < 0 ? -1 : 0;
}

static void orient3d_exact_near_planes(void)
{
    uint64_t state = 1126;
    int wrong_naive = 0, zeros = 0;
    for (int round = 0; round < 20000; round++) {
        /* b - a = u, c - a = v with u and v nearly proportional in x and y,
         * so the normal u x v has a small z component; d = a + i u + j v
         * moved by -1, 0 or 1 along z: the determinant is that times the
         * small component, or exactly 0. */
        int64_t a[3], u[3], v[3], b[3], c[3], d[3];
        for (int k = 0; k < 3; k++) {
            a[k] = random_k(&state, 38);
            u[k] = random_k(&state, 38);
        }
        v[0] = u[0] + random_k(&state, 2);
        v[1] = u[1] + random_k(&state, 2);
        v[2] = random_k(&state, 38);
        int64_t i = random_k(&state, 1), j = random_k(&state, 1), dz = random_k(&state, 1);
        for (int k = 0; k < 3; k++) {
            b[k] = a[k] + u[k];
            c[k] = a[k] + v[k];
            d[k] = a[k] + i * u[k] + j * v[k] + (k == 2 ? dz : 0);
        }
        int want = oracle3d(a, b, c, d);
        zeros += want == 0;
        for (int shifted = 0; shifted < 2; shifted++) {
            double pa[3], pb[3], pc[3], pd[3];
            double offset = shifted ? OFFSET : 0;
            to_doubles(a, 3, offset, pa);
            to_doubles(b, 3, offset, pb);
            to_doubles(c, 3, offset, pc);
            to_doubles(d, 3, offset, pd);
            int got = mt_orient3d(pa, pb, pc, pd);
            if (got != want) {
                mt_test_fail(__FILE__, __LINE__, "round %d offset %g: orient3d %d, exact %d", round,
                             offset, got, want);
                return;
            }
            CHECK_EQ(mt_orient3d(pb, pa, pc, pd), -want);
            CHECK_EQ(mt_orient3d(pa, pb, pd, pc), -want);
            CHECK_EQ(mt_orient3d(pd, pa, pb, pc), -want); /* a 4-cycle is odd */
            wrong_naive += naive3d(pa, pb, pc, pd) != want;
        }
    }
    printf(
        "orient3d: 40000 near-coplanar cases exact (%d coplanar); the naive formula got %d "
        "wrong\n",
        zeros, wrong_naive);
    CHECK(wrong_naive > 100);
    CHECK(zeros > 10);
}

static void orientation_conventions(void)
{
    const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0}, z[3] = {0, 0, 1};
    CHECK_EQ(mt_orient2d(o, x, y), 1); /* counterclockwise */
    CHECK_EQ(mt_orient2d(o, y, x), -1);
    CHECK_EQ(mt_orient2d(o, x, (double[2]){2, 0}), 0);
    CHECK_EQ(mt_orient3d(o, x, y, z), 1); /* z on the side of (x - o) x (y - o) */
    CHECK_EQ(mt_orient3d(o, y, x, z), -1);
    CHECK_EQ(mt_orient3d(o, x, y, (double[3]){5, -7, 0}), 0);
    /* Far apart magnitudes: exact, not drowned. */
    const double tiny[3] = {0x1p-200, 0x1p-200, 0x1p-200};
    CHECK_EQ(mt_orient3d((double[3]){0x1p100, 0, 0}, (double[3]){0, 0x1p100, 0},
                         (double[3]){-0x1p100, -0x1p100, 0}, tiny),
             1);
    /* Right of the direction from a to b, down the line y = x. */
    CHECK_EQ(mt_orient2d((double[2]){0x1p100, 0x1p100}, (double[2]){-0x1p100, -0x1p100},
                         (double[2]){-0x1p-200, 0x1p-200}),
             -1);
    /* Non-finite coordinates give 0. */
    CHECK_EQ(mt_orient2d(o, x, (double[2]){NAN, 1}), 0);
    CHECK_EQ(mt_orient3d(o, x, y, (double[3]){0, 0, INFINITY}), 0);
}

/* T(a, b, c) as a 3x3 array literal. */
#define TRI(ax, ay, az, bx, by, bz, cx, cy, cz) \
    (const double[3][3])                        \
    {                                           \
        {ax, ay, az}, {bx, by, bz},             \
        {                                       \
            cx, cy, cz                          \
        }                                       \
    }

static void triangles_touching_and_not(void)
{
    const double(*flat)[3] = TRI(0, 0, 0, 4, 0, 0, 0, 4, 0);
    /* Crossing: a vertical triangle through the flat one. */
    CHECK(mt_triangles_intersect(flat, TRI(1, 1, -1, 1, 1, 1, 2, 0.5, 0)));
    /* Parallel planes. */
    CHECK(!mt_triangles_intersect(flat, TRI(0, 0, 1, 4, 0, 1, 0, 4, 1)));
    /* A corner on the flat one's inside, on its edge, on its corner: touching. */
    CHECK(mt_triangles_intersect(flat, TRI(1, 1, 0, 1, 1, 3, 2, 2, 3)));
    CHECK(mt_triangles_intersect(flat, TRI(2, 0, 0, 2, 1, 3, 2, -1, 3)));
    CHECK(mt_triangles_intersect(flat, TRI(4, 0, 0, 5, 1, 3, 5, -1, 3)));
    /* The same corner one representable step above the plane: apart. */
    double above = nextafter(0.0, 1.0);
    CHECK(!mt_triangles_intersect(flat, TRI(1, 1, above, 1, 1, 3, 2, 2, 3)));
    /* A corner on the slanted edge y = x / 3 (at x = 1.5, y = 0.5), one
     * representable step inside it and one outside. */
    const double(*slanted)[3] = TRI(0, 0, 0, 3, 1, 0, 0, 1, 0);
    double in = nextafter(0.5, 1.0), out = nextafter(0.5, 0.0);
    CHECK(mt_triangles_intersect(slanted, TRI(1.5, 0.5, 0, 1.5, 0.5, 2, 2, 2, 2)));
    CHECK(mt_triangles_intersect(slanted, TRI(1.5, in, 0, 1.5, in, 2, 2, 2, 2)));
    CHECK(!mt_triangles_intersect(slanted, TRI(1.5, out, 0, 1.5, out, 2, 2, 2, 2)));
    /* Coplanar: overlapping, one inside the other, sharing an edge, apart. */
    CHECK(mt_triangles_intersect(flat, TRI(1, 1, 0, 5, 1, 0, 1, 5, 0)));
    CHECK(mt_triangles_intersect(flat, TRI(0.5, 0.5, 0, 1, 0.5, 0, 0.5, 1, 0)));
    CHECK(mt_triangles_intersect(flat, TRI(4, 0, 0, 0, 4, 0, 4, 4, 0)));
    CHECK(!mt_triangles_intersect(flat, TRI(4.5, 0, 0, 4.5, 4, 0, 8, 2, 0)));
    /* Degenerate: a segment through it, a segment beside it in its plane,
     * a point in it, a point beside it. */
    CHECK(mt_triangles_intersect(flat, TRI(1, 1, -1, 1, 1, 1, 1, 1, 0.5)));
    CHECK(!mt_triangles_intersect(flat, TRI(3, 3, 0, 5, 5, 0, 4, 4, 0)));
    CHECK(mt_triangles_intersect(flat, TRI(1, 1, 0, 1, 1, 0, 1, 1, 0)));
    CHECK(!mt_triangles_intersect(flat, TRI(3, 3, 0, 3, 3, 0, 3, 3, 0)));
    /* Two segments on one line, overlapping and apart; a point on a segment. */
    CHECK(mt_triangles_intersect(TRI(0, 0, 0, 2, 2, 2, 1, 1, 1), TRI(1, 1, 1, 3, 3, 3, 3, 3, 3)));
    CHECK(!mt_triangles_intersect(TRI(0, 0, 0, 1, 1, 1, 1, 1, 1), TRI(2, 2, 2, 3, 3, 3, 3, 3, 3)));
    CHECK(mt_triangles_intersect(TRI(0, 0, 0, 2, 2, 2, 2, 2, 2), TRI(1, 1, 1, 1, 1, 1, 1, 1, 1)));
    /* Skew segments do not meet; crossing ones do. */
    CHECK(!mt_triangles_intersect(TRI(0, 0, 0, 2, 0, 0, 2, 0, 0), TRI(1, -1, 1, 1, 1, 1, 1, 1, 1)));
    CHECK(mt_triangles_intersect(TRI(0, 0, 0, 2, 0, 0, 2, 0, 0), TRI(1, -1, 0, 1, 1, 0, 1, 1, 0)));
    /* The segment test alone, and symmetry. */
    CHECK(mt_segment_hits_triangle((double[3]){1, 1, -1}, (double[3]){1, 1, 1}, flat));
    CHECK(!mt_segment_hits_triangle((double[3]){1, 1, 0.5}, (double[3]){1, 1, 1}, flat));
}

/* Near misses far from the origin: two triangles moved by 2^20, one of them
 * by a tiny step more, toward and away from the other. */
static void triangles_near_miss_far_away(void)
{
    const double o = 0x1p20, step = 0x1p-30;
    double a[3][3] = {{o, o, o}, {o + 1, o, o}, {o, o + 1, o}};
    /* b's corner lies on a's plane z = o at the edge x + y = o + 1 ... */
    double b[3][3] = {{o + 0.5, o + 0.5, o}, {o + 1, o + 1, o + 1}, {o + 2, o, o + 1}};
    CHECK(mt_triangles_intersect(a, b));
    /* ... moved off a's edge (outside) by a step: apart. */
    for (int i = 0; i < 3; i++) {
        b[i][0] += step;
        b[i][1] += step;
    }
    CHECK(!mt_triangles_intersect(a, b));
    CHECK(!mt_triangles_intersect(b, a));
    /* and back inside by two steps: touching a's plane inside it. */
    for (int i = 0; i < 3; i++) {
        b[i][0] -= 2 * step;
        b[i][1] -= 2 * step;
    }
    CHECK(mt_triangles_intersect(a, b));
    CHECK(mt_triangles_intersect(b, a));
}

static const mt_test_case cases[] = {
    {"triangles_touching_and_not", triangles_touching_and_not},
    {"triangles_near_miss_far_away", triangles_near_miss_far_away},
    {"orientation_conventions", orientation_conventions},
    {"orient2d_exact_near_lines", orient2d_exact_near_lines},
    {"orient3d_exact_near_planes", orient3d_exact_near_planes},
};
const mt_test_table mt_tests_predicates = {cases, sizeof cases / sizeof cases[0]};
