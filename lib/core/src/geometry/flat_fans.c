/* Flat fans (for mt_mesh_self_intersections): vertices whose triangles can
 * be shown, with a few exact 2D orientations, to meet one another only at
 * the vertex and along the sides they share. On a smooth scan almost every
 * pair of triangles whose boxes overlap shares a vertex, so skipping the
 * pairs around such vertices leaves the exact 3D narrow phase the few pairs
 * that can cross.
 *
 * The test: v's faces form one closed fan of triangles (v, a_i, a_i+1)
 * (v is no boundary vertex, has no copies, and no polygon face or skipped
 * face touches it); projected onto a coordinate plane (the one v's normal
 * is most nearly perpendicular to), every triangle turns the same way and
 * the link a_0, a_1, ... winds around v exactly once. Then the projected
 * triangles are angular sectors that tile a disc around v once, so two of
 * them share only v or a side; each triangle projects one-to-one, so in 3D
 * they share no more either. Every decision is exact (mt_orient2d and
 * comparisons of coordinates); the choice of plane need not be.
 *
 * The winding is counted triangle by triangle (the side a_i -> a_i+1 of
 * each crosses the ray from v along +x, or not), so the triangles are read
 * in the order given, which is the Morton order of the check: walking each
 * vertex's fan through the half-edges would read a shuffled mesh at random.
 * Threads (parallel.c) split the vertices, each reading every triangle. */
#include <math.h>
#include <string.h>

#include "geometry/geometry_internal.h"
#include "meshtopo/predicates.h"

/* What the triangles of a vertex showed, in its projection. */
enum {
    TURNS_LEFT = 1,  /* a triangle turns counter-clockwise */
    TURNS_RIGHT = 2, /* a triangle turns clockwise */
    TURNS_NONE = 4   /* a triangle projects onto a line or point */
};

typedef struct fan_state {
    uint8_t turns;    /* TURNS_* seen */
    uint8_t up, down; /* sides crossing the ray upwards, downwards (saturating) */
} fan_state;

typedef struct fan_pass {
    const mt_mesh *m;
    const mt__tri *tris;
    uint32_t num_tris;
    uint32_t first, end; /* the vertices this pass judges */
    float *normal;       /* [3 * num_verts] */
    fan_state *state;    /* [num_verts] */
    uint8_t *flat;       /* [num_verts]: in, 0 where v cannot be flat; out, the answer */
} fan_pass;

