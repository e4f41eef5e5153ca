/* meshtopo::archive: built meshes archived to HDF5, one immutable file per
 * mesh version, written crash-safely (temporary name, flush, fsync, link,
 * directory fsync). Each file is a VTKHDF 1.0 UnstructuredGrid (VTK 9.1's
 * vtkHDFReader and ParaView open it) plus a /meshtopo group holding the face
 * list exactly as submitted, provenance, the build's topology report and
 * (format 2 and later) the half-edge arrays, so that a reload skips the rebuild.
 * Every value read back from a file is checked before use.
 *
 * Files in the directory are untrusted. Temporary files get unguessable
 * names and are created exclusively (O_CREAT | O_EXCL | O_NOFOLLOW); HDF5
 * writes the file so created, never a name that could have been replaced;
 * the final name is a hard link to that file, which never replaces what is
 * there (a symbolic link included) and never writes through it. Reading
 * opens without following symbolic links and refuses what is not a regular
 * file owned by the process's effective user. Loading a mesh checks the
 * face list's content hash and the stored half-edge arrays (validated, and
 * matched against the digest stored with them) before serving; loading and
 * `archive verify` share those checks and report the same mt_archive_fault
 * for every file. Failures caused by the system carry its errno text (No
 * space left on device, Permission denied) and the file's name. */
