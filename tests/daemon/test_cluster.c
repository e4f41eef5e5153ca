/* Tests of meshtopod's cluster membership (daemon/cluster.c) on a made-up
 * clock: rendezvous shares are near even, a member joining or leaving moves
 * only the ids it wins or held, members that hear each other agree on the
 * owner of every id, heartbeats of other clusters are not members, silent
 * members leave after the expiry, and the testing option that ignores one
 * member gives two views that disagree. */
#include <stdio.h>
#include <string.h>

#include "cluster.h"
#include "harness.h"

#define MS 1000LL
#define T0 (100 * 1000 * MS)
#define EXPIRY (2000 * MS)

static const char *const instances[] = {"alpha:101:1700000000000001", "beta:202:1700000000000002",
                                        "gamma:303:1700000000000003", "delta:404:1700000000000004"};

static void id_of(int k, char *id, size_t size)
{
    snprintf(id, size, "robot-%d/scan", k);
}

static void shares_even(void)
{
    for (size_t members = 2; members <= 4; members++) {
        for (int ids = 300; ids <= 30000; ids *= 100) {
            int owned[4] = {0};
            for (int k = 0; k < ids; k++) {
                char id[32];
                id_of(k, id, sizeof id);
                owned[mtd_cluster_owner_of(instances, members, id)]++;
            }
            const double even = (double)ids / (double)members;
            const double slack = ids == 300 ? 0.25 : 0.05;
            for (size_t m = 0; m < members; m++) {
                CHECK(owned[m] >= even * (1 - slack) && owned[m] <= even * (1 + slack));
                if (!(owned[m] >= even * (1 - slack) && owned[m] <= even * (1 + slack)))
                    printf("%zu members, %d ids: member %zu owns %d (even %.0f)\n", members, ids, m,
                           owned[m], even);
            }
        }
    }
}

static void minimal_movement(void)
{
    /* Three members, then gamma gone, then delta joined. */
    const char *const three[] = {instances[0], instances[1], instances[2]};
    const char *const two[] = {instances[0], instances[1]};
    const char *const joined[] = {instances[0], instances[1], instances[2], instances[3]};
    int moved_leave = 0, moved_join = 0;
    for (int k = 0; k < 3000; k++) {
        char id[32];
        id_of(k, id, sizeof id);
        size_t before = mtd_cluster_owner_of(three, 3, id);
        size_t after_leave = mtd_cluster_owner_of(two, 2, id);
        size_t after_join = mtd_cluster_owner_of(joined, 4, id);
        if (before != 2) CHECK_EQ(after_leave, before); /* only gamma's ids move */
        moved_leave += before != after_leave;
        if (after_join != 3) CHECK_EQ(after_join, before); /* only delta's win move */
        moved_join += after_join != before;
    }
    /* About a third, then about a quarter, of the ids moved. */
    CHECK(moved_leave > 800 && moved_leave < 1200);
    CHECK(moved_join > 550 && moved_join < 950);
}

static mtd_cluster *member(int k, const char *ignored)
{
    char name[16];
    snprintf(name, sizeof name, "m%d", k);
    mtd_cluster_options o = {.name = "mapping",
                             .instance = instances[k],
                             .member_name = name,
                             .expiry_us = EXPIRY,
                             .ignored_name = ignored};
    mtd_cluster *c = NULL;
    CHECK_OK(mtd_cluster_create(&o, &c));
    return c;
}

/* Each cluster of cs hears every other's heartbeat at `now`. */
static void hear_all(mtd_cluster **cs, int n, int64_t now)
{
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            char name[16];
            snprintf(name, sizeof name, "m%d", b);
            CHECK(mtd_cluster_heard(cs[a], "mapping", instances[b], name, now));
        }
}

/* Ids owned by exactly one of cs, of 1000. */
static int owned_once(mtd_cluster **cs, int n, int *owners_per_id_max)
{
    int once = 0, most = 0;
    for (int k = 0; k < 1000; k++) {
        char id[32];
        id_of(k, id, sizeof id);
        int owners = 0;
        for (int i = 0; i < n; i++) owners += mtd_cluster_owns(cs[i], id);
        once += owners == 1;
        if (owners > most) most = owners;
    }
    *owners_per_id_max = most;
    return once;
}

