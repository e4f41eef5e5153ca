/* The mesh object's layout, shared by the core's source files only.
 * Callers see it through mesh.h (raw view) and query.h. Everything here is
 * established by build.c and checked by validate.c. */
#ifndef MESHTOPO_MESH_INTERNAL_H
#define MESHTOPO_MESH_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/mesh.h"
#include "meshtopo/report.h"
#include "meshtopo/status.h"

#include "base/base.h"

struct mt_mesh {
    uint32_t num_verts;          /* caller's V */
    uint32_t num_verts_internal; /* num_verts + num_copies */
    uint32_t num_faces;          /* caller's F, rejected records included */
    uint32_t num_half_edges;     /* 2 * internal edges */

    uint32_t *he_head; /* [num_half_edges] internal vertex it points to */
    uint32_t *he_next; /* [num_half_edges] */
    uint32_t *he_face; /* [num_half_edges] MT_NONE on boundary */
    uint32_t *face_he; /* [num_faces] first side (vertex 0 -> 1), MT_NONE if rejected */
    uint32_t *vert_he; /* [num_verts_internal] outgoing; boundary one when there is one */
    double *positions; /* [3 * num_verts] or NULL */

    /* Vertex copies: internal vertex num_verts + i is a copy of caller vertex
     * copy_original[i], holding one extra fan of it. copies_sorted lists the
     * copy ids ordered by (original, id) so that a vertex's copies are found
     * by binary search. */
    uint32_t num_copies;
    uint32_t *copy_original; /* [num_copies] */
    uint32_t *copies_sorted; /* [num_copies] internal ids */

    /* Edge bundles: one undirected caller edge held by several internal
     * edges (used by more than two faces, or by two faces running the same
     * way). Bundle b holds internal edges bundle_edges[bundle_offsets[b] ..
     * bundle_offsets[b+1]). bundled_sorted lists every bundled internal edge
     * ascending with bundled_bundle its bundle, for binary search. */
    uint32_t num_bundles;
    uint32_t *bundle_offsets; /* [num_bundles + 1] */
    uint32_t *bundle_edges;   /* [bundle_offsets[num_bundles]] */
    uint32_t *bundled_sorted; /* [bundle_offsets[num_bundles]] */
    uint32_t *bundled_bundle; /* [bundle_offsets[num_bundles]] */

    /* Edge-connected component of each internal vertex (all faces of a fan
     * share it), numbered as report.components; NULL when there is at most
     * one component. */
    uint32_t *vert_component;

    mt_report report;

    /* Edit bookkeeping (edit_*.c), all zero after a build. Capacities of the
     * arrays once an edit has grown them (0 = sized exactly by the build):
     * the half-edge block (he_head, he_next, he_face), face_he, and the
     * per-vertex arrays (vert_he, positions, vert_component). */
    uint32_t cap_half_edges;
    uint32_t cap_faces;
    uint32_t cap_verts;
    struct mt__edit_state *edit;          /* NULL until the first edit */
    struct mt__attribute_set *attributes; /* NULL until the first attribute (attributes.c) */
    bool skip_hidden;                     /* queries leave hidden elements out */
};

/* Edit bookkeeping the mesh keeps between edits (mesh->edit): made by the
 * first edit (edit/edit_state.c), read by validate.c, freed with the mesh. */
typedef struct mt__edit_state {
    mt__vec undo;          /* mt__undo entries of the edit in progress */
    mt__vec freed;         /* edges freed by the edit in progress (reused by it) */
    mt__vec touched;       /* vertices whose fans the edit in progress changed */
    mt__vec prim;          /* scratch of the primitives (uint32_t) */
    mt__vec work;          /* scratch of the edits themselves (uint32_t) */
    uint8_t *vert_deleted; /* [cap_verts] 1 = deleted; NULL before the first deletion */
    uint32_t num_deleted_verts;
    uint64_t edits; /* edits since the report was made */
} mt__edit_state;

/* Frees the edit bookkeeping (mesh_lifetime.c). NULL-safe. */
void mt__edit_state_free(mt__edit_state *state);

/* Frees the attributes (attributes.c). NULL-safe. */
void mt__attribute_set_free(struct mt__attribute_set *set);

/* Makes every attribute array hold as many elements as the mesh's arrays
 * now have room for (the new ones zero): called after an edit grows them.
 * MT_ERR_NOMEM leaves the arrays that could not grow as they were. */
mt_status mt__attributes_fit(mt_mesh *m);

/* Carries the attributes of `old` to `fresh`, its compaction: vertex, face
 * and half-edge i of old becomes vmap[i], fmap[i], hemap[i] of fresh
 * (MT_NONE: dropped; edges follow their first half-edge). */
mt_status mt__attributes_remap(const mt_mesh *old, mt_mesh *fresh, const uint32_t *vmap,
                               const uint32_t *fmap, const uint32_t *hemap);

/* The hidden flags of element kind `kind` (mt_element_kind) that queries
 * leave out: the kind's hidden attribute when the mesh skips hidden
 * elements (mt_mesh_skip_hidden), else NULL (attributes.c). */
const uint8_t *mt__skipped_flags(const mt_mesh *m, int kind);

/* Whether element id of a kind with those flags (counted `count`) is left out. */
static inline bool mt__skipped(const uint8_t *flags, uint32_t count, uint32_t id)
{
    return flags && id < count && flags[id] != 0;
}

/* Caller id of an internal vertex. */
static inline uint32_t mt__original(const mt_mesh *m, uint32_t v)
{
    return v < m->num_verts ? v : m->copy_original[v - m->num_verts];
}

/* Copies of caller vertex v: *out_first points into copies_sorted, the
 * return value is how many (0 for almost every vertex). */
uint32_t mt__vert_copies(const mt_mesh *m, uint32_t v, const uint32_t **out_first);

/* Bundle of an internal edge, MT_NONE when the edge is alone. */
uint32_t mt__edge_bundle(const mt_mesh *m, uint32_t edge);

/* Previous half-edge in h's ring (walks the ring: two steps in a triangle). */
static inline uint32_t mt__he_prev(const mt_mesh *m, uint32_t h)
{
    uint32_t p = h;
    uint32_t steps = 0;
    while (m->he_next[p] != h && steps++ < MT_RING_STEP_LIMIT) p = m->he_next[p];
    return p;
}

/* The three half-edge arrays share one allocation starting at he_head,
 * he_head, he_next and he_face in turn with this many bytes between them
 * (a page and three lines), so that entry h of each falls in a different
 * cache set: builds and queries touch all three at the same index, and equal
 * offsets modulo the page size made them evict one another. Edits that grow
 * the block drop the gap (cap_half_edges). */
#define MT__HE_STAGGER (4096 + 3 * 64)

/* Length an array of the mesh was allocated for: the capacity an edit grew
 * it to (cap_half_edges, cap_faces, cap_verts), else its count. Edits raise a
 * capacity only once every array it covers has been grown. */
static inline uint32_t mt__cap_or(uint32_t capacity, uint32_t count)
{
    return capacity ? capacity : count;
}

#endif
