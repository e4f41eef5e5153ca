/* Request cache tests: a finished request is answered from the cache with
 * its exact bytes, a running one is reported pending (and abandoning it lets
 * a retry run it), the key is (channel, id) as a pair, the oldest answered
 * requests are evicted by count and by bytes while pending ones stay, a
 * reply outlives its eviction while held, and racing copies of one request
 * start it exactly once. */
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "daemon_test_util.h"
#include "harness.h"
#include "request_cache.h"

static mtd_reqcache *cache_new(size_t max_entries, size_t max_bytes)
{
    mtd_reqcache_options opt = {max_entries, max_bytes};
    mtd_reqcache *cache = NULL;
    CHECK_OK(mtd_reqcache_create(&opt, &cache));
    return cache;
}

/* begin() and return the state; a DONE reply is compared with `expect`
 * (NULL: not expected to be DONE). */
static mtd_request_state begin(mtd_reqcache *cache, const char *channel, int64_t id,
                               const char *expect, int line)
{
    mtd_request_state state = MTD_REQUEST_NEW;
    mtd_reply *reply = NULL;
    mt_status s = mtd_reqcache_begin(cache, channel, id, &state, &reply);
    if (s != MT_OK) mt_test_fail(__FILE__, line, "begin: %s", mt_strerror(s));
    if (state == MTD_REQUEST_DONE) {
        if (!reply) {
            mt_test_fail(__FILE__, line, "DONE without a reply");
        } else if (!expect) {
            mt_test_fail(__FILE__, line, "unexpected stored reply");
        } else if (mtd_reply_size(reply) != strlen(expect) ||
                   memcmp(mtd_reply_data(reply), expect, strlen(expect)) != 0) {
            mt_test_fail(__FILE__, line, "stored reply differs from '%s'", expect);
        }
    } else if (reply) {
        mt_test_fail(__FILE__, line, "a reply came back with state %d", (int)state);
    }
    mtd_reply_release(reply);
    return state;
}
#define BEGIN(cache, channel, id, expect) begin((cache), (channel), (id), (expect), __LINE__)

static void finish(mtd_reqcache *cache, const char *channel, int64_t id, const char *reply)
{
    CHECK_OK(mtd_reqcache_finish(cache, channel, id, reply, strlen(reply)));
}

static void test_reqcache_hit(void)
{
    mtd_reqcache *cache = cache_new(0, 0);
    if (!cache) return;
    CHECK_EQ(BEGIN(cache, "NODE_A_REPLY", 7, NULL), MTD_REQUEST_NEW);
    finish(cache, "NODE_A_REPLY", 7, "reply seven");
    CHECK_EQ(BEGIN(cache, "NODE_A_REPLY", 7, "reply seven"), MTD_REQUEST_DONE);
    CHECK_EQ(BEGIN(cache, "NODE_A_REPLY", 7, "reply seven"), MTD_REQUEST_DONE);
    /* The key is the pair: another channel or another id is a new request. */
    CHECK_EQ(BEGIN(cache, "NODE_B_REPLY", 7, NULL), MTD_REQUEST_NEW);
    CHECK_EQ(BEGIN(cache, "NODE_A_REPLY", 8, NULL), MTD_REQUEST_NEW);
    CHECK_EQ(BEGIN(cache, "NODE_A_REPLY", -7, NULL), MTD_REQUEST_NEW);
    CHECK_EQ(BEGIN(cache, "NODE_A_REPL", 7, NULL), MTD_REQUEST_NEW);
    /* A second finish keeps the reply that was sent first. */
    finish(cache, "NODE_A_REPLY", 7, "another answer");
    CHECK_EQ(BEGIN(cache, "NODE_A_REPLY", 7, "reply seven"), MTD_REQUEST_DONE);
    /* Finish without begin remembers the reply too; empty replies are kept. */
    finish(cache, "NODE_C_REPLY", INT64_MIN, "");
    CHECK_EQ(BEGIN(cache, "NODE_C_REPLY", INT64_MIN, ""), MTD_REQUEST_DONE);

    mtd_reqcache_stats st;
    mtd_reqcache_get_stats(cache, &st);
    CHECK_EQ(st.entries, 6);
    CHECK_EQ(st.pending, 4);
    CHECK_EQ(st.done_hits, 4);
    CHECK_EQ(st.new_requests, 5);
    CHECK_EQ(st.evictions, 0);
    mtd_reqcache_destroy(cache);
    mtd_reqcache_destroy(NULL);
}

