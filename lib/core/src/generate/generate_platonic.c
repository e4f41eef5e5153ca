/* The five Platonic solids as face lists (generate.h): centred at the origin,
 * circumradius 1, every face counter-clockwise seen from outside. The tables
 * were laid out for that orientation; tests/core/test_generate.c checks it
 * (outward face normals, every edge used once in each direction). The
 * dodecahedron is the icosahedron's dual: its vertices are the icosahedron's
 * face centres and its face v lists the faces around icosahedron vertex v. */
#include <math.h>
#include <string.h>

#include "meshtopo/generate.h"

static const uint8_t tetrahedron_faces[4][3] = {
    {0, 1, 2},
    {0, 3, 1},
    {0, 2, 3},
    {1, 3, 2},
};

/* Cube vertex v is (x, y, z) with x = bit 0, y = bit 1, z = bit 2 of v (0 -> -1, 1 -> +1). */
static const uint8_t cube_faces[6][4] = {
    {0, 4, 6, 2}, /* x = -1 */
    {1, 3, 7, 5}, /* x = +1 */
    {0, 1, 5, 4}, /* y = -1 */
    {2, 6, 7, 3}, /* y = +1 */
    {0, 2, 3, 1}, /* z = -1 */
    {4, 5, 7, 6}, /* z = +1 */
};

static const uint8_t octahedron_faces[8][3] = {
    {0, 2, 4}, {0, 5, 2}, {0, 4, 3}, {0, 3, 5}, {1, 4, 2}, {1, 2, 5}, {1, 3, 4}, {1, 5, 3},
};

static const uint8_t icosahedron_faces[20][3] = {
    {0, 8, 2}, {0, 2, 10}, {0, 6, 4},  {0, 4, 8}, {0, 10, 6},  {1, 3, 9},   {1, 11, 3},
    {1, 4, 6}, {1, 9, 4},  {1, 6, 11}, {2, 5, 7}, {2, 8, 5},   {2, 7, 10},  {3, 7, 5},
    {3, 5, 9}, {3, 11, 7}, {4, 9, 8},  {5, 8, 9}, {6, 10, 11}, {7, 11, 10},
};

static const uint8_t dodecahedron_faces[12][5] = {
    {0, 1, 4, 2, 3},    {5, 8, 7, 9, 6},      {0, 11, 10, 12, 1}, {5, 6, 15, 13, 14},
    {2, 7, 8, 16, 3},   {10, 11, 17, 14, 13}, {2, 4, 18, 9, 7},   {10, 13, 15, 19, 12},
    {0, 3, 16, 17, 11}, {5, 14, 17, 16, 8},   {1, 12, 19, 18, 4}, {6, 9, 18, 19, 15},
};

/* Fills *out from a vertex table (scaled to circumradius 1) and a face table. */
static mt_status solid_make(const double (*verts)[3], uint32_t num_verts, const uint8_t *faces,
                            uint32_t num_faces, uint32_t face_size, mt_face_list *out)
{
    mt_status status =
        mt_face_list_alloc(out, num_verts, num_faces, (uint64_t)num_faces * face_size, NULL);
    if (status != MT_OK) return status;
    for (uint32_t v = 0; v < num_verts; v++) {
        double r =
            sqrt(verts[v][0] * verts[v][0] + verts[v][1] * verts[v][1] + verts[v][2] * verts[v][2]);
        for (int k = 0; k < 3; k++) out->positions[3 * v + k] = verts[v][k] / r;
    }
    for (uint32_t f = 0; f < num_faces; f++) out->face_sizes[f] = face_size;
    for (uint32_t i = 0; i < num_faces * face_size; i++) out->face_indices[i] = faces[i];
    return MT_OK;
}

mt_status mt_gen_platonic(mt_platonic kind, mt_face_list *out)
{
    if (!out) return MT_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    const double p = (1.0 + sqrt(5.0)) / 2.0; /* golden ratio */
    const double q = 1.0 / p;
    switch (kind) {
        case MT_TETRAHEDRON: {
            const double verts[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
            return solid_make(verts, 4, &tetrahedron_faces[0][0], 4, 3, out);
        }
        case MT_CUBE: {
            double verts[8][3];
            for (int v = 0; v < 8; v++) {
                for (int k = 0; k < 3; k++) verts[v][k] = ((v >> k) & 1) ? 1.0 : -1.0;
            }
            return solid_make((const double(*)[3])verts, 8, &cube_faces[0][0], 6, 4, out);
        }
        case MT_OCTAHEDRON: {
            const double verts[6][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                        {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
            return solid_make(verts, 6, &octahedron_faces[0][0], 8, 3, out);
        }
        case MT_DODECAHEDRON: {
            const double verts[20][3] = {
                {-q, 0, -p}, {q, 0, -p},  {0, -p, -q}, {-1, -1, -1}, {1, -1, -1},
                {-q, 0, p},  {q, 0, p},   {0, -p, q},  {-1, -1, 1},  {1, -1, 1},
                {0, p, -q},  {-1, 1, -1}, {1, 1, -1},  {0, p, q},    {-1, 1, 1},
                {1, 1, 1},   {-p, -q, 0}, {-p, q, 0},  {p, -q, 0},   {p, q, 0},
            };
            return solid_make(verts, 20, &dodecahedron_faces[0][0], 12, 5, out);
        }
        case MT_ICOSAHEDRON: {
            const double verts[12][3] = {
                {0, -1, -p}, {0, -1, p}, {0, 1, -p},  {0, 1, p},  {-1, -p, 0}, {-1, p, 0},
                {1, -p, 0},  {1, p, 0},  {-p, 0, -1}, {-p, 0, 1}, {p, 0, -1},  {p, 0, 1},
            };
            return solid_make(verts, 12, &icosahedron_faces[0][0], 20, 3, out);
        }
    }
    return MT_ERR_INVALID_ARG; /* kind outside MT_TETRAHEDRON .. MT_ICOSAHEDRON */
}
