/* Mesh store under concurrency: threads adding freshly built meshes, threads
 * acquiring (latest and by version, some holding entries across removals)
 * and threads removing versions and listing, all on the same few ids. Every
 * acquired mesh must be the one its metadata names, the totals must add up
 * afterwards, and every mesh must be freed exactly once. Meant to run under
 * ThreadSanitizer as well (scripts/test.sh tsan). */
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon_test_util.h"
#include "harness.h"
#include "mesh_store.h"

#define NUM_IDS 4
#define ADDERS 3
#define GETTERS 3
#define REMOVERS 2
#define ADDS_PER_ADDER 150

typedef struct shared {
    mtd_store *store;
    atomic_int adders_left;
    atomic_long adds;
    atomic_long removals;
    atomic_long frees;
    atomic_long acquires;
    atomic_int failures; /* counted here, reported from the main thread */
} shared;

static void count_free(void *ctx, const mt_mesh *mesh, const mtd_mesh_info *info)
{
    shared *sh = ctx;
    if (mt_mesh_num_verts(mesh) != dt_platonic_verts((mt_platonic)(info->content_hash & 0xff)))
        atomic_fetch_add(&sh->failures, 1);
    atomic_fetch_add(&sh->frees, 1);
}

static void id_name(char *buf, unsigned i)
{
    snprintf(buf, 8, "m%u", i % NUM_IDS);
}

/* The entry's mesh is the solid its content hash names. */
static int entry_consistent(const mtd_mesh_entry *e, int full)
{
    const mtd_mesh_info *info = mtd_entry_info(e);
    mt_platonic kind = (mt_platonic)(info->content_hash & 0xff);
    if (kind > MT_ICOSAHEDRON) return 0;
    if (mt_mesh_num_verts(mtd_entry_mesh(e)) != dt_platonic_verts(kind)) return 0;
    if ((uint64_t)info->utime != info->content_hash >> 8) return 0;
    if (full && mt_mesh_validate(mtd_entry_mesh(e), NULL) != MT_OK) return 0;
    return 1;
}

static void *adder(void *arg)
{
    shared *sh = arg;
    unsigned seed = (unsigned)(uintptr_t)&seed;
    for (int i = 0; i < ADDS_PER_ADDER; i++) {
        mt_platonic kind = (mt_platonic)(rand_r(&seed) % 5);
        mt_face_list fl;
        mt_mesh *mesh = NULL;
        if (mt_gen_platonic(kind, &fl) != MT_OK) {
            atomic_fetch_add(&sh->failures, 1);
            continue;
        }
        mt_status s = mt_mesh_build(&fl, NULL, &mesh, NULL); /* built outside the store */
        mt_face_list_free(&fl);
        if (s != MT_OK || mt_mesh_validate(mesh, NULL) != MT_OK) {
            atomic_fetch_add(&sh->failures, 1);
            mt_mesh_destroy(mesh);
            continue;
        }
        char id[8];
        id_name(id, (unsigned)rand_r(&seed));
        uint64_t stamp = (uint64_t)rand_r(&seed);
        mtd_mesh_meta meta = {"adder", (int64_t)stamp, (stamp << 8) | (uint64_t)kind, 0, false};
        if (mtd_store_add(sh->store, id, mesh, &meta, NULL, NULL, NULL) != MT_OK) {
            atomic_fetch_add(&sh->failures, 1);
            mt_mesh_destroy(mesh);
            continue;
        }
        atomic_fetch_add(&sh->adds, 1);
    }
    atomic_fetch_sub(&sh->adders_left, 1);
    return NULL;
}

static void *getter(void *arg)
{
    shared *sh = arg;
    unsigned seed = (unsigned)(uintptr_t)&seed;
    mtd_mesh_entry *held = NULL; /* kept across iterations, while others remove it */
    for (long n = 0; atomic_load(&sh->adders_left) > 0 || n < 100; n++) {
        char id[8];
        id_name(id, (unsigned)rand_r(&seed));
        mtd_mesh_entry *e = NULL;
        if (mtd_store_acquire(sh->store, id, 0, &e, NULL) != MT_OK) continue;
        atomic_fetch_add(&sh->acquires, 1);
        if (!entry_consistent(e, n % 16 == 0) || strcmp(mtd_entry_info(e)->id, id) != 0)
            atomic_fetch_add(&sh->failures, 1);
        /* An older version, when still held, is that exact version. */
        uint32_t v = mtd_entry_info(e)->version;
        mtd_mesh_entry *old = NULL;
        if (v > 1 && mtd_store_acquire(sh->store, id, v - 1, &old, NULL) == MT_OK) {
            if (mtd_entry_info(old)->version != v - 1 || !entry_consistent(old, 0))
                atomic_fetch_add(&sh->failures, 1);
            mtd_entry_release(old);
        }
        if (held && !entry_consistent(held, n % 8 == 0)) atomic_fetch_add(&sh->failures, 1);
        if (n % 4 == 0) {
            mtd_entry_release(held);
            held = e;
        } else {
            mtd_entry_release(e);
        }
    }
    mtd_entry_release(held);
    return NULL;
}

