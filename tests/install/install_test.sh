#!/usr/bin/env bash
# Install test: installs a finished meshtopo build into a fresh prefix, then
# builds this folder's programs against it twice, once through
# find_package(meshtopo) and once through `pkg-config --cflags --libs`, and
# runs them (consumers.sh). Fails unless every program prints the expected
# topology.
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
    include/meshtopo/archive.h include/meshtopo/defect_record.h \
    "$libdir/pkgconfig/meshtopo-archive.pc" \
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
ls "$prefix/$libdir"/libmeshtopo-core.* "$prefix/$libdir"/libmeshtopo-io.* \
    "$prefix/$libdir"/libmeshtopo-archive.* >/dev/null ||
    fail "libraries not installed in $prefix/$libdir"
# The installed tool runs from the prefix (a shared build finds its libraries
# through its RUNPATH, so LD_LIBRARY_PATH is not set yet).
if [ -x "$prefix/bin/meshtopo" ]; then
    run_expect "installed meshtopo --version" "meshtopo" "$prefix/bin/meshtopo" --version
fi
bash "$here/consumers.sh" "$prefix" "$libdir" "$work" "$cc" "$generator" "$extra_flags"

step "install test passed"
