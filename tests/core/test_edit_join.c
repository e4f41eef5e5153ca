/* Tests of mt_face_join: two quads of a grid become a hexagon with the
 * right corners, the edge and one face gone and V - E + F unchanged; a
 * whole row joins into one polygon; joining is refused, changing nothing,
 * across a boundary edge and between faces that share more than the edge;
 * on a mesh with a non-manifold edge it is unsupported, as every edit. */
#include <string.h>

#include "harness.h"
#include "meshtopo/core.h"

static mt_mesh *grid_mesh(uint32_t nx, uint32_t ny)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(nx, ny, false, &grid));
    mt_mesh *m = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(&grid, NULL, &m, &diag));
    mt_face_list_free(&grid);
    return m;
}

/* Vertex id of grid corner (x, y) in an nx-wide grid. */
static uint32_t at(uint32_t nx, uint32_t x, uint32_t y)
{
    return y * (nx + 1) + x;
}

static void check_counts(const mt_mesh *m, uint32_t faces, uint64_t edges, int line)
{
    const mt_report *r = mt_mesh_report(m);
    if (r->num_faces_valid != faces || r->num_edges != edges)
        mt_test_fail(__FILE__, line, "%u faces and %llu edges, expected %u and %llu",
                     r->num_faces_valid, (unsigned long long)r->num_edges, faces,
                     (unsigned long long)edges);
    if ((int64_t)r->num_verts - (int64_t)r->num_edges + r->num_faces_valid !=
        r->euler_characteristic)
        mt_test_fail(__FILE__, line, "V - E + F differs from the Euler characteristic");
    if (r->euler_characteristic != 1)
        mt_test_fail(__FILE__, line, "Euler characteristic %lld",
                     (long long)r->euler_characteristic);
    mt_diag diag;
    if (mt_mesh_validate(m, &diag) != MT_OK) mt_test_fail(__FILE__, line, "%s", diag.message);
}

static void test_join_two_quads(void)
{
    mt_mesh *m = grid_mesh(3, 2); /* 6 quads, 17 edges */
    if (!m) return;
    check_counts(m, 6, 17, __LINE__);
    mt_diag diag;
    uint32_t kept = MT_NONE;
    /* The edge between quads 0 and 1: corners (1, 0) - (1, 1). */
    CHECK_OK(mt_face_join(m, at(3, 1, 0), at(3, 1, 1), &kept, &diag));
    check_counts(m, 5, 16, __LINE__);
    CHECK(kept == 0 || kept == 1);
    uint32_t gone = kept == 0 ? 1 : 0, verts[8];
    size_t n = 0;
    CHECK_STATUS(mt_face_verts(m, gone, verts, 8, &n), MT_ERR_NOT_FOUND);
    CHECK_OK(mt_face_verts(m, kept, verts, 8, &n));
    CHECK_EQ(n, 6);
    /* The hexagon's corners: the two quads' six, each once, without the
     * edge: (0,0) (1,0) (2,0) (2,1) (1,1) (0,1) in some rotation. */
    const uint32_t want[6] = {at(3, 0, 0), at(3, 1, 0), at(3, 2, 0),
                              at(3, 2, 1), at(3, 1, 1), at(3, 0, 1)};
    int found = 0;
    for (uint32_t r = 0; r < 6 && !found; r++) {
        uint32_t k = 0;
        while (k < 6 && verts[(k + r) % 6] == want[k]) k++;
        found = k == 6;
    }
    CHECK(found);
    mt_mesh_destroy(m);
}

static void test_join_row(void)
{
    mt_mesh *m = grid_mesh(5, 1); /* one row of 5 quads */
    if (!m) return;
    mt_diag diag;
    for (uint32_t x = 1; x < 5; x++) {
        CHECK_OK(mt_face_join(m, at(5, x, 0), at(5, x, 1), NULL, &diag));
        check_counts(m, 5 - x, 16 - x, __LINE__);
    }
    mt_face_shape shape;
    for (uint32_t f = 0; f < 5; f++) {
        size_t n = 0;
        if (mt_face_verts(m, f, NULL, 0, &n) == MT_ERR_NOT_FOUND) continue;
        CHECK_EQ(n, 12);
        CHECK_OK(mt_face_shape_of(m, f, &shape, &diag));
        CHECK_EQ(shape.kind, MT_FACE_SIMPLE);
    }
    mt_mesh_destroy(m);
}

static void test_join_refused(void)
{
    mt_mesh *m = grid_mesh(2, 2);
    if (!m) return;
    mt_diag diag;
    /* A boundary edge. */
    CHECK_STATUS(mt_face_join(m, at(2, 0, 0), at(2, 1, 0), NULL, &diag), MT_ERR_REFUSED);
    CHECK(strstr(diag.message, "used by 1 face") != NULL);
    /* Rows joined into two hexagons that share the two middle edges. */
    CHECK_OK(mt_face_join(m, at(2, 1, 0), at(2, 1, 1), NULL, &diag));
    CHECK_OK(mt_face_join(m, at(2, 1, 1), at(2, 1, 2), NULL, &diag));
    check_counts(m, 2, 10, __LINE__);
    CHECK_STATUS(mt_face_join(m, at(2, 0, 1), at(2, 1, 1), NULL, &diag), MT_ERR_REFUSED);
    CHECK(strstr(diag.message, "share more than edge") != NULL);
    check_counts(m, 2, 10, __LINE__); /* unchanged */
    /* Not an edge at all. */
    CHECK(mt_face_join(m, at(2, 0, 0), at(2, 2, 2), NULL, &diag) != MT_OK);
    mt_mesh_destroy(m);

    /* Three triangles on one edge: edits need a manifold mesh. */
    double p[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1};
    uint32_t sizes[] = {3, 3, 3}, idx[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    mt_face_list fins = {5, 3, 9, p, sizes, idx};
    CHECK_OK(mt_mesh_build(&fins, NULL, &m, &diag));
    if (!m) return;
    CHECK_STATUS(mt_face_join(m, 0, 1, NULL, &diag), MT_ERR_UNSUPPORTED);
    CHECK(strstr(diag.message, "join faces: mesh has") != NULL);
    CHECK(strstr(diag.message, "edits need a manifold mesh") != NULL);
    mt_mesh_destroy(m);
}

static const mt_test_case cases[] = {
    {"join_two_quads", test_join_two_quads},
    {"join_row", test_join_row},
    {"join_refused", test_join_refused},
};
const mt_test_table mt_tests_edit_join = {cases, sizeof cases / sizeof cases[0]};
