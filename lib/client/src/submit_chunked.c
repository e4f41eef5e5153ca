/* Chunked submission (msgs/mesh_chunk_t.lcm): the content of a mesh_t too
 * large for one datagram is sent in pieces of chunk_bytes, each encoded from
 * the mesh's arrays as it is sent (meshtopo/mesh_content.h), a window at a
 * time; the last chunk of each window asks the daemon for its transfer
 * status, whose missing ranges decide the next window (lost chunks first,
 * then new ones). Silence for a few round trips of the status (measured;
 * between MT__CHUNK_POLL_MIN_US and MT__CHUNK_POLL_MAX_US) brings a poll (an
 * empty chunk asking for the status), so a lost datagram costs about as much
 * as the network is slow, not a fixed delay; the pending request's usual timeout and
 * retries bound how long the daemon may stay silent. Ends with the ack. */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "client_internal.h"
#include "meshtopo/mesh_content.h"

/* Wait for a status at least / at most this long before polling the
 * daemon (the most until a status round trip has been measured). */
#define MT__CHUNK_POLL_MIN_US 2000
#define MT__CHUNK_POLL_MAX_US 50000

typedef struct chunk_sender {
    mt_client *client;
    meshtopo_mesh_chunk_t msg; /* header fields set once; offset/length/data per chunk */
    const meshtopo_mesh_t *mesh;
    uint8_t *data; /* one chunk's content */
    uint64_t total;
    uint64_t chunk; /* bytes per chunk */
    size_t num_chunks;
    uint8_t *held;    /* per chunk: the daemon confirmed it */
    uint8_t *scratch; /* encoded chunk */
    int scratch_size;
    int64_t asked_us;      /* when a chunk last asked for the status (monotonic) */
    int64_t smooth_rtt_us; /* of the status: asked -> arrived, smoothed; 0 until one */
} chunk_sender;

static int64_t monotonic_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

/* A status arrived: the round trip since the last ask, smoothed as TCP does
 * (RFC 6298's 1/8 gain). */
static void note_round_trip(chunk_sender *s)
{
    int64_t sample = monotonic_us() - s->asked_us;
    if (sample < 0) sample = 0;
    s->smooth_rtt_us = s->smooth_rtt_us ? (7 * s->smooth_rtt_us + sample) / 8 : sample;
}

/* How long to wait for a status before polling. */
static int64_t poll_wait_us(const chunk_sender *s)
{
    if (!s->smooth_rtt_us) return MT__CHUNK_POLL_MAX_US;
    int64_t wait = 4 * s->smooth_rtt_us + 1000;
    return wait < MT__CHUNK_POLL_MIN_US   ? MT__CHUNK_POLL_MIN_US
           : wait > MT__CHUNK_POLL_MAX_US ? MT__CHUNK_POLL_MAX_US
                                          : wait;
}

static void publish_chunk(chunk_sender *s, size_t index, int want_status, int poll)
{
    uint64_t offset = poll ? 0 : (uint64_t)index * s->chunk;
    uint64_t length = poll ? 0 : s->total - offset < s->chunk ? s->total - offset : s->chunk;
    s->msg.offset = (int64_t)offset;
    s->msg.length = (int32_t)length;
    mt_msgs_mesh_content_encode(s->mesh, offset, (size_t)length, s->data);
    s->msg.data = s->data;
    s->msg.want_status = want_status ? 1 : 0;
    if (want_status) s->asked_us = monotonic_us();
    int size = meshtopo_mesh_chunk_t_encode(s->scratch, 0, s->scratch_size, &s->msg);
    int failed = size <= 0 || lcm_publish(s->client->lcm, s->client->chunk_channel, s->scratch,
                                          (unsigned)size) != 0;
    pthread_mutex_lock(&s->client->mutex);
    s->client->stats.attempts++;
    if (failed) s->client->stats.publish_errors++;
    pthread_mutex_unlock(&s->client->mutex);
}

/* Marks the chunks the daemon holds according to status t (mutex held). */
static void note_status(chunk_sender *s, const mt__transfer *t)
{
    size_t below = (size_t)(t->listed_until / s->chunk); /* chunks wholly below the bound */
    if (t->listed_until >= s->total) below = s->num_chunks;
    for (size_t i = 0; i < below; i++) s->held[i] = 1;
    for (size_t g = 0; g < t->num_missing; g++) {
        if (t->missing_offsets[g] < 0 || t->missing_lengths[g] <= 0) continue;
        uint64_t start = (uint64_t)t->missing_offsets[g];
        uint64_t end = start + (uint64_t)t->missing_lengths[g];
        if (start >= s->total) continue;
        if (end > s->total) end = s->total;
        for (size_t i = (size_t)(start / s->chunk); i < s->num_chunks && i * s->chunk < end; i++)
            s->held[i] = 0;
    }
}

static void add_us(struct timespec *ts, int64_t us)
{
    ts->tv_nsec += (long)(us % 1000000) * 1000L;
    ts->tv_sec += (time_t)(us / 1000000) + ts->tv_nsec / 1000000000L;
    ts->tv_nsec %= 1000000000L;
}

