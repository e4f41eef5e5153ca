/* The default choice of queried elements for `meshtopo inspect --json` and
 * the Python binding's report, exactly as DEFINITIONS.md "Queries" states
 * it, so that a report without named elements reproduces a corpus reference
 * answer: first the interesting spots (non-manifold, isolated, boundary,
 * flipped), then evenly spread ids, up to 5 of each, no repeats. */
#include <stdlib.h>
#include <string.h>

#include "meshtopo/query.h"
#include "meshtopo/report_json.h"

enum { NUM_QUERIES = MT_REPORT_JSON_MAX_QUERIES };

typedef struct choice {
    uint32_t ids[NUM_QUERIES];
    size_t count;
} choice;

/* Adds id unless the choice is full, id is outside [0, limit) or already chosen. */
static void choice_add(choice *c, uint64_t id, uint64_t limit)
{
    if (c->count == NUM_QUERIES || id >= limit) return;
    for (size_t i = 0; i < c->count; i++)
        if (c->ids[i] == id) return;
    c->ids[c->count++] = (uint32_t)id;
}

static void choice_store(const choice *c, uint32_t *out_ids, size_t *out_count)
{
    memcpy(out_ids, c->ids, c->count * sizeof *out_ids);
    *out_count = c->count;
}

/* Smallest `a` among the report's defects of one kind, MT_NONE if none. */
static uint32_t defect_min_a(const mt_report *report, mt_defect_kind kind)
{
    uint32_t best = MT_NONE;
    for (size_t i = 0; i < report->num_defects; i++) {
        const mt_defect *d = &report->defects[i];
        if (d->kind == (uint32_t)kind && d->a < best) best = d->a;
    }
    return best;
}

/* What one sweep over the valid faces finds about their sides. */
typedef struct side_sweep {
    uint32_t min_face_nonmanifold;  /* smallest face on an edge used by > 2 faces */
    uint32_t min_face_inconsistent; /* smallest face on a use-2 same-direction edge */
    uint32_t min_face_boundary;     /* smallest face on an edge used once */
    uint32_t min_vert_boundary;     /* smallest vertex on such an edge */
    uint32_t *valid_faces;          /* ascending; malloc'ed */
    size_t num_valid_faces;
} side_sweep;

/* A growable list of face ids. */
typedef struct face_list_buf {
    uint32_t *ids;
    size_t capacity, count;
} face_list_buf;

/* The faces on caller edge {a, b} into buf (grown as needed); none when
 * no valid face uses the edge. */
static mt_status faces_on_edge(const mt_mesh *mesh, uint32_t a, uint32_t b, face_list_buf *buf)
{
    mt_status st = mt_edge_faces(mesh, a, b, buf->ids, buf->capacity, &buf->count);
    if (st == MT_ERR_BUFFER_TOO_SMALL || (st == MT_OK && !buf->ids)) {
        uint32_t *grown = realloc(buf->ids, (buf->count + 1) * sizeof *grown);
        if (!grown) return MT_ERR_NOMEM;
        buf->ids = grown;
        buf->capacity = buf->count + 1;
        st = mt_edge_faces(mesh, a, b, buf->ids, buf->capacity, &buf->count);
    }
    if (st == MT_ERR_NOT_FOUND) buf->count = 0;
    return st == MT_ERR_NOT_FOUND ? MT_OK : st;
}

static uint32_t smallest(const uint32_t *ids, size_t n, uint32_t best)
{
    for (size_t i = 0; i < n; i++)
        if (ids[i] < best) best = ids[i];
    return best;
}

/* The edges that matter are few: non-manifold and same-direction edges are
 * the report's defects, and a boundary edge is an internal edge with a
 * face on one side only that no other face uses. Each is looked up with
 * mt_edge_faces; no per-face query is needed. */
