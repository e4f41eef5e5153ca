/* The topology arrays of /VTKHDF worked out from a built mesh (no HDF5
 * here): per cell (kept face) its component, the defect kinds involving it,
 * whether it touches a boundary, whether its orientation agrees with its
 * neighbours' and, when asked, whether it meets another face; per point
 * boundary, non-manifold and defect kinds. Meanings are in archive.h
 * ("Topology as VTK arrays"). The cost is a sweep over the half-edges for
 * the boundary, plus, on a mesh with defects, a look-up per defect and one
 * sweep over the face list; nothing is allocated for an array with nothing
 * to show. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "archive_internal.h"
#include "meshtopo/query.h"

_Static_assert(MT_DEFECT_KIND_COUNT <= 32, "a defect kind per bit of a uint32 bitmask");

const mt__topo_info mt__topo_arrays[MT__TOPO_COUNT] = {
    [MT__TOPO_CELL_COMPONENT] = {"component", true, MT__TOPO_INT32, 0, false,
                                 "edge-connected component of the cell's face, numbered as "
                                 "/meshtopo/report/components (0 .. connected_components - 1)"},
    [MT__TOPO_CELL_DEFECTS] = {"defects", true, MT__TOPO_UINT32, 0, true,
                               "defect kinds of /meshtopo/report/defects involving the face: bit k "
                               "(value 2^k) for kind k, named by attribute bits; a face defect "
                               "involves its face, an edge defect the faces on the edge "
                               "(same_direction_edge: those crossing its edge u -> v), a vertex "
                               "defect the faces with the vertex as a corner"},
    [MT__TOPO_CELL_TOUCHES_BOUNDARY] = {"touches_boundary", true, MT__TOPO_UINT8, 0, false,
                                        "1 when a side of the face is a boundary edge (an edge "
                                        "used by one face), else 0"},
    [MT__TOPO_CELL_ORIENTATION_CONSISTENT] = {"orientation_consistent", true, MT__TOPO_UINT8, 1,
                                              false,
                                              "1 when every face that is the only other face on "
                                              "one of this face's edges runs that edge the "
                                              "opposite way; 0 when one runs it the same way "
                                              "(both faces get 0). Edges of three or more faces "
                                              "do not count"},
    [MT__TOPO_CELL_SELF_INTERSECTING] = {"self_intersecting", true, MT__TOPO_UINT8, 0, false,
                                         "1 when the face meets another face other than along "
                                         "the vertices and edges they share "
                                         "(mt_mesh_self_intersections), else 0; attribute pairs "
                                         "is the number of such pairs of faces"},
    [MT__TOPO_POINT_BOUNDARY] = {"boundary", false, MT__TOPO_UINT8, 0, false,
                                 "1 when the vertex ends a boundary edge (an edge used by one "
                                 "face), else 0"},
    [MT__TOPO_POINT_NON_MANIFOLD] = {"non_manifold", false, MT__TOPO_UINT8, 0, false,
                                     "1 when the vertex is a nonmanifold_vertex of "
                                     "/meshtopo/report/defects (its faces do not form a single "
                                     "fan: for example a bowtie, or the end of an edge of three "
                                     "or more faces), else 0"},
    [MT__TOPO_POINT_DEFECTS] = {"defects", false, MT__TOPO_UINT32, 0, true,
                                "defect kinds of /meshtopo/report/defects involving the vertex: "
                                "bit k (value 2^k) for kind k, named by attribute bits; a vertex "
                                "defect involves its vertex, an edge defect both ends, a face "
                                "defect the face's corners (those of a rejected face too, which "
                                "is not a cell)"},
};

size_t mt__topo_type_size(mt__topo_type type)
{
    return type == MT__TOPO_UINT8 ? 1 : 4;
}

/* Every per-kind array's name fits MT__TOPO_KIND_NAME_MAX. */
#define MT__KIND_NAME_FITS(name, key, text)                         \
    _Static_assert(sizeof("defect_" key) <= MT__TOPO_KIND_NAME_MAX, \
                   "defect_" key " fits MT__TOPO_KIND_NAME_MAX");
