/* Tests of the edits (edit.h) one operation at a time: the seed rectangle's
 * flip checked half-edge by half-edge, exact count changes of every edit on
 * the Platonic solids, a grid with boundary and a torus, refusals (each leaves
 * the mesh byte-identical and names its reason), bad ids, meshes the edits do
 * not support, and compaction against a brute-force relabelling. Every mesh is
 * validated after every edit. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "edit_check.h"
#include "harness.h"
#include "mesh/mesh_internal.h"
#include "meshtopo/edit.h"
#include "meshtopo/generate.h"
#include "meshtopo/mesh.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"
#include "meshtopo/validate.h"

#define CHECK_VALID(m)                                              \
    do {                                                            \
        mt_diag mt__vd;                                             \
        if (mt_mesh_validate((m), &mt__vd) != MT_OK)                \
            mt_test_fail(__FILE__, __LINE__, "%s", mt__vd.message); \
    } while (0)

/* Live counts must match the report's running counts and change by (dv, de, df). */
#define CHECK_DELTA(m, before, dv, de, df)                     \
    do {                                                       \
        edit_counts now = edit_count(m);                       \
        CHECK_EQ(now.verts, (int64_t)(before).verts + (dv));   \
        CHECK_EQ(now.edges, (int64_t)(before).edges + (de));   \
        CHECK_EQ(now.faces, (int64_t)(before).faces + (df));   \
        CHECK_EQ((m)->report.num_edges, now.edges);            \
        CHECK_EQ((m)->report.num_faces_valid, now.faces);      \
        CHECK_EQ((m)->report.euler_characteristic, now.euler); \
    } while (0)

static mt_mesh *platonic(mt_platonic kind)
{
    mt_face_list l;
    if (mt_gen_platonic(kind, &l) != MT_OK) exit(2);
    return edit_build(&l);
}

static mt_mesh *rectangle(void)
{
    mt_face_list l;
    if (mt_gen_rectangle(2.0, 1.0, &l) != MT_OK) exit(2);
    return edit_build(&l);
}

static mt_mesh *grid(uint32_t n, bool tri)
{
    mt_face_list l;
    if (mt_gen_grid(n, n, tri, &l) != MT_OK) exit(2);
    return edit_build(&l);
}

static mt_mesh *torus(void)
{
    mt_face_list l;
    if (mt_gen_torus(8, 6, &l) != MT_OK) exit(2);
    return edit_build(&l);
}

/* Vertices of a face in stored order (up to 16). */
static size_t face_verts(const mt_mesh *m, uint32_t f, uint32_t *out)
{
    size_t n = 0;
    if (mt_face_verts(m, f, out, 16, &n) != MT_OK) return 0;
    return n;
}

static void check_face(const mt_mesh *m, uint32_t f, const uint32_t *want, size_t n, int line)
{
    uint32_t got[16];
    size_t k = face_verts(m, f, got);
    if (k != n) {
        mt_test_fail(__FILE__, line, "face %u has %zu corners, expected %zu", f, k, n);
        return;
    }
    for (size_t i = 0; i < n; i++)
        if (got[i] != want[i])
            mt_test_fail(__FILE__, line, "face %u corner %zu is %u, expected %u", f, i, got[i],
                         want[i]);
}
#define CHECK_FACE(m, f, ...)                             \
    check_face((m), (f), (const uint32_t[]){__VA_ARGS__}, \
               sizeof((const uint32_t[]){__VA_ARGS__}) / sizeof(uint32_t), __LINE__)

static uint32_t he_between(const mt_mesh *m, uint32_t a, uint32_t b)
{
    for (uint32_t h = 0; h < m->num_half_edges; h++)
        if (m->he_head[h] == b && m->he_head[h ^ 1u] == a) return h;
    return MT_NONE;
}

