#!/usr/bin/env bash
# meshtopo's full test suite (the README's test command; .ci/run calls it):
#   normal  in a copy of the checkout with nothing beside it (what `git clone`
#           gives, uncommitted changes included): the README's two commands
#           (scripts/install-deps.sh when run as root, scripts/demo.sh), then
#           a RelWithDebInfo build with -Werror and every ctest
#   asan    clang ASan+UBSan build (shared libraries), every ctest
#   tsan    clang ThreadSanitizer build: the core library's tests (builds run
#           on two threads), the readers' (large files are parsed on two
#           threads), the daemon's parts, the whole daemon in process
#           over memq:// (test_meshtopod*) and the client library
#   package the Debian packages of a static and of a shared build: lintian
#           clean, man pages and control fields (tests/install/package_check.sh),
#           then, as root with CI=true, installed with apt and checked in use,
#           then purged (tests/install/apt_install_check.sh)
#   fuzz    clang libFuzzer build, each fuzz target for FUZZ_SECONDS seconds
#   format  clang-format check of the C sources
# usage: scripts/test.sh [normal] [asan] [tsan] [package] [fuzz] [format]   (default: all)
# environment: FUZZ_SECONDS (default 60), MESHTOPO_BUILD_ROOT (default build/test),
#              MESHTOPO_CORPUS (a directory of more corpus meshes, added to
#              tests/corpus: cmake/MeshtopoCorpus.cmake).
# Every step runs even after one fails; the exit status is 1 if any failed.
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
build_root=${MESHTOPO_BUILD_ROOT:-$repo/build/test}
fuzz_seconds=${FUZZ_SECONDS:-60}
extra_corpus=${MESHTOPO_CORPUS:-}
unset MESHTOPO_CORPUS
jobs=$(nproc 2>/dev/null || echo 2)

header() {
    printf '\n'
    printf '=%.0s' {1..78}
    printf '\n== %s\n' "$*"
    printf '=%.0s' {1..78}
    printf '\n'
}

# configure_and_build DIR [SOURCE] -- CMAKE_ARGS...: SOURCE defaults to the checkout.
configure_and_build() {
    local dir=$1 source=$repo
    shift
    if [ "${1:-}" != -- ]; then
        source=$1
        shift
    fi
    shift
    # A tree configured from another source directory is laid anew.
    if [ -f "$dir/CMakeCache.txt" ] &&
        ! grep -qxF "CMAKE_HOME_DIRECTORY:INTERNAL=$source" "$dir/CMakeCache.txt"; then
        rm -rf "$dir"
    fi
    cmake -S "$source" -B "$dir" -G Ninja -DMESHTOPO_EXTRA_CORPUS="$extra_corpus" "$@"
    cmake --build "$dir" -j "$jobs"
}

# Lays into DIR the files a clone of this checkout would hold (the tracked
# ones and the new ones git does not ignore, as they are in the working
# tree), with nothing beside them. DIR/build (the demo's build) is kept.
lay_clone() {
    local dest=$1
    git -C "$repo" rev-parse --is-inside-work-tree >/dev/null 2>&1 ||
        { echo "$repo is not a git checkout: nothing to copy" >&2; return 1; }
    mkdir -p "$dest"
    find "$dest" -mindepth 1 -maxdepth 1 ! -name build -exec rm -rf {} +
    (
        cd "$repo"
        git ls-files -z --cached --others --exclude-standard --deduplicate |
            while IFS= read -r -d '' f; do [ -e "$f" ] && printf '%s\0' "$f"; done |
            tar --null -T - -cf -
    ) | tar -xf - -C "$dest"
}

# Every ctest of build DIR; then why each skipped test skipped (ctest shows
# the output of failed tests only, and counts the skipped in its summary).
run_ctest() {
    local rc=0
    ctest --test-dir "$1" --output-on-failure -j 2 || rc=$?
    local log=$1/Testing/Temporary/LastTest.log
    if [ -f "$log" ] && grep -q '^skipped: ' "$log"; then
        echo "-- why tests skipped (from $log):"
        grep -h '^skipped: ' "$log" | sort | uniq -c | sed 's/^/  /'
    fi
    return "$rc"
}

