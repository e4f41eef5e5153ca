/* The content hash of a submitted mesh, as msgs/mesh_t.lcm defines it:
 * 64-bit FNV-1a over the bytes LCM encodes for mesh_t's content fields,
 * num_verts to face_vertex_indices (the tail of the encoded message). The
 * daemon hashes what it received, the client what it sent; both call this. */
#ifndef MESHTOPO_CONTENT_HASH_H
#define MESHTOPO_CONTENT_HASH_H

#include <stddef.h>
#include <stdint.h>

#include "lcmtypes/meshtopo_mesh_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Starting value of a 64-bit FNV-1a hash. */
#define MT_MSGS_FNV1A_BASIS 0xcbf29ce484222325ull

/* Continues a 64-bit FNV-1a hash over n bytes. */
uint64_t mt_msgs_fnv1a(uint64_t hash, const void *bytes, size_t n);

/* The content hash of msg, given the whole encoded message it was decoded
 * from or encoded to. 0 when encoded_size is smaller than the content fields
 * msg's counts imply (not a message msg came from). */
uint64_t mt_msgs_mesh_content_hash(const meshtopo_mesh_t *msg, const void *encoded,
                                   size_t encoded_size);

#ifdef __cplusplus
}
#endif

#endif
