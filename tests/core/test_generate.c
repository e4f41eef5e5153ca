/* Tests of the generators (generate.h) and mt_face_list_permute, on the face
 * lists alone: counts, ids, orientation, closedness, boundary and Euler
 * characteristic are recomputed here by brute force (sorted directed edges,
 * union-find) and positions are checked against each shape's geometry.
 * The checks that need mt_mesh_build live in test_generate_build.c. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "meshtopo/generate.h"

/* ---- brute-force topology of a face list ---- */

typedef struct topo {
    bool indices_in_range;
    uint32_t degenerate_faces;     /* fewer than 3 entries or a repeated vertex */
    uint32_t unused_verts;         /* in no face */
    uint64_t edges;                /* distinct undirected edges */
    uint64_t boundary_edges;       /* used by one face */
    uint64_t nonmanifold_edges;    /* used by more than two faces */
    uint64_t same_direction_edges; /* used by two faces running the same way */
    uint64_t duplicate_directed;   /* directed sides used by two or more faces */
    uint32_t boundary_loops;       /* components of the boundary-edge graph */
    bool boundary_simple;          /* every vertex has boundary degree 0 or 2 */
    uint32_t components;           /* classes of faces sharing an edge */
    bool orientable;               /* some choice of face flips is consistent */
    int64_t euler;                 /* V - E + F */
} topo;

typedef struct side {
    uint64_t key; /* min << 32 | max */
    uint32_t face;
    uint32_t forward; /* 1 if the face runs min -> max */
} side;

static int side_cmp(const void *x, const void *y)
{
    const side *a = x, *b = y;
    if (a->key != b->key) return a->key < b->key ? -1 : 1;
    if (a->forward != b->forward) return a->forward < b->forward ? -1 : 1;
    return a->face < b->face ? -1 : a->face > b->face;
}

/* Union-find with parity (for orientability): parity[x] is x's flip relative
 * to its parent. */
static uint32_t uf_find(uint32_t *parent, uint8_t *parity, uint32_t x, uint8_t *out_parity)
{
    uint8_t p = 0;
    while (parent[x] != x) {
        p ^= parity ? parity[x] : 0;
        x = parent[x];
    }
    if (out_parity) *out_parity = p;
    return x;
}

/* Joins a and b; with parity, requires flip(a) ^ flip(b) == rel and returns
 * false when that contradicts earlier constraints. */
static bool uf_join(uint32_t *parent, uint8_t *parity, uint32_t a, uint32_t b, uint8_t rel)
{
    uint8_t pa = 0, pb = 0;
    uint32_t ra = uf_find(parent, parity, a, &pa), rb = uf_find(parent, parity, b, &pb);
    if (ra == rb) return !parity || (uint8_t)(pa ^ pb) == rel;
    parent[ra] = rb;
    if (parity) parity[ra] = (uint8_t)(pa ^ pb ^ rel);
    return true;
}

static topo topo_compute(const mt_face_list *l)
{
    topo t;
    memset(&t, 0, sizeof t);
    t.indices_in_range = true;
    t.boundary_simple = true;
    t.orientable = true;
    side *sides = calloc(l->num_indices + 1, sizeof *sides);
    uint32_t *vert_uses = calloc((size_t)l->num_verts + 1, sizeof *vert_uses);
    uint32_t *bdeg = calloc((size_t)l->num_verts + 1, sizeof *bdeg);
    uint32_t *vparent = calloc((size_t)l->num_verts + 1, sizeof *vparent);
    uint32_t *fparent = calloc((size_t)l->num_faces + 1, sizeof *fparent);
    uint32_t *fcomp = calloc((size_t)l->num_faces + 1, sizeof *fcomp);
    uint8_t *fparity = calloc((size_t)l->num_faces + 1, 1);
    if (!sides || !vert_uses || !bdeg || !vparent || !fparent || !fcomp || !fparity) {
        CHECK(!"test out of memory");
        goto done;
    }
    for (uint32_t v = 0; v < l->num_verts; v++) vparent[v] = v;
    for (uint32_t f = 0; f < l->num_faces; f++) fparent[f] = fcomp[f] = f;

    size_t n = 0;
    uint64_t at = 0;
    for (uint32_t f = 0; f < l->num_faces; f++) {
        uint32_t size = l->face_sizes[f];
        const uint32_t *fi = l->face_indices + at;
        at += size;
        bool bad = size < 3;
        for (uint32_t k = 0; k < size; k++) {
            if (fi[k] >= l->num_verts) t.indices_in_range = false;
            for (uint32_t m = 0; m < k; m++) bad = bad || fi[m] == fi[k];
        }
        if (bad) t.degenerate_faces++;
        for (uint32_t k = 0; k < size; k++) {
            uint32_t a = fi[k], b = fi[(k + 1) % size];
            if (a < l->num_verts) vert_uses[a]++;
            uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
            sides[n].key = (uint64_t)lo << 32 | hi;
            sides[n].face = f;
            sides[n].forward = a < b;
            n++;
        }
    }
    if (!t.indices_in_range) goto done;
    for (uint32_t v = 0; v < l->num_verts; v++) t.unused_verts += vert_uses[v] == 0;
    qsort(sides, n, sizeof *sides, side_cmp);
    for (size_t i = 0; i < n;) {
        size_t j = i;
        uint32_t fwd = 0;
        while (j < n && sides[j].key == sides[i].key) fwd += sides[j++].forward;
        uint32_t uses = (uint32_t)(j - i);
        uint32_t a = (uint32_t)(sides[i].key >> 32), b = (uint32_t)sides[i].key;
        t.edges++;
        if (uses == 1) {
            t.boundary_edges++;
            bdeg[a]++;
            bdeg[b]++;
            uf_join(vparent, NULL, a, b, 0);
        }
        if (uses > 2) t.nonmanifold_edges++;
        if (fwd > 1 || uses - fwd > 1) t.duplicate_directed++;
        if (uses == 2 && fwd != 1) t.same_direction_edges++;
        for (size_t k = i + 1; k < j; k++) uf_join(fcomp, NULL, sides[i].face, sides[k].face, 0);
        if (uses == 2 &&
            !uf_join(fparent, fparity, sides[i].face, sides[i + 1].face, fwd == 1 ? 0 : 1))
            t.orientable = false;
        i = j;
    }
    for (uint32_t v = 0; v < l->num_verts; v++) {
        if (bdeg[v] != 0 && bdeg[v] != 2) t.boundary_simple = false;
        if (bdeg[v] != 0 && uf_find(vparent, NULL, v, NULL) == v) t.boundary_loops++;
    }
    for (uint32_t f = 0; f < l->num_faces; f++) t.components += uf_find(fcomp, NULL, f, NULL) == f;
    t.euler = (int64_t)l->num_verts - (int64_t)t.edges + (int64_t)l->num_faces;
done:
    free(sides);
    free(vert_uses);
    free(bdeg);
    free(vparent);
    free(fparent);
    free(fcomp);
    free(fparity);
    return t;
}

