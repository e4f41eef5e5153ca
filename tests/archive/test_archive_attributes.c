/* Attributes and hidden flags in the archive: a mesh with attributes on
 * every kind of element (values of 1, 4, 8 and 24 bytes) and hidden
 * elements is written and loaded back with every value, in the same order;
 * a file whose half-edge arrays fail loads by a rebuild with its vertex and
 * face values only; a damaged attribute dataset loads the mesh with the
 * other attributes, names the dataset, and fails verification. */
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "archive_test_util.h"
#include "harness.h"
#include "meshtopo/core.h"

typedef struct spec {
    mt_element_kind kind;
    const char *name;
    uint32_t bytes;
} spec;

static const spec specs[] = {
    {MT_ELEMENT_VERTEX, "temperature", 8}, {MT_ELEMENT_VERTEX, "rgb", 3},
    {MT_ELEMENT_EDGE, "crease", 1},        {MT_ELEMENT_HALF_EDGE, "uv", 24},
    {MT_ELEMENT_FACE, "label", 4},
};
#define NUM_SPECS (sizeof specs / sizeof specs[0])

/* A torus with every attribute of specs filled with bytes that depend on
 * the element, two faces and an edge hidden. */
static mt_mesh *attributed_torus(mt_face_list *list)
{
    CHECK_OK(mt_gen_torus(12, 8, list));
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_mesh_build(list, NULL, &mesh, NULL));
    for (size_t s = 0; s < NUM_SPECS; s++) {
        CHECK_OK(mt_attribute_add(mesh, specs[s].kind, specs[s].name, specs[s].bytes, NULL));
        uint8_t *values = NULL;
        uint32_t bytes = 0, count = 0;
        CHECK_OK(
            mt_attribute_values(mesh, specs[s].kind, specs[s].name, &values, &bytes, &count, NULL));
        for (size_t i = 0; i < (size_t)count * bytes; i++) values[i] = (uint8_t)(i * 31 + s);
    }
    CHECK_OK(mt_set_hidden(mesh, MT_ELEMENT_FACE, 3, true, NULL));
    CHECK_OK(mt_set_hidden(mesh, MT_ELEMENT_FACE, 4, true, NULL));
    CHECK_OK(mt_set_hidden(mesh, MT_ELEMENT_EDGE, 5, true, NULL));
    return mesh;
}

/* Whether loaded has attribute s of mesh with the same values. */
static bool same_attribute(const mt_mesh *mesh, const mt_mesh *loaded, mt_element_kind kind,
                           const char *name)
{
    uint8_t *a = NULL, *b = NULL;
    uint32_t ab = 0, ac = 0, bb = 0, bc = 0;
    if (mt_attribute_values((mt_mesh *)mesh, kind, name, &a, &ab, &ac, NULL) != MT_OK ||
        mt_attribute_values((mt_mesh *)loaded, kind, name, &b, &bb, &bc, NULL) != MT_OK)
        return false;
    return ab == bb && ac == bc && memcmp(a, b, (size_t)ab * ac) == 0;
}

static mt_archive *archive_torus(char *dir, size_t size, mt_face_list *list, mt_mesh **out_mesh,
                                 char *path, size_t path_size)
{
    mt_archive *archive = NULL;
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    CHECK(at_tmpdir(dir, size));
    CHECK_OK(mt_archive_open(dir, NULL, &archive, NULL));
    *out_mesh = attributed_torus(list);
    uint64_t hash = 0;
    at_hash(NULL, list, &hash, NULL);
    mt_archive_meta meta = {"t", 1, 7, "test-node", hash};
    mt_diag diag;
    CHECK_OK(mt_archive_write(archive, &meta, list, *out_mesh, NULL, &diag));
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name("t", 1, name, sizeof name);
    snprintf(path, path_size, "%s/%s", dir, name);
    return archive;
}

static void test_archive_attributes_round_trip(void)
{
    char dir[512], path[1024];
    mt_face_list list;
    mt_mesh *mesh = NULL;
    mt_archive *archive = archive_torus(dir, sizeof dir, &list, &mesh, path, sizeof path);
    mt_archive_load_info info;
    mt_mesh *loaded = NULL;
    mt_diag diag;
    CHECK_OK(mt_archive_load_mesh(archive, "t", 1, false, NULL, &loaded, &info, &diag));
    CHECK(loaded && info.restored && info.fault == MT_ARCHIVE_FAULT_NONE);
    for (int k = 0; loaded && k < MT_ELEMENT_KIND_COUNT; k++) {
        const mt_element_kind kind = (mt_element_kind)k;
        CHECK_EQ(mt_attribute_count(loaded, kind), mt_attribute_count(mesh, kind));
        for (size_t i = 0; i < mt_attribute_count(mesh, kind); i++) {
            const char *name = NULL, *loaded_name = NULL;
            mt_attribute_info(mesh, kind, i, &name, NULL);
            CHECK_OK(mt_attribute_info(loaded, kind, i, &loaded_name, NULL));
            CHECK(loaded_name && strcmp(name, loaded_name) == 0); /* same order */
            CHECK(same_attribute(mesh, loaded, kind, name));
        }
    }
    CHECK(mt_is_hidden(loaded, MT_ELEMENT_FACE, 3) && mt_is_hidden(loaded, MT_ELEMENT_FACE, 4));
    CHECK(mt_is_hidden(loaded, MT_ELEMENT_EDGE, 5) && !mt_is_hidden(loaded, MT_ELEMENT_FACE, 5));
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name("t", 1, name, sizeof name);
    CHECK_OK(mt_archive_verify_file(archive, name, at_hash, NULL, &diag));
    mt_mesh_destroy(loaded);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    mt_archive_close(archive);
    at_rmdir(dir);
}

