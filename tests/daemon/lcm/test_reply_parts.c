/* Large answers in parts (msgs/reply_part_t.lcm, reply_pull_t.lcm) over
 * in-process LCM (memq://). Against a scripted daemon (the test answers the
 * queries itself): parts out of order and duplicated, parts lost and pulled
 * again, parts that lie about their offset, length or answer (ignored and
 * counted), a reassembled answer whose hash is wrong (asked for again), the
 * client's reassembly memory cap (TOO_LARGE). Against the real daemon: the
 * one-rings of every vertex of a grid and the boundary loops of a grid with
 * many holes through mt_client_query, mt_client_query_async and
 * mt_client_list, equal to the core's; and pulls sent by hand (windows,
 * limits, unknown requests, another answer). */
#include <inttypes.h>
#include <lcm/lcm.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "daemon.h"
#include "harness.h"
#include "log.h"
#include "meshtopo/answer_hash.h"
#include "meshtopo/client.h"
#include "meshtopo/core.h"
#include "parts_expect.h"

/* ---- A scripted daemon ---------------------------------------------------- */

#define FAKE_PART 4000
#define FAKE_MAX_PARTS 1024

typedef struct fake {
    lcm_t *lcm;
    int32_t num_items; /* the VALENCE answer has this many items */
    /* Script. */
    bool all_at_once;    /* every part with the answer (else the first 16) */
    bool reverse, twice; /* order and duplicates of that first send */
    bool lie;            /* lying parts before the real ones */
    bool bad_hash_first; /* the first query's parts announce a wrong hash */
    int drop_first[8];   /* parts lost the first time they are sent (-1 = none) */
    /* What happened. */
    int queries, pulls, pulled_parts;
    uint8_t sent[FAKE_MAX_PARTS];
    uint8_t *answer;
    size_t size;
    /* All of the above: the fake's handler runs on the client's thread, the
     * test reads and changes the script between calls. */
    pthread_mutex_t lock;
} fake;

/* The answer to a query: a VALENCE reply_t with num_items items of one value. */
static void fake_answer(fake *f, int64_t request_id)
{
    int32_t n = f->num_items;
    int8_t *item_status = calloc((size_t)n, 1);
    uint8_t *boundary = calloc((size_t)n, 1);
    int32_t *offsets = malloc(((size_t)n + 1) * sizeof *offsets);
    int32_t *values = malloc((size_t)n * sizeof *values);
    for (int32_t i = 0; i <= n; i++) offsets[i] = i;
    for (int32_t i = 0; i < n; i++) values[i] = (int32_t)((uint32_t)i * 2654435761u >> 8);
    meshtopo_reply_t r;
    memset(&r, 0, sizeof r);
    r.utime = 1700000000000000;
    r.request_id = request_id;
    r.error = "";
    r.mesh_id = "scripted";
    r.version = 1;
    r.kind = MESHTOPO_QUERY_T_VALENCE;
    r.num_items = n;
    r.item_status = item_status;
    r.num_item_offsets = n + 1;
    r.item_offsets = offsets;
    r.num_groups = n;
    r.group_boundary = (int8_t *)boundary;
    r.num_value_offsets = n + 1;
    r.value_offsets = offsets;
    r.value2_offsets = calloc((size_t)n + 1, sizeof(int32_t));
    r.num_values = n;
    r.values = values;
    free(f->answer);
    f->size = (size_t)meshtopo_reply_t_encoded_size(&r);
    f->answer = malloc(f->size);
    CHECK_EQ(meshtopo_reply_t_encode(f->answer, 0, (int)f->size, &r), (int)f->size);
    free(item_status);
    free(boundary);
    free(offsets);
    free(values);
    free(r.value2_offsets);
}

static size_t fake_num_parts(const fake *f)
{
    return (f->size + FAKE_PART - 1) / FAKE_PART;
}

/* Publishes a part on the parts channel of reply_channel. */
static void fake_publish(fake *f, const char *reply_channel, const meshtopo_reply_part_t *part)
{
    int size = meshtopo_reply_part_t_encoded_size(part);
    void *buf = malloc((size_t)size);
    CHECK_EQ(meshtopo_reply_part_t_encode(buf, 0, size, part), size);
    char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
    CHECK_EQ(mt_msgs_reply_channel_name(reply_channel, &mt_msgs_type_reply_part, channel), MT_OK);
    CHECK_EQ(lcm_publish(f->lcm, channel, buf, (unsigned)size), 0);
    free(buf);
}

