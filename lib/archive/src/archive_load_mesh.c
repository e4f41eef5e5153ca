/* Reloading an archived version as a queryable mesh (mt_archive_load_mesh):
 * the file is opened safely (archive_read.c) and checked the way
 * verification checks it (archive_check.c): the face list's content hash,
 * a format 4 file's half-edge arrays restored with mt_mesh_restore (which
 * validates them; they come from a file and are never trusted) and matched
 * with their digest, so no rebuild is needed. Older files, or arrays that
 * fail, are rebuilt from the stored face list; the reason and the fault are
 * kept in the load info. */
#include <stdlib.h>
#include <string.h>

#include "archive_internal.h"

mt_status mt_archive_load_mesh_file(const mt_archive *archive, const char *file_name,
                                    bool with_faces, mt_archive_record *out_record,
                                    mt_mesh **out_mesh, mt_archive_load_info *out_info,
                                    mt_diag *diag)
{
    mt_diag_clear(diag);
    mt_archive_load_info info;
    memset(&info, 0, sizeof info);
    mt_diag_clear(&info.fallback);
    if (out_record) memset(out_record, 0, sizeof *out_record);
    if (out_mesh) *out_mesh = NULL;
    if (out_info) *out_info = info;
    if (!archive || !out_mesh)
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_load_mesh: NULL argument");
    if (!file_name || strchr(file_name, '/') || file_name[0] == '.')
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "'%s' is not an archive file name",
                                file_name ? file_name : "(null)");
    double t0 = mt__archive_now_ms();
    hid_t file;
    mt_status st = mt__archive_h5_open(archive, file_name, &file, NULL, &info.fault, diag);
    if (st != MT_OK) {
        if (out_info) *out_info = info;
        return st;
    }
    double opened = mt__archive_now_ms() - t0;
    mt__check c;
    memset(&c, 0, sizeof c);
    c.hash = archive->content_hash;
    c.hash_ctx = archive->content_hash_ctx;
    c.keep_faces = with_faces;
    st = mt__archive_check(file, file_name, &c, diag);
    if (H5Fclose(file) < 0 && st == MT_OK) {
        st = mt__h5_fail(diag, MT_ERR_IO, NULL, "%s: H5Fclose failed", file_name);
        c.fault = MT_ARCHIVE_FAULT_SYSTEM;
        mt_mesh_destroy(c.mesh);
        c.mesh = NULL;
        mt_archive_record_free(&c.record);
    }
    info.restored = st == MT_OK && c.restored;
    info.fault = c.fault;
    info.hash_checked = c.hash_checked;
    info.fallback = c.fallback;
    info.read_ms = opened + c.read_ms;
    info.mesh_ms = c.mesh_ms;
    info.check_ms = c.check_ms;
    if (out_info) *out_info = info;
    if (st != MT_OK) return st;
    *out_mesh = c.mesh;
    if (out_record)
        *out_record = c.record;
    else
        mt_archive_record_free(&c.record);
    return MT_OK;
}
