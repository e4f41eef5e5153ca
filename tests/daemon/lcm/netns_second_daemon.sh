#!/usr/bin/env bash
# daemon.second_daemon, run inside netns-run: a second meshtopod started on
# the prefix where one already runs refuses to serve (exit 1, an error naming
# the running one's pid and instance) and the first keeps answering; on
# another prefix a second daemon runs beside it.
# usage: netns_second_daemon.sh MESHTOPOD MESHTOPO
set -uo pipefail
meshtopod=$1 meshtopo=$2
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
source "$(dirname "$0")/../../netns/stop_pid.sh"
dir=$(mktemp -d)
first_pid="" other_pid=""
cleanup() {
    [ -n "$first_pid" ] && mt_stop_pid "$first_pid" TERM meshtopod >/dev/null 2>&1
    [ -n "$other_pid" ] && mt_stop_pid "$other_pid" TERM meshtopod >/dev/null 2>&1
    rm -rf "$dir"
}
trap cleanup EXIT
fail() {
    echo "FAIL: $*" >&2
    for f in "$dir"/*.log; do echo "== $f" >&2; cat "$f" >&2; done
    exit 1
}

"$meshtopod" --heartbeat-ms 100 --name first 2>"$dir/first.log" &
first_pid=$!
"$meshtopo" watch --count 1 --timeout-ms 10000 >/dev/null || fail "the first daemon never beat"

start=$(date +%s%N)
"$meshtopod" --heartbeat-ms 100 --name second 2>"$dir/second.log"
rc=$?
took_ms=$((($(date +%s%N) - start) / 1000000))
[ "$rc" -eq 1 ] || fail "the second daemon on the prefix exited with $rc, expected 1"
grep -q "another meshtopod serves prefix MESHTOPO_: 'first' (instance .*:$first_pid:[0-9]*, pid $first_pid)" \
    "$dir/second.log" || fail "the second daemon's error does not name the first"
grep -q " info start " "$dir/second.log" && fail "the second daemon started serving"
echo "second daemon refused in $took_ms ms: $(grep second_daemon "$dir/second.log")"
kill -0 "$first_pid" || fail "the first daemon died"
"$meshtopo" watch --json --count 1 --timeout-ms 5000 | grep -q '"name": *"first"' ||
    fail "the first daemon no longer beats"

"$meshtopod" --heartbeat-ms 100 --name other --prefix OTHER_ 2>"$dir/other.log" &
other_pid=$!
"$meshtopo" watch --prefix OTHER_ --count 1 --timeout-ms 10000 >/dev/null ||
    fail "a daemon on another prefix never beat"
kill -0 "$first_pid" || fail "the first daemon died beside the other prefix"
echo "a daemon on another prefix runs beside it"
