/* Tests of the face, vertex and edge geometry (geometry.h) on meshes whose
 * answers are known by hand: the seed rectangle, a unit cube, an L-shaped
 * polygon with a reflex corner, the Platonic solids (dihedral angles and
 * vertex deficits from their closed forms), degenerate faces (no NaN),
 * non-manifold and same-direction edges, and bad input: no positions, ids out
 * of range, NULL pointers, rejected faces, and every buffer size from 0 up to
 * the exact one. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geometry_mesh.h"
#include "harness.h"
#include "meshtopo/core.h"

#define PI 3.14159265358979323846
#define TOL 1e-12

/* ---- hand-checked values ------------------------------------------------ */

static void check_vec(const double *got, double x, double y, double z, const char *file, int line)
{
    if (!(fabs(got[0] - x) <= TOL && fabs(got[1] - y) <= TOL && fabs(got[2] - z) <= TOL))
        mt_test_fail(file, line, "got (%.17g, %.17g, %.17g), expected (%.17g, %.17g, %.17g)",
                     got[0], got[1], got[2], x, y, z);
}
#define CHECK_VEC(got, x, y, z) check_vec((got), (x), (y), (z), __FILE__, __LINE__)

static void test_geometry_rectangle(void)
{
    mt_face_list list;
    CHECK_OK(mt_gen_rectangle(3.0, 2.0, &list));
    mt_mesh *m = geom_build(&list, "rectangle");
    mt_face_list_free(&list);
    if (!m) return;
    double v[3], area;
    /* Faces (0, 1, 2) and (0, 2, 3) of the 3 x 2 rectangle in z = 0. */
    CHECK_OK(mt_face_normal(m, 0, v, NULL));
    CHECK_VEC(v, 0, 0, 1);
    CHECK_OK(mt_face_normal(m, 1, v, NULL));
    CHECK_VEC(v, 0, 0, 1);
    CHECK_OK(mt_face_area(m, 0, &area, NULL));
    CHECK_NEAR(area, 3.0, TOL);
    CHECK_OK(mt_face_area(m, 1, &area, NULL));
    CHECK_NEAR(area, 3.0, TOL);
    CHECK_OK(mt_face_centroid(m, 0, v, NULL));
    CHECK_VEC(v, 2.0, 2.0 / 3.0, 0.0);
    CHECK_OK(mt_face_centroid(m, 1, v, NULL));
    CHECK_VEC(v, 1.0, 4.0 / 3.0, 0.0);

    /* Every vertex is a boundary corner turning by pi/2; the diagonal is flat. */
    for (uint32_t i = 0; i < 4; i++) {
        double d = 0;
        bool boundary = false;
        CHECK_OK(mt_vert_angle_deficit(m, i, &d, &boundary, NULL));
        CHECK_NEAR(d, PI / 2, TOL);
        CHECK(boundary);
        CHECK_OK(mt_vert_normal(m, i, v, NULL));
        CHECK_VEC(v, 0, 0, 1);
    }
    double angle = 0;
    mt_edge_shape shape = MT_EDGE_REFLEX;
    CHECK_OK(mt_edge_dihedral_angle(m, 2, 0, &angle, NULL));
    CHECK_NEAR(angle, PI, TOL);
    CHECK_OK(mt_edge_convexity(m, 0, 2, 1e-9, &shape, NULL));
    CHECK_EQ(shape, MT_EDGE_FLAT);
    mt_diag diag;
    mt_diag_clear(&diag);
    CHECK_STATUS(mt_edge_dihedral_angle(m, 0, 1, &angle, &diag), MT_ERR_UNSUPPORTED);
    CHECK(strstr(diag.message, "0-1") != NULL && strstr(diag.message, "boundary") != NULL);
    CHECK_OK(mt_edge_convexity(m, 1, 0, 0.0, &shape, NULL));
    CHECK_EQ(shape, MT_EDGE_BOUNDARY);
    CHECK_STATUS(mt_edge_dihedral_angle(m, 1, 3, &angle, NULL), MT_ERR_NOT_FOUND);
    mt_mesh_destroy(m);
}

