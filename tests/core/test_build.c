/* Builder tests: the half-edge relations of the seed rectangle checked by
 * hand, each defect kind reported with its element ids, strict mode, bad
 * arguments, allocation failure at every allocation, and thread counts. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "mesh/mesh_internal.h"
#include "meshtopo/core.h"

/* A face list over caller arrays (no allocation). */
static mt_face_list list_of(uint32_t num_verts, uint32_t num_faces, uint32_t *sizes,
                            uint32_t *indices, double *positions)
{
    uint64_t total = 0;
    for (uint32_t f = 0; f < num_faces; f++) total += sizes[f];
    mt_face_list fl = {num_verts, num_faces, total, positions, sizes, indices};
    return fl;
}

static mt_mesh *build_ok(const mt_face_list *fl)
{
    mt_mesh *m = NULL;
    mt_diag d;
    CHECK_OK(mt_mesh_build(fl, NULL, &m, &d));
    if (!m) return NULL;
    mt_status s = mt_mesh_validate(m, &d);
    if (s != MT_OK) mt_test_fail(__FILE__, __LINE__, "validate: %s", d.message);
    return m;
}

/* Half-edge from caller vertex a to b, MT_NONE if none. */
static uint32_t find_he(const mt_mesh_view *v, const mt_mesh *m, uint32_t a, uint32_t b)
{
    for (uint32_t h = 0; h < v->num_half_edges; h++)
        if (mt_vert_original(m, mt_he_tail(v, h)) == a && mt_vert_original(m, v->he_head[h]) == b)
            return h;
    return MT_NONE;
}

static size_t count_kind(const mt_report *r, mt_defect_kind kind)
{
    return mt_report_count_defects(r, kind);
}

static const mt_defect *first_of(const mt_report *r, mt_defect_kind kind)
{
    for (size_t i = 0; i < r->num_defects; i++)
        if (r->defects[i].kind == (uint32_t)kind) return &r->defects[i];
    return NULL;
}

/* The seed article's rectangle: (0,0),(w,0),(w,h),(0,h), diagonal v0-v2. */
static void test_rectangle_relations(void)
{
    mt_face_list fl;
    CHECK_OK(mt_gen_rectangle(2.0, 1.0, &fl));
    mt_mesh *m = build_ok(&fl);
    if (!m) return;
    mt_mesh_view v;
    mt_mesh_get_view(m, &v);
    CHECK_EQ(v.num_verts, 4);
    CHECK_EQ(v.num_verts_internal, 4);
    CHECK_EQ(v.num_half_edges, 10); /* 5 edges: 4 on the boundary, the diagonal inside */

    /* Face 0 = (0,1,2): 0->1, 1->2, 2->0 in that order from face_he. */
    uint32_t h01 = find_he(&v, m, 0, 1), h12 = find_he(&v, m, 1, 2), h20 = find_he(&v, m, 2, 0);
    uint32_t h02 = find_he(&v, m, 0, 2), h23 = find_he(&v, m, 2, 3), h30 = find_he(&v, m, 3, 0);
    CHECK_EQ(v.face_he[0], h01);
    CHECK_EQ(v.face_he[1], h02);
    CHECK_EQ(v.he_next[h01], h12);
    CHECK_EQ(v.he_next[h12], h20);
    CHECK_EQ(v.he_next[h20], h01);
    CHECK_EQ(v.he_next[h02], h23);
    CHECK_EQ(v.he_next[h23], h30);
    CHECK_EQ(v.he_next[h30], h02);
    CHECK_EQ(v.he_face[h01], 0);
    CHECK_EQ(v.he_face[h12], 0);
    CHECK_EQ(v.he_face[h20], 0);
    CHECK_EQ(v.he_face[h02], 1);
    CHECK_EQ(v.he_face[h23], 1);
    CHECK_EQ(v.he_face[h30], 1);
    /* The diagonal's two half-edges are twins. */
    CHECK_EQ(mt_he_twin(h20), h02);
    /* The boundary: one ring 0->3->2->1->0 without faces, the other way round. */
    uint32_t b03 = find_he(&v, m, 0, 3), b32 = find_he(&v, m, 3, 2);
    uint32_t b21 = find_he(&v, m, 2, 1), b10 = find_he(&v, m, 1, 0);
    CHECK_EQ(mt_he_twin(b03), h30);
    CHECK_EQ(mt_he_twin(b32), h23);
    CHECK_EQ(mt_he_twin(b21), h12);
    CHECK_EQ(mt_he_twin(b10), h01);
    CHECK_EQ(v.he_face[b03], MT_NONE);
    CHECK_EQ(v.he_face[b32], MT_NONE);
    CHECK_EQ(v.he_face[b21], MT_NONE);
    CHECK_EQ(v.he_face[b10], MT_NONE);
    CHECK_EQ(v.he_next[b03], b32);
    CHECK_EQ(v.he_next[b32], b21);
    CHECK_EQ(v.he_next[b21], b10);
    CHECK_EQ(v.he_next[b10], b03);
    /* Every vertex is on the boundary and keeps its boundary half-edge. */
    CHECK_EQ(v.vert_he[0], b03);
    CHECK_EQ(v.vert_he[1], b10);
    CHECK_EQ(v.vert_he[2], b21);
    CHECK_EQ(v.vert_he[3], b32);
    /* Rotation around vertex 0 from its boundary half-edge: 0->3, 0->2, 0->1. */
    CHECK_EQ(mt_he_rotate(&v, b03), h02);
    CHECK_EQ(mt_he_rotate(&v, h02), h01);
    CHECK_EQ(mt_he_rotate(&v, h01), b03);

    const mt_report *r = mt_mesh_report(m);
    CHECK_EQ(r->num_edges, 5);
    CHECK_EQ(r->boundary_edges, 4);
    CHECK_EQ(r->boundary_loops, 1);
    CHECK_EQ(r->boundary_loop_lengths[0], 4);
    CHECK_EQ(r->euler_characteristic, 1);
    CHECK_EQ(r->connected_components, 1);
    CHECK(r->manifold && r->orientable && !r->closed && r->consistently_oriented);
    CHECK_EQ(r->components[0].genus, -1);
    CHECK_EQ(r->components[0].genus_with_boundary, 0);
    CHECK_EQ(r->num_defects, 0);
    CHECK(mt_mesh_position(m, 2)[0] == 2.0 && mt_mesh_position(m, 2)[1] == 1.0);
    mt_mesh_destroy(m);
    mt_face_list_free(&fl);
}