MT_DEFECT_TABLE(MT__KIND_NAME_FITS)
#undef MT__KIND_NAME_FITS

void mt__topo_kind_name(mt_defect_kind kind, char *buf, size_t size)
{
    snprintf(buf, size, "defect_%s", mt_defect_key(kind));
}

/* Defect kinds by what they name. */
#define BIT(kind) (1u << (kind))
#define FACE_KINDS                                                        \
    (BIT(MT_DEFECT_OUT_OF_RANGE_INDEX) | BIT(MT_DEFECT_DEGENERATE_FACE) | \
     BIT(MT_DEFECT_DUPLICATE_FACE))
#define VERTEX_KINDS                                                      \
    (BIT(MT_DEFECT_NONMANIFOLD_VERTEX) | BIT(MT_DEFECT_ISOLATED_VERTEX) | \
     BIT(MT_DEFECT_NONFINITE_COORD))

void mt__topology_free(mt__topology *t)
{
    if (!t) return;
    for (int i = 0; i < MT__TOPO_COUNT; i++) free(t->values[i]);
    memset(t, 0, sizeof *t);
}

int64_t mt__topology_value(const mt__topology *t, mt__topo_id id, uint64_t i)
{
    const void *v = t->values[id];
    if (!v) return mt__topo_arrays[id].fill;
    switch (mt__topo_arrays[id].type) {
        case MT__TOPO_INT32:
            return ((const int32_t *)v)[i];
        case MT__TOPO_UINT32:
            return ((const uint32_t *)v)[i];
        case MT__TOPO_UINT8:
            return ((const uint8_t *)v)[i];
    }
    return 0;
}

/* The work in progress: per face record (caller ids, compacted to cells at
 * the end) and per vertex. */
typedef struct work {
    const mt_face_list *list;
    const mt_mesh *mesh;
    mt_mesh_view view;
    mt_mesh_parts parts;
    mt__topology *out;
    uint32_t *faces; /* mt_edge_faces' answers */
    size_t faces_capacity;
} work;

/* values[id], allocated zeroed on first use with one row per face record
 * (cell arrays) or vertex; NULL when out of memory. A uint8 array whose
 * fill is 1 starts all ones. */
static void *array_of(work *w, mt__topo_id id)
{
    mt__topology *t = w->out;
    if (t->values[id]) return t->values[id];
    const mt__topo_info *info = &mt__topo_arrays[id];
    size_t rows = info->cell ? w->list->num_faces : w->list->num_verts;
    size_t size = mt__topo_type_size(info->type);
    void *v = calloc(rows + 1, size);
    if (v && info->fill == 1 && info->type == MT__TOPO_UINT8) memset(v, 1, rows);
    t->values[id] = v;
    return v;
}

static uint32_t *bits_of(work *w, mt__topo_id id)
{
    return array_of(w, id);
}

static uint8_t *flags_of(work *w, mt__topo_id id)
{
    return array_of(w, id);
}

static int compare_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* Whether internal edge e is one of several the build made of one caller
 * edge (a non-manifold or same-direction edge): its boundary twin is a
 * seam, not a boundary. */
static bool bundled(const mt_mesh_parts *p, uint32_t e)
{
    return p->num_bundled > 0 &&
           bsearch(&e, p->bundled_sorted, p->num_bundled, sizeof e, compare_u32) != NULL;
}

/* Boundary: every half-edge without a face whose twin has one, on an edge
 * of its own (not bundled), is a side of exactly one face. */
static mt_status sweep_boundary(work *w, mt_diag *diag)
{
    const mt_mesh_view *v = &w->view;
    for (uint32_t h = 0; h < v->num_half_edges; h++) {
        if (v->he_face[h] != MT_NONE || v->he_face[h ^ 1u] == MT_NONE) continue;
        if (bundled(&w->parts, h >> 1)) continue;
        uint8_t *faces = flags_of(w, MT__TOPO_CELL_TOUCHES_BOUNDARY);
        uint8_t *verts = flags_of(w, MT__TOPO_POINT_BOUNDARY);
        if (!faces || !verts) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
        faces[v->he_face[h ^ 1u]] = 1;
        verts[mt_vert_original(w->mesh, v->he_head[h])] = 1;
        verts[mt_vert_original(w->mesh, v->he_head[h ^ 1u])] = 1;
    }
    return MT_OK;
}

