/* Mesh store tests: add, get (latest and by version), per-id versions,
 * remove, list and totals, the mesh id rules one by one, limits, and
 * reference counting (an entry outlives removal and the store until its
 * release; the free callback tells exactly when the mesh goes). */
#include <stdlib.h>
#include <string.h>

#include "daemon_test_util.h"
#include "harness.h"
#include "mesh_store.h"

/* Counts on_entry_free calls and remembers the last version freed. */
typedef struct free_log {
    int count;
    uint32_t last_version;
    char last_id[MESHTOPO_MESH_T_MESH_ID_MAX + 1];
} free_log;

static void log_free(void *ctx, const mt_mesh *mesh, const mtd_mesh_info *info)
{
    free_log *log = ctx;
    DT_CHECK_VALID(mesh); /* still intact when the callback runs */
    log->count++;
    log->last_version = info->version;
    strcpy(log->last_id, info->id);
}

static mtd_store *store_with_log(free_log *log, uint32_t max_versions, size_t max_bytes)
{
    memset(log, 0, sizeof *log);
    mtd_store_options opt = {0};
    opt.max_versions_per_id = max_versions;
    opt.max_bytes = max_bytes;
    opt.on_entry_free = log_free;
    opt.on_entry_free_ctx = log;
    mtd_store *store = NULL;
    CHECK_OK(mtd_store_create(&opt, &store));
    return store;
}

/* Adds a freshly built solid; returns its version (0 on failure). */
static uint32_t add_solid(mtd_store *store, const char *id, mt_platonic kind, const char *source,
                          int64_t utime)
{
    mt_mesh *mesh = dt_build_platonic(kind);
    if (!mesh) return 0;
    mtd_mesh_meta meta = {source, utime, 0x1000u + (uint64_t)kind, 0, false};
    uint32_t version = 0;
    mt_diag diag;
    mt_status s = mtd_store_add(store, id, mesh, &meta, &version, NULL, &diag);
    if (s != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "mtd_store_add(%s): %s", id, diag.message);
        mt_mesh_destroy(mesh);
        return 0;
    }
    return version;
}

/* Acquires id/version and checks it is the solid `kind`; returns the version. */
static uint32_t check_solid(mtd_store *store, const char *id, uint32_t version, mt_platonic kind)
{
    mtd_mesh_entry *e = NULL;
    mt_diag diag;
    mt_status s = mtd_store_acquire(store, id, version, &e, &diag);
    if (s != MT_OK) {
        mt_test_fail(__FILE__, __LINE__, "acquire %s v%u: %s", id, (unsigned)version, diag.message);
        return 0;
    }
    const mtd_mesh_info *info = mtd_entry_info(e);
    CHECK_EQ(mt_mesh_num_verts(mtd_entry_mesh(e)), dt_platonic_verts(kind));
    CHECK_EQ(info->content_hash, 0x1000u + (uint64_t)kind);
    CHECK(strcmp(info->id, id) == 0);
    DT_CHECK_VALID(mtd_entry_mesh(e));
    uint32_t got = info->version;
    mtd_entry_release(e);
    return got;
}

