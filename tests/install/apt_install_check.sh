#!/usr/bin/env bash
# Installs the Debian packages a build made the way a user would, `apt-get
# install ./BUILD_DIR/*.deb` (apt resolves their dependencies), checks the
# installed meshtopo, then purges every package the install added (ours and
# any dependency apt pulled in) and the system user the package created, so
# the machine is left as it was. Checks: `meshtopo bench --help` runs
# meshtopo-bench, the archive commands' module loads, `man -w` finds the man
# pages, the systemd unit verifies (`systemctl cat` when systemd runs,
# `systemd-analyze verify` otherwise), meshtopod's user and /var/lib/meshtopo
# exist, the README's C example (tests/install/main.c) builds with
# `pkg-config meshtopo-core` against /usr and runs, and the README's Python
# example prints with /usr/bin/python3 what the README says.
#
# It changes the system, so it runs only as root and only when CI=true or
# with --really; otherwise it exits 77 (skipped). It refuses to start when a
# meshtopo package is installed already (the purge would remove it).
#
# usage: apt_install_check.sh [--really] BUILD_DIR
#   BUILD_DIR  the build tree the packages were made in (its *.deb files)
set -euo pipefail

really=false
if [ "${1:-}" = --really ]; then
    really=true
    shift
fi
if [ $# -ne 1 ]; then
    echo "usage: $0 [--really] BUILD_DIR" >&2
    exit 2
fi
build_dir=$(cd "$1" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)

if ! $really && [ "${CI:-}" != true ]; then
    echo "apt install check skipped: it installs and purges packages system-wide;" \
        "run it with --really (or CI=true)"
    exit 77
fi
if [ "$(id -u)" -ne 0 ]; then
    echo "apt install check skipped: run as root (it calls apt-get install and purge)"
    exit 77
fi
for tool in apt-get dpkg-deb dpkg-query cc pkg-config man; do
    command -v "$tool" >/dev/null || {
        echo "apt install check FAILED: $tool not found (scripts/install-deps.sh --tests)" >&2
        exit 1
    }
done

failures=0
step() { printf '\n-- %s\n' "$*"; }
fail() {
    echo "apt install check FAILED: $*" >&2
    failures=$((failures + 1))
}

mapfile -t debs < <(find "$build_dir" -maxdepth 1 -name '*.deb' | sort)
if [ ${#debs[@]} -eq 0 ]; then
    echo "apt install check FAILED: no .deb in $build_dir" \
        "(cmake --build $build_dir --target package)" >&2
    exit 1
fi
ours=()
for deb in "${debs[@]}"; do ours+=("$(dpkg-deb -f "$deb" Package)"); done

# Installed packages, one "name:arch" a line, sorted.
installed_packages() {
    dpkg-query -W -f='${db:Status-Status} ${binary:Package}\n' | awk '$1 == "installed" { print $2 }' |
        sort
}
for package in "${ours[@]}"; do
    if [ "$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null)" = installed ]; then
        echo "apt install check FAILED: $package is installed already; this check would" \
            "purge it (apt-get purge ${ours[*]} first)" >&2
        exit 1
    fi
done

work=$(mktemp -d)
installed_packages >"$work/before"
had_user=false
had_group=false
had_state_dir=false
if getent passwd meshtopod >/dev/null; then had_user=true; fi
if getent group meshtopod >/dev/null; then had_group=true; fi
if [ -e /var/lib/meshtopo ]; then had_state_dir=true; fi
export DEBIAN_FRONTEND=noninteractive

# Purges what the install added and removes what the package's postinst
# created that Debian leaves on purge (the system user), once.
cleaned=false
cleanup() {
    $cleaned && return 0
    cleaned=true
    step "apt-get purge: the packages the install added"
    installed_packages >"$work/after"
    # What the packages hold (for the check of leftovers after the purge).
    for package in "${ours[@]}"; do dpkg -L "$package" 2>/dev/null || true; done |
        grep meshtopo | sort -r >"$work/files" || true
    mapfile -t added < <(comm -13 "$work/before" "$work/after")
    if [ ${#added[@]} -gt 0 ]; then
        echo "added by the install: ${added[*]}"
        apt-get purge -y "${added[@]}" || fail "apt-get purge failed"
    fi
    if ! $had_user && getent passwd meshtopod >/dev/null; then
        userdel meshtopod || fail "userdel meshtopod failed"
    fi
    if ! $had_group && getent group meshtopod >/dev/null; then
        groupdel meshtopod || fail "groupdel meshtopod failed"
    fi
    local left=()
    while IFS= read -r path; do
        if [ -e "$path" ] || [ -L "$path" ]; then left+=("$path"); fi
    done <"$work/files"
    [ ${#left[@]} -eq 0 ] || fail "left behind by the purge: ${left[*]}"
    if ! $had_state_dir && [ -e /var/lib/meshtopo ]; then
        fail "/var/lib/meshtopo is still there after the purge (not empty?): $(ls -A /var/lib/meshtopo)"
    fi
    installed_packages >"$work/after"
    if ! cmp -s "$work/before" "$work/after"; then
        fail "the installed packages differ from before: $(diff "$work/before" "$work/after" | grep '^[<>]' | tr '\n' ' ')"
    else
        echo "the installed packages are as before"
    fi
    rm -rf "$work"
}
trap 'cleanup; exit 1' INT TERM
trap cleanup EXIT

step "apt-get install ${debs[*]##*/}"
if ! apt-get install -y "${debs[@]}"; then
    fail "apt-get install failed"
    exit 1
fi
for package in "${ours[@]}"; do
    printf '%s %s\n' "$package" "$(dpkg-query -W -f='${Version} ${db:Status-Status}' "$package")"
done

step "the installed programs"
/usr/bin/meshtopo --version || fail "meshtopo --version failed"
/usr/bin/meshtopod --version || fail "meshtopod --version failed"
if bench_help=$(/usr/bin/meshtopo bench --help 2>&1) && grep -q '^usage: meshtopo-bench' <<<"$bench_help"; then
    echo "meshtopo bench --help: $(sed -n 1p <<<"$bench_help")"
else
    fail "meshtopo bench --help did not run meshtopo-bench: $bench_help"
fi
mkdir -p "$work/archive"
/usr/bin/meshtopo archive ls "$work/archive" || fail "meshtopo archive ls (the archive module) failed"

step "man -w"
for page in meshtopo meshtopod meshtopo-bench meshtopo-inspect; do
    if path=$(env -u MANPATH man -w "$page" 2>&1) && [ "$path" = "/usr/share/man/man1/$page.1.gz" ]; then
        echo "$page: $path"
    else
        fail "man -w $page: '$path', not /usr/share/man/man1/$page.1.gz"
    fi
done

step "the systemd unit, its user and its directory"
unit=/usr/lib/systemd/system/meshtopod.service
if [ -d /run/systemd/system ]; then
    systemctl cat meshtopod.service || fail "systemctl cat meshtopod.service failed"
elif command -v systemd-analyze >/dev/null; then
    if systemd-analyze verify "$unit"; then
        echo "systemd-analyze verify $unit: ok"
    else
        fail "systemd-analyze verify $unit failed"
    fi
else
    echo "no systemd here: the unit is not verified"
fi
if command -v systemd-sysusers >/dev/null; then
    getent passwd meshtopod || fail "the postinst created no user meshtopod"
    owner=$(stat -c %U /var/lib/meshtopo 2>/dev/null || true)
    [ "$owner" = meshtopod ] || fail "/var/lib/meshtopo is not meshtopod's (owner: '$owner')"
    [ -z "$owner" ] || ls -ld /var/lib/meshtopo
else
    echo "no systemd-sysusers here: the postinst creates no user"
fi

step "the README's C example against /usr (pkg-config meshtopo-core)"
multiarch=$(cc -print-multiarch)
pc_dirs=/usr/lib/$multiarch/pkgconfig:/usr/lib/pkgconfig:/usr/share/pkgconfig
if [ -d /usr/local/include/meshtopo ]; then
    echo "note: /usr/local/include/meshtopo exists and comes first in cc's include path"
fi
pc() { env -u PKG_CONFIG_PATH PKG_CONFIG_LIBDIR="$pc_dirs" pkg-config "$@"; }
echo "meshtopo-core.pc: $(pc --variable=pcfiledir meshtopo-core)/meshtopo-core.pc"
# shellcheck disable=SC2046 # pkg-config's output is words
if cc "$here/main.c" $(pc --cflags --libs meshtopo-core) -o "$work/app" && "$work/app" >"$work/app.out"; then
    cat "$work/app.out"
    grep -qx 'V=4 E=6 F=4' "$work/app.out" || fail "the C example did not print V=4 E=6 F=4"
else
    fail "the C example did not build or run against /usr"
fi

step "the README's Python example with /usr/bin/python3"
/usr/bin/python3 - "$repo/tests/python" "$work" <<'EOF' || fail "the README's Python example could not be read"
import sys
sys.path.insert(0, sys.argv[1])
from readme_blocks import local_example
code, printed = local_example()
open(sys.argv[2] + "/example.py", "w").write(code)
open(sys.argv[2] + "/expected.txt", "w").write(printed)
EOF
# A clean environment in an empty folder: the installed package, nothing else.
py() { (cd "$work" && env -i PATH=/usr/bin:/bin HOME="$work" /usr/bin/python3 "$@"); }
if location=$(py -c 'import meshtopo; print(meshtopo.__file__)'); then
    echo "meshtopo: $location"
    [[ "$location" == /usr/lib/python3/dist-packages/meshtopo/* ]] ||
        fail "python3 imports meshtopo from $location, not /usr/lib/python3/dist-packages"
else
    fail "/usr/bin/python3 cannot import meshtopo"
fi
if [ -f "$work/example.py" ] && py "$work/example.py" >"$work/example.out"; then
    cat "$work/example.out"
    diff -u "$work/expected.txt" "$work/example.out" ||
        fail "the README's Python example printed other than the README says"
else
    fail "the README's Python example failed"
fi

cleanup
if [ $failures -ne 0 ]; then
    printf '\napt install check FAILED: %d problem(s)\n' "$failures" >&2
    exit 1
fi
step "apt install check passed"