static void test_reqcache_pending(void)
{
    mtd_reqcache *cache = cache_new(0, 0);
    if (!cache) return;
    CHECK_EQ(BEGIN(cache, "R", 1, NULL), MTD_REQUEST_NEW);
    CHECK_EQ(BEGIN(cache, "R", 1, NULL), MTD_REQUEST_PENDING); /* a retry while it runs */
    CHECK_EQ(BEGIN(cache, "R", 1, NULL), MTD_REQUEST_PENDING);
    mtd_reqcache_stats st;
    mtd_reqcache_get_stats(cache, &st);
    CHECK_EQ(st.pending_hits, 2);
    CHECK_EQ(st.pending, 1);
    finish(cache, "R", 1, "one");
    CHECK_EQ(BEGIN(cache, "R", 1, "one"), MTD_REQUEST_DONE);

    /* Abandoned: the next copy runs it again. */
    CHECK_EQ(BEGIN(cache, "R", 2, NULL), MTD_REQUEST_NEW);
    mtd_reqcache_abandon(cache, "R", 2);
    CHECK_EQ(BEGIN(cache, "R", 2, NULL), MTD_REQUEST_NEW);
    /* Abandon leaves an answered request alone. */
    mtd_reqcache_abandon(cache, "R", 1);
    CHECK_EQ(BEGIN(cache, "R", 1, "one"), MTD_REQUEST_DONE);
    mtd_reqcache_abandon(cache, "R", 99); /* unknown: nothing happens */
    mtd_reqcache_get_stats(cache, &st);
    CHECK_EQ(st.entries, 2);
    CHECK_EQ(st.pending, 1);
    mtd_reqcache_destroy(cache); /* with a request still pending */
}

static void test_reqcache_evict_count(void)
{
    mtd_reqcache *cache = cache_new(3, 0);
    if (!cache) return;
    char reply[32];
    for (int64_t id = 1; id <= 5; id++) {
        CHECK_EQ(BEGIN(cache, "R", id, NULL), MTD_REQUEST_NEW);
        snprintf(reply, sizeof reply, "reply %d", (int)id);
        finish(cache, "R", id, reply);
    }
    mtd_reqcache_stats st;
    mtd_reqcache_get_stats(cache, &st);
    CHECK_EQ(st.entries, 3);
    CHECK_EQ(st.evictions, 2);
    /* 1 and 2 are gone (oldest first); 3, 4 and 5 answer from the cache. */
    CHECK_EQ(BEGIN(cache, "R", 3, "reply 3"), MTD_REQUEST_DONE);
    CHECK_EQ(BEGIN(cache, "R", 4, "reply 4"), MTD_REQUEST_DONE);
    CHECK_EQ(BEGIN(cache, "R", 5, "reply 5"), MTD_REQUEST_DONE);
    CHECK_EQ(BEGIN(cache, "R", 1, NULL), MTD_REQUEST_NEW); /* evicts 3 */
    CHECK_EQ(BEGIN(cache, "R", 3, NULL), MTD_REQUEST_NEW); /* evicts 4 */
    CHECK_EQ(BEGIN(cache, "R", 5, "reply 5"), MTD_REQUEST_DONE);
    mtd_reqcache_get_stats(cache, &st);
    CHECK_EQ(st.entries, 3);
    CHECK_EQ(st.pending, 2);
    CHECK_EQ(st.evictions, 4);
    mtd_reqcache_destroy(cache);
}

