/* Face geometry: normal, area and centroid of one face or of every face.
 * A polygon's vector area is Newell's, summed over the fan from its first
 * vertex ((p[i] - p[0]) x (p[i+1] - p[0]), halved), which is exact for
 * planar polygons, convex or not, and translation-robust; the normal is the
 * vector area normalised (the zero vector for a degenerate face), the area
 * its length. Time linear in the face size; no allocation. */
#include <math.h>

#include "geometry/geometry_internal.h"
#include "meshtopo/geometry.h"

mt_status mt__geom_ready(const mt_mesh *m, const char *what, mt_diag *diag)
{
    if (!m) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: mesh is NULL", what);
    if (!m->positions)
        return mt__fail(diag, MT_ERR_NO_GEOMETRY, MT_NONE,
                        "%s: the mesh was built without vertex positions", what);
    return MT_OK;
}

mt_status mt__face_ring_area2(const mt_mesh *m, uint32_t h, double out[3], uint32_t *out_size)
{
    out[0] = out[1] = out[2] = 0.0;
    *out_size = 0;
    if (!mt__he_ok(m, h)) return MT_ERR_CORRUPT;
    const double *p0 = mt__geom_pos(m, m->he_head[h ^ 1u]);
    if (!p0) return MT_ERR_CORRUPT;
    uint32_t start = h, steps = 0, size = 0;
    double prev[3] = {0.0, 0.0, 0.0};
    do {
        const double *p = mt__geom_pos(m, m->he_head[h]);
        if (!p) return MT_ERR_CORRUPT;
        double d[3], c[3];
        mt__v3_sub(p, p0, d);
        mt__v3_cross(prev, d, c);
        out[0] += c[0];
        out[1] += c[1];
        out[2] += c[2];
        prev[0] = d[0];
        prev[1] = d[1];
        prev[2] = d[2];
        size++;
        if (!mt__ring_step(m, &h, &steps)) return MT_ERR_CORRUPT;
    } while (h != start);
    *out_size = size;
    return MT_OK;
}

bool mt__unit(const double area2[3], double out[3])
{
    double len = sqrt(mt__v3_dot(area2, area2));
    if (!(len > 0.0) || !isfinite(len)) {
        out[0] = out[1] = out[2] = 0.0;
        return false;
    }
    out[0] = area2[0] / len;
    out[1] = area2[1] / len;
    out[2] = area2[2] / len;
    return true;
}

mt_status mt__face_unit_normal(const mt_mesh *m, uint32_t f, double out[3], uint32_t *out_size,
                               bool *out_ok)
{
    double a2[3];
    mt_status s = mt__face_ring_area2(m, m->face_he[f], a2, out_size);
    *out_ok = s == MT_OK && mt__unit(a2, out);
    if (s != MT_OK) out[0] = out[1] = out[2] = 0.0;
    return s;
}

/* Checks face and returns its first half-edge in *out_he. */
static mt_status face_start(const mt_mesh *m, uint32_t face, const char *what, uint32_t *out_he,
                            mt_diag *diag)
{
    mt_status s = mt__geom_ready(m, what, diag);
    if (s != MT_OK) return s;
    if (face >= m->num_faces)
        return mt__fail(diag, MT_ERR_OUT_OF_RANGE, face, "%s: face %u out of range (%u faces)",
                        what, face, m->num_faces);
    uint32_t h = m->face_he[face];
    if (h == MT_NONE)
        return mt__fail(diag, MT_ERR_NOT_FOUND, face,
                        "%s: face %u was rejected by the build or deleted", what, face);
    *out_he = h;
    return MT_OK;
}

static mt_status corrupt(mt_diag *diag, const char *what, uint32_t face)
{
    return mt__fail(diag, MT_ERR_CORRUPT, face, "%s: the ring of face %u is broken", what, face);
}

mt_status mt_face_normal(const mt_mesh *mesh, uint32_t face, double out_normal[3], mt_diag *diag)
{
    if (!out_normal)
        return mt__fail(diag, MT_ERR_INVALID_ARG, face, "mt_face_normal: out_normal is NULL");
    uint32_t h = MT_NONE, size = 0;
    mt_status s = face_start(mesh, face, "mt_face_normal", &h, diag);
    if (s != MT_OK) return s;
    double a2[3];
    if (mt__face_ring_area2(mesh, h, a2, &size) != MT_OK)
        return corrupt(diag, "mt_face_normal", face);
    mt__unit(a2, out_normal);
    return MT_OK;
}

