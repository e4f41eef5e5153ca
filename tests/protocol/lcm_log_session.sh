#!/usr/bin/env bash
# protocol.lcm_log_decodes, run inside netns-run: records a whole meshtopo
# session with lcm-logger (small meshes as mesh_t, a 200k-triangle grid in
# chunks, one-rings and boundary loops, a one-ring answer of megabytes in
# reply_part_t pieces) and has LogDecode decode every event of the log with
# its channel's one type. Processes are stopped by their PIDs only.
# usage: lcm_log_session.sh MESHTOPOD MESHTOPO JAVA CLASSPATH WORKDIR
#   corpus: $MESHTOPO_CORPUS (ctest sets the build's), else the repository's tests/corpus
# Exit status: LogDecode's (0 every event decoded and every channel seen), 1 a
# step failed, 2 usage, 77 skipped (lcm-logger missing: Debian liblcm-bin).
set -uo pipefail
if [ $# -ne 5 ]; then
    echo "usage: lcm_log_session.sh MESHTOPOD MESHTOPO JAVA CLASSPATH WORKDIR" >&2
    exit 2
fi
meshtopod=$1 meshtopo=$2 java=$3 classpath=$4 work=$5
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
corpus=${MESHTOPO_CORPUS:-$here/../corpus}
for f in cgal_tetrahedron.off npm_bunny.off vcg_nonmanifold.off; do
    [ -r "$corpus/$f" ] || { echo "no corpus file $corpus/$f (set MESHTOPO_CORPUS)" >&2; exit 2; }
done
if ! command -v lcm-logger >/dev/null; then
    echo "skipped: lcm-logger not found (Debian liblcm-bin)"
    exit 77
fi

. "$here/lcm_log_env.sh"
prefix=MESHTOPO_

# Runs the CLI with a time limit, its output to the session's files.
cli() {
    local out=$1 rc
    shift
    echo "\$ meshtopo $*"
    timeout --kill-after=5 60 "$meshtopo" "$@" >"$work/$out" 2>&1
    rc=$?
    [ "$rc" -eq 0 ] || { tail -20 "$work/$out" >&2; fail "meshtopo $* exited with $rc"; }
}

write_grid_off "$work/grid.off"

# Every channel but LCM_SELF_TEST, which each LCM process's udpm provider
# publishes for itself when it starts (LCM's, not meshtopo's).
lcm-logger --lcm-url "$url" --invert-channels --channel LCM_SELF_TEST --force --quiet "$log" \
    >"$logger_log" 2>&1 &
logger_pid=$!
"$meshtopod" --lcm-url "$url" --prefix "$prefix" --heartbeat-ms 200 --workers 2 2>"$daemon_log" &
daemon_pid=$!

cli watch.txt watch --count 1 --timeout-ms 10000
for _ in $(seq 100); do
    [ -s "$log" ] && break
    sleep 0.1
done
[ -s "$log" ] || fail "lcm-logger wrote nothing to $log (its output: $(cat "$logger_log"))"

cli send-tet.txt send "$corpus/cgal_tetrahedron.off" --id tet --quiet
cli send-bunny.txt send "$corpus/npm_bunny.off" --id bunny --quiet
cli send-nonmanifold.txt send "$corpus/vcg_nonmanifold.off" --id nonmanifold --quiet
cli send-grid.txt send "$work/grid.off" --id grid --quiet
cli ring-tet.txt query tet ring 0-3
cli ring-bunny.txt query bunny ring 0,78
cli loops-bunny.txt query bunny boundary-loops
cli loops-nonmanifold.txt query nonmanifold boundary-loops
cli loops-grid.txt query grid boundary-loops
# Every vertex's one-ring: megabytes, far over 60,000 bytes, so the answer
# comes as reply_part_t pieces and the client pulls the rest (reply_pull_t).
cli ring-grid.txt query grid ring 0-100488
lines=$(wc -l <"$work/ring-grid.txt")
echo "the grid's one-rings: $lines lines, $(wc -c <"$work/ring-grid.txt") bytes printed"
[ "$lines" -ge 100489 ] || fail "the grid's one-rings came back incomplete ($lines lines)"

mt_stop_pid "$daemon_pid" TERM meshtopod
rc=$?
daemon_pid=
[ "$rc" -eq 0 ] || fail "meshtopod exited with $rc after SIGTERM"
sleep 0.5  # lcm-logger flushes every 100 ms
mt_stop_pid "$logger_pid" INT lcm-logger
rc=$?
logger_pid=
[ "$rc" -eq 0 ] || fail "lcm-logger exited with $rc after SIGINT ($(cat "$logger_log"))"
echo "recorded $(wc -c <"$log") bytes in $log"

"$java" -cp "$classpath" LogDecode --prefix "$prefix" "$log"
