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

/* Reads what mt_archive_list shows of one file into *e (file_name is set
 * by the caller). */
mt_status mt__archive_read_entry(const mt_archive *archive, const char *file_name,
                                 mt_archive_entry *e, mt_diag *diag);

#endif
