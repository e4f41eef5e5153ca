/* lcm_selftest: publishes numbered messages on a test channel over LCM's UDP
 * multicast and receives them itself, to check the network that netns-run
 * sets up. Exits 0 when every message arrived; with --expect-loss PERCENT,
 * when some but fewer than PERCENT % arrived (netns-run --loss works). Talks
 * to LCM the way the daemon will: lcm_get_fileno + poll, then lcm_handle.
 *
 * usage: lcm_selftest [--count N] [--size BYTES] [--url URL] [--channel NAME]
 *                     [--timeout-ms MS] [--expect-loss PERCENT] */
#include <errno.h>
#include <inttypes.h>
#include <lcm/lcm.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define SELFTEST_MAGIC 0x4d545354u /* "MTST" */
#define HEADER_BYTES 16            /* magic, run nonce, sequence number, count */

typedef struct selftest {
    uint32_t nonce;
    uint32_t count;
    uint32_t received;   /* distinct sequence numbers seen */
    uint32_t duplicates; /* the same number seen again */
    uint32_t foreign;    /* messages on the channel that are not ours */
    unsigned char *seen; /* [count] */
} selftest;

static void put_u32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static uint32_t get_u32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | (uint32_t)p[3];
}

static void on_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    selftest *st = user;
    const unsigned char *p = rbuf->data;
    if (rbuf->data_size < HEADER_BYTES || get_u32(p) != SELFTEST_MAGIC ||
        get_u32(p + 4) != st->nonce || get_u32(p + 12) != st->count ||
        get_u32(p + 8) >= st->count) {
        st->foreign++;
        return;
    }
    uint32_t seq = get_u32(p + 8);
    if (st->seen[seq]) {
        st->duplicates++;
        return;
    }
    st->seen[seq] = 1;
    st->received++;
}

static int64_t now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* Handles every message that arrives within timeout_ms (0: only those
 * already there). Returns -1 on a poll or LCM error. */
static int handle_for(lcm_t *lcm, selftest *st, int timeout_ms)
{
    int fd = lcm_get_fileno(lcm);
    int64_t deadline = now_ms() + timeout_ms;
    if (st->received == st->count && timeout_ms > 0) return 0;
    for (;;) {
        int64_t left = deadline - now_ms();
        if (left < 0) left = 0;
        struct pollfd pfd = {fd, POLLIN, 0};
        int r = poll(&pfd, 1, (int)left);
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) {
            perror("lcm_selftest: poll");
            return -1;
        }
        if (r == 0) return 0;
        if (lcm_handle(lcm) != 0) {
            fprintf(stderr, "lcm_selftest: lcm_handle failed\n");
            return -1;
        }
        if (st->received == st->count && timeout_ms > 0) return 0;
    }
}

static int usage(void)
{
    fprintf(stderr,
            "usage: lcm_selftest [--count N] [--size BYTES] [--url URL] [--channel NAME]\n"
            "                    [--timeout-ms MS] [--expect-loss PERCENT]\n");
    return 2;
}

/* Parses a whole number in [min, max]; 0 on error. */
static int parse_u32(const char *text, uint32_t min, uint32_t max, uint32_t *out)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(text, &end, 10);
    if (errno || end == text || *end || text[0] == '-' || v < min || v > max) return 0;
    *out = (uint32_t)v;
    return 1;
}

