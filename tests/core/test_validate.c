/* Tests of mt_mesh_validate: the hand-written meshes and every generated
 * mesh pass; then each invariant is broken on a hand-written mesh, one test
 * per invariant, and the validator must answer MT_ERR_CORRUPT naming that
 * invariant and the element (and never read out of bounds doing it). */
#include <stdlib.h>
#include <string.h>

#include "hand_mesh.h"
#include "harness.h"
#include "mesh/mesh_internal.h"
#include "meshtopo/generate.h"
#include "meshtopo/mesh.h"
#include "meshtopo/validate.h"

#define N MT_NONE

/* Checks that validation fails as corrupt, that the message holds `needle`
 * and that the diag names `element`; frees the mesh. */
#define EXPECT_CORRUPT(mesh, needle, element) \
    expect_corrupt((mesh), (needle), (element), __FILE__, __LINE__)

static void expect_corrupt(mt_mesh *m, const char *needle, uint32_t element, const char *file,
                           int line)
{
    mt_diag d;
    mt_status s = mt_mesh_validate(m, &d);
    if (s != MT_ERR_CORRUPT || d.status != MT_ERR_CORRUPT)
        mt_test_fail(file, line, "validate returned %s (diag %s), expected MT_ERR_CORRUPT",
                     mt_strerror(s), mt_strerror(d.status));
    else if (!strstr(d.message, needle))
        mt_test_fail(file, line, "message \"%s\" does not contain \"%s\"", d.message, needle);
    else if (d.element != element)
        mt_test_fail(file, line, "diag element %u, expected %u (message \"%s\")", d.element,
                     element, d.message);
    /* Without a diag the status is the same. */
    if (mt_mesh_validate(m, NULL) != MT_ERR_CORRUPT)
        mt_test_fail(file, line, "validate without diag does not report the corruption");
    hand_mesh_free(m);
}

static void expect_valid(const mt_mesh *m, const char *what)
{
    mt_diag d;
    mt_status s = mt_mesh_validate(m, &d);
    if (s != MT_OK) mt_test_fail(__FILE__, __LINE__, "%s: %s", what, d.message);
    CHECK_EQ(d.status, MT_OK);
    CHECK_EQ(d.message[0], '\0');
    CHECK_EQ(d.element, MT_NONE);
}

/* ---- meshes that must pass ---- */

static void test_validate_hand_meshes(void)
{
    mt_mesh *meshes[] = {hand_triangle(NULL), hand_rectangle(NULL), hand_tetrahedron(NULL),
                         hand_bowtie(NULL), hand_fin(NULL)};
    const char *names[] = {"triangle", "rectangle", "tetrahedron", "bowtie", "fin"};
    for (size_t i = 0; i < sizeof meshes / sizeof meshes[0]; i++) {
        expect_valid(meshes[i], names[i]);
        hand_mesh_free(meshes[i]);
    }
}

static void test_validate_empty_and_isolated(void)
{
    hand_spec empty = {0};
    mt_mesh *m = hand_mesh_new(&empty);
    expect_valid(m, "empty mesh");
    hand_mesh_free(m);

    /* The triangle plus an isolated vertex 3 and a rejected face record 1. */
    m = hand_triangle_isolated();
    CHECK_EQ(m->report.num_faces_valid, 1);
    expect_valid(m, "triangle with isolated vertex and rejected record");
    hand_mesh_free(m);
}

static void test_validate_null(void)
{
    mt_diag d;
    CHECK_STATUS(mt_mesh_validate(NULL, &d), MT_ERR_INVALID_ARG);
    CHECK_EQ(d.status, MT_ERR_INVALID_ARG);
    CHECK(strstr(d.message, "NULL") != NULL);
    CHECK_STATUS(mt_mesh_validate(NULL, NULL), MT_ERR_INVALID_ARG);
}

