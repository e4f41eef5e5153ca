/* mt_mesh_restore (meshtopo/mesh_parts.h): meshes made from their own
 * arrays answer every query like the built mesh, for generated, defective
 * and corpus meshes; hostile arrays (wrong lengths, a next ring that does
 * not close, indices out of range, a twin mismatch, wrapping bundle
 * offsets, random corruption) are refused with a message and never read
 * out of bounds. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "archive_test_util.h"
#include "harness.h"
#include "meshtopo/archive.h"
#include "meshtopo/core.h"
#include "restore_check.h"

/* Builds, restores from the built mesh's parts, and checks the restored
 * mesh: validates, same arrays, same answers. */
static void restore_round_trip(const mt_face_list *list, const char *what)
{
    mt_mesh *built = NULL, *restored = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(list, NULL, &built, &diag));
    if (!built) return;
    CHECK_OK(mt_mesh_validate(built, &diag));
    mt_mesh_parts parts;
    mt_mesh_get_parts(built, &parts);
    mt_status st = mt_mesh_restore(&parts, mt_mesh_report(built), &restored, &diag);
    CHECK_OK(st);
    if (st != MT_OK) printf("%s: restore: %s\n", what, diag.message);
    if (restored) {
        CHECK_OK(mt_mesh_validate(restored, &diag));
        CHECK(rc_same_answers(built, restored, what));
        mt_mesh_parts again;
        mt_mesh_get_parts(restored, &again);
        CHECK_EQ(again.num_half_edges, parts.num_half_edges);
        CHECK_EQ(again.num_copies, parts.num_copies);
        CHECK_EQ(again.num_bundled, parts.num_bundled);
        CHECK((again.vert_component == NULL) == (parts.vert_component == NULL));
        CHECK(again.he_next != parts.he_next); /* a copy, not the same memory */
    }
    mt_mesh_destroy(restored);
    mt_mesh_destroy(built);
}

/* Two triangles sharing no vertex (two components: vert_component is
 * kept), a vertex used by no face, a face with an out-of-range index, a
 * degenerate face and a duplicate face. */
static void make_messy(mt_face_list *list)
{
    static const uint32_t sizes[] = {3, 3, 3, 3, 3};
    static const uint32_t indices[] = {0, 1, 2, 3, 4, 5, 0, 1, 9, 3, 3, 4, 2, 0, 1};
    CHECK_OK(mt_face_list_alloc(list, 7, 5, 15, NULL));
    memcpy(list->face_sizes, sizes, sizeof sizes);
    memcpy(list->face_indices, indices, sizeof indices);
    for (uint32_t i = 0; i < 21; i++) list->positions[i] = (double)i * 0.25;
}

static void test_restore_round_trip_generated(void)
{
    mt_face_list list;
    mt_platonic kinds[] = {MT_TETRAHEDRON, MT_CUBE, MT_ICOSAHEDRON};
    for (int i = 0; i < 3; i++) {
        CHECK_OK(mt_gen_platonic(kinds[i], &list));
        restore_round_trip(&list, "platonic");
        mt_face_list_free(&list);
    }
    CHECK_OK(mt_gen_grid(9, 6, true, &list));
    restore_round_trip(&list, "grid");
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_torus(8, 6, &list));
    restore_round_trip(&list, "torus");
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_moebius(9, &list));
    restore_round_trip(&list, "moebius");
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_double_torus(8, &list));
    restore_round_trip(&list, "double torus");
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_bowtie(&list)); /* vertex copies */
    restore_round_trip(&list, "bowtie");
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_fin(&list)); /* edge bundles */
    restore_round_trip(&list, "fin");
    mt_face_list_free(&list);
    make_messy(&list);
    restore_round_trip(&list, "messy");
    free(list.positions);
    list.positions = NULL;
    restore_round_trip(&list, "messy without geometry");
    mt_face_list_free(&list);
    mt_face_list empty;
    memset(&empty, 0, sizeof empty);
    restore_round_trip(&empty, "empty");
}

static void restore_named(const char *name, const mt_face_list *list, void *ctx)
{
    (void)ctx;
    restore_round_trip(list, name);
}

static void test_restore_round_trip_corpus(void)
{
    int meshes = at_for_each_corpus_mesh(restore_named, NULL);
    CHECK(meshes >= 20);
}

/* Writable copies of a mesh's arrays, to damage one at a time. */
typedef struct damaged {
    mt_mesh_parts parts;
    uint32_t *arrays[12];
    double *positions;
} damaged;

