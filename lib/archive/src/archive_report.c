/* The topology report (meshtopo/report.h) in an archive file: counts and
 * flags as attributes of /meshtopo/report named like mt_report's fields,
 * the lists as datasets of named compound rows (h5dump and h5py show the
 * column names; defect kinds are an HDF5 enum of their keys; defects are
 * defect records, meshtopo/defect_record.h, from format 7 on). Also the
 * field-by-field comparison used to check a rebuild against the file, and
 * the hash of the stored values that the half-edge digest includes. */
#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "archive_internal.h"
#include "meshtopo/defect_record.h"

#define FIELD(name, type)                      \
    {                                          \
#name, offsetof(mt_report, name), type \
    }

const mt__report_field mt__report_fields[] = {
    FIELD(num_verts, MT__FIELD_U32),
    FIELD(num_faces, MT__FIELD_U32),
    FIELD(num_faces_valid, MT__FIELD_U32),
    FIELD(num_edges, MT__FIELD_U64),
    FIELD(num_half_edges, MT__FIELD_U64),
    FIELD(boundary_edges, MT__FIELD_U64),
    FIELD(boundary_loops, MT__FIELD_U32),
    FIELD(boundary_loops_ambiguous, MT__FIELD_BOOL),
    FIELD(nonmanifold_edges, MT__FIELD_U64),
    FIELD(inconsistent_orientation_edges, MT__FIELD_U64),
    FIELD(duplicate_directed_edges, MT__FIELD_U64),
    FIELD(nonmanifold_vertices, MT__FIELD_U32),
    FIELD(bowtie_vertices, MT__FIELD_U32),
    FIELD(isolated_vertices, MT__FIELD_U32),
    FIELD(unreferenced_vertices, MT__FIELD_U32),
    FIELD(degenerate_faces, MT__FIELD_U32),
    FIELD(duplicate_faces, MT__FIELD_U32),
    FIELD(out_of_range_indices, MT__FIELD_U64),
    FIELD(faces_with_out_of_range_indices, MT__FIELD_U32),
    FIELD(nonfinite_vertices, MT__FIELD_U32),
    FIELD(connected_components, MT__FIELD_U32),
    FIELD(vertex_connected_components, MT__FIELD_U32),
    FIELD(euler_characteristic, MT__FIELD_I64),
    FIELD(closed, MT__FIELD_BOOL),
    FIELD(manifold, MT__FIELD_BOOL),
    FIELD(orientable, MT__FIELD_BOOL),
    FIELD(consistently_oriented, MT__FIELD_BOOL),
    FIELD(genus, MT__FIELD_I32),
};
const size_t mt__num_report_fields = sizeof mt__report_fields / sizeof mt__report_fields[0];

/* A component as stored: flags as uint8 so a hostile file cannot put a
 * value other than 0 or 1 into a C bool. */
typedef struct component_row {
    uint32_t min_face, faces, vertices;
    uint64_t edges;
    int64_t euler_characteristic;
    uint64_t boundary_edges;
    uint32_t boundary_loops;
    uint8_t closed, manifold, orientable;
    int32_t genus, genus_with_boundary;
} component_row;

static hid_t component_type(void)
{
    hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(component_row));
    if (t < 0) return -1;
#define MEMBER(name, type) H5Tinsert(t, #name, offsetof(component_row, name), type)
    if (MEMBER(min_face, H5T_NATIVE_UINT32) < 0 || MEMBER(faces, H5T_NATIVE_UINT32) < 0 ||
        MEMBER(vertices, H5T_NATIVE_UINT32) < 0 || MEMBER(edges, H5T_NATIVE_UINT64) < 0 ||
        MEMBER(euler_characteristic, H5T_NATIVE_INT64) < 0 ||
        MEMBER(boundary_edges, H5T_NATIVE_UINT64) < 0 ||
        MEMBER(boundary_loops, H5T_NATIVE_UINT32) < 0 || MEMBER(closed, H5T_NATIVE_UINT8) < 0 ||
        MEMBER(manifold, H5T_NATIVE_UINT8) < 0 || MEMBER(orientable, H5T_NATIVE_UINT8) < 0 ||
        MEMBER(genus, H5T_NATIVE_INT32) < 0 || MEMBER(genus_with_boundary, H5T_NATIVE_INT32) < 0) {
        H5Tclose(t);
        return -1;
    }
