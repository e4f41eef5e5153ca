/* meshtopod's queries (query.h): one query_t answered with one reply_t, every
 * id of the batch in it as two-level CSR (items -> groups -> values, values2,
 * reals), exactly what the core library's query and geometry functions
 * (meshtopo/query.h, meshtopo/geometry.h) answer; the table in
 * msgs/reply_t.lcm says what each kind puts where. Every id is checked before
 * anything is answered: one id out of range gives OUT_OF_RANGE and no items.
 * Runs on the LCM thread; it only reads immutable store entries, so a build
 * never holds it up, and a sender over its share of that thread's time is
 * answered BUSY (fair_share.h). A version that must first be loaded from the store's
 * backing is fetched, and the query answered, on a worker. */
#include "query.h"

#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "fair_share.h"
#include "log.h"
#include "meshtopo/geometry.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"
#include "topology.h"

struct mtd_queries {
    mtd_store *store;
    mtd_pool *pool;
    mtd_replies *replies;
    mtd_cluster *cluster;  /* NULL without --cluster */
    mtd_fair_share *share; /* the LCM thread's time, per reply channel */
    /* Self-intersection checks handed to a worker and not yet answered:
     * at most one, so that senders asking for them (any node may) never
     * hold more than one worker away from the builds. */
    atomic_uint self_checks;
};

/* A growable array of int32_t (int8_t ones are stored widened, then narrowed). */
typedef struct ivec {
    int32_t *v;
    size_t n, cap;
} ivec;

/* The answer being built, and the first error met while building it. */
typedef struct answer {
    ivec item_status, item_offsets, group_boundary, value_offsets, value2_offsets, values, values2;
    double *reals; /* the geometry kinds' real values (reply_t.reals) */
    size_t num_reals, reals_cap;
    size_t bytes;
    int32_t status;
    char error[MTD_ERROR_MAX];
} answer;

static void fail(answer *a, int32_t status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static void fail(answer *a, int32_t status, const char *fmt, ...)
{
    if (a->status != MESHTOPO_STATUS_CODE_T_OK) return;
    a->status = status;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(a->error, sizeof a->error, fmt, ap);
    va_end(ap);
}

static void push(answer *a, ivec *vec, int32_t value)
{
    if (a->status != MESHTOPO_STATUS_CODE_T_OK) return;
    if (vec->n == vec->cap) {
        a->bytes += vec->cap * sizeof(int32_t);
        if (a->bytes > MTD_REPLY_MAX_BYTES) {
            fail(a, MESHTOPO_STATUS_CODE_T_TOO_LARGE,
                 "the answer exceeds the daemon's reply limit of %u bytes; ask for fewer ids",
                 (unsigned)MTD_REPLY_MAX_BYTES);
            return;
        }
        size_t cap = vec->cap ? 2 * vec->cap : 64;
        int32_t *v = realloc(vec->v, cap * sizeof *v);
        if (!v) {
            fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory building the answer");
            return;
        }
        vec->v = v;
        vec->cap = cap;
    }
    vec->v[vec->n++] = value;
}

static void push_real(answer *a, double value)
{
    if (a->status != MESHTOPO_STATUS_CODE_T_OK) return;
    if (a->num_reals == a->reals_cap) {
        a->bytes += a->reals_cap * sizeof(double);
        if (a->bytes > MTD_REPLY_MAX_BYTES) {
            fail(a, MESHTOPO_STATUS_CODE_T_TOO_LARGE,
                 "the answer exceeds the daemon's reply limit of %u bytes; ask for fewer ids",
                 (unsigned)MTD_REPLY_MAX_BYTES);
            return;
        }
        size_t cap = a->reals_cap ? 2 * a->reals_cap : 64;
        double *v = realloc(a->reals, cap * sizeof *v);
        if (!v) {
            fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory building the answer");
            return;
        }
        a->reals = v;
        a->reals_cap = cap;
    }
    a->reals[a->num_reals++] = value;
}

static void answer_init(answer *a)
{
    memset(a, 0, sizeof *a);
    a->status = MESHTOPO_STATUS_CODE_T_OK;
    push(a, &a->item_offsets, 0);
    push(a, &a->value_offsets, 0);
    push(a, &a->value2_offsets, 0);
}

static void answer_free(answer *a)
{
    ivec *vecs[] = {&a->item_status,    &a->item_offsets, &a->group_boundary, &a->value_offsets,
                    &a->value2_offsets, &a->values,       &a->values2};
    for (size_t i = 0; i < sizeof vecs / sizeof vecs[0]; i++) free(vecs[i]->v);
    free(a->reals);
}

/* Ends a group of the current item. */
static void group_end(answer *a, bool boundary)
{
    push(a, &a->group_boundary, boundary);
    push(a, &a->value_offsets, (int32_t)a->values.n);
    push(a, &a->value2_offsets, (int32_t)a->values2.n);
}

/* Ends an item whose groups were just added. */
static void item_end(answer *a, int32_t item_status)
{
    push(a, &a->item_status, item_status);
    push(a, &a->item_offsets, (int32_t)a->group_boundary.n);
}

static void fail_core(answer *a, mt_status s, const char *what, int32_t id)
{
    fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "%s of %" PRId32 ": %s", what, id, mt_strerror(s));
}

