/* meshtopo::archive: round trips of generated and corpus meshes (defective
 * ones too) with every field compared, mesh id escaping, versions, listing,
 * removal, and the crash-safety rules (leftover temporaries removed at
 * open, an existing version never overwritten). */
#include <dirent.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "archive_test_util.h"
#include "harness.h"
#include "meshtopo/core.h"
#include "meshtopo/io.h"

/* Loads mesh_id/version back and compares everything with what was written. */
static void check_round_trip(mt_archive *archive, const char *mesh_id, uint32_t version,
                             const mt_face_list *list, const mt_mesh *mesh, uint64_t hash)
{
    mt_archive_record rec;
    mt_diag diag;
    mt_status st = mt_archive_load(archive, mesh_id, version, &rec, &diag);
    CHECK_OK(st);
    if (st != MT_OK) {
        printf("load '%s' v%u: %s\n", mesh_id, version, diag.message);
        return;
    }
    CHECK(strcmp(rec.mesh_id, mesh_id) == 0);
    CHECK_EQ(rec.version, version);
    CHECK_EQ(rec.utime, 1700000000000000 + version);
    CHECK(strcmp(rec.source, "test-node") == 0);
    CHECK(rec.content_hash == hash);
    CHECK_EQ(rec.format_version, MT_ARCHIVE_FORMAT_VERSION);
    CHECK(at_face_lists_equal(&rec.faces, list));
    char why[256];
    bool same = mt_archive_report_equal(&rec.report, mt_mesh_report(mesh), why, sizeof why);
    CHECK(same);
    if (!same) printf("report differs: %s\n", why);
    mt_mesh *rebuilt = NULL;
    CHECK_OK(mt_archive_record_build(&rec, &rebuilt, &diag));
    CHECK(rebuilt != NULL);
    if (rebuilt) CHECK_OK(mt_mesh_validate(rebuilt, &diag));
    mt_mesh_destroy(rebuilt);
    uint64_t test_hash = 0;
    at_hash(NULL, list, &test_hash, NULL);
    st = mt_archive_verify_file(archive, rec.file_name, at_hash, NULL, &diag);
    if (test_hash == hash) {
        CHECK_OK(st);
        if (st != MT_OK) printf("verify: %s\n", diag.message);
    } else {
        /* Archived with another hash: verify names the mismatch and the file. */
        CHECK_STATUS(st, MT_ERR_CORRUPT);
        CHECK(strstr(diag.message, "content hash mismatch") != NULL);
        CHECK(strstr(diag.message, rec.file_name) != NULL);
        CHECK_OK(mt_archive_verify_file(archive, rec.file_name, NULL, NULL, &diag));
    }
    mt_archive_record_free(&rec);
}

/* Archives list as mesh_id v1 with the test hash and checks the round trip. */
static void round_trip(mt_archive *archive, const char *mesh_id, const mt_face_list *list)
{
    uint64_t hash = 0;
    at_hash(NULL, list, &hash, NULL);
    mt_mesh *mesh = NULL;
    CHECK_OK(at_archive_list(archive, mesh_id, 1, list, hash, &mesh));
    if (mesh) check_round_trip(archive, mesh_id, 1, list, mesh, hash);
    mt_mesh_destroy(mesh);
}

static mt_archive *open_fresh(char *dir, size_t size)
{
    mt_archive *archive = NULL;
    mt_diag diag;
    CHECK(at_tmpdir(dir, size));
    CHECK_OK(mt_archive_open(dir, NULL, &archive, &diag));
    return archive;
}

/* A face list with every defect the builder rejects or reports: an index
 * -1 (stored as 0xffffffff), one past the end, a face of 2 entries, a face
 * repeating a vertex, an empty face, a duplicate face and an isolated vertex. */
