#!/usr/bin/env bash
# bench.rtt_quick: `meshtopo bench rtt --quick` runs its whole course in the
# private network namespace it makes (daemon started and stopped, ping-pong,
# checked query answers, throughput runs) and prints every row of its table;
# a usage error exits 2 and a daemon that cannot start exits 1 with a reason.
# Timings are not judged here. Exit 77 (skip) where no namespace can be made.
# usage: rtt_quick.sh MESHTOPO
set -uo pipefail
meshtopo=$1
out=$(mktemp)
trap 'rm -f "$out" "$out.csv"' EXIT

fail() {
    echo "bench.rtt_quick: $*" >&2
    cat "$out" >&2
    exit 1
}

"$meshtopo" bench rtt --quick --csv "$out.csv" >"$out" 2>&1
rc=$?
[ "$rc" -eq 77 ] && { cat "$out"; exit 77; }
[ "$rc" -eq 0 ] || fail "exit status $rc, expected 0"
for row in "p50 raw LCM ping-pong" "p50 one-ring query" "p50 ratio query / raw" \
    "p99 ratio query / raw" "single-id queries, 4 clients" "batches of 100, 4 clients"; do
    grep -qF "| $row" "$out" || grep -qF "$row" "$out" || fail "row '$row' missing"
done
grep -q "daemon.*private network namespace" "$out" || fail "no mention of the daemon start"
[ "$(wc -l <"$out.csv")" -eq 9 ] || fail "CSV: expected a header and 8 rows"
# Every figure is a positive number.
python3 - "$out.csv" <<'PY' || fail "CSV holds a figure that is not positive"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
sys.exit(0 if len(rows) == 8 and all(float(r["median"]) > 0 for r in rows) else 1)
PY

"$meshtopo" bench rtt --no-such-option >"$out" 2>&1
rc=$?
[ "$rc" -eq 2 ] || fail "unknown option: exit $rc, expected 2"
grep -q "unknown option --no-such-option" "$out" || fail "unknown option not named"

"$meshtopo" bench rtt --quick --daemon /nonexistent/meshtopod >"$out" 2>&1
rc=$?
[ "$rc" -eq 77 ] && exit 77
[ "$rc" -eq 1 ] || fail "missing daemon: exit $rc, expected 1"
grep -q "no heartbeat from /nonexistent/meshtopod" "$out" || fail "missing daemon not named"
exit 0