mt_status mt_face_area(const mt_mesh *mesh, uint32_t face, double *out_area, mt_diag *diag)
{
    if (!out_area)
        return mt__fail(diag, MT_ERR_INVALID_ARG, face, "mt_face_area: out_area is NULL");
    uint32_t h = MT_NONE, size = 0;
    mt_status s = face_start(mesh, face, "mt_face_area", &h, diag);
    if (s != MT_OK) return s;
    double a2[3];
    if (mt__face_ring_area2(mesh, h, a2, &size) != MT_OK)
        return corrupt(diag, "mt_face_area", face);
    *out_area = 0.5 * sqrt(mt__v3_dot(a2, a2));
    return MT_OK;
}

mt_status mt_face_centroid(const mt_mesh *mesh, uint32_t face, double out_centroid[3],
                           mt_diag *diag)
{
    if (!out_centroid)
        return mt__fail(diag, MT_ERR_INVALID_ARG, face, "mt_face_centroid: out_centroid is NULL");
    uint32_t h = MT_NONE, size = 0;
    mt_status s = face_start(mesh, face, "mt_face_centroid", &h, diag);
    if (s != MT_OK) return s;
    double a2[3], n[3];
    if (mt__face_ring_area2(mesh, h, a2, &size) != MT_OK)
        return corrupt(diag, "mt_face_centroid", face);
    bool ok = mt__unit(a2, n);
    /* Positions relative to the first vertex, so far-off meshes keep their digits. */
    const double *p0 = mt__geom_pos(mesh, mesh->he_head[h ^ 1u]);
    double sum[3] = {0.0, 0.0, 0.0}, mean[3] = {0.0, 0.0, 0.0}, weight = 0.0;
    double prev[3] = {0.0, 0.0, 0.0};
    uint32_t start = h, steps = 0;
    do {
        double d[3], c[3];
        mt__v3_sub(mt__geom_pos(mesh, mesh->he_head[h]), p0, d);
        mt__v3_cross(prev, d, c);
        double w = mt__v3_dot(c, n); /* twice the signed area of triangle (p0, prev, p) */
        for (int k = 0; k < 3; k++) {
            sum[k] += w * (prev[k] + d[k]) / 3.0;
            mean[k] += d[k] / size;
        }
        weight += w;
        prev[0] = d[0];
        prev[1] = d[1];
        prev[2] = d[2];
        if (!mt__ring_step(mesh, &h, &steps)) return corrupt(diag, "mt_face_centroid", face);
    } while (h != start);
    for (int k = 0; k < 3; k++)
        out_centroid[k] = p0[k] + (ok && weight > 0.0 ? sum[k] / weight : mean[k]);
    return MT_OK;
}

mt_status mt_mesh_face_normals(const mt_mesh *mesh, double *out_normals, double *out_areas,
                               size_t capacity, size_t *out_count, mt_diag *diag)
{
    mt_status s = mt__geom_ready(mesh, "mt_mesh_face_normals", diag);
    if (s != MT_OK) return s;
    if (!out_count)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "mt_mesh_face_normals: out_count is NULL");
    size_t n = mesh->num_faces;
    *out_count = n;
    if ((!out_normals && !out_areas) || capacity == 0) return MT_OK;
    if (capacity < n)
        return mt__fail(diag, MT_ERR_BUFFER_TOO_SMALL, MT_NONE,
                        "mt_mesh_face_normals: capacity %zu, the mesh has %zu faces", capacity, n);
    for (uint32_t f = 0; f < mesh->num_faces; f++) {
        double a2[3] = {0.0, 0.0, 0.0};
        uint32_t size;
        if (mesh->face_he[f] != MT_NONE &&
            mt__face_ring_area2(mesh, mesh->face_he[f], a2, &size) != MT_OK)
            return corrupt(diag, "mt_mesh_face_normals", f);
        if (out_normals) mt__unit(a2, out_normals + 3 * (size_t)f);
        if (out_areas) out_areas[f] = 0.5 * sqrt(mt__v3_dot(a2, a2));
    }
    return MT_OK;
}
