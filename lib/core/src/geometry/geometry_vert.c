/* Vertex geometry: angle-weighted normals (Thuermer and Wuethrich, "Computing
 * vertex normals from polygonal facets", JGT 1998) and angle deficits (2 pi,
 * or pi on the boundary, minus the corner angles: discrete Gaussian and
 * geodesic curvature, so that their sum is 2 pi chi). One vertex walks the
 * rotation of each of its fans; the whole-mesh sweep walks every face ring
 * once and then every edge once, linear time. */
#include <math.h>

#include "geometry/geometry_internal.h"
#include "meshtopo/geometry.h"

/* A real boundary edge: one side has no face and the edge is not one of
 * several internal edges holding a non-manifold or same-direction edge. */
static bool boundary_edge(const mt_mesh *m, uint32_t h)
{
    if (m->he_face[h] != MT_NONE && m->he_face[h ^ 1u] != MT_NONE) return false;
    if (m->he_face[h] == MT_NONE && m->he_face[h ^ 1u] == MT_NONE) return false;
    return m->num_bundles == 0 || mt__edge_bundle(m, h >> 1) == MT_NONE;
}

/* Sums over every corner of caller vertex v (all its fans): corner angles
 * into *angle_sum, angle-weighted unit face normals into normal_sum; whether
 * some corner or boundary edge was seen. */
typedef struct vert_sums {
    double normal[3];
    double angles;
    bool has_face, boundary;
} vert_sums;

static mt_status vert_sum(const mt_mesh *m, uint32_t v, vert_sums *out)
{
    out->normal[0] = out->normal[1] = out->normal[2] = 0.0;
    out->angles = 0.0;
    out->has_face = out->boundary = false;
    mt__vert_walk w;
    mt__vert_walk_begin(&w, m, v);
    while (mt__vert_walk_fan(&w)) {
        do {
            const uint32_t h = w.he;
            if (boundary_edge(m, h)) out->boundary = true;
            uint32_t f = m->he_face[h];
            if (f != MT_NONE) {
                if (f >= m->num_faces) return MT_ERR_CORRUPT;
                double n[3];
                uint32_t size;
                bool ok;
                if (mt__face_ring_area2(m, h, n, &size) != MT_OK) return MT_ERR_CORRUPT;
                ok = mt__unit(n, n);
                double angle = mt__corner_angle(m, mt__he_prev(m, h), n, size);
                out->angles += angle;
                out->has_face = true;
                if (ok)
                    for (int k = 0; k < 3; k++) out->normal[k] += angle * n[k];
            }
        } while (mt__vert_walk_step(&w));
    }
    return w.status;
}

static mt_status vert_check(const mt_mesh *m, uint32_t v, const void *out, const char *what,
                            mt_diag *diag)
{
    mt_status s = mt__geom_ready(m, what, diag);
    if (s != MT_OK) return s;
    if (!out) return mt__fail(diag, MT_ERR_INVALID_ARG, v, "%s: output pointer is NULL", what);
    if (v >= m->num_verts)
        return mt__fail(diag, MT_ERR_OUT_OF_RANGE, v, "%s: vertex %u out of range (%u vertices)",
                        what, v, m->num_verts);
    return MT_OK;
}

static double deficit_of(const vert_sums *s)
{
    if (!s->has_face) return 0.0;
    return (s->boundary ? MT__PI : 2.0 * MT__PI) - s->angles;
}

mt_status mt_vert_normal(const mt_mesh *mesh, uint32_t vert, double out_normal[3], mt_diag *diag)
{
    mt_status s = vert_check(mesh, vert, out_normal, "mt_vert_normal", diag);
    if (s != MT_OK) return s;
    vert_sums sums;
    if (vert_sum(mesh, vert, &sums) != MT_OK)
        return mt__fail(diag, MT_ERR_CORRUPT, vert,
                        "mt_vert_normal: broken rotation or face ring at vertex %u", vert);
    mt__unit(sums.normal, out_normal);
    return MT_OK;
}

mt_status mt_vert_angle_deficit(const mt_mesh *mesh, uint32_t vert, double *out_deficit,
                                bool *out_boundary, mt_diag *diag)
{
    mt_status s = vert_check(mesh, vert, out_deficit, "mt_vert_angle_deficit", diag);
    if (s != MT_OK) return s;
    vert_sums sums;
    if (vert_sum(mesh, vert, &sums) != MT_OK)
        return mt__fail(diag, MT_ERR_CORRUPT, vert,
                        "mt_vert_angle_deficit: broken rotation or face ring at vertex %u", vert);
    *out_deficit = deficit_of(&sums);
    if (out_boundary) *out_boundary = sums.has_face && sums.boundary;
    return MT_OK;
}