static void test_closed_solids(void)
{
    const mt_platonic kinds[] = {MT_TETRAHEDRON, MT_CUBE, MT_OCTAHEDRON, MT_DODECAHEDRON,
                                 MT_ICOSAHEDRON};
    const uint32_t edges[] = {6, 12, 12, 30, 30};
    for (size_t k = 0; k < 5; k++) {
        mt_face_list fl;
        CHECK_OK(mt_gen_platonic(kinds[k], &fl));
        mt_mesh *m = build_ok(&fl);
        if (!m) continue;
        const mt_report *r = mt_mesh_report(m);
        CHECK_EQ(r->num_edges, edges[k]);
        CHECK_EQ(r->euler_characteristic, 2);
        CHECK(r->closed && r->manifold && r->orientable);
        CHECK_EQ(r->genus, 0);
        CHECK_EQ(r->boundary_edges, 0);
        CHECK_EQ(r->num_defects, 0);
        mt_mesh_view v;
        mt_mesh_get_view(m, &v);
        CHECK_EQ(v.num_half_edges, 2 * edges[k]);
        for (uint32_t h = 0; h < v.num_half_edges; h++) CHECK(v.he_face[h] != MT_NONE);
        mt_mesh_destroy(m);
        mt_face_list_free(&fl);
    }
}

static void test_genus(void)
{
    mt_face_list fl;
    CHECK_OK(mt_gen_torus(12, 8, &fl));
    mt_mesh *m = build_ok(&fl);
    if (m) {
        CHECK_EQ(mt_mesh_report(m)->genus, 1);
        CHECK_EQ(mt_mesh_report(m)->euler_characteristic, 0);
        mt_mesh_destroy(m);
    }
    mt_face_list_free(&fl);
    CHECK_OK(mt_gen_double_torus(8, &fl));
    m = build_ok(&fl);
    if (m) {
        CHECK_EQ(mt_mesh_report(m)->genus, 2);
        CHECK(mt_mesh_report(m)->manifold);
        mt_mesh_destroy(m);
    }
    mt_face_list_free(&fl);
    CHECK_OK(mt_gen_moebius(10, &fl));
    m = build_ok(&fl);
    if (m) {
        const mt_report *r = mt_mesh_report(m);
        CHECK(!r->orientable);
        CHECK(r->manifold);
        CHECK_EQ(r->boundary_loops, 1);
        CHECK_EQ(r->boundary_loop_lengths[0], 20);
        CHECK_EQ(r->genus, -1);
        mt_mesh_destroy(m);
    }
    mt_face_list_free(&fl);
}

static void test_bowtie_splits_vertex(void)
{
    mt_face_list fl;
    CHECK_OK(mt_gen_bowtie(&fl));
    mt_mesh *m = build_ok(&fl);
    if (!m) return;
    mt_mesh_view v;
    mt_mesh_get_view(m, &v);
    CHECK_EQ(v.num_verts_internal, 6); /* vertex 0 holds two fans: one copy */
    CHECK_EQ(mt_vert_original(m, 5), 0);
    const mt_report *r = mt_mesh_report(m);
    CHECK_EQ(r->bowtie_vertices, 1);
    CHECK_EQ(r->nonmanifold_vertices, 1);
    CHECK(!r->manifold);
    CHECK_EQ(r->connected_components, 2);
    CHECK_EQ(r->vertex_connected_components, 1);
    CHECK_EQ(r->boundary_loops, 1); /* a figure eight */
    CHECK(r->boundary_loops_ambiguous);
    CHECK(r->components[0].manifold && r->components[1].manifold);
    const mt_defect *d = first_of(r, MT_DEFECT_NONMANIFOLD_VERTEX);
    CHECK(d && d->a == 0 && d->b == 2 && d->c == 0);
    mt_mesh_destroy(m);
    mt_face_list_free(&fl);
}

