#!/usr/bin/env bash
# bench.cluster_quick: `meshtopo bench cluster --quick` runs its whole course
# in the private network namespace it makes (members started and stopped,
# two pairs of 1- and 2-member runs, two members killed) and prints the
# throughput table, the ratio and the failover time, each positive; a usage
# error exits 2. Timings are not judged here. Exit 77 (skip) where no
# namespace can be made.
# usage: cluster_quick.sh MESHTOPO
set -uo pipefail
meshtopo=$1
out=$(mktemp)
trap 'rm -f "$out"' EXIT
fail() {
    echo "bench.cluster_quick: $*" >&2
    cat "$out" >&2
    exit 1
}
"$meshtopo" bench cluster --quick >"$out" 2>&1
rc=$?
[ "$rc" -eq 77 ] && { cat "$out"; exit 77; }
[ "$rc" -eq 0 ] || fail "exit status $rc, expected 0"
cat "$out"
grep -Eq '^\| 1 \| [0-9.]*[1-9][0-9.]* \|' "$out" || fail "no positive 1-member throughput"
grep -Eq '^\| 2 \| [0-9.]*[1-9][0-9.]* \|' "$out" || fail "no positive 2-member throughput"
grep -Eq 'paired ratios: [0-9.]+x \(target >= 1.8x: (met|MISSED)\)' "$out" || fail "no ratio line"
grep -Eq 'failover, .*: median [1-9][0-9]* ms' "$out" || fail "no failover time"
"$meshtopo" bench cluster --no-such-option >"$out" 2>&1
[ $? -eq 2 ] || fail "an unknown option did not exit 2"
exit 0