static void test_store_add_get_latest(void)
{
    free_log log;
    mtd_store *store = store_with_log(&log, 0, 0);
    if (!store) return;
    CHECK_EQ(add_solid(store, "scan", MT_TETRAHEDRON, "lidar", 111), 1);
    CHECK_EQ(add_solid(store, "scan", MT_CUBE, "lidar", 222), 2);
    CHECK_EQ(add_solid(store, "scan", MT_OCTAHEDRON, "", 333), 3);

    /* 0 = latest; explicit versions give exactly that one. */
    CHECK_EQ(check_solid(store, "scan", 0, MT_OCTAHEDRON), 3);
    CHECK_EQ(check_solid(store, "scan", 1, MT_TETRAHEDRON), 1);
    CHECK_EQ(check_solid(store, "scan", 2, MT_CUBE), 2);

    mtd_mesh_entry *e = NULL;
    mt_diag diag;
    CHECK_OK(mtd_store_acquire(store, "scan", 2, &e, &diag));
    if (e) {
        const mtd_mesh_info *info = mtd_entry_info(e);
        CHECK(strcmp(info->source, "lidar") == 0);
        CHECK_EQ(info->utime, 222);
        CHECK(info->memory_bytes >= mt_mesh_memory_bytes(mtd_entry_mesh(e)) +
                                        mt_mesh_report_memory_bytes(mtd_entry_mesh(e)));
        mtd_entry_release(e);
    }
    CHECK_STATUS(mtd_store_acquire(store, "scan", 4, &e, &diag), MT_ERR_NOT_FOUND);
    CHECK(e == NULL);
    CHECK(strstr(diag.message, "no version 4 of mesh 'scan'") != NULL);
    CHECK_STATUS(mtd_store_acquire(store, "other", 0, &e, &diag), MT_ERR_NOT_FOUND);
    CHECK(strstr(diag.message, "no mesh 'other'") != NULL);

    mtd_store_totals t;
    mtd_store_get_totals(store, &t);
    CHECK_EQ(t.ids, 1);
    CHECK_EQ(t.versions, 3);
    CHECK(t.memory_bytes > 0);
    CHECK_EQ(log.count, 0);
    mtd_store_destroy(store);
    CHECK_EQ(log.count, 3); /* the store's references were the last */
}

static void test_store_versions_per_id(void)
{
    free_log log;
    mtd_store *store = store_with_log(&log, 0, 0);
    if (!store) return;
    CHECK_EQ(add_solid(store, "a", MT_TETRAHEDRON, "n", 1), 1);
    CHECK_EQ(add_solid(store, "b", MT_CUBE, "n", 2), 1);
    CHECK_EQ(add_solid(store, "a", MT_CUBE, "n", 3), 2);
    CHECK_EQ(add_solid(store, "b", MT_OCTAHEDRON, "n", 4), 2);
    CHECK_EQ(check_solid(store, "a", 0, MT_CUBE), 2);
    CHECK_EQ(check_solid(store, "b", 0, MT_OCTAHEDRON), 2);

    /* Removing every version keeps the count going: a number is never reused. */
    CHECK_OK(mtd_store_remove(store, "a", 1, NULL));
    CHECK_OK(mtd_store_remove(store, "a", 2, NULL));
    mtd_mesh_entry *e = NULL;
    CHECK_STATUS(mtd_store_acquire(store, "a", 0, &e, NULL), MT_ERR_NOT_FOUND);
    CHECK_EQ(add_solid(store, "a", MT_DODECAHEDRON, "n", 5), 3);
    CHECK_EQ(check_solid(store, "a", 0, MT_DODECAHEDRON), 3);

    /* An explicit version (archive reload) must be above every earlier one. */
    mt_mesh *mesh = dt_build_platonic(MT_ICOSAHEDRON);
    if (!mesh) goto done;
    mtd_mesh_meta meta = {"archive", 9, 0x1000u + MT_ICOSAHEDRON, 3, false};
    uint32_t version = 99;
    mt_diag diag;
    CHECK_STATUS(mtd_store_add(store, "a", mesh, &meta, &version, NULL, &diag), MT_ERR_INVALID_ARG);
    CHECK_EQ(version, 0);
    CHECK(strstr(diag.message, "already had version 3") != NULL);
    meta.version = 10;
    CHECK_OK(mtd_store_add(store, "a", mesh, &meta, &version, NULL, &diag)); /* store owns it now */
    CHECK_EQ(version, 10);
    CHECK_EQ(check_solid(store, "a", 0, MT_ICOSAHEDRON), 10);
    CHECK_EQ(add_solid(store, "a", MT_TETRAHEDRON, "n", 6), 11);
    CHECK_EQ(check_solid(store, "a", 3, MT_DODECAHEDRON), 3);
    CHECK_STATUS(mtd_store_acquire(store, "a", 5, &e, NULL), MT_ERR_NOT_FOUND);
done:
    mtd_store_destroy(store);
    CHECK_EQ(log.count, 2 + 2 + 3);
}

