/* The client object: its LCM instance, private reply channel, table of
 * pending requests and the thread that handles LCM (lcm_get_fileno + poll),
 * resends a request whose attempt timed out (same request id) and completes
 * it after the last attempt. Replies are decoded only with mt_msgs_decode;
 * anything else on the reply channel is counted and dropped. A large answer
 * arrives as reply_part_t pieces: reassembled here (reply_assembly.c), its next
 * windows and lost parts pulled with reply_pull_t, the query itself sent
 * again only when the daemon stays silent for a whole timeout. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "client_internal.h"
#include "meshtopo/answer_hash.h"
#include "meshtopo/client_reply.h"

/* LCM keeps at most this many undelivered messages per subscription (30 by
 * default); replies to many asynchronous queries may arrive together. */
#define MT__REPLY_QUEUE_CAPACITY 10000
/* Retries published per pass of the client thread (the rest go next pass). */
#define MT__MAX_DUE_PER_PASS 64
/* Silence after a part before the missing ones are pulled again. */
#define MT__PARTS_QUIET_MS 30

/* ---- Small helpers ------------------------------------------------------ */

int64_t mt__client_now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

int64_t mt__client_utime(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

mt_status mt__client_fail(mt_diag *diag, mt_status status, const char *fmt, ...)
{
    if (diag) {
        mt_diag_clear(diag);
        diag->status = status;
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(diag->message, sizeof diag->message, fmt, ap);
        va_end(ap);
    }
    return status;
}

mt__msgbuf *mt__msgbuf_new(int size)
{
    if (size < 0) return NULL;
    mt__msgbuf *buf = malloc(sizeof *buf + (size_t)size);
    if (!buf) return NULL;
    atomic_init(&buf->refs, 1);
    buf->size = size;
    return buf;
}

void mt__msgbuf_release(mt__msgbuf *buf)
{
    if (buf && atomic_fetch_sub(&buf->refs, 1) == 1) free(buf);
}

static uint64_t random_u64(void)
{
    uint64_t r = 0;
    int fd = open("/dev/urandom", O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
        if (read(fd, &r, sizeof r) != (ssize_t)sizeof r) r = 0;
        close(fd);
    }
    if (r == 0) { /* no /dev/urandom: mix the clocks, pid and an address */
        r = (uint64_t)mt__client_utime() * 0x9e3779b97f4a7c15ull;
        r ^= (uint64_t)mt__client_now_us() << 17;
        r ^= (uint64_t)getpid() << 40;
        r ^= (uint64_t)(uintptr_t)&r;
    }
    return r;
}

int64_t mt__client_next_id(mt_client *client)
{
    pthread_mutex_lock(&client->mutex);
    int64_t id = client->next_request_id++;
    pthread_mutex_unlock(&client->mutex);
    return id;
}

static void wake_thread(mt_client *client)
{
    char byte = 1;
    /* Non-blocking: a full pipe already wakes the thread. */
    if (write(client->wake_pipe[1], &byte, 1) < 0) { /* nothing to do */
    }
}

/* ---- The table of pending requests (caller holds the mutex) ------------- */

static size_t bucket_of(int64_t request_id)
{
    uint64_t h = (uint64_t)request_id * 0x9e3779b97f4a7c15ull;
    return (size_t)(h >> 56) % MT__BUCKETS;
}

static void table_insert(mt_client *client, mt__pending *p)
{
    size_t b = bucket_of(p->request_id);
    p->next = client->buckets[b];
    client->buckets[b] = p;
    client->num_pending++;
}

/* Removes and returns the request with this id, or NULL. */
static mt__pending *table_take(mt_client *client, int64_t request_id)
{
    mt__pending **link = &client->buckets[bucket_of(request_id)];
    for (mt__pending *p = *link; p; link = &p->next, p = p->next) {
        if (p->request_id == request_id) {
            *link = p->next;
            p->next = NULL;
            client->num_pending--;
            return p;
        }
    }
    return NULL;
}

/* Releases a request's partly received answer (mutex held). */
static void drop_parts(mt_client *client, mt__pending *p)
{
    if (!p->parts) return;
    client->parts_bytes -= p->parts->total;
    mt__parts_free(p->parts);
    p->parts = NULL;
}

/* A reply_pull_t asking for the next window of p's missing parts (mutex
 * held); NULL when out of memory or nothing is missing. */
static mt__msgbuf *pull_locked(mt_client *client, mt__pending *p)
{
    int64_t offsets[MESHTOPO_REPLY_PULL_T_RANGES_MAX], lengths[MESHTOPO_REPLY_PULL_T_RANGES_MAX];
    size_t num_parts = 0;
    size_t n = mt__parts_missing(p->parts, (size_t)client->window_chunks,
                                 MESHTOPO_REPLY_PULL_T_RANGES_MAX, offsets, lengths, &num_parts);
    if (n == 0) return NULL;
    meshtopo_reply_pull_t pull;
    memset(&pull, 0, sizeof pull);
    pull.utime = mt__client_utime();
    pull.request_id = p->request_id;
    pull.reply_channel = client->reply_channel;
    pull.total_size = (int64_t)p->parts->total;
    pull.answer_hash = (int64_t)p->parts->hash;
    pull.num_ranges = (int32_t)n;
    pull.offsets = offsets;
    pull.lengths = lengths;
    int size = meshtopo_reply_pull_t_encoded_size(&pull);
    mt__msgbuf *buf = mt__msgbuf_new(size);
    if (!buf) return NULL;
    if (meshtopo_reply_pull_t_encode(buf->data, 0, size, &pull) != size) {
        mt__msgbuf_release(buf);
        return NULL;
    }
    p->parts->window_parts = num_parts;
    p->parts->window_have = 0;
    client->stats.reply_pulls++;
    client->stats.attempts++;
    return buf;
}

/* Frees an asynchronous request that is out of the table. */
static void pending_free(mt__pending *p)
{
    if (p->has_answer) p->answer_type->decode_cleanup(&p->answer);
    mt__msgbuf_release(p->buf);
    free(p);
}

/* Marks a synchronous request done (mutex held) or, for an asynchronous one,
 * returns it to be called back after the mutex is released. */
static mt__pending *complete_locked(mt__pending *p)
{
    if (p->callback) return p;
    p->done = 1;
    pthread_cond_signal(&p->cond);
    return NULL;
}

static void call_back(mt__pending *p)
{
    p->callback(p->status, p->has_answer ? &p->answer.reply : NULL, &p->diag, p->user);
    pending_free(p);
}

static void publish(mt_client *client, const char *channel, mt__msgbuf *buf)
{
    if (lcm_publish(client->lcm, channel, buf->data, (unsigned int)buf->size) != 0) {
        pthread_mutex_lock(&client->mutex);
        client->stats.publish_errors++;
        pthread_mutex_unlock(&client->mutex);
    }
}

/* ---- Requests ----------------------------------------------------------- */

mt_status mt__client_start(mt_client *client, mt__pending *p)
{
    if (!p->callback && client->thread_started && pthread_equal(pthread_self(), client->thread))
        return mt__client_fail(&p->diag, MT_ERR_INVALID_ARG,
                               "synchronous call from the client's own thread (an asynchronous "
                               "callback) would wait forever; use mt_client_query_async there");
    int wake = 0;
    pthread_mutex_lock(&client->mutex);
    p->deadline_us = mt__client_now_us() + (int64_t)client->timeout_ms * 1000;
    p->attempts_left = client->attempts - 1;
    table_insert(client, p);
    client->stats.requests++;
    client->stats.attempts++;
    if (p->deadline_us < client->next_deadline_us) {
        client->next_deadline_us = p->deadline_us;
        wake = 1;
    }
    /* The reply may complete (and free) p before lcm_publish returns. */
    mt__msgbuf *buf = p->buf;
    const char *channel = p->channel;
    atomic_fetch_add(&buf->refs, 1);
    pthread_mutex_unlock(&client->mutex);
    if (wake) wake_thread(client);
    publish(client, channel, buf);
    mt__msgbuf_release(buf);
    return MT_OK;
}

void mt__client_wait(mt_client *client, mt__pending *p)
{
    pthread_mutex_lock(&client->mutex);
    while (!p->done) pthread_cond_wait(&p->cond, &client->mutex);
    pthread_mutex_unlock(&client->mutex);
    mt__msgbuf_release(p->buf);
    p->buf = NULL;
}

/* Resends every request whose attempt timed out and completes those out of
 * attempts. Runs on the client thread. */
static void run_deadlines(mt_client *client)
{
    struct {
        const char *channel;
        mt__msgbuf *buf;
    } due[MT__MAX_DUE_PER_PASS];
    size_t num_due = 0;
    mt__pending *expired = NULL;

    int64_t now = mt__client_now_us();
    pthread_mutex_lock(&client->mutex);
    if (now < client->next_deadline_us) {
        pthread_mutex_unlock(&client->mutex);
        return;
    }
    int64_t next = INT64_MAX;
    for (size_t b = 0; b < MT__BUCKETS; b++) {
        mt__pending **link = &client->buckets[b];
        while (*link) {
            mt__pending *p = *link;
            if (p->parts && p->deadline_us <= now && num_due < MT__MAX_DUE_PER_PASS) {
                if (now - p->parts->last_us < (int64_t)client->timeout_ms * 1000) {
                    /* Parts stopped coming: pull what is missing again. */
                    p->deadline_us = now + MT__PARTS_QUIET_MS * 1000;
                    mt__msgbuf *pull = pull_locked(client, p);
                    if (pull) {
                        due[num_due].channel = client->pull_channel;
                        due[num_due].buf = pull;
                        num_due++;
                    }
                    if (p->deadline_us < next) next = p->deadline_us;
                    link = &p->next;
                    continue;
                }
                /* Silent for a whole timeout (the daemon lost the answer?):
                 * start over with the query itself. */
                drop_parts(client, p);
            }
            if (p->deadline_us <= now && p->attempts_left > 0 && num_due < MT__MAX_DUE_PER_PASS) {
                p->attempts_left--;
                p->deadline_us = now + (int64_t)client->timeout_ms * 1000;
                atomic_fetch_add(&p->buf->refs, 1);
                due[num_due].channel = p->channel;
                due[num_due].buf = p->buf;
                num_due++;
                client->stats.attempts++;
            } else if (p->deadline_us <= now && p->attempts_left == 0) {
                *link = p->next;
                p->next = NULL;
                client->num_pending--;
                client->stats.timeouts++;
                drop_parts(client, p);
                p->status = mt__client_fail(
                    &p->diag, MT_ERR_IO,
                    "timeout: no reply to request %lld on %s after %d attempt%s of %d ms",
                    (long long)p->request_id, p->channel, client->attempts,
                    client->attempts == 1 ? "" : "s", client->timeout_ms);
                if (complete_locked(p)) {
                    p->due_next = expired;
                    expired = p;
                }
                continue;
            }
            if (p->deadline_us < next) next = p->deadline_us;
            link = &p->next;
        }
    }
    client->next_deadline_us = next;
    pthread_mutex_unlock(&client->mutex);

    for (size_t i = 0; i < num_due; i++) {
        publish(client, due[i].channel, due[i].buf);
        mt__msgbuf_release(due[i].buf);
    }
    while (expired) {
        mt__pending *p = expired;
        expired = p->due_next;
        call_back(p);
    }
}

/* The request with this id, left in the table, or NULL (mutex held). */
static mt__pending *table_find(mt_client *client, int64_t request_id)
{
    for (mt__pending *p = client->buckets[bucket_of(request_id)]; p; p = p->next)
        if (p->request_id == request_id) return p;
    return NULL;
}

/* The pause before sending p again after its n-th BUSY answer (mutex held):
 * MT_CLIENT_BUSY_PAUSE_MS doubled n - 1 times, at most
 * MT_CLIENT_BUSY_PAUSE_MAX_MS, times a factor in [0.75, 1.25) so that the
 * clients a busy daemon turned away do not all come back at once. */
static int64_t busy_pause_us(mt_client *client, int n)
{
    int64_t ms = MT_CLIENT_BUSY_PAUSE_MS;
    for (int i = 1; i < n && ms < MT_CLIENT_BUSY_PAUSE_MAX_MS; i++) ms *= 2;
    if (ms > MT_CLIENT_BUSY_PAUSE_MAX_MS) ms = MT_CLIENT_BUSY_PAUSE_MAX_MS;
    /* xorshift64: a spread, not a secret */
    uint64_t x = client->jitter_state;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    client->jitter_state = x;
    int64_t us = ms * 1000;
    return us * 3 / 4 + (int64_t)(x % (uint64_t)(us / 2));
}

/* A BUSY answer to p while it has attempts left (mutex held): p stays in the
 * table and is sent again after a pause, by run_deadlines (or, for a chunked
 * submission, by its sender once transfer->resume_us has passed). Returns
 * whether p is kept; false when it is out of attempts. */
static int retry_busy_locked(mt_client *client, mt__pending *p, int *wake)
{
    if (p->attempts_left <= 0) return 0;
    int64_t resume = mt__client_now_us() + busy_pause_us(client, ++p->busy_answers);
    client->stats.busy_retries++;
    if (p->transfer && !p->transfer->complete) { /* refused on admission: its sender polls */
        p->transfer->resume_us = resume;
        p->attempts_left--;
        p->deadline_us = resume + (int64_t)client->timeout_ms * 1000;
        pthread_cond_broadcast(&p->cond);
    } else {
        p->deadline_us = resume;
    }
    if (p->deadline_us < client->next_deadline_us) {
        client->next_deadline_us = p->deadline_us;
        *wake = 1;
    }
    return 1;
}

/* A mesh_transfer_t: progress of a chunked submission (recorded for its
 * sender, which is woken; the submission's attempts start afresh since the
 * daemon is alive), or its refusal (which completes it). */
static void on_transfer_status(mt_client *client, meshtopo_mesh_transfer_t *msg)
{
    pthread_mutex_lock(&client->mutex);
    mt__pending *p = table_find(client, msg->request_id);
    if (!p || !p->transfer) {
        client->stats.unknown_replies++;
        pthread_mutex_unlock(&client->mutex);
        return;
    }
    client->stats.replies++;
    int wake = 0;
    if (msg->status == MESHTOPO_STATUS_CODE_T_BUSY && retry_busy_locked(client, p, &wake)) {
        pthread_mutex_unlock(&client->mutex);
        if (wake) wake_thread(client);
        return;
    }
    if (msg->status != MESHTOPO_STATUS_CODE_T_OK) {
        table_take(client, p->request_id);
        drop_parts(client, p);
        p->status = mt_msgs_status_of_code(msg->status);
        mt__client_fail(&p->diag, p->status, "%s: %s", mt_msgs_code_name(msg->status),
                        msg->error && msg->error[0] ? msg->error : "(no error text)");
        complete_locked(p); /* chunked submissions are synchronous */
        pthread_mutex_unlock(&client->mutex);
        return;
    }
    mt__transfer *t = p->transfer;
    t->seq++;
    t->complete = msg->complete;
    t->received = msg->received_bytes > 0 ? (uint64_t)msg->received_bytes : 0;
    t->listed_until = msg->listed_until > 0 ? (uint64_t)msg->listed_until : 0;
    size_t n = msg->num_missing > 0 ? (size_t)msg->num_missing : 0;
    if (n > MESHTOPO_MESH_TRANSFER_T_MISSING_MAX) n = MESHTOPO_MESH_TRANSFER_T_MISSING_MAX;
    if (n > 0) { /* the arrays are NULL when empty */
        memcpy(t->missing_offsets, msg->missing_offsets, n * sizeof *t->missing_offsets);
        memcpy(t->missing_lengths, msg->missing_lengths, n * sizeof *t->missing_lengths);
    }
    t->num_missing = n;
    p->deadline_us = mt__client_now_us() + (int64_t)client->timeout_ms * 1000;
    p->attempts_left = client->attempts - 1;
    pthread_cond_broadcast(&p->cond);
    pthread_mutex_unlock(&client->mutex);
}

static void on_part(mt_client *client, const void *data, size_t size);

/* Notes the answer a call completed with (mutex held). */
static void remember_answer(mt_client *client, int64_t request_id, const mt_msgs_type *type,
                            int64_t utime)
{
    client->recent[client->recent_next] = (mt__recent_answer){request_id, type, utime};
    client->recent_next = (client->recent_next + 1) % MT__RECENT_ANSWERS;
}

/* Whether an answer for no waiting request answers a recent call
 * differently from the answer it completed with (mutex held): sent at
 * another moment, so not a copy the daemon sent again but another daemon's
 * answer. */
static bool is_other_answer(const mt_client *client, int64_t request_id, const mt_msgs_type *type,
                            int64_t utime)
{
    for (size_t i = 0; i < MT__RECENT_ANSWERS; i++) {
        const mt__recent_answer *r = &client->recent[i];
        if (r->type == type && r->request_id == request_id) return r->utime != utime;
    }
    return false;
}

/* An answer received whole or reassembled: decode, match by request id,
 * complete. */
static void handle_answer(mt_client *client, const void *data, size_t size)
{
    const mt_msgs_type *type = mt_msgs_type_of(data, size);
    if (type == &mt_msgs_type_reply_part) {
        on_part(client, data, size);
        return;
    }
    if (type == &mt_msgs_type_mesh_transfer) {
        meshtopo_mesh_transfer_t msg;
        if (mt_msgs_decode(type, data, size, &msg, NULL, 0) != 0) {
            pthread_mutex_lock(&client->mutex);
            client->stats.undecodable++;
            pthread_mutex_unlock(&client->mutex);
            return;
        }
        on_transfer_status(client, &msg);
        meshtopo_mesh_transfer_t_decode_cleanup(&msg);
        return;
    }
    mt__answer answer;
    char error[MT_MSGS_ERROR_SIZE];
    if ((type != &mt_msgs_type_reply && type != &mt_msgs_type_ack) ||
        mt_msgs_decode(type, data, size, &answer, error, sizeof error) != 0) {
        pthread_mutex_lock(&client->mutex);
        client->stats.undecodable++;
        pthread_mutex_unlock(&client->mutex);
        return;
    }
    int64_t request_id =
        type == &mt_msgs_type_reply ? answer.reply.request_id : answer.ack.request_id;
    int32_t code = type == &mt_msgs_type_reply ? answer.reply.status : answer.ack.status;
    const char *text = type == &mt_msgs_type_reply ? answer.reply.error : answer.ack.error;

    pthread_mutex_lock(&client->mutex);
    mt__pending *p = table_take(client, request_id);
    if (p && p->answer_type != type) { /* an ack for a query or the reverse */
        table_insert(client, p);
        p = NULL;
    }
    int64_t utime = type == &mt_msgs_type_reply ? answer.reply.utime : answer.ack.utime;
    if (!p) {
        client->stats.unknown_replies++;
        if (is_other_answer(client, request_id, type, utime)) client->stats.conflicting_answers++;
        pthread_mutex_unlock(&client->mutex);
        type->decode_cleanup(&answer);
        return;
    }
    client->stats.replies++;
    drop_parts(client, p);
    int wake = 0;
    if (code == MESHTOPO_STATUS_CODE_T_BUSY && retry_busy_locked(client, p, &wake)) {
        table_insert(client, p);
        pthread_mutex_unlock(&client->mutex);
        type->decode_cleanup(&answer);
        if (wake) wake_thread(client);
        return;
    }
    if (type == &mt_msgs_type_reply && mt_client_reply_check(&answer.reply, &p->diag) != MT_OK) {
        /* Offsets that do not describe the arrays: never handed out. */
        p->status = MT_ERR_CORRUPT;
        type->decode_cleanup(&answer);
    } else {
        p->answer = answer;
        p->has_answer = 1;
        p->status = mt_msgs_status_of_code(code);
        if (p->status == MT_OK)
            mt_diag_clear(&p->diag);
        else
            mt__client_fail(&p->diag, p->status, "%s: %s", mt_msgs_code_name(code),
                            text && text[0] ? text : "(no error text)");
    }
    remember_answer(client, request_id, type, utime);
    p = complete_locked(p);
    pthread_mutex_unlock(&client->mutex);
    if (p) call_back(p);
}

/* One reply_part_t: kept in its request's reassembly; the next window is
 * pulled once the last one is in; a complete answer whose hash matches is
 * handled like one received whole, one that does not is dropped and its
 * query sent again. */
static void on_part(mt_client *client, const void *data, size_t size)
{
    meshtopo_reply_part_t part;
    if (mt_msgs_decode(&mt_msgs_type_reply_part, data, size, &part, NULL, 0) != 0) {
        pthread_mutex_lock(&client->mutex);
        client->stats.undecodable++;
        pthread_mutex_unlock(&client->mutex);
        return;
    }
    mt__msgbuf *send = NULL;
    const char *send_channel = NULL;
    uint8_t *answer = NULL;
    size_t answer_size = 0;
    mt__pending *failed = NULL;
    int wake = 0;
    int64_t now = mt__client_now_us();

    pthread_mutex_lock(&client->mutex);
    mt__pending *p = table_find(client, part.request_id);
    if (!p) {
        client->stats.unknown_replies++;
        goto out;
    }
    if (!p->parts) {
        mt__parts *parts = NULL;
        /* The cap is checked before anything is allocated. */
        mt_status s = part.total_size > 0 && (uint64_t)part.total_size >
                                                 client->max_reply_bytes - client->parts_bytes
                          ? MT_ERR_TOO_LARGE
                          : mt__parts_create(&part, &parts);
        if (s == MT_ERR_INVALID_ARG) {
            client->stats.bad_parts++;
            goto out;
        }
        if (s != MT_OK) {
            table_take(client, p->request_id);
            p->status = mt__client_fail(
                &p->diag, s,
                s == MT_ERR_TOO_LARGE
                    ? "answer to request %lld is %lld bytes in parts: with the %llu bytes other "
                      "partly received answers hold that exceeds max_reply_bytes (%llu)"
                    : "answer to request %lld is %lld bytes in parts: no memory to reassemble "
                      "it (%llu bytes held by others, limit %llu)",
                (long long)p->request_id, (long long)part.total_size,
                (unsigned long long)client->parts_bytes,
                (unsigned long long)client->max_reply_bytes);
            mt__parts_free(parts);
            failed = complete_locked(p);
            goto out;
        }
        p->parts = parts;
        client->parts_bytes += parts->total;
        parts->window_parts = parts->num_parts < MESHTOPO_REPLY_PART_T_FIRST_PARTS
                                  ? parts->num_parts
                                  : MESHTOPO_REPLY_PART_T_FIRST_PARTS;
    }
    mt__part_result r = mt__parts_add(p->parts, &part);
    if (r == MT__PART_OTHER || r == MT__PART_BAD) client->stats.bad_parts++;
    if (r != MT__PART_ADDED) goto out;
    client->stats.reply_parts++;
    mt__parts *parts = p->parts;
    parts->last_us = now;
    parts->window_have++;
    /* The daemon is alive: attempts start afresh, the quiet timer runs. */
    p->attempts_left = client->attempts - 1;
    p->deadline_us = now + MT__PARTS_QUIET_MS * 1000;
    if (p->deadline_us < client->next_deadline_us) {
        client->next_deadline_us = p->deadline_us;
        wake = 1;
    }
    if (mt__parts_complete(parts)) {
        const mt_msgs_type *type = mt_msgs_type_of(parts->data, (size_t)parts->total);
        if (mt_msgs_answer_hash(parts->data, (size_t)parts->total) == parts->hash &&
            (type == &mt_msgs_type_reply || type == &mt_msgs_type_ack)) {
            answer = parts->data;
            answer_size = (size_t)parts->total;
            parts->data = NULL;
            drop_parts(client, p);
        } else { /* not the answer announced: start over */
            client->stats.bad_parts++;
            drop_parts(client, p);
            send = p->buf;
            send_channel = p->channel;
            atomic_fetch_add(&send->refs, 1);
            client->stats.attempts++;
            /* The query is asked again: its answer gets a whole attempt's
             * time, not the 30 ms quiet timer of the parts just dropped. */
            p->deadline_us = now + (int64_t)client->timeout_ms * 1000;
        }
    } else if (parts->window_have >= parts->window_parts) {
        send = pull_locked(client, p);
        send_channel = client->pull_channel;
    }
out:
    pthread_mutex_unlock(&client->mutex);
    meshtopo_reply_part_t_decode_cleanup(&part);
    if (wake) wake_thread(client);
    if (send) {
        publish(client, send_channel, send);
        mt__msgbuf_release(send);
    }
    if (failed) call_back(failed);
    if (answer) {
        handle_answer(client, answer, answer_size);
        free(answer);
    }
}

/* The reply channel's handler. */
static void on_reply(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    handle_answer(user, rbuf->data, rbuf->data_size);
}

void mt__client_run_on_thread(mt_client *client, void (*fn)(void *arg), void *arg)
{
    if (client->external_handle || !client->thread_started ||
        pthread_equal(pthread_self(), client->thread)) {
        fn(arg);
        return;
    }
    mt__thread_call call = {.fn = fn, .arg = arg};
    pthread_mutex_lock(&client->mutex);
    call.next = client->calls;
    client->calls = &call;
    pthread_mutex_unlock(&client->mutex);
    wake_thread(client);
    pthread_mutex_lock(&client->mutex);
    while (!call.done) pthread_cond_wait(&client->calls_done, &client->mutex);
    pthread_mutex_unlock(&client->mutex);
}

/* Runs the calls waiting for the client's thread (on it). */
static void run_calls(mt_client *client)
{
    pthread_mutex_lock(&client->mutex);
    mt__thread_call *calls = client->calls;
    client->calls = NULL;
    pthread_mutex_unlock(&client->mutex);
    if (!calls) return;
    for (mt__thread_call *c = calls; c; c = c->next) c->fn(c->arg);
    pthread_mutex_lock(&client->mutex);
    for (mt__thread_call *c = calls, *next; c; c = next) {
        next = c->next; /* read before done: the waiter's frame holds c */
        c->done = 1;
    }
    pthread_cond_broadcast(&client->calls_done);
    pthread_mutex_unlock(&client->mutex);
}

static void *client_thread(void *arg)
{
    mt_client *client = arg;
    int lcm_fd = client->external_handle ? -1 : lcm_get_fileno(client->lcm);
    for (;;) {
        pthread_mutex_lock(&client->mutex);
        int stop = client->stop;
        int64_t next = client->next_deadline_us;
        pthread_mutex_unlock(&client->mutex);
        if (stop) break;

        int timeout_ms = 1000;
        if (next != INT64_MAX) {
            int64_t wait_us = next - mt__client_now_us();
            if (wait_us < 0) wait_us = 0;
            if (wait_us < 1000000) timeout_ms = (int)((wait_us + 999) / 1000);
        }
        struct pollfd fds[2] = {{client->wake_pipe[0], POLLIN, 0}, {lcm_fd, POLLIN, 0}};
        int n = poll(fds, lcm_fd >= 0 ? 2 : 1, timeout_ms);
        if (n > 0 && (fds[0].revents & POLLIN)) {
            char drain[64];
            while (read(client->wake_pipe[0], drain, sizeof drain) > 0) {
            }
        }
        if (n > 0 && lcm_fd >= 0 && (fds[1].revents & (POLLIN | POLLERR | POLLHUP)))
            lcm_handle(client->lcm);
        run_deadlines(client);
        run_calls(client);
    }
    return NULL;
}

/* ---- Create and destroy ------------------------------------------------- */

static int valid_prefix(const char *s)
{
    size_t n = strlen(s);
    if (n == 0 || n > MT_CLIENT_MAX_PREFIX) return 0;
    for (size_t i = 0; i < n; i++) {
        char c = s[i];
        if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
              c == '_' || c == '-'))
            return 0;
    }
    return 1;
}

