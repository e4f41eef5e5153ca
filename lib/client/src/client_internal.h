/* Internals of meshtopo::client shared by its files: the client object, the
 * table of pending requests keyed by request id, and the request life cycle
 * (send, retry on timeout, complete on reply or after the last attempt).
 * Every field of a pending request is guarded by the client's mutex. */
#ifndef MESHTOPO_CLIENT_INTERNAL_H
#define MESHTOPO_CLIENT_INTERNAL_H

#include <pthread.h>
#include <stdatomic.h>

#include "meshtopo/client.h"

/* An encoded request, shared by the pending request and any thread publishing
 * it; freed when the last reference is dropped. */
typedef struct mt__msgbuf {
    atomic_int refs;
    int size;
    uint8_t data[];
} mt__msgbuf;

/* A decoded answer: reply_t to a query_t, ack_t to a mesh_t. */
typedef union mt__answer {
    meshtopo_reply_t reply;
    meshtopo_ack_t ack;
} mt__answer;

/* What the daemon last said about a chunked submission (mesh_transfer_t). */
#define MT__TRANSFER_GAPS_MAX 1024
typedef struct mt__transfer {
    uint64_t seq; /* statuses received so far */
    int complete; /* every byte is in: only the ack is awaited */
    uint64_t received, listed_until;
    size_t num_missing;
    int64_t missing_offsets[MT__TRANSFER_GAPS_MAX];
    int64_t missing_lengths[MT__TRANSFER_GAPS_MAX];
} mt__transfer;

typedef struct mt__pending {
    int64_t request_id;
    struct mt__pending *next;     /* in its bucket of the table */
    struct mt__pending *due_next; /* in the client thread's list of due requests */
    const mt_msgs_type *answer_type;
    const char *channel; /* where the request goes (the client's strings) */
    mt__msgbuf *buf;
    int64_t deadline_us; /* monotonic clock */
    int attempts_left;   /* after the one in flight */

    /* Completion. */
    int done;
    mt_status status;
    int has_answer;
    mt__answer answer;
    mt_diag diag;

    /* A chunked submission: statuses land here and signal cond. */
    mt__transfer *transfer;

    /* Synchronous: the waiter sleeps on cond. Asynchronous: callback != NULL. */
    pthread_cond_t cond;
    mt_client_reply_fn callback;
    void *user;
} mt__pending;

#define MT__BUCKETS 256

struct mt_client {
    lcm_t *lcm;
    int own_lcm;
    int external_handle;
    lcm_subscription_t *subscription;
    char reply_channel[LCM_MAX_CHANNEL_NAME_LENGTH + 1];
    char submit_channel[LCM_MAX_CHANNEL_NAME_LENGTH + 1];
    char query_channel[LCM_MAX_CHANNEL_NAME_LENGTH + 1];
    char source[256];
    int timeout_ms;
    int attempts;      /* 1 + retries */
    int chunk_bytes;   /* content bytes per mesh_chunk_t */
    int window_chunks; /* chunks sent per status round trip */
    mt_client_progress_fn progress;
    void *progress_user;

    pthread_t thread;
    int thread_started;
    int wake_pipe[2];

    pthread_mutex_t mutex;
    int stop;
    mt__pending *buckets[MT__BUCKETS];
    size_t num_pending;
    int64_t next_deadline_us;
    int64_t next_request_id;
    mt_client_stats stats;
};

/* Monotonic and wall clocks in microseconds. */
int64_t mt__client_now_us(void);
int64_t mt__client_utime(void);

/* Formats into diag (NULL-safe) and returns status. */
mt_status mt__client_fail(mt_diag *diag, mt_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Bytes of mesh_t's content fields once encoded (content_hash.c); 0 when a
 * count does not fit its int32 field or the message would exceed LCM's limit. */
uint64_t mt__content_size(const mt_face_list *list);

/* A new request id (unique within the client). */
int64_t mt__client_next_id(mt_client *client);

/* A message buffer of `size` bytes with one reference; NULL when out of memory. */
mt__msgbuf *mt__msgbuf_new(int size);
void mt__msgbuf_release(mt__msgbuf *buf);

/* Inserts p (request_id, answer_type, channel, buf and callback set) into the
 * table and publishes the first attempt. Returns MT_OK, or MT_ERR_INVALID_ARG
 * for a synchronous call from the client's own thread; p is then not in the
 * table. */
mt_status mt__client_start(mt_client *client, mt__pending *p);

/* Sends a mesh whose encoded mesh_t (buf, `size` bytes; its last `tail`
 * bytes are the content) is too large for one datagram as mesh_chunk_t
 * pieces and waits for the ack, like a synchronous call: p (zeroed by the
 * caller) holds the answer whatever the status (submit_chunked.c). */
mt_status mt__client_submit_chunked(mt_client *client, const meshtopo_mesh_t *m,
                                    const uint8_t *encoded, size_t size, size_t tail,
                                    uint64_t content_hash, mt__pending *p, mt_diag *diag);

/* Waits until the synchronous request p completes (it is then out of the
 * table) and releases its buffer. */
void mt__client_wait(mt_client *client, mt__pending *p);

#endif
