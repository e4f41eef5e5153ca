/* The content hash of a submitted mesh, as msgs/mesh_t.lcm defines it:
 * XXH3-64 (xxHash 0.8, seed 0) over the bytes LCM encodes for mesh_t's
 * content fields, num_verts to face_vertex_indices (the tail of the encoded
 * message). The daemon hashes what it received, the client what it sends;
 * both call these (or mesh_content.h's decoder, which hashes as it goes).
 * The same hash of a face list, without LCM, is meshtopo::ident's
 * (meshtopo/mesh_ident.h), which the archive uses. */
#ifndef MESHTOPO_CONTENT_HASH_H
#define MESHTOPO_CONTENT_HASH_H

#include <stddef.h>
#include <stdint.h>

#include "lcmtypes/meshtopo_mesh_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The content hash of n bytes of encoded content. */
uint64_t mt_msgs_content_hash_bytes(const void *bytes, size_t n);

/* The content hash of msg, given the whole encoded message it was decoded
 * from or encoded to. 0 when encoded_size is smaller than the content fields
 * msg's counts imply (not a message msg came from). */
uint64_t mt_msgs_mesh_content_hash(const meshtopo_mesh_t *msg, const void *encoded,
                                   size_t encoded_size);

/* The content hash of msg's content fields, encoded a block at a time (no
 * copy of the whole content is made). msg's arrays must hold what its counts
 * say. */
uint64_t mt_msgs_mesh_content_hash_of(const meshtopo_mesh_t *msg);

#ifdef __cplusplus
}
#endif

#endif
