/* meshtopo::archive: built meshes archived to HDF5, one immutable file per
 * mesh version, written crash-safely (temporary name, flush, fsync, rename,
 * directory fsync). Each file is a VTKHDF 1.0 UnstructuredGrid (VTK 9.1's
 * vtkHDFReader and ParaView open it) plus a /meshtopo group holding the face
 * list exactly as submitted, provenance, the build's topology report and
 * (format 2 and later) the half-edge arrays, so that a reload skips the rebuild.
 * Every value read back from a file is checked before use. */
#ifndef MESHTOPO_ARCHIVE_H
#define MESHTOPO_ARCHIVE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/face_list.h"
#include "meshtopo/mesh.h"
#include "meshtopo/report.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Version of the /meshtopo group's layout (attribute format_version)
 * written by this meshtopo. 2 added /meshtopo/halfedge (the half-edge
 * arrays); files of version 1 lack it and still load, by a rebuild from
 * their face list. 3 has the same layout, its content_hash is the one
 * msgs/mesh_t.lcm now defines (XXH3-64); versions 1 and 2 carry the former
 * hash (FNV-1a), which verification does not check. */
#define MT_ARCHIVE_FORMAT_VERSION 3

/* Oldest format version whose content_hash verification checks. */
#define MT_ARCHIVE_FORMAT_VERSION_HASHED 3

/* Oldest format version read. */
#define MT_ARCHIVE_FORMAT_VERSION_MIN 1

/* Suffix of every archive file: ParaView picks its VTKHDF reader by it. */
#define MT_ARCHIVE_SUFFIX ".vtkhdf"

/* The file name (no directory) of version `version` of mesh_id:
 * "<escaped id>.v<version>.vtkhdf". Every id byte outside [A-Za-z0-9_-] is
 * written as %XX (so '.', '/', '%' and ' ' never appear raw); an escaped id
 * longer than 160 bytes keeps its first 140 bytes (whole escapes only)
 * followed by '~' and the 16 hex digits of its 64-bit FNV-1a hash ('~' is
 * always escaped, so the two kinds of names cannot collide). The file's
 * mesh_id attribute holds the id itself. Writes at most size bytes
 * (NUL-terminated when size > 0) and returns the length the full name needs;
 * 0 for an id mt_msgs_mesh_id_check (meshtopo/protocol.h) refuses or
 * version 0. */
size_t mt_archive_file_name(const char *mesh_id, uint32_t version, char *buf, size_t size);

/* Longest name mt_archive_file_name returns, without the NUL. */
#define MT_ARCHIVE_FILE_NAME_MAX 192

typedef struct mt_archive mt_archive;

/* Options for mt_archive_open; a zeroed struct (or NULL) gives the defaults. */
typedef struct mt_archive_options {
    /* Create the directory (one level, mode 0777 & ~umask) when missing. */
    bool create;
    /* Open for reading only: no writes, no removals, and leftovers of
     * interrupted writes are left alone (a writer may be running). */
    bool read_only;
} mt_archive_options;

/* Opens the archive in directory `dir`. Unless read_only, removes leftovers
 * of interrupted writes: temporary files (".mt-tmp-<pid>-...") whose writing
 * process is gone; their number is mt_archive_leftovers_removed(). On MT_OK
 * *out_archive is to be closed with mt_archive_close. MT_ERR_IO when dir is
 * not a directory or cannot be read, with diag naming it. */
mt_status mt_archive_open(const char *dir, const mt_archive_options *options,
                          mt_archive **out_archive, mt_diag *diag);

/* Closes an archive handle. NULL-safe. */
void mt_archive_close(mt_archive *archive);

/* The directory the archive was opened on. */
const char *mt_archive_dir(const mt_archive *archive);

/* Leftover temporary files removed by mt_archive_open. */
size_t mt_archive_leftovers_removed(const mt_archive *archive);

/* Who submitted a mesh version and what it was. Strings are copied. */
typedef struct mt_archive_meta {
    const char *mesh_id;   /* see mt_msgs_mesh_id_check */
    uint32_t version;      /* >= 1 */
    int64_t utime;         /* microseconds since the epoch, from the submission */
    const char *source;    /* the sending node; NULL means "" */
    uint64_t content_hash; /* as the daemon computed it (meshtopo/content_hash.h) */
} mt_archive_meta;

