/* Mesh files: OFF, OBJ, PLY (ASCII, binary little and big endian) and STL
 * (ASCII and binary) to and from face lists, gzip-compressed files
 * included. Nothing is welded, reordered or dropped by reading: vertex
 * order, face order and every face record, degenerate and out-of-range ones
 * too, come through as they are in the file (an STL file gives a soup:
 * three new vertices per triangle). Welding is a separate, explicit step
 * (mt_face_list_weld). This is its own library (meshtopo::io) because
 * reading .gz needs zlib, and the core library depends on libc and libm
 * only. */
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
    MT_FORMAT_PLY_BINARY_BE,
    MT_FORMAT_STL_ASCII,
    MT_FORMAT_STL_BINARY /* little endian, as every binary STL file is */
} mt_format;

/* Short name: "off", "obj", "ply-ascii", "ply-le", "ply-be", "stl-ascii",
 * "stl-binary", "auto". */
const char *mt_format_name(mt_format format);

/* Format named by a path's suffix (".off", ".obj", ".ply", ".stl", each
 * optionally followed by ".gz"); ".ply" gives MT_FORMAT_PLY_BINARY_LE and
 * ".stl" MT_FORMAT_STL_BINARY. MT_FORMAT_AUTO when the suffix is unknown. */
mt_format mt_format_from_path(const char *path);

/* Reading options; a zeroed struct (or NULL) gives the defaults. */
typedef struct mt_read_options {
    /* The largest input read, in bytes after gzip inflation: a longer input
     * fails with MT_ERR_TOO_LARGE naming the limit, as soon as it is known to
     * be longer (at once for a plain file, else when inflation passes the
     * limit). 0: MT_READ_DEFAULT_MAX_INPUT_BYTES. */
    uint64_t max_input_bytes;
    /* Bytes of input held at once while a file or gzip data is parsed
     * (0: MT_READ_DEFAULT_WINDOW_BYTES); a token or PLY header longer than
     * the window widens it, up to MT_READ_MAX_HELD_BYTES. Plain text parsed
     * on several threads holds one window more: the next one, read while
     * the threads parse. Nonzero also makes
     * mt_read_memory_with parse a plain buffer through such a window, as a
     * file is (for tests: the result is the same). */
    size_t window_bytes;
    /* Threads that parse text (OFF, ASCII PLY, OBJ) at once: 0 (the default)
     * takes one per online core, up to 4; 1 parses on the calling thread
     * only. The result is the same whatever the count. */
    unsigned threads;
} mt_read_options;

/* 16 GiB: the default of mt_read_options.max_input_bytes. */
#define MT_READ_DEFAULT_MAX_INPUT_BYTES ((uint64_t)16 << 30)
/* 3 MiB: the default of mt_read_options.window_bytes: large enough that
 * text in it is worth parsing on several threads, and chosen against 4 MiB
 * by measurement (docs/performance/inspect.md, "Window size"). */
#define MT_READ_DEFAULT_WINDOW_BYTES ((size_t)3 << 20)
/* 4 MiB: the longest token (or PLY header) read from a file or gzip data;
 * a longer one fails with MT_ERR_TOO_LARGE. */
#define MT_READ_MAX_HELD_BYTES ((size_t)4 << 20)
/* 1 MiB: how much whitespace (and, in OFF, comments) may follow the last
 * element an OFF or PLY header declares. Reading stops there: more fails
 * with MT_ERR_PARSE at the byte past the allowance. */
#define MT_READ_MAX_TRAILING_BYTES ((uint64_t)1 << 20)

