/* Internal pieces of meshtopo::archive shared by its files: the archive
 * handle, diagnostics helpers (errno text included), the names of temporary
 * files, files opened so nothing planted redirects them (archive_fd.c), the
 * HDF5 helpers (archive_h5.c) that read attributes and datasets with their
 * type and shape checked, and the checks a load and a verification share
 * (archive_check.c). Nothing here is part of the public API. */
#ifndef MESHTOPO_ARCHIVE_INTERNAL_H
#define MESHTOPO_ARCHIVE_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/stat.h>

#include <hdf5.h>

#include "meshtopo/archive.h"
#include "meshtopo/mesh_ident.h"
#include "meshtopo/mesh_parts.h"

struct mt_archive {
    char *dir;
    bool read_only;
    size_t leftovers_removed;
    mt_archive_hash_fn content_hash; /* mt_archive_set_content_hash, may be NULL */
    void *content_hash_ctx;
};

/* Prefix of temporary files: ".mt-tmp-<pid>-<16 random hex digits>.<host>.part"
 * (meshtopo before format 4 used "<pid>-<counter>.part", then until
 * clusters "<pid>-<16 hex>.part"). A leading dot keeps them out of
 * listings; the pid and host tell whether the writer still runs; the random
 * part (getrandom) makes the name unguessable. */
#define MT__ARCHIVE_TMP_PREFIX ".mt-tmp-"
/* Longest host name put in a temporary file's name. */
#define MT__ARCHIVE_HOST_MAX 64

/* This machine's host name as it goes into temporary file names: at most
 * MT__ARCHIVE_HOST_MAX bytes of [A-Za-z0-9.-], anything else as '_'. */
void mt__archive_host(char *out, size_t size);

/* Prefix of files set aside (mt_archive_set_aside): hidden, never listed,
 * never removed as leftovers. */
#define MT__ARCHIVE_ASIDE_PREFIX ".mt-aside-"

/* Largest array (elements) a file may claim before anything is allocated:
 * 2^31 - 1, the face list's and mesh_t's limit. */
#define MT__ARCHIVE_MAX_ELEMENTS 0x7fffffffull