static bool finite3(const double *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

/* The projection dropping axis `drop`. */
static void project(const double *p, int drop, double out[2])
{
    out[0] = p[drop == 0 ? 1 : 0];
    out[1] = p[drop == 2 ? 1 : 2];
}

static int largest_axis(const float *n)
{
    const float ax = fabsf(n[0]), ay = fabsf(n[1]), az = fabsf(n[2]);
    return ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
}

static bool mine(const fan_pass *p, uint32_t v)
{
    return v >= p->first && v < p->end;
}

/* Adds each triangle's area vector to the normals of its corners. */
static void sum_normals(fan_pass *p)
{
    const double *pos = p->m->positions;
    for (uint32_t t = 0; t < p->num_tris; t++) {
        const uint32_t *v = p->tris[t].v;
        if (!mine(p, v[0]) && !mine(p, v[1]) && !mine(p, v[2])) continue;
        const double *a = pos + 3 * (size_t)v[0], *b = pos + 3 * (size_t)v[1],
                     *c = pos + 3 * (size_t)v[2];
        double ab[3], ac[3], n[3];
        mt__v3_sub(b, a, ab);
        mt__v3_sub(c, a, ac);
        mt__v3_cross(ab, ac, n);
        for (int k = 0; k < 3; k++)
            if (mine(p, v[k]))
                for (int d = 0; d < 3; d++) p->normal[3 * (size_t)v[k] + d] += (float)n[d];
    }
}

/* Judges triangle (v, a, b) for corner v. */
static void judge_corner(fan_pass *p, uint32_t v, uint32_t a, uint32_t b)
{
    const double *pos = p->m->positions;
    const int drop = largest_axis(p->normal + 3 * (size_t)v);
    double centre[2], here[2], next[2];
    project(pos + 3 * (size_t)v, drop, centre);
    project(pos + 3 * (size_t)a, drop, here);
    project(pos + 3 * (size_t)b, drop, next);
    fan_state *s = &p->state[v];
    const int o = mt_orient2d(centre, here, next);
    s->turns |= o > 0 ? TURNS_LEFT : (o < 0 ? TURNS_RIGHT : TURNS_NONE);
    /* the side here -> next crosses the ray from the centre along +x
     * upwards (counted when the fan turns left) or downwards (right) */
    if (here[1] <= centre[1] && next[1] > centre[1] && s->up < UINT8_MAX) s->up++;
    if (here[1] > centre[1] && next[1] <= centre[1] && s->down < UINT8_MAX) s->down++;
}

/* The fans of pass `part`'s vertices. */
static void run_pass(void *ctx, uint32_t part, uint32_t parts)
{
    (void)parts;
    fan_pass *p = &((fan_pass *)ctx)[part];
    sum_normals(p);
    for (uint32_t t = 0; t < p->num_tris; t++) {
        const uint32_t *v = p->tris[t].v;
        for (int k = 0; k < 3; k++)
            if (mine(p, v[k]) && p->flat[v[k]])
                judge_corner(p, v[k], v[(k + 1) % 3], v[(k + 2) % 3]);
    }
    for (uint32_t v = p->first; v < p->end; v++) {
        const fan_state *s = &p->state[v];
        p->flat[v] = p->flat[v] && ((s->turns == TURNS_LEFT && s->up == 1) ||
                                    (s->turns == TURNS_RIGHT && s->down == 1));
    }
}

/* Clears flat[] for the caller vertices at an end of a half-edge without
 * a face, or with copies: their faces are not one closed fan. */
static void clear_open_and_copied(const mt_mesh *m, uint8_t *flat)
{
    for (uint32_t h = 0; h < m->num_half_edges; h++) {
        if (m->he_face[h] != MT_NONE) continue;
        const uint32_t head = mt__original_checked(m, m->he_head[h]);
        const uint32_t tail = mt__original_checked(m, m->he_head[h ^ 1u]);
        if (head != MT_NONE) flat[head] = 0;
        if (tail != MT_NONE) flat[tail] = 0;
    }
    for (uint32_t i = 0; i < m->num_copies; i++)
        if (m->copy_original[i] < m->num_verts) flat[m->copy_original[i]] = 0;
}

mt_status mt__flat_fans(const mt_mesh *m, const mt__tri *tris, uint32_t num_tris, uint32_t threads,
                        uint8_t *flat)
{
    if (m->edit) { /* edits leave deleted faces in fans: judge every pair */
        memset(flat, 0, m->num_verts);
        return MT_OK;
    }
    clear_open_and_copied(m, flat);
    for (uint32_t v = 0; v < m->num_verts; v++)
        if (flat[v] && !finite3(m->positions + 3 * (size_t)v)) flat[v] = 0;
    float *normal = mt__calloc(3 * (size_t)m->num_verts, sizeof *normal);
    fan_state *state = mt__calloc(m->num_verts, sizeof *state);
    if (!normal || !state) {
        mt__free(normal);
        mt__free(state);
        return MT_ERR_NOMEM;
    }
    fan_pass passes[MT__MAX_THREADS];
    if (threads > MT__MAX_THREADS) threads = MT__MAX_THREADS;
    for (uint32_t t = 0; t < threads; t++)
        passes[t] = (fan_pass){.m = m,
                               .tris = tris,
                               .num_tris = num_tris,
                               .normal = normal,
                               .state = state,
                               .flat = flat};
    for (uint32_t t = 0; t < threads; t++)
        mt__part_range(m->num_verts, t, threads, &passes[t].first, &passes[t].end);
    mt__in_parallel(threads, run_pass, passes);
    mt__free(normal);
    mt__free(state);
    return MT_OK;
}
