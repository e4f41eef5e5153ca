/* The hostile sender of `meshtopo-bench soak`: one thread with an LCM
 * handle of its own that publishes, on a fixed schedule, what no client
 * library would send (soak.h lists it), and counts what comes back. It
 * calls LCM directly because meshtopo::client only ever sends well-formed
 * requests; it is the one part of the benchmarks that must not. */
#include <inttypes.h>
#include <lcm/lcm.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "meshtopo/channels.h"
#include "meshtopo/msgs.h"
#include "soak.h"

#define PREFIX "MESHTOPO_"
#define REPLY "HOSTILE_R" /* its own reply channel, for counting */
#define GIB ((int64_t)1 << 30)
#define CLAIM_VERTS (16 << 20) /* the most --max-verts allows by default */
#define TICK_MS 10             /* the schedule's step */
#define LIVE_TRICKLES 4        /* 1 GiB transfers kept alive at once */

struct mt__soak_hostile {
    lcm_t *lcm;
    char mesh_id[256];
    uint32_t flood_ids;
    pthread_t thread;
    atomic_bool stop;
    pthread_mutex_t lock; /* counts */
    mt__soak_hostile_counts counts;
};

static void count(mt__soak_hostile *h, uint64_t *field)
{
    pthread_mutex_lock(&h->lock);
    (*field)++;
    pthread_mutex_unlock(&h->lock);
}

static void on_ack(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mt__soak_hostile *h = user;
    meshtopo_ack_t ack;
    if (mt_msgs_decode(&mt_msgs_type_ack, rbuf->data, rbuf->data_size, &ack, NULL, 0) != 0) return;
    if (ack.status == MESHTOPO_STATUS_CODE_T_TOO_LARGE) count(h, &h->counts.claims_refused);
    if (ack.status == MESHTOPO_STATUS_CODE_T_OK) count(h, &h->counts.claims_accepted);
    meshtopo_ack_t_decode_cleanup(&ack);
}

static void on_reply(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    mt__soak_hostile *h = user;
    meshtopo_reply_t r;
    if (mt_msgs_decode(&mt_msgs_type_reply, rbuf->data, rbuf->data_size, &r, NULL, 0) != 0) return;
    if (r.status == MESHTOPO_STATUS_CODE_T_BUSY) count(h, &h->counts.flood_busy);
    meshtopo_reply_t_decode_cleanup(&r);
}

static void on_part(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)rbuf;
    (void)channel;
    mt__soak_hostile *h = user;
    count(h, &h->counts.flood_parts);
}

static void on_own_channel(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)rbuf;
    (void)channel;
    mt__soak_hostile *h = user;
    count(h, &h->counts.on_own_channels);
}

static void publish(mt__soak_hostile *h, const char *suffix, const mt_msgs_type *type,
                    const void *msg)
{
    char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
    snprintf(channel, sizeof channel, PREFIX "%s", suffix);
    int size = type->encoded_size(msg);
    void *buf = size > 0 ? malloc((size_t)size) : NULL;
    if (buf && type->encode(buf, 0, size, msg) == size)
        lcm_publish(h->lcm, channel, buf, (unsigned)size);
    free(buf);
}

/* A 100-odd-byte mesh_t claiming CLAIM_VERTS vertices, no positions. */
static void send_claim(mt__soak_hostile *h, uint64_t n)
{
    static int32_t sizes[6] = {3, 3, 3, 3, 3, 3};
    int32_t indices[18];
    for (int i = 0; i < 18; i++) indices[i] = CLAIM_VERTS - 1 - i;
    char id[64];
    snprintf(id, sizeof id, "hostile-claim-%" PRIu64, n);
    meshtopo_mesh_t m;
    memset(&m, 0, sizeof m);
    m.request_id = (int64_t)(1000000 + n);
    m.reply_channel = REPLY;
    m.mesh_id = id;
    m.source = "hostile";
    m.num_verts = CLAIM_VERTS;
    m.num_faces = 6;
    m.face_vertex_counts = sizes;
    m.num_indices = 18;
    m.face_vertex_indices = indices;
    publish(h, "SUBMIT", &mt_msgs_type_mesh, &m);
    count(h, &h->counts.claims);
}

