#!/usr/bin/env bash
# Install test: installs a finished meshtopo build into a fresh prefix, then
# builds this folder's programs against it twice, once through
# find_package(meshtopo) and once through `pkg-config --cflags --libs`, and
# runs them. Fails unless every program prints the expected topology.
#
# usage: install_test.sh BUILD_DIR WORK_DIR LIBDIR C_COMPILER GENERATOR [EXTRA_C_FLAGS]
#   BUILD_DIR   the meshtopo build tree to install (cmake --install)
#   WORK_DIR    scratch folder, emptied first
#   LIBDIR      CMAKE_INSTALL_LIBDIR of that build (lib, lib/x86_64-linux-gnu, ...)
#   EXTRA_C_FLAGS  flags the build's libraries need at link time (sanitizers)
set -euo pipefail

if [ $# -lt 5 ]; then
    echo "usage: $0 BUILD_DIR WORK_DIR LIBDIR C_COMPILER GENERATOR [EXTRA_C_FLAGS]" >&2
    exit 2
fi
build_dir=$1
work=$2
libdir=$3
cc=$4
generator=$5
extra_flags=${6:-}
here=$(cd "$(dirname "$0")" && pwd)
prefix=$work/prefix

step() { printf '\n-- %s\n' "$*"; }
fail() {
    echo "install test FAILED: $*" >&2
    exit 1
}

# Runs a program; fails unless it exits 0 and its output holds the expected text.
run_expect() {
    local what=$1 expected=$2 output rc=0
    shift 2
    output=$("$@" 2>&1) || rc=$?
    printf '%s\n' "$output"
    [ "$rc" -eq 0 ] || fail "$what exited with status $rc"
    grep -qF -- "$expected" <<<"$output" || fail "$what: expected '$expected' in its output"
}

rm -rf "$work"
mkdir -p "$work"

step "cmake --install $build_dir --prefix $prefix"
cmake --install "$build_dir" --prefix "$prefix" >"$work/install.log" ||
    { cat "$work/install.log"; fail "cmake --install failed"; }
for f in include/meshtopo/core.h include/meshtopo/io.h include/meshtopo/status.h \
    include/meshtopo/client.h include/meshtopo/msgs.h include/meshtopo/msgs_types.h \
    include/lcmtypes/meshtopo_mesh_t.h "$libdir/pkgconfig/meshtopo-client.pc" \
    "$libdir/cmake/meshtopo/meshtopoConfig.cmake" \
    "$libdir/cmake/meshtopo/meshtopoConfigVersion.cmake" \
    "$libdir/cmake/meshtopo/meshtopoTargets.cmake" \
    "$libdir/pkgconfig/meshtopo.pc" "$libdir/pkgconfig/meshtopo-core.pc" \
    "$libdir/pkgconfig/meshtopo-io.pc"; do
    [ -f "$prefix/$f" ] || fail "not installed: $f"
done
for f in share/meshtopo/lcm/mesh_t.lcm share/meshtopo/lcm/query_t.lcm share/doc/meshtopo/README.md; do
    [ -f "$prefix/$f" ] || fail "not installed: $f"
done
# The unit's documentation is a file URI naming an installed file.
unit=$prefix/share/meshtopo/systemd/meshtopod.service
if [ -f "$unit" ]; then
    doc=$(sed -n 's|^Documentation=file://||p' "$unit")
    [ -n "$doc" ] && [ -f "$doc" ] || fail "meshtopod.service: Documentation= names no installed file ($doc)"
fi
ls "$prefix/$libdir"/libmeshtopo-core.* "$prefix/$libdir"/libmeshtopo-io.* >/dev/null ||
    fail "libraries not installed in $prefix/$libdir"
# The installed tool runs from the prefix (a shared build finds its libraries
# through its RUNPATH, so LD_LIBRARY_PATH is not set yet).
if [ -x "$prefix/bin/meshtopo" ]; then
    run_expect "installed meshtopo --version" "meshtopo" "$prefix/bin/meshtopo" --version
fi
# Shared installs: the pkg-config-built programs find the libraries here.
export LD_LIBRARY_PATH="$prefix/$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

step "find_package(meshtopo): configure and build tests/install"
cmake -S "$here" -B "$work/consumer" -G "$generator" \
    -DCMAKE_C_COMPILER="$cc" -DCMAKE_C_FLAGS="$extra_flags" \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$work/consumer-configure.log" ||
    { cat "$work/consumer-configure.log"; fail "configuring the consumer failed"; }
found=$(sed -n 's/^meshtopo_DIR:PATH=//p' "$work/consumer/CMakeCache.txt")
[ "$found" = "$prefix/$libdir/cmake/meshtopo" ] ||
    fail "find_package found meshtopo in '$found', not in the test prefix"
cmake --build "$work/consumer" >"$work/consumer-build.log" ||
    { cat "$work/consumer-build.log"; fail "building the consumer failed"; }
run_expect "consumer (meshtopo::core)" "Euler characteristic: 2, genus: 0" \
    "$work/consumer/consumer"
run_expect "consumer_io (meshtopo::io)" "cube (off): Euler characteristic: 2" \
    "$work/consumer/consumer_io"
run_expect "consumer_client (meshtopo::client)" "client ok: cube content hash" \
    "$work/consumer/consumer_client"
# The same hash from the pkg-config build below.
client_line=$("$work/consumer/consumer_client" | grep "client ok")

step "pkg-config: compile main.c and read_main.c"
export PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
for pc in meshtopo-core meshtopo-io meshtopo-client meshtopo; do
    printf '%s: %s\n' "$pc" "$(pkg-config --cflags --libs "$pc")"
done
[ "$(pkg-config --modversion meshtopo-core)" = "$(pkg-config --modversion meshtopo)" ] ||
    fail "meshtopo.pc and meshtopo-core.pc disagree on the version"
# shellcheck disable=SC2046,SC2086  # pkg-config output is meant to be word-split
"$cc" $extra_flags $(pkg-config --cflags meshtopo-core) "$here/main.c" \
    $(pkg-config --libs meshtopo-core) -o "$work/main_pc" ||
    fail "compiling main.c with pkg-config meshtopo-core failed"
# shellcheck disable=SC2046,SC2086
"$cc" $extra_flags $(pkg-config --cflags meshtopo-io) "$here/read_main.c" \
    $(pkg-config --libs meshtopo-io) -o "$work/read_pc" ||
    fail "compiling read_main.c with pkg-config meshtopo-io failed"
# shellcheck disable=SC2046,SC2086
"$cc" $extra_flags $(pkg-config --cflags meshtopo) "$here/read_main.c" \
    $(pkg-config --libs meshtopo) -o "$work/read_pc_all" ||
    fail "compiling read_main.c with pkg-config meshtopo failed"
# shellcheck disable=SC2046,SC2086
"$cc" $extra_flags $(pkg-config --cflags meshtopo-client) "$here/client_main.c" \
    $(pkg-config --libs meshtopo-client) -o "$work/client_pc" ||
    fail "compiling client_main.c with pkg-config meshtopo-client failed"
run_expect "main.c (pkg-config)" "Euler characteristic: 2, genus: 0" "$work/main_pc"
run_expect "read_main.c (pkg-config)" "cube (off): Euler characteristic: 2" "$work/read_pc"
run_expect "read_main.c (pkg-config meshtopo)" "cube (off): Euler characteristic: 2" \
    "$work/read_pc_all"
run_expect "client_main.c (pkg-config)" "$client_line" "$work/client_pc"

step "install test passed"
