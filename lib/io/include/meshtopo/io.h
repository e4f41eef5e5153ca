/* Mesh files: OFF, OBJ and PLY (ASCII, binary little and big endian) to and
 * from face lists, gzip-compressed files included. Nothing is welded,
 * reordered or dropped: vertex order, face order and every face record,
 * degenerate and out-of-range ones too, come through as they are in the
 * file. This is its own library (meshtopo::io) because reading .gz needs
 * zlib, and the core library depends on libc and libm only. */
#ifndef MESHTOPO_IO_H
#define MESHTOPO_IO_H

#include <stddef.h>
#include <stdint.h>

#include "meshtopo/face_list.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mt_format {
    MT_FORMAT_AUTO = 0, /* reading: from the content (and the name); writing: from the name */
    MT_FORMAT_OFF,
    MT_FORMAT_OBJ,
    MT_FORMAT_PLY_ASCII,
    MT_FORMAT_PLY_BINARY_LE,
    MT_FORMAT_PLY_BINARY_BE
} mt_format;

/* Short name: "off", "obj", "ply-ascii", "ply-le", "ply-be", "auto". */
const char *mt_format_name(mt_format format);

/* Format named by a path's suffix (".off", ".obj", ".ply", each optionally
 * followed by ".gz"); ".ply" gives MT_FORMAT_PLY_BINARY_LE. MT_FORMAT_AUTO
 * when the suffix is unknown. */
mt_format mt_format_from_path(const char *path);

/* Reads a mesh file into *out (free with mt_face_list_free). A gzip file is
 * recognised by its magic bytes whatever its name. With MT_FORMAT_AUTO the
 * format comes from the content ("OFF", "ply" headers) and otherwise the
 * name. OBJ: v and f lines (f entries a, a/b, a/b/c, a//c; negative indices
 * are relative; index 0 is stored as -1, i.e. out of range); other lines
 * ignored. PLY: x y z of the vertex element, vertex_indices (or
 * vertex_index) of the face element; other properties skipped.
 * Parse errors: MT_ERR_PARSE with diag naming the file, the line (text) or
 * byte offset (binary) and the problem; MT_ERR_IO when the file cannot be
 * read; *out is then left zeroed. */
mt_status mt_read_file(const char *path, mt_format format, mt_face_list *out, mt_diag *diag);

/* The same from a buffer in memory (already decompressed, or gzip: it is
 * recognised and inflated). `name` is used in messages only (may be NULL). */
mt_status mt_read_memory(const void *data, size_t size, mt_format format, const char *name,
                         mt_face_list *out, mt_diag *diag);

/* Writes a face list. MT_FORMAT_AUTO takes the format from the path's
 * suffix; a path ending in ".gz" is gzip-compressed. Positions are written
 * as the shortest decimal that reads back to the same double (text formats)
 * or as float64 (binary PLY); a list without positions gets zeros. Face
 * records are written as they are, out-of-range indices as their signed
 * value. The file is written to a temporary name and renamed into place. */
mt_status mt_write_file(const char *path, mt_format format, const mt_face_list *list,
                        mt_diag *diag);

#ifdef __cplusplus
}
#endif

#endif