static meshtopo_reply_part_t fake_part(const fake *f, int64_t request_id, size_t k)
{
    meshtopo_reply_part_t part;
    memset(&part, 0, sizeof part);
    part.utime = 1700000000000000;
    part.request_id = request_id;
    part.total_size = (int64_t)f->size;
    part.answer_hash = (int64_t)mt_msgs_answer_hash(f->answer, f->size);
    part.part_size = FAKE_PART;
    part.offset = (int64_t)(k * FAKE_PART);
    part.length =
        (int32_t)(f->size - k * FAKE_PART < FAKE_PART ? f->size - k * FAKE_PART : FAKE_PART);
    part.data = f->answer + k * FAKE_PART;
    return part;
}

/* Sends part k unless the script loses it this time. */
static void fake_send(fake *f, const char *channel, int64_t request_id, size_t k, bool bad_hash)
{
    bool first = !f->sent[k];
    f->sent[k] = 1;
    for (int i = 0; i < 8; i++)
        if (first && f->drop_first[i] == (int)k) return;
    meshtopo_reply_part_t part = fake_part(f, request_id, k);
    if (bad_hash) part.answer_hash ^= 1;
    fake_publish(f, channel, &part);
}

static void fake_lies(fake *f, const char *channel, int64_t request_id)
{
    uint8_t junk[FAKE_PART];
    memset(junk, 0xee, sizeof junk);
    meshtopo_reply_part_t part = fake_part(f, request_id, 0);
    part.data = junk;
    part.offset = (int64_t)f->size; /* at the end */
    fake_publish(f, channel, &part);
    part.offset = FAKE_PART / 2; /* not on a part boundary */
    fake_publish(f, channel, &part);
    part.offset = (int64_t)(fake_num_parts(f) - 1) * FAKE_PART; /* the last part, too long */
    fake_publish(f, channel, &part);
    part = fake_part(f, request_id, 1);
    part.data = junk;
    part.length = 100; /* too short */
    fake_publish(f, channel, &part);
    part = fake_part(f, request_id, 2);
    part.data = junk;
    part.answer_hash ^= 0x5a5a; /* another answer */
    fake_publish(f, channel, &part);
    part = fake_part(f, request_id, 2);
    part.data = junk;
    part.total_size *= 2; /* another size */
    fake_publish(f, channel, &part);
}

static void fake_on_query(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    fake *f = user;
    pthread_mutex_lock(&f->lock);
    const mt_msgs_type *type = mt_msgs_type_of(rbuf->data, rbuf->data_size);
    if (type == &mt_msgs_type_query) {
        meshtopo_query_t q;
        CHECK_EQ(mt_msgs_decode(type, rbuf->data, rbuf->data_size, &q, NULL, 0), 0);
        bool bad_hash = f->bad_hash_first && f->queries == 0;
        f->queries++;
        fake_answer(f, q.request_id);
        if (f->lie) fake_lies(f, q.reply_channel, q.request_id);
        size_t n = fake_num_parts(f);
        size_t first = f->all_at_once || n < 16 ? n : 16;
        for (int round = 0; round < (f->twice ? 2 : 1); round++)
            for (size_t i = 0; i < first; i++)
                fake_send(f, q.reply_channel, q.request_id, f->reverse ? first - 1 - i : i,
                          bad_hash);
        meshtopo_query_t_decode_cleanup(&q);
    } else if (type == &mt_msgs_type_reply_pull) {
        meshtopo_reply_pull_t pull;
        CHECK_EQ(mt_msgs_decode(type, rbuf->data, rbuf->data_size, &pull, NULL, 0), 0);
        f->pulls++;
        CHECK_EQ(pull.total_size, (int64_t)f->size);
        /* A pull for the answer announced with a wrong hash is not answered
         * (the daemon holds no such answer). */
        bool known = pull.answer_hash == (int64_t)mt_msgs_answer_hash(f->answer, f->size);
        CHECK(known || f->bad_hash_first);
        for (int32_t i = 0; known && i < pull.num_ranges; i++) {
            CHECK(pull.offsets[i] % FAKE_PART == 0);
            CHECK(pull.lengths[i] > 0);
            for (int64_t at = pull.offsets[i]; at < pull.offsets[i] + pull.lengths[i];
                 at += FAKE_PART) {
                f->pulled_parts++;
                fake_send(f, pull.reply_channel, pull.request_id, (size_t)(at / FAKE_PART), false);
            }
        }
        meshtopo_reply_pull_t_decode_cleanup(&pull);
    }
    pthread_mutex_unlock(&f->lock);
}