static void test_store_remove(void)
{
    free_log log;
    mtd_store *store = store_with_log(&log, 0, 0);
    if (!store) return;
    for (int i = 0; i < 3; i++) CHECK_EQ(add_solid(store, "m", (mt_platonic)i, "n", i), i + 1);
    mtd_store_totals before, after;
    mtd_store_get_totals(store, &before);

    mt_diag diag;
    CHECK_OK(mtd_store_remove(store, "m", 2, &diag));
    CHECK_EQ(log.count, 1);
    CHECK_EQ(log.last_version, 2);
    CHECK(strcmp(log.last_id, "m") == 0);
    mtd_mesh_entry *e = NULL;
    CHECK_STATUS(mtd_store_acquire(store, "m", 2, &e, NULL), MT_ERR_NOT_FOUND);
    CHECK_STATUS(mtd_store_remove(store, "m", 2, &diag), MT_ERR_NOT_FOUND);
    CHECK(strstr(diag.message, "no version 2 of mesh 'm'") != NULL);
    CHECK_STATUS(mtd_store_remove(store, "m", 0, &diag), MT_ERR_INVALID_ARG);
    CHECK(strstr(diag.message, "needs a version") != NULL);
    CHECK_STATUS(mtd_store_remove(store, "nothing", 1, &diag), MT_ERR_NOT_FOUND);

    mtd_store_get_totals(store, &after);
    CHECK_EQ(after.versions, before.versions - 1);
    CHECK(after.memory_bytes < before.memory_bytes);

    /* Removing the latest makes the previous one the latest. */
    CHECK_OK(mtd_store_remove(store, "m", 3, NULL));
    CHECK_EQ(check_solid(store, "m", 0, MT_TETRAHEDRON), 1);
    CHECK_OK(mtd_store_remove(store, "m", 1, NULL));
    mtd_store_get_totals(store, &after);
    CHECK_EQ(after.ids, 0);
    CHECK_EQ(after.versions, 0);
    CHECK_EQ(after.memory_bytes, 0);
    CHECK_EQ(log.count, 3);
    mtd_store_destroy(store);
    CHECK_EQ(log.count, 3);
}

static void test_store_list(void)
{
    free_log log;
    mtd_store *store = store_with_log(&log, 0, 0);
    if (!store) return;
    mtd_store_listing *listing = NULL;
    CHECK_OK(mtd_store_list(store, &listing));
    if (listing) CHECK_EQ(listing->num_ids, 0);
    mtd_store_listing_free(listing);

    add_solid(store, "zebra", MT_CUBE, "cam2", 10);
    add_solid(store, "apple", MT_TETRAHEDRON, "cam1", 20);
    add_solid(store, "mango", MT_OCTAHEDRON, "cam3", 30);
    add_solid(store, "apple", MT_ICOSAHEDRON, "cam4", 40);
    add_solid(store, "gone", MT_CUBE, "cam5", 50);
    CHECK_OK(mtd_store_remove(store, "gone", 1, NULL)); /* ids without versions are not listed */
    CHECK_OK(mtd_store_list(store, &listing));
    mtd_store_destroy(store); /* the listing owns its strings */
    if (!listing) return;

    CHECK_EQ(listing->num_ids, 3);
    CHECK_EQ(listing->totals.ids, 3);
    CHECK_EQ(listing->totals.versions, 4);
    const char *order[] = {"apple", "mango", "zebra"};
    const uint32_t counts[] = {2, 1, 1};
    size_t bytes = 0;
    for (size_t i = 0; i < listing->num_ids && i < 3; i++) {
        const mtd_listed_id *row = &listing->ids[i];
        CHECK(strcmp(row->id, order[i]) == 0);
        CHECK_EQ(row->num_versions, counts[i]);
        for (uint32_t v = 0; v < row->num_versions; v++) {
            CHECK_EQ(row->versions[v].version, v + 1);
            CHECK(strcmp(row->versions[v].id, order[i]) == 0);
            bytes += row->versions[v].memory_bytes;
        }
    }
    CHECK_EQ(bytes, listing->totals.memory_bytes);
    const mtd_mesh_info *apple2 = &listing->ids[0].versions[1];
    CHECK(strcmp(apple2->source, "cam4") == 0);
    CHECK_EQ(apple2->utime, 40);
    CHECK_EQ(apple2->content_hash, 0x1000u + MT_ICOSAHEDRON);
    CHECK(strcmp(listing->ids[2].versions[0].source, "cam2") == 0);
    mtd_store_listing_free(listing);
    mtd_store_listing_free(NULL);
}

