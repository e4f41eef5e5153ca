/* Tests of face shape (mt_face_shape_of, mt_mesh_nonsimple_faces): squares,
 * concave and tilted polygons are simple; a crossed quad, a pentagram, a
 * {7/2} star, sides folding back over each other and a corner touching a side
 * are self-crossing with the right sides named; a warped quad is warped and
 * a barely bent one is not; a regular 1000-gon is simple until one corner is
 * pulled across it; on random polygons the sweep line agrees with a check of
 * every pair of sides written here; triangulating a crossing face is refused;
 * boundary loops that cross themselves are found the same way. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "meshtopo/core.h"

/* One polygon face over its own n corners (positions 3 per corner). */
static mt_mesh *polygon_mesh(const double *positions, uint32_t n)
{
    uint32_t *indices = malloc(n * sizeof *indices);
    for (uint32_t i = 0; i < n; i++) indices[i] = i;
    uint32_t size = n;
    mt_face_list list = {n, 1, n, (double *)positions, &size, indices};
    mt_mesh *mesh = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(&list, NULL, &mesh, &diag));
    free(indices);
    return mesh;
}

/* The n corners (3n doubles) of a regular n-gon in z = 0 taken two steps at
 * a time: a star polygon crossing itself. */
static void star_polygon(int n, double *out)
{
    for (int i = 0; i < n; i++) {
        double a = 2 * 3.14159265358979323846 * (2 * i % n) / n;
        out[3 * i] = cos(a);
        out[3 * i + 1] = sin(a);
        out[3 * i + 2] = 0;
    }
}

static mt_face_shape shape_of(const double *positions, uint32_t n)
{
    mt_face_shape shape;
    memset(&shape, 0xff, sizeof shape);
    mt_mesh *mesh = polygon_mesh(positions, n);
    mt_diag diag;
    if (mesh) CHECK_OK(mt_face_shape_of(mesh, 0, &shape, &diag));
    mt_mesh_destroy(mesh);
    return shape;
}

#define CHECK_SHAPE(positions, n, want_kind, want_a, want_b)                                 \
    do {                                                                                     \
        mt_face_shape got = shape_of(positions, n);                                          \
        if (got.kind != (want_kind) || got.side_a != (uint32_t)(want_a) ||                   \
            got.side_b != (uint32_t)(want_b))                                                \
            mt_test_fail(__FILE__, __LINE__, "kind %d sides %u %u, expected %d sides %u %u", \
                         (int)got.kind, got.side_a, got.side_b, (int)(want_kind),            \
                         (uint32_t)(want_a), (uint32_t)(want_b));                            \
    } while (0)