static void validate_built(mt_face_list *list, const char *what)
{
    mt_mesh *mesh = NULL;
    mt_diag d;
    mt_status s = mt_mesh_build(list, NULL, &mesh, &d);
    if (s != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: build failed: %s", what, d.message);
    } else {
        expect_valid(mesh, what);
        /* Shuffled ids and face order give another structure, valid too. */
        mt_mesh_destroy(mesh);
        CHECK_OK(mt_face_list_permute(list, 12345, NULL));
        s = mt_mesh_build(list, NULL, &mesh, &d);
        if (s != MT_OK)
            mt_test_fail(__FILE__, __LINE__, "%s permuted: build failed: %s", what, d.message);
        else
            expect_valid(mesh, what);
        mt_mesh_destroy(mesh);
    }
    mt_face_list_free(list);
}

static void test_validate_generated(void)
{
    mt_face_list list;
    const mt_platonic solids[] = {MT_TETRAHEDRON, MT_CUBE, MT_OCTAHEDRON, MT_DODECAHEDRON,
                                  MT_ICOSAHEDRON};
    for (size_t i = 0; i < sizeof solids / sizeof solids[0]; i++) {
        CHECK_OK(mt_gen_platonic(solids[i], &list));
        validate_built(&list, "platonic solid");
    }
    CHECK_OK(mt_gen_rectangle(2.0, 1.0, &list));
    validate_built(&list, "rectangle");
    CHECK_OK(mt_gen_grid(7, 5, true, &list));
    validate_built(&list, "triangle grid");
    CHECK_OK(mt_gen_grid(4, 9, false, &list));
    validate_built(&list, "quad grid");
    CHECK_OK(mt_gen_torus(12, 7, &list));
    validate_built(&list, "torus");
    CHECK_OK(mt_gen_icosphere(3, &list));
    validate_built(&list, "icosphere");
    CHECK_OK(mt_gen_double_torus(6, &list));
    validate_built(&list, "double torus");
    CHECK_OK(mt_gen_moebius(9, &list));
    validate_built(&list, "moebius strip");
    CHECK_OK(mt_gen_bowtie(&list));
    validate_built(&list, "bowtie");
    CHECK_OK(mt_gen_fin(&list));
    validate_built(&list, "fin");
}

/* Messy face lists: every defect the builder keeps (bundles, copies,
 * flipped and duplicated faces, rejected records) in one mesh. */
static void test_validate_messy_builds(void)
{
    static const uint32_t sizes[] = {3, 3, 3, 3, 3, 3, 3, 3, 2, 3, 4, 3, 3};
    static const uint32_t idx[] = {
        0,  1,  2,      /* fin: three faces on 0-1 */
        1,  0,  3,      /*                         */
        0,  1,  4,      /*                         */
        0,  5,  6,      /* bowtie at 0             */
        2,  1,  7,      /* flipped against face 0 (same direction on 1-2) */
        0,  1,  2,      /* duplicate of face 0     */
        8,  9,  10,     /* separate triangle       */
        8,  10, 9,      /* its flip: a closed two-face pocket */
        3,  4,          /* degenerate: two entries */
        5,  5,  6,      /* degenerate: repeated vertex */
        6,  5,  12, 11, /* quad next to the bowtie */
        0,  99, 1,      /* out-of-range index */
        13, 14, 15,     /* isolated vertex 16 stays out */
    };
    mt_face_list list = {
        17, 13, sizeof idx / sizeof idx[0], NULL, (uint32_t *)sizes, (uint32_t *)idx};
    mt_mesh *mesh = NULL;
    mt_diag d;
    CHECK_OK(mt_mesh_build(&list, NULL, &mesh, &d));
    if (mesh) {
        expect_valid(mesh, "messy mesh");
        CHECK(mesh->num_copies > 0);
        CHECK(mesh->num_bundles > 0);
    }
    mt_mesh_destroy(mesh);
}

/* ---- sizes and ranges ---- */

static void test_validate_odd_half_edges(void)
{
    mt_mesh *m = hand_triangle(NULL);
    m->num_half_edges = 5;
    EXPECT_CORRUPT(m, "odd number of half-edges (5)", N);
}

static void test_validate_vertex_counts(void)
{
    mt_mesh *m = hand_bowtie(NULL);
    m->num_verts_internal = 5; /* one copy, but no room for it */
    EXPECT_CORRUPT(m, "5 internal vertices but 5 caller vertices and 1 copies", N);
}