/* The unit cube [0, 1]^3 as six quads, counter-clockwise from outside. */
static const double cube_pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                                  0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
static const uint32_t cube_sizes[] = {4, 4, 4, 4, 4, 4};
static const uint32_t cube_idx[] = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4,
                                    2, 3, 7, 6, 1, 2, 6, 5, 0, 4, 7, 3};

static void test_geometry_unit_cube(void)
{
    mt_mesh *m = geom_build_arrays(8, cube_pos, 6, cube_sizes, cube_idx, "unit cube");
    if (!m) return;
    static const double normals[6][3] = {{0, 0, -1}, {0, 0, 1}, {0, -1, 0},
                                         {0, 1, 0},  {1, 0, 0}, {-1, 0, 0}};
    for (uint32_t f = 0; f < 6; f++) {
        double n[3], c[3], area;
        CHECK_OK(mt_face_normal(m, f, n, NULL));
        CHECK_VEC(n, normals[f][0], normals[f][1], normals[f][2]);
        CHECK_OK(mt_face_area(m, f, &area, NULL));
        CHECK_NEAR(area, 1.0, TOL);
        CHECK_OK(mt_face_centroid(m, f, c, NULL));
        /* The centre of the face: 0.5 on two axes, 0 or 1 along the normal. */
        for (int k = 0; k < 3; k++) {
            double want = normals[f][k] == 0 ? 0.5 : normals[f][k] > 0 ? 1.0 : 0.0;
            CHECK_NEAR(c[k], want, TOL);
        }
    }
    for (uint32_t v = 0; v < 8; v++) {
        double d, n[3];
        bool boundary = true;
        CHECK_OK(mt_vert_angle_deficit(m, v, &d, &boundary, NULL));
        CHECK_NEAR(d, PI / 2, TOL);
        CHECK(!boundary);
        CHECK_OK(mt_vert_normal(m, v, n, NULL));
        const double *p = mt_mesh_position(m, v);
        double s = 1.0 / sqrt(3.0);
        CHECK_VEC(n, (2 * p[0] - 1) * s, (2 * p[1] - 1) * s, (2 * p[2] - 1) * s);
    }
    /* Whole-mesh forms agree with the single calls. */
    size_t count = 0;
    double all_n[18], all_a[6];
    CHECK_OK(mt_mesh_face_normals(m, all_n, all_a, 6, &count, NULL));
    CHECK_EQ(count, 6);
    for (uint32_t f = 0; f < 6; f++) {
        CHECK_VEC(all_n + 3 * f, normals[f][0], normals[f][1], normals[f][2]);
        CHECK_NEAR(all_a[f], 1.0, TOL);
    }
    uint32_t edges[24];
    double angles[12];
    mt_edge_shape shapes[12];
    CHECK_OK(mt_mesh_dihedral_angles(m, 1e-9, edges, angles, shapes, 12, &count, NULL));
    CHECK_EQ(count, 12);
    for (size_t e = 0; e < 12 && e < count; e++) {
        CHECK_NEAR(angles[e], PI / 2, TOL);
        CHECK_EQ(shapes[e], MT_EDGE_CONVEX);
        CHECK(edges[2 * e] < edges[2 * e + 1]);
        /* A cube edge changes one coordinate. */
        const double *a = mt_mesh_position(m, edges[2 * e]),
                     *b = mt_mesh_position(m, edges[2 * e + 1]);
        CHECK_NEAR(fabs(a[0] - b[0]) + fabs(a[1] - b[1]) + fabs(a[2] - b[2]), 1.0, TOL);
        double single;
        CHECK_OK(mt_edge_dihedral_angle(m, edges[2 * e + 1], edges[2 * e], &single, NULL));
        CHECK_NEAR(single, angles[e], TOL);
    }
    mt_mesh_destroy(m);
}

/* An L-shaped hexagon in z = 0: area 3, centroid (5/6, 5/6), a reflex
 * corner of 3 pi / 2 at vertex 3. */