static void test_fin_bundles_edge(void)
{
    mt_face_list fl;
    CHECK_OK(mt_gen_fin(&fl));
    mt_mesh *m = build_ok(&fl);
    if (!m) return;
    const mt_report *r = mt_mesh_report(m);
    CHECK_EQ(r->nonmanifold_edges, 1);
    CHECK_EQ(r->num_edges, 7);
    CHECK_EQ(r->connected_components, 1);
    CHECK(!r->manifold && !r->components[0].manifold);
    const mt_defect *d = first_of(r, MT_DEFECT_NONMANIFOLD_EDGE);
    CHECK(d && d->a == 0 && d->b == 1 && d->c == 3);
    CHECK_EQ(count_kind(r, MT_DEFECT_NONMANIFOLD_VERTEX), 2);
    size_t count = 0;
    uint32_t faces[4];
    CHECK_OK(mt_edge_faces(m, 1, 0, faces, 4, &count));
    CHECK_EQ(count, 3);
    mt_mesh_destroy(m);
    mt_face_list_free(&fl);
}

/* Every defect kind in one face list, each reported with its ids. */
static void test_defects_named(void)
{
    double pos[3 * 9] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 0,
                         0, 2, 1, 0, 5, 5, 5, 0, 0, 0, 3, 3, 3};
    pos[3 * 8 + 1] = NAN;
    uint32_t sizes[] = {3, 3, 3, 3, 3, 2, 4};
    uint32_t idx[] = {0,           1, 2,     /* f0 */
                      2,           1, 3,     /* f1 */
                      2,           1, 3,     /* f2: repeats f1, and runs 1->3 the same way */
                      1,           4, 9,     /* f3: index 9 out of range */
                      4,           5, 4,     /* f4: repeated vertex */
                      4,           5,        /* f5: two vertices */
                      0xffffffffu, 1, 2, 3}; /* f6: -1 */
    mt_face_list fl = list_of(9, 7, sizes, idx, pos);
    mt_mesh *m = build_ok(&fl);
    if (!m) return;
    const mt_report *r = mt_mesh_report(m);
    CHECK_EQ(r->num_faces_valid, 3);
    CHECK_EQ(r->out_of_range_indices, 2);
    CHECK_EQ(r->faces_with_out_of_range_indices, 2);
    const mt_defect *d = first_of(r, MT_DEFECT_OUT_OF_RANGE_INDEX);
    CHECK(d && d->a == 3 && d->b == 9 && d->c == 2);
    CHECK_EQ(r->degenerate_faces, 2);
    d = first_of(r, MT_DEFECT_DEGENERATE_FACE);
    CHECK(d && d->a == 4 && d->b == 2 && d->c == 3);
    CHECK_EQ(r->duplicate_faces, 1);
    d = first_of(r, MT_DEFECT_DUPLICATE_FACE);
    CHECK(d && d->a == 2 && d->b == 1);
    CHECK_EQ(r->duplicate_directed_edges, 3);
    CHECK_EQ(r->inconsistent_orientation_edges, 2); /* 2-3 and 3-1: two faces each, same way */
    CHECK_EQ(r->nonmanifold_edges, 1);              /* 1-2: f0, f1, f2 */
    CHECK_EQ(r->isolated_vertices, 5);              /* 4, 5 (only in bad faces), 6, 7, 8 */
    CHECK_EQ(count_kind(r, MT_DEFECT_ISOLATED_VERTEX), r->isolated_vertices);
    CHECK_EQ(r->unreferenced_vertices, 3);
    CHECK_EQ(r->nonfinite_vertices, 1);
    d = first_of(r, MT_DEFECT_NONFINITE_COORD);
    CHECK(d && d->a == 8 && d->b == 1);
    char text[256];
    for (size_t i = 0; i < r->num_defects; i++) {
        size_t n = mt_defect_describe(&r->defects[i], text, sizeof text);
        CHECK(n > 0 && strlen(text) == n);
    }
    mt_mesh_destroy(m);
}

static void test_strict_mode(void)
{
    mt_build_options strict = {.strict = true};
    mt_mesh *m = NULL;
    mt_diag d;
    mt_face_list fl;
    CHECK_OK(mt_gen_fin(&fl));
    CHECK_STATUS(mt_mesh_build(&fl, &strict, &m, &d), MT_ERR_DEFECT);
    CHECK(m == NULL);
    CHECK(strstr(d.message, "0-1") != NULL);
    CHECK(d.status == MT_ERR_DEFECT);
    mt_face_list_free(&fl);
    CHECK_OK(mt_gen_platonic(MT_ICOSAHEDRON, &fl));
    CHECK_OK(mt_mesh_build(&fl, &strict, &m, &d));
    CHECK(m != NULL);
    mt_mesh_destroy(m);
    mt_face_list_free(&fl);
}

