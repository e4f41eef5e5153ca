#!/usr/bin/env bash
# Debian package test: makes the .deb packages of a finished meshtopo build
# with `cpack -G DEB` (into WORK_DIR, the build tree is left as it is),
# checks their names, Depends and contents, unpacks them with `dpkg -x` into
# a scratch root and builds this folder's programs, the README's C example
# first, against the unpacked /usr through find_package(meshtopo) and
# pkg-config (consumers.sh); then runs the unpacked tools and imports the
# unpacked Python package (not in a sanitizer build, as python.*). Needs dpkg-deb and dpkg-shlibdeps (dpkg-dev);
# exits 77 (skipped) without them.
#
# usage: deb_test.sh BUILD_DIR WORK_DIR LIBDIR C_COMPILER GENERATOR [EXTRA_C_FLAGS]
#   BUILD_DIR   the meshtopo build tree (its CPackConfig.cmake)
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
packages=$work/packages
root=$work/root
prefix=$root/usr

step() { printf '\n-- %s\n' "$*"; }
fail() {
    echo "deb test FAILED: $*" >&2
    exit 1
}

for tool in cpack dpkg-deb dpkg-shlibdeps; do
    command -v "$tool" >/dev/null || {
        echo "deb test skipped: $tool not found (Debian: apt-get install dpkg-dev)"
        exit 77
    }
done

rm -rf "$work"
mkdir -p "$packages" "$root"

step "cpack -G DEB (from $build_dir into $packages)"
(cd "$build_dir" && cpack -G DEB -B "$packages" --config "$build_dir/CPackConfig.cmake") \
    >"$work/cpack.log" 2>&1 || { cat "$work/cpack.log"; fail "cpack failed"; }
ls -l "$packages"/*.deb

# The one package named $1 (its file), failing when it is missing.
deb_of() {
    local found
    found=$(find "$packages" -maxdepth 1 -name "$1_*.deb" -print -quit)
    [ -n "$found" ] || fail "no package $1 among $(ls "$packages")"
    printf '%s\n' "$found"
}
# Fails unless package $1's field $2 holds each of the following words.
expect_field() {
    local deb=$1 field=$2 value
    shift 2
    value=$(dpkg-deb -f "$deb" "$field")
    for want in "$@"; do
        grep -qE "(^|[ ,])$want([ ,(]|$)" <<<"$value" ||
            fail "$(basename "$deb"): $field '$value' lacks $want"
    done
}

step "package names, Depends and contents"
tools_deb=$(deb_of meshtopo)
dev_deb=$(deb_of libmeshtopo-dev)
python_deb=$(deb_of python3-meshtopo)
for deb in "$packages"/*.deb; do
    printf '%s: %s\n' "$(dpkg-deb -f "$deb" Package)" "$(dpkg-deb -f "$deb" Depends)"
done
expect_field "$tools_deb" Depends libc6 liblcm1 'libhdf5-[0-9.-]+' libxxhash0
expect_field "$dev_deb" Depends liblcm-dev libhdf5-dev libxxhash-dev zlib1g-dev
libs_deb=$(find "$packages" -maxdepth 1 -name 'libmeshtopo[0-9]*_*.deb' -print -quit)
if [ -n "$libs_deb" ]; then
    # A shared build: the Python package gets LCM through the libraries'
    # package (which liblcm1 is a dependency of), whatever the linker kept.
    expect_field "$python_deb" Depends python3 python3-numpy "$(dpkg-deb -f "$libs_deb" Package)"
    expect_field "$libs_deb" Depends libc6 liblcm1 'libhdf5-[0-9.-]+' libxxhash0
else
    expect_field "$python_deb" Depends python3 python3-numpy liblcm1
fi
version=$(dpkg-deb -f "$tools_deb" Version)
for deb in "$packages"/*.deb; do
    [ "$(dpkg-deb -f "$deb" Version)" = "$version" ] ||
        fail "$(basename "$deb") is not version $version"
    dpkg-deb -x "$deb" "$root"
done

for f in usr/bin/meshtopo usr/bin/meshtopod usr/share/doc/meshtopo/README.md \
    usr/share/meshtopo/lcm/mesh_t.lcm usr/share/meshtopo/systemd/meshtopod.service \
    usr/lib/systemd/system/meshtopod.service usr/include/meshtopo/core.h \
    usr/include/meshtopo/archive.h usr/include/meshtopo/defect_record.h \
    usr/include/lcmtypes/meshtopo_mesh_t.h "usr/$libdir/cmake/meshtopo/meshtopoConfig.cmake" \
    "usr/$libdir/pkgconfig/meshtopo-core.pc" "usr/$libdir/pkgconfig/meshtopo-archive.pc" \
    usr/lib/python3/dist-packages/meshtopo/__init__.py \
    usr/lib/python3/dist-packages/meshtopo/libmeshtopo-python.so \
    "usr/$libdir/meshtopo/meshtopo-archive-commands.so"; do
    [ -f "$root/$f" ] || fail "no package holds /$f"
done
ls "$prefix/$libdir"/libmeshtopo-archive.* >/dev/null || fail "libmeshtopo-archive not packaged"
# Every file in exactly one package.
dups=$(for deb in "$packages"/*.deb; do dpkg-deb -c "$deb" | awk '$1 !~ /^d/ {print $6}'; done |
    sort | uniq -d)
[ -z "$dups" ] || fail "files in two packages: $dups"
# The unit starts the packaged daemon.
grep -qx "ExecStart=/usr/bin/meshtopod" "$root/usr/lib/systemd/system/meshtopod.service" ||
    fail "meshtopod.service does not start /usr/bin/meshtopod"

step "the unpacked tools run"
"$prefix/bin/meshtopo" --version
"$prefix/bin/meshtopod" --version
# The archive commands load their module from beside the unpacked program.
mkdir -p "$work/empty-archive"
"$prefix/bin/meshtopo" archive ls "$work/empty-archive" ||
    fail "the unpacked meshtopo cannot run its archive commands"

bash "$here/consumers.sh" "$prefix" "$libdir" "$work" "$cc" "$generator" "$extra_flags"

step "the unpacked Python package imports and builds a mesh"
if [[ "$extra_flags" == *-fsanitize* ]]; then
    # As python.*: a sanitized shared object needs its runtime preloaded.
    echo "sanitizer build: the Python package is not imported"
elif /usr/bin/python3 -c "import numpy" 2>/dev/null; then
    PYTHONPATH="$prefix/lib/python3/dist-packages" PYTHONDONTWRITEBYTECODE=1 \
        MESHTOPO_PYTHON_LIBRARY='' /usr/bin/python3 -c "
import meshtopo, numpy as np
assert meshtopo.__file__.startswith('$prefix/'), meshtopo.__file__
mesh = meshtopo.Mesh(np.eye(3), np.array([[0, 1, 2]]))
print('python ok:', meshtopo.__file__, mesh.report()['E'], 'edges')
" || fail "the unpacked Python package does not work"
else
    echo "python3-numpy not installed: not imported"
fi

step "deb test passed"