step_normal() {
    local clone=$build_root/clone/meshtopo dir=$build_root/normal
    lay_clone "$clone"
    echo "-- a copy of the checkout alone in $clone ($(find "$clone" -type f | wc -l) files)"
    [ ! -e "$clone/../shared" ] || { echo "$clone/../shared exists" >&2; return 1; }
    if [ "$(id -u)" -eq 0 ]; then
        echo "-- scripts/install-deps.sh (the README's first command)"
        bash "$clone/scripts/install-deps.sh" </dev/null >"$build_root/clone/install-deps.log" 2>&1 || {
            tail -n 40 "$build_root/clone/install-deps.log"
            echo "install-deps.sh failed" >&2
            return 1
        }
    else
        echo "-- scripts/install-deps.sh left out: not root"
    fi
    echo "-- scripts/demo.sh (the README's second command, building its own tree)"
    bash "$clone/scripts/demo.sh" >"$build_root/clone/demo.log" 2>&1 || {
        cat "$build_root/clone/demo.log"
        echo "demo failed" >&2
        return 1
    }
    echo "demo ran: $(grep -c '^\$ meshtopo' "$build_root/clone/demo.log") commands," \
        "output in $build_root/clone/demo.log"
    echo "-- the test suite, built from the copy"
    configure_and_build "$dir" "$clone" -- -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMESHTOPO_WERROR=ON
    run_ctest "$dir"
}

step_asan() {
    local dir=$build_root/asan
    command -v clang >/dev/null ||
        { echo "clang is not installed: run sudo scripts/install-deps.sh" >&2; return 1; }
    # clang: its UBSan also catches pointer arithmetic on NULL, and its -Werror
    # warnings complement gcc's from the normal build. -O1 keeps asserts (no
    # NDEBUG) and stays fast enough for the corpus tests.
    configure_and_build "$dir" -- -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
        -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
        -DMESHTOPO_SANITIZE=ON -DMESHTOPO_WERROR=ON -DBUILD_SHARED_LIBS=ON
    # HDF5 unloads its filter plugins at exit, and the Blosc plugin (LZ4
    # archives) takes with it the library holding Blosc's one-time global
    # buffers, which LeakSanitizer then reports as leaks of an unknown
    # module. Preloading that library keeps it, and them, reachable, as in
    # a normal run.
    # awk reads the whole list: quitting at the match would end ldconfig
    # with SIGPIPE, which pipefail turns into this step's failure.
    local blosc
    blosc=$(ldconfig -p | awk '/libblosc\.so\.1 / && !path {path = $NF} END {print path}')
    LD_PRELOAD=${blosc} \
        ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:check_initialization_order=1 \
        UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 run_ctest "$dir"
}

step_tsan() {
    local dir=$build_root/tsan
    command -v clang >/dev/null ||
        { echo "clang is not installed: run sudo scripts/install-deps.sh" >&2; return 1; }
    configure_and_build "$dir" -- -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_C_FLAGS="-fsanitize=thread" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" \
        -DMESHTOPO_BUILD_BENCH=OFF -DMESHTOPO_WERROR=ON
    # tests/tsan.supp: reports raised inside LCM and GLib, which are not
    # instrumented and synchronise with futexes TSan cannot see.
    TSAN_OPTIONS="halt_on_error=1 suppressions=$repo/tests/tsan.supp" \
        ctest --test-dir "$dir" --output-on-failure -j 2 \
        -R '^test_(core|io|daemon|client|meshtopod[a-z_]*)\.'
}

