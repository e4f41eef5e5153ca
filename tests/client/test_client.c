/* meshtopo::client tests over in-process memq:// LCM with a fake responder
 * thread standing in for meshtopod: answers, retries with the same request
 * id, timeouts after the configured attempts, garbage and foreign replies
 * ignored, 8 threads sharing one client, asynchronous callbacks, argument
 * checks, status mapping and the content hash of a submission.
 *
 * LCM 1.3.1's memq provider keeps one queue per lcm_t (a message published on
 * one instance never reaches another, checked by memq_is_per_instance), so the
 * client and the responder share one lcm_t (mt_client_options.lcm); the
 * client's thread handles it, and the responder's handler only queues the
 * bytes for the responder thread, which answers. */
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <xxhash.h>

#include "harness.h"
#include "meshtopo/client.h"

/* ThreadSanitizer cannot see the lock that orders memq's queue (GLib's
 * GMutex is futex-based, not a pthread mutex), so it would report LCM's and
 * GLib's own copies of a message (g_strdup, memcpy in lcm_publish, strcmp in
 * dispatch) as races with the handling thread. Accesses made inside those two
 * libraries are left out; everything in meshtopo's code is still checked. */
#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define MT_TEST_TSAN 1
#endif
#endif
#if defined(__SANITIZE_THREAD__)
#define MT_TEST_TSAN 1
#endif
#ifdef MT_TEST_TSAN
const char *__tsan_default_suppressions(void);
const char *__tsan_default_suppressions(void)
{
    return "called_from_lib:liblcm.so\ncalled_from_lib:libglib-2.0.so\n";
}
#endif

/* ---- The fake responder -------------------------------------------------- */

typedef enum mode {
    MODE_ANSWER,     /* every request answered */
    MODE_DROP_FIRST, /* the first attempt of each request id ignored */
    MODE_SILENT,     /* nothing answered */
    MODE_NOISE,      /* garbage, a reply for another id and an ack first, then the answer */
    MODE_ERROR,      /* UNKNOWN_MESH with an error text */
    MODE_CORRUPT,    /* a reply whose value_offsets decrease */
    MODE_BUSY_TWICE, /* the first two attempts of each request id answered BUSY */
    MODE_BUSY,       /* every attempt answered BUSY */
    MODE_TWICE,      /* every query answered twice with the same bytes (a copy) */
    MODE_TWO_DAEMONS /* every query answered twice, the second sent at another moment */
} mode;

#define MAX_IDS 4096

typedef struct queued {
    struct queued *next;
    size_t size;
    uint8_t data[];
} queued;

typedef struct fixture {
    lcm_t *lcm;
    mt_client *client;
    lcm_subscription_t *subs[2];
    pthread_t thread;
    pthread_mutex_t mutex;
    pthread_cond_t cond;
    queued *head, *tail;
    int stop;
    mode mode;
    /* Every request id seen and how often (guarded by mutex). */
    int64_t ids[MAX_IDS];
    int counts[MAX_IDS];
    int num_ids;
    int requests;         /* messages received */
    int64_t answer_utime; /* reply_t.utime of the answers */
} fixture;

static int64_t now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

/* Runs on the client's thread (it handles the shared lcm_t): queue the bytes. */
static void on_request(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    fixture *f = user;
    queued *q = malloc(sizeof *q + rbuf->data_size);
    if (!q) return;
    q->next = NULL;
    q->size = rbuf->data_size;
    memcpy(q->data, rbuf->data, rbuf->data_size);
    pthread_mutex_lock(&f->mutex);
    if (f->tail)
        f->tail->next = q;
    else
        f->head = q;
    f->tail = q;
    pthread_cond_signal(&f->cond);
    pthread_mutex_unlock(&f->mutex);
}

/* Records an attempt of request_id; returns how many were seen, this one included. */
static int record_id(fixture *f, int64_t request_id)
{
    pthread_mutex_lock(&f->mutex);
    f->requests++;
    int n = 0;
    for (int i = 0; i < f->num_ids; i++) {
        if (f->ids[i] == request_id) {
            n = ++f->counts[i];
            break;
        }
    }
    if (n == 0 && f->num_ids < MAX_IDS) {
        f->ids[f->num_ids] = request_id;
        f->counts[f->num_ids++] = 1;
        n = 1;
    }
    pthread_mutex_unlock(&f->mutex);
    return n;
}

/* What the responder recorded, read under its mutex. */
static int seen_num_ids(fixture *f)
{
    pthread_mutex_lock(&f->mutex);
    int n = f->num_ids;
    pthread_mutex_unlock(&f->mutex);
    return n;
}

static int seen_count(fixture *f, int i)
{
    pthread_mutex_lock(&f->mutex);
    int n = i < f->num_ids ? f->counts[i] : 0;
    pthread_mutex_unlock(&f->mutex);
    return n;
}

static int64_t seen_id(fixture *f, int i)
{
    pthread_mutex_lock(&f->mutex);
    int64_t id = i < f->num_ids ? f->ids[i] : -1;
    pthread_mutex_unlock(&f->mutex);
    return id;
}

static int seen_requests(fixture *f)
{
    pthread_mutex_lock(&f->mutex);
    int n = f->requests;
    pthread_mutex_unlock(&f->mutex);
    return n;
}

/* The channel of answers of `type` to a request naming reply_channel. */
static const char *answer_channel(const char *reply_channel, const mt_msgs_type *type,
                                  char out[MT_MSGS_CHANNEL_NAME_MAX + 1])
{
    CHECK_EQ(mt_msgs_reply_channel_name(reply_channel, type, out), MT_OK);
    return out;
}

static void publish_reply(fixture *f, const char *reply_channel, const meshtopo_reply_t *r)
{
    char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
    answer_channel(reply_channel, &mt_msgs_type_reply, channel);
    int size = meshtopo_reply_t_encoded_size(r);
    uint8_t *buf = malloc((size_t)size);
    CHECK(buf != NULL);
    CHECK_EQ(meshtopo_reply_t_encode(buf, 0, size, r), size);
    CHECK_EQ(lcm_publish(f->lcm, channel, buf, (unsigned)size), 0);
    free(buf);
}

/* The answer to a query: VALENCE item i is one group holding 2 * ids[i];
 * LIST_MESHES lists one mesh "m" version 3. */
