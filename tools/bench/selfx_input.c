/* The meshes of `meshtopo-bench selfx`, each a generator's mesh with a few
 * hundred self-intersections planted by moving vertices (the faces are left
 * as they are, so every face pair that meets does so through the surface):
 *   - a grid with a breaking wave: a round bump whose crest is carried
 *     sideways beyond the bump and down through the flat grid, folding the
 *     bump through itself on the way;
 *   - a torus with fingers: round patches of the outer equator pushed
 *     straight towards the hole, through the tube and out of its inner wall.
 * Moved vertices also get a small pseudo-random offset, so that no contact is
 * an exact tie (a vertex exactly on another face). And the polygon mesh the
 * rate of mt_mesh_nonsimple_faces is measured on: the dual of an icosphere. */
#include <math.h>
#include <string.h>

#include "bench_selfx.h"
#include "meshtopo/generate.h"

#define TWO_PI 6.283185307179586476925286766559

/* Fingers pushed through the torus, their radius on the surface and how far
 * they go towards the axis (the tube's outer equator is at 1.25, its inner
 * wall at 0.75 from the axis). */
#define TORUS_FINGERS 3
#define FINGER_RADIUS 0.05
#define FINGER_DEPTH 0.6

/* The bump profile: 1 at the centre, falling smoothly to 0 (with zero
 * slope) at distance 1. */
static double profile(double d2)
{
    return d2 < 1.0 ? (1.0 - d2) * (1.0 - d2) : 0.0;
}

/* A uniform offset in [-amplitude, amplitude]. */
static double jitter(uint64_t *state, double amplitude)
{
    double u = (double)(mt__bench_rand_u64(state) >> 11) * (1.0 / 9007199254740992.0);
    return amplitude * (2.0 * u - 1.0);
}

/* Vertex (i, j) of the grid is at (i, j, 0); cells are unit squares. The
 * bump, of radius r cells around (cx, cy), is carried 4 r along x at its
 * centre (less towards its rim) while its height goes up to r / 2 and back
 * down to -4 r: the ring where it comes back to z = 0 lies beyond the bump,
 * over flat grid, and on the way the sheet folds over itself. */
static bool grid_wave(uint64_t faces, uint64_t seed, mt_face_list *out, char *name,
                      size_t name_size, char *err, size_t err_size)
{
    double cells = (double)faces / 2.0;
    uint32_t nx = (uint32_t)floor(sqrt(cells));
    uint32_t ny = (uint32_t)floor(cells / nx + 0.5);
    mt_status st = mt_gen_grid(nx, ny, true, out);
    if (st != MT_OK) {
        snprintf(err, err_size, "mt_gen_grid(%u, %u) failed: %s", nx, ny, mt_strerror(st));
        return false;
    }
    double r = fmin(10.0, fmin(nx, ny) / 12.0);
    const double cx = nx / 4 + 0.37, cy = ny / 2 + 0.21;
    const double shift = 4.0 * r, height = 4.0 * r;
    uint64_t rng = seed;
    for (uint32_t v = 0; v < out->num_verts; v++) {
        double *p = out->positions + 3 * (size_t)v;
        double dx = (p[0] - cx) / r, dy = (p[1] - cy) / r;
        double w = profile(dx * dx + dy * dy);
        if (w == 0.0) continue;
        p[0] += shift * w + jitter(&rng, 1e-3 * w);
        p[1] += jitter(&rng, 1e-3 * w);
        p[2] = height * w * (1.0 - 2.0 * w) + jitter(&rng, 1e-3 * w);
    }
    snprintf(name, name_size, "grid %ux%u, wave r=%.0f", nx, ny, r);
    return true;
}

/* Vertex (i, j) of the torus is at angle 2 pi i / nu around the axis and
 * 2 pi j / nv around the tube (j = 0: the outer equator). Each finger is a
 * patch of the outer equator, centred between vertices, moved parallel to
 * the direction from its centre to the axis by up to FINGER_DEPTH. */