static void make_defective(mt_face_list *list)
{
    static const uint32_t sizes[] = {3, 3, 3, 2, 4, 0, 3, 3};
    static const uint32_t idx[] = {0, 1, 2, 0, 2, 3, 1, 0xffffffffu, 2, 0, 1,
                                   0, 1, 1, 2, 2, 1, 4, 0,           1, 2};
    CHECK_OK(mt_face_list_alloc(list, 7, 8, sizeof idx / sizeof idx[0], NULL));
    memcpy(list->face_sizes, sizes, sizeof sizes);
    memcpy(list->face_indices, idx, sizeof idx);
    list->face_indices[17] = 9; /* face 6 uses vertex 9 of 7: out of range */
    for (uint32_t i = 0; i < 3 * 7; i++) list->positions[i] = (double)i * 0.5 - 1.0;
}

static void test_round_trip_generated(void)
{
    char dir[512];
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    mt_face_list list;
    const char *names[] = {"tetrahedron", "cube", "dodecahedron"};
    mt_platonic kinds[] = {MT_TETRAHEDRON, MT_CUBE, MT_DODECAHEDRON};
    for (int i = 0; i < 3; i++) {
        CHECK_OK(mt_gen_platonic(kinds[i], &list));
        round_trip(archive, names[i], &list);
        mt_face_list_free(&list);
    }
    CHECK_OK(mt_gen_grid(7, 5, true, &list));
    round_trip(archive, "grid", &list);
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_torus(8, 6, &list));
    round_trip(archive, "torus", &list);
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_moebius(9, &list));
    round_trip(archive, "moebius", &list);
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_bowtie(&list));
    round_trip(archive, "bowtie", &list);
    mt_face_list_free(&list);
    CHECK_OK(mt_gen_fin(&list));
    round_trip(archive, "fin", &list);
    mt_face_list_free(&list);
    make_defective(&list);
    round_trip(archive, "defective", &list);
    /* Without geometry: positions stay NULL after the round trip. */
    free(list.positions);
    list.positions = NULL;
    round_trip(archive, "no geometry", &list);
    mt_face_list_free(&list);
    /* An empty mesh. */
    mt_face_list empty;
    memset(&empty, 0, sizeof empty);
    round_trip(archive, "empty", &empty);
    mt_archive_close(archive);
    at_rmdir(dir);
}

/* The corpus file name as mesh id: its '.' is escaped. */
static void round_trip_named(const char *name, const mt_face_list *list, void *archive)
{
    round_trip(archive, name, list);
}

static void test_round_trip_corpus(void)
{
    char dir[512];
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    int meshes = at_for_each_corpus_mesh(round_trip_named, archive);
    CHECK(meshes >= 20);
    mt_archive_listing listing;
    CHECK_OK(mt_archive_list(archive, &listing, NULL));
    CHECK_EQ(listing.count, meshes);
    for (size_t i = 0; i < listing.count; i++) CHECK_OK(listing.entries[i].status);
    mt_archive_listing_free(&listing);
    mt_archive_close(archive);
    at_rmdir(dir);
}