static void test_validate_missing_array(void)
{
    mt_mesh *m = hand_triangle(NULL);
    free(m->he_next);
    m->he_next = NULL;
    EXPECT_CORRUPT(m, "half-edge array is missing", N);
    m = hand_fin(NULL);
    free(m->bundled_sorted);
    m->bundled_sorted = NULL;
    EXPECT_CORRUPT(m, "bundle array is missing", N);
}

static void test_validate_report_counts(void)
{
    mt_mesh *m = hand_rectangle(NULL);
    m->report.num_faces = 3;
    EXPECT_CORRUPT(m, "report counts 4 vertices and 3 faces but the mesh has 4 and 2", N);
    m = hand_rectangle(NULL);
    m->report.num_faces_valid = 1;
    EXPECT_CORRUPT(m, "keeps 2 faces but the report counts 1 valid faces", N);
}

static void test_validate_head_out_of_range(void)
{
    mt_mesh *m = hand_triangle(NULL);
    m->he_head[3] = 7;
    EXPECT_CORRUPT(m, "half-edge 3: head 7 is not a vertex", 3);
    m = hand_bowtie(NULL);
    m->he_head[6] = N;
    EXPECT_CORRUPT(m, "half-edge 6: head 4294967295 is not a vertex", 6);
}

static void test_validate_next_out_of_range(void)
{
    mt_mesh *m = hand_triangle(NULL);
    m->he_next[4] = 6;
    EXPECT_CORRUPT(m, "half-edge 4: next 6 is not a half-edge", 4);
    m = hand_triangle(NULL);
    m->he_next[0] = N;
    EXPECT_CORRUPT(m, "half-edge 0: next 4294967295 is not a half-edge", 0);
}

static void test_validate_face_out_of_range(void)
{
    mt_mesh *m = hand_rectangle(NULL);
    m->he_face[4] = 2;
    EXPECT_CORRUPT(m, "half-edge 4: face 2 is not a face record", 4);
}

static void test_validate_face_he_out_of_range(void)
{
    mt_mesh *m = hand_rectangle(NULL);
    m->face_he[1] = 10;
    EXPECT_CORRUPT(m, "face 1: face_he 10 is not a half-edge", 1);
}

static void test_validate_vert_he_out_of_range(void)
{
    mt_mesh *m = hand_tetrahedron(NULL);
    m->vert_he[2] = 12;
    EXPECT_CORRUPT(m, "vertex 2: vert_he 12 is not a half-edge", 2);
}

static void test_validate_copy_out_of_range(void)
{
    mt_mesh *m = hand_bowtie(NULL);
    m->copy_original[0] = 5;
    EXPECT_CORRUPT(m, "vertex copy 5: original 5 is not a caller vertex", 5);
    m = hand_bowtie(NULL);
    m->copies_sorted[0] = 4;
    EXPECT_CORRUPT(m, "copies_sorted[0] = 4 is not a vertex copy", 4);
}

static void test_validate_bundle_out_of_range(void)
{
    mt_mesh *m = hand_fin(NULL);
    m->bundle_edges[1] = 8;
    EXPECT_CORRUPT(m, "bundle_edges[1] = 8 is not an edge (8 edges)", 1);
    m = hand_fin(NULL);
    m->bundled_sorted[1] = 100;
    EXPECT_CORRUPT(m, "bundled_sorted[1] = 100 is not an edge", 1);
    m = hand_fin(NULL);
    m->bundled_bundle[0] = 1;
    EXPECT_CORRUPT(m, "bundled_bundle[0] = 1 is not a bundle (1 bundles)", 0);
    m = hand_fin(NULL);
    m->bundle_offsets[1] = 1;
    EXPECT_CORRUPT(m, "bundle 0: offsets 0..1 hold fewer than 2 edges", 0);
    m = hand_fin(NULL);
    m->bundle_offsets[0] = 1;
    EXPECT_CORRUPT(m, "bundle 0 starts at 1, not 0", 0);
}

static void test_validate_component_out_of_range(void)
{
    mt_mesh *m = hand_bowtie(NULL);
    m->vert_component[4] = 2;
    EXPECT_CORRUPT(m, "vertex 4: component 2 is not a component (2 components)", 4);
}

/* ---- the half-edge invariants ---- */