/* Sizes add up, every index in range, no repeated vertex in a face, every
 * vertex used. */
static void check_well_formed(const mt_face_list *l, const topo *t)
{
    CHECK_OK(mt_face_list_check(l, NULL));
    CHECK(l->positions != NULL);
    CHECK(t->indices_in_range);
    CHECK_EQ(t->degenerate_faces, 0);
    CHECK_EQ(t->unused_verts, 0);
}

/* A closed, consistently oriented, connected manifold with Euler characteristic euler. */
static void check_closed_surface(const mt_face_list *l, int64_t euler)
{
    topo t = topo_compute(l);
    check_well_formed(l, &t);
    CHECK_EQ(t.boundary_edges, 0);
    CHECK_EQ(t.nonmanifold_edges, 0);
    CHECK_EQ(t.duplicate_directed, 0);
    CHECK_EQ(t.same_direction_edges, 0);
    CHECK_EQ(t.components, 1);
    CHECK(t.orientable);
    CHECK_EQ(t.euler, euler);
    CHECK_EQ(2 * t.edges, l->num_indices); /* each edge used exactly twice */
}

/* ---- geometry ---- */

static const double *pos(const mt_face_list *l, uint32_t v)
{
    return l->positions + 3 * (size_t)v;
}

/* Newell normal (twice the vector area) and centroid of face f starting at index at. */
static void face_normal(const mt_face_list *l, uint64_t at, uint32_t size, double n[3], double c[3])
{
    n[0] = n[1] = n[2] = c[0] = c[1] = c[2] = 0;
    for (uint32_t k = 0; k < size; k++) {
        const double *p = pos(l, l->face_indices[at + k]);
        const double *q = pos(l, l->face_indices[at + (k + 1) % size]);
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
        for (int d = 0; d < 3; d++) c[d] += p[d] / size;
    }
}

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Smallest face area (|Newell normal| / 2) and, if outward, the number of
 * faces whose normal points towards the origin (counted for convex shapes
 * centred at the origin). */
static double faces_min_area(const mt_face_list *l, uint32_t *out_inward)
{
    double min_area = INFINITY;
    uint32_t inward = 0;
    uint64_t at = 0;
    for (uint32_t f = 0; f < l->num_faces; f++) {
        double n[3], c[3];
        face_normal(l, at, l->face_sizes[f], n, c);
        double area = sqrt(dot3(n, n)) / 2;
        if (area < min_area) min_area = area;
        if (dot3(n, c) <= 0) inward++;
        at += l->face_sizes[f];
    }
    if (out_inward) *out_inward = inward;
    return min_area;
}

/* Signed volume enclosed by a closed mesh: positive when faces point outwards. */
static double signed_volume(const mt_face_list *l)
{
    double vol = 0;
    uint64_t at = 0;
    for (uint32_t f = 0; f < l->num_faces; f++) {
        const double *a = pos(l, l->face_indices[at]);
        for (uint32_t k = 1; k + 1 < l->face_sizes[f]; k++) {
            const double *b = pos(l, l->face_indices[at + k]);
            const double *c = pos(l, l->face_indices[at + k + 1]);
            vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                    a[2] * (b[0] * c[1] - b[1] * c[0])) /
                   6;
        }
        at += l->face_sizes[f];
    }
    return vol;
}

static int pos_cmp(const void *x, const void *y)
{
    const double *a = x, *b = y;
    for (int d = 0; d < 3; d++)
        if (a[d] != b[d]) return a[d] < b[d] ? -1 : 1;
    return 0;
}

