/* Edge geometry: the interior dihedral angle of an edge and whether it is
 * convex, flat or reflex. With unit normals n1 (face on half-edge h, running
 * along e) and n2 (the face across), the signed bend is
 * atan2((n1 x n2) . e / |e|, n1 . n2), positive for a ridge, and the interior
 * angle is pi minus it, in [0, 2 pi). An edge has one only with exactly two
 * faces crossing it in opposite directions, both non-degenerate. One edge is
 * found through mt_edge_faces; the sweep visits each internal edge once. */
#include <math.h>
#include <string.h>

#include "geometry/geometry_internal.h"
#include "meshtopo/geometry.h"
#include "meshtopo/query.h"

const char *mt_edge_shape_name(mt_edge_shape shape)
{
    switch (shape) {
        case MT_EDGE_CONVEX:
            return "convex";
        case MT_EDGE_FLAT:
            return "flat";
        case MT_EDGE_REFLEX:
            return "reflex";
        case MT_EDGE_BOUNDARY:
            return "boundary";
        case MT_EDGE_NONMANIFOLD:
            return "nonmanifold";
        case MT_EDGE_INCONSISTENT:
            return "inconsistent";
        case MT_EDGE_DEGENERATE:
            return "degenerate";
    }
    return "unknown";
}

/* Unit normal of face f into n, from the sweep's cache when there is one;
 * false when degenerate (or the ring is broken: *corrupt is set). */
static bool face_normal(const mt_mesh *m, const double *cache, uint32_t f, double n[3],
                        bool *corrupt)
{
    if (cache) {
        memcpy(n, cache + 3 * (size_t)f, 3 * sizeof *n);
        return n[0] != 0.0 || n[1] != 0.0 || n[2] != 0.0;
    }
    uint32_t size;
    bool ok;
    if (mt__face_unit_normal(m, f, n, &size, &ok) != MT_OK) *corrupt = true;
    return ok;
}

/* Bend of the edge between face half-edges h1 and h2 (each with a face):
 * its shape under tol and, when it has one, its interior angle. */
static mt_status bend(const mt_mesh *m, const double *cache, uint32_t h1, uint32_t h2, double tol,
                      mt_edge_shape *out_shape, double *out_angle)
{
    *out_angle = 0.0;
    uint32_t t1 = mt__original_checked(m, m->he_head[h1 ^ 1u]);
    uint32_t t2 = mt__original_checked(m, m->he_head[h2 ^ 1u]);
    if (t1 == MT_NONE || t2 == MT_NONE) return MT_ERR_CORRUPT;
    if (t1 == t2) {
        *out_shape = MT_EDGE_INCONSISTENT;
        return MT_OK;
    }
    double n1[3], n2[3];
    bool corrupt = false;
    bool ok1 = face_normal(m, cache, m->he_face[h1], n1, &corrupt);
    bool ok2 = face_normal(m, cache, m->he_face[h2], n2, &corrupt);
    if (corrupt) return MT_ERR_CORRUPT;
    if (!ok1 || !ok2) {
        *out_shape = MT_EDGE_DEGENERATE;
        return MT_OK;
    }
    double e[3], c[3];
    mt__v3_sub(mt__geom_pos(m, m->he_head[h1]), mt__geom_pos(m, m->he_head[h1 ^ 1u]), e);
    mt__v3_cross(n1, n2, c);
    double len = sqrt(mt__v3_dot(e, e));
    double y = len > 0.0 ? mt__v3_dot(c, e) / len : 0.0;
    double phi = atan2(y, mt__v3_dot(n1, n2));
    *out_angle = MT__PI - phi;
    *out_shape = phi > tol ? MT_EDGE_CONVEX : phi < -tol ? MT_EDGE_REFLEX : MT_EDGE_FLAT;
    return MT_OK;
}

/* Half-edge of face f joining caller vertices a and b (either way), MT_NONE
 * when there is none or the ring is broken. */
static uint32_t face_side(const mt_mesh *m, uint32_t f, uint32_t a, uint32_t b)
{
    uint32_t start = m->face_he[f];
    if (start == MT_NONE || !mt__he_ok(m, start)) return MT_NONE;
    uint32_t h = start, steps = 0;
    do {
        uint32_t t = mt__original_checked(m, m->he_head[h ^ 1u]);
        uint32_t d = mt__original_checked(m, m->he_head[h]);
        if ((t == a && d == b) || (t == b && d == a)) return h;
        if (!mt__ring_step(m, &h, &steps)) return MT_NONE;
    } while (h != start);
    return MT_NONE;
}