static void test_shape_simple(void)
{
    const double square[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    CHECK_SHAPE(square, 4, MT_FACE_SIMPLE, MT_NONE, MT_NONE);
    CHECK(shape_of(square, 4).warp == 0.0);
    const double arrow[] = {0, 0, 0, 2, 1, 0, 0, 2, 0, 0.5, 1, 0}; /* concave */
    CHECK_SHAPE(arrow, 4, MT_FACE_SIMPLE, MT_NONE, MT_NONE);
    /* A concave hexagon on the tilted plane x + y + z = 1. */
    double tilted[18];
    const double uv[6][2] = {{0, 0}, {3, 0}, {3, 2}, {2, 1}, {1, 2}, {0, 2}};
    for (int i = 0; i < 6; i++) {
        double u = uv[i][0], v = uv[i][1];
        tilted[3 * i] = u;
        tilted[3 * i + 1] = v;
        tilted[3 * i + 2] = 1 - u - v;
    }
    CHECK_SHAPE(tilted, 6, MT_FACE_SIMPLE, MT_NONE, MT_NONE);
    CHECK(shape_of(tilted, 6).warp < 1e-12);
    /* A triangle is always simple. */
    const double tri[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    CHECK_SHAPE(tri, 3, MT_FACE_SIMPLE, MT_NONE, MT_NONE);
}

static void test_shape_crossing(void)
{
    /* The crossed quad: sides 0 (0-1) and 2 (2-3) cross; its Newell area is 0. */
    const double bowtie[] = {0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0};
    CHECK_SHAPE(bowtie, 4, MT_FACE_SELF_CROSSING, 0, 2);
    /* The same, lifted onto a tilted plane. */
    double lifted[12];
    for (int i = 0; i < 4; i++) {
        lifted[3 * i] = bowtie[3 * i];
        lifted[3 * i + 1] = bowtie[3 * i + 1];
        lifted[3 * i + 2] = 0.3 * bowtie[3 * i] - 0.7 * bowtie[3 * i + 1];
    }
    CHECK_EQ(shape_of(lifted, 4).kind, MT_FACE_SELF_CROSSING);
    /* A pentagram and a heptagram: corners of a regular polygon taken two
     * steps at a time. */
    double star[21];
    star_polygon(5, star);
    CHECK_EQ(shape_of(star, 5).kind, MT_FACE_SELF_CROSSING);
    star_polygon(7, star);
    CHECK_EQ(shape_of(star, 7).kind, MT_FACE_SELF_CROSSING);
    /* Corner 2 lies on side 0 (touching, not crossing). */
    const double touch[] = {0, 0, 0, 2, 0, 0, 1, 0, 0, 1, 1, 0};
    mt_face_shape t = shape_of(touch, 4);
    CHECK_EQ(t.kind, MT_FACE_SELF_CROSSING);
    /* Sides 1 and 2 fold back over each other: all corners on one line. */
    const double line[] = {0, 0, 0, 1, 0, 0, 3, 0, 0, 2, 0, 0};
    CHECK_EQ(shape_of(line, 4).kind, MT_FACE_SELF_CROSSING);
    /* Two corners at one position. */
    const double pinch[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0.5, 0.5, 0, 0, 1, 0, 0.5, 0.5, 0};
    CHECK_EQ(shape_of(pinch, 6).kind, MT_FACE_SELF_CROSSING);
    /* Two consecutive corners at one position: the empty side 1 between
     * them has no line to order it by; sides 0 and 2 touch there. */
    const double repeated[] = {0, 0, 0, 0, 1, 0, 0, 1, 0, 2, 1, 0};
    CHECK_SHAPE(repeated, 4, MT_FACE_SELF_CROSSING, 0, 2);
    /* Corner 3 lies 7e-18 below side 0's line (exactly; in doubles the
     * orientation rounds to 0): simple. */
    const double near[] = {0, 0, 0, 3, 1, 0, 3, -1, 0, 0.1, 0.03333333333333333, 0};
    CHECK_EQ(shape_of(near, 4).kind, MT_FACE_SIMPLE);
}

static void test_shape_warped(void)
{
    const double warped[] = {0, 0, 0, 1, 0, 0, 1, 1, 0.3, 0, 1, 0};
    mt_face_shape w = shape_of(warped, 4);
    CHECK_EQ(w.kind, MT_FACE_WARPED);
    CHECK(w.warp > MT_FACE_WARP_TOLERANCE && w.warp < 0.1);
    CHECK_EQ(w.side_a, MT_NONE);
    const double barely[] = {0, 0, 0, 1, 0, 0, 1, 1, 1e-6, 0, 1, 0};
    mt_face_shape b = shape_of(barely, 4);
    CHECK_EQ(b.kind, MT_FACE_SIMPLE);
    CHECK(b.warp > 0 && b.warp < MT_FACE_WARP_TOLERANCE);
}

static void test_shape_large_polygon(void)
{
    const uint32_t n = 1000;
    double *p = malloc(3 * n * sizeof *p);
    for (uint32_t i = 0; i < n; i++) {
        double a = 2 * 3.14159265358979323846 * i / n;
        p[3 * i] = cos(a);
        p[3 * i + 1] = sin(a);
        p[3 * i + 2] = 0;
    }
    CHECK_SHAPE(p, n, MT_FACE_SIMPLE, MT_NONE, MT_NONE);
    /* Corner 500 pulled across the circle: its two sides cross others. */
    p[3 * 500] = 2;
    p[3 * 500 + 1] = 0.001;
    CHECK_EQ(shape_of(p, n).kind, MT_FACE_SELF_CROSSING);
    free(p);
}

/* ---- an independent check: every pair of sides, exactly as the shape's
 * definition says ---- */

static double orient2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static int on_segment(const double *a, const double *b, const double *c)
{
    return fmin(a[0], b[0]) <= c[0] && c[0] <= fmax(a[0], b[0]) && fmin(a[1], b[1]) <= c[1] &&
           c[1] <= fmax(a[1], b[1]);
}

static int brute_crossing(const double (*q)[2], uint32_t n)
{
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = i + 1; j < n; j++) {
            const double *a = q[i], *b = q[(i + 1) % n], *c = q[j], *d = q[(j + 1) % n];
            if (j == i + 1 || (i == 0 && j == n - 1)) {
                /* neighbours: only a fold back over the shared corner */
                const double *s = j == i + 1 ? b : a, *x = j == i + 1 ? a : b,
                             *y = j == i + 1 ? d : c;
                if (orient2(s, x, y) == 0 &&
                    (x[0] - s[0]) * (y[0] - s[0]) + (x[1] - s[1]) * (y[1] - s[1]) > 0)
                    return 1;
                continue;
            }
            double d1 = orient2(c, d, a), d2 = orient2(c, d, b), d3 = orient2(a, b, c),
                   d4 = orient2(a, b, d);
            if (((d1 > 0) != (d2 > 0) && d1 != 0 && d2 != 0) &&
                ((d3 > 0) != (d4 > 0) && d3 != 0 && d4 != 0))
                return 1;
            if ((d1 == 0 && on_segment(c, d, a)) || (d2 == 0 && on_segment(c, d, b)) ||
                (d3 == 0 && on_segment(a, b, c)) || (d4 == 0 && on_segment(a, b, d)))
                return 1;
        }
    return 0;
}

static void test_shape_random_against_pairs(void)
{
    uint64_t state = 12345;
    int crossing = 0, simple = 0;
    for (int t = 0; t < 2000; t++) {
        uint32_t n = 4 + (uint32_t)(t % 9);
        double p[3 * 12], q[12][2];
        for (uint32_t i = 0; i < n; i++) {
            for (int d = 0; d < 2; d++) {
                state = state * 6364136223846793005ull + 1442695040888963407ull;
                /* a coarse grid makes touching and collinear cases common */
                q[i][d] = (double)((state >> 33) % 7);
            }
            p[3 * i] = q[i][0];
            p[3 * i + 1] = q[i][1];
            p[3 * i + 2] = 0;
        }
        /* Skip polygons with coincident consecutive corners (a repeated
         * vertex is a different, combinatorial defect) or all on one line
         * with fewer than two distinct x and y (no plane to speak of). */
        int skip = 0;
        for (uint32_t i = 0; i < n; i++)
            if (q[i][0] == q[(i + 1) % n][0] && q[i][1] == q[(i + 1) % n][1]) skip = 1;
        if (skip) continue;
        int want = brute_crossing((const double(*)[2])q, n);
        mt_face_shape got = shape_of(p, n);
        int have = got.kind == MT_FACE_SELF_CROSSING;
        if (have != want)
            mt_test_fail(__FILE__, __LINE__, "polygon %d (%u corners): sweep says %d, pairs say %d",
                         t, n, have, want);
        crossing += want;
        simple += !want;
    }
    CHECK(crossing > 100 && simple > 100); /* both kinds were tried */
}

static void test_shape_whole_mesh(void)
{
    /* Faces: a square, a bowtie, a warped quad, a triangle. */
    double positions[] = {0,  0, 0, 1,  0, 0, 1,  1, 0,   0,  1, 0, /* 0-3 square */
                          5,  0, 0, 6,  1, 0, 6,  0, 0,   5,  1, 0, /* 4-7 bowtie */
                          10, 0, 0, 11, 0, 0, 11, 1, 0.5, 10, 1, 0, /* 8-11 warped */
                          20, 0, 0, 21, 0, 0, 20, 1, 0};            /* 12-14 triangle */
    uint32_t sizes[] = {4, 4, 4, 3};
    uint32_t indices[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14};
    mt_face_list list = {15, 4, 15, positions, sizes, indices};
    mt_mesh *mesh = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(&list, NULL, &mesh, &diag));
    if (!mesh) return;
    size_t count = 0;
    CHECK_OK(mt_mesh_nonsimple_faces(mesh, NULL, 0, &count, &diag));
    CHECK_EQ(count, 2);
    mt_face_shape one[1];
    CHECK_STATUS(mt_mesh_nonsimple_faces(mesh, one, 1, &count, &diag), MT_ERR_BUFFER_TOO_SMALL);
    CHECK_EQ(count, 2);
    CHECK_EQ(one[0].face, 1);
    mt_face_shape all[2];
    CHECK_OK(mt_mesh_nonsimple_faces(mesh, all, 2, &count, &diag));
    CHECK(all[0].face == 1 && all[0].kind == MT_FACE_SELF_CROSSING && all[0].side_a == 0 &&
          all[0].side_b == 2);
    CHECK(all[1].face == 2 && all[1].kind == MT_FACE_WARPED);
    mt_face_shape s;
    CHECK_STATUS(mt_face_shape_of(mesh, 9, &s, &diag), MT_ERR_OUT_OF_RANGE);
    CHECK(strstr(diag.message, "face 9") != NULL);
    mt_mesh_destroy(mesh);
    /* Without positions. */
    mt_face_list bare = {15, 4, 15, NULL, sizes, indices};
    CHECK_OK(mt_mesh_build(&bare, NULL, &mesh, &diag));
    CHECK_STATUS(mt_mesh_nonsimple_faces(mesh, NULL, 0, &count, &diag), MT_ERR_NO_GEOMETRY);
    mt_mesh_destroy(mesh);
}

