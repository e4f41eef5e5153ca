/* The icosphere (generate.h): the icosahedron subdivided `level` times, each
 * triangle into four, new vertices pushed onto the unit sphere at every level.
 * Midpoints are shared through edge ids carried along the subdivision instead
 * of a hash table: edge e of a level gets midpoint vertex V + e, its halves
 * become edges 2e and 2e+1 of the next level (2e touching the smaller vertex
 * id) and the three inner edges of face f become 2E + 3f .. 2E + 3f + 2. So a
 * level costs one linear pass and the build makes a fixed number of
 * allocations whatever the level. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "meshtopo/generate.h"

#define ICOSPHERE_MAX_LEVEL 10u

/* Edge of the next level that is the half of edge e (from x to y) touching x. */
static uint32_t half_edge_at(uint32_t e, uint32_t x, uint32_t y)
{
    return 2 * e + (x < y ? 0u : 1u);
}

/* Numbers the icosahedron's 30 edges in order of first use: edges[3f+k] is the
 * edge from corner k to corner k+1 of face f. */
static void base_edges_number(const uint32_t *faces, uint32_t *edges)
{
    uint32_t ends[30][2];
    uint32_t count = 0;
    for (uint32_t c = 0; c < 60; c++) {
        uint32_t a = faces[c], b = faces[c % 3 == 2 ? c - 2 : c + 1];
        uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
        uint32_t e = 0;
        while (e < count && !(ends[e][0] == lo && ends[e][1] == hi)) e++;
        if (e == count && count < 30) {
            ends[count][0] = lo;
            ends[count][1] = hi;
            count++;
        }
        edges[c] = e;
    }
}

/* Midpoint of p and q, projected onto the unit sphere. */
static void midpoint_put(const double *p, const double *q, double *out)
{
    double m[3] = {p[0] + q[0], p[1] + q[1], p[2] + q[2]};
    double r = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    for (int k = 0; k < 3; k++) out[k] = m[k] / r;
}

/* One subdivision: num_faces triangles (faces, edges) of a level with
 * num_verts vertices and num_edges edges become 4 * num_faces triangles in
 * out_faces (and their edge ids in out_edges unless it is NULL). */
static void level_subdivide(const uint32_t *faces, const uint32_t *edges, uint32_t num_faces,
                            uint32_t num_verts, uint32_t num_edges, double *positions,
                            uint32_t *out_faces, uint32_t *out_edges)
{
    for (uint32_t f = 0; f < num_faces; f++) {
        const uint32_t *v = faces + 3 * (size_t)f;
        const uint32_t *e = edges + 3 * (size_t)f;
        uint32_t a = v[0], b = v[1], c = v[2];
        uint32_t ab = num_verts + e[0], bc = num_verts + e[1], ca = num_verts + e[2];
        for (int k = 0; k < 3; k++) {
            uint32_t x = v[k], y = v[k == 2 ? 0 : k + 1];
            if (x < y)
                midpoint_put(positions + 3 * (size_t)x, positions + 3 * (size_t)y,
                             positions + 3 * ((size_t)num_verts + e[k]));
        }
        /*        c
         *       / \
         *     ca---bc        corner triangles 0, 1, 2 and the middle one 3,
         *     / \ 3 / \      all counter-clockwise like (a, b, c)
         *    a---ab----b                                                  */
        uint32_t *o = out_faces + 12 * (size_t)f;
        const uint32_t tris[12] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
        memcpy(o, tris, sizeof tris);
        if (out_edges) {
            uint32_t inner = 2 * num_edges + 3 * f;
            const uint32_t sides[12] = {
                half_edge_at(e[0], a, b),
                inner + 0,
                half_edge_at(e[2], a, c),
                half_edge_at(e[0], b, a),
                half_edge_at(e[1], b, c),
                inner + 1,
                inner + 2,
                half_edge_at(e[1], c, b),
                half_edge_at(e[2], c, a),
                inner + 1,
                inner + 2,
                inner + 0,
            };
            memcpy(out_edges + 12 * (size_t)f, sides, sizeof sides);
        }
    }
}

mt_status mt_gen_icosphere(uint32_t level, mt_face_list *out)
{
    if (!out) return MT_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    if (level > ICOSPHERE_MAX_LEVEL) return MT_ERR_INVALID_ARG; /* level 0 .. 10 */
    const uint32_t pow4 = 1u << (2 * level);                    /* <= 2^20 */
    mt_face_list base;
    mt_status status = mt_gen_platonic(MT_ICOSAHEDRON, &base);
    if (status != MT_OK) return status;
    status = mt_face_list_alloc(out, 10 * pow4 + 2, 20 * pow4, 60 * (uint64_t)pow4, NULL);
    if (status != MT_OK) {
        mt_face_list_free(&base);
        return status;
    }
    memcpy(out->positions, base.positions, 12 * 3 * sizeof(double));
    for (uint32_t f = 0; f < 20 * pow4; f++) out->face_sizes[f] = 3;

    /* Ping-pong buffers: the faces of level k live in out when level - k is
     * even, else in tmp_faces; the edge ids of level k (< level) live in
     * edges_a when level - 1 - k is even, else in edges_b. */
    const size_t top = level > 0 ? 60 * (size_t)(pow4 / 4) : 60; /* 3 faces of level-1 */
    const size_t below = top / 4 > 60 ? top / 4 : 60;            /* 3 faces of level-2 */
    uint32_t *scratch = malloc((2 * top + below) * sizeof(uint32_t));
    if (!scratch) {
        mt_face_list_free(&base);
        mt_face_list_free(out);
        return MT_ERR_NOMEM;
    }
    uint32_t *tmp_faces = scratch;
    uint32_t *edges_a = scratch + top;
    uint32_t *edges_b = scratch + 2 * top;

    uint32_t *faces = level % 2 == 0 ? out->face_indices : tmp_faces;
    uint32_t *edges = (level + 1) % 2 == 0 ? edges_a : edges_b;
    memcpy(faces, base.face_indices, 60 * sizeof(uint32_t));
    mt_face_list_free(&base);
    if (level > 0) base_edges_number(faces, edges);

    uint32_t num_verts = 12, num_edges = 30, num_faces = 20;
    for (uint32_t k = 0; k < level; k++) {
        uint32_t *next_faces = faces == tmp_faces ? out->face_indices : tmp_faces;
        uint32_t *next_edges = k + 1 < level ? (edges == edges_a ? edges_b : edges_a) : NULL;
        level_subdivide(faces, edges, num_faces, num_verts, num_edges, out->positions, next_faces,
                        next_edges);
        num_verts += num_edges;
        num_edges = 2 * num_edges + 3 * num_faces;
        num_faces *= 4;
        faces = next_faces;
        edges = next_edges;
    }
    free(scratch);
    return MT_OK;
}