#ifndef MESHTOPO_ARCHIVE_H
#define MESHTOPO_ARCHIVE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "meshtopo/face_list.h"
#include "meshtopo/geometry.h"
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
 * hash (FNV-1a), which verification does not check. 4 adds the digest
 * attribute of /meshtopo/halfedge, which lets a load check the stored arrays
 * and report without a rebuild; files of versions 2 and 3 have none, and a
 * load checks their arrays against a rebuild (as slow as version 1's). 5
 * adds the group /meshtopo/attributes (meshtopo/attributes.h), present when
 * the archived mesh has attributes: a load gives them back. 6 adds the
 * topology arrays of /VTKHDF/CellData and /VTKHDF/PointData (see "Topology
 * as VTK arrays" below): loads never read them (they are derived from the
 * mesh), verification checks them; files of earlier versions lack them and
 * load and verify as before. 7 stores /meshtopo/report/defects as defect
 * records (meshtopo/defect_record.h: members kind, vertices, faces, edge,
 * face_count, index, ...) with a description attribute; earlier versions
 * store {kind, a, b, c} (mt_defect), which loads read as before. 8 adds
 * the per-kind arrays CellData/defect_<key> and PointData/defect_<key> (one
 * uint8 0/1 array per defect kind beside each defects bitmask, see
 * "Topology as VTK arrays"): verification checks them in files of format 8
 * and later only, so files of formats 6 and 7, which lack them, verify as
 * before; loads never read them. */
#define MT_ARCHIVE_FORMAT_VERSION 8

/* Oldest format version whose content_hash verification checks. */
#define MT_ARCHIVE_FORMAT_VERSION_HASHED 3

/* Oldest format version whose half-edge arrays carry a digest. */
#define MT_ARCHIVE_FORMAT_VERSION_DIGEST 4

/* Oldest format version whose VTKHDF groups carry the topology arrays. */
#define MT_ARCHIVE_FORMAT_VERSION_TOPOLOGY 6

/* Oldest format version whose defects are defect records. */
#define MT_ARCHIVE_FORMAT_VERSION_DEFECT_RECORDS 7

/* Oldest format version with a 0/1 array per defect kind (defect_<key>). */
#define MT_ARCHIVE_FORMAT_VERSION_DEFECT_KINDS 8

/* Oldest format version read. */
#define MT_ARCHIVE_FORMAT_VERSION_MIN 1

/* Suffix of the archive files written: ParaView picks its reader by the
 * name alone, and ".hdf" is the one name every ParaView with a VTKHDF
 * reader maps to it (Debian 12's ParaView 5.11 maps no other). */
#define MT_ARCHIVE_SUFFIX ".hdf"

/* Suffix of the archive files earlier meshtopo versions wrote: such files
 * are still listed, loaded, verified, set aside and removed, never
 * written. */
#define MT_ARCHIVE_SUFFIX_LEGACY ".vtkhdf"

/* The file name (no directory) of version `version` of mesh_id, as it is
 * written: "<escaped id>.v<version>.hdf". Every id byte outside [A-Za-z0-9_-] is
 * written as %XX (so '.', '/', '%' and ' ' never appear raw); an escaped id
 * longer than 160 bytes keeps its first 140 bytes (whole escapes only)
 * followed by '~' and the 16 hex digits of its 64-bit FNV-1a hash ('~' is
 * always escaped, so the two kinds of names cannot collide). The file's
 * mesh_id attribute holds the id itself. Writes at most size bytes
 * (NUL-terminated when size > 0) and returns the length the full name needs;
 * 0 for an id mt_mesh_id_check (meshtopo/mesh_ident.h) refuses or
 * version 0. */
size_t mt_archive_file_name(const char *mesh_id, uint32_t version, char *buf, size_t size);

/* Longest name mt_archive_file_name returns, without the NUL. */
#define MT_ARCHIVE_FILE_NAME_MAX 192

typedef struct mt_archive mt_archive;

/* A content hash of a face list, to check a stored face list against the
 * hash its submission was acknowledged with: mt_archive_content_hash (the
 * daemon's, meshtopo/mesh_ident.h) or, in tests, a stand-in. */
typedef mt_status (*mt_archive_hash_fn)(void *ctx, const mt_face_list *faces, uint64_t *out_hash,
                                        mt_diag *diag);

/* The daemon's content hash (XXH3-64 over the bytes LCM encodes for
 * mesh_t's content fields: mt_face_list_content_hash, meshtopo/mesh_ident.h)
 * of a face list, as an mt_archive_hash_fn (ctx unused). MT_ERR_TOO_LARGE
 * for a list whose counts do not fit mesh_t's int32 fields. */
mt_status mt_archive_content_hash(void *ctx, const mt_face_list *faces, uint64_t *out_hash,
                                  mt_diag *diag);

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
 * process on this host is gone (those another host wrote, in a directory
 * several machines share, are left to that host); their number is
 * mt_archive_leftovers_removed(). Only
 * regular files owned by the effective user are removed: anything else with
 * such a name (a symbolic link planted there, a directory, another user's
 * file) is left alone, never followed and never opened. On MT_OK
 * *out_archive is to be closed with mt_archive_close. MT_ERR_IO when dir is
 * not a directory or cannot be read, with diag naming it and the errno text. */
mt_status mt_archive_open(const char *dir, const mt_archive_options *options,
                          mt_archive **out_archive, mt_diag *diag);

/* Sets the content hash mt_archive_load_mesh* checks each stored face list
 * against (files of format MT_ARCHIVE_FORMAT_VERSION_HASHED and later) and
 * mt_archive_verify_file* uses when passed none; call it before sharing the
 * handle between threads. NULL (the default): loads do not check it (a face
 * list is then taken as intact when its rebuild gives the stored report).
 * The daemon sets mt_archive_content_hash, which a load computes a block
 * at a time straight from the file. (A setter rather than a member of
 * mt_archive_options: callers initialize that struct positionally.) */
void mt_archive_set_content_hash(mt_archive *archive, mt_archive_hash_fn hash, void *ctx);

/* Closes an archive handle. NULL-safe. */
void mt_archive_close(mt_archive *archive);

/* The directory the archive was opened on. */
const char *mt_archive_dir(const mt_archive *archive);

/* Leftover temporary files removed by mt_archive_open. */
size_t mt_archive_leftovers_removed(const mt_archive *archive);

/* Who submitted a mesh version and what it was. Strings are copied. */
typedef struct mt_archive_meta {
    const char *mesh_id;   /* see mt_mesh_id_check */
    uint32_t version;      /* >= 1 */
    int64_t utime;         /* microseconds since the epoch, from the submission */
    const char *source;    /* the sending node; NULL means "" */
    uint64_t content_hash; /* as the daemon computed it (meshtopo/mesh_ident.h) */
} mt_archive_meta;

/* Time spent by one mt_archive_write. */
typedef struct mt_archive_write_stats {
    double write_ms;     /* HDF5 create, datasets, flush, close */
    double fsync_ms;     /* fsync of the file, link into place, fsync of the directory */
    uint64_t file_bytes; /* size of the archived file */
    double topology_ms;  /* part of write_ms: the topology arrays worked out (the
                            self-intersections included when asked for) */
} mt_archive_write_stats;

/* Topology as VTK arrays (format 6). Besides the cells, /VTKHDF carries
 * what a viewer colours a mesh by. Cells are the faces the build kept, in
 * face order (CellData/original_face_id gives each one's face id); points
 * are all the vertices, in vertex order.
 *
 *   CellData/component               int32  edge-connected component of the
 *                                           face, numbered as the report's
 *                                           components (0 .. n-1)
 *   CellData/defects                 uint32 defect kinds involving the face:
 *                                           bit k (value 1 << k) for kind k of
 *                                           MT_DEFECT_TABLE (meshtopo/report.h)
 *   CellData/touches_boundary        uint8  1: a side of the face is a
 *                                           boundary edge (used by one face)
 *   CellData/orientation_consistent  uint8  1: every face that is the only
 *                                           other face on one of this face's
 *                                           edges runs that edge the
 *                                           opposite way; 0: one runs it the
 *                                           same way (both faces get 0);
 *                                           edges of three or more faces do
 *                                           not count
 *   CellData/self_intersecting       uint8  1: the face meets another face
 *                                           other than along what they share
 *                                           (mt_mesh_self_intersections);
 *                                           present only when the write was
 *                                           asked for it (otherwise CellData's
 *                                           attribute self_intersecting says
 *                                           why it is missing)
 *   PointData/boundary               uint8  1: the vertex ends a boundary edge
 *   PointData/non_manifold           uint8  1: the vertex is listed as a
 *                                           nonmanifold_vertex of the report
 *                                           (for example a bowtie, or the end
 *                                           of a non-manifold edge)
 *   PointData/defects                uint32 defect kinds involving the vertex,
 *                                           the bits of CellData/defects
 *   CellData/defect_<key>,           uint8  (format 8) one array per defect
 *   PointData/defect_<key>                  kind, named by its key
 *                                           (defect_nonmanifold_edge, ...):
 *                                           1 where the defects bitmask
 *                                           beside it has that kind's bit,
 *                                           else 0; attribute "bit" is k
 *
 * The bitmask arrays stay for the programs that read them; the per-kind
 * arrays are what a viewer shows by name. VTKHDF has no place for a lookup
 * table or its annotations, and vtkHDFReader (VTK 9.1, ParaView 5.11's VTK
 * 9.2) turns only datasets, not HDF5 attributes, into VTK arrays, so the
 * "bits" attribute never reaches ParaView: coloured by defects, ParaView
 * shows a continuous scale over the bitmask values (0 .. 56 for kinds 3, 4
 * and 5) that names no kind. An array per kind is listed by its name in
 * ParaView's colouring menu and titles its scalar bar, with no script and
 * in every VTK reader. A categorical legend of the bitmask itself (a name
 * per value) needs a lookup table set up by a script:
 * tools/vtk/paraview_defects.py (installed in share/meshtopo).
 *
 * A defect involves the faces and vertices it names: a face defect
 * (out_of_range_index, degenerate_face, duplicate_face: its face a) involves
 * that face and its corners (in range), so the corners of a rejected face,
 * which is no cell, show where it was; an edge defect (nonmanifold_edge: the
 * faces on edge a-b; same_direction_edge: the faces running a -> b) involves
 * those faces and both ends; a vertex defect (nonmanifold_vertex,
 * isolated_vertex, nonfinite_coordinate) the vertex and every face with it
 * as a corner. The defect kinds' numbers are stored in the file (the
 * report's defects dataset) and never change meaning; new kinds take new
 * numbers.
 *
 * Every dataset has a string attribute "description"; the bitmasks have
 * "bits", one string per bit (bit k's key at index k), the per-kind arrays
 * "bit" (uint32 k). An array whose values are all the same (a mesh with
 * one component, no defect, no boundary) is stored as an HDF5 dataset
 * that was never written: readers get its fill value (0, or 1 for
 * orientation_consistent), and it costs no space or time. On a
 * 1M-triangle grid (meshtopo-bench archive) the arrays add about 1.5 MB to
 * the 111 MB file. */

/* Whether mt_archive_write_with stores CellData/self_intersecting. */
typedef enum mt_archive_self_intersections {
    /* The default: left out. Finding them costs about ten times a build on a
     * large mesh, and the daemon's write sits before the acknowledgement of
     * a submission. CellData's string attribute self_intersecting says
     * "not computed". */
    MT_ARCHIVE_SELF_INTERSECTIONS_SKIP = 0,
    /* Found during the write with mt_mesh_self_intersections (a mesh
     * without positions has none to find: left out, and the attribute says
     * so). */
    MT_ARCHIVE_SELF_INTERSECTIONS_COMPUTE,
    /* Taken from the options' pairs, as mt_mesh_self_intersections gave
     * them for this mesh (for a caller that has them already). */
    MT_ARCHIVE_SELF_INTERSECTIONS_GIVEN,
} mt_archive_self_intersections;

/* Archives one built mesh version: `list` is the face list exactly as
 * submitted and `mesh` what mt_mesh_build made of it (its report is stored;
 * faces it rejected are kept in the face list but left out of the VTKHDF
 * cells). When this returns MT_OK the file is durable (linked into place
 * and the directory fsynced), so a submission may then be acknowledged.
 * The temporary file is ".mt-tmp-<pid>-<16 random hex digits>.<host>.part",
 * created exclusively (another name is drawn when one is taken). An
 * existing version is never overwritten: MT_ERR_INVALID_ARG ("already
 * archived"), like a bad id, version 0 or a mesh that is not list's build;
 * anything else at the final name (a symbolic link, a directory) is
 * refused the same way, its kind named, and nothing is written through it
 * (take another version number). MT_ERR_IO on any HDF5 or file system
 * failure, with the file's name and the system's reason when it has one
 * ("No space left on device", "Permission denied", "File too large" and
 * the limit); the temporary file is then removed. MT_ERR_UNSUPPORTED on a
 * read-only handle. out_stats may be NULL. */
mt_status mt_archive_write(mt_archive *archive, const mt_archive_meta *meta,
                           const mt_face_list *list, const mt_mesh *mesh,
                           mt_archive_write_stats *out_stats, mt_diag *diag);

/* How mt_archive_write_with stores the large datasets. */
typedef enum mt_archive_compression {
    /* The default: contiguous, uncompressed, which every HDF5 reader opens
     * as it is. Measured on 1M-triangle grids (meshtopo-bench archive, 111
     * MB per file), shuffle + deflate level 1 makes a scan-like mesh's file
     * 2.2x smaller but its write several times slower and its reload
     * slower too (an archive write sits before the acknowledgement of a
     * submission and a reload before the first query); LZ4 below is as
     * fast but needs a filter plugin in every reader. */
    MT_ARCHIVE_COMPRESSION_DEFAULT = 0,
    MT_ARCHIVE_COMPRESSION_NONE,    /* contiguous datasets, no filters */
    MT_ARCHIVE_COMPRESSION_DEFLATE, /* 1 MiB chunks, shuffle + deflate */
    /* 1 MiB chunks through HDF5 filter 32001 (Blosc: bit shuffle + LZ4,
     * level 5), a plugin HDF5 loads at run time: on Debian
     * hdf5-filter-plugin-blosc-serial, which readers of the file (h5py,
     * VTK, ParaView) need too. About half the size of NONE on a scan-like
     * mesh, written no slower (README, "The archive"). */
    MT_ARCHIVE_COMPRESSION_LZ4,
} mt_archive_compression;

/* Whether HDF5 finds the filter plugin MT_ARCHIVE_COMPRESSION_LZ4 needs
 * (Blosc, filter 32001) in its plugin path (HDF5_PLUGIN_PATH, else its
 * built-in directory). */
bool mt_archive_lz4_available(void);

/* Options for mt_archive_write_with; a zeroed struct (or NULL) gives the
 * defaults. */
typedef struct mt_archive_write_options {
    mt_archive_compression compression;
    /* Deflate level 1..9 with MT_ARCHIVE_COMPRESSION_DEFLATE; 0 means 1. */
    uint32_t deflate_level;
    /* CellData/self_intersecting: left out (the default), computed, or
     * from the pairs below. */
    mt_archive_self_intersections self_intersections;
    /* MT_ARCHIVE_SELF_INTERSECTIONS_GIVEN: num_self_intersection_pairs face
     * pairs (not copied; read during the call). */
    const mt_face_pair *self_intersection_pairs;
    size_t num_self_intersection_pairs;
} mt_archive_write_options;

/* mt_archive_write with options (NULL = defaults). Datasets under 4 KiB
 * are stored contiguously whatever the compression. MT_ERR_UNSUPPORTED for
 * MT_ARCHIVE_COMPRESSION_LZ4 when its filter plugin is not found (nothing
 * is written). MT_ERR_INVALID_ARG for
 * an unknown compression or a level above 9, an unknown self_intersections
 * value, or given pairs naming a face that is out of range or that the
 * build rejected (or NULL pairs with a non-zero count). With
 * MT_ARCHIVE_SELF_INTERSECTIONS_COMPUTE, mt_mesh_self_intersections' errors
 * (MT_ERR_NOMEM) fail the write before anything is written. */
mt_status mt_archive_write_with(mt_archive *archive, const mt_archive_meta *meta,
                                const mt_face_list *list, const mt_mesh *mesh,
                                const mt_archive_write_options *options,
                                mt_archive_write_stats *out_stats, mt_diag *diag);

/* Whether version `version` of mesh_id has a file in the archive (named
 * with either suffix). */
bool mt_archive_contains(const mt_archive *archive, const char *mesh_id, uint32_t version);

/* The name of the file holding version `version` (>= 1) of mesh_id: the
 * name mt_archive_file_name gives, or the same with MT_ARCHIVE_SUFFIX_LEGACY
 * when only a file written by an earlier meshtopo is there. Written to buf
 * as mt_archive_file_name writes it. MT_ERR_NOT_FOUND when neither entry
 * exists (buf then holds the name a new file gets), MT_ERR_INVALID_ARG for
 * a bad id or version 0. Looks entries up with lstat: nothing is opened or
 * followed. */
mt_status mt_archive_file_find(const mt_archive *archive, const char *mesh_id, uint32_t version,
                               char *buf, size_t size, mt_diag *diag);

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

/* What is wrong with an archive file, as a load (mt_archive_load_mesh*) or
 * a verification (mt_archive_verify_file_with) finds it, for the caller to
 * act on. The two run the same checks, so they report the same fault for
 * every file (verification adds MT_ARCHIVE_FAULT_VTK, which loads do not
 * read). */
typedef enum mt_archive_fault {
    /* Nothing: the file holds what was archived. */
    MT_ARCHIVE_FAULT_NONE = 0,
    /* What the build derived from the face list is damaged: the half-edge
     * arrays (unreadable, invalid, or not what was archived: their digest
     * differs) or the report; the face list is intact (its content hash
     * matches, or its rebuild gives the stored report). A load succeeds
     * with the mesh rebuilt from the face list (with the rebuild's report)
     * and says why in mt_archive_load_info.fallback; verification fails
     * with MT_ERR_CORRUPT. The file is left as it is: the caller logs it.
     * Damaged user attributes (/meshtopo/attributes) count here too: the
     * mesh loads with those that could be read. */
    MT_ARCHIVE_FAULT_DERIVED,
    /* The VTKHDF datasets (what ParaView reads) disagree with the face
     * list, or (format 6) the topology arrays with the mesh. Only
     * verification reads them (MT_ERR_PARSE); loads succeed. */
    MT_ARCHIVE_FAULT_VTK,
    /* Nothing in the file can be served: not HDF5 or truncated, the face
     * list unreadable or not matching its content hash (MT_ERR_CORRUPT,
     * naming both hashes), provenance or report unreadable, or a rebuild
     * not giving the stored report without a content hash to vouch for the
     * face list. The caller sets the file aside (mt_archive_set_aside) and
     * logs it. */
    MT_ARCHIVE_FAULT_CONTENT,
    /* A format_version above MT_ARCHIVE_FORMAT_VERSION (MT_ERR_UNSUPPORTED):
     * written by a newer meshtopo, or damaged there. Not served, not to be
     * set aside by this meshtopo. */
    MT_ARCHIVE_FAULT_NEWER,
    /* Refused before being read (MT_ERR_IO, message "refused: ..."): a
     * symbolic link, anything else that is not a regular file, or a file
     * not owned by this process's effective user. Never followed, opened
     * (beyond the check) or read. */
    MT_ARCHIVE_FAULT_UNSAFE,
    /* The system failed the read (MT_ERR_IO with the errno text, such as
     * "Permission denied" or "Input/output error"; MT_ERR_NOT_FOUND;
     * MT_ERR_NOMEM). The file itself may be fine: do not set it aside. */
    MT_ARCHIVE_FAULT_SYSTEM,
} mt_archive_fault;

/* "none", "derived", "vtk", "content", "newer", "unsafe", "system"; never
 * NULL ("unknown" for other values). */
const char *mt_archive_fault_name(mt_archive_fault fault);

/* One file of the archive as mt_archive_list sees it. */
typedef struct mt_archive_entry {
    char *file_name;  /* in the archive directory */
    mt_status status; /* MT_OK, or why the file could not be read (diag) */
    mt_diag diag;     /* names the file and the attribute or dataset */
    /* NONE when status is MT_OK; otherwise CONTENT, NEWER, UNSAFE (a
     * symbolic link or other non-regular entry, or a foreign owner: listed,
     * never opened) or SYSTEM. Listing reads attributes only: it finds no
     * DERIVED or VTK fault. */
    mt_archive_fault fault;
    char *mesh_id; /* the rest is set only when status is MT_OK */
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

/* Lists every "*.hdf" and "*.vtkhdf" entry of the archive, reading only its
 * attributes. An entry that cannot be read (a symbolic link or another
 * non-regular entry included) is listed with its status and fault; the call
 * fails only when the directory cannot be read (MT_ERR_IO) or memory runs
 * out.
 * Free with mt_archive_listing_free. */
mt_status mt_archive_list(const mt_archive *archive, mt_archive_listing *out, mt_diag *diag);
void mt_archive_listing_free(mt_archive_listing *listing);

/* The highest version of mesh_id with a file in the archive, found from
 * the directory's file names alone (no file is opened): 0 when there is
 * none. Several writers sharing one directory number versions with it: the
 * next one tries the highest plus one, and mt_archive_write refuses a taken
 * number ("already archived"), so the one that loses the race takes the
 * next. MT_ERR_INVALID_ARG for a bad id, MT_ERR_IO when the directory
 * cannot be read (diag with the errno text). Costs one pass over the
 * directory's entries. */
mt_status mt_archive_highest_version(const mt_archive *archive, const char *mesh_id,
                                     uint32_t *out_version, mt_diag *diag);

/* One file of the archive directory as mt_archive_list lists it, by name:
 * *out is filled as a listing's entry is (status, diag and fault included)
 * and freed with mt_archive_entry_free. Returns out->status, or
 * MT_ERR_INVALID_ARG for a name that is not an archive file's or
 * MT_ERR_NOMEM. */
mt_status mt_archive_list_file(const mt_archive *archive, const char *file_name,
                               mt_archive_entry *out, mt_diag *diag);

/* Frees what an entry of mt_archive_list_file owns and zeroes it. NULL-safe. */
void mt_archive_entry_free(mt_archive_entry *entry);

/* Which files mt_archive_list_filtered reads: true to read file_name. */
typedef bool (*mt_archive_name_filter)(void *ctx, const char *file_name);

/* mt_archive_list for the archive files whose name `wanted` accepts: the
 * others are not opened (a writer sharing the directory lists only the
 * files it does not know yet). wanted NULL lists every file. */
mt_status mt_archive_list_filtered(const mt_archive *archive, mt_archive_name_filter wanted,
                                   void *ctx, mt_archive_listing *out, mt_diag *diag);

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
 * MT_ERR_NOT_FOUND when there is no such file; MT_ERR_IO when the file is
 * refused ("refused: ...": a symbolic link, not a regular file, not owned
 * by the effective user) or the system fails the read (its errno text: a
 * file without read permission is "Permission denied"); for a bad file
 * MT_ERR_PARSE (wrong shape, type, count or range; mesh id or version not
 * those of the file name), MT_ERR_IO (not HDF5, truncated) or
 * MT_ERR_TOO_LARGE, with diag naming the file and the dataset or attribute.
 * *out is zeroed on failure. This reads the record as stored: the content
 * hash and the half-edge arrays are checked by mt_archive_load_mesh* and
 * mt_archive_verify_file*. */
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
     * rebuilt from the face list (a version 1 to 3 file, or stored arrays
     * or report that failed their checks: fault is then DERIVED). */
    bool restored;
    /* NONE or DERIVED when the load succeeded (DERIVED: served rebuilt,
     * the file is damaged, log it); on failure what failed (CONTENT: set
     * the file aside; NEWER, UNSAFE, SYSTEM: leave it). */
    mt_archive_fault fault;
    /* The stored face list's content hash was checked (a hash function is
     * set and the file's format is MT_ARCHIVE_FORMAT_VERSION_HASHED or
     * later). */
    bool hash_checked;
    /* Why the stored arrays or report were not used, naming the file and
     * the problem (status MT_OK when restored, or when the file predates
     * the arrays and its rebuild matches). */
    mt_diag fallback;
    double read_ms;  /* HDF5 reads of attributes, report and face list */
    double mesh_ms;  /* arrays read into the mesh and validated, or the rebuild */
    double check_ms; /* content hash and digest (or comparison with the rebuild) */
} mt_archive_load_info;

/* Reloads one archived version as a queryable mesh, after these checks
 * (the ones mt_archive_verify_file_with makes, so both agree on every
 * file):
 *  1. The file is opened safely (see mt_archive_load): a symbolic link,
 *     another non-regular file or a foreign owner is refused (UNSAFE).
 *  2. Provenance and the stored report are read. When the archive has a
 *     content hash function (mt_archive_set_content_hash) and the file
 *     is of format MT_ARCHIVE_FORMAT_VERSION_HASHED or later, the stored
 *     face list must hash to the stored content_hash (mt_archive_content_hash
 *     is computed a block at a time from the file, other functions get the
 *     face list): otherwise MT_ERR_CORRUPT naming the file and both hashes
 *     (CONTENT).
 *  3. Format 4 and later: the half-edge arrays and positions are read and
 *     made into the mesh with mt_mesh_restore (which validates them), then
 *     the digest of arrays, positions and report must equal the stored one.
 *     Formats 2 and 3 (no digest): the arrays are read and must equal the
 *     arrays of a rebuild from the face list, which is served.
 *  4. When the arrays are missing (format 1) or fail step 3, the mesh is
 *     rebuilt from the face list (mt_archive_record_build's checks), and
 *     out_info->fallback says why (fault DERIVED unless format 1). A rebuild
 *     whose report differs from the stored one fails the load (CONTENT,
 *     MT_ERR_CORRUPT) unless step 2 vouched for the face list; the stored
 *     report is then the damaged part (DERIVED) and the rebuild's is used.
 * Only a failure of the rebuild fails a load whose arrays were bad (its
 * status, with diag naming the file and both problems). with_faces also
 * reads the face list into out_record->faces (otherwise left empty unless a
 * check or the rebuild needed it). out_record may be NULL; otherwise it is
 * filled as mt_archive_load_file fills it (free with mt_archive_record_free).
 * On MT_OK *out_mesh is the mesh (mt_mesh_destroy); on failure it is NULL,
 * out_record is zeroed and out_info->fault says what failed. out_info may
 * be NULL. Cost, 1M-triangle grid: a restore of about 52 ms (31 of them
 * validation) gains about 3 ms for the digest and, with
 * mt_archive_content_hash set, about 6 ms for the content hash; a format 2
 * or 3 file costs a rebuild instead (about 4 times a restore). */
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

/* Verifies one file of the archive: the checks of mt_archive_load_mesh_file
 * (safe open, provenance and report, the content hash when hash is not NULL
 * and the file's format is MT_ARCHIVE_FORMAT_VERSION_HASHED or later, the
 * stored half-edge arrays against their digest or, formats 2 and 3, against
 * a rebuild; format 1 and a fallback rebuild against the stored report),
 * then the VTKHDF datasets against the face list and (format 6) the
 * topology arrays against the ones the mesh gives (self_intersecting, when
 * present, only for its length and values 0 or 1: finding the
 * intersections again would cost ten builds). hash NULL: the archive's
 * content hash function (mt_archive_set_content_hash), if any. MT_OK or
 * the first problem's status with diag naming the file and the problem. */
mt_status mt_archive_verify_file(const mt_archive *archive, const char *file_name,
                                 mt_archive_hash_fn hash, void *hash_ctx, mt_diag *diag);

/* mt_archive_verify_file that also says what is wrong: *out_fault (may be
 * NULL) is the fault mt_archive_load_mesh_file reports for the same file
 * and hash (NONE when the load would serve it as stored), or VTK when only
 * the VTKHDF datasets are wrong. A DERIVED file fails verification with
 * MT_ERR_CORRUPT (a load would serve it rebuilt). */
mt_status mt_archive_verify_file_with(const mt_archive *archive, const char *file_name,
                                      mt_archive_hash_fn hash, void *hash_ctx,
                                      mt_archive_fault *out_fault, mt_diag *diag);

/* Sets a file of the archive aside: renames it to ".mt-aside-<file_name>.
 * <16 random hex digits>" in the same directory (hidden: never listed,
 * loaded or removed as a leftover; kept for inspection), then fsyncs the
 * directory. A symbolic link is renamed itself, never followed. The new
 * name goes to out_name (size bytes, may be NULL/0). MT_ERR_NOT_FOUND when
 * there is no such entry, MT_ERR_INVALID_ARG for a name that is not an
 * archive file's, MT_ERR_UNSUPPORTED on a read-only handle, MT_ERR_IO with
 * the errno text. */
mt_status mt_archive_set_aside(mt_archive *archive, const char *file_name, char *out_name,
                               size_t size, mt_diag *diag);

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
