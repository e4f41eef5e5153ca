/* Reading archive files back. Every value comes from a file that may be
 * truncated, foreign or hostile: the file is opened without following links
 * and must be a regular file of ours (archive_fd.c), attributes are
 * range-checked, datasets shape- and type-checked (archive_h5.c) before any
 * allocation, the arrays decoded by archive_decode.c, and the file name must
 * be the one the stored mesh id and version give. Errors name the file and
 * the object. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "archive_internal.h"

/* Longest source name read back (the LCM string has no fixed limit). */
#define SOURCE_MAX 65535

mt_archive_fault mt__archive_read_fault(mt_status status)
{
    if (status == MT_ERR_NOMEM || status == MT_ERR_NOT_FOUND || mt__archive_last_errno != 0)
        return MT_ARCHIVE_FAULT_SYSTEM;
    return status == MT_ERR_UNSUPPORTED ? MT_ARCHIVE_FAULT_NEWER : MT_ARCHIVE_FAULT_CONTENT;
}

/* Whether the file HDF5 opened is `sb`'s (device and inode). */
static bool same_file(hid_t file, const struct stat *sb)
{
    void *handle = NULL;
    struct stat hs;
    return H5Fget_vfd_handle(file, H5P_DEFAULT, &handle) >= 0 && handle &&
           fstat(*(int *)handle, &hs) == 0 && hs.st_dev == sb->st_dev && hs.st_ino == sb->st_ino;
}

mt_status mt__archive_h5_open(const mt_archive *archive, const char *file_name, hid_t *out_file,
                              uint64_t *out_bytes, mt_archive_fault *out_fault, mt_diag *diag)
{
    *out_file = -1;
    mt_archive_fault ignored;
    if (!out_fault) out_fault = &ignored;
    mt__h5_quiet();
    mt__archive_last_errno = 0;
    int fd;
    struct stat sb;
    mt_status st = mt__archive_open_fd(archive, file_name, &fd, &sb, out_fault, diag);
    if (st != MT_OK) return st;
    char *path = mt__archive_path(archive, file_name);
    if (!path) {
        close(fd);
        *out_fault = MT_ARCHIVE_FAULT_SYSTEM;
        return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    }
    if (out_bytes) *out_bytes = (uint64_t)sb.st_size;
    /* HDF5 opens files by name only. It is given /proc/self/fd/N, which
     * opens the very file checked above whatever happens to its directory
     * entry meanwhile. Without /proc (a chroot) it gets the name, and what
     * it opened is compared with the checked file afterwards: a swap in
     * between is then refused, though HDF5 has opened what was swapped in. */
    char proc[32];
    bool by_fd = mt__fd_proc_path(fd, proc, sizeof proc);
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    if (fapl >= 0) H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
    hid_t file = fapl < 0 ? -1 : H5Fopen(by_fd ? proc : path, H5F_ACC_RDONLY, fapl);
    int err = file < 0 ? mt__h5_os_errno() : 0;
    if (fapl >= 0) H5Pclose(fapl);
    if (file < 0 && err) {
        *out_fault = MT_ARCHIVE_FAULT_SYSTEM;
        st = mt__archive_fail_os(diag, MT_ERR_IO, err, path, "%s: cannot be read", path);
    } else if (file < 0) {
        *out_fault = MT_ARCHIVE_FAULT_CONTENT;
        st = mt__archive_fail(diag, MT_ERR_IO,
                              "%s: not a readable HDF5 file (truncated or not HDF5)", path);
    } else if (!by_fd && !same_file(file, &sb)) {
        H5Fclose(file);
        file = -1;
        *out_fault = MT_ARCHIVE_FAULT_UNSAFE;
        st = mt__archive_fail(diag, MT_ERR_IO,
                              "%s: refused: replaced by another file while being opened", path);
    }
    close(fd);
    free(path);
    *out_file = file;
    return st;
}

/* Opens group `name` of loc; a missing one is a parse error. */
hid_t mt__archive_group_open(hid_t loc, const char *name, const char *file, mt_diag *diag)
{
    if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) {
        mt__archive_fail(diag, MT_ERR_PARSE, "%s: group %s is missing", file, name);
        return -1;
    }
    hid_t g = H5Gopen2(loc, name, H5P_DEFAULT);
    if (g < 0) mt__archive_fail(diag, MT_ERR_PARSE, "%s: %s is not a readable group", file, name);
    return g;
}