# Packages of one Release build (CMAKE_ARGS...) in DIR, checked, then
# installed with apt, checked and purged where apt_install_check.sh may
# (root and CI=true; it says why when it skips). The build tree is moved
# aside meanwhile, so nothing installed can fall back on a program or file
# of the build.
check_packages() {
    local dir=$1 rc=0
    shift
    configure_and_build "$dir" -- -DCMAKE_BUILD_TYPE=Release -DMESHTOPO_BUILD_TESTS=OFF "$@"
    rm -f "$dir"/*.deb
    cmake --build "$dir" -j "$jobs" --target package
    bash "$repo/tests/install/package_check.sh" "$dir"
    rm -rf "$dir.debs" "$dir.aside"
    mkdir -p "$dir.debs"
    cp "$dir"/*.deb "$dir.debs/"
    mv "$dir" "$dir.aside"
    bash "$repo/tests/install/apt_install_check.sh" "$dir.debs" || rc=$?
    mv "$dir.aside" "$dir"
    if [ "$rc" -eq 77 ]; then
        echo "(apt install check skipped, as it says above)"
    elif [ "$rc" -ne 0 ]; then
        return "$rc"
    fi
}

step_package() {
    echo "-- static libraries: meshtopo, libmeshtopo-dev, python3-meshtopo"
    check_packages "$build_root/pkg"
    echo
    echo "-- shared libraries: the same and the shared-library package"
    check_packages "$build_root/pkg-shared" -DBUILD_SHARED_LIBS=ON
}

# Seeds for one fuzz target: its committed regressions, tests/fuzz/seeds/<target>/
# if present, and for fuzz_read_<ext> the small meshes of tests/corpus of that
# format (one gzip-compressed too).
seed_corpus() {
    local target=$1 dir=$2 src
    mkdir -p "$dir"
    for src in "$repo/tests/fuzz/regressions/$target" "$repo/tests/fuzz/seeds/$target"; do
        if [ -d "$src" ]; then find "$src" -maxdepth 1 -type f -exec cp {} "$dir/" \;; fi
    done
    case $target in
    fuzz_read_*)
        local ext=${target#fuzz_read_} first=""
        local corpus=$repo/tests/corpus
        while IFS= read -r src; do
            cp "$src" "$dir/"
            [ -n "$first" ] || first=$src
        done < <(find "$corpus" -maxdepth 1 -name "*.$ext" -size -16k | sort)
        if [ -n "$first" ]; then gzip -c "$first" >"$dir/$(basename "$first").gz"; fi
        ;;
    esac
}

step_fuzz() {
    local dir=$build_root/fuzz
    command -v clang >/dev/null ||
        { echo "clang is not installed: run sudo scripts/install-deps.sh" >&2; return 1; }
    configure_and_build "$dir" -- -DCMAKE_C_COMPILER=clang \
        -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" \
        -DMESHTOPO_BUILD_FUZZERS=ON -DMESHTOPO_BUILD_TESTS=OFF -DMESHTOPO_BUILD_BENCH=OFF \
        -DMESHTOPO_WERROR=ON
    local targets=()
    mapfile -t targets < <(find "$dir/tests/fuzz" -maxdepth 1 -type f -name 'fuzz_*' -perm -u+x |
        sort)
    if [ ${#targets[@]} -eq 0 ]; then
        echo "no fuzz targets were built" >&2
        return 1
    fi
    echo "fuzzing ${#targets[@]} targets for ${fuzz_seconds}s each, $jobs at a time"
    local crashes=$dir/crashes logs=$dir/logs
    rm -rf "$crashes"
    mkdir -p "$crashes" "$logs"
    # Run the targets $jobs at a time; each is single-threaded. Each job
    # writes its exit status to a file: `wait PID` for a job that ended long
    # before can answer "not a child of this shell" once bash has dropped
    # the job's saved status.
    local names=() bin name
    for bin in "${targets[@]}"; do
        name=$(basename "$bin")
        seed_corpus "$name" "$dir/corpus/$name"
        mkdir -p "$crashes/$name"
        rm -f "$logs/$name.status"
        if "$bin" -max_total_time="$fuzz_seconds" -timeout=10 -rss_limit_mb=2048 \
            -print_final_stats=1 -artifact_prefix="$crashes/$name/" "$dir/corpus/$name" \
            >"$logs/$name.log" 2>&1; then
            echo 0
        else
            echo $?
        fi >"$logs/$name.status" &
        names+=("$name")
        while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do sleep 1; done
    done
    wait
    local failed=0
    for name in "${names[@]}"; do
        if [ "$(cat "$logs/$name.status" 2>/dev/null)" = 0 ]; then
            printf '%-24s ok   %s\n' "$name" "$(grep -m1 -o 'stat::number_of_executed_units: *[0-9]*' \
                "$logs/$name.log" | sed 's/.*: */runs: /')"
        else
            failed=1
            printf '%-24s FAILED (log: %s)\n' "$name" "$logs/$name.log"
            tail -n 40 "$logs/$name.log"
        fi
    done
    if [ "$failed" -ne 0 ] || [ -n "$(find "$crashes" -type f -print -quit)" ]; then
        echo
        echo "Crashing inputs (reproduce with: $dir/tests/fuzz/<target> FILE; once fixed, commit"
        echo "each into tests/fuzz/regressions/<target>/ so the normal build replays it):"
        find "$crashes" -type f | sed 's/^/  /'
        return 1
    fi
}

