/* Shared declarations of `meshtopo-bench transfer`: the end-to-end time of a
 * chunked submission to a real meshtopod (send -> built -> acked) at 0 % and
 * 5 % UDP loss, next to pushing the same bytes as raw single-datagram LCM
 * messages with the same acknowledgement window and no protocol. Runs in the
 * private network namespace of `meshtopo-bench rtt` (rtt.h), whose daemon
 * and namespace helpers it reuses. */
#ifndef MESHTOPO_BENCH_TRANSFER_H
#define MESHTOPO_BENCH_TRANSFER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Entry point: `meshtopo-bench transfer [options]` (argv[0] is "transfer").
 * Returns 0 when every measurement ran (missed targets included), 1 when one
 * failed, 2 on a usage error, 77 when no private network namespace can be
 * made here. */
int mt__bench_transfer_command(int argc, char **argv);

/* ---- transfer_raw.c ------------------------------------------------------ */

/* The raw baseline's receiver: a child process that takes datagrams on
 * TRANSFER_RAW and acknowledges every one that asks for it on
 * TRANSFER_RAW_ACK, with LCM alone. Forked while the caller has no thread. */
typedef struct mt__raw_acker {
    int pid;
} mt__raw_acker;

bool mt__raw_acker_start(mt__raw_acker *out, char *err, size_t err_size);
void mt__raw_acker_stop(mt__raw_acker *acker);

/* Pushes `total` bytes of `bytes` as messages of `chunk` bytes, `window` at
 * a time, the last of each window asking for an acknowledgement that must
 * come before the next window (a window without one is sent again after
 * 50 ms). Writes the seconds from the first send to the last
 * acknowledgement to *out_seconds. */
bool mt__raw_push(const uint8_t *bytes, uint64_t total, uint32_t chunk, uint32_t window,
                  double *out_seconds, char *err, size_t err_size);

/* ---- transfer_loss.c ----------------------------------------------------- */

/* Drops `percent` of the UDP packets sent in this (private) network
 * namespace with an nftables rule (numgen random, as tests/netns/netns-run);
 * 0 removes the rule. false when `nft` is missing or refuses (err says). */
bool mt__transfer_set_loss(int percent, char *err, size_t err_size);

#endif