static void members_agree_and_expire(void)
{
    mtd_cluster *cs[3] = {member(0, NULL), member(1, NULL), member(2, NULL)};
    if (!cs[0] || !cs[1] || !cs[2]) return;
    int most = 0;
    /* Alone, each owns everything. */
    CHECK_EQ(owned_once(cs, 1, &most), 1000);
    CHECK(!mtd_cluster_refresh(cs[0], T0));
    hear_all(cs, 3, T0);
    for (int i = 0; i < 3; i++) CHECK(mtd_cluster_refresh(cs[i], T0)); /* joins changed it */
    CHECK(!mtd_cluster_refresh(cs[0], T0 + MS));
    CHECK_EQ(owned_once(cs, 3, &most), 1000);
    CHECK_EQ(most, 1);
    mtd_cluster_view v0, v1;
    mtd_cluster_get_view(cs[0], &v0);
    mtd_cluster_get_view(cs[1], &v1);
    CHECK_EQ(v0.members, 3);
    CHECK(v0.hash == v1.hash && v0.hash != 0);
    CHECK(v0.share > 0.28 && v0.share < 0.39);
    CHECK(strstr(v0.names, "m1 (beta:202:") != NULL);

    /* Another cluster's daemon, or one without a cluster, is not a member. */
    CHECK(!mtd_cluster_heard(cs[0], "other", instances[3], "x", T0));
    CHECK(!mtd_cluster_heard(cs[0], "", instances[3], "x", T0));
    CHECK(!mtd_cluster_refresh(cs[0], T0 + 2 * MS));

    /* m2 goes silent: the others drop it after the expiry, not before, and
     * then own every id between them. */
    for (int64_t t = T0 + 500 * MS; t <= T0 + EXPIRY; t += 500 * MS) {
        hear_all(cs, 2, t);
        CHECK(!mtd_cluster_refresh(cs[0], t));
    }
    CHECK(mtd_cluster_refresh(cs[0], T0 + EXPIRY + 1));
    CHECK(mtd_cluster_refresh(cs[1], T0 + EXPIRY + 1));
    CHECK_EQ(owned_once(cs, 2, &most), 1000);
    mtd_cluster_get_view(cs[0], &v0);
    mtd_cluster_get_view(cs[1], &v1);
    CHECK_EQ(v0.members, 2);
    CHECK(v0.hash == v1.hash);
    /* Everyone else silent: the member itself stays, owning every id. */
    CHECK(mtd_cluster_refresh(cs[0], T0 + 100 * EXPIRY));
    mtd_cluster_get_view(cs[0], &v0);
    CHECK_EQ(v0.members, 1);
    CHECK(v0.share == 1.0);
    for (int i = 0; i < 3; i++) mtd_cluster_destroy(cs[i]);
}

static void ignored_member_disagrees(void)
{
    /* m0 ignores m1's heartbeats; m1 hears m0: m0 believes it owns every id,
     * m1 owns about half, and those are owned twice. */
    mtd_cluster *cs[2] = {member(0, "m1"), member(1, NULL)};
    if (!cs[0] || !cs[1]) return;
    hear_all(cs, 2, T0);
    mtd_cluster_view v0, v1;
    mtd_cluster_get_view(cs[0], &v0);
    mtd_cluster_get_view(cs[1], &v1);
    CHECK_EQ(v0.members, 1);
    CHECK_EQ(v1.members, 2);
    CHECK(v0.hash != v1.hash);
    int most = 0;
    int once = owned_once(cs, 2, &most);
    CHECK_EQ(most, 2);
    CHECK(once > 350 && once < 650);
    for (int i = 0; i < 2; i++) mtd_cluster_destroy(cs[i]);
}

/* A node forging heartbeats of the cluster under many instances: the
 * membership stays within MTD_CLUSTER_MAX_MEMBERS (memory bounded), the
 * forged members leave once they stop beating, and the view is whole again. */
static void forged_members_bounded(void)
{
    mtd_cluster *c = member(0, NULL);
    if (!c) return;
    for (int k = 0; k < 1000; k++) {
        char instance[64];
        snprintf(instance, sizeof instance, "forged:%d:1700000000000000", k);
        CHECK(mtd_cluster_heard(c, "mapping", instance, "forged", T0));
    }
    mtd_cluster_view v;
    mtd_cluster_get_view(c, &v);
    CHECK_EQ(v.members, MTD_CLUSTER_MAX_MEMBERS);
    CHECK(v.share < 0.05); /* the forgers took most ids: the documented risk */
    CHECK(mtd_cluster_refresh(c, T0 + EXPIRY + 1));
    mtd_cluster_get_view(c, &v);
    CHECK_EQ(v.members, 1);
    CHECK(v.share == 1.0);
    mtd_cluster_destroy(c);
}

static void refuses_bad_options(void)
{
    mtd_cluster *c = NULL;
    mtd_cluster_options o = {.name = "", .instance = instances[0], .expiry_us = EXPIRY};
    CHECK_STATUS(mtd_cluster_create(&o, &c), MT_ERR_INVALID_ARG);
    o.name = "mapping";
    o.instance = NULL;
    CHECK_STATUS(mtd_cluster_create(&o, &c), MT_ERR_INVALID_ARG);
    CHECK(c == NULL);
    CHECK(mtd_cluster_owns(NULL, "anything"));
}

static const mt_test_case cases[] = {
    {"shares_even", shares_even},
    {"minimal_movement", minimal_movement},
    {"members_agree_and_expire", members_agree_and_expire},
    {"ignored_member_disagrees", ignored_member_disagrees},
    {"forged_members_bounded", forged_members_bounded},
    {"refuses_bad_options", refuses_bad_options},
};
const mt_test_table mt_tests_cluster = {cases, sizeof cases / sizeof cases[0]};
