#!/usr/bin/env bash
# Writes meshtopo's manual pages with help2man from the programs' own --help:
# meshtopo(1), meshtopo-COMMAND(1) for every command `meshtopo --help` lists
# (`meshtopo bench` runs meshtopo-bench, whose page is meshtopo-bench(1)),
# meshtopod(1) and, when built, meshtopo-bench(1); each compressed with
# gzip -9n into OUT_DIR/man1/. Run at build time by the meshtopo_man_pages
# target (cmake/MeshtopoManPages.cmake); packaging/README.md tells more.
#
# usage: man-pages.sh OUT_DIR VERSION MESHTOPO MESHTOPOD [MESHTOPO_BENCH]
#        man-pages.sh --run PROGRAM [ARGS...]
# The second form is what help2man runs: PROGRAM's output (stderr too) with
# its "usage:" lines spelled as help2man finds them ("Usage:", "   or:").
set -euo pipefail

# Sanitizer builds: a leak report at exit must not fail the build.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"

if [ "${1:-}" = --run ]; then
    shift
    set +e
    out=$("$@" 2>&1)
    status=$?
    set -e
    # "usage: prog ..." and the lines aligned under it ("       prog ...").
    printf '%s\n' "$out" | awk '
        /^usage: / { sub(/^usage: /, "Usage: "); in_usage = 1; print; next }
        in_usage && /^       [^ ]/ { sub(/^       /, "   or: "); print; next }
        { in_usage = 0; print }'
    exit "$status"
fi

if [ $# -lt 4 ]; then
    echo "usage: $0 OUT_DIR VERSION MESHTOPO MESHTOPOD [MESHTOPO_BENCH]" >&2
    exit 2
fi
out_dir=$1
version=$2
meshtopo=$3
meshtopod=$4
bench=${5:-}
self=$(cd "$(dirname "$0")" && pwd)/$(basename "$0")
man_dir=$out_dir/man1
work=$out_dir/work

fail() {
    echo "man-pages.sh: $*" >&2
    exit 1
}
command -v help2man >/dev/null || fail "help2man not found (Debian: apt-get install help2man)"
command -v gzip >/dev/null || fail "gzip not found"

rm -rf "$man_dir" "$work"
mkdir -p "$man_dir" "$work"

# The commands of `meshtopo --help`: the lines after "commands:" up to the
# first blank line, "  NAME  summary".
"$meshtopo" --help >"$work/meshtopo.help" || fail "$meshtopo --help failed"
commands=()
summaries=()
while IFS=$'\t' read -r name summary; do
    commands+=("$name")
    summaries+=("$summary")
done < <(awk '
    /^commands:$/ { listing = 1; next }
    listing && /^$/ { exit }
    listing { name = $1; sub(/^ *[^ ]+ +/, ""); print name "\t" $0 }' "$work/meshtopo.help")
[ ${#commands[@]} -gt 0 ] || fail "no commands found in $meshtopo --help"

# The page name of each command: meshtopo-NAME, except bench (meshtopo-bench).
pages=(meshtopo meshtopod)
for name in "${commands[@]}"; do
    if [ "$name" != bench ]; then pages+=("meshtopo-$name"); fi
done
if [ -n "$bench" ]; then pages+=(meshtopo-bench); fi

# SEE ALSO of every page: the other pages and the README.
see_also() {
    local this=$1 page first=1
    printf '[SEE ALSO]\n'
    for page in "${pages[@]}"; do
        if [ "$page" = "$this" ]; then continue; fi
        if [ $first -eq 0 ]; then printf ',\n'; fi
        printf '.BR %s (1)' "${page//-/\\-}"
        first=0
    done
    printf '\n.PP\nREADME.md in the documentation directory of meshtopo\n'
    printf '(/usr/share/doc/meshtopo in the Debian package) documents the library,\n'
    printf 'the daemon and every command in full.\n'
}

# page NAME SYNOPSIS_TEXT VERSION_OPTION_ARGS... -- PROGRAM ARGS...
# (the program is run with ARGS --help through --run).
page() {
    local name=$1 summary=$2
    shift 2
    local help2man_args=()
    while [ "$1" != -- ]; do
        help2man_args+=("$1")
        shift
    done
    shift
    local quoted="" arg
    for arg in "$@"; do quoted+=" $(printf '%q' "$arg")"; done
    "$@" --help >/dev/null 2>&1 || fail "$* --help failed"
    see_also "$name" >"$work/$name.include"
    if [ -f "$work/$name.extra" ]; then cat "$work/$name.extra" >>"$work/$name.include"; fi
    help2man --no-info --section=1 --name="$summary" --include="$work/$name.include" \
        --help-option="--run$quoted --help" "${help2man_args[@]}" \
        --output="$work/$name.1" "$self" ||
        fail "help2man failed for $name"
    gzip -9n <"$work/$name.1" >"$man_dir/$name.1.gz"
    echo "man page: $name(1)"
}

first_line=$(head -n 1 "$work/meshtopo.help")
page meshtopo "${first_line#meshtopo: }" --version-string="meshtopo $version" -- "$meshtopo"
page meshtopod "the meshtopo daemon: builds meshes submitted over LCM and answers queries" \
    --version-string="meshtopod $version" -- "$meshtopod"
for i in "${!commands[@]}"; do
    name=${commands[$i]}
    if [ "$name" = bench ]; then continue; fi
    page "meshtopo-$name" "${summaries[$i]}" --version-string="meshtopo-$name $version" \
        -- "$meshtopo" "$name"
done
if [ -n "$bench" ]; then
    # Its page is also meshtopo bench's: add the overview of `meshtopo help bench`.
    for i in "${!commands[@]}"; do
        if [ "${commands[$i]}" = bench ]; then bench_summary=${summaries[$i]}; fi
    done
    {
        printf '[COMMANDS]\n.nf\n'
        # The description of `meshtopo help bench`: what follows its usage and summary.
        "$meshtopo" help bench | awk 'blank >= 2 { print; next } /^$/ { blank++ }' |
            sed -e 's/\\/\\e/g' -e "s/^[.']/\\\\\&&/"
        printf '.fi\n'
    } >"$work/meshtopo-bench.extra"
    page meshtopo-bench "${bench_summary:-meshtopo benchmarks}" \
        --version-string="meshtopo-bench $version" -- "$bench"
fi
rm -rf "$work"