static void fake_init(fake *f, int32_t num_items)
{
    memset(f, 0, sizeof *f);
    for (int i = 0; i < 8; i++) f->drop_first[i] = -1;
    f->num_items = num_items;
    pthread_mutex_init(&f->lock, NULL);
    f->lcm = lcm_create("memq://");
    CHECK(f->lcm != NULL);
    lcm_subscribe(f->lcm, "MESHTOPO_QUERY", fake_on_query, f);
    lcm_subscribe(f->lcm, "MESHTOPO_QUERY_PULL", fake_on_query, f);
}

static mt_client *fake_client(fake *f, uint64_t max_reply_bytes)
{
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm = f->lcm;
    /* Long enough that no query is sent twice on a slow (sanitized) run:
     * the tests count the queries. */
    opts.timeout_ms = 5000;
    opts.max_reply_bytes = max_reply_bytes;
    mt_client *client = NULL;
    mt_diag diag;
    CHECK_OK(mt_client_create(&opts, &client, &diag));
    return client;
}

static void fake_free(fake *f)
{
    lcm_destroy(f->lcm);
    free(f->answer);
    pthread_mutex_destroy(&f->lock);
}

/* The reply equals the scripted answer, field by field. */
static void check_fake_reply(fake *f, const meshtopo_reply_t *r, int line)
{
    meshtopo_reply_t want;
    pthread_mutex_lock(&f->lock);
    CHECK_EQ(mt_msgs_decode(&mt_msgs_type_reply, f->answer, f->size, &want, NULL, 0), 0);
    pthread_mutex_unlock(&f->lock);
    if (r->num_items != want.num_items || r->num_values != want.num_values ||
        memcmp(r->values, want.values, (size_t)want.num_values * sizeof *r->values) != 0 ||
        memcmp(r->value_offsets, want.value_offsets,
               (size_t)want.num_value_offsets * sizeof *r->value_offsets) != 0 ||
        r->request_id != want.request_id || strcmp(r->mesh_id, want.mesh_id) != 0)
        mt_test_fail(__FILE__, line, "reassembled reply differs from the answer sent");
    meshtopo_reply_t_decode_cleanup(&want);
}

static mt_status fake_query(mt_client *client, meshtopo_reply_t *out, mt_diag *diag)
{
    uint32_t id = 0;
    return mt_client_query(client, "scripted", 0, MESHTOPO_QUERY_T_VALENCE, &id, 1, out, diag);
}

/* An asynchronous call's outcome, handed from the client's thread. */
typedef struct async_wait {
    pthread_mutex_t lock;
    pthread_cond_t cond;
    int done;
    mt_status status;
    bool equal;
    fake *f;
} async_wait;

static void async_init(async_wait *w, fake *f)
{
    memset(w, 0, sizeof *w);
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->cond, NULL);
    w->f = f;
}

static void on_async_reply(mt_status status, const meshtopo_reply_t *reply, const mt_diag *diag,
                           void *user)
{
    (void)diag;
    async_wait *w = user;
    bool equal = false;
    if (status == MT_OK && reply) {
        int before = mt_test_failures();
        check_fake_reply(w->f, reply, __LINE__);
        equal = mt_test_failures() == before;
    }
    pthread_mutex_lock(&w->lock);
    w->status = status;
    w->equal = equal;
    w->done = 1;
    pthread_cond_signal(&w->cond);
    pthread_mutex_unlock(&w->lock);
}

static mt_status async_wait_done(async_wait *w)
{
    pthread_mutex_lock(&w->lock);
    while (!w->done) pthread_cond_wait(&w->cond, &w->lock);
    pthread_mutex_unlock(&w->lock);
    pthread_mutex_destroy(&w->lock);
    pthread_cond_destroy(&w->cond);
    return w->status;
}

