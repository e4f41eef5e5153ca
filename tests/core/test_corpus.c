/* Corpus conformance through the library itself (no CLI, no JSON writer):
 * each corpus mesh is read with mt_read_file, built, validated, and every
 * key of its NAME.expected.json (tests/corpus/DEFINITIONS.md) is compared
 * with the report struct (corpus_expect.c, shared with daemon.corpus.*) and
 * with the query functions. One named test per corpus mesh, plus one that
 * fails when the corpus holds a mesh without a row here, so new corpus files
 * are never skipped silently. A row whose mesh is not in the corpus skips,
 * naming it. */
#include <cJSON.h>
#include <ctype.h>
#include <dirent.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "corpus_expect.h"
#include "harness.h"
#include "meshtopo/core.h"
#include "meshtopo/io.h"

extern const mt_test_table mt_tests_corpus;

/* ---- the mesh under test ------------------------------------------------ */

typedef struct ctx {
    const char *name; /* corpus mesh name, for messages */
    const mt_mesh *mesh;
    const mt_report *report;
} ctx;

/* Records a failure naming the mesh and the key path. */
#define fail_key(c, ...) mt_test_corpus_fail((c)->name, __VA_ARGS__)

/* The component query agrees with the report's numbering. */
static void check_component_numbering(const ctx *c)
{
    const mt_report *r = c->report;
    for (uint32_t i = 0; i < r->connected_components; i++) {
        uint32_t comp = MT_NONE;
        CHECK_OK(mt_face_component(c->mesh, r->components[i].min_face, &comp));
        if (comp != i)
            fail_key(c, "components", "mt_face_component(%u) = %u, expected %u",
                     r->components[i].min_face, comp, i);
    }
}

/* ---- queries ----------------------------------------------------------- */

static void check_vertex_query(const ctx *c, size_t index, const cJSON *q)
{
    char key[96];
    long long v;
    if (!mt_test_json_int(cJSON_GetObjectItemCaseSensitive(q, "vertex"), &v) || v < 0 ||
        v >= c->report->num_verts) {
        fail_key(c, "vertex_queries", "entry %zu has no valid vertex", index);
        return;
    }
    if (cJSON_GetArraySize(q) != 3) fail_key(c, "vertex_queries", "unchecked keys");

    /* Learn the sizes with empty buffers, then fill. */
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    mt_status st = mt_vert_ring(c->mesh, (uint32_t)v, &ring);
    CHECK(st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL);
    ring.neighbors = calloc(ring.num_neighbors + 1, sizeof *ring.neighbors);
    ring.faces = calloc(ring.num_faces + 1, sizeof *ring.faces);
    ring.fans = calloc(ring.num_fans + 1, sizeof *ring.fans);
    ring.neighbors_capacity = ring.num_neighbors;
    ring.faces_capacity = ring.num_faces;
    ring.fans_capacity = ring.num_fans;
    CHECK(ring.neighbors && ring.faces && ring.fans);
    if (ring.neighbors && ring.faces && ring.fans) {
        CHECK_OK(mt_vert_ring(c->mesh, (uint32_t)v, &ring));
        /* The fans partition the buffers; an open fan has one more neighbour than faces. */
        size_t nsum = 0, fsum = 0;
        for (size_t k = 0; k < ring.num_fans; k++) {
            const mt_fan *fan = &ring.fans[k];
            CHECK_EQ(fan->neighbor_begin, nsum);
            CHECK_EQ(fan->face_begin, fsum);
            CHECK_EQ(fan->neighbor_count, fan->face_count + (fan->boundary ? 1 : 0));
            nsum += fan->neighbor_count;
            fsum += fan->face_count;
        }
        CHECK_EQ(nsum, ring.num_neighbors);
        CHECK_EQ(fsum, ring.num_faces);

        size_t nn = mt_test_sort_unique(ring.neighbors, ring.num_neighbors, MT_NONE);
        size_t nf = mt_test_sort_unique(ring.faces, ring.num_faces, MT_NONE);
        snprintf(key, sizeof key, "vertex_queries[%zu] (vertex %lld).neighbors", index, v);
        mt_test_expect_ids(c->name, key, cJSON_GetObjectItemCaseSensitive(q, "neighbors"),
                           ring.neighbors, nn);
        snprintf(key, sizeof key, "vertex_queries[%zu] (vertex %lld).faces", index, v);
        mt_test_expect_ids(c->name, key, cJSON_GetObjectItemCaseSensitive(q, "faces"), ring.faces,
                           nf);

        uint32_t valence = MT_NONE;
        CHECK_OK(mt_vert_valence(c->mesh, (uint32_t)v, &valence));
        snprintf(key, sizeof key, "vertex_queries[%zu] (vertex %lld) valence", index, v);
        if (valence != nn)
            fail_key(c, key, "mt_vert_valence(%lld) = %u, distinct ring neighbours %zu", v, valence,
                     nn);
    }
    free(ring.neighbors);
    free(ring.faces);
    free(ring.fans);
}

