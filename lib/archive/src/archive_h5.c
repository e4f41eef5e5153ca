/* The HDF5 calls of meshtopo::archive, each wrapped so a failure becomes a
 * status and a message naming the file and the object (and the system's
 * reason, found on HDF5's error stack, when the system failed it: a full
 * disk, a permission), never a print or an abort. Reads check rank, shape,
 * type class, element size and the storage actually present before
 * allocating: a file may claim any size (mt__h5_read_known_rows, whose
 * caller knows the length and allocates for it, skips the last check). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "archive_internal.h"

void mt__h5_quiet(void)
{
    /* HDF5 prints its error stack by default; we report through mt_diag.
     * The setting is per thread in a thread-safe HDF5 build, so it is set on
     * every entry point rather than once. */
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

/* Finds the first "errno = N" in the descriptions of the error stack: the
 * sec2 driver (H5FDsec2.c) records every failed open, read, write and
 * truncate as "..., errno = N, error message = '...', ...". */
static herr_t find_errno(unsigned n, const H5E_error2_t *e, void *data)
{
    int *found = data;
    const char *at = e && e->desc ? strstr(e->desc, "errno = ") : NULL;
    if (at && *found == 0) {
        int value = atoi(at + strlen("errno = "));
        if (value > 0) *found = value;
    }
    return 0;
}

int mt__h5_os_errno(void)
{
    int found = 0;
    /* H5Ewalk2 leaves the stack as it is (it does not clear it on entry). */
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, find_errno, &found);
    return found;
}

mt_status mt__h5_fail(mt_diag *diag, mt_status status, const char *path, const char *fmt, ...)
{
    int err = mt__h5_os_errno();
    char what[sizeof diag->message];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    if (err) return mt__archive_fail_os(diag, status, err, path, "%s", what);
    return mt__archive_fail(diag, status, "%s", what);
}

static mt_status write_attr(hid_t obj, const char *name, hid_t type, hid_t space, const void *value,
                            const char *file, mt_diag *diag)
{
    mt_status st = MT_OK;
    hid_t attr = space < 0 ? -1 : H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    if (attr < 0 || H5Awrite(attr, type, value) < 0)
        st = mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot write attribute %s", file, name);
    if (attr >= 0) H5Aclose(attr);
    if (space >= 0) H5Sclose(space);
    return st;
}

mt_status mt__h5_write_attr_int(hid_t obj, const char *name, hid_t type, const void *value,
                                const char *file, mt_diag *diag)
{
    return write_attr(obj, name, type, H5Screate(H5S_SCALAR), value, file, diag);
}

mt_status mt__h5_write_attr_ints(hid_t obj, const char *name, hid_t type, const void *values,
                                 hsize_t count, const char *file, mt_diag *diag)
{
    return write_attr(obj, name, type, H5Screate_simple(1, &count, NULL), values, file, diag);
}

mt_status mt__h5_write_attr_string(hid_t obj, const char *name, const char *value, const char *file,
                                   mt_diag *diag)
{
    /* Fixed-length ASCII: VTK 9.1 reads /VTKHDF's Type only in this form. */
    size_t len = strlen(value);
    hid_t type = H5Tcopy(H5T_C_S1);
    if (type < 0 || H5Tset_size(type, len > 0 ? len : 1) < 0 ||
        H5Tset_strpad(type, H5T_STR_NULLPAD) < 0 || H5Tset_cset(type, H5T_CSET_ASCII) < 0) {
        if (type >= 0) H5Tclose(type);
        return mt__archive_fail(diag, MT_ERR_IO, "%s: cannot make the type of attribute %s", file,
                                name);
    }
    char empty[1] = {0};
    mt_status st =
        write_attr(obj, name, type, H5Screate(H5S_SCALAR), len > 0 ? value : empty, file, diag);
    H5Tclose(type);
    return st;
}