/* Reads a mesh file into *out (free with mt_face_list_free). A gzip file is
 * recognised by its magic bytes whatever its name. With MT_FORMAT_AUTO the
 * format comes from the content ("OFF", "ply" headers; for a file, in its
 * first 64 KiB) and otherwise the name. OBJ: v and f lines (f entries a,
 * a/b, a/b/c, a//c; negative indices are relative; index 0 is stored as
 * -1, i.e. out of range); other lines ignored. PLY: x y z of the vertex
 * element, vertex_indices (or vertex_index) of the face element; other
 * properties skipped.
 *
 * STL: every facet becomes a face of new vertices, in file order (facet f
 * has vertices 3f, 3f+1, 3f+2); normals and attribute byte counts are
 * skipped. Binary STL (80-byte header, uint32 little-endian triangle
 * count, 50 bytes per triangle, float32 little-endian coordinates stored
 * exactly as doubles) is recognised by its length being 84 + 50 * count,
 * even when its header starts with "solid"; otherwise a file starting with
 * "solid" and text-like in its first 256 bytes is ASCII STL ("solid",
 * facets of "facet normal n n n / outer loop / vertex x y z ... / endloop /
 * endfacet", "endsolid"; keywords in any case; several solids in a row;
 * a loop of more than 3 vertices gives a polygon), one that is not is
 * binary, and an unrecognised ".stl" file is read as binary (so that a
 * truncated one says how many triangles it lacks). For gzip data the
 * length is learned first (inflating it once) when it decides.
 *
 * Memory. The file is parsed as it is read (and inflated), through a window
 * of mt_read_options.window_bytes, and the face list grows as elements are
 * read, never by the counts a header declares beyond what the input can
 * hold: a read holds the mesh read so far and a fixed window (or two),
 * whatever the file's size or what it inflates to. Where the input's
 * length is known from the start (a plain file, a buffer), the face list
 * gets room at once for the counts a header declares, once they are
 * checked against it (below). OFF and PLY stop at the counts their
 * header declares (see MT_READ_MAX_TRAILING_BYTES). Those counts are
 * checked against the bytes that follow them: at once for a plain file or
 * buffer; gzip data tells its length only at its end, so before the face
 * list grows past 64 MiB the rest of the data is inflated once, not kept,
 * to learn it (for gzip from a buffer or a regular file; from a pipe,
 * max_input_bytes is the bound). A gzip file that inflates to gigabytes of
 * plausible data under a header declaring more is so refused before memory
 * is spent on it.
 *
 * Order of errors in gzip data: damage in the data (a bad checksum,
 * truncation) is found when the parser reaches it, and a size check when
 * the data's length is learned; an error met in the data before either is
 * reported instead (a plain file reports the size check first).
 *
 * Errors: MT_ERR_PARSE with diag naming the file, the line (text) or byte
 * offset (binary; in the compressed bytes for damaged gzip data) and the
 * problem; MT_ERR_IO when the file cannot be read; MT_ERR_TOO_LARGE past
 * the limits above or meshtopo's (2^31 - 1 vertices, 2^32 - 1 faces);
 * *out is then left zeroed. */
mt_status mt_read_file(const char *path, mt_format format, mt_face_list *out, mt_diag *diag);

/* mt_read_file with options (NULL: the defaults). */
mt_status mt_read_file_with(const char *path, mt_format format, const mt_read_options *options,
                            mt_face_list *out, mt_diag *diag);

/* The same from an open file descriptor (a pipe, standard input, a
 * socket, or a file), read to its end and not closed. `name` is used in
 * messages only (NULL: "fd N"). A descriptor that is not a regular file is
 * read once, as a pipe (max_input_bytes bounds it). */
mt_status mt_read_fd_with(int fd, const char *name, mt_format format,
                          const mt_read_options *options, mt_face_list *out, mt_diag *diag);

/* The same from a buffer in memory (already decompressed, or gzip: it is
 * recognised and inflated as it is parsed). `name` is used in messages only
 * (may be NULL). */
mt_status mt_read_memory(const void *data, size_t size, mt_format format, const char *name,
                         mt_face_list *out, mt_diag *diag);