/* Number of vertices sharing their exact position with another one. */
static uint32_t positions_repeated(const mt_face_list *l)
{
    double *p = malloc(3 * sizeof(double) * ((size_t)l->num_verts + 1));
    if (!p) return UINT32_MAX;
    memcpy(p, l->positions, 3 * sizeof(double) * l->num_verts);
    qsort(p, l->num_verts, 3 * sizeof(double), pos_cmp);
    uint32_t repeats = 0;
    for (uint32_t v = 1; v < l->num_verts; v++) repeats += pos_cmp(p + 3 * (v - 1), p + 3 * v) == 0;
    free(p);
    return repeats;
}

static bool list_is_zeroed(const mt_face_list *l)
{
    return l->num_verts == 0 && l->num_faces == 0 && l->num_indices == 0 && !l->positions &&
           !l->face_sizes && !l->face_indices;
}

/* A list with garbage in it, to see that failing generators zero it. */
static mt_face_list list_garbage(void)
{
    mt_face_list l;
    memset(&l, 0xab, sizeof l);
    return l;
}

/* ---- Platonic solids ---- */

static void test_gen_platonic(void)
{
    static const struct {
        mt_platonic kind;
        uint32_t verts, faces, size;
    } solids[] = {
        {MT_TETRAHEDRON, 4, 4, 3},    {MT_CUBE, 8, 6, 4},          {MT_OCTAHEDRON, 6, 8, 3},
        {MT_DODECAHEDRON, 20, 12, 5}, {MT_ICOSAHEDRON, 12, 20, 3},
    };
    for (size_t s = 0; s < sizeof solids / sizeof solids[0]; s++) {
        mt_face_list l;
        CHECK_OK(mt_gen_platonic(solids[s].kind, &l));
        CHECK_EQ(l.num_verts, solids[s].verts);
        CHECK_EQ(l.num_faces, solids[s].faces);
        CHECK_EQ(l.num_indices, (uint64_t)solids[s].faces * solids[s].size);
        for (uint32_t f = 0; f < l.num_faces; f++) CHECK_EQ(l.face_sizes[f], solids[s].size);
        check_closed_surface(&l, 2);
        /* circumradius 1, all edges the same length, planar faces, pointing out */
        for (uint32_t v = 0; v < l.num_verts; v++)
            CHECK(fabs(dot3(pos(&l, v), pos(&l, v)) - 1) < 1e-12);
        double edge = -1;
        uint64_t at = 0;
        for (uint32_t f = 0; f < l.num_faces; f++) {
            double n[3], c[3];
            face_normal(&l, at, l.face_sizes[f], n, c);
            CHECK(dot3(n, c) > 0);
            for (uint32_t k = 0; k < l.face_sizes[f]; k++) {
                const double *p = pos(&l, l.face_indices[at + k]);
                const double *q = pos(&l, l.face_indices[at + (k + 1) % l.face_sizes[f]]);
                double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
                double len = sqrt(dot3(d, d));
                if (edge < 0) edge = len;
                CHECK(fabs(len - edge) < 1e-12);
                double off[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
                CHECK(fabs(dot3(off, n)) < 1e-12);
            }
            at += l.face_sizes[f];
        }
        CHECK(signed_volume(&l) > 0);
        CHECK_EQ(positions_repeated(&l), 0);
        mt_face_list_free(&l);
    }
}

static void test_gen_platonic_invalid(void)
{
    mt_face_list l = list_garbage();
    CHECK_STATUS(mt_gen_platonic((mt_platonic)5, &l), MT_ERR_INVALID_ARG);
    CHECK(list_is_zeroed(&l));
    l = list_garbage();
    CHECK_STATUS(mt_gen_platonic((mt_platonic)-1, &l), MT_ERR_INVALID_ARG);
    CHECK(list_is_zeroed(&l));
    CHECK_STATUS(mt_gen_platonic(MT_CUBE, NULL), MT_ERR_INVALID_ARG);
}

/* ---- rectangle and grid ---- */

static void test_gen_rectangle(void)
{
    mt_face_list l;
    CHECK_OK(mt_gen_rectangle(3.0, 2.0, &l));
    CHECK_EQ(l.num_verts, 4);
    CHECK_EQ(l.num_faces, 2);
    CHECK_EQ(l.num_indices, 6);
    static const double want_pos[12] = {0, 0, 0, 3, 0, 0, 3, 2, 0, 0, 2, 0};
    for (int i = 0; i < 12; i++) CHECK(l.positions[i] == want_pos[i]);
    static const uint32_t want_idx[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++) CHECK_EQ(l.face_indices[i], want_idx[i]);
    CHECK_EQ(l.face_sizes[0], 3);
    CHECK_EQ(l.face_sizes[1], 3);
    topo t = topo_compute(&l);
    check_well_formed(&l, &t);
    CHECK_EQ(t.edges, 5);
    CHECK_EQ(t.boundary_edges, 4);
    CHECK_EQ(t.boundary_loops, 1);
    CHECK_EQ(t.duplicate_directed, 0);
    CHECK_EQ(t.euler, 1);
    mt_face_list_free(&l);
}

static void test_gen_rectangle_invalid(void)
{
    const double bad[] = {0.0, -1.0, NAN, INFINITY, -INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        mt_face_list l = list_garbage();
        CHECK_STATUS(mt_gen_rectangle(bad[i], 1.0, &l), MT_ERR_INVALID_ARG);
        CHECK(list_is_zeroed(&l));
        CHECK_STATUS(mt_gen_rectangle(1.0, bad[i], &l), MT_ERR_INVALID_ARG);
        CHECK(list_is_zeroed(&l));
    }
    CHECK_STATUS(mt_gen_rectangle(1.0, 1.0, NULL), MT_ERR_INVALID_ARG);
}

/* A flat nx x ny grid: ids, positions, counts, one boundary loop, normals +z. */
static void check_grid(uint32_t nx, uint32_t ny, bool triangles)
{
    mt_face_list l;
    CHECK_OK(mt_gen_grid(nx, ny, triangles, &l));
    uint32_t cells = nx * ny, per = triangles ? 2 : 1, size = triangles ? 3 : 4;
    CHECK_EQ(l.num_verts, (nx + 1) * (ny + 1));
    CHECK_EQ(l.num_faces, per * cells);
    CHECK_EQ(l.num_indices, (uint64_t)per * cells * size);
    for (uint32_t j = 0; j <= ny; j++) {
        for (uint32_t i = 0; i <= nx; i++) {
            const double *p = pos(&l, j * (nx + 1) + i);
            CHECK(p[0] == i && p[1] == j && p[2] == 0);
        }
    }
    /* cell (i, j) is faces per*(j*nx+i) ...; triangles split along a-c */
    for (uint32_t j = 0; j < ny; j++) {
        for (uint32_t i = 0; i < nx; i++) {
            uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
            const uint32_t *fi = l.face_indices + (size_t)size * per * (j * nx + i);
            if (triangles) {
                const uint32_t want[6] = {a, b, c, a, c, d};
                for (int k = 0; k < 6; k++) CHECK_EQ(fi[k], want[k]);
            } else {
                const uint32_t want[4] = {a, b, c, d};
                for (int k = 0; k < 4; k++) CHECK_EQ(fi[k], want[k]);
            }
        }
    }
    for (uint32_t f = 0; f < l.num_faces; f++) CHECK_EQ(l.face_sizes[f], size);
    topo t = topo_compute(&l);
    check_well_formed(&l, &t);
    CHECK_EQ(t.boundary_edges, 2 * (nx + ny));
    CHECK_EQ(t.boundary_loops, 1);
    CHECK(t.boundary_simple);
    CHECK_EQ(t.nonmanifold_edges, 0);
    CHECK_EQ(t.duplicate_directed, 0);
    CHECK_EQ(t.same_direction_edges, 0);
    CHECK_EQ(t.components, 1);
    CHECK_EQ(t.euler, 1);
    uint64_t at = 0;
    for (uint32_t f = 0; f < l.num_faces; f++) {
        double n[3], c[3];
        face_normal(&l, at, l.face_sizes[f], n, c);
        CHECK(n[0] == 0 && n[1] == 0 && n[2] == (triangles ? 1.0 : 2.0));
        at += l.face_sizes[f];
    }
    mt_face_list_free(&l);
}

static void test_gen_grid(void)
{
    check_grid(1, 1, false);
    check_grid(1, 1, true);
    check_grid(3, 2, false);
    check_grid(3, 2, true);
    check_grid(1, 7, true);
    check_grid(17, 9, true);
}

static void test_gen_grid_invalid(void)
{
    mt_face_list l = list_garbage();
    CHECK_STATUS(mt_gen_grid(0, 1, true, &l), MT_ERR_INVALID_ARG);
    CHECK(list_is_zeroed(&l));
    CHECK_STATUS(mt_gen_grid(1, 0, false, &l), MT_ERR_INVALID_ARG);
    CHECK(list_is_zeroed(&l));
    CHECK_STATUS(mt_gen_grid(1, 1, false, NULL), MT_ERR_INVALID_ARG);
    /* Counts past 32 bits are refused before anything is allocated. */
    l = list_garbage();
    CHECK_STATUS(mt_gen_grid(100000, 100000, true, &l), MT_ERR_TOO_LARGE);
    CHECK(list_is_zeroed(&l));
    CHECK_STATUS(mt_gen_grid(100000, 100000, false, &l), MT_ERR_TOO_LARGE);
    CHECK_STATUS(mt_gen_grid(UINT32_MAX, 1, false, &l), MT_ERR_TOO_LARGE);
    CHECK_STATUS(mt_gen_grid(UINT32_MAX, UINT32_MAX, true, &l), MT_ERR_TOO_LARGE);
    /* 65535 x 65535 cells: vertices fit, 2 * cells triangles do not */
    CHECK_STATUS(mt_gen_grid(65535, 65535, true, &l), MT_ERR_TOO_LARGE);
    CHECK(list_is_zeroed(&l));
}

/* ---- torus ---- */

static void test_gen_torus(void)
{
    const uint32_t sizes[][2] = {{3, 3}, {3, 8}, {8, 5}, {40, 12}};
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        uint32_t nu = sizes[s][0], nv = sizes[s][1];
        mt_face_list l;
        CHECK_OK(mt_gen_torus(nu, nv, &l));
        CHECK_EQ(l.num_verts, nu * nv);
        CHECK_EQ(l.num_faces, 2 * nu * nv);
        CHECK_EQ(l.num_indices, 6 * nu * nv);
        check_closed_surface(&l, 0);
        for (uint32_t v = 0; v < l.num_verts; v++) {
            const double *p = pos(&l, v);
            double ring = sqrt(p[0] * p[0] + p[1] * p[1]) - 1.0;
            CHECK(fabs(ring * ring + p[2] * p[2] - 0.0625) < 1e-12);
        }
        CHECK(faces_min_area(&l, NULL) > 1e-6);
        CHECK(signed_volume(&l) > 0);
        CHECK_EQ(positions_repeated(&l), 0);
        mt_face_list_free(&l);
    }
}

