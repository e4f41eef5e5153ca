#!/usr/bin/env bash
# daemon.concurrency, run inside netns-run: starts its own meshtopod with 2
# workers, lets meshtopod_concurrency_client run 8 querying processes against
# 3 small meshes while a large mesh is built, then stops that daemon by its
# PID (SIGTERM, SIGKILL after 10 s) and expects a clean exit.
# usage: netns_concurrency.sh MESHTOPOD CLIENT
# Exit status: the client's (77 = skipped), or 1 when the daemon did not stop cleanly.
set -uo pipefail
meshtopod=$1 client=$2
. "$(dirname "$0")/../../netns/stop_pid.sh"
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
# Both ends ask for a 4 MiB UDP receive buffer (see netns_corpus.sh): the big
# mesh is one message of several MiB, and every client's socket sees it too.
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
log=$(mktemp)
trap 'rm -f "$log"' EXIT

"$meshtopod" --lcm-url "$LCM_DEFAULT_URL" --heartbeat-ms 100 --workers 2 2>"$log" &
daemon_pid=$!

timeout --kill-after=5 200 "$client"
rc=$?
[ "$rc" -eq 124 ] && echo "meshtopod_concurrency_client timed out after 200 s" >&2

mt_stop_pid "$daemon_pid" TERM meshtopod
daemon_rc=$?
grep ' built ' "$log" | sed 's/^/meshtopod: /'
if [ "$rc" -ne 0 ] && [ "$rc" -ne 77 ]; then
    echo "daemon log:" >&2
    cat "$log" >&2
    exit "$rc"
fi
if [ "$daemon_rc" -ne 0 ] || ! grep -q ' info stop ' "$log"; then
    cat "$log" >&2
    echo "meshtopod exited with $daemon_rc after SIGTERM, or did not log its stop" >&2
    exit 1
fi
exit "$rc"
