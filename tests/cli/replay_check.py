#!/usr/bin/env python3
"""cli.replay: `meshtopo replay` against a real meshtopod over LCM.

Run inside netns-run. Writes an archive with replay_fixture (small corpus
meshes with chosen utimes 0.5 s apart and two sources), then: the error exits
before any daemon runs (missing archive 3, bad options 2, no daemon 6); starts
meshtopod (prefix RPL_, explicit udpm URL), waits for its heartbeat, watches
its TOPOLOGY reports; replays everything fast and checks every mesh is
acknowledged in utime order with the archived content hash (also against
`meshtopo archive ls --json`) and arrives with its archived source; --ids and
--since/--until subsets; spacing at --rate 1 and 2 measured from the replay's
--json send times; --channel; the progress line on a terminal and silence in
pipes; an unreadable file and a wrong archived hash (exit 3, others still
replayed); the same file marked archive format 2 (a former kind of hash),
checked against the hash of its face list instead (exit 0). Stops the daemon
by its PID and expects exit 0.

usage: replay_check.py --meshtopo PATH --meshtopod PATH --fixture PATH --corpus DIR
"""
import argparse
import json
import os
import pty
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

CALL_TIMEOUT = 30
LCM_URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
PREFIX = "RPL_"
T0 = 1795334400000000  # 2026-11-22T08:00:00Z
failures = []

# (mesh id, archived version, utime offset in us, source, corpus file)
ARCHIVED = [
    ("tet", 1, 0, "lidar_a", "cgal_tetrahedron.off"),
    ("eight", 4, 500000, "lidar_b", "vcg_quad5.off"),
    ("tet", 2, 1000000, "lidar_a", "vcg_nonmanifold.off"),
    ("prim", 1, 1500000, "stereo_left", "cgal_prim.off"),
]


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


def replay(cli, archive, *args):
    """Runs replay --json; returns (process, list of result objects)."""
    p = run([cli, "replay", archive, "--json", *args])
    if p is None:
        return None, []
    lines = []
    for line in p.stdout.splitlines():
        try:
            lines.append(json.loads(line))
        except json.JSONDecodeError as e:
            check(False, f"replay --json line is JSON ({e}): {line!r}")
    return p, lines


def make_archive(fixture, corpus, directory, rows, wrong_hash=None):
    for mesh_id, version, offset, source, name in rows:
        cmd = [fixture, directory, mesh_id, version, T0 + offset, source,
               os.path.join(corpus, name)]
        if wrong_hash and mesh_id == wrong_hash:
            cmd.append("0123456789abcdef")
        p = run(cmd)
        if not check(p is not None and p.returncode == 0,
                     f"replay_fixture archives {mesh_id} v{version} ({p and p.stderr.strip()})"):
            return False
    return True


