/* Gauss-Bonnet through mt_mesh_vert_curvature: the angle deficits of a
 * closed mesh add up to 2 pi chi. Checked on the closed generator meshes
 * (Platonic solids, icospheres, tori, the double torus) and on every closed
 * mesh of the corpus (a missing corpus file fails the test, and so does a
 * closed corpus mesh missing from the list below). Tolerance: 1e-9 relative
 * to 2 pi |chi|, and 1e-9 absolute when chi = 0 (the rounding of V terms of
 * size about 2 pi stays near 1e-11 for the largest mesh here). Isolated
 * vertices are not part of the surface (deficit 0), so they come off chi;
 * on a closed mesh with non-manifold edges the identity reads
 * sum = 2 pi (V' - F) - pi * (sides on edges - 2 E): each face of n sides has
 * corner angles adding up to (n - 2) pi. */
#include <cJSON.h>
#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "corpus_expect.h"
#include "geometry_mesh.h"
#include "harness.h"
#include "meshtopo/core.h"
#include "meshtopo/io.h"

#define PI 3.14159265358979323846

/* Compensated sum of the deficits, checked against the report's topology. */
static void check_gauss_bonnet(const mt_mesh *m, const char *what)
{
    const mt_report *r = mt_mesh_report(m);
    size_t n = 0;
    CHECK_OK(mt_mesh_vert_curvature(m, NULL, NULL, NULL, 0, &n, NULL));
    double *def = malloc((n + 1) * sizeof *def);
    bool *boundary = malloc(n + 1);
    if (!def || !boundary) abort();
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status s = mt_mesh_vert_curvature(m, NULL, def, boundary, n, &n, &diag);
    if (s != MT_OK) mt_test_fail(__FILE__, __LINE__, "%s: %s", what, diag.message);
    double sum = 0.0, comp = 0.0;
    size_t on_boundary = 0, nonfinite = 0;
    for (size_t v = 0; s == MT_OK && v < n; v++) {
        nonfinite += !isfinite(def[v]);
        on_boundary += boundary[v];
        double y = def[v] - comp, t = sum + y;
        comp = (t - sum) - y;
        sum = t;
    }
    CHECK_EQ(nonfinite, 0);
    CHECK_EQ(on_boundary, 0);
    /* Face sides on edges (the sum of k * edges used k times); 2 E when manifold. */
    uint64_t sides = 0;
    for (size_t i = 0; i < r->num_edge_use_bins; i++)
        sides += r->edge_use_histogram[i].key * r->edge_use_histogram[i].count;
    int64_t chi = r->euler_characteristic - (int64_t)r->isolated_vertices;
    double want = 2.0 * PI * (double)chi - PI * ((double)sides - 2.0 * (double)r->num_edges);
    double tol = want == 0.0 ? 1e-9 : 1e-9 * fabs(want);
    if (!(fabs(sum - want) <= tol))
        mt_test_fail(__FILE__, __LINE__,
                     "%s: sum of angle deficits %.17g, expected %.17g (chi %lld, %llu sides on "
                     "%llu edges), off by %.3g",
                     what, sum, want, (long long)chi, (unsigned long long)sides,
                     (unsigned long long)r->num_edges, fabs(sum - want));
    free(def);
    free(boundary);
}

static void check_generated(mt_status gen_status, mt_face_list *list, const char *what, int64_t chi)
{
    CHECK_OK(gen_status);
    if (gen_status != MT_OK) return;
    mt_mesh *m = geom_build(list, what);
    mt_face_list_free(list);
    if (!m) return;
    const mt_report *r = mt_mesh_report(m);
    CHECK(r->closed);
    CHECK_EQ(r->euler_characteristic, chi);
    check_gauss_bonnet(m, what);
    mt_mesh_destroy(m);
}

static void test_geometry_gauss_bonnet_generated(void)
{
    mt_face_list list;
    for (int kind = MT_TETRAHEDRON; kind <= MT_ICOSAHEDRON; kind++)
        check_generated(mt_gen_platonic((mt_platonic)kind, &list), &list, "platonic solid", 2);
    for (uint32_t level = 0; level <= 4; level++)
        check_generated(mt_gen_icosphere(level, &list), &list, "icosphere", 2);
    check_generated(mt_gen_torus(3, 3, &list), &list, "torus 3x3", 0);
    check_generated(mt_gen_torus(40, 17, &list), &list, "torus 40x17", 0);
    check_generated(mt_gen_double_torus(4, &list), &list, "double torus 4", -2);
    check_generated(mt_gen_double_torus(24, &list), &list, "double torus 24", -2);
    /* Shuffled ids change nothing. */
    if (mt_gen_icosphere(3, &list) == MT_OK) {
        CHECK_OK(mt_face_list_permute(&list, 99, NULL));
        check_generated(MT_OK, &list, "shuffled icosphere", 2);
    }
}