/* Every part at once, backwards, each twice: each kept once, the query sent once. */
static void test_out_of_order_duplicates(void)
{
    fake f;
    fake_init(&f, 20000); /* ~200 KB: 50 parts */
    f.all_at_once = f.reverse = f.twice = true;
    mt_client *client = fake_client(&f, 0);
    meshtopo_reply_t r;
    mt_diag diag;
    CHECK_OK(fake_query(client, &r, &diag));
    check_fake_reply(&f, &r, __LINE__);
    mt_client_stats st;
    mt_client_get_stats(client, &st);
    CHECK_EQ(st.reply_parts, fake_num_parts(&f));
    CHECK_EQ(st.bad_parts, 0);
    pthread_mutex_lock(&f.lock);
    CHECK_EQ(f.queries, 1);
    pthread_mutex_unlock(&f.lock);
    mt_client_reply_free(&r);
    mt_client_destroy(client);
    fake_free(&f);
}

/* The first 16 parts with the answer, the rest pulled a window at a time;
 * parts lost on their first send (in the first window, a later one, and the
 * very last part) are pulled again. The query is sent once. */
static void test_missing_recovered(void)
{
    fake f;
    fake_init(&f, 20000);
    int drops[] = {3, 7, 15, 20, 40, -2};
    for (int i = 0; drops[i] != -2; i++) f.drop_first[i] = drops[i];
    mt_client *client = fake_client(&f, 0);
    size_t last = 0;
    meshtopo_reply_t r;
    mt_diag diag;
    CHECK_OK(fake_query(client, &r, &diag));
    last = fake_num_parts(&f) - 1;
    check_fake_reply(&f, &r, __LINE__);
    mt_client_stats st;
    mt_client_get_stats(client, &st);
    CHECK_EQ(st.reply_parts, fake_num_parts(&f));
    CHECK(st.reply_pulls >= 3); /* 50 parts in windows of 16, plus the lost ones */
    pthread_mutex_lock(&f.lock);
    CHECK_EQ(f.queries, 1);
    CHECK(f.pulls >= 3);
    for (size_t k = 0; k <= last; k++) CHECK(f.sent[k]);
    mt_client_reply_free(&r);

    /* Asynchronous: the same recovery, the first and the last part lost. */
    memset(f.sent, 0, sizeof f.sent);
    f.drop_first[0] = (int)last;
    f.drop_first[1] = 0;
    pthread_mutex_unlock(&f.lock);
    async_wait w;
    async_init(&w, &f);
    CHECK_OK(mt_client_query_async(client, "scripted", 0, MESHTOPO_QUERY_T_VALENCE, (uint32_t[]){0},
                                   1, on_async_reply, &w, &diag));
    CHECK_OK(async_wait_done(&w));
    CHECK(w.equal);
    pthread_mutex_lock(&f.lock);
    CHECK_EQ(f.queries, 2);
    pthread_mutex_unlock(&f.lock);
    mt_client_destroy(client);
    fake_free(&f);
}

/* Lying parts (past the end, off a part boundary, too long, too short,
 * another hash, another size) are ignored and counted; the answer is intact. */
static void test_lying_parts(void)
{
    fake f;
    fake_init(&f, 20000);
    f.lie = true;
    f.all_at_once = true;
    mt_client *client = fake_client(&f, 0);
    meshtopo_reply_t r;
    mt_diag diag;
    CHECK_OK(fake_query(client, &r, &diag));
    check_fake_reply(&f, &r, __LINE__);
    mt_client_stats st;
    mt_client_get_stats(client, &st);
    CHECK_EQ(st.bad_parts, 6);
    CHECK_EQ(st.reply_parts, fake_num_parts(&f));
    mt_client_reply_free(&r);
    mt_client_destroy(client);
    fake_free(&f);
}

/* Parts whose reassembled bytes do not hash to the announced hash: dropped,
 * the query asked again, the second answer kept. */
static void test_bad_hash(void)
{
    fake f;
    fake_init(&f, 5000);
    f.bad_hash_first = true;
    f.all_at_once = true;
    mt_client *client = fake_client(&f, 0);
    meshtopo_reply_t r;
    mt_diag diag;
    CHECK_OK(fake_query(client, &r, &diag));
    check_fake_reply(&f, &r, __LINE__);
    mt_client_stats st;
    mt_client_get_stats(client, &st);
    pthread_mutex_lock(&f.lock);
    CHECK_EQ(f.queries, 2);
    pthread_mutex_unlock(&f.lock);
    CHECK_EQ(st.bad_parts, 1);
    mt_client_reply_free(&r);
    mt_client_destroy(client);
    fake_free(&f);
}

