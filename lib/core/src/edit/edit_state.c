/* The edit context (edit_internal.h): undo log, rollback, geometric growth of
 * the mesh arrays, new elements, the final manifold check of the touched
 * vertices, and the small look-ups every edit uses. Everything here costs
 * time linear in what the edit touches (growth is amortised constant). */
#include <stdlib.h>
#include <string.h>

#include "edit/edit_internal.h"
#include "meshtopo/edit.h"

/* Largest half-edge count: validate's limit. */
#define MT__MAX_HALF_EDGES 0x7ffffffeu
#define MT__MAX_IDS 0x7fffffffu

static uint32_t grown(uint32_t cap, uint32_t need, uint32_t limit)
{
    uint64_t c = (uint64_t)cap * 2;
    if (c < need) c = need;
    if (c < 64) c = 64;
    if (c > limit) c = limit;
    return (uint32_t)c;
}

/* Room for `need` half-edges: a new block holding the three arrays (the
 * layout of the build, so mt_mesh_destroy frees it through he_head). */
static mt_status grow_half_edges(mt_mesh *m, uint32_t need)
{
    uint32_t cap = mt__cap_or(m->cap_half_edges, m->num_half_edges);
    if (need <= cap) return MT_OK;
    if (need > MT__MAX_HALF_EDGES) return MT_ERR_TOO_LARGE;
    cap = grown(cap, need, MT__MAX_HALF_EDGES);
    uint32_t *block = mt__malloc((size_t)cap * 3 * sizeof(uint32_t));
    if (!block) return MT_ERR_NOMEM;
    const size_t bytes = (size_t)m->num_half_edges * sizeof(uint32_t);
    if (bytes) {
        memcpy(block, m->he_head, bytes);
        memcpy(block + cap, m->he_next, bytes);
        memcpy(block + 2 * (size_t)cap, m->he_face, bytes);
    }
    mt__free(m->he_head);
    m->he_head = block;
    m->he_next = block + cap;
    m->he_face = block + 2 * (size_t)cap;
    m->cap_half_edges = cap;
    return mt__attributes_fit(m);
}

static mt_status grow_faces(mt_mesh *m, uint32_t need)
{
    uint32_t cap = mt__cap_or(m->cap_faces, m->num_faces);
    if (need <= cap) return MT_OK;
    if (need > MT__MAX_IDS) return MT_ERR_TOO_LARGE;
    cap = grown(cap, need, MT__MAX_IDS);
    uint32_t *p = mt__realloc(m->face_he, (size_t)cap * sizeof(uint32_t));
    if (!p) return MT_ERR_NOMEM;
    m->face_he = p;
    m->cap_faces = cap;
    return mt__attributes_fit(m);
}

/* Each per-vertex array is reallocated in turn; the capacity is raised only
 * once all have the room, so a failure part-way leaves larger arrays with
 * the same contents. */
static mt_status grow_verts(mt_mesh *m, mt__edit_state *s, uint32_t need)
{
    uint32_t cap = mt__cap_or(m->cap_verts, m->num_verts_internal);
    if (need <= cap) return MT_OK;
    if (need > MT__MAX_IDS) return MT_ERR_TOO_LARGE;
    cap = grown(cap, need, MT__MAX_IDS);
    uint32_t *vh = mt__realloc(m->vert_he, (size_t)cap * sizeof(uint32_t));
    if (!vh) return MT_ERR_NOMEM;
    m->vert_he = vh;
    if (m->positions) {
        double *p = mt__realloc(m->positions, (size_t)cap * 3 * sizeof(double));
        if (!p) return MT_ERR_NOMEM;
        m->positions = p;
    }
    if (m->vert_component) {
        uint32_t *c = mt__realloc(m->vert_component, (size_t)cap * sizeof(uint32_t));
        if (!c) return MT_ERR_NOMEM;
        m->vert_component = c;
    }
    if (s->vert_deleted) {
        uint8_t *d = mt__realloc(s->vert_deleted, cap);
        if (!d) return MT_ERR_NOMEM;
        s->vert_deleted = d;
    }
    m->cap_verts = cap;
    return mt__attributes_fit(m);
}