static void test_id_escaping(void)
{
    char dir[512];
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    /* "../x" itself is not a valid id ('/' and ".."); escaping is checked on valid ones. */
    CHECK_EQ(mt_archive_file_name("../x", 3, name, sizeof name), 0);
    mt_archive_file_name(".", 1, name, sizeof name);
    CHECK(strcmp(name, "%2E.v1.hdf") == 0);
    mt_archive_file_name("a b", 2, name, sizeof name);
    CHECK(strcmp(name, "a%20b.v2.hdf") == 0);
    mt_archive_file_name("%", 1, name, sizeof name);
    CHECK(strcmp(name, "%25.v1.hdf") == 0);
    CHECK_EQ(mt_archive_file_name("a/b", 1, name, sizeof name), 0);
    CHECK_EQ(mt_archive_file_name("a", 0, name, sizeof name), 0);
    CHECK_EQ(mt_archive_file_name("..", 1, name, sizeof name), 0);
    CHECK_EQ(mt_archive_file_name("a\nb", 1, name, sizeof name), 0);
    CHECK_EQ(mt_archive_file_name("", 1, name, sizeof name), 0);

    char long_a[256], long_b[256], long_pct[256];
    memset(long_a, 'x', 255);
    long_a[255] = '\0';
    memcpy(long_b, long_a, 256);
    long_b[254] = 'y';
    memset(long_pct, '%', 255);
    long_pct[255] = '\0';
    const char *ids[] = {"a b",   "%",  ".",    "x.y",  "~",      ". .",
                         "a%2Eb", "-_", long_a, long_b, long_pct, "x%2Ey"};
    size_t num_ids = sizeof ids / sizeof ids[0];
    mt_face_list list;
    CHECK_OK(mt_gen_platonic(MT_OCTAHEDRON, &list));
    for (size_t i = 0; i < num_ids; i++) {
        size_t len = mt_archive_file_name(ids[i], 1, name, sizeof name);
        CHECK(len > 0 && len <= MT_ARCHIVE_FILE_NAME_MAX);
        CHECK(strchr(name, '/') == NULL);
        CHECK(name[0] != '.');
        CHECK(strchr(name, '.') == strstr(name, ".v1.hdf")); /* the only dots are the suffix's */
        round_trip(archive, ids[i], &list);
    }
    mt_face_list_free(&list);
    /* Every file is directly inside the archive directory, one per id. */
    mt_archive_listing listing;
    CHECK_OK(mt_archive_list(archive, &listing, NULL));
    CHECK_EQ(listing.count, num_ids);
    for (size_t i = 0; i < listing.count; i++) {
        CHECK_OK(listing.entries[i].status);
        bool known = false;
        for (size_t k = 0; k < num_ids; k++)
            if (listing.entries[i].mesh_id && strcmp(listing.entries[i].mesh_id, ids[k]) == 0)
                known = true;
        CHECK(known);
    }
    mt_archive_listing_free(&listing);
    /* Invalid ids are refused by every call. */
    mt_archive_record rec;
    CHECK_STATUS(mt_archive_load(archive, "../x", 1, &rec, NULL), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_archive_remove(archive, "a/b", 1, NULL), MT_ERR_INVALID_ARG);
    mt_archive_close(archive);
    at_rmdir(dir);
}

static void test_versions_and_listing(void)
{
    char dir[512];
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    mt_face_list a, b, c;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &a));
    CHECK_OK(mt_gen_grid(3, 2, false, &b));
    CHECK_OK(mt_gen_torus(4, 3, &c));
    mt_mesh *mc = NULL;
    CHECK_OK(at_archive_list(archive, "scan", 1, &a, 11, NULL));
    CHECK_OK(at_archive_list(archive, "scan", 2, &b, 22, NULL));
    CHECK_OK(at_archive_list(archive, "scan", 10, &c, 33, &mc));
    CHECK_OK(at_archive_list(archive, "other", 1, &a, 44, NULL));
    CHECK(mt_archive_contains(archive, "scan", 2));
    CHECK(!mt_archive_contains(archive, "scan", 3));
    if (mc) check_round_trip(archive, "scan", 10, &c, mc, 33);
    mt_archive_record rec;
    CHECK_OK(mt_archive_load(archive, "scan", 0, &rec, NULL)); /* 0 = the highest: 10, not 2 */
    CHECK_EQ(rec.version, 10);
    CHECK(at_face_lists_equal(&rec.faces, &c));
    mt_archive_record_free(&rec);
    CHECK_STATUS(mt_archive_load(archive, "scan", 3, &rec, NULL), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_archive_load(archive, "nothing", 0, &rec, NULL), MT_ERR_NOT_FOUND);

    mt_archive_listing l;
    CHECK_OK(mt_archive_list(archive, &l, NULL));
    CHECK_EQ(l.count, 4);
    if (l.count == 4) {
        CHECK(strcmp(l.entries[0].mesh_id, "other") == 0);
        CHECK(strcmp(l.entries[1].mesh_id, "scan") == 0 && l.entries[1].version == 1);
        CHECK_EQ(l.entries[2].version, 2);
        CHECK_EQ(l.entries[3].version, 10);
        const mt_archive_summary *s = &l.entries[3].summary;
        const mt_report *r = mt_mesh_report(mc);
        CHECK_EQ(s->num_verts, r->num_verts);
        CHECK_EQ(s->num_faces, r->num_faces);
        CHECK_EQ(s->num_edges, r->num_edges);
        CHECK_EQ(s->genus, 1);
        CHECK(s->closed && s->manifold && s->orientable);
        CHECK_EQ(l.entries[3].content_hash, 33);
        CHECK(l.entries[3].file_bytes > 0);
        CHECK_EQ(l.entries[3].utime, 1700000000000010);
    }
    mt_archive_listing_free(&l);

    CHECK_OK(mt_archive_remove(archive, "scan", 2, NULL));
    CHECK(!mt_archive_contains(archive, "scan", 2));
    CHECK_STATUS(mt_archive_remove(archive, "scan", 2, NULL), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mt_archive_remove(archive, "scan", 0, NULL), MT_ERR_INVALID_ARG);
    CHECK(mt_archive_contains(archive, "scan", 1));
    mt_mesh_destroy(mc);
    mt_face_list_free(&a);
    mt_face_list_free(&b);
    mt_face_list_free(&c);
    mt_archive_close(archive);
    at_rmdir(dir);
}

