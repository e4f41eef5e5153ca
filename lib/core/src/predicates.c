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

#include <math.h>
#include <stdbool.h>

#define EPS 0x1p-53
#define ORIENT2D_BOUND ((3.0 + 16.0 * EPS) * EPS)
#define ORIENT3D_BOUND ((7.0 + 56.0 * EPS) * EPS)

/* Longest expansion an exact orient3d builds: 3 x (16-term minor times a
 * 2-term difference) = 192 components. */
#define MAX_TERMS 256

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

/* An expansion: n components, increasing in magnitude, none zero (n == 0
 * is the number zero). */
typedef struct expansion {
    double c[MAX_TERMS];
    int n;
} expansion;

/* h = e + b. */
static void grow(const expansion *e, double b, expansion *h)
{
    double q = b;
    int m = 0;
    for (int i = 0; i < e->n; i++) {
        double s, err;
        two_sum(q, e->c[i], &s, &err);
        if (err != 0) h->c[m++] = err;
        q = s;
    }
    if (q != 0) h->c[m++] = q;
    h->n = m;
}

/* *e += f (sign: +1 or -1 times f). */
static void add(expansion *e, const expansion *f, double sign)
{
    expansion t;
    for (int j = 0; j < f->n; j++) {
        grow(e, sign * f->c[j], &t);
        *e = t;
    }
}

/* h = e * b. */
static void scale(const expansion *e, double b, expansion *h)
{
    int m = 0;
    if (e->n == 0 || b == 0) {
        h->n = 0;
        return;
    }
    double q, low;
    two_product(e->c[0], b, &q, &low);
    if (low != 0) h->c[m++] = low;
    for (int i = 1; i < e->n; i++) {
        double hi, lo, s, err;
        two_product(e->c[i], b, &hi, &lo);
        two_sum(q, lo, &s, &err);
        if (err != 0) h->c[m++] = err;
        two_sum(hi, s, &q, &err);
        if (err != 0) h->c[m++] = err;
    }
    if (q != 0) h->c[m++] = q;
    h->n = m;
}

/* h = e * f. */
static void multiply(const expansion *e, const expansion *f, expansion *h)
{
    expansion part;
    h->n = 0;
    for (int j = 0; j < f->n; j++) {
        scale(e, f->c[j], &part);
        add(h, &part, 1.0);
    }
}

/* The exact difference a - b as an expansion. */
static void difference(double a, double b, expansion *out)
{
    double x, y;
    two_sum(a, -b, &x, &y);
    out->n = 0;
    if (y != 0) out->c[out->n++] = y;
    if (x != 0) out->c[out->n++] = x;
}

static int sign_of(const expansion *e)
{
    return e->n == 0 ? 0 : e->c[e->n - 1] > 0 ? 1 : -1;
}

/* ux vy - uy vx, exactly. */
static void cross2(const expansion *ux, const expansion *uy, const expansion *vx,
                   const expansion *vy, expansion *out)
{
    expansion right;
    multiply(ux, vy, out);
    multiply(uy, vx, &right);
    add(out, &right, -1.0);
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
    if (!finite2(a) || !finite2(b) || !finite2(c)) return 0;
    double left = (b[0] - a[0]) * (c[1] - a[1]);
    double right = (b[1] - a[1]) * (c[0] - a[0]);
    double det = left - right;
    double bound = ORIENT2D_BOUND * (fabs(left) + fabs(right));
    if (det > bound || -det > bound) return det > 0 ? 1 : -1;
    expansion ux, uy, vx, vy, d;
    difference(b[0], a[0], &ux);
    difference(b[1], a[1], &uy);
    difference(c[0], a[0], &vx);
    difference(c[1], a[1], &vy);
    cross2(&ux, &uy, &vx, &vy, &d);
    return sign_of(&d);
}

int mt_orient3d(const double a[3], const double b[3], const double c[3], const double d[3])
{
    if (!finite3(a) || !finite3(b) || !finite3(c) || !finite3(d)) return 0;
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
    if (det > bound || -det > bound) return det > 0 ? 1 : -1;

    expansion eu[3], ev[3], ew[3];
    for (int k = 0; k < 3; k++) {
        difference(b[k], a[k], &eu[k]);
        difference(c[k], a[k], &ev[k]);
        difference(d[k], a[k], &ew[k]);
    }
    expansion total, minor, term;
    total.n = 0;
    /* u0 (v1 w2 - v2 w1) + u1 (v2 w0 - v0 w2) + u2 (v0 w1 - v1 w0) */
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        cross2(&ev[i], &ev[j], &ew[i], &ew[j], &minor);
        multiply(&minor, &eu[k], &term);
        add(&total, &term, 1.0);
    }
    return sign_of(&total);
}
