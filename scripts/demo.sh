#!/usr/bin/env bash
# meshtopo demo: builds the CLI and the daemon (Release, in build/demo) if
# needed, inspects three corpus meshes, a clean one, one with holes and a
# non-manifold one, prints one report as JSON, then runs the LCM service in a
# private network namespace (scripts/demo-network.sh): meshtopod started,
# the three meshes submitted (and archived), queried over LCM, meshtopod
# stopped, restarted on its archive and a reloaded mesh queried.
#   scripts/demo.sh
# MESHTOPO_BUILD_DIR=DIR uses an existing build instead (DIR/tools/meshtopo,
# DIR/daemon/meshtopod). The meshes come from the repository's tests/corpus.
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
corpus=$repo/tests/corpus

if [ -n "${MESHTOPO_BUILD_DIR:-}" ]; then
    build=$MESHTOPO_BUILD_DIR
else
    build=$repo/build/demo
    if [ ! -f "$build/CMakeCache.txt" ]; then
        echo "== Configuring a Release build in $build"
        cmake -S "$repo" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
            -DMESHTOPO_BUILD_TESTS=OFF -DMESHTOPO_BUILD_BENCH=OFF
    fi
    echo "== Building meshtopo and meshtopod"
    cmake --build "$build" --target meshtopo meshtopod
fi
meshtopo=$build/tools/meshtopo
[ -x "$meshtopo" ] || { echo "demo: $meshtopo was not built" >&2; exit 1; }
[ -d "$corpus" ] || { echo "demo: no corpus at $corpus" >&2; exit 1; }
meshtopo=$(cd "$(dirname "$meshtopo")" && pwd)/meshtopo

# Runs the tool from inside the corpus folder, so the commands read as typed.
run() {
    printf '\n$ meshtopo %s\n' "$*"
    (cd "$corpus" && "$meshtopo" "$@")
}

echo
echo "== 1. A clean mesh: the Stanford bunny, closed, manifold, genus 0."
run inspect npm_bunny.off

echo
echo "== 2. A mesh with holes: each hole is a boundary loop, listed by length."
run inspect cgal_elephant_with_holes.off

echo
echo "== 3. A non-manifold mesh: three triangles share edge 7-8. Nothing is dropped: every"
echo "==    defect names its elements, and the one-ring of vertex 7 comes as separate fans."
run inspect vcg_nonmanifold.off --vertices 7 --faces 2

echo
echo "== 4. A report as JSON, with the keys of the corpus reference answers, for scripts and tests."
run inspect cgal_tetrahedron.off --json

echo
status=0
"$repo/tests/netns/netns-run" bash "$repo/scripts/demo-network.sh" "$build" "$corpus" || status=$?
if [ "$status" -eq 77 ]; then
    echo "== (The network part needs a private network namespace, which this machine"
    echo "==  cannot make; run the demo as root, or where unprivileged user namespaces work.)"
elif [ "$status" -ne 0 ]; then
    echo "demo: the network part failed (status $status)" >&2
    exit "$status"
fi

echo
echo "== Demo done."
