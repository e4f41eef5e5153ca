/* Checking an archived version: rebuilding the half-edge mesh from the
 * stored face list and comparing its report with the stored one (also the
 * reload path of version 1 files), and the whole-file verification behind
 * `meshtopo archive verify`: readable, the VTKHDF datasets agreeing with the
 * face list, the content hash matching, the stored half-edge arrays (format
 * 2) validating and equal to the rebuild's. */
#include <stdlib.h>
#include <string.h>

#include "archive_internal.h"
#include "meshtopo/validate.h"

mt_status mt_archive_record_build(const mt_archive_record *record, mt_mesh **out_mesh,
                                  mt_diag *diag)
{
    mt_diag_clear(diag);
    if (out_mesh) *out_mesh = NULL;
    if (!record) return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "mt_archive_record_build: NULL");
    const char *name = record->file_name ? record->file_name : "record";
    mt_mesh *mesh = NULL;
    mt_diag why;
    mt_status st = mt_mesh_build(&record->faces, NULL, &mesh, &why);
    if (st != MT_OK)
        return mt__archive_fail(diag, st, "%s: rebuilding the stored face list failed: %s", name,
                                why.message);
    st = mt_mesh_validate(mesh, &why);
    if (st != MT_OK) {
        mt_mesh_destroy(mesh);
        return mt__archive_fail(diag, MT_ERR_CORRUPT, "%s: the rebuilt mesh is invalid: %s", name,
                                why.message);
    }
    char difference[256];
    if (!mt_archive_report_equal(&record->report, mt_mesh_report(mesh), difference,
                                 sizeof difference)) {
        mt_mesh_destroy(mesh);
        return mt__archive_fail(diag, MT_ERR_CORRUPT,
                                "%s: the rebuild's report differs from the stored one (%s: "
                                "stored != rebuilt)",
                                name, difference);
    }
    if (out_mesh)
        *out_mesh = mesh;
    else
        mt_mesh_destroy(mesh);
    return MT_OK;
}

/* The VTKHDF datasets of a file, owned. */
typedef struct vtk_read {
    void *points, *connectivity, *offsets, *types, *face_ids;
    mt_archive_vtk_arrays arrays;
} vtk_read;

static void vtk_read_free(vtk_read *v)
{
    free(v->points);
    free(v->connectivity);
    free(v->offsets);
    free(v->types);
    free(v->face_ids);
}

/* Reads one of the one-entry count datasets of /VTKHDF. */
static mt_status read_count(hid_t g, const char *name, const char *file, int64_t *out,
                            mt_diag *diag)
{
    void *data = NULL;
    uint64_t rows = 0;
    mt_status st = mt__h5_read_dataset(g, name, file, 1, 0, MT__H5_INT, 8, H5T_NATIVE_INT64, &data,
                                       &rows, diag);
    if (st == MT_OK && rows != 1)
        st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: dataset /VTKHDF/%s must hold one value",
                              file, name);
    if (st == MT_OK) memcpy(out, data, sizeof *out);
    free(data);
    return st;
}

static mt_status read_vtk(hid_t file, const char *name, vtk_read *v, mt_diag *diag)
{
    memset(v, 0, sizeof *v);
    if (H5Lexists(file, "VTKHDF", H5P_DEFAULT) <= 0)
        return mt__archive_fail(diag, MT_ERR_PARSE, "%s: group VTKHDF is missing", name);
    hid_t g = H5Gopen2(file, "VTKHDF", H5P_DEFAULT);
    if (g < 0) return mt__archive_fail(diag, MT_ERR_PARSE, "%s: VTKHDF is not a group", name);
    mt_archive_vtk_arrays *a = &v->arrays;
    char *type = NULL;
    mt_status st = mt__h5_read_attr_string(g, "Type", name, 64, &type, diag);
    if (st == MT_OK && strcmp(type, "UnstructuredGrid") != 0)
        st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: VTKHDF Type is \"%s\"", name, type);
    free(type);
    if (st == MT_OK && H5Aexists(g, "Version") > 0) {
        hid_t attr = H5Aopen(g, "Version", H5P_DEFAULT);
        hid_t space = attr < 0 ? -1 : H5Aget_space(attr);
        int64_t values[2] = {0, 0};
        if (attr < 0 || space < 0 || H5Sget_simple_extent_npoints(space) != 2 ||
            H5Aread(attr, H5T_NATIVE_INT64, values) < 0 || values[0] != 1 || values[1] != 0)
            st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: VTKHDF Version is not [1, 0]", name);
        if (space >= 0) H5Sclose(space);
        if (attr >= 0) H5Aclose(attr);
    } else if (st == MT_OK) {
        st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: VTKHDF Version is missing", name);
    }
    if (st == MT_OK) st = read_count(g, "NumberOfPoints", name, &a->number_of_points, diag);
    if (st == MT_OK) st = read_count(g, "NumberOfCells", name, &a->number_of_cells, diag);
    if (st == MT_OK)
        st = read_count(g, "NumberOfConnectivityIds", name, &a->number_of_connectivity_ids, diag);
    if (st == MT_OK)
        st = mt__h5_read_dataset(g, "/VTKHDF/Points", name, 2, 3, MT__H5_FLOAT, 8,
                                 H5T_NATIVE_DOUBLE, &v->points, &a->points_rows, diag);
    if (st == MT_OK)
        st = mt__h5_read_dataset(g, "/VTKHDF/Connectivity", name, 1, 0, MT__H5_INT, 8,
                                 H5T_NATIVE_INT64, &v->connectivity, &a->num_connectivity, diag);
    if (st == MT_OK)
        st = mt__h5_read_dataset(g, "/VTKHDF/Offsets", name, 1, 0, MT__H5_INT, 8, H5T_NATIVE_INT64,
                                 &v->offsets, &a->num_offsets, diag);
    if (st == MT_OK)
        st = mt__h5_read_dataset(g, "/VTKHDF/Types", name, 1, 0, MT__H5_UINT, 1, H5T_NATIVE_UINT8,
                                 &v->types, &a->num_types, diag);
    if (st == MT_OK)
        st = mt__h5_read_dataset(g, "/VTKHDF/CellData/original_face_id", name, 1, 0, MT__H5_INT, 8,
                                 H5T_NATIVE_INT64, &v->face_ids, &a->num_face_ids, diag);
    H5Gclose(g);
    a->points = v->points;
    a->connectivity = v->connectivity;
    a->offsets = v->offsets;
    a->types = v->types;
    a->face_ids = v->face_ids;
    return st;
}

