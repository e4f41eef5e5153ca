/* Checking an archived version: rebuilding the half-edge mesh from the
 * stored face list and comparing its report with the stored one
 * (mt_archive_record_build), and the whole-file verification behind
 * `meshtopo archive verify`: the checks a load makes (archive_check.c, so a
 * load and a verification agree on every file), then the VTKHDF datasets
 * against the face list and (format 6) the topology arrays against the
 * mesh (archive_topology_check.c). */
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

mt_status mt_archive_verify_file_with(const mt_archive *archive, const char *file_name,
                                      mt_archive_hash_fn hash, void *hash_ctx,
                                      mt_archive_fault *out_fault, mt_diag *diag)
{
    mt_diag_clear(diag);
    mt_archive_fault fault = MT_ARCHIVE_FAULT_NONE;
    if (out_fault) *out_fault = fault;
    if (!archive || !file_name || strchr(file_name, '/') || file_name[0] == '.')
        return mt__archive_fail(diag, MT_ERR_INVALID_ARG, "'%s' is not an archive file name",
                                file_name ? file_name : "(null)");
    hid_t file;
    mt_status st = mt__archive_h5_open(archive, file_name, &file, NULL, &fault, diag);
    if (st != MT_OK) {
        if (out_fault) *out_fault = fault;
        return st;
    }
    /* The checks of a load, with the face list kept for the VTKHDF check. */
    mt__check c;
    memset(&c, 0, sizeof c);
    c.hash = hash ? hash : archive->content_hash;
    c.hash_ctx = hash ? hash_ctx : archive->content_hash_ctx;
    c.keep_faces = true;
    st = mt__archive_check(file, file_name, &c, diag);
    fault = c.fault;
    if (st == MT_OK && fault == MT_ARCHIVE_FAULT_DERIVED)
        st = mt__archive_fail(diag, MT_ERR_CORRUPT, "%s", c.fallback.message);
    if (st == MT_OK) {
        /* The VTKHDF cells are the faces the mesh kept. */
        vtk_read v;
        st = read_vtk(file, file_name, &v, diag);
        uint8_t *kept = st == MT_OK ? malloc((size_t)c.record.faces.num_faces + 1) : NULL;
        if (st == MT_OK && !kept) st = mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
        if (st == MT_OK) {
            mt_mesh_view view;
            mt_mesh_get_view(c.mesh, &view);
            for (uint32_t f = 0; f < c.record.faces.num_faces; f++)
                kept[f] = view.face_he[f] != MT_NONE;
            st = mt_archive_check_vtk(&v.arrays, &c.record.faces, kept, file_name, diag);
        }
        if (st == MT_OK && c.record.format_version >= MT_ARCHIVE_FORMAT_VERSION_TOPOLOGY)
            st = mt__topology_check(file, &c.record.faces, c.mesh, c.record.format_version,
                                    file_name, diag);
        free(kept);
        vtk_read_free(&v);
        if (st != MT_OK)
            fault = st == MT_ERR_NOMEM || mt__archive_last_errno ? MT_ARCHIVE_FAULT_SYSTEM
                                                                 : MT_ARCHIVE_FAULT_VTK;
    }
    H5Fclose(file);
    mt_mesh_destroy(c.mesh);
    mt_archive_record_free(&c.record);
    if (out_fault) *out_fault = fault;
    return st;
}

mt_status mt_archive_verify_file(const mt_archive *archive, const char *file_name,
                                 mt_archive_hash_fn hash, void *hash_ctx, mt_diag *diag)
{
    return mt_archive_verify_file_with(archive, file_name, hash, hash_ctx, NULL, diag);
}