#undef MEMBER
    return t;
}

/* A histogram bin {key_name: uint32, count_name: uint64}. */
static hid_t histogram_type(const char *key_name, const char *count_name)
{
    hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(mt_histogram_bin));
    if (t < 0) return -1;
    if (H5Tinsert(t, key_name, offsetof(mt_histogram_bin, key), H5T_NATIVE_UINT32) < 0 ||
        H5Tinsert(t, count_name, offsetof(mt_histogram_bin, count), H5T_NATIVE_UINT64) < 0) {
        H5Tclose(t);
        return -1;
    }
    return t;
}

/* The HDF5 enum of the defect kinds' keys, over uint32. */
static hid_t defect_kind_type(void)
{
    hid_t kind = H5Tenum_create(H5T_NATIVE_UINT32);
    bool ok = kind >= 0;
    for (uint32_t k = 0; ok && k < MT_DEFECT_KIND_COUNT; k++)
        ok = H5Tenum_insert(kind, mt_defect_key((mt_defect_kind)k), &k) >= 0;
    if (!ok && kind >= 0) H5Tclose(kind);
    return ok ? kind : -1;
}

/* A defect record (meshtopo/defect_record.h), members named like its
 * fields: kind the enum of the keys, vertices, faces and edge two uint32
 * each, index int64, the others uint32. Format 7 and later. */
static hid_t defect_record_type(void)
{
    const hsize_t two[1] = {2};
    hid_t kind = defect_kind_type();
    hid_t pair = H5Tarray_create2(H5T_NATIVE_UINT32, 1, two);
    hid_t t = kind < 0 || pair < 0 ? -1 : H5Tcreate(H5T_COMPOUND, sizeof(mt_defect_record));
#define MEMBER(name, type) (H5Tinsert(t, #name, offsetof(mt_defect_record, name), type) >= 0)
    bool ok = t >= 0 && MEMBER(kind, kind) && MEMBER(vertices, pair) && MEMBER(faces, pair) &&
              MEMBER(edge, pair) && MEMBER(face_count, H5T_NATIVE_UINT32) &&
              MEMBER(index, H5T_NATIVE_INT64) && MEMBER(position, H5T_NATIVE_UINT32) &&
              MEMBER(face_size, H5T_NATIVE_UINT32) &&
              MEMBER(distinct_vertices, H5T_NATIVE_UINT32) && MEMBER(fans, H5T_NATIVE_UINT32) &&
              MEMBER(on_nonmanifold_edge, H5T_NATIVE_UINT32) && MEMBER(axis, H5T_NATIVE_UINT32);
#undef MEMBER
    if (kind >= 0) H5Tclose(kind);
    if (pair >= 0) H5Tclose(pair);
    if (!ok && t >= 0) H5Tclose(t);
    return ok ? t : -1;
}

/* A defect as formats 1 to 6 stored it: mt_defect {kind: the enum of the
 * keys, a, b, c: uint32}. */
static hid_t legacy_defect_type(void)
{
    hid_t kind = defect_kind_type();
    hid_t t = kind < 0 ? -1 : H5Tcreate(H5T_COMPOUND, sizeof(mt_defect));
    bool ok = t >= 0 && H5Tinsert(t, "kind", offsetof(mt_defect, kind), kind) >= 0 &&
              H5Tinsert(t, "a", offsetof(mt_defect, a), H5T_NATIVE_UINT32) >= 0 &&
              H5Tinsert(t, "b", offsetof(mt_defect, b), H5T_NATIVE_UINT32) >= 0 &&
              H5Tinsert(t, "c", offsetof(mt_defect, c), H5T_NATIVE_UINT32) >= 0;
    if (kind >= 0) H5Tclose(kind);
    if (!ok && t >= 0) H5Tclose(t);
    return ok ? t : -1;
}

