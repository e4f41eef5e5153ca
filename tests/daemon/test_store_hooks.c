/* The store's two hooks and its memory budget, with fakes in place of the
 * archive: the archiving policy is told exactly once per version put (admit
 * before it is visible, on_added after; withdraw when the store refuses an
 * admitted one), a policy's refusal adds nothing, a version the backing
 * keeps is read through its load only and added by the store, new versions
 * are numbered after what the backing keeps, and the budget drops the least
 * recently used kept versions, which the next fetch loads again. The store
 * links without the catalog and the writer (meshtopod_core has neither), so
 * it reaches them only through these hooks. */
#include <stdlib.h>
#include <string.h>

#include "daemon_test_util.h"
#include "harness.h"
#include "memory_budget.h"
#include "mesh_store.h"

/* ---- a fake archiving policy ---------------------------------------------- */

typedef struct fake_policy {
    int admits, withdraws, added;
    uint32_t last_admitted, last_withdrawn;
    uint32_t raise_to;     /* admit keeps the version under this number (0: as proposed) */
    mt_status refuse;      /* admit's answer */
    bool visible_at_admit; /* whether the version was held when admit ran */
    mtd_store *store;
    const mt_face_list *expected_list;
    bool list_ok;
} fake_policy;

static mt_status fake_admit(void *ctx, const mtd_mesh_info *info, const mt_face_list *list,
                            const mt_mesh *mesh, uint32_t *io_version, mt_diag *diag)
{
    fake_policy *p = ctx;
    p->admits++;
    p->list_ok = list == p->expected_list && mesh != NULL;
    mtd_mesh_entry *e = NULL;
    p->visible_at_admit = mtd_store_acquire(p->store, info->id, info->version, &e, NULL) == MT_OK;
    mtd_entry_release(e);
    if (p->refuse != MT_OK) return mt_diag_set(diag, p->refuse, "refused by the fake policy");
    if (p->raise_to) *io_version = p->raise_to;
    p->last_admitted = *io_version;
    return MT_OK;
}

static void fake_withdraw(void *ctx, const char *id, uint32_t version)
{
    (void)id;
    fake_policy *p = ctx;
    p->withdraws++;
    p->last_withdrawn = version;
}

static void fake_on_added(void *ctx, mtd_mesh_entry *entry, const mt_face_list *list)
{
    fake_policy *p = ctx;
    (void)list;
    p->added++;
    CHECK(mtd_entry_info(entry)->version >= 1);
}

static mtd_store *store_with_policy(fake_policy *p, size_t max_bytes, bool sync)
{
    memset(p, 0, sizeof *p);
    mtd_store_options opt = {0};
    opt.max_bytes = max_bytes;
    mtd_store *store = NULL;
    CHECK_OK(mtd_store_create(&opt, &store));
    mtd_store_policy policy = {.ctx = p, .on_added = fake_on_added};
    if (sync) {
        policy.admit = fake_admit;
        policy.withdraw = fake_withdraw;
    }
    mtd_store_set_policy(store, &policy);
    p->store = store;
    return store;
}

static mt_status put(mtd_store *store, const char *id, const mt_face_list *list,
                     uint32_t *out_version, bool *out_by_policy)
{
    mt_mesh *mesh = dt_build_platonic(MT_CUBE);
    mtd_mesh_meta meta = {.source = "test", .utime = 1, .content_hash = 2};
    mtd_mesh_entry *entry = NULL;
    mt_diag diag;
    mt_status s =
        mtd_store_put(store, id, mesh, &meta, list, out_version, &entry, out_by_policy, &diag);
    if (s != MT_OK)
        mt_mesh_destroy(mesh);
    else
        mtd_entry_release(entry);
    return s;
}

