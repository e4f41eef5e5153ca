/* meshtopod's chunked submissions (msgs/mesh_chunk_t.lcm) over in-process
 * LCM (memq://): chunks out of order and duplicated, two transfers
 * interleaved, chunks that lie (BAD_REQUEST naming the field, the transfer
 * unharmed), a transfer abandoned half way (expired, memory released, seen
 * in the heartbeat), a sender restarting under a new id and channel
 * (resumed), the memory cap (BUSY, TOO_LARGE), pieces cutting values in two,
 * counts that do not fit the content (UNDECODABLE), and meshtopo::client
 * choosing chunks by itself. Every mesh is built once and checked with the sender's
 * content hash; the in-process builds are validated. */
#include <inttypes.h>
#include <lcm/lcm.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "daemon.h"
#include "harness.h"
#include "meshtopo/client.h"
#include "meshtopo/content_hash.h"
#include "meshtopo/core.h"

#define REPLY "TEST_REPLY"
#define REPLY2 "TEST_REPLY_RESTARTED"
#define MAX_RECEIVED 256
#define CHUNK 4096

typedef struct received {
    void *data;
    size_t size;
} received;

typedef struct fixture {
    lcm_t *lcm;
    mtd_daemon *daemon;
    received inbox[MAX_RECEIVED];
    size_t num_inbox;
    meshtopo_status_t status;
    bool have_status;
} fixture;

/* A mesh encoded as mesh_t: its content is the tail the chunks carry. */
typedef struct sent_mesh {
    mt_face_list list;
    void *encoded;
    size_t size;
    const uint8_t *content;
    uint64_t total, hash;
    const char *mesh_id;
} sent_mesh;

static void on_reply(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    fixture *fx = user;
    if (fx->num_inbox == MAX_RECEIVED) return;
    void *copy = malloc(rbuf->data_size);
    memcpy(copy, rbuf->data, rbuf->data_size);
    fx->inbox[fx->num_inbox++] = (received){copy, rbuf->data_size};
}

static void on_status(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    fixture *fx = user;
    if (fx->have_status) meshtopo_status_t_decode_cleanup(&fx->status);
    fx->have_status = mt_msgs_decode(&mt_msgs_type_status, rbuf->data, rbuf->data_size, &fx->status,
                                     NULL, 0) == 0;
}

/* The daemon's options: two workers, the given transfer limits. */
static void fixture_config(mtd_config *config, const char *max_transfer, const char *timeout_ms)
{
    char *argv[] = {"meshtopod",
                    "--workers",
                    "2",
                    "--log-level",
                    "error",
                    "--max-transfer-bytes",
                    (char *)max_transfer,
                    "--transfer-timeout-ms",
                    (char *)timeout_ms};
    mtd_config_action action;
    mt_diag diag;
    CHECK_OK(mtd_config_parse(9, argv, config, &action, &diag));
}

static void fixture_start(fixture *fx, const mtd_config *config)
{
    memset(fx, 0, sizeof *fx);
    mt_diag diag;
    mtd_log_set_level(config->log_level);
    fx->lcm = lcm_create("memq://");
    CHECK(fx->lcm != NULL);
    CHECK_OK(mtd_daemon_create(config, fx->lcm, NULL, &fx->daemon, &diag));
    lcm_subscribe(fx->lcm, REPLY "_(ACK|TRANSFER)", on_reply, fx);
    lcm_subscribe(fx->lcm, REPLY2 "_(ACK|TRANSFER)", on_reply, fx);
    lcm_subscribe(fx->lcm, "MESHTOPO_STATUS", on_status, fx);
}

static void fixture_init(fixture *fx, const char *max_transfer, const char *timeout_ms)
{
    mtd_config config;
    fixture_config(&config, max_transfer, timeout_ms);
    fixture_start(fx, &config);
}

static void fixture_free(fixture *fx)
{
    mtd_daemon_destroy(fx->daemon);
    lcm_destroy(fx->lcm);
    for (size_t i = 0; i < fx->num_inbox; i++) free(fx->inbox[i].data);
    if (fx->have_status) meshtopo_status_t_decode_cleanup(&fx->status);
}

/* A grid of nx * ny quads as triangles, encoded as mesh_t. */
static void sent_mesh_make(sent_mesh *s, const char *mesh_id, uint32_t nx, uint32_t ny)
{
    memset(s, 0, sizeof *s);
    s->mesh_id = mesh_id;
    CHECK_OK(mt_gen_grid(nx, ny, true, &s->list));
    mt_mesh *mesh = NULL;
    mt_diag diag;
    mt_build_options bo = {.strict = false, .threads = 1};
    CHECK_OK(mt_mesh_build(&s->list, &bo, &mesh, &diag));
    CHECK_OK(mt_mesh_validate(mesh, &diag));
    mt_mesh_destroy(mesh);
    meshtopo_mesh_t m;
    memset(&m, 0, sizeof m);
    m.utime = 1700000000000000;
    m.reply_channel = REPLY;
    m.mesh_id = (char *)mesh_id;
    m.source = "test_chunks";
    m.num_verts = (int32_t)s->list.num_verts;
    m.num_position_values = 3 * (int32_t)s->list.num_verts;
    m.positions = s->list.positions;
    m.num_faces = (int32_t)s->list.num_faces;
    m.face_vertex_counts = (int32_t *)s->list.face_sizes;
    m.num_indices = (int32_t)s->list.num_indices;
    m.face_vertex_indices = (int32_t *)s->list.face_indices;
    int size = meshtopo_mesh_t_encoded_size(&m);
    s->encoded = malloc((size_t)size);
    CHECK_EQ(meshtopo_mesh_t_encode(s->encoded, 0, size, &m), size);
    s->size = (size_t)size;
    s->total = 16 + 8ull * (uint64_t)m.num_position_values + 4ull * s->list.num_faces +
               4ull * s->list.num_indices;
    s->content = (const uint8_t *)s->encoded + (s->size - s->total);
    s->hash = mt_msgs_mesh_content_hash(&m, s->encoded, s->size);
    CHECK(s->hash != 0);
}

