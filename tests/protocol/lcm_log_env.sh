# The common start of the lcm-logger tests (lcm_log_session.sh,
# lcm_log_replay.sh), sourced by them inside netns-run with $work (their
# directory, made afresh) and $here set: the LCM URL they all use, the
# session's files, stopping the daemon and the logger (by PID) on exit,
# fail, and the mesh they send. A window of chunks or answer parts is megabytes, which the kernel's
# default UDP receive buffer (about 200 KiB) would mostly drop at the logger:
# every process asks for 4 MiB in the URL, as the README's recording URL and
# scripts/demo-network.sh do (the kernel grants twice the request, capped at
# net.core.rmem_max, which is left alone).
echo "net.core.rmem_max $(cat /proc/sys/net/core/rmem_max)," \
    "net.core.rmem_default $(cat /proc/sys/net/core/rmem_default)"
url="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
export MESHTOPO_LCM_URL=$url LCM_DEFAULT_URL=$url
unset MESHTOPO_PREFIX

rm -rf "$work"
mkdir -p "$work" || exit 1
log=$work/session.lcmlog daemon_log=$work/meshtopod.log logger_log=$work/lcm-logger.log
logger_pid='' daemon_pid=''

. "$here/../netns/stop_pid.sh"
cleanup() {
    [ -n "$daemon_pid" ] && mt_stop_pid "$daemon_pid" TERM meshtopod
    [ -n "$logger_pid" ] && mt_stop_pid "$logger_pid" INT lcm-logger
}
trap cleanup EXIT

fail() {
    echo "FAIL: $*" >&2
    echo "meshtopod log (last 30 lines):" >&2
    tail -30 "$daemon_log" >&2
    exit 1
}

# A 316 x 316 grid of squares cut in two into the OFF file $1: 100,489
# vertices, 199,712 triangles, about 5.6 MB of content, so it travels as
# about 100 mesh_chunk_t datagrams.
write_grid_off() {
    awk -v n=317 'BEGIN {
        print "OFF"; print n * n, 2 * (n - 1) * (n - 1), 0
        for (j = 0; j < n; j++) for (i = 0; i < n; i++) printf "%d %d 0\n", i, j
        for (j = 0; j < n - 1; j++) for (i = 0; i < n - 1; i++) {
            a = j * n + i
            printf "3 %d %d %d\n3 %d %d %d\n", a, a + 1, a + n + 1, a, a + n + 1, a + n
        }
    }' >"$1" || fail "could not write the grid"
}
