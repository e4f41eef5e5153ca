/* Deleting faces, edges and vertices: mt__face_remove, the removal every
 * edit builds on (pmp-library's SurfaceMesh::delete_face: the face's sides
 * become boundary, an edge with no face left is unlinked from both rings and
 * marked deleted), and the public deletions, which refuse to leave a vertex
 * with two boundary gaps. Time linear in the faces removed and their corners'
 * valences. */
#include "edit/edit_internal.h"
#include "meshtopo/edit.h"

/* Unlinks edge h >> 1, whose two sides have no face, and marks it deleted. */
static void delete_edge(mt__edit *e, uint32_t h0)
{
    mt_mesh *m = e->m;
    const uint32_t h1 = h0 ^ 1u;
    const uint32_t v0 = m->he_head[h0], next0 = m->he_next[h0], prev0 = mt__edit_prev(m, h0);
    const uint32_t v1 = m->he_head[h1], next1 = m->he_next[h1], prev1 = mt__edit_prev(m, h1);
    mt__set_next(e, prev0, next1);
    mt__set_next(e, prev1, next0);
    if (m->vert_he[v0] == h1) mt__set_vert_he(e, v0, next0 == h1 ? MT_NONE : next0);
    if (m->vert_he[v1] == h0) mt__set_vert_he(e, v1, next1 == h0 ? MT_NONE : next1);
    mt__edit_set(e, MT__A_HEAD, h0, MT_NONE);
    mt__edit_set(e, MT__A_HEAD, h1, MT_NONE);
    mt__set_next(e, h0, h0);
    mt__set_next(e, h1, h1);
    const uint32_t edge = h0 >> 1;
    if (mt__vec_push(&e->s->freed, &edge) != MT_OK) e->status = MT_ERR_NOMEM;
    m->report.num_edges--;
    m->report.euler_characteristic++;
}

mt_status mt__face_remove(mt__edit *e, uint32_t f)
{
    mt_mesh *m = e->m;
    mt__vec *prim = &e->s->prim;
    prim->len = 0;
    const uint32_t start = m->face_he[f];
    uint32_t h = start;
    do {
        if (mt__vec_push(prim, &h) != MT_OK) return MT_ERR_NOMEM;
        h = m->he_next[h];
    } while (h != start && prim->len <= m->num_half_edges);
    const uint32_t n = (uint32_t)prim->len;
    mt_status s = mt__edit_reserve(e, (size_t)16 * n + 16);
    if (s != MT_OK) return s;
    const uint32_t *hs = prim->data;
    for (uint32_t i = 0; i < n; i++) {
        mt__edit_set(e, MT__A_FACE, hs[i], MT_NONE);
        if (mt__edit_touch(e, m->he_head[hs[i]]) != MT_OK) return e->status;
    }
    mt__edit_set(e, MT__A_FACE_HE, f, MT_NONE);
    m->report.num_faces_valid--;
    m->report.euler_characteristic--;
    /* The touched list ends with this face's corners, in ring order. */
    const uint32_t *corners = (const uint32_t *)e->s->touched.data + e->s->touched.len - n;
    for (uint32_t i = 0; i < n; i++)
        if (m->he_face[hs[i] ^ 1u] == MT_NONE) delete_edge(e, hs[i]);
    for (uint32_t i = 0; i < n; i++) mt__edit_adjust_vert(e, corners[i]);
    return e->status;
}

mt_status mt_face_delete(mt_mesh *mesh, uint32_t face, mt_diag *diag)
{
    mt__edit e;
    mt_status s = mt__edit_begin(&e, mesh, diag, "delete face");
    if (s == MT_OK) s = mt__edit_check_face(&e, face, "delete face");
    if (s != MT_OK) return s;
    /* A boundary corner whose gap is not next to the face would get a second gap. */
    const mt_mesh *m = mesh;
    const uint32_t start = m->face_he[face];
    uint32_t h = start, steps = 0;
    do {
        const uint32_t next = m->he_next[h], v = m->he_head[h];
        if (mt__vert_on_boundary(m, v) && m->he_face[h ^ 1u] != MT_NONE &&
            m->he_face[next ^ 1u] != MT_NONE)
            return mt__fail(diag, MT_ERR_REFUSED, v,
                            "delete face refused: vertex %u of face %u is on a boundary that "
                            "does not touch the face; deleting it would leave the vertex with "
                            "two boundary gaps (a bowtie)",
                            v, face);
        h = next;
    } while (h != start && ++steps < m->num_half_edges);
    s = mt__face_remove(&e, face);
    if (s != MT_OK) return mt__edit_abort(&e, s);
    return mt__edit_finish(&e);
}

mt_status mt_edge_delete(mt_mesh *mesh, uint32_t a, uint32_t b, mt_diag *diag)
{
    mt__edit e;
    uint32_t h;
    mt_status s = mt__edit_begin(&e, mesh, diag, "delete edge");
    if (s == MT_OK) s = mt__edit_check_edge(&e, a, b, "delete edge", &h);
    if (s != MT_OK) return s;
    const uint32_t f0 = mesh->he_face[h], f1 = mesh->he_face[h ^ 1u];
    if (f0 != MT_NONE) s = mt__face_remove(&e, f0);
    if (s == MT_OK && f1 != MT_NONE) s = mt__face_remove(&e, f1);
    if (s != MT_OK) return mt__edit_abort(&e, s);
    return mt__edit_finish(&e);
}

mt_status mt_vert_delete(mt_mesh *mesh, uint32_t vert, mt_diag *diag)
{
    mt__edit e;
    mt_status s = mt__edit_begin(&e, mesh, diag, "delete vertex");
    if (s == MT_OK) s = mt__edit_check_vert(&e, vert, "delete vertex");
    if (s != MT_OK) return s;
    mt__vec *faces = &e.s->work;
    const uint32_t start = mesh->vert_he[vert];
    if (start != MT_NONE) {
        uint32_t h = start, steps = 0;
        do {
            const uint32_t f = mesh->he_face[h];
            if (f != MT_NONE && mt__vec_push(faces, &f) != MT_OK)
                return mt__edit_abort(&e, MT_ERR_NOMEM);
            h = mesh->he_next[h ^ 1u];
        } while (h != start && ++steps < mesh->num_half_edges);
    }
    for (size_t i = 0; i < faces->len && s == MT_OK; i++)
        s = mt__face_remove(&e, ((const uint32_t *)faces->data)[i]);
    if (s == MT_OK) s = mt__edit_delete_vert(&e, vert);
    if (s != MT_OK) return mt__edit_abort(&e, s);
    return mt__edit_finish(&e);
}
