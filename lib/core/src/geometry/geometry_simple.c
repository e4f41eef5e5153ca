/* Face shape (meshtopo/geometry.h): whether a polygon face is simple in its
 * best-fit plane, by a sweep line over its sides (Shamos and Hoey, 1976),
 * and how far its corners leave that plane. The plane is fitted to the
 * corners by least squares (the normal is the covariance's least direction,
 * found by the largest 2x2 determinant), not by Newell's normal: a bowtie's
 * Newell normal is zero. The corners are projected by dropping the normal's
 * largest axis. The sweep keeps the sides crossing the sweep line in an
 * array ordered bottom to top: O(n log n) comparisons; the array's moves are
 * O(k) per event for k sides under the line at once, a few for a face. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geometry/geometry_internal.h"
#include "meshtopo/predicates.h"
#include "meshtopo/query.h"

typedef struct side {
    const double *lo, *hi; /* endpoints, lo before hi in (x, y) order */
} side;

typedef struct event {
    const double *at;
    uint32_t side;
    int is_end; /* 0: the side starts here, 1: it ends here */
} event;

typedef struct sweep {
    const double (*pts)[2];
    uint32_t n;
    side *sides;
    uint32_t *active; /* sides under the sweep line, bottom to top */
    uint32_t num_active;
} sweep;

/* The exact sign of (b - a) x (c - a): rounding never decides a crossing. */
static int orient(const double *a, const double *b, const double *c)
{
    return mt_orient2d(a, b, c);
}

/* Whether a and b, on one line with q, lie on the same side of it (both
 * different from q). Compares coordinates, so it is exact. */
static bool same_direction(const double *q, const double *a, const double *b)
{
    for (int k = 0; k < 2; k++)
        if (a[k] != q[k]) return b[k] != q[k] && (a[k] > q[k]) == (b[k] > q[k]);
    return false;
}

static int before(const double *a, const double *b)
{
    return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]);
}

static int compare_events(const void *pa, const void *pb)
{
    const event *a = pa, *b = pb;
    if (before(a->at, b->at)) return -1;
    if (before(b->at, a->at)) return 1;
    return a->is_end - b->is_end; /* starts first: sides meeting at a point are both checked */
}

/* c on segment [a, b], given that it is on their line. */
static bool within(const double *a, const double *b, const double *c)
{
    return fmin(a[0], b[0]) <= c[0] && c[0] <= fmax(a[0], b[0]) && fmin(a[1], b[1]) <= c[1] &&
           c[1] <= fmax(a[1], b[1]);
}

/* Whether sides i and j cross or touch. Consecutive sides meet at their
 * shared corner by construction; they count only when they fold back over
 * each other. */
static bool sides_meet(const sweep *s, uint32_t i, uint32_t j)
{
    const double(*p)[2] = s->pts;
    const uint32_t n = s->n;
    if ((i + 1) % n == j || (j + 1) % n == i) {
        uint32_t first = (i + 1) % n == j ? i : j, second = first == i ? j : i;
        const double *q = p[second], *a = p[first], *b = p[(second + 1) % n];
        return orient(q, a, b) == 0 && same_direction(q, a, b);
    }
    const double *a = p[i], *b = p[(i + 1) % n], *c = p[j], *d = p[(j + 1) % n];
    int d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c), d4 = orient(a, b, d);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return true;
    return (d1 == 0 && within(c, d, a)) || (d2 == 0 && within(c, d, b)) ||
           (d3 == 0 && within(a, b, c)) || (d4 == 0 && within(a, b, d));
}

/* Whether side j lies below point q of side i (which starts at q). */
static bool below(const sweep *s, uint32_t j, uint32_t i)
{
    const side *t = &s->sides[j], *u = &s->sides[i];
    int o = orient(t->lo, t->hi, u->lo);
    if (o == 0) o = orient(t->lo, t->hi, u->hi);
    return o > 0;
}

/* Runs the sweep; true with the two sides in *out_a < *out_b when two sides
 * cross or touch. */
