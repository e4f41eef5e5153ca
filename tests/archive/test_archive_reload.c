/* Reloading archived meshes (mt_archive_load_mesh): format 2 files restore
 * the stored half-edge arrays without a rebuild and answer every query like
 * the built mesh (generated, defective and corpus meshes, contiguous and
 * deflated); format 1 files (no arrays) still load by a rebuild; stored
 * arrays damaged in the file are reported naming the file and fall back to
 * the rebuild, and verify names them; the compression option. */
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "archive_legacy.h"
#include "archive_test_util.h"
#include "harness.h"
#include "meshtopo/core.h"
#include "restore_check.h"

static mt_archive *open_fresh(char *dir, size_t size)
{
    mt_archive *archive = NULL;
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    CHECK(at_tmpdir(dir, size));
    CHECK_OK(mt_archive_open(dir, NULL, &archive, NULL));
    return archive;
}

/* Reloads mesh_id v1 and checks it against `built`: restored (or rebuilt
 * when expect_restored is false), same answers, provenance read. */
static void check_reload(mt_archive *archive, const char *mesh_id, const mt_mesh *built,
                         const mt_face_list *list, bool expect_restored)
{
    mt_archive_record rec;
    mt_mesh *loaded = NULL;
    mt_archive_load_info info;
    mt_diag diag;
    mt_status st = mt_archive_load_mesh(archive, mesh_id, 1, true, &rec, &loaded, &info, &diag);
    CHECK_OK(st);
    if (st != MT_OK) {
        printf("reload '%s': %s\n", mesh_id, diag.message);
        return;
    }
    CHECK_EQ(info.restored, expect_restored);
    if (expect_restored) CHECK_EQ(info.fallback.status, MT_OK);
    if (info.restored != expect_restored) printf("fallback: %s\n", info.fallback.message);
    CHECK_OK(mt_mesh_validate(loaded, &diag));
    CHECK(rc_same_answers(built, loaded, mesh_id));
    CHECK(strcmp(rec.mesh_id, mesh_id) == 0);
    CHECK_EQ(rec.version, 1);
    CHECK(at_face_lists_equal(&rec.faces, list));
    mt_mesh_destroy(loaded);
    mt_archive_record_free(&rec);
    /* Without the face list: the record has none, the mesh is the same. */
    st = mt_archive_load_mesh(archive, mesh_id, 1, false, &rec, &loaded, NULL, &diag);
    CHECK_OK(st);
    if (st == MT_OK) {
        if (expect_restored) CHECK_EQ(rec.faces.num_faces, 0);
        CHECK(rc_same_answers(built, loaded, mesh_id));
    }
    mt_mesh_destroy(loaded);
    mt_archive_record_free(&rec);
}

static void archive_and_reload(mt_archive *archive, const char *mesh_id, const mt_face_list *list)
{
    uint64_t hash = 0;
    at_hash(NULL, list, &hash, NULL);
    mt_mesh *built = NULL;
    CHECK_OK(at_archive_list(archive, mesh_id, 1, list, hash, &built));
    if (!built) return;
    check_reload(archive, mesh_id, built, list, true);
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name(mesh_id, 1, name, sizeof name);
    mt_diag diag;
    mt_status st = mt_archive_verify_file(archive, name, at_hash, NULL, &diag);
    CHECK_OK(st);
    if (st != MT_OK) printf("verify: %s\n", diag.message);
    mt_mesh_destroy(built);
}

static void test_reload_restores_generated(void)
{
    char dir[512];
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    mt_face_list list;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &list));
    archive_and_reload(archive, "cube", &list);
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_torus(12, 7, &list));
    archive_and_reload(archive, "torus", &list);
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_bowtie(&list));
    archive_and_reload(archive, "bowtie", &list);
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_fin(&list));
    archive_and_reload(archive, "fin", &list);
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_moebius(7, &list));
    free(list.positions);
    list.positions = NULL;
    archive_and_reload(archive, "moebius without geometry", &list);
    mt_face_list_free(&list);
    mt_face_list empty;
    memset(&empty, 0, sizeof empty);
    archive_and_reload(archive, "empty", &empty);
    mt_archive_close(archive);
    at_rmdir(dir);
}

static void reload_named(const char *name, const mt_face_list *list, void *archive)
{
    archive_and_reload(archive, name, list);
}

static void test_reload_restores_corpus(void)
{
    char dir[512];
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    int meshes = at_for_each_corpus_mesh(reload_named, archive);
    CHECK(meshes >= 20);
    mt_archive_close(archive);
    at_rmdir(dir);
}