/* An answer larger than max_reply_bytes fails with TOO_LARGE naming the
 * limit, holds no memory afterwards, and a smaller one still works. */
static void test_memory_cap(void)
{
    fake f;
    fake_init(&f, 20000);
    f.all_at_once = true;
    mt_client *client = fake_client(&f, 100000);
    meshtopo_reply_t r;
    mt_diag diag;
    CHECK_STATUS(fake_query(client, &r, &diag), MT_ERR_TOO_LARGE);
    CHECK(strstr(diag.message, "max_reply_bytes") != NULL);
    CHECK(r.num_items == 0);
    pthread_mutex_lock(&f.lock);
    f.num_items = 5000; /* ~50 KB */
    f.lie = true;       /* the lying part of twice the size must not count either */
    pthread_mutex_unlock(&f.lock);
    CHECK_OK(fake_query(client, &r, &diag));
    check_fake_reply(&f, &r, __LINE__);
    mt_client_reply_free(&r);
    CHECK_OK(fake_query(client, &r, &diag)); /* nothing left held by the first */
    mt_client_reply_free(&r);
    mt_client_destroy(client);
    fake_free(&f);
}

/* ---- The real daemon --------------------------------------------------- */

#define RAW_REPLY "TEST_PARTS_REPLY"
#define MAX_INBOX 512

typedef struct fixture {
    lcm_t *lcm;
    mtd_daemon *daemon;
    void *inbox[MAX_INBOX];
    size_t inbox_size[MAX_INBOX];
    size_t num_inbox;
} fixture;

static void on_raw(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    fixture *fx = user;
    if (fx->num_inbox == MAX_INBOX) return;
    fx->inbox[fx->num_inbox] = malloc(rbuf->data_size);
    memcpy(fx->inbox[fx->num_inbox], rbuf->data, rbuf->data_size);
    fx->inbox_size[fx->num_inbox++] = rbuf->data_size;
}

static void fixture_init(fixture *fx)
{
    memset(fx, 0, sizeof *fx);
    char *argv[] = {"meshtopod", "--workers", "2", "--log-level", "error"};
    mtd_config config;
    mtd_config_action action;
    mt_diag diag;
    CHECK_OK(mtd_config_parse(5, argv, &config, &action, &diag));
    mtd_log_set_level(config.log_level);
    fx->lcm = lcm_create("memq://");
    CHECK(fx->lcm != NULL);
    CHECK_OK(mtd_daemon_create(&config, fx->lcm, NULL, &fx->daemon, &diag));
    lcm_subscribe(fx->lcm, RAW_REPLY "_(REPLY|PART)", on_raw, fx);
}

static void fixture_drain(fixture *fx)
{
    for (size_t i = 0; i < fx->num_inbox; i++) free(fx->inbox[i]);
    fx->num_inbox = 0;
}

static void fixture_free(fixture *fx)
{
    mtd_daemon_destroy(fx->daemon);
    lcm_destroy(fx->lcm);
    fixture_drain(fx);
}

static mt_client *daemon_client(fixture *fx, const char *source)
{
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm = fx->lcm;
    opts.source = source;
    opts.timeout_ms = 2000;
    mt_client *client = NULL;
    mt_diag diag;
    CHECK_OK(mt_client_create(&opts, &client, &diag));
    return client;
}

/* Builds list in-process (validated) and submits it as mesh_id. */
static mt_mesh *submit_and_build(mt_client *client, const char *mesh_id, const mt_face_list *list)
{
    mt_mesh *mesh = NULL;
    mt_diag diag;
    CHECK_OK(mt_mesh_build(list, NULL, &mesh, &diag));
    if (mesh) CHECK_OK(mt_mesh_validate(mesh, &diag));
    mt_client_ack ack;
    CHECK_OK(mt_client_submit(client, mesh_id, list, 0, &ack, &diag));
    mt_client_ack_free(&ack);
    return mesh;
}

