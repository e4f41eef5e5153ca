#!/usr/bin/env bash
# daemon.netns_parts_*, run inside netns-run (with --loss for the lossy
# variant): starts meshtopod, lets meshtopod_parts_client submit a 2M-triangle
# grid with holes and compare its large answers (reply_part_t) with the core,
# prints the daemon's log lines about them, and stops the daemon by its PID.
# usage: netns_parts.sh MESHTOPOD CLIENT NAME
set -uo pipefail
meshtopod=$1 client=$2 name=$3
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
log=$(mktemp)
trap 'rm -f "$log"' EXIT

"$meshtopod" --heartbeat-ms 100 --workers 2 2>"$log" &
daemon_pid=$!

timeout --kill-after=5 100 "$client" "$name"
rc=$?
[ "$rc" -eq 124 ] && echo "$name: client timed out after 100 s" >&2

kill -TERM "$daemon_pid" 2>/dev/null
for _ in $(seq 100); do
    kill -0 "$daemon_pid" 2>/dev/null || break
    sleep 0.1
done
kill -0 "$daemon_pid" 2>/dev/null && kill -KILL "$daemon_pid" 2>/dev/null
wait "$daemon_pid"
daemon_rc=$?
grep -E ' (built|reply_pull|chunk_error) ' "$log" | sed 's/^/meshtopod: /'
if [ "$rc" -ne 0 ]; then
    echo "daemon log:" >&2
    tail -50 "$log" >&2
    exit "$rc"
fi
[ "$daemon_rc" -eq 0 ] || { echo "meshtopod exited with $daemon_rc" >&2; exit 1; }
