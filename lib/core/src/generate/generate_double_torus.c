/* The double torus (generate.h) as the surface of a thick plate with two
 * square holes, which is a closed orientable genus-2 surface embedded without
 * self-intersection. With k = segments, the plate is a 5k x 3k grid of cells
 * (x from -2.5 to 2.5, y from -1.5 to 1.5, cell side 1/k) minus two k x k
 * holes; its top (z = +0.25) and bottom (z = -0.25) are triangulated like
 * mt_gen_grid and joined by a wall of two triangles along every boundary edge
 * of the plate. Top vertices come first (row by row), then the bottom copies. */
#include <stdlib.h>
#include <string.h>

#include "meshtopo/generate.h"

static const double half_thickness = 0.25;

/* Cell (i, j) belongs to the plate: inside the grid and in neither hole. */
static bool cell_solid(int64_t i, int64_t j, int64_t k)
{
    if (i < 0 || j < 0 || i >= 5 * k || j >= 3 * k) return false;
    bool hole_row = j >= k && j < 2 * k;
    bool hole_col = (i >= k && i < 2 * k) || (i >= 3 * k && i < 4 * k);
    return !(hole_row && hole_col);
}

mt_status mt_gen_double_torus(uint32_t segments, mt_face_list *out)
{
    if (!out) return MT_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    if (segments < 4) return MT_ERR_INVALID_ARG; /* segments >= 4 */
    const uint64_t k = segments;
    const uint64_t nx = 5 * k, ny = 3 * k;
    /* Each layer: every grid vertex except the (k-1)^2 inside each hole.
     * Faces: 13k^2 cells per layer, 2 triangles each, plus 2 triangles for
     * each of the 16k + 2 * 4k boundary edges. */
    const uint64_t grid_verts = (nx + 1) * (ny + 1);
    const uint64_t layer_verts = grid_verts - 2 * (k - 1) * (k - 1);
    const uint64_t num_faces = 2 * 2 * 13 * k * k + 2 * 24 * k;
    if (2 * layer_verts > UINT32_MAX || num_faces > UINT32_MAX) return MT_ERR_TOO_LARGE;
    const uint32_t n = (uint32_t)layer_verts;

    /* id[j*(nx+1)+i]: top-layer id of grid vertex (i, j), MT_NONE inside a hole. */
    uint32_t *id = malloc((size_t)grid_verts * sizeof(uint32_t));
    if (!id) return MT_ERR_NOMEM;
    mt_status status = mt_face_list_alloc(out, 2 * n, (uint32_t)num_faces, 3 * num_faces, NULL);
    if (status != MT_OK) {
        free(id);
        return status;
    }
    uint32_t next = 0;
    for (uint64_t j = 0; j <= ny; j++) {
        for (uint64_t i = 0; i <= nx; i++) {
            int64_t si = (int64_t)i, sj = (int64_t)j, sk = (int64_t)k;
            bool used = cell_solid(si - 1, sj - 1, sk) || cell_solid(si, sj - 1, sk) ||
                        cell_solid(si - 1, sj, sk) || cell_solid(si, sj, sk);
            id[j * (nx + 1) + i] = used ? next : MT_NONE;
            if (!used) continue;
            double x = (double)i / (double)k - 2.5, y = (double)j / (double)k - 1.5;
            double *top = out->positions + 3 * (size_t)next;
            double *bottom = out->positions + 3 * ((size_t)n + next);
            top[0] = bottom[0] = x;
            top[1] = bottom[1] = y;
            top[2] = half_thickness;
            bottom[2] = -half_thickness;
            next++;
        }
    }

    uint32_t *idx = out->face_indices;
    for (uint64_t j = 0; j < ny; j++) {
        for (uint64_t i = 0; i < nx; i++) {
            int64_t si = (int64_t)i, sj = (int64_t)j, sk = (int64_t)k;
            if (!cell_solid(si, sj, sk)) continue;
            /* corners counter-clockwise seen from +z */
            const uint32_t c[4] = {id[j * (nx + 1) + i], id[j * (nx + 1) + i + 1],
                                   id[(j + 1) * (nx + 1) + i + 1], id[(j + 1) * (nx + 1) + i]};
            const uint32_t tris[12] = {c[0],     c[1],     c[2],     c[0],     c[2],     c[3],
                                       n + c[0], n + c[2], n + c[1], n + c[0], n + c[3], n + c[2]};
            memcpy(idx, tris, sizeof tris);
            idx += 12;
            /* Sides of the cell in its own order (bottom, right, top, left) and
             * the cell across each; a side with no plate cell across is on the
             * boundary and gets a wall facing away from the cell. */
            const int64_t across[4][2] = {{si, sj - 1}, {si + 1, sj}, {si, sj + 1}, {si - 1, sj}};
            for (int s = 0; s < 4; s++) {
                if (cell_solid(across[s][0], across[s][1], sk)) continue;
                uint32_t p = c[s], q = c[(s + 1) % 4];
                /* the top uses p -> q, the bottom n+q -> n+p: the wall uses
                 * q -> p on top and n+p -> n+q below */
                const uint32_t wall[6] = {q, p, n + p, q, n + p, n + q};
                memcpy(idx, wall, sizeof wall);
                idx += 6;
            }
        }
    }
    free(id);
    for (uint32_t f = 0; f < out->num_faces; f++) out->face_sizes[f] = 3;
    return MT_OK;
}
