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
typedef struct mt__transfer {
    uint64_t seq; /* statuses received so far */
    int complete; /* every byte is in: only the ack is awaited */
    uint64_t received, listed_until;
    size_t num_missing;
    int64_t resume_us; /* BUSY: send nothing before this (monotonic) */
    int64_t missing_offsets[MESHTOPO_MESH_TRANSFER_T_MISSING_MAX];
    int64_t missing_lengths[MESHTOPO_MESH_TRANSFER_T_MISSING_MAX];
} mt__transfer;

/* A large answer being reassembled from reply_part_t pieces (reply_assembly.c). */
typedef struct mt__parts {
    uint64_t total, hash; /* of the answer, from its first part */
    uint32_t part_size;
    size_t num_parts, num_have;
    uint8_t *have;                    /* per part */
    uint8_t *data;                    /* total bytes */
    int64_t last_us;                  /* monotonic time of the last new part */
    size_t window_parts, window_have; /* parts asked for by the last pull, and of them arrived */
} mt__parts;

typedef enum mt__part_result {
    MT__PART_ADDED,
    MT__PART_DUPLICATE,
    MT__PART_OTHER, /* another answer: total_size, answer_hash or part_size differ */
    MT__PART_BAD    /* offset or length break the layout */
} mt__part_result;

typedef struct mt__pending {
    int64_t request_id;
    struct mt__pending *next;     /* in its bucket of the table */
    struct mt__pending *due_next; /* in the client thread's list of due requests */
    const mt_msgs_type *answer_type;
    const char *channel; /* where the request goes (the client's strings) */
    mt__msgbuf *buf;
    int64_t deadline_us; /* monotonic clock */
    int attempts_left;   /* after the one in flight */
    int busy_answers;    /* BUSY answers so far, each retried after a longer pause */

    /* Completion. */
    int done;
    mt_status status;
    int has_answer;
    mt__answer answer;
    mt_diag diag;

    /* A chunked submission: statuses land here and signal cond. */
    mt__transfer *transfer;
    /* A large answer arriving in parts (NULL until its first part). */
    mt__parts *parts;

    /* Synchronous: the waiter sleeps on cond. Asynchronous: callback != NULL. */
    pthread_cond_t cond;
    mt_client_reply_fn callback;
    void *user;
} mt__pending;

#define MT__BUCKETS 256
/* Answers remembered after their call completed, to tell a copy of one
 * (the daemon sending it again) from another answer (a second daemon). */
#define MT__RECENT_ANSWERS 64

typedef struct mt__recent_answer {
    int64_t request_id;
    const mt_msgs_type *type;
    int64_t utime; /* the answer's: a copy has the same */
} mt__recent_answer;

/* A function the client's thread runs between two lcm_handle calls
 * (mt__client_run_on_thread). */
typedef struct mt__thread_call {
    struct mt__thread_call *next;
    void (*fn)(void *arg);
    void *arg;
    int done;
} mt__thread_call;

struct mt_client {
    lcm_t *lcm;
    int own_lcm;
    int external_handle;
    lcm_subscription_t *subscriptions[4];                   /* R_ACK, R_REPLY, R_PART, R_TRANSFER */
    char reply_channel[LCM_MAX_CHANNEL_NAME_LENGTH + 1];    /* R: answers come on R_ACK, ... */
    char submit_channel[LCM_MAX_CHANNEL_NAME_LENGTH + 1];   /* mesh_t */
    char chunk_channel[LCM_MAX_CHANNEL_NAME_LENGTH + 1];    /* mesh_chunk_t */
    char query_channel[LCM_MAX_CHANNEL_NAME_LENGTH + 1];    /* query_t */
    char pull_channel[LCM_MAX_CHANNEL_NAME_LENGTH + 1];     /* reply_pull_t */
    char status_channel[LCM_MAX_CHANNEL_NAME_LENGTH + 1];   /* status_t, watched */
    char topology_channel[LCM_MAX_CHANNEL_NAME_LENGTH + 1]; /* topology_t, watched */
    char source[256];
    int timeout_ms;
    int attempts;      /* 1 + retries */
    int chunk_bytes;   /* content bytes per mesh_chunk_t */
    int window_chunks; /* chunks sent per status round trip */
    mt_client_progress_fn progress;
    void *progress_user;
    uint64_t max_reply_bytes; /* held by partly received answers, all together */
    uint64_t parts_bytes;     /* held now */

    pthread_t thread;
    int thread_started;
    int wake_pipe[2];

    pthread_mutex_t mutex;
    int stop;
    mt__pending *buckets[MT__BUCKETS];
    mt__thread_call *calls;    /* waiting for the client's thread */
    pthread_cond_t calls_done; /* broadcast when one has run */
    size_t num_pending;
    int64_t next_deadline_us;
    int64_t next_request_id;
    uint64_t jitter_state; /* spreads the pauses after BUSY */
    mt__recent_answer recent[MT__RECENT_ANSWERS];
    size_t recent_next;
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

/* Bytes of mesh_t's content fields once encoded (submit_content.c); 0 when a
 * count does not fit its int32 field or the message would exceed LCM's limit. */
uint64_t mt__content_size(const mt_face_list *list);

/* Points m's content fields (num_verts .. face_vertex_indices) at list's
 * arrays (submit_content.c); the list must fit (mt__content_size > 0). */
void mt__mesh_content_of(const mt_face_list *list, meshtopo_mesh_t *m);

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

/* Sends mesh m, whose encoded mesh_t is too large for one datagram, as
 * mesh_chunk_t pieces of its content (encoded from m's arrays a chunk at a
 * time; content_hash is the content's hash) and waits for the ack, like a
 * synchronous call: p (zeroed by the caller) holds the answer whatever the
 * status (submit_chunked.c). */
mt_status mt__client_submit_chunked(mt_client *client, const meshtopo_mesh_t *m,
                                    uint64_t content_hash, mt__pending *p, mt_diag *diag);

/* Reassembly of large answers (reply_assembly.c). mt__parts_create checks the
 * first part's header (MT_ERR_INVALID_ARG when it is impossible) and
 * allocates total_size bytes (MT_ERR_NOMEM); it does not add the part. */
mt_status mt__parts_create(const meshtopo_reply_part_t *part, mt__parts **out_parts);
void mt__parts_free(mt__parts *parts);
mt__part_result mt__parts_add(mt__parts *parts, const meshtopo_reply_part_t *part);
int mt__parts_complete(const mt__parts *parts);
/* The first missing parts (at most max_parts), as at most max_ranges merged
 * byte ranges into out_offsets / out_lengths. Returns the number of ranges;
 * *out_num_parts (may be NULL) gets the number of parts they cover. */
size_t mt__parts_missing(const mt__parts *parts, size_t max_parts, size_t max_ranges,
                         int64_t *out_offsets, int64_t *out_lengths, size_t *out_num_parts);

/* Waits until the synchronous request p completes (it is then out of the
 * table) and releases its buffer. */
void mt__client_wait(mt_client *client, mt__pending *p);

/* Runs fn(arg) on the client's thread between two lcm_handle calls, so that
 * no LCM handler runs meanwhile, and returns once it has run. On the
 * client's thread itself (or with external_handle, where the caller's own
 * thread handles LCM) it runs fn at once. */
void mt__client_run_on_thread(mt_client *client, void (*fn)(void *arg), void *arg);

#endif
