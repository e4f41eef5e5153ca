/* Data users attach to a mesh's elements: named attributes (one value of a
 * fixed number of bytes per element) and the `hidden` flag, on vertices,
 * edges, half-edges and faces. Elements are named by their ids: caller
 * vertex and face ids, and the internal edge and half-edge ids of the raw
 * view (mesh.h: edge e has half-edges 2e and 2e + 1).
 *
 * Attributes live with the mesh: edits keep the values of the elements
 * they keep (an edge an edit takes out and puts back as another edge in the
 * same edit, the flipped diagonal, keeps its id and values), elements an
 * edit adds start with every byte zero, and mt_mesh_compact carries every
 * value to the element's new id. The archive (meshtopo/archive.h) writes
 * them and a load gives them back.
 *
 * The hidden flag of a kind is its attribute named MT_ATTRIBUTE_HIDDEN, one
 * byte per element (0 shown, 1 hidden), made by the first mt_set_hidden. */
#ifndef MESHTOPO_ATTRIBUTES_H
#define MESHTOPO_ATTRIBUTES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/mesh.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The kinds of elements. */
typedef enum mt_element_kind {
    MT_ELEMENT_VERTEX = 0,
    MT_ELEMENT_EDGE = 1,
    MT_ELEMENT_HALF_EDGE = 2,
    MT_ELEMENT_FACE = 3,
} mt_element_kind;

#define MT_ELEMENT_KIND_COUNT 4

/* "vertex", "edge", "half_edge", "face"; "unknown" for other values. */
const char *mt_element_kind_name(mt_element_kind kind);

/* How many ids a kind has: caller vertices, internal edges, half-edges,
 * face records (deleted and rejected ones included). 0 for a NULL mesh or
 * an unknown kind. */
uint32_t mt_mesh_num_elements(const mt_mesh *mesh, mt_element_kind kind);

/* Longest attribute name (bytes), largest value, most attributes per kind. */
#define MT_ATTRIBUTE_NAME_MAX 63
#define MT_ATTRIBUTE_VALUE_MAX 1024
#define MT_ATTRIBUTES_PER_KIND 64

/* The name of the hidden flags' attribute. */
#define MT_ATTRIBUTE_HIDDEN "hidden"

/* Adds attribute `name` (1 to MT_ATTRIBUTE_NAME_MAX bytes of letters,
 * digits, '_', '-' and '.') to every element of `kind`, value_bytes bytes
 * each (1 to MT_ATTRIBUTE_VALUE_MAX), all zero. MT_ERR_INVALID_ARG for a bad
 * name, size or kind, or a name the kind already has; MT_ERR_TOO_LARGE past
 * MT_ATTRIBUTES_PER_KIND; MT_ERR_NOMEM. */
mt_status mt_attribute_add(mt_mesh *mesh, mt_element_kind kind, const char *name,
                           uint32_t value_bytes, mt_diag *diag);

/* Removes an attribute and its values. MT_ERR_NOT_FOUND when the kind has no
 * attribute of that name. */
mt_status mt_attribute_remove(mt_mesh *mesh, mt_element_kind kind, const char *name, mt_diag *diag);

/* How many attributes a kind has, and the name and value size of the i-th
 * (in the order they were added; MT_ERR_OUT_OF_RANGE past the count). The
 * name stays valid until the attribute is removed. */
size_t mt_attribute_count(const mt_mesh *mesh, mt_element_kind kind);
mt_status mt_attribute_info(const mt_mesh *mesh, mt_element_kind kind, size_t index,
                            const char **out_name, uint32_t *out_value_bytes);

/* The value of element `id`: value_bytes bytes copied to or from `value`,
 * whose size must be the attribute's value size. MT_ERR_NOT_FOUND for an
 * unknown attribute, MT_ERR_OUT_OF_RANGE for an id past the kind's count,
 * MT_ERR_INVALID_ARG for a size that differs. */
mt_status mt_attribute_get(const mt_mesh *mesh, mt_element_kind kind, const char *name, uint32_t id,
                           void *value, size_t size, mt_diag *diag);
mt_status mt_attribute_set(mt_mesh *mesh, mt_element_kind kind, const char *name, uint32_t id,
                           const void *value, size_t size, mt_diag *diag);

/* Every value at once: element i's value is the value_bytes bytes at
 * (*out_values) + i * value_bytes, for i below *out_count (the kind's
 * count). Writable; valid until the next edit, compaction or attribute
 * added or removed. MT_ERR_NOT_FOUND for an unknown attribute. */
mt_status mt_attribute_values(mt_mesh *mesh, mt_element_kind kind, const char *name,
                              uint8_t **out_values, uint32_t *out_value_bytes, uint32_t *out_count,
                              mt_diag *diag);

/* Hides or shows an element (making the kind's hidden attribute when it has
 * none). MT_ERR_OUT_OF_RANGE for an id past the kind's count. */
mt_status mt_set_hidden(mt_mesh *mesh, mt_element_kind kind, uint32_t id, bool hidden,
                        mt_diag *diag);

/* Whether an element is hidden: false without a hidden attribute or for an
 * id out of range. */
bool mt_is_hidden(const mt_mesh *mesh, mt_element_kind kind, uint32_t id);

/* Makes the queries of meshtopo/query.h leave hidden elements out (skip
 * true) or list them like any other (false, the default). While skipping:
 *  - mt_vert_ring lists a neighbour only when it, the edge to it and the
 *    half-edge from the vertex to it are shown, and a face only when it is
 *    shown; a fan left with neither is not listed. Each fan keeps its
 *    counter-clockwise order, but once something is left out the k-th face
 *    no longer lies between the k-th and (k+1)-th neighbours.
 *  - mt_vert_valence counts the neighbours mt_vert_ring lists.
 *  - mt_face_verts, mt_face_neighbors and mt_face_component answer
 *    MT_ERR_NOT_FOUND for a hidden face; mt_face_neighbors leaves hidden
 *    faces out of what is across each side.
 *  - mt_edge_faces answers MT_ERR_NOT_FOUND for a hidden edge and leaves
 *    hidden faces out (MT_ERR_NOT_FOUND when none is left).
 * Boundary loops, components and the report describe the whole mesh. The
 * setting is the mesh's: set it before sharing the mesh between threads.
 * MT_ERR_INVALID_ARG for a NULL mesh. */
mt_status mt_mesh_skip_hidden(mt_mesh *mesh, bool skip);

#ifdef __cplusplus
}
#endif

#endif