static void test_validate_next_not_permutation(void)
{
    mt_mesh *m = hand_triangle(NULL);
    m->he_next[1] = 2; /* h0 already leads to h2 */
    EXPECT_CORRUPT(m, "half-edge 2 is the next of both 0 and 1: next is not a permutation", 2);
}

/* A head changed on one side of an edge: the rings no longer join up. */
static void test_validate_broken_twin_head(void)
{
    mt_mesh *m = hand_triangle(NULL);
    m->he_head[1] = 1; /* both sides of edge 0 now point at vertex 1 */
    EXPECT_CORRUPT(m, "edge 0: both half-edges point at caller vertex 1", 0);
    m = hand_triangle(NULL);
    m->he_head[4] = 0; /* so face 0's side 2 -> 0 now starts at 0 */
    EXPECT_CORRUPT(m, "half-edge 2: next(2)=5 starts at vertex 0 but 2 ends at vertex 2", 2);
    m = hand_triangle(NULL);
    m->he_head[2] = 0;
    EXPECT_CORRUPT(m, "half-edge 2: next(2)=5 starts at vertex 2 but 2 ends at vertex 0", 2);
}

static void test_validate_face_ring_mismatch(void)
{
    mt_mesh *m = hand_rectangle(NULL);
    m->he_face[2] = 1; /* one half-edge of face 0's ring names face 1 */
    EXPECT_CORRUPT(m, "half-edge 0: face 0 but its next 2 has face 1", 0);
    m = hand_rectangle(NULL);
    m->he_face[8] = 0; /* a boundary half-edge names a face */
    EXPECT_CORRUPT(m, "half-edge 1: face -1 but its next 8 has face 0", 1);
}

static void test_validate_face_he_mismatch(void)
{
    mt_mesh *m = hand_rectangle(NULL);
    m->face_he[1] = 0; /* half-edge 0 belongs to face 0 */
    EXPECT_CORRUPT(m, "face 1: face_he[1]=0 but half-edge 0 names face 0", 1);
    m = hand_rectangle(NULL);
    m->face_he[0] = 1; /* a boundary half-edge */
    EXPECT_CORRUPT(m, "face 0: face_he[0]=1 but half-edge 1 names face -1", 0);
}

/* A ring naming a face whose record is rejected (face_he none). */
static void test_validate_face_rejected_but_named(void)
{
    mt_mesh *m = hand_triangle(NULL);
    uint32_t *face_he = realloc(m->face_he, 2 * sizeof *face_he);
    CHECK(face_he != NULL);
    if (!face_he) {
        hand_mesh_free(m);
        return;
    }
    m->face_he = face_he;
    m->face_he[0] = N;
    m->face_he[1] = N;
    m->num_faces = m->report.num_faces = 2;
    m->report.num_faces_valid = 0;
    m->he_face[0] = m->he_face[2] = m->he_face[5] = 1;
    EXPECT_CORRUPT(m, "half-edge 0 names face 1, a rejected face record", 0);
}

/* Two separate rings naming the same face. */
static void test_validate_face_two_rings(void)
{
    mt_mesh *m = hand_bowtie(NULL);
    m->he_face[6] = m->he_face[9] = m->he_face[10] = 0;
    m->face_he[1] = N;
    m->report.num_faces_valid = 1;
    free(m->vert_component);
    m->vert_component = NULL;
    EXPECT_CORRUPT(m, "half-edge 6 names face 0 but is not on the ring of face_he[0]=0", 6);
}

static void test_validate_edge_without_face(void)
{
    mt_mesh *m = hand_triangle(NULL);
    m->he_face[0] = m->he_face[2] = m->he_face[5] = N;
    EXPECT_CORRUPT(m, "edge 0 has no face on either side", 0);
}