static void test_bad_arguments(void)
{
    mt_mesh *m = (mt_mesh *)&m; /* must be reset to NULL on failure */
    mt_diag d;
    CHECK_STATUS(mt_mesh_build(NULL, NULL, &m, &d), MT_ERR_INVALID_ARG);
    CHECK(m == NULL);
    CHECK(d.message[0] != '\0');
    uint32_t sizes[] = {3, 3};
    uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    mt_face_list fl = list_of(4, 2, sizes, idx, NULL);
    CHECK_STATUS(mt_mesh_build(&fl, NULL, NULL, &d), MT_ERR_INVALID_ARG);
    fl.num_indices = 5; /* sizes add up to 6 */
    CHECK_STATUS(mt_mesh_build(&fl, NULL, &m, &d), MT_ERR_INVALID_ARG);
    CHECK(strstr(d.message, "face 1") != NULL);
    fl.num_indices = 6;
    sizes[1] = 0x80000000u; /* a face claiming 2^31 vertices */
    CHECK_STATUS(mt_mesh_build(&fl, NULL, &m, &d), MT_ERR_INVALID_ARG);
    sizes[1] = 3;
    fl.face_sizes = NULL;
    CHECK_STATUS(mt_mesh_build(&fl, NULL, &m, &d), MT_ERR_INVALID_ARG);
    fl.face_sizes = sizes;
    fl.face_indices = NULL;
    CHECK_STATUS(mt_mesh_build(&fl, NULL, &m, &d), MT_ERR_INVALID_ARG);
    fl.face_indices = idx;
    fl.num_verts = 0x80000000u;
    CHECK_STATUS(mt_mesh_build(&fl, NULL, &m, &d), MT_ERR_TOO_LARGE);
    fl.num_verts = 4;
    uint32_t big_sizes[] = {0x80000000u, 0x80000000u};
    mt_face_list huge = {4, 2, 0x100000000ull, NULL, big_sizes, idx};
    CHECK_STATUS(mt_mesh_build(&huge, NULL, &m, &d), MT_ERR_TOO_LARGE);
    CHECK(m == NULL);
    /* Empty meshes are fine. */
    mt_face_list empty = {0, 0, 0, NULL, NULL, NULL};
    CHECK_OK(mt_mesh_build(&empty, NULL, &m, &d));
    if (m) {
        CHECK_OK(mt_mesh_validate(m, &d));
        CHECK_EQ(mt_mesh_report(m)->connected_components, 0);
        CHECK(!mt_mesh_report(m)->closed);
        mt_mesh_destroy(m);
    }
    mt_face_list verts_only = {3, 0, 0, NULL, NULL, NULL};
    CHECK_OK(mt_mesh_build(&verts_only, NULL, &m, &d));
    if (m) {
        CHECK_EQ(mt_mesh_report(m)->isolated_vertices, 3);
        CHECK_OK(mt_mesh_validate(m, &d));
        mt_mesh_destroy(m);
    }
    mt_mesh_destroy(NULL);
}

/* A mesh touching every allocation path: bundles, copies, defects, holes,
 * several components, flipped faces, big polygons. */
static void messy_list(mt_face_list *out)
{
    mt_face_list a, b;
    CHECK_OK(mt_gen_torus(6, 5, &a));
    CHECK_OK(mt_gen_fin(&b));
    uint32_t extra_faces = 3;
    uint64_t n = a.num_indices + b.num_indices + 3 + 70 + 3;
    CHECK_OK(mt_face_list_alloc(out, a.num_verts + b.num_verts + 70,
                                a.num_faces + b.num_faces + extra_faces, n, NULL));
    uint32_t f = 0;
    uint64_t k = 0;
    for (uint32_t i = 0; i < a.num_faces; i++) out->face_sizes[f++] = a.face_sizes[i];
    for (uint64_t i = 0; i < a.num_indices; i++) out->face_indices[k++] = a.face_indices[i];
    for (uint32_t i = 0; i < b.num_faces; i++) out->face_sizes[f++] = b.face_sizes[i];
    for (uint64_t i = 0; i < b.num_indices; i++)
        out->face_indices[k++] = b.face_indices[i] + a.num_verts;
    /* A flipped copy of the torus' first face, a 70-gon, a bad face. */
    out->face_sizes[f++] = 3;
    out->face_indices[k++] = a.face_indices[2];
    out->face_indices[k++] = a.face_indices[1];
    out->face_indices[k++] = a.face_indices[0];
    out->face_sizes[f++] = 70;
    for (uint32_t i = 0; i < 70; i++) out->face_indices[k++] = a.num_verts + b.num_verts + i;
    out->face_sizes[f++] = 3;
    out->face_indices[k++] = 0;
    out->face_indices[k++] = 0;
    out->face_indices[k++] = 99999;
    mt_face_list_free(&a);
    mt_face_list_free(&b);
}