/* Rewrites an attribute of /meshtopo as a uint32 scalar. */
static bool set_meshtopo_u32(const char *path, const char *name, uint32_t value)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (f < 0) return false;
    hid_t g = H5Gopen2(f, "meshtopo", H5P_DEFAULT);
    H5Adelete(g, name);
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t attr = H5Acreate2(g, name, H5T_STD_U32LE, space, H5P_DEFAULT, H5P_DEFAULT);
    bool ok = attr >= 0 && H5Awrite(attr, H5T_NATIVE_UINT32, &value) >= 0;
    if (attr >= 0) H5Aclose(attr);
    H5Sclose(space);
    H5Gclose(g);
    return H5Fclose(f) >= 0 && ok;
}

/* Makes a format 3 file a format 1 file: no /meshtopo/halfedge and
 * format_version 1, exactly the layout version 1 wrote. */
static bool make_version1(const char *path)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (f < 0) return false;
    bool ok = H5Ldelete(f, "/meshtopo/halfedge", H5P_DEFAULT) >= 0;
    ok = H5Fclose(f) >= 0 && ok;
    return ok && al_set_format(path, 1);
}

/* Overwrites one uint32 entry of a dataset in place. */
static bool poke_u32(const char *path, const char *dataset, hsize_t index, uint32_t value)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (f < 0) return false;
    hid_t d = H5Dopen2(f, dataset, H5P_DEFAULT);
    hid_t space = d < 0 ? -1 : H5Dget_space(d);
    hsize_t one = 1;
    hid_t mem = H5Screate_simple(1, &one, NULL);
    bool ok = space >= 0 &&
              H5Sselect_hyperslab(space, H5S_SELECT_SET, &index, NULL, &one, NULL) >= 0 &&
              H5Dwrite(d, H5T_NATIVE_UINT32, mem, space, H5P_DEFAULT, &value) >= 0;
    H5Sclose(mem);
    if (space >= 0) H5Sclose(space);
    if (d >= 0) H5Dclose(d);
    return H5Fclose(f) >= 0 && ok;
}

/* Replaces a dataset by a 1-D uint32 one of n zeros. */
static bool replace_u32(const char *path, const char *dataset, hsize_t n)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (f < 0) return false;
    bool ok = H5Ldelete(f, dataset, H5P_DEFAULT) >= 0;
    uint32_t *zeros = calloc(n + 1, sizeof *zeros);
    hid_t space = H5Screate_simple(1, &n, NULL);
    hid_t d = H5Dcreate2(f, dataset, H5T_STD_U32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ok = ok && d >= 0 &&
         (n == 0 || H5Dwrite(d, H5T_NATIVE_UINT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros) >= 0);
    if (d >= 0) H5Dclose(d);
    H5Sclose(space);
    free(zeros);
    return H5Fclose(f) >= 0 && ok;
}

/* An archive with one torus "t" v1; its path in path. */
static mt_archive *torus_archive(char *dir, size_t size, char *path, size_t path_size,
                                 mt_mesh **out_built, mt_face_list *list)
{
    mt_archive *archive = open_fresh(dir, size);
    if (!archive) return NULL;
    CHECK_OK(mt_gen_torus(10, 6, list));
    uint64_t hash = 0;
    at_hash(NULL, list, &hash, NULL);
    CHECK_OK(at_archive_list(archive, "t", 1, list, hash, out_built));
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name("t", 1, name, sizeof name);
    snprintf(path, path_size, "%s/%s", dir, name);
    return archive;
}

static void test_reload_version1(void)
{
    char dir[512], path[1024];
    mt_mesh *built = NULL;
    mt_face_list list;
    mt_archive *archive = torus_archive(dir, sizeof dir, path, sizeof path, &built, &list);
    if (!archive || !built) return;
    CHECK(make_version1(path));
    /* Loads by a rebuild, with no fallback message: the file predates the arrays. */
    check_reload(archive, "t", built, &list, false);
    mt_archive_load_info info;
    mt_mesh *loaded = NULL;
    CHECK_OK(mt_archive_load_mesh(archive, "t", 1, false, NULL, &loaded, &info, NULL));
    CHECK(!info.restored);
    CHECK_EQ(info.fallback.status, MT_OK);
    mt_mesh_destroy(loaded);
    mt_archive_record rec;
    CHECK_OK(mt_archive_load(archive, "t", 1, &rec, NULL));
    CHECK_EQ(rec.format_version, 1);
    mt_archive_record_free(&rec);
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name("t", 1, name, sizeof name);
    CHECK_OK(mt_archive_verify_file(archive, name, at_hash, NULL, NULL));
    /* A version this meshtopo does not know is refused. */
    CHECK(set_meshtopo_u32(path, "format_version", MT_ARCHIVE_FORMAT_VERSION + 1));
    mt_diag diag;
    CHECK_STATUS(mt_archive_load_mesh(archive, "t", 1, false, NULL, &loaded, NULL, &diag),
                 MT_ERR_UNSUPPORTED);
    CHECK(strstr(diag.message, "format_version") != NULL);
    CHECK(loaded == NULL);
    mt_mesh_destroy(built);
    mt_face_list_free(&list);
    mt_archive_close(archive);
    at_rmdir(dir);
}