/* A refused edit: the status, a message, and not one byte changed. */
#define CHECK_REFUSED(m, call, expected)                                    \
    do {                                                                    \
        edit_snapshot snap;                                                 \
        edit_snapshot_take((m), &snap);                                     \
        CHECK_STATUS(call, expected);                                       \
        CHECK(d.message[0] != '\0');                                        \
        if (!edit_snapshot_same((m), &snap))                                \
            mt_test_fail(__FILE__, __LINE__, "%s changed the mesh", #call); \
        edit_snapshot_free(&snap);                                          \
        CHECK_VALID(m);                                                     \
    } while (0)

/* ---- the seed rectangle ------------------------------------------------- */

static void rectangle_flip(void)
{
    mt_mesh *m = rectangle();
    edit_counts before = edit_count(m);
    mt_diag d;
    CHECK_OK(mt_edge_flip(m, 0, 2, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, before, 0, 0, 0);
    /* Face 1 was (0, 2, 3) and keeps vertex 0 first; face 0 was (0, 1, 2). */
    CHECK_FACE(m, 1, 0, 1, 3);
    CHECK_FACE(m, 0, 1, 2, 3);
    CHECK(he_between(m, 0, 2) == MT_NONE && he_between(m, 2, 0) == MT_NONE);
    /* Every half-edge by hand: the two triangles' rings, the diagonal's twins,
     * the boundary ring 0 -> 3 -> 2 -> 1 -> 0 and the vertices' half-edges. */
    const uint32_t h01 = he_between(m, 0, 1), h13 = he_between(m, 1, 3), h30 = he_between(m, 3, 0);
    const uint32_t h12 = he_between(m, 1, 2), h23 = he_between(m, 2, 3), h31 = he_between(m, 3, 1);
    const uint32_t b03 = he_between(m, 0, 3), b32 = he_between(m, 3, 2), b21 = he_between(m, 2, 1);
    const uint32_t b10 = he_between(m, 1, 0);
    const uint32_t all[] = {h01, h13, h30, h12, h23, h31, b03, b32, b21, b10};
    for (size_t i = 0; i < 10; i++) CHECK(all[i] != MT_NONE);
    if (mt_test_failures()) {
        mt_mesh_destroy(m);
        return;
    }
    CHECK_EQ(m->num_half_edges, 10);
    CHECK_EQ(h13 ^ 1u, h31);
    CHECK_EQ(h01 ^ 1u, b10);
    CHECK_EQ(h30 ^ 1u, b03);
    CHECK_EQ(h12 ^ 1u, b21);
    CHECK_EQ(h23 ^ 1u, b32);
    CHECK_EQ(m->he_next[h01], h13);
    CHECK_EQ(m->he_next[h13], h30);
    CHECK_EQ(m->he_next[h30], h01);
    CHECK_EQ(m->he_next[h12], h23);
    CHECK_EQ(m->he_next[h23], h31);
    CHECK_EQ(m->he_next[h31], h12);
    CHECK_EQ(m->he_next[b03], b32);
    CHECK_EQ(m->he_next[b32], b21);
    CHECK_EQ(m->he_next[b21], b10);
    CHECK_EQ(m->he_next[b10], b03);
    CHECK_EQ(m->he_face[h01], 1);
    CHECK_EQ(m->he_face[h13], 1);
    CHECK_EQ(m->he_face[h30], 1);
    CHECK_EQ(m->he_face[h12], 0);
    CHECK_EQ(m->he_face[h23], 0);
    CHECK_EQ(m->he_face[h31], 0);
    CHECK_EQ(m->he_face[b03], MT_NONE);
    CHECK_EQ(m->he_face[b32], MT_NONE);
    CHECK_EQ(m->he_face[b21], MT_NONE);
    CHECK_EQ(m->he_face[b10], MT_NONE);
    CHECK_EQ(m->face_he[1], h01);
    CHECK_EQ(m->face_he[0], h12);
    CHECK_EQ(m->vert_he[0], b03);
    CHECK_EQ(m->vert_he[1], b10);
    CHECK_EQ(m->vert_he[2], b21);
    CHECK_EQ(m->vert_he[3], b32);
    /* Edge orientation: the first half-edge of every edge runs low -> high. */
    CHECK_EQ(h13 & 1u, 0);
    uint32_t faces[2];
    size_t nf;
    CHECK_OK(mt_edge_faces(m, 1, 3, faces, 2, &nf));
    CHECK_EQ(nf, 2);
    /* Flipping back restores the original diagonal. */
    CHECK_OK(mt_edge_flip(m, 1, 3, &d));
    CHECK_VALID(m);
    CHECK(he_between(m, 0, 2) != MT_NONE);
    CHECK_REFUSED(m, mt_edge_flip(m, 0, 1, &d), MT_ERR_REFUSED); /* boundary */
    mt_mesh_destroy(m);
}

static void rectangle_every_edit(void)
{
    mt_diag d;
    /* Split the diagonal: 1 vertex, 3 edges, 2 faces, at the midpoint. */
    mt_mesh *m = rectangle();
    edit_counts c = edit_count(m);
    uint32_t v;
    CHECK_OK(mt_edge_split(m, 0, 2, NULL, &v, &d));
    CHECK_VALID(m);
    CHECK_EQ(v, 4);
    CHECK_DELTA(m, c, 1, 3, 2);
    const double *p = mt_mesh_position(m, v);
    CHECK(p && p[0] == 1.0 && p[1] == 0.5 && p[2] == 0.0);
    uint32_t val;
    CHECK_OK(mt_vert_valence(m, v, &val));
    CHECK_EQ(val, 4);
    /* Split a boundary edge: 1 vertex, 2 edges, 1 face. */
    c = edit_count(m);
    const double at[3] = {0.5, 0.0, 0.0};
    CHECK_OK(mt_edge_split(m, 0, 1, at, &v, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, 1, 2, 1);
    CHECK(mt_mesh_position(m, v)[0] == 0.5);
    /* Collapse it back: boundary edge, one triangle. */
    c = edit_count(m);
    CHECK_OK(mt_edge_collapse(m, v, 0, NULL, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, -1, -2, -1);
    CHECK(mt_vert_is_deleted(m, v));
    CHECK_EQ(m->vert_he[v], MT_NONE);
    /* The rectangle's last collapse would leave a dangling edge or a pinch. */
    mt_mesh_destroy(m);

    m = rectangle();
    CHECK_REFUSED(m, mt_edge_collapse(m, 0, 2, NULL, &d), MT_ERR_REFUSED); /* pinch */
    CHECK(strstr(d.message, "boundary") != NULL);
    /* Collapsing boundary edge 1-2 leaves the single triangle (0, 2, 3). */
    c = edit_count(m);
    CHECK_OK(mt_edge_collapse(m, 1, 2, NULL, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, -1, -2, -1);
    CHECK_FACE(m, 1, 0, 2, 3);
    /* A lone triangle: both other sides of any edge are boundary. */
    CHECK_REFUSED(m, mt_edge_collapse(m, 0, 2, NULL, &d), MT_ERR_REFUSED);
    CHECK(strstr(d.message, "dangling") != NULL);
    mt_mesh_destroy(m);
    m = rectangle();
    /* Face split on a triangle: every pair of corners is a side. */
    CHECK_REFUSED(m, mt_face_split(m, 0, 0, 2, NULL, &d), MT_ERR_REFUSED);
    /* Triangulating a triangle changes nothing. */
    uint32_t added = 7;
    CHECK_OK(mt_face_triangulate(m, 0, &added, &d));
    CHECK_EQ(added, 0);
    CHECK_VALID(m);
    /* Add a triangle on the outside of side 1-2, then delete it again. */
    c = edit_count(m);
    const double q[3] = {3.0, 0.5, 0.0};
    CHECK_OK(mt_mesh_add_vert(m, q, &v, &d));
    CHECK_EQ(v, 4);
    CHECK_VALID(m);
    uint32_t f;
    const uint32_t tri[3] = {2, 1, 4};
    CHECK_OK(mt_mesh_add_face(m, tri, 3, &f, &d));
    CHECK_EQ(f, 2);
    CHECK_VALID(m);
    CHECK_DELTA(m, c, 1, 2, 1);
    CHECK_EQ(m->report.euler_characteristic, 1);
    CHECK_FACE(m, 2, 2, 1, 4);
    c = edit_count(m);
    CHECK_OK(mt_face_delete(m, 2, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, 0, -2, -1);
    CHECK_EQ(m->face_he[2], MT_NONE);
    CHECK_EQ(m->vert_he[4], MT_NONE); /* isolated, not deleted */
    CHECK(!mt_vert_is_deleted(m, 4));
    /* Delete the diagonal: both faces go, the boundary edges stay. */
    c = edit_count(m);
    CHECK_OK(mt_edge_delete(m, 0, 2, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, 0, -5, -2);
    mt_mesh_destroy(m);

    /* Delete vertex 1: face 0 goes, 0-1 and 1-2 with it. */
    m = rectangle();
    c = edit_count(m);
    CHECK_OK(mt_vert_delete(m, 1, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, -1, -2, -1);
    CHECK(mt_vert_is_deleted(m, 1));
    CHECK_STATUS(mt_vert_delete(m, 1, &d), MT_ERR_NOT_FOUND);
    mt_mesh_destroy(m);
}

/* ---- Platonic solids ----------------------------------------------------- */

static void platonic_splits_flips_collapses(void)
{
    const mt_platonic kinds[] = {MT_TETRAHEDRON, MT_CUBE, MT_OCTAHEDRON, MT_DODECAHEDRON,
                                 MT_ICOSAHEDRON};
    for (size_t k = 0; k < 5; k++) {
        mt_mesh *m = platonic(kinds[k]);
        mt_diag d;
        const uint32_t a = m->he_head[1], b = m->he_head[0];
        uint32_t fa = m->he_face[0], fb = m->he_face[1];
        uint32_t va[16], vb[16];
        const size_t na = face_verts(m, fa, va), nb = face_verts(m, fb, vb);
        const bool tris = na == 3 && nb == 3;
        edit_counts c = edit_count(m);
        uint32_t v;
        CHECK_OK(mt_edge_split(m, a, b, NULL, &v, &d));
        CHECK_VALID(m);
        CHECK_DELTA(m, c, 1, tris ? 3 : 1, tris ? 2 : 0);
        CHECK_EQ(m->report.euler_characteristic, 2);
        if (!tris) {
            /* Polygons get the new vertex as one more corner. */
            CHECK_EQ(face_verts(m, fa, va), na + 1);
            CHECK_EQ(face_verts(m, fb, vb), nb + 1);
        }
        /* Collapse the new vertex back into a. */
        c = edit_count(m);
        mt_status s = mt_edge_collapse(m, v, a, NULL, &d);
        CHECK_VALID(m);
        if (kinds[k] == MT_TETRAHEDRON) {
            /* Collapsing makes the opposite corners valence 3 again: allowed. */
            CHECK_OK(s);
        } else {
            CHECK_OK(s);
        }
        CHECK_DELTA(m, c, -1, tris ? -3 : -1, tris ? -2 : 0);
        CHECK_EQ(m->report.euler_characteristic, 2);
        /* Flip where both faces are triangles. */
        if (tris) {
            c = edit_count(m);
            s = mt_edge_flip(m, a, b, &d);
            if (kinds[k] == MT_TETRAHEDRON) {
                /* The other two corners are already joined. */
                CHECK_STATUS(s, MT_ERR_REFUSED);
            } else {
                CHECK_OK(s);
                CHECK_VALID(m);
                CHECK_DELTA(m, c, 0, 0, 0);
            }
        } else {
            CHECK_REFUSED(m, mt_edge_flip(m, a, b, &d), MT_ERR_REFUSED);
        }
        mt_mesh_destroy(m);
    }
}

static void tetrahedron_refusals(void)
{
    mt_mesh *m = platonic(MT_TETRAHEDRON);
    mt_diag d;
    /* Any collapse leaves a two-triangle pillow. */
    CHECK_REFUSED(m, mt_edge_collapse(m, 0, 1, NULL, &d), MT_ERR_REFUSED);
    CHECK_REFUSED(m, mt_edge_flip(m, 0, 1, &d), MT_ERR_REFUSED);
    CHECK(strstr(d.message, "already joined") != NULL);
    /* Adding a face on a closed surface. */
    const uint32_t tri[3] = {0, 1, 2};
    CHECK_REFUSED(m, mt_mesh_add_face(m, tri, 3, NULL, &d), MT_ERR_REFUSED);
    /* Bad ids. */
    CHECK_REFUSED(m, mt_edge_split(m, 0, 9, NULL, NULL, &d), MT_ERR_OUT_OF_RANGE);
    CHECK_REFUSED(m, mt_edge_split(m, 0, 0, NULL, NULL, &d), MT_ERR_NOT_FOUND);
    CHECK_REFUSED(m, mt_face_delete(m, 4, &d), MT_ERR_OUT_OF_RANGE);
    CHECK_REFUSED(m, mt_face_split(m, 0, 0, 1, NULL, &d), MT_ERR_REFUSED);
    CHECK_REFUSED(m, mt_face_split(m, 0, 0, 3, NULL, &d), MT_ERR_NOT_FOUND); /* not a corner */
    const uint32_t dup[3] = {0, 1, 1};
    CHECK_REFUSED(m, mt_mesh_add_face(m, dup, 3, NULL, &d), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_edge_split(NULL, 0, 1, NULL, NULL, &d), MT_ERR_INVALID_ARG);
    mt_mesh_destroy(m);
}

static void octahedron_collapse(void)
{
    mt_mesh *m = platonic(MT_OCTAHEDRON);
    mt_diag d;
    edit_counts c = edit_count(m);
    const uint32_t a = m->he_head[1], b = m->he_head[0];
    const double to[3] = {0.0, 0.0, 0.0};
    CHECK_OK(mt_edge_collapse(m, a, b, to, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, -1, -3, -2);
    CHECK(mt_mesh_position(m, b)[0] == 0.0);
    /* Now 5 vertices: the two former apexes have valence 3; another collapse
     * at one of them is refused (pillow) or allowed but never breaks. */
    for (uint32_t h = 0; h < m->num_half_edges; h += 2) {
        if (m->he_head[h] == MT_NONE) continue;
        mt_status s = mt_edge_collapse(m, m->he_head[h + 1], m->he_head[h], NULL, &d);
        CHECK(s == MT_OK || s == MT_ERR_REFUSED);
        CHECK_VALID(m);
        CHECK_EQ(m->report.euler_characteristic, 2);
    }
    mt_mesh_destroy(m);
}

static void cube_face_edits(void)
{
    mt_mesh *m = platonic(MT_CUBE);
    mt_diag d;
    uint32_t vs[16];
    CHECK_EQ(face_verts(m, 0, vs), 4);
    edit_counts c = edit_count(m);
    uint32_t nf;
    CHECK_REFUSED(m, mt_face_split(m, 0, vs[0], vs[1], NULL, &d), MT_ERR_REFUSED);
    CHECK_REFUSED(m, mt_face_split(m, 0, vs[0], 99, NULL, &d), MT_ERR_OUT_OF_RANGE);
    CHECK_OK(mt_face_split(m, 0, vs[2], vs[0], &nf, &d));
    CHECK_VALID(m);
    CHECK_EQ(nf, 6);
    CHECK_DELTA(m, c, 0, 1, 1);
    CHECK_FACE(m, 0, vs[0], vs[2], vs[3]);
    CHECK_FACE(m, 6, vs[0], vs[1], vs[2]);
    /* The same diagonal again: the pair is already an edge. */
    CHECK_EQ(face_verts(m, 1, vs), 4);
    c = edit_count(m);
    uint32_t added;
    CHECK_OK(mt_face_triangulate(m, 1, &added, &d));
    CHECK_EQ(added, 1);
    CHECK_VALID(m);
    CHECK_DELTA(m, c, 0, 1, 1);
    c = edit_count(m);
    CHECK_OK(mt_mesh_triangulate(m, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, 0, 4, 4);
    CHECK_EQ(edit_count(m).faces, 12);
    CHECK_EQ(m->report.euler_characteristic, 2);
    mt_mesh_destroy(m);

    m = platonic(MT_DODECAHEDRON);
    CHECK_OK(mt_mesh_triangulate(m, &d));
    CHECK_VALID(m);
    CHECK_EQ(edit_count(m).faces, 36);
    CHECK_EQ(m->report.euler_characteristic, 2);
    /* Compaction gives the same surface with a fresh report. */
    CHECK_OK(mt_mesh_compact(m, NULL, 0, NULL, 0, &d));
    CHECK_VALID(m);
    CHECK_EQ(mt_mesh_report(m)->num_faces, 36);
    CHECK_EQ(mt_mesh_report(m)->genus, 0);
    CHECK(mt_mesh_report(m)->closed && mt_mesh_report(m)->manifold);
    CHECK_EQ(mt_mesh_edit_count(m), 0);
    mt_mesh_destroy(m);
}

/* An L-shaped hexagon: ear clipping must give triangles of positive area. */
static void triangulate_nonconvex(void)
{
    double pos[] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 1, 2, 0, 0, 2, 0};
    uint32_t sizes[] = {6}, idx[] = {0, 1, 2, 3, 4, 5};
    mt_face_list l = {6, 1, 6, pos, sizes, idx};
    mt_mesh *m = NULL;
    CHECK_OK(mt_mesh_build(&l, NULL, &m, NULL));
    mt_diag d;
    uint32_t added;
    CHECK_OK(mt_face_triangulate(m, 0, &added, &d));
    CHECK_EQ(added, 3);
    CHECK_VALID(m);
    CHECK_EQ(m->report.euler_characteristic, 1);
    double area = 0;
    for (uint32_t f = 0; f < m->num_faces; f++) {
        uint32_t v[16];
        CHECK_EQ(face_verts(m, f, v), 3);
        const double *a = pos + 3 * v[0], *b = pos + 3 * v[1], *c = pos + 3 * v[2];
        const double cr = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        CHECK(cr > 0);
        area += cr / 2;
    }
    CHECK(fabs(area - 3.0) < 1e-12);
    mt_mesh_destroy(m);
}

/* ---- grid with boundary, torus ---------------------------------------- */

static void grid_edits(void)
{
    mt_mesh *m = grid(4, true);
    mt_diag d;
    const int64_t chi = m->report.euler_characteristic;
    CHECK_EQ(chi, 1);
    /* Vertex (i, j) is j*5+i. Interior vertex 6 = (1, 1). */
    edit_counts c = edit_count(m);
    uint32_t val;
    CHECK_OK(mt_vert_valence(m, 12, &val));
    CHECK_OK(mt_vert_delete(m, 12, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, -1, -(int64_t)val, -(int64_t)val);
    CHECK_EQ(m->report.euler_characteristic, 0); /* one more boundary loop */
    size_t nv, nl;
    CHECK_OK(mt_boundary_loops(m, NULL, 0, NULL, 0, &nv, &nl));
    CHECK_EQ(nl, 2);
    /* Deleting a corner face of the hole's neighbour would make a bowtie at a
     * vertex on the hole: find a face touching the hole only at one corner. */
    uint32_t refused = 0;
    for (uint32_t f = 0; f < m->num_faces; f++) {
        if (m->face_he[f] == MT_NONE) continue;
        edit_snapshot snap;
        edit_snapshot_take(m, &snap);
        mt_status s = mt_face_delete(m, f, &d);
        if (s == MT_ERR_REFUSED) {
            refused++;
            CHECK(strstr(d.message, "bowtie") != NULL);
            CHECK(edit_snapshot_same(m, &snap));
        } else {
            CHECK_OK(s);
            CHECK_VALID(m);
        }
        edit_snapshot_free(&snap);
    }
    CHECK(refused > 0);
    mt_mesh_destroy(m);

    /* Boundary edge collapse and split on a quad grid. */
    m = grid(3, false);
    c = edit_count(m);
    uint32_t v;
    CHECK_OK(mt_edge_split(m, 0, 1, NULL, &v, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, 1, 1, 0);
    CHECK_OK(mt_edge_collapse(m, v, 1, NULL, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, 0, 0, 0);
    /* Adding a quad to the outside of the bottom row. */
    uint32_t w0, w1;
    CHECK_OK(mt_mesh_add_vert(m, NULL, &w0, &d));
    CHECK_OK(mt_mesh_add_vert(m, NULL, &w1, &d));
    const uint32_t quad[4] = {1, 0, w0, w1};
    c = edit_count(m);
    CHECK_OK(mt_mesh_add_face(m, quad, 4, NULL, &d));
    CHECK_VALID(m);
    CHECK_DELTA(m, c, 0, 3, 1);
    /* Same direction as an existing face, and a bowtie at a corner. */
    const uint32_t same[3] = {1, 2, w0}; /* grid face runs 1 -> 2 */
    CHECK_REFUSED(m, mt_mesh_add_face(m, same, 3, NULL, &d), MT_ERR_REFUSED);
    CHECK(strstr(d.message, "same direction") != NULL);
    uint32_t x, y;
    CHECK_OK(mt_mesh_add_vert(m, NULL, &x, &d));
    CHECK_OK(mt_mesh_add_vert(m, NULL, &y, &d));
    const uint32_t bow[3] = {3, x, y};
    CHECK_REFUSED(m, mt_mesh_add_face(m, bow, 3, NULL, &d), MT_ERR_REFUSED);
    CHECK(strstr(d.message, "bowtie") != NULL);
    const uint32_t inner[3] = {5, x, y}; /* interior vertex (1, 1) */
    CHECK_REFUSED(m, mt_mesh_add_face(m, inner, 3, NULL, &d), MT_ERR_REFUSED);
    mt_mesh_destroy(m);
}

static void torus_edits(void)
{
    mt_mesh *m = torus();
    mt_diag d;
    CHECK_EQ(m->report.genus, 1);
    for (uint32_t h = 0; h < 40; h += 2) {
        const uint32_t a = m->he_head[h + 1], b = m->he_head[h];
        if (a == MT_NONE) continue;
        edit_counts c = edit_count(m);
        uint32_t v;
        CHECK_OK(mt_edge_split(m, a, b, NULL, &v, &d));
        CHECK_DELTA(m, c, 1, 3, 2);
        c = edit_count(m);
        mt_status s = mt_edge_flip(m, a, v, &d);
        CHECK(s == MT_OK || s == MT_ERR_REFUSED);
        s = mt_edge_collapse(m, v, b, NULL, &d);
        CHECK(s == MT_OK || s == MT_ERR_REFUSED);
        CHECK_VALID(m);
        CHECK_EQ(m->report.euler_characteristic, 0);
    }
    CHECK_OK(mt_mesh_compact(m, NULL, 0, NULL, 0, &d));
    CHECK_VALID(m);
    CHECK_EQ(mt_mesh_report(m)->genus, 1);
    CHECK_EQ(mt_mesh_report(m)->euler_characteristic, 0);
    mt_mesh_destroy(m);
}

/* ---- meshes edits do not support --------------------------------------- */

static void nonmanifold_unsupported(void)
{
    mt_face_list l;
    CHECK_OK(mt_gen_bowtie(&l));
    mt_mesh *m = edit_build(&l);
    mt_diag d;
    CHECK_REFUSED(m, mt_edge_split(m, 0, 1, NULL, NULL, &d), MT_ERR_UNSUPPORTED);
    CHECK(strstr(d.message, "manifold") != NULL);
    CHECK_OK(mt_mesh_compact(m, NULL, 0, NULL, 0, &d)); /* compaction works on any mesh */
    CHECK_VALID(m);
    mt_mesh_destroy(m);
}

/* ---- compaction ---------------------------------------------------------- */

static void compact_maps(void)
{
    mt_face_list l;
    CHECK_OK(mt_gen_icosphere(2, &l));
    mt_mesh *m = edit_build(&l);
    mt_diag d;
    /* Delete scattered vertices and faces, split a few edges. */
    for (uint32_t v = 3; v < m->num_verts; v += 17) {
        mt_status s = mt_vert_delete(m, v, &d);
        CHECK(s == MT_OK || s == MT_ERR_REFUSED);
    }
    for (uint32_t f = 1; f < m->num_faces; f += 23) {
        mt_status s = mt_face_delete(m, f, &d);
        CHECK(s == MT_OK || s == MT_ERR_REFUSED || s == MT_ERR_NOT_FOUND);
    }
    CHECK_OK(mt_edge_split(m, m->he_head[1], m->he_head[0], NULL, NULL, &d));
    CHECK_VALID(m);
    /* The old faces as vertex lists, for the brute-force relabel. */
    const uint32_t old_v = m->num_verts, old_f = m->num_faces;
    uint32_t *old_faces = calloc((size_t)old_f * 16, sizeof(uint32_t));
    size_t *old_n = calloc(old_f, sizeof(size_t));
    double *old_pos = malloc((size_t)old_v * 3 * sizeof(double));
    bool *old_del = calloc(old_v, 1);
    memcpy(old_pos, m->positions, (size_t)old_v * 3 * sizeof(double));
    for (uint32_t f = 0; f < old_f; f++)
        if (m->face_he[f] != MT_NONE) old_n[f] = face_verts(m, f, old_faces + 16 * (size_t)f);
    for (uint32_t v = 0; v < old_v; v++) old_del[v] = mt_vert_is_deleted(m, v);
    const edit_counts c = edit_count(m);

    uint32_t *vmap = malloc(old_v * sizeof(uint32_t)), *fmap = malloc(old_f * sizeof(uint32_t));
    CHECK_STATUS(mt_mesh_compact(m, vmap, old_v - 1, fmap, old_f, &d), MT_ERR_BUFFER_TOO_SMALL);
    CHECK_OK(mt_mesh_compact(m, vmap, old_v, fmap, old_f, &d));
    CHECK_VALID(m);
    /* Brute force: new ids are the old ones in order, deleted ones skipped. */
    uint32_t next = 0;
    for (uint32_t v = 0; v < old_v; v++) {
        CHECK_EQ(vmap[v], old_del[v] ? MT_NONE : next);
        if (!old_del[v]) {
            const double *p = mt_mesh_position(m, next);
            CHECK(p && memcmp(p, old_pos + 3 * (size_t)v, 3 * sizeof(double)) == 0);
            next++;
        }
    }
    CHECK_EQ(m->num_verts, next);
    next = 0;
    for (uint32_t f = 0; f < old_f; f++) {
        CHECK_EQ(fmap[f], old_n[f] ? next : MT_NONE);
        if (!old_n[f]) continue;
        uint32_t got[16];
        CHECK_EQ(face_verts(m, next, got), old_n[f]);
        for (size_t i = 0; i < old_n[f]; i++) CHECK_EQ(got[i], vmap[old_faces[16 * (size_t)f + i]]);
        next++;
    }
    CHECK_EQ(m->num_faces, next);
    const mt_report *r = mt_mesh_report(m);
    CHECK_EQ(r->num_verts, c.verts);
    CHECK_EQ(r->num_edges, c.edges);
    CHECK_EQ(r->num_faces_valid, c.faces);
    CHECK_EQ(r->euler_characteristic, c.euler);
    CHECK_EQ(m->num_half_edges, 2 * c.edges);
    free(old_faces);
    free(old_n);
    free(old_pos);
    free(old_del);
    free(vmap);
    free(fmap);
    mt_mesh_destroy(m);
}

/* The report's V, E, F and Euler characteristic agree after every collapse,
 * deletion and undo, before compaction: V leaves out deleted vertices while
 * mt_mesh_num_verts keeps the id range. */
static void test_edit_report_counts_agree(void)
{
    mt_face_list list;
    CHECK_OK(mt_gen_icosphere(2, &list));
    mt_mesh *m = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(&list, NULL, &m, &diag));
    mt_face_list_free(&list);
    if (!m) return;
    const uint32_t ids = mt_mesh_num_verts(m);
    int collapses = 0;
    for (uint32_t f = 0; f < mt_mesh_num_faces(m) && collapses < 20; f += 7) {
        uint32_t verts[3];
        size_t n = 0;
        if (mt_face_verts(m, f, verts, 3, &n) != MT_OK || n != 3) continue;
        if (mt_edge_collapse(m, verts[0], verts[1], NULL, &diag) != MT_OK) continue;
        collapses++;
        const mt_report *r = mt_mesh_report(m);
        CHECK_EQ((int64_t)r->num_verts - (int64_t)r->num_edges + (int64_t)r->num_faces_valid,
                 r->euler_characteristic);
        CHECK_EQ(r->euler_characteristic, 2);
        CHECK_EQ(mt_mesh_num_verts(m), ids);
        CHECK_OK(mt_mesh_validate(m, &diag));
    }
    CHECK(collapses > 10);
    /* A refused edit leaves the counts as they were. */
    const uint32_t v_before = mt_mesh_report(m)->num_verts;
    CHECK(mt_vert_delete(m, ids + 5, &diag) != MT_OK);
    CHECK_EQ(mt_mesh_report(m)->num_verts, v_before);
    /* Compaction keeps V and renumbers the ids to it. */
    CHECK_OK(mt_mesh_compact(m, NULL, 0, NULL, 0, &diag));
    CHECK_EQ(mt_mesh_report(m)->num_verts, v_before);
    CHECK_EQ(mt_mesh_num_verts(m), v_before);
    mt_mesh_destroy(m);
}

static const mt_test_case cases[] = {
    {"edit_report_counts_agree", test_edit_report_counts_agree},
    {"edit_rectangle_flip", rectangle_flip},
    {"edit_rectangle_every_edit", rectangle_every_edit},
    {"edit_platonic", platonic_splits_flips_collapses},
    {"edit_tetrahedron_refusals", tetrahedron_refusals},
    {"edit_octahedron_collapse", octahedron_collapse},
    {"edit_cube_face_edits", cube_face_edits},
    {"edit_triangulate_nonconvex", triangulate_nonconvex},
    {"edit_grid", grid_edits},
    {"edit_torus", torus_edits},
    {"edit_nonmanifold_unsupported", nonmanifold_unsupported},
    {"edit_compact_maps", compact_maps},
};
const mt_test_table mt_tests_edit = {cases, sizeof cases / sizeof cases[0]};