/* Triangulating a face that crosses itself is refused, naming the sides, and
 * changes nothing; a simple concave face still triangulates. */
static void test_shape_triangulate_refused(void)
{
    double star[15];
    star_polygon(5, star);
    mt_mesh *mesh = polygon_mesh(star, 5);
    if (!mesh) return;
    mt_diag diag;
    uint32_t added = 99;
    CHECK_STATUS(mt_face_triangulate(mesh, 0, &added, &diag), MT_ERR_REFUSED);
    CHECK(strstr(diag.message, "face 0 crosses itself") != NULL);
    CHECK(strstr(diag.message, "sides") != NULL);
    CHECK_EQ(added, 99);
    CHECK_STATUS(mt_mesh_triangulate(mesh, &diag), MT_ERR_REFUSED);
    CHECK_EQ(mt_mesh_num_faces(mesh), 1);
    uint32_t verts[5];
    size_t n = 0;
    CHECK_OK(mt_face_verts(mesh, 0, verts, 5, &n));
    CHECK_EQ(n, 5);
    for (uint32_t i = 0; i < 5; i++) CHECK_EQ(verts[i], i);
    mt_mesh_destroy(mesh);

    const double arrow[] = {0, 0, 0, 2, 1, 0, 0, 2, 0, 0.5, 1, 0, 0.2, 0.8, 0};
    mesh = polygon_mesh(arrow, 5);
    if (!mesh) return;
    CHECK_OK(mt_face_triangulate(mesh, 0, &added, &diag));
    CHECK_EQ(added, 2);
    mt_mesh_destroy(mesh);
}

