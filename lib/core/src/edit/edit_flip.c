/* mt_edge_flip: the diagonal of two triangles turned to the other two
 * corners. Both triangles are removed and inserted again on the new
 * diagonal under their old ids. Constant time plus the corners' valences. */
#include "edit/edit_internal.h"
#include "meshtopo/edit.h"

mt_status mt_edge_flip(mt_mesh *mesh, uint32_t a, uint32_t b, mt_diag *diag)
{
    mt__edit e;
    uint32_t h;
    mt_status s = mt__edit_begin(&e, mesh, diag, "flip edge");
    if (s == MT_OK) s = mt__edit_check_edge(&e, a, b, "flip edge", &h);
    if (s != MT_OK) return s;
    const uint32_t f0 = mesh->he_face[h], f1 = mesh->he_face[h ^ 1u];
    if (f0 == MT_NONE || f1 == MT_NONE)
        return mt__fail(diag, MT_ERR_REFUSED, a,
                        "flip edge refused: edge %u-%u is on the boundary (one face)", a, b);
    mt__vec *work = &e.s->work;
    const uint32_t n0 = mt__face_collect(mesh, f0, work);
    const uint32_t n1 = mt__face_collect(mesh, f1, work);
    if (n0 == 0 || n1 == 0) return mt__edit_abort(&e, MT_ERR_NOMEM);
    if (n0 != 3 || n1 != 3)
        return mt__fail(diag, MT_ERR_REFUSED, n0 != 3 ? f0 : f1,
                        "flip edge refused: face %u on edge %u-%u has %u sides; only an edge "
                        "between two triangles flips",
                        n0 != 3 ? f0 : f1, a, b, n0 != 3 ? n0 : n1);
    /* f0 runs a -> b -> c, f1 runs b -> a -> d. */
    const uint32_t c = mesh->he_head[mesh->he_next[h]];
    const uint32_t d = mesh->he_head[mesh->he_next[h ^ 1u]];
    if (c == d || mt__edit_find_he(mesh, c, d) != MT_NONE)
        return mt__fail(diag, MT_ERR_REFUSED, c,
                        "flip edge refused: vertices %u and %u are already joined by an edge; "
                        "flipping %u-%u would join them twice",
                        c, d, a, b);
    const uint32_t *lists = work->data;
    const uint32_t first0 = lists[0], first1 = lists[3];
    uint32_t ta[3] = {c, a, d}, tb[3] = {d, b, c};
    uint32_t *keep0 = first0 == b ? tb : ta, *keep1 = first0 == b ? ta : tb;
    mt__list_rotate_to(keep0, 3, first0);
    mt__list_rotate_to(keep1, 3, first1);
    s = mt__face_remove(&e, f0);
    if (s == MT_OK) s = mt__face_remove(&e, f1);
    if (s == MT_OK) s = mt__face_insert(&e, keep0, 3, f0, false);
    if (s == MT_OK) s = mt__face_insert(&e, keep1, 3, f1, false);
    if (s != MT_OK) return mt__edit_abort(&e, s);
    return mt__edit_finish(&e);
}
