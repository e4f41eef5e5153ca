/* The defects of an archived report (/meshtopo/report/defects): format 7
 * writes defect records (meshtopo/defect_record.h) with members named like
 * their fields and a description attribute, and reads them back into the
 * report; files of earlier formats, which store {kind, a, b, c}, still load
 * and verify; records no defect gives, and a layout that does not match the
 * file's format, are refused naming the dataset. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "archive_legacy.h"
#include "archive_test_util.h"
#include "harness.h"
#include "meshtopo/core.h"

/* A face list with a defect of every kind: faces 0 (0 1 2), 1 (1 0 3) and
 * 2 (0 1 4) share edge 0-1 (non-manifold; faces 0 and 2 cross it the same
 * way), face 3 (0 5 6) is a second fan at vertex 0 (a bowtie), face 4
 * (3 4) is degenerate, face 5 (0 17 1) is out of range, face 6 repeats
 * face 0; vertices 7 to 10 are isolated and vertex 7 is at NaN. */
static void every_kind(mt_face_list *list)
{
    static const uint32_t sizes[] = {3, 3, 3, 3, 2, 3, 3};
    static const uint32_t idx[] = {0, 1, 2, 1, 0, 3, 0, 1, 4, 0, 5, 6, 3, 4, 0, 17, 1, 0, 1, 2};
    CHECK_OK(mt_face_list_alloc(list, 11, 7, sizeof idx / sizeof idx[0], NULL));
    memcpy(list->face_sizes, sizes, sizeof sizes);
    memcpy(list->face_indices, idx, sizeof idx);
    for (int i = 0; i < 33; i++) list->positions[i] = (double)((i * 5) % 7);
    list->positions[3 * 7] = NAN;
}

typedef struct archived {
    char dir[512];
    char path[1024];
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    mt_archive *archive;
    mt_face_list list;
    mt_mesh *built;
} archived;

static bool archive_every_kind(archived *a)
{
    memset(a, 0, sizeof *a);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    CHECK(at_tmpdir(a->dir, sizeof a->dir));
    CHECK_OK(mt_archive_open(a->dir, NULL, &a->archive, NULL));
    if (!a->archive) return false;
    every_kind(&a->list);
    uint64_t hash = 0;
    at_hash(NULL, &a->list, &hash, NULL);
    CHECK_OK(at_archive_list(a->archive, "kinds", 1, &a->list, hash, &a->built));
    mt_archive_file_name("kinds", 1, a->name, sizeof a->name);
    snprintf(a->path, sizeof a->path, "%s/%s", a->dir, a->name);
    return a->built != NULL;
}

static void archived_done(archived *a)
{
    mt_mesh_destroy(a->built);
    mt_face_list_free(&a->list);
    mt_archive_close(a->archive);
    at_rmdir(a->dir);
}

/* Loads and verifies the file; the loaded report's defects are the build's. */
static void expect_loads(archived *a, const char *what)
{
    mt_archive_record rec;
    mt_diag diag;
    mt_status st = mt_archive_load(a->archive, "kinds", 1, &rec, &diag);
    CHECK_OK(st);
    if (st != MT_OK) {
        printf("%s: load: %s\n", what, diag.message);
        return;
    }
    const mt_report *built = mt_mesh_report(a->built);
    CHECK_EQ(rec.report.num_defects, built->num_defects);
    if (rec.report.num_defects == built->num_defects)
        CHECK(memcmp(rec.report.defects, built->defects,
                     built->num_defects * sizeof *built->defects) == 0);
    mt_archive_record_free(&rec);
    mt_mesh *loaded = NULL;
    CHECK_OK(mt_archive_load_mesh(a->archive, "kinds", 1, false, NULL, &loaded, NULL, &diag));
    mt_mesh_destroy(loaded);
    st = mt_archive_verify_file(a->archive, a->name, at_hash, NULL, &diag);
    CHECK_OK(st);
    if (st != MT_OK) printf("%s: verify: %s\n", what, diag.message);
}