/* Accepts names that do not hold "scan" (the filter of the test below). */
static bool not_scan(void *ctx, const char *file_name)
{
    (*(int *)ctx)++;
    return strstr(file_name, "scan") == NULL;
}

/* Numbering shared by writers of one directory: the highest version by file
 * name, the write of a taken number refused, and a listing that reads only
 * the files a filter accepts. */
static void test_highest_version_and_filtered_listing(void)
{
    char dir[512];
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    mt_face_list a;
    CHECK_OK(mt_gen_platonic(MT_TETRAHEDRON, &a));
    uint32_t highest = 99;
    CHECK_OK(mt_archive_highest_version(archive, "scan", &highest, NULL));
    CHECK_EQ(highest, 0);
    CHECK_OK(at_archive_list(archive, "scan", 1, &a, 1, NULL));
    CHECK_OK(at_archive_list(archive, "scan", 7, &a, 1, NULL));
    CHECK_OK(at_archive_list(archive, "scan.v9", 12, &a, 1, NULL)); /* '.' escaped: not "scan" */
    CHECK_OK(at_archive_list(archive, "sca", 30, &a, 1, NULL));
    CHECK_OK(mt_archive_highest_version(archive, "scan", &highest, NULL));
    CHECK_EQ(highest, 7);
    CHECK_OK(mt_archive_highest_version(archive, "sca", &highest, NULL));
    CHECK_EQ(highest, 30);
    CHECK_OK(mt_archive_highest_version(archive, "scan.v9", &highest, NULL));
    CHECK_EQ(highest, 12);
    /* A second writer that believed 7 was free is refused, naming the version. */
    mt_diag diag;
    mt_mesh *mesh = NULL;
    CHECK_OK(mt_mesh_build(&a, NULL, &mesh, NULL));
    mt_archive_meta meta = {.mesh_id = "scan", .version = 7, .utime = 1, .source = "b"};
    CHECK_STATUS(mt_archive_write(archive, &meta, &a, mesh, NULL, &diag), MT_ERR_INVALID_ARG);
    CHECK(strstr(diag.message, "version 7 of mesh 'scan' is already archived") != NULL);
    mt_mesh_destroy(mesh);
    CHECK_STATUS(mt_archive_highest_version(archive, "bad/id", &highest, &diag),
                 MT_ERR_INVALID_ARG);

    int asked = 0;
    mt_archive_listing l;
    CHECK_OK(mt_archive_list_filtered(archive, not_scan, &asked, &l, NULL));
    CHECK_EQ(asked, 4);
    CHECK_EQ(l.count, 1);
    if (l.count == 1) CHECK(strcmp(l.entries[0].mesh_id, "sca") == 0);
    mt_archive_listing_free(&l);
    mt_face_list_free(&a);
    mt_archive_close(archive);
    CHECK_STATUS(mt_archive_open(dir, &(mt_archive_options){.read_only = true}, &archive, NULL),
                 MT_OK);
    at_rmdir(dir);
    CHECK_STATUS(mt_archive_highest_version(archive, "scan", &highest, &diag), MT_ERR_IO);
    CHECK(strstr(diag.message, "No such file or directory") != NULL);
    mt_archive_close(archive);
}