/* Time spent by one mt_archive_write. */
typedef struct mt_archive_write_stats {
    double write_ms;     /* HDF5 create, datasets, flush, close */
    double fsync_ms;     /* fsync of the file, rename, fsync of the directory */
    uint64_t file_bytes; /* size of the archived file */
} mt_archive_write_stats;

/* Archives one built mesh version: `list` is the face list exactly as
 * submitted and `mesh` what mt_mesh_build made of it (its report is stored;
 * faces it rejected are kept in the face list but left out of the VTKHDF
 * cells). When this returns MT_OK the file is durable (renamed into place
 * and the directory fsynced), so a submission may then be acknowledged.
 * An existing version is never overwritten: MT_ERR_INVALID_ARG ("already
 * archived"), like a bad id, version 0 or a mesh that is not list's build.
 * MT_ERR_IO on any HDF5 or file system failure (the temporary file is then
 * removed); MT_ERR_UNSUPPORTED on a read-only handle. out_stats may be NULL. */
mt_status mt_archive_write(mt_archive *archive, const mt_archive_meta *meta,
                           const mt_face_list *list, const mt_mesh *mesh,
                           mt_archive_write_stats *out_stats, mt_diag *diag);

/* How mt_archive_write_with stores the large datasets. */
typedef enum mt_archive_compression {
    /* The default: contiguous, uncompressed. Measured on 1M-triangle grids
     * (meshtopo-bench archive, 111 MB per file), shuffle + deflate level 1
     * makes a scan-like mesh's file 2.2x smaller (a generated grid's 73x)
     * but its write 3x (grid) to 13x (scan-like) slower and its reload
     * slower too; an archive write sits before the acknowledgement of a
     * submission and a reload before the first query. */
    MT_ARCHIVE_COMPRESSION_DEFAULT = 0,
    MT_ARCHIVE_COMPRESSION_NONE,    /* contiguous datasets, no filters */
    MT_ARCHIVE_COMPRESSION_DEFLATE, /* 1 MiB chunks, shuffle + deflate */
} mt_archive_compression;

/* Options for mt_archive_write_with; a zeroed struct (or NULL) gives the
 * defaults. */
typedef struct mt_archive_write_options {
    mt_archive_compression compression;
    /* Deflate level 1..9 with MT_ARCHIVE_COMPRESSION_DEFLATE; 0 means 1. */
    uint32_t deflate_level;
} mt_archive_write_options;

/* mt_archive_write with options (NULL = defaults). Datasets under 4 KiB
 * are stored contiguously whatever the compression. MT_ERR_INVALID_ARG for
 * an unknown compression or a level above 9. */
mt_status mt_archive_write_with(mt_archive *archive, const mt_archive_meta *meta,
                                const mt_face_list *list, const mt_mesh *mesh,
                                const mt_archive_write_options *options,
                                mt_archive_write_stats *out_stats, mt_diag *diag);

/* Whether version `version` of mesh_id has a file in the archive. */
bool mt_archive_contains(const mt_archive *archive, const char *mesh_id, uint32_t version);

/* Topology figures of an archived version, read from its attributes. */
typedef struct mt_archive_summary {
    uint32_t num_verts, num_faces, num_faces_valid;
    uint64_t num_edges;
    uint64_t num_defects;
    uint32_t connected_components;
    uint32_t boundary_loops;
    int64_t euler_characteristic;
    int32_t genus;
    bool closed, manifold, orientable;
} mt_archive_summary;

/* One file of the archive as mt_archive_list sees it. */
typedef struct mt_archive_entry {
    char *file_name;  /* in the archive directory */
    mt_status status; /* MT_OK, or why the file could not be read (diag) */
    mt_diag diag;     /* names the file and the attribute or dataset */
    char *mesh_id;    /* the rest is set only when status is MT_OK */
    uint32_t version;
    int64_t utime;
    char *source;
    uint64_t content_hash;
    uint64_t file_bytes;
    mt_archive_summary summary;
} mt_archive_entry;

typedef struct mt_archive_listing {
    mt_archive_entry *entries; /* readable ones by mesh id then version, then the others by name */
    size_t count;
} mt_archive_listing;

/* Lists every "*.vtkhdf" file of the archive, reading only its attributes.
 * A file that cannot be read is listed with its status; the call fails only
 * when the directory cannot be read (MT_ERR_IO) or memory runs out.
 * Free with mt_archive_listing_free. */
