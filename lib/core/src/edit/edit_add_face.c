/* Adding faces and vertices: mt__face_insert, the insertion every edit
 * builds on (pmp-library's SurfaceMesh::add_face: find the existing sides,
 * re-link boundary patches, create the missing edges, then splice the new
 * half-edges into the boundary rings), and the public mt_mesh_add_face and
 * mt_mesh_add_vert. Time linear in the face size plus its corners' valences. */
#include <stdlib.h>
#include <string.h>

#include "edit/edit_internal.h"
#include "meshtopo/edit.h"

/* Makes vec hold `count` zeroed uint32_t entries. */
static mt_status vec_fill(mt__vec *vec, size_t count)
{
    vec->len = 0;
    const uint32_t zero = 0;
    for (size_t i = 0; i < count; i++)
        if (mt__vec_push(vec, &zero) != MT_OK) return MT_ERR_NOMEM;
    return MT_OK;
}

/* Side i of the new face (verts[i] -> verts[i+1]) must be free: no half-edge
 * yet, or a boundary one. */
static mt_status check_side(mt__edit *e, uint32_t a, uint32_t b, uint32_t h)
{
    const mt_mesh *m = e->m;
    if (h == MT_NONE || m->he_face[h] == MT_NONE) return MT_OK;
    if (m->he_face[h ^ 1u] != MT_NONE)
        return mt__fail(e->diag, MT_ERR_REFUSED, a,
                        "add face refused: edge %u-%u already has two faces", a, b);
    return mt__fail(e->diag, MT_ERR_REFUSED, a,
                    "add face refused: face %u already runs %u -> %u; the new face would cross "
                    "edge %u-%u in the same direction",
                    m->he_face[h], a, b, a, b);
}

/* Component ids (vert_component, when the mesh has several components): the
 * corners take the component of any corner that has one; two different ones
 * are merged by relabelling the second, a whole-mesh pass (the one edit step
 * that is not local, and only when a face joins two components). */
static void set_components(mt__edit *e, const uint32_t *verts, uint32_t n)
{
    mt_mesh *m = e->m;
    if (!m->vert_component) return;
    uint32_t c = MT_NONE;
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t k = m->vert_component[verts[i]];
        if (k == MT_NONE) continue;
        if (c == MT_NONE) {
            c = k;
        } else if (k != c) {
            for (uint32_t v = 0; v < m->num_verts; v++)
                if (m->vert_component[v] == k) mt__edit_set(e, MT__A_COMP, v, c);
        }
    }
    if (c == MT_NONE) c = 0;
    for (uint32_t i = 0; i < n; i++)
        if (m->vert_component[verts[i]] != c) mt__edit_set(e, MT__A_COMP, verts[i], c);
}