/* Files earlier versions named "*.vtkhdf": listed, found, loaded, counted
 * in the numbering, verified, kept from being written again and removed,
 * next to "*.hdf" files of the same mesh. */
static void test_legacy_suffix(void)
{
    char dir[512];
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    mt_face_list a;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &a));
    CHECK_OK(at_archive_list(archive, "old", 1, &a, 1, NULL));
    CHECK_OK(at_archive_list(archive, "old", 2, &a, 1, NULL));
    char from[1024], to[1024];
    snprintf(from, sizeof from, "%s/old.v1.hdf", dir);
    snprintf(to, sizeof to, "%s/old.v1.vtkhdf", dir);
    CHECK(rename(from, to) == 0);
    char name[MT_ARCHIVE_FILE_NAME_MAX + 1];
    CHECK_EQ(mt_archive_file_name("old", 1, name, sizeof name), strlen("old.v1.hdf"));
    CHECK(strcmp(name, "old.v1.hdf") == 0);
    CHECK_OK(mt_archive_file_find(archive, "old", 1, name, sizeof name, NULL));
    CHECK(strcmp(name, "old.v1.vtkhdf") == 0);
    CHECK_OK(mt_archive_file_find(archive, "old", 2, name, sizeof name, NULL));
    CHECK(strcmp(name, "old.v2.hdf") == 0);
    CHECK_STATUS(mt_archive_file_find(archive, "old", 3, name, sizeof name, NULL),
                 MT_ERR_NOT_FOUND);
    CHECK(strcmp(name, "old.v3.hdf") == 0);
    CHECK(mt_archive_contains(archive, "old", 1));

    mt_archive_listing l;
    CHECK_OK(mt_archive_list(archive, &l, NULL));
    CHECK_EQ(l.count, 2);
    if (l.count == 2) {
        CHECK(l.entries[0].status == MT_OK && l.entries[0].version == 1);
        CHECK(strcmp(l.entries[0].file_name, "old.v1.vtkhdf") == 0);
        CHECK(l.entries[1].status == MT_OK && l.entries[1].version == 2);
    }
    mt_archive_listing_free(&l);
    mt_archive_record rec;
    CHECK_OK(mt_archive_load(archive, "old", 1, &rec, NULL));
    CHECK(at_face_lists_equal(&rec.faces, &a));
    mt_archive_record_free(&rec);
    mt_mesh *loaded = NULL;
    CHECK_OK(mt_archive_load_mesh(archive, "old", 1, false, NULL, &loaded, NULL, NULL));
    mt_mesh_destroy(loaded);
    CHECK_OK(mt_archive_verify_file(archive, "old.v1.vtkhdf", NULL, NULL, NULL));

    /* The highest version counts both kinds of names. */
    CHECK_OK(mt_archive_remove(archive, "old", 2, NULL));
    uint32_t highest = 0;
    CHECK_OK(mt_archive_highest_version(archive, "old", &highest, NULL));
    CHECK_EQ(highest, 1);
    /* Version 1 is taken by its .vtkhdf file: no .hdf file is written. */
    mt_mesh *mesh = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(&a, NULL, &mesh, NULL));
    mt_archive_meta meta = {"old", 1, 5, "other", 2};
    CHECK_STATUS(mt_archive_write(archive, &meta, &a, mesh, NULL, &diag), MT_ERR_INVALID_ARG);
    CHECK(strstr(diag.message, "old.v1.vtkhdf: version 1 of mesh 'old' is already archived") !=
          NULL);
    mt_mesh_destroy(mesh);
    CHECK(access(from, F_OK) != 0);
    CHECK_OK(mt_archive_remove(archive, "old", 1, NULL));
    CHECK(access(to, F_OK) != 0);
    CHECK(!mt_archive_contains(archive, "old", 1));
    mt_face_list_free(&a);
    mt_archive_close(archive);
    at_rmdir(dir);
}

