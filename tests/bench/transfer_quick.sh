#!/usr/bin/env bash
# bench.transfer_quick: `meshtopo bench transfer --quick` runs its whole
# course in the private network namespace it makes (daemon started and
# stopped, raw push, submissions at 0 % and, where nft exists, 5 % loss) and
# prints every row of its table with a positive figure; a usage error exits 2
# and a daemon that cannot start exits 1 with a reason. Timings are not
# judged here. Exit 77 (skip) where no namespace can be made.
# usage: transfer_quick.sh MESHTOPO
set -uo pipefail
meshtopo=$1
out=$(mktemp)
trap 'rm -f "$out" "$out.csv"' EXIT

fail() {
    echo "bench.transfer_quick: $*" >&2
    cat "$out" >&2
    exit 1
}

"$meshtopo" bench transfer --quick --csv "$out.csv" >"$out" 2>&1
rc=$?
[ "$rc" -eq 77 ] && { cat "$out"; exit 77; }
[ "$rc" -eq 0 ] || fail "exit status $rc, expected 0"
cat "$out"
rows="raw LCM push, 0% loss|submit end to end, 0% loss|of which the daemon's build|transfer part|of which the content hash|ratio transfer part / raw push"
expected=6
if command -v nft >/dev/null 2>&1; then
    rows="$rows|submit end to end, 5% loss|ratio 5% loss / 0% loss"
    expected=8
else
    grep -q "5% loss row skipped: nft" "$out" || fail "no nft, but no note that the 5% row was skipped"
fi
IFS='|' read -ra names <<<"$rows"
for row in "${names[@]}"; do
    grep -qF "| $row" "$out" || grep -qF "|   $row" "$out" || fail "row '$row' missing"
done
grep -Eq '\| (met|MISS) \|' "$out" || fail "no target marked met or MISS"
[ "$(wc -l <"$out.csv")" -eq $((expected + 1)) ] || fail "CSV: expected a header and $expected rows"
python3 - "$out.csv" <<'PY' || fail "CSV holds a figure that is not positive"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
sys.exit(0 if rows and all(float(r["median"]) > 0 for r in rows) else 1)
PY

"$meshtopo" bench transfer --no-such-option >"$out" 2>&1
rc=$?
[ "$rc" -eq 2 ] || fail "unknown option: exit $rc, expected 2"
grep -q "unknown option --no-such-option" "$out" || fail "unknown option not named"

"$meshtopo" bench transfer --quick --daemon /nonexistent/meshtopod >"$out" 2>&1
rc=$?
[ "$rc" -eq 77 ] && exit 77
[ "$rc" -eq 1 ] || fail "missing daemon: exit $rc, expected 1"
grep -q "no heartbeat from /nonexistent/meshtopod" "$out" || fail "missing daemon not named"
exit 0