mt_status mt__edit_begin(mt__edit *e, mt_mesh *m, mt_diag *diag, const char *what)
{
    mt_diag_clear(diag);
    memset(e, 0, sizeof *e);
    e->diag = diag;
    e->moved_vert = MT_NONE;
    if (!m) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: mesh is NULL", what);
    if (m->num_copies || m->num_bundles)
        return mt__fail(diag, MT_ERR_UNSUPPORTED, MT_NONE,
                        "%s: mesh has %u non-manifold vertex cop%s and %u non-manifold edge "
                        "bundle%s; edits need a manifold mesh",
                        what, m->num_copies, m->num_copies == 1 ? "y" : "ies", m->num_bundles,
                        m->num_bundles == 1 ? "" : "s");
    if (!m->edit) {
        m->edit = mt__calloc(1, sizeof *m->edit);
        if (!m->edit) return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "%s: out of memory", what);
        m->edit->undo.elem_size = sizeof(mt__undo);
        m->edit->freed.elem_size = m->edit->touched.elem_size = sizeof(uint32_t);
        m->edit->prim.elem_size = m->edit->work.elem_size = sizeof(uint32_t);
    }
    e->m = m;
    e->s = m->edit;
    e->s->undo.len = e->s->freed.len = e->s->touched.len = 0;
    e->s->prim.len = e->s->work.len = 0;
    e->num_verts = m->num_verts;
    e->report_verts = m->report.num_verts;
    e->num_faces = m->num_faces;
    e->num_half_edges = m->num_half_edges;
    e->num_faces_valid = m->report.num_faces_valid;
    e->num_edges = m->report.num_edges;
    e->euler = m->report.euler_characteristic;
    e->num_deleted_verts = e->s->num_deleted_verts;
    return MT_OK;
}

static uint32_t *slot32(mt_mesh *m, uint32_t array, uint32_t index)
{
    switch (array) {
        case MT__A_HEAD:
            return &m->he_head[index];
        case MT__A_NEXT:
            return &m->he_next[index];
        case MT__A_FACE:
            return &m->he_face[index];
        case MT__A_FACE_HE:
            return &m->face_he[index];
        case MT__A_VERT_HE:
            return &m->vert_he[index];
        default:
            return &m->vert_component[index];
    }
}

void mt__edit_set(mt__edit *e, uint32_t array, uint32_t index, uint32_t value)
{
    if (e->status != MT_OK) return;
    mt__undo u = {array, index, 0};
    if (array == MT__A_DEL)
        u.old = e->s->vert_deleted[index];
    else
        u.old = *slot32(e->m, array, index);
    if (mt__vec_push(&e->s->undo, &u) != MT_OK) {
        e->status = MT_ERR_NOMEM;
        return;
    }
    if (array == MT__A_DEL)
        e->s->vert_deleted[index] = (uint8_t)value;
    else
        *slot32(e->m, array, index) = value;
}

mt_status mt__edit_reserve(mt__edit *e, size_t writes)
{
    mt__vec *v = &e->s->undo;
    if (v->len + writes <= v->cap) return MT_OK;
    size_t cap = v->cap ? v->cap : 64, bytes;
    while (cap < v->len + writes) cap *= 2;
    if (!mt__mul_size(cap, v->elem_size, &bytes)) return MT_ERR_NOMEM;
    void *p = mt__realloc(v->data, bytes);
    if (!p) return MT_ERR_NOMEM;
    v->data = p;
    v->cap = cap;
    return MT_OK;
}

mt_status mt__edit_abort(mt__edit *e, mt_status status)
{
    if (!e->m) return status;
    mt_mesh *m = e->m;
    const mt__undo *log = e->s->undo.data;
    for (size_t i = e->s->undo.len; i-- > 0;) {
        if (log[i].array == MT__A_DEL)
            e->s->vert_deleted[log[i].index] = (uint8_t)log[i].old;
        else
            *slot32(m, log[i].array, log[i].index) = log[i].old;
    }
    e->s->undo.len = 0;
    m->num_verts = m->num_verts_internal = e->num_verts;
    m->num_faces = e->num_faces;
    m->num_half_edges = e->num_half_edges;
    m->report.num_verts = e->report_verts;
    m->report.num_faces = e->num_faces;
    m->report.num_faces_valid = e->num_faces_valid;
    m->report.num_edges = e->num_edges;
    m->report.euler_characteristic = e->euler;
    e->s->num_deleted_verts = e->num_deleted_verts;
    if (e->moved_vert != MT_NONE && m->positions)
        memcpy(m->positions + 3 * (size_t)e->moved_vert, e->moved_pos, sizeof e->moved_pos);
    if (status == MT_ERR_NOMEM && (!e->diag || e->diag->status == MT_OK))
        mt__fail(e->diag, MT_ERR_NOMEM, MT_NONE, "edit: out of memory; the mesh is unchanged");
    return status;
}