static mt_status sweep_sides(const mt_mesh *mesh, side_sweep *s)
{
    s->min_face_nonmanifold = s->min_face_inconsistent = MT_NONE;
    s->min_face_boundary = s->min_vert_boundary = MT_NONE;
    s->num_valid_faces = 0;
    mt_mesh_view view;
    mt_mesh_get_view(mesh, &view);
    /* calloc checks the multiplication for overflow */
    s->valid_faces = calloc((size_t)view.num_faces + 1, sizeof *s->valid_faces);
    if (!s->valid_faces) return MT_ERR_NOMEM;
    for (uint32_t f = 0; f < view.num_faces; f++)
        if (view.face_he[f] != MT_NONE) s->valid_faces[s->num_valid_faces++] = f;

    const mt_report *r = mt_mesh_report(mesh);
    face_list_buf faces = {0};
    mt_status st = MT_OK;
    for (size_t i = 0; i < r->num_defects && st == MT_OK; i++) {
        const mt_defect *d = &r->defects[i];
        if (d->kind != MT_DEFECT_NONMANIFOLD_EDGE && d->kind != MT_DEFECT_SAME_DIRECTION_EDGE)
            continue;
        st = faces_on_edge(mesh, d->a, d->b, &faces);
        if (st != MT_OK) break;
        if (faces.count > 2)
            s->min_face_nonmanifold = smallest(faces.ids, faces.count, s->min_face_nonmanifold);
        else if (faces.count == 2 && d->kind == MT_DEFECT_SAME_DIRECTION_EDGE)
            s->min_face_inconsistent = smallest(faces.ids, faces.count, s->min_face_inconsistent);
    }
    for (uint32_t h = 0; h + 1 < view.num_half_edges && st == MT_OK; h += 2) {
        if (view.he_head[h] == MT_NONE) continue; /* deleted */
        const uint32_t f0 = view.he_face[h], f1 = view.he_face[h + 1];
        if ((f0 == MT_NONE) == (f1 == MT_NONE)) continue; /* interior, or no face */
        const uint32_t a = mt_vert_original(mesh, view.he_head[h + 1]);
        const uint32_t b = mt_vert_original(mesh, view.he_head[h]);
        st = faces_on_edge(mesh, a, b, &faces);
        if (st != MT_OK || faces.count != 1) continue; /* a seam of a bundled edge */
        const uint32_t f = f0 != MT_NONE ? f0 : f1;
        if (f < s->min_face_boundary) s->min_face_boundary = f;
        if (a < s->min_vert_boundary) s->min_vert_boundary = a;
        if (b < s->min_vert_boundary) s->min_vert_boundary = b;
    }
    free(faces.ids);
    if (st != MT_OK) {
        free(s->valid_faces);
        s->valid_faces = NULL;
    }
    return st;
}

mt_status mt_report_json_default_queries(const mt_mesh *mesh,
                                         uint32_t out_verts[MT_REPORT_JSON_MAX_QUERIES],
                                         size_t *out_num_verts,
                                         uint32_t out_faces[MT_REPORT_JSON_MAX_QUERIES],
                                         size_t *out_num_faces)
{
    const bool want_vertices = out_verts && out_num_verts;
    const bool want_faces = out_faces && out_num_faces;
    if (!mesh) return MT_ERR_INVALID_ARG;
    if (!want_vertices && !want_faces) return MT_OK;
    const mt_report *report = mt_mesh_report(mesh);
    side_sweep sweep;
    mt_status st = sweep_sides(mesh, &sweep);
    if (st != MT_OK) return st;

    if (want_vertices) {
        uint64_t n = mt_mesh_num_verts(mesh);
        choice c = {{0}, 0};
        choice_add(&c, defect_min_a(report, MT_DEFECT_NONMANIFOLD_VERTEX), n);
        choice_add(&c, defect_min_a(report, MT_DEFECT_ISOLATED_VERTEX), n);
        choice_add(&c, sweep.min_vert_boundary, n);
        if (n > 0) {
            const uint64_t spread[] = {0, n / 4, n / 2, 3 * n / 4, n - 1};
            for (size_t i = 0; i < sizeof spread / sizeof spread[0]; i++)
                choice_add(&c, spread[i], n);
        }
        for (uint64_t v = 1; c.count < NUM_QUERIES && v < n; v++) choice_add(&c, v, n);
        choice_store(&c, out_verts, out_num_verts);
    }
    if (want_faces) {
        uint64_t faces = mt_mesh_num_faces(mesh);
        size_t n = sweep.num_valid_faces;
        choice c = {{0}, 0};
        choice_add(&c, sweep.min_face_nonmanifold, faces);
        choice_add(&c, sweep.min_face_inconsistent, faces);
        choice_add(&c, sweep.min_face_boundary, faces);
        if (n > 0) {
            /* positions 0, n//4, n//2, 3n//4, n-1 (3n//4 written so 3n cannot overflow) */
            const size_t spread[] = {0, n / 4, n / 2, 3 * (n / 4) + (3 * (n % 4)) / 4, n - 1};
            for (size_t i = 0; i < sizeof spread / sizeof spread[0]; i++)
                choice_add(&c, sweep.valid_faces[spread[i]], faces);
        }
        for (size_t p = 1; c.count < NUM_QUERIES && p < n; p++)
            choice_add(&c, sweep.valid_faces[p], faces);
        choice_store(&c, out_faces, out_num_faces);
    }
    free(sweep.valid_faces);
    return MT_OK;
}
