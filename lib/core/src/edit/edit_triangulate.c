/* Triangulating polygon faces by ear clipping (polygon_ears.c), cutting
 * no diagonal that is already an edge of the mesh. Without positions any
 * corner is an ear. A face that crosses itself in its plane
 * (mt_face_shape_of) is refused: no set of triangles covers it without
 * folding. */
#include "edit/edit_internal.h"
#include "geometry/geometry_internal.h"
#include "meshtopo/edit.h"

typedef struct face_corners {
    const mt_mesh *m;
    const uint32_t *verts;
} face_corners;

/* A diagonal may be cut unless it is already an edge of the mesh. */
static bool diagonal_is_new(void *user, uint32_t i, uint32_t j)
{
    const face_corners *fc = user;
    return mt__edit_find_he(fc->m, fc->verts[i], fc->verts[j]) == MT_NONE;
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
    const uint32_t *verts = work->data;
    const double **pos = m->positions ? mt__malloc(n * sizeof *pos) : NULL;
    uint32_t *scratch = mt__malloc((size_t)(n + 3 * (n - 2)) * sizeof *scratch);
    if ((m->positions && !pos) || !scratch) {
        mt__free(pos);
        mt__free(scratch);
        return MT_ERR_NOMEM;
    }
    for (uint32_t i = 0; pos && i < n; i++) pos[i] = mt__geom_pos(m, verts[i]);
    uint32_t *tris = scratch + n;
    face_corners fc = {m, verts};
    const bool cut = mt__ear_clip(pos, n, diagonal_is_new, &fc, scratch, tris);
    mt__free(pos);
    if (!cut) {
        mt__free(scratch);
        return mt__fail(e->diag, MT_ERR_REFUSED, f,
                        "triangulate refused: face %u: every diagonal left to cut is already "
                        "an edge of the mesh",
                        f);
    }
    /* Corner indices to vertex ids; the first triangle keeps the id and
     * starts at the face's first corner. */
    for (uint32_t i = 0; i < 3 * (n - 2); i++) tris[i] = verts[tris[i]];
    mt__list_rotate_to(tris, 3, verts[0]);
    mt_status s = mt__face_remove(e, f);
    for (uint32_t t = 0; t < n - 2 && s == MT_OK; t++) {
        uint32_t id = f;
        if (t > 0) s = mt__edit_new_face(e, &id);
        if (s == MT_OK) s = mt__face_insert(e, tris + 3 * t, 3, id, false);
    }
    mt__free(scratch);
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