static void test_gen_torus_invalid(void)
{
    mt_face_list l = list_garbage();
    CHECK_STATUS(mt_gen_torus(2, 3, &l), MT_ERR_INVALID_ARG);
    CHECK(list_is_zeroed(&l));
    CHECK_STATUS(mt_gen_torus(3, 2, &l), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_gen_torus(0, 0, &l), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_gen_torus(3, 3, NULL), MT_ERR_INVALID_ARG);
    l = list_garbage();
    CHECK_STATUS(mt_gen_torus(65536, 65536, &l), MT_ERR_TOO_LARGE);
    CHECK(list_is_zeroed(&l));
    CHECK_STATUS(mt_gen_torus(UINT32_MAX, UINT32_MAX, &l), MT_ERR_TOO_LARGE);
    CHECK_STATUS(mt_gen_torus(1u << 31, 3, &l), MT_ERR_TOO_LARGE);
}

/* ---- icosphere ---- */

static void test_gen_icosphere(void)
{
    for (uint32_t level = 0; level <= 5; level++) {
        mt_face_list l;
        CHECK_OK(mt_gen_icosphere(level, &l));
        uint32_t pow4 = 1u << (2 * level);
        CHECK_EQ(l.num_verts, 10 * pow4 + 2);
        CHECK_EQ(l.num_faces, 20 * pow4);
        CHECK_EQ(l.num_indices, 60 * pow4);
        check_closed_surface(&l, 2);
        for (uint32_t v = 0; v < l.num_verts; v++)
            CHECK(fabs(dot3(pos(&l, v), pos(&l, v)) - 1) < 1e-12);
        uint32_t inward = 1;
        CHECK(faces_min_area(&l, &inward) > 1e-5);
        CHECK_EQ(inward, 0);
        CHECK_EQ(positions_repeated(&l), 0);
        /* the first 12 vertices are the icosahedron's, which level 0 is */
        mt_face_list ico;
        CHECK_OK(mt_gen_platonic(MT_ICOSAHEDRON, &ico));
        CHECK(memcmp(l.positions, ico.positions, 12 * 3 * sizeof(double)) == 0);
        if (level == 0) CHECK(memcmp(l.face_indices, ico.face_indices, 60 * sizeof(uint32_t)) == 0);
        mt_face_list_free(&ico);
        mt_face_list_free(&l);
    }
}

