#!/usr/bin/env bash
# Measures meshtopod's first build against its later ones, with and without
# --prepare-faces (docs/performance/first-build.md): for each round, a fresh
# daemon without the option and a fresh daemon with --prepare-faces N each
# get FILE three times from `meshtopo send`; the build times come from the
# daemon's "built" log lines (build_us). Prints one line per daemon, then the
# medians of the first and of the later builds.
# Run it inside tests/netns/netns-run (LCM traffic stays in that namespace):
#   bash tests/netns/netns-run bash tools/bench/first_build.sh \
#       build-rel/daemon/meshtopod build-rel/tools/meshtopo FILE [--rounds N] [--prepare N]
# --prepare defaults to the number of faces of FILE. Processes are stopped by
# their PIDs only.
set -uo pipefail
if [ $# -lt 3 ]; then
    sed -n '2,/^# their PIDs/p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
fi
meshtopod=$(readlink -f "$1") meshtopo=$(readlink -f "$2") file=$3
shift 3
rounds=5 prepare=
while [ $# -gt 0 ]; do
    case $1 in
        --rounds) rounds=$2; shift 2 ;;
        --prepare) prepare=$2; shift 2 ;;
        *) echo "first_build.sh: unknown option $1" >&2; exit 2 ;;
    esac
done
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through tests/netns/netns-run" >&2; exit 2; }
if [ -z "$prepare" ]; then
    prepare=$("$meshtopo" inspect "$file" --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["F"])') || exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export MESHTOPO_LCM_URL="udpm://239.255.76.67:7667?ttl=0"

# One daemon: starts it (with extra options), sends FILE three times, stops it
# by its PID and prints the three build times in ms.
run_daemon() {
    local log=$work/daemon.log
    "$meshtopod" --lcm-url "$MESHTOPO_LCM_URL" --max-faces 64000000 --max-indices 256M \
        --workers 1 "$@" 2>"$log" &
    local pid=$!
    for _ in $(seq 100); do
        grep -q ' info start ' "$log" 2>/dev/null && break
        sleep 0.05
    done
    for k in 1 2 3; do
        "$meshtopo" send "$file" --id first --quiet >/dev/null || { kill -TERM "$pid"; wait "$pid"; cat "$log" >&2; return 1; }
    done
    kill -TERM "$pid"
    wait "$pid"
    grep ' built ' "$log" | sed -n 's/.*build_us=\([0-9]*\).*/\1/p' |
        awk '{printf "%s%.1f", (NR > 1 ? " " : ""), $1 / 1000} END {print ""}'
}

median() { sort -n | awk '{v[NR] = $1} END {print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

echo "file: $file, --prepare-faces $prepare, $rounds rounds"
: >"$work/plain" && : >"$work/prepared"
for r in $(seq "$rounds"); do
    plain=$(run_daemon) || exit 1
    prepared=$(run_daemon --prepare-faces "$prepare") || exit 1
    echo "round $r: plain $plain ms; prepared $prepared ms"
    echo "$plain" >>"$work/plain"
    echo "$prepared" >>"$work/prepared"
done
for kind in plain prepared; do
    first=$(awk '{print $1}' "$work/$kind" | median)
    later=$(awk '{print $2; print $3}' "$work/$kind" | median)
    echo "$kind: first build median $first ms, later builds median $later ms"
done