static void answer_query(fixture *f, const meshtopo_query_t *q, int32_t status, int64_t request_id)
{
    int32_t n = q->kind == MESHTOPO_QUERY_T_VALENCE && status == 0 ? q->num_ids : 0;
    int8_t *item_status = calloc((size_t)n + 1, 1);
    int32_t *offsets = calloc((size_t)n + 1, sizeof *offsets);
    int32_t *values = calloc((size_t)n + 1, sizeof *values);
    int8_t *boundary = calloc((size_t)n + 1, sizeof *boundary);
    int32_t *zeros = calloc((size_t)n + 1, sizeof *zeros);
    for (int32_t i = 0; i < n; i++) values[i] = 2 * q->ids[i];
    for (int32_t i = 0; i <= n; i++) offsets[i] = i;
    char *list_ids[1] = {"m"};
    int32_t list_versions[1] = {3};
    char *list_sources[1] = {"test"};
    int64_t list_i64[1] = {0};
    int32_t list_i32[1] = {0};

    meshtopo_reply_t r;
    memset(&r, 0, sizeof r);
    r.request_id = request_id;
    r.utime = f->answer_utime;
    r.status = status;
    r.error = status == 0 ? "" : "no mesh with this id";
    r.mesh_id = q->mesh_id;
    r.version = q->version;
    r.kind = q->kind;
    r.num_items = n;
    r.item_status = item_status;
    r.num_item_offsets = n + 1;
    r.item_offsets = offsets;
    r.num_groups = n;
    r.group_boundary = boundary;
    r.num_value_offsets = n + 1;
    r.value_offsets = offsets;
    r.value2_offsets = zeros;
    r.num_values = n;
    r.values = values;
    if (q->kind == MESHTOPO_QUERY_T_LIST_MESHES && status == 0) {
        r.num_meshes = 1;
        r.list_mesh_ids = list_ids;
        r.list_versions = list_versions;
        r.list_sources = list_sources;
        r.list_utimes = list_i64;
        r.list_num_verts = list_i32;
        r.list_num_faces = list_i32;
        r.list_num_defects = list_i64;
        r.list_content_hashes = list_i64;
    }
    publish_reply(f, q->reply_channel, &r);
    free(item_status);
    free(offsets);
    free(values);
    free(boundary);
    free(zeros);
}

/* Acks a submission with version 1, the hash of the received bytes' content
 * tail (XXH3-64, as msgs/mesh_t.lcm defines it, computed here with libxxhash
 * itself) and a report naming the counts. */
static void answer_submit(fixture *f, const meshtopo_mesh_t *m, const uint8_t *data, size_t size)
{
    size_t tail = 8 + 8 * (size_t)m->num_position_values + 4 + 4 * (size_t)m->num_faces + 4 +
                  4 * (size_t)m->num_indices;
    meshtopo_topology_t report;
    memset(&report, 0, sizeof report);
    report.mesh_id = m->mesh_id;
    report.version = 1;
    report.source = m->source;
    report.num_verts = m->num_verts;
    report.num_faces = m->num_faces;
    report.content_hash = (int64_t)XXH3_64bits(data + size - tail, tail);
    meshtopo_ack_t ack;
    memset(&ack, 0, sizeof ack);
    ack.request_id = m->request_id;
    ack.error = "";
    ack.mesh_id = m->mesh_id;
    ack.version = 1;
    ack.content_hash = report.content_hash;
    ack.num_reports = 1;
    ack.reports = &report;
    int n = meshtopo_ack_t_encoded_size(&ack);
    uint8_t *buf = malloc((size_t)n);
    CHECK_EQ(meshtopo_ack_t_encode(buf, 0, n, &ack), n);
    char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
    answer_channel(m->reply_channel, &mt_msgs_type_ack, channel);
    CHECK_EQ(lcm_publish(f->lcm, channel, buf, (unsigned)n), 0);
    free(buf);
}

/* A BUSY ack_t or reply_t, as a daemon whose limits are reached sends. */
static void answer_busy(fixture *f, const char *reply_channel, int64_t request_id,
                        const char *mesh_id, const mt_msgs_type *type)
{
    char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
    answer_channel(reply_channel, type, channel);
    const char *why = "build queue full (8 waiting): retry later";
    if (type == &mt_msgs_type_ack) {
        meshtopo_ack_t ack;
        memset(&ack, 0, sizeof ack);
        ack.request_id = request_id;
        ack.status = MESHTOPO_STATUS_CODE_T_BUSY;
        ack.error = (char *)why;
        ack.mesh_id = (char *)mesh_id;
        CHECK_EQ(meshtopo_ack_t_publish(f->lcm, channel, &ack), 0);
        return;
    }
    int32_t zero = 0;
    meshtopo_reply_t r;
    memset(&r, 0, sizeof r);
    r.request_id = request_id;
    r.status = MESHTOPO_STATUS_CODE_T_BUSY;
    r.error = (char *)why;
    r.mesh_id = (char *)mesh_id;
    r.num_item_offsets = r.num_value_offsets = 1;
    r.item_offsets = r.value_offsets = r.value2_offsets = &zero;
    publish_reply(f, reply_channel, &r);
}

static int answers_busy(const fixture *f, int seen)
{
    return f->mode == MODE_BUSY || (f->mode == MODE_BUSY_TWICE && seen <= 2);
}

static void respond(fixture *f, const uint8_t *data, size_t size)
{
    const mt_msgs_type *type = mt_msgs_type_of(data, size);
    char error[MT_MSGS_ERROR_SIZE];
    if (type == &mt_msgs_type_mesh) {
        meshtopo_mesh_t m;
        if (mt_msgs_decode(type, data, size, &m, error, sizeof error) != 0) {
            mt_test_fail(__FILE__, __LINE__, "client sent an undecodable mesh_t: %s", error);
            return;
        }
        int seen = record_id(f, m.request_id);
        if (answers_busy(f, seen))
            answer_busy(f, m.reply_channel, m.request_id, m.mesh_id, &mt_msgs_type_ack);
        else if (f->mode == MODE_ANSWER || f->mode == MODE_BUSY_TWICE ||
                 (f->mode == MODE_DROP_FIRST && seen > 1))
            answer_submit(f, &m, data, size);
        meshtopo_mesh_t_decode_cleanup(&m);
        return;
    }
    meshtopo_query_t q;
    if (type != &mt_msgs_type_query ||
        mt_msgs_decode(type, data, size, &q, error, sizeof error) != 0) {
        mt_test_fail(__FILE__, __LINE__, "client sent an undecodable query_t");
        return;
    }
    int seen = record_id(f, q.request_id);
    switch (f->mode) {
        case MODE_ANSWER:
            answer_query(f, &q, 0, q.request_id);
            break;
        case MODE_TWICE:
        case MODE_TWO_DAEMONS:
            f->answer_utime = 1700000000000001;
            answer_query(f, &q, 0, q.request_id);
            if (f->mode == MODE_TWO_DAEMONS) f->answer_utime += 250;
            answer_query(f, &q, 0, q.request_id);
            break;
        case MODE_BUSY_TWICE:
        case MODE_BUSY:
            if (answers_busy(f, seen))
                answer_busy(f, q.reply_channel, q.request_id, q.mesh_id, &mt_msgs_type_reply);
            else
                answer_query(f, &q, 0, q.request_id);
            break;
        case MODE_DROP_FIRST:
            if (seen > 1) answer_query(f, &q, 0, q.request_id);
            break;
        case MODE_SILENT:
            break;
        case MODE_NOISE: {
            static const uint8_t garbage[] = "definitely not an LCM message";
            char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
            answer_channel(q.reply_channel, &mt_msgs_type_reply, channel);
            CHECK_EQ(lcm_publish(f->lcm, channel, garbage, sizeof garbage), 0);
            /* A reply's fingerprint followed by bytes cut short. */
            uint8_t cut[12];
            int64_t fp = mt_msgs_type_reply.fingerprint();
            for (int i = 0; i < 8; i++) cut[i] = (uint8_t)((uint64_t)fp >> (56 - 8 * i));
            memset(cut + 8, 0xff, 4);
            CHECK_EQ(lcm_publish(f->lcm, channel, cut, sizeof cut), 0);
            answer_query(f, &q, 0, q.request_id + 1000003); /* nobody waits for it */
            meshtopo_ack_t ack;                             /* the right id but the wrong type */
            memset(&ack, 0, sizeof ack);
            ack.request_id = q.request_id;
            ack.error = "";
            ack.mesh_id = q.mesh_id;
            CHECK_EQ(meshtopo_ack_t_publish(f->lcm, channel, &ack), 0); /* on the reply_t channel */
            answer_query(f, &q, 0, q.request_id);
            break;
        }
        case MODE_ERROR:
            answer_query(f, &q, MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH, q.request_id);
            break;
        case MODE_CORRUPT: {
            int8_t item_status[2] = {0, 0}, boundary[2] = {0, 0};
            int32_t item_offsets[3] = {0, 1, 2}, value_offsets[3] = {0, 2, 1};
            int32_t value2_offsets[3] = {0, 0, 0}, values[2] = {7, 8};
            meshtopo_reply_t r;
            memset(&r, 0, sizeof r);
            r.request_id = q.request_id;
            r.error = "";
            r.mesh_id = q.mesh_id;
            r.kind = q.kind;
            r.num_items = 2;
            r.item_status = item_status;
            r.num_item_offsets = 3;
            r.item_offsets = item_offsets;
            r.num_groups = 2;
            r.group_boundary = boundary;
            r.num_value_offsets = 3;
            r.value_offsets = value_offsets;
            r.value2_offsets = value2_offsets;
            r.num_values = 2;
            r.values = values;
            publish_reply(f, q.reply_channel, &r);
            break;
        }
    }
    meshtopo_query_t_decode_cleanup(&q);
}