mt_status mt__client_submit_chunked(mt_client *client, const meshtopo_mesh_t *m,
                                    uint64_t content_hash, mt__pending *p, mt_diag *diag)
{
    chunk_sender s;
    memset(&s, 0, sizeof s);
    mt__transfer *transfer = calloc(1, sizeof *transfer);
    s.client = client;
    s.mesh = m;
    s.total = mt_msgs_mesh_content_size(m);
    s.chunk = (uint64_t)client->chunk_bytes;
    s.num_chunks = (size_t)((s.total + s.chunk - 1) / s.chunk);
    s.held = calloc(s.num_chunks, 1);
    s.msg.utime = m->utime;
    s.msg.request_id = m->request_id;
    s.msg.reply_channel = m->reply_channel;
    s.msg.mesh_id = m->mesh_id;
    s.msg.source = m->source;
    s.msg.strict = m->strict;
    s.msg.total_size = (int64_t)s.total;
    s.msg.content_hash = (int64_t)content_hash;
    s.msg.length = (int32_t)s.chunk;
    s.scratch_size = meshtopo_mesh_chunk_t_encoded_size(&s.msg);
    s.scratch = malloc((size_t)s.scratch_size);
    s.data = malloc((size_t)s.chunk);
    /* The poll is the request's retry message: an empty chunk asking for status. */
    s.msg.length = 0;
    s.msg.want_status = 1;
    int poll_size = meshtopo_mesh_chunk_t_encoded_size(&s.msg);
    mt__msgbuf *poll = mt__msgbuf_new(poll_size);
    if (!transfer || !s.held || !s.scratch || !s.data || !poll) {
        free(transfer);
        free(s.held);
        free(s.scratch);
        free(s.data);
        mt__msgbuf_release(poll);
        return mt__client_fail(diag, MT_ERR_NOMEM, "no memory to send %llu bytes in chunks",
                               (unsigned long long)s.total);
    }
    meshtopo_mesh_chunk_t_encode(poll->data, 0, poll_size, &s.msg);

    memset(p, 0, sizeof *p);
    p->request_id = m->request_id;
    p->answer_type = &mt_msgs_type_ack;
    p->channel = client->chunk_channel;
    p->buf = poll;
    p->transfer = transfer;
    pthread_cond_init(&p->cond, NULL);
    s.asked_us = monotonic_us();
    mt_status st = mt__client_start(client, p); /* publishes the first poll */
    if (st != MT_OK) {
        mt__msgbuf_release(poll);
        p->buf = NULL;
    } else {
        uint64_t seen = 0;
        pthread_mutex_lock(&client->mutex);
        while (!p->done) {
            if (transfer->seq != seen && !transfer->complete) {
                seen = transfer->seq;
                note_round_trip(&s);
                note_status(&s, transfer);
                uint64_t received = transfer->received;
                /* The next window: the first chunks the daemon lacks. */
                size_t window[4096];
                size_t n = 0;
                for (size_t i = 0; i < s.num_chunks && n < (size_t)client->window_chunks; i++)
                    if (!s.held[i]) window[n++] = i;
                pthread_mutex_unlock(&client->mutex);
                if (client->progress) client->progress(received, s.total, client->progress_user);
                for (size_t k = 0; k < n; k++) publish_chunk(&s, window[k], k + 1 == n, 0);
                pthread_mutex_lock(&client->mutex);
                continue;
            }
            if (transfer->complete) { /* the ack comes after the build; p retries by itself */
                seen = transfer->seq;
                pthread_cond_wait(&p->cond, &client->mutex);
                continue;
            }
            /* No status for a while: poll, but not before a BUSY pause ends. */
            int64_t poll_at = monotonic_us() + poll_wait_us(&s);
            for (;;) {
                int64_t at = poll_at > transfer->resume_us ? poll_at : transfer->resume_us;
                int64_t wait = at - monotonic_us();
                if (p->done || transfer->seq != seen || wait <= 0) break;
                struct timespec until;
                clock_gettime(CLOCK_REALTIME, &until);
                add_us(&until, wait);
                pthread_cond_timedwait(&p->cond, &client->mutex, &until);
            }
            if (!p->done && transfer->seq == seen) {
                pthread_mutex_unlock(&client->mutex);
                publish_chunk(&s, 0, 1, 1);
                pthread_mutex_lock(&client->mutex);
            }
        }
        pthread_mutex_unlock(&client->mutex);
        mt__msgbuf_release(p->buf);
        p->buf = NULL;
        st = p->status;
        if (st == MT_OK && client->progress)
            client->progress(s.total, s.total, client->progress_user);
    }
    if (st != MT_OK && diag) *diag = p->diag;
    pthread_cond_destroy(&p->cond);
    p->transfer = NULL;
    free(transfer);
    free(s.held);
    free(s.scratch);
    free(s.data);
    return st;
}
