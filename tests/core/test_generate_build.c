/* Tests that build every generated shape with mt_mesh_build: the mesh must
 * validate and its topology report must say what the shape is (closed,
 * manifold, orientable, genus, boundary loops, the one defect of the bowtie
 * and the fin), also after mt_face_list_permute. */
#include <stdbool.h>
#include <string.h>

#include "harness.h"
#include "meshtopo/generate.h"
#include "meshtopo/mesh.h"
#include "meshtopo/report.h"
#include "meshtopo/validate.h"

/* What a report must say about a generated shape. */
typedef struct expect {
    int64_t euler;
    bool closed, manifold, orientable;
    int32_t genus;           /* -1: undefined */
    uint32_t boundary_loops; /* when closed: 0 */
    uint64_t boundary_edges;
} expect;

/* Builds l, validates it and checks the report against e; frees l. */
static void check_build(mt_face_list *l, const expect *e, const char *what)
{
    const int failures_before = mt_test_failures();
    mt_mesh *m = NULL;
    mt_diag diag;
    mt_diag_clear(&diag);
    CHECK_OK(mt_mesh_build(l, NULL, &m, &diag));
    if (!m) {
        mt_test_fail(__FILE__, __LINE__, "%s: build failed: %s", what, diag.message);
        mt_face_list_free(l);
        return;
    }
    CHECK_OK(mt_mesh_validate(m, &diag));
    const mt_report *r = mt_mesh_report(m);
    CHECK_EQ(r->num_verts, l->num_verts);
    CHECK_EQ(r->num_faces, l->num_faces);
    CHECK_EQ(r->num_faces_valid, l->num_faces);
    CHECK_EQ(r->num_half_edges, l->num_indices);
    CHECK_EQ(r->euler_characteristic, e->euler);
    CHECK_EQ(r->closed, e->closed);
    CHECK_EQ(r->manifold, e->manifold);
    CHECK_EQ(r->orientable, e->orientable);
    CHECK_EQ(r->genus, e->genus);
    CHECK_EQ(r->boundary_loops, e->boundary_loops);
    CHECK_EQ(r->boundary_edges, e->boundary_edges);
    CHECK_EQ(r->connected_components, 1);
    CHECK_EQ(r->isolated_vertices, 0);
    CHECK_EQ(r->degenerate_faces, 0);
    CHECK_EQ(r->duplicate_faces, 0);
    CHECK_EQ(r->out_of_range_indices, 0);
    CHECK_EQ(r->nonfinite_vertices, 0);
    if (mt_test_failures() > failures_before)
        mt_test_fail(__FILE__, __LINE__, "(while checking %s)", what);
    mt_mesh_destroy(m);
    mt_face_list_free(l);
}

/* A closed, consistently oriented surface of the given genus. */
static void check_closed(mt_face_list *l, int32_t genus, const char *what)
{
    expect e = {2 - 2 * genus, true, true, true, genus, 0, 0};
    const uint64_t indices = l->num_indices;
    mt_mesh *m = NULL;
    if (mt_mesh_build(l, NULL, &m, NULL) == MT_OK) {
        const mt_report *r = mt_mesh_report(m);
        CHECK(r->consistently_oriented);
        CHECK_EQ(r->num_edges, indices / 2);
        CHECK_EQ(r->nonmanifold_vertices, 0);
        CHECK_EQ(r->inconsistent_orientation_edges, 0);
        CHECK_EQ(r->duplicate_directed_edges, 0);
        mt_mesh_destroy(m);
    }
    check_build(l, &e, what);
}

static void test_gen_build_platonic(void)
{
    const mt_platonic kinds[] = {MT_TETRAHEDRON, MT_CUBE, MT_OCTAHEDRON, MT_DODECAHEDRON,
                                 MT_ICOSAHEDRON};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        mt_face_list l;
        CHECK_OK(mt_gen_platonic(kinds[k], &l));
        check_closed(&l, 0, "platonic");
    }
}

static void test_gen_build_surfaces(void)
{
    mt_face_list l;
    CHECK_OK(mt_gen_torus(12, 7, &l));
    check_closed(&l, 1, "torus 12x7");
    CHECK_OK(mt_gen_torus(3, 3, &l));
    check_closed(&l, 1, "torus 3x3");
    for (uint32_t level = 0; level <= 4; level++) {
        CHECK_OK(mt_gen_icosphere(level, &l));
        check_closed(&l, 0, "icosphere");
    }
    CHECK_OK(mt_gen_double_torus(4, &l));
    check_closed(&l, 2, "double torus 4");
    CHECK_OK(mt_gen_double_torus(9, &l));
    check_closed(&l, 2, "double torus 9");
}

