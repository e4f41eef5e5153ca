/* Tests of meshtopod's fair share of query work (daemon/fair_share.c) on a
 * made-up clock: a sender alone may use all of it; while the thread is
 * busy, one over its share of the window among the active senders is
 * refused with the figures, the others are not; charges decay with the
 * sliding window. */
#include <string.h>

#include "fair_share.h"
#include "harness.h"

#define MS 1000LL
#define T0 (100 * 1000 * MS) /* some monotonic time */

static void alone_uses_everything(void)
{
    mtd_fair_share *s;
    CHECK_OK(mtd_fair_share_create(&s));
    char why[256];
    CHECK(mtd_fair_share_allowed(s, "A", T0, why, sizeof why));
    mtd_fair_share_charge(s, "A", T0 + 900 * MS, 900 * MS);
    CHECK(mtd_fair_share_allowed(s, "A", T0 + 901 * MS, why, sizeof why));
    mtd_fair_share_destroy(s);
}

static void busy_thread_shared(void)
{
    mtd_fair_share *s;
    CHECK_OK(mtd_fair_share_create(&s));
    char why[256] = "";
    mtd_fair_share_charge(s, "FLOOD", T0 + 100 * MS, 800 * MS);
    mtd_fair_share_charge(s, "ROBOT", T0 + 110 * MS, 10 * MS);
    CHECK(!mtd_fair_share_allowed(s, "FLOOD", T0 + 120 * MS, why, sizeof why));
    CHECK(strstr(why, "'FLOOD' used 800 ms") != NULL);
    CHECK(strstr(why, "share of 500 ms among 2 senders") != NULL);
    CHECK(mtd_fair_share_allowed(s, "ROBOT", T0 + 120 * MS, why, sizeof why));
    CHECK(mtd_fair_share_allowed(s, "NEWCOMER", T0 + 120 * MS, why, sizeof why));
    /* A third active sender shrinks the share. */
    mtd_fair_share_charge(s, "THIRD", T0 + 130 * MS, 1 * MS);
    CHECK(!mtd_fair_share_allowed(s, "FLOOD", T0 + 140 * MS, why, sizeof why));
    CHECK(strstr(why, "among 3 senders") != NULL);
    mtd_fair_share_destroy(s);
}

static void idle_thread_not_shared(void)
{
    mtd_fair_share *s;
    CHECK_OK(mtd_fair_share_create(&s));
    char why[256];
    mtd_fair_share_charge(s, "BIG", T0 + 100 * MS, 400 * MS);
    mtd_fair_share_charge(s, "SMALL", T0 + 110 * MS, 10 * MS);
    /* 410 ms of a second: the thread has room, nobody is refused. */
    CHECK(mtd_fair_share_allowed(s, "BIG", T0 + 120 * MS, why, sizeof why));
    mtd_fair_share_destroy(s);
}

static void charges_decay(void)
{
    mtd_fair_share *s;
    CHECK_OK(mtd_fair_share_create(&s));
    char why[256];
    int64_t start = T0 - T0 % (1000 * MS); /* a bucket boundary */
    mtd_fair_share_charge(s, "FLOOD", start + 900 * MS, 900 * MS);
    mtd_fair_share_charge(s, "ROBOT", start + 910 * MS, 5 * MS);
    CHECK(!mtd_fair_share_allowed(s, "FLOOD", start + 950 * MS, why, sizeof why));
    /* Half a second into the next bucket half the charge is left: 450 ms. */
    CHECK(mtd_fair_share_allowed(s, "FLOOD", start + 1500 * MS, why, sizeof why));
    /* Two idle seconds later nothing is left. */
    mtd_fair_share_charge(s, "ROBOT", start + 3100 * MS, 5 * MS);
    mtd_fair_share_charge(s, "FLOOD", start + 3100 * MS, 499 * MS);
    CHECK(mtd_fair_share_allowed(s, "FLOOD", start + 3200 * MS, why, sizeof why));
    mtd_fair_share_destroy(s);
}

static const mt_test_case cases[] = {
    {"alone_uses_everything", alone_uses_everything},
    {"busy_thread_shared", busy_thread_shared},
    {"idle_thread_not_shared", idle_thread_not_shared},
    {"charges_decay", charges_decay},
};
const mt_test_table mt_tests_fair_share = {cases, sizeof cases / sizeof cases[0]};
