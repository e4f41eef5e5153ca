#!/usr/bin/env bash
# Measures how far LCM's own recorder and player carry a meshtopo session
# (docs/performance/lcm-logging.md): for each receive buffer asked of
# lcm-logger, meshtopod takes grids of increasing size from `meshtopo send`
# (chunked transfers) while lcm-logger records; then, for each lcm-logplayer
# speed, a fresh meshtopod (a new process on the same prefix) gets the log's
# submissions replayed and the script checks which meshes it built with the
# original content hash. It prints one line per (buffer, size, speed) with the
# datagrams sent and dropped, the chunks the log holds and the outcome, and
# finally replays the archive of the recording daemon with `meshtopo replay`.
# Run it inside tests/netns/netns-run (LCM traffic stays in that namespace):
#   bash tests/netns/netns-run bash tools/bench/lcm_record_replay.sh \
#       build/daemon/meshtopod build/tools/meshtopo /tmp/lcm-rr [options]
# options: --sizes "200000 1000000 2000000"  grid triangles
#          --bufs "default 4194304 16777216 max"  lcm-logger's recv_buf_size
#                                  (default: none in the URL; max: net.core.rmem_max)
#          --speeds "1 0"          lcm-logplayer --speed values (0: as fast as it can)
#          --repeat N              recordings per buffer (default 1)
#          --logger-prefix "CMD"   run lcm-logger under CMD (e.g. "nice -n -10")
# Processes are stopped by their PIDs only; no sysctl is changed.
set -uo pipefail
if [ $# -lt 3 ]; then
    sed -n '2,/^# Processes/p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
fi
meshtopod=$(readlink -f "$1") meshtopo=$(readlink -f "$2") work=$3
shift 3
sizes="200000 1000000 2000000" bufs="default 4194304 16777216 max" speeds="1 0" repeat=1
logger_prefix=
while [ $# -gt 0 ]; do
    case $1 in
    --sizes) sizes=$2; shift 2 ;;
    --bufs) bufs=$2; shift 2 ;;
    --speeds) speeds=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --logger-prefix) logger_prefix=$2; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
    esac
done
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through tests/netns/netns-run" >&2; exit 2; }
if ! command -v lcm-logger >/dev/null || ! command -v lcm-logplayer >/dev/null; then
    echo "lcm-logger / lcm-logplayer not found (Debian liblcm-bin)" >&2
    exit 77
fi
here=$(cd "$(dirname "$0")" && pwd)
chunks_py=$here/../../tests/protocol/lcm_log_chunks.py
. "$here/../../tests/netns/stop_pid.sh"

rmem_max=$(cat /proc/sys/net/core/rmem_max)
group="udpm://239.255.76.67:7667?ttl=0"
# meshtopod and meshtopo use the receive buffer the README recommends
# throughout; only lcm-logger's varies.
url="$group&recv_buf_size=4194304"
export MESHTOPO_LCM_URL=$url LCM_DEFAULT_URL=$url
unset MESHTOPO_PREFIX
mkdir -p "$work" || exit 1
echo "# $(date -u +%FT%TZ) $(uname -r), $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# net.core.rmem_max $rmem_max, rmem_default $(cat /proc/sys/net/core/rmem_default)"

daemon_pid='' logger_pid=''
cleanup() {
    [ -n "$daemon_pid" ] && mt_stop_pid "$daemon_pid" TERM meshtopod
    [ -n "$logger_pid" ] && mt_stop_pid "$logger_pid" INT lcm-logger
}
trap cleanup EXIT

