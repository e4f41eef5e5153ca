# Sourced by the netns test scripts: mt_stop_pid PID SIGNAL NAME stops a
# process the script started, by its PID only: SIGNAL, then SIGKILL if it
# still runs 10 s later. Returns the process's exit status (wait).
mt_stop_pid() {
    local pid=$1 sig=$2 name=$3
    kill "-$sig" "$pid" 2>/dev/null
    for _ in $(seq 100); do
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.1
    done
    if kill -0 "$pid" 2>/dev/null; then
        echo "$name (pid $pid) still runs 10 s after SIG$sig: SIGKILL" >&2
        kill -KILL "$pid" 2>/dev/null
    fi
    wait "$pid"
}