mt_status mt__h5_write_attr_strings(hid_t obj, const char *name, const char *const *values,
                                    size_t count, const char *file, mt_diag *diag)
{
    size_t width = 1;
    for (size_t i = 0; i < count; i++)
        if (strlen(values[i]) > width) width = strlen(values[i]);
    char *packed = count > 0 ? calloc(count, width) : NULL;
    if (count > 0 && !packed) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < count; i++) memcpy(packed + i * width, values[i], strlen(values[i]));
    hid_t type = H5Tcopy(H5T_C_S1);
    mt_status st = MT_OK;
    if (type < 0 || H5Tset_size(type, width) < 0 || H5Tset_strpad(type, H5T_STR_NULLPAD) < 0 ||
        H5Tset_cset(type, H5T_CSET_ASCII) < 0) {
        st = mt__archive_fail(diag, MT_ERR_IO, "%s: cannot make the type of attribute %s", file,
                              name);
    } else {
        hsize_t n = count;
        char none[1] = {0};
        st = write_attr(obj, name, type, H5Screate_simple(1, &n, NULL), packed ? packed : none,
                        file, diag);
    }
    if (type >= 0) H5Tclose(type);
    free(packed);
    return st;
}

/* Blosc's parameters: four slots the filter fills in itself, then level 5,
 * bit shuffle (2) and LZ4 (compressor 1). Bit shuffle groups the bits of
 * integer ids that differ little from their neighbours, which LZ4 then
 * finds as runs; measured against byte shuffle, Zstd and LZ4HC in
 * meshtopo-bench archive --scan. Optional: a chunk Blosc cannot make
 * smaller (random positions) is stored as it is, where a mandatory filter
 * would fail the write. */
static const unsigned blosc_lz4_params[7] = {0, 0, 0, 0, 5, 2, 1};

bool mt_archive_lz4_available(void)
{
    mt__h5_quiet();
    return H5Zfilter_avail(MT__H5_FILTER_BLOSC) > 0;
}

static bool compressed(const mt__h5_layout *layout)
{
    return layout && (layout->compression == MT_ARCHIVE_COMPRESSION_DEFLATE ||
                      layout->compression == MT_ARCHIVE_COMPRESSION_LZ4);
}

/* The creation property list of a dataset of `elements` elements of
 * elem_size bytes: contiguous (H5P_DEFAULT) unless layout asks for
 * compression and the dataset is large enough for filters to pay (4 KiB);
 * then chunks of about MT__H5_CHUNK_BYTES with shuffle and deflate, or
 * Blosc. -1 on failure. */
static hid_t dataset_dcpl(int rank, const hsize_t *dims, size_t elem_size,
                          const mt__h5_layout *layout)
{
    hsize_t elements = 1;
    for (int i = 0; i < rank; i++) elements *= dims[i];
    if (!compressed(layout) || elements * elem_size < 4096) return H5P_DEFAULT;
    hsize_t row_bytes = elem_size * (rank == 2 ? dims[1] : 1);
    hsize_t chunk[2] = {MT__H5_CHUNK_BYTES / row_bytes, rank == 2 ? dims[1] : 1};
    if (chunk[0] < 1) chunk[0] = 1;
    if (chunk[0] > dims[0]) chunk[0] = dims[0];
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    if (dcpl < 0) return -1;
    herr_t set = H5Pset_chunk(dcpl, rank, chunk);
    if (set >= 0 && layout->compression == MT_ARCHIVE_COMPRESSION_LZ4)
        set = H5Pset_filter(dcpl, MT__H5_FILTER_BLOSC, H5Z_FLAG_OPTIONAL, 7, blosc_lz4_params);
    else if (set >= 0)
        set =
            H5Pset_shuffle(dcpl) < 0 ? -1 : H5Pset_deflate(dcpl, layout->level ? layout->level : 1);
    if (set < 0) {
        H5Pclose(dcpl);
        return -1;
    }
    return dcpl;
}

