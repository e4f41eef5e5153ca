#!/usr/bin/env bash
# The network half of the meshtopo demo (scripts/demo.sh runs it inside a
# private network namespace through tests/netns/netns-run): starts meshtopod,
# waits for its first heartbeat, submits three corpus meshes with
# `meshtopo send`, queries one-rings and face neighbours, lists what the
# daemon holds and stops the daemon with SIGTERM; then starts a fresh daemon
# on the archive the first one wrote and queries a mesh it reloads from it.
#   scripts/demo-network.sh BUILD_DIR CORPUS_DIR
set -euo pipefail

build=$1
corpus=$2
meshtopo=$build/tools/meshtopo
meshtopod=$build/daemon/meshtopod
[ -x "$meshtopod" ] || { echo "demo: $meshtopod was not built" >&2; exit 1; }
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "demo: run me through tests/netns/netns-run" >&2; exit 1; }

# Meshes and answers larger than one datagram travel in acknowledged chunks;
# a larger UDP receive buffer than the kernel's default (about 200 KiB) lets
# a window of them arrive without drops (the kernel caps it at
# net.core.rmem_max).
export MESHTOPO_LCM_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
log=$(mktemp /tmp/meshtopod-demo.XXXXXX)
# The archive stays after the demo, in the build tree, to be opened with VTK
# or ParaView; each run starts it afresh.
archive=$build/demo-archive
rm -rf "$archive"
mkdir -p "$archive"
daemon_pid=

stop_daemon() {
    if [ -n "$daemon_pid" ]; then
        kill -TERM "$daemon_pid" 2>/dev/null || true
        wait "$daemon_pid" 2>/dev/null || true
        daemon_pid=
    fi
}
trap 'stop_daemon; rm -f "$log"' EXIT

run() {
    printf '\n$ meshtopo %s\n' "$*"
    (cd "$corpus" && "$meshtopo" "$@")
}

echo "== 5. The LCM service, in a private network namespace: meshtopod builds what"
echo "==    nodes submit and answers queries over LCM."
printf "\n$ meshtopod --lcm-url '%s' --archive %s &\n" "$MESHTOPO_LCM_URL" "$archive"
"$meshtopod" --lcm-url "$MESHTOPO_LCM_URL" --archive "$archive" 2>"$log" &
daemon_pid=$!

echo
echo "== Wait for the daemon's first heartbeat on MESHTOPO_STATUS."
run watch --count 1 --timeout-ms 10000

echo
echo "== Submit a clean mesh, one with holes and a non-manifold one; each ack carries the report."
run send npm_bunny.off --id bunny
run send cgal_elephant_with_holes.off --id elephant
run send vcg_nonmanifold.off --id nonmanifold

echo
echo "== Ask the daemon: one-rings (per fan), face neighbours (per side), boundary loops."
run query bunny ring 0 78
run query nonmanifold ring 7
run query nonmanifold face-neighbors 2
run query nonmanifold boundary-loops
run list

echo
echo "== Stop the daemon with SIGTERM; it finishes, says goodbye and exits 0."
kill -TERM "$daemon_pid"
status=0
wait "$daemon_pid" || status=$?
daemon_pid=
echo "meshtopod exited with status $status; its log:"
cat "$log"
[ "$status" -eq 0 ]

echo
echo "== Every mesh was archived (HDF5, one file per version) before it was acknowledged."
run archive ls "$archive"

echo
echo "== A fresh daemon on the same archive serves them again: the first query of a"
echo "==    mesh loads it from the archive (same version, same content hash)."
printf "\n$ meshtopod --lcm-url '%s' --archive %s &\n" "$MESHTOPO_LCM_URL" "$archive"
"$meshtopod" --lcm-url "$MESHTOPO_LCM_URL" --archive "$archive" 2>"$log" &
daemon_pid=$!
run watch --count 1 --timeout-ms 10000
run list
run query nonmanifold ring 7
sleep 1.2
echo
echo "== The heartbeat counts what was loaded from the archive."
run watch --count 1 --timeout-ms 10000
kill -TERM "$daemon_pid"
status=0
wait "$daemon_pid" || status=$?
daemon_pid=
echo "the restarted meshtopod exited with status $status"
[ "$status" -eq 0 ]
echo
echo "== The archive stays in $archive: each file is VTKHDF (VTK's vtkHDFReader,"
echo "==    h5py), with the face list and the report under /meshtopo."