static void check_listing(shared *sh)
{
    mtd_store_listing *listing = NULL;
    if (mtd_store_list(sh->store, &listing) != MT_OK) {
        atomic_fetch_add(&sh->failures, 1);
        return;
    }
    size_t versions = 0, bytes = 0;
    for (size_t i = 0; i < listing->num_ids; i++) {
        const mtd_listed_id *row = &listing->ids[i];
        if (i > 0 && strcmp(listing->ids[i - 1].id, row->id) >= 0)
            atomic_fetch_add(&sh->failures, 1);
        if (row->num_versions == 0) atomic_fetch_add(&sh->failures, 1);
        for (uint32_t v = 0; v < row->num_versions; v++) {
            if (v > 0 && row->versions[v - 1].version >= row->versions[v].version)
                atomic_fetch_add(&sh->failures, 1);
            bytes += row->versions[v].memory_bytes;
        }
        versions += row->num_versions;
    }
    if (versions != listing->totals.versions || bytes != listing->totals.memory_bytes ||
        listing->num_ids != listing->totals.ids)
        atomic_fetch_add(&sh->failures, 1);
    mtd_store_listing_free(listing);
}

static void *remover(void *arg)
{
    shared *sh = arg;
    unsigned seed = (unsigned)(uintptr_t)&seed;
    for (long n = 0; atomic_load(&sh->adders_left) > 0 || n < 200; n++) {
        char id[8];
        id_name(id, (unsigned)rand_r(&seed));
        mtd_mesh_entry *e = NULL;
        if (mtd_store_acquire(sh->store, id, 0, &e, NULL) == MT_OK) {
            uint32_t v = mtd_entry_info(e)->version;
            mtd_entry_release(e);
            /* Mostly an older version, sometimes the latest. */
            uint32_t target = (rand_r(&seed) % 3 == 0 || v == 1) ? v : v - 1;
            mt_status s = mtd_store_remove(sh->store, id, target, NULL);
            if (s == MT_OK)
                atomic_fetch_add(&sh->removals, 1);
            else if (s != MT_ERR_NOT_FOUND)
                atomic_fetch_add(&sh->failures, 1);
        }
        if (n % 32 == 0) check_listing(sh);
    }
    return NULL;
}

static void test_store_concurrent(void)
{
    shared sh;
    memset(&sh, 0, sizeof sh);
    atomic_init(&sh.adders_left, ADDERS);
    mtd_store_options opt = {0};
    opt.on_entry_free = count_free;
    opt.on_entry_free_ctx = &sh;
    CHECK_OK(mtd_store_create(&opt, &sh.store));
    if (!sh.store) return;

    pthread_t threads[ADDERS + GETTERS + REMOVERS];
    int n = 0;
    for (int i = 0; i < ADDERS; i++) CHECK_EQ(pthread_create(&threads[n++], NULL, adder, &sh), 0);
    for (int i = 0; i < GETTERS; i++) CHECK_EQ(pthread_create(&threads[n++], NULL, getter, &sh), 0);
    for (int i = 0; i < REMOVERS; i++)
        CHECK_EQ(pthread_create(&threads[n++], NULL, remover, &sh), 0);
    for (int i = 0; i < n; i++) pthread_join(threads[i], NULL);

    CHECK_EQ(atomic_load(&sh.failures), 0);
    CHECK_EQ(atomic_load(&sh.adds), ADDERS * ADDS_PER_ADDER);
    CHECK(atomic_load(&sh.removals) > 0);
    CHECK(atomic_load(&sh.acquires) > 0);
    mtd_store_totals t;
    mtd_store_get_totals(sh.store, &t);
    CHECK_EQ(t.versions, atomic_load(&sh.adds) - atomic_load(&sh.removals));
    CHECK_EQ(atomic_load(&sh.frees), atomic_load(&sh.removals)); /* nothing is held any more */
    check_listing(&sh);
    CHECK_EQ(atomic_load(&sh.failures), 0);

    /* Versions of each id are 1.. in add order: the highest held is at most
     * the number of adds, and the latest is the highest. */
    for (unsigned i = 0; i < NUM_IDS; i++) {
        char id[8];
        id_name(id, i);
        mtd_mesh_entry *e = NULL;
        if (mtd_store_acquire(sh.store, id, 0, &e, NULL) != MT_OK) continue;
        CHECK(mtd_entry_info(e)->version <= (uint32_t)(ADDERS * ADDS_PER_ADDER));
        CHECK(entry_consistent(e, 1));
        mtd_entry_release(e);
    }
    mtd_store_destroy(sh.store);
    CHECK_EQ(atomic_load(&sh.frees), atomic_load(&sh.adds));
}

static const mt_test_case cases[] = {
    {"store_concurrent", test_store_concurrent},
};
const mt_test_table mt_tests_store_concurrency = {cases, sizeof cases / sizeof cases[0]};
