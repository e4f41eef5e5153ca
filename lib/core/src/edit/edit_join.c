/* Joining two faces across their shared edge into one polygon (the f1 u f2
 * step of the proof of Euler's formula): both faces are removed and their
 * boundary walked around the edge is inserted under the first one's id; the
 * edge disappears with the second face, so V - E + F does not change. */
#include "edit/edit_internal.h"
#include "meshtopo/edit.h"
#include "meshtopo/query.h"

mt_status mt_face_join(mt_mesh *mesh, uint32_t a, uint32_t b, uint32_t *out_face, mt_diag *diag)
{
    mt__edit e;
    uint32_t h = MT_NONE;
    mt_status s = mt__edit_begin(&e, mesh, diag, "join faces");
    if (s == MT_OK) s = mt__edit_check_edge(&e, a, b, "join faces", &h);
    if (s != MT_OK) return s;
    const mt_mesh *m = mesh;
    size_t users = 0;
    mt_edge_faces(mesh, a, b, NULL, 0, &users);
    const uint32_t f1 = m->he_face[h], f2 = m->he_face[h ^ 1u];
    if (users != 2 || f1 == MT_NONE || f2 == MT_NONE)
        return mt__fail(diag, MT_ERR_REFUSED, a,
                        "join faces refused: edge %u-%u is used by %zu face(s), not 2: only an "
                        "edge between exactly two faces can be removed",
                        a, b, users);
    if (f1 == f2)
        return mt__fail(diag, MT_ERR_REFUSED, f1,
                        "join faces refused: face %u lies on both sides of edge %u-%u", f1, a, b);
    mt__vec *work = &e.s->work;
    work->len = 0;
    const uint32_t n1 = mt__face_collect(m, f1, work);
    const uint32_t n2 = n1 ? mt__face_collect(m, f2, work) : 0;
    if (n1 == 0 || n2 == 0) return MT_ERR_NOMEM;
    uint32_t *c = work->data; /* f1's corners, then f2's */
    /* f1 holds a -> b, f2 holds b -> a. The joined face runs around f1 from
     * b to a, then around f2 from a to b, without the edge. */
    mt__list_rotate_to(c, n1, b);
    mt__list_rotate_to(c + n1, n2, a);
    const uint32_t n = n1 + n2 - 2;
    for (uint32_t i = 0; i + 1 < n2 - 1; i++) c[n1 + i] = c[n1 + 1 + i];
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = i + 1; j < n; j++)
            if (c[i] == c[j])
                return mt__fail(diag, MT_ERR_REFUSED, c[i],
                                "join faces refused: faces %u and %u share more than edge %u-%u "
                                "(vertex %u is in both): the joined face would repeat it",
                                f1, f2, a, b, c[i]);
    s = mt__face_remove(&e, f1);
    if (s == MT_OK) s = mt__face_remove(&e, f2);
    if (s == MT_OK) s = mt__face_insert(&e, c, n, f1, true);
    if (s != MT_OK) return mt__edit_abort(&e, s);
    s = mt__edit_finish(&e);
    if (s == MT_OK && out_face) *out_face = f1;
    return s;
}