static void test_never_overwritten(void)
{
    char dir[512];
    mt_archive *archive = open_fresh(dir, sizeof dir);
    if (!archive) return;
    mt_face_list a, b;
    CHECK_OK(mt_gen_platonic(MT_CUBE, &a));
    CHECK_OK(mt_gen_platonic(MT_ICOSAHEDRON, &b));
    CHECK_OK(at_archive_list(archive, "m", 1, &a, 1, NULL));
    mt_mesh *mesh = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(&b, NULL, &mesh, &diag));
    CHECK_OK(mt_mesh_validate(mesh, &diag));
    mt_archive_meta meta = {"m", 1, 5, "other", 2};
    CHECK_STATUS(mt_archive_write(archive, &meta, &b, mesh, NULL, &diag), MT_ERR_INVALID_ARG);
    CHECK(strstr(diag.message, "already archived") != NULL);
    /* A mesh that is not the list's build is refused too. */
    meta.version = 2;
    CHECK_STATUS(mt_archive_write(archive, &meta, &a, mesh, NULL, &diag), MT_ERR_INVALID_ARG);
    meta.version = 0;
    CHECK_STATUS(mt_archive_write(archive, &meta, &b, mesh, NULL, &diag), MT_ERR_INVALID_ARG);
    mt_archive_record rec;
    CHECK_OK(mt_archive_load(archive, "m", 1, &rec, NULL));
    CHECK(at_face_lists_equal(&rec.faces, &a)); /* still the first one */
    CHECK(rec.content_hash == 1);
    mt_archive_record_free(&rec);
    /* Nothing but the one file is left in the directory (no temporaries). */
    DIR *d = opendir(dir);
    int files = 0;
    struct dirent *ent;
    while (d && (ent = readdir(d)) != NULL)
        if (strcmp(ent->d_name, ".") && strcmp(ent->d_name, "..")) files++;
    if (d) closedir(d);
    CHECK_EQ(files, 1);
    /* A read-only handle writes and removes nothing. */
    mt_archive *ro = NULL;
    mt_archive_options options = {.read_only = true};
    CHECK_OK(mt_archive_open(dir, &options, &ro, NULL));
    meta.version = 3;
    CHECK_STATUS(mt_archive_write(ro, &meta, &b, mesh, NULL, &diag), MT_ERR_UNSUPPORTED);
    CHECK_STATUS(mt_archive_remove(ro, "m", 1, &diag), MT_ERR_UNSUPPORTED);
    mt_archive_close(ro);
    mt_mesh_destroy(mesh);
    mt_face_list_free(&a);
    mt_face_list_free(&b);
    mt_archive_close(archive);
    at_rmdir(dir);
}