/* Swaps the roles of half-edges a and b everywhere in the mesh. */
static void swap_half_edges(mt_mesh *m, uint32_t a, uint32_t b)
{
    uint32_t t;
    t = m->he_head[a], m->he_head[a] = m->he_head[b], m->he_head[b] = t;
    t = m->he_next[a], m->he_next[a] = m->he_next[b], m->he_next[b] = t;
    t = m->he_face[a], m->he_face[a] = m->he_face[b], m->he_face[b] = t;
    for (uint32_t h = 0; h < m->num_half_edges; h++) {
        if (m->he_next[h] == a)
            m->he_next[h] = b;
        else if (m->he_next[h] == b)
            m->he_next[h] = a;
    }
    for (uint32_t f = 0; f < m->num_faces; f++) {
        if (m->face_he[f] == a)
            m->face_he[f] = b;
        else if (m->face_he[f] == b)
            m->face_he[f] = a;
    }
    for (uint32_t v = 0; v < m->num_verts_internal; v++) {
        if (m->vert_he[v] == a)
            m->vert_he[v] = b;
        else if (m->vert_he[v] == b)
            m->vert_he[v] = a;
    }
}

static void test_validate_edge_direction(void)
{
    /* Relabelling the two sides of edge 0 keeps every ring intact, so only
     * the smaller-to-larger convention is broken. */
    mt_mesh *m = hand_triangle(NULL);
    swap_half_edges(m, 0, 1);
    EXPECT_CORRUPT(m, "edge 0: half-edge 0 runs from caller vertex 1 to 0", 0);
    m = hand_triangle(NULL);
    swap_half_edges(m, 0, 1);
    swap_half_edges(m, 0, 1);
    expect_valid(m, "triangle relabelled twice");
    hand_mesh_free(m);
}

/* A two-sided face: half-edges 0->1 and 1->0 of two bundled edges. */
static void test_validate_short_face_ring(void)
{
    static const uint32_t head[] = {1, 0, 1, 0};
    static const uint32_t next[] = {3, 2, 1, 0};
    static const uint32_t face[] = {0, N, N, 0};
    static const uint32_t face_he[] = {0};
    static const uint32_t vert_he[] = {2, 1};
    static const uint32_t offsets[] = {0, 2};
    static const uint32_t edges[] = {0, 1};
    static const uint32_t bundles[] = {0, 0};
    hand_spec s = {0};
    s.num_verts = 2;
    s.num_faces = 1;
    s.num_half_edges = 4;
    s.num_bundles = 1;
    s.he_head = head;
    s.he_next = next;
    s.he_face = face;
    s.face_he = face_he;
    s.vert_he = vert_he;
    s.bundle_offsets = offsets;
    s.bundle_edges = edges;
    s.bundled_sorted = edges;
    s.bundled_bundle = bundles;
    s.components = 1;
    EXPECT_CORRUPT(hand_mesh_new(&s), "face 0: its ring has 2 half-edges, fewer than 3", 0);
}

/* A quad (0, 1, 3, 2) where 3 is a copy of 0: caller vertex 0 twice. */
static void test_validate_face_repeats_vertex(void)
{
    static const uint32_t head[] = {1, 0, 1, 3, 2, 3, 2, 0};
    static const uint32_t next[] = {3, 6, 1, 4, 7, 2, 5, 0};
    static const uint32_t face[] = {0, N, N, 0, 0, N, N, 0};
    static const uint32_t face_he[] = {0};
    static const uint32_t vert_he[] = {6, 1, 5, 2};
    static const uint32_t copy_original[] = {0};
    static const uint32_t copies_sorted[] = {3};
    static const uint32_t offsets[] = {0, 2, 4};
    static const uint32_t edges[] = {0, 1, 2, 3};
    static const uint32_t bundles[] = {0, 0, 1, 1};
    hand_spec s = {0};
    s.num_verts = 3;
    s.num_faces = 1;
    s.num_half_edges = 8;
    s.num_copies = 1;
    s.num_bundles = 2;
    s.he_head = head;
    s.he_next = next;
    s.he_face = face;
    s.face_he = face_he;
    s.vert_he = vert_he;
    s.copy_original = copy_original;
    s.copies_sorted = copies_sorted;
    s.bundle_offsets = offsets;
    s.bundle_edges = edges;
    s.bundled_sorted = edges;
    s.bundled_bundle = bundles;
    s.components = 1;
    EXPECT_CORRUPT(hand_mesh_new(&s), "face 0: caller vertex 0 appears twice in its ring", 0);
}