static void *responder_thread(void *arg)
{
    fixture *f = arg;
    pthread_mutex_lock(&f->mutex);
    for (;;) {
        while (!f->head && !f->stop) pthread_cond_wait(&f->cond, &f->mutex);
        if (!f->head) break;
        queued *q = f->head;
        f->head = q->next;
        if (!f->head) f->tail = NULL;
        pthread_mutex_unlock(&f->mutex);
        respond(f, q->data, q->size);
        free(q);
        pthread_mutex_lock(&f->mutex);
    }
    pthread_mutex_unlock(&f->mutex);
    return NULL;
}

/* A memq lcm_t, the responder on it, and a client sharing it. */
static fixture *fixture_start(mode m, int timeout_ms, int retries)
{
    fixture *f = calloc(1, sizeof *f);
    f->mode = m;
    f->lcm = lcm_create("memq://");
    CHECK(f->lcm != NULL);
    pthread_mutex_init(&f->mutex, NULL);
    pthread_cond_init(&f->cond, NULL);
    f->subs[0] = lcm_subscribe(f->lcm, "MESHTOPO_QUERY", on_request, f);
    f->subs[1] = lcm_subscribe(f->lcm, "MESHTOPO_SUBMIT", on_request, f);
    for (int i = 0; i < 2; i++) lcm_subscription_set_queue_capacity(f->subs[i], 100000);
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm = f->lcm;
    opts.timeout_ms = timeout_ms;
    opts.retries = retries;
    opts.source = "test_client";
    mt_diag diag;
    CHECK_OK(mt_client_create(&opts, &f->client, &diag));
    CHECK(pthread_create(&f->thread, NULL, responder_thread, f) == 0);
    return f;
}

static void fixture_stop(fixture *f)
{
    mt_client_destroy(f->client); /* joins the thread that handles the lcm_t */
    pthread_mutex_lock(&f->mutex);
    f->stop = 1;
    pthread_cond_signal(&f->cond);
    pthread_mutex_unlock(&f->mutex);
    pthread_join(f->thread, NULL);
    while (f->head) {
        queued *q = f->head;
        f->head = q->next;
        free(q);
    }
    for (int i = 0; i < 2; i++) lcm_unsubscribe(f->lcm, f->subs[i]);
    lcm_destroy(f->lcm);
    pthread_mutex_destroy(&f->mutex);
    pthread_cond_destroy(&f->cond);
    free(f);
}

/* Checks a VALENCE reply to ids: item i answers 2 * ids[i]. Returns 1 if right. */
static int valence_reply_ok(const meshtopo_reply_t *r, const uint32_t *ids, int n)
{
    if (r->status != 0 || mt_client_reply_num_items(r) != (size_t)n) return 0;
    for (int i = 0; i < n; i++) {
        mt_client_item item = mt_client_reply_item(r, (size_t)i);
        if (item.num_groups != 1) return 0;
        mt_client_group g = mt_client_item_group(r, &item, 0);
        if (g.num_values != 1 || g.values[0] != (int32_t)(2 * ids[i])) return 0;
    }
    return 1;
}

/* ---- Tests -------------------------------------------------------------- */

static void memq_is_per_instance(void)
{
    lcm_t *a = lcm_create("memq://");
    lcm_t *b = lcm_create("memq://");
    int got = 0;
    lcm_subscription_t *sub = lcm_subscribe(b, "X", on_request, NULL);
    CHECK_EQ(lcm_publish(a, "X", "hi", 2), 0);
    got = lcm_handle_timeout(b, 50);
    CHECK_EQ(got, 0); /* nothing crossed from a to b */
    lcm_unsubscribe(b, sub);
    lcm_destroy(a);
    lcm_destroy(b);
}

static void query_answered(void)
{
    fixture *f = fixture_start(MODE_ANSWER, 2000, 0);
    uint32_t ids[] = {3, 5, 7};
    meshtopo_reply_t reply;
    mt_diag diag;
    CHECK_OK(
        mt_client_query(f->client, "bunny", 0, MESHTOPO_QUERY_T_VALENCE, ids, 3, &reply, &diag));
    CHECK(valence_reply_ok(&reply, ids, 3));
    CHECK(strcmp(reply.mesh_id, "bunny") == 0);
    CHECK_EQ(seen_num_ids(f), 1);
    CHECK_EQ(reply.request_id, seen_id(f, 0));
    mt_client_reply_free(&reply);
    mt_client_stats st;
    mt_client_get_stats(f->client, &st);
    CHECK_EQ(st.requests, 1);
    CHECK_EQ(st.attempts, 1);
    CHECK_EQ(st.replies, 1);
    CHECK_EQ(st.timeouts, 0);
    fixture_stop(f);
}

static void retry_reuses_request_id(void)
{
    fixture *f = fixture_start(MODE_DROP_FIRST, 50, 3);
    uint32_t ids[] = {11};
    meshtopo_reply_t reply;
    mt_diag diag;
    CHECK_OK(mt_client_query(f->client, "m", 2, MESHTOPO_QUERY_T_VALENCE, ids, 1, &reply, &diag));
    CHECK(valence_reply_ok(&reply, ids, 1));
    CHECK_EQ(seen_num_ids(f), 1);  /* one request id ... */
    CHECK_EQ(seen_count(f, 0), 2); /* ... sent twice */
    CHECK_EQ(reply.request_id, seen_id(f, 0));
    mt_client_reply_free(&reply);
    mt_client_stats st;
    mt_client_get_stats(f->client, &st);
    CHECK_EQ(st.attempts, 2);
    CHECK_EQ(st.replies, 1);
    fixture_stop(f);
}