def run_on_pty(cmd, timeout=CALL_TIMEOUT):
    """Runs cmd with stderr on a pseudo-terminal; returns (rc, stderr text)."""
    master, slave = pty.openpty()
    proc = subprocess.Popen([str(a) for a in cmd], stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    out = b""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        r, _, _ = select.select([master], [], [], 0.1)
        if r:
            try:
                chunk = os.read(master, 4096)
            except OSError:
                break
            if not chunk:
                break
            out += chunk
        elif proc.poll() is not None:
            break
    os.close(master)
    try:
        rc = proc.wait(timeout=5)
    except subprocess.TimeoutExpired:
        proc.kill()
        rc = proc.wait()
    return rc, out.decode("utf-8", "replace")


def check_errors_without_daemon(cli, archive, tmp):
    p = run([cli, "replay", os.path.join(tmp, "no-such-archive")])
    check(p is not None and p.returncode == 3 and "no-such-archive" in p.stderr,
          f"a missing archive exits 3 naming it (got {p and p.returncode}: {p and p.stderr.strip()})")
    notdir = os.path.join(tmp, "plain-file")
    with open(notdir, "w", encoding="utf-8") as f:
        f.write("not an archive\n")
    p = run([cli, "replay", notdir])
    check(p is not None and p.returncode == 3, f"a file instead of a directory exits 3 "
          f"(got {p and p.returncode})")
    for bad in (["--rate", "-1"], ["--rate", "fast"], ["--rate", "nan"], ["--rate", "1e-300"],
                ["--since", "yesterday"], ["--until", "2026-13-01T00:00:00Z"],
                ["--since", "2026-02-29T00:00:00Z"],
                ["--since", "2026-11-22T08:00:01Z", "--until", "2026-11-22T08:00:00Z"],
                ["--ids", "tet,nosuch"], ["--ids", ""],
                ["--channel", "X_SUBMIT", "--prefix", "X_"],
                ["--channel", "THIS_PREFIX_IS_FAR_TOO_LONG_FOR_LCM_SUBMIT"],
                ["--as-fast-as-possible", "--rate", "2"], ["--no-such-option"]):
        p = run([cli, "replay", archive, *bad])
        check(p is not None and p.returncode == 2 and p.stderr.strip() != "",
              f"replay {' '.join(bad)} is a usage error (2) with a message "
              f"(got {p and p.returncode})")
    p = run([cli, "replay"])
    check(p is not None and p.returncode == 2, "replay without DIR exits 2")

    t = time.monotonic()
    p, lines = replay(cli, archive, "--rate", "0", "--timeout-ms", "200", "--retries", "0")
    check(p is not None and p.returncode == 6 and len(lines) == 1 and
          lines[0]["status"] == "NO_ANSWER" and "RPL_" in p.stderr,
          f"replay without a daemon exits 6 after the first mesh (got {p and p.returncode}, "
          f"{len(lines)} lines: {p and p.stderr.strip()})")
    check(time.monotonic() - t < 10, "replay without a daemon gives up promptly")

    p = run([cli, "replay", "--help"])
    check(p is not None and p.returncode == 0 and p.stdout.startswith("usage: meshtopo replay") and
          "--since" in p.stdout and "2026-11-22T08:00:00Z" in p.stdout and
          "--as-fast-as-possible" in p.stdout, "replay --help documents the options and times")


class Watcher:
    """`meshtopo watch --json` read by a thread that stamps each line with the
    time it arrived (monotonic seconds): the daemon's TOPOLOGY reports as the
    test sees them, independent of the replay's own clock."""

    def __init__(self, cli):
        self.proc = subprocess.Popen([cli, "watch", "--json", "--timeout-ms", "60000"],
                                     stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        self.lines = []  # (arrival time, message object)
        self.lock = threading.Lock()
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self):
        for line in self.proc.stdout:
            msg = json.loads(line)
            with self.lock:
                self.lines.append((time.monotonic(), msg))

    def count(self):
        with self.lock:
            return len(self.lines)

    def topologies(self, keys, wait=5):
        """{(mesh id, version): (arrival time, topology message)} for keys."""
        deadline = time.monotonic() + wait
        seen = {}
        while time.monotonic() < deadline:
            with self.lock:
                for t, msg in self.lines:
                    m = msg["message"]
                    if msg["type"] == "topology_t" and (m["mesh_id"], m["version"]) in keys:
                        seen[(m["mesh_id"], m["version"])] = (t, m)
            if len(seen) == len(keys):
                break
            time.sleep(0.05)
        return seen

    def stop(self):
        self.proc.send_signal(signal.SIGINT)
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        self.thread.join(timeout=5)
        return self.proc.returncode


def expected_order(rows):
    return [(r[0], r[1]) for r in sorted(rows, key=lambda r: (r[2], r[0], r[1]))]


def check_full_replay(cli, archive, watcher):
    listed = json.loads(run([cli, "archive", "ls", archive, "--json"]).stdout)["meshes"]
    hashes = {(m["mesh_id"], m["version"]): m["content_hash"] for m in listed}
    p, lines = replay(cli, archive, "--rate", "100")
    if not check(p is not None and p.returncode == 0,
                 f"replay --rate 100 exits 0 (got {p and p.returncode}: {p and p.stderr})"):
        return
    check(p.stderr == "", f"no progress or other output on stderr in a pipe (got {p.stderr!r})")
    got = [(l["mesh_id"], l["original_version"]) for l in lines]
    check(got == expected_order(ARCHIVED), f"every mesh replayed once in utime order: {got}")
    for l in lines:
        key = (l["mesh_id"], l["original_version"])
        check(l["status"] == "OK" and l["hash_match"] is True and
              l["content_hash"] == hashes[key] == l["archived_content_hash"] and
              isinstance(l["version"], int) and l["version"] >= 1,
              f"{key} acknowledged as version {l['version']} with the archived content hash "
              f"{hashes[key]} (got {l['content_hash']})")
        exp_sched = (l["utime"] - T0) // 100
        check(abs(l["scheduled_us"] - exp_sched) <= 1 and l["sent_us"] >= l["scheduled_us"] - 1000,
              f"{key} scheduled at {exp_sched} us at rate 100, sent at {l['sent_us']} us")
    tet = [l["version"] for l in lines if l["mesh_id"] == "tet"]
    check(len(tet) == 2 and tet[1] == tet[0] + 1, f"tet's two versions become consecutive new "
          f"versions {tet}")

    # The daemon saw each submission with its archived source.
    sources = {(r[0], r[1]): r[3] for r in ARCHIVED}
    new_to_old = {(l["mesh_id"], l["version"]): (l["mesh_id"], l["original_version"])
                  for l in lines}
    seen = {k: m["source"] for k, (_, m) in watcher.topologies(new_to_old).items()}
    for new, old in new_to_old.items():
        check(seen.get(new) == sources[old], f"TOPOLOGY of {new} carries the archived source "
              f"{sources[old]!r} (got {seen.get(new)!r})")

    # Text output: one line per mesh naming both versions and the hash verdict.
    p = run([cli, "replay", archive, "--as-fast-as-possible", "--ids", "prim"])
    check(p is not None and p.returncode == 0 and len(p.stdout.splitlines()) == 1 and
          p.stdout.startswith("prim version 1 -> version ") and "matches the archive" in p.stdout,
          f"text output is one line per mesh (got {p and p.stdout!r})")


def check_subsets(cli, archive):
    p, lines = replay(cli, archive, "--rate", "0", "--ids", "prim,eight")
    check(p is not None and p.returncode == 0 and
          [(l["mesh_id"], l["original_version"]) for l in lines] == [("eight", 4), ("prim", 1)],
          f"--ids prim,eight replays exactly those, in utime order "
          f"{[(l['mesh_id'], l['original_version']) for l in lines]}")
    p, lines = replay(cli, archive, "--rate", "0", "--ids", "tet")
    check(p is not None and p.returncode == 0 and
          [(l["mesh_id"], l["original_version"]) for l in lines] == [("tet", 1), ("tet", 2)],
          "--ids tet replays both archived versions of tet")
    # since inclusive, until exclusive; ISO and microseconds mixed.
    p, lines = replay(cli, archive, "--rate", "0", "--since", "2026-11-22T08:00:00.5Z",
                      "--until", str(T0 + 1500000))
    check(p is not None and p.returncode == 0 and
          [(l["mesh_id"], l["original_version"]) for l in lines] == [("eight", 4), ("tet", 2)],
          f"--since 08:00:00.5Z --until T0+1.5s selects eight v4 and tet v2 "
          f"{[(l['mesh_id'], l['original_version']) for l in lines]}")
    p, lines = replay(cli, archive, "--rate", "0", "--since", str(T0 + 1000001))
    check(p is not None and p.returncode == 0 and
          [(l["mesh_id"], l["original_version"]) for l in lines] == [("prim", 1)],
          "--since in microseconds selects what is at or after it")
    p, lines = replay(cli, archive, "--rate", "0", "--until", "2026-11-22T08:00:00+00:00")
    check(p is not None and p.returncode == 0 and lines == [] and "nothing" in p.stderr,
          "--until the first utime selects nothing, says so and exits 0")
    p, lines = replay(cli, archive, "--rate", "0", "--ids", "tet", "--since",
                      "2026-11-22T08:00:00.000001Z")
    check(p is not None and [(l["mesh_id"], l["original_version"]) for l in lines] == [("tet", 2)],
          "--ids and --since combine")


def check_spacing(cli, archive, watcher):
    for rate, gap in (("1", 500000), ("2", 250000)):
        p, lines = replay(cli, archive, "--rate", rate, "--until", str(T0 + 600000))
        if not check(p is not None and p.returncode == 0 and len(lines) == 2,
                     f"--rate {rate} --until T0+0.6s replays two meshes"):
            continue
        sent_gap = lines[1]["sent_us"] - lines[0]["sent_us"]
        check(lines[1]["scheduled_us"] == gap, f"--rate {rate}: second mesh scheduled "
              f"{gap} us after the first (got {lines[1]['scheduled_us']})")
        check(sent_gap >= gap * 0.9, f"--rate {rate}: meshes {gap / 1e6:.2f} s apart are sent "
              f">= {gap * 0.9 / 1e6:.3f} s apart (got {sent_gap / 1e6:.3f} s)")
        # Independently of the replay's clock: when the daemon's TOPOLOGY
        # reports of the two builds reached the watcher.
        keys = [(l["mesh_id"], l["version"]) for l in lines]
        seen = watcher.topologies(keys)
        if check(len(seen) == 2, f"--rate {rate}: the daemon reported both builds"):
            seen_gap = seen[keys[1]][0] - seen[keys[0]][0]
            check(seen_gap >= gap * 0.9 / 1e6, f"--rate {rate}: their TOPOLOGY reports arrive "
                  f">= {gap * 0.9 / 1e6:.3f} s apart (got {seen_gap:.3f} s)")


def check_channel(cli, archive):
    for channel in (PREFIX + "SUBMIT", PREFIX):
        p, lines = replay(cli, archive, "--rate", "0", "--ids", "eight", "--channel", channel)
        check(p is not None and p.returncode == 0 and len(lines) == 1 and
              lines[0]["status"] == "OK", f"--channel {channel} reaches the daemon")
    p, lines = replay(cli, archive, "--rate", "0", "--ids", "eight", "--channel",
                      "NOBODY_SUBMIT", "--timeout-ms", "200", "--retries", "0")
    check(p is not None and p.returncode == 6 and "NOBODY_" in p.stderr,
          f"--channel NOBODY_SUBMIT gets no answer (6) (got {p and p.returncode})")


def check_progress(cli, archive):
    rc, err = run_on_pty([cli, "replay", archive, "--rate", "0"])
    check(rc == 0 and f"replay {len(ARCHIVED)}/{len(ARCHIVED)} meshes" in err and
          "elapsed" in err and "\r" in err and err.count("\n") <= 2,
          f"on a terminal stderr shows one progress line (got {err!r})")
    rc, err = run_on_pty([cli, "replay", archive, "--rate", "0", "--quiet"])
    check(rc == 0 and "meshes" not in err, f"--quiet: no progress line (got {err!r})")


def check_bad_files(cli, fixture, corpus, tmp):
    bad = os.path.join(tmp, "bad-archive")
    if not make_archive(fixture, corpus, bad, ARCHIVED, wrong_hash="prim"):
        return
    with open(os.path.join(bad, "junk.v1.hdf"), "wb") as f:
        f.write(b"this is not HDF5\n" * 10)
    p, lines = replay(cli, bad, "--rate", "0")
    if not check(p is not None, "replay of a damaged archive finishes"):
        return
    check(p.returncode == 3, f"an unreadable file and a wrong hash exit 3 (got {p.returncode})")
    check("junk.v1.hdf" in p.stderr, f"the unreadable file is named on stderr ({p.stderr!r})")
    unreadable = [l for l in lines if l.get("status") == "UNREADABLE"]
    check(len(unreadable) == 1 and unreadable[0]["file"] == "junk.v1.hdf" and
          unreadable[0]["error"], "--json lists the unreadable file with its error")
    done = [l for l in lines if l.get("status") == "OK"]
    check(len(done) == len(ARCHIVED), f"the other {len(ARCHIVED)} meshes are still replayed "
          f"(got {len(done)})")
    prim = [l for l in done if l["mesh_id"] == "prim"]
    check(len(prim) == 1 and prim[0]["hash_match"] is False and
          prim[0]["archived_content_hash"] == "0123456789abcdef" and
          prim[0]["content_hash"] != "0123456789abcdef",
          "a wrong archived hash is reported as a mismatch")
    check(all(l["hash_match"] for l in done if l["mesh_id"] != "prim"),
          "the others match their archived hashes")
    p = run([cli, "replay", bad, "--rate", "0", "--ids", "prim"])
    check(p is not None and p.returncode == 3 and "DIFFERS" in p.stdout and
          "prim.v1.hdf" in p.stderr, f"text output flags the differing hash "
          f"({p and p.stdout.strip()} / {p and p.stderr.strip()})")
    # The same file marked as archive format 2, whose content hash is of the
    # former kind: the ack is checked against the hash of what was sent. Its
    # defects become the {kind, a, b, c} rows formats before 7 stored.
    # (h5py is Debian's python3-h5py, for the system python.)
    mark = ("import sys, h5py, numpy as np\n"
            "with h5py.File(sys.argv[1], 'r+') as f:\n"
            "    a = f['meshtopo'].attrs\n"
            "    kind = a['format_version'].dtype\n"
            "    del a['format_version']\n"
            "    a.create('format_version', 2, dtype=kind)\n"
            "    d = f['meshtopo/report/defects']\n"
            "    enum = d.dtype['kind']\n"
            "    key = {v: k for k, v in h5py.check_enum_dtype(enum).items()}\n"
            "    abc = {'out_of_range_index': lambda r: (r['faces'][0], r['index'] & 0xFFFFFFFF, r['position']),\n"
            "           'degenerate_face': lambda r: (r['faces'][0], r['distinct_vertices'], r['face_size']),\n"
            "           'duplicate_face': lambda r: (r['faces'][0], r['faces'][1], 0),\n"
            "           'nonmanifold_edge': lambda r: (r['edge'][0], r['edge'][1], r['face_count']),\n"
            "           'same_direction_edge': lambda r: (r['edge'][0], r['edge'][1], r['face_count']),\n"
            "           'nonmanifold_vertex': lambda r: (r['vertices'][0], r['fans'], r['on_nonmanifold_edge']),\n"
            "           'isolated_vertex': lambda r: (r['vertices'][0], 0, 0),\n"
            "           'nonfinite_coordinate': lambda r: (r['vertices'][0], r['axis'], 0)}\n"
            "    rows = [(r['kind'],) + tuple(int(x) for x in abc[key[int(r['kind'])]](r)) for r in d[()]]\n"
            "    del f['meshtopo/report/defects']\n"
            "    t = np.dtype([('kind', enum), ('a', '<u4'), ('b', '<u4'), ('c', '<u4')])\n"
            "    f['meshtopo/report'].create_dataset('defects', data=np.array(rows, dtype=t))\n")
    os.remove(os.path.join(bad, "junk.v1.hdf"))
    p = run(["/usr/bin/python3", "-c", mark, os.path.join(bad, "prim.v1.hdf")])
    if not check(p is not None and p.returncode == 0,
                 f"prim.v1.hdf marked as format 2 ({p and p.stderr.strip()})"):
        return
    p, lines = replay(cli, bad, "--rate", "0", "--ids", "prim")
    prim = [l for l in lines if l.get("mesh_id") == "prim"]
    check(p is not None and p.returncode == 0 and len(prim) == 1 and
          prim[0]["hash_match"] is True and prim[0]["archived_content_hash"] == "0123456789abcdef",
          f"a format 2 file is checked against the hash of its face list "
          f"(exit {p and p.returncode}, {prim})")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--meshtopod", required=True)
    ap.add_argument("--fixture", required=True)
    ap.add_argument("--corpus", default=os.environ.get("MESHTOPO_CORPUS"))
    args = ap.parse_args()
    if not args.corpus:
        ap.error("need --corpus or MESHTOPO_CORPUS")
    if os.environ.get("MESHTOPO_NETNS") != "1":
        print("run me through netns-run", file=sys.stderr)
        return 2
    cli = args.meshtopo
    os.environ["MESHTOPO_LCM_URL"] = LCM_URL
    os.environ["MESHTOPO_PREFIX"] = PREFIX
    tmp = tempfile.mkdtemp(prefix="meshtopo-replay-")
    archive = os.path.join(tmp, "archive")
    daemon = watcher = None
    log = open(os.path.join(tmp, "meshtopod.log"), "w", encoding="utf-8")
    try:
        if not make_archive(args.fixture, args.corpus, archive, ARCHIVED):
            return 1
        check_errors_without_daemon(cli, archive, tmp)

        daemon = subprocess.Popen([args.meshtopod, "--lcm-url", LCM_URL, "--prefix", PREFIX,
                                   "--heartbeat-ms", "100", "--workers", "2"],
                                  stderr=log, stdout=subprocess.DEVNULL)
        p = run([cli, "watch", "--count", "1", "--timeout-ms", "10000"])
        if not check(p is not None and p.returncode == 0, "watch --count 1 sees the heartbeat"):
            return 1
        watcher = Watcher(cli)
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and watcher.count() == 0:
            time.sleep(0.05)
        check(watcher.count() > 0, "the watcher is receiving")

        check_full_replay(cli, archive, watcher)
        check_subsets(cli, archive)
        check_spacing(cli, archive, watcher)
        check_channel(cli, archive)
        check_progress(cli, archive)
        check_bad_files(cli, args.fixture, args.corpus, tmp)
    finally:
        if watcher is not None:
            check(watcher.stop() == 0, "watch stops on SIGINT with 0")
        if daemon is not None:
            daemon.send_signal(signal.SIGTERM)
            try:
                rc = daemon.wait(timeout=15)
            except subprocess.TimeoutExpired:
                daemon.kill()
                rc = daemon.wait()
            check(rc == 0, f"meshtopod exits 0 after SIGTERM (got {rc})")
        log.close()
        if failures:
            with open(log.name, encoding="utf-8", errors="replace") as f:
                print("meshtopod log:\n" + f.read())
        shutil.rmtree(tmp, ignore_errors=True)

    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
