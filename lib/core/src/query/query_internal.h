/* Bounds-checked steps shared by the query files (query_*.c). Queries trust
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