int main(int argc, char **argv)
{
    uint32_t count = 100, size = 64, timeout_ms = 2000, expect_loss = 0;
    const char *url = "udpm://239.255.76.67:7667?ttl=0";
    const char *channel = "MESHTOPO_NETNS_SELFTEST";
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (i + 1 >= argc) return usage();
        const char *value = argv[++i];
        int ok = 1;
        if (strcmp(arg, "--count") == 0)
            ok = parse_u32(value, 1, 1000000, &count);
        else if (strcmp(arg, "--size") == 0)
            ok = parse_u32(value, HEADER_BYTES, 60000, &size);
        else if (strcmp(arg, "--timeout-ms") == 0)
            ok = parse_u32(value, 1, 600000, &timeout_ms);
        else if (strcmp(arg, "--expect-loss") == 0)
            ok = parse_u32(value, 1, 100, &expect_loss);
        else if (strcmp(arg, "--url") == 0)
            url = value;
        else if (strcmp(arg, "--channel") == 0)
            channel = value;
        else
            return usage();
        if (!ok) {
            fprintf(stderr, "lcm_selftest: bad value '%s' for %s\n", value, arg);
            return 2;
        }
    }

    selftest st = {0};
    st.count = count;
    st.nonce = (uint32_t)getpid() ^ (uint32_t)now_ms();
    st.seen = calloc(count, 1);
    unsigned char *msg = calloc(size, 1);
    if (!st.seen || !msg) {
        fprintf(stderr, "lcm_selftest: out of memory\n");
        return 2;
    }
    lcm_t *lcm = lcm_create(url);
    if (!lcm) {
        fprintf(stderr,
                "lcm_selftest: lcm_create(\"%s\") failed (is there a multicast route? run it "
                "through tests/netns/netns-run)\n",
                url);
        return 1;
    }
    lcm_subscription_t *sub = lcm_subscribe(lcm, channel, on_message, &st);
    if (!sub) {
        fprintf(stderr, "lcm_selftest: cannot subscribe to %s\n", channel);
        lcm_destroy(lcm);
        return 1;
    }
    /* LCM queues at most 30 unhandled messages per subscription by default and
     * silently drops the rest, which a burst of publishes overruns: room for
     * all of them, so that only the network can lose one. */
    lcm_subscription_set_queue_capacity(sub, (int)count);
    int status = 0;
    /* The receiving socket exists once the file descriptor has been asked for. */
    if (lcm_get_fileno(lcm) < 0) status = -1;
    for (uint32_t seq = 0; status == 0 && seq < count; seq++) {
        put_u32(msg, SELFTEST_MAGIC);
        put_u32(msg + 4, st.nonce);
        put_u32(msg + 8, seq);
        put_u32(msg + 12, count);
        if (lcm_publish(lcm, channel, msg, size) != 0) {
            /* A publish can fail when --loss drops the packet at output
             * (EPERM from the firewall): that is a lost message, not an error. */
            if (!expect_loss) fprintf(stderr, "lcm_selftest: publish %u failed\n", seq);
        }
        status = handle_for(lcm, &st, 0);
    }
    if (status == 0) status = handle_for(lcm, &st, (int)timeout_ms);
    lcm_destroy(lcm);
    free(msg);
    free(st.seen);
    if (status != 0) return 1;

    printf("lcm_selftest: received %" PRIu32 " of %" PRIu32 " messages of %" PRIu32
           " bytes on %s via %s (%" PRIu32 " duplicates, %" PRIu32 " foreign)\n",
           st.received, count, size, channel, url, st.duplicates, st.foreign);
    if (expect_loss) {
        /* Loss is working when some messages got through and clearly fewer
         * than all: more than none, fewer than expect_loss percent. */
        uint64_t limit = (uint64_t)count * expect_loss;
        if (st.received == 0) {
            fprintf(stderr, "lcm_selftest: nothing arrived: the network is broken, not lossy\n");
            return 1;
        }
        if ((uint64_t)st.received * 100 >= limit) {
            fprintf(stderr,
                    "lcm_selftest: %" PRIu32 " of %" PRIu32 " arrived, expected fewer than %" PRIu32
                    "%%: no loss was injected\n",
                    st.received, count, expect_loss);
            return 1;
        }
        return 0;
    }
    if (st.received != count) {
        fprintf(stderr, "lcm_selftest: %" PRIu32 " of %" PRIu32 " messages lost\n",
                count - st.received, count);
        return 1;
    }
    return 0;
}
