#!/usr/bin/env bash
# daemon.corpus.NAME, run inside netns-run: starts its own meshtopod, lets
# meshtopod_corpus_client check the corpus mesh NAME over LCM against
# NAME.expected.json, then stops that daemon by its PID (SIGTERM, SIGKILL
# after 10 s) and expects a clean exit. Every step has a time limit.
# usage: netns_corpus.sh MESHTOPOD CLIENT NAME
# Exit status: the client's (77 = skipped: the mesh does not fit one LCM
# message or the UDP receive buffer), or 1 when the daemon did not stop cleanly.
set -uo pipefail
meshtopod=$1 client=$2 name=$3
. "$(dirname "$0")/../../netns/stop_pid.sh"
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
# LCM's udpm keeps the kernel's default UDP receive buffer (rmem_default,
# often 208 KiB) unless the URL asks for more, and a submission larger than
# the buffer loses fragments. Both ends ask for 4 MiB (the kernel caps it at
# net.core.rmem_max; the client skips meshes that cannot fit).
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
log=$(mktemp)
trap 'rm -f "$log"' EXIT

"$meshtopod" --lcm-url "$LCM_DEFAULT_URL" --heartbeat-ms 100 --workers 2 2>"$log" &
daemon_pid=$!

timeout --kill-after=5 100 "$client" "$name"
rc=$?
[ "$rc" -eq 124 ] && echo "meshtopod_corpus_client timed out after 100 s" >&2

mt_stop_pid "$daemon_pid" TERM meshtopod
daemon_rc=$?
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