typedef struct ring_wait {
    async_wait w;
    const mt_mesh *mesh;
    const uint32_t *ids;
    size_t n;
} ring_wait;

static void on_async_rings(mt_status status, const meshtopo_reply_t *reply, const mt_diag *diag,
                           void *user)
{
    (void)diag;
    ring_wait *rw = user;
    char why[256] = "";
    bool equal = status == MT_OK && reply &&
                 mt_test_check_rings(rw->mesh, rw->ids, rw->n, reply, why, sizeof why) == 0;
    if (status == MT_OK && !equal) mt_test_fail(__FILE__, __LINE__, "async rings: %s", why);
    pthread_mutex_lock(&rw->w.lock);
    rw->w.status = status;
    rw->w.equal = equal;
    rw->w.done = 1;
    pthread_cond_signal(&rw->w.cond);
    pthread_mutex_unlock(&rw->w.lock);
}

/* The one-rings of every vertex of a 150 x 150 grid (~1.4 MB of reply_t),
 * synchronously and asynchronously, and the boundary loops of a grid with
 * 10,000 holes, equal to the core's; the reply arrived in parts and pulls. */
static void test_daemon_answers(void)
{
    fixture fx;
    fixture_init(&fx);
    mt_client *client = daemon_client(&fx, "test_reply_parts");
    mt_face_list grid, holes;
    CHECK_OK(mt_gen_grid(150, 150, true, &grid));
    CHECK_OK(mt_test_grid_with_holes(300, 300, 3, &holes));
    mt_mesh *gm = submit_and_build(client, "grid", &grid);
    mt_mesh *hm = submit_and_build(client, "holes", &holes);
    uint32_t n = grid.num_verts;
    uint32_t *ids = malloc(n * sizeof *ids);
    for (uint32_t v = 0; v < n; v++) ids[v] = v;
    char why[256] = "";

    meshtopo_reply_t r;
    mt_diag diag;
    CHECK_OK(mt_client_query(client, "grid", 0, MESHTOPO_QUERY_T_VERTEX_RING, ids, n, &r, &diag));
    if (mt_test_check_rings(gm, ids, n, &r, why, sizeof why) != 0)
        mt_test_fail(__FILE__, __LINE__, "rings: %s", why);
    mt_client_reply_free(&r);
    mt_client_stats st;
    mt_client_get_stats(client, &st);
    CHECK(st.reply_parts > 16);
    CHECK(st.reply_pulls >= 1);
    CHECK_EQ(st.bad_parts, 0);

    ring_wait rw;
    async_init(&rw.w, NULL);
    rw.mesh = gm;
    rw.ids = ids;
    rw.n = n;
    CHECK_OK(mt_client_query_async(client, "grid", 0, MESHTOPO_QUERY_T_VERTEX_RING, ids, n,
                                   on_async_rings, &rw, &diag));
    CHECK_OK(async_wait_done(&rw.w));
    CHECK(rw.w.equal);

    CHECK_OK(
        mt_client_query(client, "holes", 0, MESHTOPO_QUERY_T_BOUNDARY_LOOPS, NULL, 0, &r, &diag));
    CHECK_EQ(r.num_items, 10001);
    if (mt_test_check_loops(hm, &r, why, sizeof why) != 0)
        mt_test_fail(__FILE__, __LINE__, "loops: %s", why);
    mt_client_reply_free(&r);

    mt_mesh_destroy(gm);
    mt_mesh_destroy(hm);
    mt_face_list_free(&grid);
    mt_face_list_free(&holes);
    free(ids);
    mt_client_destroy(client);
    fixture_free(&fx);
}

/* LIST_MESHES of 300 meshes with long source names (~80 KB) comes in parts
 * through mt_client_list and lists every mesh. */
