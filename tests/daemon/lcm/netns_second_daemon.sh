#!/usr/bin/env bash
# daemon.second_daemon, run inside netns-run: a second meshtopod started on
# the prefix where one already runs refuses to serve (exit 1, an error naming
# the running one's pid and instance) and the first keeps answering; on
# another prefix a second daemon runs beside it; two started at the same
# moment on one prefix both run (a heartbeat can be forged, so none stops)
# and each logs the other.
# usage: netns_second_daemon.sh MESHTOPOD MESHTOPO
set -uo pipefail
meshtopod=$1 meshtopo=$2
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
source "$(dirname "$0")/../../netns/stop_pid.sh"
dir=$(mktemp -d)
first_pid="" other_pid="" twin_a="" twin_b=""
cleanup() {
    for pid in $first_pid $other_pid $twin_a $twin_b; do
        mt_stop_pid "$pid" TERM meshtopod >/dev/null 2>&1
    done
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
"$meshtopo" watch --json --count 1 --timeout-ms 5000 >"$dir/first.jsonl"
grep -q '"name": *"first"' "$dir/first.jsonl" || fail "the first daemon no longer beats"

"$meshtopod" --heartbeat-ms 100 --name other --prefix OTHER_ 2>"$dir/other.log" &
other_pid=$!
"$meshtopo" watch --prefix OTHER_ --count 1 --timeout-ms 10000 >/dev/null ||
    fail "a daemon on another prefix never beat"
kill -0 "$first_pid" || fail "the first daemon died beside the other prefix"
echo "a daemon on another prefix runs beside it"

"$meshtopod" --heartbeat-ms 100 --name twin-a --prefix TWIN_ 2>"$dir/twin-a.log" &
twin_a=$!
"$meshtopod" --heartbeat-ms 100 --name twin-b --prefix TWIN_ 2>"$dir/twin-b.log" &
twin_b=$!
sleep 1.5
# Whether the second one's listening caught the first one's first heartbeat
# is a race: either it refused to start, naming the other, or both run and
# each names the other. Never both silent.
if kill -0 "$twin_a" 2>/dev/null && kill -0 "$twin_b" 2>/dev/null; then
    grep -q "another meshtopod 'twin-b' (instance .*:$twin_b:[0-9]*, pid $twin_b) beats on this prefix" \
        "$dir/twin-a.log" || fail "twin-a does not name twin-b"
    grep -q "another meshtopod 'twin-a' (instance .*:$twin_a:[0-9]*, pid $twin_a) beats on this prefix" \
        "$dir/twin-b.log" || fail "twin-b does not name twin-a"
    "$meshtopo" watch --prefix TWIN_ --json --count 4 --timeout-ms 5000 >"$dir/twins.jsonl"
    grep -q 'another meshtopod' "$dir/twins.jsonl" || fail "the heartbeat's last_error does not say so"
    echo "two daemons started together both run and each names the other"
else
    for pair in "twin-a $twin_a twin-b $twin_b" "twin-b $twin_b twin-a $twin_a"; do
        set -- $pair
        if ! kill -0 "$2" 2>/dev/null; then
            wait "$2"
            [ $? -eq 1 ] || fail "$1 stopped with another status than 1"
            grep -q "another meshtopod serves prefix TWIN_: '$3' (instance .*:$4:" "$dir/$1.log" ||
                fail "$1 stopped without naming $3"
            kill -0 "$4" || fail "both daemons started together stopped"
            echo "of two daemons started together, $1 saw $3's heartbeat and did not start"
            [ "$1" = twin-a ] && twin_a="" || twin_b=""
        fi
    done
fi
