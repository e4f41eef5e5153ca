/* Packet loss for `meshtopo-bench transfer`: an nftables table in the
 * benchmark's own private network namespace whose output chain drops a share
 * of UDP packets (`numgen random mod 100 < P`, the rule tests/netns/netns-run
 * installs). Only ever run after mt__rtt_enter_private_network, so the host's
 * firewall is never touched. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "bench_transfer.h"

#define TABLE "meshtopo_bench_loss"

/* Runs `nft -f -` with `script` on its input; true on exit status 0. */
static bool run_nft(const char *script, char *err, size_t err_size)
{
    FILE *p = popen("nft -f - 2>&1", "w");
    if (!p) {
        snprintf(err, err_size, "cannot run nft");
        return false;
    }
    fputs(script, p);
    int status = pclose(p);
    if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        snprintf(err, err_size, "nft failed (exit %d)%s",
                 status == -1 || !WIFEXITED(status) ? -1 : WEXITSTATUS(status),
                 WIFEXITED(status) && WEXITSTATUS(status) == 127 ? ": nft is not installed" : "");
        return false;
    }
    return true;
}

bool mt__transfer_set_loss(int percent, char *err, size_t err_size)
{
    if (system("command -v nft >/dev/null 2>&1") != 0) {
        snprintf(err, err_size, "nft is not installed (Debian: nftables)");
        return false;
    }
    char script[512];
    /* Declaring the table first makes the delete succeed when it is absent. */
    snprintf(script, sizeof script, "table inet %s\ndelete table inet %s\n", TABLE, TABLE);
    if (!run_nft(script, err, err_size)) return false;
    if (percent <= 0) return true;
    snprintf(script, sizeof script,
             "table inet %s {\n"
             "    chain output {\n"
             "        type filter hook output priority 0; policy accept;\n"
             "        meta l4proto udp numgen random mod 100 < %d counter drop\n"
             "    }\n"
             "}\n",
             TABLE, percent > 99 ? 99 : percent);
    return run_nft(script, err, err_size);
}