static void test_hooks_policy_once_per_version(void)
{
    fake_policy p;
    mtd_store *store = store_with_policy(&p, 0, true);
    mt_face_list list = {0};
    p.expected_list = &list;
    uint32_t version = 0;
    bool by_policy = true;
    for (uint32_t i = 1; i <= 3; i++) {
        CHECK_OK(put(store, "m", &list, &version, &by_policy));
        CHECK_EQ(version, i);
        CHECK(!by_policy);
        CHECK_EQ(p.admits, (int)i);
        CHECK_EQ(p.added, (int)i);
        CHECK_EQ(p.last_admitted, i);
        CHECK(p.list_ok);
        CHECK(!p.visible_at_admit); /* durable before anyone sees it */
    }
    CHECK_EQ(p.withdraws, 0);
    mtd_store_destroy(store);
}

static void test_hooks_async_policy_after_visible(void)
{
    fake_policy p;
    mtd_store *store = store_with_policy(&p, 0, false);
    uint32_t version = 0;
    CHECK_OK(put(store, "m", NULL, &version, NULL));
    CHECK_OK(put(store, "m", NULL, &version, NULL));
    CHECK_EQ(version, 2);
    CHECK_EQ(p.admits, 0);
    CHECK_EQ(p.added, 2);
    mtd_store_destroy(store);
}

static void test_hooks_policy_refuses(void)
{
    fake_policy p;
    mtd_store *store = store_with_policy(&p, 0, true);
    p.refuse = MT_ERR_IO;
    uint32_t version = 7;
    bool by_policy = false;
    CHECK_STATUS(put(store, "m", NULL, &version, &by_policy), MT_ERR_IO);
    CHECK(by_policy);
    CHECK_EQ(version, 0);
    CHECK_EQ(p.added, 0);
    mtd_store_totals t;
    mtd_store_get_totals(store, &t);
    CHECK_EQ(t.versions, 0);
    /* The refused number stays a gap. */
    p.refuse = MT_OK;
    CHECK_OK(put(store, "m", NULL, &version, &by_policy));
    CHECK_EQ(version, 2);
    mtd_store_destroy(store);
}

static void test_hooks_store_refusal_withdraws(void)
{
    fake_policy p;
    mtd_store *store = store_with_policy(&p, 1, true); /* nothing fits */
    uint32_t version = 0;
    bool by_policy = true;
    CHECK_STATUS(put(store, "m", NULL, &version, &by_policy), MT_ERR_TOO_LARGE);
    CHECK(!by_policy);
    CHECK_EQ(p.admits, 1);
    CHECK_EQ(p.withdraws, 1);
    CHECK_EQ(p.last_withdrawn, 1);
    CHECK_EQ(p.added, 0);
    mtd_store_destroy(store);
}

static void test_hooks_policy_renumbers(void)
{
    fake_policy p;
    mtd_store *store = store_with_policy(&p, 0, true);
    p.raise_to = 9; /* a shared directory had up to 8 */
    uint32_t version = 0;
    CHECK_OK(put(store, "m", NULL, &version, NULL));
    CHECK_EQ(version, 9);
    p.raise_to = 0;
    CHECK_OK(put(store, "m", NULL, &version, NULL));
    CHECK_EQ(version, 10);
    mtd_store_destroy(store);
}

/* ---- a fake backing ------------------------------------------------------- */

#define KEPT 4

typedef struct fake_backing {
    int loads, loaded_ok, loaded_failed;
    bool fail_load;
} fake_backing;

static uint32_t fake_highest(void *ctx, const char *id)
{
    (void)ctx;
    return strcmp(id, "k") == 0 ? KEPT : 0;
}

static bool fake_keeps(void *ctx, const char *id, uint32_t version)
{
    (void)ctx;
    return strcmp(id, "k") == 0 && version >= 1 && version <= KEPT;
}

static mt_status fake_load(void *ctx, const char *id, uint32_t version, mt_mesh **out_mesh,
                           mtd_mesh_meta *out_meta, mt_diag *diag)
{
    (void)id;
    (void)version;
    fake_backing *b = ctx;
    b->loads++;
    if (b->fail_load) return mt_diag_set(diag, MT_ERR_IO, "the fake file is damaged");
    *out_mesh = dt_build_platonic(MT_TETRAHEDRON);
    out_meta->source = strdup("archived");
    out_meta->utime = 5;
    out_meta->content_hash = 6;
    return MT_OK;
}