static void sent_mesh_free(sent_mesh *s)
{
    free(s->encoded);
    mt_face_list_free(&s->list);
}

static size_t num_chunks(const sent_mesh *s)
{
    return (size_t)((s->total + CHUNK - 1) / CHUNK);
}

/* A chunk of s as request request_id on channel; the caller may change it
 * before publish_chunk. */
static meshtopo_mesh_chunk_t chunk_of(const sent_mesh *s, const char *channel, int64_t request_id,
                                      size_t index, bool want_status)
{
    meshtopo_mesh_chunk_t c;
    memset(&c, 0, sizeof c);
    c.utime = 1700000000000000;
    c.request_id = request_id;
    c.reply_channel = (char *)channel;
    c.mesh_id = (char *)s->mesh_id;
    c.source = "test_chunks";
    c.total_size = (int64_t)s->total;
    c.content_hash = (int64_t)s->hash;
    c.want_status = want_status;
    uint64_t offset = (uint64_t)index * CHUNK;
    c.offset = (int64_t)offset;
    c.length = (int32_t)(s->total - offset < CHUNK ? s->total - offset : CHUNK);
    c.data = (uint8_t *)(uintptr_t)(s->content + offset);
    return c;
}

static void publish_chunk(fixture *fx, const meshtopo_mesh_chunk_t *c)
{
    int size = meshtopo_mesh_chunk_t_encoded_size(c);
    void *buf = malloc((size_t)size);
    CHECK_EQ(meshtopo_mesh_chunk_t_encode(buf, 0, size, c), size);
    CHECK_EQ(lcm_publish(fx->lcm, "MESHTOPO_SUBMIT_CHUNK", buf, (unsigned)size), 0);
    free(buf);
}

static void send_chunk(fixture *fx, const sent_mesh *s, const char *channel, int64_t request_id,
                       size_t index, bool want_status)
{
    meshtopo_mesh_chunk_t c = chunk_of(s, channel, request_id, index, want_status);
    publish_chunk(fx, &c);
}

/* A poll: an empty chunk asking for the status. */
static void send_poll(fixture *fx, const sent_mesh *s, const char *channel, int64_t request_id)
{
    meshtopo_mesh_chunk_t c = chunk_of(s, channel, request_id, 0, true);
    c.length = 0;
    publish_chunk(fx, &c);
}

static int64_t request_id_of(const mt_msgs_type *type, const void *msg)
{
    if (type == &mt_msgs_type_ack) return ((const meshtopo_ack_t *)msg)->request_id;
    return ((const meshtopo_mesh_transfer_t *)msg)->request_id;
}

/* Handles LCM until a message of `type` for request_id arrives (into out,
 * decode_cleanup it) or 20 s pass. Returns 0 when found. Other messages of
 * the type for the request that came before it are dropped. */
static int wait_for(fixture *fx, const mt_msgs_type *type, int64_t request_id, void *out, int line)
{
    for (int round = 0; round < 400; round++) {
        lcm_handle_timeout(fx->lcm, round == 0 ? 0 : 50);
        for (size_t i = 0; i < fx->num_inbox; i++) {
            received *r = &fx->inbox[i];
            if (mt_msgs_type_of(r->data, r->size) != type) continue;
            if (mt_msgs_decode(type, r->data, r->size, out, NULL, 0) != 0) continue;
            if (request_id_of(type, out) == request_id) {
                free(r->data);
                memmove(&fx->inbox[i], &fx->inbox[i + 1],
                        (fx->num_inbox - i - 1) * sizeof *fx->inbox);
                fx->num_inbox--;
                return 0;
            }
            type->decode_cleanup(out);
        }
    }
    mt_test_fail(__FILE__, line, "no %s for request %" PRId64 " within 20 s", type->name,
                 request_id);
    return -1;
}

/* Drops every message received so far (after handling what is queued). */
static void drain(fixture *fx)
{
    while (lcm_handle_timeout(fx->lcm, 20) > 0) {
    }
    for (size_t i = 0; i < fx->num_inbox; i++) free(fx->inbox[i].data);
    fx->num_inbox = 0;
}

/* Waits for the ack of a complete transfer and checks it: OK, the sender's
 * content hash, the grid's counts. Returns the version. */
static int32_t expect_ack(fixture *fx, const sent_mesh *s, int64_t request_id, int line)
{
    meshtopo_ack_t ack;
    if (wait_for(fx, &mt_msgs_type_ack, request_id, &ack, line) != 0) return 0;
    if (ack.status != 0) mt_test_fail(__FILE__, line, "ack: %s", ack.error);
    if ((uint64_t)ack.content_hash != s->hash)
        mt_test_fail(__FILE__, line, "ack content hash %016" PRIx64 ", sent %016" PRIx64,
                     (uint64_t)ack.content_hash, s->hash);
    CHECK_EQ(ack.num_reports, 1);
    if (ack.num_reports == 1) {
        CHECK_EQ(ack.reports[0].num_faces, s->list.num_faces);
        CHECK_EQ(ack.reports[0].num_verts, s->list.num_verts);
        CHECK_EQ(ack.reports[0].num_defects, 0);
    }
    int32_t version = ack.version;
    meshtopo_ack_t_decode_cleanup(&ack);
    return version;
}

/* Waits for a mesh_transfer_t with `status` whose error names `needle`. */
static void expect_transfer_error(fixture *fx, int64_t request_id, int32_t status,
                                  const char *needle, int line)
{
    meshtopo_mesh_transfer_t t;
    if (wait_for(fx, &mt_msgs_type_mesh_transfer, request_id, &t, line) != 0) return;
    if (t.status != status)
        mt_test_fail(__FILE__, line, "status %d, expected %d (error '%s')", (int)t.status,
                     (int)status, t.error);
    else if (!strstr(t.error, needle))
        mt_test_fail(__FILE__, line, "error '%s' does not name '%s'", t.error, needle);
    meshtopo_mesh_transfer_t_decode_cleanup(&t);
}

