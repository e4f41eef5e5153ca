/* Tests of mt_gen_dual: the duals of the five Platonic solids have the
 * counts and face sizes of their partners (cube <-> octahedron, icosahedron
 * <-> dodecahedron, the tetrahedron its own), their centroid positions, and
 * consistent orientation; the dual of the dual gives back every face's
 * corners up to rotation; an open grid's dual covers its interior vertices
 * only; a mesh without positions gives a dual without them. */
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "meshtopo/core.h"

static mt_mesh *build(const mt_face_list *list)
{
    mt_mesh *m = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(list, NULL, &m, &diag));
    return m;
}

/* Face i of list, from its offset. */
static const uint32_t *face_of(const mt_face_list *list, uint32_t i)
{
    uint64_t at = 0;
    for (uint32_t k = 0; k < i; k++) at += list->face_sizes[k];
    return list->face_indices + at;
}

/* Whether a and b hold the same cycle, up to rotation. */
static int same_cycle(const uint32_t *a, const uint32_t *b, uint32_t n)
{
    for (uint32_t r = 0; r < n; r++) {
        uint32_t k = 0;
        while (k < n && a[k] == b[(k + r) % n]) k++;
        if (k == n) return 1;
    }
    return 0;
}

static void test_dual_platonic(void)
{
    const struct {
        mt_platonic solid, partner;
    } pairs[] = {{MT_TETRAHEDRON, MT_TETRAHEDRON},
                 {MT_CUBE, MT_OCTAHEDRON},
                 {MT_OCTAHEDRON, MT_CUBE},
                 {MT_ICOSAHEDRON, MT_DODECAHEDRON},
                 {MT_DODECAHEDRON, MT_ICOSAHEDRON}};
    for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++) {
        mt_face_list solid, partner, dual, dual2;
        CHECK_OK(mt_gen_platonic(pairs[p].solid, &solid));
        CHECK_OK(mt_gen_platonic(pairs[p].partner, &partner));
        mt_mesh *m = build(&solid);
        mt_diag diag;
        CHECK_OK(mt_gen_dual(m, &dual, &diag));
        CHECK_EQ(dual.num_verts, partner.num_verts);
        CHECK_EQ(dual.num_faces, partner.num_faces);
        CHECK_EQ(dual.num_faces, solid.num_verts); /* dual face v is vertex v */
        for (uint32_t f = 0; f < dual.num_faces; f++)
            CHECK_EQ(dual.face_sizes[f], partner.face_sizes[0]);
        /* Dual vertex f at the centroid of face f. */
        for (uint32_t f = 0; f < dual.num_verts; f++) {
            double c[3];
            CHECK_OK(mt_face_centroid(m, f, c, NULL));
            CHECK(memcmp(c, dual.positions + 3 * f, sizeof c) == 0);
        }
        /* A closed, manifold, consistently oriented solid of the partner's
         * topology: same V, E, F, genus 0, no defect. */
        mt_mesh *d = build(&dual);
        const mt_report *r = mt_mesh_report(d);
        CHECK(r->closed && r->manifold && r->consistently_oriented && r->num_defects == 0);
        CHECK_EQ(r->num_edges, mt_mesh_report(m)->num_edges);
        CHECK_EQ(r->genus, 0);
        /* Every dual vertex has the valence of the solid's face size. */
        for (uint32_t v = 0; v < dual.num_verts; v++) {
            uint32_t valence = 0;
            CHECK_OK(mt_vert_valence(d, v, &valence));
            CHECK_EQ(valence, solid.face_sizes[v]);
        }
        /* Orientation kept: outward normals on both. */
        double n0[3], c0[3];
        CHECK_OK(mt_face_normal(d, 0, n0, NULL));
        CHECK_OK(mt_face_centroid(d, 0, c0, NULL));
        CHECK(n0[0] * c0[0] + n0[1] * c0[1] + n0[2] * c0[2] > 0);
        /* The dual of the dual: the solid's faces again. */
        CHECK_OK(mt_gen_dual(d, &dual2, &diag));
        CHECK_EQ(dual2.num_verts, solid.num_verts);
        CHECK_EQ(dual2.num_faces, solid.num_faces);
        for (uint32_t f = 0; f < solid.num_faces; f++) {
            CHECK_EQ(dual2.face_sizes[f], solid.face_sizes[f]);
            if (!same_cycle(face_of(&dual2, f), face_of(&solid, f), solid.face_sizes[f]))
                mt_test_fail(__FILE__, __LINE__, "solid %d face %u: the dual's dual differs",
                             (int)pairs[p].solid, f);
        }
        mt_mesh_destroy(d);
        mt_mesh_destroy(m);
        mt_face_list_free(&dual2);
        mt_face_list_free(&dual);
        mt_face_list_free(&partner);
        mt_face_list_free(&solid);
    }
}

static void test_dual_open_and_bare(void)
{
    /* A 4 x 3 grid of quads has 3 x 2 interior vertices: 6 dual faces. */
    mt_face_list grid, dual;
    CHECK_OK(mt_gen_grid(4, 3, false, &grid));
    mt_mesh *m = build(&grid);
    mt_diag diag;
    CHECK_OK(mt_gen_dual(m, &dual, &diag));
    CHECK_EQ(dual.num_verts, 12);
    CHECK_EQ(dual.num_faces, 6);
    for (uint32_t f = 0; f < 6; f++) CHECK_EQ(dual.face_sizes[f], 4);
    mt_face_list_free(&dual);
    mt_mesh_destroy(m);
    /* Without positions, a dual without them. */
    double *positions = grid.positions;
    grid.positions = NULL;
    m = build(&grid);
    CHECK_OK(mt_gen_dual(m, &dual, &diag));
    CHECK(dual.positions == NULL);
    CHECK_EQ(dual.num_faces, 6);
    mt_face_list_free(&dual);
    mt_mesh_destroy(m);
    grid.positions = positions;
    mt_face_list_free(&grid);
    CHECK_STATUS(mt_gen_dual(NULL, &dual, &diag), MT_ERR_INVALID_ARG);
}

static const mt_test_case cases[] = {
    {"dual_platonic", test_dual_platonic},
    {"dual_open_and_bare", test_dual_open_and_bare},
};
const mt_test_table mt_tests_generate_dual = {cases, sizeof cases / sizeof cases[0]};
