/* Verification of a file's topology arrays (format 6): each one read back
 * (its type and length checked before anything is compared) must equal
 * what the mesh gives (archive_topology.c), and from format 8 on each
 * per-kind array defect_<key> must hold its kind's bit of the bitmask.
 * self_intersecting, present only when the writer was asked for it, is
 * checked for its length and its values 0 or 1: finding the intersections
 * again would cost about ten builds. Loads never call this: the arrays
 * are derived data, and damaged ones are a VTK fault of verification
 * only. */
#include <stdio.h>
#include <stdlib.h>

#include "archive_internal.h"

/* Reads array `info` of /VTKHDF, which must have `rows` rows, into a new
 * buffer (*out, free it). */
static mt_status read_array(hid_t file, const mt__topo_info *info, uint64_t rows, void **out,
                            const char *file_name, mt_diag *diag)
{
    char path[96];
    snprintf(path, sizeof path, "/VTKHDF/%s/%s", info->cell ? "CellData" : "PointData", info->name);
    const size_t size = mt__topo_type_size(info->type);
    *out = malloc((size_t)rows * size + 1);
    if (!*out) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    const mt__h5_kind kind = info->type == MT__TOPO_INT32 ? MT__H5_INT : MT__H5_UINT;
    const hid_t mtype = info->type == MT__TOPO_INT32    ? H5T_NATIVE_INT32
                        : info->type == MT__TOPO_UINT32 ? H5T_NATIVE_UINT32
                                                        : H5T_NATIVE_UINT8;
    mt_status st =
        mt__h5_read_known_rows(file, path, file_name, kind, size, mtype, *out, rows, diag);
    if (st != MT_OK) {
        free(*out);
        *out = NULL;
    }
    return st;
}

static int64_t stored_value(const void *values, mt__topo_type type, uint64_t i)
{
    switch (type) {
        case MT__TOPO_INT32:
            return ((const int32_t *)values)[i];
        case MT__TOPO_UINT32:
            return ((const uint32_t *)values)[i];
        case MT__TOPO_UINT8:
            return ((const uint8_t *)values)[i];
    }
    return 0;
}

static const char *group_of(const mt__topo_info *info)
{
    return info->cell ? "CellData" : "PointData";
}

/* The stored array against the mesh's. */
static mt_status check_array(hid_t file, const mt__topology *t, mt__topo_id id,
                             const char *file_name, mt_diag *diag)
{
    const mt__topo_info *info = &mt__topo_arrays[id];
    const uint64_t rows = info->cell ? t->cells : t->points;
    void *stored = NULL;
    mt_status st = read_array(file, info, rows, &stored, file_name, diag);
    for (uint64_t i = 0; st == MT_OK && i < rows; i++) {
        const int64_t got = stored_value(stored, info->type, i);
        const int64_t want = mt__topology_value(t, id, i);
        if (got != want)
            st = mt__archive_fail(diag, MT_ERR_PARSE,
                                  "%s: /VTKHDF/%s/%s[%llu] is %lld, the mesh gives %lld", file_name,
                                  group_of(info), info->name, (unsigned long long)i, (long long)got,
                                  (long long)want);
    }
    free(stored);
    return st;
}

/* The per-kind arrays beside bitmask `id` (format 8): defect_<key>[i] is
 * bit k of the mesh's bitmask at i. */
static mt_status check_kind_arrays(hid_t file, const mt__topology *t, mt__topo_id id,
                                   const char *file_name, mt_diag *diag)
{
    const mt__topo_info *bitmask = &mt__topo_arrays[id];
    const uint64_t rows = bitmask->cell ? t->cells : t->points;
    mt_status st = MT_OK;
    for (uint32_t k = 0; st == MT_OK && k < MT_DEFECT_KIND_COUNT; k++) {
        char name[MT__TOPO_KIND_NAME_MAX];
        mt__topo_kind_name((mt_defect_kind)k, name, sizeof name);
        const mt__topo_info info = {name, bitmask->cell, MT__TOPO_UINT8, 0, false, ""};
        uint8_t *stored = NULL;
        st = read_array(file, &info, rows, (void **)&stored, file_name, diag);
        for (uint64_t i = 0; st == MT_OK && i < rows; i++) {
            const unsigned want = (unsigned)((mt__topology_value(t, id, i) >> k) & 1);
            if (stored[i] != want)
                st = mt__archive_fail(diag, MT_ERR_PARSE,
                                      "%s: /VTKHDF/%s/%s[%llu] is %u, the mesh gives %u (bit %u "
                                      "of defects)",
                                      file_name, group_of(bitmask), name, (unsigned long long)i,
                                      stored[i], want, k);
        }
        free(stored);
    }
    return st;
}

/* self_intersecting, when there: one row per cell, values 0 or 1. */
static mt_status check_self_intersecting(hid_t file, const mt__topology *t, const char *file_name,
                                         mt_diag *diag)
{
    const mt__topo_info *info = &mt__topo_arrays[MT__TOPO_CELL_SELF_INTERSECTING];
    if (H5Lexists(file, "/VTKHDF/CellData/self_intersecting", H5P_DEFAULT) <= 0) return MT_OK;
    uint8_t *stored = NULL;
    mt_status st = read_array(file, info, t->cells, (void **)&stored, file_name, diag);
    for (uint64_t i = 0; st == MT_OK && i < t->cells; i++)
        if (stored[i] > 1)
            st = mt__archive_fail(diag, MT_ERR_PARSE,
                                  "%s: /VTKHDF/CellData/self_intersecting[%llu] is %u (0 or 1)",
                                  file_name, (unsigned long long)i, stored[i]);
    free(stored);
    return st;
}

mt_status mt__topology_check(hid_t file, const mt_face_list *faces, const mt_mesh *mesh,
                             uint32_t format_version, const char *file_name, mt_diag *diag)
{
    mt__topology t;
    mt_status st =
        mt__topology_compute(faces, mesh, MT_ARCHIVE_SELF_INTERSECTIONS_SKIP, NULL, 0, &t, diag);
    if (st != MT_OK) return st;
    if (H5Lexists(file, "/VTKHDF/CellData", H5P_DEFAULT) <= 0 ||
        H5Lexists(file, "/VTKHDF/PointData", H5P_DEFAULT) <= 0)
        st = mt__archive_fail(diag, MT_ERR_PARSE,
                              "%s: group /VTKHDF/CellData or PointData is missing", file_name);
    for (int id = 0; st == MT_OK && id < MT__TOPO_COUNT; id++)
        if (id != MT__TOPO_CELL_SELF_INTERSECTING)
            st = check_array(file, &t, (mt__topo_id)id, file_name, diag);
    for (int id = 0; st == MT_OK && format_version >= MT_ARCHIVE_FORMAT_VERSION_DEFECT_KINDS &&
                     id < MT__TOPO_COUNT;
         id++)
        if (mt__topo_arrays[id].bitmask)
            st = check_kind_arrays(file, &t, (mt__topo_id)id, file_name, diag);
    if (st == MT_OK) st = check_self_intersecting(file, &t, file_name, diag);
    mt__topology_free(&t);
    return st;
}