static uint32_t *dup_u32(const uint32_t *src, size_t n)
{
    uint32_t *p = malloc((n ? n : 1) * sizeof *p);
    if (p && n) memcpy(p, src, n * sizeof *p);
    return p;
}

static void damaged_make(const mt_mesh *m, damaged *d)
{
    memset(d, 0, sizeof *d);
    mt_mesh_get_parts(m, &d->parts);
    mt_mesh_parts *p = &d->parts;
    const uint32_t **fields[12] = {&p->he_head,        &p->he_next,        &p->he_face,
                                   &p->face_he,        &p->vert_he,        &p->copy_original,
                                   &p->copies_sorted,  &p->bundle_offsets, &p->bundle_edges,
                                   &p->bundled_sorted, &p->bundled_bundle, &p->vert_component};
    const size_t lengths[12] = {
        p->num_half_edges,     p->num_half_edges,
        p->num_half_edges,     p->num_faces,
        p->num_verts_internal, p->num_copies,
        p->num_copies,         p->num_bundles ? p->num_bundles + 1 : 0,
        p->num_bundled,        p->num_bundled,
        p->num_bundled,        p->vert_component ? p->num_verts_internal : 0};
    for (int i = 0; i < 12; i++) {
        if (!*fields[i]) continue;
        d->arrays[i] = dup_u32(*fields[i], lengths[i]);
        *fields[i] = d->arrays[i];
    }
    if (p->positions) {
        d->positions = malloc(3 * (size_t)p->num_verts * sizeof(double));
        memcpy(d->positions, p->positions, 3 * (size_t)p->num_verts * sizeof(double));
        p->positions = d->positions;
    }
}

static void damaged_free(damaged *d)
{
    for (int i = 0; i < 12; i++) free(d->arrays[i]);
    free(d->positions);
}

/* Restoring must fail with `status` and a message containing `text`. */
static void expect_refused(const damaged *d, const mt_report *report, mt_status status,
                           const char *text, const char *what)
{
    mt_mesh *m = (mt_mesh *)(uintptr_t)1;
    mt_diag diag;
    mt_status st = mt_mesh_restore(&d->parts, report, &m, &diag);
    CHECK_STATUS(st, status);
    CHECK(m == NULL);
    CHECK(diag.message[0] != '\0');
    bool named = strstr(diag.message, text) != NULL;
    CHECK(named);
    if (st != status || !named || getenv("MT_TEST_VERBOSE"))
        printf("%s: %s (expected \"%s\")\n", what, diag.message, text);
    if (st == MT_OK) mt_mesh_destroy(m);
}

/* A mesh with copies (a bowtie) and two bundles (two fins), three
 * components, no geometry. */
static mt_mesh *build_hostile_base(void)
{
    mt_face_list pieces[3], all;
    CHECK_OK(mt_gen_bowtie(&pieces[0]));
    CHECK_OK(mt_gen_fin(&pieces[1]));
    CHECK_OK(mt_gen_fin(&pieces[2]));
    uint32_t nv = 0, nf = 0;
    uint64_t ni = 0;
    for (int i = 0; i < 3; i++) {
        nv += pieces[i].num_verts;
        nf += pieces[i].num_faces;
        ni += pieces[i].num_indices;
    }
    CHECK_OK(mt_face_list_alloc(&all, nv, nf, ni, NULL));
    free(all.positions);
    all.positions = NULL;
    uint32_t v0 = 0, f0 = 0;
    uint64_t i0 = 0;
    for (int i = 0; i < 3; i++) {
        memcpy(all.face_sizes + f0, pieces[i].face_sizes, pieces[i].num_faces * sizeof(uint32_t));
        for (uint64_t k = 0; k < pieces[i].num_indices; k++)
            all.face_indices[i0 + k] = pieces[i].face_indices[k] + v0;
        v0 += pieces[i].num_verts;
        f0 += pieces[i].num_faces;
        i0 += pieces[i].num_indices;
        mt_face_list_free(&pieces[i]);
    }
    mt_mesh *m = NULL;
    CHECK_OK(mt_mesh_build(&all, NULL, &m, NULL));
    if (m) CHECK_OK(mt_mesh_validate(m, NULL));
    mt_face_list_free(&all);
    return m;
}

