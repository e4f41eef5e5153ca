/* Helpers for the geometry tests: building and validating meshes, a random
 * source, angle checks, and an incremental convex hull (Clarkson-Shor style
 * without conflict lists: each point is tested against every current face,
 * the visible faces are removed and the horizon is coned to the point). */
#include "geometry_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"

mt_mesh *geom_build(const mt_face_list *list, const char *what)
{
    mt_mesh *mesh = NULL;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status s = mt_mesh_build(list, NULL, &mesh, &diag);
    if (s != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: mt_mesh_build: %s (%s)", what, mt_strerror(s),
                     diag.message);
        return NULL;
    }
    s = mt_mesh_validate(mesh, &diag);
    if (s != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "%s: mt_mesh_validate: %s (%s)", what, mt_strerror(s),
                     diag.message);
        mt_mesh_destroy(mesh);
        return NULL;
    }
    return mesh;
}

mt_mesh *geom_build_arrays(uint32_t num_verts, const double *positions, uint32_t num_faces,
                           const uint32_t *sizes, const uint32_t *indices, const char *what)
{
    uint64_t num_indices = 0;
    for (uint32_t f = 0; f < num_faces; f++) num_indices += sizes[f];
    mt_face_list list = {num_verts,           num_faces,         num_indices,
                         (double *)positions, (uint32_t *)sizes, (uint32_t *)indices};
    return geom_build(&list, what);
}

mt_mesh *geom_build_platonic(int kind)
{
    mt_face_list list;
    if (mt_gen_platonic((mt_platonic)kind, &list) != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "mt_gen_platonic(%d) failed", kind);
        return NULL;
    }
    mt_mesh *mesh = geom_build(&list, "platonic solid");
    mt_face_list_free(&list);
    return mesh;
}

void geom_check_near(double got, double want, double tol, const char *expr, const char *file,
                     int line)
{
    if (!(fabs(got - want) <= tol))
        mt_test_fail(file, line, "%s = %.17g, expected %.17g (tolerance %g)", expr, got, want, tol);
}

double geom_random(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1.0p-53;
}

/* ---- convex hull ---------------------------------------------------------- */

typedef struct tri {
    uint32_t v[3];
} tri;

/* Six times the signed volume of (a, b, c, d): positive when d is on the
 * side a, b, c's counter-clockwise normal points to. */
static double orient(const double *a, const double *b, const double *c, const double *d)
{
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
}

int geom_convex_hull(const double *points, uint32_t n, mt_face_list *out)
{
    memset(out, 0, sizeof *out);
    if (n < 4) return 0;
#define P(i) (points + 3 * (size_t)(i))
    /* A first tetrahedron: 0, 1, then the points farthest from line and plane. */
    uint32_t i2 = MT_NONE, i3 = MT_NONE;
    double best = 0.0;
    for (uint32_t i = 2; i < n; i++) {
        double u[3] = {P(1)[0] - P(0)[0], P(1)[1] - P(0)[1], P(1)[2] - P(0)[2]};
        double w[3] = {P(i)[0] - P(0)[0], P(i)[1] - P(0)[1], P(i)[2] - P(0)[2]};
        double c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                       u[0] * w[1] - u[1] * w[0]};
        double d = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        if (d > best) best = d, i2 = i;
    }
    best = 0.0;
    for (uint32_t i = 2; i2 != MT_NONE && i < n; i++) {
        double d = fabs(orient(P(0), P(1), P(i2), P(i)));
        if (d > best) best = d, i3 = i;
    }
    if (i3 == MT_NONE) return 0;
    size_t cap = 8 * (size_t)n + 8, count = 0;
    tri *faces = malloc(cap * sizeof *faces);
    unsigned char *visible = calloc(cap, 1);
    unsigned char *marked = calloc((size_t)n * n, 1); /* directed edge of a visible face */
    unsigned char *on_hull = calloc(n, 1);
    int ok = faces && visible && marked && on_hull;
    if (ok) {
        uint32_t t[4] = {0, 1, i2, i3};
        if (orient(P(0), P(1), P(i2), P(i3)) > 0) t[1] = i2, t[2] = 1; /* i3 below (0, 1, i2) */
        faces[count++] = (tri){{t[0], t[1], t[2]}};
        faces[count++] = (tri){{t[0], t[3], t[1]}};
        faces[count++] = (tri){{t[1], t[3], t[2]}};
        faces[count++] = (tri){{t[2], t[3], t[0]}};
    }
    for (uint32_t p = 0; ok && p < n; p++) {
        if (p == 0 || p == 1 || p == i2 || p == i3) continue;
        size_t num_visible = 0;
        for (size_t f = 0; f < count; f++) {
            const tri *t = &faces[f];
            visible[f] = orient(P(t->v[0]), P(t->v[1]), P(t->v[2]), P(p)) > 1e-12;
            if (!visible[f]) continue;
            num_visible++;
            for (int k = 0; k < 3; k++) marked[(size_t)t->v[k] * n + t->v[(k + 1) % 3]] = 1;
        }
        if (num_visible == 0) continue;
        /* Cone the horizon (a visible side whose twin is hidden) to p, clear
         * the marks, then drop the visible faces. */
        tri *horizon = malloc(3 * num_visible * sizeof *horizon);
        size_t num_horizon = 0, kept = 0;
        if (!horizon) {
            ok = 0;
            break;
        }
        for (size_t f = 0; f < count; f++) {
            if (!visible[f]) continue;
            for (int k = 0; k < 3; k++) {
                uint32_t a = faces[f].v[k], b = faces[f].v[(k + 1) % 3];
                if (!marked[(size_t)b * n + a]) horizon[num_horizon++] = (tri){{a, b, p}};
            }
        }
        for (size_t f = 0; f < count; f++) {
            if (!visible[f]) {
                faces[kept++] = faces[f];
                continue;
            }
            for (int k = 0; k < 3; k++)
                marked[(size_t)faces[f].v[k] * n + faces[f].v[(k + 1) % 3]] = 0;
        }
        count = kept;
        for (size_t h = 0; h < num_horizon && count < cap; h++) faces[count++] = horizon[h];
        free(horizon);
        if (count >= cap) ok = 0;
    }
    if (ok) {
        /* Renumber the hull's points 0 .. nv-1 in input order. */
        uint32_t *ids = malloc(n * sizeof *ids);
        uint32_t nv = 0;
        for (size_t f = 0; f < count; f++)
            for (int k = 0; k < 3; k++) on_hull[faces[f].v[k]] = 1;
        ok = ids != NULL;
        for (uint32_t i = 0; ok && i < n; i++) ids[i] = on_hull[i] ? nv++ : MT_NONE;
        ok = ok && mt_face_list_alloc(out, nv, (uint32_t)count, 3 * (uint64_t)count, NULL) == MT_OK;
        for (uint32_t i = 0; ok && i < n; i++)
            if (ids[i] != MT_NONE)
                memcpy(out->positions + 3 * (size_t)ids[i], P(i), 3 * sizeof(double));
        for (size_t f = 0; ok && f < count; f++) {
            out->face_sizes[f] = 3;
            for (int k = 0; k < 3; k++) out->face_indices[3 * f + k] = ids[faces[f].v[k]];
        }
        free(ids);
    }
#undef P
    free(faces);
    free(visible);
    free(marked);
    free(on_hull);
    return ok;
}
