/* Writing the topology arrays (archive_topology.c) into /VTKHDF/CellData
 * and /VTKHDF/PointData, each with its description (and, for a bitmask,
 * the name of every bit) as attributes. An array holding one value
 * throughout is created with that value as its HDF5 fill value and never
 * written: HDF5 allocates no storage for it and every reader (vtkHDFReader,
 * h5py, h5dump) gets the value, so a clean mesh's arrays cost neither
 * space nor time. */
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

static mt_status write_array(hid_t loc, mt__topo_id id, const mt__topology *t,
                             const mt__h5_layout *layout, const char *file, mt_diag *diag)
{
    const mt__topo_info *info = &mt__topo_arrays[id];
    const uint64_t rows = info->cell ? t->cells : t->points;
    const void *values = t->values[id];
    hid_t dset = values ? mt__h5_create_dataset(loc, info->name, file_type(info->type), rows,
                                                layout, file, diag)
                        : create_constant(loc, info, rows, file, diag);
    if (dset < 0) return MT_ERR_IO;
    mt_status st = MT_OK;
    if (values)
        st = mt__h5_write_rows(dset, memory_type(info->type), 0, rows, values, file, info->name,
                               diag);
    if (st == MT_OK) st = describe(dset, info, t, file, diag);
    H5Dclose(dset);
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
    }
    return st;
}
