/* Exact segment and triangle tests for the self-intersection oracle
 * (selfx_exact.h). Every quantity is an integer polynomial in the
 * coordinates, so nothing is rounded: a segment meets a plane where
 * Cramer's rule puts its parameter in range, two segments meet where the
 * cross products put both parameters in [0, 1], and parallel or
 * degenerate cases are decided by collinearity and dot-product intervals. */
#include "selfx_exact.h"

#include <assert.h>

void sx_pool_init(sx_pool *pool)
{
    for (int i = 0; i < SX_POOL_SIZE; i++) mpz_init(pool->z[i]);
    pool->top = 0;
}

void sx_pool_clear(sx_pool *pool)
{
    for (int i = 0; i < SX_POOL_SIZE; i++) mpz_clear(pool->z[i]);
    pool->top = 0;
}

static mpz_ptr take(sx_pool *pool)
{
    assert(pool->top < SX_POOL_SIZE);
    return pool->z[pool->top++];
}

static sx_vec take_vec(sx_pool *pool)
{
    sx_vec v = {{take(pool), take(pool), take(pool)}};
    return v;
}

static void vec_sub(sx_vec out, sx_vec a, sx_vec b)
{
    for (int k = 0; k < 3; k++) mpz_sub(out.c[k], a.c[k], b.c[k]);
}

/* out = a x b; out must not be a or b. */
static void vec_cross(sx_vec out, sx_vec a, sx_vec b)
{
    mpz_mul(out.c[0], a.c[1], b.c[2]);
    mpz_submul(out.c[0], a.c[2], b.c[1]);
    mpz_mul(out.c[1], a.c[2], b.c[0]);
    mpz_submul(out.c[1], a.c[0], b.c[2]);
    mpz_mul(out.c[2], a.c[0], b.c[1]);
    mpz_submul(out.c[2], a.c[1], b.c[0]);
}

static void vec_dot(mpz_ptr out, sx_vec a, sx_vec b)
{
    mpz_mul(out, a.c[0], b.c[0]);
    mpz_addmul(out, a.c[1], b.c[1]);
    mpz_addmul(out, a.c[2], b.c[2]);
}

static bool vec_is_zero(sx_vec a)
{
    return mpz_sgn(a.c[0]) == 0 && mpz_sgn(a.c[1]) == 0 && mpz_sgn(a.c[2]) == 0;
}

static bool vec_equal(sx_vec a, sx_vec b)
{
    return mpz_cmp(a.c[0], b.c[0]) == 0 && mpz_cmp(a.c[1], b.c[1]) == 0 &&
           mpz_cmp(a.c[2], b.c[2]) == 0;
}

/* 0 <= num <= den, for den > 0. */
static bool in_unit_range(mpz_srcptr num, mpz_srcptr den)
{
    return mpz_sgn(num) >= 0 && mpz_cmp(num, den) <= 0;
}

/* Whether p lies on the line through base with direction d (d non-zero). */
static bool on_line(sx_pool *pool, sx_vec base, sx_vec d, sx_vec p)
{
    const int mark = pool->top;
    sx_vec r = take_vec(pool), c = take_vec(pool);
    vec_sub(r, p, base);
    vec_cross(c, r, d);
    bool on = vec_is_zero(c);
    pool->top = mark;
    return on;
}

bool sx_segments_meet(sx_pool *pool, sx_vec s, sx_vec e, sx_vec p, sx_vec q)
{
    const int mark = pool->top;
    sx_vec d1 = take_vec(pool), d2 = take_vec(pool), r = take_vec(pool), n = take_vec(pool);
    sx_vec w = take_vec(pool);
    mpz_ptr k = take(pool), den = take(pool), num_t = take(pool), num_u = take(pool);
    vec_sub(d1, e, s);
    vec_sub(d2, q, p);
    vec_sub(r, p, s);
    vec_cross(n, d1, d2);
    bool meet;
    if (!vec_is_zero(n)) {
        /* Lines not parallel: s + t d1 = p + u d2 needs r in their plane;
         * crossing with d2 (d1) gives t (u) as a quotient by n . n. */
        vec_dot(k, r, n);
        if (mpz_sgn(k) != 0) {
            meet = false; /* skew */
        } else {
            vec_dot(den, n, n);
            vec_cross(w, r, d2);
            vec_dot(num_t, w, n);
            vec_cross(w, r, d1);
            vec_dot(num_u, w, n);
            meet = in_unit_range(num_t, den) && in_unit_range(num_u, den);
        }
    } else if (vec_is_zero(d1) && vec_is_zero(d2)) {
        meet = vec_equal(s, p); /* two points */
    } else {
        /* Parallel (or one is a point): all four on one line, then the
         * intervals of their positions along it overlap. */
        sx_vec d = vec_is_zero(d1) ? d2 : d1, base = vec_is_zero(d1) ? p : s;
        meet = on_line(pool, base, d, s) && on_line(pool, base, d, e) &&
               on_line(pool, base, d, p) && on_line(pool, base, d, q);
        if (meet) {
            mpz_ptr a0 = k, a1 = den, b0 = num_t, b1 = num_u;
            vec_dot(a0, s, d);
            vec_dot(a1, e, d);
            vec_dot(b0, p, d);
            vec_dot(b1, q, d);
            if (mpz_cmp(a0, a1) > 0) mpz_swap(a0, a1);
            if (mpz_cmp(b0, b1) > 0) mpz_swap(b0, b1);
            meet = mpz_cmp(a0, b1) <= 0 && mpz_cmp(b0, a1) <= 0;
        }
    }
    pool->top = mark;
    return meet;
}