/* The description attribute of /meshtopo/report/defects: the record's
 * members, from the one table of them. */
static const char defects_description[] =
    "One row per defect of the report, grouped by kind, then by first id; the members are "
    "those of every meshtopo defect record (README.md, Defect records). A member that does not "
    "apply to the row's kind holds 4294967295, as does the unused end of vertices and faces. "
#define MT__FIELD_TEXT(name, text) #name ": " text ". "
    MT_DEFECT_RECORD_FIELDS(MT__FIELD_TEXT)
#undef MT__FIELD_TEXT
    ;

static hid_t field_file_type(mt__field_type type)
{
    switch (type) {
        case MT__FIELD_U32:
            return H5T_STD_U32LE;
        case MT__FIELD_U64:
            return H5T_STD_U64LE;
        case MT__FIELD_I32:
            return H5T_STD_I32LE;
        case MT__FIELD_I64:
            return H5T_STD_I64LE;
        case MT__FIELD_BOOL:
            return H5T_STD_U8LE;
    }
    return -1;
}

static hid_t field_mem_type(mt__field_type type)
{
    switch (type) {
        case MT__FIELD_U32:
            return H5T_NATIVE_UINT32;
        case MT__FIELD_U64:
            return H5T_NATIVE_UINT64;
        case MT__FIELD_I32:
            return H5T_NATIVE_INT32;
        case MT__FIELD_I64:
            return H5T_NATIVE_INT64;
        case MT__FIELD_BOOL:
            return H5T_NATIVE_UINT8;
    }
    return -1;
}

/* Writes one compound dataset of n rows made by `type` (closed here). */
static mt_status write_rows(hid_t group, const char *name, hid_t type, const void *rows, uint64_t n,
                            const char *file, mt_diag *diag)
{
    if (type < 0)
        return mt__archive_fail(diag, MT_ERR_IO, "%s: cannot make the type of dataset %s", file,
                                name);
    hsize_t dims[1] = {n};
    mt_status st = mt__h5_write_dataset(group, name, type, type, 1, dims, rows, file, diag);
    H5Tclose(type);
    return st;
}

/* Writes /meshtopo/report/defects: the report's defects as records. */
static mt_status write_defects(hid_t group, const mt_report *r, const char *file, mt_diag *diag)
{
    mt_defect_record *rows = calloc(r->num_defects + 1u, sizeof *rows);
    if (!rows) return mt__archive_fail(diag, MT_ERR_NOMEM, "%s: out of memory", file);
    mt_defect_to_records(r->defects, r->num_defects, rows);
    mt_status st =
        write_rows(group, "defects", defect_record_type(), rows, r->num_defects, file, diag);
    free(rows);
    hid_t dset = st == MT_OK ? H5Dopen2(group, "defects", H5P_DEFAULT) : -1;
    if (st == MT_OK && dset < 0)
        st = mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot open dataset report/defects", file);
    if (st == MT_OK)
        st = mt__h5_write_attr_string(dset, "description", defects_description, file, diag);
    if (dset >= 0) H5Dclose(dset);
    return st;
}