mt_status mt_archive_list(const mt_archive *archive, mt_archive_listing *out, mt_diag *diag);
void mt_archive_listing_free(mt_archive_listing *listing);

/* One archived version read back. Owns everything; free with
 * mt_archive_record_free. */
typedef struct mt_archive_record {
    char *file_name;
    char *mesh_id;
    uint32_t version;
    int64_t utime;
    char *source;
    uint64_t content_hash;
    uint32_t format_version;
    mt_face_list faces; /* exactly as submitted, rejected faces included */
    mt_report report;   /* the report stored when it was archived */
} mt_archive_record;

/* Reads version `version` of mesh_id (0 = its highest archived version).
 * MT_ERR_NOT_FOUND when there is no such file; for a bad file MT_ERR_PARSE
 * (wrong shape, type, count or range; mesh id or version not those of the
 * file name), MT_ERR_IO (not HDF5, truncated) or MT_ERR_TOO_LARGE, with diag
 * naming the file and the dataset or attribute. *out is zeroed on failure. */
mt_status mt_archive_load(const mt_archive *archive, const char *mesh_id, uint32_t version,
                          mt_archive_record *out, mt_diag *diag);

/* The same for one file of the archive directory, by name. */
mt_status mt_archive_load_file(const mt_archive *archive, const char *file_name,
                               mt_archive_record *out, mt_diag *diag);

/* Frees a record and zeroes it. NULL-safe. */
void mt_archive_record_free(mt_archive_record *record);

/* Rebuilds the half-edge mesh of a record from its stored face list,
 * validates it and compares its report with the stored one (what
 * mt_archive_load_mesh falls back to; verify checks every file this way). On MT_OK *out_mesh is the
 * mesh (free with mt_mesh_destroy). MT_ERR_CORRUPT when the reports differ
 * (diag names the first differing field) or validation fails; build errors
 * as mt_mesh_build. out_mesh may be NULL to check only. */
mt_status mt_archive_record_build(const mt_archive_record *record, mt_mesh **out_mesh,
                                  mt_diag *diag);

/* How mt_archive_load_mesh made its mesh. */
typedef struct mt_archive_load_info {
    /* true: restored from /meshtopo/halfedge without a rebuild; false:
     * rebuilt from the face list (a version 1 file, or stored arrays that
     * failed to read or validate). */
    bool restored;
    /* Why the stored arrays were not used, naming the file and the problem
     * (status MT_OK when restored or when the file predates them). */
    mt_diag fallback;
    double read_ms; /* HDF5 reads of attributes, report and face list */
    double mesh_ms; /* arrays read into the mesh and validated, or the rebuild */
} mt_archive_load_info;

/* Reloads one archived version as a queryable mesh: reads provenance, the
 * stored report and, in a format 2 or later file, the half-edge arrays and
 * positions, and makes the mesh with mt_mesh_restore (which validates the
 * untrusted arrays) instead of rebuilding it. When a version 1 file has no
 * arrays, or the arrays cannot be read or fail validation, it falls back to
 * mt_archive_record_build (a rebuild from the face list compared with the
 * stored report) and says why in out_info->fallback; only if that fails too
 * does the call fail (its status, with diag naming the file and both
 * problems). with_faces also reads the face list into out_record->faces
 * (otherwise left empty unless the fallback needed it). out_record may be
 * NULL; otherwise it is filled as mt_archive_load_file fills it (free with
 * mt_archive_record_free). On MT_OK *out_mesh is the mesh (mt_mesh_destroy);
 * on failure it is NULL and out_record is zeroed. out_info may be NULL. */
mt_status mt_archive_load_mesh(const mt_archive *archive, const char *mesh_id, uint32_t version,
                               bool with_faces, mt_archive_record *out_record, mt_mesh **out_mesh,
                               mt_archive_load_info *out_info, mt_diag *diag);

/* The same for one file of the archive directory, by name. */
mt_status mt_archive_load_mesh_file(const mt_archive *archive, const char *file_name,
                                    bool with_faces, mt_archive_record *out_record,
                                    mt_mesh **out_mesh, mt_archive_load_info *out_info,
                                    mt_diag *diag);

/* Compares two reports field by field. Returns true when equal; otherwise
 * writes the first difference ("boundary_loops: 2 != 3") into buf. */