mt_status mt__edit_touch(mt__edit *e, uint32_t v)
{
    if (mt__vec_push(&e->s->touched, &v) != MT_OK) e->status = MT_ERR_NOMEM;
    return e->status;
}

mt_status mt__edit_new_vert(mt__edit *e, const double *pos, uint32_t *out_vert)
{
    mt_mesh *m = e->m;
    if (m->num_verts >= MT__MAX_IDS)
        return mt__fail(e->diag, MT_ERR_TOO_LARGE, MT_NONE, "edit: mesh has 2^31 - 1 vertices");
    mt_status s = grow_verts(m, e->s, m->num_verts + 1);
    if (s != MT_OK) return s;
    const uint32_t v = m->num_verts;
    m->vert_he[v] = MT_NONE;
    if (m->positions) {
        double *p = m->positions + 3 * (size_t)v;
        if (pos) {
            memcpy(p, pos, 3 * sizeof(double));
        } else {
            p[0] = p[1] = p[2] = 0.0;
        }
    }
    if (m->vert_component) m->vert_component[v] = MT_NONE;
    if (e->s->vert_deleted) e->s->vert_deleted[v] = 0;
    m->num_verts = m->num_verts_internal = v + 1;
    m->report.num_verts++;
    m->report.euler_characteristic++;
    *out_vert = v;
    return MT_OK;
}

mt_status mt__edit_new_face(mt__edit *e, uint32_t *out_face)
{
    mt_mesh *m = e->m;
    if (m->num_faces >= MT__MAX_IDS)
        return mt__fail(e->diag, MT_ERR_TOO_LARGE, MT_NONE, "edit: mesh has 2^31 - 1 faces");
    mt_status s = grow_faces(m, m->num_faces + 1);
    if (s != MT_OK) return s;
    m->face_he[m->num_faces] = MT_NONE;
    *out_face = m->num_faces++;
    m->report.num_faces = m->num_faces;
    return MT_OK;
}

mt_status mt__edit_new_edge(mt__edit *e, uint32_t a, uint32_t b, uint32_t *out_he)
{
    mt_mesh *m = e->m;
    uint32_t edge;
    if (e->s->freed.len) {
        edge = ((uint32_t *)e->s->freed.data)[--e->s->freed.len];
    } else {
        if (m->num_half_edges >= MT__MAX_HALF_EDGES)
            return mt__fail(e->diag, MT_ERR_TOO_LARGE, MT_NONE,
                            "edit: mesh has 2^31 - 2 half-edges");
        mt_status s = grow_half_edges(m, m->num_half_edges + 2);
        if (s != MT_OK) return s;
        edge = m->num_half_edges / 2;
        m->he_head[2 * edge] = m->he_head[2 * edge + 1] = MT_NONE;
        m->he_next[2 * edge] = 2 * edge;
        m->he_next[2 * edge + 1] = 2 * edge + 1;
        m->he_face[2 * edge] = m->he_face[2 * edge + 1] = MT_NONE;
        m->num_half_edges += 2;
    }
    /* The first half-edge runs from the smaller vertex id to the larger. */
    const uint32_t h = a < b ? 2 * edge : 2 * edge + 1;
    mt__edit_set(e, MT__A_HEAD, h, b);
    mt__edit_set(e, MT__A_HEAD, h ^ 1u, a);
    m->report.num_edges++;
    m->report.euler_characteristic--;
    *out_he = h;
    return e->status;
}

void mt__edit_move_vert(mt__edit *e, uint32_t v, const double *pos)
{
    mt_mesh *m = e->m;
    if (!m->positions || !pos) return;
    double *p = m->positions + 3 * (size_t)v;
    if (e->moved_vert == MT_NONE) {
        e->moved_vert = v;
        memcpy(e->moved_pos, p, sizeof e->moved_pos);
    }
    memcpy(p, pos, 3 * sizeof(double));
}