/* One period of the daemon's loop: stalled transfers expire, then the
 * heartbeat goes out. */
static void heartbeat(fixture *fx)
{
    mtd_daemon_tick(fx->daemon);
    lcm_handle_timeout(fx->lcm, 100);
    CHECK(fx->have_status);
}

/* Version `version` of s as the daemon stores it has s's positions, bit for
 * bit, and the topology of s built in-process: the chunks' bytes were turned
 * into the right values whatever their sizes and order. */
static void expect_stored(fixture *fx, const sent_mesh *s, int32_t version, int line)
{
    mtd_mesh_entry *entry = NULL;
    if (mtd_store_acquire(mtd_daemon_store(fx->daemon), s->mesh_id, (uint32_t)version, &entry,
                          NULL) != MT_OK) {
        mt_test_fail(__FILE__, line, "version %d of '%s' is not stored", (int)version, s->mesh_id);
        return;
    }
    const mt_mesh *held = mtd_entry_mesh(entry);
    mt_diag diag;
    CHECK_OK(mt_mesh_validate(held, &diag));
    mt_mesh_view view;
    mt_mesh_get_view(held, &view);
    if (!view.positions ||
        memcmp(view.positions, s->list.positions, sizeof(double) * 3 * s->list.num_verts) != 0)
        mt_test_fail(__FILE__, line, "the stored positions differ from the sent ones");
    mt_mesh *local = NULL;
    mt_build_options bo = {.strict = false, .threads = 1};
    CHECK_OK(mt_mesh_build(&s->list, &bo, &local, &diag));
    const mt_report *a = mt_mesh_report(held), *b = mt_mesh_report(local);
    CHECK_EQ(a->num_verts, b->num_verts);
    CHECK_EQ(a->num_faces_valid, b->num_faces_valid);
    CHECK_EQ(a->num_edges, b->num_edges);
    CHECK_EQ(a->boundary_edges, b->boundary_edges);
    CHECK_EQ(a->boundary_loops, b->boundary_loops);
    CHECK_EQ(a->euler_characteristic, b->euler_characteristic);
    CHECK_EQ(a->out_of_range_indices, 0);
    mt_mesh_destroy(local);
    mtd_entry_release(entry);
}

/* A piece of s's content: bytes [offset, offset + length). */
static void send_piece(fixture *fx, const sent_mesh *s, int64_t request_id, uint64_t offset,
                       uint64_t length, bool want_status)
{
    meshtopo_mesh_chunk_t c = chunk_of(s, REPLY, request_id, 0, want_status);
    c.offset = (int64_t)offset;
    c.length = (int32_t)length;
    c.data = (uint8_t *)(uintptr_t)(s->content + offset);
    publish_chunk(fx, &c);
}

/* Chunks in reverse order, each sent twice; a poll half way lists exactly the
 * chunks not yet sent; the mesh is built once. */
static void test_out_of_order_duplicates(void)
{
    fixture fx;
    fixture_init(&fx, "64M", "10000");
    sent_mesh s;
    sent_mesh_make(&s, "reverse", 30, 30);
    size_t n = num_chunks(&s);
    CHECK(n > 8);
    size_t half = n / 2;
    for (size_t k = n; k-- > half;) {
        send_chunk(&fx, &s, REPLY, 7, k, false);
        send_chunk(&fx, &s, REPLY, 7, k, false);
    }
    send_poll(&fx, &s, REPLY, 7);
    meshtopo_mesh_transfer_t t;
    if (wait_for(&fx, &mt_msgs_type_mesh_transfer, 7, &t, __LINE__) == 0) {
        CHECK_EQ(t.status, 0);
        CHECK(!t.complete);
        CHECK_EQ(t.total_size, (int64_t)s.total);
        CHECK_EQ(t.received_bytes, (int64_t)(s.total - half * CHUNK));
        CHECK_EQ(t.listed_until, (int64_t)s.total);
        CHECK_EQ(t.num_missing, 1);
        if (t.num_missing == 1) {
            CHECK_EQ(t.missing_offsets[0], 0);
            CHECK_EQ(t.missing_lengths[0], (int64_t)(half * CHUNK));
        }
        meshtopo_mesh_transfer_t_decode_cleanup(&t);
    }
    for (size_t k = half; k-- > 0;) {
        send_chunk(&fx, &s, REPLY, 7, k, false);
        send_chunk(&fx, &s, REPLY, 7, k, false);
    }
    CHECK_EQ(expect_ack(&fx, &s, 7, __LINE__), 1);
    /* Chunks arriving after the ack get the ack again, and build nothing. */
    send_chunk(&fx, &s, REPLY, 7, 0, true);
    CHECK_EQ(expect_ack(&fx, &s, 7, __LINE__), 1);
    drain(&fx);
    heartbeat(&fx);
    CHECK_EQ(fx.status.builds, 1);
    CHECK_EQ(fx.status.submissions, 1);
    CHECK_EQ(fx.status.transfers_completed, 1);
    CHECK_EQ(fx.status.transfers_active, 0);
    CHECK_EQ(fx.status.transfer_bytes, 0);
    CHECK_EQ(fx.status.chunks, (int64_t)(2 * n + 2));
    CHECK_EQ(fx.status.errors, 0);
    sent_mesh_free(&s);
    fixture_free(&fx);
}

/* Two transfers on the same channel, chunk by chunk in turn: each mesh is
 * built from its own bytes. */
