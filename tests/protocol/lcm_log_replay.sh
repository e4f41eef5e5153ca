#!/usr/bin/env bash
# protocol.lcm_log_replays, run inside netns-run: the README's record and
# replay with LCM's own tools. lcm-logger records, with the documented
# receive buffer (recv_buf_size=4194304 in the URL), a session in which
# meshtopod takes a 200k-triangle grid in chunks from `meshtopo send`; the
# daemon stops, a fresh meshtopod starts on the same prefix, lcm-logplayer
# replays the log's submissions (channels MESHTOPO_SUBMIT.*) and the fresh
# daemon must hold the same mesh: vertex and face counts and content hash of
# the original acknowledgement (`meshtopo list --json`). The logger runs
# under `chrt -f 10` when allowed, as the README says; a recording that
# still lacks chunks (lost inside lcm-logger, see below) is made again, at
# most 3 times. Processes are stopped by their PIDs only.
# usage: lcm_log_replay.sh MESHTOPOD MESHTOPO WORKDIR
# Exit status: 0 the replay rebuilt the mesh, 1 a step failed, 2 usage, 77
# skipped (lcm-logger or lcm-logplayer missing: Debian liblcm-bin; no python3).
set -uo pipefail
if [ $# -ne 3 ]; then
    echo "usage: lcm_log_replay.sh MESHTOPOD MESHTOPO WORKDIR" >&2
    exit 2
fi
meshtopod=$1 meshtopo=$2 work=$3
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
for tool in lcm-logger lcm-logplayer python3; do
    if ! command -v "$tool" >/dev/null; then
        echo "skipped: $tool not found (Debian liblcm-bin, python3)"
        exit 77
    fi
done

. "$here/lcm_log_env.sh"

start_daemon() {
    "$meshtopod" --lcm-url "$url" --heartbeat-ms 200 --workers 2 2>>"$daemon_log" &
    daemon_pid=$!
    timeout 20 "$meshtopo" watch --count 1 --timeout-ms 10000 >/dev/null ||
        fail "meshtopod (pid $daemon_pid) gave no heartbeat"
}
stop_daemon() {
    mt_stop_pid "$daemon_pid" TERM meshtopod
    local rc=$?
    daemon_pid=
    [ "$rc" -eq 0 ] || fail "meshtopod exited with $rc after SIGTERM"
}

# "num_verts num_faces content_hash" of mesh grid, as the daemon lists it.
listed_grid() {
    timeout 30 "$meshtopo" list --json --timeout-ms 2000 2>/dev/null | python3 -c '
import json, sys
for m in json.load(sys.stdin)["meshes"]:
    if m["mesh_id"] == "grid":
        print(m["num_verts"], m["num_faces"], m["content_hash"])'
}

write_grid_off "$work/grid.off"

# lcm-logger 1.3 keeps at most 30 received messages waiting for its main
# thread and drops the rest inside LCM, whatever the receive buffer: when the
# machine is busy it can miss a few chunks of a burst. Real-time priority
# (chrt, as the README suggests) keeps it up; without the right to use it the
# logger runs as it is. A recording that still misses chunks is made again,
# at most 3 times: what is judged is that a complete recording replays.
rt=()
chrt -f 10 true 2>/dev/null && rt=(chrt -f 10)

# 1. Record: lcm-logger with the URL above, every channel but LCM's own
#    LCM_SELF_TEST; meshtopod builds the grid meshtopo sends.
record() {
    echo "\$ ${rt[*]}${rt[*]:+ }lcm-logger --lcm-url '$url' --invert-channels --channel LCM_SELF_TEST session.lcmlog &"
    "${rt[@]}" lcm-logger --lcm-url "$url" --invert-channels --channel LCM_SELF_TEST --force \
        --quiet "$log" >"$logger_log" 2>&1 &
    logger_pid=$!
    start_daemon
    for _ in $(seq 100); do
        [ -s "$log" ] && break
        sleep 0.1
    done
    [ -s "$log" ] || fail "lcm-logger wrote nothing to $log ($(cat "$logger_log"))"
    echo "\$ meshtopo send grid.off --id grid"
    timeout 120 "$meshtopo" send "$work/grid.off" --id grid --quiet --json >"$work/send.json" 2>&1 ||
        fail "meshtopo send exited with $? ($(tail -5 "$work/send.json"))"
    original=$(listed_grid)
    [ -n "$original" ] || fail "the recording daemon does not list the grid"
    echo "recording daemon holds grid: $original (vertices faces content_hash)"
    ack_hash=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["content_hash"])' \
        "$work/send.json")
    [ "${original##* }" = "$ack_hash" ] || fail "list says ${original##* }, the ack said $ack_hash"
    stop_daemon
    sleep 0.5  # lcm-logger flushes every 100 ms
    mt_stop_pid "$logger_pid" INT lcm-logger
    local rc=$?
    logger_pid=
    [ "$rc" -eq 0 ] || fail "lcm-logger exited with $rc after SIGINT ($(cat "$logger_log"))"
    # 2. What the log holds: every byte of the grid's content in its chunks.
    python3 "$here/lcm_log_chunks.py" "$log" | tee "$work/chunks.txt"
    grep -q "transfer grid .* complete$" "$work/chunks.txt"
}

original=
for attempt in 1 2 3; do
    record && break
    [ "$attempt" -lt 3 ] ||
        fail "lcm-logger missed chunks of the grid in 3 recordings: a replay cannot rebuild it"
    echo "lcm-logger missed chunks of the grid (inside LCM); recording again"
done

# 3. Replay into a fresh meshtopod: only the submissions (the rest of the
#    log, the recorded daemon's heartbeats, acks and answers, would reach
#    listeners as if that daemon were still there).
start_daemon
echo "\$ lcm-logplayer --regexp 'MESHTOPO_SUBMIT.*' --speed 0.25 --lcm-url '$url' session.lcmlog"
timeout 60 lcm-logplayer --regexp 'MESHTOPO_SUBMIT.*' --speed 0.25 --lcm-url "$url" "$log" \
    >"$work/lcm-logplayer.log" 2>&1 || fail "lcm-logplayer exited with $?"
replayed=
for _ in $(seq 20); do
    replayed=$(listed_grid)
    [ -n "$replayed" ] && break
    sleep 0.5
done
echo "fresh daemon holds grid: ${replayed:-nothing}"
[ "$replayed" = "$original" ] ||
    fail "the replay built '${replayed:-nothing}', the recorded daemon '$original'"
stop_daemon
echo "ok: lcm-logplayer rebuilt grid ($original) in a fresh meshtopod"