static void test_reqcache_pending_not_evicted(void)
{
    mtd_reqcache *cache = cache_new(2, 0);
    if (!cache) return;
    CHECK_EQ(BEGIN(cache, "R", 1, NULL), MTD_REQUEST_NEW);
    CHECK_EQ(BEGIN(cache, "R", 2, NULL), MTD_REQUEST_NEW);
    CHECK_EQ(BEGIN(cache, "R", 3, NULL), MTD_REQUEST_NEW); /* all pending: over the count */
    mtd_reqcache_stats st;
    mtd_reqcache_get_stats(cache, &st);
    CHECK_EQ(st.entries, 3);
    CHECK_EQ(st.evictions, 0);
    CHECK_EQ(BEGIN(cache, "R", 1, NULL), MTD_REQUEST_PENDING);
    CHECK_EQ(BEGIN(cache, "R", 2, NULL), MTD_REQUEST_PENDING);
    /* The request just answered is never the one evicted, and pending ones
     * are not evicted: with nothing else answered the cache stays over. */
    finish(cache, "R", 2, "two");
    CHECK_EQ(BEGIN(cache, "R", 2, "two"), MTD_REQUEST_DONE);
    /* Answering 3 makes room by evicting 2, the oldest answered one; 1 stays. */
    finish(cache, "R", 3, "three");
    CHECK_EQ(BEGIN(cache, "R", 1, NULL), MTD_REQUEST_PENDING);
    CHECK_EQ(BEGIN(cache, "R", 3, "three"), MTD_REQUEST_DONE);
    mtd_reqcache_get_stats(cache, &st);
    CHECK_EQ(st.entries, 2);
    CHECK_EQ(st.evictions, 1);
    CHECK_EQ(BEGIN(cache, "R", 2, NULL), MTD_REQUEST_NEW);
    mtd_reqcache_destroy(cache);
}

/* Answers older than the age given are forgotten, oldest first; pending
 * requests and younger answers stay. */
static void test_reqcache_expire(void)
{
    mtd_reqcache *cache = cache_new(0, 0);
    if (!cache) return;
    CHECK_EQ(BEGIN(cache, "R", 1, NULL), MTD_REQUEST_NEW);
    finish(cache, "R", 1, "one");
    CHECK_EQ(BEGIN(cache, "R", 2, NULL), MTD_REQUEST_NEW); /* left pending */
    CHECK_EQ(BEGIN(cache, "R", 3, NULL), MTD_REQUEST_NEW);
    finish(cache, "R", 3, "three");
    int64_t now = mtd_monotonic_us();
    CHECK_EQ(mtd_reqcache_expire(cache, now, 60 * 1000000LL), 0); /* all young */
    CHECK_EQ(BEGIN(cache, "R", 1, "one"), MTD_REQUEST_DONE);
    CHECK_EQ(mtd_reqcache_expire(cache, now + 61 * 1000000LL, 60 * 1000000LL), 2);
    CHECK_EQ(BEGIN(cache, "R", 1, NULL), MTD_REQUEST_NEW);
    CHECK_EQ(BEGIN(cache, "R", 2, NULL), MTD_REQUEST_PENDING);
    CHECK_EQ(BEGIN(cache, "R", 3, NULL), MTD_REQUEST_NEW);
    mtd_reqcache_stats st;
    mtd_reqcache_get_stats(cache, &st);
    CHECK_EQ(st.evictions, 2);
    mtd_reqcache_destroy(cache);
}

static void test_reqcache_evict_bytes(void)
{
    /* Room for about two 1000-byte replies with their bookkeeping. */
    mtd_reqcache *cache = cache_new(100, 2600);
    if (!cache) return;
    char *big = malloc(1001);
    if (!big) return;
    for (int64_t id = 1; id <= 3; id++) {
        memset(big, 'a' + (int)id, 1000);
        big[1000] = '\0';
        CHECK_EQ(BEGIN(cache, "R", id, NULL), MTD_REQUEST_NEW);
        finish(cache, "R", id, big);
        mtd_reqcache_stats st;
        mtd_reqcache_get_stats(cache, &st);
        CHECK(st.bytes <= 2600);
    }
    mtd_reqcache_stats st;
    mtd_reqcache_get_stats(cache, &st);
    CHECK_EQ(st.entries, 2);
    CHECK_EQ(st.evictions, 1);
    CHECK(st.bytes > 2000);
    CHECK_EQ(BEGIN(cache, "R", 3, big), MTD_REQUEST_DONE);
    memset(big, 'c', 1000);
    CHECK_EQ(BEGIN(cache, "R", 2, big), MTD_REQUEST_DONE);
    CHECK_EQ(BEGIN(cache, "R", 1, NULL), MTD_REQUEST_NEW);
    free(big);
    mtd_reqcache_destroy(cache);
}