static bool find_crossing(sweep *s, event *events, uint32_t *out_a, uint32_t *out_b)
{
    const uint32_t n = s->n;
    for (uint32_t i = 0; i < n; i++) {
        const double *a = s->pts[i], *b = s->pts[(i + 1) % n];
        s->sides[i].lo = before(b, a) ? b : a;
        s->sides[i].hi = before(b, a) ? a : b;
        events[2 * i] = (event){s->sides[i].lo, i, 0};
        events[2 * i + 1] = (event){s->sides[i].hi, i, 1};
    }
    qsort(events, 2 * (size_t)n, sizeof *events, compare_events);
    s->num_active = 0;
    for (uint32_t e = 0; e < 2 * n; e++) {
        const uint32_t i = events[e].side;
        uint32_t k = 0;
        if (!events[e].is_end) {
            uint32_t lo = 0, hi = s->num_active;
            while (lo < hi) {
                uint32_t mid = lo + (hi - lo) / 2;
                if (below(s, s->active[mid], i))
                    lo = mid + 1;
                else
                    hi = mid;
            }
            k = lo;
            memmove(&s->active[k + 1], &s->active[k], (s->num_active - k) * sizeof *s->active);
            s->active[k] = i;
            s->num_active++;
            uint32_t nb[2] = {k > 0 ? s->active[k - 1] : MT_NONE,
                              k + 1 < s->num_active ? s->active[k + 1] : MT_NONE};
            for (int t = 0; t < 2; t++) {
                if (nb[t] != MT_NONE && sides_meet(s, i, nb[t])) {
                    *out_a = i < nb[t] ? i : nb[t];
                    *out_b = i < nb[t] ? nb[t] : i;
                    return true;
                }
            }
        } else {
            while (k < s->num_active && s->active[k] != i) k++;
            if (k == s->num_active) continue;
            if (k > 0 && k + 1 < s->num_active) {
                uint32_t a = s->active[k - 1], b = s->active[k + 1];
                if (sides_meet(s, a, b)) {
                    *out_a = a < b ? a : b;
                    *out_b = a < b ? b : a;
                    return true;
                }
            }
            memmove(&s->active[k], &s->active[k + 1], (s->num_active - k - 1) * sizeof *s->active);
            s->num_active--;
        }
    }
    return false;
}

/* Two consecutive corners at one point: the sides before and after the
 * empty side between them touch there, which the sweep, ordering sides by
 * their lines, can miss (an empty side has no line). True with those two
 * sides, *out_a < *out_b. n >= 4. */
static bool repeated_corner(const double (*p)[2], uint32_t n, uint32_t *out_a, uint32_t *out_b)
{
    for (uint32_t i = 0; i < n; i++) {
        const double *a = p[i], *b = p[(i + 1) % n];
        if (a[0] != b[0] || a[1] != b[1]) continue;
        const uint32_t prev = (i + n - 1) % n, next = (i + 1) % n;
        *out_a = prev < next ? prev : next;
        *out_b = prev < next ? next : prev;
        return true;
    }
    return false;
}

/* Least-squares plane of the corners: its unit normal (zero when the corners
 * are on one line) and centroid. */
static void fit_plane(const double *const *corner, uint32_t n, double normal[3], double centre[3])
{
    centre[0] = centre[1] = centre[2] = 0;
    for (uint32_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) centre[d] += corner[i][d] / n;
    double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
    for (uint32_t i = 0; i < n; i++) {
        double x = corner[i][0] - centre[0], y = corner[i][1] - centre[1],
               z = corner[i][2] - centre[2];
        xx += x * x;
        xy += x * y;
        xz += x * z;
        yy += y * y;
        yz += y * z;
        zz += z * z;
    }
    double det_x = yy * zz - yz * yz, det_y = xx * zz - xz * xz, det_z = xx * yy - xy * xy;
    double best = fmax(det_x, fmax(det_y, det_z));
    normal[0] = normal[1] = normal[2] = 0;
    if (!(best > 0)) return;
    if (best == det_x) {
        normal[0] = det_x;
        normal[1] = xz * yz - xy * zz;
        normal[2] = xy * yz - xz * yy;
    } else if (best == det_y) {
        normal[0] = xz * yz - xy * zz;
        normal[1] = det_y;
        normal[2] = xy * xz - yz * xx;
    } else {
        normal[0] = xy * yz - xz * yy;
        normal[1] = xy * xz - yz * xx;
        normal[2] = det_z;
    }
    double len = sqrt(mt__v3_dot(normal, normal));
    for (int d = 0; d < 3; d++) normal[d] = len > 0 ? normal[d] / len : 0;
}

void mt__polygon_plane(const double *const *corner, uint32_t n, int *out_drop, double *out_warp)
{
    double normal[3], centre[3], lo[3], hi[3];
    fit_plane(corner, n, normal, centre);
    for (int d = 0; d < 3; d++) lo[d] = hi[d] = corner[0][d];
    for (uint32_t i = 1; i < n; i++)
        for (int d = 0; d < 3; d++) {
            lo[d] = fmin(lo[d], corner[i][d]);
            hi[d] = fmax(hi[d], corner[i][d]);
        }
    /* Drop the normal's largest axis; on one line, the bounding box's smallest. */
    int drop = 0;
    for (int d = 1; d < 3; d++) {
        bool larger = normal[0] || normal[1] || normal[2] ? fabs(normal[d]) > fabs(normal[drop])
                                                          : hi[d] - lo[d] < hi[drop] - lo[drop];
        if (larger) drop = d;
    }
    double warp = 0;
    for (uint32_t i = 0; i < n; i++) {
        double off[3];
        mt__v3_sub(corner[i], centre, off);
        warp = fmax(warp, fabs(mt__v3_dot(off, normal)));
    }
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    *out_drop = drop;
    *out_warp = diag > 0 ? warp / diag : 0;
}

