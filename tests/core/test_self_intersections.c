/* Tests of mt_mesh_self_intersections on hand-built meshes whose answers
 * are worked out in the comments: an octahedron with one apex pushed out
 * through the opposite face, two interpenetrating tetrahedra, faces that only
 * touch along what they share, closed fans that wind twice around their
 * vertex, coplanar overlaps and folds, a mesh of
 * degenerate triangles, polygon faces (a concave one whose notch another face
 * passes through), faces skipped for NaN corners or deletion, the size query
 * and a short buffer; and, on a soup of random triangles large enough to be
 * checked on several threads, the same pairs as a check of every pair.
 * mt_mesh_self_intersections_at_most: piles of faces at one place, whose
 * pairs number n(n-1)/2, against the bound on pairs; a stack of parallel
 * triangles that do not cross, each pair of them one exact test, against
 * the bound on tests; and the same least bound on tests for the soup
 * however its threads share the work. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "meshtopo/core.h"
#include "meshtopo/predicates.h"

/* Builds a mesh of the given faces (sizes may be NULL: all triangles). */
static mt_mesh *mesh_of(const double *positions, uint32_t num_verts, const uint32_t *indices,
                        const uint32_t *sizes, uint32_t num_faces)
{
    uint32_t *face_sizes = malloc(num_faces * sizeof *face_sizes);
    uint64_t num_indices = 0;
    for (uint32_t f = 0; f < num_faces; f++) {
        face_sizes[f] = sizes ? sizes[f] : 3;
        num_indices += face_sizes[f];
    }
    mt_face_list list = {num_verts,           num_faces,  num_indices,
                         (double *)positions, face_sizes, (uint32_t *)indices};
    mt_mesh *mesh = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(&list, NULL, &mesh, &diag));
    free(face_sizes);
    return mesh;
}

/* The pairs of mesh as "a-b a-b ..." (at most 64 pairs), for comparison. */
static void pairs_text(const mt_mesh *mesh, char *out, size_t size)
{
    mt_face_pair pairs[64];
    size_t count = 0;
    mt_diag diag;
    out[0] = '\0';
    CHECK_OK(mt_mesh_self_intersections(mesh, pairs, 64, &count, &diag));
    size_t used = 0;
    for (size_t i = 0; i < count && i < 64; i++)
        used += (size_t)snprintf(out + used, size - used, "%s%u-%u", i ? " " : "", pairs[i].a,
                                 pairs[i].b);
}

#define CHECK_PAIRS(mesh, want)                                                           \
    do {                                                                                  \
        char got[1024];                                                                   \
        pairs_text(mesh, got, sizeof got);                                                \
        if (strcmp(got, want) != 0)                                                       \
            mt_test_fail(__FILE__, __LINE__, "pairs \"%s\", expected \"%s\"", got, want); \
    } while (0)

/* The octahedron with vertices +-x (0, 1), +-y (2, 3), +-z (4, 5); faces 0-3
 * around the top apex, 4-7 around the bottom one, all outward. */
static const uint32_t octahedron_faces[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                                            2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};