mt_status mt__report_write(hid_t group, const mt_report *r, const char *file, mt_diag *diag)
{
    mt_status st = MT_OK;
    for (size_t i = 0; st == MT_OK && i < mt__num_report_fields; i++) {
        const mt__report_field *f = &mt__report_fields[i];
        const char *p = (const char *)r + f->offset;
        uint8_t flag;
        if (f->type == MT__FIELD_BOOL) {
            flag = *(const bool *)(const void *)p ? 1 : 0;
            p = (const char *)&flag;
        }
        /* The memory type converts to the little-endian file type. */
        hid_t mtype = field_mem_type(f->type);
        hid_t space = H5Screate(H5S_SCALAR);
        hid_t attr = space < 0 ? -1
                               : H5Acreate2(group, f->name, field_file_type(f->type), space,
                                            H5P_DEFAULT, H5P_DEFAULT);
        if (attr < 0 || H5Awrite(attr, mtype, p) < 0)
            st = mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot write attribute report/%s", file,
                             f->name);
        if (attr >= 0) H5Aclose(attr);
        if (space >= 0) H5Sclose(space);
    }
    uint64_t num_defects = r->num_defects;
    if (st == MT_OK)
        st = mt__h5_write_attr_int(group, "num_defects", H5T_NATIVE_UINT64, &num_defects, file,
                                   diag);
    if (st == MT_OK) {
        hsize_t dims[1] = {r->boundary_loops};
        st = mt__h5_write_dataset(group, "boundary_loop_lengths", H5T_STD_U32LE, H5T_NATIVE_UINT32,
                                  1, dims, r->boundary_loop_lengths, file, diag);
    }
    if (st == MT_OK) {
        component_row *rows = calloc(r->connected_components + 1u, sizeof *rows);
        if (!rows) return mt__archive_fail(diag, MT_ERR_NOMEM, "%s: out of memory", file);
        for (uint32_t i = 0; i < r->connected_components; i++) {
            const mt_component_info *c = &r->components[i];
            rows[i] = (component_row){c->min_face,
                                      c->faces,
                                      c->vertices,
                                      c->edges,
                                      c->euler_characteristic,
                                      c->boundary_edges,
                                      c->boundary_loops,
                                      c->closed,
                                      c->manifold,
                                      c->orientable,
                                      c->genus,
                                      c->genus_with_boundary};
        }
        st = write_rows(group, "components", component_type(), rows, r->connected_components, file,
                        diag);
        free(rows);
    }
    if (st == MT_OK)
        st = write_rows(group, "face_size_histogram", histogram_type("face_size", "faces"),
                        r->face_size_histogram, r->num_face_size_bins, file, diag);
    if (st == MT_OK)
        st = write_rows(group, "edge_use_histogram", histogram_type("faces_per_edge", "edges"),
                        r->edge_use_histogram, r->num_edge_use_bins, file, diag);
    if (st == MT_OK) st = write_defects(group, r, file, diag);
    return st;
}

mt_status mt__report_read_scalars(hid_t group, const char *file, mt_report *out,
                                  uint64_t *out_num_defects, mt_diag *diag)
{
    memset(out, 0, sizeof *out);
    for (size_t i = 0; i < mt__num_report_fields; i++) {
        const mt__report_field *f = &mt__report_fields[i];
        char *p = (char *)out + f->offset;
        int64_t v = 0;
        uint64_t u = 0;
        mt_status st;
        bool ok;
        if (f->type == MT__FIELD_U64) {
            st = mt__h5_read_attr_u64(group, f->name, file, &u, diag);
            ok = true;
        } else {
            st = mt__h5_read_attr_i64(group, f->name, file, &v, diag);
            ok = f->type == MT__FIELD_U32    ? v >= 0 && v <= UINT32_MAX
                 : f->type == MT__FIELD_I32  ? v >= INT32_MIN && v <= INT32_MAX
                 : f->type == MT__FIELD_BOOL ? v == 0 || v == 1
                                             : true;
        }
        if (st != MT_OK) return st;
        if (!ok)
            return mt__archive_fail(diag, MT_ERR_PARSE,
                                    "%s: attribute report/%s is out of range (%" PRId64 ")", file,
                                    f->name, v);
        switch (f->type) {
            case MT__FIELD_U32:
                *(uint32_t *)(void *)p = (uint32_t)v;
                break;
            case MT__FIELD_U64:
                *(uint64_t *)(void *)p = u;
                break;
            case MT__FIELD_I32:
                *(int32_t *)(void *)p = (int32_t)v;
                break;
            case MT__FIELD_I64:
                *(int64_t *)(void *)p = v;
                break;
            case MT__FIELD_BOOL:
                *(bool *)(void *)p = v == 1;
                break;
        }
    }
    return mt__h5_read_attr_u64(group, "num_defects", file, out_num_defects, diag);
}