void sx_triangle_normal(const sx_vec t[3], sx_vec out)
{
    mpz_t u[3], v[3];
    for (int k = 0; k < 3; k++) {
        mpz_init(u[k]);
        mpz_init(v[k]);
    }
    sx_vec ub = {{u[0], u[1], u[2]}}, vb = {{v[0], v[1], v[2]}};
    vec_sub(ub, t[1], t[0]);
    vec_sub(vb, t[2], t[0]);
    vec_cross(out, ub, vb);
    for (int k = 0; k < 3; k++) {
        mpz_clear(u[k]);
        mpz_clear(v[k]);
    }
}

/* Whether p, in the plane of triangle t (normal n, non-zero), lies in the
 * closed triangle: on the inner side of each of its sides or on it. */
static bool point_in_triangle(sx_pool *pool, sx_vec p, const sx_vec t[3], sx_vec n)
{
    const int mark = pool->top;
    sx_vec side = take_vec(pool), to_p = take_vec(pool), c = take_vec(pool);
    mpz_ptr k = take(pool);
    bool inside = true;
    for (int i = 0; i < 3 && inside; i++) {
        vec_sub(side, t[(i + 1) % 3], t[i]);
        vec_sub(to_p, p, t[i]);
        vec_cross(c, side, to_p);
        vec_dot(k, c, n);
        inside = mpz_sgn(k) >= 0;
    }
    pool->top = mark;
    return inside;
}

bool sx_segment_meets_triangle(sx_pool *pool, sx_vec s, sx_vec e, const sx_vec t[3])
{
    const int mark = pool->top;
    sx_vec ab = take_vec(pool), ac = take_vec(pool), n = take_vec(pool);
    sx_vec m1 = take_vec(pool), r = take_vec(pool), w = take_vec(pool);
    mpz_ptr det = take(pool), det_t = take(pool), det_u = take(pool), det_v = take(pool);
    vec_sub(ab, t[0], t[1]); /* a - b */
    vec_sub(ac, t[0], t[2]); /* a - c */
    vec_cross(n, ab, ac);    /* (b - a) x (c - a) */
    bool meet;
    if (vec_is_zero(n)) {
        /* Corners on one line: the union of the three sides. */
        meet = sx_segments_meet(pool, s, e, t[0], t[1]) ||
               sx_segments_meet(pool, s, e, t[1], t[2]) || sx_segments_meet(pool, s, e, t[2], t[0]);
        pool->top = mark;
        return meet;
    }
    /* s + t (e - s) = a + u (b - a) + v (c - a), by Cramer's rule on the
     * columns m1 = e - s, a - b, a - c and the right side r = a - s:
     * det = m1 . n, det_t = r . n, det_u = m1 . (r x (a - c)),
     * det_v = m1 . ((a - b) x r). */
    vec_sub(m1, e, s);
    vec_sub(r, t[0], s);
    vec_dot(det, m1, n);
    vec_dot(det_t, r, n);
    if (mpz_sgn(det) != 0) {
        vec_cross(w, r, ac);
        vec_dot(det_u, m1, w);
        vec_cross(w, ab, r);
        vec_dot(det_v, m1, w);
        if (mpz_sgn(det) < 0) {
            mpz_neg(det, det);
            mpz_neg(det_t, det_t);
            mpz_neg(det_u, det_u);
            mpz_neg(det_v, det_v);
        }
        mpz_add(w.c[0], det_u, det_v);
        meet = in_unit_range(det_t, det) && mpz_sgn(det_u) >= 0 && mpz_sgn(det_v) >= 0 &&
               mpz_cmp(w.c[0], det) <= 0;
    } else if (mpz_sgn(det_t) != 0) {
        meet = false; /* parallel to the plane, off it */
    } else {
        /* In the plane: an end inside, or the segment crosses a side. */
        meet = point_in_triangle(pool, s, t, n) || point_in_triangle(pool, e, t, n) ||
               sx_segments_meet(pool, s, e, t[0], t[1]) ||
               sx_segments_meet(pool, s, e, t[1], t[2]) || sx_segments_meet(pool, s, e, t[2], t[0]);
    }
    pool->top = mark;
    return meet;
}

bool sx_triangles_meet(sx_pool *pool, const sx_vec a[3], const sx_vec b[3])
{
    for (int i = 0; i < 3; i++) {
        if (sx_segment_meets_triangle(pool, a[i], a[(i + 1) % 3], b)) return true;
        if (sx_segment_meets_triangle(pool, b[i], b[(i + 1) % 3], a)) return true;
    }
    return false;
}