static bool torus_fingers(uint64_t faces, uint64_t seed, mt_face_list *out, char *name,
                          size_t name_size, char *err, size_t err_size)
{
    double cells = (double)faces / 2.0;
    uint32_t nv = (uint32_t)fmax(3.0, floor(sqrt(cells / 4.0)));
    uint32_t nu = (uint32_t)fmax(3.0, floor(cells / nv + 0.5));
    mt_status st = mt_gen_torus(nu, nv, out);
    if (st != MT_OK) {
        snprintf(err, err_size, "mt_gen_torus(%u, %u) failed: %s", nu, nv, mt_strerror(st));
        return false;
    }
    const double major = 1.0, minor = 0.25;
    uint64_t rng = seed;
    for (uint32_t k = 0; k < TORUS_FINGERS; k++) {
        /* The centre, in cells: a third of the way round per finger, a
         * fraction of a cell off every vertex. */
        double ci = nu * (k + 0.15) / TORUS_FINGERS + 0.37, cj = 0.29;
        double theta0 = TWO_PI * ci / nu;
        double dir[2] = {-cos(theta0), -sin(theta0)};
        /* The patch's reach in cells, each way: its radius over a cell's
         * length on the outer equator. */
        double reach_i = FINGER_RADIUS / ((major + minor) * TWO_PI / nu);
        double reach_j = FINGER_RADIUS / (minor * TWO_PI / nv);
        double jitter_size = 1e-3 * FINGER_RADIUS;
        for (int64_t dj = (int64_t)floor(-reach_j - 1); dj <= (int64_t)ceil(reach_j + 1); dj++) {
            for (int64_t di = (int64_t)floor(ci - reach_i - 1);
                 di <= (int64_t)ceil(ci + reach_i + 1); di++) {
                uint32_t i = (uint32_t)((di % nu + nu) % nu);
                uint32_t j = (uint32_t)((dj % nv + nv) % nv);
                double u = ((double)di - ci) / reach_i, t = ((double)dj - cj) / reach_j;
                double w = profile(u * u + t * t);
                if (w == 0.0) continue;
                double *p = out->positions + 3 * ((size_t)j * nu + i);
                p[0] += FINGER_DEPTH * w * dir[0] + jitter(&rng, jitter_size * w);
                p[1] += FINGER_DEPTH * w * dir[1] + jitter(&rng, jitter_size * w);
                p[2] += jitter(&rng, jitter_size * w);
            }
        }
    }
    snprintf(name, name_size, "torus %ux%u, %d fingers", nu, nv, TORUS_FINGERS);
    return true;
}

bool mt__selfx_mesh_make(uint32_t which, uint64_t faces, uint64_t seed, mt_face_list *out,
                         char *name, size_t name_size, char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    if (which == 0) return grid_wave(faces, seed, out, name, name_size, err, err_size);
    return torus_fingers(faces, seed, out, name, name_size, err, err_size);
}

bool mt__selfx_polygon_mesh_make(uint64_t faces, mt_mesh **out, char *name, size_t name_size,
                                 char *err, size_t err_size)
{
    *out = NULL;
    uint32_t level = 1;
    while (level < 10 && 10ull * (1ull << (2 * (level + 1))) + 2 <= faces) level++;
    mt_face_list sphere, dual;
    mt_mesh *sphere_mesh = NULL;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_gen_icosphere(level, &sphere);
    if (st == MT_OK) {
        st = mt_mesh_build(&sphere, NULL, &sphere_mesh, &diag);
        mt_face_list_free(&sphere);
    }
    if (st == MT_OK) {
        st = mt_gen_dual(sphere_mesh, &dual, &diag);
        mt_mesh_destroy(sphere_mesh);
    }
    if (st == MT_OK) {
        st = mt_mesh_build(&dual, NULL, out, &diag);
        mt_face_list_free(&dual);
    }
    if (st != MT_OK) {
        snprintf(err, err_size, "dual of icosphere level %u: %s %s", level, mt_strerror(st),
                 diag.message);
        return false;
    }
    snprintf(name, name_size, "dual of icosphere %u", level);
    return true;
}
