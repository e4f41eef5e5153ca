#!/usr/bin/env bash
# daemon.large_ack, run inside netns-run at LCM's default receive buffer (no
# recv_buf_size, as the README's shell example runs): a triangle soup of
# 100,000 separate triangles (100,000 components and boundary loops, so its
# report needs many datagrams) is sent 20 times with meshtopo send; every
# send must be acknowledged with the next version (the ack travels in
# reply_part_t pieces). The topology broadcasts (best effort: a watcher's
# socket also receives every chunk on the group) must be cut to one
# datagram: those meshtopo watch gets list fewer loops than they count.
# usage: netns_large_ack.sh MESHTOPOD MESHTOPO
set -uo pipefail
meshtopod=$1 meshtopo=$2
[ "${MESHTOPO_NETNS:-}" = 1 ] || { echo "run me through netns-run" >&2; exit 2; }
source "$(dirname "$0")/../../netns/stop_pid.sh"
unset LCM_DEFAULT_URL MESHTOPO_LCM_URL
dir=$(mktemp -d)
daemon_pid="" watch_pid=""
cleanup() {
    [ -n "$watch_pid" ] && mt_stop_pid "$watch_pid" TERM "meshtopo watch" >/dev/null 2>&1
    [ -n "$daemon_pid" ] && mt_stop_pid "$daemon_pid" TERM meshtopod >/dev/null 2>&1
    rm -rf "$dir"
}
trap cleanup EXIT
fail() {
    echo "FAIL: $*" >&2
    tail -30 "$dir/daemon.log" >&2
    exit 1
}

python3 - "$dir/soup.off" <<'PY'
import random, sys
n = 100000
rnd = random.Random(7)
with open(sys.argv[1], "w") as f:
    f.write(f"OFF\n{3 * n} {n} 0\n")
    for t in range(n):
        x, y, z = rnd.random() * 100, rnd.random() * 100, rnd.random() * 100
        f.write(f"{x:.4f} {y:.4f} {z:.4f}\n{x + 0.1:.4f} {y:.4f} {z:.4f}\n{x:.4f} {y + 0.1:.4f} {z:.4f}\n")
    for t in range(n):
        f.write(f"3 {3 * t} {3 * t + 1} {3 * t + 2}\n")
PY

"$meshtopod" --heartbeat-ms 100 --workers 2 2>"$dir/daemon.log" &
daemon_pid=$!
"$meshtopo" watch --count 1 --timeout-ms 10000 >/dev/null || fail "no heartbeat"
"$meshtopo" watch --json --timeout-ms 30000 >"$dir/watch.jsonl" 2>/dev/null &
watch_pid=$!

acked=0
start=$(date +%s%N)
for i in $(seq 20); do
    if ! "$meshtopo" send "$dir/soup.off" --id soup --json >"$dir/ack.json" 2>"$dir/send.err"; then
        cat "$dir/send.err" >&2
        fail "send $i was not acknowledged"
    fi
    python3 - "$dir/ack.json" "$i" <<'PY' || fail "send $i: wrong acknowledgement"
import json, sys
ack = json.load(open(sys.argv[1]))
def find(o, key):
    if isinstance(o, dict):
        if key in o: return o[key]
        for v in o.values():
            r = find(v, key)
            if r is not None: return r
    return None
version, comps = find(ack, "version"), find(ack, "connected_components")
assert version == int(sys.argv[2]), f"version {version}, expected {sys.argv[2]}"
assert comps == 100000, f"{comps} components"
PY
    acked=$((acked + 1))
done
took_ms=$((($(date +%s%N) - start) / 1000000))
echo "20 sends of a 100,000-triangle soup: $acked acknowledged in $took_ms ms"
sleep 0.5
python3 - "$dir/watch.jsonl" <<'PY' || fail "topology broadcasts"
import json, sys
seen = 0
for line in open(sys.argv[1]):
    m = json.loads(line)
    if m["type"] != "topology_t": continue
    t = m["message"]
    loops = t["boundary_loops"]
    assert loops["count"] == 100000, f"{loops['count']} loops"
    assert 0 < len(loops["lengths"]) < 100000, f"{len(loops['lengths'])} loop lengths listed"
    seen += 1
assert seen >= 1, "no topology broadcast arrived"
print(f"meshtopo watch got {seen} of 20 topology broadcasts, each cut to one datagram")
PY
