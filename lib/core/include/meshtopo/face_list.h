/* A mesh as a plain polygon face list: positions, face sizes and flat vertex
 * indices (the USD-style face_vertex_counts / face_vertex_indices). It is the
 * input of mt_mesh_build and the output of the file readers and generators. */
#ifndef MESHTOPO_FACE_LIST_H
#define MESHTOPO_FACE_LIST_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The arrays are plain pointers: a caller may point them at its own memory
 * (mt_mesh_build only reads them) or let mt_face_list_alloc allocate them,
 * in which case mt_face_list_free releases them.
 *
 * face_indices holds num_indices entries, face i using face_sizes[i] of them
 * in order. A value >= num_verts is an out-of-range index; a negative index
 * read from a file (OBJ's 0 becomes -1) is stored as its two's complement,
 * so it is out of range too and prints back as negative with
 * mt_index_as_signed(). Nothing in a face list is ever required to be valid:
 * the builder reports every defect. */
typedef struct mt_face_list {
    uint32_t num_verts;
    uint32_t num_faces;
    uint64_t num_indices;
    double *positions;      /* 3 * num_verts doubles (x, y, z), or NULL: no geometry */
    uint32_t *face_sizes;   /* num_faces entries */
    uint32_t *face_indices; /* num_indices entries */
} mt_face_list;

/* Allocates zero-filled arrays for the given sizes (positions included) and
 * sets the counts. On failure *out is left zeroed and nothing is allocated. */
mt_status mt_face_list_alloc(mt_face_list *out, uint32_t num_verts, uint32_t num_faces,
                             uint64_t num_indices, mt_diag *diag);

/* Frees arrays allocated by mt_face_list_alloc (or by a reader or generator)
 * and zeroes the struct. NULL-safe. Do not call it on caller-owned arrays. */
void mt_face_list_free(mt_face_list *list);

/* Checks that the sizes are consistent: the face sizes add up to num_indices
 * without overflow and every pointer needed for a non-zero count is set.
 * This is the only thing a face list must satisfy; indices are not checked. */
mt_status mt_face_list_check(const mt_face_list *list, mt_diag *diag);

/* Shuffles vertex ids and face order with a deterministic generator seeded by
 * seed (positions move with their vertices; each face keeps its cyclic order).
 * Used to test and benchmark meshes in cache-unfriendly order, as real scans
 * arrive. Out-of-range indices are kept as they are. */
mt_status mt_face_list_permute(mt_face_list *list, uint64_t seed, mt_diag *diag);

/* A face-list index as the signed value it was read as (for messages). */
static inline int64_t mt_index_as_signed(uint32_t index)
{
    return index >= 0x80000000u ? (int64_t)index - 0x100000000ll : (int64_t)index;
}

#ifdef __cplusplus
}
#endif

#endif