/* Whether {a0, a1} is the undirected edge {b0, b1}. */
static int same_edge(const uint32_t *a, uint32_t b0, uint32_t b1)
{
    return (a[0] == b0 && a[1] == b1) || (a[0] == b1 && a[1] == b0);
}

/* Boundary loops: a fan whose rim is a pentagram has one loop that crosses
 * itself; a crossed quad's loop is its own sides; a grid's is simple. */
static void test_shape_boundary_loops(void)
{
    double p[3 * 6] = {0, 0, 0.1};
    star_polygon(5, p + 3);
    uint32_t sizes[5] = {3, 3, 3, 3, 3}, idx[15];
    for (uint32_t i = 0; i < 5; i++) {
        idx[3 * i] = 0;
        idx[3 * i + 1] = 1 + i;
        idx[3 * i + 2] = 1 + (i + 1) % 5;
    }
    mt_face_list fan = {6, 5, 15, p, sizes, idx};
    mt_mesh *mesh = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(&fan, NULL, &mesh, &diag));
    if (!mesh) return;
    size_t count = 0;
    CHECK_STATUS(mt_mesh_boundary_loop_crossings(mesh, NULL, 0, &count, &diag), MT_OK);
    CHECK_EQ(count, 1);
    mt_loop_crossing c;
    CHECK_OK(mt_mesh_boundary_loop_crossings(mesh, &c, 1, &count, &diag));
    CHECK_EQ(c.loop, 0);
    /* Rim edges i: (1 + i, 1 + (i + 1) % 5); two that are not neighbours. */
    int a = -1, b = -1;
    for (int i = 0; i < 5; i++) {
        if (same_edge(c.edge_a, 1 + i, 1 + (i + 1) % 5)) a = i;
        if (same_edge(c.edge_b, 1 + i, 1 + (i + 1) % 5)) b = i;
    }
    CHECK(a >= 0 && b >= 0 && a != b && (a + 1) % 5 != b && (b + 1) % 5 != a);
    mt_mesh_destroy(mesh);

    const double bowtie[] = {0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0};
    mesh = polygon_mesh(bowtie, 4);
    if (!mesh) return;
    CHECK_OK(mt_mesh_boundary_loop_crossings(mesh, &c, 1, &count, &diag));
    CHECK_EQ(count, 1);
    CHECK((same_edge(c.edge_a, 0, 1) && same_edge(c.edge_b, 2, 3)) ||
          (same_edge(c.edge_a, 2, 3) && same_edge(c.edge_b, 0, 1)));
    mt_mesh_destroy(mesh);

    mt_face_list grid;
    CHECK_OK(mt_gen_grid(20, 10, true, &grid));
    CHECK_OK(mt_mesh_build(&grid, NULL, &mesh, &diag));
    CHECK_OK(mt_mesh_boundary_loop_crossings(mesh, NULL, 0, &count, &diag));
    CHECK_EQ(count, 0);
    mt_mesh_destroy(mesh);
    double *positions = grid.positions;
    grid.positions = NULL;
    CHECK_OK(mt_mesh_build(&grid, NULL, &mesh, &diag));
    CHECK_STATUS(mt_mesh_boundary_loop_crossings(mesh, NULL, 0, &count, &diag), MT_ERR_NO_GEOMETRY);
    mt_mesh_destroy(mesh);
    grid.positions = positions;
    mt_face_list_free(&grid);
}

static const mt_test_case cases[] = {
    {"shape_boundary_loops", test_shape_boundary_loops},
    {"shape_triangulate_refused", test_shape_triangulate_refused},
    {"shape_simple", test_shape_simple},
    {"shape_crossing", test_shape_crossing},
    {"shape_warped", test_shape_warped},
    {"shape_large_polygon", test_shape_large_polygon},
    {"shape_random_against_pairs", test_shape_random_against_pairs},
    {"shape_whole_mesh", test_shape_whole_mesh},
};
const mt_test_table mt_tests_geometry_shape = {cases, sizeof cases / sizeof cases[0]};