/* Expects id to be refused with a message containing `says` and the given
 * offending byte offset; the store must refuse it on every call. */
static void expect_bad_id(mtd_store *store, const char *id, const char *says, uint64_t offset,
                          int line)
{
    mt_diag diag;
    if (mt_msgs_mesh_id_check(id, &diag) != MT_ERR_INVALID_ARG) {
        mt_test_fail(__FILE__, line, "id accepted, expected: %s", says);
        return;
    }
    if (!strstr(diag.message, says))
        mt_test_fail(__FILE__, line, "message '%s' does not say '%s'", diag.message, says);
    if (diag.status != MT_ERR_INVALID_ARG) mt_test_fail(__FILE__, line, "diag.status not set");
    if (diag.byte_offset != offset)
        mt_test_fail(__FILE__, line, "byte_offset %llu, expected %llu",
                     (unsigned long long)diag.byte_offset, (unsigned long long)offset);

    mt_mesh *mesh = dt_build_platonic(MT_TETRAHEDRON);
    if (!mesh) return;
    static char not_null;
    uint32_t version = 7;
    mtd_mesh_entry *e = (mtd_mesh_entry *)(void *)&not_null; /* must come back NULL */
    if (mtd_store_add(store, id, mesh, NULL, &version, &e, &diag) != MT_ERR_INVALID_ARG ||
        !strstr(diag.message, says) || version != 0 || e != NULL)
        mt_test_fail(__FILE__, line, "mtd_store_add did not refuse the id: %s", diag.message);
    DT_CHECK_VALID(mesh); /* the caller still owns it */
    mt_mesh_destroy(mesh);
    if (mtd_store_acquire(store, id, 0, &e, &diag) != MT_ERR_INVALID_ARG ||
        !strstr(diag.message, says))
        mt_test_fail(__FILE__, line, "mtd_store_acquire did not refuse the id");
    if (mtd_store_remove(store, id, 1, &diag) != MT_ERR_INVALID_ARG || !strstr(diag.message, says))
        mt_test_fail(__FILE__, line, "mtd_store_remove did not refuse the id");
}

static void expect_good_id(mtd_store *store, const char *id, int line)
{
    mt_diag diag;
    if (mt_msgs_mesh_id_check(id, &diag) != MT_OK) {
        mt_test_fail(__FILE__, line, "id refused: %s", diag.message);
        return;
    }
    if (add_solid(store, id, MT_TETRAHEDRON, "n", 1) != 1)
        mt_test_fail(__FILE__, line, "good id not stored");
}

static void test_store_id_rules(void)
{
    free_log log;
    mtd_store *store = store_with_log(&log, 0, 0);
    if (!store) return;

    expect_bad_id(store, NULL, "missing", UINT64_MAX, __LINE__);
    expect_bad_id(store, "", "mesh id is empty", UINT64_MAX, __LINE__);

    char *big = malloc(10241);
    if (big) {
        memset(big, 'a', 10240);
        big[10240] = '\0';
        expect_bad_id(store, big, "mesh id is 10240 bytes long; the limit is 255 bytes", UINT64_MAX,
                      __LINE__);
        big[256] = '\0';
        expect_bad_id(store, big, "256 bytes long", UINT64_MAX, __LINE__);
        big[255] = '\0';
        expect_good_id(store, big, __LINE__); /* exactly the limit */
        free(big);
    }

    expect_bad_id(store, "../x", "contains \"..\" at byte 0", 0, __LINE__);
    expect_bad_id(store, "x..", "contains \"..\" at byte 1", 1, __LINE__);
    expect_bad_id(store, "a/b", "contains '/' at byte 1", 1, __LINE__);
    expect_bad_id(store, "/abs", "contains '/' at byte 0", 0, __LINE__);
    expect_bad_id(store, "x/../y", "contains '/' at byte 1", 1, __LINE__);
    expect_bad_id(store, "a\nb", "byte 1 is 0x0a", 1, __LINE__);
    expect_bad_id(store, "tab\there", "byte 3 is 0x09", 3, __LINE__);
    expect_bad_id(store, "esc\x1b", "byte 3 is 0x1b", 3, __LINE__);
    expect_bad_id(store, "del\x7f", "byte 3 is 0x7f", 3, __LINE__);
    expect_bad_id(store, "caf\xc3\xa9", "byte 3 is 0xc3", 3, __LINE__);
    CHECK(mt_msgs_mesh_id_check("x", NULL) == MT_OK); /* NULL diag is fine */
    CHECK(mt_msgs_mesh_id_check("a/b", NULL) == MT_ERR_INVALID_ARG);

    expect_good_id(store, "scan", __LINE__);
    expect_good_id(store, "a.b", __LINE__);
    expect_good_id(store, ".hidden", __LINE__);
    expect_good_id(store, "with space", __LINE__);
    expect_good_id(store, "A-Z_0-9~!@#$%^&*()+=[]{}:;'\"<>,?|\\`", __LINE__);

    mtd_store_totals t;
    mtd_store_get_totals(store, &t);
    CHECK_EQ(t.ids, 6); /* the good ones only */
    mtd_store_destroy(store);
    CHECK_EQ(log.count, 6);
}