mt_status mt__h5_write_dataset_layout(hid_t loc, const char *name, hid_t ftype, hid_t mtype,
                                      int rank, const hsize_t *dims, const void *data,
                                      const mt__h5_layout *layout, const char *file, mt_diag *diag)
{
    mt_status st = MT_OK;
    hsize_t elements = 1;
    for (int i = 0; i < rank; i++) elements *= dims[i];
    hid_t dcpl = dataset_dcpl(rank, dims, H5Tget_size(ftype), layout);
    hid_t space = dcpl < 0 ? -1 : H5Screate_simple(rank, dims, NULL);
    hid_t dset =
        space < 0 ? -1 : H5Dcreate2(loc, name, ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    if (dset < 0 ||
        (elements > 0 && H5Dwrite(dset, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0))
        st = mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot write dataset %s", file, name);
    if (dset >= 0) H5Dclose(dset);
    if (space >= 0) H5Sclose(space);
    if (dcpl >= 0 && dcpl != H5P_DEFAULT) H5Pclose(dcpl);
    return st;
}

hid_t mt__h5_create_dataset(hid_t loc, const char *name, hid_t ftype, hsize_t rows,
                            const mt__h5_layout *layout, const char *file, mt_diag *diag)
{
    hsize_t dims[1] = {rows};
    hid_t dcpl = dataset_dcpl(1, dims, H5Tget_size(ftype), layout);
    hid_t space = dcpl < 0 ? -1 : H5Screate_simple(1, dims, NULL);
    hid_t dset =
        space < 0 ? -1 : H5Dcreate2(loc, name, ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    if (dset < 0) mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot create dataset %s", file, name);
    if (space >= 0) H5Sclose(space);
    if (dcpl >= 0 && dcpl != H5P_DEFAULT) H5Pclose(dcpl);
    return dset;
}

mt_status mt__h5_write_rows(hid_t dset, hid_t mtype, hsize_t first, hsize_t count, const void *data,
                            const char *file, const char *name, mt_diag *diag)
{
    if (count == 0) return MT_OK;
    hid_t fspace = H5Dget_space(dset);
    hid_t mspace = H5Screate_simple(1, &count, NULL);
    bool ok = fspace >= 0 && mspace >= 0 &&
              H5Sselect_hyperslab(fspace, H5S_SELECT_SET, &first, NULL, &count, NULL) >= 0 &&
              H5Dwrite(dset, mtype, mspace, fspace, H5P_DEFAULT, data) >= 0;
    mt_status st = MT_OK;
    if (!ok) /* before the closes below, which clear HDF5's error stack */
        st = mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot write rows %llu.. of dataset %s", file,
                         (unsigned long long)first, name);
    if (mspace >= 0) H5Sclose(mspace);
    if (fspace >= 0) H5Sclose(fspace);
    return st;
}

mt_status mt__h5_write_dataset(hid_t loc, const char *name, hid_t ftype, hid_t mtype, int rank,
                               const hsize_t *dims, const void *data, const char *file,
                               mt_diag *diag)
{
    return mt__h5_write_dataset_layout(loc, name, ftype, mtype, rank, dims, data, NULL, file, diag);
}

/* Opens attribute `name` of obj holding exactly one element; *out_type is
 * its type. */
static mt_status open_attr(hid_t obj, const char *name, const char *file, hid_t *out_attr,
                           hid_t *out_type, mt_diag *diag)
{
    *out_attr = *out_type = -1;
    if (H5Aexists(obj, name) <= 0)
        return mt__archive_fail(diag, MT_ERR_PARSE, "%s: attribute %s is missing", file, name);
    hid_t attr = H5Aopen(obj, name, H5P_DEFAULT);
    hid_t space = attr < 0 ? -1 : H5Aget_space(attr);
    hssize_t n = space < 0 ? -1 : H5Sget_simple_extent_npoints(space);
    if (space >= 0) H5Sclose(space);
    if (attr < 0 || n != 1) {
        if (attr >= 0) H5Aclose(attr);
        return mt__archive_fail(diag, MT_ERR_PARSE,
                                "%s: attribute %s is not a single value (%lld elements)", file,
                                name, (long long)n);
    }
    *out_attr = attr;
    *out_type = H5Aget_type(attr);
    return MT_OK;
}

static mt_status read_attr_int(hid_t obj, const char *name, const char *file, hid_t mtype,
                               void *out, mt_diag *diag)
{
    hid_t attr, type;
    mt_status st = open_attr(obj, name, file, &attr, &type, diag);
    if (st != MT_OK) return st;
    if (type < 0 || H5Tget_class(type) != H5T_INTEGER || H5Tget_size(type) > 8)
        st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: attribute %s is not an integer", file, name);
    else if (H5Aread(attr, mtype, out) < 0)
        st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: attribute %s cannot be read", file, name);
    if (type >= 0) H5Tclose(type);
    H5Aclose(attr);
    return st;
}

mt_status mt__h5_read_attr_i64(hid_t obj, const char *name, const char *file, int64_t *out,
                               mt_diag *diag)
{
    return read_attr_int(obj, name, file, H5T_NATIVE_INT64, out, diag);
}

mt_status mt__h5_read_attr_u64(hid_t obj, const char *name, const char *file, uint64_t *out,
                               mt_diag *diag)
{
    return read_attr_int(obj, name, file, H5T_NATIVE_UINT64, out, diag);
}

mt_status mt__h5_read_attr_string(hid_t obj, const char *name, const char *file, size_t max_len,
                                  char **out, mt_diag *diag)
{
    *out = NULL;
    hid_t attr, type;
    mt_status st = open_attr(obj, name, file, &attr, &type, diag);
    if (st != MT_OK) return st;
    hid_t mtype = -1;
    if (type < 0 || H5Tget_class(type) != H5T_STRING) {
        st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: attribute %s is not a string", file, name);
    } else if (H5Tis_variable_str(type) > 0) {
        char *value = NULL;
        mtype = H5Tcopy(H5T_C_S1);
        if (mtype < 0 || H5Tset_size(mtype, H5T_VARIABLE) < 0 || H5Aread(attr, mtype, &value) < 0 ||
            !value) {
            st =
                mt__archive_fail(diag, MT_ERR_PARSE, "%s: attribute %s cannot be read", file, name);
        } else if (strlen(value) > max_len) {
            st = mt__archive_fail(diag, MT_ERR_PARSE,
                                  "%s: attribute %s is %zu bytes long (at most %zu)", file, name,
                                  strlen(value), max_len);
        } else if (!(*out = mt__archive_strdup(value))) {
            st = mt__archive_fail(diag, MT_ERR_NOMEM, "%s: out of memory", file);
        }
        if (value) H5free_memory(value);
    } else {
        size_t size = H5Tget_size(type);
        char *value = NULL;
        mtype = H5Tcopy(H5T_C_S1);
        if (size == 0 || size > max_len + 1) {
            st = mt__archive_fail(diag, MT_ERR_PARSE,
                                  "%s: attribute %s is %zu bytes long (at most %zu)", file, name,
                                  size, max_len);
        } else if (!(value = calloc(size + 1, 1))) {
            st = mt__archive_fail(diag, MT_ERR_NOMEM, "%s: out of memory", file);
        } else if (mtype < 0 || H5Tset_size(mtype, size) < 0 ||
                   H5Tset_strpad(mtype, H5T_STR_NULLPAD) < 0 || H5Aread(attr, mtype, value) < 0) {
            st =
                mt__archive_fail(diag, MT_ERR_PARSE, "%s: attribute %s cannot be read", file, name);
        }
        if (st == MT_OK && strlen(value) > max_len)
            st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: attribute %s is too long", file, name);
        if (st == MT_OK)
            *out = value;
        else
            free(value);
    }
    if (mtype >= 0) H5Tclose(mtype);
    if (type >= 0) H5Tclose(type);
    H5Aclose(attr);
    return st;
}

/* Whether the dataset's element type is what the reader expects. */
static bool type_matches(hid_t type, mt__h5_kind kind, size_t elem_size)
{
    H5T_class_t cls = H5Tget_class(type);
    switch (kind) {
        case MT__H5_INT:
        case MT__H5_UINT:
            return cls == H5T_INTEGER && H5Tget_size(type) == elem_size &&
                   H5Tget_sign(type) == (kind == MT__H5_INT ? H5T_SGN_2 : H5T_SGN_NONE);
        case MT__H5_FLOAT:
            return cls == H5T_FLOAT && H5Tget_size(type) == elem_size;
        case MT__H5_COMPOUND:
            return cls == H5T_COMPOUND;
    }
    return false;
}

static const char *kind_name(mt__h5_kind kind, size_t elem_size)
{
    switch (kind) {
        case MT__H5_INT:
            return elem_size == 8 ? "int64" : elem_size == 4 ? "int32" : "signed integer";
        case MT__H5_UINT:
            return elem_size == 1 ? "uint8" : elem_size == 4 ? "uint32" : "unsigned";
        case MT__H5_FLOAT:
            return "float64";
        case MT__H5_COMPOUND:
            return "compound";
    }
    return "?";
}

/* Opens dataset `name` and checks rank, shape, type, the row limit and
 * (check_storage) that the stored bytes can back the claimed size. On
 * MT_OK *out_dset is open (close with H5Dclose) and *out_rows its first
 * dimension. */
static mt_status open_dataset(hid_t loc, const char *name, const char *file, int rank, hsize_t cols,
                              mt__h5_kind kind, size_t elem_size, bool check_storage,
                              hid_t *out_dset, uint64_t *out_rows, mt_diag *diag)
{
    *out_dset = -1;
    *out_rows = 0;
    if (H5Lexists(loc, name, H5P_DEFAULT) <= 0)
        return mt__archive_fail(diag, MT_ERR_PARSE, "%s: dataset %s is missing", file, name);
    mt_status st = MT_OK;
    hid_t dset = H5Dopen2(loc, name, H5P_DEFAULT);
    hid_t space = dset < 0 ? -1 : H5Dget_space(dset);
    hid_t type = dset < 0 ? -1 : H5Dget_type(dset);
    hid_t dcpl = dset < 0 ? -1 : H5Dget_create_plist(dset);
    hsize_t dims[2] = {0, 0};
    int ndims = space < 0 ? -1 : H5Sget_simple_extent_ndims(space);
    if (dset < 0 || space < 0 || type < 0 || dcpl < 0) {
        st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: dataset %s cannot be opened", file, name);
    } else if (ndims != rank || H5Sget_simple_extent_dims(space, dims, NULL) != rank ||
               (rank == 2 && dims[1] != cols)) {
        if (rank == 2)
            st = mt__archive_fail(diag, MT_ERR_PARSE,
                                  "%s: dataset %s must have shape (n, %llu), not rank %d", file,
                                  name, (unsigned long long)cols, ndims);
        else
            st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: dataset %s must be 1-D, not rank %d",
                                  file, name, ndims);
        if (rank == 2 && ndims == 2)
            mt__archive_fail(diag, MT_ERR_PARSE,
                             "%s: dataset %s must have shape (n, %llu), not (%llu, %llu)", file,
                             name, (unsigned long long)cols, (unsigned long long)dims[0],
                             (unsigned long long)dims[1]);
    } else if (!type_matches(type, kind, elem_size)) {
        st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: dataset %s must hold %s values", file, name,
                              kind_name(kind, elem_size));
    } else if (dims[0] > MT__ARCHIVE_MAX_ELEMENTS) {
        st = mt__archive_fail(diag, MT_ERR_TOO_LARGE,
                              "%s: dataset %s claims %llu rows (at most %llu)", file, name,
                              (unsigned long long)dims[0], MT__ARCHIVE_MAX_ELEMENTS);
    }
    uint64_t elements = (uint64_t)dims[0] * (rank == 2 ? cols : 1);
    if (st == MT_OK && check_storage && elements > 0) {
        /* The bytes present must back the claimed size: without filters the
         * stored size is the data's; deflate compresses at most ~1032:1. */
        uint64_t needed = elements * H5Tget_size(type);
        uint64_t stored = H5Dget_storage_size(dset);
        int filters = H5Pget_nfilters(dcpl);
        uint64_t backed = filters > 0 ? stored * 1100 + 4096 : stored;
        if (needed > backed)
            st = mt__archive_fail(diag, MT_ERR_TOO_LARGE,
                                  "%s: dataset %s claims %llu elements but stores only %llu bytes",
                                  file, name, (unsigned long long)elements,
                                  (unsigned long long)stored);
    }
    if (dcpl >= 0) H5Pclose(dcpl);
    if (type >= 0) H5Tclose(type);
    if (space >= 0) H5Sclose(space);
    if (st != MT_OK) {
        if (dset >= 0) H5Dclose(dset);
        return st;
    }
    *out_dset = dset;
    *out_rows = dims[0];
    return MT_OK;
}