# A grid of about T triangles: an n x n lattice of vertices, each square cut
# in two (2 (n-1)^2 triangles, one boundary loop), written once as OFF.
grid() {
    local t=$1 f=$work/grid-$1.off n
    n=$(awk -v t="$t" 'BEGIN { printf "%d", sqrt(t / 2) + 1.5 }')
    [ -s "$f" ] || awk -v n="$n" 'BEGIN {
        print "OFF"; print n * n, 2 * (n - 1) * (n - 1), 0
        for (j = 0; j < n; j++) for (i = 0; i < n; i++) printf "%d %d 0\n", i, j
        for (j = 0; j < n - 1; j++) for (i = 0; i < n - 1; i++) {
            a = j * n + i
            printf "3 %d %d %d\n3 %d %d %d\n", a, a + 1, a + n + 1, a, a + n + 1, a + n
        }
    }' >"$f"
    echo "$f"
}

# "rb drops" of the UDP sockets of process $1 (ss: receive buffer granted,
# datagrams the kernel dropped at them).
sock_stats() {
    ss -u -a -m -n -p 2>/dev/null | awk -v pid="pid=$1," '
        index($0, pid) { want = 1; next }
        want && /skmem/ { match($0, /rb[0-9]+/); r = substr($0, RSTART + 2, RLENGTH - 2) + 0
                          if (r > rb) rb = r
                          match($0, /d[0-9]+\)/); d += substr($0, RSTART + 1, RLENGTH - 2); want = 0 }
        END { print rb + 0, d + 0 }'
}
# Udp OutDatagrams and RcvbufErrors of this namespace.
udp_counts() {
    awk '/^Udp:/ { n++; if (n == 2) print $5, $6 }' /proc/net/snmp
}

start_daemon() {
    "$meshtopod" --lcm-url "$url" --heartbeat-ms 200 --workers 2 "$@" 2>>"$work/meshtopod.log" &
    daemon_pid=$!
    timeout 20 "$meshtopo" watch --count 1 --timeout-ms 15000 >/dev/null ||
        { echo "meshtopod gave no heartbeat" >&2; exit 1; }
}
stop_daemon() {
    mt_stop_pid "$daemon_pid" TERM meshtopod >/dev/null
    daemon_pid=
}

# id vertices faces content_hash of every mesh the daemon holds.
held() {
    timeout 60 "$meshtopo" list --json --timeout-ms 3000 2>/dev/null | python3 -c '
import json, sys
for m in json.load(sys.stdin)["meshes"]:
    print(m["mesh_id"], m["num_verts"], m["num_faces"], m["content_hash"])'
}

for t in $sizes; do grid "$t" >/dev/null; done
# sent_dg: UDP datagrams sent in the namespace during the send (chunks, the
# daemon's answers, heartbeats); logged: events the log holds of that time;
# kdrop: of them dropped at lcm-logger's socket (kernel, receive buffer full);
# the rest of sent_dg - logged was dropped inside lcm-logger's LCM (its
# subscription queue holds 30 messages). chunks/cover: mesh_chunk_t events
# of the transfer in the log and the share of the content they cover.
# replay: built (same counts and content hash) or MISSING, the fresh daemon's
# kernel drops during the replay, lcm-logplayer's run time.
printf '%-9s %-8s %3s %9s %6s %7s %7s %5s %6s %6s %s\n' buffer granted run triangles \
    send_s sent_dg logged kdrop chunks cover replay