static void test_geometry_reflex_polygon(void)
{
    static const double pos[] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 1, 2, 0, 0, 2, 0};
    static const uint32_t sizes[] = {6}, idx[] = {0, 1, 2, 3, 4, 5};
    mt_mesh *m = geom_build_arrays(6, pos, 1, sizes, idx, "L hexagon");
    if (!m) return;
    double v[3], area;
    CHECK_OK(mt_face_area(m, 0, &area, NULL));
    CHECK_NEAR(area, 3.0, TOL);
    CHECK_OK(mt_face_centroid(m, 0, v, NULL));
    CHECK_VEC(v, 5.0 / 6.0, 5.0 / 6.0, 0.0);
    double sum = 0;
    for (uint32_t i = 0; i < 6; i++) {
        double d;
        CHECK_OK(mt_vert_angle_deficit(m, i, &d, NULL, NULL));
        CHECK_NEAR(d, i == 3 ? -PI / 2 : PI / 2, TOL);
        sum += d;
    }
    CHECK_NEAR(sum, 2 * PI, TOL); /* a disk: chi = 1 */
    mt_mesh_destroy(m);
}

/* Dihedral angles and deficits of the five solids against closed forms. */
static void test_geometry_platonic_values(void)
{
    static const struct {
        int kind;
        double dihedral, deficit;
    } solids[] = {
        {MT_TETRAHEDRON, 0, PI},        /* acos(1/3), 3 x 60 degrees */
        {MT_CUBE, PI / 2, PI / 2},      /* 3 x 90 */
        {MT_OCTAHEDRON, 0, 2 * PI / 3}, /* acos(-1/3), 4 x 60 */
        {MT_DODECAHEDRON, 0, PI / 5},   /* acos(-1/sqrt 5), 3 x 108 */
        {MT_ICOSAHEDRON, 0, PI / 3},    /* acos(-sqrt 5/3), 5 x 60 */
    };
    const double dihedral[] = {acos(1.0 / 3.0), PI / 2, acos(-1.0 / 3.0), acos(-1.0 / sqrt(5.0)),
                               acos(-sqrt(5.0) / 3.0)};
    for (size_t i = 0; i < 5; i++) {
        mt_mesh *m = geom_build_platonic(solids[i].kind);
        if (!m) continue;
        const mt_report *r = mt_mesh_report(m);
        size_t count = 0;
        CHECK_OK(mt_mesh_dihedral_angles(m, 1e-9, NULL, NULL, NULL, 0, &count, NULL));
        CHECK_EQ(count, r->num_edges);
        uint32_t *edges = malloc(2 * count * sizeof *edges);
        double *angles = malloc(count * sizeof *angles);
        CHECK_OK(mt_mesh_dihedral_angles(m, 1e-9, edges, angles, NULL, count, &count, NULL));
        for (size_t e = 0; e < count; e++) {
            CHECK_NEAR(angles[e], dihedral[i], 1e-12);
            double single = 0;
            mt_edge_shape shape = MT_EDGE_FLAT;
            CHECK_OK(mt_edge_dihedral_angle(m, edges[2 * e], edges[2 * e + 1], &single, NULL));
            CHECK_NEAR(single, dihedral[i], 1e-12);
            CHECK_OK(mt_edge_convexity(m, edges[2 * e], edges[2 * e + 1], 1e-9, &shape, NULL));
            CHECK_EQ(shape, MT_EDGE_CONVEX);
        }
        free(edges);
        free(angles);
        double *def = malloc(r->num_verts * sizeof *def);
        double *normals = malloc(3 * r->num_verts * sizeof *normals);
        CHECK_OK(mt_mesh_vert_curvature(m, normals, def, NULL, r->num_verts, &count, NULL));
        CHECK_EQ(count, r->num_verts);
        for (uint32_t v = 0; v < r->num_verts; v++) {
            CHECK_NEAR(def[v], solids[i].deficit, 1e-12);
            double d, n[3];
            CHECK_OK(mt_vert_angle_deficit(m, v, &d, NULL, NULL));
            CHECK_NEAR(d, def[v], 1e-12);
            /* Centred at the origin: the vertex normal is the position's direction. */
            const double *p = mt_mesh_position(m, v);
            double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
            CHECK_OK(mt_vert_normal(m, v, n, NULL));
            CHECK_VEC(n, p[0] / len, p[1] / len, p[2] / len);
            CHECK_VEC(normals + 3 * v, n[0], n[1], n[2]);
        }
        free(def);
        free(normals);
        mt_mesh_destroy(m);
    }
}

