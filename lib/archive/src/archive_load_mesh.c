/* Reloading an archived version as a queryable mesh (mt_archive_load_mesh):
 * a format 2 file's half-edge arrays are restored with mt_mesh_restore,
 * which validates them (they come from a file and are never trusted), so no
 * rebuild is needed. A version 1 file, or arrays that cannot be read or fail
 * validation, fall back to a rebuild from the stored face list compared
 * with the stored report; the reason is kept in the load info. */
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
    mt_status st = mt__archive_h5_open(archive, file_name, &file, NULL, diag);
    if (st != MT_OK) return st;
    mt_archive_record r;
    memset(&r, 0, sizeof r);
    r.file_name = mt__archive_strdup(file_name);
    if (!r.file_name) st = mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    hid_t g = st == MT_OK ? mt__archive_group_open(file, "meshtopo", file_name, diag) : -1;
    if (st == MT_OK && g < 0) st = MT_ERR_PARSE;
    if (st == MT_OK) st = mt__archive_read_provenance(g, file_name, &r, diag);
    hid_t rg = st == MT_OK ? mt__archive_group_open(g, "report", file_name, diag) : -1;
    if (st == MT_OK && rg < 0) st = MT_ERR_PARSE;
    if (st == MT_OK) st = mt__report_read(rg, file_name, &r.report, diag);
    if (rg >= 0) H5Gclose(rg);
    info.read_ms = mt__archive_now_ms() - t0;

    mt_mesh *mesh = NULL;
    if (st == MT_OK && r.format_version >= 2) {
        double t1 = mt__archive_now_ms();
        mt_status rs = mt__halfedge_restore(g, file_name, &r.report, &mesh, &info.fallback);
        info.mesh_ms += mt__archive_now_ms() - t1;
        if (rs == MT_ERR_NOMEM) st = mt__archive_fail(diag, rs, "%s", info.fallback.message);
        info.restored = rs == MT_OK;
    }
    if (st == MT_OK && (!mesh || with_faces)) {
        double t1 = mt__archive_now_ms();
        mt_diag why;
        st = mt__archive_read_faces(g, file_name, &r.faces, &why);
        if (st != MT_OK && !mesh && info.fallback.status != MT_OK)
            mt__archive_fail(diag, st, "%s; the face list for a rebuild cannot be read either: %s",
                             info.fallback.message, why.message);
        else if (st != MT_OK && diag)
            *diag = why;
        if (st == MT_OK &&
            (r.report.num_verts != r.faces.num_verts || r.report.num_faces != r.faces.num_faces))
            st = mt__archive_fail(diag, MT_ERR_PARSE,
                                  "%s: the report counts %u vertices and %u faces, the face list "
                                  "%u and %u",
                                  file_name, r.report.num_verts, r.report.num_faces,
                                  r.faces.num_verts, r.faces.num_faces);
        info.read_ms += mt__archive_now_ms() - t1;
    }
    if (g >= 0) H5Gclose(g);
    if (H5Fclose(file) < 0 && st == MT_OK)
        st = mt__archive_fail(diag, MT_ERR_IO, "%s: H5Fclose failed", file_name);
    if (st == MT_OK && !mesh) {
        double t2 = mt__archive_now_ms();
        mt_diag why;
        st = mt_archive_record_build(&r, &mesh, &why);
        if (st != MT_OK && info.fallback.status != MT_OK)
            mt__archive_fail(diag, st, "%s; the rebuild from the face list failed too: %s",
                             info.fallback.message, why.message);
        else if (st != MT_OK && diag)
            *diag = why;
        info.mesh_ms += mt__archive_now_ms() - t2;
    }
    if (st != MT_OK) {
        mt_mesh_destroy(mesh);
        mt_archive_record_free(&r);
        if (out_info) *out_info = info;
        return st;
    }
    *out_mesh = mesh;
    if (out_record)
        *out_record = r;
    else
        mt_archive_record_free(&r);
    if (out_info) *out_info = info;
    return MT_OK;
}