/* The corpus meshes whose expected.json says closed. */
static const char *const closed_corpus[] = {
    "cgal_eight",
    "cgal_prim",
    "cgal_tetrahedron",
    "cgal_torus_quad",
    "igl_fertility",
    "npm_bunny",
    "npm_conway_djmeD",
    "openmesh_cube_minimal_quads",
    "trimesh_joined_tetrahedra",
    "trimesh_multibody_stl_welded",
    "trimesh_two_objects",
};

static void check_corpus_mesh(const char *name)
{
    char path[4096];
    cJSON *expected = mt_test_corpus_load(name, path, sizeof path);
    if (!expected) return; /* recorded as a failure */
    CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(expected, "closed")));
    mt_face_list list;
    mt_diag diag;
    memset(&list, 0, sizeof list);
    mt_diag_clear(&diag);
    mt_status s = mt_read_file(path, MT_FORMAT_AUTO, &list, &diag);
    if (s != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: mt_read_file: %s (%s)", name, mt_strerror(s),
                     diag.message);
    } else {
        mt_mesh *m = geom_build(&list, name);
        if (m) {
            CHECK(mt_mesh_report(m)->closed);
            check_gauss_bonnet(m, name);
            mt_mesh_destroy(m);
        }
    }
    mt_face_list_free(&list);
    cJSON_Delete(expected);
}

/* Whether the corpus holds NAME's answers (tests/corpus lacks some meshes
 * of the list: tests/corpus/MANIFEST.md says why). */
static bool corpus_has(const char *name)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.expected.json", mt_test_corpus_dir(), name);
    return access(path, F_OK) == 0;
}

static void test_geometry_gauss_bonnet_corpus(void)
{
    for (size_t i = 0; i < sizeof closed_corpus / sizeof closed_corpus[0]; i++) {
        if (corpus_has(closed_corpus[i]))
            check_corpus_mesh(closed_corpus[i]);
        else
            printf("%s is not in the corpus %s: left out\n", closed_corpus[i],
                   mt_test_corpus_dir());
    }
}

/* Every corpus answer file saying "closed": true is in the list above. */
static void test_geometry_gauss_bonnet_corpus_list(void)
{
    DIR *dir = opendir(mt_test_corpus_dir());
    CHECK(dir != NULL);
    if (!dir) return;
    size_t closed = 0;
    struct dirent *de;
    while ((de = readdir(dir)) != NULL) {
        const char *suffix = ".expected.json";
        size_t len = strlen(de->d_name), sl = strlen(suffix);
        if (len <= sl || strcmp(de->d_name + len - sl, suffix) != 0) continue;
        char name[256];
        if (len - sl >= sizeof name) continue;
        memcpy(name, de->d_name, len - sl);
        name[len - sl] = '\0';
        char path[4096];
        cJSON *expected = mt_test_corpus_load(name, path, sizeof path);
        if (!expected) continue;
        if (cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(expected, "closed"))) {
            closed++;
            bool listed = false;
            for (size_t i = 0; i < sizeof closed_corpus / sizeof closed_corpus[0]; i++)
                listed |= strcmp(closed_corpus[i], name) == 0;
            if (!listed)
                mt_test_fail(__FILE__, __LINE__,
                             "closed corpus mesh %s is not in test_geometry_gauss.c's list", name);
        }
        cJSON_Delete(expected);
    }
    closedir(dir);
    size_t listed_here = 0;
    for (size_t i = 0; i < sizeof closed_corpus / sizeof closed_corpus[0]; i++)
        listed_here += corpus_has(closed_corpus[i]);
    CHECK_EQ(closed, listed_here);
}

static const mt_test_case cases[] = {
    {"geometry_gauss_bonnet_generated", test_geometry_gauss_bonnet_generated},
    {"geometry_gauss_bonnet_corpus", test_geometry_gauss_bonnet_corpus},
    {"geometry_gauss_bonnet_corpus_list", test_geometry_gauss_bonnet_corpus_list},
};

const mt_test_table mt_tests_geometry_gauss = {cases, sizeof cases / sizeof cases[0]};