static void test_daemon_list(void)
{
    fixture fx;
    fixture_init(&fx);
    char source[201];
    memset(source, 's', 200);
    source[200] = '\0';
    mt_client *client = daemon_client(&fx, source);
    mt_face_list tri;
    CHECK_OK(mt_gen_grid(1, 1, true, &tri));
    mt_diag diag;
    for (int i = 0; i < 300; i++) {
        char id[32];
        snprintf(id, sizeof id, "mesh%04d", i);
        mt_client_ack ack;
        CHECK_OK(mt_client_submit(client, id, &tri, 0, &ack, &diag));
        mt_client_ack_free(&ack);
    }
    meshtopo_reply_t r;
    CHECK_OK(mt_client_list(client, NULL, &r, &diag));
    CHECK_EQ(r.num_meshes, 300);
    for (int i = 0; i < r.num_meshes && i < 300; i++) {
        char id[32];
        snprintf(id, sizeof id, "mesh%04d", i);
        CHECK(strcmp(r.list_mesh_ids[i], id) == 0);
        CHECK(strcmp(r.list_sources[i], source) == 0);
    }
    mt_client_reply_free(&r);
    mt_client_stats st;
    mt_client_get_stats(client, &st);
    CHECK(st.reply_parts >= 2);
    mt_face_list_free(&tri);
    mt_client_destroy(client);
    fixture_free(&fx);
}

/* Publishes a query_t or reply_pull_t on its channel. */
static void publish_raw(fixture *fx, const mt_msgs_type *type, const void *msg)
{
    int size = type->encoded_size(msg);
    void *buf = malloc((size_t)size);
    CHECK_EQ(type->encode(buf, 0, size, msg), size);
    const char *channel =
        type == &mt_msgs_type_reply_pull ? "MESHTOPO_QUERY_PULL" : "MESHTOPO_QUERY";
    CHECK_EQ(lcm_publish(fx->lcm, channel, buf, (unsigned)size), 0);
    free(buf);
}

/* Handles LCM until nothing arrives for 100 ms; returns the reply_parts in
 * the inbox (decoded into parts[], at most max) and empties it. */
static size_t collect_parts(fixture *fx, meshtopo_reply_part_t *parts, size_t max)
{
    while (lcm_handle_timeout(fx->lcm, 100) > 0) {
    }
    size_t n = 0;
    for (size_t i = 0; i < fx->num_inbox && n < max; i++)
        if (mt_msgs_type_of(fx->inbox[i], fx->inbox_size[i]) == &mt_msgs_type_reply_part &&
            mt_msgs_decode(&mt_msgs_type_reply_part, fx->inbox[i], fx->inbox_size[i], &parts[n],
                           NULL, 0) == 0)
            n++;
    fixture_drain(fx);
    return n;
}

static void free_parts(meshtopo_reply_part_t *parts, size_t n)
{
    for (size_t i = 0; i < n; i++) meshtopo_reply_part_t_decode_cleanup(&parts[i]);
}

/* The daemon's side, by hand: the first 16 parts come with the answer; a
 * pull for everything brings at most 64; a pull naming another answer or an
 * unknown request brings nothing; the query sent again brings the first 16
 * again without running it again. */
