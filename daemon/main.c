/* meshtopod: the meshtopo daemon's entry point and LCM loop. Settings come
 * from flags and MESHTOPOD_* variables (`meshtopod --help`). One thread runs
 * LCM: lcm_get_fileno + poll with the heartbeat as timeout, and a self-pipe
 * for SIGINT/SIGTERM in the same poll. On a signal it stops taking work,
 * cancels queued builds (their senders get BUSY), lets running builds finish,
 * publishes a last heartbeat and exits 0. */
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <lcm/lcm.h>
#include <poll.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "config.h"
#include "daemon.h"
#include "log.h"

static int signal_pipe[2] = {-1, -1};

static void on_signal(int signo)
{
    int saved = errno;
    unsigned char byte = (unsigned char)signo;
    ssize_t ignored = write(signal_pipe[1], &byte, 1);
    (void)ignored;
    errno = saved;
}

static int install_signals(void)
{
    if (pipe(signal_pipe) != 0) return -1;
    for (int i = 0; i < 2; i++) {
        fcntl(signal_pipe[i], F_SETFL, fcntl(signal_pipe[i], F_GETFL) | O_NONBLOCK);
        fcntl(signal_pipe[i], F_SETFD, FD_CLOEXEC);
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    if (sigaction(SIGINT, &sa, NULL) != 0 || sigaction(SIGTERM, &sa, NULL) != 0) return -1;
    signal(SIGPIPE, SIG_IGN);
    return 0;
}

/* Listens on the status channel for two of our heartbeat periods before
 * serving: a daemon already on the prefix beats within that time. Returns
 * false (after logging it) when one does that is not a member of our
 * cluster; the members heard go to `cluster` (NULL without one), so that
 * this daemon starts with the ids it owns and not every id. */
static bool prefix_is_free(lcm_t *lcm, const mtd_config *config, mtd_cluster *cluster)
{
    char channel[MT_MSGS_CHANNEL_NAME_MAX + 1];
    if (mt_msgs_channel_name(config->channel_prefix, MT_MSGS_CHANNEL_STATUS, channel) != MT_OK)
        return true; /* the daemon refuses the prefix itself */
    mtd_peers *probe = NULL;
    if (mtd_peers_create(lcm, channel, "", INT64_MAX, NULL, cluster, &probe) != MT_OK) return true;
    int64_t wait_us = 2 * (int64_t)config->heartbeat_ms * 1000;
    if (wait_us > 3000000) wait_us = 3000000;
    const int64_t until = mtd_now_utime() + wait_us;
    char who[256];
    bool taken = false;
    for (int64_t now = mtd_now_utime(); now < until && !taken; now = mtd_now_utime()) {
        lcm_handle_timeout(lcm, (int)((until - now + 999) / 1000));
        taken = mtd_peers_older_seen(probe, who, sizeof who);
    }
    mtd_peers_destroy(probe);
    if (taken)
        mtd_log(MTD_LOG_ERROR, "second_daemon",
                "another meshtopod serves prefix %s: %s; not starting (one daemon per prefix: "
                "give this one another --prefix, or stop the other)",
                config->channel_prefix, who);
    return !taken;
}

/* Runs until a signal arrives; returns the signal number (0 on an LCM error). */
static int run_loop(mtd_daemon *d, lcm_t *lcm, const mtd_config *config)
{
    const int64_t period_us = (int64_t)config->heartbeat_ms * 1000;
    const int64_t watch_us = period_us / 4; /* the cluster's view: a quarter period late at most */
    int64_t next_beat = mtd_monotonic_us(), next_watch = next_beat;
    struct pollfd fds[2] = {{.fd = lcm_get_fileno(lcm), .events = POLLIN},
                            {.fd = signal_pipe[0], .events = POLLIN}};
    for (;;) {
        int64_t now = mtd_monotonic_us();
        if (now >= next_beat) {
            mtd_daemon_tick(d);
            next_beat = now + period_us;
        }
        if (now >= next_watch) {
            mtd_daemon_watch_cluster(d);
            next_watch = now + watch_us;
        }
        int64_t next = next_watch < next_beat ? next_watch : next_beat;
        int timeout_ms = (int)((next - now + 999) / 1000);
        int n = poll(fds, 2, timeout_ms);
        if (n < 0 && errno != EINTR) {
            mtd_log(MTD_LOG_ERROR, "poll", "error=%s", strerror(errno));
            return 0;
        }
        if (n > 0 && (fds[1].revents & POLLIN)) {
            unsigned char signo = 0;
            if (read(signal_pipe[0], &signo, 1) == 1) return signo;
        }
        if (n > 0 && (fds[0].revents & POLLIN) && lcm_handle(lcm) != 0) {
            mtd_log(MTD_LOG_ERROR, "lcm", "lcm_handle failed");
            return 0;
        }
    }
}

int main(int argc, char **argv)
{
    mtd_config config;
    mtd_config_action action = MTD_CONFIG_RUN;
    mt_diag diag;
    if (mtd_config_parse(argc, argv, &config, &action, &diag) != MT_OK) {
        fprintf(stderr, "meshtopod: %s\n", diag.message);
        return 2;
    }
    if (action == MTD_CONFIG_HELP) {
        mtd_config_usage(stdout);
        return 0;
    }
    if (action == MTD_CONFIG_VERSION) {
        printf("meshtopod %s\n", MESHTOPO_VERSION);
        return 0;
    }
    mtd_log_set_level(config.log_level);
    if (install_signals() != 0) {
        mtd_log(MTD_LOG_ERROR, "start", "cannot install the signal handlers: %s", strerror(errno));
        return 1;
    }
    lcm_t *lcm = lcm_create(config.lcm_url[0] ? config.lcm_url : NULL);
    if (!lcm) {
        mtd_log(MTD_LOG_ERROR, "start", "cannot create LCM with url=%s",
                config.lcm_url[0] ? config.lcm_url : "(LCM default)");
        return 1;
    }
    mtd_cluster *cluster = NULL;
    char instance[128];
    mtd_daemon_instance_name(mtd_now_utime(), instance, sizeof instance);
    if (mtd_daemon_cluster_create(&config, instance, &cluster) != MT_OK) {
        mtd_log(MTD_LOG_ERROR, "start", "cannot create the cluster membership: out of memory");
        lcm_destroy(lcm);
        return 1;
    }
    if (!prefix_is_free(lcm, &config, cluster)) {
        mtd_cluster_destroy(cluster);
        lcm_destroy(lcm);
        return 1;
    }
    mtd_daemon *d = NULL;
    if (mtd_daemon_create(&config, lcm, cluster, &d, &diag) != MT_OK) {
        mtd_log(MTD_LOG_ERROR, "start", "error=%s", diag.message);
        lcm_destroy(lcm);
        return 1;
    }
    mtd_config_log(&config);
    mtd_log(MTD_LOG_INFO, "start", "version=%s submit=%s query=%s instance=%s", MESHTOPO_VERSION,
            mtd_daemon_channel(d, MT_MSGS_CHANNEL_SUBMIT),
            mtd_daemon_channel(d, MT_MSGS_CHANNEL_QUERY), mtd_daemon_instance(d));
    int signo = run_loop(d, lcm, &config);
    mtd_log(MTD_LOG_INFO, "stopping", "signal=%s",
            signo == SIGINT    ? "SIGINT"
            : signo == SIGTERM ? "SIGTERM"
                               : "none (LCM error)");
    mtd_daemon_stop(d);
    mtd_daemon_heartbeat(d);
    mtd_counters counts;
    mtd_daemon_get_counts(d, &counts);
    mtd_log(MTD_LOG_INFO, "stop",
            "submissions=%" PRId64 " builds=%" PRId64 " queries=%" PRId64 " errors=%" PRId64,
            counts.submissions, counts.builds, counts.queries, counts.errors);
    mtd_daemon_destroy(d);
    lcm_destroy(lcm);
    return signo ? 0 : 1;
}