static void fake_loaded(void *ctx, const char *id, uint32_t version, mt_status status,
                        mt_diag *diag)
{
    (void)id;
    (void)version;
    (void)diag;
    fake_backing *b = ctx;
    if (status == MT_OK)
        b->loaded_ok++;
    else
        b->loaded_failed++;
}

static mt_status fake_list(void *ctx, const mtd_store_listing *held, mtd_store_listing **out)
{
    (void)ctx;
    (void)held;
    *out = NULL;
    return MT_ERR_UNSUPPORTED;
}

static mtd_store *store_with_backing(fake_backing *b, mtd_budget *budget)
{
    memset(b, 0, sizeof *b);
    mtd_store_options opt = {0};
    opt.budget = budget;
    mtd_store *store = NULL;
    CHECK_OK(mtd_store_create(&opt, &store));
    mtd_store_backing backing = {.ctx = b,
                                 .highest = fake_highest,
                                 .keeps = fake_keeps,
                                 .load = fake_load,
                                 .loaded = fake_loaded,
                                 .list = fake_list};
    mtd_store_set_backing(store, &backing);
    return store;
}

static void test_hooks_backing_load(void)
{
    fake_backing b;
    mtd_store *store = store_with_backing(&b, NULL);
    mtd_mesh_entry *e = NULL;
    mt_diag diag;
    CHECK_EQ(mtd_store_fetch(store, "k", 0, false, &e, &diag), MTD_FETCH_NEEDS_LOAD);
    CHECK_EQ(b.loads, 0);
    CHECK_EQ(mtd_store_fetch(store, "k", 0, true, &e, &diag), MTD_FETCH_OK);
    CHECK_EQ(b.loads, 1);
    CHECK_EQ(b.loaded_ok, 1);
    CHECK_EQ(mtd_entry_info(e)->version, KEPT);
    CHECK(strcmp(mtd_entry_info(e)->source, "archived") == 0);
    DT_CHECK_VALID(mtd_entry_mesh(e));
    mtd_entry_release(e);
    /* Held now: no second read. */
    CHECK_EQ(mtd_store_fetch(store, "k", KEPT, true, &e, &diag), MTD_FETCH_OK);
    CHECK_EQ(b.loads, 1);
    mtd_entry_release(e);
    CHECK_EQ(mtd_store_fetch(store, "k", KEPT + 1, true, &e, &diag), MTD_FETCH_NOT_HELD);
    CHECK_EQ(mtd_store_fetch(store, "other", 0, true, &e, &diag), MTD_FETCH_NOT_HELD);
    /* A failed read is the backing's answer. */
    b.fail_load = true;
    CHECK_EQ(mtd_store_fetch(store, "k", 1, true, &e, &diag), MTD_FETCH_LOAD_FAILED);
    CHECK(strstr(diag.message, "damaged") != NULL);
    CHECK(e == NULL);
    /* New versions come after what the backing keeps. */
    uint32_t version = 0;
    CHECK_OK(put(store, "k", NULL, &version, NULL));
    CHECK_EQ(version, KEPT + 1);
    CHECK_OK(put(store, "new", NULL, &version, NULL));
    CHECK_EQ(version, 1);
    mtd_store_destroy(store);
}