static void test_interleaved(void)
{
    fixture fx;
    fixture_init(&fx, "64M", "10000");
    sent_mesh a, b;
    sent_mesh_make(&a, "alpha", 30, 30);
    sent_mesh_make(&b, "beta", 25, 40);
    size_t na = num_chunks(&a), nb = num_chunks(&b);
    for (size_t k = 0; k < na || k < nb; k++) {
        if (k < na) send_chunk(&fx, &a, REPLY, 100, k, false);
        if (k < nb) send_chunk(&fx, &b, REPLY, 200, k, false);
    }
    CHECK_EQ(expect_ack(&fx, &a, 100, __LINE__), 1);
    CHECK_EQ(expect_ack(&fx, &b, 200, __LINE__), 1);
    drain(&fx);
    heartbeat(&fx);
    CHECK_EQ(fx.status.builds, 2);
    CHECK_EQ(fx.status.transfers_completed, 2);
    CHECK_EQ(fx.status.transfers_active, 0);
    sent_mesh_free(&a);
    sent_mesh_free(&b);
    fixture_free(&fx);
}

/* Chunks that lie about offset, length, total, hash or mesh id are refused
 * with BAD_REQUEST naming the field (a chunk cut short: UNDECODABLE); the
 * transfer they claim to belong to completes unharmed. */
static void test_lying_chunks(void)
{
    fixture fx;
    fixture_init(&fx, "64M", "10000");
    sent_mesh s;
    sent_mesh_make(&s, "honest", 30, 30);
    size_t n = num_chunks(&s);
    for (size_t k = 0; k < n / 2; k++) send_chunk(&fx, &s, REPLY, 9, k, false);

    meshtopo_mesh_chunk_t c = chunk_of(&s, REPLY, 9, n - 1, true);
    c.offset = (int64_t)s.total - 10; /* reaches past the end */
    publish_chunk(&fx, &c);
    expect_transfer_error(&fx, 9, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "reaches past total_size",
                          __LINE__);
    c = chunk_of(&s, REPLY, 9, 1, true);
    c.offset = -4096;
    publish_chunk(&fx, &c);
    expect_transfer_error(&fx, 9, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "offset: -4096 is negative",
                          __LINE__);
    c = chunk_of(&s, REPLY, 9, 1, true);
    c.total_size = (int64_t)s.total + 100; /* inconsistent total; bytes fit either */
    publish_chunk(&fx, &c);
    expect_transfer_error(&fx, 9, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "total_size", __LINE__);
    c = chunk_of(&s, REPLY, 9, 1, true);
    c.content_hash ^= 1;
    publish_chunk(&fx, &c);
    expect_transfer_error(&fx, 9, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "content_hash", __LINE__);
    c = chunk_of(&s, REPLY, 9, 1, true);
    c.mesh_id = "other";
    publish_chunk(&fx, &c);
    expect_transfer_error(&fx, 9, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "mesh_id", __LINE__);
    c = chunk_of(&s, REPLY, 9, 1, true);
    c.total_size = 0;
    publish_chunk(&fx, &c);
    expect_transfer_error(&fx, 9, MESHTOPO_STATUS_CODE_T_BAD_REQUEST, "must be positive", __LINE__);
    /* A length larger than the bytes that follow: the message is cut short. */
    c = chunk_of(&s, REPLY, 9, 1, true);
    int size = meshtopo_mesh_chunk_t_encoded_size(&c);
    uint8_t *buf = malloc((size_t)size);
    CHECK_EQ(meshtopo_mesh_chunk_t_encode(buf, 0, size, &c), size);
    CHECK_EQ(lcm_publish(fx.lcm, "MESHTOPO_SUBMIT_CHUNK", buf, (unsigned)(size - 100)), 0);
    free(buf);
    expect_transfer_error(&fx, 9, MESHTOPO_STATUS_CODE_T_UNDECODABLE, "mesh_chunk_t", __LINE__);

    /* The honest transfer still holds its first half and completes. */
    send_poll(&fx, &s, REPLY, 9);
    meshtopo_mesh_transfer_t t;
    if (wait_for(&fx, &mt_msgs_type_mesh_transfer, 9, &t, __LINE__) == 0) {
        CHECK_EQ(t.status, 0);
        CHECK_EQ(t.received_bytes, (int64_t)(n / 2) * CHUNK);
        meshtopo_mesh_transfer_t_decode_cleanup(&t);
    }
    for (size_t k = n / 2; k < n; k++) send_chunk(&fx, &s, REPLY, 9, k, false);
    CHECK_EQ(expect_ack(&fx, &s, 9, __LINE__), 1);
    drain(&fx);
    heartbeat(&fx);
    CHECK_EQ(fx.status.builds, 1);
    CHECK_EQ(fx.status.errors, 7);
    sent_mesh_free(&s);
    fixture_free(&fx);
}

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

/* A sender that stops half way: after the timeout the transfer is dropped
 * and its memory released (heartbeat); its next chunk starts afresh. */
static void test_abandoned(void)
{
    fixture fx;
    fixture_init(&fx, "64M", "200");
    sent_mesh s;
    sent_mesh_make(&s, "abandoned", 30, 30);
    size_t n = num_chunks(&s);
    for (size_t k = 0; k < n / 2; k++) send_chunk(&fx, &s, REPLY, 11, k, false);
    drain(&fx);
    heartbeat(&fx);
    CHECK_EQ(fx.status.transfers_active, 1);
    CHECK(fx.status.transfer_bytes >= (int64_t)s.total);
    CHECK_EQ(fx.status.transfers_expired, 0);
    sleep_ms(400);
    heartbeat(&fx);
    CHECK_EQ(fx.status.transfers_active, 0);
    CHECK_EQ(fx.status.transfer_bytes, 0);
    CHECK_EQ(fx.status.transfers_expired, 1);
    CHECK_EQ(fx.status.builds, 0);
    send_poll(&fx, &s, REPLY, 11);
    meshtopo_mesh_transfer_t t;
    if (wait_for(&fx, &mt_msgs_type_mesh_transfer, 11, &t, __LINE__) == 0) {
        CHECK_EQ(t.status, 0);
        CHECK_EQ(t.received_bytes, 0);
        CHECK_EQ(t.num_missing, 1);
        meshtopo_mesh_transfer_t_decode_cleanup(&t);
    }
    for (size_t k = 0; k < n; k++) send_chunk(&fx, &s, REPLY, 11, k, false);
    CHECK_EQ(expect_ack(&fx, &s, 11, __LINE__), 1);
    sent_mesh_free(&s);
    fixture_free(&fx);
}

