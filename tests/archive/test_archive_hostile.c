/* Hostile archive files: truncated, not HDF5, wrong dataset shapes and
 * types, counts that disagree, indices out of range, a huge claimed size,
 * a mesh id attribute with "../", a defect of unknown kind. Each is made
 * from a good file with the HDF5 C API; load, verify and list must report
 * it with its file name and the object at fault, never crash, and the
 * other meshes of the archive must still load. */
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "archive_test_util.h"
#include "harness.h"
#include "meshtopo/core.h"

typedef struct hostile {
    char dir[512];
    mt_archive *archive;
} hostile;

/* An archive holding "good" v1 and `id` v1 (a cube), plus the path of the
 * latter for the test to damage. */
static bool hostile_setup(hostile *h, const char *id, char *path, size_t size)
{
    memset(h, 0, sizeof *h);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    if (!at_tmpdir(h->dir, sizeof h->dir)) return false;
    CHECK_OK(mt_archive_open(h->dir, NULL, &h->archive, NULL));
    if (!h->archive) return false;
    mt_face_list list;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &list));
    uint64_t hash = 0;
    at_hash(NULL, &list, &hash, NULL);
    CHECK_OK(at_archive_list(h->archive, "good", 1, &list, hash, NULL));
    CHECK_OK(at_archive_list(h->archive, id, 1, &list, hash, NULL));
    mt_face_list_free(&list);
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name(id, 1, name, sizeof name);
    snprintf(path, size, "%s/%s", h->dir, name);
    return true;
}

/* The damaged file must fail to load and verify with `status` (0 = any
 * failure) and a message naming the file and `object`; the listing still
 * works and "good" still loads. */
static void expect_reported(hostile *h, const char *id, mt_status status, const char *object)
{
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name(id, 1, name, sizeof name);
    mt_archive_record rec;
    mt_diag diag;
    mt_status st = mt_archive_load(h->archive, id, 1, &rec, &diag);
    mt_status vst = mt_archive_verify_file(h->archive, name, at_hash, NULL, &diag);
    CHECK(st != MT_OK || vst != MT_OK);
    if (status != MT_OK) CHECK_STATUS(vst, status);
    CHECK(strstr(diag.message, name) != NULL);
    CHECK(strstr(diag.message, object) != NULL);
    if (getenv("MT_TEST_VERBOSE") || !strstr(diag.message, object) || !strstr(diag.message, name))
        printf("message: %s (expected %s)\n", diag.message, object);
    if (st == MT_OK) mt_archive_record_free(&rec);
    mt_archive_listing l;
    CHECK_OK(mt_archive_list(h->archive, &l, NULL));
    CHECK_EQ(l.count, 2);
    mt_archive_listing_free(&l);
    CHECK_OK(mt_archive_load(h->archive, "good", 1, &rec, NULL));
    CHECK_EQ(rec.faces.num_faces, 6);
    mt_archive_record_free(&rec);
    CHECK_OK(mt_archive_verify_file(h->archive, "good.v1.hdf", at_hash, NULL, NULL));
}

static void hostile_done(hostile *h)
{
    mt_archive_close(h->archive);
    at_rmdir(h->dir);
}

/* Replaces dataset `name` of the file with one of the given type and shape
 * holding `data` (NULL: nothing written). */
static void replace_dataset(const char *path, const char *name, hid_t type, int rank,
                            const hsize_t *dims, const void *data)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    CHECK(f >= 0);
    CHECK(H5Ldelete(f, name, H5P_DEFAULT) >= 0);
    hid_t space = H5Screate_simple(rank, dims, NULL);
    hid_t d = H5Dcreate2(f, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    CHECK(d >= 0);
    if (data) CHECK(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0);
    H5Dclose(d);
    H5Sclose(space);
    H5Fclose(f);
}