/* Adjacent faces of f through mt_face_neighbors, sorted, distinct, without
 * f; *out (malloc'ed) and the count. */
static size_t face_adjacent_by_neighbors(const ctx *c, uint32_t f, uint32_t **out)
{
    size_t num_faces = 0, num_edges = 0;
    mt_status st = mt_face_neighbors(c->mesh, f, NULL, 0, NULL, 0, &num_faces, &num_edges);
    CHECK(st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL);
    uint32_t *faces = calloc(num_faces + 1, sizeof *faces);
    uint32_t *offsets = calloc(num_edges + 1, sizeof *offsets);
    *out = faces;
    if (!faces || !offsets) {
        free(offsets);
        return 0;
    }
    CHECK_OK(mt_face_neighbors(c->mesh, f, faces, num_faces, offsets, num_edges + 1, &num_faces,
                               &num_edges));
    CHECK_EQ(offsets[0], 0);
    CHECK_EQ(offsets[num_edges], num_faces);
    free(offsets);
    return mt_test_sort_unique(faces, num_faces, f);
}

/* The same through mt_face_verts and mt_edge_faces on each side. */
static size_t face_adjacent_by_edges(const ctx *c, uint32_t f, uint32_t **out)
{
    *out = NULL;
    size_t n = 0;
    mt_status st = mt_face_verts(c->mesh, f, NULL, 0, &n);
    CHECK(st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL);
    uint32_t *verts = calloc(n + 1, sizeof *verts);
    if (!verts) return 0;
    CHECK_OK(mt_face_verts(c->mesh, f, verts, n, &n));
    size_t cap = 16, count = 0;
    uint32_t *all = malloc(cap * sizeof *all);
    for (size_t i = 0; all && i < n; i++) {
        size_t k = 0;
        st = mt_edge_faces(c->mesh, verts[i], verts[(i + 1) % n], NULL, 0, &k);
        CHECK(st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL);
        CHECK(k >= 1); /* f itself has this side */
        if (count + k > cap) {
            while (count + k > cap) cap *= 2;
            uint32_t *bigger = realloc(all, cap * sizeof *all);
            if (!bigger) {
                free(all);
                all = NULL;
                break;
            }
            all = bigger;
        }
        size_t got = 0;
        CHECK_OK(mt_edge_faces(c->mesh, verts[i], verts[(i + 1) % n], all + count, k, &got));
        CHECK_EQ(got, k);
        bool has_f = false;
        for (size_t j = 0; j < got && j < k; j++) {
            has_f |= all[count + j] == f;
            if (j > 0) CHECK(all[count + j - 1] < all[count + j]); /* ascending */
        }
        CHECK(has_f);
        count += got < k ? got : k;
    }
    free(verts);
    *out = all;
    return all ? mt_test_sort_unique(all, count, f) : 0;
}