/* ---- degenerate and non-manifold input ------------------------------------ */

/* Triangle 0 has collinear corners; triangle 1 shares its edge 0-1. */
static void test_geometry_degenerate_face(void)
{
    static const double pos[] = {0, 0, 0, 2, 0, 0, 1, 0, 0, 1, -1, 0};
    static const uint32_t sizes[] = {3, 3}, idx[] = {0, 1, 2, 1, 0, 3};
    mt_mesh *m = geom_build_arrays(4, pos, 2, sizes, idx, "degenerate triangle");
    if (!m) return;
    double v[3] = {9, 9, 9}, area = 9;
    CHECK_OK(mt_face_normal(m, 0, v, NULL));
    CHECK_VEC(v, 0, 0, 0);
    CHECK_OK(mt_face_area(m, 0, &area, NULL));
    CHECK_NEAR(area, 0.0, 0.0);
    CHECK_OK(mt_face_centroid(m, 0, v, NULL));
    CHECK_VEC(v, 1, 0, 0); /* mean of the corners */
    double angle;
    mt_edge_shape shape = MT_EDGE_CONVEX;
    mt_diag diag;
    mt_diag_clear(&diag);
    CHECK_STATUS(mt_edge_dihedral_angle(m, 0, 1, &angle, &diag), MT_ERR_UNSUPPORTED);
    CHECK(strstr(diag.message, "degenerate") != NULL);
    CHECK_OK(mt_edge_convexity(m, 0, 1, 0.0, &shape, NULL));
    CHECK_EQ(shape, MT_EDGE_DEGENERATE);
    /* Corner angles 0, 0 and pi in the flat triangle: finite deficits, and
     * the vertex normals come from triangle 1 alone. */
    double def[4], normals[12];
    bool boundary[4];
    size_t count;
    CHECK_OK(mt_mesh_vert_curvature(m, normals, def, boundary, 4, &count, NULL));
    for (int i = 0; i < 4; i++) {
        CHECK(isfinite(def[i]));
        CHECK(boundary[i]);
        if (i == 2)
            CHECK_VEC(normals + 3 * i, 0, 0, 0); /* only in the degenerate face */
        else
            CHECK_VEC(normals + 3 * i, 0, 0, 1);
    }
    CHECK_NEAR(def[2], 0.0, TOL); /* pi - pi */
    mt_convexity c;
    CHECK_OK(mt_mesh_convexity(m, 1e-9, &c, NULL, 0, NULL));
    CHECK(!c.convex);
    CHECK(c.reasons & MT_NONCONVEX_DEGENERATE_FACE);
    CHECK_EQ(c.num_degenerate, 1);
    mt_mesh_destroy(m);
}