static void test_allocation_failures(void)
{
    mt_face_list fl;
    messy_list(&fl);
    int succeeded = 0;
    for (long n = 0; n < 200 && !succeeded; n++) {
        mt_mesh *m = NULL;
        mt_diag d;
        mt__test_fail_alloc_after(n);
        mt_status s = mt_mesh_build(&fl, NULL, &m, &d);
        mt__test_fail_alloc_after(-1);
        if (s == MT_OK) {
            succeeded = 1;
            CHECK_OK(mt_mesh_validate(m, &d));
            mt_mesh_destroy(m);
        } else {
            CHECK_EQ(s, MT_ERR_NOMEM);
            CHECK(m == NULL);
            CHECK(strstr(d.message, "memory") != NULL);
        }
    }
    CHECK(succeeded);
    mt_face_list_free(&fl);
}

static void check_same_mesh(const mt_mesh *a_mesh, const mt_mesh *b_mesh)
{
    mt_mesh_view a, b;
    mt_mesh_get_view(a_mesh, &a);
    mt_mesh_get_view(b_mesh, &b);
    CHECK_EQ(a.num_half_edges, b.num_half_edges);
    CHECK_EQ(a.num_verts_internal, b.num_verts_internal);
    if (a.num_half_edges != b.num_half_edges || a.num_verts_internal != b.num_verts_internal)
        return;
    CHECK(memcmp(a.he_next, b.he_next, a.num_half_edges * sizeof(uint32_t)) == 0);
    CHECK(memcmp(a.he_head, b.he_head, a.num_half_edges * sizeof(uint32_t)) == 0);
    CHECK(memcmp(a.he_face, b.he_face, a.num_half_edges * sizeof(uint32_t)) == 0);
    CHECK(memcmp(a.face_he, b.face_he, a.num_faces * sizeof(uint32_t)) == 0);
    CHECK(memcmp(a.vert_he, b.vert_he, a.num_verts_internal * sizeof(uint32_t)) == 0);
    const mt_report *ra = mt_mesh_report(a_mesh), *rb = mt_mesh_report(b_mesh);
    CHECK_EQ(ra->num_defects, rb->num_defects);
    if (ra->num_defects == rb->num_defects)
        CHECK(memcmp(ra->defects, rb->defects, ra->num_defects * sizeof(mt_defect)) == 0);
    CHECK_EQ(ra->connected_components, rb->connected_components);
    CHECK_EQ(ra->nonmanifold_vertices, rb->nonmanifold_vertices);
}

/* mt_mesh_build_taking_positions: the mesh holds the list's own positions
 * array (no copy) and the list gives it up; structure, report and positions
 * are those of a copying build, the non-finite coordinate planted here
 * included. A build that fails (a strict refusal, each allocation failing
 * in turn) leaves the array to the list, which frees it. */
static void test_taking_positions(void)
{
    mt_face_list fl, copy;
    messy_list(&fl);
    messy_list(&copy);
    fl.positions[3 * 7 + 2] = copy.positions[3 * 7 + 2] = NAN;
    const double *array = fl.positions;
    mt_mesh *taken = NULL, *copied = NULL;
    mt_diag d;
    CHECK_OK(mt_mesh_build(&copy, NULL, &copied, &d));
    CHECK_OK(mt_mesh_build_taking_positions(&fl, NULL, &taken, &d));
    CHECK(fl.positions == NULL);
    CHECK(mt_mesh_position(taken, 0) == array);
    CHECK_OK(mt_mesh_validate(taken, &d));
    check_same_mesh(taken, copied);
    CHECK_EQ(mt_mesh_report(taken)->nonfinite_vertices, 1);
    for (uint32_t v = 0; v < copy.num_verts; v++)
        CHECK(memcmp(mt_mesh_position(taken, v), &copy.positions[3 * (size_t)v],
                     3 * sizeof(double)) == 0);
    mt_mesh_destroy(taken);
    mt_mesh_destroy(copied);
    mt_face_list_free(&fl);
    mt_face_list_free(&copy);

    mt_build_options strict = {.strict = true};
    CHECK_OK(mt_gen_fin(&fl));
    array = fl.positions;
    CHECK_STATUS(mt_mesh_build_taking_positions(&fl, &strict, &taken, &d), MT_ERR_DEFECT);
    CHECK(taken == NULL && fl.positions == array);
    mt_face_list_free(&fl);

    int succeeded = 0;
    for (long n = 0; n < 200 && !succeeded; n++) {
        messy_list(&fl);
        array = fl.positions;
        mt__test_fail_alloc_after(n);
        mt_status s = mt_mesh_build_taking_positions(&fl, NULL, &taken, &d);
        mt__test_fail_alloc_after(-1);
        if (s == MT_OK) {
            succeeded = 1;
            CHECK(fl.positions == NULL && mt_mesh_position(taken, 0) == array);
            CHECK_OK(mt_mesh_validate(taken, &d));
            mt_mesh_destroy(taken);
        } else {
            CHECK_EQ(s, MT_ERR_NOMEM);
            CHECK(taken == NULL && fl.positions == array);
        }
        mt_face_list_free(&fl);
    }
    CHECK(succeeded);
}