static void test_validate_vert_he_wrong_tail(void)
{
    mt_mesh *m = hand_rectangle(NULL);
    m->vert_he[1] = 4; /* 0 -> 2 */
    EXPECT_CORRUPT(m, "vertex 1: vert_he[1]=4 starts at vertex 0, not at 1", 1);
}

static void test_validate_vert_he_not_boundary(void)
{
    mt_mesh *m = hand_rectangle(NULL);
    m->vert_he[0] = 4; /* a face half-edge out of 0, though 8 is a boundary one */
    EXPECT_CORRUPT(m, "vertex 0 has boundary half-edge 8 but vert_he[0]=4 is not a boundary", 0);
}

static void test_validate_vert_he_missing(void)
{
    mt_mesh *m = hand_rectangle(NULL);
    m->vert_he[3] = N;
    EXPECT_CORRUPT(m, "vertex 3 has 2 outgoing half-edges but no vert_he", 3);
}

/* The bowtie with its copy folded back into vertex 0: one vertex, two fans. */
static mt_mesh *bowtie_without_copy(void)
{
    mt_mesh *m = hand_bowtie(NULL);
    m->he_head[7] = m->he_head[9] = 0;
    m->num_copies = 0;
    m->num_verts_internal = 5;
    free(m->copy_original);
    free(m->copies_sorted);
    free(m->vert_component);
    m->copy_original = m->copies_sorted = m->vert_component = NULL;
    return m;
}

static void test_validate_rotation_misses_half_edges(void)
{
    mt_mesh *m = bowtie_without_copy();
    EXPECT_CORRUPT(m, "vertex 0: one rotation from vert_he[0]=2 visits 2 of its 4 outgoing", 0);
}

/* The two boundary rings of the folded bowtie joined into a figure eight:
 * one rotation now covers the vertex, through two boundary half-edges. */
static void test_validate_fan_two_boundaries(void)
{
    mt_mesh *m = bowtie_without_copy();
    m->he_next[1] = 8;
    m->he_next[7] = 2;
    EXPECT_CORRUPT(m, "vertex 0: its fan holds two boundary half-edges, 2 and 8", 0);
}

static void test_validate_copy_without_fan(void)
{
    mt_mesh *m = hand_triangle(NULL);
    uint32_t *vert_he = realloc(m->vert_he, 4 * sizeof *vert_he);
    uint32_t *original = malloc(sizeof *original), *sorted = malloc(sizeof *sorted);
    CHECK(vert_he && original && sorted);
    if (!vert_he || !original || !sorted) {
        free(original);
        free(sorted);
        hand_mesh_free(m);
        return;
    }
    m->vert_he = vert_he;
    m->vert_he[3] = N;
    original[0] = 0;
    sorted[0] = 3;
    m->copy_original = original;
    m->copies_sorted = sorted;
    m->num_copies = 1;
    m->num_verts_internal = 4;
    EXPECT_CORRUPT(m, "vertex copy 3 (of caller vertex 0) holds no fan", 3);
}

static void test_validate_copies_order(void)
{
    mt_mesh *m = hand_fin(NULL);
    m->copies_sorted[0] = 6;
    m->copies_sorted[1] = 5;
    EXPECT_CORRUPT(m, "copies_sorted[1]=5 (copy of 0) does not follow copies_sorted[0]=6", 5);
}

static void test_validate_bundle_endpoints(void)
{
    mt_mesh *m = hand_fin(NULL);
    m->bundle_edges[1] = 6; /* 1-4, not 0-1 */
    m->bundled_sorted[1] = 6;
    EXPECT_CORRUPT(m, "bundle 0: edge 6 joins caller vertices 1-4 but edge 0 joins 0-1", 6);
}

static void test_validate_bundle_lookup(void)
{
    mt_mesh *m = hand_fin(NULL);
    m->bundled_sorted[1] = 4; /* lists edge 4 instead of 5 */
    EXPECT_CORRUPT(m, "bundle 0: edge 5 is not found under that bundle", 5);
    m = hand_fin(NULL);
    m->bundled_sorted[0] = 5;
    m->bundled_sorted[1] = 0;
    EXPECT_CORRUPT(m, "bundled_sorted[1]=0 does not follow bundled_sorted[0]=5", 1);
    m = hand_fin(NULL);
    m->bundle_edges[1] = 0;
    EXPECT_CORRUPT(m, "edge 0 is listed twice in bundles", 0);
}