/* One chunk of a 1 GiB transfer (length 0: a poll). */
static void send_chunk(mt__soak_hostile *h, int64_t request_id, const char *mesh_id, int64_t offset,
                       int32_t length, bool want_status)
{
    uint8_t byte = 0x5a;
    meshtopo_mesh_chunk_t c;
    memset(&c, 0, sizeof c);
    c.request_id = request_id;
    c.reply_channel = REPLY;
    c.mesh_id = (char *)mesh_id;
    c.source = "hostile";
    c.total_size = GIB;
    c.content_hash = request_id;
    c.want_status = want_status;
    c.offset = offset;
    c.length = length;
    c.data = &byte;
    publish(h, "SUBMIT_CHUNK", &mt_msgs_type_mesh_chunk, &c);
}

/* A query of flood_ids one-rings, sent and never waited for. */
static void send_flood(mt__soak_hostile *h, int32_t *ids, uint64_t n)
{
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.request_id = (int64_t)(3000000 + n);
    q.reply_channel = REPLY;
    q.instance = "";
    q.mesh_id = h->mesh_id;
    q.kind = MESHTOPO_QUERY_T_VERTEX_RING;
    q.num_ids = (int32_t)h->flood_ids;
    q.ids = ids;
    publish(h, "QUERY", &mt_msgs_type_query, &q);
    count(h, &h->counts.floods);
}

/* Requests whose reply channel is one of the daemon's own. */
static void send_own_channel(mt__soak_hostile *h, uint64_t n)
{
    static const char *const own[] = {PREFIX "STATUS", PREFIX "QUERY", PREFIX "SUBMIT",
                                      PREFIX "TOPOLOGY"};
    int32_t vertex = 0;
    meshtopo_query_t q;
    memset(&q, 0, sizeof q);
    q.request_id = (int64_t)(4000000 + n);
    q.reply_channel = (char *)own[n % 4];
    q.instance = "";
    q.mesh_id = h->mesh_id;
    q.kind = MESHTOPO_QUERY_T_VALENCE;
    q.num_ids = 1;
    q.ids = &vertex;
    publish(h, "QUERY", &mt_msgs_type_query, &q);
    count(h, &h->counts.own_channels);
}

static void send_garbage(mt__soak_hostile *h, uint64_t *rng)
{
    static const char *const channels[] = {PREFIX "SUBMIT", PREFIX "SUBMIT_CHUNK", PREFIX "QUERY",
                                           PREFIX "QUERY_PULL"};
    uint8_t bytes[512];
    size_t n = 1 + mt__bench_rand_u64(rng) % sizeof bytes;
    for (size_t i = 0; i < n; i++) bytes[i] = (uint8_t)mt__bench_rand_u64(rng);
    lcm_publish(h->lcm, channels[mt__bench_rand_u64(rng) % 4], bytes, (unsigned)n);
    count(h, &h->counts.garbage);
}

/* The schedule, every TICK_MS: one-byte scattered chunks and garbage each
 * tick; a claim and a request on an own channel every 100 ms; a flood
 * query every 50 ms; a new 1 GiB transfer every second (LIVE_TRICKLES of
 * them fed one byte every 2 s, the oldest dropped); and LCM handled for the
 * answers in between. */