/* Grows a uint32_t buffer to hold at least `need` elements. */
static bool reserve_u32(answer *a, uint32_t **buf, size_t *cap, size_t need)
{
    if (need <= *cap) return true;
    if (need > MTD_REPLY_MAX_BYTES / sizeof(uint32_t)) {
        fail(a, MESHTOPO_STATUS_CODE_T_TOO_LARGE, "the answer exceeds the daemon's reply limit");
        return false;
    }
    uint32_t *p = realloc(*buf, need * sizeof *p);
    if (!p) {
        fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory building the answer");
        return false;
    }
    *buf = p;
    *cap = need;
    return true;
}

static void answer_rings(answer *a, const mt_mesh *mesh, const int32_t *ids, int32_t n)
{
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    for (int32_t i = 0; i < n && a->status == MESHTOPO_STATUS_CODE_T_OK; i++) {
        mt_status s = mt_vert_ring(mesh, (uint32_t)ids[i], &ring);
        /* NULL buffers only learn the sizes, even when the call says MT_OK. */
        if (s == MT_ERR_BUFFER_TOO_SMALL ||
            (s == MT_OK &&
             (ring.num_fans > ring.fans_capacity || ring.num_neighbors > ring.neighbors_capacity ||
              ring.num_faces > ring.faces_capacity))) {
            mt_fan *fans = realloc(ring.fans, ring.num_fans * sizeof *fans);
            if (!fans && ring.num_fans) {
                fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory building the answer");
                break;
            }
            if (fans) ring.fans = fans, ring.fans_capacity = ring.num_fans;
            if (!reserve_u32(a, &ring.neighbors, &ring.neighbors_capacity, ring.num_neighbors) ||
                !reserve_u32(a, &ring.faces, &ring.faces_capacity, ring.num_faces))
                break;
            s = mt_vert_ring(mesh, (uint32_t)ids[i], &ring);
        }
        if (s != MT_OK) {
            fail_core(a, s, "one-ring", ids[i]);
            break;
        }
        for (size_t f = 0; f < ring.num_fans; f++) {
            const mt_fan *fan = &ring.fans[f];
            for (uint32_t k = 0; k < fan->neighbor_count; k++)
                push(a, &a->values, (int32_t)ring.neighbors[fan->neighbor_begin + k]);
            for (uint32_t k = 0; k < fan->face_count; k++)
                push(a, &a->values2, (int32_t)ring.faces[fan->face_begin + k]);
            group_end(a, fan->boundary);
        }
        item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
    free(ring.neighbors);
    free(ring.faces);
    free(ring.fans);
}

static void answer_valences(answer *a, const mt_mesh *mesh, const int32_t *ids, int32_t n)
{
    for (int32_t i = 0; i < n && a->status == MESHTOPO_STATUS_CODE_T_OK; i++) {
        uint32_t valence = 0;
        mt_status s = mt_vert_valence(mesh, (uint32_t)ids[i], &valence);
        if (s != MT_OK) {
            fail_core(a, s, "valence", ids[i]);
            break;
        }
        push(a, &a->values, (int32_t)valence);
        group_end(a, false);
        item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
}

static void answer_face_neighbors(answer *a, const mt_mesh *mesh, const int32_t *ids, int32_t n)
{
    uint32_t *faces = NULL, *offsets = NULL, *verts = NULL;
    size_t faces_cap = 0, offsets_cap = 0, verts_cap = 0;
    for (int32_t i = 0; i < n && a->status == MESHTOPO_STATUS_CODE_T_OK; i++) {
        uint32_t face = (uint32_t)ids[i];
        size_t num_faces = 0, num_sides = 0, num_verts = 0;
        mt_status s = mt_face_neighbors(mesh, face, faces, faces_cap, offsets, offsets_cap,
                                        &num_faces, &num_sides);
        if (s == MT_ERR_BUFFER_TOO_SMALL ||
            (s == MT_OK && (num_faces > faces_cap || num_sides + 1 > offsets_cap))) {
            if (!reserve_u32(a, &faces, &faces_cap, num_faces) ||
                !reserve_u32(a, &offsets, &offsets_cap, num_sides + 1))
                break;
            s = mt_face_neighbors(mesh, face, faces, faces_cap, offsets, offsets_cap, &num_faces,
                                  &num_sides);
        }
        if (s == MT_ERR_NOT_FOUND) {
            item_end(a, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
            continue;
        }
        if (s == MT_OK) {
            s = mt_face_verts(mesh, face, verts, verts_cap, &num_verts);
            if (s == MT_ERR_BUFFER_TOO_SMALL || (s == MT_OK && num_verts > verts_cap)) {
                if (!reserve_u32(a, &verts, &verts_cap, num_verts)) break;
                s = mt_face_verts(mesh, face, verts, verts_cap, &num_verts);
            }
        }
        if (s != MT_OK || num_verts != num_sides) {
            fail_core(a, s == MT_OK ? MT_ERR_CORRUPT : s, "face neighbours", ids[i]);
            break;
        }
        for (size_t k = 0; k < num_sides; k++) {
            for (uint32_t j = offsets[k]; j < offsets[k + 1]; j++)
                push(a, &a->values, (int32_t)faces[j]);
            push(a, &a->values2, (int32_t)verts[k]);
            push(a, &a->values2, (int32_t)verts[(k + 1) % num_sides]);
            group_end(a, offsets[k] == offsets[k + 1]);
        }
        item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
    free(faces);
    free(offsets);
    free(verts);
}

static void answer_edge_faces(answer *a, const mt_mesh *mesh, const int32_t *ids, int32_t n)
{
    uint32_t *faces = NULL;
    size_t cap = 0;
    for (int32_t i = 0; i + 1 < n && a->status == MESHTOPO_STATUS_CODE_T_OK; i += 2) {
        size_t count = 0;
        mt_status s =
            mt_edge_faces(mesh, (uint32_t)ids[i], (uint32_t)ids[i + 1], faces, cap, &count);
        if (s == MT_ERR_BUFFER_TOO_SMALL || (s == MT_OK && count > cap)) {
            if (!reserve_u32(a, &faces, &cap, count)) break;
            s = mt_edge_faces(mesh, (uint32_t)ids[i], (uint32_t)ids[i + 1], faces, cap, &count);
        }
        if (s == MT_ERR_NOT_FOUND) {
            item_end(a, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
            continue;
        }
        if (s != MT_OK) {
            fail_core(a, s, "edge faces at vertex", ids[i]);
            break;
        }
        for (size_t k = 0; k < count; k++) push(a, &a->values, (int32_t)faces[k]);
        group_end(a, false);
        item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
    free(faces);
}

static void answer_boundary_loops(answer *a, const mt_mesh *mesh)
{
    size_t num_verts = 0, num_loops = 0;
    mt_status s = mt_boundary_loops(mesh, NULL, 0, NULL, 0, &num_verts, &num_loops);
    uint32_t *verts = NULL, *offsets = NULL;
    size_t verts_cap = 0, offsets_cap = 0;
    if (s == MT_ERR_BUFFER_TOO_SMALL || s == MT_OK) {
        if (!reserve_u32(a, &verts, &verts_cap, num_verts ? num_verts : 1) ||
            !reserve_u32(a, &offsets, &offsets_cap, num_loops + 1))
            goto done;
        s = mt_boundary_loops(mesh, verts, verts_cap, offsets, offsets_cap, &num_verts, &num_loops);
    }
    if (s != MT_OK) {
        fail_core(a, s, "boundary loops", 0);
        goto done;
    }
    for (size_t l = 0; l < num_loops; l++) {
        for (uint32_t k = offsets[l]; k < offsets[l + 1]; k++)
            push(a, &a->values, (int32_t)verts[k]);
        group_end(a, true);
        item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
done:
    free(verts);
    free(offsets);
}

static void answer_component(answer *a, const mt_mesh *mesh, uint32_t face)
{
    uint32_t component = 0;
    mt_status s = mt_face_component(mesh, face, &component);
    if (s == MT_ERR_NOT_FOUND) {
        item_end(a, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
        return;
    }
    if (s != MT_OK) {
        fail_core(a, s, "component", (int32_t)face);
        return;
    }
    push(a, &a->values, (int32_t)component);
    group_end(a, false);
    item_end(a, MESHTOPO_STATUS_CODE_T_OK);
}

static void answer_components(answer *a, const mt_mesh *mesh, const int32_t *ids, int32_t n)
{
    if (n == 0) {
        uint32_t faces = mt_mesh_num_faces(mesh);
        for (uint32_t f = 0; f < faces && a->status == MESHTOPO_STATUS_CODE_T_OK; f++)
            answer_component(a, mesh, f);
    }
    for (int32_t i = 0; i < n && a->status == MESHTOPO_STATUS_CODE_T_OK; i++)
        answer_component(a, mesh, (uint32_t)ids[i]);
}

static void answer_defect_kind(answer *a, const mt_report *report, uint32_t kind)
{
    for (size_t i = 0; i < report->num_defects; i++) {
        const mt_defect *d = &report->defects[i];
        if (d->kind != kind) continue;
        push(a, &a->values, (int32_t)d->a);
        push(a, &a->values, (int32_t)d->b);
        push(a, &a->values, (int32_t)d->c);
    }
    group_end(a, false);
    item_end(a, MESHTOPO_STATUS_CODE_T_OK);
}

static void answer_defects(answer *a, const mt_mesh *mesh, const int32_t *ids, int32_t n)
{
    const mt_report *report = mt_mesh_report(mesh);
    if (n == 0)
        for (uint32_t k = 0; k < MT_DEFECT_KIND_COUNT; k++) answer_defect_kind(a, report, k);
    for (int32_t i = 0; i < n; i++) answer_defect_kind(a, report, (uint32_t)ids[i]);
}

/* ---- geometry (meshtopo/geometry.h) ---------------------------------------- */

/* A geometry call's failure: NO_GEOMETRY for a mesh without positions. */
static void fail_geometry(answer *a, mt_status s, const char *what, int32_t id)
{
    if (s == MT_ERR_NO_GEOMETRY)
        fail(a, MESHTOPO_STATUS_CODE_T_NO_GEOMETRY, "%s: the mesh was submitted without positions",
             what);
    else
        fail_core(a, s, what, id);
}

static void answer_dihedral_angles(answer *a, const mt_mesh *mesh, const int32_t *ids, int32_t n)
{
    for (int32_t i = 0; i + 1 < n && a->status == MESHTOPO_STATUS_CODE_T_OK; i += 2) {
        uint32_t u = (uint32_t)ids[i], v = (uint32_t)ids[i + 1];
        mt_edge_shape shape = MT_EDGE_BOUNDARY;
        mt_status s =
            mt_edge_convexity(mesh, u, v, MESHTOPO_QUERY_T_GEOMETRY_TOLERANCE, &shape, NULL);
        if (s == MT_ERR_NOT_FOUND) {
            push_real(a, NAN);
            item_end(a, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
            continue;
        }
        double angle = NAN;
        if (s == MT_OK && shape <= MT_EDGE_REFLEX)
            s = mt_edge_dihedral_angle(mesh, u, v, &angle, NULL);
        if (s != MT_OK) {
            fail_geometry(a, s, "dihedral angle at vertex", ids[i]);
            break;
        }
        push(a, &a->values, (int32_t)shape);
        push_real(a, angle);
        group_end(a, false);
        item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
}

static void answer_angle_deficits(answer *a, const mt_mesh *mesh, const int32_t *ids, int32_t n)
{
    for (int32_t i = 0; i < n && a->status == MESHTOPO_STATUS_CODE_T_OK; i++) {
        double deficit = 0.0;
        bool boundary = false;
        mt_status s = mt_vert_angle_deficit(mesh, (uint32_t)ids[i], &deficit, &boundary, NULL);
        if (s != MT_OK) {
            fail_geometry(a, s, "angle deficit of vertex", ids[i]);
            break;
        }
        push_real(a, deficit);
        group_end(a, boundary);
        item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
}

static void answer_convexity(answer *a, const mt_mesh *mesh)
{
    mt_convexity c;
    const double tolerance = MESHTOPO_QUERY_T_GEOMETRY_TOLERANCE;
    mt_status s = mt_mesh_convexity(mesh, tolerance, &c, NULL, 0, NULL);
    uint32_t *edges = NULL;
    size_t cap = 0;
    if (s == MT_OK || s == MT_ERR_BUFFER_TOO_SMALL) {
        if (!reserve_u32(a, &edges, &cap, 2 * c.num_reflex + 1)) return;
        s = mt_mesh_convexity(mesh, tolerance, &c, edges, c.num_reflex, NULL);
    }
    if (s != MT_OK) {
        fail_geometry(a, s, "convexity of the mesh", 0);
        free(edges);
        return;
    }
    push(a, &a->values, c.convex ? 1 : 0);
    push(a, &a->values, (int32_t)c.reasons);
    push(a, &a->values, (int32_t)c.num_reflex);
    push(a, &a->values, (int32_t)c.num_degenerate);
    group_end(a, false);
    for (size_t k = 0; k < 2 * c.num_reflex; k++) push(a, &a->values, (int32_t)edges[k]);
    group_end(a, false);
    push_real(a, c.volume);
    item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    free(edges);
}

/* A whole-mesh geometry list of meshtopo/geometry.h (self-intersecting
 * pairs, non-simple faces, self-crossing loops), with its element size. */
typedef struct geometry_list {
    mt_status (*query)(const mt_mesh *mesh, void *out, size_t capacity, size_t *out_count,
                       mt_diag *diag);
    size_t elem_size;
    const char *what;
} geometry_list;

/* Exact tests of two triangles a self-intersection check may take: a
 * surface needs a few per face, while n faces piled on one another need
 * n^2/2, crossing or not, and would hold a worker and the daemon's
 * shutdown for as long as that takes. */
#define SELFX_TESTS_PER_FACE 32u
#define SELFX_TESTS_BASE ((uint64_t)1 << 20)

/* At most the pairs a reply carries (n faces piled at one place make n^2/2
 * pairs, which the check would otherwise gather before counting) and the
 * tests above. */
static mt_status self_intersections_list(const mt_mesh *m, void *out, size_t cap, size_t *n,
                                         mt_diag *d)
{
    const uint64_t tests = SELFX_TESTS_BASE + (uint64_t)SELFX_TESTS_PER_FACE * mt_mesh_num_faces(m);
    return mt_mesh_self_intersections_at_most(m, MTD_REPLY_MAX_BYTES / sizeof(mt_face_pair), tests,
                                              out, cap, n, d);
}

static mt_status nonsimple_faces_list(const mt_mesh *m, void *out, size_t cap, size_t *n,
                                      mt_diag *d)
{
    return mt_mesh_nonsimple_faces(m, out, cap, n, d);
}

static mt_status loop_crossings_list(const mt_mesh *m, void *out, size_t cap, size_t *n, mt_diag *d)
{
    return mt_mesh_boundary_loop_crossings(m, out, cap, n, d);
}

/* The list into a new array (NULL on failure, reported in a): asked first
 * with room for a few elements, again with room for all only when they do
 * not fit, so the whole-mesh check usually runs once. */
static void *fetch_list(answer *a, const mt_mesh *mesh, const geometry_list *list, size_t *count)
{
    const size_t most = MTD_REPLY_MAX_BYTES / list->elem_size;
    size_t cap = 256;
    void *items = malloc(cap * list->elem_size);
    mt_diag diag;
    mt_status s = items ? list->query(mesh, items, cap, count, &diag) : MT_ERR_NOMEM;
    if (s == MT_ERR_BUFFER_TOO_SMALL && *count <= most) {
        void *all = realloc(items, *count * list->elem_size);
        s = all ? list->query(mesh, all, *count, count, &diag) : MT_ERR_NOMEM;
        items = all ? all : items;
    }
    if (s == MT_ERR_BUFFER_TOO_SMALL)
        fail(a, MESHTOPO_STATUS_CODE_T_TOO_LARGE,
             "more than %zu %s: they exceed the daemon's reply limit of %u bytes", most, list->what,
             (unsigned)MTD_REPLY_MAX_BYTES);
    else if (s == MT_ERR_TOO_LARGE) /* a bound the query was given: its message names it */
        fail(a, MESHTOPO_STATUS_CODE_T_TOO_LARGE, "%s", diag.message);
    else if (s != MT_OK)
        fail_geometry(a, s, list->what, 0);
    if (s != MT_OK) {
        free(items);
        return NULL;
    }
    return items;
}

/* SELF_INTERSECTIONS: three groups (msgs/reply_t.lcm), reals the warps. */
static void answer_self_intersections(answer *a, const mt_mesh *mesh)
{
    static const geometry_list pairs_list = {self_intersections_list, sizeof(mt_face_pair),
                                             "self-intersecting face pairs"};
    static const geometry_list faces_list = {nonsimple_faces_list, sizeof(mt_face_shape),
                                             "non-simple faces"};
    static const geometry_list loops_list = {loop_crossings_list, sizeof(mt_loop_crossing),
                                             "self-crossing boundary loops"};
    size_t num_pairs = 0, num_faces = 0, num_loops = 0;
    mt_face_pair *pairs = fetch_list(a, mesh, &pairs_list, &num_pairs);
    mt_face_shape *faces = pairs ? fetch_list(a, mesh, &faces_list, &num_faces) : NULL;
    mt_loop_crossing *loops = faces ? fetch_list(a, mesh, &loops_list, &num_loops) : NULL;
    if (loops) {
        for (size_t i = 0; i < num_pairs; i++) {
            push(a, &a->values, (int32_t)pairs[i].a);
            push(a, &a->values, (int32_t)pairs[i].b);
        }
        group_end(a, false);
        for (size_t i = 0; i < num_faces; i++) {
            const bool crossing = faces[i].kind == MT_FACE_SELF_CROSSING;
            push(a, &a->values, (int32_t)faces[i].face);
            push(a, &a->values, (int32_t)faces[i].kind);
            push(a, &a->values, crossing ? (int32_t)faces[i].side_a : -1);
            push(a, &a->values, crossing ? (int32_t)faces[i].side_b : -1);
            push_real(a, faces[i].warp);
        }
        group_end(a, false);
        for (size_t i = 0; i < num_loops; i++) {
            push(a, &a->values, (int32_t)loops[i].loop);
            for (int k = 0; k < 2; k++) push(a, &a->values, (int32_t)loops[i].edge_a[k]);
            for (int k = 0; k < 2; k++) push(a, &a->values, (int32_t)loops[i].edge_b[k]);
        }
        group_end(a, false);
        item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
    free(pairs);
    free(faces);
    free(loops);
}

/* Checks the ids against what the kind takes and the mesh's counts. */
static void check_ids(answer *a, const meshtopo_query_t *q, const mt_mesh *mesh)
{
    uint32_t verts = mt_mesh_num_verts(mesh), faces = mt_mesh_num_faces(mesh);
    uint32_t limit = 0;
    const char *what = "", *whats = "";
    switch (q->kind) {
        case MESHTOPO_QUERY_T_VERTEX_RING:
        case MESHTOPO_QUERY_T_VALENCE:
        case MESHTOPO_QUERY_T_EDGE_FACES:
        case MESHTOPO_QUERY_T_DIHEDRAL_ANGLES:
        case MESHTOPO_QUERY_T_ANGLE_DEFICITS:
            limit = verts, what = "vertex", whats = "vertices";
            break;
        case MESHTOPO_QUERY_T_FACE_NEIGHBORS:
        case MESHTOPO_QUERY_T_COMPONENTS:
            limit = faces, what = "face", whats = "faces";
            break;
        default:
            return;
    }
    for (int32_t i = 0; i < q->num_ids; i++) {
        if ((uint32_t)q->ids[i] >= limit) {
            fail(a, MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE,
                 "ids[%" PRId32 "] = %" PRId32 ": no such %s (mesh '%s' has %" PRIu32 " %s)", i,
                 q->ids[i], what, q->mesh_id, limit, whats);
            return;
        }
    }
}

/* Checks the kind and the shape of the ids (not their range). */
static void check_request(answer *a, const meshtopo_query_t *q)
{
    switch (q->kind) {
        case MESHTOPO_QUERY_T_VERTEX_RING:
        case MESHTOPO_QUERY_T_VALENCE:
        case MESHTOPO_QUERY_T_FACE_NEIGHBORS:
        case MESHTOPO_QUERY_T_EDGE_FACES:
        case MESHTOPO_QUERY_T_DIHEDRAL_ANGLES:
        case MESHTOPO_QUERY_T_ANGLE_DEFICITS:
            if (q->num_ids == 0)
                fail(a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "ids: kind %" PRId32 " needs ids",
                     q->kind);
            else if ((q->kind == MESHTOPO_QUERY_T_EDGE_FACES ||
                      q->kind == MESHTOPO_QUERY_T_DIHEDRAL_ANGLES) &&
                     q->num_ids % 2)
                fail(a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST,
                     "ids: kind %" PRId32 " takes vertex pairs, got an odd count (%" PRId32 ")",
                     q->kind, q->num_ids);
            break;
        case MESHTOPO_QUERY_T_BOUNDARY_LOOPS:
        case MESHTOPO_QUERY_T_REPORT:
        case MESHTOPO_QUERY_T_LIST_MESHES:
        case MESHTOPO_QUERY_T_CONVEXITY:
        case MESHTOPO_QUERY_T_SELF_INTERSECTIONS:
            if (q->num_ids != 0)
                fail(a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST,
                     "ids: kind %" PRId32 " takes no ids, got %" PRId32, q->kind, q->num_ids);
            break;
        case MESHTOPO_QUERY_T_COMPONENTS:
            break;
        case MESHTOPO_QUERY_T_DEFECTS:
            for (int32_t i = 0; i < q->num_ids; i++)
                if (q->ids[i] < 0 || q->ids[i] >= (int32_t)MT_DEFECT_KIND_COUNT) {
                    fail(a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST,
                         "ids[%" PRId32 "] = %" PRId32 ": not a topology_t.DEFECT_* kind (0..%d)",
                         i, q->ids[i], (int)MT_DEFECT_KIND_COUNT - 1);
                    break;
                }
            break;
        default:
            fail(a, MESHTOPO_STATUS_CODE_T_UNKNOWN_KIND,
                 "kind: %" PRId32 " is not a query_t kind (1..13)", q->kind);
    }
    if (a->status == MESHTOPO_STATUS_CODE_T_OK && q->version < 0)
        fail(a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "version: %" PRId32 " is negative", q->version);
}

/* Publishes the finished answer (or its error). */
static void send_answer(mtd_replies *replies, const meshtopo_query_t *q, answer *a, int32_t version,
                        meshtopo_topology_t *report, meshtopo_reply_t *list)
{
    if (a->status != MESHTOPO_STATUS_CODE_T_OK) {
        bool remember = a->status != MESHTOPO_STATUS_CODE_T_INTERNAL;
        if (!remember)
            mtd_reply_abandon(replies, q->reply_channel, q->request_id, &mt_msgs_type_reply);
        mtd_reply_query_error(replies, q->reply_channel, q->request_id, q->mesh_id, q->kind,
                              remember, a->status, a->error);
        return;
    }
    meshtopo_reply_t reply;
    if (list)
        reply = *list;
    else
        memset(&reply, 0, sizeof reply);
    int8_t *item_status = malloc(a->item_status.n + 1);
    int8_t *boundary = malloc(a->group_boundary.n + 1);
    if (!item_status || !boundary) {
        free(item_status);
        free(boundary);
        mtd_reply_abandon(replies, q->reply_channel, q->request_id, &mt_msgs_type_reply);
        mtd_reply_query_error(replies, q->reply_channel, q->request_id, q->mesh_id, q->kind, false,
                              MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory sending the answer");
        return;
    }
    for (size_t i = 0; i < a->item_status.n; i++) item_status[i] = (int8_t)a->item_status.v[i];
    for (size_t i = 0; i < a->group_boundary.n; i++) boundary[i] = (int8_t)a->group_boundary.v[i];
    reply.utime = mtd_now_utime();
    reply.request_id = q->request_id;
    reply.status = MESHTOPO_STATUS_CODE_T_OK;
    reply.error = "";
    reply.mesh_id = q->mesh_id;
    reply.version = version;
    reply.kind = q->kind;
    reply.num_items = (int32_t)a->item_status.n;
    reply.item_status = item_status;
    reply.num_item_offsets = (int32_t)a->item_offsets.n;
    reply.item_offsets = a->item_offsets.v;
    reply.num_groups = (int32_t)a->group_boundary.n;
    reply.group_boundary = boundary;
    reply.num_value_offsets = (int32_t)a->value_offsets.n;
    reply.value_offsets = a->value_offsets.v;
    reply.value2_offsets = a->value2_offsets.v;
    reply.num_values = (int32_t)a->values.n;
    reply.values = a->values.v;
    reply.num_values2 = (int32_t)a->values2.n;
    reply.values2 = a->values2.v;
    reply.num_reals = (int32_t)a->num_reals;
    reply.reals = a->reals;
    reply.num_reports = report ? 1 : 0;
    reply.reports = report;
    mtd_reply_send(replies, q->reply_channel, q->request_id, true, &mt_msgs_type_reply, &reply,
                   MESHTOPO_STATUS_CODE_T_OK, "");
    free(item_status);
    free(boundary);
}

/* Whether a listing shows `id`: the one asked for, or every id this
 * member owns. */
static bool listed(mtd_cluster *cluster, const char *mesh_id, const char *id)
{
    return mesh_id[0] ? strcmp(mesh_id, id) == 0 : mtd_cluster_owns(cluster, id);
}

/* LIST_MESHES: fills the list_* arrays of *out (freed by free_list). */
static void list_meshes(mtd_store *store, mtd_cluster *cluster, answer *a, const char *mesh_id,
                        meshtopo_reply_t *out)
{
    memset(out, 0, sizeof *out);
    mtd_store_listing *listing = NULL;
    if (mtd_store_list(store, &listing) != MT_OK) {
        fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory listing the meshes");
        return;
    }
    size_t n = 0;
    for (size_t i = 0; i < listing->num_ids; i++)
        if (listed(cluster, mesh_id, listing->ids[i].id)) n += listing->ids[i].num_versions;
    out->list_mesh_ids = calloc(n + 1, sizeof(char *));
    out->list_versions = calloc(n + 1, sizeof(int32_t));
    out->list_sources = calloc(n + 1, sizeof(char *));
    out->list_utimes = calloc(n + 1, sizeof(int64_t));
    out->list_num_verts = calloc(n + 1, sizeof(int32_t));
    out->list_num_faces = calloc(n + 1, sizeof(int32_t));
    out->list_num_defects = calloc(n + 1, sizeof(int64_t));
    out->list_content_hashes = calloc(n + 1, sizeof(int64_t));
    if (!out->list_mesh_ids || !out->list_versions || !out->list_sources || !out->list_utimes ||
        !out->list_num_verts || !out->list_num_faces || !out->list_num_defects ||
        !out->list_content_hashes) {
        fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory listing the meshes");
        mtd_store_listing_free(listing);
        return;
    }
    size_t k = 0;
    for (size_t i = 0; i < listing->num_ids && k < n; i++) {
        const mtd_listed_id *id = &listing->ids[i];
        if (!listed(cluster, mesh_id, id->id)) continue;
        for (uint32_t v = 0; v < id->num_versions && k < n; v++) {
            const mtd_mesh_info *info = &id->versions[v];
            out->list_mesh_ids[k] = strdup(info->id);
            out->list_sources[k] = strdup(info->source);
            out->list_versions[k] = (int32_t)info->version;
            out->list_utimes[k] = info->utime;
            out->list_content_hashes[k] = (int64_t)info->content_hash;
            out->list_num_verts[k] = (int32_t)info->num_verts;
            out->list_num_faces[k] = (int32_t)info->num_faces;
            out->list_num_defects[k] = (int64_t)info->num_defects;
            if (!out->list_mesh_ids[k] || !out->list_sources[k])
                fail(a, MESHTOPO_STATUS_CODE_T_INTERNAL, "out of memory listing the meshes");
            k++;
        }
    }
    out->num_meshes = (int32_t)k;
    mtd_store_listing_free(listing);
}

static void free_list(meshtopo_reply_t *list)
{
    for (int32_t i = 0; list->list_mesh_ids && i < list->num_meshes; i++) {
        free(list->list_mesh_ids[i]);
        free(list->list_sources[i]);
    }
    free(list->list_mesh_ids);
    free(list->list_versions);
    free(list->list_sources);
    free(list->list_utimes);
    free(list->list_num_verts);
    free(list->list_num_faces);
    free(list->list_num_defects);
    free(list->list_content_hashes);
}

/* Answers q from the store; on the LCM thread (may_load false) a version to
 * load first sends q to a worker. */
static void answer_query(mtd_queries *qs, const meshtopo_query_t *q, bool may_load);

typedef struct load_job {
    mtd_queries *queries;
    meshtopo_query_t *query; /* a copy */
} load_job;

static void load_job_run(void *arg, bool cancelled)
{
    load_job *job = arg;
    const meshtopo_query_t *q = job->query;
    if (cancelled) {
        /* A self-intersection check's turn ends before its answer goes
         * out, so that asking again on the answer is not told it runs. */
        if (q->kind == MESHTOPO_QUERY_T_SELF_INTERSECTIONS)
            atomic_fetch_sub(&job->queries->self_checks, 1);
        mtd_reply_abandon(job->queries->replies, q->reply_channel, q->request_id,
                          &mt_msgs_type_reply);
        mtd_reply_query_error(job->queries->replies, q->reply_channel, q->request_id, q->mesh_id,
                              q->kind, false, MESHTOPO_STATUS_CODE_T_BUSY,
                              "the daemon is shutting down; the mesh was not loaded");
    } else {
        answer_query(job->queries, q, true);
    }
    meshtopo_query_t_destroy(job->query);
    free(job);
}

/* Hands q to a worker that loads its version and answers. false when it
 * cannot (out of memory, the pool full or stopping). */
static bool defer_to_worker(mtd_queries *qs, const meshtopo_query_t *q)
{
    load_job *job = calloc(1, sizeof *job);
    meshtopo_query_t *copy = job ? meshtopo_query_t_copy(q) : NULL;
    if (!copy) {
        free(job);
        return false;
    }
    job->queries = qs;
    job->query = copy;
    if (mtd_pool_submit(qs->pool, load_job_run, job) != MTD_SUBMIT_OK) {
        meshtopo_query_t_destroy(copy);
        free(job);
        return false;
    }
    return true;
}

static void answer_query(mtd_queries *qs, const meshtopo_query_t *q, bool may_load)
{
    answer a;
    answer_init(&a);
    check_request(&a, q);
    if (a.status == MESHTOPO_STATUS_CODE_T_OK && q->kind == MESHTOPO_QUERY_T_LIST_MESHES) {
        meshtopo_reply_t list;
        list_meshes(qs->store, qs->cluster, &a, q->mesh_id, &list);
        send_answer(qs->replies, q, &a, 0, NULL, &list);
        free_list(&list);
        answer_free(&a);
        return;
    }
    /* The self-intersection check takes long enough on a large mesh to hold
     * up every other request on the LCM thread: a worker answers it, one
     * check at a time, or nobody when that one or every worker is taken. */
    if (a.status == MESHTOPO_STATUS_CODE_T_OK && !may_load &&
        q->kind == MESHTOPO_QUERY_T_SELF_INTERSECTIONS) {
        if (atomic_fetch_add(&qs->self_checks, 1) == 0 && defer_to_worker(qs, q)) {
            answer_free(&a);
            return;
        }
        atomic_fetch_sub(&qs->self_checks, 1);
        fail(&a, MESHTOPO_STATUS_CODE_T_BUSY,
             "a self-intersection check is running or every worker is busy; ask again later");
    }
    mtd_mesh_entry *entry = NULL;
    if (a.status == MESHTOPO_STATUS_CODE_T_OK) {
        mt_diag diag;
        mtd_fetch_result r =
            mtd_store_fetch(qs->store, q->mesh_id, (uint32_t)q->version, may_load, &entry, &diag);
        if (r == MTD_FETCH_NEEDS_LOAD && defer_to_worker(qs, q)) {
            answer_free(&a); /* a worker answers */
            return;
        }
        if (r == MTD_FETCH_BAD_ID)
            fail(&a, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "mesh_id: %.400s", diag.message);
        else if (r == MTD_FETCH_LOAD_FAILED)
            fail(&a, MESHTOPO_STATUS_CODE_T_ARCHIVE_FAILED, "%s", diag.message);
        else if (r != MTD_FETCH_OK && q->version)
            fail(&a, MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH,
                 "mesh_id '%s' version %" PRId32 ": not held", q->mesh_id, q->version);
        else if (r != MTD_FETCH_OK)
            fail(&a, MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH, "mesh_id '%s': no such mesh", q->mesh_id);
    }
    int32_t version = 0;
    meshtopo_topology_t report;
    bool have_report = false;
    if (entry) {
        const mt_mesh *mesh = mtd_entry_mesh(entry);
        version = (int32_t)mtd_entry_info(entry)->version;
        check_ids(&a, q, mesh);
        if (a.status == MESHTOPO_STATUS_CODE_T_OK) {
            switch (q->kind) {
                case MESHTOPO_QUERY_T_VERTEX_RING:
                    answer_rings(&a, mesh, q->ids, q->num_ids);
                    break;
                case MESHTOPO_QUERY_T_VALENCE:
                    answer_valences(&a, mesh, q->ids, q->num_ids);
                    break;
                case MESHTOPO_QUERY_T_FACE_NEIGHBORS:
                    answer_face_neighbors(&a, mesh, q->ids, q->num_ids);
                    break;
                case MESHTOPO_QUERY_T_EDGE_FACES:
                    answer_edge_faces(&a, mesh, q->ids, q->num_ids);
                    break;
                case MESHTOPO_QUERY_T_BOUNDARY_LOOPS:
                    answer_boundary_loops(&a, mesh);
                    break;
                case MESHTOPO_QUERY_T_COMPONENTS:
                    answer_components(&a, mesh, q->ids, q->num_ids);
                    break;
                case MESHTOPO_QUERY_T_DEFECTS:
                    answer_defects(&a, mesh, q->ids, q->num_ids);
                    break;
                case MESHTOPO_QUERY_T_DIHEDRAL_ANGLES:
                    answer_dihedral_angles(&a, mesh, q->ids, q->num_ids);
                    break;
                case MESHTOPO_QUERY_T_ANGLE_DEFICITS:
                    answer_angle_deficits(&a, mesh, q->ids, q->num_ids);
                    break;
                case MESHTOPO_QUERY_T_CONVEXITY:
                    answer_convexity(&a, mesh);
                    break;
                case MESHTOPO_QUERY_T_SELF_INTERSECTIONS:
                    answer_self_intersections(&a, mesh);
                    break;
                case MESHTOPO_QUERY_T_REPORT:
                    if (mtd_topology_fill(mesh, mtd_entry_info(entry), 0, SIZE_MAX, &report) == 0)
                        have_report = true;
                    else
                        fail(&a, MESHTOPO_STATUS_CODE_T_INTERNAL,
                             "out of memory copying the report");
                    break;
                default:
                    break;
            }
        }
    }
    if (may_load && q->kind == MESHTOPO_QUERY_T_SELF_INTERSECTIONS)
        atomic_fetch_sub(&qs->self_checks, 1); /* its turn ends before its answer goes out */
    send_answer(qs->replies, q, &a, version, have_report ? &report : NULL, NULL);
    if (have_report) mtd_topology_free(&report);
    mtd_entry_release(entry);
    answer_free(&a);
}

void mtd_query_handle(mtd_queries *qs, const meshtopo_query_t *q)
{
    mtd_log(MTD_LOG_DEBUG, "query",
            "mesh_id=%.64s version=%" PRId32 " kind=%" PRId32 " ids=%" PRId32, q->mesh_id,
            q->version, q->kind, q->num_ids);
    int64_t start = mtd_monotonic_us();
    char why[MTD_ERROR_MAX];
    if (!mtd_fair_share_allowed(qs->share, q->reply_channel, start, why, sizeof why)) {
        mtd_reply_abandon(qs->replies, q->reply_channel, q->request_id, &mt_msgs_type_reply);
        mtd_reply_query_error(qs->replies, q->reply_channel, q->request_id, q->mesh_id, q->kind,
                              false, MESHTOPO_STATUS_CODE_T_BUSY, why);
        return;
    }
    answer_query(qs, q, false);
    int64_t end = mtd_monotonic_us();
    mtd_fair_share_charge(qs->share, q->reply_channel, end, end - start);
}

mt_status mtd_queries_create(mtd_store *store, mtd_pool *pool, mtd_replies *replies,
                             mtd_cluster *cluster, mtd_queries **out_queries)
{
    mtd_queries *qs = calloc(1, sizeof *qs);
    *out_queries = qs;
    if (!qs) return MT_ERR_NOMEM;
    qs->store = store;
    qs->pool = pool;
    qs->replies = replies;
    qs->cluster = cluster;
    atomic_init(&qs->self_checks, 0);
    if (mtd_fair_share_create(&qs->share) != MT_OK) {
        free(qs);
        *out_queries = NULL;
        return MT_ERR_NOMEM;
    }
    return MT_OK;
}

void mtd_queries_destroy(mtd_queries *qs)
{
    if (!qs) return;
    mtd_fair_share_destroy(qs->share);
    free(qs);
}