mt_status mt__face_insert(mt__edit *e, const uint32_t *v, uint32_t n, uint32_t face, bool strict)
{
    mt_mesh *m = e->m;
    mt__vec *prim = &e->s->prim;
    /* Layout of prim: he[n], is_new[n], adjust[n], then the next-cache pairs. */
    if (vec_fill(prim, (size_t)3 * n + 2 * (size_t)4 * n) != MT_OK) return MT_ERR_NOMEM;
    uint32_t *he = prim->data, *is_new = he + n, *adjust = is_new + n, *cache = adjust + n;
    size_t num_cache = 0;

    for (uint32_t i = 0; i < n; i++) {
        const uint32_t a = v[i], b = v[(i + 1) % n];
        const uint32_t out = m->vert_he[a];
        if (out != MT_NONE && m->he_face[out] != MT_NONE)
            return mt__fail(e->diag, MT_ERR_REFUSED, a,
                            "add face refused: vertex %u is interior (its faces close around "
                            "it); no face can be added at it",
                            a);
        he[i] = mt__edit_find_he(m, a, b);
        is_new[i] = he[i] == MT_NONE;
        mt_status s = check_side(e, a, b, he[i]);
        if (s != MT_OK) return s;
    }
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t ii = (i + 1) % n, vv = v[ii];
        if (strict && is_new[i] && is_new[ii] && m->vert_he[vv] != MT_NONE)
            return mt__fail(e->diag, MT_ERR_REFUSED, vv,
                            "add face refused: vertex %u is on the boundary but neither side of "
                            "the new face at it is an edge there; its fans would not join (a "
                            "bowtie)",
                            vv);
        if (is_new[i] || is_new[ii]) continue;
        const uint32_t inner_prev = he[i], inner_next = he[ii];
        if (m->he_next[inner_prev] == inner_next) continue;
        if (strict)
            return mt__fail(e->diag, MT_ERR_REFUSED, vv,
                            "add face refused: at vertex %u the new face's sides are separate "
                            "boundary edges; its fans would not join",
                            vv);
        /* Re-link the patch between them into another gap at vv. */
        uint32_t boundary_prev = inner_next ^ 1u, steps = 0;
        do {
            boundary_prev = m->he_next[boundary_prev] ^ 1u;
        } while ((m->he_face[boundary_prev] != MT_NONE || boundary_prev == inner_prev) &&
                 ++steps < m->num_half_edges);
        const uint32_t boundary_next = m->he_next[boundary_prev];
        if (boundary_next == inner_next || m->he_face[boundary_prev] != MT_NONE)
            return mt__fail(e->diag, MT_ERR_REFUSED, vv,
                            "add face refused: vertex %u has no free boundary gap to move its "
                            "other faces to",
                            vv);
        const uint32_t patch_start = m->he_next[inner_prev];
        const uint32_t patch_end = mt__edit_prev(m, inner_next);
        cache[num_cache++] = boundary_prev;
        cache[num_cache++] = patch_start;
        cache[num_cache++] = patch_end;
        cache[num_cache++] = boundary_next;
        cache[num_cache++] = inner_prev;
        cache[num_cache++] = inner_next;
    }

    /* No refusal past this point. */
    mt_status s = mt__edit_reserve(e, (size_t)16 * n + 16 + num_cache);
    if (s != MT_OK) return s;
    for (uint32_t i = 0; i < n; i++) {
        if (!is_new[i]) continue;
        s = mt__edit_new_edge(e, v[i], v[(i + 1) % n], &he[i]);
        if (s != MT_OK) return s;
    }
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t ii = (i + 1) % n, vv = v[ii];
        const uint32_t inner_prev = he[i], inner_next = he[ii];
        const uint32_t id = (is_new[i] ? 1u : 0u) | (is_new[ii] ? 2u : 0u);
        if (id) {
            const uint32_t outer_prev = inner_next ^ 1u, outer_next = inner_prev ^ 1u;
            if (id == 1) { /* prev side new, next side old */
                const uint32_t boundary_prev = mt__edit_prev(m, inner_next);
                cache[num_cache++] = boundary_prev;
                cache[num_cache++] = outer_next;
                mt__set_vert_he(e, vv, outer_next);
            } else if (id == 2) { /* next side new, prev side old */
                const uint32_t boundary_next = m->he_next[inner_prev];
                cache[num_cache++] = outer_prev;
                cache[num_cache++] = boundary_next;
                mt__set_vert_he(e, vv, boundary_next);
            } else if (m->vert_he[vv] == MT_NONE) { /* both new, isolated vertex */
                mt__set_vert_he(e, vv, outer_next);
                cache[num_cache++] = outer_prev;
                cache[num_cache++] = outer_next;
            } else { /* both new, next to an existing fan (joined later by the edit) */
                const uint32_t boundary_next = m->vert_he[vv];
                const uint32_t boundary_prev = mt__edit_prev(m, boundary_next);
                cache[num_cache++] = boundary_prev;
                cache[num_cache++] = outer_next;
                cache[num_cache++] = outer_prev;
                cache[num_cache++] = boundary_next;
            }
            cache[num_cache++] = inner_prev;
            cache[num_cache++] = inner_next;
        } else {
            adjust[ii] = m->vert_he[vv] == inner_next;
        }
        mt__edit_set(e, MT__A_FACE, inner_prev, face);
    }
    for (size_t k = 0; k < num_cache; k += 2) mt__set_next(e, cache[k], cache[k + 1]);
    mt__edit_set(e, MT__A_FACE_HE, face, he[0]);
    for (uint32_t i = 0; i < n; i++) {
        mt__edit_adjust_vert(e, v[i]);
        if (mt__edit_touch(e, v[i]) != MT_OK) return e->status;
    }
    set_components(e, v, n);
    m->report.num_faces_valid++;
    m->report.euler_characteristic++;
    return e->status;
}

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

mt_status mt_mesh_add_face(mt_mesh *mesh, const uint32_t *verts, uint32_t count, uint32_t *out_face,
                           mt_diag *diag)
{
    mt__edit e;
    mt_status s = mt__edit_begin(&e, mesh, diag, "add face");
    if (s != MT_OK) return s;
    if (!verts || count < 3)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "add face: a face needs at least 3 vertices (got %u%s)", count,
                        verts ? "" : ", vertex list NULL");
    for (uint32_t i = 0; i < count; i++) {
        s = mt__edit_check_vert(&e, verts[i], "add face");
        if (s != MT_OK) return s;
        if (mt__vec_push(&e.s->work, &verts[i]) != MT_OK) return mt__edit_abort(&e, MT_ERR_NOMEM);
    }
    uint32_t *sorted = e.s->work.data;
    qsort(sorted, count, sizeof *sorted, compare_u32);
    for (uint32_t i = 1; i < count; i++)
        if (sorted[i] == sorted[i - 1])
            return mt__fail(diag, MT_ERR_INVALID_ARG, sorted[i],
                            "add face: vertex %u appears twice in the face", sorted[i]);
    uint32_t face;
    s = mt__edit_new_face(&e, &face);
    if (s == MT_OK) s = mt__face_insert(&e, verts, count, face, true);
    if (s != MT_OK) return mt__edit_abort(&e, s);
    s = mt__edit_finish(&e);
    if (s == MT_OK && out_face) *out_face = face;
    return s;
}

mt_status mt_mesh_add_vert(mt_mesh *mesh, const double *position, uint32_t *out_vert, mt_diag *diag)
{
    mt__edit e;
    mt_status s = mt__edit_begin(&e, mesh, diag, "add vertex");
    if (s != MT_OK) return s;
    uint32_t v;
    s = mt__edit_new_vert(&e, position, &v);
    if (s != MT_OK) return mt__edit_abort(&e, s);
    s = mt__edit_finish(&e);
    if (s == MT_OK && out_vert) *out_vert = v;
    return s;
}