/* Component of each face: that of its first vertex (every vertex of a face
 * is in the face's component). A mesh of one component keeps the fill. */
static mt_status fill_components(work *w, mt_diag *diag)
{
    const uint32_t *comp = w->parts.vert_component;
    if (!comp) return MT_OK;
    int32_t *out = array_of(w, MT__TOPO_CELL_COMPONENT);
    if (!out) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    const mt_mesh_view *v = &w->view;
    for (uint32_t f = 0; f < v->num_faces; f++) {
        uint32_t h = v->face_he[f];
        if (h == MT_NONE) continue;
        uint32_t c = comp[v->he_head[h]];
        out[f] = c == MT_NONE ? -1 : (int32_t)c;
    }
    return MT_OK;
}

/* The faces on caller edge {a, b} into w->faces; their number. */
static mt_status edge_faces(work *w, uint32_t a, uint32_t b, size_t *out_count, mt_diag *diag)
{
    *out_count = 0;
    size_t n = 0;
    mt_status st = mt_edge_faces(w->mesh, a, b, NULL, 0, &n);
    if (st == MT_ERR_NOT_FOUND || st == MT_ERR_OUT_OF_RANGE) return MT_OK;
    if (st != MT_OK)
        return mt__archive_fail(diag, st, "the faces of edge %u-%u: %s", a, b, mt_strerror(st));
    if (n > w->faces_capacity) {
        uint32_t *grown = realloc(w->faces, n * sizeof *grown);
        if (!grown) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
        w->faces = grown;
        w->faces_capacity = n;
    }
    st = mt_edge_faces(w->mesh, a, b, w->faces, w->faces_capacity, &n);
    if (st != MT_OK)
        return mt__archive_fail(diag, st, "the faces of edge %u-%u: %s", a, b, mt_strerror(st));
    *out_count = n;
    return MT_OK;
}

/* Whether face f has a side from caller vertex a to caller vertex b. */
static bool face_runs(const work *w, uint32_t f, uint32_t a, uint32_t b)
{
    const mt_mesh_view *v = &w->view;
    const uint32_t start = v->face_he[f];
    uint32_t h = start, steps = 0;
    const uint32_t limit = w->list->face_sizes[f];
    do {
        if (mt_vert_original(w->mesh, mt_he_tail(v, h)) == a &&
            mt_vert_original(w->mesh, v->he_head[h]) == b)
            return true;
        h = v->he_next[h];
    } while (h != start && ++steps < limit);
    return false;
}

/* An edge defect: both ends, and the faces on the edge (a same-direction
 * edge: those running a -> b; when they are the edge's only two faces,
 * their orientations disagree). */
static mt_status mark_edge(work *w, const mt_defect *d, mt_diag *diag)
{
    const uint32_t bit = BIT(d->kind), nv = w->list->num_verts;
    uint32_t *vbits = bits_of(w, MT__TOPO_POINT_DEFECTS);
    uint32_t *fbits = bits_of(w, MT__TOPO_CELL_DEFECTS);
    if (!vbits || !fbits) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    if (d->a < nv) vbits[d->a] |= bit;
    if (d->b < nv) vbits[d->b] |= bit;
    size_t n = 0;
    mt_status st = edge_faces(w, d->a, d->b, &n, diag);
    if (st != MT_OK) return st;
    const bool directed = d->kind == MT_DEFECT_SAME_DIRECTION_EDGE;
    for (size_t i = 0; i < n; i++)
        if (!directed || face_runs(w, w->faces[i], d->a, d->b)) fbits[w->faces[i]] |= bit;
    if (directed && n == 2) {
        uint8_t *consistent = flags_of(w, MT__TOPO_CELL_ORIENTATION_CONSISTENT);
        if (!consistent) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
        consistent[w->faces[0]] = consistent[w->faces[1]] = 0;
    }
    return MT_OK;
}