static void test_gen_build_open(void)
{
    mt_face_list l;
    const expect disk4 = {1, false, true, true, -1, 1, 4};
    CHECK_OK(mt_gen_rectangle(2.0, 1.0, &l));
    check_build(&l, &disk4, "rectangle");

    const expect grid_tri = {1, false, true, true, -1, 1, 2 * (6 + 4)};
    CHECK_OK(mt_gen_grid(6, 4, true, &l));
    check_build(&l, &grid_tri, "grid 6x4 triangles");
    CHECK_OK(mt_gen_grid(6, 4, false, &l));
    check_build(&l, &grid_tri, "grid 6x4 quads");

    for (uint32_t n = 3; n <= 12; n += 9) {
        CHECK_OK(mt_gen_moebius(n, &l));
        mt_mesh *m = NULL;
        if (mt_mesh_build(&l, NULL, &m, NULL) == MT_OK) {
            const mt_report *r = mt_mesh_report(m);
            CHECK(!r->consistently_oriented);
            CHECK_EQ(r->inconsistent_orientation_edges, 1);
            CHECK_EQ(r->components[0].genus_with_boundary, -1);
            CHECK_EQ(r->boundary_loop_lengths[0], 2 * n);
            mt_mesh_destroy(m);
        }
        const expect moebius = {0, false, true, false, -1, 1, 2 * n};
        check_build(&l, &moebius, "moebius");
    }
}

static void test_gen_build_defects(void)
{
    mt_face_list l;
    mt_mesh *m = NULL;
    CHECK_OK(mt_gen_bowtie(&l));
    CHECK_OK(mt_mesh_build(&l, NULL, &m, NULL));
    if (m) {
        CHECK_OK(mt_mesh_validate(m, NULL));
        const mt_report *r = mt_mesh_report(m);
        CHECK_EQ(r->bowtie_vertices, 1);
        CHECK_EQ(r->nonmanifold_vertices, 1);
        CHECK_EQ(r->nonmanifold_edges, 0);
        CHECK(!r->manifold);
        CHECK_EQ(r->connected_components, 2);
        CHECK_EQ(r->vertex_connected_components, 1);
        CHECK_EQ(r->boundary_edges, 6);
        CHECK_EQ(mt_report_count_defects(r, MT_DEFECT_NONMANIFOLD_VERTEX), 1);
        mt_mesh_destroy(m);
    }
    mt_face_list_free(&l);

    CHECK_OK(mt_gen_fin(&l));
    m = NULL;
    CHECK_OK(mt_mesh_build(&l, NULL, &m, NULL));
    if (m) {
        CHECK_OK(mt_mesh_validate(m, NULL));
        const mt_report *r = mt_mesh_report(m);
        CHECK_EQ(r->nonmanifold_edges, 1);
        CHECK_EQ(r->bowtie_vertices, 0);
        CHECK(!r->manifold);
        CHECK(r->orientable); /* an edge of three faces adds no constraint */
        CHECK_EQ(r->connected_components, 1);
        CHECK_EQ(r->num_edges, 7);
        CHECK_EQ(mt_report_count_defects(r, MT_DEFECT_NONMANIFOLD_EDGE), 1);
        mt_mesh_destroy(m);
    }
    mt_face_list_free(&l);

    /* Strict mode refuses both. */
    const mt_build_options strict = {.strict = true};
    CHECK_OK(mt_gen_bowtie(&l));
    m = NULL;
    CHECK_STATUS(mt_mesh_build(&l, &strict, &m, NULL), MT_ERR_DEFECT);
    CHECK(m == NULL);
    mt_face_list_free(&l);
    CHECK_OK(mt_gen_fin(&l));
    CHECK_STATUS(mt_mesh_build(&l, &strict, &m, NULL), MT_ERR_DEFECT);
    CHECK(m == NULL);
    mt_face_list_free(&l);
}

/* Shuffling ids and face order changes nothing in the report's topology. */
static void test_gen_build_permuted(void)
{
    mt_face_list l;
    CHECK_OK(mt_gen_double_torus(5, &l));
    CHECK_OK(mt_face_list_permute(&l, 99, NULL));
    check_closed(&l, 2, "permuted double torus");
    CHECK_OK(mt_gen_icosphere(3, &l));
    CHECK_OK(mt_face_list_permute(&l, 1, NULL));
    check_closed(&l, 0, "permuted icosphere");
    CHECK_OK(mt_gen_moebius(20, &l));
    CHECK_OK(mt_face_list_permute(&l, 5, NULL));
    const expect moebius = {0, false, true, false, -1, 1, 40};
    check_build(&l, &moebius, "permuted moebius");
}

static const mt_test_case cases[] = {
    {"gen_build_platonic", test_gen_build_platonic},
    {"gen_build_surfaces", test_gen_build_surfaces},
    {"gen_build_open", test_gen_build_open},
    {"gen_build_defects", test_gen_build_defects},
    {"gen_build_permuted", test_gen_build_permuted},
};
const mt_test_table mt_tests_generate_build = {cases, sizeof cases / sizeof cases[0]};