static void timeout_after_retries(void)
{
    fixture *f = fixture_start(MODE_SILENT, 40, 2);
    uint32_t ids[] = {1};
    meshtopo_reply_t reply;
    mt_diag diag;
    int64_t start = now_ms();
    CHECK_STATUS(
        mt_client_query(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, ids, 1, &reply, &diag),
        MT_ERR_IO);
    int64_t took = now_ms() - start;
    CHECK(took >= 3 * 40);
    CHECK(took < 3000);
    CHECK(strncmp(diag.message, "timeout:", 8) == 0);
    CHECK(strstr(diag.message, "3 attempts") != NULL);
    CHECK_EQ(reply.num_items, 0); /* zeroed: nothing to free, freeing is fine */
    mt_client_reply_free(&reply);
    sleep_ms(20); /* let the responder record the last attempt */
    CHECK_EQ(seen_num_ids(f), 1);
    CHECK_EQ(seen_count(f, 0), 3);
    mt_client_stats st;
    mt_client_get_stats(f->client, &st);
    CHECK_EQ(st.attempts, 3);
    CHECK_EQ(st.timeouts, 1);
    fixture_stop(f);
}

/* BUSY is retried after pauses that grow (100 ms, then about 200 ms), under
 * the same request id, within the retry budget; then the answer counts. */
static void busy_retried_with_backoff(void)
{
    fixture *f = fixture_start(MODE_BUSY_TWICE, 2000, 3);
    uint32_t ids[] = {4};
    meshtopo_reply_t reply;
    mt_diag diag;
    int64_t start = now_ms();
    CHECK_OK(mt_client_query(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, ids, 1, &reply, &diag));
    int64_t took = now_ms() - start;
    CHECK(valence_reply_ok(&reply, ids, 1));
    mt_client_reply_free(&reply);
    CHECK(took >= (MT_CLIENT_BUSY_PAUSE_MS + 2 * MT_CLIENT_BUSY_PAUSE_MS) * 3 / 4);
    CHECK(took < 2000); /* the pauses, not the 2 s timeout */
    CHECK_EQ(seen_num_ids(f), 1);
    CHECK_EQ(seen_count(f, 0), 3);
    double positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t sizes[] = {3}, indices[] = {0, 1, 2};
    mt_face_list triangle = {3, 1, 3, positions, sizes, indices};
    mt_client_ack ack;
    CHECK_OK(mt_client_submit(f->client, "triangle", &triangle, 0, &ack, &diag));
    CHECK_EQ(ack.msg.status, 0);
    mt_client_ack_free(&ack);
    CHECK_EQ(seen_count(f, 1), 3);
    mt_client_stats st;
    mt_client_get_stats(f->client, &st);
    CHECK_EQ(st.busy_retries, 4);
    CHECK_EQ(st.timeouts, 0);
    fixture_stop(f);
}

/* BUSY on every attempt: the call fails with the daemon's answer once the
 * retries are spent, not at the first BUSY and not as a timeout. */
static void busy_until_retries_spent(void)
{
    fixture *f = fixture_start(MODE_BUSY, 2000, 2);
    uint32_t ids[] = {4};
    meshtopo_reply_t reply;
    mt_diag diag;
    CHECK_STATUS(
        mt_client_query(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, ids, 1, &reply, &diag),
        MT_ERR_IO);
    CHECK(strstr(diag.message, "BUSY: build queue full") != NULL);
    CHECK_EQ(reply.status, MESHTOPO_STATUS_CODE_T_BUSY);
    mt_client_reply_free(&reply);
    CHECK_EQ(seen_count(f, 0), 3);
    mt_client_stats st;
    mt_client_get_stats(f->client, &st);
    CHECK_EQ(st.busy_retries, 2);
    fixture_stop(f);
}

/* Two different answers to one call (two daemons on the prefix) are
 * counted; a copy of the answer (the daemon sending it again) is not. */
static void conflicting_answers_counted(void)
{
    const mode modes[2] = {MODE_TWICE, MODE_TWO_DAEMONS};
    for (int m = 0; m < 2; m++) {
        fixture *f = fixture_start(modes[m], 2000, 0);
        uint32_t ids[] = {2};
        meshtopo_reply_t reply;
        mt_diag diag;
        for (int i = 0; i < 3; i++) {
            CHECK_OK(mt_client_query(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, ids, 1, &reply,
                                     &diag));
            mt_client_reply_free(&reply);
        }
        mt_client_stats st;
        for (int wait = 0; wait < 100; wait++) {
            mt_client_get_stats(f->client, &st);
            if (st.unknown_replies == 3) break;
            sleep_ms(10);
        }
        CHECK_EQ(st.unknown_replies, 3);
        CHECK_EQ(st.conflicting_answers, modes[m] == MODE_TWO_DAEMONS ? 3 : 0);
        fixture_stop(f);
    }
}

static void garbage_and_foreign_replies_ignored(void)
{
    fixture *f = fixture_start(MODE_NOISE, 2000, 0);
    uint32_t ids[] = {4, 8};
    meshtopo_reply_t reply;
    mt_diag diag;
    CHECK_OK(mt_client_query(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, ids, 2, &reply, &diag));
    CHECK(valence_reply_ok(&reply, ids, 2));
    mt_client_reply_free(&reply);
    mt_client_stats st;
    mt_client_get_stats(f->client, &st);
    CHECK_EQ(st.undecodable, 2);     /* garbage, cut-short reply */
    CHECK_EQ(st.unknown_replies, 2); /* another id, an ack for a query */
    CHECK_EQ(st.replies, 1);
    fixture_stop(f);
}

#define NUM_THREADS 8
#define QUERIES_PER_THREAD 200

typedef struct worker {
    mt_client *client;
    int index;
    int ok;
} worker;

static void *query_worker(void *arg)
{
    worker *w = arg;
    for (int i = 0; i < QUERIES_PER_THREAD; i++) {
        uint32_t ids[3] = {(uint32_t)(w->index * 100000 + i), (uint32_t)i, (uint32_t)w->index};
        int n = 1 + i % 3;
        meshtopo_reply_t reply;
        mt_diag diag;
        if (mt_client_query(w->client, "shared", 0, MESHTOPO_QUERY_T_VALENCE, ids, (size_t)n,
                            &reply, &diag) == MT_OK &&
            valence_reply_ok(&reply, ids, n))
            w->ok++;
        mt_client_reply_free(&reply);
    }
    return NULL;
}

static void many_threads_one_client(void)
{
    fixture *f = fixture_start(MODE_ANSWER, 2000, 3);
    pthread_t threads[NUM_THREADS];
    worker workers[NUM_THREADS];
    for (int t = 0; t < NUM_THREADS; t++) {
        workers[t] = (worker){f->client, t, 0};
        CHECK(pthread_create(&threads[t], NULL, query_worker, &workers[t]) == 0);
    }
    for (int t = 0; t < NUM_THREADS; t++) pthread_join(threads[t], NULL);
    for (int t = 0; t < NUM_THREADS; t++) CHECK_EQ(workers[t].ok, QUERIES_PER_THREAD);
    mt_client_stats st;
    mt_client_get_stats(f->client, &st);
    CHECK_EQ(st.requests, NUM_THREADS * QUERIES_PER_THREAD);
    CHECK_EQ(st.replies, NUM_THREADS * QUERIES_PER_THREAD);
    CHECK_EQ(st.unknown_replies, 0);
    CHECK_EQ(seen_num_ids(f), NUM_THREADS * QUERIES_PER_THREAD); /* every id distinct */
    fixture_stop(f);
}