/* A poll claiming 1 GiB and one-byte chunks spread across it: nothing is
 * charged for the claim, chunks beyond the window are dropped, memory stays
 * flat, and an honest sender beside it is neither refused nor slowed;
 * once the claimer stops, its transfer expires and everything is given
 * back. */
static void test_claims_cost_only_what_is_sent(void)
{
    fixture fx;
    fixture_init(&fx, "1G", "300");
    long rss_before = mt_test_rss_kb();
    uint8_t byte = 7;
    meshtopo_mesh_chunk_t c;
    memset(&c, 0, sizeof c);
    c.request_id = 90;
    c.reply_channel = REPLY2;
    c.mesh_id = "claim";
    c.source = "hostile";
    c.total_size = (int64_t)1 << 30;
    c.content_hash = 12345;
    c.want_status = true;
    publish_chunk(&fx, &c);
    meshtopo_mesh_transfer_t t;
    if (wait_for(&fx, &mt_msgs_type_mesh_transfer, 90, &t, __LINE__) == 0) {
        CHECK_EQ(t.status, 0);
        meshtopo_mesh_transfer_t_decode_cleanup(&t);
    }
    heartbeat(&fx);
    CHECK_EQ(fx.status.transfers_active, 1);
    CHECK_EQ(fx.status.transfer_bytes, 0);
    /* One byte every MiB: only those within the window are kept. */
    c.want_status = false;
    c.length = 1;
    c.data = &byte;
    for (int k = 0; k < 1024; k++) {
        c.offset = ((int64_t)k << 20) + 1;
        publish_chunk(&fx, &c);
        if (k % 64 == 0) drain(&fx);
    }
    drain(&fx);
    mtd_transfer_stats stats;
    mtd_transfers_get_stats(mtd_daemon_transfers(fx.daemon), &stats);
    CHECK_EQ(stats.dropped, 1024 - MESHTOPO_MESH_CHUNK_T_WINDOW_BYTES / (1 << 20));
    CHECK(stats.bytes <= MESHTOPO_MESH_CHUNK_T_WINDOW_BYTES + (64 << 10));
    CHECK(mt_test_rss_kb() - rss_before < 16 * 1024);
    /* The honest sender is served at once. */
    sent_mesh s;
    sent_mesh_make(&s, "honest", 60, 60);
    for (size_t k = 0; k < num_chunks(&s); k++) send_chunk(&fx, &s, REPLY, 91, k, false);
    CHECK_EQ(expect_ack(&fx, &s, 91, __LINE__), 1);
    /* The claimer goes quiet: its transfer expires, memory comes back. */
    sleep_ms(400);
    heartbeat(&fx);
    CHECK_EQ(fx.status.transfers_active, 0);
    CHECK_EQ(fx.status.transfer_bytes, 0);
    CHECK_EQ(fx.status.transfers_expired, 1);
    CHECK(mt_test_rss_kb() - rss_before < 16 * 1024);
    sent_mesh_free(&s);
    fixture_free(&fx);
}

/* Scattered one-byte chunks within the window: at most RANGES_MAX separate
 * ranges are kept, the rest dropped; a reply channel holding transfers
 * beside another one's gets BUSY past its share, and the other goes on. */
static void test_ranges_and_shares(void)
{
    fixture fx;
    fixture_init(&fx, "4M", "10000");
    uint8_t byte = 1;
    meshtopo_mesh_chunk_t c;
    memset(&c, 0, sizeof c);
    c.request_id = 95;
    c.reply_channel = REPLY2;
    c.mesh_id = "scatter";
    c.source = "hostile";
    c.total_size = 3 << 20;
    c.content_hash = 1;
    c.length = 1;
    c.data = &byte;
    for (int k = 0; k < MESHTOPO_MESH_CHUNK_T_RECEIVED_RANGES_MAX + 100; k++) {
        c.offset = 2 + 2 * (int64_t)k; /* never touching: one range each */
        publish_chunk(&fx, &c);
        if (k % 256 == 0) drain(&fx);
    }
    drain(&fx);
    mtd_transfer_stats stats;
    mtd_transfers_get_stats(mtd_daemon_transfers(fx.daemon), &stats);
    CHECK_EQ(stats.dropped, 100);
    /* A second transfer of the same channel reaching 3 MiB: past a quarter
     * of 4M while REPLY has a transfer too. */
    sent_mesh s;
    sent_mesh_make(&s, "honest", 40, 40);
    send_chunk(&fx, &s, REPLY, 96, 0, false);
    c.request_id = 97;
    c.want_status = true;
    c.offset = (3 << 20) - 1;
    c.length = 1;
    c.mesh_id = "second";
    c.total_size = 3 << 20;
    publish_chunk(&fx, &c);
    expect_transfer_error(&fx, 97, MESHTOPO_STATUS_CODE_T_BUSY, "its share", __LINE__);
    for (size_t k = 1; k < num_chunks(&s); k++) send_chunk(&fx, &s, REPLY, 96, k, false);
    CHECK_EQ(expect_ack(&fx, &s, 96, __LINE__), 1);
    sent_mesh_free(&s);
    fixture_free(&fx);
}

/* A sender restarts: under a new request id and reply channel, the same
 * content resumes where the old transfer stopped; and a restart under the
 * same id (all chunks again) after the ack builds nothing twice. */