mt_status mt__edit_delete_vert(mt__edit *e, uint32_t v)
{
    mt_mesh *m = e->m;
    mt__edit_state *s = e->s;
    if (!s->vert_deleted) {
        s->vert_deleted = mt__calloc(mt__cap_or(m->cap_verts, m->num_verts_internal), 1);
        if (!s->vert_deleted) return MT_ERR_NOMEM;
    }
    mt__edit_set(e, MT__A_DEL, v, 1);
    if (m->vert_he[v] != MT_NONE) mt__set_vert_he(e, v, MT_NONE);
    if (m->vert_component && m->vert_component[v] != MT_NONE)
        mt__edit_set(e, MT__A_COMP, v, MT_NONE);
    s->num_deleted_verts++;
    m->report.num_verts--; /* V - E + F stays the Euler characteristic */
    m->report.euler_characteristic--;
    return e->status;
}

uint32_t mt__edit_find_he(const mt_mesh *m, uint32_t a, uint32_t b)
{
    const uint32_t start = m->vert_he[a];
    if (start == MT_NONE) return MT_NONE;
    uint32_t h = start, steps = 0;
    do {
        if (m->he_head[h] == b) return h;
        h = m->he_next[h ^ 1u];
    } while (h != start && ++steps < m->num_half_edges);
    return MT_NONE;
}

uint32_t mt__edit_prev(const mt_mesh *m, uint32_t h)
{
    uint32_t x = h ^ 1u, steps = 0;
    while (m->he_next[x] != h && steps++ < m->num_half_edges) x = m->he_next[x] ^ 1u;
    return x;
}

void mt__edit_adjust_vert(mt__edit *e, uint32_t v)
{
    const mt_mesh *m = e->m;
    const uint32_t start = m->vert_he[v];
    if (start == MT_NONE || m->he_face[start] == MT_NONE) return;
    uint32_t h = start, steps = 0;
    do {
        if (m->he_face[h] == MT_NONE) {
            mt__set_vert_he(e, v, h);
            return;
        }
        h = m->he_next[h ^ 1u];
    } while (h != start && ++steps < m->num_half_edges);
}

uint32_t mt__vert_valence(const mt_mesh *m, uint32_t v)
{
    const uint32_t start = m->vert_he[v];
    if (start == MT_NONE) return 0;
    uint32_t h = start, n = 0;
    do {
        n++;
        h = m->he_next[h ^ 1u];
    } while (h != start && n < m->num_half_edges);
    return n;
}

bool mt__vert_on_boundary(const mt_mesh *m, uint32_t v)
{
    return m->vert_he[v] != MT_NONE && m->he_face[m->vert_he[v]] == MT_NONE;
}

uint32_t mt__face_collect(const mt_mesh *m, uint32_t f, mt__vec *vec)
{
    const uint32_t start = m->face_he[f];
    if (start == MT_NONE) return 0;
    uint32_t h = start, n = 0;
    do {
        if (mt__vec_push(vec, &m->he_head[h ^ 1u]) != MT_OK) return 0;
        n++;
        h = m->he_next[h];
    } while (h != start && n < m->num_half_edges);
    return n;
}

bool mt_vert_is_deleted(const mt_mesh *mesh, uint32_t vert)
{
    return mesh && mesh->edit && mesh->edit->vert_deleted && vert < mesh->num_verts &&
           mesh->edit->vert_deleted[vert];
}

uint64_t mt_mesh_edit_count(const mt_mesh *mesh)
{
    return mesh && mesh->edit ? mesh->edit->edits : 0;
}

mt_status mt__edit_check_vert(mt__edit *e, uint32_t v, const char *what)
{
    if (v >= e->m->num_verts)
        return mt__fail(e->diag, MT_ERR_OUT_OF_RANGE, v,
                        "%s: vertex %u is out of range (%u vertices)", what, v, e->m->num_verts);
    if (mt_vert_is_deleted(e->m, v))
        return mt__fail(e->diag, MT_ERR_NOT_FOUND, v, "%s: vertex %u was deleted", what, v);
    return MT_OK;
}

mt_status mt__edit_check_edge(mt__edit *e, uint32_t a, uint32_t b, const char *what,
                              uint32_t *out_he)
{
    mt_status s = mt__edit_check_vert(e, a, what);
    if (s == MT_OK) s = mt__edit_check_vert(e, b, what);
    if (s != MT_OK) return s;
    uint32_t h = a == b ? MT_NONE : mt__edit_find_he(e->m, a, b);
    if (h == MT_NONE)
        return mt__fail(e->diag, MT_ERR_NOT_FOUND, a, "%s: there is no edge %u-%u", what, a, b);
    *out_he = h;
    return MT_OK;
}

