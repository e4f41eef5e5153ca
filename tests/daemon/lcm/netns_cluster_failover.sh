#!/usr/bin/env bash
# daemon.cluster_failover, run inside netns-run: three members of a cluster
# over a temporary shared archive; meshtopod_cluster_client kills one with
# SIGKILL at a random instant of a stream of submissions and queries, ten
# times, starting a new member after each (see its "chaos" mode), then every
# acknowledged version is queried and the archive is verified.
# usage: netns_cluster_failover.sh MESHTOPOD CLUSTER_CLIENT MESHTOPO
set -uo pipefail
meshtopod=$1 client=$2 meshtopo=$3
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir "$dir/archive" "$dir/logs"
if ! "$client" chaos "$meshtopod" "$dir/archive" "$dir/logs" 3 10 300; then
    for f in "$dir"/logs/*.log; do echo "== $f" >&2; tail -20 "$f" >&2; done
    echo "FAIL: the chaos rounds failed" >&2
    exit 1
fi
"$meshtopo" archive verify "$dir/archive" >"$dir/verify.txt" 2>&1 || {
    tail -20 "$dir/verify.txt" >&2
    echo "FAIL: archive verify on the shared directory" >&2
    exit 1
}
echo "archive verify: $(tail -1 "$dir/verify.txt")"