/* Any thread count gives the same structure, messy input included. */
static void test_thread_counts_agree(void)
{
    mt_face_list fl;
    messy_list(&fl);
    mt_mesh *messy = build_ok(&fl);
    for (uint32_t t = 2; t <= 3 && messy; t++) {
        mt_build_options o = {.threads = t};
        mt_mesh *m = NULL;
        CHECK_OK(mt_mesh_build(&fl, &o, &m, NULL));
        if (m) check_same_mesh(messy, m);
        mt_mesh_destroy(m);
    }
    mt_mesh_destroy(messy);
    mt_face_list_free(&fl);
    CHECK_OK(mt_gen_grid(40, 30, true, &fl));
    CHECK_OK(mt_face_list_permute(&fl, 7, NULL));
    mt_mesh *ref = build_ok(&fl);
    for (uint32_t t = 0; t <= 3 && ref; t++) {
        mt_build_options o = {.threads = t};
        mt_mesh *m = NULL;
        CHECK_OK(mt_mesh_build(&fl, &o, &m, NULL));
        if (!m) continue;
        CHECK_OK(mt_mesh_validate(m, NULL));
        check_same_mesh(ref, m);
        mt_mesh_destroy(m);
    }
    mt_mesh_destroy(ref);
    mt_face_list_free(&fl);
}

/* A shuffled grid of several matching blocks (of 2048 vertices or more each)
 * with defects spread over them: fins, flipped and repeated faces, and a
 * hub vertex with two fans of many triangles (more sides on one vertex
 * than a short sort takes). */
static void messy_grid(mt_face_list *out)
{
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(150, 150, true, &grid));
    CHECK_OK(mt_face_list_permute(&grid, 11, NULL));
    enum { FINS = 40, FLIPS = 40, REPEATS = 10, FAN_A = 99, FAN_B = 50 };
    const uint32_t nv = grid.num_verts, hub = nv + FINS;
    const uint32_t extra_verts = FINS + 1 + (FAN_A + 1) + (FAN_B + 1);
    const uint32_t extra_faces = FINS + FLIPS + REPEATS + FAN_A + FAN_B;
    CHECK_OK(mt_face_list_alloc(out, nv + extra_verts, grid.num_faces + extra_faces,
                                grid.num_indices + 3 * (uint64_t)extra_faces, NULL));
    memcpy(out->face_sizes, grid.face_sizes, grid.num_faces * sizeof(uint32_t));
    memcpy(out->face_indices, grid.face_indices, grid.num_indices * sizeof(uint32_t));
    uint32_t f = grid.num_faces, *idx = out->face_indices + grid.num_indices;
    uint64_t state = 12345;
    for (uint32_t i = 0; i < FINS + FLIPS + REPEATS; i++) {
        state = state * 6364136223846793005u + 1442695040888963407u;
        const uint32_t *g = grid.face_indices + 3 * ((state >> 33) % grid.num_faces);
        const uint32_t fin[3] = {g[0], g[1], nv + i}, flip[3] = {g[2], g[1], g[0]};
        const uint32_t *face = i < FINS ? fin : i < FINS + FLIPS ? flip : g;
        out->face_sizes[f++] = 3;
        for (int k = 0; k < 3; k++) *idx++ = face[k];
    }
    for (uint32_t i = 0; i < FAN_A + FAN_B; i++) {
        const uint32_t rim = i < FAN_A ? hub + 1 + i : hub + 2 + i;
        out->face_sizes[f++] = 3;
        *idx++ = hub;
        *idx++ = rim;
        *idx++ = rim + 1;
    }
    CHECK_EQ(f, out->num_faces);
    mt_face_list_free(&grid);
}

/* Matching split over blocks on two threads gives the one-thread mesh. */
static void test_thread_counts_agree_across_blocks(void)
{
    mt_face_list fl;
    messy_grid(&fl);
    mt_mesh *one = NULL, *two = NULL;
    mt_build_options o1 = {.threads = 1}, o2 = {.threads = 2};
    CHECK_OK(mt_mesh_build(&fl, &o1, &one, NULL));
    CHECK_OK(mt_mesh_build(&fl, &o2, &two, NULL));
    if (one && two) {
        CHECK_OK(mt_mesh_validate(one, NULL));
        CHECK_OK(mt_mesh_validate(two, NULL));
        check_same_mesh(one, two);
        const mt_report *r = mt_mesh_report(one);
        CHECK_EQ(r->nonmanifold_edges, 40 + 3 * 40 + 3 * 10); /* fins, then flips and repeats */
        CHECK_EQ(r->nonmanifold_vertices >= 1, 1);
        CHECK_EQ(r->duplicate_faces, 40 + 10);
    }
    mt_mesh_destroy(one);
    mt_mesh_destroy(two);
    mt_face_list_free(&fl);
}

/* A workspace kept across builds of different sizes, on one and two
 * threads, changes nothing in the result (its arrays hold the last build's
 * values, not zeros); it grows to the largest build and then stays. */
