/* Earlier archive formats made from files this meshtopo wrote
 * (archive_legacy.h): the defect records of format 7 turned back into the
 * {kind, a, b, c} rows of formats 1 to 6 with mt_defect_from_record, and
 * below format 8 the per-kind arrays defect_<key> removed. */
#include "archive_legacy.h"

#include <hdf5.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "archive_test_util.h"
#include "meshtopo/archive.h"
#include "meshtopo/defect_record.h"

static const char defects_path[] = "/meshtopo/report/defects";

static hid_t kind_type(void)
{
    hid_t kind = H5Tenum_create(H5T_NATIVE_UINT32);
    for (uint32_t k = 0; k < MT_DEFECT_KIND_COUNT; k++)
        H5Tenum_insert(kind, mt_defect_key((mt_defect_kind)k), &k);
    return kind;
}

int64_t al_record_type(void)
{
    const hsize_t two[1] = {2};
    hid_t kind = kind_type(), pair = H5Tarray_create2(H5T_NATIVE_UINT32, 1, two);
    hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(mt_defect_record));
#define MEMBER(name, type) H5Tinsert(t, #name, offsetof(mt_defect_record, name), type)
    MEMBER(kind, kind);
    MEMBER(vertices, pair);
    MEMBER(faces, pair);
    MEMBER(edge, pair);
    MEMBER(face_count, H5T_NATIVE_UINT32);
    MEMBER(index, H5T_NATIVE_INT64);
    MEMBER(position, H5T_NATIVE_UINT32);
    MEMBER(face_size, H5T_NATIVE_UINT32);
    MEMBER(distinct_vertices, H5T_NATIVE_UINT32);
    MEMBER(fans, H5T_NATIVE_UINT32);
    MEMBER(on_nonmanifold_edge, H5T_NATIVE_UINT32);
    MEMBER(axis, H5T_NATIVE_UINT32);
#undef MEMBER
    H5Tclose(kind);
    H5Tclose(pair);
    return t;
}

/* Replaces the defects dataset by `count` rows of type t from rows. */
static bool replace_defects(const char *path, hid_t t, const void *rows, uint64_t count)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (f < 0) return false;
    bool ok = H5Ldelete(f, defects_path, H5P_DEFAULT) >= 0;
    hsize_t n = count;
    hid_t space = H5Screate_simple(1, &n, NULL);
    hid_t d = H5Dcreate2(f, defects_path, t, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ok = ok && d >= 0 && (count == 0 || H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows) >= 0);
    if (d >= 0) H5Dclose(d);
    H5Sclose(space);
    return H5Fclose(f) >= 0 && ok;
}

bool al_write_records(const char *path, const void *records, uint64_t count)
{
    hid_t t = al_record_type();
    bool ok = replace_defects(path, t, records, count);
    H5Tclose(t);
    return ok;
}

bool al_write_compact_defects(const char *path, const uint32_t (*rows)[4], uint64_t count)
{
    hid_t kind = kind_type();
    hid_t t = H5Tcreate(H5T_COMPOUND, 4 * sizeof(uint32_t));
    H5Tinsert(t, "kind", 0, kind);
    H5Tinsert(t, "a", 4, H5T_NATIVE_UINT32);
    H5Tinsert(t, "b", 8, H5T_NATIVE_UINT32);
    H5Tinsert(t, "c", 12, H5T_NATIVE_UINT32);
    bool ok = replace_defects(path, t, rows, count);
    H5Tclose(t);
    H5Tclose(kind);
    return ok;
}

/* Reads the file's defect records as compact rows (malloc'ed). */
static bool read_compact(const char *path, uint32_t (**out_rows)[4], uint64_t *out_count)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    *out_rows = NULL;
    *out_count = 0;
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = f < 0 ? -1 : H5Dopen2(f, defects_path, H5P_DEFAULT);
    hid_t space = d < 0 ? -1 : H5Dget_space(d);
    hsize_t n = 0;
    bool ok = space >= 0 && H5Sget_simple_extent_dims(space, &n, NULL) == 1;
    mt_defect_record *records = ok ? calloc(n + 1, sizeof *records) : NULL;
    uint32_t(*rows)[4] = ok ? calloc(n + 1, sizeof *rows) : NULL;
    hid_t t = al_record_type();
    ok = ok && records && rows &&
         (n == 0 || H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, records) >= 0);
    for (hsize_t i = 0; ok && i < n; i++) {
        mt_defect defect;
        ok = mt_defect_from_record(&records[i], &defect) == MT_OK;
        rows[i][0] = defect.kind;
        rows[i][1] = defect.a;
        rows[i][2] = defect.b;
        rows[i][3] = defect.c;
    }
    H5Tclose(t);
    free(records);
    if (space >= 0) H5Sclose(space);
    if (d >= 0) H5Dclose(d);
    if (f >= 0) H5Fclose(f);
    if (!ok) {
        free(rows);
        return false;
    }
    *out_rows = rows;
    *out_count = n;
    return true;
}

/* Whether the file's defects are records (not yet rewritten). */
static bool has_records(const char *path)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = f < 0 ? -1 : H5Dopen2(f, defects_path, H5P_DEFAULT);
    hid_t t = d < 0 ? -1 : H5Dget_type(d);
    bool records = t >= 0 && H5Tget_member_index(t, "vertices") >= 0;
    if (t >= 0) H5Tclose(t);
    if (d >= 0) H5Dclose(d);
    if (f >= 0) H5Fclose(f);
    return records;
}

/* Deletes /VTKHDF/CellData/defect_<key> and PointData/defect_<key> (those
 * there). */
static bool remove_kind_arrays(const char *path)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    bool ok = f >= 0;
    static const char *const groups[] = {"CellData", "PointData"};
    for (int g = 0; ok && g < 2; g++)
        for (uint32_t k = 0; ok && k < MT_DEFECT_KIND_COUNT; k++) {
            char link[96];
            snprintf(link, sizeof link, "/VTKHDF/%s/defect_%s", groups[g],
                     mt_defect_key((mt_defect_kind)k));
            if (H5Lexists(f, link, H5P_DEFAULT) > 0) ok = H5Ldelete(f, link, H5P_DEFAULT) >= 0;
        }
    return f >= 0 && H5Fclose(f) >= 0 && ok;
}

bool al_set_format(const char *path, int64_t version)
{
    if (version < MT_ARCHIVE_FORMAT_VERSION_DEFECT_KINDS && !remove_kind_arrays(path)) return false;
    if (version < MT_ARCHIVE_FORMAT_VERSION_DEFECT_RECORDS && has_records(path)) {
        uint32_t(*rows)[4] = NULL;
        uint64_t count = 0;
        bool ok = read_compact(path, &rows, &count) &&
                  al_write_compact_defects(path, (const uint32_t(*)[4])rows, count);
        free(rows);
        if (!ok) return false;
    }
    return at_set_attr_i64(path, "/meshtopo", "format_version", version);
}