static void *run(void *arg)
{
    mt__soak_hostile *h = arg;
    int32_t *ids = malloc(h->flood_ids * sizeof *ids);
    for (uint32_t i = 0; ids && i < h->flood_ids; i++) ids[i] = (int32_t)i;
    uint64_t rng = 0x5eed5eed;
    uint64_t tick = 0, claims = 0, floods = 0, own = 0;
    int64_t trickle_ids[LIVE_TRICKLES] = {0};
    int64_t trickle_next[LIVE_TRICKLES] = {0};
    const int64_t scatter_id = 2000000;
    send_chunk(h, scatter_id, "hostile-scatter", 0, 0, true);
    while (!atomic_load(&h->stop)) {
        for (int k = 0; k < 5; k++) { /* 500 scattered bytes a second */
            int64_t at = (int64_t)(mt__bench_rand_u64(&rng) % (uint64_t)GIB);
            send_chunk(h, scatter_id, "hostile-scatter", at, 1, false);
            pthread_mutex_lock(&h->lock);
            h->counts.scatter_bytes++;
            pthread_mutex_unlock(&h->lock);
        }
        send_garbage(h, &rng);
        if (tick % 10 == 0) {
            send_claim(h, claims++);
            send_own_channel(h, own++);
        }
        if (tick % 5 == 0 && ids) send_flood(h, ids, floods++);
        if (tick % 100 == 0) { /* a new claimed gigabyte in the oldest slot */
            size_t slot = (size_t)(tick / 100) % LIVE_TRICKLES;
            trickle_ids[slot] = 2100000 + (int64_t)(tick / 100);
            trickle_next[slot] = 0;
            send_chunk(h, trickle_ids[slot], "hostile-trickle", 0, 0, true);
            count(h, &h->counts.claim_polls);
        }
        if (tick % 200 == 0) { /* each live one gets its next byte */
            for (size_t s = 0; s < LIVE_TRICKLES; s++) {
                if (!trickle_ids[s]) continue;
                send_chunk(h, trickle_ids[s], "hostile-trickle", trickle_next[s]++, 1, false);
                count(h, &h->counts.trickle_bytes);
            }
        }
        lcm_handle_timeout(h->lcm, 0);
        mt__bench_sleep_ms(TICK_MS);
        tick++;
    }
    free(ids);
    return NULL;
}

mt__soak_hostile *mt__soak_hostile_start(const char *lcm_url, const char *mesh_id,
                                         uint32_t flood_ids, char *err, size_t err_size)
{
    mt__soak_hostile *h = calloc(1, sizeof *h);
    if (!h) {
        snprintf(err, err_size, "out of memory");
        return NULL;
    }
    h->lcm = lcm_create(lcm_url);
    if (!h->lcm) {
        snprintf(err, err_size, "hostile sender: cannot create LCM on %s", lcm_url);
        free(h);
        return NULL;
    }
    snprintf(h->mesh_id, sizeof h->mesh_id, "%s", mesh_id);
    h->flood_ids = flood_ids;
    pthread_mutex_init(&h->lock, NULL);
    lcm_subscribe(h->lcm, REPLY "_ACK", on_ack, h);
    lcm_subscribe(h->lcm, REPLY "_REPLY", on_reply, h);
    lcm_subscribe(h->lcm, REPLY "_PART", on_part, h);
    lcm_subscribe(h->lcm, PREFIX "(SUBMIT|QUERY|TOPOLOGY|STATUS).*_(ACK|REPLY|PART|TRANSFER)",
                  on_own_channel, h);
    if (pthread_create(&h->thread, NULL, run, h) != 0) {
        snprintf(err, err_size, "hostile sender: cannot start its thread");
        lcm_destroy(h->lcm);
        pthread_mutex_destroy(&h->lock);
        free(h);
        return NULL;
    }
    return h;
}

void mt__soak_hostile_stop(mt__soak_hostile *h, mt__soak_hostile_counts *out)
{
    atomic_store(&h->stop, true);
    pthread_join(h->thread, NULL);
    /* Answers still on their way. */
    for (int i = 0; i < 50; i++) lcm_handle_timeout(h->lcm, 10);
    pthread_mutex_lock(&h->lock);
    *out = h->counts;
    pthread_mutex_unlock(&h->lock);
    lcm_destroy(h->lcm);
    pthread_mutex_destroy(&h->lock);
    free(h);
}