/* Rewrites one element of an int32/int64 dataset. */
static void poke_i64(const char *path, const char *name, hsize_t index, int64_t value)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    hid_t space = H5Dget_space(d);
    hsize_t one = 1;
    hid_t mspace = H5Screate_simple(1, &one, NULL);
    CHECK(H5Sselect_elements(space, H5S_SELECT_SET, 1, &index) >= 0);
    CHECK(H5Dwrite(d, H5T_NATIVE_INT64, mspace, space, H5P_DEFAULT, &value) >= 0);
    H5Sclose(mspace);
    H5Sclose(space);
    H5Dclose(d);
    H5Fclose(f);
}

static void set_attr_string(const char *path, const char *obj, const char *name, const char *value)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t g = H5Oopen(f, obj, H5P_DEFAULT);
    H5Adelete(g, name);
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, strlen(value));
    hid_t s = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(g, name, t, s, H5P_DEFAULT, H5P_DEFAULT);
    CHECK(a >= 0 && H5Awrite(a, t, value) >= 0);
    H5Aclose(a);
    H5Sclose(s);
    H5Tclose(t);
    H5Oclose(g);
    H5Fclose(f);
}

static void set_attr_i64(const char *path, const char *obj, const char *name, int64_t value)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t g = H5Oopen(f, obj, H5P_DEFAULT);
    H5Adelete(g, name);
    hid_t s = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(g, name, H5T_STD_I64LE, s, H5P_DEFAULT, H5P_DEFAULT);
    CHECK(a >= 0 && H5Awrite(a, H5T_NATIVE_INT64, &value) >= 0);
    H5Aclose(a);
    H5Sclose(s);
    H5Oclose(g);
    H5Fclose(f);
}

static void test_truncated(void)
{
    hostile h;
    char path[1024], copy[1100];
    if (!hostile_setup(&h, "cut", path, sizeof path)) return;
    snprintf(copy, sizeof copy, "%s.orig", path);
    CHECK(at_copy_file(path, copy, -1));
    CHECK(at_copy_file(copy, path, 3000)); /* the first 3000 bytes only */
    unlink(copy);
    expect_reported(&h, "cut", MT_ERR_IO, "not a readable HDF5 file");
    hostile_done(&h);
}

static void test_not_hdf5(void)
{
    hostile h;
    char path[1024];
    if (!hostile_setup(&h, "text", path, sizeof path)) return;
    const char *text = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    CHECK(at_write_bytes(path, text, strlen(text)));
    expect_reported(&h, "text", MT_ERR_IO, "not a readable HDF5 file");
    CHECK(at_write_bytes(path, "", 0)); /* empty */
    expect_reported(&h, "text", MT_ERR_IO, "not a readable HDF5 file");
    hostile_done(&h);
}

static void test_wrong_shape(void)
{
    hostile h;
    char path[1024];
    if (!hostile_setup(&h, "shape", path, sizeof path)) return;
    double pos[8][2] = {{0}};
    hsize_t dims[2] = {8, 2};
    replace_dataset(path, "/meshtopo/positions", H5T_NATIVE_DOUBLE, 2, dims, pos);
    expect_reported(&h, "shape", MT_ERR_PARSE, "positions");
    hostile_done(&h);
}

static void test_wrong_type(void)
{
    hostile h;
    char path[1024];
    if (!hostile_setup(&h, "type", path, sizeof path)) return;
    double counts[6] = {4, 4, 4, 4, 4, 4};
    hsize_t dims[1] = {6};
    replace_dataset(path, "/meshtopo/face_vertex_counts", H5T_NATIVE_DOUBLE, 1, dims, counts);
    expect_reported(&h, "type", MT_ERR_PARSE, "face_vertex_counts");
    hostile_done(&h);
    /* int64 instead of int32: refused too (a conversion would clip). */
    if (!hostile_setup(&h, "type", path, sizeof path)) return;
    int64_t wide[24] = {0};
    hsize_t n[1] = {24};
    replace_dataset(path, "/meshtopo/face_vertex_indices", H5T_NATIVE_INT64, 1, n, wide);
    expect_reported(&h, "type", MT_ERR_PARSE, "face_vertex_indices");
    hostile_done(&h);
}

