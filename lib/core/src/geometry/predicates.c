/* Exact orientation predicates (meshtopo/predicates.h): a floating-point
 * determinant with a forward error bound decides when it can; otherwise the
 * determinant is computed exactly as an expansion, a sum of doubles whose
 * components do not overlap (each smaller than the next one's last bit), by
 * error-free transformations: TwoSum (Knuth) and TwoProduct (with fma).
 * The sign of such a sum is the sign of its largest component.
 *
 * Why by hand: Debian packages no C library of robust predicates (CGAL's are
 * C++ templates, and GMP rationals would allocate in every undecided test);
 * the arithmetic is a few dozen lines. The error bounds are those of the
 * standard analysis of these determinants (eps = 2^-53): orient2d's
 * (3 + 16 eps) eps and orient3d's (7 + 56 eps) eps times the permanent.
 *
 * Floating-point contraction (a * b + c fused) would break TwoSum and the
 * bounds: lib/core/CMakeLists.txt compiles this file with
 * -ffp-contract=off, and -ffast-math must never reach it. */
#include "meshtopo/predicates.h"

#include "geometry/geometry_internal.h"

#include <math.h>
#include <stdbool.h>

#define EPS 0x1p-53
#define ORIENT2D_BOUND ((3.0 + 16.0 * EPS) * EPS)
#define ORIENT3D_BOUND ((7.0 + 56.0 * EPS) * EPS)

/* Longest expansion an exact orient3d builds: a difference has at most 2
 * components, a product of two differences 8, a 2x2 minor 16, a minor times
 * a difference 64, and the sum of three such terms 192. */
#define MAX_TERMS 192

/* a + b = *x + *y exactly, *x = fl(a + b). */
static void two_sum(double a, double b, double *x, double *y)
{
    double s = a + b;
    double bv = s - a;
    double av = s - bv;
    *y = (a - av) + (b - bv);
    *x = s;
}

/* a * b = *x + *y exactly, *x = fl(a * b). */
static void two_product(double a, double b, double *x, double *y)
{
    double p = a * b;
    *y = fma(a, b, -p);
    *x = p;
}

/* Expansions are arrays of components, increasing in magnitude, none zero
 * (length 0 is the number zero). Each operation writes a new array, which
 * never aliases its inputs, and returns its length. */

/* h = e + b. */
static int grow(const double *e, int n, double b, double *h)
{
    double q = b;
    int m = 0;
    for (int i = 0; i < n; i++) {
        double s, err;
        two_sum(q, e[i], &s, &err);
        if (err != 0) h[m++] = err;
        q = s;
    }
    if (q != 0) h[m++] = q;
    return m;
}

/* h = e + sign * f, by growing e with each component of f in turn (the
 * expansions here are short: quadratic time costs less than merging). */
static int sum(const double *e, int ne, const double *f, int nf, double sign, double *h)
{
    double spare[MAX_TERMS];
    /* Alternate between h and spare so that the last grow writes into h. */
    double *out = nf % 2 ? h : spare, *other = nf % 2 ? spare : h;
    const double *in = e;
    int n = ne;
    if (nf == 0) {
        for (int i = 0; i < ne; i++) h[i] = e[i];
        return ne;
    }
    for (int j = 0; j < nf; j++) {
        n = grow(in, n, sign * f[j], out);
        in = out;
        double *t = out;
        out = other;
        other = t;
    }
    return n;
}

/* h = e * b. */
static int scale(const double *e, int n, double b, double *h)
{
    if (n == 0 || b == 0) return 0;
    int m = 0;
    double q, low;
    two_product(e[0], b, &q, &low);
    if (low != 0) h[m++] = low;
    for (int i = 1; i < n; i++) {
        double hi, lo, s, err;
        two_product(e[i], b, &hi, &lo);
        two_sum(q, lo, &s, &err);
        if (err != 0) h[m++] = err;
        two_sum(hi, s, &q, &err);
        if (err != 0) h[m++] = err;
    }
    if (q != 0) h[m++] = q;
    return m;
}

/* h = e * f. */
static int multiply(const double *e, int ne, const double *f, int nf, double *h)
{
    double part[MAX_TERMS], acc[MAX_TERMS];
    int n = 0;
    for (int j = 0; j < nf; j++) {
        const int np = scale(e, ne, f[j], part);
        n = sum(j % 2 ? acc : h, n, part, np, 1.0, j % 2 ? h : acc);
    }
    /* After the loop the result is in acc when nf is odd. */
    if (nf % 2)
        for (int i = 0; i < n; i++) h[i] = acc[i];
    return n;
}

/* The exact difference a - b (at most 2 components). */
static int difference(double a, double b, double out[2])
{
    double x, y;
    two_sum(a, -b, &x, &y);
    int n = 0;
    if (y != 0) out[n++] = y;
    if (x != 0) out[n++] = x;
    return n;
}

static int sign_of(const double *e, int n)
{
    return n == 0 ? 0 : e[n - 1] > 0 ? 1 : -1;
}

/* A difference as an expansion. */
typedef struct diff {
    double c[2];
    int n;
} diff;

/* ux vy - uy vx, exactly (at most 16 components). */
static int cross2(const diff *ux, const diff *uy, const diff *vx, const diff *vy, double *out)
{
    double left[8], right[8];
    const int nl = multiply(ux->c, ux->n, vy->c, vy->n, left);
    const int nr = multiply(uy->c, uy->n, vx->c, vx->n, right);
    return sum(left, nl, right, nr, -1.0, out);
}

