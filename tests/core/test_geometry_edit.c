/* Geometry after in-place edits (edit.h): deleted faces, edges and vertices
 * are skipped by the whole-mesh sweeps. An icosphere with one vertex deleted
 * is a disk: its deficits (pi minus the corner angles on the new boundary)
 * still add up to 2 pi chi = 2 pi, the deleted vertex and faces read as zero,
 * and the dihedral sweep lists exactly the report's current edge count. */
#include <math.h>
#include <stdlib.h>

#include "geometry_mesh.h"
#include "harness.h"
#include "meshtopo/core.h"

#define PI 3.14159265358979323846

static void test_geometry_after_deletion(void)
{
    mt_face_list list;
    CHECK_OK(mt_gen_icosphere(2, &list));
    mt_mesh *m = geom_build(&list, "icosphere");
    mt_face_list_free(&list);
    if (!m) return;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status s = mt_vert_delete(m, 7, &diag);
    if (s != MT_OK) mt_test_fail(__FILE__, __LINE__, "mt_vert_delete: %s", diag.message);
    mt_diag_clear(&diag);
    s = mt_mesh_validate(m, &diag);
    if (s != MT_OK) mt_test_fail(__FILE__, __LINE__, "mt_mesh_validate: %s", diag.message);
    CHECK(mt_vert_is_deleted(m, 7));
    const mt_report *r = mt_mesh_report(m);
    uint32_t nv = mt_mesh_num_verts(m), nf = mt_mesh_num_faces(m);

    double *def = malloc(nv * sizeof *def), *vn = malloc(3 * (size_t)nv * sizeof *vn);
    bool *boundary = malloc(nv);
    size_t count = 0, on_boundary = 0;
    CHECK_OK(mt_mesh_vert_curvature(m, vn, def, boundary, nv, &count, NULL));
    double sum = 0;
    for (uint32_t v = 0; v < nv; v++) {
        sum += def[v];
        on_boundary += boundary[v];
        double d;
        bool b;
        CHECK_OK(mt_vert_angle_deficit(m, v, &d, &b, NULL));
        CHECK_NEAR(d, def[v], 1e-12);
        CHECK_EQ(b, boundary[v]);
    }
    CHECK_NEAR(def[7], 0.0, 0.0);
    CHECK(!boundary[7]);
    CHECK_NEAR(vn[21] * vn[21] + vn[22] * vn[22] + vn[23] * vn[23], 0.0, 0.0);
    CHECK_EQ(on_boundary, 5); /* the ring of the deleted valence-5 vertex */
    CHECK_NEAR(sum, 2 * PI, 1e-9 * 2 * PI);
    CHECK_EQ(r->euler_characteristic, 1);

    /* Deleted faces: zero normal and area in the sweep, NOT_FOUND alone. */
    double *fn = malloc(3 * (size_t)nf * sizeof *fn), *fa = malloc(nf * sizeof *fa);
    CHECK_OK(mt_mesh_face_normals(m, fn, fa, nf, &count, NULL));
    size_t zero = 0;
    for (uint32_t f = 0; f < nf; f++) {
        double a;
        s = mt_face_area(m, f, &a, NULL);
        CHECK(s == MT_OK || s == MT_ERR_NOT_FOUND);
        if (s == MT_ERR_NOT_FOUND) {
            zero++;
            CHECK_NEAR(fa[f], 0.0, 0.0);
        } else {
            CHECK_NEAR(fa[f], a, 1e-15);
            CHECK(a > 0.0);
        }
    }
    CHECK_EQ(zero, 5);

    /* Edges: the report's current count, none of them at vertex 7. */
    CHECK_OK(mt_mesh_dihedral_angles(m, 1e-9, NULL, NULL, NULL, 0, &count, NULL));
    CHECK_EQ(count, r->num_edges);
    uint32_t *edges = malloc(2 * count * sizeof *edges);
    mt_edge_shape *shapes = malloc(count * sizeof *shapes);
    CHECK_OK(mt_mesh_dihedral_angles(m, 1e-9, edges, NULL, shapes, count, &count, NULL));
    size_t boundary_edges = 0;
    for (size_t e = 0; e < count; e++) {
        CHECK(edges[2 * e] != 7 && edges[2 * e + 1] != 7);
        boundary_edges += shapes[e] == MT_EDGE_BOUNDARY;
        CHECK(shapes[e] == MT_EDGE_BOUNDARY || shapes[e] == MT_EDGE_CONVEX);
    }
    CHECK_EQ(boundary_edges, 5);
    mt_convexity c;
    CHECK_OK(mt_mesh_convexity(m, 1e-9, &c, NULL, 0, NULL));
    CHECK(!c.convex);
    CHECK(c.reasons & MT_NONCONVEX_OPEN); /* found on the structure: the report's flag lags */
    CHECK(c.reasons & MT_NONCONVEX_NOT_SPHERE);
    CHECK_EQ(c.volume, 0.0);
    free(edges);
    free(shapes);
    free(fn);
    free(fa);
    free(def);
    free(vn);
    free(boundary);
    mt_mesh_destroy(m);
}

static const mt_test_case cases[] = {
    {"geometry_after_deletion", test_geometry_after_deletion},
};

const mt_test_table mt_tests_geometry_edit = {cases, sizeof cases / sizeof cases[0]};
