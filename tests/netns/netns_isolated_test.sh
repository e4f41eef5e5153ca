#!/usr/bin/env bash
# netns.isolated: checks tests/netns/netns-run itself. Inside, only lo is up
# with the multicast route and nothing else is reachable; the host's links,
# routes and firewall are the same after a run (with --loss) as before; the
# inner setup refuses to run outside a namespace it made; the command's exit
# status comes back; bad options are refused. Exit 77 (skip) when this
# machine cannot create a network namespace.
# usage: netns_isolated_test.sh PATH/TO/netns-run
set -uo pipefail
run=$1
failures=0
fail() {
    echo "FAIL: $*" >&2
    failures=$((failures + 1))
}

bash "$run" true
status=$?
[ "$status" -eq 77 ] && exit 77
[ "$status" -eq 0 ] || { echo "FAIL: netns-run true exited $status" >&2; exit 1; }

# What netns-run would change if it ever ran its setup on the host: lo's
# flags, the multicast route, our nftables table. (Only these, so that other
# activity on a busy host does not make the comparison fail.)
host_state() {
    ip -o link show lo
    ip route show table all | grep -E '^(multicast )?224\.0\.0\.0/4' || true
    if command -v nft >/dev/null; then nft list tables 2>/dev/null | grep meshtopo || true; fi
}
before=$(host_state)

# Inside: lo up with multicast, the 224.0.0.0/4 route, no other interface up,
# no address but loopback ones, nothing routed to the outside.
inside=$(bash "$run" bash -c '
    set -u
    echo "netns=$MESHTOPO_NETNS"
    ip -o link show up | awk -F": " "{print \"up=\" \$2}"
    ip -o link show lo | grep -q MULTICAST && echo lo_multicast=yes
    ip -o addr show | awk "{print \"addr_dev=\" \$2}" | sort -u
    ip route show | grep -q "^224.0.0.0/4 dev lo" && echo mcast_route=yes
    ip route get 192.0.2.1 >/dev/null 2>&1 && echo outside=reachable || echo outside=unreachable
')
echo "$inside"
grep -qx 'netns=1' <<<"$inside" || fail "MESHTOPO_NETNS is not set inside"
[ "$(grep '^up=' <<<"$inside")" = "up=lo" ] || fail "interfaces other than lo are up inside"
grep -qx 'lo_multicast=yes' <<<"$inside" || fail "multicast is off on lo"
[ "$(grep '^addr_dev=' <<<"$inside")" = "addr_dev=lo" ] || fail "addresses on devices besides lo"
grep -qx 'mcast_route=yes' <<<"$inside" || fail "no route 224.0.0.0/4 dev lo"
grep -qx 'outside=unreachable' <<<"$inside" || fail "an outside address is routable inside"

# The exit status comes back; --loss sets up a rule and the host is untouched.
bash "$run" sh -c 'exit 7'
[ $? -eq 7 ] || fail "the command's exit status was not returned"
if command -v nft >/dev/null; then
    bash "$run" --loss 10 sh -c 'nft list ruleset | grep -q "numgen random mod 100 < 10"' ||
        fail "--loss 10 did not install its nftables rule"
fi

# The inner setup refuses the caller's own namespace (here: the host's).
out=$(bash "$run" --inside "$(stat -L -c %i /proc/self/ns/net)" 5 -- true 2>&1)
status=$?
[ "$status" -eq 2 ] || fail "--inside on the host namespace exited $status, expected 2"
grep -q 'refusing' <<<"$out" || fail "--inside on the host namespace did not say it refuses"

for bad in "--loss" "--loss 101" "--loss -3" "--loss abc" "--bogus true" ""; do
    # shellcheck disable=SC2086
    bash "$run" $bad >/dev/null 2>&1
    status=$?
    [ "$status" -eq 2 ] || fail "netns-run $bad exited $status, expected 2"
done

after=$(host_state)
[ "$before" = "$after" ] || {
    fail "the host's network changed"
    diff <(echo "$before") <(echo "$after") >&2
}

[ "$failures" -eq 0 ] && echo "netns.isolated: ok"
[ "$failures" -eq 0 ]
