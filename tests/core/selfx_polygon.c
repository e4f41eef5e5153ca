/* Polygon helpers of the self-intersection oracle (selfx_polygon.h):
 * candidate triangles and triangulations of a face (the classic interval
 * recursion: the triangle on side (i, j) of sub-polygon i..j has a third
 * corner k between them), the library's best-fit plane, and the
 * all-pairs crossing test of a polyline in exact integers. */
#include "selfx_polygon.h"

#include <assert.h>
#include <math.h>

#include "geometry/geometry_internal.h"

uint32_t sx_num_candidates(uint32_t n)
{
    return n * (n - 1) * (n - 2) / 6;
}

uint32_t sx_candidate_index(uint32_t i, uint32_t j, uint32_t k)
{
    assert(i < j && j < k);
    return k * (k - 1) * (k - 2) / 6 + j * (j - 1) / 2 + i;
}

bool sx_has_unmarked_triangulation(uint32_t n, const bool *marked)
{
    assert(n >= 3 && n <= SX_MAX_POLYGON);
    /* clean[i][j]: sub-polygon i, i+1, .., j has a triangulation avoiding
     * the marked triangles (true for a single side). */
    bool clean[SX_MAX_POLYGON][SX_MAX_POLYGON] = {{false}};
    for (uint32_t i = 0; i + 1 < n; i++) clean[i][i + 1] = true;
    for (uint32_t len = 2; len < n; len++) {
        for (uint32_t i = 0; i + len < n; i++) {
            uint32_t j = i + len;
            for (uint32_t k = i + 1; k < j && !clean[i][j]; k++)
                clean[i][j] = !marked[sx_candidate_index(i, k, j)] && clean[i][k] && clean[k][j];
        }
    }
    return clean[0][n - 1];
}

typedef struct enumeration {
    uint32_t n;
    uint32_t tris[SX_MAX_POLYGON];
    uint32_t num_tris;
    uint32_t pending[2 * SX_MAX_POLYGON][2]; /* sub-polygons still to triangulate */
    uint32_t num_pending;
    bool (*visit)(const uint32_t *tris, void *ctx);
    void *ctx;
} enumeration;

static bool enumerate(enumeration *e)
{
    if (e->num_pending == 0) return e->visit(e->tris, e->ctx);
    e->num_pending--;
    const uint32_t i = e->pending[e->num_pending][0], j = e->pending[e->num_pending][1];
    bool go_on = true;
    if (j - i < 2) {
        go_on = enumerate(e);
    } else {
        for (uint32_t k = i + 1; k < j && go_on; k++) {
            e->tris[e->num_tris++] = sx_candidate_index(i, k, j);
            e->pending[e->num_pending][0] = i;
            e->pending[e->num_pending][1] = k;
            e->pending[e->num_pending + 1][0] = k;
            e->pending[e->num_pending + 1][1] = j;
            e->num_pending += 2;
            go_on = enumerate(e);
            e->num_pending -= 2;
            e->num_tris--;
        }
    }
    e->pending[e->num_pending][0] = i;
    e->pending[e->num_pending][1] = j;
    e->num_pending++;
    return go_on;
}

bool sx_each_triangulation(uint32_t n, bool (*visit)(const uint32_t *tris, void *ctx), void *ctx)
{
    assert(n >= 3 && n <= SX_MAX_POLYGON);
    enumeration e = {.n = n, .num_tris = 0, .num_pending = 1, .visit = visit, .ctx = ctx};
    e.pending[0][0] = 0;
    e.pending[0][1] = n - 1;
    return enumerate(&e);
}

/* ---- the library's plane: the projection is the library's choice, taken
 * from it (mt__polygon_plane); the crossings are decided here ------------- */

void sx_polygon_plane(const double *const *corner, uint32_t n, int *out_drop, double *out_warp)
{
    mt__polygon_plane(corner, n, out_drop, out_warp);
}

/* ---- crossings, exactly ----------------------------------------------------- */

bool sx_polyline_sides_meet(sx_pool *pool, const sx_vec *pts, uint32_t n, uint32_t i, uint32_t j)
{
    assert(i != j && i < n && j < n);
    if ((i + 1) % n == j) return sx_sides_fold(pool, pts[i], pts[j], pts[(j + 1) % n]);
    if ((j + 1) % n == i) return sx_sides_fold(pool, pts[j], pts[i], pts[(i + 1) % n]);
    return sx_segments_meet(pool, pts[i], pts[(i + 1) % n], pts[j], pts[(j + 1) % n]);
}

/* Whether the boxes of sides i and j overlap (closed). */
static bool side_boxes_overlap(const double (*xy)[2], uint32_t n, uint32_t i, uint32_t j)
{
    const double *a = xy[i], *b = xy[(i + 1) % n], *c = xy[j], *d = xy[(j + 1) % n];
    for (int k = 0; k < 2; k++)
        if (fmax(a[k], b[k]) < fmin(c[k], d[k]) || fmax(c[k], d[k]) < fmin(a[k], b[k]))
            return false;
    return true;
}

bool sx_polyline_crosses(sx_pool *pool, const sx_vec *pts, const double (*xy)[2], uint32_t n,
                         uint32_t *out_a, uint32_t *out_b)
{
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = i + 1; j < n; j++)
            if (side_boxes_overlap(xy, n, i, j) && sx_polyline_sides_meet(pool, pts, n, i, j)) {
                *out_a = i;
                *out_b = j;
                return true;
            }
    return false;
}
