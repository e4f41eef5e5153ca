/* Internal pieces of meshtopo::archive shared by its files: the archive
 * handle, diagnostics helpers, the names of temporary files, and the HDF5
 * helpers (archive_h5.c) that read attributes and datasets with their type
 * and shape checked. Nothing here is part of the public API. */
#ifndef MESHTOPO_ARCHIVE_INTERNAL_H
#define MESHTOPO_ARCHIVE_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <hdf5.h>

#include "meshtopo/archive.h"
#include "meshtopo/mesh_parts.h"
#include "meshtopo/msgs.h"
#include "meshtopo/protocol.h"

struct mt_archive {
    char *dir;
    bool read_only;
    size_t leftovers_removed;
};

/* Prefix of temporary files: ".mt-tmp-<pid>-<counter>.part". A leading dot
 * keeps them out of listings; the pid tells whether the writer still runs. */
#define MT__ARCHIVE_TMP_PREFIX ".mt-tmp-"

/* Largest array (elements) a file may claim before anything is allocated:
 * 2^31 - 1, the face list's and mesh_t's limit. */
#define MT__ARCHIVE_MAX_ELEMENTS 0x7fffffffull

/* Fills diag (NULL-safe) with status and a printf message; returns status. */
mt_status mt__archive_fail(mt_diag *diag, mt_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* "dir/name" (malloc'ed), NULL when out of memory. */
char *mt__archive_path(const mt_archive *archive, const char *name);

/* strdup (not in C11). */
char *mt__archive_strdup(const char *text);

/* Parses "<stem>.v<version>.vtkhdf": writes the stem's length and the
 * version (>= 1, no leading zeros). False for any other name. */
bool mt__archive_name_parse(const char *name, size_t *out_stem_len, uint32_t *out_version);

/* Milliseconds on a monotonic clock. */
double mt__archive_now_ms(void);

/* ---- HDF5 helpers (archive_h5.c). Each returns MT_OK or fills diag with a
 * message naming `file` and the object; none of them lets HDF5 print. ---- */

/* Turns off HDF5's automatic error printing (once per process). */
void mt__h5_quiet(void);

mt_status mt__h5_write_attr_int(hid_t obj, const char *name, hid_t type, const void *value,
                                const char *file, mt_diag *diag);
mt_status mt__h5_write_attr_ints(hid_t obj, const char *name, hid_t type, const void *values,
                                 hsize_t count, const char *file, mt_diag *diag);
mt_status mt__h5_write_attr_string(hid_t obj, const char *name, const char *value, const char *file,
                                   mt_diag *diag);
/* A dataset of `rank` dimensions (1 or 2) in file type ftype from memory of
 * type mtype (which may be a same-size reinterpretation). */
mt_status mt__h5_write_dataset(hid_t loc, const char *name, hid_t ftype, hid_t mtype, int rank,
                               const hsize_t *dims, const void *data, const char *file,
                               mt_diag *diag);

/* How large datasets are stored: contiguous, or chunked with shuffle and
 * deflate (mt_archive_write_options). */
typedef struct mt__h5_layout {
    bool deflate;
    unsigned level; /* deflate level 1..9; 0 means 1 */
} mt__h5_layout;

/* Bytes per chunk of a deflated dataset (HDF5's default chunk cache holds
 * one such chunk per dataset). */
#define MT__H5_CHUNK_BYTES (1u << 20)

/* mt__h5_write_dataset with a layout (NULL = contiguous). Datasets under
 * 4 KiB stay contiguous whatever the layout. */
mt_status mt__h5_write_dataset_layout(hid_t loc, const char *name, hid_t ftype, hid_t mtype,
                                      int rank, const hsize_t *dims, const void *data,
                                      const mt__h5_layout *layout, const char *file, mt_diag *diag);

/* Creates a 1-D dataset of `rows` rows with the layout (NULL = contiguous)
 * for mt__h5_write_rows; -1 (diag filled) on failure. */
hid_t mt__h5_create_dataset(hid_t loc, const char *name, hid_t ftype, hsize_t rows,
                            const mt__h5_layout *layout, const char *file, mt_diag *diag);

/* Writes rows first .. first + count of a 1-D dataset from memory of type
 * mtype. `name` is for the message. */
mt_status mt__h5_write_rows(hid_t dset, hid_t mtype, hsize_t first, hsize_t count, const void *data,
                            const char *file, const char *name, mt_diag *diag);

/* Kind of element a read expects: integers of a given size and signedness,
 * floats, or a compound whose members HDF5 matches by name (elem_size is
 * then not checked; a missing member makes the read fail). */
typedef enum mt__h5_kind { MT__H5_INT, MT__H5_UINT, MT__H5_FLOAT, MT__H5_COMPOUND } mt__h5_kind;

/* Reads a scalar (or one-element) integer attribute into *out (int64). The
 * stored type must be an integer of at most 8 bytes. */
mt_status mt__h5_read_attr_i64(hid_t obj, const char *name, const char *file, int64_t *out,
                               mt_diag *diag);
/* The same for an unsigned 64-bit value stored as uint64. */
mt_status mt__h5_read_attr_u64(hid_t obj, const char *name, const char *file, uint64_t *out,
                               mt_diag *diag);
/* Reads a string attribute (fixed or variable length, at most max_len
 * bytes) into a malloc'ed NUL-terminated string. */
mt_status mt__h5_read_attr_string(hid_t obj, const char *name, const char *file, size_t max_len,
                                  char **out, mt_diag *diag);
/* Reads a whole dataset of rank `rank` whose second dimension (rank 2) is
 * `cols`, with element type of `kind` and exactly `elem_size` bytes, into a
 * malloc'ed buffer of memory type mtype; *out_rows is the first dimension.
 * Refuses more than MT__ARCHIVE_MAX_ELEMENTS rows before allocating. */
mt_status mt__h5_read_dataset(hid_t loc, const char *name, const char *file, int rank, hsize_t cols,
                              mt__h5_kind kind, size_t elem_size, hid_t mtype, void **out_data,
                              uint64_t *out_rows, mt_diag *diag);

/* The first dimension of a dataset, with the checks of mt__h5_read_dataset
 * but nothing read. */
mt_status mt__h5_dataset_rows(hid_t loc, const char *name, const char *file, int rank, hsize_t cols,
                              mt__h5_kind kind, size_t elem_size, uint64_t *out_rows,
                              mt_diag *diag);

/* Reads a whole dataset into buf, which holds `rows` rows: any other row
 * count is MT_ERR_PARSE ("has N rows, the counts say M"). */
mt_status mt__h5_read_dataset_into(hid_t loc, const char *name, const char *file, int rank,
                                   hsize_t cols, mt__h5_kind kind, size_t elem_size, hid_t mtype,
                                   void *buf, uint64_t rows, mt_diag *diag);

/* ---- The topology report in a file (archive_report.c) ---- */

/* Type of a scalar report field. */
typedef enum mt__field_type {
    MT__FIELD_U32,
    MT__FIELD_U64,
    MT__FIELD_I32,
    MT__FIELD_I64,
    MT__FIELD_BOOL
} mt__field_type;

/* One scalar field of mt_report, stored as an attribute of the same name. */
typedef struct mt__report_field {
    const char *name;
    size_t offset;
    mt__field_type type;
} mt__report_field;

extern const mt__report_field mt__report_fields[];
extern const size_t mt__num_report_fields;

/* Writes the report into group `group`: every scalar field as an attribute,
 * num_defects too, and the lists as datasets (boundary_loop_lengths,
 * components, face_size_histogram, edge_use_histogram, defects). */
mt_status mt__report_write(hid_t group, const mt_report *report, const char *file, mt_diag *diag);

/* Reads the scalar attributes into *out (arrays NULL, their counts 0) and
 * the num_defects attribute. */
mt_status mt__report_read_scalars(hid_t group, const char *file, mt_report *out,
                                  uint64_t *out_num_defects, mt_diag *diag);

/* Reads the whole report (free with mt_archive_report_free), checking every
 * list's length against its count and every value's range. */
mt_status mt__report_read(hid_t group, const char *file, mt_report *out, mt_diag *diag);

/* ---- Reading (archive_read.c) ---- */

/* Opens file_name of the archive read-only after checking it is a regular
 * file; *out_file is an HDF5 file id to close with H5Fclose.
 * *out_bytes (may be NULL) is its size. */
mt_status mt__archive_h5_open(const mt_archive *archive, const char *file_name, hid_t *out_file,
                              uint64_t *out_bytes, mt_diag *diag);

/* Opens group `name` of loc; -1 (diag filled: MT_ERR_PARSE) when missing
 * or unreadable. */
hid_t mt__archive_group_open(hid_t loc, const char *name, const char *file, mt_diag *diag);

/* Reads the provenance attributes of /meshtopo (group g) into r (mesh_id,
 * source, version, utime, content_hash, format_version) and checks that
 * they give file_name. */
mt_status mt__archive_read_provenance(hid_t g, const char *file_name, mt_archive_record *r,
                                      mt_diag *diag);

/* Reads and decodes the face list datasets of /meshtopo (group g). */
mt_status mt__archive_read_faces(hid_t g, const char *file_name, mt_face_list *out, mt_diag *diag);

/* ---- The half-edge arrays in a file (archive_halfedge.c), format 2 ---- */

/* Writes group /meshtopo/halfedge (under g = /meshtopo) from the mesh's
 * arrays (mt_mesh_get_parts); positions are /meshtopo/positions already. */
mt_status mt__halfedge_write(hid_t g, const mt_mesh *mesh, const mt__h5_layout *layout,
                             const char *file, mt_diag *diag);

/* Restores the mesh of /meshtopo/halfedge and /meshtopo/positions (g =
 * /meshtopo) with `report`: the counts come from the group's attributes
 * and /meshtopo's num_verts and num_faces, every dataset's length is
 * checked against them, the arrays are read straight into the pending
 * mesh (mt_mesh_restore_begin) and mt_mesh_restore_finish validates them.
 * Messages name the file and the dataset or the invariant broken. */
mt_status mt__halfedge_restore(hid_t g, const char *file, const mt_report *report,
                               mt_mesh **out_mesh, mt_diag *diag);

/* Whether two meshes' arrays are identical; otherwise writes the first
 * difference into buf ("he_next[17]: 4 != 5"). */
bool mt__parts_equal(const mt_mesh_parts *a, const mt_mesh_parts *b, char *buf, size_t size);

/* The file name of version `version` (0 = the highest archived) of mesh_id
 * into name (MT_ARCHIVE_FILE_NAME_MAX + 1 bytes); MT_ERR_NOT_FOUND when
 * there is no such file, MT_ERR_INVALID_ARG for a bad id. */
mt_status mt__archive_resolve(const mt_archive *archive, const char *mesh_id, uint32_t version,
                              char *name, mt_diag *diag);

/* Reads what mt_archive_list shows of one file into *e (file_name is set
 * by the caller). */
mt_status mt__archive_read_entry(const mt_archive *archive, const char *file_name,
                                 mt_archive_entry *e, mt_diag *diag);

#endif