/* Provenance attributes of /meshtopo; checks that they give this file's name. */
mt_status mt__archive_read_provenance(hid_t g, const char *file_name, mt_archive_record *r,
                                      mt_diag *diag)
{
    int64_t format_version = 0, utime = 0;
    uint64_t version = 0, hash = 0;
    mt_status st = mt__h5_read_attr_i64(g, "format_version", file_name, &format_version, diag);
    if (st == MT_OK && (format_version < MT_ARCHIVE_FORMAT_VERSION_MIN ||
                        format_version > MT_ARCHIVE_FORMAT_VERSION))
        st = mt__archive_fail(diag, MT_ERR_UNSUPPORTED,
                              "%s: attribute meshtopo/format_version is %lld; this meshtopo reads "
                              "formats %d to %d",
                              file_name, (long long)format_version, MT_ARCHIVE_FORMAT_VERSION_MIN,
                              MT_ARCHIVE_FORMAT_VERSION);
    if (st == MT_OK)
        st = mt__h5_read_attr_string(g, "mesh_id", file_name, MT_MESH_ID_MAX, &r->mesh_id, diag);
    if (st == MT_OK) {
        mt_diag why;
        if (mt_mesh_id_check(r->mesh_id, &why) != MT_OK)
            st = mt__archive_fail(diag, MT_ERR_PARSE,
                                  "%s: attribute meshtopo/mesh_id is not a valid mesh id (%s)",
                                  file_name, why.message);
    }
    if (st == MT_OK) st = mt__h5_read_attr_u64(g, "version", file_name, &version, diag);
    if (st == MT_OK && (version == 0 || version > UINT32_MAX))
        st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: attribute meshtopo/version is %llu",
                              file_name, (unsigned long long)version);
    if (st == MT_OK) st = mt__h5_read_attr_i64(g, "utime", file_name, &utime, diag);
    if (st == MT_OK)
        st = mt__h5_read_attr_string(g, "source", file_name, SOURCE_MAX, &r->source, diag);
    if (st == MT_OK) st = mt__h5_read_attr_u64(g, "content_hash", file_name, &hash, diag);
    if (st != MT_OK) return st;
    r->format_version = (uint32_t)format_version;
    r->version = (uint32_t)version;
    r->utime = utime;
    r->content_hash = hash;
    char expected[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name(r->mesh_id, r->version, expected, sizeof expected);
    if (!mt__archive_name_matches(file_name, r->mesh_id, r->version))
        return mt__archive_fail(diag, MT_ERR_PARSE,
                                "%s: the file's mesh_id and version attributes belong to a file "
                                "named %s",
                                file_name, expected);
    return MT_OK;
}

/* The face list datasets of /meshtopo, decoded. */
mt_status mt__archive_read_faces(hid_t g, const char *file_name, mt_face_list *out, mt_diag *diag)
{
    mt_archive_face_arrays a;
    memset(&a, 0, sizeof a);
    void *positions = NULL, *counts = NULL, *indices = NULL;
    int64_t num_faces = 0, num_indices = 0;
    mt_status st = mt__h5_read_attr_i64(g, "num_verts", file_name, &a.num_verts, diag);
    if (st == MT_OK) st = mt__h5_read_attr_i64(g, "num_faces", file_name, &num_faces, diag);
    if (st == MT_OK) st = mt__h5_read_attr_i64(g, "num_indices", file_name, &num_indices, diag);
    if (st == MT_OK)
        st = mt__h5_read_dataset(g, "/meshtopo/positions", file_name, 2, 3, MT__H5_FLOAT, 8,
                                 H5T_NATIVE_DOUBLE, &positions, &a.positions_rows, diag);
    if (st == MT_OK)
        st = mt__h5_read_dataset(g, "/meshtopo/face_vertex_counts", file_name, 1, 0, MT__H5_INT, 4,
                                 H5T_NATIVE_INT32, &counts, &a.num_counts, diag);
    if (st == MT_OK)
        st = mt__h5_read_dataset(g, "/meshtopo/face_vertex_indices", file_name, 1, 0, MT__H5_INT, 4,
                                 H5T_NATIVE_INT32, &indices, &a.num_indices, diag);
    if (st == MT_OK && ((uint64_t)num_faces != a.num_counts ||
                        (uint64_t)num_indices != a.num_indices || num_faces < 0 || num_indices < 0))
        st = mt__archive_fail(diag, MT_ERR_PARSE,
                              "%s: attributes num_faces %lld and num_indices %lld disagree with "
                              "datasets face_vertex_counts (%llu) and face_vertex_indices (%llu)",
                              file_name, (long long)num_faces, (long long)num_indices,
                              (unsigned long long)a.num_counts, (unsigned long long)a.num_indices);
    if (st == MT_OK) {
        a.positions = positions;
        a.counts = counts;
        a.indices = indices;
        mt_diag why;
        st = mt_archive_decode_faces(&a, file_name, out, &why);
        if (st != MT_OK && diag) *diag = why;
    }
    free(positions);
    free(counts);
    free(indices);
    return st;
}