static void check_face_query(const ctx *c, size_t index, const cJSON *q)
{
    char key[96];
    long long f;
    if (!mt_test_json_int(cJSON_GetObjectItemCaseSensitive(q, "face"), &f) || f < 0 ||
        f >= c->report->num_faces) {
        fail_key(c, "face_queries", "entry %zu has no valid face", index);
        return;
    }
    if (cJSON_GetArraySize(q) != 2) fail_key(c, "face_queries", "unchecked keys");
    const cJSON *want = cJSON_GetObjectItemCaseSensitive(q, "adjacent_faces");

    uint32_t *adj = NULL;
    size_t n = face_adjacent_by_neighbors(c, (uint32_t)f, &adj);
    snprintf(key, sizeof key, "face_queries[%zu] (face %lld).adjacent_faces", index, f);
    mt_test_expect_ids(c->name, key, want, adj, n);
    free(adj);

    n = face_adjacent_by_edges(c, (uint32_t)f, &adj);
    snprintf(key, sizeof key, "face_queries[%zu] (face %lld).adjacent_faces via mt_edge_faces",
             index, f);
    mt_test_expect_ids(c->name, key, want, adj, n);
    free(adj);
}

/* ---- boundary rings against the report ------------------------------- */

/* Half-edge boundary rings match the boundary-edge graph's loops when no
 * edge is non-manifold or doubly directed and no loop is pinched. */
static void check_boundary_rings(const ctx *c)
{
    const mt_report *r = c->report;
    size_t num_verts = 0, num_loops = 0;
    mt_status st = mt_boundary_loops(c->mesh, NULL, 0, NULL, 0, &num_verts, &num_loops);
    CHECK(st == MT_OK || st == MT_ERR_BUFFER_TOO_SMALL);
    uint32_t *verts = calloc(num_verts + 1, sizeof *verts);
    uint32_t *offsets = calloc(num_loops + 1, sizeof *offsets);
    if (verts && offsets) {
        CHECK_OK(mt_boundary_loops(c->mesh, verts, num_verts, offsets, num_loops + 1, &num_verts,
                                   &num_loops));
        if (!r->boundary_loops_ambiguous && r->nonmanifold_edges == 0 &&
            r->duplicate_directed_edges == 0) {
            uint32_t *lengths = calloc(num_loops + 1, sizeof *lengths);
            if (lengths) {
                for (size_t i = 0; i < num_loops; i++) lengths[i] = offsets[i + 1] - offsets[i];
                qsort(lengths, num_loops, sizeof *lengths, mt_test_compare_u32);
                if (num_loops != r->boundary_loops)
                    fail_key(c, "mt_boundary_loops", "%zu rings, report has %u loops", num_loops,
                             r->boundary_loops);
                for (size_t i = 0; i < num_loops && i < r->boundary_loops; i++)
                    if (lengths[i] != r->boundary_loop_lengths[i])
                        fail_key(c, "mt_boundary_loops",
                                 "ring %zu (by length) has %u vertices, "
                                 "report loop has %u edges",
                                 i, lengths[i], r->boundary_loop_lengths[i]);
                free(lengths);
            }
        }
    }
    free(verts);
    free(offsets);
}

/* ---- the whole check ------------------------------------------------- */

static void check_report(const ctx *c, const cJSON *e)
{
    mt_test_corpus_check_report(c->name, c->report, e);
    check_component_numbering(c);

    const cJSON *q;
    size_t i = 0;
    cJSON_ArrayForEach(q, cJSON_GetObjectItemCaseSensitive(e, "vertex_queries"))
        check_vertex_query(c, i++, q);
    i = 0;
    cJSON_ArrayForEach(q, cJSON_GetObjectItemCaseSensitive(e, "face_queries"))
        check_face_query(c, i++, q);

    check_boundary_rings(c);
}

