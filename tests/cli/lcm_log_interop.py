#!/usr/bin/env python3
"""cli.lcm_log_interop: a session recorded with lcm-logger and played back
with lcm-logplayer into a fresh daemon yields the same archive as the live
session.

Run inside netns-run. Records every channel with Debian's lcm-logger while a
`meshtopod --archive DIR1` receives three corpus meshes from `meshtopo send`
(one id twice, so versions 1 and 2); stops both; starts a fresh
`meshtopod --archive DIR2`, plays the log into it with lcm-logplayer and
waits for its archive to fill; then compares `meshtopo archive ls --json` and
`meshtopo archive show --json` of the two archives: same ids, versions,
utimes, sources, content hashes and reports (file sizes and paths aside).
Exits 77 (skipped) while `meshtopod --help` does not offer --archive or when
lcm-logger / lcm-logplayer (Debian liblcm-bin) are missing.

usage: lcm_log_interop.py --meshtopo PATH --meshtopod PATH --corpus DIR
"""
import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SKIP = 77
CALL_TIMEOUT = 20
LCM_URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
PREFIX = "IOP_"
# (mesh id, corpus file): sent in this order during the live session.
SENT = [("m1", "cgal_tetrahedron.off"), ("m2", "vcg_nonmanifold.off"), ("m1", "cgal_prim.off")]
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        failures.append(what)
    return ok


def run(cmd, timeout=CALL_TIMEOUT):
    cmd = [str(a) for a in cmd]
    try:
        return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        check(False, f"`{' '.join(cmd)}` finished within {timeout} s")
        return None


def stop(proc, sig, what):
    """Stops a process this script started; returns its exit status."""
    proc.send_signal(sig)
    try:
        return proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        check(False, f"{what} stops within 10 s of signal {sig}")
        proc.kill()
        return proc.wait()


def start_daemon(meshtopod, archive, log):
    return subprocess.Popen([meshtopod, "--lcm-url", LCM_URL, "--prefix", PREFIX,
                             "--heartbeat-ms", "100", "--archive", archive],
                            stdout=subprocess.DEVNULL, stderr=log)


def wait_heartbeat(cli):
    p = run([cli, "watch", "--count", "1", "--timeout-ms", "10000"])
    return check(p is not None and p.returncode == 0, "meshtopod's heartbeat is seen")


def archive_state(cli, archive):
    """{(mesh id, version): (ls entry, show object)} with file-specific keys removed."""
    p = run([cli, "archive", "ls", archive, "--json"])
    if not check(p is not None and p.returncode == 0, f"archive ls {archive} exits 0"):
        return {}
    listing = json.loads(p.stdout)
    check(listing["unreadable"] == [], f"{archive}: no unreadable file ({listing['unreadable']})")
    state = {}
    for m in listing["meshes"]:
        key = (m["mesh_id"], m["version"])
        for k in ("file", "file_bytes"):
            m.pop(k, None)
        p = run([cli, "archive", "show", archive, m["mesh_id"], "--version", m["version"],
                 "--json"])
        shown = None
        if check(p is not None and p.returncode == 0, f"archive show {key} exits 0"):
            shown = json.loads(p.stdout)
            for k in ("archive", "file", "file_bytes"):
                shown.pop(k, None)
        state[key] = (m, shown)
    return state