static void test_reqcache_too_large(void)
{
    mtd_reqcache *cache = cache_new(10, 1000);
    if (!cache) return;
    char *big = calloc(1, 2000);
    if (!big) return;
    finish(cache, "R", 1, "small");
    CHECK_EQ(BEGIN(cache, "R", 2, NULL), MTD_REQUEST_NEW);
    CHECK_STATUS(mtd_reqcache_finish(cache, "R", 2, big, 2000), MT_ERR_TOO_LARGE);
    /* Not stored, no longer pending: a retry runs it again; nothing else lost. */
    CHECK_EQ(BEGIN(cache, "R", 2, NULL), MTD_REQUEST_NEW);
    CHECK_EQ(BEGIN(cache, "R", 1, "small"), MTD_REQUEST_DONE);
    CHECK_STATUS(mtd_reqcache_finish(cache, "R", 3, big, SIZE_MAX), MT_ERR_TOO_LARGE);
    free(big);
    mtd_reqcache_destroy(cache);
}

static void test_reqcache_reply_outlives_eviction(void)
{
    mtd_reqcache *cache = cache_new(1, 0);
    if (!cache) return;
    finish(cache, "R", 1, "first reply");
    mtd_request_state state;
    mtd_reply *held = NULL;
    CHECK_OK(mtd_reqcache_begin(cache, "R", 1, &state, &held));
    CHECK_EQ(state, MTD_REQUEST_DONE);
    finish(cache, "R", 2, "second reply"); /* evicts 1 */
    CHECK_EQ(BEGIN(cache, "R", 1, NULL), MTD_REQUEST_NEW);
    if (held) {
        CHECK_EQ(mtd_reply_size(held), strlen("first reply")); /* ASan: still allocated */
        CHECK(memcmp(mtd_reply_data(held), "first reply", 11) == 0);
    }
    mtd_reqcache_destroy(cache);
    if (held) CHECK(memcmp(mtd_reply_data(held), "first reply", 11) == 0);
    mtd_reply_release(held);
    mtd_reply_release(NULL);
}

static void test_reqcache_bad_args(void)
{
    mtd_reqcache *cache = (mtd_reqcache *)(void *)&cache;
    mtd_reqcache_options opt = {MTD_REQCACHE_MAX_ENTRIES + 1, 0};
    CHECK_STATUS(mtd_reqcache_create(&opt, &cache), MT_ERR_INVALID_ARG);
    CHECK(cache == NULL);
    CHECK_OK(mtd_reqcache_create(NULL, &cache));
    if (!cache) return;
    mtd_request_state state;
    mtd_reply *reply = NULL;
    char channel[MTD_REPLY_CHANNEL_MAX + 2];
    memset(channel, 'c', sizeof channel - 1);
    channel[sizeof channel - 1] = '\0';
    CHECK_STATUS(mtd_reqcache_begin(cache, NULL, 1, &state, &reply), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mtd_reqcache_begin(cache, "", 1, &state, &reply), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mtd_reqcache_begin(cache, channel, 1, &state, &reply), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mtd_reqcache_finish(cache, channel, 1, "x", 1), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mtd_reqcache_finish(cache, "R", 1, NULL, 1), MT_ERR_INVALID_ARG);
    channel[MTD_REPLY_CHANNEL_MAX] = '\0'; /* exactly the limit */
    CHECK_OK(mtd_reqcache_begin(cache, channel, 1, &state, &reply));
    CHECK_EQ(state, MTD_REQUEST_NEW);
    mtd_reqcache_stats st;
    mtd_reqcache_get_stats(cache, &st);
    CHECK_EQ(st.entries, 1);
    mtd_reqcache_destroy(cache);
}