static mt_status open_checked(hid_t loc, const char *name, const char *file, int rank, hsize_t cols,
                              mt__h5_kind kind, size_t elem_size, hid_t *out_dset,
                              uint64_t *out_rows, mt_diag *diag)
{
    return open_dataset(loc, name, file, rank, cols, kind, elem_size, true, out_dset, out_rows,
                        diag);
}

/* Why reading dataset `name` failed: a filter HDF5 does not find (the
 * Blosc plugin of an LZ4 archive on a machine without it) is named, with
 * what provides it, as MT_ERR_UNSUPPORTED; anything else is MT_ERR_IO. */
static mt_status read_failed(hid_t dset, const char *name, const char *file, mt_diag *diag)
{
    hid_t dcpl = H5Dget_create_plist(dset);
    int missing = -1;
    for (int i = 0; dcpl >= 0 && missing < 0 && i < H5Pget_nfilters(dcpl); i++) {
        unsigned flags, config;
        size_t nvalues = 0;
        H5Z_filter_t id =
            H5Pget_filter2(dcpl, (unsigned)i, &flags, &nvalues, NULL, 0, NULL, &config);
        if (id >= 0 && H5Zfilter_avail(id) <= 0) missing = (int)id;
    }
    if (dcpl >= 0) H5Pclose(dcpl);
    if (missing == MT__H5_FILTER_BLOSC)
        return mt__archive_fail(
            diag, MT_ERR_UNSUPPORTED,
            "%s: dataset %s is compressed with Blosc (HDF5 filter %d), whose "
            "plugin HDF5 does not find: install hdf5-filter-plugin-blosc-serial "
            "or point HDF5_PLUGIN_PATH at it",
            file, name, missing);
    if (missing >= 0)
        return mt__archive_fail(diag, MT_ERR_UNSUPPORTED,
                                "%s: dataset %s needs HDF5 filter %d, which HDF5 does not find",
                                file, name, missing);
    return mt__h5_fail(diag, MT_ERR_IO, file, "%s: dataset %s cannot be read", file, name);
}

