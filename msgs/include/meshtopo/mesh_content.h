/* The content of a mesh_t (msgs/mesh_t.lcm: the fields num_verts to
 * face_vertex_indices) as bytes, exactly as LCM encodes them, for messages
 * that carry it in pieces (msgs/mesh_chunk_t.lcm): encoding any byte range
 * of it straight from the arrays, and turning received bytes into the arrays
 * in place, hashing them on the way. LCM's generated code encodes and
 * decodes only whole messages, which would mean encoding a 100 MB mesh whole
 * before its first chunk leaves and decoding it into a second copy after its
 * last one arrives; these functions let chunks be made and consumed as they
 * travel. Their bytes are LCM's (the tests compare them with its encoder). */
#ifndef MESHTOPO_MESH_CONTENT_H
#define MESHTOPO_MESH_CONTENT_H

#include <stddef.h>
#include <stdint.h>

#include "lcmtypes/meshtopo_mesh_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Bytes of m's content once encoded: 16 for the four counts, then 8 per
 * position value and 4 per face count and per index. Counts are read as
 * unsigned (a negative count is not a message m could encode). */
uint64_t mt_msgs_mesh_content_size(const meshtopo_mesh_t *m);

/* Writes bytes [offset, offset + length) of m's encoded content to out
 * (length bytes). The range must lie within mt_msgs_mesh_content_size(m);
 * m's arrays must hold what its counts say. */
void mt_msgs_mesh_content_encode(const meshtopo_mesh_t *m, uint64_t offset, size_t length,
                                 uint8_t *out);

/* Turns the content of a mesh_t, received in pieces into one buffer, into
 * host-order arrays in that same buffer, while hashing it (content_hash.h).
 * The caller writes bytes anywhere in the buffer and, each time the bytes
 * [0, ready) are all present, calls mt_msgs_content_decoder_advance(ready);
 * the decoder hashes them and converts every whole value among them, so the
 * work follows the arrival of the data. */
typedef struct mt_msgs_content_decoder mt_msgs_content_decoder;

/* A decoder for `total` bytes of content in `bytes` (not owned; it must stay
 * valid, be aligned for doubles, as malloc's memory is, and only be written
 * beyond the ready prefix). NULL when out of memory. */
mt_msgs_content_decoder *mt_msgs_content_decoder_new(uint8_t *bytes, uint64_t total);

/* Bytes [0, ready) are present (ready <= total; a smaller ready than before
 * changes nothing). Hashes and converts what is new. */
void mt_msgs_content_decoder_advance(mt_msgs_content_decoder *decoder, uint64_t ready);

/* Once bytes [0, total) were advanced over: *out_hash gets the content hash
 * of the received bytes, and, when the counts describe exactly `total`
 * bytes, out's content fields get the counts and point into the buffer (out
 * does not own them: never pass it to meshtopo_mesh_t_decode_cleanup with
 * them set) and 0 is returned. Otherwise -1, with a message naming the field
 * and the sizes in error (error_size bytes, NUL-terminated); *out_hash is set
 * all the same. -1 too, saying so, before everything was advanced over. */
int mt_msgs_content_decoder_finish(mt_msgs_content_decoder *decoder, meshtopo_mesh_t *out,
                                   uint64_t *out_hash, char *error, size_t error_size);

/* Frees the decoder (not the buffer). NULL-safe. */
void mt_msgs_content_decoder_free(mt_msgs_content_decoder *decoder);

#ifdef __cplusplus
}
#endif

#endif