/* Shape and angle of caller edge {a, b}, with the errors of the public calls. */
static mt_status edge_bend(const mt_mesh *m, uint32_t a, uint32_t b, double tol, const char *what,
                           mt_edge_shape *out_shape, double *out_angle, mt_diag *diag)
{
    mt_status s = mt__geom_ready(m, what, diag);
    if (s != MT_OK) return s;
    if (a >= m->num_verts || b >= m->num_verts)
        return mt__fail(diag, MT_ERR_OUT_OF_RANGE, a >= m->num_verts ? a : b,
                        "%s: vertex %u out of range (%u vertices)", what, a >= m->num_verts ? a : b,
                        m->num_verts);
    uint32_t faces[3];
    size_t count = 0;
    s = mt_edge_faces(m, a, b, faces, 3, &count);
    if (s == MT_ERR_NOT_FOUND)
        return mt__fail(diag, s, a, "%s: no face has the edge %u-%u", what, a, b);
    if (s == MT_ERR_BUFFER_TOO_SMALL || (s == MT_OK && count > 2)) {
        *out_shape = MT_EDGE_NONMANIFOLD;
        *out_angle = 0.0;
        return MT_OK;
    }
    if (s != MT_OK) return mt__fail(diag, s, a, "%s: edge %u-%u: %s", what, a, b, mt_strerror(s));
    *out_angle = 0.0;
    if (count == 1) {
        *out_shape = MT_EDGE_BOUNDARY;
        return MT_OK;
    }
    uint32_t h1 = face_side(m, faces[0], a, b), h2 = face_side(m, faces[1], a, b);
    if (h1 == MT_NONE || h2 == MT_NONE || bend(m, NULL, h1, h2, tol, out_shape, out_angle) != MT_OK)
        return mt__fail(diag, MT_ERR_CORRUPT, a, "%s: broken face ring at edge %u-%u", what, a, b);
    return MT_OK;
}

mt_status mt_edge_dihedral_angle(const mt_mesh *mesh, uint32_t a, uint32_t b, double *out_angle,
                                 mt_diag *diag)
{
    const char *what = "mt_edge_dihedral_angle";
    if (!out_angle)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: out_angle is NULL", what);
    mt_edge_shape shape;
    double angle;
    mt_status s = edge_bend(mesh, a, b, 0.0, what, &shape, &angle, diag);
    if (s != MT_OK) return s;
    if (shape > MT_EDGE_REFLEX)
        return mt__fail(diag, MT_ERR_UNSUPPORTED, a, "%s: edge %u-%u is %s: no dihedral angle",
                        what, a, b, mt_edge_shape_name(shape));
    *out_angle = angle;
    return MT_OK;
}

mt_status mt_edge_convexity(const mt_mesh *mesh, uint32_t a, uint32_t b, double tolerance,
                            mt_edge_shape *out_shape, mt_diag *diag)
{
    const char *what = "mt_edge_convexity";
    if (!out_shape)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: out_shape is NULL", what);
    if (!(tolerance >= 0.0))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: tolerance %g is not >= 0", what,
                        tolerance);
    double angle;
    return edge_bend(mesh, a, b, tolerance, what, out_shape, &angle, diag);
}

/* ---- every edge ---------------------------------------------------------- */

/* Shape and angle of the caller edge held by internal edge e; false in
 * *out_listed when e is not the edge's first internal edge (or deleted). */
static mt_status sweep_edge(const mt_mesh *m, const double *cache, uint32_t e, double tol,
                            bool *out_listed, mt_edge_shape *out_shape, double *out_angle)
{
    *out_listed = false;
    *out_angle = 0.0;
    if (m->he_head[2 * e] == MT_NONE || m->he_head[2 * e + 1] == MT_NONE) return MT_OK;
    uint32_t b = m->num_bundles ? mt__edge_bundle(m, e) : MT_NONE;
    uint32_t sides[2], count = 0;
    if (b == MT_NONE) {
        for (uint32_t side = 0; side < 2; side++)
            if (m->he_face[2 * e + side] != MT_NONE) sides[count++] = 2 * e + side;
    } else {
        uint32_t begin, end;
        if (!mt__bundle_range(m, b, &begin, &end) || begin == end) return MT_ERR_CORRUPT;
        if (m->bundle_edges[begin] != e) return MT_OK;
        for (uint32_t k = begin; k < end; k++) {
            uint32_t g = m->bundle_edges[k];
            if (g >= m->num_half_edges / 2) return MT_ERR_CORRUPT;
            for (uint32_t side = 0; side < 2; side++) {
                if (m->he_face[2 * g + side] == MT_NONE) continue;
                if (count < 2) sides[count] = 2 * g + side;
                count++;
            }
        }
    }
    *out_listed = true;
    if (count > 2) {
        *out_shape = MT_EDGE_NONMANIFOLD;
        return MT_OK;
    }
    if (count < 2) {
        *out_shape = MT_EDGE_BOUNDARY;
        return MT_OK;
    }
    return bend(m, cache, sides[0], sides[1], tol, out_shape, out_angle);
}