typedef struct async_result {
    pthread_mutex_t mutex;
    pthread_cond_t cond;
    int calls;
    mt_status status;
    int had_reply;
    int reply_ok;
    int on_caller_thread;
    pthread_t caller;
    char message[512];
} async_result;

static uint32_t async_ids[] = {21, 22};

static void on_async(mt_status status, const meshtopo_reply_t *reply, const mt_diag *diag,
                     void *user)
{
    async_result *r = user;
    pthread_mutex_lock(&r->mutex);
    r->calls++;
    r->status = status;
    r->had_reply = reply != NULL;
    r->reply_ok = reply && valence_reply_ok(reply, async_ids, 2);
    r->on_caller_thread = pthread_equal(pthread_self(), r->caller);
    snprintf(r->message, sizeof r->message, "%s", diag ? diag->message : "");
    pthread_cond_signal(&r->cond);
    pthread_mutex_unlock(&r->mutex);
}

static void async_wait(async_result *r)
{
    pthread_mutex_lock(&r->mutex);
    int64_t start = now_ms();
    while (r->calls == 0 && now_ms() - start < 10000) {
        pthread_mutex_unlock(&r->mutex);
        sleep_ms(1);
        pthread_mutex_lock(&r->mutex);
    }
    pthread_mutex_unlock(&r->mutex);
}

static void async_answer_and_timeout(void)
{
    for (int silent = 0; silent < 2; silent++) {
        fixture *f = fixture_start(silent ? MODE_SILENT : MODE_ANSWER, 30, 1);
        async_result r;
        memset(&r, 0, sizeof r);
        pthread_mutex_init(&r.mutex, NULL);
        pthread_cond_init(&r.cond, NULL);
        r.caller = pthread_self();
        mt_diag diag;
        CHECK_OK(mt_client_query_async(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, async_ids, 2,
                                       on_async, &r, &diag));
        async_wait(&r);
        sleep_ms(100); /* a second call would show up here */
        pthread_mutex_lock(&r.mutex);
        CHECK_EQ(r.calls, 1);
        CHECK(!r.on_caller_thread);
        if (silent) {
            CHECK_STATUS(r.status, MT_ERR_IO);
            CHECK(!r.had_reply);
            CHECK(strncmp(r.message, "timeout:", 8) == 0);
        } else {
            CHECK_OK(r.status);
            CHECK(r.reply_ok);
        }
        pthread_mutex_unlock(&r.mutex);
        fixture_stop(f);
        pthread_mutex_destroy(&r.mutex);
        pthread_cond_destroy(&r.cond);
    }
}

static void async_destroy_calls_back(void)
{
    fixture *f = fixture_start(MODE_SILENT, 5000, 0);
    async_result r;
    memset(&r, 0, sizeof r);
    pthread_mutex_init(&r.mutex, NULL);
    pthread_cond_init(&r.cond, NULL);
    CHECK_OK(mt_client_query_async(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, async_ids, 2,
                                   on_async, &r, NULL));
    fixture_stop(f);
    CHECK_EQ(r.calls, 1);
    CHECK_STATUS(r.status, MT_ERR_IO);
    CHECK(strstr(r.message, "destroyed") != NULL);
    pthread_mutex_destroy(&r.mutex);
    pthread_cond_destroy(&r.cond);
}

static void error_status_mapped(void)
{
    fixture *f = fixture_start(MODE_ERROR, 2000, 0);
    meshtopo_reply_t reply;
    mt_diag diag;
    CHECK_STATUS(
        mt_client_query(f->client, "nope", 0, MESHTOPO_QUERY_T_REPORT, NULL, 0, &reply, &diag),
        MT_ERR_NOT_FOUND);
    CHECK(strstr(diag.message, "UNKNOWN_MESH") != NULL);
    CHECK(strstr(diag.message, "no mesh with this id") != NULL);
    CHECK_EQ(reply.status, MESHTOPO_STATUS_CODE_T_UNKNOWN_MESH); /* the reply is kept */
    mt_client_reply_free(&reply);
    CHECK_EQ(mt_msgs_status_of_code(MESHTOPO_STATUS_CODE_T_DEFECT_REFUSED), MT_ERR_DEFECT);
    CHECK_EQ(mt_msgs_status_of_code(MESHTOPO_STATUS_CODE_T_OUT_OF_RANGE), MT_ERR_OUT_OF_RANGE);
    CHECK_EQ(mt_msgs_status_of_code(999), MT_ERR_IO);
    CHECK(strcmp(mt_msgs_code_name(999), "UNKNOWN_CODE") == 0);
    fixture_stop(f);
}

static void list_answered(void)
{
    fixture *f = fixture_start(MODE_ANSWER, 2000, 0);
    meshtopo_reply_t reply;
    mt_diag diag;
    CHECK_OK(mt_client_list(f->client, NULL, &reply, &diag));
    CHECK_EQ(reply.kind, MESHTOPO_QUERY_T_LIST_MESHES);
    CHECK_EQ(reply.num_meshes, 1);
    if (reply.num_meshes == 1) {
        CHECK(strcmp(reply.list_mesh_ids[0], "m") == 0);
        CHECK_EQ(reply.list_versions[0], 3);
    }
    mt_client_reply_free(&reply);
    fixture_stop(f);
}

static void submit_ack_and_content_hash(void)
{
    fixture *f = fixture_start(MODE_DROP_FIRST, 50, 3);
    double positions[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, -0.5};
    uint32_t sizes[] = {3, 3};
    uint32_t indices[] = {0, 1, 2, 0, 2, 3};
    mt_face_list list = {4, 2, 6, positions, sizes, indices};
    uint64_t hash = 0;
    mt_diag diag;
    CHECK_OK(mt_client_content_hash(&list, &hash, &diag));
    mt_client_ack ack;
    CHECK_OK(mt_client_submit(f->client, "quad", &list, 1, &ack, &diag));
    CHECK_EQ(ack.sent_content_hash, hash);
    CHECK_EQ((uint64_t)ack.msg.content_hash, hash); /* the responder hashed the bytes it got */
    CHECK_EQ(ack.msg.version, 1);
    const meshtopo_topology_t *report = mt_client_ack_report(&ack);
    CHECK(report != NULL);
    if (report) {
        CHECK_EQ(report->num_verts, 4);
        CHECK_EQ(report->num_faces, 2);
        CHECK(strcmp(report->source, "test_client") == 0);
    }
    CHECK_EQ(seen_num_ids(f), 1);
    CHECK_EQ(seen_count(f, 0), 2); /* retried with the same request id */
    mt_client_ack_free(&ack);
    mt_client_ack_free(&ack); /* zeroed: fine again */

    /* Without positions the hash changes, and a different mesh hashes differently. */
    mt_face_list bare = list;
    bare.positions = NULL;
    uint64_t hash2 = 0;
    CHECK_OK(mt_client_content_hash(&bare, &hash2, NULL));
    CHECK(hash2 != hash);
    fixture_stop(f);
}