/* Reads compound dataset `name` made by `type` (closed here) and checks its
 * length against the count the attributes give. */
static mt_status read_rows(hid_t group, const char *name, hid_t type, uint64_t expected,
                           const char *file, void **out, mt_diag *diag)
{
    if (type < 0)
        return mt__archive_fail(diag, MT_ERR_NOMEM, "%s: cannot make the type of dataset %s", file,
                                name);
    uint64_t rows = 0;
    mt_status st =
        mt__h5_read_dataset(group, name, file, 1, 0, MT__H5_COMPOUND, 0, type, out, &rows, diag);
    H5Tclose(type);
    if (st == MT_OK && rows != expected) {
        free(*out);
        *out = NULL;
        st = mt__archive_fail(diag, MT_ERR_PARSE,
                              "%s: dataset %s has %llu rows, the attributes say %llu", file, name,
                              (unsigned long long)rows, (unsigned long long)expected);
    }
    return st;
}

/* Reads /meshtopo/report/defects into r (num_defects rows): records from
 * format 7 on, each converted back to the mt_defect it stands for, and the
 * rows {kind, a, b, c} of earlier formats. */
static mt_status read_defects(hid_t group, uint32_t format_version, uint64_t num_defects,
                              const char *file, mt_report *r, mt_diag *diag)
{
    const char *name = "/meshtopo/report/defects";
    void *data = NULL;
    if (format_version < MT_ARCHIVE_FORMAT_VERSION_DEFECT_RECORDS) {
        mt_status st = read_rows(group, name, legacy_defect_type(), num_defects, file, &data, diag);
        if (st != MT_OK) return st;
        r->defects = data;
        r->num_defects = (size_t)num_defects;
        for (size_t i = 0; i < r->num_defects; i++)
            if (r->defects[i].kind >= MT_DEFECT_KIND_COUNT)
                return mt__archive_fail(diag, MT_ERR_PARSE,
                                        "%s: dataset %s row %zu has unknown kind %u", file, name, i,
                                        r->defects[i].kind);
        return MT_OK;
    }
    mt_status st = read_rows(group, name, defect_record_type(), num_defects, file, &data, diag);
    if (st != MT_OK) return st;
    const mt_defect_record *rows = data;
    r->defects = calloc((size_t)num_defects + 1u, sizeof *r->defects);
    if (!r->defects) st = mt__archive_fail(diag, MT_ERR_NOMEM, "%s: out of memory", file);
    if (st == MT_OK) r->num_defects = (size_t)num_defects;
    for (size_t i = 0; st == MT_OK && i < r->num_defects; i++)
        if (mt_defect_from_record(&rows[i], &r->defects[i]) != MT_OK)
            st = mt__archive_fail(diag, MT_ERR_PARSE,
                                  "%s: dataset %s row %zu is no defect record (kind %u with "
                                  "members it does not have, or an unknown kind)",
                                  file, name, i, rows[i].kind);
    free(data);
    return st;
}