mt_status mt__edit_check_face(mt__edit *e, uint32_t f, const char *what)
{
    if (f >= e->m->num_faces)
        return mt__fail(e->diag, MT_ERR_OUT_OF_RANGE, f, "%s: face %u is out of range (%u faces)",
                        what, f, e->m->num_faces);
    if (e->m->face_he[f] == MT_NONE)
        return mt__fail(e->diag, MT_ERR_NOT_FOUND, f, "%s: face %u was deleted or rejected", what,
                        f);
    return MT_OK;
}

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

static bool is_triangle(const mt_mesh *m, uint32_t h)
{
    return m->he_next[m->he_next[m->he_next[h]]] == h;
}

/* Whether both faces around an interior vertex of valence 2 are triangles:
 * then they share all three sides and close up on their own (a pillow). */
static bool both_triangles(const mt_mesh *m, uint32_t out)
{
    return is_triangle(m, out) && is_triangle(m, m->he_next[out ^ 1u]);
}

/* One touched vertex: a single fan (at most one boundary gap), the outgoing
 * half-edge on the gap, distinct neighbours, and, when the fan is closed, not
 * just two triangles. */
static mt_status check_touched(mt__edit *e, uint32_t v)
{
    const mt_mesh *m = e->m;
    const uint32_t start = m->vert_he[v];
    if (start == MT_NONE) return MT_OK;
    mt__vec *nb = &e->s->prim;
    nb->len = 0;
    uint32_t h = start, gaps = 0, steps = 0;
    do {
        gaps += m->he_face[h] == MT_NONE;
        if (mt__vec_push(nb, &m->he_head[h]) != MT_OK) return MT_ERR_NOMEM;
        h = m->he_next[h ^ 1u];
    } while (h != start && ++steps < m->num_half_edges);
    if (gaps > 1)
        return mt__fail(e->diag, MT_ERR_REFUSED, v,
                        "edit refused: vertex %u would have %u separate boundary gaps (a "
                        "non-manifold vertex)",
                        v, gaps);
    if (gaps == 0 && nb->len <= 2 && (nb->len < 2 || both_triangles(m, start)))
        return mt__fail(e->diag, MT_ERR_REFUSED, v,
                        "edit refused: interior vertex %u would be left between two triangles "
                        "glued along all their sides (a degenerate surface)",
                        v);
    uint32_t *n = nb->data;
    qsort(n, nb->len, sizeof *n, compare_u32);
    for (size_t i = 1; i < nb->len; i++)
        if (n[i] == n[i - 1])
            return mt__fail(e->diag, MT_ERR_REFUSED, v,
                            "edit refused: vertices %u and %u would be joined by two edges", v,
                            n[i]);
    if (gaps == 1) mt__edit_adjust_vert(e, v);
    return e->status;
}

mt_status mt__edit_finish(mt__edit *e)
{
    if (e->status != MT_OK) return mt__edit_abort(e, e->status);
    const uint32_t *t = e->s->touched.data;
    for (size_t i = 0; i < e->s->touched.len; i++) {
        if (mt_vert_is_deleted(e->m, t[i])) continue;
        mt_status s = check_touched(e, t[i]);
        if (s != MT_OK) return mt__edit_abort(e, s);
    }
    e->s->undo.len = 0;
    e->s->edits++;
    return MT_OK;
}

void mt__list_rotate_to(uint32_t *list, uint32_t n, uint32_t first)
{
    uint32_t k = 0;
    while (k < n && list[k] != first) k++;
    if (k == 0 || k == n) return;
    /* Three reversals rotate in place. */
    for (uint32_t i = 0, j = k - 1; i < j; i++, j--) {
        uint32_t t = list[i];
        list[i] = list[j];
        list[j] = t;
    }
    for (uint32_t i = k, j = n - 1; i < j; i++, j--) {
        uint32_t t = list[i];
        list[i] = list[j];
        list[j] = t;
    }
    for (uint32_t i = 0, j = n - 1; i < j; i++, j--) {
        uint32_t t = list[i];
        list[i] = list[j];
        list[j] = t;
    }
}