/* Load and verify refuse the file with MT_ERR_PARSE, naming the dataset
 * and `detail`. */
static void expect_refused(archived *a, const char *detail)
{
    mt_archive_record rec;
    mt_diag diag;
    CHECK_STATUS(mt_archive_load(a->archive, "kinds", 1, &rec, &diag), MT_ERR_PARSE);
    CHECK(strstr(diag.message, "report/defects") != NULL && strstr(diag.message, detail) != NULL);
    if (!strstr(diag.message, detail)) printf("message: %s (expected %s)\n", diag.message, detail);
    CHECK_STATUS(mt_archive_verify_file(a->archive, a->name, at_hash, NULL, &diag), MT_ERR_PARSE);
    CHECK(strstr(diag.message, detail) != NULL);
}

/* Reads the file's defects as records (malloc'ed), their count in *out_n. */
static mt_defect_record *read_records(const char *path, size_t *out_n, char **out_description)
{
    *out_n = 0;
    *out_description = NULL;
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = f < 0 ? -1 : H5Dopen2(f, "/meshtopo/report/defects", H5P_DEFAULT);
    hid_t space = d < 0 ? -1 : H5Dget_space(d);
    hsize_t n = 0;
    mt_defect_record *rows = NULL;
    if (space >= 0 && H5Sget_simple_extent_dims(space, &n, NULL) == 1) {
        hid_t t = al_record_type();
        rows = calloc(n + 1, sizeof *rows);
        if (rows && H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows) >= 0) *out_n = n;
        H5Tclose(t);
    }
    hid_t attr = d < 0 ? -1 : H5Aopen(d, "description", H5P_DEFAULT);
    hid_t atype = attr < 0 ? -1 : H5Aget_type(attr);
    if (atype >= 0) {
        size_t len = H5Tget_size(atype);
        char *text = calloc(len + 1, 1);
        if (text && H5Aread(attr, atype, text) >= 0)
            *out_description = text;
        else
            free(text);
        H5Tclose(atype);
    }
    if (attr >= 0) H5Aclose(attr);
    if (space >= 0) H5Sclose(space);
    if (d >= 0) H5Dclose(d);
    if (f >= 0) H5Fclose(f);
    return rows;
}

