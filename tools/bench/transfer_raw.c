/* The raw LCM floor of `meshtopo-bench transfer`: the mesh's bytes pushed as
 * single-datagram messages (TRANSFER_RAW: a 16-byte header, then the payload),
 * a window at a time, the last of each asking the acker process for an
 * acknowledgement (TRANSFER_RAW_ACK). It measures LCM itself, so it calls LCM
 * directly (with rtt_pingpong.c, the only files of tools/ that do): no
 * reassembly, hashing or decoding, only LCM, the kernel and the ack round trips. */
#include <errno.h>
#include <lcm/lcm.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench_transfer.h"
#include "rtt.h"

#define DATA_CHANNEL "TRANSFER_RAW"
#define ACK_CHANNEL "TRANSFER_RAW_ACK"
#define HEADER_BYTES 16 /* window number (8), offset (4, in chunks), ack wanted (4) */
#define ACK_WAIT_MS 50
#define READY_WAIT_MS 5000
#define MAX_RESENDS 1000

/* ---- the acker process ---------------------------------------------------- */

typedef struct acker_state {
    lcm_t *lcm;
    uint64_t bytes; /* received, for nothing but touching them */
} acker_state;

static void on_data(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    acker_state *a = user;
    if (rbuf->data_size < HEADER_BYTES) return;
    a->bytes += rbuf->data_size - HEADER_BYTES;
    uint32_t want_ack;
    memcpy(&want_ack, (const uint8_t *)rbuf->data + 12, sizeof want_ack);
    if (want_ack) lcm_publish(a->lcm, ACK_CHANNEL, rbuf->data, 8); /* echoes the window number */
}

static void acker_main(void)
{
    acker_state a = {lcm_create(MT__RTT_LCM_URL), 0};
    if (!a.lcm) _exit(1);
    lcm_subscription_t *sub = lcm_subscribe(a.lcm, DATA_CHANNEL, on_data, &a);
    if (!sub) _exit(1);
    lcm_subscription_set_queue_capacity(sub, 10000);
    struct pollfd pfd = {lcm_get_fileno(a.lcm), POLLIN, 0};
    for (;;) { /* ends with the parent's SIGTERM */
        if (poll(&pfd, 1, 1000) > 0 && lcm_handle(a.lcm) != 0) _exit(1);
        if (getppid() == 1) _exit(0);
    }
}

bool mt__raw_acker_start(mt__raw_acker *out, char *err, size_t err_size)
{
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(err, err_size, "fork: %s", strerror(errno));
        return false;
    }
    if (pid == 0) acker_main();
    out->pid = pid;
    return true;
}

void mt__raw_acker_stop(mt__raw_acker *acker)
{
    if (acker->pid <= 0) return;
    kill(acker->pid, SIGTERM);
    waitpid(acker->pid, NULL, 0);
    acker->pid = 0;
}

/* ---- the pusher ----------------------------------------------------------- */

typedef struct pusher {
    uint64_t acked; /* the last window number acknowledged */
} pusher;

static void on_ack(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    pusher *p = user;
    uint64_t window;
    if (rbuf->data_size < sizeof window) return;
    memcpy(&window, rbuf->data, sizeof window);
    if (window > p->acked) p->acked = window;
}

/* Handles acknowledgements until window `number` is acknowledged or wait_ms
 * pass; true when it was. */
static bool await_ack(lcm_t *lcm, pusher *p, uint64_t number, int wait_ms)
{
    struct pollfd pfd = {lcm_get_fileno(lcm), POLLIN, 0};
    struct timespec start, now;
    clock_gettime(CLOCK_MONOTONIC, &start);
    while (p->acked < number) {
        clock_gettime(CLOCK_MONOTONIC, &now);
        int left = wait_ms - (int)(mt__bench_elapsed_us(&start, &now) / 1000);
        if (left < 0) return false;
        if (poll(&pfd, 1, left) > 0 && lcm_handle(lcm) != 0) return false;
    }
    return true;
}

/* Publishes chunks first .. first + count - 1, the last asking for an ack. */
static bool send_window(lcm_t *lcm, uint8_t *msg, const uint8_t *bytes, uint64_t total,
                        uint32_t chunk, uint64_t number, uint64_t first, uint32_t count)
{
    for (uint32_t k = 0; k < count; k++) {
        uint64_t offset = (first + k) * chunk;
        uint64_t length = total - offset < chunk ? total - offset : chunk;
        uint32_t index = (uint32_t)(first + k), want_ack = k + 1 == count;
        memcpy(msg, &number, 8);
        memcpy(msg + 8, &index, 4);
        memcpy(msg + 12, &want_ack, 4);
        memcpy(msg + HEADER_BYTES, bytes + offset, (size_t)length);
        if (lcm_publish(lcm, DATA_CHANNEL, msg, (unsigned)(HEADER_BYTES + length)) != 0)
            return false;
    }
    return true;
}

bool mt__raw_push(const uint8_t *bytes, uint64_t total, uint32_t chunk, uint32_t window,
                  double *out_seconds, char *err, size_t err_size)
{
    lcm_t *lcm = lcm_create(MT__RTT_LCM_URL);
    uint8_t *msg = malloc(HEADER_BYTES + (size_t)chunk);
    pusher p = {0};
    lcm_subscription_t *sub = lcm ? lcm_subscribe(lcm, ACK_CHANNEL, on_ack, &p) : NULL;
    bool ok = lcm && msg && sub;
    if (!ok) snprintf(err, err_size, "LCM or memory: cannot start the raw pusher");
    uint64_t number = (uint64_t)getpid() << 32;
    /* The acker may not listen yet: one-message windows until one is acked. */
    bool ready = false;
    for (int waited = 0; ok && !ready && waited < READY_WAIT_MS; waited += 100) {
        ok = send_window(lcm, msg, bytes, total, chunk, ++number, 0, 1);
        ready = ok && await_ack(lcm, &p, number, 100);
    }
    if (ok && !ready) {
        snprintf(err, err_size, "the raw acker did not answer within %d ms", READY_WAIT_MS);
        ok = false;
    }
    uint64_t num_chunks = (total + chunk - 1) / chunk;
    uint32_t resends = 0;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (uint64_t first = 0; ok && first < num_chunks;) {
        uint32_t count = num_chunks - first < window ? (uint32_t)(num_chunks - first) : window;
        ok = send_window(lcm, msg, bytes, total, chunk, ++number, first, count);
        if (ok && await_ack(lcm, &p, number, ACK_WAIT_MS)) {
            first += count;
        } else if (ok && ++resends > MAX_RESENDS) {
            snprintf(err, err_size, "raw push: %u windows without an acknowledgement", resends);
            ok = false;
        }
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    *out_seconds = mt__bench_elapsed_us(&t0, &t1) / 1e6;
    if (sub) lcm_unsubscribe(lcm, sub);
    if (lcm) lcm_destroy(lcm);
    free(msg);
    return ok;
}