static void test_selfx_octahedron_pushed_through(void)
{
    double pos[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    mt_mesh *mesh = mesh_of(pos, 6, octahedron_faces, NULL, 8);
    CHECK_PAIRS(mesh, "");
    mt_mesh_destroy(mesh);
    /* The top apex pushed down to (0.5, 0.5, -0.5), past face 4 (+x, +y,
     * -z; plane x + y - z = 1, the apex at 1.5). Edges -x..apex and
     * -y..apex leave the bottom pyramid through face 4, at (0.2, 0.4, -0.4)
     * and (0.4, 0.2, -0.4): faces 1, 2 and 3 (which hold those edges) pass
     * through face 4. Face 0 shares the edge +x..+y with face 4 and turns
     * about it, meeting it nowhere else. */
    pos[12] = 0.5, pos[13] = 0.5, pos[14] = -0.5;
    mesh = mesh_of(pos, 6, octahedron_faces, NULL, 8);
    CHECK_PAIRS(mesh, "1-4 2-4 3-4");
    mt_mesh_destroy(mesh);
}

static void test_selfx_interpenetrating_tetrahedra(void)
{
    /* Tetrahedron A (0-3) and a smaller one B (4-7) whose top corner
     * (0.2, 0.2, 0.1) is inside A and whose base is at z = -0.5: B's three
     * sides cross A's bottom face (z = 0, face 0) inside it and meet
     * nothing else of A (they keep x, y >= 0.1 and x + y + z <= 0.5). */
    const double pos[] = {0,   0,   0,   1,   0,   0,    0,   1,   0,    0,   0,   1,
                          0.2, 0.2, 0.1, 0.1, 0.1, -0.5, 0.4, 0.1, -0.5, 0.1, 0.4, -0.5};
    const uint32_t faces[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2,
                              4, 5, 6, 4, 6, 7, 4, 7, 5, 5, 7, 6};
    mt_mesh *mesh = mesh_of(pos, 8, faces, NULL, 8);
    CHECK_PAIRS(mesh, "0-4 0-5 0-6");
    mt_mesh_destroy(mesh);
}

static void test_selfx_touching_not_crossing(void)
{
    /* Faces that meet only in what they share: a closed tetrahedron; a flat
     * strip (coplanar triangles on both sides of their shared edge); two
     * coplanar triangles sharing a vertex whose sides leave it in opposite
     * directions along one line; a triangle whose side passes through the
     * plane of another exactly at their shared vertex. */
    const double tet[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint32_t tet_faces[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    mt_mesh *mesh = mesh_of(tet, 4, tet_faces, NULL, 4);
    CHECK_PAIRS(mesh, "");
    mt_mesh_destroy(mesh);

    const double strip[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const uint32_t strip_faces[] = {0, 1, 2, 1, 3, 2};
    mesh = mesh_of(strip, 4, strip_faces, NULL, 2);
    CHECK_PAIRS(mesh, "");
    mt_mesh_destroy(mesh);

    const double bow[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, 1, 0};
    const uint32_t bow_faces[] = {0, 1, 2, 0, 4, 3};
    mesh = mesh_of(bow, 5, bow_faces, NULL, 2);
    CHECK_PAIRS(mesh, "");
    mt_mesh_destroy(mesh);

    /* Face 0 in z = 0 (x, y >= 0); face 1 crosses that plane along the -y
     * axis, which leaves face 0 at their shared vertex 0. */
    const double stand[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, -1, -1, -1, 1, -1, 1};
    const uint32_t stand_faces[] = {0, 1, 2, 0, 3, 4};
    mesh = mesh_of(stand, 5, stand_faces, NULL, 2);
    CHECK_PAIRS(mesh, "");
    mt_mesh_destroy(mesh);
}

/* A double pyramid over the five points a_i at 144 i degrees on the unit
 * circle (z = 0), apexes v = (0, 0, 1) and w = (0, 0, -1): top faces
 * T_i = (v, a_i, a_i+1) (ids 0-4), bottom faces B_i = (w, a_i+1, a_i)
 * (ids 5-9). A closed manifold mesh, every vertex with one closed fan.
 * With step 72 degrees (`winding` 1) the base is a pentagon and nothing
 * crosses. With step 144 (winding 2) it is a pentagram: the fans of v and
 * w wind twice around them, so they are not flat, and chord i of the base
 * crosses chords i + 2 and i + 3. T_i and T_j of crossing chords share v
 * and meet along a segment from it (5 pairs), B_i and B_j likewise (5),
 * and T_i meets B_j where chords i and j cross (10). */
static mt_mesh *double_pyramid(int winding)
{
    double pos[3 * 7] = {0, 0, 1, 0, 0, -1};
    uint32_t faces[3 * 10];
    for (uint32_t i = 0; i < 5; i++) {
        const double angle = winding * 72.0 * i * 3.14159265358979323846 / 180.0;
        pos[3 * (2 + i)] = cos(angle);
        pos[3 * (2 + i) + 1] = sin(angle);
        pos[3 * (2 + i) + 2] = 0;
        const uint32_t a = 2 + i, b = 2 + (i + 1) % 5;
        const uint32_t top[3] = {0, a, b}, bottom[3] = {1, b, a};
        memcpy(faces + 3 * i, top, sizeof top);
        memcpy(faces + 3 * (5 + i), bottom, sizeof bottom);
    }
    return mesh_of(pos, 7, faces, NULL, 10);
}

static void test_selfx_fans_winding_twice(void)
{
    mt_mesh *mesh = double_pyramid(1);
    CHECK_PAIRS(mesh, "");
    mt_mesh_destroy(mesh);
    mesh = double_pyramid(2);
    CHECK_PAIRS(mesh,
                "0-2 0-3 0-7 0-8 1-3 1-4 1-8 1-9 2-4 2-5 2-9 3-5 3-6 4-6 4-7 "
                "5-7 5-8 6-8 6-9 7-9");
    mt_mesh_destroy(mesh);
}

static void test_selfx_coplanar(void)
{
    /* Two triangles in z = 0 overlapping, no shared vertex. */
    const double overlap[] = {0, 0, 0, 2, 0, 0, 0, 2, 0, 1, 1, 0, 3, 1, 0, 1, 3, 0};
    const uint32_t overlap_faces[] = {0, 1, 2, 3, 4, 5};
    mt_mesh *mesh = mesh_of(overlap, 6, overlap_faces, NULL, 2);
    CHECK_PAIRS(mesh, "0-1");
    mt_mesh_destroy(mesh);
    /* Two triangles sharing edge 0..1 with their third corners on the same
     * side of it in their common plane: folded onto each other. Also one
     * (face 2) touching face 0 only with its corner (1.5, 1, 0), which lies
     * on face 0's side 1..2 but is not shared (reported: they meet outside
     * what they share). */
    const double fold[] = {0, 0, 0, 2, 0, 0, 1, 2, 0, 1, 1, 0, 5, 0, 0, 4, 1, 0, 1.5, 1, 0};
    const uint32_t fold_faces[] = {0, 1, 2, 1, 0, 3, 4, 5, 6};
    mesh = mesh_of(fold, 7, fold_faces, NULL, 3);
    CHECK_PAIRS(mesh, "0-1 0-2");
    mt_mesh_destroy(mesh);
    /* A duplicate face (same corners, either orientation) covers the other. */
    const uint32_t dup_faces[] = {0, 1, 2, 0, 2, 1};
    mesh = mesh_of(fold, 3, dup_faces, NULL, 2);
    CHECK_PAIRS(mesh, "0-1");
    mt_mesh_destroy(mesh);
}

static void test_selfx_degenerate(void)
{
    /* Every triangle degenerate: 0-4 on the x axis at x = 0, 1, 2, 3, 4;
     * 5-10 all at one point. Face 0 (x 0..2) and face 1 (x 2..4) touch only
     * at their shared vertex 2; face 2 (x 1..4) shares vertices 3 and 4
     * with face 1 and its corner 1 lies past the same end of that side as
     * face 1's corner 2, so they overlap over x 2..3; face 2 shares vertex 1
     * with face 0 and overlaps it over x 1..2; faces 3 and 4 coincide. */
    const double pos[] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0, 5, 5,
                          5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5};
    const uint32_t faces[] = {0, 1, 2, 2, 3, 4, 1, 3, 4, 5, 6, 7, 8, 9, 10};
    mt_mesh *mesh = mesh_of(pos, 11, faces, NULL, 5);
    CHECK_PAIRS(mesh, "0-2 1-2 3-4");
    mt_mesh_destroy(mesh);
    /* The shared side 0-1 is one point (both at the origin), so faces
     * (0, 1, 2) and (1, 0, 3) are segments from it, along +x and along the
     * diagonal: they meet only there. Along one line the same way, they
     * overlap. */
    double tip[] = {0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0};
    const uint32_t tip_faces[] = {0, 1, 2, 1, 0, 3};
    mesh = mesh_of(tip, 4, tip_faces, NULL, 2);
    CHECK_PAIRS(mesh, "");
    mt_mesh_destroy(mesh);
    tip[10] = 0, tip[9] = 2;
    mesh = mesh_of(tip, 4, tip_faces, NULL, 2);
    CHECK_PAIRS(mesh, "0-1");
    mt_mesh_destroy(mesh);
}

static void test_selfx_polygons(void)
{
    /* Face 0: an L-shaped hexagon in z = 0 (the square 0..2 with the
     * corner square 1..2 x 1..2 cut out). Face 1 stands vertically through
     * the notch (x = y = 1.5), inside the hexagon's convex hull but outside
     * the hexagon: not reported.
     * Face 2, a vertical quad, passes through the hexagon at x = 0.5. */
    const double pos[] = {0,   0,   0,  2,   0,   0,  2,   1,   0, 1,   1,   0,
                          1,   2,   0,  0,   2,   0,                             /* hexagon */
                          1.4, 1.6, -1, 1.6, 1.4, -1, 1.5, 1.5, 1,               /* in the notch */
                          0.5, 0.5, -1, 0.5, 0.7, -1, 0.5, 0.7, 1, 0.5, 0.5, 1}; /* through it */
    const uint32_t faces[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    const uint32_t sizes[] = {6, 3, 4};
    mt_mesh *mesh = mesh_of(pos, 13, faces, sizes, 3);
    CHECK_PAIRS(mesh, "0-2");
    mt_mesh_destroy(mesh);
}

static void test_selfx_skipped_faces(void)
{
    /* The pushed-through octahedron with face 2 deleted, then with vertex 1
     * (-x) at NaN: faces 1 and 2, which cross face 4 through it, are not
     * judged. */
    double pos[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0.5, 0.5, -0.5, 0, 0, -1};
    mt_mesh *mesh = mesh_of(pos, 6, octahedron_faces, NULL, 8);
    mt_diag diag;
    CHECK_OK(mt_face_delete(mesh, 2, &diag));
    CHECK_PAIRS(mesh, "1-4 3-4");
    mt_mesh_destroy(mesh);
    pos[3] = NAN;
    mesh = mesh_of(pos, 6, octahedron_faces, NULL, 8);
    CHECK_PAIRS(mesh, "3-4");
    mt_mesh_destroy(mesh);
}

static void test_selfx_buffers_and_errors(void)
{
    double pos[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0.5, 0.5, -0.5, 0, 0, -1};
    mt_mesh *mesh = mesh_of(pos, 6, octahedron_faces, NULL, 8);
    mt_diag diag;
    size_t count = 99;
    CHECK_OK(mt_mesh_self_intersections(mesh, NULL, 0, &count, &diag));
    CHECK_EQ(count, 3);
    mt_face_pair two[2] = {{0, 0}, {0, 0}};
    CHECK_STATUS(mt_mesh_self_intersections(mesh, two, 2, &count, &diag), MT_ERR_BUFFER_TOO_SMALL);
    CHECK_EQ(count, 3);
    CHECK(two[0].a == 1 && two[0].b == 4 && two[1].a == 2 && two[1].b == 4);
    CHECK(strstr(diag.message, "3 pairs") != NULL);
    CHECK_STATUS(mt_mesh_self_intersections(mesh, two, 2, NULL, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_mesh_self_intersections(NULL, two, 2, &count, &diag), MT_ERR_INVALID_ARG);
    mt_mesh_destroy(mesh);
    mesh = mesh_of(NULL, 6, octahedron_faces, NULL, 8);
    CHECK_STATUS(mt_mesh_self_intersections(mesh, NULL, 0, &count, &diag), MT_ERR_NO_GEOMETRY);
    mt_mesh_destroy(mesh);
}

static uint64_t rng_state = 0x9e3779b97f4a7c15u;

static double uniform(void)
{
    rng_state = rng_state * 6364136223846793005u + 1442695040888963407u;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

/* n random triangles of about `size` in the unit cube, each on its own
 * three vertices (pos: 9 n, faces: 3 n), so that every pair is decided by
 * mt_triangles_intersect; some corners are snapped to a coarse lattice so
 * that touching and coplanar cases occur. */
static void random_soup(uint32_t n, double size, double *pos, uint32_t *faces)
{
    for (uint32_t t = 0; t < n; t++) {
        double c[3] = {uniform(), uniform(), uniform()};
        for (int i = 0; i < 3; i++) {
            faces[3 * t + i] = 3 * t + (uint32_t)i;
            for (int k = 0; k < 3; k++) {
                double x = c[k] + size * (uniform() - 0.5);
                if (t % 4 == 0) x = round(x * 64) / 64;
                pos[9 * (size_t)t + 3 * (size_t)i + (size_t)k] = x;
            }
        }
    }
}

static void test_selfx_random_soup_against_pairs(void)
{
    enum { N = 21000 }; /* enough triangles for several threads */
    double *pos = malloc(9 * (size_t)N * sizeof *pos);
    uint32_t *faces = malloc(3 * (size_t)N * sizeof *faces);
    random_soup(N, 0.03, pos, faces);
    mt_mesh *mesh = mesh_of(pos, 3 * N, faces, NULL, N);
    size_t count = 0;
    mt_diag diag;
    CHECK_OK(mt_mesh_self_intersections(mesh, NULL, 0, &count, &diag));
    mt_face_pair *got = malloc((count ? count : 1) * sizeof *got);
    CHECK_OK(mt_mesh_self_intersections(mesh, got, count, &count, &diag));
    /* Every pair, in (a, b) order, with an exact box test first. */
    size_t expected = 0, mismatches = 0;
    for (uint32_t a = 0; a < N; a++) {
        const double(*ta)[3] = (const double(*)[3])(pos + 9 * (size_t)a);
        for (uint32_t b = a + 1; b < N; b++) {
            const double(*tb)[3] = (const double(*)[3])(pos + 9 * (size_t)b);
            bool apart = false;
            for (int k = 0; k < 3 && !apart; k++)
                apart = fmax(fmax(ta[0][k], ta[1][k]), ta[2][k]) <
                            fmin(fmin(tb[0][k], tb[1][k]), tb[2][k]) ||
                        fmax(fmax(tb[0][k], tb[1][k]), tb[2][k]) <
                            fmin(fmin(ta[0][k], ta[1][k]), ta[2][k]);
            if (apart || !mt_triangles_intersect(ta, tb)) continue;
            if (expected >= count || got[expected].a != a || got[expected].b != b) mismatches++;
            expected++;
        }
    }
    CHECK_EQ(count, expected);
    CHECK_EQ(mismatches, 0);
    CHECK(expected > 100); /* the soup is dense enough to test something */
    free(got);
    mt_mesh_destroy(mesh);
    free(pos);
    free(faces);
}

/* n copies of one polygon of `corners` corners (a regular polygon in the
 * plane z = 0), each on vertices of its own: every two meet. */
static mt_mesh *pile_of(uint32_t n, uint32_t corners)
{
    double *pos = malloc(3 * (size_t)n * corners * sizeof *pos);
    uint32_t *indices = malloc((size_t)n * corners * sizeof *indices);
    uint32_t *sizes = malloc(n * sizeof *sizes);
    for (uint32_t f = 0; f < n; f++) {
        sizes[f] = corners;
        for (uint32_t k = 0; k < corners; k++) {
            const uint32_t v = f * corners + k;
            const double turn = 6.283185307179586 * k / corners;
            pos[3 * (size_t)v] = cos(turn);
            pos[3 * (size_t)v + 1] = sin(turn);
            pos[3 * (size_t)v + 2] = 0;
            indices[v] = v;
        }
    }
    mt_mesh *mesh = mesh_of(pos, n * corners, indices, sizes, n);
    free(pos);
    free(indices);
    free(sizes);
    return mesh;
}

static void test_selfx_at_most_counts_pairs_not_repeats(void)
{
    /* 40 quads at one place: 780 pairs of faces, each met by up to four
     * pairs of their triangles, so the repeats pass the bound's doubling
     * (2 * 780 + 64) before the pairs are all found. */
    mt_mesh *mesh = pile_of(40, 4);
    mt_diag diag;
    size_t count = 99;
    CHECK_OK(mt_mesh_self_intersections_at_most(mesh, 780, UINT64_MAX, NULL, 0, &count, &diag));
    CHECK_EQ(count, 780);
    mt_face_pair *all = malloc(780 * sizeof *all);
    CHECK_OK(mt_mesh_self_intersections_at_most(mesh, 780, UINT64_MAX, all, 780, &count, &diag));
    size_t i = 0;
    for (uint32_t a = 0; a < 40; a++)
        for (uint32_t b = a + 1; b < 40; b++, i++) CHECK(all[i].a == a && all[i].b == b);
    CHECK_STATUS(mt_mesh_self_intersections_at_most(mesh, 779, UINT64_MAX, all, 780, &count, &diag),
                 MT_ERR_TOO_LARGE);
    CHECK_EQ(count, 0);
    CHECK(strstr(diag.message, "more than 779 self-intersecting face pairs") != NULL);
    CHECK_OK(mt_mesh_self_intersections(mesh, NULL, 0, &count, &diag));
    CHECK_EQ(count, 780);
    free(all);
    mt_mesh_destroy(mesh);
}

static void test_selfx_at_most_stops_on_a_pile(void)
{
    /* 30000 triangles at one place (enough for several threads) make
     * 449,985,000 pairs: checking them all would take minutes and gigabytes;
     * the bound ends the search soon after its 1000th pair. */
    mt_mesh *mesh = pile_of(30000, 3);
    mt_diag diag;
    size_t count = 99;
    CHECK_STATUS(mt_mesh_self_intersections_at_most(mesh, 1000, UINT64_MAX, NULL, 0, &count, &diag),
                 MT_ERR_TOO_LARGE);
    CHECK_EQ(count, 0);
    CHECK(strstr(diag.message, "more than 1000") != NULL);
    mt_mesh_destroy(mesh);
}

/* n triangles in parallel planes z = c + (x + y) / 2, c 10^-5
 * apart, each on vertices of its own: every two boxes overlap and no two
 * triangles meet, so every pair is one exact test and none is found. */
static mt_mesh *stack_of(uint32_t n)
{
    double *pos = malloc(9 * (size_t)n * sizeof *pos);
    uint32_t *indices = malloc(3 * (size_t)n * sizeof *indices);
    for (uint32_t f = 0; f < n; f++) {
        const double c = 0.00001 * f;
        const double corners[3][3] = {{0, 0, c}, {1, 0, c + 0.5}, {0, 1, c + 0.5}};
        memcpy(pos + 9 * (size_t)f, corners, sizeof corners);
        for (uint32_t k = 0; k < 3; k++) indices[3 * f + k] = 3 * f + k;
    }
    mt_mesh *mesh = mesh_of(pos, 3 * n, indices, NULL, n);
    free(pos);
    free(indices);
    return mesh;
}

static void test_selfx_at_most_bounds_the_tests(void)
{
    /* 600 triangles: exactly 600 * 599 / 2 = 179,700 tests. */
    mt_mesh *mesh = stack_of(600);
    mt_diag diag;
    size_t count = 99;
    CHECK_OK(mt_mesh_self_intersections_at_most(mesh, SIZE_MAX, 179700, NULL, 0, &count, &diag));
    CHECK_EQ(count, 0);
    CHECK_STATUS(mt_mesh_self_intersections_at_most(mesh, SIZE_MAX, 179699, NULL, 0, &count, &diag),
                 MT_ERR_TOO_LARGE);
    CHECK_EQ(count, 0);
    CHECK(strstr(diag.message, "more than 179699 pairs of triangles whose boxes overlap") != NULL);
    mt_mesh_destroy(mesh);
    /* 30000 (several threads): 449,985,000 tests, minutes of work; the
     * bound ends it after its 100,000th. */
    mesh = stack_of(30000);
    CHECK_STATUS(mt_mesh_self_intersections_at_most(mesh, SIZE_MAX, 100000, NULL, 0, &count, &diag),
                 MT_ERR_TOO_LARGE);
    CHECK(strstr(diag.message, "more than 100000 pairs of triangles") != NULL);
    mt_mesh_destroy(mesh);
}

/* Whether the check of mesh passes with at most `tests` tests. */
static bool passes_with(const mt_mesh *mesh, uint64_t tests)
{
    size_t count;
    return mt_mesh_self_intersections_at_most(mesh, SIZE_MAX, tests, NULL, 0, &count, NULL) ==
           MT_OK;
}

static void test_selfx_tests_do_not_depend_on_threads(void)
{
    /* A random soup checked on several threads: the least bound that
     * passes, found by bisection, passes and the one below fails again and
     * again, whatever thread took which part. */
    enum { N = 21000 };
    double *pos = malloc(9 * (size_t)N * sizeof *pos);
    uint32_t *faces = malloc(3 * (size_t)N * sizeof *faces);
    random_soup(N, 0.08, pos, faces);
    mt_mesh *mesh = mesh_of(pos, 3 * N, faces, NULL, N);
    uint64_t fails = 0, passes = 1;
    while (!passes_with(mesh, passes)) fails = passes, passes *= 2;
    while (passes - fails > 1) {
        const uint64_t mid = fails + (passes - fails) / 2;
        if (passes_with(mesh, mid))
            passes = mid;
        else
            fails = mid;
    }
    CHECK(passes > 50000); /* many batches on each thread */
    for (int round = 0; round < 5; round++) {
        CHECK(passes_with(mesh, passes));
        CHECK(!passes_with(mesh, passes - 1));
    }
    mt_mesh_destroy(mesh);
    free(pos);
    free(faces);
}

static const mt_test_case cases[] = {
    {"selfx_octahedron_pushed_through", test_selfx_octahedron_pushed_through},
    {"selfx_interpenetrating_tetrahedra", test_selfx_interpenetrating_tetrahedra},
    {"selfx_touching_not_crossing", test_selfx_touching_not_crossing},
    {"selfx_fans_winding_twice", test_selfx_fans_winding_twice},
    {"selfx_coplanar", test_selfx_coplanar},
    {"selfx_degenerate", test_selfx_degenerate},
    {"selfx_polygons", test_selfx_polygons},
    {"selfx_skipped_faces", test_selfx_skipped_faces},
    {"selfx_buffers_and_errors", test_selfx_buffers_and_errors},
    {"selfx_random_soup_against_pairs", test_selfx_random_soup_against_pairs},
    {"selfx_at_most_counts_pairs_not_repeats", test_selfx_at_most_counts_pairs_not_repeats},
    {"selfx_at_most_stops_on_a_pile", test_selfx_at_most_stops_on_a_pile},
    {"selfx_at_most_bounds_the_tests", test_selfx_at_most_bounds_the_tests},
    {"selfx_tests_do_not_depend_on_threads", test_selfx_tests_do_not_depend_on_threads},
};
const mt_test_table mt_tests_self_intersections = {cases, sizeof cases / sizeof cases[0]};