/* Files of formats 1 and 2 carry the former content hash: verification
 * skips it there and checks it from format 3 on. */
static void test_verify_hash_by_format(void)
{
    char dir[512], path[1024];
    mt_mesh *built = NULL;
    mt_face_list list;
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    CHECK_OK(mt_gen_torus(10, 6, &list));
    uint64_t hash = 0;
    at_hash(NULL, &list, &hash, NULL);
    CHECK_OK(at_archive_list(archive, "old", 1, &list, hash ^ 0x5a5a, &built)); /* another hash */
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name("old", 1, name, sizeof name);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    mt_diag diag;
    CHECK_STATUS(mt_archive_verify_file(archive, name, at_hash, NULL, &diag), MT_ERR_CORRUPT);
    CHECK(strstr(diag.message, "content hash mismatch") != NULL);
    CHECK(al_set_format(path, MT_ARCHIVE_FORMAT_VERSION_HASHED - 1));
    CHECK_OK(mt_archive_verify_file(archive, name, at_hash, NULL, &diag));
    mt_mesh_destroy(built);
    mt_face_list_free(&list);
    mt_archive_close(archive);
    at_rmdir(dir);
}

/* The damaged arrays are reported naming the file and `text`; the load
 * still succeeds by a rebuild; verify fails naming the file. */
static void expect_fallback(mt_archive *archive, const char *path, const mt_mesh *built,
                            const char *text)
{
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name("t", 1, name, sizeof name);
    mt_archive_load_info info;
    mt_mesh *loaded = NULL;
    mt_diag diag;
    CHECK_OK(mt_archive_load_mesh(archive, "t", 1, false, NULL, &loaded, &info, &diag));
    CHECK(!info.restored);
    CHECK(info.fallback.status != MT_OK);
    CHECK(strstr(info.fallback.message, name) != NULL);
    bool named = strstr(info.fallback.message, text) != NULL;
    CHECK(named);
    if (!named || getenv("MT_TEST_VERBOSE"))
        printf("fallback: %s (expected \"%s\")\n", info.fallback.message, text);
    if (loaded) {
        CHECK_OK(mt_mesh_validate(loaded, NULL));
        CHECK(rc_same_answers(built, loaded, path));
    }
    mt_mesh_destroy(loaded);
    mt_status st = mt_archive_verify_file(archive, name, at_hash, NULL, &diag);
    CHECK(st != MT_OK);
    CHECK(strstr(diag.message, name) != NULL);
    if (getenv("MT_TEST_VERBOSE")) printf("verify: %s\n", diag.message);
}