static void test_restore_hostile_arrays(void)
{
    mt_mesh *m = build_hostile_base();
    if (!m) return;
    const mt_report *r = mt_mesh_report(m);
    damaged d;
    damaged_make(m, &d);
    CHECK(d.parts.num_copies > 0);
    CHECK(d.parts.num_bundles > 0);
    CHECK(d.parts.vert_component != NULL);
    mt_mesh *ok = NULL;
    CHECK_OK(mt_mesh_restore(&d.parts, r, &ok, NULL)); /* undamaged copies restore */
    mt_mesh_destroy(ok);
    mt_mesh_parts good = d.parts;
    uint32_t *head = d.arrays[0], *next = d.arrays[1], *face = d.arrays[2];
    const uint32_t nhe = good.num_half_edges, nvi = good.num_verts_internal;

    /* Wrong lengths. */
    d.parts.num_verts_internal = nvi + 1;
    expect_refused(&d, r, MT_ERR_INVALID_ARG, "copies", "internal count");
    d.parts = good;
    d.parts.num_bundled = good.num_bundled - 1;
    expect_refused(&d, r, MT_ERR_CORRUPT, "bundle_offsets ends at", "bundled count");
    d.parts = good;
    d.parts.num_faces = good.num_faces - 1;
    expect_refused(&d, r, MT_ERR_INVALID_ARG, "report counts", "face count");
    d.parts = good;
    d.parts.num_half_edges = nhe - 1;
    expect_refused(&d, r, MT_ERR_CORRUPT, "odd number of half-edges", "odd half-edges");
    d.parts = good;
    d.parts.num_half_edges = 0x80000000u;
    expect_refused(&d, r, MT_ERR_TOO_LARGE, "2^31", "huge half-edge count");
    d.parts = good;
    d.parts.he_next = NULL;
    expect_refused(&d, r, MT_ERR_INVALID_ARG, "missing", "missing he_next");
    d.parts = good;

    /* A next ring that does not close: two half-edges with the same next. */
    uint32_t saved = next[0];
    next[0] = next[2];
    expect_refused(&d, r, MT_ERR_CORRUPT, "not a permutation", "next not a permutation");
    next[0] = saved;
    /* A next ring that closes early (h is its own next). */
    next[0] = 0;
    expect_refused(&d, r, MT_ERR_CORRUPT, "half-edge 0", "ring of one");
    next[0] = saved;

    /* Indices out of range. */
    saved = head[3];
    head[3] = nvi + 5;
    expect_refused(&d, r, MT_ERR_CORRUPT, "is not a vertex", "head out of range");
    head[3] = saved;
    saved = next[4];
    next[4] = nhe;
    expect_refused(&d, r, MT_ERR_CORRUPT, "is not a half-edge", "next out of range");
    next[4] = saved;
    uint32_t *first = &face[0];
    for (uint32_t h = 0; h < nhe; h++)
        if (face[h] != MT_NONE) {
            first = &face[h];
            break;
        }
    saved = *first;
    *first = good.num_faces + 3;
    expect_refused(&d, r, MT_ERR_CORRUPT, "is not a face record", "face out of range");
    *first = saved;
    saved = d.arrays[3][0];
    d.arrays[3][0] = nhe + 7;
    expect_refused(&d, r, MT_ERR_CORRUPT, "face_he", "face_he out of range");
    d.arrays[3][0] = saved;
    damaged_free(&d);
    damaged_make(m, &d);
    d.arrays[4][1] = 0xfffffff0u;
    expect_refused(&d, r, MT_ERR_CORRUPT, "vert_he", "vert_he out of range");
    damaged_free(&d);
    damaged_make(m, &d);
    d.arrays[5][0] = good.num_verts;
    expect_refused(&d, r, MT_ERR_CORRUPT, "is not a caller vertex", "copy original");
    damaged_free(&d);
    damaged_make(m, &d);
    d.arrays[8][0] = nhe; /* bundle_edges: past the edges */
    expect_refused(&d, r, MT_ERR_CORRUPT, "is not an edge", "bundle edge");
    damaged_free(&d);
    damaged_make(m, &d);
    d.arrays[11][0] = 1000;
    expect_refused(&d, r, MT_ERR_CORRUPT, "is not a component", "vertex component");
    damaged_free(&d);

    /* Bundle offsets that wrap around: with offsets[1] = 2^32 - 1,
     * offsets[1] + 2 overflows uint32 and a check written as
     * offsets[2] < offsets[1] + 2 lets bundle 1 run past the arrays. */
    damaged_make(m, &d);
    CHECK(d.parts.num_bundles >= 2);
    if (d.parts.num_bundles >= 2) {
        d.arrays[7][1] = 0xffffffffu;
        expect_refused(&d, r, MT_ERR_CORRUPT, "bundle 1: offsets 4294967295..",
                       "wrapping bundle offsets");
    }
    damaged_free(&d);

    /* A twin mismatch: an edge's half-edges swap heads, so next(h) no longer
     * starts where h ends. */
    damaged_make(m, &d);
    head = d.arrays[0];
    saved = head[0];
    head[0] = head[1];
    head[1] = saved;
    expect_refused(&d, r, MT_ERR_CORRUPT, "starts at vertex", "twin mismatch");
    damaged_free(&d);

    /* A report whose lists are missing or whose defect kind is unknown. */
    damaged_make(m, &d);
    mt_report bad = *r;
    bad.defects = NULL;
    if (r->num_defects > 0) expect_refused(&d, &bad, MT_ERR_INVALID_ARG, "report", "report list");
    bad = *r;
    bad.num_faces_valid = r->num_faces_valid + 1;
    expect_refused(&d, &bad, MT_ERR_CORRUPT, "valid faces", "report valid faces");
    damaged_free(&d);
    mt_mesh_destroy(m);
}