static void test_restart(void)
{
    fixture fx;
    fixture_init(&fx, "64M", "10000");
    sent_mesh s;
    sent_mesh_make(&s, "restarted", 30, 30);
    size_t n = num_chunks(&s);
    for (size_t k = 0; k < n / 2; k++) send_chunk(&fx, &s, REPLY, 21, k, false);
    send_poll(&fx, &s, REPLY2, 5000);
    meshtopo_mesh_transfer_t t;
    if (wait_for(&fx, &mt_msgs_type_mesh_transfer, 5000, &t, __LINE__) == 0) {
        CHECK_EQ(t.status, 0);
        CHECK_EQ(t.received_bytes, (int64_t)(n / 2) * CHUNK);
        CHECK_EQ(t.num_missing, 1);
        if (t.num_missing == 1) CHECK_EQ(t.missing_offsets[0], (int64_t)(n / 2) * CHUNK);
        meshtopo_mesh_transfer_t_decode_cleanup(&t);
    }
    drain(&fx);
    heartbeat(&fx);
    CHECK_EQ(fx.status.transfers_active, 1); /* the old one was taken over */
    for (size_t k = n / 2; k < n; k++) send_chunk(&fx, &s, REPLY2, 5000, k, false);
    CHECK_EQ(expect_ack(&fx, &s, 5000, __LINE__), 1);
    for (size_t k = 0; k < n; k++) send_chunk(&fx, &s, REPLY2, 5000, k, k + 1 == n);
    CHECK_EQ(expect_ack(&fx, &s, 5000, __LINE__), 1);
    drain(&fx);
    heartbeat(&fx);
    CHECK_EQ(fx.status.builds, 1);
    CHECK_EQ(fx.status.transfers_active, 0);
    sent_mesh_free(&s);
    fixture_free(&fx);
}

/* --max-transfer-bytes: a transfer larger than the cap is TOO_LARGE; one
 * that fits alone but not beside another unfinished one is BUSY, and gets in
 * once the first is done. */
static void test_over_limit(void)
{
    fixture fx;
    fixture_init(&fx, "100k", "10000");
    sent_mesh a, b, big;
    sent_mesh_make(&a, "first", 30, 30);
    sent_mesh_make(&b, "second", 30, 31);
    sent_mesh_make(&big, "big", 60, 60);
    CHECK(a.total + b.total > 100 * 1024);
    CHECK(big.total > 100 * 1024);
    send_chunk(&fx, &big, REPLY, 31, 0, true);
    expect_transfer_error(&fx, 31, MESHTOPO_STATUS_CODE_T_TOO_LARGE, "--max-transfer-bytes",
                          __LINE__);
    send_chunk(&fx, &a, REPLY, 32, 0, true);
    meshtopo_mesh_transfer_t t;
    if (wait_for(&fx, &mt_msgs_type_mesh_transfer, 32, &t, __LINE__) == 0) {
        CHECK_EQ(t.status, 0);
        meshtopo_mesh_transfer_t_decode_cleanup(&t);
    }
    send_chunk(&fx, &b, REPLY, 33, 0, true);
    expect_transfer_error(&fx, 33, MESHTOPO_STATUS_CODE_T_BUSY, "retry later", __LINE__);
    for (size_t k = 1; k < num_chunks(&a); k++) send_chunk(&fx, &a, REPLY, 32, k, false);
    CHECK_EQ(expect_ack(&fx, &a, 32, __LINE__), 1);
    for (size_t k = 0; k < num_chunks(&b); k++) send_chunk(&fx, &b, REPLY, 33, k, false);
    CHECK_EQ(expect_ack(&fx, &b, 33, __LINE__), 1);
    drain(&fx);
    heartbeat(&fx);
    CHECK_EQ(fx.status.transfers_refused, 2);
    CHECK_EQ(fx.status.builds, 2);
    CHECK_EQ(fx.status.transfer_bytes, 0);
    sent_mesh_free(&a);
    sent_mesh_free(&b);
    sent_mesh_free(&big);
    fixture_free(&fx);
}

/* Pieces of odd sizes that cut values in two, the first ones again after the
 * daemon has turned them into values, then the rest backwards: the stored
 * mesh is the sent one. */
static void test_odd_pieces(void)
{
    fixture fx;
    fixture_init(&fx, "64M", "10000");
    sent_mesh s;
    sent_mesh_make(&s, "odd", 25, 25);
    const uint64_t piece = 997; /* prime: cuts doubles and ints anywhere */
    const uint64_t n = (s.total + piece - 1) / piece;
    CHECK(n > 20);
    for (uint64_t k = 0; k < n / 2; k++) send_piece(&fx, &s, 21, k * piece, piece, false);
    for (uint64_t k = 0; k < 3; k++) /* sent again: below the decoded bytes */
        send_piece(&fx, &s, 21, k * piece + 5, piece - 5, false);
    for (uint64_t k = n; k-- > n / 2;) {
        uint64_t at = k * piece;
        send_piece(&fx, &s, 21, at, s.total - at < piece ? s.total - at : piece, false);
    }
    int32_t version = expect_ack(&fx, &s, 21, __LINE__);
    CHECK_EQ(version, 1);
    expect_stored(&fx, &s, version, __LINE__);
    sent_mesh_free(&s);
    fixture_free(&fx);
}

/* Waits for the ack of request_id and checks it refuses the mesh with
 * `status`, naming `needle`. */
static void expect_ack_error(fixture *fx, int64_t request_id, int32_t status, const char *needle,
                             int line)
{
    meshtopo_ack_t ack;
    if (wait_for(fx, &mt_msgs_type_ack, request_id, &ack, line) != 0) return;
    if (ack.status != status)
        mt_test_fail(__FILE__, line, "ack status %d, expected %d (error '%s')", (int)ack.status,
                     (int)status, ack.error);
    else if (!strstr(ack.error, needle))
        mt_test_fail(__FILE__, line, "ack error '%s' does not name '%s'", ack.error, needle);
    meshtopo_ack_t_decode_cleanup(&ack);
}

