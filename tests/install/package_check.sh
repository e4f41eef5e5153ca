#!/usr/bin/env bash
# Debian policy check of the packages a build made (`cmake --build BUILD
# --target package`): lintian finds no error and no warning in any of them
# (overrides only in packaging/*lintian-overrides.in, each with its reason),
# the meshtopo package has a man page for meshtopo, meshtopod, meshtopo-bench
# and every command the packaged `meshtopo --help` lists, and the control
# fields are right: a real Maintainer, a synopsis of its own for each
# package, Recommends with python3-vtk9 and xvfb; plus the files every
# package and the meshtopo package must have (copyright, changelog, unit,
# sysusers.d and tmpfiles.d snippets). Reads the .deb files only: the
# packages are unpacked with dpkg-deb -x into a scratch root, never installed
# (tests/install/apt_install_check.sh installs them). Exits 77 (skipped)
# without lintian or dpkg-deb (Debian: apt-get install lintian dpkg-dev).
#
# usage: package_check.sh [--cpack WORK_DIR] BUILD_DIR
#   BUILD_DIR  the build tree the packages were made in (its *.deb files)
#   --cpack WORK_DIR  make them first, with `cpack -G DEB` from BUILD_DIR's
#              CPackConfig.cmake into WORK_DIR (emptied; the build tree is left
#              as it is), and check those: what a ctest of a finished build runs
set -euo pipefail

