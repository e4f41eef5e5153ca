/* Whether a mesh bounds a convex polytope. Topology comes from the build's
 * report (closed, manifold, orientable and consistently oriented, one
 * component, Euler characteristic 2 without isolated vertices); geometry from
 * one sweep over faces (degenerate ones, signed volume by the divergence
 * theorem), edges (reflex ones, listed) and vertices (negative deficits). A
 * closed surface locally convex at every edge and vertex bounds a convex body
 * (J. van Heijenoort, "On locally convex manifolds", CPAM 1952). */
#include <stdio.h>
#include <string.h>

#include "geometry/geometry_internal.h"
#include "meshtopo/geometry.h"

/* The reflex edges (listed up to capacity) and how many edges of each shape. */
typedef struct reflex_list {
    uint32_t *edges;
    size_t capacity, count;
    size_t shapes[MT_EDGE_DEGENERATE + 1];
} reflex_list;

static void collect_reflex(void *user, uint32_t a, uint32_t b, mt_edge_shape shape, double angle)
{
    (void)angle;
    reflex_list *l = user;
    if ((unsigned)shape <= MT_EDGE_DEGENERATE) l->shapes[shape]++;
    if (shape != MT_EDGE_REFLEX) return;
    if (l->edges && l->count < l->capacity) {
        l->edges[2 * l->count] = a;
        l->edges[2 * l->count + 1] = b;
    }
    l->count++;
}

/* Degenerate live faces and six times the signed volume (relative to the
 * first vertex of the first live face, to keep digits on far-off meshes). */
static mt_status face_sweep(const mt_mesh *m, size_t *out_live, size_t *out_degenerate,
                            double *out_volume6, mt_diag *diag)
{
    const double *origin = NULL;
    double vol6 = 0.0;
    size_t live = 0, degenerate = 0;
    for (uint32_t f = 0; f < m->num_faces; f++) {
        uint32_t start = m->face_he[f];
        if (start == MT_NONE) continue;
        double a2[3];
        uint32_t size;
        if (mt__face_ring_area2(m, start, a2, &size) != MT_OK)
            return mt__fail(diag, MT_ERR_CORRUPT, f, "mt_mesh_convexity: face %u's ring is broken",
                            f);
        live++;
        double n[3];
        if (!mt__unit(a2, n)) degenerate++;
        const double *p0 = mt__geom_pos(m, m->he_head[start ^ 1u]);
        if (!origin) origin = p0;
        /* det(p0 - o, p_i - o, p_i+1 - o) over the fan = (p0 - o) . (twice the vector area) */
        double d[3];
        mt__v3_sub(p0, origin, d);
        vol6 += mt__v3_dot(d, a2);
    }
    *out_live = live;
    *out_degenerate = degenerate;
    *out_volume6 = vol6;
    return MT_OK;
}

/* Vertices not on the boundary whose deficit is below -tol. */
static mt_status saddle_count(const mt_mesh *m, double tol, size_t *out_count, mt_diag *diag)
{
    size_t n = m->num_verts;
    double *deficits = mt__calloc(n, sizeof *deficits);
    bool *boundary = mt__calloc(n, sizeof *boundary);
    mt_status s = MT_OK;
    *out_count = 0;
    if (!deficits || !boundary) {
        s = mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "mt_mesh_convexity: out of memory");
    } else if (n > 0) {
        size_t count;
        s = mt_mesh_vert_curvature(m, NULL, deficits, boundary, n, &count, diag);
        for (size_t v = 0; s == MT_OK && v < n; v++)
            if (!boundary[v] && deficits[v] < -tol) ++*out_count;
    }
    mt__free(deficits);
    mt__free(boundary);
    return s;
}