def wait_archived(cli, archive, count, wait=15):
    deadline = time.monotonic() + wait
    while time.monotonic() < deadline:
        p = run([cli, "archive", "ls", archive, "--json"])
        if p is not None and p.returncode == 0 and len(json.loads(p.stdout)["meshes"]) >= count:
            return True
        time.sleep(0.2)
    return False


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--meshtopod", required=True)
    ap.add_argument("--corpus", default=os.environ.get("MESHTOPO_CORPUS"))
    args = ap.parse_args()
    if not args.corpus:
        ap.error("need --corpus or MESHTOPO_CORPUS")
    if os.environ.get("MESHTOPO_NETNS") != "1":
        print("run me through netns-run", file=sys.stderr)
        return 2
    for tool in ("lcm-logger", "lcm-logplayer"):
        if shutil.which(tool) is None:
            print(f"skipped: {tool} not found (Debian package liblcm-bin)")
            return SKIP
    p = run([args.meshtopod, "--help"])
    if p is None or "--archive" not in p.stdout + p.stderr:
        print("skipped: meshtopod --help does not offer --archive yet")
        return SKIP
    cli = args.meshtopo
    os.environ["MESHTOPO_LCM_URL"] = LCM_URL
    os.environ["MESHTOPO_PREFIX"] = PREFIX

    tmp = tempfile.mkdtemp(prefix="meshtopo-lcmlog-")
    live, played = os.path.join(tmp, "live"), os.path.join(tmp, "played")
    os.mkdir(live)
    os.mkdir(played)
    lcm_log = os.path.join(tmp, "session.lcmlog")
    daemon_log = open(os.path.join(tmp, "meshtopod.log"), "w", encoding="utf-8")
    logger = daemon = None
    acks = []
    try:
        # ---- the live session, recorded ------------------------------------
        logger = subprocess.Popen(["lcm-logger", "--lcm-url", LCM_URL, "--quiet", "--force",
                                   lcm_log], stdout=subprocess.DEVNULL, stderr=daemon_log)
        daemon = start_daemon(args.meshtopod, live, daemon_log)
        if not wait_heartbeat(cli):
            return 1
        # The logger is recording once heartbeats reach its file.
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and (
                not os.path.exists(lcm_log) or os.path.getsize(lcm_log) == 0):
            time.sleep(0.05)
        if not check(os.path.exists(lcm_log) and os.path.getsize(lcm_log) > 0,
                     "lcm-logger records the session"):
            return 1
        for mesh_id, name in SENT:
            p = run([cli, "send", os.path.join(args.corpus, name), "--id", mesh_id, "--json"])
            if check(p is not None and p.returncode == 0,
                     f"send {name} as {mesh_id} is acknowledged ({p and p.stderr.strip()})"):
                acks.append(json.loads(p.stdout))
        rc = stop(daemon, signal.SIGTERM, "meshtopod (live)")
        daemon = None
        check(rc == 0, f"the live meshtopod exits 0 (got {rc})")
        time.sleep(0.3)  # the logger's flush interval is 100 ms
        rc = stop(logger, signal.SIGINT, "lcm-logger")
        logger = None
        check(rc == 0, f"lcm-logger exits 0 (got {rc})")

        # ---- the log played back into a fresh daemon ------------------------
        daemon = start_daemon(args.meshtopod, played, daemon_log)
        if not wait_heartbeat(cli):
            return 1
        p = run(["lcm-logplayer", "--lcm-url", LCM_URL, lcm_log], timeout=40)
        check(p is not None and p.returncode == 0, "lcm-logplayer plays the log back")
        check(wait_archived(cli, played, len(SENT)),
              f"the fresh daemon archives {len(SENT)} meshes from the played-back log")
        time.sleep(0.5)  # anything more (a duplicate) would show in the comparison
        rc = stop(daemon, signal.SIGTERM, "meshtopod (played back)")
        daemon = None
        check(rc == 0, f"the played-back meshtopod exits 0 (got {rc})")

        # ---- the two archives ------------------------------------------------
        a, b = archive_state(cli, live), archive_state(cli, played)
        expect = {(k["mesh_id"], k["version"]) for k in acks}
        check(set(a) == expect == {("m1", 1), ("m2", 1), ("m1", 2)},
              f"the live archive holds what was acknowledged: {sorted(a)}")
        for ack in acks:
            key = (ack["mesh_id"], ack["version"])
            check(key in a and a[key][0]["content_hash"] == ack["content_hash"],
                  f"{key}: archived with the acknowledged content hash {ack['content_hash']}")
        check(sorted(a) == sorted(b), f"same ids and versions: {sorted(a)} vs {sorted(b)}")
        for key in sorted(set(a) & set(b)):
            check(a[key][0] == b[key][0], f"{key}: same ls entry (utime, source, content hash, "
                  f"summary): {a[key][0]} vs {b[key][0]}")
            check(a[key][1] is not None and a[key][1] == b[key][1],
                  f"{key}: same archived report (archive show --json)")
    finally:
        if daemon is not None:
            stop(daemon, signal.SIGTERM, "meshtopod")
        if logger is not None:
            stop(logger, signal.SIGINT, "lcm-logger")
        daemon_log.close()
        if failures:
            with open(daemon_log.name, encoding="utf-8", errors="replace") as f:
                print("meshtopod / lcm-logger log:\n" + f.read())
        shutil.rmtree(tmp, ignore_errors=True)

    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