/* Many threads deliver copies of the same requests: each request is NEW
 * exactly once; the thread that got NEW answers it; every DONE carries the
 * right bytes. */
#define RACE_THREADS 6
#define RACE_REQUESTS 400

typedef struct race {
    mtd_reqcache *cache;
    atomic_int new_count[RACE_REQUESTS];
    atomic_int wrong;
} race;

static void *race_thread(void *arg)
{
    race *r = arg;
    char expect[32];
    for (int round = 0; round < 3; round++) {
        for (int i = 0; i < RACE_REQUESTS; i++) {
            const char *channel = (i % 2) ? "NODE_ODD" : "NODE_EVEN";
            mtd_request_state state;
            mtd_reply *reply = NULL;
            if (mtd_reqcache_begin(r->cache, channel, i, &state, &reply) != MT_OK) {
                atomic_fetch_add(&r->wrong, 1);
                continue;
            }
            snprintf(expect, sizeof expect, "answer %d", i);
            if (state == MTD_REQUEST_NEW) {
                atomic_fetch_add(&r->new_count[i], 1);
                if (mtd_reqcache_finish(r->cache, channel, i, expect, strlen(expect)) != MT_OK)
                    atomic_fetch_add(&r->wrong, 1);
            } else if (state == MTD_REQUEST_DONE) {
                if (mtd_reply_size(reply) != strlen(expect) ||
                    memcmp(mtd_reply_data(reply), expect, strlen(expect)) != 0)
                    atomic_fetch_add(&r->wrong, 1);
            }
            mtd_reply_release(reply);
        }
    }
    return NULL;
}

static void test_reqcache_concurrent(void)
{
    race *r = calloc(1, sizeof *r);
    if (!r) return;
    r->cache = cache_new(RACE_REQUESTS, 0); /* large enough: nothing is evicted */
    if (!r->cache) {
        free(r);
        return;
    }
    pthread_t t[RACE_THREADS];
    for (int i = 0; i < RACE_THREADS; i++) CHECK_EQ(pthread_create(&t[i], NULL, race_thread, r), 0);
    for (int i = 0; i < RACE_THREADS; i++) pthread_join(t[i], NULL);
    CHECK_EQ(atomic_load(&r->wrong), 0);
    for (int i = 0; i < RACE_REQUESTS; i++)
        if (atomic_load(&r->new_count[i]) != 1)
            mt_test_fail(__FILE__, __LINE__, "request %d started %d times", i,
                         atomic_load(&r->new_count[i]));
    mtd_reqcache_stats st;
    mtd_reqcache_get_stats(r->cache, &st);
    CHECK_EQ(st.entries, RACE_REQUESTS);
    CHECK_EQ(st.pending, 0);
    CHECK_EQ(st.new_requests, RACE_REQUESTS);
    CHECK_EQ(st.new_requests + st.pending_hits + st.done_hits, 3 * RACE_THREADS * RACE_REQUESTS);
    mtd_reqcache_destroy(r->cache);
    free(r);
}

static const mt_test_case cases[] = {
    {"reqcache_hit", test_reqcache_hit},
    {"reqcache_pending", test_reqcache_pending},
    {"reqcache_evict_count", test_reqcache_evict_count},
    {"reqcache_expire", test_reqcache_expire},
    {"reqcache_pending_not_evicted", test_reqcache_pending_not_evicted},
    {"reqcache_evict_bytes", test_reqcache_evict_bytes},
    {"reqcache_too_large", test_reqcache_too_large},
    {"reqcache_reply_outlives_eviction", test_reqcache_reply_outlives_eviction},
    {"reqcache_bad_args", test_reqcache_bad_args},
    {"reqcache_concurrent", test_reqcache_concurrent},
};
const mt_test_table mt_tests_request_cache = {cases, sizeof cases / sizeof cases[0]};
