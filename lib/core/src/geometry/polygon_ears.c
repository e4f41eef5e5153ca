/* Ear clipping (Eberly, "Triangulation by Ear Clipping", 2002): cuts a
 * polygon face into triangles in the plane of its Newell normal. Shared by
 * the triangulate edit and the self-intersection check. Ear clipping is
 * chosen over a fan because a fan from one corner overlaps itself on a
 * non-convex polygon. O(n^3) in the face size at worst; faces are small. */
#include <math.h>

#include "geometry/geometry_internal.h"

/* 2D coordinates of a corner: the position with the normal's largest axis dropped. */
static void project(const double *p, int drop, double out[2])
{
    out[0] = p[drop == 0 ? 1 : 0];
    out[1] = p[drop == 2 ? 1 : 2];
}

static double cross(const double o[2], const double a[2], const double b[2])
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* Whether corner k of the remaining polygon rem[0..r) is a geometric ear. */
static bool is_ear(const double *const *pos, const uint32_t *rem, uint32_t r, uint32_t k, int drop,
                   double sign)
{
    double p[2], c[2], n[2], q[2];
    project(pos[rem[(k + r - 1) % r]], drop, p);
    project(pos[rem[k]], drop, c);
    project(pos[rem[(k + 1) % r]], drop, n);
    if (sign * cross(p, c, n) <= 0) return false;
    for (uint32_t j = 0; j < r; j++) {
        if (j == k || j == (k + 1) % r || j == (k + r - 1) % r) continue;
        project(pos[rem[j]], drop, q);
        if (sign * cross(p, c, q) >= 0 && sign * cross(c, n, q) >= 0 && sign * cross(n, p, q) >= 0)
            return false;
    }
    return true;
}

bool mt__ear_clip(const double *const *pos, uint32_t n, mt__diagonal_ok diagonal_ok, void *user,
                  uint32_t *rem, uint32_t *out_tris)
{
    int drop = 2;
    double sign = 1.0;
    if (pos) {
        double nrm[3] = {0, 0, 0};
        for (uint32_t i = 0; i < n; i++) {
            const double *p = pos[i], *q = pos[(i + 1) % n];
            nrm[0] += (p[1] - q[1]) * (p[2] + q[2]);
            nrm[1] += (p[2] - q[2]) * (p[0] + q[0]);
            nrm[2] += (p[0] - q[0]) * (p[1] + q[1]);
        }
        drop = fabs(nrm[0]) > fabs(nrm[1]) ? (fabs(nrm[0]) > fabs(nrm[2]) ? 0 : 2)
                                           : (fabs(nrm[1]) > fabs(nrm[2]) ? 1 : 2);
        /* Dropping axis x keeps (y, z), dropping y keeps (x, z): the latter
         * is a left-handed view of the plane. */
        sign = nrm[drop] >= 0 ? 1.0 : -1.0;
        if (drop == 1) sign = -sign;
    }
    for (uint32_t i = 0; i < n; i++) rem[i] = i;
    uint32_t r = n, t = 0;
    while (r > 3) {
        uint32_t ear = r, fallback = r;
        for (uint32_t k = 0; k < r && ear == r; k++) {
            if (diagonal_ok && !diagonal_ok(user, rem[(k + r - 1) % r], rem[(k + 1) % r])) continue;
            if (fallback == r) fallback = k;
            if (pos && is_ear(pos, rem, r, k, drop, sign)) ear = k;
        }
        if (ear == r) ear = fallback;
        if (ear == r) return false;
        out_tris[t++] = rem[(ear + r - 1) % r];
        out_tris[t++] = rem[ear];
        out_tris[t++] = rem[(ear + 1) % r];
        for (uint32_t i = ear; i + 1 < r; i++) rem[i] = rem[i + 1];
        r--;
    }
    for (uint32_t i = 0; i < 3; i++) out_tris[t++] = rem[i];
    return true;
}