static void test_gen_icosphere_invalid(void)
{
    mt_face_list l = list_garbage();
    CHECK_STATUS(mt_gen_icosphere(11, &l), MT_ERR_INVALID_ARG);
    CHECK(list_is_zeroed(&l));
    CHECK_STATUS(mt_gen_icosphere(UINT32_MAX, &l), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_gen_icosphere(0, NULL), MT_ERR_INVALID_ARG);
}

/* ---- double torus ---- */

static void test_gen_double_torus(void)
{
    const uint32_t segs[] = {4, 5, 7, 16};
    for (size_t s = 0; s < sizeof segs / sizeof segs[0]; s++) {
        uint32_t k = segs[s];
        mt_face_list l;
        CHECK_OK(mt_gen_double_torus(k, &l));
        CHECK_EQ(l.num_verts, 2 * ((5 * k + 1) * (3 * k + 1) - 2 * (k - 1) * (k - 1)));
        CHECK_EQ(l.num_faces, 52 * k * k + 48 * k);
        for (uint32_t f = 0; f < l.num_faces; f++) CHECK_EQ(l.face_sizes[f], 3);
        check_closed_surface(&l, -2); /* connected, closed, orientable: genus 2 */
        CHECK(faces_min_area(&l, NULL) > 1e-6);
        CHECK(signed_volume(&l) > 0);
        CHECK_EQ(positions_repeated(&l), 0);
        mt_face_list_free(&l);
    }
}

static void test_gen_double_torus_invalid(void)
{
    mt_face_list l = list_garbage();
    CHECK_STATUS(mt_gen_double_torus(3, &l), MT_ERR_INVALID_ARG);
    CHECK(list_is_zeroed(&l));
    CHECK_STATUS(mt_gen_double_torus(0, &l), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_gen_double_torus(4, NULL), MT_ERR_INVALID_ARG);
    l = list_garbage();
    CHECK_STATUS(mt_gen_double_torus(100000, &l), MT_ERR_TOO_LARGE);
    CHECK(list_is_zeroed(&l));
    CHECK_STATUS(mt_gen_double_torus(UINT32_MAX, &l), MT_ERR_TOO_LARGE);
}

/* ---- Moebius strip ---- */