/* MT_OK when the compound stored in dset has every member of the memory
 * compound mtype: HDF5 matches members by name and would leave a missing
 * one unwritten. */
static mt_status check_members(hid_t dset, hid_t mtype, const char *file, const char *name,
                               mt_diag *diag)
{
    hid_t ftype = H5Dget_type(dset);
    int n = H5Tget_nmembers(mtype);
    mt_status st = ftype < 0 || n < 0
                       ? mt__archive_fail(diag, MT_ERR_PARSE, "%s: dataset %s: no type", file, name)
                       : MT_OK;
    for (int i = 0; st == MT_OK && i < n; i++) {
        char *member = H5Tget_member_name(mtype, (unsigned)i);
        if (!member)
            st = mt__archive_fail(diag, MT_ERR_NOMEM, "%s: out of memory", file);
        else if (H5Tget_member_index(ftype, member) < 0)
            st = mt__archive_fail(diag, MT_ERR_PARSE, "%s: dataset %s has no member %s", file, name,
                                  member);
        if (member) H5free_memory(member);
    }
    if (ftype >= 0) H5Tclose(ftype);
    return st;
}

mt_status mt__h5_read_dataset(hid_t loc, const char *name, const char *file, int rank, hsize_t cols,
                              mt__h5_kind kind, size_t elem_size, hid_t mtype, void **out_data,
                              uint64_t *out_rows, mt_diag *diag)
{
    *out_data = NULL;
    *out_rows = 0;
    hid_t dset;
    uint64_t rows;
    mt_status st = open_checked(loc, name, file, rank, cols, kind, elem_size, &dset, &rows, diag);
    if (st != MT_OK) return st;
    if (kind == MT__H5_COMPOUND) st = check_members(dset, mtype, file, name, diag);
    uint64_t elements = rows * (rank == 2 ? cols : 1);
    size_t msize = H5Tget_size(mtype);
    if (st == MT_OK && elements > 0) {
        if (msize == 0 || elements > SIZE_MAX / msize) {
            st =
                mt__archive_fail(diag, MT_ERR_TOO_LARGE, "%s: dataset %s is too large", file, name);
        } else if (!(*out_data = malloc((size_t)elements * msize))) {
            st = mt__archive_fail(diag, MT_ERR_NOMEM, "%s: out of memory reading dataset %s", file,
                                  name);
        } else if (H5Dread(dset, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, *out_data) < 0) {
            st = read_failed(dset, name, file, diag);
        }
    }
    if (st == MT_OK) {
        *out_rows = rows;
    } else {
        free(*out_data);
        *out_data = NULL;
    }
    H5Dclose(dset);
    return st;
}

