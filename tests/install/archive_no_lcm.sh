#!/usr/bin/env bash
# install.archive_no_lcm: the archive needs no LCM. Installs a finished
# meshtopo build into a fresh prefix, then checks that
#  - meshtopo-archive.pc names no LCM (pkg-config --libs, and --static);
#  - the installed archive libraries (libmeshtopo-archive.a and .so, and
#    libmeshtopo-ident.a beneath it) hold no LCM symbol (lcm_*) and no
#    message type's (meshtopo_*_t), defined or referenced (nm);
#  - archive_io_main.c, built with pkg-config meshtopo-core meshtopo-io
#    meshtopo-archive only, needs no liblcm (readelf NEEDED, ldd, nm), and
#    runs (write, reload with the content hash checked) where liblcm cannot
#    be loaded: in a user and mount namespace (unshare -rm) with every
#    liblcm.so* file replaced by an empty file, which the installed meshtopod
#    is first shown not to start with. Without unshare, that run is skipped
#    (exit 77) once every other check has passed.
#
# usage: archive_no_lcm.sh BUILD_DIR WORK_DIR LIBDIR C_COMPILER [EXTRA_C_FLAGS]
set -euo pipefail

if [ $# -lt 4 ]; then
    echo "usage: $0 BUILD_DIR WORK_DIR LIBDIR C_COMPILER [EXTRA_C_FLAGS]" >&2
    exit 2
fi
build_dir=$1
work=$2
libdir=$3
cc=$4
extra_flags=${5:-}
here=$(cd "$(dirname "$0")" && pwd)
prefix=$work/prefix

step() { printf '\n-- %s\n' "$*"; }
fail() {
    echo "archive_no_lcm FAILED: $*" >&2
    exit 1
}
# LCM's symbols and lcm-gen's (meshtopo_mesh_t_encode, __meshtopo_mesh_t_get_hash, ...).
lcm_symbols='^_*(lcm_|meshtopo_[A-Za-z0-9_]+_t(_|$))'

rm -rf "$work"
mkdir -p "$work"
step "cmake --install $build_dir --prefix $prefix"
cmake --install "$build_dir" --prefix "$prefix" >"$work/install.log" ||
    { cat "$work/install.log"; fail "cmake --install failed"; }
export PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig"
export LD_LIBRARY_PATH="$prefix/$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

step "pkg-config meshtopo-archive"
for flags in --libs "--libs --static" --cflags; do
    # shellcheck disable=SC2086  # two flags in one word
    out=$(pkg-config $flags meshtopo-archive) || fail "pkg-config $flags meshtopo-archive failed"
    printf 'pkg-config %s meshtopo-archive: %s\n' "$flags" "$out"
    # A word naming LCM's library, headers or meshtopo-msgs (the prefix's path may say lcm).
    found=$(tr ' ' '\n' <<<"$out" | grep -E -- '^-l(lcm|meshtopo-msgs)$|/liblcm|/lcm(types)?$' || true)
    [ -z "$found" ] || fail "pkg-config $flags meshtopo-archive names LCM or meshtopo-msgs: $found"

done
requires=$(pkg-config --print-requires --print-requires-private meshtopo-archive)
printf 'meshtopo-archive requires: %s\n' "$(tr '\n' ' ' <<<"$requires")"
grep -Eq '^(lcm|lcm-java|glib-2\.0)( |$)' <<<"$requires" && fail "meshtopo-archive.pc requires LCM: $requires"

step "nm of the installed archive libraries"
libs=()
for f in "$prefix/$libdir"/libmeshtopo-archive.a "$prefix/$libdir"/libmeshtopo-archive.so \
    "$prefix/$libdir"/libmeshtopo-ident.a; do
    [ -e "$f" ] && libs+=("$(realpath "$f")")
done
[ ${#libs[@]} -gt 0 ] || fail "no libmeshtopo-archive installed in $prefix/$libdir"
for lib in "${libs[@]}"; do
    symbols=$(nm -P "$lib" 2>/dev/null | awk 'NF >= 2 && $2 != "a" {print $1}')
    if [[ $lib == *.so* ]]; then
        symbols+=$'\n'$(nm -D -P "$lib" | awk '{print $1}')
    fi
    [ -n "$symbols" ] || fail "nm found no symbols in $lib"
    found=$(grep -E "$lcm_symbols" <<<"$symbols" | sort -u || true)
    [ -z "$found" ] || fail "$lib has LCM symbols: $(tr '\n' ' ' <<<"$found")"
    printf '%s: %d symbols, none lcm_* or meshtopo_*_t\n' "$(basename "$lib")" \
        "$(sort -u <<<"$symbols" | wc -l)"
done

step "archive_io_main.c with pkg-config meshtopo-core meshtopo-io meshtopo-archive"
pcs="meshtopo-core meshtopo-io meshtopo-archive"
# shellcheck disable=SC2046,SC2086  # pkg-config output is meant to be word-split
"$cc" $extra_flags $(pkg-config --cflags $pcs) "$here/archive_io_main.c" \
    $(pkg-config --libs $pcs) -o "$work/archive_io" || fail "compiling archive_io_main.c failed"
needed=$(readelf -d "$work/archive_io" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
printf 'NEEDED: %s\n' "$(tr '\n' ' ' <<<"$needed")"
grep -q '^liblcm\.' <<<"$needed" && fail "archive_io needs liblcm directly"
loaded=$(ldd "$work/archive_io")
grep -q 'liblcm\.so' <<<"$loaded" && fail "archive_io loads liblcm: $loaded"
found=$(nm -P "$work/archive_io" | awk '{print $1}' | grep -E "$lcm_symbols" || true)
[ -z "$found" ] || fail "archive_io has LCM symbols: $(tr '\n' ' ' <<<"$found")"
echo "archive_io: no liblcm among the libraries it loads (ldd), no LCM symbol (nm)"
output=$("$work/archive_io") || fail "archive_io failed: $output"
printf '%s\n' "$output"
grep -qF "archive io ok" <<<"$output" || fail "archive_io: expected 'archive io ok'"

step "archive_io where liblcm cannot be loaded"
lcm_files=$(ldconfig -p | sed -n 's/^[[:space:]]*liblcm\.so[^ ]* .* => //p' | sort -u)
[ -n "$lcm_files" ] || fail "ldconfig knows no liblcm.so: nothing to hide (LCM is needed to build meshtopo)"
: >"$work/empty"
daemon=$prefix/bin/meshtopod
hidden_run() {
    # shellcheck disable=SC2016  # expanded by the inner shell
    unshare -rm sh -c 'empty=$1; shift; files=$1; shift
        for f in $files; do mount --bind "$empty" "$(realpath "$f")" || exit 90; done
        exec "$@"' sh "$work/empty" "$lcm_files" "$@"
}
if ! unshare -rm true 2>/dev/null; then
    echo "unshare -rm is not permitted here: the run without liblcm is skipped"
    exit 77
fi
if [ -x "$daemon" ]; then
    if daemon_out=$(hidden_run "$daemon" --version 2>&1); then
        fail "meshtopod started with liblcm hidden: the hiding does not work ($daemon_out)"
    fi
    printf 'meshtopod --version with liblcm hidden: %s\n' "$daemon_out"
    grep -q liblcm <<<"$daemon_out" || fail "meshtopod failed for another reason than liblcm"
fi
output=$(hidden_run "$work/archive_io" 2>&1) || fail "archive_io failed with liblcm hidden: $output"
printf '%s\n' "$output"
grep -qF "archive io ok" <<<"$output" || fail "archive_io with liblcm hidden: expected 'archive io ok'"

step "archive_no_lcm passed"