static void test_hooks_budget_evicts_lru(void)
{
    mt_mesh *probe = dt_build_platonic(MT_TETRAHEDRON);
    mtd_store_options plain = {0};
    mtd_store *measure = NULL;
    CHECK_OK(mtd_store_create(&plain, &measure));
    CHECK_OK(mtd_store_add(measure, "x", probe, NULL, NULL, NULL, NULL));
    mtd_store_totals one;
    mtd_store_get_totals(measure, &one);
    mtd_store_destroy(measure);

    mtd_budget *budget = NULL;
    CHECK_OK(mtd_budget_create(one.memory_bytes * 2 + one.memory_bytes / 2, &budget));
    fake_backing b;
    mtd_store *store = store_with_backing(&b, budget);
    mtd_mesh_entry *e = NULL;
    mt_diag diag;
    for (uint32_t v = 1; v <= 3; v++) {
        CHECK_EQ(mtd_store_fetch(store, "k", v, true, &e, &diag), MTD_FETCH_OK);
        mtd_entry_release(e);
        if (v == 2) {
            /* 1 used again after 2: 2 is the least recently used. */
            CHECK_EQ(mtd_store_fetch(store, "k", 1, true, &e, &diag), MTD_FETCH_OK);
            mtd_entry_release(e);
        }
    }
    mtd_store_totals t;
    mtd_store_get_totals(store, &t);
    CHECK(t.memory_bytes <= mtd_budget_bytes(budget));
    CHECK_EQ(t.versions, 2);
    CHECK_EQ(mtd_budget_evictions(budget), 1);
    CHECK_STATUS(mtd_store_acquire(store, "k", 2, &e, NULL), MT_ERR_NOT_FOUND);
    /* The evicted version comes back on demand. */
    CHECK_EQ(b.loads, 3);
    CHECK_EQ(mtd_store_fetch(store, "k", 2, true, &e, &diag), MTD_FETCH_OK);
    CHECK_EQ(b.loads, 4);
    mtd_entry_release(e);
    /* Versions the backing does not keep are never dropped. */
    uint32_t version = 0;
    for (int i = 0; i < 3; i++) CHECK_OK(put(store, "fresh", NULL, &version, NULL));
    CHECK_OK(mtd_store_acquire(store, "fresh", 1, &e, NULL));
    mtd_entry_release(e);
    mtd_store_destroy(store);
    mtd_budget_destroy(budget);
}

static void test_budget_order(void)
{
    mtd_budget *b = NULL;
    CHECK_OK(mtd_budget_create(100, &b));
    CHECK(!mtd_budget_over(b, 100));
    CHECK(mtd_budget_over(b, 101));
    mtd_budget_track(b, "a", 1);
    mtd_budget_track(b, "b", 1);
    mtd_budget_track(b, "a", 2);
    mtd_budget_touch(b, "a", 1);
    mtd_budget_touch(b, "zz", 9); /* not tracked: nothing */
    CHECK_EQ(mtd_budget_tracked(b), 3);
    mtd_budget_forget(b, "a", 2);
    char id[16];
    uint32_t v = 0;
    CHECK(mtd_budget_pick(b, id, sizeof id, &v));
    CHECK(strcmp(id, "b") == 0 && v == 1);
    CHECK(mtd_budget_pick(b, id, sizeof id, &v));
    CHECK(strcmp(id, "a") == 0 && v == 1);
    CHECK(!mtd_budget_pick(b, id, sizeof id, &v));
    mtd_budget_destroy(b);
    /* Without a budget nothing is tracked or picked. */
    CHECK_OK(mtd_budget_create(0, &b));
    mtd_budget_track(b, "a", 1);
    CHECK_EQ(mtd_budget_tracked(b), 0);
    CHECK(!mtd_budget_over(b, SIZE_MAX));
    mtd_budget_destroy(b);
    CHECK_EQ(mtd_budget_bytes(NULL), 0);
}

static const mt_test_case cases[] = {
    {"hooks_policy_once_per_version", test_hooks_policy_once_per_version},
    {"hooks_async_policy_after_visible", test_hooks_async_policy_after_visible},
    {"hooks_policy_refuses", test_hooks_policy_refuses},
    {"hooks_store_refusal_withdraws", test_hooks_store_refusal_withdraws},
    {"hooks_policy_renumbers", test_hooks_policy_renumbers},
    {"hooks_backing_load", test_hooks_backing_load},
    {"hooks_budget_evicts_lru", test_hooks_budget_evicts_lru},
    {"budget_order", test_budget_order},
};
const mt_test_table mt_tests_store_hooks = {cases, sizeof cases / sizeof cases[0]};