mt_status mt__edge_sweep(const mt_mesh *m, double tol, const char *what, mt__edge_visit visit,
                         void *user, mt_diag *diag)
{
    double *cache = NULL;
    size_t bytes;
    if (m->num_faces && mt__mul_size(m->num_faces, 3 * sizeof *cache, &bytes))
        cache = mt__malloc(bytes);
    if (m->num_faces && !cache)
        return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "%s: out of memory", what);
    mt_status s = MT_OK;
    for (uint32_t f = 0; f < m->num_faces && s == MT_OK; f++) {
        uint32_t size;
        bool ok;
        double *n = cache + 3 * (size_t)f;
        n[0] = n[1] = n[2] = 0.0;
        if (m->face_he[f] != MT_NONE && mt__face_unit_normal(m, f, n, &size, &ok) != MT_OK)
            s = mt__fail(diag, MT_ERR_CORRUPT, f, "%s: face %u's ring is broken", what, f);
    }
    for (uint32_t e = 0; e < m->num_half_edges / 2 && s == MT_OK; e++) {
        bool listed;
        mt_edge_shape shape;
        double angle;
        s = sweep_edge(m, cache, e, tol, &listed, &shape, &angle);
        if (s != MT_OK) {
            s = mt__fail(diag, MT_ERR_CORRUPT, e, "%s: internal edge %u is broken", what, e);
            break;
        }
        if (!listed) continue;
        uint32_t a = mt__original_checked(m, m->he_head[2 * e + 1]);
        uint32_t b = mt__original_checked(m, m->he_head[2 * e]);
        if (a == MT_NONE || b == MT_NONE) {
            s = mt__fail(diag, MT_ERR_CORRUPT, e, "%s: internal edge %u has a bad vertex", what, e);
            break;
        }
        if (a > b) {
            uint32_t t = a;
            a = b;
            b = t;
        }
        visit(user, a, b, shape, angle);
    }
    mt__free(cache);
    return s;
}

typedef struct angle_out {
    uint32_t *edges;
    double *angles;
    mt_edge_shape *shapes;
    size_t n, capacity;
} angle_out;

static void write_edge(void *user, uint32_t a, uint32_t b, mt_edge_shape shape, double angle)
{
    angle_out *o = user;
    if (o->n >= o->capacity) return; /* only on a mesh corrupted between the passes */
    if (o->edges) {
        o->edges[2 * o->n] = a;
        o->edges[2 * o->n + 1] = b;
    }
    if (o->angles) o->angles[o->n] = angle;
    if (o->shapes) o->shapes[o->n] = shape;
    o->n++;
}

mt_status mt_mesh_dihedral_angles(const mt_mesh *mesh, double tolerance, uint32_t *out_edges,
                                  double *out_angles, mt_edge_shape *out_shapes, size_t capacity,
                                  size_t *out_count, mt_diag *diag)
{
    const char *what = "mt_mesh_dihedral_angles";
    mt_status s = mt__geom_ready(mesh, what, diag);
    if (s != MT_OK) return s;
    if (!out_count)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: out_count is NULL", what);
    if (!(tolerance >= 0.0))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: tolerance %g is not >= 0", what,
                        tolerance);
    /* Counting needs no normals: an edge is listed once whatever its shape. */
    size_t n = 0;
    for (uint32_t e = 0; e < mesh->num_half_edges / 2; e++) {
        if (mesh->he_head[2 * e] == MT_NONE || mesh->he_head[2 * e + 1] == MT_NONE) continue;
        uint32_t b = mesh->num_bundles ? mt__edge_bundle(mesh, e) : MT_NONE;
        uint32_t begin, end;
        if (b != MT_NONE && mt__bundle_range(mesh, b, &begin, &end) && begin < end &&
            mesh->bundle_edges[begin] != e)
            continue;
        n++;
    }
    *out_count = n;
    if ((!out_edges && !out_angles && !out_shapes) || capacity == 0) return MT_OK;
    if (capacity < n)
        return mt__fail(diag, MT_ERR_BUFFER_TOO_SMALL, MT_NONE,
                        "%s: capacity %zu, the mesh has %zu edges", what, capacity, n);
    angle_out o = {out_edges, out_angles, out_shapes, 0, capacity};
    return mt__edge_sweep(mesh, tolerance, what, write_edge, &o, diag);
}