enum { HAS_FACE = 1, ON_BOUNDARY = 2 };

/* The sweep proper; flags has num_verts zeroed bytes, angles num_verts
 * zeroed doubles, normals (or NULL) 3 * num_verts. */
static mt_status sweep(const mt_mesh *m, unsigned char *flags, double *angles, double *normals,
                       mt_diag *diag)
{
    for (uint32_t f = 0; f < m->num_faces; f++) {
        uint32_t start = m->face_he[f];
        if (start == MT_NONE) continue;
        double n[3];
        uint32_t size;
        bool ok;
        if (mt__face_unit_normal(m, f, n, &size, &ok) != MT_OK)
            return mt__fail(diag, MT_ERR_CORRUPT, f,
                            "mt_mesh_vert_curvature: face %u's ring is broken", f);
        uint32_t h = start, steps = 0;
        do {
            uint32_t v = mt__original_checked(m, m->he_head[h]);
            if (v == MT_NONE) return mt__fail(diag, MT_ERR_CORRUPT, f, "face %u: bad vertex", f);
            double angle = mt__corner_angle(m, h, n, size);
            angles[v] += angle;
            flags[v] |= HAS_FACE;
            if (normals && ok)
                for (int k = 0; k < 3; k++) normals[3 * (size_t)v + k] += angle * n[k];
            if (!mt__ring_step(m, &h, &steps))
                return mt__fail(diag, MT_ERR_CORRUPT, f, "face %u's ring is broken", f);
        } while (h != start);
    }
    for (uint32_t h = 0; h + 1 < m->num_half_edges; h += 2) {
        if (m->he_head[h] == MT_NONE || !boundary_edge(m, h)) continue;
        uint32_t a = mt__original_checked(m, m->he_head[h]);
        uint32_t b = mt__original_checked(m, m->he_head[h + 1]);
        if (a == MT_NONE || b == MT_NONE)
            return mt__fail(diag, MT_ERR_CORRUPT, h, "half-edge %u has a bad head", h);
        flags[a] |= ON_BOUNDARY;
        flags[b] |= ON_BOUNDARY;
    }
    return MT_OK;
}

mt_status mt_mesh_vert_curvature(const mt_mesh *mesh, double *out_normals, double *out_deficits,
                                 bool *out_boundary, size_t capacity, size_t *out_count,
                                 mt_diag *diag)
{
    mt_status s = mt__geom_ready(mesh, "mt_mesh_vert_curvature", diag);
    if (s != MT_OK) return s;
    if (!out_count)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "mt_mesh_vert_curvature: out_count is NULL");
    size_t n = mesh->num_verts;
    *out_count = n;
    if ((!out_normals && !out_deficits && !out_boundary) || capacity == 0) return MT_OK;
    if (capacity < n)
        return mt__fail(diag, MT_ERR_BUFFER_TOO_SMALL, MT_NONE,
                        "mt_mesh_vert_curvature: capacity %zu, the mesh has %zu vertices", capacity,
                        n);
    unsigned char *flags = mt__calloc(n, 1);
    double *angles = mt__calloc(n, sizeof *angles);
    double *normals = out_normals ? mt__calloc(n, 3 * sizeof *normals) : NULL;
    if (!flags || !angles || (out_normals && !normals)) {
        s = mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "mt_mesh_vert_curvature: out of memory");
    } else {
        s = sweep(mesh, flags, angles, normals, diag);
    }
    if (s == MT_OK) {
        for (size_t v = 0; v < n; v++) {
            vert_sums sums = {{0.0, 0.0, 0.0},
                              angles[v],
                              (flags[v] & HAS_FACE) != 0,
                              (flags[v] & ON_BOUNDARY) != 0};
            if (out_deficits) out_deficits[v] = deficit_of(&sums);
            if (out_boundary) out_boundary[v] = sums.has_face && sums.boundary;
            if (out_normals) mt__unit(normals + 3 * v, out_normals + 3 * v);
        }
    }
    mt__free(flags);
    mt__free(angles);
    mt__free(normals);
    return s;
}
