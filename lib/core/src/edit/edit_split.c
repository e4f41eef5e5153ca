/* mt_edge_split: a new vertex on an edge. The faces on the edge are removed
 * and inserted again around the new vertex: a triangle as two triangles, a
 * larger polygon with one more corner. Time linear in the sizes of the two
 * faces and their corners' valences. */
#include "edit/edit_internal.h"
#include "meshtopo/edit.h"

/* Re-inserts the face that held side x -> y (vertex list at offset `at` of
 * the work vector, n corners) with `mid` between x and y. */
static mt_status split_side(mt__edit *e, uint32_t face, size_t at, uint32_t n, uint32_t x,
                            uint32_t y, uint32_t mid)
{
    mt__vec *work = &e->s->work;
    const uint32_t *list = (const uint32_t *)work->data + at;
    uint32_t i = 0;
    while (i < n && !(list[i] == x && list[(i + 1) % n] == y)) i++;
    const uint32_t first = list[0];
    if (n == 3) {
        const uint32_t c = list[(i + 2) % 3];
        uint32_t keep[3] = {x, mid, c}, other[3] = {mid, y, c};
        if (first == y) {
            keep[0] = mid, keep[1] = y, keep[2] = c;
            other[0] = x, other[1] = mid, other[2] = c;
        }
        mt__list_rotate_to(keep, 3, first);
        uint32_t new_face;
        mt_status s = mt__face_insert(e, keep, 3, face, false);
        if (s == MT_OK) s = mt__edit_new_face(e, &new_face);
        if (s == MT_OK) s = mt__face_insert(e, other, 3, new_face, false);
        return s;
    }
    const size_t out = work->len;
    for (uint32_t k = 0; k < n; k++) {
        const uint32_t w = ((const uint32_t *)work->data)[at + k];
        if (mt__vec_push(work, &w) != MT_OK) return MT_ERR_NOMEM;
        if (k == i && mt__vec_push(work, &mid) != MT_OK) return MT_ERR_NOMEM;
    }
    return mt__face_insert(e, (const uint32_t *)work->data + out, n + 1, face, false);
}

mt_status mt_edge_split(mt_mesh *mesh, uint32_t a, uint32_t b, const double *position,
                        uint32_t *out_vert, mt_diag *diag)
{
    mt__edit e;
    uint32_t h;
    mt_status s = mt__edit_begin(&e, mesh, diag, "split edge");
    if (s == MT_OK) s = mt__edit_check_edge(&e, a, b, "split edge", &h);
    if (s != MT_OK) return s;
    const uint32_t f0 = mesh->he_face[h], f1 = mesh->he_face[h ^ 1u];
    mt__vec *work = &e.s->work;
    const uint32_t n0 = f0 == MT_NONE ? 0 : mt__face_collect(mesh, f0, work);
    const uint32_t n1 = f1 == MT_NONE ? 0 : mt__face_collect(mesh, f1, work);
    if ((f0 != MT_NONE && n0 == 0) || (f1 != MT_NONE && n1 == 0))
        return mt__edit_abort(&e, MT_ERR_NOMEM);
    double mid_pos[3];
    const double *pos = position;
    if (!pos && mesh->positions) {
        const double *pa = mesh->positions + 3 * (size_t)a, *pb = mesh->positions + 3 * (size_t)b;
        for (int k = 0; k < 3; k++) mid_pos[k] = 0.5 * (pa[k] + pb[k]);
        pos = mid_pos;
    }
    uint32_t mid;
    s = mt__edit_new_vert(&e, pos, &mid);
    if (s == MT_OK && f0 != MT_NONE) s = mt__face_remove(&e, f0);
    if (s == MT_OK && f1 != MT_NONE) s = mt__face_remove(&e, f1);
    if (s == MT_OK && f0 != MT_NONE) s = split_side(&e, f0, 0, n0, a, b, mid);
    if (s == MT_OK && f1 != MT_NONE) s = split_side(&e, f1, n0, n1, b, a, mid);
    if (s == MT_OK) s = mt__edit_touch(&e, mid);
    if (s != MT_OK) return mt__edit_abort(&e, s);
    s = mt__edit_finish(&e);
    if (s == MT_OK && out_vert) *out_vert = mid;
    return s;
}
