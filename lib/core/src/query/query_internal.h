/* Bounds-checked steps shared by the query files (query_*.c) and the
 * families above them (geometry/, edit/, generate/). Queries trust
 * the structure only as far as these checks go: every index read from the
 * mesh is range-checked before it is followed and every walk is bounded by
 * the number of half-edges, so a corrupted mesh gives MT_ERR_CORRUPT, never an
 * out-of-bounds read or an endless loop. */
#ifndef MESHTOPO_QUERY_INTERNAL_H
#define MESHTOPO_QUERY_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mesh/mesh_internal.h"

/* True when h and its twin are both valid half-edge ids. */
static inline bool mt__he_ok(const mt_mesh *m, uint32_t h)
{
    return h < (m->num_half_edges & ~1u);
}

/* Caller id of internal vertex v, MT_NONE when v is not a valid internal id
 * (or a copy names an original out of range). */
static inline uint32_t mt__original_checked(const mt_mesh *m, uint32_t v)
{
    if (v < m->num_verts) return v;
    if (v >= m->num_verts_internal || v - m->num_verts >= m->num_copies) return MT_NONE;
    uint32_t o = m->copy_original[v - m->num_verts];
    return o < m->num_verts ? o : MT_NONE;
}

/* One rotation step around the tail of *h (to next(twin)); false when the
 * result is out of range or the walk has taken more steps than there are
 * half-edges (a rotation that never closes). */
static inline bool mt__rotate_step(const mt_mesh *m, uint32_t *h, uint32_t *steps)
{
    uint32_t n = m->he_next[*h ^ 1u];
    if (!mt__he_ok(m, n) || ++*steps > m->num_half_edges) return false;
    *h = n;
    return true;
}

/* One step along a face or boundary ring (to next); false as above. */
static inline bool mt__ring_step(const mt_mesh *m, uint32_t *h, uint32_t *steps)
{
    uint32_t n = m->he_next[*h];
    if (!mt__he_ok(m, n) || ++*steps > m->num_half_edges) return false;
    *h = n;
    return true;
}

/* The i-th internal vertex holding a fan of caller vertex v: v itself for
 * i = 0, then its copies in ascending id. MT_NONE when out of range. */
static inline uint32_t mt__vert_fan_owner(const mt_mesh *m, uint32_t v, const uint32_t *copies,
                                          uint32_t i)
{
    uint32_t u = i == 0 ? v : copies[i - 1];
    return u < m->num_verts_internal ? u : MT_NONE;
}

/* The walk around a caller vertex: every outgoing half-edge of each of its
 * fans (its own, then its copies' in ascending id), each fan in rotation
 * order from its stored outgoing half-edge (the boundary one on an open
 * fan). Bounds-checked like the steps above; a broken fan stops the walk
 * with status MT_ERR_CORRUPT. The queries, the vertex geometry and the
 * edge look-up all walk a vertex this way:
 *
 *     mt__vert_walk w;
 *     mt__vert_walk_begin(&w, m, v);
 *     while (mt__vert_walk_fan(&w)) {
 *         do {
 *             ... w.he ...
 *         } while (mt__vert_walk_step(&w));
 *     }
 *     if (w.status != MT_OK) return w.status;
 */
typedef struct mt__vert_walk {
    const mt_mesh *m;
    const uint32_t *copies; /* the vertex's copies (mt__vert_copies) */
    uint32_t vert, num_copies;
    uint32_t next_fan; /* the fan mt__vert_walk_fan tries next: 0 = the vertex's own */
    uint32_t start;    /* the current fan's first half-edge */
    uint32_t he;       /* the half-edge at hand */
    uint32_t steps;    /* rotation steps taken in the current fan */
    mt_status status;  /* MT_OK, or MT_ERR_CORRUPT once a fan was found broken */
} mt__vert_walk;

/* Starts a walk around caller vertex v (v < m->num_verts). */
static inline void mt__vert_walk_begin(mt__vert_walk *w, const mt_mesh *m, uint32_t v)
{
    w->m = m;
    w->vert = v;
    w->num_copies = mt__vert_copies(m, v, &w->copies);
    w->next_fan = 0;
    w->start = w->he = MT_NONE;
    w->steps = 0;
    w->status = MT_OK;
}

/* Moves to the vertex's next fan that has an outgoing half-edge: w->he and
 * w->start are that half-edge. False once every fan is walked, or when a fan
 * is broken (w->status). */
static inline bool mt__vert_walk_fan(mt__vert_walk *w)
{
    while (w->status == MT_OK && w->next_fan <= w->num_copies) {
        uint32_t u = mt__vert_fan_owner(w->m, w->vert, w->copies, w->next_fan++);
        uint32_t start = u == MT_NONE ? MT_NONE : w->m->vert_he[u];
        if (u != MT_NONE && start == MT_NONE) continue;
        if (u == MT_NONE || !mt__he_ok(w->m, start)) {
            w->status = MT_ERR_CORRUPT;
            return false;
        }
        w->start = w->he = start;
        w->steps = 0;
        return true;
    }
    return false;
}

/* One rotation step within the current fan: false once it is back at the
 * fan's first half-edge, or when the rotation is broken (w->status). */
static inline bool mt__vert_walk_step(mt__vert_walk *w)
{
    if (!mt__rotate_step(w->m, &w->he, &w->steps)) {
        w->status = MT_ERR_CORRUPT;
        return false;
    }
    return w->he != w->start;
}

/* Members of bundle b as a range of bundle_edges; false when the bundle
 * table is inconsistent. */
static inline bool mt__bundle_range(const mt_mesh *m, uint32_t b, uint32_t *out_begin,
                                    uint32_t *out_end)
{
    if (b >= m->num_bundles) return false;
    uint32_t begin = m->bundle_offsets[b], end = m->bundle_offsets[b + 1];
    if (begin > end || end > m->bundle_offsets[m->num_bundles]) return false;
    *out_begin = begin;
    *out_end = end;
    return true;
}

/* The caller passed no buffer (NULL or capacity 0): a size query. */
static inline bool mt__buffer_absent(const void *buf, size_t capacity)
{
    return buf == NULL || capacity == 0;
}

/* A buffer that can hold `needed` elements (a size of 0 fits anything). */
static inline bool mt__buffer_fits(const void *buf, size_t capacity, size_t needed)
{
    return needed == 0 || (buf != NULL && capacity >= needed);
}

#endif
