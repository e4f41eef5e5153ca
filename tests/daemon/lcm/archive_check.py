#!/usr/bin/env python3
"""daemon.archive_*: meshtopod --archive with real processes, inside netns-run.

  roundtrip  every corpus mesh that fits one datagram is sent to
             `meshtopod --archive DIR`; the daemon is stopped; a fresh one on
             DIR answers REPORT, one-rings and face neighbours exactly as the
             first did, with the same versions and content hashes (LIST).
  crash      50 times: a sender process streams small meshes into the daemon
             and logs every acknowledged id, version and content hash; the
             daemon gets SIGKILL after a random delay; then `meshtopo archive
             verify DIR` passes and every acknowledged version is archived
             with its hash.
  budget     five meshes with --memory-budget holding about two; queries to
             all five in turn answer as before; the heartbeat counts
             evictions and loads.
  modes      async: acknowledged, then all archived; off: nothing written;
             --archive-compression lz4: a smaller file, served again after a
             restart and verifiable.
  hostile    files planted in the archive directory: a symbolic link at the
             name of the next version (the write takes the next number, the
             file it points to is untouched), at guessable temporary names, and
             in place of a version file (refused, not followed); a version
             whose face list was altered (verify says BAD, the daemon does not
             serve it, sets it aside and says why); every acknowledged
             version the attacker did not touch stays served.

usage: archive_check.py MODE --meshtopo PATH --meshtopod PATH [--corpus DIR]
"""
import argparse
import json
import os
import random
import signal
import subprocess
import sys
import tempfile
import time

LCM_URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
PREFIX = "ARC_"
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        failures.append(what)
    return ok


def run(cmd, timeout=20):
    try:
        return subprocess.run([str(a) for a in cmd], capture_output=True, text=True,
                              timeout=timeout)
    except subprocess.TimeoutExpired:
        check(False, f"`{' '.join(map(str, cmd))}` finished within {timeout} s")
        return None


class Daemon:
    def __init__(self, meshtopod, archive, *extra, log=None):
        self.proc = subprocess.Popen(
            [meshtopod, "--lcm-url", LCM_URL, "--prefix", PREFIX, "--heartbeat-ms", "100",
             "--archive", archive, *map(str, extra)],
            stdout=subprocess.DEVNULL, stderr=log or subprocess.DEVNULL)

    def stop(self):
        self.proc.send_signal(signal.SIGTERM)
        try:
            return self.proc.wait(timeout=15)
        except subprocess.TimeoutExpired:
            check(False, "meshtopod stops within 15 s of SIGTERM")
            self.proc.kill()
            return self.proc.wait()

    def kill(self):
        self.proc.send_signal(signal.SIGKILL)
        self.proc.wait()