static void test_counts_disagree(void)
{
    hostile h;
    char path[1024];
    if (!hostile_setup(&h, "sum", path, sizeof path)) return;
    poke_i64(path, "/meshtopo/face_vertex_counts", 0, 5); /* sizes add up to 25, not 24 */
    expect_reported(&h, "sum", MT_ERR_PARSE, "face_vertex_counts");
    hostile_done(&h);
    if (!hostile_setup(&h, "neg", path, sizeof path)) return;
    poke_i64(path, "/meshtopo/face_vertex_counts", 2, -4);
    expect_reported(&h, "neg", MT_ERR_PARSE, "face_vertex_counts[2] is negative");
    hostile_done(&h);
    if (!hostile_setup(&h, "attr", path, sizeof path)) return;
    set_attr_i64(path, "/meshtopo", "num_faces", 7);
    expect_reported(&h, "attr", MT_ERR_PARSE, "num_faces");
    hostile_done(&h);
    if (!hostile_setup(&h, "verts", path, sizeof path)) return;
    set_attr_i64(path, "/meshtopo", "num_verts", 9); /* positions has 8 rows */
    expect_reported(&h, "verts", MT_ERR_PARSE, "positions");
    hostile_done(&h);
    if (!hostile_setup(&h, "loops", path, sizeof path)) return;
    set_attr_i64(path, "/meshtopo/report", "boundary_loops", 3);
    expect_reported(&h, "loops", MT_ERR_PARSE, "boundary_loop_lengths");
    hostile_done(&h);
    if (!hostile_setup(&h, "cells", path, sizeof path)) return;
    poke_i64(path, "/VTKHDF/NumberOfCells", 0, 1000000);
    expect_reported(&h, "cells", MT_ERR_PARSE, "NumberOfCells");
    hostile_done(&h);
}

static void test_index_out_of_range(void)
{
    hostile h;
    char path[1024];
    /* A VTKHDF connectivity entry a viewer would read out of bounds. */
    if (!hostile_setup(&h, "conn", path, sizeof path)) return;
    poke_i64(path, "/VTKHDF/Connectivity", 5, 1000000000);
    expect_reported(&h, "conn", MT_ERR_PARSE, "Connectivity[5]");
    hostile_done(&h);
    if (!hostile_setup(&h, "offs", path, sizeof path)) return;
    poke_i64(path, "/VTKHDF/Offsets", 3, -7);
    expect_reported(&h, "offs", MT_ERR_PARSE, "Offsets[3]");
    hostile_done(&h);
    /* An out-of-range face index in /meshtopo is data (stored as
     * submitted): the face list no longer has its content hash. Without a
     * hash to check, the stored arrays (intact, matching their digest) are
     * what a load serves, and verification finds the VTKHDF cells no longer
     * those of the face list. */
    if (!hostile_setup(&h, "idx", path, sizeof path)) return;
    poke_i64(path, "/meshtopo/face_vertex_indices", 0, 99);
    expect_reported(&h, "idx", MT_ERR_CORRUPT, "content hash mismatch");
    {
        mt_diag diag;
        mt_archive_fault fault = MT_ARCHIVE_FAULT_NONE;
        CHECK_STATUS(
            mt_archive_verify_file_with(h.archive, "idx.v1.hdf", NULL, NULL, &fault, &diag),
            MT_ERR_PARSE);
        CHECK(strstr(diag.message, "Connectivity") != NULL);
        CHECK_EQ(fault, MT_ARCHIVE_FAULT_VTK);
        if (getenv("MT_TEST_VERBOSE")) printf("without a hash: %s\n", diag.message);
    }
    hostile_done(&h);
    /* Defects stored as plain integers, not records (test_archive_defects.c
     * has records no defect gives). */
    if (!hostile_setup(&h, "kind", path, sizeof path)) return;
    hsize_t one[1] = {1};
    uint32_t row[4] = {77, 0, 0, 0};
    replace_dataset(path, "/meshtopo/report/defects", H5T_NATIVE_UINT32, 1, one, row);
    expect_reported(&h, "kind", MT_ERR_PARSE, "defects");
    hostile_done(&h);
}

