/* Exact intersection tests of segments and triangles
 * (meshtopo/predicates.h), built only on mt_orient2d, mt_orient3d and
 * comparisons of coordinates, so that no rounding decides anything: two
 * closed triangles meet exactly when an edge of one meets the other; a
 * segment meets a triangle when it crosses or touches its plane inside it,
 * or, lying in that plane, meets it in a projection that keeps the plane
 * one to one. Degenerate triangles (three points on a line, or one point)
 * are the union of their sides. */
#include <math.h>
#include <stdbool.h>

#include "geometry/geometry_internal.h"
#include "meshtopo/predicates.h"

/* p projected by dropping coordinate `drop`. */
static void project(const double p[3], int drop, double out[2])
{
    out[0] = p[drop == 0 ? 1 : 0];
    out[1] = p[drop == 2 ? 1 : 2];
}

/* Whether p, on the line through a and b, lies between them (closed). */
static bool between(const double *a, const double *b, const double *p, int dims)
{
    for (int k = 0; k < dims; k++) {
        double lo = a[k] < b[k] ? a[k] : b[k], hi = a[k] < b[k] ? b[k] : a[k];
        if (p[k] < lo || p[k] > hi) return false;
    }
    return true;
}

/* Closed segments [p, q] and [r, s] in the plane. */
static bool segments_meet_2d(const double p[2], const double q[2], const double r[2],
                             const double s[2])
{
    int d1 = mt_orient2d(r, s, p), d2 = mt_orient2d(r, s, q);
    int d3 = mt_orient2d(p, q, r), d4 = mt_orient2d(p, q, s);
    if (d1 * d2 < 0 && d3 * d4 < 0) return true;
    return (d1 == 0 && between(r, s, p, 2)) || (d2 == 0 && between(r, s, q, 2)) ||
           (d3 == 0 && between(p, q, r, 2)) || (d4 == 0 && between(p, q, s, 2));
}

/* A coordinate to drop that keeps the plane of a, b, c one to one (one
 * where their projections are not collinear); -1 when a, b, c are on one
 * line (or coincide) and span no plane. The axes are tried largest normal
 * component first (the normal in doubles only orders the tries), so the
 * first try usually decides with the fast filter of mt_orient2d. */
