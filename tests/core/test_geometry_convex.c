/* Tests of mt_mesh_convexity and edge convexity: the five Platonic solids
 * and convex hulls of random point sets are convex; a triangulated cube with
 * one corner pushed in is not, and exactly its three reflex diagonals are
 * named; open, multi-component, higher-genus and inward-facing meshes are
 * refused with the right reasons; the reflex list follows the buffer rules. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geometry_mesh.h"
#include "harness.h"
#include "meshtopo/core.h"

static void expect_convex(const mt_mesh *m, const char *what)
{
    mt_convexity c;
    memset(&c, 0xff, sizeof c);
    mt_diag diag;
    mt_diag_clear(&diag);
    CHECK_OK(mt_mesh_convexity(m, 1e-9, &c, NULL, 0, &diag));
    char text[256];
    mt_convexity_describe(c.reasons, text, sizeof text);
    if (!c.convex) mt_test_fail(__FILE__, __LINE__, "%s is not convex: %s", what, text);
    CHECK_EQ(c.reasons, 0);
    CHECK_EQ(c.num_reflex, 0);
    CHECK_EQ(c.num_degenerate, 0);
    CHECK(c.volume > 0.0);
    CHECK(strcmp(text, "convex") == 0);
}

static void test_geometry_convex_platonic(void)
{
    /* Volumes at circumradius 1 from the edge length a. */
    const double a_tet = sqrt(8.0 / 3.0), a_cube = 2.0 / sqrt(3.0), a_oct = sqrt(2.0);
    const double a_dod = 4.0 / (sqrt(3.0) * (1.0 + sqrt(5.0)));
    const double a_ico = 4.0 / sqrt(10.0 + 2.0 * sqrt(5.0));
    const double volume[] = {pow(a_tet, 3) / (6.0 * sqrt(2.0)), pow(a_cube, 3),
                             sqrt(2.0) / 3.0 * pow(a_oct, 3),
                             (15.0 + 7.0 * sqrt(5.0)) / 4.0 * pow(a_dod, 3),
                             5.0 * (3.0 + sqrt(5.0)) / 12.0 * pow(a_ico, 3)};
    for (int kind = MT_TETRAHEDRON; kind <= MT_ICOSAHEDRON; kind++) {
        mt_mesh *m = geom_build_platonic(kind);
        if (!m) continue;
        expect_convex(m, "platonic solid");
        mt_convexity c;
        CHECK_OK(mt_mesh_convexity(m, 0.0, &c, NULL, 0, NULL));
        CHECK_NEAR(c.volume, volume[kind], 1e-12);
        mt_mesh_destroy(m);
    }
}

