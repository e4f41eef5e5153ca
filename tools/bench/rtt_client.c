/* The clients of a `meshtopo-bench rtt` or `transfer` run: a client on the
 * run's LCM URL, and waiting through one for the heartbeat of the meshtopod
 * the run started (mt_client_wait_daemon). Each lives in one process; the
 * waiting client is gone before the run forks its helper processes. */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "rtt.h"

mt_client *mt__rtt_client_new(const char *source)
{
    mt_client_options opts;
    memset(&opts, 0, sizeof opts);
    opts.lcm_url = MT__RTT_LCM_URL;
    opts.source = source;
    mt_client *client = NULL;
    mt_diag diag;
    mt_diag_clear(&diag);
    mt_status st = mt_client_create(&opts, &client, &diag);
    if (st != MT_OK)
        fprintf(stderr, "meshtopo-bench rtt: %s: cannot create a client: %s (%s)\n", source,
                mt_strerror(st), diag.message);
    return client;
}

bool mt__rtt_daemon_wait(pid_t pid, int timeout_ms)
{
    mt_client *client = mt__rtt_client_new("meshtopo-bench-rtt-wait");
    if (!client) return false;
    double deadline = mt__bench_now_ms() + timeout_ms;
    bool heard = false;
    /* Heartbeats of another daemon on the group do not count. */
    for (int left = timeout_ms; !heard && left > 0; left = (int)(deadline - mt__bench_now_ms())) {
        meshtopo_status_t *status = NULL;
        mt_diag diag;
        if (mt_client_wait_daemon(client, left, &status, &diag) != MT_OK) break;
        heard = status->pid == (int32_t)pid;
        meshtopo_status_t_destroy(status);
    }
    mt_client_destroy(client);
    return heard;
}