def heartbeat(cli, timeout_ms=10000):
    """The next heartbeat (status_t message as a dict), or None."""
    w = subprocess.Popen([cli, "watch", "--json", "--timeout-ms", str(timeout_ms)],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    found = None
    try:
        for line in w.stdout:
            obj = json.loads(line)
            if "status_t" in str(obj.get("type", "")):
                found = obj["message"]
                break
    finally:
        w.kill()
        w.wait()
    return found


def latest_heartbeat(cli):
    """A heartbeat sent after this call (the daemon beats every 100 ms)."""
    time.sleep(0.25)
    return heartbeat(cli)


def send(cli, path, mesh_id):
    p = run([cli, "send", path, "--id", mesh_id, "--json", "--quiet"], timeout=60)
    if p is None or p.returncode != 0:
        return None
    return json.loads(p.stdout)


def listing(cli):
    p = run([cli, "list", "--json"])
    if p is None or p.returncode != 0:
        return None
    return {(m["mesh_id"], m["version"]): m for m in json.loads(p.stdout)["meshes"]}


def answers(cli, mesh_id, version, nverts, nfaces):
    """The daemon's REPORT, one-rings and face neighbours (first 64 of each)."""
    out = {}
    for kind, ids in (("report", []), ("ring", range(min(nverts, 64))),
                      ("face-neighbors", range(min(nfaces, 64)))):
        if kind != "report" and not ids:
            continue
        p = run([cli, "query", mesh_id, kind, *ids, "--version", version, "--json",
                 "--timeout-ms", 3000])
        if p is None or p.returncode != 0:
            out[kind] = ("error", p.returncode if p else None, p.stdout if p else "")
        else:
            out[kind] = json.loads(p.stdout)
            out[kind].pop("utime", None)
    return out


def archive_ls(cli, archive):
    p = run([cli, "archive", "ls", archive, "--json"])
    if p is None or p.returncode != 0:
        return None
    return json.loads(p.stdout)


def corpus_meshes(corpus):
    names = sorted(f[:-len(".expected.json")] for f in os.listdir(corpus)
                   if f.endswith(".expected.json"))
    out = []
    for n in names:
        for ext in (".off", ".obj", ".ply", ".off.gz", ".obj.gz", ".ply.gz"):
            if os.path.exists(os.path.join(corpus, n + ext)):
                out.append((n, os.path.join(corpus, n + ext)))
                break
    return out


def mode_roundtrip(args, tmp):
    archive = os.path.join(tmp, "arc")
    log = open(os.path.join(tmp, "daemon.log"), "w")
    d = Daemon(args.meshtopod, archive, log=log)
    if not check(heartbeat(args.meshtopo) is not None, "first daemon's heartbeat"):
        d.stop()
        return
    sent = {}
    for name, path in corpus_meshes(args.corpus):
        ack = send(args.meshtopo, path, name)
        if ack is None or ack.get("status") not in (0, "OK"):
            print(f"skip  {name}: not acknowledged by the live daemon ({ack and ack.get('error')})")
            continue
        rep = ack["report"]
        sent[name] = (ack, answers(args.meshtopo, name, ack["version"], rep["V"],
                                   rep["F"]))
    before = listing(args.meshtopo)
    check(d.stop() == 0, "first daemon exits 0 on SIGTERM")
    d = Daemon(args.meshtopod, archive, log=log)
    check(heartbeat(args.meshtopo) is not None, "restarted daemon's heartbeat")
    after = listing(args.meshtopo)
    check(after is not None and before is not None and
          {k: v["content_hash"] for k, v in after.items()} ==
          {k: v["content_hash"] for k, v in before.items()},
          f"LIST after the restart has the same {len(before or {})} versions and content hashes")
    same = 0
    for name, (ack, live) in sent.items():
        rep = ack["report"]
        again = answers(args.meshtopo, name, ack["version"], rep["V"], rep["F"])
        row = (after or {}).get((name, ack["version"]))
        ok = again == live and row is not None and row["content_hash"] == ack["content_hash"]
        same += ok
        check(ok, f"{name} v{ack['version']}: reloaded answers and content hash equal the live ones")
    hb = latest_heartbeat(args.meshtopo)
    check(hb is not None and hb["archive_loads"] == len(sent),
          f"heartbeat: {hb and hb['archive_loads']} loads from the archive for {len(sent)} meshes")
    print(f"roundtrip: {same} of {len(sent)} corpus meshes answer identically after the restart")
    check(d.stop() == 0, "restarted daemon exits 0 on SIGTERM")


def make_grid(path, n, seed):
    """A small OFF grid n x n with a seed-dependent shape."""
    rnd = random.Random(seed)
    verts = [(x, y, rnd.random()) for y in range(n + 1) for x in range(n + 1)]
    faces = []
    for y in range(n):
        for x in range(n):
            a = y * (n + 1) + x
            faces.append((a, a + 1, a + n + 2))
            faces.append((a, a + n + 2, a + n + 1))
    with open(path, "w") as f:
        f.write(f"OFF\n{len(verts)} {len(faces)} 0\n")
        for v in verts:
            f.write("%.6f %.6f %.6f\n" % v)
        for t in faces:
            f.write("3 %d %d %d\n" % t)


SENDER = r"""
import json, subprocess, sys
cli, ackfile, files = sys.argv[1], sys.argv[2], sys.argv[3:]
i = 0
with open(ackfile, "a") as log:
    while True:
        path = files[i % len(files)]
        mid = "s%d" % (i % 7)
        p = subprocess.run([cli, "send", path, "--id", mid, "--json", "--quiet",
                            "--timeout-ms", "2000", "--retries", "0"],
                           capture_output=True, text=True)
        if p.returncode == 0:
            a = json.loads(p.stdout)
            log.write("%s %d %s\n" % (a["mesh_id"], a["version"], a["content_hash"]))
            log.flush()
        i += 1
"""


def mode_crash(args, tmp):
    archive = os.path.join(tmp, "arc")
    files = []
    for k in range(6):
        files.append(os.path.join(tmp, f"g{k}.off"))
        make_grid(files[-1], 4 + k, k)
    ackfile = os.path.join(tmp, "acks.txt")
    # Created here: a sender killed before its interpreter started acknowledged nothing.
    open(ackfile, "a").close()
    rnd = random.Random(int(os.environ.get("ARCHIVE_CRASH_SEED", "4")))
    start = time.monotonic()
    kills = intact = 0
    for it in range(args.kills):
        d = Daemon(args.meshtopod, archive)
        if not check(heartbeat(args.meshtopo, 5000) is not None, f"kill {it}: heartbeat"):
            d.kill()
            break
        sender = subprocess.Popen([sys.executable, "-c", SENDER, args.meshtopo, ackfile, *files],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(rnd.uniform(0.05, 0.6))
        d.kill()
        kills += 1
        sender.send_signal(signal.SIGKILL)
        sender.wait()
        p = run([args.meshtopo, "archive", "verify", archive])
        if not check(p is not None and p.returncode == 0,
                     f"kill {it}: archive verify passes ({p and p.stdout.strip()[-200:]})"):
            break
        ls = archive_ls(args.meshtopo, archive)
        have = {(m["mesh_id"], m["version"]): m["content_hash"] for m in (ls or {}).get("meshes", [])}
        acked = []
        with open(ackfile) as f:
            for line in f:
                parts = line.split()
                if len(parts) == 3:
                    acked.append(((parts[0], int(parts[1])), parts[2]))
        missing = [k for k, h in acked if have.get(k) != h]
        if not check(not missing and not (ls or {}).get("unreadable"),
                     f"kill {it}: all {len(acked)} acknowledged versions archived intact "
                     f"({len(have)} files; missing {missing[:3]})"):
            break
        intact += 1
    elapsed = time.monotonic() - start
    print(f"crash: {kills} SIGKILLs, archive verified and every acknowledged mesh intact after "
          f"{intact}; {len(have)} versions archived; {elapsed:.1f} s")
    check(kills == args.kills and intact == args.kills, f"{args.kills} kills survived")


def mode_budget(args, tmp):
    archive = os.path.join(tmp, "arc")
    files = []
    for k in range(5):
        files.append(os.path.join(tmp, f"b{k}.off"))
        make_grid(files[-1], 40, 100 + k)
    # Learn one mesh's memory size from an unbudgeted daemon's heartbeat.
    d = Daemon(args.meshtopod, os.path.join(tmp, "probe"))
    heartbeat(args.meshtopo)
    send(args.meshtopo, files[0], "probe")
    hb = latest_heartbeat(args.meshtopo)
    d.stop()
    one = hb["memory_bytes"] if hb else 0
    budget = int(one * 2.5)
    print(f"budget: one mesh holds {one} bytes; --memory-budget {budget}")
    d = Daemon(args.meshtopod, archive, "--memory-budget", budget)
    heartbeat(args.meshtopo)
    acks = [send(args.meshtopo, f, f"b{k}") for k, f in enumerate(files)]
    check(all(a and a["version"] == 1 for a in acks), "five meshes acknowledged")
    live = [answers(args.meshtopo, f"b{k}", 1, 41 * 41, 3200) for k in range(5)]
    for rnd in range(2):
        for k in range(5):
            again = answers(args.meshtopo, f"b{k}", 1, 41 * 41, 3200)
            check(again == live[k], f"round {rnd}: b{k} answers as when it was sent")
    hb = latest_heartbeat(args.meshtopo)
    ok = hb is not None and hb["archive_evictions"] >= 5 and hb["archive_loads"] >= 5 and \
        hb["memory_bytes"] <= budget
    check(ok, f"heartbeat: {hb and hb['archive_evictions']} evictions, "
              f"{hb and hb['archive_loads']} loads, {hb and hb['memory_bytes']} bytes held "
              f"<= budget {budget}")
    lst = listing(args.meshtopo)
    check(lst is not None and len(lst) == 5, f"LIST shows all 5 versions ({lst and len(lst)})")
    check(d.stop() == 0, "daemon exits 0")


def mode_modes(args, tmp):
    files = []
    for k in range(4):
        files.append(os.path.join(tmp, f"m{k}.off"))
        make_grid(files[-1], 6, 200 + k)
    arc = os.path.join(tmp, "async")
    d = Daemon(args.meshtopod, arc, "--archive-mode", "async")
    heartbeat(args.meshtopo)
    acks = [send(args.meshtopo, f, f"a{k}") for k, f in enumerate(files)]
    check(all(a is not None for a in acks), "async: four meshes acknowledged")
    deadline = time.monotonic() + 10
    n = 0
    while time.monotonic() < deadline:
        ls = archive_ls(args.meshtopo, arc)
        n = len((ls or {}).get("meshes", []))
        if n == 4:
            break
        time.sleep(0.1)
    check(n == 4, f"async: all four archived eventually ({n})")
    hb = latest_heartbeat(args.meshtopo)
    check(hb is not None and hb["archive_writes"] == 4 and hb["archive_backlog"] == 0,
          f"async: heartbeat counts 4 writes, backlog 0 ({hb and hb['archive_writes']}, "
          f"{hb and hb['archive_backlog']})")
    check(d.stop() == 0, "async daemon exits 0")
    arc = os.path.join(tmp, "off")
    os.mkdir(arc)
    d = Daemon(args.meshtopod, arc, "--archive-mode", "off")
    heartbeat(args.meshtopo)
    acks = [send(args.meshtopo, f, f"o{k}") for k, f in enumerate(files)]
    check(all(a is not None for a in acks), "off: four meshes acknowledged")
    check(d.stop() == 0, "off daemon exits 0")
    check(os.listdir(arc) == [], f"off: the directory stays empty ({os.listdir(arc)[:3]})")
    # A sync archive that cannot be written: the submission fails, nothing is stored.
    arc = os.path.join(tmp, "ro")
    os.mkdir(arc)
    d = Daemon(args.meshtopod, arc)
    heartbeat(args.meshtopo)
    os.chmod(arc, 0o500)
    p = run([args.meshtopo, "send", files[0], "--id", "ro", "--json", "--quiet"])
    os.chmod(arc, 0o700)
    if os.geteuid() != 0:
        out = json.loads(p.stdout) if p and p.stdout else {}
        check(p is not None and p.returncode == 5 and "archive" in out.get("error", ""),
              f"sync: an unwritable archive refuses the submission ({out.get('error')})")
        lst = listing(args.meshtopo)
        check(lst is not None and ("ro", 1) not in lst, "sync: the refused mesh is not held")
    else:
        print("skip  unwritable archive: running as root")
    check(d.stop() == 0, "sync daemon exits 0")
    # --archive-compression lz4: the same mesh in about half the bytes or
    # less, served again by a fresh daemon (whose own setting is the default),
    # and a verifiable archive.
    big = os.path.join(tmp, "big.off")
    make_grid(big, 60, 300)
    sizes, first = {}, {}
    for comp in ("none", "lz4"):
        arc = os.path.join(tmp, "c-" + comp)
        d = Daemon(args.meshtopod, arc, "--archive-compression", comp)
        heartbeat(args.meshtopo)
        ack = send(args.meshtopo, big, "big")
        check(ack is not None, f"{comp}: the grid is acknowledged")
        first[comp] = answers(args.meshtopo, "big", 1, 61 * 61, 7200)
        check(d.stop() == 0, f"{comp} daemon exits 0")
        sizes[comp] = sum(os.path.getsize(os.path.join(arc, n)) for n in os.listdir(arc)
                          if n.endswith(".hdf"))
    check(0 < sizes["lz4"] < sizes["none"] / 2,
          f"lz4: {sizes['lz4']} bytes against {sizes['none']} uncompressed")
    arc = os.path.join(tmp, "c-lz4")
    d = Daemon(args.meshtopod, arc)
    heartbeat(args.meshtopo)
    check(answers(args.meshtopo, "big", 1, 61 * 61, 7200) == first["lz4"] == first["none"],
          "lz4: a fresh daemon serves the archived grid as it was first answered")
    check(d.stop() == 0, "daemon on the lz4 archive exits 0")
    p = run([args.meshtopo, "archive", "verify", arc], timeout=60)
    check(p is not None and p.returncode == 0, "lz4: archive verify passes")
    # Where HDF5 finds no Blosc plugin, the reader says what is missing.
    env = dict(os.environ, HDF5_PLUGIN_PATH=os.path.join(tmp, "no-plugins"))
    p = subprocess.run([args.meshtopo, "archive", "verify", arc], env=env, timeout=60,
                       capture_output=True, text=True)
    check(p.returncode != 0 and "hdf5-filter-plugin-blosc-serial" in p.stdout + p.stderr,
          "lz4 without the plugin: verify names the package ({})".format(
              (p.stdout + p.stderr).strip()[:160]))


def file_sha(path):
    import hashlib
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def mode_hostile(args, tmp):
    import glob
    import h5py
    archive = os.path.join(tmp, "arc")
    outside = os.path.join(tmp, "outside")
    os.makedirs(outside)
    target = os.path.join(outside, "precious.txt")
    with open(target, "w") as f:
        f.write("not the daemon's to write\n")
    before = file_sha(target)
    grid = os.path.join(tmp, "g.off")
    make_grid(grid, 6, 1)
    log_path = os.path.join(tmp, "daemon.log")
    log = open(log_path, "w")
    d = Daemon(args.meshtopod, archive, log=log)
    if not check(heartbeat(args.meshtopo) is not None, "daemon's heartbeat"):
        d.stop()
        return
    a1 = send(args.meshtopo, grid, "m")
    check(a1 is not None and a1["version"] == 1, "m v1 acknowledged")
    keep = send(args.meshtopo, grid, "keep")
    check(keep is not None and keep["version"] == 1, "keep v1 acknowledged")
    # A link at the name version 2 would get, and at temporary names.
    os.symlink(target, os.path.join(archive, "m.v2.hdf"))
    for k in range(4):
        os.symlink(target, os.path.join(archive, f".mt-tmp-{d.proc.pid}-{k:016x}.part"))
    a3 = send(args.meshtopo, grid, "m")
    check(a3 is not None and a3["version"] == 3,
          f"m with version 2's name taken: acknowledged as {a3 and a3['version']} (3 expected)")
    check(file_sha(target) == before and os.path.islink(os.path.join(archive, "m.v2.hdf")),
          "the file the planted links point to is untouched, the link still there")
    # A version file replaced by a link to a copy of itself.
    v1 = os.path.join(archive, "m.v1.hdf")
    copy = os.path.join(outside, "m.v1.copy")
    os.rename(v1, copy)
    os.symlink(copy, v1)
    # The face list of m v3 altered in place.
    v3 = os.path.join(archive, "m.v3.hdf")
    with h5py.File(v3, "r+") as h:
        idx = h["/meshtopo/face_vertex_indices"]
        first = idx[0]
        idx[0] = idx[1]
        idx[1] = first
    p = run([args.meshtopo, "archive", "verify", archive, "--json"], timeout=60)
    verdict = json.loads(p.stdout) if p is not None and p.stdout.strip() else None
    files = {r["file"]: r for r in (verdict or {}).get("files", [])} if verdict else {}
    check(p is not None and p.returncode != 0, "archive verify fails on the planted and altered files")
    want = {"keep.v1.hdf": (True, "", "none"),
            "m.v1.hdf": (False, "symbolic link", "unsafe"),
            "m.v2.hdf": (False, "symbolic link", "unsafe"),
            "m.v3.hdf": (False, "content hash", "content")}
    for name, (ok, needle, fault) in want.items():
        r = files.get(name)
        check(r is not None and r["ok"] == ok and needle in (r["error"] or "") and
              r["fault"] == fault,
              f"verify: {name} {'OK' if ok else 'BAD naming ' + repr(needle)}, fault {fault}: {r}")
    check(d.stop() == 0, "daemon exits 0 on SIGTERM")
    log.close()
    log = open(log_path, "a")
    d = Daemon(args.meshtopod, archive, log=log)
    check(heartbeat(args.meshtopo) is not None, "restarted daemon's heartbeat")
    q = run([args.meshtopo, "query", "m", "report", "--version", 3, "--json", "--timeout-ms", 3000])
    check(q is not None and q.returncode == 5 and "content" in (q.stderr + q.stdout).lower(),
          f"m v3 (altered face list) is refused, naming the content hash: {q and q.stderr.strip()}")
    q = run([args.meshtopo, "query", "m", "report", "--version", 1, "--json", "--timeout-ms", 3000])
    check(q is not None and q.returncode == 5, f"m v1 (a link) is not served: {q and q.stderr.strip()}")
    q = run([args.meshtopo, "query", "keep", "report", "--json", "--timeout-ms", 3000])
    check(q is not None and q.returncode == 0, "keep v1, untouched, is still served")
    aside = glob.glob(os.path.join(archive, ".mt-aside-m.v3.hdf.*"))
    check(len(aside) == 1 and not os.path.exists(v3), f"m v3 set aside as {aside}")
    check(file_sha(target) == before and file_sha(copy) != "", "files outside the archive untouched")
    a4 = send(args.meshtopo, grid, "m")
    check(a4 is not None and a4["version"] == 4, f"m takes version {a4 and a4['version']} next")
    check(d.stop() == 0, "restarted daemon exits 0 on SIGTERM")
    log.close()
    text = open(log_path).read()
    check("set aside as .mt-aside-m.v3.hdf." in text, "the daemon logged the set-aside file")
    check("m.v1.hdf: refused: a symbolic link" in text,
          "the daemon logged the link in place of m v1 as refused, not followed")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mode", choices=["roundtrip", "crash", "budget", "modes", "hostile"])
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--meshtopod", required=True)
    ap.add_argument("--corpus", default=os.environ.get("MESHTOPO_CORPUS"))
    ap.add_argument("--kills", type=int, default=50)
    args = ap.parse_args()
    if os.environ.get("MESHTOPO_NETNS") != "1":
        print("run me through netns-run", file=sys.stderr)
        return 2
    os.environ["MESHTOPO_LCM_URL"] = LCM_URL
    os.environ["MESHTOPO_PREFIX"] = PREFIX
    with tempfile.TemporaryDirectory(prefix="meshtopo-archive-") as tmp:
        {"roundtrip": mode_roundtrip, "crash": mode_crash, "budget": mode_budget,
         "modes": mode_modes, "hostile": mode_hostile}[args.mode](args, tmp)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
