/* Every array of a half-edge mesh, read out (mt_mesh_get_parts) and made
 * into a mesh again without a rebuild (mt_mesh_restore): what an archive
 * stores so that a reload costs a copy and a validation instead of a build.
 * Restored arrays are untrusted: mt_mesh_restore checks their lengths and
 * runs mt_mesh_validate, so a mesh it returns is safe for every query. */
#ifndef MESHTOPO_MESH_PARTS_H
#define MESHTOPO_MESH_PARTS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/mesh.h"
#include "meshtopo/report.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The arrays of a mesh (see mesh.h for the structure and mesh_internal.h's
 * field comments). Each pointer's length is given by the counts beside it;
 * MT_NONE (UINT32_MAX) is the "no element" value wherever one is allowed. */
typedef struct mt_mesh_parts {
    uint32_t num_verts;          /* caller's vertex count */
    uint32_t num_verts_internal; /* num_verts + num_copies */
    uint32_t num_faces;          /* caller's face records */
    uint32_t num_half_edges;     /* even: 2 * internal edges */

    const uint32_t *he_head; /* [num_half_edges] internal vertex it points to */
    const uint32_t *he_next; /* [num_half_edges] next in its face or boundary ring. Walking
                                the outgoing half-edges of a vertex by h = he_next[h ^ 1]
                                turns clockwise for counter-clockwise faces: the opposite
                                of mt_vert_ring's order */
    const uint32_t *he_face; /* [num_half_edges] face, MT_NONE on a boundary */
    const uint32_t *face_he; /* [num_faces] first side, MT_NONE for a rejected record */
    const uint32_t *vert_he; /* [num_verts_internal] outgoing, MT_NONE when isolated */
    const double *positions; /* [3 * num_verts], or NULL for a mesh without geometry */

    /* Vertex copies: internal vertex num_verts + i holds one extra fan of
     * caller vertex copy_original[i]; copies_sorted lists the copy ids by
     * (original, id). */
    uint32_t num_copies;
    const uint32_t *copy_original; /* [num_copies] */
    const uint32_t *copies_sorted; /* [num_copies] */

    /* Edge bundles: bundle b holds internal edges bundle_edges[
     * bundle_offsets[b] .. bundle_offsets[b+1]); bundled_sorted lists the
     * bundled edges ascending and bundled_bundle their bundles. */
    uint32_t num_bundles;
    uint32_t num_bundled;           /* bundle_offsets[num_bundles], 0 without bundles */
    const uint32_t *bundle_offsets; /* [num_bundles + 1], may be NULL without bundles */
    const uint32_t *bundle_edges;   /* [num_bundled] */
    const uint32_t *bundled_sorted; /* [num_bundled] */
    const uint32_t *bundled_bundle; /* [num_bundled] */

    /* Edge-connected component of each internal vertex (numbered as
     * report->components), MT_NONE for an isolated vertex; NULL when the
     * mesh has at most one component. */
    const uint32_t *vert_component; /* [num_verts_internal] or NULL */
} mt_mesh_parts;

/* Points *out_parts at the mesh's own arrays (valid until the mesh is edited
 * or destroyed; nothing is copied). A NULL mesh gives zero counts. */
void mt_mesh_get_parts(const mt_mesh *mesh, mt_mesh_parts *out_parts);

/* Makes a mesh from parts and its report without a rebuild: copies every
 * array and the report's lists (the caller keeps its own), checks that the
 * counts agree with each other (num_verts_internal = num_verts + num_copies,
 * num_bundled = bundle_offsets[num_bundles], the report's vertex and face
 * counts, arrays present for non-zero counts, defect kinds known), then runs
 * mt_mesh_validate. The arrays may come from a file: whatever their values,
 * nothing is read out of bounds, and a mesh returned is safe for every query
 * and edit. On MT_OK *out_mesh owns its copies (free with mt_mesh_destroy).
 * Otherwise *out_mesh is NULL and the status is MT_ERR_INVALID_ARG (NULL
 * arguments, counts that disagree, a missing array), MT_ERR_TOO_LARGE (past
 * 2^31 - 1 half-edges), MT_ERR_CORRUPT (bundle_offsets not ending at
 * num_bundled, or validation failed; diag names the broken invariant and
 * the element) or MT_ERR_NOMEM. */
mt_status mt_mesh_restore(const mt_mesh_parts *parts, const mt_report *report, mt_mesh **out_mesh,
                          mt_diag *diag);

/* Restoring without a copy, for a reader that can fill the arrays in place
 * (an HDF5 read straight into them): mt_mesh_restore_begin allocates a
 * pending mesh with arrays of the sizes `shape` gives and hands out
 * pointers to them; the caller fills every one; mt_mesh_restore_finish
 * then checks and validates it exactly as mt_mesh_restore does. A pending
 * mesh must not be queried, edited or passed anywhere but to
 * mt_mesh_restore_finish or mt_mesh_destroy. */
typedef struct mt_mesh_shape {
    uint32_t num_verts, num_verts_internal, num_faces, num_half_edges;
    uint32_t num_copies, num_bundles, num_bundled;
    bool has_positions;      /* positions gets 3 * num_verts doubles */
    bool has_vert_component; /* vert_component gets num_verts_internal entries */
} mt_mesh_shape;

/* Writable arrays of a pending mesh; the lengths are those of mt_mesh_parts
 * (bundle_offsets: num_bundles + 1, NULL without bundles); positions and
 * vert_component are NULL unless the shape asked for them. */
typedef struct mt_mesh_parts_buffers {
    uint32_t *he_head, *he_next, *he_face;
    uint32_t *face_he, *vert_he;
    double *positions;
    uint32_t *copy_original, *copies_sorted;
    uint32_t *bundle_offsets, *bundle_edges, *bundled_sorted, *bundled_bundle;
    uint32_t *vert_component;
} mt_mesh_parts_buffers;

/* Allocates a pending mesh of the given shape. On MT_OK *out_pending and
 * *out_buffers are set; MT_ERR_INVALID_ARG when num_verts_internal is not
 * num_verts + num_copies or bundled edges come without bundles,
 * MT_ERR_TOO_LARGE past 2^31 - 1 half-edges, MT_ERR_NOMEM. */
mt_status mt_mesh_restore_begin(const mt_mesh_shape *shape, mt_mesh **out_pending,
                                mt_mesh_parts_buffers *out_buffers, mt_diag *diag);

/* Checks the filled arrays of a pending mesh against each other and the
 * report (copied), then runs mt_mesh_validate. Always consumes `pending`:
 * on MT_OK *out_mesh is the mesh, otherwise the pending mesh is freed,
 * *out_mesh is NULL and the status is as for mt_mesh_restore. */
mt_status mt_mesh_restore_finish(mt_mesh *pending, const mt_report *report, mt_mesh **out_mesh,
                                 mt_diag *diag);

#ifdef __cplusplus
}
#endif

#endif
