/* meshtopod's answers to the geometry kinds of query_t (answer.h): dihedral
 * angles, angle deficits, convexity and self-intersections, exactly what
 * meshtopo/geometry.h answers; msgs/reply_t.lcm says what each kind puts
 * where. A mesh submitted without positions gets NO_GEOMETRY. */
#include <math.h>
#include <stdlib.h>

#include "answer.h"
#include "meshtopo/geometry.h"

void mtd_answer_dihedral_angles(mtd_answer *a, const mtd_answer_input *in)
{
    const mt_mesh *mesh = in->mesh;
    const int32_t *ids = in->query->ids;
    const int32_t n = in->query->num_ids;
    for (int32_t i = 0; i + 1 < n && mtd_answer_ok(a); i += 2) {
        uint32_t u = (uint32_t)ids[i], v = (uint32_t)ids[i + 1];
        mt_edge_shape shape = MT_EDGE_BOUNDARY;
        mt_status s =
            mt_edge_convexity(mesh, u, v, MESHTOPO_QUERY_T_GEOMETRY_TOLERANCE, &shape, NULL);
        if (s == MT_ERR_NOT_FOUND) {
            mtd_answer_push_real(a, NAN);
            mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
            continue;
        }
        double angle = NAN;
        if (s == MT_OK && shape <= MT_EDGE_REFLEX)
            s = mt_edge_dihedral_angle(mesh, u, v, &angle, NULL);
        if (s != MT_OK) {
            mtd_answer_fail_status(a, s, "dihedral angle at vertex", ids[i]);
            break;
        }
        mtd_answer_value(a, (int32_t)shape);
        mtd_answer_push_real(a, angle);
        mtd_answer_group_end(a, false);
        mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
}

void mtd_answer_angle_deficits(mtd_answer *a, const mtd_answer_input *in)
{
    const mt_mesh *mesh = in->mesh;
    const int32_t *ids = in->query->ids;
    const int32_t n = in->query->num_ids;
    for (int32_t i = 0; i < n && mtd_answer_ok(a); i++) {
        double deficit = 0.0;
        bool boundary = false;
        mt_status s = mt_vert_angle_deficit(mesh, (uint32_t)ids[i], &deficit, &boundary, NULL);
        if (s != MT_OK) {
            mtd_answer_fail_status(a, s, "angle deficit of vertex", ids[i]);
            break;
        }
        mtd_answer_push_real(a, deficit);
        mtd_answer_group_end(a, boundary);
        mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
}

void mtd_answer_convexity(mtd_answer *a, const mtd_answer_input *in)
{
    const mt_mesh *mesh = in->mesh;
    mt_convexity c;
    const double tolerance = MESHTOPO_QUERY_T_GEOMETRY_TOLERANCE;
    mt_status s = mt_mesh_convexity(mesh, tolerance, &c, NULL, 0, NULL);
    uint32_t *edges = NULL;
    size_t cap = 0;
    if (s == MT_OK || s == MT_ERR_BUFFER_TOO_SMALL) {
        if (!mtd_answer_reserve_u32(a, &edges, &cap, 2 * c.num_reflex + 1)) return;
        s = mt_mesh_convexity(mesh, tolerance, &c, edges, c.num_reflex, NULL);
    }
    if (s != MT_OK) {
        mtd_answer_fail_status(a, s, "convexity of the mesh", 0);
        free(edges);
        return;
    }
    mtd_answer_value(a, c.convex ? 1 : 0);
    mtd_answer_value(a, (int32_t)c.reasons);
    mtd_answer_value(a, (int32_t)c.num_reflex);
    mtd_answer_value(a, (int32_t)c.num_degenerate);
    mtd_answer_group_end(a, false);
    for (size_t k = 0; k < 2 * c.num_reflex; k++) mtd_answer_value(a, (int32_t)edges[k]);
    mtd_answer_group_end(a, false);
    mtd_answer_push_real(a, c.volume);
    mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_OK);
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
static void *fetch_list(mtd_answer *a, const mt_mesh *mesh, const geometry_list *list,
                        size_t *count)
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
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_TOO_LARGE,
                        "more than %zu %s: they exceed the daemon's reply limit of %u bytes", most,
                        list->what, (unsigned)MTD_REPLY_MAX_BYTES);
    else if (s == MT_ERR_TOO_LARGE) /* a bound the query was given: its message names it */
        mtd_answer_fail(a, MESHTOPO_STATUS_CODE_T_TOO_LARGE, "%s", diag.message);
    else if (s != MT_OK)
        mtd_answer_fail_status(a, s, list->what, 0);
    if (s != MT_OK) {
        free(items);
        return NULL;
    }
    return items;
}

/* SELF_INTERSECTIONS: three groups (msgs/reply_t.lcm), reals the warps. */
void mtd_answer_self_intersections(mtd_answer *a, const mtd_answer_input *in)
{
    const mt_mesh *mesh = in->mesh;
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
            mtd_answer_value(a, (int32_t)pairs[i].a);
            mtd_answer_value(a, (int32_t)pairs[i].b);
        }
        mtd_answer_group_end(a, false);
        for (size_t i = 0; i < num_faces; i++) {
            const bool crossing = faces[i].kind == MT_FACE_SELF_CROSSING;
            mtd_answer_value(a, (int32_t)faces[i].face);
            mtd_answer_value(a, (int32_t)faces[i].kind);
            mtd_answer_value(a, crossing ? (int32_t)faces[i].side_a : -1);
            mtd_answer_value(a, crossing ? (int32_t)faces[i].side_b : -1);
            mtd_answer_push_real(a, faces[i].warp);
        }
        mtd_answer_group_end(a, false);
        for (size_t i = 0; i < num_loops; i++) {
            mtd_answer_value(a, (int32_t)loops[i].loop);
            for (int k = 0; k < 2; k++) mtd_answer_value(a, (int32_t)loops[i].edge_a[k]);
            for (int k = 0; k < 2; k++) mtd_answer_value(a, (int32_t)loops[i].edge_b[k]);
        }
        mtd_answer_group_end(a, false);
        mtd_answer_item_end(a, MESHTOPO_STATUS_CODE_T_OK);
    }
    free(pairs);
    free(faces);
    free(loops);
}
