/* Corner angles of faces, the building block of vertex normals and angle
 * deficits. A triangle's corner is the unsigned angle between its sides,
 * atan2(|u x w|, u . w), accurate for small and near-flat angles. A larger
 * polygon's corner is its interior angle in the plane of its normal: pi minus
 * the signed turn from the incoming to the outgoing side, both projected on
 * that plane, so reflex corners count above pi and the corners of an n-gon
 * add up to (n - 2) pi. A degenerate polygon falls back to unsigned angles. */
#include <math.h>

#include "geometry/geometry_internal.h"

/* Removes the component along the unit vector n. */
static void project(double v[3], const double n[3])
{
    double d = mt__v3_dot(v, n);
    v[0] -= d * n[0];
    v[1] -= d * n[1];
    v[2] -= d * n[2];
}

double mt__corner_angle(const mt_mesh *m, uint32_t h_in, const double unit_normal[3],
                        uint32_t face_size)
{
    uint32_t h_out = m->he_next[h_in];
    const double *prev = mt__geom_pos(m, m->he_head[h_in ^ 1u]);
    const double *p = mt__geom_pos(m, m->he_head[h_in]);
    const double *next = mt__geom_pos(m, m->he_head[h_out]);
    if (!prev || !p || !next) return 0.0;
    bool planar = unit_normal[0] != 0.0 || unit_normal[1] != 0.0 || unit_normal[2] != 0.0;
    if (face_size == 3 || !planar) {
        double u[3], w[3], c[3];
        mt__v3_sub(prev, p, u);
        mt__v3_sub(next, p, w);
        mt__v3_cross(u, w, c);
        return atan2(sqrt(mt__v3_dot(c, c)), mt__v3_dot(u, w));
    }
    double e_in[3], e_out[3], c[3];
    mt__v3_sub(p, prev, e_in);
    mt__v3_sub(next, p, e_out);
    project(e_in, unit_normal);
    project(e_out, unit_normal);
    mt__v3_cross(e_in, e_out, c);
    double turn = atan2(mt__v3_dot(c, unit_normal), mt__v3_dot(e_in, e_out));
    return MT__PI - turn;
}