static int plane_projection(const double a[3], const double b[3], const double c[3])
{
    double u[3], v[3], n[3];
    for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
    n[0] = fabs(u[1] * v[2] - u[2] * v[1]);
    n[1] = fabs(u[2] * v[0] - u[0] * v[2]);
    n[2] = fabs(u[0] * v[1] - u[1] * v[0]);
    int order[3] = {0, 1, 2};
    for (int i = 1; i < 3; i++)
        for (int j = i; j > 0 && n[order[j]] > n[order[j - 1]]; j--) {
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    for (int i = 0; i < 3; i++) {
        const int drop = order[i];
        double pa[2], pb[2], pc[2];
        project(a, drop, pa);
        project(b, drop, pb);
        project(c, drop, pc);
        if (mt_orient2d(pa, pb, pc) != 0) return drop;
    }
    return -1;
}

/* Closed segments [p, q] and [r, s] in space. */
static bool segments_meet(const double p[3], const double q[3], const double r[3],
                          const double s[3])
{
    if (mt_orient3d(p, q, r, s) != 0) return false; /* skew */
    const double *pts[4] = {p, q, r, s};
    /* Coplanar: a projection that is one to one on their plane, if three of
     * them span it. */
    for (int i = 0; i < 4; i++) {
        int drop = plane_projection(pts[i], pts[(i + 1) % 4], pts[(i + 2) % 4]);
        if (drop < 0) continue;
        double pp[2], pq[2], pr[2], ps[2];
        project(p, drop, pp);
        project(q, drop, pq);
        project(r, drop, pr);
        project(s, drop, ps);
        return segments_meet_2d(pp, pq, pr, ps);
    }
    /* All four on one line: intervals along a coordinate that varies on it
     * (all equal: one point). */
    for (int k = 0; k < 3; k++) {
        if (p[k] == q[k] && q[k] == r[k] && r[k] == s[k]) continue;
        double lo1 = p[k] < q[k] ? p[k] : q[k], hi1 = p[k] < q[k] ? q[k] : p[k];
        double lo2 = r[k] < s[k] ? r[k] : s[k], hi2 = r[k] < s[k] ? s[k] : r[k];
        return lo1 <= hi2 && lo2 <= hi1;
    }
    return true;
}

/* Whether the closed triangle (a, b, c), not degenerate, contains p of its
 * plane, in a projection one to one on the plane. */
static bool inside_2d(const double a[2], const double b[2], const double c[2], const double p[2])
{
    int o1 = mt_orient2d(a, b, p), o2 = mt_orient2d(b, c, p), o3 = mt_orient2d(c, a, p);
    bool negative = o1 < 0 || o2 < 0 || o3<0, positive = o1> 0 || o2 > 0 || o3 > 0;
    return !(negative && positive);
}

bool mt_segment_hits_triangle(const double s[3], const double e[3], const double t[3][3])
{
    const double *a = t[0], *b = t[1], *c = t[2];
    const int drop = plane_projection(a, b, c);
    if (drop < 0)
        return segments_meet(s, e, a, b) || segments_meet(s, e, b, c) || segments_meet(s, e, c, a);
    int os = mt_orient3d(a, b, c, s), oe = mt_orient3d(a, b, c, e);
    if (os == oe && os != 0) return false; /* both on one side */
    if (os == 0 && oe == 0) {
        double pa[2], pb[2], pc[2], ps[2], pe[2];
        project(a, drop, pa);
        project(b, drop, pb);
        project(c, drop, pc);
        project(s, drop, ps);
        project(e, drop, pe);
        return inside_2d(pa, pb, pc, ps) || segments_meet_2d(ps, pe, pa, pb) ||
               segments_meet_2d(ps, pe, pb, pc) || segments_meet_2d(ps, pe, pc, pa);
    }
    /* The line through s and e crosses the plane at one point of the
     * segment: inside the triangle when it passes no edge on the outside
     * (the three orientations never disagree in sign). */
    int o1 = mt_orient3d(s, e, a, b), o2 = mt_orient3d(s, e, b, c), o3 = mt_orient3d(s, e, c, a);
    bool negative = o1 < 0 || o2 < 0 || o3<0, positive = o1> 0 || o2 > 0 || o3 > 0;
    return !(negative && positive);
}

/* Signs of three orientations all strictly the same: the points lie on one
 * side of the plane (or line). */
static bool one_side(int s0, int s1, int s2)
{
    return (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0);
}

/* Two coplanar proper triangles a and b, seen in projection `drop` (one to
 * one on their plane): whether they share a point. Convex polygons are
 * apart exactly when one's corners all lie strictly outside a side of the
 * other (the separating axis theorem), which exact orientations decide. */
static bool coplanar_overlap(const double a[3][3], const double b[3][3], int drop)
{
    double p[2][3][2];
    for (int i = 0; i < 3; i++) {
        project(a[i], drop, p[0][i]);
        project(b[i], drop, p[1][i]);
    }
    for (int t = 0; t < 2; t++) {
        const double(*own)[2] = p[t], (*other)[2] = p[1 - t];
        const int inside = mt_orient2d(own[0], own[1], own[2]);
        for (int i = 0; i < 3; i++) {
            const double *s = own[i], *e = own[(i + 1) % 3];
            const int o0 = mt_orient2d(s, e, other[0]) * inside,
                      o1 = mt_orient2d(s, e, other[1]) * inside,
                      o2 = mt_orient2d(s, e, other[2]) * inside;
            if (o0 < 0 && o1 < 0 && o2 < 0) return false;
        }
    }
    return true;
}

bool mt_triangles_intersect(const double a[3][3], const double b[3][3])
{
    /* Apart when one lies strictly on one side of the other's plane (a
     * degenerate triangle gives orientations 0, never one side); proper
     * coplanar ones are judged in their plane. */
    const double *const pa[3] = {a[0], a[1], a[2]}, *const pb[3] = {b[0], b[1], b[2]};
    int sb[3], sa[3];
    mt__orient3d_points(a[0], a[1], a[2], pb, 3, sb);
    if (one_side(sb[0], sb[1], sb[2])) return false;
    mt__orient3d_points(b[0], b[1], b[2], pa, 3, sa);
    if (one_side(sa[0], sa[1], sa[2])) return false;
    if (sb[0] == 0 && sb[1] == 0 && sb[2] == 0) {
        const int drop = plane_projection(a[0], a[1], a[2]);
        if (drop >= 0 && plane_projection(b[0], b[1], b[2]) >= 0)
            return coplanar_overlap(a, b, drop);
    }
    for (int i = 0; i < 3; i++)
        if (mt_segment_hits_triangle(a[i], a[(i + 1) % 3], b) ||
            mt_segment_hits_triangle(b[i], b[(i + 1) % 3], a))
            return true;
    return false;
}

/* Triangles sharing the side u-w, third corners a3 and b3: whether they meet
 * beyond that side. Not coplanar, they meet only along it. Coplanar, they
 * overlap when the third corners lie strictly on one side of the line; a
 * triangle whose third corner is on the line is a segment along it, which a
 * proper triangle meets only within u-w, and two such segments overlap
 * beyond u-w when both third corners lie past the same end. */
static bool fold_across_side(const double *u, const double *w, const double *a3, const double *b3)
{
    if (u[0] == w[0] && u[1] == w[1] && u[2] == w[2]) {
        /* The shared side is one point: each triangle is the segment from
         * it to its third corner, and they overlap when those leave it in
         * the same direction along one line. */
        if (plane_projection(u, a3, b3) >= 0) return false;
        for (int k = 0; k < 3; k++)
            if (a3[k] != u[k]) return b3[k] != u[k] && (a3[k] > u[k]) == (b3[k] > u[k]);
        return false;
    }
    if (mt_orient3d(u, w, a3, b3) != 0) return false;
    int drop = plane_projection(u, w, a3);
    if (drop < 0) drop = plane_projection(u, w, b3);
    if (drop >= 0) {
        double pu[2], pw[2], pa[2], pb[2];
        project(u, drop, pu);
        project(w, drop, pw);
        project(a3, drop, pa);
        project(b3, drop, pb);
        const int sa = mt_orient2d(pu, pw, pa), sb = mt_orient2d(pu, pw, pb);
        return sa != 0 && sa == sb;
    }
    for (int k = 0; k < 3; k++) { /* all four on one line */
        if (u[k] == w[k] && u[k] == a3[k] && u[k] == b3[k]) continue;
        const double lo = u[k] < w[k] ? u[k] : w[k], hi = u[k] < w[k] ? w[k] : u[k];
        return (a3[k] > hi && b3[k] > hi) || (a3[k] < lo && b3[k] < lo);
    }
    return false; /* all at one point: the shared corners' */
}

static void copy_corners(const double *const p[3], double out[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) out[i][k] = p[i][k];
}

/* Whether direction x - v lies in the closed wedge at v from l - v
 * counter-clockwise to r - v (an angle below pi), in a projection. */
static bool in_wedge(const double v[2], const double l[2], const double r[2], const double x[2])
{
    return mt_orient2d(v, l, x) >= 0 && mt_orient2d(v, x, r) >= 0;
}

/* Coplanar proper triangles (v, a1, a2) and (v, b1, b2) seen in projection
 * `drop`: whether they share more than v. Near v each is its wedge, and two
 * wedges below pi share a ray exactly when one holds a side of the other. */
static bool wedges_overlap(const double *v, const double *a1, const double *a2, const double *b1,
                           const double *b2, int drop)
{
    double pv[2], pa[2][2], pb[2][2];
    project(v, drop, pv);
    project(a1, drop, pa[0]);
    project(a2, drop, pa[1]);
    project(b1, drop, pb[0]);
    project(b2, drop, pb[1]);
    const int ka = mt_orient2d(pv, pa[0], pa[1]) > 0 ? 0 : 1; /* a's right side first */
    const int kb = mt_orient2d(pv, pb[0], pb[1]) > 0 ? 0 : 1;
    const double *al = pa[ka], *ar = pa[1 - ka], *bl = pb[kb], *br = pb[1 - kb];
    return in_wedge(pv, al, ar, bl) || in_wedge(pv, al, ar, br) || in_wedge(pv, bl, br, al) ||
           in_wedge(pv, bl, br, ar);
}

/* Triangles a = (v, a1, a2) and b = (v, b1, b2) sharing corner v: whether
 * they meet beyond it. Proper ones do not when either lies strictly on one
 * side of the other's plane but for v; coplanar ones are judged by their
 * wedges at v; otherwise the side opposite v of one meets the other. */
static bool corner_pair_cross(const double *const pa[3], int ka, const double *const pb[3], int kb)
{
    const double *v = pa[ka], *a1 = pa[(ka + 1) % 3], *a2 = pa[(ka + 2) % 3];
    const double *b1 = pb[(kb + 1) % 3], *b2 = pb[(kb + 2) % 3];
    /* A degenerate triangle gives orientations 0, never one side. */
    int s[2], t[2];
    const double *const bq[2] = {b1, b2}, *const aq[2] = {a1, a2};
    mt__orient3d_points(v, a1, a2, bq, 2, s);
    if (s[0] * s[1] > 0) return false;
    mt__orient3d_points(v, b1, b2, aq, 2, t);
    if (t[0] * t[1] > 0) return false;
    if (s[0] == 0 && s[1] == 0) {
        const int drop = plane_projection(v, a1, a2);
        if (drop >= 0 && plane_projection(v, b1, b2) >= 0)
            return wedges_overlap(v, a1, a2, b1, b2, drop);
    }
    double a[3][3], b[3][3];
    copy_corners(pa, a);
    copy_corners(pb, b);
    return mt_segment_hits_triangle(a1, a2, b) || mt_segment_hits_triangle(b1, b2, a);
}

bool mt__triangles_cross(const uint32_t ia[3], const double *const pa[3], const uint32_t ib[3],
                         const double *const pb[3])
{
    int in_b[3], shared = 0; /* in_b[k]: the corner of b that is a's corner k, or -1 */
    for (int k = 0; k < 3; k++) {
        in_b[k] = -1;
        for (int j = 0; j < 3; j++)
            if (ia[k] == ib[j]) in_b[k] = j;
        shared += in_b[k] >= 0;
    }
    if (shared == 3) return true;
    if (shared == 0) {
        double a[3][3], b[3][3];
        copy_corners(pa, a);
        copy_corners(pb, b);
        return mt_triangles_intersect(a, b);
    }
    if (shared == 1) {
        int k = 0;
        while (in_b[k] < 0) k++;
        return corner_pair_cross(pa, k, pb, in_b[k]);
    }
    int k = 0, j = 0; /* the unshared corners */
    while (in_b[k] >= 0) k++;
    while (j < 3 && (ib[j] == ia[(k + 1) % 3] || ib[j] == ia[(k + 2) % 3])) j++;
    if (j == 3) return false; /* b repeats a corner: no third one */
    return fold_across_side(pa[(k + 1) % 3], pa[(k + 2) % 3], pa[k], pb[j]);
}