static void test_archive_attributes_after_rebuild(void)
{
    char dir[512], path[1024];
    mt_face_list list;
    mt_mesh *mesh = NULL;
    mt_archive *archive = archive_torus(dir, sizeof dir, &list, &mesh, path, sizeof path);
    /* Stored arrays gone: a rebuild, whose edge ids are its own. */
    CHECK(at_delete(path, "/meshtopo/halfedge"));
    mt_archive_load_info info;
    mt_mesh *loaded = NULL;
    mt_diag diag;
    CHECK_OK(mt_archive_load_mesh(archive, "t", 1, false, NULL, &loaded, &info, &diag));
    CHECK(loaded && !info.restored);
    CHECK(same_attribute(mesh, loaded, MT_ELEMENT_VERTEX, "temperature"));
    CHECK(same_attribute(mesh, loaded, MT_ELEMENT_FACE, "label"));
    CHECK(mt_is_hidden(loaded, MT_ELEMENT_FACE, 3));
    CHECK_EQ(mt_attribute_count(loaded, MT_ELEMENT_EDGE), 0);
    CHECK_EQ(mt_attribute_count(loaded, MT_ELEMENT_HALF_EDGE), 0);
    mt_mesh_destroy(loaded);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    mt_archive_close(archive);
    at_rmdir(dir);
}

/* Replaces dataset `link` of the file with a 1-D int32 dataset of 3 values. */
static bool replace_with_ints(const char *path, const char *link)
{
    if (!at_delete(path, link)) return false;
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (f < 0) return false;
    const hsize_t dims[1] = {3};
    const int32_t values[3] = {1, 2, 3};
    hid_t space = H5Screate_simple(1, dims, NULL);
    hid_t d = H5Dcreate2(f, link, H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    bool ok = d >= 0 && H5Dwrite(d, H5T_NATIVE_INT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, values) >= 0;
    if (d >= 0) H5Dclose(d);
    H5Sclose(space);
    return H5Fclose(f) >= 0 && ok;
}

static void test_archive_attributes_damaged(void)
{
    char dir[512], path[1024];
    mt_face_list list;
    mt_mesh *mesh = NULL;
    mt_archive *archive = archive_torus(dir, sizeof dir, &list, &mesh, path, sizeof path);
    CHECK(replace_with_ints(path, "/meshtopo/attributes/face/label"));
    mt_archive_load_info info;
    mt_mesh *loaded = NULL;
    mt_diag diag;
    CHECK_OK(mt_archive_load_mesh(archive, "t", 1, false, NULL, &loaded, &info, &diag));
    CHECK(loaded && info.fault == MT_ARCHIVE_FAULT_DERIVED);
    CHECK(strstr(info.fallback.message, "attributes/face/label") != NULL);
    CHECK(same_attribute(mesh, loaded, MT_ELEMENT_VERTEX, "temperature"));
    CHECK(same_attribute(mesh, loaded, MT_ELEMENT_HALF_EDGE, "uv"));
    uint32_t label = 0;
    CHECK_STATUS(mt_attribute_get(loaded, MT_ELEMENT_FACE, "label", 0, &label, 4, NULL),
                 MT_ERR_NOT_FOUND);
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive_file_name("t", 1, name, sizeof name);
    mt_status st = mt_archive_verify_file(archive, name, at_hash, NULL, &diag);
    CHECK(st != MT_OK && strstr(diag.message, "attributes/face/label") != NULL);
    mt_mesh_destroy(loaded);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&list);
    mt_archive_close(archive);
    at_rmdir(dir);
}

static const mt_test_case cases[] = {
    {"archive_attributes_round_trip", test_archive_attributes_round_trip},
    {"archive_attributes_after_rebuild", test_archive_attributes_after_rebuild},
    {"archive_attributes_damaged", test_archive_attributes_damaged},
};
const mt_test_table mt_tests_archive_attributes = {cases, sizeof cases / sizeof cases[0]};