mt_status mt_archive_load_file(const mt_archive *archive, const char *file_name,
                               mt_archive_record *out, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!out) return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_load_file: NULL out");
    memset(out, 0, sizeof *out);
    if (!archive || !file_name || strchr(file_name, '/') || file_name[0] == '.')
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "'%s' is not an archive file name",
                                file_name ? file_name : "(null)");
    hid_t file;
    mt_status st = mt__archive_h5_open(archive, file_name, &file, NULL, NULL, diag);
    if (st != MT_OK) return st;
    mt_archive_record r;
    memset(&r, 0, sizeof r);
    r.file_name = mt__archive_strdup(file_name);
    if (!r.file_name) st = mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    hid_t g = st == MT_OK ? mt__archive_group_open(file, "meshtopo", file_name, diag) : -1;
    if (st == MT_OK && g < 0) st = MT_ERR_PARSE;
    if (st == MT_OK) st = mt__archive_read_provenance(g, file_name, &r, diag);
    if (st == MT_OK) st = mt__archive_read_faces(g, file_name, &r.faces, diag);
    hid_t rg = st == MT_OK ? mt__archive_group_open(g, "report", file_name, diag) : -1;
    if (st == MT_OK && rg < 0) st = MT_ERR_PARSE;
    if (st == MT_OK) st = mt__report_read(rg, r.format_version, file_name, &r.report, diag);
    if (st == MT_OK &&
        (r.report.num_verts != r.faces.num_verts || r.report.num_faces != r.faces.num_faces))
        st = mt__archive_fail(diag, MT_ERR_PARSE,
                              "%s: the report counts %u vertices and %u faces, the face list %u "
                              "and %u",
                              file_name, r.report.num_verts, r.report.num_faces, r.faces.num_verts,
                              r.faces.num_faces);
    if (rg >= 0) H5Gclose(rg);
    if (g >= 0) H5Gclose(g);
    if (H5Fclose(file) < 0 && st == MT_OK)
        st = mt__archive_fail(diag, MT_ERR_IO, "%s: H5Fclose failed", file_name);
    if (st != MT_OK) {
        mt_archive_record_free(&r);
        return st;
    }
    *out = r;
    return MT_OK;
}

void mt_archive_record_free(mt_archive_record *record)
{
    if (!record) return;
    free(record->file_name);
    free(record->mesh_id);
    free(record->source);
    mt_face_list_free(&record->faces);
    mt_archive_report_free(&record->report);
    memset(record, 0, sizeof *record);
}

mt_status mt__archive_read_entry(const mt_archive *archive, const char *file_name,
                                 mt_archive_entry *e, mt_diag *diag)
{
    hid_t file;
    e->fault = MT_ARCHIVE_FAULT_NONE;
    mt_status st = mt__archive_h5_open(archive, file_name, &file, &e->file_bytes, &e->fault, diag);
    if (st != MT_OK) return st;
    mt_archive_record r;
    memset(&r, 0, sizeof r);
    mt_report rep;
    uint64_t num_defects = 0;
    hid_t g = mt__archive_group_open(file, "meshtopo", file_name, diag);
    if (g < 0) st = MT_ERR_PARSE;
    if (st == MT_OK) st = mt__archive_read_provenance(g, file_name, &r, diag);
    hid_t rg = st == MT_OK ? mt__archive_group_open(g, "report", file_name, diag) : -1;
    if (st == MT_OK && rg < 0) st = MT_ERR_PARSE;
    if (st == MT_OK) st = mt__report_read_scalars(rg, file_name, &rep, &num_defects, diag);
    if (rg >= 0) H5Gclose(rg);
    if (g >= 0) H5Gclose(g);
    H5Fclose(file);
    if (st != MT_OK) {
        e->fault = mt__archive_read_fault(st);
        mt_archive_record_free(&r);
        return st;
    }
    e->mesh_id = r.mesh_id;
    e->source = r.source;
    e->version = r.version;
    e->utime = r.utime;
    e->content_hash = r.content_hash;
    mt_archive_summary *s = &e->summary;
    s->num_verts = rep.num_verts;
    s->num_faces = rep.num_faces;
    s->num_faces_valid = rep.num_faces_valid;
    s->num_edges = rep.num_edges;
    s->num_defects = num_defects;
    s->connected_components = rep.connected_components;
    s->boundary_loops = rep.boundary_loops;
    s->euler_characteristic = rep.euler_characteristic;
    s->genus = rep.genus;
    s->closed = rep.closed;
    s->manifold = rep.manifold;
    s->orientable = rep.orientable;
    return MT_OK;
}
