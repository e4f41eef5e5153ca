#!/usr/bin/env bash
# daemon.netns_roundtrip, run inside netns-run: starts meshtopod, lets the
# test client submit a mesh and check one-rings over LCM, then sends SIGTERM
# to the daemon it started and expects a clean exit (status 0, "stop" logged).
# usage: netns_roundtrip.sh MESHTOPOD CLIENT MESH_FILE
set -uo pipefail
meshtopod=$1 client=$2 mesh=$3
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
log=$(mktemp)
trap 'rm -f "$log"' EXIT

"$meshtopod" --heartbeat-ms 100 --workers 2 2>"$log" &
daemon_pid=$!

if ! "$client" "$mesh"; then
    echo "client failed; daemon log:" >&2
    cat "$log" >&2
    kill -TERM "$daemon_pid" 2>/dev/null
    wait "$daemon_pid"
    exit 1
fi
kill -TERM "$daemon_pid"
wait "$daemon_pid"
rc=$?
cat "$log"
if [ "$rc" -ne 0 ]; then
    echo "meshtopod exited with $rc after SIGTERM" >&2
    exit 1
fi
grep -q ' info stop ' "$log" || { echo "meshtopod did not log its stop" >&2; exit 1; }
echo "meshtopod stopped cleanly"
