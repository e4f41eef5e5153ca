/* Tests of the queries (query.h) and raw access (mesh.h): exact answers on
 * the hand-written meshes (hand_mesh.c), the buffer protocol at every
 * capacity, bad arguments, corrupted meshes (an error, never a bad read),
 * and built meshes of every generator checked against the brute-force
 * reference (oracle.c): ring sets, counter-clockwise fan order, face
 * neighbours, edge faces, components and boundary loops. And the queries
 * into buffers that grow: from empty, reused, errors passed through. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hand_mesh.h"
#include "harness.h"
#include "mesh/mesh_internal.h"
#include "meshtopo/generate.h"
#include "meshtopo/mesh.h"
#include "meshtopo/query.h"
#include "meshtopo/validate.h"
#include "oracle.h"

#define N MT_NONE

/* ---- helpers ----------------------------------------------------------- */

#define CHECK_U32S(got, got_count, ...)                             \
    check_u32s((got), (got_count), (const uint32_t[]){__VA_ARGS__}, \
               sizeof((const uint32_t[]){__VA_ARGS__}) / sizeof(uint32_t), __FILE__, __LINE__)

static void check_u32s(const uint32_t *got, size_t got_count, const uint32_t *want,
                       size_t want_count, const char *file, int line)
{
    if (got_count != want_count) {
        mt_test_fail(file, line, "got %zu values, expected %zu", got_count, want_count);
        return;
    }
    for (size_t i = 0; i < want_count; i++)
        if (got[i] != want[i]) {
            mt_test_fail(file, line, "value %zu is %u, expected %u", i, got[i], want[i]);
            return;
        }
}

static int compare_u32(const void *pa, const void *pb)
{
    uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
    return (a > b) - (a < b);
}

static size_t sort_unique(uint32_t *v, size_t n)
{
    if (n == 0) return 0;
    qsort(v, n, sizeof *v, compare_u32);
    size_t m = 1;
    for (size_t i = 1; i < n; i++)
        if (v[i] != v[m - 1]) v[m++] = v[i];
    return m;
}

static void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p) abort();
    return p;
}

/* A ring with buffers of exactly the sizes a size query reports. */
static mt_status ring_get(const mt_mesh *m, uint32_t v, mt_ring *ring)
{
    memset(ring, 0, sizeof *ring);
    mt_status s = mt_vert_ring(m, v, ring);
    if (s != MT_OK) return s;
    ring->neighbors = xmalloc(ring->num_neighbors * sizeof(uint32_t));
    ring->neighbors_capacity = ring->num_neighbors;
    ring->faces = xmalloc(ring->num_faces * sizeof(uint32_t));
    ring->faces_capacity = ring->num_faces;
    ring->fans = xmalloc(ring->num_fans * sizeof(mt_fan));
    ring->fans_capacity = ring->num_fans;
    return mt_vert_ring(m, v, ring);
}

static void ring_free(mt_ring *ring)
{
    free(ring->neighbors);
    free(ring->faces);
    free(ring->fans);
    memset(ring, 0, sizeof *ring);
}

#define CHECK_FAN(fan, nb_begin, nb_count, f_begin, f_count, is_boundary) \
    do {                                                                  \
        CHECK_EQ((fan).neighbor_begin, (nb_begin));                       \
        CHECK_EQ((fan).neighbor_count, (nb_count));                       \
        CHECK_EQ((fan).face_begin, (f_begin));                            \
        CHECK_EQ((fan).face_count, (f_count));                            \
        CHECK_EQ((fan).boundary, (is_boundary));                          \
    } while (0)

/* Face list of mt_face_neighbors, all sides, sorted and deduplicated. */
typedef struct adjacency {
    uint32_t faces[64];
    uint32_t offsets[16];
    size_t num_faces, num_edges;
} adjacency;

static mt_status adjacency_get(const mt_mesh *m, uint32_t f, adjacency *a)
{
    return mt_face_neighbors(m, f, a->faces, 64, a->offsets, 16, &a->num_faces, &a->num_edges);
}

typedef struct loops {
    uint32_t verts[256];
    uint32_t offsets[32];
    size_t num_verts, num_loops;
} loops;

static mt_status loops_get(const mt_mesh *m, loops *l)
{
    return mt_boundary_loops(m, l->verts, 256, l->offsets, 32, &l->num_verts, &l->num_loops);
}

/* ---- hand-written meshes: exact answers -------------------------------- */