static bool finite2(const double *p)
{
    return isfinite(p[0]) && isfinite(p[1]);
}

static bool finite3(const double *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

int mt_orient2d(const double a[2], const double b[2], const double c[2])
{
    double left = (b[0] - a[0]) * (c[1] - a[1]);
    double right = (b[1] - a[1]) * (c[0] - a[0]);
    double det = left - right;
    double bound = ORIENT2D_BOUND * (fabs(left) + fabs(right));
    /* A NaN or infinite coordinate makes a difference, and so the bound,
     * NaN or infinite; so does an overflowing product, decided exactly. */
    if (!isfinite(bound) && (!finite2(a) || !finite2(b) || !finite2(c))) return 0;
    if (det > bound || -det > bound) return det > 0 ? 1 : -1;
    /* A product of differences is 0 in doubles only when a difference is
     * exactly 0 (within the range of exactness nothing underflows): then
     * both exact products are 0 too. Points on an axis-aligned line. */
    if (bound == 0) return 0;
    diff ux, uy, vx, vy;
    ux.n = difference(b[0], a[0], ux.c);
    uy.n = difference(b[1], a[1], uy.c);
    vx.n = difference(c[0], a[0], vx.c);
    vy.n = difference(c[1], a[1], vy.c);
    double d[16];
    return sign_of(d, cross2(&ux, &uy, &vx, &vy, d));
}

void mt__orient3d_points(const double a[3], const double b[3], const double c[3],
                         const double *const *q, int n, int *out)
{
    /* mt_orient3d(a, q, b, c) has the sign of mt_orient3d(a, b, c, q) (a
     * cyclic permutation of the rows) and its minors come from b - a and
     * c - a alone: computed once, its filter is mt_orient3d's own. */
    double v[3], w[3];
    for (int k = 0; k < 3; k++) {
        v[k] = b[k] - a[k];
        w[k] = c[k] - a[k];
    }
    const double m0a = v[1] * w[2], m0b = v[2] * w[1];
    const double m1a = v[2] * w[0], m1b = v[0] * w[2];
    const double m2a = v[0] * w[1], m2b = v[1] * w[0];
    const double d0 = m0a - m0b, d1 = m1a - m1b, d2 = m2a - m2b;
    const double p0 = fabs(m0a) + fabs(m0b), p1 = fabs(m1a) + fabs(m1b), p2 = fabs(m2a) + fabs(m2b);
    for (int i = 0; i < n; i++) {
        double u[3];
        for (int k = 0; k < 3; k++) u[k] = q[i][k] - a[k];
        const double det = u[0] * d0 + u[1] * d1 + u[2] * d2;
        const double bound = ORIENT3D_BOUND * (p0 * fabs(u[0]) + p1 * fabs(u[1]) + p2 * fabs(u[2]));
        if (isfinite(bound) && (det > bound || -det > bound))
            out[i] = det > 0 ? 1 : -1;
        else
            out[i] = mt_orient3d(a, q[i], b, c);
    }
}

int mt_orient3d(const double a[3], const double b[3], const double c[3], const double d[3])
{
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = d[k] - a[k];
    }
    /* det [u; v; w] along u: minors of v and w. */
    double m0a = v[1] * w[2], m0b = v[2] * w[1];
    double m1a = v[2] * w[0], m1b = v[0] * w[2];
    double m2a = v[0] * w[1], m2b = v[1] * w[0];
    double det = u[0] * (m0a - m0b) + u[1] * (m1a - m1b) + u[2] * (m2a - m2b);
    double permanent = (fabs(m0a) + fabs(m0b)) * fabs(u[0]) + (fabs(m1a) + fabs(m1b)) * fabs(u[1]) +
                       (fabs(m2a) + fabs(m2b)) * fabs(u[2]);
    double bound = ORIENT3D_BOUND * permanent;
    /* As in mt_orient2d: a coordinate that is not finite shows in the bound. */
    if (!isfinite(bound) && (!finite3(a) || !finite3(b) || !finite3(c) || !finite3(d))) return 0;
    if (det > bound || -det > bound) return det > 0 ? 1 : -1;
    /* As in mt_orient2d: every product has an exactly zero factor, so the
     * determinant is exactly 0 (points on an axis-aligned plane). */
    if (bound == 0) return 0;

    diff eu[3], ev[3], ew[3];
    for (int k = 0; k < 3; k++) {
        eu[k].n = difference(b[k], a[k], eu[k].c);
        ev[k].n = difference(c[k], a[k], ev[k].c);
        ew[k].n = difference(d[k], a[k], ew[k].c);
    }
    /* u0 (v1 w2 - v2 w1) + u1 (v2 w0 - v0 w2) + u2 (v0 w1 - v1 w0) */
    double total[MAX_TERMS], next[MAX_TERMS];
    int n = 0;
    for (int k = 0; k < 3; k++) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        double minor[16], term[64];
        const int nm = cross2(&ev[i], &ev[j], &ew[i], &ew[j], minor);
        const int nt = multiply(minor, nm, eu[k].c, eu[k].n, term);
        n = sum(total, n, term, nt, 1.0, next);
        for (int t = 0; t < n; t++) total[t] = next[t];
    }
    return sign_of(total, n);
}