static void test_gen_moebius(void)
{
    const uint32_t segs[] = {3, 4, 10, 101};
    for (size_t s = 0; s < sizeof segs / sizeof segs[0]; s++) {
        uint32_t n = segs[s];
        mt_face_list l;
        CHECK_OK(mt_gen_moebius(n, &l));
        CHECK_EQ(l.num_verts, 2 * n);
        CHECK_EQ(l.num_faces, n);
        CHECK_EQ(l.num_indices, 4 * n);
        for (uint32_t f = 0; f < n; f++) CHECK_EQ(l.face_sizes[f], 4);
        topo t = topo_compute(&l);
        check_well_formed(&l, &t);
        CHECK_EQ(t.edges, 3 * n);
        CHECK_EQ(t.boundary_edges, 2 * n);
        CHECK_EQ(t.boundary_loops, 1);
        CHECK(t.boundary_simple);
        CHECK_EQ(t.nonmanifold_edges, 0);
        CHECK_EQ(t.same_direction_edges, 1); /* only the seam */
        CHECK_EQ(t.duplicate_directed, 1);
        CHECK_EQ(t.components, 1);
        CHECK(!t.orientable);
        CHECK_EQ(t.euler, 0);
        /* the seam is edge 0-1, crossed 1 -> 0 by the first and the last quad */
        CHECK_EQ(l.face_indices[2], 3);
        CHECK_EQ(l.face_indices[3], 1);
        CHECK_EQ(l.face_indices[0], 0);
        CHECK_EQ(l.face_indices[4 * (n - 1) + 1], 1);
        CHECK_EQ(l.face_indices[4 * (n - 1) + 2], 0);
        /* points lie on the strip: a quarter from the centre circle */
        for (uint32_t v = 0; v < l.num_verts; v++) {
            const double *p = pos(&l, v);
            double ring = sqrt(p[0] * p[0] + p[1] * p[1]) - 1.0;
            CHECK(fabs(ring * ring + p[2] * p[2] - 0.0625) < 1e-12);
        }
        CHECK(faces_min_area(&l, NULL) > 1e-6);
        CHECK_EQ(positions_repeated(&l), 0);
        mt_face_list_free(&l);
    }
}

static void test_gen_moebius_invalid(void)
{
    mt_face_list l = list_garbage();
    CHECK_STATUS(mt_gen_moebius(2, &l), MT_ERR_INVALID_ARG);
    CHECK(list_is_zeroed(&l));
    CHECK_STATUS(mt_gen_moebius(0, &l), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_gen_moebius(3, NULL), MT_ERR_INVALID_ARG);
    l = list_garbage();
    CHECK_STATUS(mt_gen_moebius(UINT32_MAX, &l), MT_ERR_TOO_LARGE);
    CHECK(list_is_zeroed(&l));
    CHECK_STATUS(mt_gen_moebius(1u << 31, &l), MT_ERR_TOO_LARGE);
}

/* ---- defects ---- */

static void test_gen_bowtie(void)
{
    mt_face_list l;
    CHECK_OK(mt_gen_bowtie(&l));
    CHECK_EQ(l.num_verts, 5);
    CHECK_EQ(l.num_faces, 2);
    CHECK_EQ(l.num_indices, 6);
    static const uint32_t want[6] = {0, 1, 2, 0, 3, 4};
    for (int i = 0; i < 6; i++) CHECK_EQ(l.face_indices[i], want[i]);
    topo t = topo_compute(&l);
    check_well_formed(&l, &t);
    CHECK_EQ(t.edges, 6);
    CHECK_EQ(t.boundary_edges, 6);
    CHECK(!t.boundary_simple); /* vertex 0 has four boundary edges */
    CHECK_EQ(t.components, 2); /* the triangles share no edge */
    CHECK_EQ(t.duplicate_directed, 0);
    CHECK_EQ(t.euler, 1);
    CHECK(faces_min_area(&l, NULL) > 0.1);
    uint64_t at = 0;
    for (uint32_t f = 0; f < 2; f++, at += 3) {
        double n[3], c[3];
        face_normal(&l, at, 3, n, c);
        CHECK(n[2] > 0); /* both counter-clockwise seen from +z */
    }
    mt_face_list_free(&l);
    CHECK_STATUS(mt_gen_bowtie(NULL), MT_ERR_INVALID_ARG);
}

static void test_gen_fin(void)
{
    mt_face_list l;
    CHECK_OK(mt_gen_fin(&l));
    CHECK_EQ(l.num_verts, 5);
    CHECK_EQ(l.num_faces, 3);
    CHECK_EQ(l.num_indices, 9);
    topo t = topo_compute(&l);
    check_well_formed(&l, &t);
    CHECK_EQ(t.edges, 7);
    CHECK_EQ(t.nonmanifold_edges, 1);
    CHECK_EQ(t.boundary_edges, 6);
    CHECK_EQ(t.components, 1);
    CHECK_EQ(t.euler, 1);
    /* all three faces hold edge 0-1 */
    for (uint32_t f = 0; f < 3; f++) {
        const uint32_t *fi = l.face_indices + 3 * f;
        bool has0 = false, has1 = false;
        for (int k = 0; k < 3; k++) {
            has0 = has0 || fi[k] == 0;
            has1 = has1 || fi[k] == 1;
        }
        CHECK(has0 && has1);
    }
    CHECK(faces_min_area(&l, NULL) > 0.1);
    mt_face_list_free(&l);
    CHECK_STATUS(mt_gen_fin(NULL), MT_ERR_INVALID_ARG);
}

/* ---- permute ---- */