/* The shape of a face whose n >= 4 corners are `corner`. */
static mt_status shape_of(const double *const *corner, uint32_t n, mt_face_shape *out)
{
    int drop = 0;
    mt__polygon_plane(corner, n, &drop, &out->warp);
    double(*pts)[2] = malloc(n * sizeof *pts);
    side *sides = malloc(n * sizeof *sides);
    uint32_t *active = malloc(n * sizeof *active);
    event *events = malloc(2 * (size_t)n * sizeof *events);
    if (!pts || !sides || !active || !events) {
        free(pts);
        free(sides);
        free(active);
        free(events);
        return MT_ERR_NOMEM;
    }
    for (uint32_t i = 0; i < n; i++) {
        pts[i][0] = corner[i][drop == 0 ? 1 : 0];
        pts[i][1] = corner[i][drop == 2 ? 1 : 2];
    }
    sweep s = {(const double(*)[2])pts, n, sides, active, 0};
    uint32_t a = 0, b = 0;
    if (repeated_corner(s.pts, n, &a, &b) || find_crossing(&s, events, &a, &b)) {
        out->kind = MT_FACE_SELF_CROSSING;
        out->side_a = a;
        out->side_b = b;
    } else {
        out->kind = out->warp > MT_FACE_WARP_TOLERANCE ? MT_FACE_WARPED : MT_FACE_SIMPLE;
    }
    free(pts);
    free(sides);
    free(active);
    free(events);
    return MT_OK;
}

/* The shape of the closed polyline through `verts` (caller ids, n >= 4;
 * fewer cannot cross): out->kind and sides as for a face. Corners at NaN or
 * infinity leave it unjudged (simple). MT_OK or MT_ERR_NOMEM. */
static mt_status polyline_shape(const mt_mesh *m, const uint32_t *verts, size_t n,
                                mt_face_shape *out)
{
    if (n < 4) return MT_OK;
    const double **corner = malloc(n * sizeof *corner);
    if (!corner) return MT_ERR_NOMEM;
    bool finite = true;
    for (size_t i = 0; i < n; i++) {
        corner[i] = m->positions + 3 * (size_t)verts[i];
        finite =
            finite && isfinite(corner[i][0]) && isfinite(corner[i][1]) && isfinite(corner[i][2]);
    }
    mt_status s = finite ? shape_of(corner, (uint32_t)n, out) : MT_OK;
    free(corner);
    return s;
}

/* The shape of valid face f (its corners in mt_face_verts order). */
static mt_status face_shape(const mt_mesh *m, uint32_t f, mt_face_shape *out, mt_diag *diag,
                            const char *what)
{
    memset(out, 0, sizeof *out);
    out->face = f;
    out->side_a = out->side_b = MT_NONE;
    size_t n = 0;
    mt_status s = mt_face_verts(m, f, NULL, 0, &n);
    if (s == MT_ERR_OUT_OF_RANGE || s == MT_ERR_NOT_FOUND)
        return mt_diag_set(diag, s, "%s: face %u %s", what, f,
                           s == MT_ERR_NOT_FOUND ? "was rejected or deleted" : "is out of range");
    if (s != MT_OK && s != MT_ERR_BUFFER_TOO_SMALL)
        return mt_diag_set(diag, s, "%s: face %u", what, f);
    if (n < 4) return MT_OK; /* a triangle is simple and planar */
    uint32_t *verts = malloc(n * sizeof *verts);
    if (!verts) return mt_diag_set(diag, MT_ERR_NOMEM, "%s: no memory for face %u", what, f);
    s = mt_face_verts(m, f, verts, n, &n);
    if (s != MT_OK) mt_diag_set(diag, s, "%s: face %u", what, f);
    /* A corner at NaN or infinity has no place in a plane: the face is not
     * judged (the report lists the vertex as a nonfinite_coordinate). */
    if (s == MT_OK) s = polyline_shape(m, verts, n, out);
    if (s == MT_ERR_NOMEM) mt_diag_set(diag, s, "%s: no memory for face %u", what, f);
    free(verts);
    return s;
}