static void test_defects_written_as_records(void)
{
    archived a;
    if (!archive_every_kind(&a)) {
        archived_done(&a);
        return;
    }
    const mt_report *r = mt_mesh_report(a.built);
    bool seen[MT_DEFECT_KIND_COUNT] = {false};
    for (size_t i = 0; i < r->num_defects; i++)
        if (r->defects[i].kind < MT_DEFECT_KIND_COUNT) seen[r->defects[i].kind] = true;
    for (int k = 0; k < MT_DEFECT_KIND_COUNT; k++) CHECK(seen[k]);
    size_t n = 0;
    char *description = NULL;
    mt_defect_record *rows = read_records(a.path, &n, &description);
    CHECK_EQ(n, r->num_defects);
    for (size_t i = 0; rows && i < n && i < r->num_defects; i++) {
        const mt_defect_record want = mt_defect_to_record(&r->defects[i]);
        CHECK(memcmp(&rows[i], &want, sizeof want) == 0);
    }
    CHECK(description != NULL);
    static const char *const members[] = {"kind: ",
                                          "vertices: ",
                                          "faces: ",
                                          "edge: ",
                                          "face_count: ",
                                          "index: ",
                                          "position: ",
                                          "face_size: ",
                                          "distinct_vertices: ",
                                          "fans: ",
                                          "on_nonmanifold_edge: ",
                                          "axis: "};
    for (size_t m = 0; description && m < sizeof members / sizeof members[0]; m++)
        CHECK(strstr(description, members[m]) != NULL);
    CHECK(description && strstr(description, "4294967295") != NULL);
    /* The members in the order of the record's fields. */
    hid_t f = H5Fopen(a.path, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = H5Dopen2(f, "/meshtopo/report/defects", H5P_DEFAULT);
    hid_t t = H5Dget_type(d);
    CHECK_EQ(H5Tget_nmembers(t), 12);
    for (int m = 0; m < 12 && m < H5Tget_nmembers(t); m++) {
        char *name = H5Tget_member_name(t, (unsigned)m);
        CHECK(name && strncmp(members[m], name, strlen(name)) == 0 &&
              members[m][strlen(name)] == ':');
        H5free_memory(name);
    }
    H5Tclose(t);
    H5Dclose(d);
    H5Fclose(f);
    free(rows);
    free(description);
    expect_loads(&a, "format 7");
    archived_done(&a);
}

static void test_defects_of_earlier_formats_load(void)
{
    archived a;
    if (!archive_every_kind(&a)) {
        archived_done(&a);
        return;
    }
    /* Format 6: the same file with {kind, a, b, c} rows. */
    CHECK(al_set_format(a.path, 6));
    expect_loads(&a, "format 6");
    /* Format 1: no half-edge arrays either; a rebuild. */
    CHECK(at_delete(a.path, "/meshtopo/halfedge"));
    CHECK(al_set_format(a.path, 1));
    expect_loads(&a, "format 1");
    archived_done(&a);
}

static void test_defects_hostile(void)
{
    archived a;
    if (!archive_every_kind(&a)) {
        archived_done(&a);
        return;
    }
    char copy[1100];
    snprintf(copy, sizeof copy, "%s.copy", a.path);
    CHECK(at_copy_file(a.path, copy, -1));
    const mt_report *r = mt_mesh_report(a.built);
    mt_defect_record *rows = calloc(r->num_defects + 1, sizeof *rows);
    if (!rows) {
        archived_done(&a);
        return;
    }
    mt_defect_to_records(r->defects, r->num_defects, rows);
    /* A kind that does not exist (a value the enum does not name). */
    mt_defect_record bad = rows[0];
    bad.kind = 77;
    CHECK(al_write_records(a.path, &bad, 1));
    CHECK(at_set_attr_u64(a.path, "/meshtopo/report", "num_defects", 1));
    expect_refused(&a, "defects");
    /* An isolated vertex with fans: a record no defect gives. */
    CHECK(at_copy_file(copy, a.path, -1));
    size_t last = r->num_defects - 1;
    CHECK_EQ(rows[last].kind, MT_DEFECT_NONFINITE_COORD);
    rows[last].fans = 2;
    CHECK(al_write_records(a.path, rows, r->num_defects));
    expect_refused(&a, "row");
    /* Format 7 with the rows of earlier formats: members missing. */
    CHECK(at_copy_file(copy, a.path, -1));
    CHECK(al_set_format(a.path, 6));
    CHECK(at_set_attr_i64(a.path, "/meshtopo", "format_version", 7));
    expect_refused(&a, "has no member");
    /* Format 6 with a kind that does not exist. */
    CHECK(at_copy_file(copy, a.path, -1));
    const uint32_t compact[1][4] = {{MT_DEFECT_KIND_COUNT + 3, 0, 0, 0}};
    CHECK(al_set_format(a.path, 6));
    CHECK(al_write_compact_defects(a.path, compact, 1));
    CHECK(at_set_attr_u64(a.path, "/meshtopo/report", "num_defects", 1));
    expect_refused(&a, "defects");
    free(rows);
    unlink(copy);
    archived_done(&a);
}

static const mt_test_case cases[] = {
    {"defects_written_as_records", test_defects_written_as_records},
    {"defects_of_earlier_formats_load", test_defects_of_earlier_formats_load},
    {"defects_hostile", test_defects_hostile},
};

const mt_test_table mt_tests_archive_defects = {cases, sizeof cases / sizeof cases[0]};