cpack_dir=""
if [ "${1:-}" = --cpack ] && [ $# -ge 2 ]; then
    cpack_dir=$2
    shift 2
fi
if [ $# -ne 1 ]; then
    echo "usage: $0 [--cpack WORK_DIR] BUILD_DIR" >&2
    exit 2
fi
build_dir=$(cd "$1" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)

failures=0
step() { printf '\n-- %s\n' "$*"; }
fail() {
    echo "package check FAILED: $*" >&2
    failures=$((failures + 1))
}

for tool in lintian dpkg-deb; do
    command -v "$tool" >/dev/null || {
        echo "package check skipped: $tool not found (Debian: apt-get install lintian dpkg-dev)"
        exit 77
    }
done

if [ -n "$cpack_dir" ]; then
    command -v cpack >/dev/null || { echo "package check FAILED: cpack not found" >&2; exit 1; }
    rm -rf "$cpack_dir"
    mkdir -p "$cpack_dir"
    cpack_dir=$(cd "$cpack_dir" && pwd)
    step "cpack -G DEB (from $build_dir into $cpack_dir)"
    (cd "$build_dir" && cpack -G DEB -B "$cpack_dir" --config "$build_dir/CPackConfig.cmake") \
        >"$cpack_dir/cpack.log" 2>&1 || {
        cat "$cpack_dir/cpack.log"
        echo "package check FAILED: cpack failed" >&2
        exit 1
    }
    build_dir=$cpack_dir
fi
mapfile -t debs < <(find "$build_dir" -maxdepth 1 -name '*.deb' | sort)
if [ ${#debs[@]} -eq 0 ]; then
    echo "package check FAILED: no .deb in $build_dir" \
        "(cmake --build $build_dir --target package)" >&2
    exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The one package named $1 (its file), empty when there is none.
deb_of() {
    local deb
    for deb in "${debs[@]}"; do
        if [ "$(dpkg-deb -f "$deb" Package)" = "$1" ]; then
            printf '%s\n' "$deb"
            return
        fi
    done
}

step "lintian --fail-on error,warning ${debs[*]##*/}"
status=0
output=$(lintian --fail-on error,warning "${debs[@]}" 2>&1) || status=$?
# lintian says so when it runs as root (CI); that line is not a finding.
output=$(grep -v '^running with root privileges is not recommended!$' <<<"$output" || true)
if [ -n "$output" ]; then printf '%s\n' "$output"; else echo "(no tags)"; fi
[ $status -eq 0 ] || fail "lintian found errors or warnings (listed above)"

step "control fields"
declare -A synopsis_of
for deb in "${debs[@]}"; do
    package=$(dpkg-deb -f "$deb" Package)
    maintainer=$(dpkg-deb -f "$deb" Maintainer)
    synopsis=$(dpkg-deb -f "$deb" Description | sed -n 1p)
    printf '%s\n  Maintainer: %s\n  Synopsis:   %s\n' "$package" "$maintainer" "$synopsis"
    [[ "$maintainer" =~ ^[^\<\>]+\ \<[^@\<\>\ ]+@[^@\<\>\ ]+\.[a-z]+\>$ ]] ||
        fail "$package: Maintainer '$maintainer' is not 'Name <address>'"
    [[ "$maintainer" != *@localhost* ]] || fail "$package: Maintainer '$maintainer' is at localhost"
    for other in "${!synopsis_of[@]}"; do
        [ "${synopsis_of[$other]}" != "$synopsis" ] ||
            fail "$package has the synopsis of $other: '$synopsis'"
    done
    synopsis_of[$package]=$synopsis
done
tools_deb=$(deb_of meshtopo)
[ -n "$tools_deb" ] || { fail "no meshtopo package among: ${debs[*]}"; exit 1; }
recommends=$(dpkg-deb -f "$tools_deb" Recommends)
suggests=$(dpkg-deb -f "$tools_deb" Suggests)
echo "meshtopo Recommends: $recommends"
echo "meshtopo Suggests:   $suggests"
for want in python3-vtk9 xvfb; do
    grep -qE "(^|[ ,|])$want([ ,|(]|$)" <<<"$recommends" || fail "meshtopo Recommends lacks $want"
done
for want in paraview liblcm-java default-jre; do
    grep -qE "(^|[ ,|])$want([ ,|(]|$)" <<<"$suggests" || fail "meshtopo Suggests lacks $want"
done

step "files of every package: copyright (DEP-5, BSD-3-Clause), changelog of its version"
root=$work/root
mkdir -p "$root"
licence_text=$(sed -n '4,$p' "$repo/LICENSE" | sed -e 's/^$/./' -e 's/^/ /')
for deb in "${debs[@]}"; do
    package=$(dpkg-deb -f "$deb" Package)
    version=$(dpkg-deb -f "$deb" Version)
    dpkg-deb -x "$deb" "$root"
    doc=$root/usr/share/doc/$package
    if [ -f "$doc/copyright" ]; then
        [ "$(sed -n 1p "$doc/copyright")" = \
            'Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/' ] ||
            fail "$package: copyright is not in the DEP-5 format"
        grep -qx 'License: BSD-3-Clause' "$doc/copyright" ||
            fail "$package: copyright names no BSD-3-Clause licence"
        # The text of the last "License: BSD-3-Clause" paragraph: LICENSE's.
        text=$(awk '{ line[NR] = $0 } /^License: BSD-3-Clause$/ { last = NR }
            END { for (i = last + 1; i <= NR && line[i] != ""; i++) print line[i] }' \
            "$doc/copyright")
        [ "$text" = "$licence_text" ] ||
            fail "$package: the licence text of its copyright differs from LICENSE"
    else
        fail "$package: no /usr/share/doc/$package/copyright"
    fi
    if [ -f "$doc/changelog.Debian.gz" ]; then
        first=$(gzip -dc "$doc/changelog.Debian.gz" | sed -n 1p)
        [ "$first" = "meshtopo ($version) unstable; urgency=medium" ] ||
            fail "$package: changelog starts '$first', not with version $version"
    else
        fail "$package: no /usr/share/doc/$package/changelog.Debian.gz"
    fi
    echo "$package $version: copyright and changelog ok"
done

step "the meshtopo package: programs, unit, sysusers.d, tmpfiles.d"
listing=$(dpkg-deb -c "$tools_deb" | awk '{print $6}')
for f in usr/bin/meshtopo usr/bin/meshtopod usr/bin/meshtopo-bench \
    usr/lib/systemd/system/meshtopod.service usr/lib/sysusers.d/meshtopod.conf \
    usr/lib/tmpfiles.d/meshtopod.conf usr/share/doc/meshtopo/msgs.md; do
    if grep -qx "\./$f" <<<"$listing"; then
        echo "has /$f"
    else
        fail "the meshtopo package lacks /$f"
    fi
done
grep -qx 'User=meshtopod' "$root/usr/lib/systemd/system/meshtopod.service" ||
    fail "the packaged unit does not run meshtopod as the user meshtopod"
grep -q '^u *meshtopod ' "$root/usr/lib/sysusers.d/meshtopod.conf" ||
    fail "sysusers.d/meshtopod.conf creates no user meshtopod"

step "man pages in the meshtopo package (dpkg -c)"
# The commands as the packaged program lists them (run from the unpacked
# root: it finds its module, and a shared build its libraries, beside it).
if ! help=$("$root/usr/bin/meshtopo" --help); then
    fail "the packaged meshtopo --help failed"
fi
mapfile -t commands < <(awk '/^commands:$/ { on = 1; next } on && /^$/ { exit } on { print $1 }' \
    <<<"$help")
[ ${#commands[@]} -gt 0 ] || fail "no commands in the packaged meshtopo --help"
pages=(meshtopo meshtopod meshtopo-bench)
for name in "${commands[@]}"; do
    # `meshtopo bench` runs meshtopo-bench, whose page it shares.
    if [ "$name" != bench ]; then pages+=("meshtopo-$name"); fi
done
for page in "${pages[@]}"; do
    if grep -qx "\./usr/share/man/man1/$page\.1\.gz" <<<"$listing"; then
        echo "has $page(1)"
    else
        fail "the meshtopo package has no /usr/share/man/man1/$page.1.gz (help2man installed?)"
    fi
done

step "lintian overrides the packages carry (each with its reason in packaging/)"
for file in "$root"/usr/share/lintian/overrides/*; do
    [ -f "$file" ] || continue
    grep -v '^#' "$file" | grep -v '^$' || true
done

if [ $failures -ne 0 ]; then
    printf '\npackage check FAILED: %d problem(s)\n' "$failures" >&2
    exit 1
fi
step "package check passed: ${#debs[@]} packages"
