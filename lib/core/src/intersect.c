/* Exact intersection tests of segments and triangles
 * (meshtopo/predicates.h), built only on mt_orient2d, mt_orient3d and
 * comparisons of coordinates, so that no rounding decides anything: two
 * closed triangles meet exactly when an edge of one meets the other; a
 * segment meets a triangle when it crosses or touches its plane inside it,
 * or, lying in that plane, meets it in a projection that keeps the plane
 * one to one. Degenerate triangles (three points on a line, or one point)
 * are the union of their sides. */
#include <stdbool.h>

#include "geometry_internal.h"
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
 * line (or coincide) and span no plane. */
static int plane_projection(const double a[3], const double b[3], const double c[3])
{
    for (int drop = 0; drop < 3; drop++) {
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

bool mt_triangles_intersect(const double a[3][3], const double b[3][3])
{
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
    if (shared < 2) {
        double a[3][3], b[3][3];
        copy_corners(pa, a);
        copy_corners(pb, b);
        if (shared == 0) return mt_triangles_intersect(a, b);
        int k = 0;
        while (in_b[k] < 0) k++;
        const int j = in_b[k];
        return mt_segment_hits_triangle(pa[(k + 1) % 3], pa[(k + 2) % 3], b) ||
               mt_segment_hits_triangle(pb[(j + 1) % 3], pb[(j + 2) % 3], a);
    }
    int k = 0, j = 0; /* the unshared corners */
    while (in_b[k] >= 0) k++;
    while (j < 3 && (ib[j] == ia[(k + 1) % 3] || ib[j] == ia[(k + 2) % 3])) j++;
    if (j == 3) return false; /* b repeats a corner: no third one */
    return fold_across_side(pa[(k + 1) % 3], pa[(k + 2) % 3], pa[k], pb[j]);
}