static void test_query_triangle(void)
{
    mt_mesh *m = hand_triangle(NULL);
    CHECK_OK(mt_mesh_validate(m, NULL));
    mt_ring ring;
    CHECK_OK(ring_get(m, 0, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 1, 2);
    CHECK_U32S(ring.faces, ring.num_faces, 0);
    CHECK_EQ(ring.num_fans, 1);
    CHECK_FAN(ring.fans[0], 0, 2, 0, 1, true);
    ring_free(&ring);
    CHECK_OK(ring_get(m, 1, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 2, 0);
    CHECK_U32S(ring.faces, ring.num_faces, 0);
    ring_free(&ring);
    CHECK_OK(ring_get(m, 2, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 0, 1);
    ring_free(&ring);

    uint32_t valence = 0;
    for (uint32_t v = 0; v < 3; v++) {
        CHECK_OK(mt_vert_valence(m, v, &valence));
        CHECK_EQ(valence, 2);
    }
    uint32_t verts[3];
    size_t count = 0;
    CHECK_OK(mt_face_verts(m, 0, verts, 3, &count));
    CHECK_U32S(verts, count, 0, 1, 2);

    adjacency adj;
    CHECK_OK(adjacency_get(m, 0, &adj));
    CHECK_EQ(adj.num_faces, 0);
    CHECK_EQ(adj.num_edges, 3);
    CHECK_U32S(adj.offsets, 4, 0, 0, 0, 0);

    uint32_t faces[4];
    CHECK_OK(mt_edge_faces(m, 2, 0, faces, 4, &count));
    CHECK_U32S(faces, count, 0);

    loops l;
    CHECK_OK(loops_get(m, &l));
    CHECK_EQ(l.num_loops, 1);
    CHECK_U32S(l.offsets, 2, 0, 3);
    CHECK_U32S(l.verts, l.num_verts, 1, 2, 0); /* faces on the left: counter-clockwise */

    uint32_t component = N;
    CHECK_OK(mt_face_component(m, 0, &component));
    CHECK_EQ(component, 0);
    hand_mesh_free(m);
}

static void test_query_rectangle(void)
{
    mt_mesh *m = hand_rectangle(NULL);
    CHECK_OK(mt_mesh_validate(m, NULL));
    mt_ring ring;
    CHECK_OK(ring_get(m, 0, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 1, 2, 3);
    CHECK_U32S(ring.faces, ring.num_faces, 0, 1);
    CHECK_EQ(ring.num_fans, 1);
    CHECK_FAN(ring.fans[0], 0, 3, 0, 2, true);
    ring_free(&ring);
    CHECK_OK(ring_get(m, 1, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 2, 0);
    CHECK_U32S(ring.faces, ring.num_faces, 0);
    ring_free(&ring);
    CHECK_OK(ring_get(m, 2, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 3, 0, 1);
    CHECK_U32S(ring.faces, ring.num_faces, 1, 0);
    ring_free(&ring);
    CHECK_OK(ring_get(m, 3, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 0, 2);
    CHECK_U32S(ring.faces, ring.num_faces, 1);
    ring_free(&ring);

    const uint32_t valences[] = {3, 2, 3, 2};
    for (uint32_t v = 0; v < 4; v++) {
        uint32_t valence = 0;
        CHECK_OK(mt_vert_valence(m, v, &valence));
        CHECK_EQ(valence, valences[v]);
    }

    uint32_t verts[3];
    size_t count = 0;
    CHECK_OK(mt_face_verts(m, 1, verts, 3, &count));
    CHECK_U32S(verts, count, 0, 2, 3);

    adjacency adj;
    CHECK_OK(adjacency_get(m, 0, &adj));
    CHECK_U32S(adj.faces, adj.num_faces, 1);
    CHECK_U32S(adj.offsets, adj.num_edges + 1, 0, 0, 0, 1); /* across the diagonal 2-0 */
    CHECK_OK(adjacency_get(m, 1, &adj));
    CHECK_U32S(adj.faces, adj.num_faces, 0);
    CHECK_U32S(adj.offsets, adj.num_edges + 1, 0, 1, 1, 1);

    uint32_t faces[4];
    CHECK_OK(mt_edge_faces(m, 0, 2, faces, 4, &count));
    CHECK_U32S(faces, count, 0, 1);
    CHECK_OK(mt_edge_faces(m, 2, 0, faces, 4, &count));
    CHECK_U32S(faces, count, 0, 1);
    CHECK_OK(mt_edge_faces(m, 3, 2, faces, 4, &count));
    CHECK_U32S(faces, count, 1);
    CHECK_STATUS(mt_edge_faces(m, 1, 3, faces, 4, &count), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_edge_faces(m, 1, 1, faces, 4, &count), MT_ERR_NOT_FOUND);

    loops l;
    CHECK_OK(loops_get(m, &l));
    CHECK_EQ(l.num_loops, 1);
    CHECK_U32S(l.verts, l.num_verts, 1, 2, 3, 0);
    hand_mesh_free(m);
}

static void test_query_tetrahedron(void)
{
    mt_mesh *m = hand_tetrahedron(NULL);
    CHECK_OK(mt_mesh_validate(m, NULL));
    mt_ring ring;
    CHECK_OK(ring_get(m, 0, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 1, 3, 2);
    CHECK_U32S(ring.faces, ring.num_faces, 1, 3, 0);
    CHECK_EQ(ring.num_fans, 1);
    CHECK_FAN(ring.fans[0], 0, 3, 0, 3, false);
    ring_free(&ring);
    CHECK_OK(ring_get(m, 1, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 0, 2, 3);
    CHECK_U32S(ring.faces, ring.num_faces, 0, 2, 1);
    ring_free(&ring);

    for (uint32_t v = 0; v < 4; v++) {
        uint32_t valence = 0;
        CHECK_OK(mt_vert_valence(m, v, &valence));
        CHECK_EQ(valence, 3);
    }
    adjacency adj;
    CHECK_OK(adjacency_get(m, 0, &adj));
    CHECK_U32S(adj.faces, adj.num_faces, 3, 2, 1);
    CHECK_U32S(adj.offsets, adj.num_edges + 1, 0, 1, 2, 3);

    uint32_t faces[4];
    size_t count = 0;
    CHECK_OK(mt_edge_faces(m, 3, 2, faces, 4, &count));
    CHECK_U32S(faces, count, 2, 3);

    /* Closed: no loops, and the offsets still get their leading 0. */
    loops l;
    l.offsets[0] = 77;
    CHECK_OK(loops_get(m, &l));
    CHECK_EQ(l.num_loops, 0);
    CHECK_EQ(l.num_verts, 0);
    CHECK_EQ(l.offsets[0], 0);
    hand_mesh_free(m);
}

static void test_query_bowtie(void)
{
    mt_mesh *m = hand_bowtie(NULL);
    CHECK_OK(mt_mesh_validate(m, NULL));
    mt_ring ring;
    CHECK_OK(ring_get(m, 0, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 1, 2, 3, 4);
    CHECK_U32S(ring.faces, ring.num_faces, 0, 1);
    CHECK_EQ(ring.num_fans, 2);
    CHECK_FAN(ring.fans[0], 0, 2, 0, 1, true);
    CHECK_FAN(ring.fans[1], 2, 2, 1, 1, true);
    ring_free(&ring);
    CHECK_OK(ring_get(m, 3, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 4, 0); /* the copy answers as 0 */
    CHECK_U32S(ring.faces, ring.num_faces, 1);
    ring_free(&ring);

    uint32_t valence = 0;
    CHECK_OK(mt_vert_valence(m, 0, &valence));
    CHECK_EQ(valence, 4);

    uint32_t verts[3];
    size_t count = 0;
    CHECK_OK(mt_face_verts(m, 1, verts, 3, &count));
    CHECK_U32S(verts, count, 0, 3, 4);

    uint32_t component = N;
    CHECK_OK(mt_face_component(m, 0, &component));
    CHECK_EQ(component, 0);
    CHECK_OK(mt_face_component(m, 1, &component));
    CHECK_EQ(component, 1);

    uint32_t faces[4];
    CHECK_OK(mt_edge_faces(m, 4, 0, faces, 4, &count));
    CHECK_U32S(faces, count, 1);
    CHECK_STATUS(mt_edge_faces(m, 1, 3, faces, 4, &count), MT_ERR_NOT_FOUND);

    loops l;
    CHECK_OK(loops_get(m, &l));
    CHECK_EQ(l.num_loops, 2);
    CHECK_U32S(l.offsets, 3, 0, 3, 6);
    CHECK_U32S(l.verts, l.num_verts, 1, 2, 0, 3, 4, 0);

    CHECK_EQ(mt_vert_original(m, 5), 0);
    CHECK_EQ(mt_vert_original(m, 4), 4);
    CHECK_EQ(mt_vert_original(m, 6), N);
    hand_mesh_free(m);
}

static void test_query_fin(void)
{
    mt_mesh *m = hand_fin(NULL);
    CHECK_OK(mt_mesh_validate(m, NULL));
    mt_ring ring;
    CHECK_OK(ring_get(m, 0, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 3, 1, 2, 1, 4);
    CHECK_U32S(ring.faces, ring.num_faces, 1, 0, 2);
    CHECK_EQ(ring.num_fans, 2);
    CHECK_FAN(ring.fans[0], 0, 3, 0, 2, true);
    CHECK_FAN(ring.fans[1], 3, 2, 2, 1, true);
    ring_free(&ring);
    CHECK_OK(ring_get(m, 1, &ring));
    CHECK_U32S(ring.neighbors, ring.num_neighbors, 2, 0, 3, 4, 0);
    CHECK_U32S(ring.faces, ring.num_faces, 0, 1, 2);
    ring_free(&ring);

    /* Neighbour 1 of vertex 0 is reached through both bundled edges. */
    const uint32_t valences[] = {4, 4, 2, 2, 2};
    for (uint32_t v = 0; v < 5; v++) {
        uint32_t valence = 0;
        CHECK_OK(mt_vert_valence(m, v, &valence));
        CHECK_EQ(valence, valences[v]);
    }

    adjacency adj;
    CHECK_OK(adjacency_get(m, 0, &adj));
    CHECK_U32S(adj.faces, adj.num_faces, 1, 2);
    CHECK_U32S(adj.offsets, adj.num_edges + 1, 0, 2, 2, 2);
    CHECK_OK(adjacency_get(m, 1, &adj));
    CHECK_U32S(adj.faces, adj.num_faces, 0, 2);
    CHECK_OK(adjacency_get(m, 2, &adj));
    CHECK_U32S(adj.faces, adj.num_faces, 0, 1);
    CHECK_U32S(adj.offsets, adj.num_edges + 1, 0, 2, 2, 2);

    uint32_t faces[4];
    size_t count = 0;
    CHECK_OK(mt_edge_faces(m, 0, 1, faces, 4, &count));
    CHECK_U32S(faces, count, 0, 1, 2);
    CHECK_OK(mt_edge_faces(m, 1, 0, faces, 4, &count));
    CHECK_U32S(faces, count, 0, 1, 2);
    CHECK_OK(mt_edge_faces(m, 4, 0, faces, 4, &count));
    CHECK_U32S(faces, count, 2);
    CHECK_STATUS(mt_edge_faces(m, 2, 3, faces, 4, &count), MT_ERR_NOT_FOUND);

    loops l;
    CHECK_OK(loops_get(m, &l));
    CHECK_EQ(l.num_loops, 2);
    CHECK_U32S(l.offsets, 3, 0, 4, 7);
    CHECK_U32S(l.verts, l.num_verts, 2, 0, 3, 1, 1, 4, 0);

    uint32_t component = N;
    CHECK_OK(mt_face_component(m, 2, &component));
    CHECK_EQ(component, 0);
    hand_mesh_free(m);
}

static void test_query_mesh_access(void)
{
    mt_mesh *m = hand_fin(NULL);
    CHECK_EQ(mt_mesh_num_verts(m), 5);
    CHECK_EQ(mt_mesh_num_faces(m), 3);
    CHECK_EQ(mt_mesh_num_verts(NULL), 0);
    CHECK_EQ(mt_mesh_num_faces(NULL), 0);
    CHECK(mt_mesh_position(m, 0) == NULL); /* no geometry */

    mt_mesh_view view;
    mt_mesh_get_view(m, &view);
    CHECK_EQ(view.num_verts, 5);
    CHECK_EQ(view.num_verts_internal, 7);
    CHECK_EQ(view.num_faces, 3);
    CHECK_EQ(view.num_half_edges, 16);
    CHECK(view.he_head == m->he_head && view.he_next == m->he_next);
    CHECK(view.he_face == m->he_face && view.face_he == m->face_he);
    CHECK(view.vert_he == m->vert_he && view.positions == NULL);
    /* The view's iterator walks the fans the queries use. */
    uint32_t visited[8], n = 0;
    MT_FOR_VERT_OUT(&view, 0, it)
    {
        if (n < 8) visited[n] = it.current;
        n++;
    }
    CHECK_U32S(visited, n, 4, 0, 6);
    mt_mesh_get_view(NULL, &view);
    CHECK_EQ(view.num_half_edges, 0);
    CHECK(view.he_head == NULL);
    mt_mesh_get_view(m, NULL); /* no crash */

    const uint32_t *copies = NULL;
    CHECK_EQ(mt__vert_copies(m, 0, &copies), 1);
    CHECK_EQ(copies[0], 5);
    CHECK_EQ(mt__vert_copies(m, 1, &copies), 1);
    CHECK_EQ(copies[0], 6);
    CHECK_EQ(mt__vert_copies(m, 2, &copies), 0);
    CHECK_EQ(mt__vert_copies(m, 99, &copies), 0);
    CHECK_EQ(mt__edge_bundle(m, 0), 0);
    CHECK_EQ(mt__edge_bundle(m, 5), 0);
    CHECK_EQ(mt__edge_bundle(m, 1), N);
    CHECK_EQ(mt__edge_bundle(m, 99), N);
    CHECK_EQ(mt_vert_original(m, 6), 1);
    CHECK_EQ(mt_vert_original(m, 7), N);
    CHECK_EQ(mt_vert_original(NULL, 0), N);
    hand_mesh_free(m);

    /* Positions come back per caller vertex. */
    m = hand_triangle(NULL);
    m->positions = malloc(9 * sizeof(double));
    CHECK(m->positions != NULL);
    if (m->positions) {
        for (int i = 0; i < 9; i++) m->positions[i] = i;
        const double *p = mt_mesh_position(m, 2);
        CHECK(p != NULL && p[0] == 6.0 && p[2] == 8.0);
        CHECK(mt_mesh_position(m, 3) == NULL);
        CHECK(mt_mesh_position(NULL, 0) == NULL);
    }
    hand_mesh_free(m);
}

/* Copies of several vertices: the binary search finds each vertex's run. */
static void test_query_vert_copies_lookup(void)
{
    mt_mesh *m = hand_fin(NULL);
    /* Pretend copies: 5 of 0, 6 of 1 are real; widen the table by hand. */
    uint32_t *orig = realloc(m->copy_original, 6 * sizeof *orig);
    uint32_t *sorted = realloc(m->copies_sorted, 6 * sizeof *sorted);
    CHECK(orig && sorted);
    if (orig) m->copy_original = orig;
    if (sorted) m->copies_sorted = sorted;
    if (!orig || !sorted) {
        hand_mesh_free(m);
        return;
    }
    const uint32_t originals[] = {3, 1, 3, 0, 3, 4}; /* copies 5..10 */
    const uint32_t by_original[] = {8, 6, 5, 7, 9, 10};
    memcpy(orig, originals, sizeof originals);
    memcpy(sorted, by_original, sizeof by_original);
    m->num_copies = 6;
    m->num_verts_internal = 11;
    const uint32_t *copies = NULL;
    CHECK_EQ(mt__vert_copies(m, 0, &copies), 1);
    CHECK_EQ(copies[0], 8);
    CHECK_EQ(mt__vert_copies(m, 1, &copies), 1);
    CHECK_EQ(copies[0], 6);
    CHECK_EQ(mt__vert_copies(m, 2, &copies), 0);
    CHECK_EQ(mt__vert_copies(m, 3, &copies), 3);
    CHECK_U32S(copies, 3, 5, 7, 9);
    CHECK_EQ(mt__vert_copies(m, 4, &copies), 1);
    CHECK_EQ(copies[0], 10);
    m->num_copies = 2; /* restore before freeing: the arrays are just longer */
    m->num_verts_internal = 7;
    hand_mesh_free(m);
}

/* ---- the buffer protocol ---------------------------------------------- */

/* Every combination of capacities 0..needed with buffers of exactly that
 * size (so AddressSanitizer sees any overrun): all empty is a size query
 * (MT_OK with sizes), any short one gives MT_ERR_BUFFER_TOO_SMALL with the
 * sizes and untouched buffers, enough room fills them. */
static void test_query_ring_buffers(void)
{
    mt_mesh *m = hand_fin(NULL);
    for (uint32_t nb_cap = 0; nb_cap <= 5; nb_cap++)
        for (uint32_t f_cap = 0; f_cap <= 3; f_cap++)
            for (uint32_t fan_cap = 0; fan_cap <= 2; fan_cap++) {
                mt_ring ring;
                memset(&ring, 0, sizeof ring);
                ring.neighbors = nb_cap ? xmalloc(nb_cap * sizeof(uint32_t)) : NULL;
                ring.faces = f_cap ? xmalloc(f_cap * sizeof(uint32_t)) : NULL;
                ring.fans = fan_cap ? xmalloc(fan_cap * sizeof(mt_fan)) : NULL;
                ring.neighbors_capacity = nb_cap;
                ring.faces_capacity = f_cap;
                ring.fans_capacity = fan_cap;
                for (uint32_t i = 0; i < nb_cap; i++) ring.neighbors[i] = 0xdeadu;
                for (uint32_t i = 0; i < f_cap; i++) ring.faces[i] = 0xdeadu;
                mt_status s = mt_vert_ring(m, 0, &ring);
                CHECK_EQ(ring.num_neighbors, 5);
                CHECK_EQ(ring.num_faces, 3);
                CHECK_EQ(ring.num_fans, 2);
                if (nb_cap == 0 && f_cap == 0 && fan_cap == 0) {
                    CHECK_OK(s);
                } else if (nb_cap == 5 && f_cap == 3 && fan_cap == 2) {
                    CHECK_OK(s);
                    CHECK_U32S(ring.neighbors, 5, 3, 1, 2, 1, 4);
                } else {
                    CHECK_STATUS(s, MT_ERR_BUFFER_TOO_SMALL);
                    for (uint32_t i = 0; i < nb_cap; i++) CHECK_EQ(ring.neighbors[i], 0xdeadu);
                    for (uint32_t i = 0; i < f_cap; i++) CHECK_EQ(ring.faces[i], 0xdeadu);
                }
                ring_free(&ring);
            }
    /* A size query counts NULL buffers with capacities set as empty too. */
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    ring.neighbors_capacity = ring.faces_capacity = ring.fans_capacity = 100;
    CHECK_OK(mt_vert_ring(m, 1, &ring));
    CHECK_EQ(ring.num_neighbors, 5);
    hand_mesh_free(m);
}

static void test_query_face_buffers(void)
{
    mt_mesh *m = hand_tetrahedron(NULL);
    size_t count = 99;
    CHECK_OK(mt_face_verts(m, 2, NULL, 0, &count));
    CHECK_EQ(count, 3);
    for (size_t cap = 1; cap <= 3; cap++) {
        uint32_t *verts = xmalloc(cap * sizeof *verts);
        for (size_t i = 0; i < cap; i++) verts[i] = 0xdeadu;
        count = 0;
        mt_status s = mt_face_verts(m, 2, verts, cap, &count);
        CHECK_EQ(count, 3);
        if (cap < 3) {
            CHECK_STATUS(s, MT_ERR_BUFFER_TOO_SMALL);
            for (size_t i = 0; i < cap; i++) CHECK_EQ(verts[i], 0xdeadu);
        } else {
            CHECK_OK(s);
            CHECK_U32S(verts, count, 1, 2, 3);
        }
        free(verts);
    }

    for (size_t fcap = 0; fcap <= 3; fcap++)
        for (size_t ocap = 0; ocap <= 4; ocap++) {
            uint32_t *faces = fcap ? xmalloc(fcap * sizeof *faces) : NULL;
            uint32_t *offsets = ocap ? xmalloc(ocap * sizeof *offsets) : NULL;
            for (size_t i = 0; i < fcap; i++) faces[i] = 0xdeadu;
            for (size_t i = 0; i < ocap; i++) offsets[i] = 0xdeadu;
            size_t nf = 0, ne = 0;
            mt_status s = mt_face_neighbors(m, 3, faces, fcap, offsets, ocap, &nf, &ne);
            CHECK_EQ(nf, 3);
            CHECK_EQ(ne, 3);
            if (fcap == 0 && ocap == 0) {
                CHECK_OK(s);
            } else if (fcap == 3 && ocap == 4) {
                CHECK_OK(s);
                /* face 3 = (0, 3, 2): across 0-3 face 1, 3-2 face 2, 2-0 face 0 */
                CHECK_U32S(faces, 3, 1, 2, 0);
                CHECK_U32S(offsets, 4, 0, 1, 2, 3);
            } else {
                CHECK_STATUS(s, MT_ERR_BUFFER_TOO_SMALL);
                for (size_t i = 0; i < fcap; i++) CHECK_EQ(faces[i], 0xdeadu);
                for (size_t i = 0; i < ocap; i++) CHECK_EQ(offsets[i], 0xdeadu);
            }
            free(faces);
            free(offsets);
        }

    /* A face with no neighbour needs no face buffer at all. */
    hand_mesh_free(m);
    m = hand_triangle(NULL);
    uint32_t offsets[4];
    size_t nf = 9, ne = 9;
    CHECK_OK(mt_face_neighbors(m, 0, NULL, 0, offsets, 4, &nf, &ne));
    CHECK_EQ(nf, 0);
    CHECK_U32S(offsets, 4, 0, 0, 0, 0);
    CHECK_STATUS(mt_face_neighbors(m, 0, NULL, 0, offsets, 3, &nf, &ne), MT_ERR_BUFFER_TOO_SMALL);
    hand_mesh_free(m);
}

static void test_query_edge_buffers(void)
{
    mt_mesh *m = hand_fin(NULL);
    size_t count = 0;
    CHECK_OK(mt_edge_faces(m, 1, 0, NULL, 0, &count));
    CHECK_EQ(count, 3);
    for (size_t cap = 1; cap <= 3; cap++) {
        uint32_t *faces = xmalloc(cap * sizeof *faces);
        for (size_t i = 0; i < cap; i++) faces[i] = 0xdeadu;
        count = 0;
        mt_status s = mt_edge_faces(m, 1, 0, faces, cap, &count);
        CHECK_EQ(count, 3);
        if (cap < 3) {
            CHECK_STATUS(s, MT_ERR_BUFFER_TOO_SMALL);
            for (size_t i = 0; i < cap; i++) CHECK_EQ(faces[i], 0xdeadu);
        } else {
            CHECK_OK(s);
            CHECK_U32S(faces, count, 0, 1, 2);
        }
        free(faces);
    }
    hand_mesh_free(m);
}

static void test_query_loop_buffers(void)
{
    mt_mesh *m = hand_fin(NULL);
    size_t nv = 0, nl = 0;
    CHECK_OK(mt_boundary_loops(m, NULL, 0, NULL, 0, &nv, &nl));
    CHECK_EQ(nv, 7);
    CHECK_EQ(nl, 2);
    for (size_t vcap = 0; vcap <= 7; vcap++)
        for (size_t ocap = 0; ocap <= 3; ocap++) {
            uint32_t *verts = vcap ? xmalloc(vcap * sizeof *verts) : NULL;
            uint32_t *offsets = ocap ? xmalloc(ocap * sizeof *offsets) : NULL;
            for (size_t i = 0; i < vcap; i++) verts[i] = 0xdeadu;
            for (size_t i = 0; i < ocap; i++) offsets[i] = 0xdeadu;
            nv = nl = 0;
            mt_status s = mt_boundary_loops(m, verts, vcap, offsets, ocap, &nv, &nl);
            CHECK_EQ(nv, 7);
            CHECK_EQ(nl, 2);
            if (vcap == 0 && ocap == 0) {
                CHECK_OK(s);
            } else if (vcap == 7 && ocap == 3) {
                CHECK_OK(s);
                CHECK_U32S(offsets, 3, 0, 4, 7);
            } else {
                CHECK_STATUS(s, MT_ERR_BUFFER_TOO_SMALL);
                for (size_t i = 0; i < vcap; i++) CHECK_EQ(verts[i], 0xdeadu);
                for (size_t i = 0; i < ocap; i++) CHECK_EQ(offsets[i], 0xdeadu);
            }
            free(verts);
            free(offsets);
        }
    /* The bitmap is the one allocation: its failure is reported. */
    mt__test_fail_alloc_after(0);
    CHECK_STATUS(mt_boundary_loops(m, NULL, 0, NULL, 0, &nv, &nl), MT_ERR_NOMEM);
    mt__test_fail_alloc_after(-1);
    hand_mesh_free(m);
}

/* ---- queries into buffers that grow --------------------------------------- */

/* From empty on a vertex of 40 faces, reused (no new allocation) on one of
 * 2, a rejected face and a bad id passed through, a failed allocation
 * reported; the answers equal the plain queries'. */
static void test_query_growing(void)
{
    enum { RIM = 40 };
    double pos[3 * (RIM + 1)] = {0, 0, 0};
    uint32_t indices[3 * (RIM + 1)], sizes[RIM + 1];
    for (uint32_t i = 1; i <= RIM; i++) {
        pos[3 * i] = (double)(i % 7);
        pos[3 * i + 1] = (double)i;
        pos[3 * i + 2] = 1;
    }
    for (uint32_t f = 0; f < RIM; f++) {
        indices[3 * f] = 0, indices[3 * f + 1] = f + 1, indices[3 * f + 2] = (f + 1) % RIM + 1;
        sizes[f] = 3;
    }
    indices[3 * RIM] = 0, indices[3 * RIM + 1] = 1, indices[3 * RIM + 2] = 999; /* rejected */
    sizes[RIM] = 3;
    mt_face_list list = {RIM + 1, RIM + 1, 3 * (RIM + 1), pos, sizes, indices};
    mt_mesh *m = NULL;
    CHECK_OK(mt_mesh_build(&list, NULL, &m, NULL));
    if (!m) return;

    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    CHECK_OK(mt_vert_ring_growing(m, 0, &ring));
    CHECK(ring.num_neighbors == RIM && ring.num_faces == RIM && ring.num_fans == 1);
    uint32_t neighbors[RIM], faces[RIM];
    mt_fan fans[1];
    mt_ring plain = {neighbors, RIM, faces, RIM, fans, 1, 0, 0, 0};
    CHECK_OK(mt_vert_ring(m, 0, &plain));
    CHECK(ring.num_neighbors == RIM && memcmp(ring.neighbors, neighbors, sizeof neighbors) == 0 &&
          memcmp(ring.faces, faces, sizeof faces) == 0);
    const uint32_t *kept = ring.neighbors;
    CHECK_OK(mt_vert_ring_growing(m, 1, &ring));
    CHECK(ring.num_neighbors == 3 && ring.num_faces == 2);
    CHECK(ring.neighbors == kept && ring.neighbors_capacity == RIM);
    CHECK_STATUS(mt_vert_ring_growing(m, RIM + 1, &ring), MT_ERR_OUT_OF_RANGE);
    mt_ring_free(&ring);
    CHECK(ring.neighbors == NULL && ring.neighbors_capacity == 0 && ring.fans == NULL);

    /* face 0 = (0 1 2): across 0 -> 1 face RIM - 1, 1 -> 2 on the rim, 2 -> 0 face 1 */
    mt_face_adjacency adj;
    memset(&adj, 0, sizeof adj);
    CHECK_OK(mt_face_neighbors_growing(m, 0, &adj));
    CHECK_EQ(adj.num_edges, 3);
    CHECK_U32S(adj.offsets, adj.num_edges + 1, 0, 1, 1, 2);
    CHECK_U32S(adj.faces, adj.num_faces, RIM - 1, 1);
    CHECK_STATUS(mt_face_neighbors_growing(m, RIM, &adj), MT_ERR_NOT_FOUND);
    mt_face_adjacency_free(&adj);
    CHECK(adj.faces == NULL && adj.offsets == NULL);

    mt_face_corners corners;
    memset(&corners, 0, sizeof corners);
    CHECK_OK(mt_face_verts_growing(m, 5, &corners));
    CHECK_U32S(corners.verts, corners.count, 0, 6, 7);
    CHECK_STATUS(mt_face_verts_growing(m, RIM, &corners), MT_ERR_NOT_FOUND);
    mt_face_corners_free(&corners);

    mt__test_fail_alloc_after(0);
    CHECK_STATUS(mt_vert_ring_growing(m, 0, &ring), MT_ERR_NOMEM);
    CHECK_STATUS(mt_face_verts_growing(m, 5, &corners), MT_ERR_NOMEM);
    mt__test_fail_alloc_after(-1);
    mt_ring_free(&ring);
    mt_face_corners_free(&corners);
    mt_mesh_destroy(m);
}

/* ---- bad arguments ------------------------------------------------------ */

static void test_query_bad_arguments(void)
{
    mt_mesh *m = hand_triangle(NULL);
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    uint32_t value = 0, buf[8];
    size_t count = 0, count2 = 0;

    CHECK_STATUS(mt_vert_ring(NULL, 0, &ring), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_vert_ring(m, 0, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_vert_ring(m, 3, &ring), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_vert_ring(m, N, &ring), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_vert_valence(NULL, 0, &value), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_vert_valence(m, 0, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_vert_valence(m, 3, &value), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_face_verts(NULL, 0, buf, 8, &count), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_verts(m, 0, buf, 8, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_verts(m, 1, buf, 8, &count), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_face_neighbors(NULL, 0, buf, 8, buf, 8, &count, &count2), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_neighbors(m, 0, buf, 8, buf, 8, NULL, &count2), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_neighbors(m, 0, buf, 8, buf, 8, &count, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_neighbors(m, 5, buf, 8, buf, 8, &count, &count2), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_edge_faces(NULL, 0, 1, buf, 8, &count), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_edge_faces(m, 0, 1, buf, 8, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_edge_faces(m, 0, 3, buf, 8, &count), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_edge_faces(m, N, 0, buf, 8, &count), MT_ERR_OUT_OF_RANGE);
    CHECK_STATUS(mt_boundary_loops(NULL, buf, 8, buf, 8, &count, &count2), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_boundary_loops(m, buf, 8, buf, 8, NULL, &count2), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_boundary_loops(m, buf, 8, buf, 8, &count, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_component(NULL, 0, &value), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_component(m, 0, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_face_component(m, 1, &value), MT_ERR_OUT_OF_RANGE);
    hand_mesh_free(m);
}

/* A rejected face record and an isolated vertex: the triangle plus face 1
 * (rejected) and vertex 3 (isolated). */
static void test_query_rejected_and_isolated(void)
{
    mt_mesh *m = hand_triangle_isolated();
    CHECK_OK(mt_mesh_validate(m, NULL));

    uint32_t buf[8], value = 5;
    size_t count = 0, count2 = 0;
    CHECK_STATUS(mt_face_verts(m, 1, buf, 8, &count), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_face_neighbors(m, 1, buf, 8, buf, 8, &count, &count2), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_face_component(m, 1, &value), MT_ERR_NOT_FOUND);

    mt_ring ring;
    CHECK_OK(ring_get(m, 3, &ring));
    CHECK_EQ(ring.num_neighbors, 0);
    CHECK_EQ(ring.num_faces, 0);
    CHECK_EQ(ring.num_fans, 0);
    ring_free(&ring);
    CHECK_OK(mt_vert_valence(m, 3, &value));
    CHECK_EQ(value, 0);
    CHECK_STATUS(mt_edge_faces(m, 3, 0, buf, 8, &count), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_edge_faces(m, 0, 3, buf, 8, &count), MT_ERR_NOT_FOUND);
    hand_mesh_free(m);
}

/* ---- corrupted meshes: an error, never a bad read or an endless walk ---- */

static void test_query_corrupt_rotation(void)
{
    /* next(3) = 3: the rotation around vertex 1 falls into a cycle that
     * never comes back to its start. */
    mt_mesh *m = hand_triangle(NULL);
    m->he_next[3] = 3;
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    uint32_t value, buf[8], offsets[8];
    size_t count, count2;
    CHECK_STATUS(mt_vert_ring(m, 1, &ring), MT_ERR_CORRUPT);
    CHECK_STATUS(mt_vert_valence(m, 1, &value), MT_ERR_CORRUPT);
    CHECK_STATUS(mt_boundary_loops(m, buf, 8, offsets, 8, &count, &count2), MT_ERR_CORRUPT);
    hand_mesh_free(m);
}

static void test_query_corrupt_indices(void)
{
    mt_ring ring;
    memset(&ring, 0, sizeof ring);
    uint32_t value, buf[8], offsets[8];
    size_t count, count2;

    mt_mesh *m = hand_triangle(NULL);
    m->he_next[0] = 99;
    CHECK_STATUS(mt_face_verts(m, 0, buf, 8, &count), MT_ERR_CORRUPT);
    CHECK_STATUS(mt_face_neighbors(m, 0, buf, 8, offsets, 8, &count, &count2), MT_ERR_CORRUPT);
    CHECK_STATUS(mt_vert_ring(m, 1, &ring), MT_ERR_CORRUPT); /* r(1) = next(0) */
    hand_mesh_free(m);

    m = hand_triangle(NULL);
    m->he_head[1] = 99;
    ring.neighbors = buf;
    ring.neighbors_capacity = 8;
    ring.faces = offsets;
    ring.faces_capacity = 8;
    mt_fan fans[2];
    ring.fans = fans;
    ring.fans_capacity = 2;
    CHECK_STATUS(mt_vert_ring(m, 1, &ring), MT_ERR_CORRUPT);           /* head of h1 */
    CHECK_STATUS(mt_face_verts(m, 0, buf, 8, &count), MT_ERR_CORRUPT); /* tail of h0 */
    CHECK_OK(mt_edge_faces(m, 1, 2, buf, 8, &count));                  /* found past h1 */
    hand_mesh_free(m);

    m = hand_triangle(NULL);
    m->vert_he[2] = 6;
    CHECK_STATUS(mt_vert_ring(m, 2, &ring), MT_ERR_CORRUPT);
    CHECK_STATUS(mt_vert_valence(m, 2, &value), MT_ERR_CORRUPT);
    CHECK_STATUS(mt_edge_faces(m, 2, 0, buf, 8, &count), MT_ERR_CORRUPT);
    hand_mesh_free(m);

    m = hand_triangle(NULL);
    m->face_he[0] = 6;
    CHECK_STATUS(mt_face_verts(m, 0, buf, 8, &count), MT_ERR_CORRUPT);
    CHECK_STATUS(mt_face_component(m, 0, &value), MT_ERR_CORRUPT);
    hand_mesh_free(m);

    /* An odd half-edge count: the last half-edge has no twin. */
    m = hand_triangle(NULL);
    m->num_half_edges = 5;
    CHECK_STATUS(mt_face_verts(m, 0, buf, 8, &count), MT_ERR_CORRUPT);
    CHECK_STATUS(mt_boundary_loops(m, buf, 8, offsets, 8, &count, &count2), MT_ERR_CORRUPT);
    hand_mesh_free(m);

    /* A boundary ring running into a face. */
    m = hand_triangle(NULL);
    m->he_next[3] = 0;
    CHECK_STATUS(mt_boundary_loops(m, buf, 8, offsets, 8, &count, &count2), MT_ERR_CORRUPT);
    hand_mesh_free(m);

    /* A copy table entry that is no copy is skipped; a bundle id out of
     * range is corruption. */
    m = hand_fin(NULL);
    m->copies_sorted[0] = 40;
    CHECK_OK(mt_vert_valence(m, 0, &value));
    CHECK_EQ(value, 3); /* the fan of copy 5 is not found */
    hand_mesh_free(m);
    m = hand_fin(NULL);
    m->bundled_bundle[0] = 7;
    CHECK_STATUS(mt_face_neighbors(m, 0, buf, 8, offsets, 8, &count, &count2), MT_ERR_CORRUPT);
    CHECK_STATUS(mt_vert_valence(m, 1, &value), MT_ERR_CORRUPT);
    CHECK_STATUS(mt_edge_faces(m, 0, 1, buf, 8, &count), MT_ERR_CORRUPT);
    hand_mesh_free(m);
}

/* ---- built meshes against the brute-force reference -------------------- */

typedef struct probe {
    const char *what;
    const mt_face_list *list;
    const mt_oracle *oracle;
    const mt_mesh *mesh;
} probe;

#define PROBE_FAIL(p, ...) probe_fail((p), __LINE__, __VA_ARGS__)

static void probe_fail(const probe *p, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static void probe_fail(const probe *p, int line, const char *fmt, ...)
{
    char text[400];
    va_list args;
    va_start(args, fmt);
    vsnprintf(text, sizeof text, fmt, args);
    va_end(args);
    mt_test_fail(__FILE__, line, "%s: %s", p->what, text);
}

static const uint32_t *face_at(const probe *p, uint32_t f)
{
    return p->list->face_indices + p->oracle->face_offset[f];
}

/* Vertex before and after v in face f (MT_NONE when f lacks v). */
static void face_around(const probe *p, uint32_t f, uint32_t v, uint32_t *before, uint32_t *after)
{
    const uint32_t n = p->list->face_sizes[f];
    const uint32_t *idx = face_at(p, f);
    *before = *after = MT_NONE;
    for (uint32_t i = 0; i < n; i++)
        if (idx[i] == v) {
            *before = idx[(i + n - 1) % n];
            *after = idx[(i + 1) % n];
        }
}

static bool same_set(uint32_t *got, size_t n, const uint32_t *want, size_t want_n)
{
    n = sort_unique(got, n);
    if (n != want_n) return false;
    for (size_t i = 0; i < n; i++)
        if (got[i] != want[i]) return false;
    return true;
}

static void probe_vertex(const probe *p, uint32_t v, bool oriented)
{
    const mt_oracle *o = p->oracle;
    mt_ring ring;
    mt_status s = ring_get(p->mesh, v, &ring);
    if (s != MT_OK) {
        PROBE_FAIL(p, "ring of %u: %s", v, mt_strerror(s));
        ring_free(&ring);
        return;
    }
    /* Fans tile the buffers; each face lies between the two neighbours
     * next to v in it, after v first when the mesh is oriented. */
    size_t nb = 0, nf = 0;
    for (size_t k = 0; k < ring.num_fans; k++) {
        const mt_fan *fan = &ring.fans[k];
        if (fan->neighbor_begin != nb || fan->face_begin != nf || fan->face_count == 0 ||
            fan->neighbor_count != fan->face_count + (fan->boundary ? 1u : 0u)) {
            PROBE_FAIL(p, "vertex %u: fan %zu has bad ranges", v, k);
            break;
        }
        for (uint32_t i = 0; i < fan->face_count; i++) {
            uint32_t f = ring.faces[fan->face_begin + i], before, after;
            uint32_t x = ring.neighbors[fan->neighbor_begin + i];
            uint32_t y = ring.neighbors[fan->neighbor_begin + (i + 1) % fan->neighbor_count];
            face_around(p, f, v, &before, &after);
            bool ok = oriented ? (x == after && y == before)
                               : ((x == after && y == before) || (x == before && y == after));
            if (!ok)
                PROBE_FAIL(p, "vertex %u: fan %zu face %u lies between %u and %u, not %u, %u", v, k,
                           f, before, after, x, y);
        }
        /* An open fan starts and ends on edges that have a boundary side:
         * in a manifold, consistently oriented mesh, edges used once (a
         * seam of flipped faces is a boundary of the half-edge structure). */
        if (fan->boundary && o->report.manifold && o->report.consistently_oriented) {
            uint32_t first = ring.neighbors[fan->neighbor_begin];
            uint32_t last = ring.neighbors[fan->neighbor_begin + fan->neighbor_count - 1];
            const mt_oracle_edge *e0 = mt_oracle_find_edge(o, v, first);
            const mt_oracle_edge *e1 = mt_oracle_find_edge(o, v, last);
            if (!e0 || !e1 || e0->uses != 1 || e1->uses != 1)
                PROBE_FAIL(p, "vertex %u: open fan %zu does not end on boundary edges", v, k);
        }
        nb += fan->neighbor_count;
        nf += fan->face_count;
    }
    if (nb != ring.num_neighbors || nf != ring.num_faces)
        PROBE_FAIL(p, "vertex %u: fans cover %zu/%zu neighbours, %zu/%zu faces", v, nb,
                   ring.num_neighbors, nf, ring.num_faces);

    /* The sets: every incident face exactly once, the neighbour set. */
    const size_t fb = o->vert_face_offsets[v], fe = o->vert_face_offsets[v + 1];
    const size_t nbb = o->vert_nb_offsets[v], nbe = o->vert_nb_offsets[v + 1];
    size_t faces_before = ring.num_faces;
    if (sort_unique(ring.faces, ring.num_faces) != faces_before ||
        !same_set(ring.faces, faces_before, o->vert_faces + fb, fe - fb))
        PROBE_FAIL(p, "vertex %u: ring faces differ from the reference", v);
    if (!same_set(ring.neighbors, ring.num_neighbors, o->vert_nb + nbb, nbe - nbb))
        PROBE_FAIL(p, "vertex %u: ring neighbours differ from the reference", v);
    uint32_t valence = MT_NONE;
    CHECK_OK(mt_vert_valence(p->mesh, v, &valence));
    if (valence != nbe - nbb)
        PROBE_FAIL(p, "vertex %u: valence %u, reference %zu", v, valence, nbe - nbb);
    ring_free(&ring);
}

static void probe_face(const probe *p, uint32_t f)
{
    const mt_oracle *o = p->oracle;
    size_t count = 0;
    if (!o->face_valid[f]) {
        CHECK_STATUS(mt_face_verts(p->mesh, f, NULL, 0, &count), MT_ERR_NOT_FOUND);
        return;
    }
    const uint32_t n = p->list->face_sizes[f];
    const uint32_t *idx = face_at(p, f);
    uint32_t *verts = xmalloc(n * sizeof *verts);
    CHECK_OK(mt_face_verts(p->mesh, f, verts, n, &count));
    if (count != n || memcmp(verts, idx, n * sizeof *verts) != 0)
        PROBE_FAIL(p, "face %u: vertices differ from the record", f);
    free(verts);

    size_t nf = 0, ne = 0;
    CHECK_OK(mt_face_neighbors(p->mesh, f, NULL, 0, NULL, 0, &nf, &ne));
    uint32_t *across = xmalloc(nf * sizeof *across), *offsets = xmalloc((ne + 1) * sizeof *offsets);
    CHECK_OK(mt_face_neighbors(p->mesh, f, across, nf, offsets, ne + 1, &nf, &ne));
    if (ne != n || offsets[0] != 0 || offsets[ne] != nf)
        PROBE_FAIL(p, "face %u: %zu sides, offsets %u..%u of %zu", f, ne, offsets[0], offsets[ne],
                   nf);
    for (uint32_t i = 0; i < n && ne == n; i++) {
        const mt_oracle_edge *e = mt_oracle_find_edge(o, idx[i], idx[(i + 1) % n]);
        uint32_t want[64], nwant = 0;
        for (uint32_t k = 0; e && k < e->uses && nwant < 64; k++)
            if (o->edge_faces[e->face_begin + k] != f)
                want[nwant++] = o->edge_faces[e->face_begin + k];
        uint32_t got[64];
        size_t ngot = offsets[i + 1] - offsets[i];
        if (ngot > 64) ngot = 64;
        memcpy(got, across + offsets[i], ngot * sizeof *got);
        qsort(got, ngot, sizeof *got, compare_u32);
        if (ngot != nwant || memcmp(got, want, ngot * sizeof *got) != 0)
            PROBE_FAIL(p, "face %u side %u: %zu faces across, reference %u", f, i, ngot, nwant);

        /* The faces on this side, ascending. */
        uint32_t on_edge[64];
        size_t ncount = 0;
        mt_status s = mt_edge_faces(p->mesh, idx[(i + 1) % n], idx[i], on_edge, 64, &ncount);
        if (s != MT_OK || !e || ncount != e->uses ||
            memcmp(on_edge, o->edge_faces + e->face_begin, ncount * sizeof *on_edge) != 0)
            PROBE_FAIL(p, "face %u side %u: mt_edge_faces differs from the reference", f, i);
    }
    /* All sides together: the reference adjacency set. */
    const size_t ab = o->face_adj_offsets[f], ae = o->face_adj_offsets[f + 1];
    if (!same_set(across, nf, o->face_adj + ab, ae - ab))
        PROBE_FAIL(p, "face %u: neighbours differ from the reference", f);
    free(across);
    free(offsets);

    uint32_t component = MT_NONE;
    CHECK_OK(mt_face_component(p->mesh, f, &component));
    if (component != o->face_component[f])
        PROBE_FAIL(p, "face %u: component %u, reference %u", f, component, o->face_component[f]);
}

static void probe_loops(const probe *p)
{
    const mt_oracle *o = p->oracle;
    size_t nv = 0, nl = 0;
    CHECK_OK(mt_boundary_loops(p->mesh, NULL, 0, NULL, 0, &nv, &nl));
    uint32_t *verts = xmalloc(nv * sizeof *verts), *offsets = xmalloc((nl + 1) * sizeof *offsets);
    CHECK_OK(mt_boundary_loops(p->mesh, verts, nv, offsets, nl + 1, &nv, &nl));
    const bool clean = o->report.manifold && o->report.consistently_oriented;
    /* In a clean mesh each boundary edge is one loop step, run the way of
     * its face (faces on the left). */
    if (clean && nv != o->report.boundary_edges)
        PROBE_FAIL(p, "loops have %zu steps, reference %llu boundary edges", nv,
                   (unsigned long long)o->report.boundary_edges);
    if (clean && !o->report.boundary_loops_ambiguous && nl != o->report.boundary_loops)
        PROBE_FAIL(p, "%zu loops, reference %u", nl, o->report.boundary_loops);
    for (size_t l = 0; l < nl; l++) {
        uint32_t begin = offsets[l], end = offsets[l + 1];
        if (end <= begin || end > nv) {
            PROBE_FAIL(p, "loop %zu has bad offsets", l);
            break;
        }
        for (uint32_t i = begin; i < end; i++) {
            uint32_t a = verts[i], b = verts[i + 1 < end ? i + 1 : begin];
            const mt_oracle_edge *e = mt_oracle_find_edge(o, a, b);
            if (!e) {
                PROBE_FAIL(p, "loop %zu: %u-%u is not an edge", l, a, b);
                continue;
            }
            if (!clean) continue;
            bool forward_side = a < b; /* the face side a -> b is (min, max) when a < b */
            if (e->uses != 1 || (e->forward == 1) != forward_side)
                PROBE_FAIL(p, "loop %zu: step %u->%u is not a boundary side of its face", l, a, b);
        }
    }
    free(verts);
    free(offsets);
}

static void probe_mesh(const char *what, mt_face_list *list)
{
    mt_oracle oracle;
    if (!mt_oracle_compute(list, &oracle)) {
        mt_test_fail(__FILE__, __LINE__, "%s: reference failed", what);
        return;
    }
    mt_mesh *mesh = NULL;
    mt_diag d;
    if (mt_mesh_build(list, NULL, &mesh, &d) != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: build failed: %s", what, d.message);
        mt_oracle_free(&oracle);
        return;
    }
    if (mt_mesh_validate(mesh, &d) != MT_OK)
        mt_test_fail(__FILE__, __LINE__, "%s: invalid mesh: %s", what, d.message);
    probe p = {what, list, &oracle, mesh};
    const bool oriented = oracle.report.consistently_oriented;
    for (uint32_t v = 0; v < list->num_verts; v++) probe_vertex(&p, v, oriented);
    for (uint32_t f = 0; f < list->num_faces; f++) probe_face(&p, f);
    probe_loops(&p);
    mt_mesh_destroy(mesh);
    mt_oracle_free(&oracle);
}

/* A mesh as generated and with ids and face order shuffled. */
static void probe_both(const char *what, mt_face_list *list)
{
    probe_mesh(what, list);
    if (mt_face_list_permute(list, 0x5eed, NULL) == MT_OK) probe_mesh(what, list);
    mt_face_list_free(list);
}

static void test_query_generated_closed(void)
{
    mt_face_list list;
    const mt_platonic solids[] = {MT_TETRAHEDRON, MT_CUBE, MT_OCTAHEDRON, MT_DODECAHEDRON,
                                  MT_ICOSAHEDRON};
    for (size_t i = 0; i < sizeof solids / sizeof solids[0]; i++)
        if (mt_gen_platonic(solids[i], &list) == MT_OK) probe_both("platonic", &list);
    CHECK_OK(mt_gen_torus(9, 5, &list));
    probe_both("torus", &list);
    CHECK_OK(mt_gen_icosphere(2, &list));
    probe_both("icosphere", &list);
    CHECK_OK(mt_gen_double_torus(5, &list));
    probe_both("double torus", &list);
}

static void test_query_generated_open(void)
{
    mt_face_list list;
    CHECK_OK(mt_gen_rectangle(3.0, 2.0, &list));
    probe_both("rectangle", &list);
    CHECK_OK(mt_gen_grid(6, 4, true, &list));
    probe_both("triangle grid", &list);
    CHECK_OK(mt_gen_grid(5, 3, false, &list));
    probe_both("quad grid", &list);
    CHECK_OK(mt_gen_grid(1, 1, false, &list));
    probe_both("single quad", &list);
    CHECK_OK(mt_gen_moebius(7, &list));
    probe_both("moebius strip", &list);
}

static void test_query_generated_defects(void)
{
    mt_face_list list;
    CHECK_OK(mt_gen_bowtie(&list));
    probe_both("bowtie", &list);
    CHECK_OK(mt_gen_fin(&list));
    probe_both("fin", &list);

    /* Everything at once: a fin, a bowtie, a flipped face, a duplicate, a
     * closed two-face pocket, rejected records and an isolated vertex. */
    static const uint32_t sizes[] = {3, 3, 3, 3, 3, 3, 3, 3, 2, 3, 4, 3, 3, 3, 3};
    static const uint32_t idx[] = {0, 1,  2,  1, 0,  3,  0,  1,  4,  0, 5, 6,  2, 1, 7,
                                   0, 1,  2,  8, 9,  10, 8,  10, 9,  3, 4, 5,  5, 6, 6,
                                   5, 12, 11, 0, 99, 1,  13, 14, 15, 1, 0, 16, 0, 1, 17};
    if (mt_face_list_alloc(&list, 19, 15, sizeof idx / sizeof idx[0], NULL) == MT_OK) {
        memcpy(list.face_sizes, sizes, sizeof sizes);
        memcpy(list.face_indices, idx, sizeof idx);
        probe_both("messy", &list);
    }
    /* Four faces on one edge, two each way: two consistent pairs. */
    static const uint32_t sizes4[] = {3, 3, 3, 3};
    static const uint32_t idx4[] = {0, 1, 2, 1, 0, 3, 0, 1, 4, 1, 0, 5};
    if (mt_face_list_alloc(&list, 6, 4, 12, NULL) == MT_OK) {
        memcpy(list.face_sizes, sizes4, sizeof sizes4);
        memcpy(list.face_indices, idx4, sizeof idx4);
        probe_both("four on one edge", &list);

        /* Closed pieces meeting at a vertex (two closed fans) and at an edge
         * (four faces on 0-1, two each way). */
        static const uint32_t idx_v[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2,
                                         0, 5, 4, 0, 4, 6, 4, 5, 6, 0, 6, 5};
        static const uint32_t idx_e[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2,
                                         0, 7, 1, 0, 1, 8, 1, 7, 8, 0, 8, 7};
        const uint32_t *shapes[] = {idx_v, idx_e};
        const char *names[] = {"tetrahedra sharing a vertex", "tetrahedra sharing an edge"};
        for (int k = 0; k < 2; k++) {
            if (mt_face_list_alloc(&list, 9, 8, 24, NULL) != MT_OK) continue;
            for (uint32_t f = 0; f < 8; f++) list.face_sizes[f] = 3;
            memcpy(list.face_indices, shapes[k], 24 * sizeof(uint32_t));
            probe_both(names[k], &list);
        }
    }
}

/* Cyclic rotation test: is `got` the sequence `want` started elsewhere? */
static bool is_rotation(const uint32_t *got, const uint32_t *want, size_t n)
{
    for (size_t shift = 0; shift < n; shift++) {
        size_t i = 0;
        while (i < n && got[i] == want[(i + shift) % n]) i++;
        if (i == n) return true;
    }
    return n == 0;
}

/* The outer boundary of an nx by ny grid: 2(nx+ny) vertices, counter-
 * clockwise seen from +z (faces on the left). */
static void test_query_grid_boundary_loop(void)
{
    const uint32_t sizes[][2] = {{1, 1}, {4, 3}, {7, 2}};
    for (size_t t = 0; t < 3; t++)
        for (int triangles = 0; triangles < 2; triangles++) {
            const uint32_t nx = sizes[t][0], ny = sizes[t][1];
            mt_face_list list;
            CHECK_OK(mt_gen_grid(nx, ny, triangles, &list));
            mt_mesh *mesh = NULL;
            CHECK_OK(mt_mesh_build(&list, NULL, &mesh, NULL));
            CHECK_OK(mt_mesh_validate(mesh, NULL));
            uint32_t want[64];
            size_t n = 0;
            for (uint32_t i = 0; i < nx; i++) want[n++] = i;                 /* bottom */
            for (uint32_t j = 0; j < ny; j++) want[n++] = j * (nx + 1) + nx; /* right */
            for (uint32_t i = nx; i > 0; i--) want[n++] = ny * (nx + 1) + i; /* top */
            for (uint32_t j = ny; j > 0; j--) want[n++] = j * (nx + 1);      /* left */
            CHECK_EQ(n, 2 * (nx + ny));
            loops l;
            if (mesh) {
                CHECK_OK(loops_get(mesh, &l));
                CHECK_EQ(l.num_loops, 1);
                CHECK_EQ(l.num_verts, n);
                if (l.num_verts == n && !is_rotation(l.verts, want, n))
                    mt_test_fail(__FILE__, __LINE__, "grid %ux%u: loop not in order", nx, ny);
            }
            mt_mesh_destroy(mesh);
            mt_face_list_free(&list);
        }
}

/* A hole is walked the other way: faces on the left means clockwise. */
static void test_query_hole_loop(void)
{
    mt_face_list list;
    CHECK_OK(mt_gen_grid(3, 3, false, &list));
    /* Drop the middle cell (face 4) by degenerating it: 5 5 6 10 is rejected. */
    list.face_indices[4 * 4 + 0] = 5;
    list.face_indices[4 * 4 + 1] = 5;
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_mesh_build(&list, NULL, &mesh, NULL));
    loops l;
    if (mesh) {
        CHECK_OK(mt_mesh_validate(mesh, NULL));
        CHECK_OK(loops_get(mesh, &l));
        CHECK_EQ(l.num_loops, 2);
        CHECK_EQ(l.num_verts, 16);
        const uint32_t outer[] = {0, 1, 2, 3, 7, 11, 15, 14, 13, 12, 8, 4};
        const uint32_t hole[] = {5, 9, 10, 6};
        bool found_outer = false, found_hole = false;
        for (size_t k = 0; k < l.num_loops && l.num_loops == 2; k++) {
            size_t len = l.offsets[k + 1] - l.offsets[k];
            const uint32_t *loop = l.verts + l.offsets[k];
            if (len == 12 && is_rotation(loop, outer, 12)) found_outer = true;
            if (len == 4 && is_rotation(loop, hole, 4)) found_hole = true;
        }
        CHECK(found_outer);
        CHECK(found_hole);
        size_t count = 0;
        CHECK_STATUS(mt_face_verts(mesh, 4, NULL, 0, &count), MT_ERR_NOT_FOUND);
    }
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
}

static const mt_test_case cases[] = {
    {"query_triangle", test_query_triangle},
    {"query_rectangle", test_query_rectangle},
    {"query_tetrahedron", test_query_tetrahedron},
    {"query_bowtie", test_query_bowtie},
    {"query_fin", test_query_fin},
    {"query_mesh_access", test_query_mesh_access},
    {"query_vert_copies_lookup", test_query_vert_copies_lookup},
    {"query_ring_buffers", test_query_ring_buffers},
    {"query_face_buffers", test_query_face_buffers},
    {"query_edge_buffers", test_query_edge_buffers},
    {"query_loop_buffers", test_query_loop_buffers},
    {"query_bad_arguments", test_query_bad_arguments},
    {"query_rejected_and_isolated", test_query_rejected_and_isolated},
    {"query_corrupt_rotation", test_query_corrupt_rotation},
    {"query_corrupt_indices", test_query_corrupt_indices},
    {"query_generated_closed", test_query_generated_closed},
    {"query_generated_open", test_query_generated_open},
    {"query_generated_defects", test_query_generated_defects},
    {"query_grid_boundary_loop", test_query_grid_boundary_loop},
    {"query_hole_loop", test_query_hole_loop},
    {"query_growing", test_query_growing},
};

const mt_test_table mt_tests_query = {cases, sizeof cases / sizeof cases[0]};