mt_status mt__h5_read_blocks(hid_t loc, const char *name, const char *file, mt__h5_kind kind,
                             size_t elem_size, hid_t mtype, void *buf, size_t block_rows,
                             mt__h5_block_fn fn, void *ctx, uint64_t *out_rows, mt_diag *diag)
{
    hid_t dset;
    uint64_t rows;
    *out_rows = 0;
    mt_status st = open_checked(loc, name, file, 1, 0, kind, elem_size, &dset, &rows, diag);
    if (st != MT_OK) return st;
    hid_t fspace = H5Dget_space(dset);
    if (fspace < 0)
        st = mt__h5_fail(diag, MT_ERR_IO, file, "%s: dataset %s: no dataspace", file, name);
    for (uint64_t first = 0; st == MT_OK && first < rows; first += block_rows) {
        hsize_t at = first, n = rows - first < block_rows ? rows - first : block_rows;
        hid_t mspace = H5Screate_simple(1, &n, NULL);
        if (mspace < 0 || H5Sselect_hyperslab(fspace, H5S_SELECT_SET, &at, NULL, &n, NULL) < 0 ||
            H5Dread(dset, mtype, mspace, fspace, H5P_DEFAULT, buf) < 0)
            st = read_failed(dset, name, file, diag);
        if (mspace >= 0) H5Sclose(mspace);
        if (st == MT_OK) fn(ctx, buf, (size_t)n);
    }
    if (fspace >= 0) H5Sclose(fspace);
    H5Dclose(dset);
    if (st == MT_OK) *out_rows = rows;
    return st;
}