/* PREFIX "REPLY_" host_pid_random: unique per client, no regex metacharacter
 * (lcm_subscribe takes a regular expression), within the protocol's
 * MESHTOPO_MESH_T_REPLY_CHANNEL_MAX (the host name is cut to 7 bytes). */
static void make_reply_channel(mt_client *client, const char *prefix)
{
    char host[8] = "host";
    char raw[256];
    if (gethostname(raw, sizeof raw) == 0) {
        raw[sizeof raw - 1] = '\0';
        size_t j = 0;
        for (size_t i = 0; raw[i] && j < sizeof host - 1; i++) {
            char c = raw[i];
            int ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
            host[j++] = ok ? c : '-';
        }
        if (j > 0) host[j] = '\0';
    }
    snprintf(client->reply_channel, sizeof client->reply_channel, "%sREPLY_%s_%ld_%08x", prefix,
             host, (long)getpid(), (unsigned)(random_u64() & 0xffffffffu));
}

mt_status mt_client_create(const mt_client_options *opts, mt_client **out, mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!out) return mt__client_fail(diag, MT_ERR_INVALID_ARG, "mt_client_create: out is NULL");
    *out = NULL;
    mt_client_options defaults;
    memset(&defaults, 0, sizeof defaults);
    if (!opts) opts = &defaults;

    const char *prefix = opts->channel_prefix ? opts->channel_prefix : MT_CLIENT_DEFAULT_PREFIX;
    if (!valid_prefix(prefix))
        return mt__client_fail(diag, MT_ERR_INVALID_ARG,
                               "channel prefix \"%.64s\" must be 1..%d characters of "
                               "[A-Za-z0-9_-]",
                               prefix, MT_CLIENT_MAX_PREFIX);
    if (opts->timeout_ms < 0)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "timeout_ms %d is negative",
                               opts->timeout_ms);
    if (opts->external_handle && !opts->lcm)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG,
                               "external_handle needs a caller-provided lcm");
    if (opts->chunk_bytes &&
        (opts->chunk_bytes < 64 || opts->chunk_bytes > MT_CLIENT_MAX_CHUNK_BYTES))
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "chunk_bytes %d is not within 64..%d",
                               opts->chunk_bytes, MT_CLIENT_MAX_CHUNK_BYTES);
    if (opts->window_chunks && (opts->window_chunks < 1 || opts->window_chunks > 4096))
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "window_chunks %d is not within 1..4096",
                               opts->window_chunks);
    const char *source = opts->source ? opts->source : "meshtopo-client";
    if (strlen(source) >= 256)
        return mt__client_fail(diag, MT_ERR_INVALID_ARG, "source name longer than 255 bytes");

    /* lcm-gen's fingerprints are computed on first use without a lock: do it
     * here, before any thread of ours uses a type. */
    (void)mt_msgs_type_of(NULL, 0);

    mt_client *client = calloc(1, sizeof *client);
    if (!client) return mt__client_fail(diag, MT_ERR_NOMEM, "mt_client_create: out of memory");
    client->wake_pipe[0] = client->wake_pipe[1] = -1;
    client->timeout_ms = opts->timeout_ms ? opts->timeout_ms : MT_CLIENT_DEFAULT_TIMEOUT_MS;
    int retries = opts->retries == 0 ? MT_CLIENT_DEFAULT_RETRIES : opts->retries;
    client->attempts = retries < 0 ? 1 : (retries > 1000 ? 1001 : retries + 1);
    client->external_handle = opts->external_handle;
    client->chunk_bytes = opts->chunk_bytes ? opts->chunk_bytes : MT_CLIENT_DEFAULT_CHUNK_BYTES;
    client->window_chunks =
        opts->window_chunks ? opts->window_chunks : MT_CLIENT_DEFAULT_WINDOW_CHUNKS;
    client->progress = opts->progress;
    client->progress_user = opts->progress_user;
    client->max_reply_bytes =
        opts->max_reply_bytes ? opts->max_reply_bytes : MT_CLIENT_DEFAULT_MAX_REPLY_BYTES;
    client->next_deadline_us = INT64_MAX;
    /* Ids start at a random point so a restarted node reusing a channel name
     * does not repeat recent ones; they stay positive. */
    client->next_request_id = (int64_t)(random_u64() >> 2) + 1;
    client->jitter_state = random_u64() | 1u;
    snprintf(client->source, sizeof client->source, "%s", source);
    /* valid_prefix keeps every name within LCM's limit. */
    mt_msgs_channel_name(prefix, MT_MSGS_CHANNEL_SUBMIT, client->submit_channel);
    mt_msgs_channel_name(prefix, MT_MSGS_CHANNEL_SUBMIT_CHUNK, client->chunk_channel);
    mt_msgs_channel_name(prefix, MT_MSGS_CHANNEL_QUERY, client->query_channel);
    mt_msgs_channel_name(prefix, MT_MSGS_CHANNEL_QUERY_PULL, client->pull_channel);
    mt_msgs_channel_name(prefix, MT_MSGS_CHANNEL_STATUS, client->status_channel);
    mt_msgs_channel_name(prefix, MT_MSGS_CHANNEL_TOPOLOGY, client->topology_channel);
    make_reply_channel(client, prefix);
    if (pthread_mutex_init(&client->mutex, NULL) != 0) {
        free(client);
        return mt__client_fail(diag, MT_ERR_NOMEM, "mt_client_create: no mutex");
    }
    pthread_cond_init(&client->calls_done, NULL);

    mt_status status = MT_OK;
    if (pipe(client->wake_pipe) != 0) {
        client->wake_pipe[0] = client->wake_pipe[1] = -1;
        status = mt__client_fail(diag, MT_ERR_IO, "pipe: %s", strerror(errno));
        goto fail;
    }
    for (int i = 0; i < 2; i++) {
        fcntl(client->wake_pipe[i], F_SETFL, fcntl(client->wake_pipe[i], F_GETFL) | O_NONBLOCK);
        fcntl(client->wake_pipe[i], F_SETFD, FD_CLOEXEC);
    }
    if (opts->lcm) {
        client->lcm = opts->lcm;
    } else {
        client->lcm = lcm_create(opts->lcm_url);
        client->own_lcm = 1;
        if (!client->lcm) {
            status = mt__client_fail(diag, MT_ERR_IO, "lcm_create(\"%s\") failed",
                                     opts->lcm_url ? opts->lcm_url : "(LCM default)");
            goto fail;
        }
    }
    /* One subscription per answer type, each on its own channel. */
    const mt_msgs_type *answers[4] = {&mt_msgs_type_ack, &mt_msgs_type_reply,
                                      &mt_msgs_type_reply_part, &mt_msgs_type_mesh_transfer};
    for (int i = 0; i < 4; i++) {
        char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
        mt_msgs_reply_channel_name(client->reply_channel, answers[i], channel);
        client->subscriptions[i] = lcm_subscribe(client->lcm, channel, on_reply, client);
        if (!client->subscriptions[i]) {
            status = mt__client_fail(diag, MT_ERR_IO, "lcm_subscribe(%s) failed", channel);
            goto fail;
        }
        lcm_subscription_set_queue_capacity(client->subscriptions[i], MT__REPLY_QUEUE_CAPACITY);
    }
    if (pthread_create(&client->thread, NULL, client_thread, client) != 0) {
        status = mt__client_fail(diag, MT_ERR_IO, "could not start the client thread");
        goto fail;
    }
    client->thread_started = 1;
    *out = client;
    return MT_OK;