mt_status mt_face_shape_of(const mt_mesh *mesh, uint32_t face, mt_face_shape *out, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!out) return mt_diag_set(diag, MT_ERR_INVALID_ARG, "mt_face_shape_of: out is NULL");
    memset(out, 0, sizeof *out);
    mt_status s = mt__geom_ready(mesh, "mt_face_shape_of", diag);
    if (s != MT_OK) return s;
    return face_shape(mesh, face, out, diag, "mt_face_shape_of");
}

mt_status mt_mesh_nonsimple_faces(const mt_mesh *mesh, mt_face_shape *out, size_t capacity,
                                  size_t *out_count, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (out_count) *out_count = 0;
    if (!out_count)
        return mt_diag_set(diag, MT_ERR_INVALID_ARG, "mt_mesh_nonsimple_faces: out_count is NULL");
    mt_status s = mt__geom_ready(mesh, "mt_mesh_nonsimple_faces", diag);
    if (s != MT_OK) return s;
    size_t count = 0;
    const uint32_t num_faces = mt_mesh_num_faces(mesh);
    for (uint32_t f = 0; f < num_faces; f++) {
        mt_face_shape shape;
        s = face_shape(mesh, f, &shape, diag, "mt_mesh_nonsimple_faces");
        if (s == MT_ERR_NOT_FOUND) { /* rejected or deleted */
            mt_diag_clear(diag);
            continue;
        }
        if (s != MT_OK) return s;
        if (shape.kind == MT_FACE_SIMPLE) continue;
        if (out && count < capacity) out[count] = shape;
        count++;
    }
    *out_count = count;
    if (out && count > capacity)
        return mt_diag_set(diag, MT_ERR_BUFFER_TOO_SMALL,
                           "mt_mesh_nonsimple_faces: %zu faces, room for %zu", count, capacity);
    return MT_OK;
}

mt_status mt_mesh_boundary_loop_crossings(const mt_mesh *mesh, mt_loop_crossing *out,
                                          size_t capacity, size_t *out_count, mt_diag *diag)
{
    static const char what[] = "mt_mesh_boundary_loop_crossings";
    mt_diag_clear(diag);
    if (out_count) *out_count = 0;
    if (!out_count) return mt_diag_set(diag, MT_ERR_INVALID_ARG, "%s: out_count is NULL", what);
    mt_status s = mt__geom_ready(mesh, what, diag);
    if (s != MT_OK) return s;
    size_t num_verts = 0, num_loops = 0;
    s = mt_boundary_loops(mesh, NULL, 0, NULL, 0, &num_verts, &num_loops);
    if (s != MT_OK && s != MT_ERR_BUFFER_TOO_SMALL)
        return mt_diag_set(diag, s, "%s: reading the boundary loops", what);
    uint32_t *verts = malloc((num_verts ? num_verts : 1) * sizeof *verts);
    uint32_t *offsets = malloc((num_loops + 1) * sizeof *offsets);
    if (!verts || !offsets) {
        free(verts);
        free(offsets);
        return mt_diag_set(diag, MT_ERR_NOMEM, "%s: no memory for %zu loop vertices", what,
                           num_verts);
    }
    s = mt_boundary_loops(mesh, verts, num_verts, offsets, num_loops + 1, &num_verts, &num_loops);
    size_t count = 0;
    for (size_t l = 0; s == MT_OK && l < num_loops; l++) {
        const uint32_t *loop = verts + offsets[l];
        const size_t n = offsets[l + 1] - offsets[l];
        mt_face_shape shape;
        memset(&shape, 0, sizeof shape);
        s = polyline_shape(mesh, loop, n, &shape);
        if (s != MT_OK || shape.kind != MT_FACE_SELF_CROSSING) continue;
        if (out && count < capacity) {
            mt_loop_crossing *c = &out[count];
            c->loop = (uint32_t)l;
            c->edge_a[0] = loop[shape.side_a];
            c->edge_a[1] = loop[(shape.side_a + 1) % n];
            c->edge_b[0] = loop[shape.side_b];
            c->edge_b[1] = loop[(shape.side_b + 1) % n];
        }
        count++;
    }
    free(verts);
    free(offsets);
    if (s == MT_ERR_NOMEM) return mt_diag_set(diag, s, "%s: out of memory", what);
    if (s != MT_OK) return mt_diag_set(diag, s, "%s: reading the boundary loops", what);
    *out_count = count;
    if (out && count > capacity)
        return mt_diag_set(diag, MT_ERR_BUFFER_TOO_SMALL, "%s: %zu loops cross, room for %zu", what,
                           count, capacity);
    return MT_OK;
}