mt_status mt__h5_dataset_rows(hid_t loc, const char *name, const char *file, int rank, hsize_t cols,
                              mt__h5_kind kind, size_t elem_size, uint64_t *out_rows, mt_diag *diag)
{
    hid_t dset;
    mt_status st =
        open_checked(loc, name, file, rank, cols, kind, elem_size, &dset, out_rows, diag);
    if (st == MT_OK) H5Dclose(dset);
    return st;
}

/* Reads the whole of an open dataset of `found` rows into buf, which holds
 * `rows`; closes it. */
static mt_status read_rows_into(hid_t dset, uint64_t found, const char *name, const char *file,
                                hid_t mtype, void *buf, uint64_t rows, mt_diag *diag)
{
    mt_status st = MT_OK;
    if (found != rows)
        st = mt__archive_fail(diag, MT_ERR_PARSE,
                              "%s: dataset %s has %llu rows, the counts say %llu", file, name,
                              (unsigned long long)found, (unsigned long long)rows);
    else if (rows > 0 && H5Dread(dset, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0)
        st = read_failed(dset, name, file, diag);
    H5Dclose(dset);
    return st;
}

mt_status mt__h5_read_dataset_into(hid_t loc, const char *name, const char *file, int rank,
                                   hsize_t cols, mt__h5_kind kind, size_t elem_size, hid_t mtype,
                                   void *buf, uint64_t rows, mt_diag *diag)
{
    hid_t dset;
    uint64_t found;
    mt_status st = open_checked(loc, name, file, rank, cols, kind, elem_size, &dset, &found, diag);
    if (st != MT_OK) return st;
    return read_rows_into(dset, found, name, file, mtype, buf, rows, diag);
}

mt_status mt__h5_read_known_rows(hid_t loc, const char *name, const char *file, mt__h5_kind kind,
                                 size_t elem_size, hid_t mtype, void *buf, uint64_t rows,
                                 mt_diag *diag)
{
    hid_t dset;
    uint64_t found;
    mt_status st = open_dataset(loc, name, file, 1, 0, kind, elem_size, false, &dset, &found, diag);
    if (st != MT_OK) return st;
    return read_rows_into(dset, found, name, file, mtype, buf, rows, diag);
}