static void test_daemon_pulls(void)
{
    fixture fx;
    fixture_init(&fx);
    mt_client *client = daemon_client(&fx, "test_reply_parts");
    mt_face_list grid;
    CHECK_OK(mt_gen_grid(300, 300, true, &grid)); /* rings of 90,601 vertices: ~100 parts */
    mt_mesh *gm = submit_and_build(client, "grid", &grid);
    mt_client_destroy(client); /* from here the test thread handles LCM */
    uint32_t n = grid.num_verts;
    int32_t *ids = malloc(n * sizeof *ids);
    for (uint32_t v = 0; v < n; v++) ids[v] = (int32_t)v;

    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.request_id = 77;
    q.reply_channel = RAW_REPLY;
    q.instance = "";
    q.mesh_id = "grid";
    q.kind = MESHTOPO_QUERY_T_VERTEX_RING;
    q.num_ids = (int32_t)n;
    q.ids = ids;
    publish_raw(&fx, &mt_msgs_type_query, &q);
    static meshtopo_reply_part_t parts[256];
    size_t got = collect_parts(&fx, parts, 256);
    CHECK_EQ(got, 16);
    int64_t total = parts[0].total_size, hash = parts[0].answer_hash;
    int32_t part_size = parts[0].part_size;
    CHECK(total > 64 * (int64_t)part_size);
    CHECK(part_size > 0 && part_size <= 60000);
    uint8_t *answer = calloc((size_t)total, 1);
    for (size_t i = 0; i < got; i++) {
        CHECK_EQ(parts[i].offset, (int64_t)i * part_size);
        CHECK_EQ(parts[i].length, part_size);
        CHECK_EQ(parts[i].request_id, 77);
        memcpy(answer + parts[i].offset, parts[i].data, (size_t)parts[i].length);
    }
    free_parts(parts, got);

    /* Pull everything: 64 parts at most, in order from the first wanted. */
    int64_t offsets[2] = {16 * (int64_t)part_size, 0}, lengths[2] = {total, 1};
    meshtopo_reply_pull_t pull;
    memset(&pull, 0, sizeof pull);
    pull.request_id = 77;
    pull.reply_channel = RAW_REPLY;
    pull.total_size = total;
    pull.answer_hash = hash;
    pull.num_ranges = 2;
    pull.offsets = offsets;
    pull.lengths = lengths;
    publish_raw(&fx, &mt_msgs_type_reply_pull, &pull);
    got = collect_parts(&fx, parts, 256);
    CHECK_EQ(got, 64);
    CHECK_EQ(parts[0].offset, 0); /* the range of one byte asks for part 0 */
    for (size_t i = 0; i < got; i++)
        memcpy(answer + parts[i].offset, parts[i].data, (size_t)parts[i].length);
    int64_t next = parts[got - 1].offset + part_size;
    free_parts(parts, got);
    /* The rest. */
    offsets[0] = next;
    lengths[0] = total - next;
    pull.num_ranges = 1;
    publish_raw(&fx, &mt_msgs_type_reply_pull, &pull);
    got = collect_parts(&fx, parts, 256);
    CHECK_EQ((int64_t)got, (total - next + part_size - 1) / part_size);
    for (size_t i = 0; i < got; i++)
        memcpy(answer + parts[i].offset, parts[i].data, (size_t)parts[i].length);
    free_parts(parts, got);
    CHECK((int64_t)mt_msgs_answer_hash(answer, (size_t)total) == hash);
    meshtopo_reply_t r;
    CHECK_EQ(mt_msgs_decode(&mt_msgs_type_reply, answer, (size_t)total, &r, NULL, 0), 0);
    char why[256] = "";
    if (mt_test_check_rings(gm, (const uint32_t *)ids, n, &r, why, sizeof why) != 0)
        mt_test_fail(__FILE__, __LINE__, "rings: %s", why);
    meshtopo_reply_t_decode_cleanup(&r);

    /* Another answer, another size, an unknown request, a negative range. */
    offsets[0] = 0;
    lengths[0] = total;
    pull.answer_hash = hash ^ 1;
    publish_raw(&fx, &mt_msgs_type_reply_pull, &pull);
    pull.answer_hash = hash;
    pull.total_size = total + 1;
    publish_raw(&fx, &mt_msgs_type_reply_pull, &pull);
    pull.total_size = total;
    pull.request_id = 78;
    publish_raw(&fx, &mt_msgs_type_reply_pull, &pull);
    pull.request_id = 77;
    offsets[0] = -5;
    publish_raw(&fx, &mt_msgs_type_reply_pull, &pull);
    CHECK_EQ(collect_parts(&fx, parts, 256), 0);

    /* The query again: answered from the cache, the first 16 parts again. */
    mtd_counters counts;
    mtd_daemon_get_counts(fx.daemon, &counts);
    const int64_t duplicates = counts.duplicates;
    publish_raw(&fx, &mt_msgs_type_query, &q);
    got = collect_parts(&fx, parts, 256);
    CHECK_EQ(got, 16);
    CHECK_EQ(parts[0].answer_hash, hash);
    free_parts(parts, got);
    mtd_daemon_get_counts(fx.daemon, &counts);
    CHECK_EQ(counts.duplicates, duplicates + 1);

    free(answer);
    free(ids);
    mt_mesh_destroy(gm);
    mt_face_list_free(&grid);
    fixture_free(&fx);
}

static const mt_test_case cases[] = {
    {"out_of_order_duplicates", test_out_of_order_duplicates},
    {"missing_recovered", test_missing_recovered},
    {"lying_parts", test_lying_parts},
    {"bad_hash", test_bad_hash},
    {"memory_cap", test_memory_cap},
    {"daemon_answers", test_daemon_answers},
    {"daemon_list", test_daemon_list},
    {"daemon_pulls", test_daemon_pulls},
};
const mt_test_table mt_tests_reply_parts = {cases, sizeof cases / sizeof cases[0]};