static void bad_arguments(void)
{
    fixture *f = fixture_start(MODE_ANSWER, 2000, 0);
    mt_diag diag;
    meshtopo_reply_t reply;
    uint32_t ids[] = {1};
    char long_id[300];
    memset(long_id, 'a', sizeof long_id - 1);
    long_id[sizeof long_id - 1] = '\0';
    const char *bad_ids[] = {NULL, "", "a/b", "../x", "x..y", "tab\there", "\x7f", long_id};
    for (size_t i = 0; i < sizeof bad_ids / sizeof bad_ids[0]; i++) {
        memset(&diag, 0, sizeof diag);
        CHECK_STATUS(mt_client_query(f->client, bad_ids[i], 0, MESHTOPO_QUERY_T_VALENCE, ids, 1,
                                     &reply, &diag),
                     MT_ERR_INVALID_ARG);
        CHECK(diag.message[0] != '\0');
        CHECK(strstr(diag.message, "mesh id") != NULL);
    }
    CHECK_STATUS(mt_client_query(NULL, "m", 0, MESHTOPO_QUERY_T_VALENCE, ids, 1, &reply, &diag),
                 MT_ERR_INVALID_ARG);
    CHECK(diag.message[0] != '\0');
    CHECK_STATUS(mt_client_query(f->client, "m", 0, 0, ids, 1, &reply, &diag), MT_ERR_INVALID_ARG);
    CHECK(strstr(diag.message, "kind") != NULL);
    CHECK_STATUS(mt_client_query(f->client, "m", 0, 42, ids, 1, &reply, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(
        mt_client_query(f->client, "m", -1, MESHTOPO_QUERY_T_VALENCE, ids, 1, &reply, &diag),
        MT_ERR_INVALID_ARG);
    CHECK_STATUS(
        mt_client_query(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, NULL, 1, &reply, &diag),
        MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_client_query(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, ids, 1, NULL, &diag),
                 MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_client_query_async(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, ids, 1, NULL,
                                       NULL, &diag),
                 MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_client_query_async(f->client, "", 0, MESHTOPO_QUERY_T_VALENCE, ids, 1, on_async,
                                       NULL, &diag),
                 MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_client_list(f->client, "a/b", &reply, &diag), MT_ERR_INVALID_ARG);

    mt_client_ack ack;
    double pos[3] = {0, 0, 0};
    uint32_t sizes[1] = {3};
    uint32_t idx[2] = {0, 0}; /* sizes say 3 indices, the list has 2 */
    mt_face_list bad_list = {1, 1, 2, pos, sizes, idx};
    CHECK_STATUS(mt_client_submit(f->client, "m", NULL, 0, &ack, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_client_submit(f->client, "m", &bad_list, 0, &ack, &diag), MT_ERR_INVALID_ARG);
    CHECK(diag.message[0] != '\0');
    CHECK_STATUS(mt_client_submit(f->client, "", &bad_list, 0, &ack, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_client_submit(f->client, "m", &bad_list, 0, NULL, &diag), MT_ERR_INVALID_ARG);
    mt_client_ack_free(&ack);
    mt_client_ack_free(NULL);
    mt_client_reply_free(NULL);
    mt_client_destroy(NULL);

    /* Nothing was sent for any of them. */
    sleep_ms(20);
    CHECK_EQ(seen_requests(f), 0);

    /* Options. */
    mt_client *c = (mt_client *)&diag;
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm = f->lcm;
    opts.channel_prefix = "BAD.PREFIX";
    CHECK_STATUS(mt_client_create(&opts, &c, &diag), MT_ERR_INVALID_ARG);
    CHECK(c == NULL);
    CHECK(strstr(diag.message, "prefix") != NULL);
    opts.channel_prefix = "A_PREFIX_MUCH_TOO_LONG_FOR_LCM_";
    CHECK_STATUS(mt_client_create(&opts, &c, &diag), MT_ERR_INVALID_ARG);
    opts.channel_prefix = NULL;
    opts.timeout_ms = -5;
    CHECK_STATUS(mt_client_create(&opts, &c, &diag), MT_ERR_INVALID_ARG);
    memset(&opts, 0, sizeof opts);
    opts.external_handle = 1;
    CHECK_STATUS(mt_client_create(&opts, &c, &diag), MT_ERR_INVALID_ARG);
    CHECK_STATUS(mt_client_create(NULL, NULL, &diag), MT_ERR_INVALID_ARG);
    fixture_stop(f);
}

/* A synchronous call from the client's thread (a callback) is refused. */
static mt_status nested_status = MT_OK;
static atomic_int nested_done;

static void on_async_nested(mt_status status, const meshtopo_reply_t *reply, const mt_diag *diag,
                            void *user)
{
    meshtopo_reply_t inner;
    nested_status = mt_client_query((mt_client *)user, "m", 0, MESHTOPO_QUERY_T_VALENCE, async_ids,
                                    1, &inner, NULL);
    mt_client_reply_free(&inner);
    atomic_store(&nested_done, 1);
}

static void sync_call_from_callback_refused(void)
{
    fixture *f = fixture_start(MODE_ANSWER, 2000, 0);
    CHECK_OK(mt_client_query_async(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, async_ids, 2,
                                   on_async_nested, f->client, NULL));
    int64_t start = now_ms();
    while (!atomic_load(&nested_done) && now_ms() - start < 10000) sleep_ms(1);
    CHECK(atomic_load(&nested_done));
    CHECK_STATUS(nested_status, MT_ERR_INVALID_ARG);
    fixture_stop(f);
}

/* external_handle: the caller's own loop handles the shared lcm_t; the
 * client's thread only runs timeouts and retries. */
typedef struct loop_arg {
    lcm_t *lcm;
    atomic_int stop;
} loop_arg;

static void *handle_loop(void *arg)
{
    loop_arg *l = arg;
    while (!atomic_load(&l->stop)) lcm_handle_timeout(l->lcm, 10);
    return NULL;
}

static void external_handle_loop(void)
{
    fixture *f = fixture_start(MODE_DROP_FIRST, 50, 3);
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm = f->lcm;
    opts.external_handle = 1;
    opts.timeout_ms = 50;
    opts.retries = 3;
    mt_client *ext = NULL;
    CHECK_OK(mt_client_create(&opts, &ext, NULL));
    /* The fixture's own client handles the lcm_t too; stop it first. */
    mt_client_destroy(f->client);
    f->client = NULL;
    loop_arg l = {f->lcm, 0};
    pthread_t loop;
    CHECK(pthread_create(&loop, NULL, handle_loop, &l) == 0);
    uint32_t ids[] = {9, 10};
    meshtopo_reply_t reply;
    mt_diag diag;
    CHECK_OK(mt_client_query(ext, "m", 0, MESHTOPO_QUERY_T_VALENCE, ids, 2, &reply, &diag));
    CHECK(valence_reply_ok(&reply, ids, 2));
    mt_client_reply_free(&reply);
    mt_client_stats st;
    mt_client_get_stats(ext, &st);
    CHECK_EQ(st.attempts, 2); /* the retry came from the client's timer thread */
    atomic_store(&l.stop, 1);
    pthread_join(loop, NULL);
    mt_client_destroy(ext);
    fixture_stop(f);
}

static void reply_channel_private(void)
{
    lcm_t *lcm = lcm_create("memq://");
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm = lcm;
    mt_client *a = NULL, *b = NULL;
    CHECK_OK(mt_client_create(&opts, &a, NULL));
    opts.channel_prefix = "ROBOT7_";
    CHECK_OK(mt_client_create(&opts, &b, NULL));
    const char *ca = mt_client_reply_channel(a), *cb = mt_client_reply_channel(b);
    CHECK(strncmp(ca, "MESHTOPO_REPLY_", 15) == 0);
    CHECK(strncmp(cb, "ROBOT7_REPLY_", 13) == 0);
    CHECK(strcmp(ca, cb) != 0);
    CHECK(strlen(ca) <= LCM_MAX_CHANNEL_NAME_LENGTH);
    mt_client_destroy(a);
    mt_client_destroy(b);
    lcm_destroy(lcm);
}

/* A reply as the daemon builds it: two vertices' one-rings, the first with
 * two fans (an open one with neighbours 1 2 3 and faces 10 11, a closed one
 * with 4 5 6 and 12 13 14), the second NOT_FOUND; one real per item. */
typedef struct sample_reply {
    int8_t item_status[2];
    int32_t item_offsets[3];
    int8_t boundary[2];
    int32_t value_offsets[3], value2_offsets[3];
    int32_t values[6], values2[5];
    double reals[2];
    meshtopo_reply_t r;
} sample_reply;

static void sample_reply_init(sample_reply *s)
{
    *s = (sample_reply){
        .item_status = {MESHTOPO_STATUS_CODE_T_OK, MESHTOPO_STATUS_CODE_T_NOT_FOUND},
        .item_offsets = {0, 2, 2},
        .boundary = {1, 0},
        .value_offsets = {0, 3, 6},
        .value2_offsets = {0, 2, 5},
        .values = {1, 2, 3, 4, 5, 6},
        .values2 = {10, 11, 12, 13, 14},
        .reals = {0.5, -1.0},
    };
    meshtopo_reply_t *r = &s->r;
    r->kind = MESHTOPO_QUERY_T_VERTEX_RING;
    r->num_items = 2;
    r->item_status = s->item_status;
    r->num_item_offsets = 3;
    r->item_offsets = s->item_offsets;
    r->num_groups = 2;
    r->group_boundary = s->boundary;
    r->num_value_offsets = 3;
    r->value_offsets = s->value_offsets;
    r->value2_offsets = s->value2_offsets;
    r->num_values = 6;
    r->values = s->values;
    r->num_values2 = 5;
    r->values2 = s->values2;
    r->num_reals = 2;
    r->reals = s->reals;
}

static void reply_accessors(void)
{
    sample_reply s;
    sample_reply_init(&s);
    mt_diag diag;
    CHECK_OK(mt_client_reply_check(&s.r, &diag));
    CHECK_EQ(mt_client_reply_num_items(&s.r), 2);
    mt_client_item first = mt_client_reply_item(&s.r, 0);
    CHECK_EQ(first.status, MESHTOPO_STATUS_CODE_T_OK);
    CHECK_EQ(first.num_groups, 2);
    mt_client_group open = mt_client_item_group(&s.r, &first, 0);
    mt_client_group closed = mt_client_item_group(&s.r, &first, 1);
    CHECK(open.boundary && !closed.boundary);
    CHECK_EQ(open.num_values, 3);
    CHECK_EQ(open.num_values2, 2);
    CHECK_EQ(open.values[2], 3);
    CHECK_EQ(open.values2[1], 11);
    CHECK_EQ(closed.num_values, 3);
    CHECK_EQ(closed.num_values2, 3);
    CHECK_EQ(closed.values[0], 4);
    CHECK_EQ(closed.values2[2], 14);
    mt_client_item second = mt_client_reply_item(&s.r, 1);
    CHECK_EQ(second.status, MESHTOPO_STATUS_CODE_T_NOT_FOUND);
    CHECK_EQ(second.num_groups, 0);
    CHECK(mt_client_reply_real(&s.r, 0) == 0.5);
    CHECK(mt_client_reply_real(&s.r, 1) == -1.0);
    CHECK(mt_client_reply_real(&s.r, 2) != mt_client_reply_real(&s.r, 2)); /* NaN */
    /* An empty reply, with or without offsets (the daemon's error replies
     * carry one 0 each). */
    meshtopo_reply_t empty;
    memset(&empty, 0, sizeof empty);
    CHECK_OK(mt_client_reply_check(&empty, &diag));
    CHECK_EQ(mt_client_reply_num_items(&empty), 0);
    int32_t zero[1] = {0};
    empty.num_item_offsets = empty.num_value_offsets = 1;
    empty.item_offsets = empty.value_offsets = empty.value2_offsets = zero;
    CHECK_OK(mt_client_reply_check(&empty, NULL));
}

/* Every way offsets can fail to describe the arrays is refused, naming the
 * array and the entry. */
static void reply_check_names_the_fault(void)
{
    static const char *const needles[] = {
        "item_offsets has 2 entries, expected 3",
        "item_offsets[0] = 1, expected 0",
        "item_offsets[2] = 1 is below item_offsets[1] = 2",
        "item_offsets[2] = 1, expected num_groups = 2",
        "value_offsets[2] = 6 is below value_offsets[1] = 7",
        "value_offsets[2] = 5, expected num_values = 6",
        "value2_offsets[2] = 4, expected num_values2 = 5",
    };
    for (size_t i = 0; i < sizeof needles / sizeof needles[0]; i++) {
        sample_reply s;
        sample_reply_init(&s);
        switch (i) {
            case 0:
                s.r.num_item_offsets = 2;
                break;
            case 1:
                s.item_offsets[0] = 1;
                break;
            case 2:
                s.item_offsets[2] = 1;
                break;
            case 3:
                s.item_offsets[1] = 1, s.item_offsets[2] = 1;
                break;
            case 4:
                s.value_offsets[1] = 7, s.value_offsets[2] = 6;
                break;
            case 5:
                s.value_offsets[2] = 5;
                break;
            default:
                s.value2_offsets[2] = 4;
                break;
        }
        mt_diag diag;
        CHECK_STATUS(mt_client_reply_check(&s.r, &diag), MT_ERR_CORRUPT);
        if (!strstr(diag.message, needles[i]))
            mt_test_fail(__FILE__, __LINE__, "fault %zu: '%s' does not say '%s'", i, diag.message,
                         needles[i]);
    }
}

/* A reply whose offsets are wrong never reaches the caller. */
static void corrupt_reply_refused(void)
{
    fixture *f = fixture_start(MODE_CORRUPT, 2000, 0);
    uint32_t ids[] = {1, 2};
    meshtopo_reply_t reply;
    mt_diag diag;
    CHECK_STATUS(
        mt_client_query(f->client, "bunny", 0, MESHTOPO_QUERY_T_VALENCE, ids, 2, &reply, &diag),
        MT_ERR_CORRUPT);
    CHECK(strstr(diag.message, "value_offsets[2] = 1 is below") != NULL);
    CHECK_EQ(reply.num_items, 0); /* zeroed: nothing to walk */
    CHECK(reply.value_offsets == NULL);
    mt_client_reply_free(&reply);
    fixture_stop(f);
}

/* Publishes a heartbeat of `pid` on MESHTOPO_STATUS. */
static void publish_heartbeat(lcm_t *lcm, int32_t pid)
{
    meshtopo_status_t st;
    memset(&st, 0, sizeof st);
    st.pid = pid;
    st.name = "meshtopod";
    st.instance = "test";
    st.channel_prefix = "MESHTOPO_";
    st.last_error = "";
    st.cluster = "";
    CHECK_EQ(meshtopo_status_t_publish(lcm, "MESHTOPO_STATUS", &st), 0);
}

typedef struct heartbeats {
    lcm_t *lcm;
    atomic_int stop;
} heartbeats;

/* Publishes a heartbeat every 20 ms until told to stop. */
static void *heartbeat_thread(void *arg)
{
    heartbeats *h = arg;
    while (!atomic_load(&h->stop)) {
        publish_heartbeat(h->lcm, 4242);
        nanosleep(&(struct timespec){0, 20 * 1000000L}, NULL);
    }
    return NULL;
}

static void wait_daemon_sees_heartbeat(void)
{
    fixture *f = fixture_start(MODE_ANSWER, 100, 0);
    mt_diag diag;
    meshtopo_status_t *status = NULL;
    CHECK_STATUS(mt_client_wait_daemon(f->client, 150, &status, &diag), MT_ERR_IO);
    CHECK(strstr(diag.message, "timeout: no heartbeat") != NULL);
    CHECK(strstr(diag.message, "MESHTOPO_STATUS") != NULL);
    CHECK(status == NULL);
    heartbeats h = {.lcm = f->lcm};
    pthread_t t;
    CHECK(pthread_create(&t, NULL, heartbeat_thread, &h) == 0);
    CHECK_OK(mt_client_wait_daemon(f->client, 5000, &status, &diag));
    CHECK(status != NULL);
    if (status) {
        CHECK_EQ(status->pid, 4242);
        CHECK(strcmp(status->name, "meshtopod") == 0);
    }
    if (status) meshtopo_status_t_destroy(status);
    CHECK_OK(mt_client_wait_daemon(f->client, 5000, NULL, &diag)); /* no copy wanted */
    atomic_store(&h.stop, 1);
    pthread_join(t, NULL);
    fixture_stop(f);
}

typedef struct watched {
    atomic_int statuses, reports;
    atomic_int last_pid;
    atomic_int last_version;
} watched;

static void on_watched_status(const meshtopo_status_t *st, void *user)
{
    watched *w = user;
    atomic_store(&w->last_pid, st->pid);
    atomic_fetch_add(&w->statuses, 1);
}

static void on_watched_report(const meshtopo_topology_t *t, void *user)
{
    watched *w = user;
    atomic_store(&w->last_version, t->version);
    atomic_fetch_add(&w->reports, 1);
}

/* Polls until cond() or 5 s. */
static int eventually(const atomic_int *value, int at_least)
{
    for (int i = 0; i < 500 && atomic_load(value) < at_least; i++)
        nanosleep(&(struct timespec){0, 10 * 1000000L}, NULL);
    return atomic_load(value) >= at_least;
}

/* A watch that stops itself from its first callback. */
typedef struct self_stopping {
    mt_client_watch *watch;
    atomic_int calls;
} self_stopping;

static void stop_from_callback(const meshtopo_status_t *st, void *user)
{
    (void)st;
    self_stopping *s = user;
    atomic_fetch_add(&s->calls, 1);
    mt_client_watch_stop(s->watch);
}

static void watch_decodes_broadcasts(void)
{
    fixture *f = fixture_start(MODE_ANSWER, 100, 0);
    watched w = {0};
    mt_client_watch_fns fns = {on_watched_status, on_watched_report, &w};
    mt_client_watch *watch = NULL;
    mt_diag diag;
    CHECK_OK(mt_client_watch_start(f->client, &fns, &watch, &diag));
    publish_heartbeat(f->lcm, 7);
    meshtopo_topology_t report;
    memset(&report, 0, sizeof report);
    report.mesh_id = "room";
    report.version = 3;
    report.source = "";
    CHECK_EQ(meshtopo_topology_t_publish(f->lcm, "MESHTOPO_TOPOLOGY", &report), 0);
    static const uint8_t garbage[] = "not a status_t";
    CHECK_EQ(lcm_publish(f->lcm, "MESHTOPO_STATUS", garbage, sizeof garbage), 0);
    publish_heartbeat(f->lcm, 8);
    CHECK(eventually(&w.statuses, 2));
    CHECK(eventually(&w.reports, 1));
    CHECK_EQ(atomic_load(&w.last_pid), 8);
    CHECK_EQ(atomic_load(&w.last_version), 3);
    mt_client_stats st;
    mt_client_get_stats(f->client, &st);
    CHECK_EQ(st.undecodable, 1);
    mt_client_watch_stop(watch);
    /* Stopped: nothing more is called, even for messages sent right after. */
    publish_heartbeat(f->lcm, 9);
    CHECK_EQ(meshtopo_topology_t_publish(f->lcm, "MESHTOPO_TOPOLOGY", &report), 0);
    meshtopo_reply_t reply; /* a round trip through the client's thread */
    uint32_t id = 1;
    CHECK_OK(mt_client_query(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, &id, 1, &reply, &diag));
    mt_client_reply_free(&reply);
    CHECK_EQ(atomic_load(&w.statuses), 2);
    CHECK_EQ(atomic_load(&w.reports), 1);

    /* Stopped from its own callback: that callback finishes, no other runs. */
    self_stopping s = {.watch = NULL};
    mt_client_watch_fns self_fns = {.on_status = stop_from_callback, .user = &s};
    CHECK_OK(mt_client_watch_start(f->client, &self_fns, &s.watch, &diag));
    publish_heartbeat(f->lcm, 10);
    publish_heartbeat(f->lcm, 11);
    publish_heartbeat(f->lcm, 12);
    CHECK_OK(mt_client_query(f->client, "m", 0, MESHTOPO_QUERY_T_VALENCE, &id, 1, &reply, &diag));
    mt_client_reply_free(&reply);
    CHECK_EQ(atomic_load(&s.calls), 1);
    fixture_stop(f);
}

static const mt_test_case cases[] = {
    {"memq_is_per_instance", memq_is_per_instance},
    {"query_answered", query_answered},
    {"retry_reuses_request_id", retry_reuses_request_id},
    {"busy_retried_with_backoff", busy_retried_with_backoff},
    {"busy_until_retries_spent", busy_until_retries_spent},
    {"conflicting_answers_counted", conflicting_answers_counted},
    {"timeout_after_retries", timeout_after_retries},
    {"garbage_and_foreign_replies_ignored", garbage_and_foreign_replies_ignored},
    {"many_threads_one_client", many_threads_one_client},
    {"async_answer_and_timeout", async_answer_and_timeout},
    {"async_destroy_calls_back", async_destroy_calls_back},
    {"error_status_mapped", error_status_mapped},
    {"list_answered", list_answered},
    {"submit_ack_and_content_hash", submit_ack_and_content_hash},
    {"bad_arguments", bad_arguments},
    {"sync_call_from_callback_refused", sync_call_from_callback_refused},
    {"external_handle_loop", external_handle_loop},
    {"reply_channel_private", reply_channel_private},
    {"reply_accessors", reply_accessors},
    {"reply_check_names_the_fault", reply_check_names_the_fault},
    {"corrupt_reply_refused", corrupt_reply_refused},
    {"wait_daemon_sees_heartbeat", wait_daemon_sees_heartbeat},
    {"watch_decodes_broadcasts", watch_decodes_broadcasts},
};
const mt_test_table mt_tests_client = {cases, sizeof cases / sizeof cases[0]};