static void test_leftovers_cleaned(void)
{
    char dir[512];
    CHECK(at_tmpdir(dir, sizeof dir));
    char stale[600], live[600], other[600], stale_here[600], elsewhere[600], host[256] = "";
    /* A pid above any pid_max: its writer cannot be running. */
    snprintf(stale, sizeof stale, "%s/.mt-tmp-2147483000-3.part", dir);
    snprintf(live, sizeof live, "%s/.mt-tmp-%ld-0.part", dir, (long)getppid());
    snprintf(other, sizeof other, "%s/notes.txt", dir);
    /* The same dead pid, named on this host (removed) and on another one
     * (its writer may run there: kept). */
    gethostname(host, sizeof host - 1);
    snprintf(stale_here, sizeof stale_here, "%s/.mt-tmp-2147483000-0123456789abcdef.%s.part", dir,
             host);
    snprintf(elsewhere, sizeof elsewhere, "%s/.mt-tmp-2147483000-0123456789abcdef.not-%s.part", dir,
             host);
    CHECK(at_write_bytes(stale, "\x89HDF\r\n", 6));
    CHECK(at_write_bytes(live, "\x89HDF\r\n", 6));
    CHECK(at_write_bytes(other, "keep", 4));
    CHECK(at_write_bytes(stale_here, "\x89HDF\r\n", 6));
    CHECK(at_write_bytes(elsewhere, "\x89HDF\r\n", 6));
    mt_archive *archive = NULL;
    mt_archive_options ro = {.read_only = true};
    CHECK_OK(mt_archive_open(dir, &ro, &archive, NULL));
    CHECK_EQ(mt_archive_leftovers_removed(archive), 0);
    CHECK(access(stale, F_OK) == 0);
    mt_archive_close(archive);
    CHECK_OK(mt_archive_open(dir, NULL, &archive, NULL));
    CHECK_EQ(mt_archive_leftovers_removed(archive), 2);
    CHECK(access(stale, F_OK) != 0);
    CHECK(access(stale_here, F_OK) != 0);
    CHECK(access(elsewhere, F_OK) == 0);
    CHECK(access(live, F_OK) == 0); /* its writer (our parent) still runs */
    CHECK(access(other, F_OK) == 0);
    /* Leftovers are not listed. */
    mt_archive_listing l;
    CHECK_OK(mt_archive_list(archive, &l, NULL));
    CHECK_EQ(l.count, 0);
    mt_archive_listing_free(&l);
    mt_archive_close(archive);
    /* Opening a missing directory fails unless asked to create it. */
    char sub[600];
    snprintf(sub, sizeof sub, "%s/sub", dir);
    mt_diag diag;
    CHECK_STATUS(mt_archive_open(sub, NULL, &archive, &diag), MT_ERR_IO);
    CHECK(strstr(diag.message, sub) != NULL);
    mt_archive_options create = {.create = true};
    CHECK_OK(mt_archive_open(sub, &create, &archive, NULL));
    mt_archive_close(archive);
    rmdir(sub);
    CHECK_STATUS(mt_archive_open(other, NULL, &archive, &diag), MT_ERR_IO);
    unlink(live);
    unlink(elsewhere);
    at_rmdir(dir);
}

/* A writer process killed with SIGKILL at random instants: after every
 * kill the archive opens (removing the dead writer's temporary file),
 * every file verifies, and every version the writer reported as written
 * (after mt_archive_write returned, as the daemon acknowledges) is there
 * and intact. */
