/* mt_face_split: a polygon cut in two by a diagonal between two of its
 * corners. The face is removed and its two parts inserted (the old id keeps
 * the part holding its first vertex). Time linear in the face size and its
 * corners' valences. */
#include "edit/edit_internal.h"
#include "meshtopo/edit.h"

/* Appends corners from..to (cyclic, both included) of list[0..n) to work. */
static mt_status push_arc(mt__vec *work, size_t at, uint32_t n, uint32_t from, uint32_t to)
{
    for (uint32_t i = from;; i = (i + 1) % n) {
        const uint32_t w = ((const uint32_t *)work->data)[at + i];
        if (mt__vec_push(work, &w) != MT_OK) return MT_ERR_NOMEM;
        if (i == to) return MT_OK;
    }
}

mt_status mt_face_split(mt_mesh *mesh, uint32_t face, uint32_t a, uint32_t b, uint32_t *out_face,
                        mt_diag *diag)
{
    mt__edit e;
    mt_status s = mt__edit_begin(&e, mesh, diag, "split face");
    if (s == MT_OK) s = mt__edit_check_face(&e, face, "split face");
    if (s == MT_OK) s = mt__edit_check_vert(&e, a, "split face");
    if (s == MT_OK) s = mt__edit_check_vert(&e, b, "split face");
    if (s != MT_OK) return s;
    mt__vec *work = &e.s->work;
    const uint32_t n = mt__face_collect(mesh, face, work);
    if (n == 0) return mt__edit_abort(&e, MT_ERR_NOMEM);
    const uint32_t *list = work->data;
    uint32_t ia = n, ib = n;
    for (uint32_t i = 0; i < n; i++) {
        if (list[i] == a) ia = i;
        if (list[i] == b) ib = i;
    }
    if (ia == n || ib == n)
        return mt__fail(diag, MT_ERR_NOT_FOUND, ia == n ? a : b,
                        "split face: vertex %u is not a corner of face %u", ia == n ? a : b, face);
    if (a == b || (ia + 1) % n == ib || (ib + 1) % n == ia)
        return mt__fail(diag, MT_ERR_REFUSED, face,
                        "split face refused: %u and %u are %s of face %u; a diagonal needs two "
                        "corners that are not neighbours",
                        a, b, a == b ? "the same corner" : "neighbouring corners", face);
    if (mt__edit_find_he(mesh, a, b) != MT_NONE)
        return mt__fail(diag, MT_ERR_REFUSED, face,
                        "split face refused: vertices %u and %u are already joined by an edge; "
                        "the diagonal would join them twice",
                        a, b);
    /* The part from corner 0's side keeps the id. */
    const uint32_t lo = ia < ib ? ia : ib, hi = ia < ib ? ib : ia;
    s = push_arc(work, 0, n, hi, lo); /* holds corner 0 */
    const size_t second = work->len;
    if (s == MT_OK) s = push_arc(work, 0, n, lo, hi);
    if (s != MT_OK) return mt__edit_abort(&e, s);
    const uint32_t len0 = n - (hi - lo) + 1, len1 = hi - lo + 1;
    uint32_t *part0 = (uint32_t *)work->data + n;
    mt__list_rotate_to(part0, len0, ((const uint32_t *)work->data)[0]);
    uint32_t new_face;
    s = mt__face_remove(&e, face);
    if (s == MT_OK) s = mt__face_insert(&e, (const uint32_t *)work->data + n, len0, face, false);
    if (s == MT_OK) s = mt__edit_new_face(&e, &new_face);
    if (s == MT_OK)
        s = mt__face_insert(&e, (const uint32_t *)work->data + second, len1, new_face, false);
    if (s != MT_OK) return mt__edit_abort(&e, s);
    s = mt__edit_finish(&e);
    if (s == MT_OK && out_face) *out_face = new_face;
    return s;
}
