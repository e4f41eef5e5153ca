#!/usr/bin/env bash
# Builds this folder's programs against an installed meshtopo twice, once
# through find_package(meshtopo) and once through `pkg-config --cflags
# --libs`, and runs them. Fails unless every program prints the expected
# topology. Shared by install_test.sh (a `cmake --install` tree) and
# deb_test.sh (the Debian packages unpacked).
#
# usage: consumers.sh PREFIX LIBDIR WORK_DIR C_COMPILER GENERATOR [EXTRA_C_FLAGS]
#   PREFIX      the installed tree (its include/, LIBDIR/, ...)
#   LIBDIR      its library directory, relative to PREFIX
#   WORK_DIR    scratch folder for the builds (created)
#   EXTRA_C_FLAGS  flags the installed libraries need at link time (sanitizers)
set -euo pipefail

if [ $# -lt 5 ]; then
    echo "usage: $0 PREFIX LIBDIR WORK_DIR C_COMPILER GENERATOR [EXTRA_C_FLAGS]" >&2
    exit 2
fi
prefix=$1
libdir=$2
work=$3
cc=$4
generator=$5
extra_flags=${6:-}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"

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

# Shared installs: the programs built here find the libraries in the prefix.
export LD_LIBRARY_PATH="$prefix/$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

step "find_package(meshtopo): configure and build tests/install against $prefix"
cmake -S "$here" -B "$work/consumer" -G "$generator" \
    -DCMAKE_C_COMPILER="$cc" -DCMAKE_C_FLAGS="$extra_flags" \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$work/consumer-configure.log" ||
    { cat "$work/consumer-configure.log"; fail "configuring the consumer failed"; }
found=$(sed -n 's/^meshtopo_DIR:PATH=//p' "$work/consumer/CMakeCache.txt")
[ "$found" = "$prefix/$libdir/cmake/meshtopo" ] ||
    fail "find_package found meshtopo in '$found', not in $prefix/$libdir/cmake/meshtopo"
cmake --build "$work/consumer" >"$work/consumer-build.log" ||
    { cat "$work/consumer-build.log"; fail "building the consumer failed"; }
run_expect "consumer (meshtopo::core)" "Euler characteristic: 2, genus: 0" \
    "$work/consumer/consumer"
run_expect "consumer_io (meshtopo::io)" "cube (off): Euler characteristic: 2" \
    "$work/consumer/consumer_io"
run_expect "consumer_client (meshtopo::client)" "client ok: cube content hash" \
    "$work/consumer/consumer_client"
run_expect "consumer_archive (meshtopo::archive)" "archive ok: cube v1 reloaded, Euler characteristic 2" \
    "$work/consumer/consumer_archive"
run_expect "consumer_archive_io (meshtopo::core, io, archive)" "archive io ok" \
    "$work/consumer/consumer_archive_io"
# The same hash from the pkg-config build below.
client_line=$("$work/consumer/consumer_client" | grep "client ok")

step "pkg-config: compile main.c, read_main.c, client_main.c and archive_main.c"
export PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
for pc in meshtopo-core meshtopo-io meshtopo-client meshtopo-archive meshtopo; do
    printf '%s: %s\n' "$pc" "$(pkg-config --cflags --libs "$pc")"
done
[ "$(pkg-config --modversion meshtopo-core)" = "$(pkg-config --modversion meshtopo)" ] ||
    fail "meshtopo.pc and meshtopo-core.pc disagree on the version"
[ "$(pkg-config --variable=prefix meshtopo-archive | xargs realpath)" = "$(realpath "$prefix")" ] ||
    fail "meshtopo-archive.pc's prefix is not $prefix"
# Compiles one program with the flags of one .pc file.
pc_build() {
    local pc=$1 source=$2 out=$3
    # shellcheck disable=SC2046,SC2086  # pkg-config output is meant to be word-split
    "$cc" $extra_flags $(pkg-config --cflags "$pc") "$here/$source" \
        $(pkg-config --libs "$pc") -o "$work/$out" ||
        fail "compiling $source with pkg-config $pc failed"
}
pc_build meshtopo-core main.c main_pc
pc_build meshtopo-io read_main.c read_pc
pc_build meshtopo read_main.c read_pc_all
pc_build meshtopo-client client_main.c client_pc
pc_build meshtopo-archive archive_main.c archive_pc
run_expect "main.c (pkg-config)" "Euler characteristic: 2, genus: 0" "$work/main_pc"
run_expect "read_main.c (pkg-config)" "cube (off): Euler characteristic: 2" "$work/read_pc"
run_expect "read_main.c (pkg-config meshtopo)" "cube (off): Euler characteristic: 2" \
    "$work/read_pc_all"
run_expect "client_main.c (pkg-config)" "$client_line" "$work/client_pc"
run_expect "archive_main.c (pkg-config)" "archive ok: cube v1 reloaded" "$work/archive_pc"