static void test_huge_claimed_size(void)
{
    hostile h;
    char path[1024];
    if (!hostile_setup(&h, "huge", path, sizeof path)) return;
    /* A chunked dataset of 2^30 entries with no chunk written: HDF5 would
     * hand back fill values, 4 GiB of them. */
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    CHECK(H5Ldelete(f, "/meshtopo/face_vertex_indices", H5P_DEFAULT) >= 0);
    hsize_t dims[1] = {(hsize_t)1 << 30}, chunk[1] = {1024};
    hid_t space = H5Screate_simple(1, dims, NULL);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 1, chunk);
    hid_t d = H5Dcreate2(f, "/meshtopo/face_vertex_indices", H5T_STD_I32LE, space, H5P_DEFAULT,
                         dcpl, H5P_DEFAULT);
    CHECK(d >= 0);
    H5Dclose(d);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Fclose(f);
    expect_reported(&h, "huge", MT_ERR_TOO_LARGE, "face_vertex_indices");
    hostile_done(&h);
    /* Past the element limit outright. */
    if (!hostile_setup(&h, "huge", path, sizeof path)) return;
    f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    CHECK(H5Ldelete(f, "/meshtopo/positions", H5P_DEFAULT) >= 0);
    hsize_t pdims[2] = {(hsize_t)1 << 40, 3}, pchunk[2] = {1024, 3};
    space = H5Screate_simple(2, pdims, NULL);
    dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 2, pchunk);
    d = H5Dcreate2(f, "/meshtopo/positions", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    CHECK(d >= 0);
    H5Dclose(d);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Fclose(f);
    expect_reported(&h, "huge", MT_ERR_TOO_LARGE, "positions");
    hostile_done(&h);
}

static void test_mesh_id_attribute(void)
{
    hostile h;
    char path[1024];
    if (!hostile_setup(&h, "evil", path, sizeof path)) return;
    set_attr_string(path, "/meshtopo", "mesh_id", "../evil");
    expect_reported(&h, "evil", MT_ERR_PARSE, "mesh_id");
    hostile_done(&h);
    /* A valid id that is not the file's: the name would not match. */
    if (!hostile_setup(&h, "evil", path, sizeof path)) return;
    set_attr_string(path, "/meshtopo", "mesh_id", "good");
    expect_reported(&h, "evil", MT_ERR_PARSE, "good.v1.hdf");
    hostile_done(&h);
    if (!hostile_setup(&h, "evil", path, sizeof path)) return;
    set_attr_i64(path, "/meshtopo", "version", 0);
    expect_reported(&h, "evil", MT_ERR_PARSE, "version");
    hostile_done(&h);
    if (!hostile_setup(&h, "evil", path, sizeof path)) return;
    set_attr_i64(path, "/meshtopo", "format_version", 99);
    expect_reported(&h, "evil", MT_ERR_UNSUPPORTED, "format_version");
    hostile_done(&h);
}

static const mt_test_case cases[] = {
    {"hostile_truncated", test_truncated},
    {"hostile_not_hdf5", test_not_hdf5},
    {"hostile_wrong_shape", test_wrong_shape},
    {"hostile_wrong_type", test_wrong_type},
    {"hostile_counts_disagree", test_counts_disagree},
    {"hostile_index_out_of_range", test_index_out_of_range},
    {"hostile_huge_claimed_size", test_huge_claimed_size},
    {"hostile_mesh_id_attribute", test_mesh_id_attribute},
};
const mt_test_table mt_tests_archive_hostile = {cases, sizeof cases / sizeof cases[0]};