static void test_reload_hostile_arrays(void)
{
    char dir[512], path[1024];
    mt_mesh *built = NULL;
    mt_face_list list;
    mt_archive *archive = torus_archive(dir, sizeof dir, path, sizeof path, &built, &list);
    if (!archive || !built) return;
    char copy[1100];
    snprintf(copy, sizeof copy, "%s.orig", path);
    CHECK(at_copy_file(path, copy, -1));
    mt_mesh_parts parts;
    mt_mesh_get_parts(built, &parts);

    /* A next ring that does not close. */
    CHECK(poke_u32(path, "/meshtopo/halfedge/next", 0, parts.he_next[2]));
    expect_fallback(archive, path, built, "fail validation");
    /* An index out of range. */
    CHECK(at_copy_file(copy, path, -1));
    CHECK(poke_u32(path, "/meshtopo/halfedge/head", 5, parts.num_verts_internal + 9));
    expect_fallback(archive, path, built, "is not a vertex");
    /* A twin mismatch. */
    CHECK(at_copy_file(copy, path, -1));
    CHECK(poke_u32(path, "/meshtopo/halfedge/head", 0, parts.he_head[1]));
    CHECK(poke_u32(path, "/meshtopo/halfedge/head", 1, parts.he_head[0]));
    expect_fallback(archive, path, built, "starts at vertex");
    /* Wrong lengths: a dataset shorter than its count, a count that lies. */
    CHECK(at_copy_file(copy, path, -1));
    CHECK(replace_u32(path, "/meshtopo/halfedge/face", parts.num_half_edges - 2));
    expect_fallback(archive, path, built, "meshtopo/halfedge");
    CHECK(at_copy_file(copy, path, -1));
    CHECK(replace_u32(path, "/meshtopo/halfedge/vertex_halfedge", 3));
    expect_fallback(archive, path, built, "vertex_halfedge");
    /* The whole group missing from a format 2 file. */
    CHECK(at_copy_file(copy, path, -1));
    {
        hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
        CHECK(f >= 0 && H5Ldelete(f, "/meshtopo/halfedge", H5P_DEFAULT) >= 0);
        if (f >= 0) H5Fclose(f);
    }
    expect_fallback(archive, path, built, "halfedge is missing");
    /* Damaged arrays and a damaged face list: the load fails, naming both. */
    CHECK(at_copy_file(copy, path, -1));
    CHECK(poke_u32(path, "/meshtopo/halfedge/next", 0, parts.he_next[2]));
    CHECK(replace_u32(path, "/meshtopo/face_vertex_counts", 1));
    mt_mesh *loaded = NULL;
    mt_diag diag;
    mt_status st = mt_archive_load_mesh(archive, "t", 1, false, NULL, &loaded, NULL, &diag);
    CHECK(st != MT_OK);
    CHECK(loaded == NULL);
    CHECK(strstr(diag.message, "face_vertex_counts") != NULL);
    if (getenv("MT_TEST_VERBOSE")) printf("both damaged: %s\n", diag.message);
    /* The other meshes of the archive still load. */
    mt_face_list cube;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &cube));
    CHECK_OK(at_archive_list(archive, "other", 1, &cube, 0, NULL));
    CHECK_OK(mt_archive_load_mesh(archive, "other", 1, false, NULL, &loaded, NULL, NULL));
    mt_mesh_destroy(loaded);
    mt_face_list_free(&cube);
    unlink(copy);
    mt_mesh_destroy(built);
    mt_face_list_free(&list);
    mt_archive_close(archive);
    at_rmdir(dir);
}

/* Filters of a dataset (0 for contiguous storage). */
static int dataset_filters(const char *path, const char *dataset)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = f < 0 ? -1 : H5Dopen2(f, dataset, H5P_DEFAULT);
    hid_t dcpl = d < 0 ? -1 : H5Dget_create_plist(d);
    int n = dcpl < 0 ? -1 : H5Pget_nfilters(dcpl);
    if (dcpl >= 0) H5Pclose(dcpl);
    if (d >= 0) H5Dclose(d);
    if (f >= 0) H5Fclose(f);
    return n;
}

/* The id of a dataset's first filter (-1 when it has none). */
static int first_filter(const char *path, const char *dataset)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = f < 0 ? -1 : H5Dopen2(f, dataset, H5P_DEFAULT);
    hid_t dcpl = d < 0 ? -1 : H5Dget_create_plist(d);
    unsigned flags, config;
    size_t nvalues = 0;
    int id = dcpl >= 0 && H5Pget_nfilters(dcpl) > 0
                 ? (int)H5Pget_filter2(dcpl, 0, &flags, &nvalues, NULL, 0, NULL, &config)
                 : -1;
    if (dcpl >= 0) H5Pclose(dcpl);
    if (d >= 0) H5Dclose(d);
    if (f >= 0) H5Fclose(f);
    return id;
}

