/* libFuzzer target for mt_mesh_self_intersections: the input bytes become a
 * small mesh (triangles, optionally polygons; any indices, so some faces
 * are rejected) on lattice coordinates (many coplanar, collinear and
 * coincident corners) or on raw doubles (NaN, infinities, huge and tiny
 * values). The check must succeed; its pairs must be sorted, without
 * repeats, a < b, both valid faces; a short buffer must get the same first
 * pairs and MT_ERR_BUFFER_TOO_SMALL; the search bounded at that count
 * must find it, and bounded one below must stop; and on the lattice every
 * two triangle faces sharing no vertex must be listed exactly when
 * mt_triangles_intersect says they meet. Any disagreement calls abort().
 *
 * Input layout (missing bytes read as 0, so every input is a mesh):
 *   byte 0    flags: bit 0 = raw doubles (8 bytes per coordinate) instead of
 *             the lattice (one byte per coordinate, byte % 7 - 3, halved
 *             when bit 2 is set); bit 1 = faces of 3 to 6 corners
 *   byte 1    V = 3 + byte % 30
 *   byte 2    F = byte % 40
 *   F faces   (size byte when polygons) then one index byte per corner, % V
 *   the rest  coordinates, vertex by vertex */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/core.h"
#include "meshtopo/predicates.h"

#define MAX_VERTS 33
#define MAX_FACES 40
#define MAX_FACE_SIZE 6

static void require(bool ok, const char *what, int line)
{
    if (ok) return;
    fprintf(stderr, "fuzz_self_intersections.c:%d: invariant violated: %s\n", line, what);
    abort();
}

#define REQUIRE(cond) require((cond), #cond, __LINE__)

typedef struct byte_reader {
    const uint8_t *data;
    size_t size, pos;
} byte_reader;

static uint8_t next_byte(byte_reader *r)
{
    return r->pos < r->size ? r->data[r->pos++] : 0;
}

/* Whether the sorted pairs hold (a, b). */
static bool listed(const mt_face_pair *pairs, size_t count, uint32_t a, uint32_t b)
{
    for (size_t i = 0; i < count; i++)
        if (pairs[i].a == a && pairs[i].b == b) return true;
    return false;
}

static bool shares_vertex(const uint32_t *a, const uint32_t *b)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (a[i] == b[j]) return true;
    return false;
}

/* Every two valid triangle faces sharing no vertex: listed exactly when they meet. */
static void check_against_pairs(const mt_mesh *mesh, const double *positions,
                                const mt_face_pair *pairs, size_t count)
{
    const uint32_t num_faces = mt_mesh_num_faces(mesh);
    for (uint32_t a = 0; a < num_faces; a++) {
        uint32_t va[MAX_FACE_SIZE];
        size_t na = 0;
        if (mt_face_verts(mesh, a, va, MAX_FACE_SIZE, &na) != MT_OK || na != 3) continue;
        for (uint32_t b = a + 1; b < num_faces; b++) {
            uint32_t vb[MAX_FACE_SIZE];
            size_t nb = 0;
            if (mt_face_verts(mesh, b, vb, MAX_FACE_SIZE, &nb) != MT_OK || nb != 3) continue;
            if (shares_vertex(va, vb)) continue;
            double ta[3][3], tb[3][3];
            for (int i = 0; i < 3; i++)
                for (int k = 0; k < 3; k++) {
                    ta[i][k] = positions[3 * va[i] + (uint32_t)k];
                    tb[i][k] = positions[3 * vb[i] + (uint32_t)k];
                }
            REQUIRE(mt_triangles_intersect(ta, tb) == listed(pairs, count, a, b));
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    byte_reader r = {data, size, 0};
    const uint8_t flags = next_byte(&r);
    const bool raw = flags & 1, polygons = flags & 2, halves = flags & 4;
    const uint32_t num_verts = 3 + next_byte(&r) % 30;
    const uint32_t num_faces = next_byte(&r) % 40;
    uint32_t sizes[MAX_FACES], indices[MAX_FACES * MAX_FACE_SIZE];
    uint32_t num_indices = 0;
    for (uint32_t f = 0; f < num_faces; f++) {
        sizes[f] = polygons ? 3 + next_byte(&r) % 4 : 3;
        for (uint32_t k = 0; k < sizes[f]; k++) indices[num_indices++] = next_byte(&r) % num_verts;
    }
    double positions[3 * MAX_VERTS];
    for (uint32_t i = 0; i < 3 * num_verts; i++) {
        if (raw) {
            uint8_t bytes[8];
            for (int k = 0; k < 8; k++) bytes[k] = next_byte(&r);
            memcpy(&positions[i], bytes, sizeof(double));
        } else {
            positions[i] = (double)(next_byte(&r) % 7) - 3;
            if (halves) positions[i] /= 2;
        }
    }
    mt_face_list list = {num_verts, num_faces, num_indices, positions, sizes, indices};
    mt_mesh *mesh = NULL;
    if (mt_mesh_build(&list, NULL, &mesh, NULL) != MT_OK) return 0;

    size_t count = 0;
    REQUIRE(mt_mesh_self_intersections(mesh, NULL, 0, &count, NULL) == MT_OK);
    mt_face_pair *pairs = malloc((count + 1) * sizeof *pairs);
    REQUIRE(pairs != NULL);
    size_t again = 0;
    REQUIRE(mt_mesh_self_intersections(mesh, pairs, count + 1, &again, NULL) == MT_OK);
    REQUIRE(again == count);
    for (size_t i = 0; i < count; i++) {
        REQUIRE(pairs[i].a < pairs[i].b && pairs[i].b < num_faces);
        size_t n = 0;
        REQUIRE(mt_face_verts(mesh, pairs[i].a, NULL, 0, &n) != MT_ERR_NOT_FOUND);
        REQUIRE(mt_face_verts(mesh, pairs[i].b, NULL, 0, &n) != MT_ERR_NOT_FOUND);
        if (i > 0)
            REQUIRE(pairs[i - 1].a < pairs[i].a ||
                    (pairs[i - 1].a == pairs[i].a && pairs[i - 1].b < pairs[i].b));
    }
    if (count > 1) {
        mt_face_pair *short_buf = malloc((count - 1) * sizeof *short_buf);
        REQUIRE(short_buf != NULL);
        REQUIRE(mt_mesh_self_intersections(mesh, short_buf, count - 1, &again, NULL) ==
                MT_ERR_BUFFER_TOO_SMALL);
        REQUIRE(again == count && memcmp(short_buf, pairs, (count - 1) * sizeof *pairs) == 0);
        free(short_buf);
    }
    /* the bounded search agrees: the count at the bound, too many below it */
    REQUIRE(mt_mesh_self_intersections_at_most(mesh, count, UINT64_MAX, NULL, 0, &again, NULL) ==
            MT_OK);
    REQUIRE(again == count);
    if (count > 0)
        REQUIRE(mt_mesh_self_intersections_at_most(mesh, count - 1, UINT64_MAX, NULL, 0, &again,
                                                   NULL) == MT_ERR_TOO_LARGE);
    /* with no exact test allowed it passes only where none is needed */
    const mt_status untested =
        mt_mesh_self_intersections_at_most(mesh, SIZE_MAX, 0, NULL, 0, &again, NULL);
    REQUIRE(untested == MT_ERR_TOO_LARGE || (untested == MT_OK && count == 0 && again == 0));
    if (!raw) check_against_pairs(mesh, positions, pairs, count);
    free(pairs);
    mt_mesh_destroy(mesh);
    return 0;
}