static void check_corpus(const char *name)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.expected.json", mt_test_corpus_dir(), name);
    if (access(path, F_OK) != 0) {
        mt_test_skip(
            "%s is not in the corpus %s (tests/corpus/MANIFEST.md says why; "
            "MESHTOPO_CORPUS=DIR adds it)",
            name, mt_test_corpus_dir());
        return;
    }
    cJSON *expected = mt_test_corpus_load(name, path, sizeof path);
    if (!expected) return;
    ctx c = {name, NULL, NULL};

    mt_face_list list;
    mt_diag diag;
    memset(&list, 0, sizeof list);
    mt_diag_clear(&diag);
    mt_status st = mt_read_file(path, MT_FORMAT_AUTO, &list, &diag);
    if (st != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: mt_read_file: %s (%s)", name, mt_strerror(st),
                     diag.message);
        cJSON_Delete(expected);
        return;
    }
    mt_mesh *mesh = NULL;
    mt_diag_clear(&diag);
    st = mt_mesh_build(&list, NULL, &mesh, &diag);
    if (st != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: mt_mesh_build: %s (%s)", name, mt_strerror(st),
                     diag.message);
    } else {
        mt_diag_clear(&diag);
        st = mt_mesh_validate(mesh, &diag);
        if (st != MT_OK)
            mt_test_fail(__FILE__, __LINE__, "%s: mt_mesh_validate: %s (%s)", name, mt_strerror(st),
                         diag.message);
        CHECK_EQ(mt_mesh_num_verts(mesh), list.num_verts);
        CHECK_EQ(mt_mesh_num_faces(mesh), list.num_faces);
        c.mesh = mesh;
        c.report = mt_mesh_report(mesh);
        CHECK(c.report != NULL);
        if (c.report) check_report(&c, expected);
    }
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    cJSON_Delete(expected);
}

/* ---- one test per corpus mesh ------------------------------------------ */

static void test_corpus_assimp_malformed(void)
{
    check_corpus("assimp_malformed");
}
static void test_corpus_cgal_blobby_3cc(void)
{
    check_corpus("cgal_blobby_3cc");
}
static void test_corpus_cgal_eight(void)
{
    check_corpus("cgal_eight");
}
static void test_corpus_cgal_elephant_with_holes(void)
{
    check_corpus("cgal_elephant_with_holes");
}
static void test_corpus_cgal_many_umbrellas(void)
{
    check_corpus("cgal_many_umbrellas");
}
static void test_corpus_cgal_prim(void)
{
    check_corpus("cgal_prim");
}
static void test_corpus_cgal_tetrahedron(void)
{
    check_corpus("cgal_tetrahedron");
}
static void test_corpus_cgal_torus_quad(void)
{
    check_corpus("cgal_torus_quad");
}
static void test_corpus_igl_camelhead(void)
{
    check_corpus("igl_camelhead");
}
static void test_corpus_igl_fertility(void)
{
    check_corpus("igl_fertility");
}
static void test_corpus_npm_bunny(void)
{
    check_corpus("npm_bunny");
}
static void test_corpus_npm_conway_djmed(void)
{
    check_corpus("npm_conway_djmeD");
}
static void test_corpus_npm_snowden(void)
{
    check_corpus("npm_snowden");
}
static void test_corpus_npm_teapot(void)
{
    check_corpus("npm_teapot");
}
static void test_corpus_openmesh_cube_minimal_quads(void)
{
    check_corpus("openmesh_cube_minimal_quads");
}
static void test_corpus_trimesh_joined_tetrahedra(void)
{
    check_corpus("trimesh_joined_tetrahedra");
}
static void test_corpus_trimesh_multibody_stl_soup(void)
{
    check_corpus("trimesh_multibody_stl_soup");
}
static void test_corpus_trimesh_multibody_stl_welded(void)
{
    check_corpus("trimesh_multibody_stl_welded");
}
static void test_corpus_trimesh_notenoughindices(void)
{
    check_corpus("trimesh_notenoughindices");
}
static void test_corpus_trimesh_two_objects(void)
{
    check_corpus("trimesh_two_objects");
}
static void test_corpus_vcg_moebius(void)
{
    check_corpus("vcg_moebius");
}
static void test_corpus_vcg_nonmanifold(void)
{
    check_corpus("vcg_nonmanifold");
}
static void test_corpus_vcg_quad5(void)
{
    check_corpus("vcg_quad5");
}