static void test_store_refcount(void)
{
    free_log log;
    mtd_store *store = store_with_log(&log, 0, 0);
    if (!store) return;
    mt_mesh *mesh = dt_build_platonic(MT_DODECAHEDRON);
    if (!mesh) return;
    mtd_mesh_entry *added = NULL;
    uint32_t version = 0;
    CHECK_OK(mtd_store_add(store, "held", mesh, NULL, &version, &added, NULL));
    CHECK_EQ(version, 1);
    CHECK(added != NULL);
    if (!added) return;
    CHECK(mtd_entry_mesh(added) == mesh);
    CHECK(strcmp(mtd_entry_info(added)->source, "") == 0); /* NULL meta: empty source */

    mtd_mesh_entry *got = NULL;
    CHECK_OK(mtd_store_acquire(store, "held", 1, &got, NULL));
    CHECK(got == added);
    mtd_mesh_entry *more = mtd_entry_retain(got);
    CHECK(more == got);

    /* Removed from the store, but three references are held: nothing freed. */
    CHECK_OK(mtd_store_remove(store, "held", 1, NULL));
    CHECK_EQ(log.count, 0);
    DT_CHECK_VALID(mtd_entry_mesh(got)); /* use after free here would stop ASan */
    CHECK_EQ(mt_mesh_num_verts(mtd_entry_mesh(got)), 20);
    mtd_entry_release(added);
    mtd_entry_release(more);
    CHECK_EQ(log.count, 0);
    CHECK_EQ(mtd_entry_info(got)->version, 1);
    mtd_entry_release(got); /* the last one */
    CHECK_EQ(log.count, 1);
    mtd_entry_release(NULL);

    /* Destroying the store does not free what a query still holds. */
    CHECK_EQ(add_solid(store, "held", MT_CUBE, "n", 1), 2);
    CHECK_OK(mtd_store_acquire(store, "held", 0, &got, NULL));
    mtd_store_destroy(store);
    CHECK_EQ(log.count, 1);
    if (got) {
        DT_CHECK_VALID(mtd_entry_mesh(got));
        CHECK_EQ(mt_mesh_num_verts(mtd_entry_mesh(got)), 8);
        CHECK(strcmp(mtd_entry_info(got)->id, "held") == 0);
        mtd_entry_release(got);
    }
    CHECK_EQ(log.count, 2);
    CHECK_EQ(log.last_version, 2);
    mtd_store_destroy(NULL);
}