/* Content whose hash is right but whose counts do not describe its bytes:
 * UNDECODABLE naming the count, nothing built, the daemon unharmed; the
 * content buffer is kept and reused without its old bytes showing. */
static void test_counts_that_do_not_fit(void)
{
    fixture fx;
    fixture_init(&fx, "64M", "10000");
    sent_mesh s;
    sent_mesh_make(&s, "liar", 10, 10);
    uint8_t *content = malloc(s.total);
    const struct {
        uint64_t at;   /* the count's offset in the content */
        int32_t value; /* written big-endian */
        const char *needle;
    } lies[] = {
        {4, -3, "num_position_values: -3 is negative"},
        {4, 3 * 100000, "num_position_values"},
        {8 + 8 * 3 * (uint64_t)s.list.num_verts, s.list.num_faces + 1, "num_indices"},
        {8 + 8 * 3 * (uint64_t)s.list.num_verts, 1 << 30, "num_faces"},
    };
    for (size_t i = 0; i < sizeof lies / sizeof lies[0]; i++) {
        memcpy(content, s.content, s.total);
        for (int k = 0; k < 4; k++)
            content[lies[i].at + (uint64_t)k] = (uint8_t)((uint32_t)lies[i].value >> (24 - 8 * k));
        sent_mesh liar = s;
        liar.content = content;
        liar.hash = mt_msgs_content_hash_bytes(content, s.total);
        int64_t request_id = 30 + (int64_t)i;
        for (size_t k = 0; k < num_chunks(&liar); k++)
            send_chunk(&fx, &liar, REPLY, request_id, k, false);
        expect_ack_error(&fx, request_id, MESHTOPO_STATUS_CODE_T_UNDECODABLE, lies[i].needle,
                         __LINE__);
    }
    free(content);
    /* The refused transfers' buffer is kept, and the next transfer of the
     * same size takes it (over memq the daemon runs on this thread). */
    size_t kept_capacity = 0;
    const void *kept = mtd_content_pool_kept(mtd_daemon_content_pool(fx.daemon), &kept_capacity);
    CHECK(kept != NULL && kept_capacity >= s.total);
    send_chunk(&fx, &s, REPLY, 40, 0, false);
    lcm_handle_timeout(fx.lcm, 100);
    CHECK(mtd_content_pool_kept(mtd_daemon_content_pool(fx.daemon), NULL) == NULL);
    /* The honest mesh still goes through, built from the reused buffer. */
    for (size_t k = 1; k < num_chunks(&s); k++) send_chunk(&fx, &s, REPLY, 40, k, false);
    expect_stored(&fx, &s, expect_ack(&fx, &s, 40, __LINE__), __LINE__);
    drain(&fx);
    heartbeat(&fx);
    CHECK_EQ(fx.status.builds, 1);
    CHECK_EQ(fx.status.transfers_active, 0);
    CHECK_EQ(fx.status.transfer_bytes, 0);
    sent_mesh_free(&s);
    fixture_free(&fx);
}

/* A build leaves its workspace for the next one, which takes the same
 * (over memq the daemon builds on this thread, one build at a time). */
static void test_builds_keep_a_workspace(void)
{
    fixture fx;
    fixture_init(&fx, "64M", "10000");
    sent_mesh s;
    sent_mesh_make(&s, "kept", 30, 30);
    mtd_workspace_pool *workspaces = mtd_daemon_workspace_pool(fx.daemon);
    CHECK(mtd_workspace_pool_kept(workspaces) == NULL);
    for (size_t k = 0; k < num_chunks(&s); k++) send_chunk(&fx, &s, REPLY, 50, k, false);
    expect_stored(&fx, &s, expect_ack(&fx, &s, 50, __LINE__), __LINE__);
    const mt_build_workspace *kept = mtd_workspace_pool_kept(workspaces);
    const size_t bytes = mtd_workspace_pool_bytes(workspaces);
    CHECK(kept != NULL);
    CHECK(bytes > 16 * s.list.num_indices); /* the sides alone */
    for (size_t k = 0; k < num_chunks(&s); k++) send_chunk(&fx, &s, REPLY, 51, k, false);
    expect_stored(&fx, &s, expect_ack(&fx, &s, 51, __LINE__), __LINE__);
    CHECK(mtd_workspace_pool_kept(workspaces) == kept);
    CHECK_EQ(mtd_workspace_pool_bytes(workspaces), bytes);
    sent_mesh_free(&s);
    fixture_free(&fx);
}

/* --prepare-faces: the daemon starts with a kept workspace that a grid of
 * about that many triangles was built with, holding that grid's mesh
 * arrays. The first mesh of a similar size is built with that workspace
 * and into those arrays: the same workspace is kept afterwards, holding
 * less (the mesh took at least its half-edge block, 36 bytes per face). */
static void test_prepared_workspace(void)
{
    mtd_config config;
    fixture_config(&config, "64M", "10000");
    config.prepare_faces = 2000;
    fixture fx;
    fixture_start(&fx, &config);
    mtd_workspace_pool *workspaces = mtd_daemon_workspace_pool(fx.daemon);
    const mt_build_workspace *prepared = mtd_workspace_pool_kept(workspaces);
    const size_t bytes = mtd_workspace_pool_bytes(workspaces);
    CHECK(prepared != NULL);
    /* the sides (16 bytes per corner) and the grid's half-edges at least */
    CHECK(bytes >= 16 * 3 * 2000 + 36 * 2000);
    sent_mesh s;
    sent_mesh_make(&s, "first", 30, 30);
    for (size_t k = 0; k < num_chunks(&s); k++) send_chunk(&fx, &s, REPLY, 90, k, false);
    expect_stored(&fx, &s, expect_ack(&fx, &s, 90, __LINE__), __LINE__);
    CHECK(mtd_workspace_pool_kept(workspaces) == prepared);
    CHECK(mtd_workspace_pool_bytes(workspaces) + 36 * (size_t)s.list.num_faces <= bytes);
    sent_mesh_free(&s);
    fixture_free(&fx);

    /* Without it the daemon starts with no workspace (test_builds_keep_a_workspace). */
    fixture_config(&config, "64M", "10000");
    fixture_start(&fx, &config);
    CHECK(mtd_workspace_pool_kept(mtd_daemon_workspace_pool(fx.daemon)) == NULL);
    fixture_free(&fx);
}