/* The defects of the report: vertex and face kinds on their own element,
 * edge kinds on both ends and their faces; then one sweep over the face
 * list carries vertex kinds to the faces around them and face kinds to
 * their corners. */
static mt_status mark_defects(work *w, mt_diag *diag)
{
    const mt_report *r = mt_mesh_report(w->mesh);
    if (r->num_defects == 0) return MT_OK;
    const uint32_t nv = w->list->num_verts, nf = w->list->num_faces;
    uint32_t *vbits = bits_of(w, MT__TOPO_POINT_DEFECTS);
    uint32_t *fbits = bits_of(w, MT__TOPO_CELL_DEFECTS);
    if (!vbits || !fbits) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    uint32_t spread = 0; /* kinds the face-list sweep carries */
    for (size_t i = 0; i < r->num_defects; i++) {
        const mt_defect *d = &r->defects[i];
        if (d->kind >= MT_DEFECT_KIND_COUNT) continue;
        const uint32_t bit = BIT(d->kind);
        if (bit & FACE_KINDS) {
            if (d->a < nf) fbits[d->a] |= bit;
            spread |= bit;
        } else if (bit & VERTEX_KINDS) {
            if (d->a >= nv) continue;
            vbits[d->a] |= bit;
            spread |= bit;
            if (d->kind == MT_DEFECT_NONMANIFOLD_VERTEX) {
                uint8_t *nm = flags_of(w, MT__TOPO_POINT_NON_MANIFOLD);
                if (!nm) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
                nm[d->a] = 1;
            }
        } else {
            mt_status st = mark_edge(w, d, diag);
            if (st != MT_OK) return st;
        }
    }
    /* An isolated vertex is on no kept face: nothing to carry. */
    if ((spread & ~BIT(MT_DEFECT_ISOLATED_VERTEX)) == 0) return MT_OK;
    const uint32_t *sizes = w->list->face_sizes, *indices = w->list->face_indices;
    uint64_t start = 0;
    for (uint32_t f = 0; f < nf; start += sizes[f], f++) {
        const uint32_t own = fbits[f] & FACE_KINDS;
        uint32_t around = 0;
        for (uint32_t k = 0; k < sizes[f]; k++) {
            const uint32_t v = indices[start + k];
            if (v >= nv) continue;
            around |= vbits[v];
            vbits[v] |= own;
        }
        fbits[f] |= around & VERTEX_KINDS;
    }
    return MT_OK;
}

/* Marks both faces of every pair; refuses a pair naming a face that is out
 * of range or not kept. */
static mt_status mark_self_intersections(work *w, const mt_face_pair *pairs, size_t n,
                                         mt_diag *diag)
{
    const mt_mesh_view *v = &w->view;
    if (n > 0 && !pairs)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG,
                                "%zu self-intersection pairs but none given", n);
    for (size_t i = 0; i < n; i++)
        if (pairs[i].a >= v->num_faces || pairs[i].b >= v->num_faces ||
            v->face_he[pairs[i].a] == MT_NONE || v->face_he[pairs[i].b] == MT_NONE)
            return mt__archive_fail(diag, MT_ERR_INVALID_ARG,
                                    "self-intersection pair %zu (faces %u, %u) names a face that "
                                    "is out of range or not in the mesh",
                                    i, pairs[i].a, pairs[i].b);
    w->out->present[MT__TOPO_CELL_SELF_INTERSECTING] = true;
    w->out->self_intersection_pairs = n;
    if (n == 0) return MT_OK;
    uint8_t *x = flags_of(w, MT__TOPO_CELL_SELF_INTERSECTING);
    if (!x) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < n; i++) x[pairs[i].a] = x[pairs[i].b] = 1;
    return MT_OK;
}

