/* mt_edge_collapse: edge a-b shrunk into b. The faces around a are removed
 * and inserted again with b in place of a (a triangle on the edge is left
 * out), after the checks that keep the surface manifold: the link condition
 * (Dey et al., "Topology preserving edge contraction", 1999), no pinch of two
 * boundaries, no triangle hanging on two boundary sides. The final check of
 * the touched vertices (edit_state.c) refuses what is left degenerate. Time
 * linear in the faces around a and b. */
#include "edit/edit_internal.h"
#include "meshtopo/edit.h"

/* Vertex after a in the face of half-edge h (a -> head): the apex of a
 * triangle on the edge, MT_NONE for a polygon or no face. */
static uint32_t apex(const mt_mesh *m, uint32_t h)
{
    if (m->he_face[h] == MT_NONE) return MT_NONE;
    const uint32_t n1 = m->he_next[h], n2 = m->he_next[n1];
    return m->he_next[n2] == h ? m->he_head[n1] : MT_NONE;
}

static mt_status check_collapse(mt__edit *e, uint32_t a, uint32_t b, uint32_t h)
{
    const mt_mesh *m = e->m;
    const bool edge_boundary = m->he_face[h] == MT_NONE || m->he_face[h ^ 1u] == MT_NONE;
    if (!edge_boundary && mt__vert_on_boundary(m, a) && mt__vert_on_boundary(m, b))
        return mt__fail(e->diag, MT_ERR_REFUSED, a,
                        "collapse refused: vertices %u and %u are both on the boundary but edge "
                        "%u-%u is not; collapsing would pinch the surface",
                        a, b, a, b);
    const uint32_t c = apex(m, h), d = apex(m, h ^ 1u);
    for (uint32_t side = 0; side < 2; side++) {
        const uint32_t s = side ? h ^ 1u : h, x = side ? d : c;
        if (x == MT_NONE) continue;
        const uint32_t n1 = m->he_next[s], n2 = m->he_next[n1];
        if (m->he_face[n1 ^ 1u] == MT_NONE && m->he_face[n2 ^ 1u] == MT_NONE)
            return mt__fail(e->diag, MT_ERR_REFUSED, m->he_face[s],
                            "collapse refused: triangle %u (%u, %u, %u) has both its other "
                            "sides on the boundary; collapsing %u-%u would leave a dangling edge",
                            m->he_face[s], a, b, x, a, b);
    }
    /* Link condition: a common neighbour of a and b must be an apex. */
    const uint32_t start_b = m->vert_he[b];
    uint32_t hb = start_b, steps = 0;
    do {
        const uint32_t w = m->he_head[hb];
        if (w != a && w != c && w != d && mt__edit_find_he(m, a, w) != MT_NONE)
            return mt__fail(e->diag, MT_ERR_REFUSED, w,
                            "collapse refused: vertices %u and %u share neighbour %u outside "
                            "the faces on edge %u-%u (link condition); the collapse would join "
                            "%u and %u twice",
                            a, b, w, a, b, b, w);
        hb = m->he_next[hb ^ 1u];
    } while (hb != start_b && ++steps < m->num_half_edges);
    return MT_OK;
}

mt_status mt_edge_collapse(mt_mesh *mesh, uint32_t a, uint32_t b, const double *position,
                           mt_diag *diag)
{
    mt__edit e;
    uint32_t h;
    mt_status s = mt__edit_begin(&e, mesh, diag, "collapse edge");
    if (s == MT_OK) s = mt__edit_check_edge(&e, a, b, "collapse edge", &h);
    if (s == MT_OK) s = check_collapse(&e, a, b, h);
    if (s != MT_OK) return s;

    /* Faces around a in rotation order from a -> b, as (id, size, corners...). */
    mt__vec *work = &e.s->work;
    uint32_t o = h, steps = 0, num_faces = 0;
    do {
        const uint32_t f = mesh->he_face[o];
        if (f != MT_NONE) {
            const size_t at = work->len;
            const uint32_t zero = 0;
            if (mt__vec_push(work, &f) != MT_OK || mt__vec_push(work, &zero) != MT_OK)
                return mt__edit_abort(&e, MT_ERR_NOMEM);
            const uint32_t n = mt__face_collect(mesh, f, work);
            if (n == 0) return mt__edit_abort(&e, MT_ERR_NOMEM);
            /* A face holding a and b apart from the edge would repeat b. */
            const uint32_t *corners = (const uint32_t *)work->data + at + 2;
            for (uint32_t i = 0; i < n; i++) {
                if (corners[i] != a) continue;
                const uint32_t before = corners[(i + n - 1) % n], after = corners[(i + 1) % n];
                for (uint32_t j = 0; j < n; j++)
                    if (corners[j] == b && before != b && after != b)
                        return mt__fail(diag, MT_ERR_REFUSED, f,
                                        "collapse refused: face %u holds vertices %u and %u "
                                        "but not as a side; it would hold %u twice",
                                        f, a, b, b);
            }
            ((uint32_t *)work->data)[at + 1] = n;
            num_faces++;
        }
        o = mesh->he_next[o ^ 1u];
    } while (o != h && ++steps < mesh->num_half_edges);
    const size_t lists_end = work->len;

    size_t at = 0;
    for (uint32_t k = 0; k < num_faces && s == MT_OK; k++) {
        const uint32_t *rec = (const uint32_t *)work->data + at;
        s = mt__face_remove(&e, rec[0]);
        at += 2 + rec[1];
    }
    if (s == MT_OK) s = mt__edit_delete_vert(&e, a);
    if (s == MT_OK) mt__edit_move_vert(&e, b, position);
    if (s == MT_OK) s = mt__edit_touch(&e, b);
    at = 0;
    for (uint32_t k = 0; k < num_faces && s == MT_OK; k++) {
        const uint32_t f = ((const uint32_t *)work->data)[at];
        const uint32_t n = ((const uint32_t *)work->data)[at + 1];
        /* The face with b for a, repeated b dropped. */
        work->len = lists_end;
        for (uint32_t i = 0; i < n && s == MT_OK; i++) {
            uint32_t w = ((const uint32_t *)work->data)[at + 2 + i];
            if (w == a) w = b;
            const uint32_t *out = (const uint32_t *)work->data + lists_end;
            const size_t len = work->len - lists_end;
            if (len && out[len - 1] == w) continue;
            if (mt__vec_push(work, &w) != MT_OK) s = MT_ERR_NOMEM;
        }
        const uint32_t *out = (const uint32_t *)work->data + lists_end;
        uint32_t len = (uint32_t)(work->len - lists_end);
        if (len > 1 && out[len - 1] == out[0]) len--;
        if (s == MT_OK && len >= 3) s = mt__face_insert(&e, out, len, f, false);
        at += 2 + n;
    }
    if (s != MT_OK) return mt__edit_abort(&e, s);
    /* Removing a and the faces on the edge must leave chi as it was. */
    if (mesh->report.euler_characteristic != e.euler)
        return mt__edit_abort(
            &e, mt__fail(diag, MT_ERR_REFUSED, a,
                         "collapse refused: collapsing %u-%u would change the Euler "
                         "characteristic from %lld to %lld",
                         a, b, (long long)e.euler, (long long)mesh->report.euler_characteristic));
    return mt__edit_finish(&e);
}