mt_status mt__report_read(hid_t group, uint32_t format_version, const char *file, mt_report *out,
                          mt_diag *diag)
{
    mt_report r;
    uint64_t num_defects = 0;
    mt_status st = mt__report_read_scalars(group, file, &r, &num_defects, diag);
    if (st != MT_OK) {
        memset(out, 0, sizeof *out);
        return st;
    }
    void *data = NULL;
    uint64_t rows = 0;
    st = mt__h5_read_dataset(group, "/meshtopo/report/boundary_loop_lengths", file, 1, 0,
                             MT__H5_UINT, 4, H5T_NATIVE_UINT32, &data, &rows, diag);
    if (st == MT_OK && rows != r.boundary_loops)
        st = mt__archive_fail(
            diag, MT_ERR_PARSE,
            "%s: dataset /meshtopo/report/boundary_loop_lengths has %llu entries but "
            "boundary_loops is %u",
            file, (unsigned long long)rows, r.boundary_loops);
    r.boundary_loop_lengths = data;
    component_row *comp = NULL;
    if (st == MT_OK)
        st = read_rows(group, "/meshtopo/report/components", component_type(),
                       r.connected_components, file, (void **)&comp, diag);
    if (st == MT_OK && r.connected_components > 0) {
        r.components = calloc(r.connected_components, sizeof *r.components);
        if (!r.components) st = mt__archive_fail(diag, MT_ERR_NOMEM, "%s: out of memory", file);
        for (uint32_t i = 0; st == MT_OK && i < r.connected_components; i++) {
            const component_row *c = &comp[i];
            if (c->closed > 1 || c->manifold > 1 || c->orientable > 1) {
                st = mt__archive_fail(
                    diag, MT_ERR_PARSE,
                    "%s: dataset /meshtopo/report/components row %u has a flag other "
                    "than 0 or 1",
                    file, i);
                break;
            }
            r.components[i] = (mt_component_info){c->min_face,
                                                  c->faces,
                                                  c->vertices,
                                                  c->edges,
                                                  c->euler_characteristic,
                                                  c->boundary_edges,
                                                  c->boundary_loops,
                                                  c->closed == 1,
                                                  c->manifold == 1,
                                                  c->orientable == 1,
                                                  c->genus,
                                                  c->genus_with_boundary};
        }
    }
    free(comp);
    /* Histogram lengths are not attributes: any length the row limit allows. */
    uint64_t bins = 0;
    hid_t type = histogram_type("face_size", "faces");
    if (st == MT_OK)
        st = type < 0 ? mt__archive_fail(diag, MT_ERR_NOMEM, "%s: out of memory", file)
                      : mt__h5_read_dataset(group, "/meshtopo/report/face_size_histogram", file, 1,
                                            0, MT__H5_COMPOUND, 0, type, &data, &bins, diag);
    if (type >= 0) H5Tclose(type);
    if (st == MT_OK) {
        r.face_size_histogram = data;
        r.num_face_size_bins = (size_t)bins;
    }
    type = histogram_type("faces_per_edge", "edges");
    if (st == MT_OK)
        st = type < 0 ? mt__archive_fail(diag, MT_ERR_NOMEM, "%s: out of memory", file)
                      : mt__h5_read_dataset(group, "/meshtopo/report/edge_use_histogram", file, 1,
                                            0, MT__H5_COMPOUND, 0, type, &data, &bins, diag);
    if (type >= 0) H5Tclose(type);
    if (st == MT_OK) {
        r.edge_use_histogram = data;
        r.num_edge_use_bins = (size_t)bins;
    }
    if (st == MT_OK) st = read_defects(group, format_version, num_defects, file, &r, diag);
    *out = r;
    if (st != MT_OK) mt_archive_report_free(out);
    return st;
}

/* Appends v as 8 little-endian bytes. */
static uint8_t *put_u64(uint8_t *at, uint64_t v)
{
    for (int i = 0; i < 8; i++) at[i] = (uint8_t)(v >> (8 * i));
    return at + 8;
}