static void test_store_max_versions(void)
{
    free_log log;
    mtd_store *store = store_with_log(&log, 2, 0);
    if (!store) return;
    CHECK_EQ(add_solid(store, "k", MT_TETRAHEDRON, "n", 1), 1);
    CHECK_EQ(add_solid(store, "k", MT_CUBE, "n", 2), 2);
    mtd_mesh_entry *oldest = NULL;
    CHECK_OK(mtd_store_acquire(store, "k", 1, &oldest, NULL));
    CHECK_EQ(add_solid(store, "k", MT_OCTAHEDRON, "n", 3), 3); /* drops v1 */
    CHECK_EQ(log.count, 0);                                    /* v1 is still held */
    mtd_mesh_entry *e = NULL;
    CHECK_STATUS(mtd_store_acquire(store, "k", 1, &e, NULL), MT_ERR_NOT_FOUND);
    mtd_entry_release(oldest);
    CHECK_EQ(log.count, 1);
    CHECK_EQ(log.last_version, 1);
    CHECK_EQ(add_solid(store, "k", MT_ICOSAHEDRON, "n", 4), 4); /* drops v2 */
    CHECK_EQ(log.count, 2);
    CHECK_EQ(log.last_version, 2);
    CHECK_EQ(check_solid(store, "k", 3, MT_OCTAHEDRON), 3);
    CHECK_EQ(check_solid(store, "k", 0, MT_ICOSAHEDRON), 4);
    mtd_store_totals t;
    mtd_store_get_totals(store, &t);
    CHECK_EQ(t.versions, 2);
    mtd_store_destroy(store);
    CHECK_EQ(log.count, 4);
}

static void test_store_max_bytes(void)
{
    /* Measure one entry, then allow room for two. */
    free_log log;
    mtd_store *probe = store_with_log(&log, 0, 0);
    if (!probe) return;
    add_solid(probe, "m", MT_TETRAHEDRON, "n", 1);
    mtd_store_totals one;
    mtd_store_get_totals(probe, &one);
    mtd_store_destroy(probe);
    CHECK(one.memory_bytes > 0);

    mtd_store *store = store_with_log(&log, 0, 2 * one.memory_bytes);
    if (!store) return;
    CHECK_EQ(add_solid(store, "m", MT_TETRAHEDRON, "n", 1), 1);
    CHECK_EQ(add_solid(store, "m", MT_TETRAHEDRON, "n", 2), 2);
    mt_mesh *mesh = dt_build_platonic(MT_TETRAHEDRON);
    if (mesh) {
        mt_diag diag;
        uint32_t version = 5;
        CHECK_STATUS(mtd_store_add(store, "m", mesh, NULL, &version, NULL, &diag),
                     MT_ERR_TOO_LARGE);
        CHECK_EQ(version, 0);
        CHECK(strstr(diag.message, "limit") != NULL);
        DT_CHECK_VALID(mesh);
        mtd_store_totals t;
        mtd_store_get_totals(store, &t);
        CHECK_EQ(t.versions, 2);
        CHECK_EQ(t.memory_bytes, 2 * one.memory_bytes);
        /* Room again after a removal; the refused add used no version number. */
        CHECK_OK(mtd_store_remove(store, "m", 1, NULL));
        CHECK_OK(mtd_store_add(store, "m", mesh, NULL, &version, NULL, &diag));
        CHECK_EQ(version, 3);
    }
    mtd_store_destroy(store);
    CHECK_EQ(log.count, 3);
}

static void test_store_bad_args(void)
{
    mtd_store *store = NULL;
    CHECK_OK(mtd_store_create(NULL, &store));
    if (!store) return;
    mt_diag diag;
    uint32_t version = 1;
    CHECK_STATUS(mtd_store_add(store, "m", NULL, NULL, &version, NULL, &diag), MT_ERR_INVALID_ARG);
    CHECK(strstr(diag.message, "no mesh") != NULL);
    CHECK_EQ(version, 0);
    mtd_store_totals t;
    mtd_store_get_totals(store, &t);
    CHECK_EQ(t.versions, 0);
    mtd_store_destroy(store);
}

static const mt_test_case cases[] = {
    {"store_add_get_latest", test_store_add_get_latest},
    {"store_versions_per_id", test_store_versions_per_id},
    {"store_remove", test_store_remove},
    {"store_list", test_store_list},
    {"store_id_rules", test_store_id_rules},
    {"store_refcount", test_store_refcount},
    {"store_max_versions", test_store_max_versions},
    {"store_max_bytes", test_store_max_bytes},
    {"store_bad_args", test_store_bad_args},
};
const mt_test_table mt_tests_mesh_store = {cases, sizeof cases / sizeof cases[0]};