/* Corner of t (0..2) with the given id, or -1. */
static int corner_with_id(const uint32_t ids[3], uint32_t id)
{
    for (int i = 0; i < 3; i++)
        if (ids[i] == id) return i;
    return -1;
}

bool sx_triangles_clash(sx_pool *pool, const uint32_t ids_a[3], const sx_vec a[3],
                        const uint32_t ids_b[3], const sx_vec b[3])
{
    int shared = 0, in_b[3];
    for (int i = 0; i < 3; i++) {
        in_b[i] = corner_with_id(ids_b, ids_a[i]);
        shared += in_b[i] >= 0;
    }
    if (shared == 0) return sx_triangles_meet(pool, a, b);
    if (shared == 3) return true;
    if (shared == 1) {
        int va = in_b[0] >= 0 ? 0 : in_b[1] >= 0 ? 1 : 2, vb = in_b[va];
        return sx_segment_meets_triangle(pool, a[(va + 1) % 3], a[(va + 2) % 3], b) ||
               sx_segment_meets_triangle(pool, b[(vb + 1) % 3], b[(vb + 2) % 3], a);
    }
    /* Two shared: u, w; x the third corner of a, y of b. */
    int xa = in_b[0] < 0 ? 0 : in_b[1] < 0 ? 1 : 2;
    int ua = (xa + 1) % 3, wa = (xa + 2) % 3;
    int yb = 3 - in_b[ua] - in_b[wa];
    const int mark = pool->top;
    sx_vec uw = take_vec(pool), ux = take_vec(pool), uy = take_vec(pool);
    sx_vec na = take_vec(pool), nb = take_vec(pool);
    mpz_ptr k = take(pool), len = take(pool);
    vec_sub(uw, a[wa], a[ua]);
    vec_sub(ux, a[xa], a[ua]);
    vec_sub(uy, b[yb], a[ua]);
    vec_cross(na, uw, ux); /* normal of a, from the line uw towards x */
    vec_cross(nb, uw, uy); /* the same for b and y */
    bool clash;
    if (!vec_is_zero(na) && !vec_is_zero(nb)) {
        /* Two proper triangles: coplanar, x and y strictly on one side. */
        vec_dot(k, uy, na);
        clash = mpz_sgn(k) == 0;
        vec_dot(k, na, nb);
        clash = clash && mpz_sgn(k) > 0;
    } else if (!vec_is_zero(na) || !vec_is_zero(nb)) {
        /* A proper triangle meets the line uw only in the segment uw, and
         * the other one (u != w here) lies on that line. */
        clash = false;
    } else if (!vec_is_zero(uw)) {
        /* Two segments along the line uw: they overlap beyond the segment
         * uw when x and y lie past the same end of it. */
        mpz_ptr sx = na.c[0], sy = nb.c[0];
        vec_dot(len, uw, uw);
        vec_dot(sx, ux, uw);
        vec_dot(sy, uy, uw);
        clash =
            (mpz_cmp(sx, len) > 0 && mpz_cmp(sy, len) > 0) || (mpz_sgn(sx) < 0 && mpz_sgn(sy) < 0);
    } else {
        /* u and w at one point: the segments from it to x and to y overlap
         * when they leave it in the same direction. */
        vec_cross(na, ux, uy);
        vec_dot(k, ux, uy);
        clash = !vec_is_zero(ux) && !vec_is_zero(uy) && vec_is_zero(na) && mpz_sgn(k) > 0;
    }
    pool->top = mark;
    return clash;
}

bool sx_plane_separates(sx_pool *pool, const uint32_t ids_a[3], const sx_vec a[3], sx_vec normal_a,
                        const uint32_t ids_b[3], const sx_vec b[3])
{
    const int mark = pool->top;
    sx_vec r = take_vec(pool);
    mpz_ptr k = take(pool);
    int side = 0;
    bool separated = true;
    for (int i = 0; i < 3 && separated; i++) {
        if (corner_with_id(ids_a, ids_b[i]) >= 0) continue;
        vec_sub(r, b[i], a[0]);
        vec_dot(k, r, normal_a);
        int sign = mpz_sgn(k);
        separated = sign != 0 && (side == 0 || sign == side);
        side = sign;
    }
    pool->top = mark;
    return separated && side != 0;
}

bool sx_sides_fold(sx_pool *pool, sx_vec a, sx_vec q, sx_vec b)
{
    const int mark = pool->top;
    sx_vec qa = take_vec(pool), qb = take_vec(pool), c = take_vec(pool);
    mpz_ptr k = take(pool);
    vec_sub(qa, a, q);
    vec_sub(qb, b, q);
    vec_cross(c, qa, qb);
    vec_dot(k, qa, qb);
    bool fold = vec_is_zero(c) && mpz_sgn(k) > 0;
    pool->top = mark;
    return fold;
}