static void test_geometry_nonmanifold_edges(void)
{
    mt_face_list list;
    CHECK_OK(mt_gen_fin(&list));
    mt_mesh *m = geom_build(&list, "fin");
    mt_face_list_free(&list);
    if (m) {
        double angle;
        mt_edge_shape shape = MT_EDGE_CONVEX;
        mt_diag diag;
        mt_diag_clear(&diag);
        CHECK_STATUS(mt_edge_dihedral_angle(m, 0, 1, &angle, &diag), MT_ERR_UNSUPPORTED);
        CHECK(strstr(diag.message, "nonmanifold") != NULL);
        CHECK_EQ(diag.element, 0);
        CHECK_OK(mt_edge_convexity(m, 1, 0, 0.0, &shape, NULL));
        CHECK_EQ(shape, MT_EDGE_NONMANIFOLD);
        /* The sweep lists the split edge once and says the same. */
        size_t count = 0;
        uint32_t edges[64];
        mt_edge_shape shapes[32];
        CHECK_OK(mt_mesh_dihedral_angles(m, 0.0, edges, NULL, shapes, 32, &count, NULL));
        CHECK_EQ(count, mt_mesh_report(m)->num_edges);
        size_t fins = 0;
        for (size_t e = 0; e < count; e++) {
            bool is01 = edges[2 * e] == 0 && edges[2 * e + 1] == 1;
            fins += is01;
            CHECK_EQ(shapes[e], is01 ? MT_EDGE_NONMANIFOLD : MT_EDGE_BOUNDARY);
        }
        CHECK_EQ(fins, 1);
        mt_convexity c;
        CHECK_OK(mt_mesh_convexity(m, 0.0, &c, NULL, 0, NULL));
        CHECK(c.reasons & MT_NONCONVEX_NONMANIFOLD);
        CHECK(c.reasons & MT_NONCONVEX_OPEN);
        mt_mesh_destroy(m);
    }
    /* Two triangles crossing edge 0-1 the same way. */
    static const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0};
    static const uint32_t sizes[] = {3, 3}, idx[] = {0, 1, 2, 0, 1, 3};
    m = geom_build_arrays(4, pos, 2, sizes, idx, "same direction");
    if (!m) return;
    double angle;
    mt_edge_shape shape = MT_EDGE_CONVEX;
    CHECK_STATUS(mt_edge_dihedral_angle(m, 0, 1, &angle, NULL), MT_ERR_UNSUPPORTED);
    CHECK_OK(mt_edge_convexity(m, 0, 1, 0.0, &shape, NULL));
    CHECK_EQ(shape, MT_EDGE_INCONSISTENT);
    /* Edge 0-1 is not a real boundary: vertex 0 still is (edges 0-2, 0-3). */
    double d;
    bool boundary = false;
    CHECK_OK(mt_vert_angle_deficit(m, 0, &d, &boundary, NULL));
    CHECK(boundary);
    CHECK_NEAR(d, PI - PI, TOL); /* two right angles */
    mt_mesh_destroy(m);
}

/* ---- bad input -------------------------------------------------------------- */

