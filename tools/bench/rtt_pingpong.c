/* The raw LCM floor of `meshtopo-bench rtt`: a ping of the query's encoded
 * size goes out on RTT_PING, an echo process answers with a pong of the
 * reply's size (named in the ping) on RTT_PONG, and the pinger times the round
 * trip. It measures LCM itself, so it calls LCM directly, as meshtopod and the
 * client do (lcm_get_fileno, poll, lcm_handle), with no meshtopo code between:
 * with transfer_raw.c, the only files of tools/ that use LCM without the client. */
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

#include "rtt.h"

#define PING_CHANNEL "RTT_PING"
#define PONG_CHANNEL "RTT_PONG"
#define SEQ_BYTES 8     /* a ping starts with its sequence number, */
#define HEADER_BYTES 12 /* then the size of the pong it asks for */
#define PONG_MAX (1u << 20)
#define ANSWER_WAIT_MS 1000
#define ATTEMPTS 3
#define READY_WAIT_MS 5000
#define WARMUP_ROUNDS 50

/* ---- the echo process ---------------------------------------------------- */

typedef struct echo_state {
    lcm_t *lcm;
    unsigned char *pong; /* [PONG_MAX] */
} echo_state;

static void on_ping(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    echo_state *e = user;
    uint32_t pong_size;
    if (rbuf->data_size < HEADER_BYTES) return;
    memcpy(&pong_size, (const unsigned char *)rbuf->data + SEQ_BYTES, sizeof pong_size);
    if (pong_size < SEQ_BYTES || pong_size > PONG_MAX) return;
    memcpy(e->pong, rbuf->data, SEQ_BYTES);
    lcm_publish(e->lcm, PONG_CHANNEL, e->pong, pong_size);
}

static void echo_main(void)
{
    echo_state e = {lcm_create(MT__RTT_LCM_URL), calloc(1, PONG_MAX)};
    if (!e.lcm || !e.pong) _exit(1);
    lcm_subscription_t *sub = lcm_subscribe(e.lcm, PING_CHANNEL, on_ping, &e);
    if (!sub) _exit(1);
    lcm_subscription_set_queue_capacity(sub, 10000);
    struct pollfd pfd = {lcm_get_fileno(e.lcm), POLLIN, 0};
    for (;;) { /* ends with the parent's SIGTERM */
        if (poll(&pfd, 1, 1000) > 0 && lcm_handle(e.lcm) != 0) _exit(1);
        if (getppid() == 1) _exit(0); /* the benchmark is gone */
    }
}

bool mt__rtt_echo_start(mt__rtt_echo *out, char *err, size_t err_size)
{
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(err, err_size, "fork: %s", strerror(errno));
        return false;
    }
    if (pid == 0) echo_main();
    out->pid = pid;
    return true;
}

void mt__rtt_echo_stop(mt__rtt_echo *echo)
{
    if (echo->pid <= 0) return;
    kill(echo->pid, SIGTERM);
    waitpid(echo->pid, NULL, 0);
    echo->pid = 0;
}

/* ---- the pinger ---------------------------------------------------------- */

typedef struct pinger {
    uint64_t last_seq;
    bool got;
} pinger;

static void on_pong(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    pinger *p = user;
    if (rbuf->data_size < SEQ_BYTES) return;
    memcpy(&p->last_seq, rbuf->data, SEQ_BYTES);
    p->got = true;
}

/* Publishes ping `seq` and handles pongs until that one arrives or
 * `wait_ms` pass; true when it arrived. */
static bool ping_once(lcm_t *lcm, pinger *p, unsigned char *ping, size_t ping_size, uint64_t seq,
                      int wait_ms)
{
    memcpy(ping, &seq, SEQ_BYTES);
    if (lcm_publish(lcm, PING_CHANNEL, ping, (unsigned)ping_size) != 0) return false;
    struct pollfd pfd = {lcm_get_fileno(lcm), POLLIN, 0};
    struct timespec start, now;
    clock_gettime(CLOCK_MONOTONIC, &start);
    for (;;) {
        clock_gettime(CLOCK_MONOTONIC, &now);
        int left = wait_ms - (int)(mt__bench_elapsed_us(&start, &now) / 1000);
        if (left < 0) return false;
        if (poll(&pfd, 1, left) <= 0) continue;
        p->got = false;
        if (lcm_handle(lcm) != 0) return false;
        if (p->got && p->last_seq == seq) return true;
    }
}

bool mt__rtt_pingpong(size_t ping_size, size_t pong_size, uint32_t count, double *out_us, char *err,
                      size_t err_size)
{
    if (ping_size < HEADER_BYTES) ping_size = HEADER_BYTES;
    if (pong_size < SEQ_BYTES) pong_size = SEQ_BYTES;
    if (pong_size > PONG_MAX) {
        snprintf(err, err_size, "pong of %zu bytes: larger than %u", pong_size, PONG_MAX);
        return false;
    }
    uint32_t pong_bytes = (uint32_t)pong_size;
    lcm_t *lcm = lcm_create(MT__RTT_LCM_URL);
    unsigned char *ping = calloc(1, ping_size);
    pinger p = {0, false};
    lcm_subscription_t *sub = lcm ? lcm_subscribe(lcm, PONG_CHANNEL, on_pong, &p) : NULL;
    bool ok = lcm && ping && sub;
    if (ping) memcpy(ping + SEQ_BYTES, &pong_bytes, sizeof pong_bytes);
    if (!ok) snprintf(err, err_size, "LCM or memory: cannot start the pinger");
    uint64_t seq = (uint64_t)getpid() << 32;

    /* The echo may not listen yet, and a fresh socket can miss its first
     * messages: ping until one comes back, then warm up. */
    bool ready = false;
    for (int waited = 0; ok && !ready && waited < READY_WAIT_MS; waited += 100)
        ready = ping_once(lcm, &p, ping, ping_size, ++seq, 100);
    if (ok && !ready) {
        snprintf(err, err_size, "the echo process did not answer within %d ms", READY_WAIT_MS);
        ok = false;
    }
    for (int i = 0; ok && i < WARMUP_ROUNDS; i++) ping_once(lcm, &p, ping, ping_size, ++seq, 100);

    for (uint32_t i = 0; ok && i < count; i++) {
        struct timespec t0, t1;
        bool answered = false;
        ++seq;
        /* Timed from the first attempt, as a client call with retries is. */
        clock_gettime(CLOCK_MONOTONIC, &t0);
        for (int attempt = 0; !answered && attempt < ATTEMPTS; attempt++)
            answered = ping_once(lcm, &p, ping, ping_size, seq, ANSWER_WAIT_MS);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        if (!answered) {
            snprintf(err, err_size, "ping %u got no pong after %d attempts", i, ATTEMPTS);
            ok = false;
        }
        out_us[i] = mt__bench_elapsed_us(&t0, &t1);
    }
    if (sub) lcm_unsubscribe(lcm, sub);
    if (lcm) lcm_destroy(lcm);
    free(ping);
    return ok;
}
