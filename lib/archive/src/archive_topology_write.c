/* Writing the topology arrays (archive_topology.c) into /VTKHDF/CellData
 * and /VTKHDF/PointData, each with its description (and, for a bitmask,
 * the name of every bit) as attributes, and beside each defects bitmask
 * one 0/1 array per defect kind (format 8). An array holding one value
 * throughout is created with that value as its HDF5 fill value and never
 * written: HDF5 allocates no storage for it and every reader (vtkHDFReader,
 * h5py, h5dump) gets the value, so a clean mesh's arrays cost neither
 * space nor time. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "archive_internal.h"

static hid_t file_type(mt__topo_type type)
{
    return type == MT__TOPO_INT32    ? H5T_STD_I32LE
           : type == MT__TOPO_UINT32 ? H5T_STD_U32LE
                                     : H5T_STD_U8LE;
}

static hid_t memory_type(mt__topo_type type)
{
    return type == MT__TOPO_INT32    ? H5T_NATIVE_INT32
           : type == MT__TOPO_UINT32 ? H5T_NATIVE_UINT32
                                     : H5T_NATIVE_UINT8;
}

/* A dataset of `rows` rows that is never written: reads give `fill`. */
static hid_t create_constant(hid_t loc, const mt__topo_info *info, uint64_t rows, const char *file,
                             mt_diag *diag)
{
    hsize_t dims[1] = {rows};
    uint32_t u32 = info->fill;
    int32_t i32 = (int32_t)info->fill;
    uint8_t u8 = (uint8_t)info->fill;
    const void *fill = info->type == MT__TOPO_INT32    ? (const void *)&i32
                       : info->type == MT__TOPO_UINT32 ? (const void *)&u32
                                                       : (const void *)&u8;
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    hid_t space = H5Screate_simple(1, dims, NULL);
    hid_t dset = -1;
    if (dcpl >= 0 && space >= 0 && H5Pset_fill_value(dcpl, memory_type(info->type), fill) >= 0 &&
        H5Pset_alloc_time(dcpl, H5D_ALLOC_TIME_LATE) >= 0 &&
        H5Pset_fill_time(dcpl, H5D_FILL_TIME_IFSET) >= 0)
        dset = H5Dcreate2(loc, info->name, file_type(info->type), space, H5P_DEFAULT, dcpl,
                          H5P_DEFAULT);
    if (dset < 0)
        mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot create dataset %s", file, info->name);
    if (space >= 0) H5Sclose(space);
    if (dcpl >= 0) H5Pclose(dcpl);
    return dset;
}

/* The attributes of one array's dataset. */
static mt_status describe(hid_t dset, const mt__topo_info *info, const mt__topology *t,
                          const char *file, mt_diag *diag)
{
    mt_status st = mt__h5_write_attr_string(dset, "description", info->description, file, diag);
    if (st == MT_OK && info->bitmask) {
        const char *keys[MT_DEFECT_KIND_COUNT];
        for (int k = 0; k < MT_DEFECT_KIND_COUNT; k++) keys[k] = mt_defect_key((mt_defect_kind)k);
        st = mt__h5_write_attr_strings(dset, "bits", keys, MT_DEFECT_KIND_COUNT, file, diag);
    }
    if (st == MT_OK && info == &mt__topo_arrays[MT__TOPO_CELL_SELF_INTERSECTING])
        st = mt__h5_write_attr_int(dset, "pairs", H5T_NATIVE_UINT64, &t->self_intersection_pairs,
                                   file, diag);
    return st;
}

/* The dataset of array `info` with `rows` rows: `values` written, or a
 * constant (its fill) when values is NULL. Sets *out_dset (close it) on
 * MT_OK. */