static mt_status compute_self_intersections(work *w, mt_diag *diag)
{
    size_t count = 0;
    mt_diag why;
    mt_status st = mt_mesh_self_intersections(w->mesh, NULL, 0, &count, &why);
    if (st == MT_ERR_NO_GEOMETRY) {
        w->out->absent_reason = "not computed: the mesh has no positions";
        return MT_OK;
    }
    if (st != MT_OK)
        return mt__archive_fail(diag, st, "finding the self-intersections failed: %s", why.message);
    if (count > SIZE_MAX / sizeof(mt_face_pair) - 1)
        return mt__archive_fail(diag, MT_ERR_NOMEM, "%zu self-intersecting pairs: out of memory",
                                count);
    mt_face_pair *pairs = malloc((count + 1) * sizeof *pairs);
    if (!pairs) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    st = mt_mesh_self_intersections(w->mesh, pairs, count, &count, &why);
    if (st == MT_OK)
        st = mark_self_intersections(w, pairs, count, diag);
    else
        mt__archive_fail(diag, st, "finding the self-intersections failed: %s", why.message);
    free(pairs);
    return st;
}

/* Per face record -> per cell: the kept faces' rows moved to the front. */
static void compact_cells(work *w)
{
    const mt_mesh_view *v = &w->view;
    for (int id = 0; id < MT__TOPO_COUNT; id++) {
        uint8_t *values = w->out->values[id];
        if (!values || !mt__topo_arrays[id].cell) continue;
        const size_t size = mt__topo_type_size(mt__topo_arrays[id].type);
        uint64_t cell = 0;
        for (uint32_t f = 0; f < v->num_faces; f++)
            if (v->face_he[f] != MT_NONE) memmove(values + cell++ * size, values + f * size, size);
    }
}

/* Drops an array whose rows all hold its fill value: written as such, it
 * costs neither space nor time. */
static void drop_constant(mt__topology *t, mt__topo_id id)
{
    const mt__topo_info *info = &mt__topo_arrays[id];
    if (!t->values[id]) return;
    const uint64_t rows = info->cell ? t->cells : t->points;
    if (info->type == MT__TOPO_UINT8) {
        const uint8_t *v = t->values[id];
        for (uint64_t i = 0; i < rows; i++)
            if (v[i] != info->fill) return;
    } else {
        /* int32 and uint32 alike: the fill is 0 or 1, the same bits in both. */
        const uint32_t *v = t->values[id];
        for (uint64_t i = 0; i < rows; i++)
            if (v[i] != info->fill) return;
    }
    free(t->values[id]);
    t->values[id] = NULL;
}

mt_status mt__topology_compute(const mt_face_list *list, const mt_mesh *mesh,
                               mt_archive_self_intersections self_intersections,
                               const mt_face_pair *pairs, size_t num_pairs, mt__topology *out,
                               mt_diag *diag)
{
    memset(out, 0, sizeof *out);
    work w;
    memset(&w, 0, sizeof w);
    w.list = list;
    w.mesh = mesh;
    w.out = out;
    mt_mesh_get_view(mesh, &w.view);
    mt_mesh_get_parts(mesh, &w.parts);
    for (uint32_t f = 0; f < w.view.num_faces; f++) out->cells += w.view.face_he[f] != MT_NONE;
    out->points = list->num_verts;
    for (int id = 0; id < MT__TOPO_COUNT; id++) out->present[id] = true;
    out->present[MT__TOPO_CELL_SELF_INTERSECTING] = false;
    out->absent_reason =
        "not computed (finding self-intersections costs about ten builds; meshtopo writes "
        "this array only when asked to)";

    mt_status st = fill_components(&w, diag);
    if (st == MT_OK) st = sweep_boundary(&w, diag);
    if (st == MT_OK) st = mark_defects(&w, diag);
    if (st == MT_OK && self_intersections == MT_ARCHIVE_SELF_INTERSECTIONS_COMPUTE)
        st = compute_self_intersections(&w, diag);
    if (st == MT_OK && self_intersections == MT_ARCHIVE_SELF_INTERSECTIONS_GIVEN)
        st = mark_self_intersections(&w, pairs, num_pairs, diag);
    free(w.faces);
    if (st != MT_OK) {
        mt__topology_free(out);
        return st;
    }
    if (out->cells < w.view.num_faces) compact_cells(&w);
    for (int id = 0; id < MT__TOPO_COUNT; id++) drop_constant(out, (mt__topo_id)id);
    return MT_OK;
}