/* mt_read_memory with options (NULL: the defaults). */
mt_status mt_read_memory_with(const void *data, size_t size, mt_format format, const char *name,
                              const mt_read_options *options, mt_face_list *out, mt_diag *diag);

/* Writes a face list. MT_FORMAT_AUTO takes the format from the path's
 * suffix; a path ending in ".gz" is gzip-compressed. Positions are written
 * as the shortest decimal that reads back to the same double (text formats)
 * or as float64 (binary PLY); a list without positions gets zeros. Face
 * records are written as they are, out-of-range indices as their signed
 * value. The file is written to a temporary name and renamed into place.
 *
 * STL stores triangles by their corners' positions: a face of n > 3
 * entries is written as the fan (0, k, k+1), k = 1 .. n-2, each triangle
 * with the unit normal of its corners (zero for a degenerate one) and an
 * attribute byte count of 0. Binary STL rounds positions to float32 (ASCII
 * STL keeps every double). Faces of fewer than 3 entries and out-of-range
 * indices cannot be written: MT_ERR_UNSUPPORTED naming the face, before a
 * file is created; so is more than 2^32 - 1 triangles in binary STL. */
mt_status mt_write_file(const char *path, mt_format format, const mt_face_list *list,
                        mt_diag *diag);

/* Options for mt_write_file_with; a zeroed struct (or NULL) gives
 * mt_write_file. */
typedef struct mt_write_options {
    /* Colours as red, green, blue bytes: 3 x num_verts for the vertices,
     * 3 x num_faces for the face records (NULL: none). PLY only: written as
     * "property uchar red / green / blue" of the vertex and face elements,
     * after x, y, z and after vertex_indices, as MeshLab and Open3D read
     * them. Read during the call, not kept. */
    const uint8_t *vertex_colors;
    const uint8_t *face_colors;
} mt_write_options;

/* mt_write_file with options (NULL: the defaults). MT_ERR_UNSUPPORTED,
 * before a file is created, for colours with a format other than PLY. */
mt_status mt_write_file_with(const char *path, mt_format format, const mt_face_list *list,
                             const mt_write_options *options, mt_diag *diag);

/* ---- Welding ------------------------------------------------------------ */

/* What mt_face_list_weld did. */
typedef struct mt_weld_stats {
    uint32_t vertices_before; /* list->num_verts before */
    uint32_t vertices_after;  /* list->num_verts after */
    uint32_t merged;          /* vertices_before - vertices_after */
} mt_weld_stats;

/* Merges vertices of a face list by position, in place: with eps == 0
 * those with identical coordinates (compared as values: -0.0 equals 0.0),
 * with eps > 0 those within Euclidean distance eps (a spatial hash of cells
 * of side eps, the 27 cells around a vertex searched: linear expected
 * time). A vertex with a NaN or infinite coordinate is never merged.
 *
 * Vertices are taken in id order; each merges into the lowest-numbered
 * earlier survivor within eps of it, else survives. Survivors keep their
 * own positions and their order (new ids ascend with the old ones); face
 * indices are remapped, out-of-range ones kept as they are, no face is
 * dropped (faces that lose corners to the weld stay, as degenerate
 * records the build reports). Merging is not transitive: a vertex is
 * compared with survivors only, so every merged vertex lies within eps of
 * the survivor it merged into, and a chain of points eps/2 apart does not
 * collapse into one. The result does not depend on hashing.
 *
 * out_map (may be NULL): list->num_verts entries (the count before) that
 * receive each old vertex's new id. out_stats may be NULL. Errors:
 * MT_ERR_INVALID_ARG (NULL list, inconsistent list, a list with vertices
 * but no positions, eps negative or not finite), MT_ERR_NOMEM; the list is
 * then unchanged. */
mt_status mt_face_list_weld(mt_face_list *list, double eps, uint32_t *out_map,
                            mt_weld_stats *out_stats, mt_diag *diag);

#ifdef __cplusplus
}
#endif

#endif