static mt_status create_array(hid_t loc, const mt__topo_info *info, uint64_t rows,
                              const void *values, const mt__h5_layout *layout, const char *file,
                              hid_t *out_dset, mt_diag *diag)
{
    hid_t dset = values ? mt__h5_create_dataset(loc, info->name, file_type(info->type), rows,
                                                layout, file, diag)
                        : create_constant(loc, info, rows, file, diag);
    if (dset < 0) return MT_ERR_IO;
    mt_status st = MT_OK;
    if (values)
        st = mt__h5_write_rows(dset, memory_type(info->type), 0, rows, values, file, info->name,
                               diag);
    if (st != MT_OK) {
        H5Dclose(dset);
        return st;
    }
    *out_dset = dset;
    return MT_OK;
}

static mt_status write_array(hid_t loc, mt__topo_id id, const mt__topology *t,
                             const mt__h5_layout *layout, const char *file, mt_diag *diag)
{
    const mt__topo_info *info = &mt__topo_arrays[id];
    const uint64_t rows = info->cell ? t->cells : t->points;
    hid_t dset = -1;
    mt_status st = create_array(loc, info, rows, t->values[id], layout, file, &dset, diag);
    if (st != MT_OK) return st;
    st = describe(dset, info, t, file, diag);
    H5Dclose(dset);
    return st;
}

/* defect_<key> for every kind beside bitmask `id` (CellData/defects or
 * PointData/defects), made from that bitmask so the two cannot disagree. A
 * kind no row has (on a clean mesh, every kind) is a dataset never written:
 * only the kinds a mesh has cost a byte per row each. */
static mt_status write_kind_arrays(hid_t loc, mt__topo_id id, const mt__topology *t,
                                   const mt__h5_layout *layout, const char *file, mt_diag *diag)
{
    const mt__topo_info *bitmask = &mt__topo_arrays[id];
    const uint64_t rows = bitmask->cell ? t->cells : t->points;
    const uint32_t *bits = t->values[id];
    uint8_t *flags = bits ? malloc((size_t)rows + 1) : NULL;
    if (bits && !flags) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    mt_status st = MT_OK;
    for (uint32_t k = 0; st == MT_OK && k < MT_DEFECT_KIND_COUNT; k++) {
        char name[MT__TOPO_KIND_NAME_MAX], description[384];
        mt__topo_kind_name((mt_defect_kind)k, name, sizeof name);
        snprintf(description, sizeof description,
                 "1 when the %s is involved in a defect of kind %s (%s), that is when bit %u "
                 "(value %u) of defects is set, else 0",
                 bitmask->cell ? "face" : "vertex", mt_defect_key((mt_defect_kind)k),
                 mt_defect_description((mt_defect_kind)k), k, 1u << k);
        const mt__topo_info info = {name, bitmask->cell, MT__TOPO_UINT8, 0, false, description};
        bool any = false;
        for (uint64_t i = 0; bits && i < rows; i++) {
            flags[i] = (uint8_t)((bits[i] >> k) & 1u);
            any = any || flags[i];
        }
        hid_t dset = -1;
        st = create_array(loc, &info, rows, any ? flags : NULL, layout, file, &dset, diag);
        if (st != MT_OK) break;
        st = mt__h5_write_attr_string(dset, "description", description, file, diag);
        if (st == MT_OK) st = mt__h5_write_attr_int(dset, "bit", H5T_NATIVE_UINT32, &k, file, diag);
        H5Dclose(dset);
    }
    free(flags);
    return st;
}

mt_status mt__topology_write(hid_t cell_data, hid_t point_data, const mt__topology *t,
                             const mt__h5_layout *layout, const char *file, mt_diag *diag)
{
    mt_status st = MT_OK;
    for (int id = 0; st == MT_OK && id < MT__TOPO_COUNT; id++) {
        const mt__topo_info *info = &mt__topo_arrays[id];
        hid_t loc = info->cell ? cell_data : point_data;
        if (t->present[id])
            st = write_array(loc, (mt__topo_id)id, t, layout, file, diag);
        else
            /* Where the array would be, why it is not. */
            st = mt__h5_write_attr_string(loc, info->name, t->absent_reason, file, diag);
        if (st == MT_OK && info->bitmask)
            st = write_kind_arrays(loc, (mt__topo_id)id, t, layout, file, diag);
    }
    return st;
}