/* Hulls of random points in a cube and near a sphere. */
static void test_geometry_convex_hull(void)
{
    uint64_t seed = 12345;
    for (int round = 0; round < 6; round++) {
        uint32_t n = round < 3 ? 50 + 100 * (uint32_t)round : 300;
        double *pts = malloc(3 * (size_t)n * sizeof *pts);
        for (uint32_t i = 0; i < n; i++) {
            double *p = pts + 3 * (size_t)i;
            for (int k = 0; k < 3; k++) p[k] = 2.0 * geom_random(&seed) - 1.0;
            if (round >= 3) { /* on a shell of radius 0.9 .. 1 */
                double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
                double r = 0.9 + 0.1 * geom_random(&seed);
                for (int k = 0; k < 3; k++) p[k] *= r / len;
            }
        }
        mt_face_list hull;
        CHECK(geom_convex_hull(pts, n, &hull));
        mt_mesh *m = hull.num_faces ? geom_build(&hull, "convex hull") : NULL;
        if (m) {
            const mt_report *r = mt_mesh_report(m);
            CHECK(r->closed);
            CHECK_EQ(r->genus, 0);
            CHECK_EQ(r->num_faces, 2 * r->num_verts - 4);
            /* The helper's hull holds every point. */
            size_t outside = 0;
            for (uint32_t i = 0; i < n; i++)
                for (uint32_t f = 0; f < hull.num_faces; f++) {
                    const uint32_t *t = hull.face_indices + 3 * (size_t)f;
                    const double *a = hull.positions + 3 * (size_t)t[0];
                    const double *b = hull.positions + 3 * (size_t)t[1];
                    const double *c = hull.positions + 3 * (size_t)t[2];
                    const double *p = pts + 3 * (size_t)i;
                    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
                    double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
                    double w[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
                    double det = u[0] * (v[1] * w[2] - v[2] * w[1]) -
                                 u[1] * (v[0] * w[2] - v[2] * w[0]) +
                                 u[2] * (v[0] * w[1] - v[1] * w[0]);
                    outside += det > 1e-9;
                }
            CHECK_EQ(outside, 0);
            expect_convex(m, "convex hull");
            mt_mesh_destroy(m);
        }
        mt_face_list_free(&hull);
        free(pts);
    }
}

/* The unit cube in triangles, the three faces at vertex 6 = (1, 1, 1) split
 * by diagonals from it (to 4, 3 and 1), the other three arbitrarily. */
static const double tcube_pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                                   0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
static const uint32_t tcube_sizes[] = {3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3};
static const uint32_t tcube_idx[] = {6, 7, 4, 6, 4, 5, 6, 2, 3, 6, 3, 7, 6, 5, 1, 6, 1, 2,
                                     0, 3, 2, 0, 2, 1, 0, 1, 5, 0, 5, 4, 0, 4, 7, 0, 7, 3};

static void test_geometry_convex_pushed_corner(void)
{
    mt_mesh *m = geom_build_arrays(8, tcube_pos, 12, tcube_sizes, tcube_idx, "triangulated cube");
    if (m) {
        expect_convex(m, "triangulated cube"); /* the diagonals are flat */
        mt_edge_shape shape = MT_EDGE_REFLEX;
        CHECK_OK(mt_edge_convexity(m, 6, 4, 1e-9, &shape, NULL));
        CHECK_EQ(shape, MT_EDGE_FLAT);
        mt_mesh_destroy(m);
    }
    /* Push vertex 6 to (0.6, 0.6, 0.6): the plane of triangle (6, 1, 2) now
     * tilts to normal (t, 0, 1 - t) (t = 0.6), and vertex 5 across diagonal
     * 6-1 lies 1 - t above it, so 6-1 and by symmetry 6-4, 6-3 fold into
     * valleys; the cube edges at 6 stay ridges (vertex 3 lies t below the
     * plane of (6, 1, 2), so 6-2 is still convex, and so on by symmetry). */
    double pos[24];
    memcpy(pos, tcube_pos, sizeof pos);
    pos[18] = pos[19] = pos[20] = 0.6;
    m = geom_build_arrays(8, pos, 12, tcube_sizes, tcube_idx, "cube with a corner pushed in");
    if (!m) return;
    uint32_t reflex[6] = {MT_NONE, MT_NONE, MT_NONE, MT_NONE, MT_NONE, MT_NONE};
    mt_convexity c;
    CHECK_OK(mt_mesh_convexity(m, 1e-9, &c, reflex, 3, NULL));
    CHECK(!c.convex);
    CHECK_EQ(c.num_reflex, 3);
    double deficit;
    CHECK_OK(mt_vert_angle_deficit(m, 6, &deficit, NULL, NULL));
    uint32_t want = MT_NONCONVEX_REFLEX_EDGE | (deficit < -1e-9 ? MT_NONCONVEX_SADDLE_VERTEX : 0);
    CHECK_EQ(c.reasons, want);
    CHECK(c.volume > 0.0 && c.volume < 1.0);
    /* Exactly the diagonals from 6, each once, smaller id first. */
    bool seen[8] = {false};
    for (int i = 0; i < 3; i++) {
        CHECK_EQ(reflex[2 * i + 1], 6);
        uint32_t other = reflex[2 * i];
        CHECK(other == 1 || other == 3 || other == 4);
        if (other < 8) {
            CHECK(!seen[other]);
            seen[other] = true;
        }
    }
    /* The single-edge call agrees on all 18 edges. */
    size_t count = 0;
    uint32_t edges[36];
    mt_edge_shape shapes[18];
    double angles[18];
    CHECK_OK(mt_mesh_dihedral_angles(m, 1e-9, edges, angles, shapes, 18, &count, NULL));
    CHECK_EQ(count, 18);
    size_t num_reflex = 0;
    for (size_t e = 0; e < count; e++) {
        mt_edge_shape one = MT_EDGE_BOUNDARY;
        CHECK_OK(mt_edge_convexity(m, edges[2 * e], edges[2 * e + 1], 1e-9, &one, NULL));
        CHECK_EQ(one, shapes[e]);
        bool diag6 =
            edges[2 * e + 1] == 6 && (edges[2 * e] == 1 || edges[2 * e] == 3 || edges[2 * e] == 4);
        CHECK_EQ(shapes[e] == MT_EDGE_REFLEX, diag6);
        CHECK_EQ(angles[e] > 3.14159265358979323846, diag6);
        num_reflex += shapes[e] == MT_EDGE_REFLEX;
    }
    CHECK_EQ(num_reflex, 3);
    /* The reflex list at every capacity: too small fails but still counts. */
    for (size_t cap = 0; cap <= 3; cap++) {
        uint32_t *buf = malloc((2 * cap + 1) * sizeof *buf);
        memset(&c, 0, sizeof c);
        mt_status s = mt_mesh_convexity(m, 1e-9, &c, cap ? buf : NULL, cap, NULL);
        CHECK_STATUS(s, cap == 0 || cap == 3 ? MT_OK : MT_ERR_BUFFER_TOO_SMALL);
        CHECK_EQ(c.num_reflex, 3);
        CHECK(c.reasons & MT_NONCONVEX_REFLEX_EDGE);
        free(buf);
    }
    mt_mesh_destroy(m);
}

/* Meshes that are not convex polytopes, each for its own reasons. */
static void test_geometry_convex_reasons(void)
{
    mt_face_list list;
    mt_convexity c;
    mt_mesh *m;

    CHECK_OK(mt_gen_grid(3, 2, true, &list));
    m = geom_build(&list, "grid");
    mt_face_list_free(&list);
    if (m) {
        CHECK_OK(mt_mesh_convexity(m, 1e-9, &c, NULL, 0, NULL));
        CHECK_EQ(c.reasons, MT_NONCONVEX_OPEN | MT_NONCONVEX_NOT_SPHERE);
        CHECK_EQ(c.num_reflex, 0);
        CHECK_EQ(c.volume, 0.0);
        mt_mesh_destroy(m);
    }

    CHECK_OK(mt_gen_torus(12, 8, &list));
    m = geom_build(&list, "torus");
    mt_face_list_free(&list);
    if (m) {
        CHECK_OK(mt_mesh_convexity(m, 1e-9, &c, NULL, 0, NULL));
        CHECK(c.reasons & MT_NONCONVEX_NOT_SPHERE);
        CHECK(c.reasons & MT_NONCONVEX_REFLEX_EDGE); /* the hole's rim bends the other way */
        CHECK(c.reasons & MT_NONCONVEX_SADDLE_VERTEX);
        CHECK(!(c.reasons & (MT_NONCONVEX_OPEN | MT_NONCONVEX_INWARD | MT_NONCONVEX_COMPONENTS)));
        CHECK(c.volume > 0.0);
        mt_mesh_destroy(m);
    }

    /* Two tetrahedra apart: two components, chi 4. */
    static const double two_pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1,
                                     5, 0, 0, 6, 0, 0, 5, 1, 0, 5, 0, 1};
    static const uint32_t two_sizes[] = {3, 3, 3, 3, 3, 3, 3, 3};
    static const uint32_t two_idx[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2,
                                       4, 6, 5, 4, 5, 7, 5, 6, 7, 4, 7, 6};
    m = geom_build_arrays(8, two_pos, 8, two_sizes, two_idx, "two tetrahedra");
    if (m) {
        CHECK_OK(mt_mesh_convexity(m, 1e-9, &c, NULL, 0, NULL));
        CHECK_EQ(c.reasons, MT_NONCONVEX_COMPONENTS | MT_NONCONVEX_NOT_SPHERE);
        CHECK_NEAR(c.volume, 2.0 / 6.0, 1e-12);
        mt_mesh_destroy(m);
    }

    /* The triangulated cube with every face reversed: inward, every edge a valley. */
    uint32_t flipped[36];
    for (int f = 0; f < 12; f++)
        for (int k = 0; k < 3; k++) flipped[3 * f + k] = tcube_idx[3 * f + 2 - k];
    m = geom_build_arrays(8, tcube_pos, 12, tcube_sizes, flipped, "inward cube");
    if (m) {
        CHECK_OK(mt_mesh_convexity(m, 1e-9, &c, NULL, 0, NULL));
        CHECK_EQ(c.reasons, MT_NONCONVEX_INWARD | MT_NONCONVEX_REFLEX_EDGE);
        CHECK_EQ(c.num_reflex, 12); /* the cube edges; the diagonals stay flat */
        CHECK_NEAR(c.volume, -1.0, 1e-12);
        char text[64];
        size_t len = mt_convexity_describe(c.reasons, text, sizeof text);
        CHECK(strcmp(text, "reflex_edge, inward") == 0);
        CHECK_EQ(len, strlen("reflex_edge, inward"));
        CHECK_EQ(mt_convexity_describe(c.reasons, NULL, 0), len);
        char small[8];
        CHECK_EQ(mt_convexity_describe(c.reasons, small, sizeof small), len);
        CHECK(strlen(small) == sizeof small - 1);
        mt_mesh_destroy(m);
    }
}

static const mt_test_case cases[] = {
    {"geometry_convex_platonic", test_geometry_convex_platonic},
    {"geometry_convex_hull", test_geometry_convex_hull},
    {"geometry_convex_pushed_corner", test_geometry_convex_pushed_corner},
    {"geometry_convex_reasons", test_geometry_convex_reasons},
};

const mt_test_table mt_tests_geometry_convex = {cases, sizeof cases / sizeof cases[0]};