fail:
    mt_client_destroy(client);
    return status;
}

void mt_client_destroy(mt_client *client)
{
    if (!client) return;
    if (client->thread_started) {
        pthread_mutex_lock(&client->mutex);
        client->stop = 1;
        pthread_mutex_unlock(&client->mutex);
        wake_thread(client);
        pthread_join(client->thread, NULL);
    }
    for (int i = 0; i < 4; i++)
        if (client->subscriptions[i]) lcm_unsubscribe(client->lcm, client->subscriptions[i]);

    /* Asynchronous requests still waiting get their callback. */
    for (size_t b = 0; b < MT__BUCKETS; b++) {
        while (client->buckets[b]) {
            mt__pending *p = client->buckets[b];
            client->buckets[b] = p->next;
            drop_parts(client, p);
            p->status = mt__client_fail(&p->diag, MT_ERR_IO,
                                        "client destroyed before request %lld was answered",
                                        (long long)p->request_id);
            if (complete_locked(p)) call_back(p);
        }
    }
    if (client->own_lcm && client->lcm) lcm_destroy(client->lcm);
    for (int i = 0; i < 2; i++)
        if (client->wake_pipe[i] >= 0) close(client->wake_pipe[i]);
    pthread_cond_destroy(&client->calls_done);
    pthread_mutex_destroy(&client->mutex);
    free(client);
}

const char *mt_client_reply_channel(const mt_client *client)
{
    return client ? client->reply_channel : "";
}

void mt_client_get_stats(mt_client *client, mt_client_stats *out_stats)
{
    if (!out_stats) return;
    if (!client) {
        memset(out_stats, 0, sizeof *out_stats);
        return;
    }
    pthread_mutex_lock(&client->mutex);
    *out_stats = client->stats;
    pthread_mutex_unlock(&client->mutex);
}