/* Fills diag (NULL-safe) with status and a printf message; returns status. */
mt_status mt__archive_fail(mt_diag *diag, mt_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The errno of the last operating-system failure reported through
 * mt__archive_fail_os or found on HDF5's error stack by the HDF5 helpers,
 * in this thread (0: none since it was last reset). The checks reset it and
 * read it to tell a system failure (MT_ARCHIVE_FAULT_SYSTEM) from a damaged
 * file. */
extern _Thread_local int mt__archive_last_errno;

/* mt__archive_fail with ": <strerror(err)>" and, for a full disk or a file
 * size limit, the limit appended ("No space left on device (4096 bytes
 * free on the file system of PATH)", "File too large (the file size limit,
 * RLIMIT_FSIZE, is N bytes)"). `path` (may be NULL) is the file that
 * failed, for the free-space figure. Sets mt__archive_last_errno. */
mt_status mt__archive_fail_os(mt_diag *diag, mt_status status, int err, const char *path,
                              const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* strerror(err) plus the limit behind ENOSPC, EDQUOT or EFBIG, into buf. */
void mt__archive_errno_text(int err, const char *path, char *buf, size_t size);

/* "dir/name" (malloc'ed), NULL when out of memory. */
char *mt__archive_path(const mt_archive *archive, const char *name);

/* strdup (not in C11). */
char *mt__archive_strdup(const char *text);

/* The length of name's archive suffix (MT_ARCHIVE_SUFFIX or
 * MT_ARCHIVE_SUFFIX_LEGACY), 0 when it has neither. */
size_t mt__archive_suffix_len(const char *name);

/* Parses "<stem>.v<version>.hdf" (or the legacy ".vtkhdf"): writes the
 * stem's length and the version (>= 1, no leading zeros). False for any
 * other name. */
bool mt__archive_name_parse(const char *name, size_t *out_stem_len, uint32_t *out_version);

/* Whether file_name is the name of version `version` of mesh_id, with
 * either suffix. */
bool mt__archive_name_matches(const char *file_name, const char *mesh_id, uint32_t version);

/* fsync of the archive directory, so that a new, renamed or removed name
 * survives a power loss; MT_ERR_IO with the errno text. */
mt_status mt__archive_fsync_dir(const mt_archive *archive, mt_diag *diag);

/* Milliseconds on a monotonic clock. */
double mt__archive_now_ms(void);

/* ---- HDF5 helpers (archive_h5.c). Each returns MT_OK or fills diag with a
 * message naming `file` and the object; none of them lets HDF5 print. ---- */

/* Turns off HDF5's automatic error printing (once per process). */
void mt__h5_quiet(void);

/* The errno an HDF5 file driver recorded on the current error stack ("...,
 * errno = 28, error message = 'No space left on device'") after a failed
 * HDF5 call, 0 when the failure was not the system's. Call it right after
 * the failing call: the next HDF5 call clears the stack. */
int mt__h5_os_errno(void);

/* mt__archive_fail for a failed HDF5 call: appends the system's reason
 * when HDF5's error stack holds one (mt__h5_os_errno). */
mt_status mt__h5_fail(mt_diag *diag, mt_status status, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

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

/* How large datasets are stored (mt_archive_write_options). */
typedef struct mt__h5_layout {
    mt_archive_compression compression; /* DEFAULT and NONE: contiguous */
    unsigned level;                     /* deflate level 1..9; 0 means 1 */
} mt__h5_layout;

/* HDF5's registered id of the Blosc filter (a plugin). */
#define MT__H5_FILTER_BLOSC 32001

/* Bytes per chunk of a compressed dataset (HDF5's default chunk cache
 * holds one such chunk per dataset). */
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

/* Called with each block of rows mt__h5_read_blocks reads. */
typedef void (*mt__h5_block_fn)(void *ctx, void *rows, size_t n);

/* Reads a 1-D dataset (checked as mt__h5_read_dataset checks it) a block of
 * at most block_rows rows at a time into buf (block_rows elements of mtype)
 * and hands each block to fn, so that a large dataset is streamed through a
 * small buffer; *out_rows is its length. */
mt_status mt__h5_read_blocks(hid_t loc, const char *name, const char *file, mt__h5_kind kind,
                             size_t elem_size, hid_t mtype, void *buf, size_t block_rows,
                             mt__h5_block_fn fn, void *ctx, uint64_t *out_rows, mt_diag *diag);

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
 * components, face_size_histogram, edge_use_histogram, defects as defect
 * records with a description attribute). */
mt_status mt__report_write(hid_t group, const mt_report *report, const char *file, mt_diag *diag);

/* Reads the scalar attributes into *out (arrays NULL, their counts 0) and
 * the num_defects attribute. */
mt_status mt__report_read_scalars(hid_t group, const char *file, mt_report *out,
                                  uint64_t *out_num_defects, mt_diag *diag);

/* Reads the whole report (free with mt_archive_report_free), checking every
 * list's length against its count and every value's range. The defects are
 * in the layout of the file's format_version. */
mt_status mt__report_read(hid_t group, uint32_t format_version, const char *file, mt_report *out,
                          mt_diag *diag);

/* XXH3-64 of every value the file stores of the report (the fields of
 * mt__report_fields, then each list's length and rows), each as 64
 * little-endian bits, so the hash of a report read back is the hash of the
 * report written. MT_ERR_NOMEM only. */
mt_status mt__report_hash(const mt_report *report, uint64_t *out, mt_diag *diag);

/* ---- Files opened and created safely (archive_fd.c) ---- */

/* "/proc/self/fd/N" for fd into buf (at least 32 bytes), when /proc is
 * mounted and that name leads to fd's own file (same device and inode).
 * Opening it opens that file, whatever the directory entry it came from has
 * become since: HDF5, which opens files only by name, is handed this name. */
bool mt__fd_proc_path(int fd, char *buf, size_t size);

/* 16 hex digits of random bytes (getrandom; a clock and counter mix when
 * the kernel has none to give) into out[17]. */
void mt__archive_random_hex(char out[17]);

/* Opens file_name of the archive for reading, refusing (MT_ERR_IO, message
 * "refused: ...", fault MT_ARCHIVE_FAULT_UNSAFE) a symbolic link, anything
 * not a regular file, and a file not owned by the effective user; never
 * follows a link, never blocks on a FIFO, never opens a device. *out_fd is
 * the open file (O_CLOEXEC) and *out_sb its fstat. MT_ERR_NOT_FOUND or
 * MT_ERR_IO with the errno text (fault MT_ARCHIVE_FAULT_SYSTEM) when the
 * system refuses. */
mt_status mt__archive_open_fd(const mt_archive *archive, const char *file_name, int *out_fd,
                              struct stat *out_sb, mt_archive_fault *out_fault, mt_diag *diag);

/* ---- Reading (archive_read.c) ---- */

/* Opens file_name of the archive read-only: mt__archive_open_fd's checks,
 * then HDF5 opens that very file (through mt__fd_proc_path; without /proc
 * by name, with the opened file's identity compared afterwards).
 * *out_file is an HDF5 file id to close with H5Fclose. *out_bytes (may be
 * NULL) is its size. *out_fault (may be NULL) says what a failure was:
 * UNSAFE, SYSTEM, or CONTENT for a file HDF5 cannot read. */
mt_status mt__archive_h5_open(const mt_archive *archive, const char *file_name, hid_t *out_file,
                              uint64_t *out_bytes, mt_archive_fault *out_fault, mt_diag *diag);

/* The fault a failed read of a file's contents stands for: SYSTEM when
 * mt__archive_last_errno is set or memory ran out, NEWER for a format
 * version above this meshtopo's, CONTENT otherwise. */
mt_archive_fault mt__archive_read_fault(mt_status status);

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
 * arrays (mt_mesh_get_parts), with their digest (mt__halfedge_digest of
 * the arrays, positions and report, seeded with content_hash) as attribute
 * "digest"; positions are /meshtopo/positions already. */
mt_status mt__halfedge_write(hid_t g, const mt_mesh *mesh, uint64_t content_hash,
                             const mt__h5_layout *layout, const char *file, mt_diag *diag);

/* Reads the arrays of /meshtopo/halfedge and /meshtopo/positions (g =
 * /meshtopo) into a pending mesh (mt_mesh_restore_begin): the counts come
 * from the group's attributes and /meshtopo's num_verts and num_faces and
 * every dataset's length is checked against them. `positions` (may be
 * NULL) are the face list's, already read: they are copied instead of read
 * again. On MT_OK *out_pending is to be finished (mt_mesh_restore_finish)
 * or destroyed, and *out_parts points at its arrays. Messages name the
 * file and the dataset. */
mt_status mt__halfedge_read(hid_t g, const char *file, const double *positions,
                            mt_mesh **out_pending, mt_mesh_parts *out_parts, mt_diag *diag);

/* mt__halfedge_read, then mt_mesh_restore_finish with `report` (which
 * validates the arrays); messages name the file and the invariant broken. */
mt_status mt__halfedge_restore(hid_t g, const char *file, const mt_report *report,
                               const double *positions, mt_mesh **out_mesh, mt_diag *diag);

/* The digest attribute of /meshtopo/halfedge (format 4): see
 * mt__halfedge_digest. MT_ERR_PARSE when missing or not a uint64. */
mt_status mt__halfedge_read_digest(hid_t g, const char *file, uint64_t *out, mt_diag *diag);

/* ---- The hashes a load checks (archive_hash.c) ---- */

/* mt_archive_content_hash of the face list stored in /meshtopo (group g),
 * read a block at a time straight from face_vertex_counts and
 * face_vertex_indices (no copy of the face list is made), with `positions`
 * (3 * num_verts doubles, or NULL) standing for the positions dataset they
 * were read from. MT_ERR_TOO_LARGE for counts past mesh_t's, as
 * mt_archive_content_hash. */
mt_status mt__content_hash_stored(hid_t g, const char *file, uint32_t num_verts,
                                  const double *positions, uint64_t *out, mt_diag *diag);

/* The digest a format 4 file stores with its half-edge arrays: XXH3-64
 * over content_hash, the counts, the XXH3-64 of each array of p (in the
 * order of /meshtopo/halfedge's description), of the positions and of the
 * report's stored fields (mt__report_fields and the lists), every value as
 * little-endian 64 bits. MT_ERR_NOMEM only. */
mt_status mt__halfedge_digest(const mt_mesh_parts *p, const mt_report *report,
                              uint64_t content_hash, uint64_t *out, mt_diag *diag);

/* Whether two meshes' arrays are identical; otherwise writes the first
 * difference into buf ("he_next[17]: 4 != 5"). */
bool mt__parts_equal(const mt_mesh_parts *a, const mt_mesh_parts *b, char *buf, size_t size);

/* The file name of version `version` (0 = the highest archived) of mesh_id
 * into name (MT_ARCHIVE_FILE_NAME_MAX + 1 bytes); MT_ERR_NOT_FOUND when
 * there is no such file, MT_ERR_INVALID_ARG for a bad id. */
mt_status mt__archive_resolve(const mt_archive *archive, const char *mesh_id, uint32_t version,
                              char *name, mt_diag *diag);

/* Reads what mt_archive_list shows of one file into *e (file_name is set
 * by the caller; e->fault is set too). */
mt_status mt__archive_read_entry(const mt_archive *archive, const char *file_name,
                                 mt_archive_entry *e, mt_diag *diag);

/* ---- The topology arrays of /VTKHDF (format 6) ----
 * archive_topology.c works them out from a mesh (no HDF5),
 * archive_topology_write.c writes them, archive_topology_check.c compares a
 * file's with a mesh's. The list of arrays and their meaning is in
 * archive.h ("Topology as VTK arrays"). */

typedef enum mt__topo_id {
    MT__TOPO_CELL_COMPONENT,
    MT__TOPO_CELL_DEFECTS,
    MT__TOPO_CELL_TOUCHES_BOUNDARY,
    MT__TOPO_CELL_ORIENTATION_CONSISTENT,
    MT__TOPO_CELL_SELF_INTERSECTING,
    MT__TOPO_POINT_BOUNDARY,
    MT__TOPO_POINT_NON_MANIFOLD,
    MT__TOPO_POINT_DEFECTS,
    MT__TOPO_COUNT
} mt__topo_id;

/* Element type of a topology array. */
typedef enum mt__topo_type { MT__TOPO_INT32, MT__TOPO_UINT32, MT__TOPO_UINT8 } mt__topo_type;

/* What the file says of one array: its name in CellData or PointData, its
 * type, the value of a mesh without anything to show, and its description
 * attribute; bitmask arrays also get the "bits" attribute. */
typedef struct mt__topo_info {
    const char *name;
    bool cell; /* CellData (one row per kept face), else PointData (per vertex) */
    mt__topo_type type;
    uint32_t fill;
    bool bitmask;
    const char *description;
} mt__topo_info;

extern const mt__topo_info mt__topo_arrays[MT__TOPO_COUNT];

/* Bytes of one element of a topology array. */
size_t mt__topo_type_size(mt__topo_type type);

/* Size of a per-kind array's name with its NUL ("defect_" and the longest
 * defect key, with room to spare). */
#define MT__TOPO_KIND_NAME_MAX 48

/* The name of the 0/1 array of defect kind `kind` written beside each
 * defects bitmask (format 8): "defect_" and the kind's key, for example
 * defect_nonmanifold_edge. */
void mt__topo_kind_name(mt_defect_kind kind, char *buf, size_t size);

/* A mesh's topology arrays. values[id] holds rows[id] elements of the
 * array's type, or is NULL when every element is the array's fill value;
 * present[id] is false only for self_intersecting when it was not worked
 * out (absent_reason says why). */
typedef struct mt__topology {
    uint64_t cells, points; /* kept faces, vertices */
    void *values[MT__TOPO_COUNT];
    bool present[MT__TOPO_COUNT];
    uint64_t self_intersection_pairs; /* when present */
    const char *absent_reason;        /* static text, when self_intersecting is absent */
} mt__topology;

/* Works out the topology arrays of mesh, built from list (the writer's
 * checks have passed). self_intersections: SKIP, or COMPUTE
 * (mt_mesh_self_intersections; a mesh without positions gets it absent),
 * or GIVEN with the pairs (refused with MT_ERR_INVALID_ARG when a pair
 * names a face out of range or rejected). On MT_OK free *out with
 * mt__topology_free; on failure nothing is left to free. */
mt_status mt__topology_compute(const mt_face_list *list, const mt_mesh *mesh,
                               mt_archive_self_intersections self_intersections,
                               const mt_face_pair *pairs, size_t num_pairs, mt__topology *out,
                               mt_diag *diag);

/* Frees what mt__topology_compute made and zeroes it. NULL-safe. */
void mt__topology_free(mt__topology *topology);

/* The value of element i of array id (its fill value when values[id] is
 * NULL), as 64 bits. */
int64_t mt__topology_value(const mt__topology *topology, mt__topo_id id, uint64_t i);

/* Writes the arrays into /VTKHDF's CellData (group cell_data) and
 * PointData (point_data) with their attributes; a constant array is a
 * dataset never written, whose fill value is that constant. */
mt_status mt__topology_write(hid_t cell_data, hid_t point_data, const mt__topology *topology,
                             const mt__h5_layout *layout, const char *file, mt_diag *diag);

/* Compares the topology arrays of /VTKHDF in file with the ones mesh
 * gives (mesh built from or restored with faces): every array but
 * self_intersecting must be there with the same values (the per-kind
 * defect_<key> arrays from format_version 8 on);
 * self_intersecting, when there, must have a row per cell and values 0 or
 * 1. MT_ERR_PARSE naming the dataset and the first difference,
 * MT_ERR_NOMEM, MT_ERR_IO when HDF5 fails a read. */
mt_status mt__topology_check(hid_t file, const mt_face_list *faces, const mt_mesh *mesh,
                             uint32_t format_version, const char *file_name, mt_diag *diag);

/* Writes a 1-D attribute of `count` fixed-length strings (as long as the
 * longest; NUL-padded ASCII). */
mt_status mt__h5_write_attr_strings(hid_t obj, const char *name, const char *const *values,
                                    size_t count, const char *file, mt_diag *diag);

/* Reads a whole 1-D dataset of exactly `rows` rows into buf (rows elements
 * of mtype) without the check of the stored bytes mt__h5_read_dataset
 * makes: for a dataset whose length the caller knows from elsewhere and
 * which may never have been written (it reads as its fill value). Any
 * other row count is MT_ERR_PARSE. */
mt_status mt__h5_read_known_rows(hid_t loc, const char *name, const char *file, mt__h5_kind kind,
                                 size_t elem_size, hid_t mtype, void *buf, uint64_t rows,
                                 mt_diag *diag);

/* ---- Attributes (archive_attributes.c) ---- */

/* Writes the mesh's attributes into /meshtopo (g) when it has any. */
mt_status mt__attributes_write(hid_t g, const mt_mesh *mesh, const mt__h5_layout *layout,
                               const char *file, mt_diag *diag);

/* Adds the attributes stored in /meshtopo (g) to mesh; edge and half-edge
 * ones only when `restored` (the mesh's ids are the stored arrays'). */
mt_status mt__attributes_read(hid_t g, const char *file, mt_mesh *mesh, bool restored,
                              mt_diag *diag);

/* ---- What a load and a verification check (archive_check.c) ---- */

/* One file checked: its record, the mesh to serve and what was wrong. */
typedef struct mt__check {
    /* In. */
    mt_archive_hash_fn hash; /* NULL: the content hash is not checked */
    void *hash_ctx;
    bool keep_faces; /* leave the face list in record.faces */
    /* Out. */
    mt_archive_record record;
    mt_mesh *mesh;
    mt_archive_fault fault;
    bool restored;     /* mesh made from the stored arrays */
    bool hash_checked; /* the face list's content hash was checked */
    mt_diag fallback;  /* why the stored arrays or report were not used */
    double read_ms, mesh_ms, check_ms;
} mt__check;

/* Checks the open file (file_name of the archive) the way
 * mt_archive_load_mesh_file documents, filling c's outputs. On MT_OK
 * c->mesh and c->record are the caller's (mt_mesh_destroy,
 * mt_archive_record_free) and c->fault is NONE or DERIVED; on failure both
 * are freed and c->fault says what failed. */
mt_status mt__archive_check(hid_t file, const char *file_name, mt__check *c, mt_diag *diag);

#endif