static void test_validate_unbundled_duplicate_edge(void)
{
    mt_mesh *m = hand_fin(NULL);
    m->num_bundles = 0; /* edges 0 and 5 both join 0-1 */
    EXPECT_CORRUPT(m, "caller edge 0-1 is held by several internal edges (5 among them)", 5);
}

static void test_validate_component_mismatch(void)
{
    mt_mesh *m = hand_bowtie(NULL);
    m->vert_component[2] = 1;
    EXPECT_CORRUPT(m, "edge 1 joins vertex 0 (component 0) and vertex 2 (component 1)", 1);
}

/* The one scratch allocation failing gives MT_ERR_NOMEM, not a verdict. */
static void test_validate_out_of_memory(void)
{
    mt_mesh *m = hand_tetrahedron(NULL);
    mt_diag d;
    mt__test_fail_alloc_after(0);
    CHECK_STATUS(mt_mesh_validate(m, &d), MT_ERR_NOMEM);
    mt__test_fail_alloc_after(-1);
    CHECK_EQ(d.status, MT_ERR_NOMEM);
    CHECK_OK(mt_mesh_validate(m, &d));
    hand_mesh_free(m);
}

static const mt_test_case cases[] = {
    {"validate_hand_meshes", test_validate_hand_meshes},
    {"validate_empty_and_isolated", test_validate_empty_and_isolated},
    {"validate_null", test_validate_null},
    {"validate_generated", test_validate_generated},
    {"validate_messy_builds", test_validate_messy_builds},
    {"validate_odd_half_edges", test_validate_odd_half_edges},
    {"validate_vertex_counts", test_validate_vertex_counts},
    {"validate_missing_array", test_validate_missing_array},
    {"validate_report_counts", test_validate_report_counts},
    {"validate_head_out_of_range", test_validate_head_out_of_range},
    {"validate_next_out_of_range", test_validate_next_out_of_range},
    {"validate_face_out_of_range", test_validate_face_out_of_range},
    {"validate_face_he_out_of_range", test_validate_face_he_out_of_range},
    {"validate_vert_he_out_of_range", test_validate_vert_he_out_of_range},
    {"validate_copy_out_of_range", test_validate_copy_out_of_range},
    {"validate_bundle_out_of_range", test_validate_bundle_out_of_range},
    {"validate_component_out_of_range", test_validate_component_out_of_range},
    {"validate_next_not_permutation", test_validate_next_not_permutation},
    {"validate_broken_twin_head", test_validate_broken_twin_head},
    {"validate_face_ring_mismatch", test_validate_face_ring_mismatch},
    {"validate_face_he_mismatch", test_validate_face_he_mismatch},
    {"validate_face_rejected_but_named", test_validate_face_rejected_but_named},
    {"validate_face_two_rings", test_validate_face_two_rings},
    {"validate_edge_without_face", test_validate_edge_without_face},
    {"validate_edge_direction", test_validate_edge_direction},
    {"validate_short_face_ring", test_validate_short_face_ring},
    {"validate_face_repeats_vertex", test_validate_face_repeats_vertex},
    {"validate_vert_he_wrong_tail", test_validate_vert_he_wrong_tail},
    {"validate_vert_he_not_boundary", test_validate_vert_he_not_boundary},
    {"validate_vert_he_missing", test_validate_vert_he_missing},
    {"validate_rotation_misses_half_edges", test_validate_rotation_misses_half_edges},
    {"validate_fan_two_boundaries", test_validate_fan_two_boundaries},
    {"validate_copy_without_fan", test_validate_copy_without_fan},
    {"validate_copies_order", test_validate_copies_order},
    {"validate_bundle_endpoints", test_validate_bundle_endpoints},
    {"validate_bundle_lookup", test_validate_bundle_lookup},
    {"validate_unbundled_duplicate_edge", test_validate_unbundled_duplicate_edge},
    {"validate_component_mismatch", test_validate_component_mismatch},
    {"validate_out_of_memory", test_validate_out_of_memory},
};

const mt_test_table mt_tests_validate = {cases, sizeof cases / sizeof cases[0]};