static mt_face_list list_copy(const mt_face_list *l)
{
    mt_face_list c;
    CHECK_OK(mt_face_list_alloc(&c, l->num_verts, l->num_faces, l->num_indices, NULL));
    if (l->positions && c.positions)
        memcpy(c.positions, l->positions, 3 * sizeof(double) * l->num_verts);
    if (c.face_sizes) memcpy(c.face_sizes, l->face_sizes, sizeof(uint32_t) * l->num_faces);
    if (c.face_indices) memcpy(c.face_indices, l->face_indices, sizeof(uint32_t) * l->num_indices);
    return c;
}

static bool list_equal(const mt_face_list *a, const mt_face_list *b)
{
    return a->num_verts == b->num_verts && a->num_faces == b->num_faces &&
           a->num_indices == b->num_indices &&
           memcmp(a->positions, b->positions, 3 * sizeof(double) * a->num_verts) == 0 &&
           memcmp(a->face_sizes, b->face_sizes, sizeof(uint32_t) * a->num_faces) == 0 &&
           memcmp(a->face_indices, b->face_indices, sizeof(uint32_t) * a->num_indices) == 0;
}

typedef struct face_rec {
    uint32_t size;
    uint32_t v[4];
} face_rec;

static int face_rec_cmp(const void *x, const void *y)
{
    return memcmp(x, y, sizeof(face_rec));
}

/* Faces of l (size <= 4) as records, ids passed through map (when given,
 * in-range ids only), sorted. */
static face_rec *faces_sorted(const mt_face_list *l, const uint32_t *map)
{
    face_rec *r = calloc((size_t)l->num_faces + 1, sizeof *r);
    if (!r) return NULL;
    uint64_t at = 0;
    for (uint32_t f = 0; f < l->num_faces; f++) {
        r[f].size = l->face_sizes[f];
        for (uint32_t k = 0; k < l->face_sizes[f] && k < 4; k++) {
            uint32_t v = l->face_indices[at + k];
            r[f].v[k] = map && v < l->num_verts ? map[v] : v;
        }
        at += l->face_sizes[f];
    }
    qsort(r, l->num_faces, sizeof *r, face_rec_cmp);
    return r;
}

/* Checks that p is orig with vertex ids and face order shuffled: each vertex
 * of p is found in orig by its (unique) position, the map is a bijection and
 * maps p's faces onto orig's, each starting at the same corner. Returns how
 * many vertices changed id. */
static uint32_t check_is_permutation(const mt_face_list *orig, const mt_face_list *p)
{
    CHECK_EQ(p->num_verts, orig->num_verts);
    CHECK_EQ(p->num_faces, orig->num_faces);
    CHECK_EQ(p->num_indices, orig->num_indices);
    uint32_t n = orig->num_verts, moved = 0;
    uint32_t *back = calloc((size_t)n + 1, sizeof *back);
    uint32_t *hits = calloc((size_t)n + 1, sizeof *hits);
    for (uint32_t w = 0; w < n; w++) {
        back[w] = UINT32_MAX;
        for (uint32_t v = 0; v < n; v++) {
            if (memcmp(pos(p, w), pos(orig, v), 3 * sizeof(double)) == 0) back[w] = v;
        }
        CHECK(back[w] != UINT32_MAX);
        if (back[w] < n) hits[back[w]]++;
        moved += back[w] != w;
    }
    for (uint32_t v = 0; v < n; v++) CHECK_EQ(hits[v], 1);
    face_rec *a = faces_sorted(orig, NULL);
    face_rec *b = faces_sorted(p, back);
    CHECK(a && b);
    if (a && b) CHECK(memcmp(a, b, sizeof *a * orig->num_faces) == 0);
    free(a);
    free(b);
    free(back);
    free(hits);
    return moved;
}

static void test_face_list_permute(void)
{
    mt_face_list orig, l;
    CHECK_OK(mt_gen_torus(7, 5, &orig));
    l = list_copy(&orig);
    mt_diag diag;
    mt_diag_clear(&diag);
    CHECK_OK(mt_face_list_permute(&l, 42, &diag));
    CHECK_EQ(diag.status, MT_OK);
    uint32_t moved = check_is_permutation(&orig, &l);
    CHECK(moved > orig.num_verts / 2);
    /* the arrays did change */
    CHECK(memcmp(l.face_indices, orig.face_indices, sizeof(uint32_t) * orig.num_indices) != 0);
    check_closed_surface(&l, 0);
    CHECK(signed_volume(&l) > 0); /* orientation kept */
    mt_face_list_free(&l);

    /* mixed face sizes */
    mt_face_list_free(&orig);
    CHECK_OK(mt_gen_moebius(9, &orig));
    l = list_copy(&orig);
    CHECK_OK(mt_face_list_permute(&l, 7, NULL));
    check_is_permutation(&orig, &l);
    topo t = topo_compute(&l);
    CHECK_EQ(t.same_direction_edges, 1);
    CHECK_EQ(t.boundary_loops, 1);
    mt_face_list_free(&l);
    mt_face_list_free(&orig);
}

static void test_face_list_permute_deterministic(void)
{
    mt_face_list orig, a, b, c;
    CHECK_OK(mt_gen_icosphere(2, &orig));
    a = list_copy(&orig);
    b = list_copy(&orig);
    c = list_copy(&orig);
    CHECK_OK(mt_face_list_permute(&a, 12345, NULL));
    CHECK_OK(mt_face_list_permute(&b, 12345, NULL));
    CHECK_OK(mt_face_list_permute(&c, 12346, NULL));
    CHECK(list_equal(&a, &b));
    CHECK(!list_equal(&a, &c));
    CHECK(!list_equal(&a, &orig));
    check_is_permutation(&orig, &a);
    check_is_permutation(&orig, &c);
    /* seed 0 shuffles too */
    mt_face_list_free(&a);
    a = list_copy(&orig);
    CHECK_OK(mt_face_list_permute(&a, 0, NULL));
    CHECK(!list_equal(&a, &orig));
    mt_face_list_free(&a);
    mt_face_list_free(&b);
    mt_face_list_free(&c);
    mt_face_list_free(&orig);
}

