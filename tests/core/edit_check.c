/* Helpers for the edit tests: see edit_check.h. */
#include "edit_check.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/edit.h"
#include "meshtopo/mesh.h"

mt_mesh *edit_build(mt_face_list *list)
{
    mt_mesh *m = NULL;
    mt_diag diag;
    if (mt_mesh_build(list, NULL, &m, &diag) != MT_OK) {
        fprintf(stderr, "edit test: build failed: %s\n", diag.message);
        exit(2);
    }
    mt_face_list_free(list);
    return m;
}

static void *dup(const void *src, size_t bytes)
{
    void *p = malloc(bytes ? bytes : 1);
    if (!p) exit(2);
    if (src && bytes) memcpy(p, src, bytes);
    return p;
}

void edit_snapshot_take(const mt_mesh *m, edit_snapshot *out)
{
    memset(out, 0, sizeof *out);
    out->counts = *m;
    out->edits = mt_mesh_edit_count(m);
    const size_t nhe = m->num_half_edges * sizeof(uint32_t);
    out->he_head = dup(m->he_head, nhe);
    out->he_next = dup(m->he_next, nhe);
    out->he_face = dup(m->he_face, nhe);
    out->face_he = dup(m->face_he, m->num_faces * sizeof(uint32_t));
    out->vert_he = dup(m->vert_he, m->num_verts_internal * sizeof(uint32_t));
    if (m->vert_component)
        out->vert_component = dup(m->vert_component, m->num_verts_internal * sizeof(uint32_t));
    if (m->positions) out->positions = dup(m->positions, m->num_verts * 3 * sizeof(double));
    out->deleted = dup(NULL, m->num_verts);
    for (uint32_t v = 0; v < m->num_verts; v++) out->deleted[v] = mt_vert_is_deleted(m, v);
}

bool edit_snapshot_same(const mt_mesh *m, const edit_snapshot *s)
{
    const mt_mesh *c = &s->counts;
    if (m->num_verts != c->num_verts || m->num_verts_internal != c->num_verts_internal ||
        m->num_faces != c->num_faces || m->num_half_edges != c->num_half_edges)
        return false;
    if (m->report.num_verts != c->report.num_verts || m->report.num_faces != c->report.num_faces ||
        m->report.num_faces_valid != c->report.num_faces_valid ||
        m->report.num_edges != c->report.num_edges ||
        m->report.euler_characteristic != c->report.euler_characteristic)
        return false;
    const size_t nhe = m->num_half_edges * sizeof(uint32_t);
    if (memcmp(m->he_head, s->he_head, nhe) || memcmp(m->he_next, s->he_next, nhe) ||
        memcmp(m->he_face, s->he_face, nhe) ||
        memcmp(m->face_he, s->face_he, m->num_faces * sizeof(uint32_t)) ||
        memcmp(m->vert_he, s->vert_he, m->num_verts_internal * sizeof(uint32_t)))
        return false;
    if ((m->vert_component != NULL) != (s->vert_component != NULL)) return false;
    if (m->vert_component &&
        memcmp(m->vert_component, s->vert_component, m->num_verts_internal * sizeof(uint32_t)))
        return false;
    if ((m->positions != NULL) != (s->positions != NULL)) return false;
    if (m->positions && memcmp(m->positions, s->positions, m->num_verts * 3 * sizeof(double)))
        return false;
    for (uint32_t v = 0; v < m->num_verts; v++)
        if (s->deleted[v] != mt_vert_is_deleted(m, v)) return false;
    return mt_mesh_edit_count(m) == s->edits;
}

void edit_snapshot_free(edit_snapshot *s)
{
    free(s->he_head);
    free(s->he_next);
    free(s->he_face);
    free(s->face_he);
    free(s->vert_he);
    free(s->vert_component);
    free(s->positions);
    free(s->deleted);
    memset(s, 0, sizeof *s);
}

edit_counts edit_count(const mt_mesh *m)
{
    edit_counts c = {0, 0, 0, 0};
    for (uint32_t v = 0; v < m->num_verts; v++) c.verts += !mt_vert_is_deleted(m, v);
    for (uint32_t f = 0; f < m->num_faces; f++) c.faces += m->face_he[f] != MT_NONE;
    for (uint32_t e = 0; e < m->num_half_edges / 2; e++) c.edges += m->he_head[2 * e] != MT_NONE;
    c.euler = (int64_t)c.verts - c.edges + c.faces;
    return c;
}