static void test_compression_option(void)
{
    char dir[512];
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    mt_face_list list;
    CHECK_OK(mt_gen_torus(60, 40, &list));
    mt_mesh *built = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(&list, NULL, &built, &diag));
    if (!built) return;
    CHECK_OK(mt_mesh_validate(built, &diag));
    mt_archive_meta meta = {"plain", 1, 7, "test-node", 0};
    mt_archive_write_stats plain, packed;
    CHECK_OK(mt_archive_write_with(archive, &meta, &list, built, NULL, &plain, &diag));
    mt_archive_write_options options = {.compression = MT_ARCHIVE_COMPRESSION_DEFLATE};
    meta.mesh_id = "packed";
    CHECK_OK(mt_archive_write_with(archive, &meta, &list, built, &options, &packed, &diag));
    CHECK(packed.file_bytes < plain.file_bytes);
    char path[1024], name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name("packed", 1, name, sizeof name);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    CHECK_EQ(dataset_filters(path, "/meshtopo/halfedge/head"), 2); /* shuffle + deflate */
    CHECK_EQ(dataset_filters(path, "/VTKHDF/Connectivity"), 2);
    CHECK_EQ(dataset_filters(path, "/VTKHDF/NumberOfPoints"), 0); /* small: contiguous */
    mt_archive_file_name("plain", 1, name, sizeof name);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    CHECK_EQ(dataset_filters(path, "/meshtopo/halfedge/head"), 0);
    check_reload(archive, "packed", built, &list, true);
    check_reload(archive, "plain", built, &list, true);
    mt_archive_file_name("packed", 1, name, sizeof name);
    CHECK_OK(mt_archive_verify_file(archive, name, NULL, NULL, &diag));
    /* LZ4 (Blosc): one filter, the plugin's id; smaller than deflate's
     * input, reloads and verifies the same. */
    mt_archive_write_stats lz4;
    options.compression = MT_ARCHIVE_COMPRESSION_LZ4;
    meta.mesh_id = "lz4";
    CHECK_OK(mt_archive_write_with(archive, &meta, &list, built, &options, &lz4, &diag));
    CHECK(lz4.file_bytes < plain.file_bytes / 2);
    mt_archive_file_name("lz4", 1, name, sizeof name);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    CHECK_EQ(dataset_filters(path, "/meshtopo/halfedge/head"), 1);
    CHECK_EQ(first_filter(path, "/meshtopo/halfedge/head"), 32001);
    CHECK_EQ(first_filter(path, "/VTKHDF/Points"), 32001);
    CHECK_EQ(dataset_filters(path, "/VTKHDF/NumberOfPoints"), 0);
    check_reload(archive, "lz4", built, &list, true);
    CHECK_OK(mt_archive_verify_file(archive, name, NULL, NULL, &diag));
    /* Bad options are refused before anything is written. */
    options.compression = (mt_archive_compression)7;
    meta.mesh_id = "bad";
    CHECK_STATUS(mt_archive_write_with(archive, &meta, &list, built, &options, NULL, &diag),
                 MT_ERR_INVALID_ARG);
    options.compression = MT_ARCHIVE_COMPRESSION_DEFLATE;
    options.deflate_level = 10;
    CHECK_STATUS(mt_archive_write_with(archive, &meta, &list, built, &options, NULL, &diag),
                 MT_ERR_INVALID_ARG);
    CHECK(!mt_archive_contains(archive, "bad", 1));
    mt_mesh_destroy(built);
    mt_face_list_free(&list);
    mt_archive_close(archive);
    at_rmdir(dir);
}

/* MT_ARCHIVE_COMPRESSION_LZ4 needs HDF5's Blosc plugin: found where the
 * test dependencies are installed, and a clear refusal where it is not
 * (ctest's second run of this case points HDF5_PLUGIN_PATH at an empty
 * directory and sets MESHTOPO_TEST_NO_BLOSC). */
static void test_compression_lz4_plugin(void)
{
    const bool absent = getenv("MESHTOPO_TEST_NO_BLOSC") != NULL;
    CHECK_EQ(mt_archive_lz4_available(), !absent);
    if (!absent) return;
    char dir[512];
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    mt_face_list list;
    CHECK_OK(mt_gen_torus(6, 4, &list));
    mt_mesh *built = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(&list, NULL, &built, &diag));
    mt_archive_meta meta = {"lz4", 1, 7, "test-node", 0};
    mt_archive_write_options options = {.compression = MT_ARCHIVE_COMPRESSION_LZ4};
    CHECK_STATUS(mt_archive_write_with(archive, &meta, &list, built, &options, NULL, &diag),
                 MT_ERR_UNSUPPORTED);
    CHECK(strstr(diag.message, "hdf5-filter-plugin-blosc-serial") != NULL);
    CHECK(!mt_archive_contains(archive, "lz4", 1));
    mt_mesh_destroy(built);
    mt_face_list_free(&list);
    mt_archive_close(archive);
    at_rmdir(dir);
}

static const mt_test_case cases[] = {
    {"reload_restores_generated", test_reload_restores_generated},
    {"reload_restores_corpus", test_reload_restores_corpus},
    {"reload_version1", test_reload_version1},
    {"verify_hash_by_format", test_verify_hash_by_format},
    {"reload_hostile_arrays", test_reload_hostile_arrays},
    {"compression_option", test_compression_option},
    {"compression_lz4_plugin", test_compression_lz4_plugin},
};
const mt_test_table mt_tests_archive_reload = {cases, sizeof cases / sizeof cases[0]};