static void test_face_list_permute_out_of_range(void)
{
    /* Entries 99 and 0xffffffff (-1) are out of range for 4 vertices. */
    mt_face_list orig;
    CHECK_OK(mt_face_list_alloc(&orig, 4, 3, 10, NULL));
    const uint32_t sizes[3] = {3, 3, 4};
    const uint32_t idx[10] = {0, 1, 2, 0, 2, 99, 1, 0xffffffffu, 3, 2};
    memcpy(orig.face_sizes, sizes, sizeof sizes);
    memcpy(orig.face_indices, idx, sizeof idx);
    for (uint32_t i = 0; i < 12; i++) orig.positions[i] = i;
    mt_face_list l = list_copy(&orig);
    CHECK_OK(mt_face_list_permute(&l, 3, NULL));
    check_is_permutation(&orig, &l);
    /* the bad entries are still there, each at the same corner of its face */
    uint32_t found99 = 0, found_neg = 0;
    uint64_t at = 0;
    for (uint32_t f = 0; f < 3; f++) {
        for (uint32_t k = 0; k < l.face_sizes[f]; k++) {
            if (l.face_indices[at + k] == 99) found99 += l.face_sizes[f] == 3 && k == 2;
            if (l.face_indices[at + k] == 0xffffffffu) found_neg += l.face_sizes[f] == 4 && k == 1;
        }
        at += l.face_sizes[f];
    }
    CHECK_EQ(found99, 1);
    CHECK_EQ(found_neg, 1);
    mt_face_list_free(&l);
    mt_face_list_free(&orig);
}

static void test_face_list_permute_edge_cases(void)
{
    /* Without positions. */
    mt_face_list orig, l;
    CHECK_OK(mt_gen_grid(4, 3, false, &orig));
    l = list_copy(&orig);
    free(l.positions);
    l.positions = NULL;
    CHECK_OK(mt_face_list_permute(&l, 9, NULL));
    CHECK(l.positions == NULL);
    topo t = topo_compute(&l);
    CHECK(t.indices_in_range);
    CHECK_EQ(t.boundary_loops, 1);
    CHECK_EQ(t.duplicate_directed, 0);
    CHECK_EQ(t.euler, 1);
    mt_face_list_free(&l);

    /* Inconsistent sizes: refused, list unchanged. */
    l = list_copy(&orig);
    l.num_indices -= 1;
    mt_diag diag;
    mt_diag_clear(&diag);
    CHECK_STATUS(mt_face_list_permute(&l, 9, &diag), MT_ERR_INVALID_ARG);
    CHECK_EQ(diag.status, MT_ERR_INVALID_ARG);
    CHECK(diag.message[0] != '\0');
    l.num_indices += 1;
    CHECK(list_equal(&l, &orig));
    mt_face_list_free(&l);
    mt_face_list_free(&orig);

    CHECK_STATUS(mt_face_list_permute(NULL, 1, NULL), MT_ERR_INVALID_ARG);

    /* Empty and single-element lists. */
    mt_face_list empty;
    memset(&empty, 0, sizeof empty);
    CHECK_OK(mt_face_list_permute(&empty, 1, NULL));
    CHECK(list_is_zeroed(&empty));
    CHECK_OK(mt_face_list_alloc(&l, 1, 0, 0, NULL));
    l.positions[0] = 5;
    CHECK_OK(mt_face_list_permute(&l, 1, NULL));
    CHECK(l.positions[0] == 5);
    mt_face_list_free(&l);
}

static const mt_test_case cases[] = {
    {"gen_platonic", test_gen_platonic},
    {"gen_platonic_invalid", test_gen_platonic_invalid},
    {"gen_rectangle", test_gen_rectangle},
    {"gen_rectangle_invalid", test_gen_rectangle_invalid},
    {"gen_grid", test_gen_grid},
    {"gen_grid_invalid", test_gen_grid_invalid},
    {"gen_torus", test_gen_torus},
    {"gen_torus_invalid", test_gen_torus_invalid},
    {"gen_icosphere", test_gen_icosphere},
    {"gen_icosphere_invalid", test_gen_icosphere_invalid},
    {"gen_double_torus", test_gen_double_torus},
    {"gen_double_torus_invalid", test_gen_double_torus_invalid},
    {"gen_moebius", test_gen_moebius},
    {"gen_moebius_invalid", test_gen_moebius_invalid},
    {"gen_bowtie", test_gen_bowtie},
    {"gen_fin", test_gen_fin},
    {"face_list_permute", test_face_list_permute},
    {"face_list_permute_deterministic", test_face_list_permute_deterministic},
    {"face_list_permute_out_of_range", test_face_list_permute_out_of_range},
    {"face_list_permute_edge_cases", test_face_list_permute_edge_cases},
};
const mt_test_table mt_tests_generate = {cases, sizeof cases / sizeof cases[0]};
