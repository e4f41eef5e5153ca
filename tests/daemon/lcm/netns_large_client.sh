#!/usr/bin/env bash
# daemon.netns_chunked_* and daemon.netns_parts_*, run inside netns-run (with
# --loss for the lossy variants): starts meshtopod, runs CLIENT NAME against
# it (meshtopod_chunked_client submits a 2M-triangle mesh in chunks and
# compares the ack with the in-process build; meshtopod_parts_client asks for
# large answers and compares them with the core), prints the daemon's log
# lines about transfers, parts and builds, and stops the daemon by its PID.
# usage: netns_large_client.sh MESHTOPOD CLIENT NAME
set -uo pipefail
meshtopod=$1 client=$2 name=$3
. "$(dirname "$0")/../../netns/stop_pid.sh"
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
log=$(mktemp)
trap 'rm -f "$log"' EXIT

"$meshtopod" --heartbeat-ms 100 --workers 2 2>"$log" &
daemon_pid=$!

timeout --kill-after=5 100 "$client" "$name"
rc=$?
[ "$rc" -eq 124 ] && echo "$name: client timed out after 100 s" >&2

mt_stop_pid "$daemon_pid" TERM meshtopod
daemon_rc=$?
grep -E ' (transfer_[a-z]+|built|chunk_error|reply_pull) ' "$log" | sed 's/^/meshtopod: /'
if [ "$rc" -ne 0 ]; then
    echo "daemon log:" >&2
    tail -50 "$log" >&2
    exit "$rc"
fi
[ "$daemon_rc" -eq 0 ] || { echo "meshtopod exited with $daemon_rc" >&2; exit 1; }
