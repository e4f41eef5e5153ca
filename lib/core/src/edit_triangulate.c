/* Triangulating polygon faces by ear clipping (Eberly, "Triangulation by Ear
 * Clipping", 2002) in the plane of the face's Newell normal. Ear clipping is
 * chosen over a fan because a fan from one corner overlaps itself on a
 * non-convex polygon, and because skipping ears lets it avoid diagonals that
 * are already edges of the mesh. Without positions any corner is an ear. A
 * face that crosses itself in its plane (mt_face_shape_of) is refused: no
 * set of triangles covers it without folding.
 * O(n^3) in the face size at worst; faces are small. */
#include <math.h>

#include "edit_internal.h"
#include "meshtopo/edit.h"
#include "meshtopo/geometry.h"

/* 2D coordinates of a corner: the position with the normal's largest axis dropped. */
static void project(const mt_mesh *m, uint32_t v, int drop, double out[2])
{
    const double *p = m->positions + 3 * (size_t)v;
    out[0] = p[drop == 0 ? 1 : 0];
    out[1] = p[drop == 2 ? 1 : 2];
}

static double cross(const double o[2], const double a[2], const double b[2])
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* Whether corner k of the remaining polygon rem[0..r) is a geometric ear. */
static bool is_ear(const mt_mesh *m, const uint32_t *rem, uint32_t r, uint32_t k, int drop,
                   double sign)
{
    double p[2], c[2], n[2], q[2];
    project(m, rem[(k + r - 1) % r], drop, p);
    project(m, rem[k], drop, c);
    project(m, rem[(k + 1) % r], drop, n);
    if (sign * cross(p, c, n) <= 0) return false;
    for (uint32_t j = 0; j < r; j++) {
        if (j == k || j == (k + 1) % r || j == (k + r - 1) % r) continue;
        project(m, rem[j], drop, q);
        if (sign * cross(p, c, q) >= 0 && sign * cross(c, n, q) >= 0 && sign * cross(n, p, q) >= 0)
            return false;
    }
    return true;
}

/* Triangulates face f inside edit e; *out_new gets the number of new faces. */
static mt_status triangulate_one(mt__edit *e, uint32_t f, uint32_t *out_new)
{
    mt_mesh *m = e->m;
    mt__vec *work = &e->s->work;
    work->len = 0;
    *out_new = 0;
    const uint32_t n = mt__face_collect(m, f, work);
    if (n == 0) return MT_ERR_NOMEM;
    if (n == 3) return MT_OK;
    mt_face_shape shape;
    if (m->positions && mt_face_shape_of(m, f, &shape, NULL) == MT_OK &&
        shape.kind == MT_FACE_SELF_CROSSING)
        return mt__fail(e->diag, MT_ERR_REFUSED, f,
                        "triangulate refused: face %u crosses itself in its plane (sides %u and "
                        "%u): its triangles would fold over each other",
                        f, shape.side_a, shape.side_b);
    /* work: corners [0, n), remaining [n, 2n), triangles from 2n. */
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t w = ((const uint32_t *)work->data)[i];
        if (mt__vec_push(work, &w) != MT_OK) return MT_ERR_NOMEM;
    }
    int drop = 2;
    double sign = 1.0;
    if (m->positions) {
        double nrm[3] = {0, 0, 0};
        const uint32_t *c = work->data;
        for (uint32_t i = 0; i < n; i++) {
            const double *p = m->positions + 3 * (size_t)c[i];
            const double *q = m->positions + 3 * (size_t)c[(i + 1) % n];
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
    uint32_t r = n;
    while (r > 3) {
        const uint32_t *rem = (const uint32_t *)work->data + n;
        uint32_t ear = r, fallback = r;
        for (uint32_t k = 0; k < r && ear == r; k++) {
            if (mt__edit_find_he(m, rem[(k + r - 1) % r], rem[(k + 1) % r]) != MT_NONE) continue;
            if (fallback == r) fallback = k;
            if (m->positions && is_ear(m, rem, r, k, drop, sign)) ear = k;
        }
        if (ear == r) ear = fallback;
        if (ear == r)
            return mt__fail(e->diag, MT_ERR_REFUSED, f,
                            "triangulate refused: face %u: every diagonal left to cut is already "
                            "an edge of the mesh",
                            f);
        const uint32_t tri[3] = {rem[(ear + r - 1) % r], rem[ear], rem[(ear + 1) % r]};
        for (uint32_t i = ear; i + 1 < r; i++) {
            uint32_t *w = (uint32_t *)work->data + n;
            w[i] = w[i + 1];
        }
        r--;
        for (int i = 0; i < 3; i++)
            if (mt__vec_push(work, &tri[i]) != MT_OK) return MT_ERR_NOMEM;
    }
    for (uint32_t i = 0; i < 3; i++) {
        const uint32_t w = ((const uint32_t *)work->data)[n + i];
        if (mt__vec_push(work, &w) != MT_OK) return MT_ERR_NOMEM;
    }
    /* Triangles [2n, 2n + 3(n - 2)); the first keeps the id. */
    const uint32_t first = ((const uint32_t *)work->data)[0];
    mt__list_rotate_to((uint32_t *)work->data + 2 * n, 3, first);
    mt_status s = mt__face_remove(e, f);
    for (uint32_t t = 0; t < n - 2 && s == MT_OK; t++) {
        uint32_t id = f;
        if (t > 0) s = mt__edit_new_face(e, &id);
        if (s == MT_OK)
            s = mt__face_insert(e, (const uint32_t *)work->data + 2 * n + 3 * t, 3, id, false);
    }
    if (s == MT_OK) *out_new = n - 3;
    return s;
}

mt_status mt_face_triangulate(mt_mesh *mesh, uint32_t face, uint32_t *out_new_faces, mt_diag *diag)
{
    mt__edit e;
    mt_status s = mt__edit_begin(&e, mesh, diag, "triangulate face");
    if (s == MT_OK) s = mt__edit_check_face(&e, face, "triangulate face");
    if (s != MT_OK) return s;
    uint32_t added;
    s = triangulate_one(&e, face, &added);
    if (s != MT_OK) return mt__edit_abort(&e, s);
    s = mt__edit_finish(&e);
    if (s == MT_OK && out_new_faces) *out_new_faces = added;
    return s;
}

mt_status mt_mesh_triangulate(mt_mesh *mesh, mt_diag *diag)
{
    mt__edit e;
    mt_status s = mt__edit_begin(&e, mesh, diag, "triangulate mesh");
    if (s != MT_OK) return s;
    const uint32_t num_faces = mesh->num_faces;
    for (uint32_t f = 0; f < num_faces && s == MT_OK; f++) {
        if (mesh->face_he[f] == MT_NONE) continue;
        uint32_t added;
        s = triangulate_one(&e, f, &added);
    }
    if (s != MT_OK) return mt__edit_abort(&e, s);
    return mt__edit_finish(&e);
}