/* NAME of a corpus file (mesh or answers), or false for other files. */
static bool corpus_entry_name(const char *file, char *name, size_t size)
{
    static const char *const suffixes[] = {
        ".expected.json", ".off.gz", ".obj.gz", ".ply.gz", ".stl.gz",
        ".off",           ".obj",    ".ply",    ".stl",
    };
    size_t len = strlen(file);
    for (size_t i = 0; i < sizeof suffixes / sizeof suffixes[0]; i++) {
        size_t sl = strlen(suffixes[i]);
        if (len > sl && strcmp(file + len - sl, suffixes[i]) == 0 && len - sl < size) {
            memcpy(name, file, len - sl);
            name[len - sl] = '\0';
            return true;
        }
    }
    return false;
}

/* Fails for every corpus mesh or answer file without a test row above. */
static void test_corpus_every_mesh_has_a_row(void)
{
    DIR *dir = opendir(mt_test_corpus_dir());
    CHECK(dir != NULL);
    if (!dir) return;
    size_t entries = 0;
    struct dirent *de;
    while ((de = readdir(dir)) != NULL) {
        char name[256], test_name[300];
        if (!corpus_entry_name(de->d_name, name, sizeof name)) continue;
        entries++;
        snprintf(test_name, sizeof test_name, "corpus_%s", name);
        for (char *p = test_name; *p; p++) *p = (char)tolower((unsigned char)*p);
        bool found = false;
        for (size_t i = 0; i < mt_tests_corpus.count; i++)
            found |= strcmp(mt_tests_corpus.cases[i].name, test_name) == 0;
        if (!found)
            mt_test_fail(__FILE__, __LINE__,
                         "corpus file %s has no test row: add {\"%s\", test_%s} to test_corpus.c",
                         de->d_name, test_name, test_name);
    }
    closedir(dir);
    CHECK(entries > 0);
}

static const mt_test_case cases[] = {
    {"corpus_assimp_malformed", test_corpus_assimp_malformed},
    {"corpus_cgal_blobby_3cc", test_corpus_cgal_blobby_3cc},
    {"corpus_cgal_eight", test_corpus_cgal_eight},
    {"corpus_cgal_elephant_with_holes", test_corpus_cgal_elephant_with_holes},
    {"corpus_cgal_many_umbrellas", test_corpus_cgal_many_umbrellas},
    {"corpus_cgal_prim", test_corpus_cgal_prim},
    {"corpus_cgal_tetrahedron", test_corpus_cgal_tetrahedron},
    {"corpus_cgal_torus_quad", test_corpus_cgal_torus_quad},
    {"corpus_igl_camelhead", test_corpus_igl_camelhead},
    {"corpus_igl_fertility", test_corpus_igl_fertility},
    {"corpus_npm_bunny", test_corpus_npm_bunny},
    {"corpus_npm_conway_djmed", test_corpus_npm_conway_djmed},
    {"corpus_npm_snowden", test_corpus_npm_snowden},
    {"corpus_npm_teapot", test_corpus_npm_teapot},
    {"corpus_openmesh_cube_minimal_quads", test_corpus_openmesh_cube_minimal_quads},
    {"corpus_trimesh_joined_tetrahedra", test_corpus_trimesh_joined_tetrahedra},
    {"corpus_trimesh_multibody_stl_soup", test_corpus_trimesh_multibody_stl_soup},
    {"corpus_trimesh_multibody_stl_welded", test_corpus_trimesh_multibody_stl_welded},
    {"corpus_trimesh_notenoughindices", test_corpus_trimesh_notenoughindices},
    {"corpus_trimesh_two_objects", test_corpus_trimesh_two_objects},
    {"corpus_vcg_moebius", test_corpus_vcg_moebius},
    {"corpus_vcg_nonmanifold", test_corpus_vcg_nonmanifold},
    {"corpus_vcg_quad5", test_corpus_vcg_quad5},
    {"corpus_every_mesh_has_a_row", test_corpus_every_mesh_has_a_row},
};

const mt_test_table mt_tests_corpus = {cases, sizeof cases / sizeof cases[0]};