/* The stored half-edge arrays restore (mt_mesh_restore validates them) into
 * exactly the arrays of the rebuilt mesh. */
static mt_status verify_stored_arrays(hid_t file, const char *file_name, const mt_report *report,
                                      const mt_mesh *rebuilt, mt_diag *diag)
{
    hid_t g = mt__archive_group_open(file, "meshtopo", file_name, diag);
    if (g < 0) return MT_ERR_PARSE;
    mt_mesh *restored = NULL;
    mt_status st = mt__halfedge_restore(g, file_name, report, &restored, diag);
    H5Gclose(g);
    if (st == MT_OK) {
        mt_mesh_parts a, b;
        char difference[256];
        mt_mesh_get_parts(restored, &a);
        mt_mesh_get_parts(rebuilt, &b);
        if (!mt__parts_equal(&a, &b, difference, sizeof difference))
            st = mt__archive_fail(diag, MT_ERR_CORRUPT,
                                  "%s: the stored half-edge arrays differ from the rebuild's "
                                  "(meshtopo/halfedge/%s: stored != rebuilt)",
                                  file_name, difference);
    }
    mt_mesh_destroy(restored);
    return st;
}

mt_status mt_archive_verify_file(const mt_archive *archive, const char *file_name,
                                 mt_archive_hash_fn hash, void *hash_ctx, mt_diag *diag)
{
    mt_diag_clear(diag);
    mt_archive_record record;
    mt_status st = mt_archive_load_file(archive, file_name, &record, diag);
    if (st != MT_OK) return st;
    mt_mesh *mesh = NULL;
    st = mt_archive_record_build(&record, &mesh, diag);
    if (st == MT_OK && hash && record.format_version >= MT_ARCHIVE_FORMAT_VERSION_HASHED) {
        uint64_t h = 0;
        mt_diag why;
        mt_diag_clear(&why);
        mt_status hs = hash(hash_ctx, &record.faces, &h, &why);
        if (hs != MT_OK)
            st = mt__archive_fail(diag, hs, "%s: the content hash cannot be computed: %s",
                                  file_name, why.message);
        else if (h != record.content_hash)
            st = mt__archive_fail(diag, MT_ERR_CORRUPT,
                                  "%s: content hash mismatch: the file says %016llx, the face "
                                  "list hashes to %016llx",
                                  file_name, (unsigned long long)record.content_hash,
                                  (unsigned long long)h);
    }
    if (st == MT_OK) {
        hid_t file;
        st = mt__archive_h5_open(archive, file_name, &file, NULL, diag);
        if (st == MT_OK) {
            vtk_read v;
            st = read_vtk(file, file_name, &v, diag);
            uint8_t *kept = st == MT_OK ? malloc((size_t)record.faces.num_faces + 1) : NULL;
            if (st == MT_OK && !kept) st = mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
            if (st == MT_OK) {
                mt_mesh_view view;
                mt_mesh_get_view(mesh, &view);
                for (uint32_t f = 0; f < record.faces.num_faces; f++)
                    kept[f] = view.face_he[f] != MT_NONE;
                st = mt_archive_check_vtk(&v.arrays, &record.faces, kept, file_name, diag);
            }
            free(kept);
            vtk_read_free(&v);
            if (st == MT_OK && record.format_version >= 2)
                st = verify_stored_arrays(file, file_name, &record.report, mesh, diag);
            H5Fclose(file);
        }
    }
    mt_mesh_destroy(mesh);
    mt_archive_record_free(&record);
    return st;
}