/* Every query runs on a restored mesh without reading out of bounds
 * (sanitizers watch): after any accepted corruption the mesh validates. */
static void poke_queries(const mt_mesh *m)
{
    uint32_t nv = mt_mesh_num_verts(m), nf = mt_mesh_num_faces(m);
    for (uint32_t v = 0; v <= nv; v++) {
        mt_ring ring;
        memset(&ring, 0, sizeof ring);
        uint32_t valence;
        mt_vert_ring(m, v, &ring);
        mt_vert_valence(m, v, &valence);
    }
    for (uint32_t f = 0; f <= nf; f++) {
        size_t n = 0, nn = 0, ne = 0;
        uint32_t c;
        mt_face_verts(m, f, NULL, 0, &n);
        mt_face_neighbors(m, f, NULL, 0, NULL, 0, &nn, &ne);
        mt_face_component(m, f, &c);
    }
    size_t lv, ll;
    mt_boundary_loops(m, NULL, 0, NULL, 0, &lv, &ll);
}

static void test_restore_random_corruption(void)
{
    mt_mesh *m = build_hostile_base();
    if (!m) return;
    const mt_report *r = mt_mesh_report(m);
    uint64_t state = 0x9e3779b97f4a7c15ull;
    int refused = 0, accepted = 0;
    for (int round = 0; round < 3000; round++) {
        damaged d;
        damaged_make(m, &d);
        for (int k = 0; k <= round % 3; k++) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            int which = (int)((state >> 33) % 12);
            if (!d.arrays[which]) continue;
            const size_t lengths[12] = {
                d.parts.num_half_edges, d.parts.num_half_edges,     d.parts.num_half_edges,
                d.parts.num_faces,      d.parts.num_verts_internal, d.parts.num_copies,
                d.parts.num_copies,     d.parts.num_bundles + 1u,   d.parts.num_bundled,
                d.parts.num_bundled,    d.parts.num_bundled,        d.parts.num_verts_internal};
            if (lengths[which] == 0) continue;
            size_t i = (size_t)((state >> 17) % lengths[which]);
            uint32_t values[] = {0,       1,           2,           3,
                                 MT_NONE, 0x7fffffffu, 0x80000000u, (uint32_t)(state >> 40) % 40};
            d.arrays[which][i] = values[(state >> 5) % 8];
        }
        mt_mesh *restored = NULL;
        mt_diag diag;
        mt_status st = mt_mesh_restore(&d.parts, r, &restored, &diag);
        if (st == MT_OK) {
            accepted++;
            CHECK_OK(mt_mesh_validate(restored, NULL));
            poke_queries(restored);
            mt_mesh_destroy(restored);
        } else {
            refused++;
            CHECK(restored == NULL);
            CHECK(diag.message[0] != '\0');
        }
        damaged_free(&d);
    }
    CHECK(refused > 1000);
    printf(
        "random corruption: %d refused, %d accepted (a value rewritten to itself, or a "
        "consistent change)\n",
        refused, accepted);
    mt_mesh_destroy(m);
}

static const mt_test_case cases[] = {
    {"restore_round_trip_generated", test_restore_round_trip_generated},
    {"restore_round_trip_corpus", test_restore_round_trip_corpus},
    {"restore_hostile_arrays", test_restore_hostile_arrays},
    {"restore_random_corruption", test_restore_random_corruption},
};
const mt_test_table mt_tests_mesh_restore = {cases, sizeof cases / sizeof cases[0]};