bool mt_archive_report_equal(const mt_report *a, const mt_report *b, char *buf, size_t size);

/* Frees the arrays of a report read from an archive and zeroes it.
 * (Never call it on a mesh's own report.) NULL-safe. */
void mt_archive_report_free(mt_report *report);

/* The content hash of a face list as the daemon computes it. The archive
 * does not link the LCM message library: the caller (the CLI, the daemon)
 * passes the hash function. */
typedef mt_status (*mt_archive_hash_fn)(void *ctx, const mt_face_list *faces, uint64_t *out_hash,
                                        mt_diag *diag);

/* Verifies one file of the archive: readable, every shape and type right,
 * the name matching its mesh id and version, the VTKHDF datasets agreeing
 * with the stored face list, the content hash matching (when hash is not
 * NULL and the file's format is MT_ARCHIVE_FORMAT_VERSION_HASHED or later), a
 * rebuild giving the stored report, and (format 2 and later) the stored
 * half-edge arrays restoring, validating and equal to the rebuild's. MT_OK or the first
 * problem's status with diag naming the file and the problem. */
mt_status mt_archive_verify_file(const mt_archive *archive, const char *file_name,
                                 mt_archive_hash_fn hash, void *hash_ctx, mt_diag *diag);

/* Removes version `version` (>= 1) of mesh_id and fsyncs the directory.
 * MT_ERR_NOT_FOUND when it is not archived; MT_ERR_UNSUPPORTED on a
 * read-only handle. */
mt_status mt_archive_remove(mt_archive *archive, const char *mesh_id, uint32_t version,
                            mt_diag *diag);

/* ---- Decoding of arrays read from a file (no HDF5 involved) ----
 * The reader fetches each dataset into a buffer sized from its (checked)
 * dataspace, then hands the buffers here. These functions check everything
 * that relates the arrays to each other and never read past the lengths
 * given, whatever the values: a fuzz target calls them directly. */

/* The /meshtopo face list datasets as read. */
typedef struct mt_archive_face_arrays {
    int64_t num_verts;       /* attribute num_verts */
    const double *positions; /* positions dataset, positions_rows x 3 (NULL when 0 rows) */
    uint64_t positions_rows; /* num_verts, or 0 for a mesh without geometry */
    const int32_t *counts;   /* face_vertex_counts */
    uint64_t num_counts;     /* its length: the number of faces */
    const int32_t *indices;  /* face_vertex_indices */
    uint64_t num_indices;    /* its length */
} mt_archive_face_arrays;

/* Checks the arrays against each other (num_verts in 0..2^31-1, positions
 * rows equal to num_verts or 0, face sizes non-negative and adding up to
 * num_indices) and copies them into a new face list (*out, free with
 * mt_face_list_free). Indices are kept as they are (out-of-range ones too).
 * MT_ERR_PARSE with diag naming the dataset, MT_ERR_NOMEM. `what` prefixes
 * messages (the file name; may be NULL). */
mt_status mt_archive_decode_faces(const mt_archive_face_arrays *arrays, const char *what,
                                  mt_face_list *out, mt_diag *diag);

/* The VTKHDF datasets as read. */
typedef struct mt_archive_vtk_arrays {
    int64_t number_of_points, number_of_cells, number_of_connectivity_ids;
    const double *points; /* points_rows x 3 */
    uint64_t points_rows;
    const int64_t *connectivity; /* num_connectivity */
    uint64_t num_connectivity;
    const int64_t *offsets; /* num_offsets */
    uint64_t num_offsets;
    const uint8_t *types; /* num_types */
    uint64_t num_types;
    const int64_t *face_ids; /* CellData/original_face_id, num_face_ids */
    uint64_t num_face_ids;
} mt_archive_vtk_arrays;

/* Checks that the VTKHDF arrays are exactly the cells of `faces` whose entry
 * in face_kept is non-zero (face_kept has faces->num_faces entries): counts,
 * offsets, connectivity, cell types (5 triangle, 9 quad, 7 polygon), the
 * original face ids, and points equal to the positions (zeros without
 * geometry). MT_OK or MT_ERR_PARSE naming the first disagreement. */
mt_status mt_archive_check_vtk(const mt_archive_vtk_arrays *vtk, const mt_face_list *faces,
                               const uint8_t *face_kept, const char *what, mt_diag *diag);

#ifdef __cplusplus
}
#endif

#endif