/* The half-edge block of a stored version. */
static const uint32_t *stored_half_edges(fixture *fx, const char *id, uint32_t version)
{
    mtd_mesh_entry *entry = NULL;
    if (mtd_store_acquire(mtd_daemon_store(fx->daemon), id, version, &entry, NULL) != MT_OK)
        return NULL;
    mt_mesh_view view;
    mt_mesh_get_view(mtd_entry_mesh(entry), &view);
    mtd_entry_release(entry);
    return view.he_head;
}

/* With one version kept per id, each new version drops the one before,
 * whose arrays go to the kept workspace: the version after next is built
 * into them (the same half-edge block) and is still the right mesh. */
static void test_dropped_meshes_are_recycled(void)
{
    mtd_config config;
    fixture_config(&config, "64M", "10000");
    config.max_versions = 1;
    fixture fx;
    fixture_start(&fx, &config);
    sent_mesh s;
    sent_mesh_make(&s, "frames", 30, 30);
    const uint32_t *first_block = NULL;
    size_t scratch_bytes = 0;
    for (int32_t version = 1; version <= 3; version++) {
        const int64_t request = 70 + version;
        for (size_t k = 0; k < num_chunks(&s); k++) send_chunk(&fx, &s, REPLY, request, k, false);
        const int32_t stored = expect_ack(&fx, &s, request, __LINE__);
        CHECK_EQ(stored, version);
        expect_stored(&fx, &s, stored, __LINE__);
        const size_t bytes = mtd_workspace_pool_bytes(mtd_daemon_workspace_pool(fx.daemon));
        const uint32_t *block = stored_half_edges(&fx, "frames", (uint32_t)stored);
        CHECK(block != NULL);
        if (version == 1) {
            first_block = block;
            scratch_bytes = bytes;
        } else {
            /* The dropped version's arrays: three half-edges of 12 bytes per
             * face, at least. */
            CHECK(bytes > scratch_bytes + 36 * (size_t)s.list.num_faces);
        }
        if (version == 3) CHECK(block == first_block);
    }
    sent_mesh_free(&s);
    fixture_free(&fx);
}

static void on_progress(uint64_t done, uint64_t total, void *user)
{
    uint64_t *seen = user; /* [0] last done, [1] total, [2] calls, [3] went backwards */
    if (done < seen[0]) seen[3] = 1;
    seen[0] = done;
    seen[1] = total;
    seen[2]++;
}

/* meshtopo::client sends a mesh larger than one datagram in chunks (its
 * thread handles the daemon's LCM too: one memq instance) and a small one
 * whole; progress rises to the total. */
static void test_client_chunks(void)
{
    fixture fx;
    fixture_init(&fx, "64M", "10000");
    uint64_t seen[4] = {0, 0, 0, 0};
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm = fx.lcm;
    opts.chunk_bytes = 1999; /* odd: chunks cut values in two */
    opts.window_chunks = 4;
    opts.progress = on_progress;
    opts.progress_user = seen;
    mt_client *client = NULL;
    mt_diag diag;
    CHECK_OK(mt_client_create(&opts, &client, &diag));
    sent_mesh s, small;
    sent_mesh_make(&s, "via_client", 40, 40);
    sent_mesh_make(&small, "small", 3, 3);
    mt_client_ack ack;
    CHECK_OK(mt_client_submit(client, "via_client", &s.list, 0, &ack, &diag));
    CHECK_EQ(ack.msg.status, 0);
    CHECK(ack.sent_content_hash == s.hash);
    CHECK((uint64_t)ack.msg.content_hash == s.hash);
    CHECK_EQ(ack.msg.version, 1);
    expect_stored(&fx, &s, ack.msg.version, __LINE__);
    mt_client_ack_free(&ack);
    CHECK(seen[2] >= 2);
    CHECK_EQ(seen[0], s.total);
    CHECK_EQ(seen[1], s.total);
    CHECK_EQ(seen[3], 0);
    uint64_t calls = seen[2];
    CHECK_OK(mt_client_submit(client, "small", &small.list, 0, &ack, &diag));
    CHECK((uint64_t)ack.msg.content_hash == small.hash);
    mt_client_ack_free(&ack);
    CHECK_EQ(seen[2], calls); /* whole message: no chunks, no progress */
    mt_client_destroy(client);
    heartbeat(&fx);
    CHECK_EQ(fx.status.transfers_completed, 1);
    CHECK_EQ(fx.status.builds, 2);
    sent_mesh_free(&s);
    sent_mesh_free(&small);
    fixture_free(&fx);
}

static const mt_test_case cases[] = {
    {"out_of_order_duplicates", test_out_of_order_duplicates},
    {"interleaved", test_interleaved},
    {"lying_chunks", test_lying_chunks},
    {"abandoned", test_abandoned},
    {"restart", test_restart},
    {"over_limit", test_over_limit},
    {"claims_cost_only_what_is_sent", test_claims_cost_only_what_is_sent},
    {"ranges_and_shares", test_ranges_and_shares},
    {"client_chunks", test_client_chunks},
    {"odd_pieces", test_odd_pieces},
    {"builds_keep_a_workspace", test_builds_keep_a_workspace},
    {"prepared_workspace", test_prepared_workspace},
    {"dropped_meshes_are_recycled", test_dropped_meshes_are_recycled},
    {"counts_that_do_not_fit", test_counts_that_do_not_fit},
};
const mt_test_table mt_tests_chunks = {cases, sizeof cases / sizeof cases[0]};