mt_status mt_mesh_convexity(const mt_mesh *mesh, double tolerance, mt_convexity *out,
                            uint32_t *out_reflex_edges, size_t capacity, mt_diag *diag)
{
    const char *what = "mt_mesh_convexity";
    mt_status s = mt__geom_ready(mesh, what, diag);
    if (s != MT_OK) return s;
    if (!out) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: out is NULL", what);
    if (!(tolerance >= 0.0))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: tolerance %g is not >= 0", what,
                        tolerance);
    const mt_report *r = &mesh->report;
    mt_convexity c;
    memset(&c, 0, sizeof c);

    size_t live = 0, saddles = 0;
    double vol6 = 0.0;
    s = face_sweep(mesh, &live, &c.num_degenerate, &vol6, diag);
    if (s != MT_OK) return s;
    reflex_list list = {
        mt__buffer_absent(out_reflex_edges, capacity) ? NULL : out_reflex_edges, capacity, 0, {0}};
    s = mt__edge_sweep(mesh, tolerance, what, collect_reflex, &list, diag);
    if (s != MT_OK) return s;
    s = saddle_count(mesh, tolerance, &saddles, diag);
    if (s != MT_OK) return s;
    c.num_reflex = list.count;

    /* Edge defects are judged on the current structure (edits keep it
     * current, not every report field); the rest comes from the report. */
    bool closed = r->closed && list.shapes[MT_EDGE_BOUNDARY] == 0;
    bool consistent =
        r->orientable && r->consistently_oriented && list.shapes[MT_EDGE_INCONSISTENT] == 0;
    if (live == 0) c.reasons |= MT_NONCONVEX_EMPTY;
    if (!closed) c.reasons |= MT_NONCONVEX_OPEN;
    if (!r->manifold || r->nonmanifold_edges || r->nonmanifold_vertices ||
        list.shapes[MT_EDGE_NONMANIFOLD])
        c.reasons |= MT_NONCONVEX_NONMANIFOLD;
    if (!consistent) c.reasons |= MT_NONCONVEX_INCONSISTENT;
    if (r->connected_components > 1) c.reasons |= MT_NONCONVEX_COMPONENTS;
    if (live > 0 && r->euler_characteristic - (int64_t)r->isolated_vertices != 2)
        c.reasons |= MT_NONCONVEX_NOT_SPHERE;
    if (c.num_degenerate) c.reasons |= MT_NONCONVEX_DEGENERATE_FACE;
    if (c.num_reflex) c.reasons |= MT_NONCONVEX_REFLEX_EDGE;
    if (saddles) c.reasons |= MT_NONCONVEX_SADDLE_VERTEX;
    if (closed && live > 0) {
        c.volume = vol6 / 6.0;
        if (consistent && !(c.volume > 0.0)) c.reasons |= MT_NONCONVEX_INWARD;
    }
    c.convex = c.reasons == 0;
    *out = c;
    if (list.edges && list.count > capacity)
        return mt__fail(diag, MT_ERR_BUFFER_TOO_SMALL, MT_NONE,
                        "%s: %zu reflex edges, room for %zu", what, list.count, capacity);
    return MT_OK;
}

size_t mt_convexity_describe(uint32_t reasons, char *buf, size_t size)
{
    static const char *const names[] = {
        "empty",         "open",       "nonmanifold",     "inconsistent_orientation",
        "components",    "not_sphere", "degenerate_face", "reflex_edge",
        "saddle_vertex", "inward",
    };
    if (buf && size) buf[0] = '\0';
    if (reasons == 0) return (size_t)snprintf(buf, buf ? size : 0, "convex");
    size_t len = 0;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        if (!(reasons & (1u << i))) continue;
        const char *sep = len ? ", " : "";
        int k = snprintf(buf && len < size ? buf + len : NULL, buf && len < size ? size - len : 0,
                         "%s%s", sep, names[i]);
        if (k > 0) len += (size_t)k;
    }
    if (reasons >> (sizeof names / sizeof names[0])) {
        int k = snprintf(buf && len < size ? buf + len : NULL, buf && len < size ? size - len : 0,
                         "%sunknown", len ? ", " : "");
        if (k > 0) len += (size_t)k;
    }
    return len;
}