for buf in $bufs; do
    case $buf in
    default) lurl=$group ;;
    max) lurl="$group&recv_buf_size=$rmem_max" ;;
    *) lurl="$group&recv_buf_size=$buf" ;;
    esac
    for run in $(seq "$repeat"); do
        tag=$buf-$run log=$work/session-$tag.lcmlog archive=$work/archive-$tag
        rm -rf "$archive" "$log"
        mkdir -p "$archive"
        $logger_prefix lcm-logger --lcm-url "$lurl" --invert-channels --channel LCM_SELF_TEST --force --quiet \
            "$log" >"$work/logger-$tag.txt" 2>&1 &
        logger_pid=$!
        start_daemon --archive "$archive"
        for _ in $(seq 100); do [ -s "$log" ] && break; sleep 0.1; done
        read -r granted _ <<<"$(sock_stats "$logger_pid")"
        declare -A line=() window=() kdrop=()
        for t in $sizes; do
            read -r _ d0 <<<"$(sock_stats "$logger_pid")"
            read -r out0 _ <<<"$(udp_counts)"
            s0=$(date +%s%6N)
            timeout 300 "$meshtopo" send "$(grid "$t")" --id "grid$t" --quiet --json \
                >"$work/send-$tag-$t.json" 2>&1 || echo "send of grid$t failed" >&2
            sleep 0.3
            s1=$(date +%s%6N)
            read -r _ d1 <<<"$(sock_stats "$logger_pid")"
            read -r out1 _ <<<"$(udp_counts)"
            window[$t]="$s0 $s1"
            line[$t]=$(printf '%-9s %-8s %3s %9s %6.2f %7s' "$buf" "$granted" "$run" "$t" \
                "$(echo "($s1 - $s0) / 1000000 - 0.3" | bc -l)" "$((out1 - out0))")
            kdrop[$t]=$((d1 - d0))
        done
        held >"$work/held-$tag.txt"
        stop_daemon
        sleep 0.5
        mt_stop_pid "$logger_pid" INT lcm-logger >/dev/null
        logger_pid=
        python3 "$chunks_py" --json "$log" >"$work/chunks-$tag.json"
        grep -h "Dropped" "$work/logger-$tag.txt" >&2
        for speed in $speeds; do
            start_daemon
            read -r _ e0 <<<"$(udp_counts)"
            p0=$(date +%s.%N)
            timeout 600 lcm-logplayer --speed "$speed" --regexp 'MESHTOPO_SUBMIT.*' \
                --lcm-url "$url" "$log" >/dev/null 2>"$work/player-$tag-$speed.txt"
            p1=$(date +%s.%N)
            # Builds finish after the last chunk; an incomplete transfer never does.
            expect=$(wc -l <"$work/held-$tag.txt")
            for _ in $(seq 15); do
                held >"$work/replayed-$tag-$speed.txt"
                [ "$(wc -l <"$work/replayed-$tag-$speed.txt")" -ge "$expect" ] && break
                sleep 1
            done
            read -r _ e1 <<<"$(udp_counts)"
            stop_daemon
            for t in $sizes; do
                # shellcheck disable=SC2086
                logged=$(python3 "$chunks_py" --between ${window[$t]} "$log")
                read -r chunks cover <<<"$(python3 -c '
import json, sys
s = json.load(open(sys.argv[1]))
for t in s["transfers"]:
    if t["mesh_id"] == sys.argv[2]:
        print(t["data_events"], "%.1f%%" % (100.0 * t["covered_bytes"] / t["total_size"]))
        break
else:
    print(0, "0%")' "$work/chunks-$tag.json" "grid$t")"
                want=$(grep "^grid$t " "$work/held-$tag.txt")
                got=$(grep "^grid$t " "$work/replayed-$tag-$speed.txt")
                if [ -n "$want" ] && [ "$want" = "$got" ]; then outcome=built; else outcome=MISSING; fi
                printf '%s %7s %5s %6s %6s speed %s: %s (kdrop %s, player %.1f s)\n' "${line[$t]}" \
                    "$logged" "${kdrop[$t]}" "$chunks" "$cover" "$speed" "$outcome" "$((e1 - e0))" \
                    "$(echo "$p1 - $p0" | bc)"
            done
        done
    done
done

# What to use instead: the archive the recording daemon wrote, replayed by
# meshtopo replay into a fresh daemon (every submission acknowledged).
archives=("$work"/archive-*)
last=${archives[${#archives[@]} - 1]}
start_daemon
echo "# meshtopo replay $last --rate 0:"
timeout 600 "$meshtopo" replay "$last" --rate 0 --quiet
echo "# exit status $?"
held
stop_daemon
