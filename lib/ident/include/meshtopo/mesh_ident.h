/* meshtopo::ident: what names a submitted mesh version, shared by the LCM
 * messages (msgs/) and the archive (lib/archive) so that neither depends on
 * the other: the mesh-id rule and the content hash of a face list. The
 * content hash is the one msgs/mesh_t.lcm defines: XXH3-64 (xxHash 0.8,
 * seed 0) over the bytes LCM encodes for mesh_t's content fields, num_verts
 * to face_vertex_indices: each count and value big-endian, in that order:
 *
 *   num_verts (int32), num_position_values (int32, 3 * num_verts or 0),
 *   positions (float64 each), num_faces (int32), face_vertex_counts (int32
 *   each), num_indices (int32), face_vertex_indices (int32 each).
 *
 * It is stored in archive files and compared on the wire: it never changes.
 * Pure functions, any thread; no LCM, no HDF5. */
#ifndef MESHTOPO_MESH_IDENT_H
#define MESHTOPO_MESH_IDENT_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/face_list.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Longest mesh id in bytes (msgs/mesh_t.lcm's MESH_ID_MAX, which msgs checks
 * at compile time against this). */
#define MT_MESH_ID_MAX 255

/* Checks a mesh id: not NULL, not empty, at most MT_MESH_ID_MAX bytes,
 * printable ASCII only (0x20 to 0x7e), no '/' and no "..". Mesh ids come
 * from the network and end up in archive names and logs, so a bad one is
 * refused rather than repaired. Returns MT_OK or MT_ERR_INVALID_ARG with
 * diag (NULL-safe) naming the rule broken and diag->byte_offset the
 * offending byte (UINT64_MAX for the NULL, empty and length rules). */
mt_status mt_mesh_id_check(const char *id, mt_diag *diag);

/* XXH3-64 of n bytes (the hash function of the content hash, for digests
 * built the same way). */
uint64_t mt_content_hash_bytes(const void *bytes, size_t n);

/* The content hash of a face list (positions NULL: num_position_values 0).
 * MT_ERR_TOO_LARGE, with diag, for a list whose counts do not fit mesh_t's
 * int32 fields (num_verts above INT32_MAX / 3, num_faces or num_indices
 * above INT32_MAX): its content hash is not defined. MT_ERR_INVALID_ARG for
 * NULL arguments. */
mt_status mt_face_list_content_hash(const mt_face_list *faces, uint64_t *out_hash, mt_diag *diag);

/* The content hash computed piece by piece, for content that is not in
 * memory all at once (an archive file read a block at a time): add the
 * counts and arrays in the order above, then take the digest. Values are
 * given in host order and hashed big-endian. */
typedef struct mt_content_hasher mt_content_hasher;

/* A new hasher, or NULL when out of memory. */
mt_content_hasher *mt_content_hasher_new(void);

/* Adds one count (num_verts, num_position_values, num_faces, num_indices). */
void mt_content_hasher_count(mt_content_hasher *hasher, uint32_t count);

/* Adds n int32 values (face sizes or indices; uint32_t and int32_t give the
 * same bits). */
void mt_content_hasher_int32s(mt_content_hasher *hasher, const uint32_t *values, size_t n);

/* Adds n float64 values (positions). */
void mt_content_hasher_doubles(mt_content_hasher *hasher, const double *values, size_t n);

/* The content hash of everything added so far (more may still be added). */
uint64_t mt_content_hasher_digest(const mt_content_hasher *hasher);

/* Frees a hasher. NULL-safe. */
void mt_content_hasher_free(mt_content_hasher *hasher);

#ifdef __cplusplus
}
#endif

#endif