mt_status mt__report_hash(const mt_report *r, uint64_t *out, mt_diag *diag)
{
    /* Every value stored, 8 bytes each: the fields, then each list's length
     * and rows. */
    const size_t words = mt__num_report_fields + 1 + r->boundary_loops + 1 +
                         12 * (size_t)r->connected_components + 1 + 2 * r->num_face_size_bins + 1 +
                         2 * r->num_edge_use_bins + 1 + 4 * r->num_defects;
    uint8_t *bytes = words <= SIZE_MAX / 8 ? malloc(8 * words) : NULL;
    if (!bytes) return mt__archive_fail(diag, MT_ERR_NOMEM, "out of memory hashing a report");
    uint8_t *at = bytes;
    for (size_t i = 0; i < mt__num_report_fields; i++) {
        const mt__report_field *f = &mt__report_fields[i];
        const char *p = (const char *)r + f->offset;
        uint64_t v = 0;
        switch (f->type) {
            case MT__FIELD_U32:
                v = *(const uint32_t *)(const void *)p;
                break;
            case MT__FIELD_U64:
                v = *(const uint64_t *)(const void *)p;
                break;
            case MT__FIELD_I32:
                v = (uint64_t)(int64_t) * (const int32_t *)(const void *)p;
                break;
            case MT__FIELD_I64:
                v = (uint64_t) * (const int64_t *)(const void *)p;
                break;
            case MT__FIELD_BOOL:
                v = *(const bool *)(const void *)p ? 1 : 0;
                break;
        }
        at = put_u64(at, v);
    }
    at = put_u64(at, r->boundary_loops);
    for (uint32_t i = 0; i < r->boundary_loops; i++) at = put_u64(at, r->boundary_loop_lengths[i]);
    at = put_u64(at, r->connected_components);
    for (uint32_t i = 0; i < r->connected_components; i++) {
        const mt_component_info *c = &r->components[i];
        const uint64_t row[12] = {c->min_face,
                                  c->faces,
                                  c->vertices,
                                  c->edges,
                                  (uint64_t)c->euler_characteristic,
                                  c->boundary_edges,
                                  c->boundary_loops,
                                  c->closed,
                                  c->manifold,
                                  c->orientable,
                                  (uint64_t)(int64_t)c->genus,
                                  (uint64_t)(int64_t)c->genus_with_boundary};
        for (int k = 0; k < 12; k++) at = put_u64(at, row[k]);
    }
    at = put_u64(at, r->num_face_size_bins);
    for (size_t i = 0; i < r->num_face_size_bins; i++) {
        at = put_u64(at, r->face_size_histogram[i].key);
        at = put_u64(at, r->face_size_histogram[i].count);
    }
    at = put_u64(at, r->num_edge_use_bins);
    for (size_t i = 0; i < r->num_edge_use_bins; i++) {
        at = put_u64(at, r->edge_use_histogram[i].key);
        at = put_u64(at, r->edge_use_histogram[i].count);
    }
    at = put_u64(at, r->num_defects);
    for (size_t i = 0; i < r->num_defects; i++) {
        const mt_defect *d = &r->defects[i];
        at = put_u64(at, d->kind);
        at = put_u64(at, d->a);
        at = put_u64(at, d->b);
        at = put_u64(at, d->c);
    }
    *out = mt_content_hash_bytes(bytes, (size_t)(at - bytes));
    free(bytes);
    return MT_OK;
}

void mt_archive_report_free(mt_report *report)
{
    if (!report) return;
    free(report->boundary_loop_lengths);
    free(report->components);
    free(report->face_size_histogram);
    free(report->edge_use_histogram);
    free(report->defects);
    memset(report, 0, sizeof *report);
}

static bool differ(char *buf, size_t size, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static bool differ(char *buf, size_t size, const char *fmt, ...)
{
    if (buf && size > 0) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(buf, size, fmt, ap);
        va_end(ap);
    }
    return false;
}