static void test_workspace_reuse(void)
{
    mt_build_workspace *ws = mt_build_workspace_create();
    CHECK(ws != NULL);
    CHECK_EQ(mt_build_workspace_bytes(NULL), 0);
    mt_face_list small, large;
    messy_list(&small);
    messy_grid(&large);
    const mt_face_list *order[] = {&small, &large, &small, &large};
    size_t sized = 0;
    for (int i = 0; i < 4 && ws; i++) {
        for (uint32_t threads = 1; threads <= 2; threads++) {
            mt_build_options fresh = {.threads = threads};
            mt_build_options kept = {.threads = threads, .workspace = ws};
            mt_mesh *a = NULL, *b = NULL;
            CHECK_OK(mt_mesh_build(order[i], &fresh, &a, NULL));
            CHECK_OK(mt_mesh_build(order[i], &kept, &b, NULL));
            if (a && b) {
                CHECK_OK(mt_mesh_validate(b, NULL));
                check_same_mesh(a, b);
            }
            mt_mesh_destroy(a);
            mt_mesh_destroy(b);
        }
        if (i == 1) sized = mt_build_workspace_bytes(ws);
        if (i > 1) CHECK_EQ(mt_build_workspace_bytes(ws), sized);
    }
    /* The sides alone take 16 bytes per side of the large list. */
    CHECK(sized > 16 * large.num_indices);
    mt_build_workspace_destroy(ws);
    mt_build_workspace_destroy(NULL);
    mt_face_list_free(&small);
    mt_face_list_free(&large);
}

/* A build with a workspace fails cleanly at every allocation, and the
 * workspace serves the next build. */
static void test_workspace_allocation_failures(void)
{
    mt_face_list fl;
    messy_list(&fl);
    mt_mesh *ref = build_ok(&fl);
    int succeeded = 0;
    for (long n = 0; n < 200 && !succeeded && ref; n++) {
        mt_build_workspace *ws = mt_build_workspace_create();
        CHECK(ws != NULL);
        if (!ws) break;
        mt_build_options o = {.threads = 1, .workspace = ws};
        mt_mesh *m = NULL;
        mt_diag d;
        mt__test_fail_alloc_after(n);
        mt_status s = mt_mesh_build(&fl, &o, &m, &d);
        mt__test_fail_alloc_after(-1);
        if (s == MT_OK) {
            succeeded = 1;
            check_same_mesh(ref, m);
        } else {
            CHECK_EQ(s, MT_ERR_NOMEM);
            CHECK(m == NULL);
            CHECK_OK(mt_mesh_build(&fl, &o, &m, NULL));
            if (m) check_same_mesh(ref, m);
        }
        mt_mesh_destroy(m);
        mt_build_workspace_destroy(ws);
    }
    CHECK(succeeded);
    mt_mesh_destroy(ref);
    mt_face_list_free(&fl);
}

/* Builds `list` with the workspace on two threads and checks the result
 * against `ref`; NULL when the build failed. */
static mt_mesh *build_with(const mt_face_list *list, mt_build_workspace *ws, const mt_mesh *ref)
{
    mt_build_options o = {.threads = 2, .workspace = ws};
    mt_mesh *m = NULL;
    CHECK_OK(mt_mesh_build(list, &o, &m, NULL));
    if (!m) return NULL;
    CHECK_OK(mt_mesh_validate(m, NULL));
    check_same_mesh(ref, m);
    CHECK(memcmp(m->positions, list->positions, 3 * sizeof(double) * list->num_verts) == 0);
    return m;
}

/* The four large arrays of a mesh, as recycling keeps them. */
typedef struct mesh_arrays {
    const void *he_block, *face_he, *vert_he, *positions;
} mesh_arrays;

static mesh_arrays arrays_of(const mt_mesh *m)
{
    mesh_arrays a = {m->he_head, m->face_he, m->vert_he, m->positions};
    return a;
}

/* How many of got's arrays are among kept's. */
static int arrays_reused(const mesh_arrays *got, const mesh_arrays *kept)
{
    const void *g[4] = {got->he_block, got->face_he, got->vert_he, got->positions};
    const void *k[4] = {kept->he_block, kept->face_he, kept->vert_he, kept->positions};
    int reused = 0;
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) reused += g[i] == k[j];
    }
    return reused;
}

/* A recycled mesh's arrays serve the next build with the workspace (the
 * same memory, and the mesh a fresh build gives); a build of less than half
 * their size leaves them kept; an edited mesh's grown arrays serve a build
 * too. Under AddressSanitizer a recycled array whose size was overstated
 * shows as an overflow when the next build fills it. */