static void test_killed_while_writing(void)
{
    char dir[512];
    CHECK(at_tmpdir(dir, sizeof dir));
    mt_face_list list;
    CHECK_OK(mt_gen_torus(40, 30, &list));
    uint64_t hash = 0;
    at_hash(NULL, &list, &hash, NULL);
    uint32_t next_version = 1;
    size_t leftovers = 0;
    srand((unsigned)time(NULL));
    for (int round = 0; round < 20; round++) {
        int fds[2];
        CHECK(pipe(fds) == 0);
        pid_t pid = fork();
        CHECK(pid >= 0);
        if (pid == 0) {
            close(fds[0]);
            mt_archive *a = NULL;
            if (mt_archive_open(dir, NULL, &a, NULL) != MT_OK) _exit(2);
            mt_mesh *mesh = NULL;
            if (mt_mesh_build(&list, NULL, &mesh, NULL) != MT_OK) _exit(2);
            for (uint32_t v = next_version;; v++) {
                mt_archive_meta meta = {"stream", v, 1700000000000000 + v, "test-node", hash};
                if (mt_archive_write(a, &meta, &list, mesh, NULL, NULL) != MT_OK) _exit(3);
                if (write(fds[1], &v, sizeof v) != (ssize_t)sizeof v) _exit(4);
            }
        }
        close(fds[1]);
        struct timespec pause = {0, (long)(rand() % 40000) * 1000L};
        nanosleep(&pause, NULL);
        kill(pid, SIGKILL);
        int status = 0;
        waitpid(pid, &status, 0);
        CHECK(WIFSIGNALED(status)); /* killed, not failed */
        uint32_t v, acknowledged = 0;
        while (read(fds[0], &v, sizeof v) == (ssize_t)sizeof v) acknowledged = v;
        close(fds[0]);
        /* A leftover is named ".mt-tmp-<pid>-<16 random hex digits>.<host>.part":
         * nothing about it can be guessed but the pid and the host. */
        char host[256] = "", suffix[300];
        gethostname(host, sizeof host - 1);
        snprintf(suffix, sizeof suffix, ".%s.part", host);
        DIR *before = opendir(dir);
        struct dirent *left;
        while (before && (left = readdir(before)) != NULL) {
            if (strncmp(left->d_name, ".mt-tmp-", 8) != 0) continue;
            char expected[64];
            snprintf(expected, sizeof expected, ".mt-tmp-%ld-", (long)pid);
            size_t n = strlen(expected);
            bool named = strncmp(left->d_name, expected, n) == 0 &&
                         strspn(left->d_name + n, "0123456789abcdef") == 16 &&
                         strcmp(left->d_name + n + 16, suffix) == 0;
            CHECK(named);
            if (!named) printf("leftover named %s\n", left->d_name);
        }
        if (before) closedir(before);
        mt_archive *archive = NULL;
        CHECK_OK(mt_archive_open(dir, NULL, &archive, NULL));
        if (!archive) break;
        leftovers += mt_archive_leftovers_removed(archive);
        for (uint32_t k = next_version; k <= acknowledged; k++)
            CHECK(mt_archive_contains(archive, "stream", k));
        mt_archive_listing l;
        CHECK_OK(mt_archive_list(archive, &l, NULL));
        for (size_t i = 0; i < l.count; i++) {
            mt_diag diag;
            mt_status st =
                mt_archive_verify_file(archive, l.entries[i].file_name, at_hash, NULL, &diag);
            CHECK_OK(st);
            if (st != MT_OK) printf("round %d: %s\n", round, diag.message);
            if (l.entries[i].status == MT_OK && l.entries[i].version >= next_version)
                next_version = l.entries[i].version + 1;
        }
        mt_archive_listing_free(&l);
        /* Nothing but archive files is left: no temporaries. */
        DIR *d = opendir(dir);
        struct dirent *ent;
        while (d && (ent = readdir(d)) != NULL) CHECK(strncmp(ent->d_name, ".mt-tmp-", 8) != 0);
        if (d) closedir(d);
        mt_archive_close(archive);
    }
    CHECK(next_version > 1); /* some versions were written in all */
    printf("%u versions written, %zu interrupted writes cleaned up\n", next_version - 1, leftovers);
    mt_face_list_free(&list);
    at_rmdir(dir);
}

static const mt_test_case cases[] = {
    {"round_trip_generated", test_round_trip_generated},
    {"round_trip_corpus", test_round_trip_corpus},
    {"id_escaping", test_id_escaping},
    {"versions_and_listing", test_versions_and_listing},
    {"highest_version_and_filtered_listing", test_highest_version_and_filtered_listing},
    {"legacy_suffix", test_legacy_suffix},
    {"never_overwritten", test_never_overwritten},
    {"leftovers_cleaned", test_leftovers_cleaned},
    {"killed_while_writing", test_killed_while_writing},
};
const mt_test_table mt_tests_archive = {cases, sizeof cases / sizeof cases[0]};