step_format() {
    command -v clang-format >/dev/null ||
        { echo "clang-format is not installed: run sudo scripts/install-deps.sh" >&2; return 1; }
    local files=()
    if git -C "$repo" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
        mapfile -t files < <(git -C "$repo" ls-files --cached --others --exclude-standard \
            '*.c' '*.h' | sed "s|^|$repo/|")
    else
        mapfile -t files < <(find "$repo" -path "$repo/build*" -prune -o \
            \( -name '*.c' -o -name '*.h' \) -type f -print)
    fi
    echo "clang-format --dry-run --Werror on ${#files[@]} files"
    [ ${#files[@]} -eq 0 ] || clang-format --dry-run --Werror "${files[@]}"
}

steps=("$@")
[ ${#steps[@]} -gt 0 ] || steps=(normal asan tsan package fuzz format)
for s in "${steps[@]}"; do
    case $s in
    normal | asan | tsan | package | fuzz | format) ;;
    *)
        echo "usage: $0 [normal] [asan] [tsan] [package] [fuzz] [format]" >&2
        exit 2
        ;;
    esac
done

declare -A titles=(
    [normal]="a copy alone: install-deps + demo, then RelWithDebInfo (-Werror) build + ctest"
    [asan]="clang ASan+UBSan build (shared libraries) + ctest"
    [tsan]="clang ThreadSanitizer build + core, daemon (parts and in process) and client ctests"
    [package]="Debian packages (static and shared): lintian, then apt install, use, purge"
    [fuzz]="libFuzzer build + ${fuzz_seconds}s per fuzz target"
    [format]="clang-format check"
)
passed=0
failed=0
summary=()
n=0
for s in "${steps[@]}"; do
    n=$((n + 1))
    header "[$n/${#steps[@]}] ${titles[$s]}"
    start=$SECONDS
    set +e
    (
        set -euo pipefail
        "step_$s"
    )
    rc=$?
    set -e
    took=$((SECONDS - start))
    if [ "$rc" -eq 0 ]; then
        passed=$((passed + 1))
        summary+=("$(printf 'PASS  %-7s %4ds  %s' "$s" "$took" "${titles[$s]}")")
    else
        failed=$((failed + 1))
        summary+=("$(printf 'FAIL  %-7s %4ds  %s' "$s" "$took" "${titles[$s]}")")
    fi
done

header "Summary"
printf '%s\n' "${summary[@]}"
echo "steps: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