static void test_workspace_recycle(void)
{
    mt_build_workspace *ws = mt_build_workspace_create();
    mt_face_list large, small, tiny;
    CHECK_OK(mt_gen_grid(120, 90, true, &large));
    CHECK_OK(mt_face_list_permute(&large, 5, NULL));
    CHECK_OK(mt_gen_grid(30, 30, true, &small));
    CHECK_OK(mt_gen_grid(10, 10, true, &tiny));
    mt_mesh *ref_large = build_ok(&large), *ref_small = build_ok(&small);
    mt_mesh *ref_tiny = build_ok(&tiny);
    mt_mesh *a =
        ws && ref_large && ref_small && ref_tiny ? build_with(&large, ws, ref_large) : NULL;
    if (a) {
        const size_t scratch = mt_build_workspace_bytes(ws);
        const mesh_arrays kept = arrays_of(a);
        mt_build_workspace_recycle(ws, a);
        /* Half-edges, faces, vertices and positions: 12 + 4 + 4 + 24 bytes. */
        const size_t mesh_bytes = 12 * (size_t)ref_large->num_half_edges +
                                  4 * (size_t)large.num_faces + 28 * (size_t)large.num_verts;
        CHECK(mt_build_workspace_bytes(ws) >= scratch + mesh_bytes);

        mt_mesh *b = build_with(&large, ws, ref_large);
        if (b) {
            const mesh_arrays got = arrays_of(b);
            CHECK(memcmp(&got, &kept, sizeof got) == 0);
            CHECK_EQ(mt_build_workspace_bytes(ws), scratch);
        }
        mt_build_workspace_recycle(ws, b);
        mt_mesh *c = build_with(&tiny, ws, ref_tiny);
        if (c) {
            const mesh_arrays got = arrays_of(c);
            CHECK_EQ(arrays_reused(&got, &kept), 0);
            CHECK(mt_build_workspace_bytes(ws) >= scratch + mesh_bytes);
        }
        mt_mesh_destroy(c);
    }
    /* An edit doubles every array of the small grid; the same grid built
     * next takes three of them: its faces the closest fit, the doubled
     * vertex array; its half-edges and positions their own; its vertex array
     * is new, as the doubled face array is over twice its size. */
    mt_build_workspace *edited_ws = mt_build_workspace_create();
    mt_mesh *edited = ref_small ? build_ok(&small) : NULL;
    if (edited && edited_ws) {
        const double middle[3] = {0.5, 0.5, 0.0};
        CHECK_OK(mt_edge_split(edited, 32, 33, middle, NULL, NULL));
        CHECK(edited->cap_half_edges > 0 && edited->cap_faces > 0 && edited->cap_verts > 0);
        const mesh_arrays kept = arrays_of(edited);
        mt_build_workspace_recycle(edited_ws, edited);
        mt_mesh *d = build_with(&small, edited_ws, ref_small);
        if (d) {
            const mesh_arrays got = arrays_of(d);
            CHECK_EQ(arrays_reused(&got, &kept), 3);
            CHECK(d->he_head == kept.he_block && d->face_he == kept.vert_he);
            CHECK(d->positions == kept.positions);
        }
        mt_mesh_destroy(d);
    } else {
        mt_mesh_destroy(edited);
    }
    mt_build_workspace_recycle(NULL, build_ok(&small)); /* destroys it */
    mt_build_workspace_recycle(ws, NULL);
    mt_build_workspace_destroy(edited_ws);
    mt_build_workspace_destroy(ws);
    mt_mesh_destroy(ref_large);
    mt_mesh_destroy(ref_small);
    mt_mesh_destroy(ref_tiny);
    mt_face_list_free(&large);
    mt_face_list_free(&small);
    mt_face_list_free(&tiny);
}

/* Memory stays within 56 bytes per face on a large triangle grid. */
static void test_memory_per_face(void)
{
    mt_face_list fl;
    CHECK_OK(mt_gen_grid(200, 200, true, &fl));
    mt_mesh *m = build_ok(&fl);
    if (m) {
        double per_face = (double)mt_mesh_memory_bytes(m) / fl.num_faces;
        if (per_face > 56.0) mt_test_fail(__FILE__, __LINE__, "%.1f bytes per face", per_face);
        mt_mesh_destroy(m);
    }
    mt_face_list_free(&fl);
}

static const mt_test_case cases[] = {
    {"build_rectangle_relations", test_rectangle_relations},
    {"build_closed_solids", test_closed_solids},
    {"build_genus", test_genus},
    {"build_bowtie_splits_vertex", test_bowtie_splits_vertex},
    {"build_fin_bundles_edge", test_fin_bundles_edge},
    {"build_defects_named", test_defects_named},
    {"build_strict_mode", test_strict_mode},
    {"build_bad_arguments", test_bad_arguments},
    {"build_allocation_failures", test_allocation_failures},
    {"build_taking_positions", test_taking_positions},
    {"build_thread_counts_agree", test_thread_counts_agree},
    {"build_thread_counts_agree_across_blocks", test_thread_counts_agree_across_blocks},
    {"build_workspace_reuse", test_workspace_reuse},
    {"build_workspace_allocation_failures", test_workspace_allocation_failures},
    {"build_workspace_recycle", test_workspace_recycle},
    {"build_memory_per_face", test_memory_per_face},
};
const mt_test_table mt_tests_build = {cases, sizeof cases / sizeof cases[0]};
