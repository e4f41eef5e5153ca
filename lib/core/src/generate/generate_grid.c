/* Quad-grid surfaces (generate.h): the seed rectangle, the flat grid and the
 * torus. Cells are listed row by row (cell (i, j) is cell j*nx+i); a cell with
 * corners a = (i, j), b = (i+1, j), c = (i+1, j+1), d = (i, j+1) is the quad
 * (a, b, c, d) or, split along its diagonal a-c, the triangles (a, b, c),
 * (a, c, d), the same split as the rectangle's. Counts are checked against
 * the face list's 32-bit limits before anything is allocated. */
#include <math.h>
#include <string.h>

#include "meshtopo/generate.h"

/* Writes cell (a, b, c, d) as one quad or two triangles at *idx / *sizes and
 * advances both cursors. */
static void cell_put(uint32_t a, uint32_t b, uint32_t c, uint32_t d, bool triangles, uint32_t **idx,
                     uint32_t **sizes)
{
    uint32_t *i = *idx;
    uint32_t *s = *sizes;
    if (triangles) {
        i[0] = a, i[1] = b, i[2] = c;
        i[3] = a, i[4] = c, i[5] = d;
        s[0] = 3, s[1] = 3;
        *idx = i + 6;
        *sizes = s + 2;
    } else {
        i[0] = a, i[1] = b, i[2] = c, i[3] = d;
        s[0] = 4;
        *idx = i + 4;
        *sizes = s + 1;
    }
}

mt_status mt_gen_rectangle(double width, double height, mt_face_list *out)
{
    if (!out) return MT_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    /* width and height must be finite and > 0 */
    if (!isfinite(width) || !isfinite(height) || !(width > 0) || !(height > 0))
        return MT_ERR_INVALID_ARG;
    mt_status status = mt_face_list_alloc(out, 4, 2, 6, NULL);
    if (status != MT_OK) return status;
    const double pos[12] = {0, 0, 0, width, 0, 0, width, height, 0, 0, height, 0};
    memcpy(out->positions, pos, sizeof pos);
    uint32_t *idx = out->face_indices;
    uint32_t *sizes = out->face_sizes;
    cell_put(0, 1, 2, 3, true, &idx, &sizes);
    return MT_OK;
}

/* Vertex (i, j) sits at (i, j, 0): the cells are unit squares. */
mt_status mt_gen_grid(uint32_t nx, uint32_t ny, bool triangles, mt_face_list *out)
{
    if (!out) return MT_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    if (nx < 1 || ny < 1) return MT_ERR_INVALID_ARG; /* nx, ny >= 1 */
    uint64_t cells = (uint64_t)nx * ny;              /* < 2^64: both factors < 2^32 */
    uint64_t verts = ((uint64_t)nx + 1) * ((uint64_t)ny + 1);
    uint64_t faces = triangles ? 2 * cells : cells;
    if (verts > UINT32_MAX || faces > UINT32_MAX) return MT_ERR_TOO_LARGE;
    mt_status status = mt_face_list_alloc(out, (uint32_t)verts, (uint32_t)faces,
                                          triangles ? 6 * cells : 4 * cells, NULL);
    if (status != MT_OK) return status;
    const uint32_t row = nx + 1; /* fits: verts <= UINT32_MAX */
    for (uint32_t j = 0; j <= ny; j++) {
        for (uint32_t i = 0; i <= nx; i++) {
            double *p = out->positions + 3 * ((size_t)j * row + i);
            p[0] = (double)i, p[1] = (double)j, p[2] = 0.0;
        }
    }
    uint32_t *idx = out->face_indices;
    uint32_t *sizes = out->face_sizes;
    for (uint32_t j = 0; j < ny; j++) {
        for (uint32_t i = 0; i < nx; i++) {
            uint32_t a = j * row + i;
            cell_put(a, a + 1, a + row + 1, a + row, triangles, &idx, &sizes);
        }
    }
    return MT_OK;
}

/* Vertex (i, j) has id j*nu+i: i runs around the major circle (angle
 * theta = 2 pi i / nu), j around the tube (phi = 2 pi j / nv), at
 * ((R + r cos phi) cos theta, (R + r cos phi) sin theta, r sin phi). The
 * derivatives in theta then phi span the outward normal, so cells listed
 * (i, j) -> (i+1, j) -> (i+1, j+1) face outwards. */
mt_status mt_gen_torus(uint32_t nu, uint32_t nv, mt_face_list *out)
{
    if (!out) return MT_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    if (nu < 3 || nv < 3) return MT_ERR_INVALID_ARG; /* nu, nv >= 3 */
    uint64_t cells = (uint64_t)nu * nv;
    if (2 * cells > UINT32_MAX) return MT_ERR_TOO_LARGE;
    mt_status status =
        mt_face_list_alloc(out, (uint32_t)cells, (uint32_t)(2 * cells), 6 * cells, NULL);
    if (status != MT_OK) return status;
    const double major = 1.0, minor = 0.25;
    const double two_pi = 6.283185307179586476925286766559;
    for (uint32_t j = 0; j < nv; j++) {
        double phi = two_pi * j / nv;
        double ring = major + minor * cos(phi);
        for (uint32_t i = 0; i < nu; i++) {
            double theta = two_pi * i / nu;
            double *p = out->positions + 3 * ((size_t)j * nu + i);
            p[0] = ring * cos(theta), p[1] = ring * sin(theta), p[2] = minor * sin(phi);
        }
    }
    uint32_t *idx = out->face_indices;
    uint32_t *sizes = out->face_sizes;
    for (uint32_t j = 0; j < nv; j++) {
        uint32_t j1 = j + 1 == nv ? 0 : j + 1;
        for (uint32_t i = 0; i < nu; i++) {
            uint32_t i1 = i + 1 == nu ? 0 : i + 1;
            cell_put(j * nu + i, j * nu + i1, j1 * nu + i1, j1 * nu + i, true, &idx, &sizes);
        }
    }
    return MT_OK;
}