bool mt_archive_report_equal(const mt_report *a, const mt_report *b, char *buf, size_t size)
{
    if (buf && size > 0) buf[0] = '\0';
    for (size_t i = 0; i < mt__num_report_fields; i++) {
        const mt__report_field *f = &mt__report_fields[i];
        const char *pa = (const char *)a + f->offset, *pb = (const char *)b + f->offset;
        long long va = 0, vb = 0;
        unsigned long long ua = 0, ub = 0;
        switch (f->type) {
            case MT__FIELD_U32:
                ua = *(const uint32_t *)(const void *)pa;
                ub = *(const uint32_t *)(const void *)pb;
                break;
            case MT__FIELD_U64:
                ua = *(const uint64_t *)(const void *)pa;
                ub = *(const uint64_t *)(const void *)pb;
                break;
            case MT__FIELD_I32:
                va = *(const int32_t *)(const void *)pa;
                vb = *(const int32_t *)(const void *)pb;
                break;
            case MT__FIELD_I64:
                va = *(const int64_t *)(const void *)pa;
                vb = *(const int64_t *)(const void *)pb;
                break;
            case MT__FIELD_BOOL:
                ua = *(const bool *)(const void *)pa;
                ub = *(const bool *)(const void *)pb;
                break;
        }
        if (va != vb) return differ(buf, size, "%s: %lld != %lld", f->name, va, vb);
        if (ua != ub) return differ(buf, size, "%s: %llu != %llu", f->name, ua, ub);
    }
    for (uint32_t i = 0; i < a->boundary_loops; i++)
        if (a->boundary_loop_lengths[i] != b->boundary_loop_lengths[i])
            return differ(buf, size, "boundary_loop_lengths[%u]: %u != %u", i,
                          a->boundary_loop_lengths[i], b->boundary_loop_lengths[i]);
    for (uint32_t i = 0; i < a->connected_components; i++) {
        const mt_component_info *x = &a->components[i], *y = &b->components[i];
        if (x->min_face != y->min_face || x->faces != y->faces || x->vertices != y->vertices ||
            x->edges != y->edges || x->euler_characteristic != y->euler_characteristic ||
            x->boundary_edges != y->boundary_edges || x->boundary_loops != y->boundary_loops ||
            x->closed != y->closed || x->manifold != y->manifold ||
            x->orientable != y->orientable || x->genus != y->genus ||
            x->genus_with_boundary != y->genus_with_boundary)
            return differ(buf, size, "components[%u] differ", i);
    }
    if (a->num_face_size_bins != b->num_face_size_bins)
        return differ(buf, size, "face_size_histogram: %zu != %zu bins", a->num_face_size_bins,
                      b->num_face_size_bins);
    for (size_t i = 0; i < a->num_face_size_bins; i++)
        if (a->face_size_histogram[i].key != b->face_size_histogram[i].key ||
            a->face_size_histogram[i].count != b->face_size_histogram[i].count)
            return differ(buf, size, "face_size_histogram[%zu] differs", i);
    if (a->num_edge_use_bins != b->num_edge_use_bins)
        return differ(buf, size, "edge_use_histogram: %zu != %zu bins", a->num_edge_use_bins,
                      b->num_edge_use_bins);
    for (size_t i = 0; i < a->num_edge_use_bins; i++)
        if (a->edge_use_histogram[i].key != b->edge_use_histogram[i].key ||
            a->edge_use_histogram[i].count != b->edge_use_histogram[i].count)
            return differ(buf, size, "edge_use_histogram[%zu] differs", i);
    if (a->num_defects != b->num_defects)
        return differ(buf, size, "defects: %zu != %zu", a->num_defects, b->num_defects);
    for (size_t i = 0; i < a->num_defects; i++) {
        const mt_defect *x = &a->defects[i], *y = &b->defects[i];
        if (x->kind != y->kind || x->a != y->a || x->b != y->b || x->c != y->c)
            return differ(buf, size, "defects[%zu]: %s %u %u %u != %s %u %u %u", i,
                          mt_defect_key((mt_defect_kind)x->kind), x->a, x->b, x->c,
                          mt_defect_key((mt_defect_kind)y->kind), y->a, y->b, y->c);
    }
    return true;
}
