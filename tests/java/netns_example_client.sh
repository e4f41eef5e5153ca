#!/usr/bin/env bash
# java.example_client, run inside netns-run: starts meshtopod, runs the Java example client
# (msgs/java/examples/ExampleClient.java, which waits for the daemon's first heartbeat itself)
# with --lose-part 1 so that it must pull a part, then stops the daemon it started, by its PID,
# and expects a clean exit.
# usage: netns_example_client.sh MESHTOPOD JAVA CLASSPATH
set -uo pipefail
meshtopod=$1 java=$2 classpath=$3
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
source "$(dirname "$0")/../netns/stop_pid.sh"
unset LCM_DEFAULT_URL
log=$(mktemp)
daemon_pid=""
cleanup() {
    [ -n "$daemon_pid" ] && mt_stop_pid "$daemon_pid" TERM meshtopod >/dev/null 2>&1
    rm -f "$log"
}
trap cleanup EXIT

"$meshtopod" --heartbeat-ms 100 --workers 2 2>"$log" &
daemon_pid=$!
start=$(date +%s%N)
if ! "$java" -cp "$classpath" ExampleClient --lose-part 1; then
    echo "ExampleClient failed; daemon log:" >&2
    tail -30 "$log" >&2
    exit 1
fi
echo "ExampleClient ran in $((($(date +%s%N) - start) / 1000000)) ms"
mt_stop_pid "$daemon_pid" TERM meshtopod
rc=$?
daemon_pid=""
if [ "$rc" -ne 0 ]; then
    echo "meshtopod exited with $rc after SIGTERM" >&2
    tail -30 "$log" >&2
    exit 1
fi
echo "meshtopod stopped cleanly"