static void test_geometry_bad_input(void)
{
    double v[3], x;
    bool b;
    mt_edge_shape shape;
    mt_convexity c;
    size_t count;
    mt_diag diag;

    /* No positions: every call says so. */
    mt_mesh *m = geom_build_arrays(8, NULL, 6, cube_sizes, cube_idx, "cube without positions");
    if (m) {
        mt_diag_clear(&diag);
        CHECK_STATUS(mt_face_normal(m, 0, v, &diag), MT_ERR_NO_GEOMETRY);
        CHECK(strstr(diag.message, "positions") != NULL);
        CHECK_STATUS(mt_face_area(m, 0, &x, NULL), MT_ERR_NO_GEOMETRY);
        CHECK_STATUS(mt_face_centroid(m, 0, v, NULL), MT_ERR_NO_GEOMETRY);
        CHECK_STATUS(mt_mesh_face_normals(m, NULL, NULL, 0, &count, NULL), MT_ERR_NO_GEOMETRY);
        CHECK_STATUS(mt_vert_normal(m, 0, v, NULL), MT_ERR_NO_GEOMETRY);
        CHECK_STATUS(mt_vert_angle_deficit(m, 0, &x, &b, NULL), MT_ERR_NO_GEOMETRY);
        CHECK_STATUS(mt_mesh_vert_curvature(m, NULL, NULL, NULL, 0, &count, NULL),
                     MT_ERR_NO_GEOMETRY);
        CHECK_STATUS(mt_edge_dihedral_angle(m, 0, 1, &x, NULL), MT_ERR_NO_GEOMETRY);
        CHECK_STATUS(mt_edge_convexity(m, 0, 1, 0.0, &shape, NULL), MT_ERR_NO_GEOMETRY);
        CHECK_STATUS(mt_mesh_dihedral_angles(m, 0.0, NULL, NULL, NULL, 0, &count, NULL),
                     MT_ERR_NO_GEOMETRY);
        CHECK_STATUS(mt_mesh_convexity(m, 0.0, &c, NULL, 0, NULL), MT_ERR_NO_GEOMETRY);
        mt_mesh_destroy(m);
    }

    /* NULL mesh and NULL outputs. */
    CHECK_STATUS(mt_face_normal(NULL, 0, v, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_vert_angle_deficit(NULL, 0, &x, NULL, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_mesh_convexity(NULL, 0.0, &c, NULL, 0, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_mesh_dihedral_angles(NULL, 0.0, NULL, NULL, NULL, 0, &count, NULL),
                 MT_ERR_INVALID_ARG);
    m = geom_build_arrays(8, cube_pos, 6, cube_sizes, cube_idx, "unit cube");
    if (!m) return;
    CHECK_STATUS(mt_face_normal(m, 0, NULL, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_area(m, 0, NULL, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_centroid(m, 0, NULL, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_vert_normal(m, 0, NULL, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_vert_angle_deficit(m, 0, NULL, &b, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_edge_dihedral_angle(m, 0, 1, NULL, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_edge_convexity(m, 0, 1, 0.0, NULL, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_mesh_convexity(m, 0.0, NULL, NULL, 0, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_mesh_face_normals(m, v, NULL, 1, NULL, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_mesh_vert_curvature(m, NULL, &x, NULL, 1, NULL, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_mesh_dihedral_angles(m, 0.0, NULL, &x, NULL, 1, NULL, NULL),
                 MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_edge_convexity(m, 0, 1, -1.0, &shape, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_edge_convexity(m, 0, 1, NAN, &shape, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_mesh_convexity(m, -1e-3, &c, NULL, 0, NULL), MT_ERR_INVALID_ARG);

    /* Ids out of range, with the id in diag; edges that do not exist. */
    mt_diag_clear(&diag);
    CHECK_STATUS(mt_face_normal(m, 6, v, &diag), MT_ERR_OUT_OF_RANGE);
    CHECK_EQ(diag.element, 6);
    CHECK(strstr(diag.message, "face 6") != NULL);
    CHECK_STATUS(mt_face_area(m, MT_NONE, &x, NULL), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_face_centroid(m, 100, v, NULL), MT_ERR_OUT_OF_RANGE);
    mt_diag_clear(&diag);
    CHECK_STATUS(mt_vert_normal(m, 8, v, &diag), MT_ERR_OUT_OF_RANGE);
    CHECK(strstr(diag.message, "vertex 8") != NULL);
    CHECK_STATUS(mt_vert_angle_deficit(m, MT_NONE, &x, NULL, NULL), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_edge_dihedral_angle(m, 0, 8, &x, NULL), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_edge_convexity(m, 9, 0, 0.0, &shape, NULL), MT_ERR_OUT_OF_RANGE);
    mt_diag_clear(&diag);
    CHECK_STATUS(mt_edge_dihedral_angle(m, 0, 6, &x, &diag), MT_ERR_NOT_FOUND); /* a diagonal */
    CHECK(strstr(diag.message, "0-6") != NULL);
    CHECK_STATUS(mt_edge_convexity(m, 3, 3, 0.0, &shape, NULL), MT_ERR_NOT_FOUND);
    mt_mesh_destroy(m);

    /* A rejected face record: NOT_FOUND alone, zeros in the sweep. */
    static const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const uint32_t sizes[] = {3, 3}, idx[] = {0, 1, 2, 0, 7, 1};
    m = geom_build_arrays(3, pos, 2, sizes, idx, "triangle and a bad face");
    if (!m) return;
    mt_diag_clear(&diag);
    CHECK_STATUS(mt_face_normal(m, 1, v, &diag), MT_ERR_NOT_FOUND);
    CHECK(strstr(diag.message, "face 1") != NULL);
    double normals[6], areas[2];
    CHECK_OK(mt_mesh_face_normals(m, normals, areas, 2, &count, NULL));
    CHECK_VEC(normals, 0, 0, 1);
    CHECK_VEC(normals + 3, 0, 0, 0);
    CHECK_NEAR(areas[0], 0.5, TOL);
    CHECK_NEAR(areas[1], 0.0, 0.0);
    mt_mesh_destroy(m);
}

/* Every whole-mesh call, at every capacity from 0 to the exact size, with
 * buffers of exactly that many elements (so AddressSanitizer sees overruns):
 * 0 is a size query, too small leaves the buffer alone, exact fills it. */
static void test_geometry_buffer_sizes(void)
{
    mt_face_list list;
    CHECK_OK(mt_gen_platonic(MT_ICOSAHEDRON, &list));
    mt_mesh *m = geom_build(&list, "icosahedron");
    mt_face_list_free(&list);
    if (!m) return;
    const size_t nf = 20, nv = 12, ne = 30;
    for (size_t cap = 0; cap <= nf; cap++) {
        double *n = malloc((3 * cap + 1) * sizeof *n), *a = malloc((cap + 1) * sizeof *a);
        for (size_t i = 0; i < cap; i++) a[i] = -7.0;
        size_t count = 0;
        mt_status s = mt_mesh_face_normals(m, cap ? n : NULL, cap ? a : NULL, cap, &count, NULL);
        CHECK_EQ(count, nf);
        CHECK_STATUS(s, cap == 0 || cap == nf ? MT_OK : MT_ERR_BUFFER_TOO_SMALL);
        for (size_t i = 0; i < cap; i++) CHECK(cap == nf ? a[i] > 0.0 : a[i] == -7.0);
        free(n);
        free(a);
    }
    for (size_t cap = 0; cap <= nv; cap++) {
        double *d = malloc((cap + 1) * sizeof *d);
        bool *b = malloc(cap + 1);
        for (size_t i = 0; i < cap; i++) d[i] = -7.0;
        size_t count = 0;
        mt_status s =
            mt_mesh_vert_curvature(m, NULL, cap ? d : NULL, cap ? b : NULL, cap, &count, NULL);
        CHECK_EQ(count, nv);
        CHECK_STATUS(s, cap == 0 || cap == nv ? MT_OK : MT_ERR_BUFFER_TOO_SMALL);
        for (size_t i = 0; i < cap; i++) CHECK(cap == nv ? d[i] > 1.0 : d[i] == -7.0);
        free(d);
        free(b);
    }
    for (size_t cap = 0; cap <= ne; cap++) {
        uint32_t *e = malloc((2 * cap + 1) * sizeof *e);
        double *ang = malloc((cap + 1) * sizeof *ang);
        mt_edge_shape *sh = malloc((cap + 1) * sizeof *sh);
        for (size_t i = 0; i < cap; i++) ang[i] = -7.0;
        size_t count = 0;
        mt_status s = mt_mesh_dihedral_angles(m, 0.0, cap ? e : NULL, cap ? ang : NULL,
                                              cap ? sh : NULL, cap, &count, NULL);
        CHECK_EQ(count, ne);
        CHECK_STATUS(s, cap == 0 || cap == ne ? MT_OK : MT_ERR_BUFFER_TOO_SMALL);
        for (size_t i = 0; i < cap; i++) CHECK(cap == ne ? ang[i] > 2.0 : ang[i] == -7.0);
        free(e);
        free(ang);
        free(sh);
    }
    mt_mesh_destroy(m);
}

static const mt_test_case cases[] = {
    {"geometry_rectangle", test_geometry_rectangle},
    {"geometry_unit_cube", test_geometry_unit_cube},
    {"geometry_reflex_polygon", test_geometry_reflex_polygon},
    {"geometry_platonic_values", test_geometry_platonic_values},
    {"geometry_degenerate_face", test_geometry_degenerate_face},
    {"geometry_nonmanifold_edges", test_geometry_nonmanifold_edges},
    {"geometry_bad_input", test_geometry_bad_input},
    {"geometry_buffer_sizes", test_geometry_buffer_sizes},
};

const mt_test_table mt_tests_geometry = {cases, sizeof cases / sizeof cases[0]};
