#!/usr/bin/env python3
"""cli.netns_remote: the meshtopo CLI against a real meshtopod over LCM.

Run inside netns-run (udpm over a private lo). Starts meshtopod, waits for its
heartbeat with `meshtopo watch --count 1`, sends a clean and a non-manifold
corpus mesh with `meshtopo send`, checks `meshtopo query ring` and
`face-neighbors` against NAME.expected.json (vertex_queries / face_queries,
compared as sets as DEFINITIONS.md defines them), the defect records of
`query defects --json` and of the ack against `inspect --json-defects`, `meshtopo list --json`,
`meshtopo watch --json` seeing each build's TOPOLOGY report, the unknown-mesh
error (exit 5, message naming the mesh), no answer (exit 6) and every
command's --help; then stops the daemon it started by its PID (SIGTERM) and
expects a clean exit. Every child process runs with a timeout.

usage: netns_remote.py --meshtopo PATH --meshtopod PATH --corpus DIR [CLEAN NONMANIFOLD]
       (--corpus defaults to the MESHTOPO_CORPUS environment variable)
"""
import argparse
import json
import math
import os
import signal
import subprocess
import sys
import tempfile
import time

CALL_TIMEOUT = 30  # seconds for any one CLI run
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        failures.append(what)
    return ok


def run(cli, *args, timeout=CALL_TIMEOUT):
    cmd = [cli] + [str(a) for a in args]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        check(False, f"`{' '.join(cmd)}` finished within {timeout} s")
        return None
    return p


def run_json(cli, *args):
    p = run(cli, *args)
    if p is None:
        return None
    if not check(p.returncode == 0, f"`meshtopo {' '.join(map(str, args))}` exits 0 "
                 f"(got {p.returncode}; stderr: {p.stderr.strip()})"):
        return None
    try:
        return json.loads(p.stdout)
    except json.JSONDecodeError as e:
        check(False, f"`meshtopo {' '.join(map(str, args))}` prints JSON ({e})")
        return None


def check_mesh(cli, corpus, name):
    with open(os.path.join(corpus, name + ".expected.json"), encoding="utf-8") as f:
        exp = json.load(f)
    path = os.path.join(corpus, exp["file"])

    ack = run_json(cli, "send", path, "--id", name, "--json")
    if ack is None:
        return
    rep = ack.get("report") or {}
    check(ack["status"] == "OK" and ack["version"] >= 1, f"{name}: send acked with a version")
    for key in ("V", "F", "F_valid", "E", "face_size_histogram", "edge_use_histogram",
                "boundary_edges", "boundary_loops",
                "nonmanifold_edges", "connected_components", "euler_characteristic", "closed",
                "manifold", "orientable"):
        check(rep.get(key) == exp[key],
              f"{name}: ack report {key} = {exp[key]} (got {rep.get(key)})")

    # Defects: the same records (README.md "Defect records") from the daemon,
    # in the ack's report and answering `query defects`, as `inspect` lists.
    p = run(cli, "inspect", path, "--json-defects")
    local = json.loads(p.stdout)["defects"] if p is not None and p.returncode == 0 else None
    got = run_json(cli, "query", name, "defects", "--json")
    if check(local is not None, f"{name}: inspect --json-defects") and got is not None:
        remote = [d for item in got.get("items", []) for d in item.get("defects", [])]
        check(remote == local, f"{name}: query defects --json gives inspect's {len(local)} "
              f"records (got {remote[:2]}...)")
        check(rep.get("defects") == local, f"{name}: the ack's report lists inspect's records")

    # One-rings: neighbours and faces as sorted sets over every fan.
    verts = [q["vertex"] for q in exp["vertex_queries"]]
    got = run_json(cli, "query", name, "ring", ",".join(map(str, verts)), "--json")
    if got is not None:
        items = got["items"]
        check(len(items) == len(verts), f"{name}: ring answers {len(verts)} items")
        for q, item in zip(exp["vertex_queries"], items):
            nb = sorted({v for fan in item["fans"] for v in fan["vertices"]})
            fs = sorted({f for fan in item["fans"] for f in fan["faces"]})
            check(item["vertex"] == q["vertex"] and nb == q["neighbors"] and fs == q["faces"],
                  f"{name}: ring of vertex {q['vertex']}: neighbors {q['neighbors']} faces "
                  f"{q['faces']} (got {nb} {fs})")

    # Face neighbours: every face across any side, without the face itself, as a set.
    faces = [q["face"] for q in exp["face_queries"]]
    got = run_json(cli, "query", name, "face-neighbors", *faces, "--json")
    if got is not None:
        items = got["items"]
        check(len(items) == len(faces), f"{name}: face-neighbors answers {len(faces)} items")
        for q, item in zip(exp["face_queries"], items):
            adj = sorted({g for side in item["sides"] for g in side["faces"]} - {q["face"]})
            check(item["face"] == q["face"] and adj == q["adjacent_faces"],
                  f"{name}: neighbours of face {q['face']}: {q['adjacent_faces']} (got {adj})")

    # The readable form: one line per item, fans labelled.
    p = run(cli, "query", name, "ring", *verts)
    if p is not None:
        lines = p.stdout.splitlines()
        check(p.returncode == 0 and len(lines) == len(verts) and
              all(l.startswith(f"vertex {v}:") for v, l in zip(verts, lines)) and
              all(" fan 0 " in l or "isolated" in l for l in lines),
              f"{name}: readable ring output is one labelled line per vertex")
    return exp


def check_geometry(cli, corpus):
    """The geometry kinds on openmesh_cube_minimal_quads, whose quads turn
    inward (face 0 runs counter-clockwise seen from inside): every edge is a
    reflex 3 pi / 2 edge, every corner has deficit pi / 2, and convexity says
    why the cube does not count as convex."""
    path = os.path.join(corpus, "openmesh_cube_minimal_quads.off")
    ack = run_json(cli, "send", path, "--id", "cube", "--json")
    check(ack is not None and ack["status"] == "OK", "cube: sent")
    got = run_json(cli, "query", "cube", "dihedral", "0", "1", "1", "2", "0", "6", "--json")
    if check(got is not None and len(got["items"]) == 3, "cube: dihedral answers 3 pairs"):
        for item in got["items"][:2]:
            check(item["shape"] == "reflex" and abs(item["dihedral_angle"] - 1.5 * math.pi) < 1e-12,
                  f"cube: edge {item['edge']} is reflex at 3 pi / 2 ({item})")
        check(got["items"][2]["status"] == "NOT_FOUND" and got["items"][2]["dihedral_angle"] is None,
              "cube: 0-6 is no edge: NOT_FOUND, no angle")
    got = run_json(cli, "query", "cube", "deficit", "0-7", "--json")
    if check(got is not None and len(got["items"]) == 8, "cube: deficit answers 8 vertices"):
        check(all(abs(i["angle_deficit"] - math.pi / 2) < 1e-12 and not i["boundary"]
                  for i in got["items"]), "cube: every corner's deficit is pi / 2")
    got = run_json(cli, "query", "cube", "convexity", "--json")
    if check(got is not None and len(got["items"]) == 1, "cube: convexity answers"):
        c = got["items"][0]
        check(not c["convex"] and "inward" in c["reasons"] and len(c["reflex_edges"]) == 12
              and c["volume"] < 0, f"cube: not convex, inward, 12 reflex edges ({c})")
    p = run(cli, "query", "cube", "convexity")
    check(p is not None and p.returncode == 0 and "not convex (" in p.stdout,
          f"cube: convexity prints a readable line ({p and p.stdout.strip()})")
    p = run(cli, "query", "cube", "dihedral", "0")
    check(p is not None and p.returncode == 2, "dihedral with an odd id count is a usage error")

    # self-intersections over the wire answers what inspect answers locally,
    # on the teapot (lid and spout pass through the body; open loops cross).
    path = os.path.join(corpus, "npm_teapot.off")
    ack = run_json(cli, "send", path, "--id", "teapot", "--json")
    check(ack is not None and ack["status"] == "OK", "teapot: sent")
    got = run_json(cli, "query", "teapot", "self-intersections", "--json")
    local = run_json(cli, "inspect", path, "--self-intersections", "--json")
    if check(got is not None and local is not None and len(got["items"]) == 1,
             "teapot: self-intersections answers one item"):
        item = got["items"][0]
        keys = ["self_intersecting_pairs", "non_simple_faces", "self_intersecting_boundary_loops",
                "self_intersections"]
        check(all(item.get(k) == local.get(k) for k in keys) and item["self_intersecting_pairs"] > 0,
              f"teapot: remote self-intersections equal inspect's "
              f"({item.get('self_intersecting_pairs')} pairs)")
    p = run(cli, "query", "teapot", "self-intersections")
    check(p is not None and p.returncode == 0 and "self-intersections: " in p.stdout and
          "faces " in p.stdout, "teapot: self-intersections prints readable lines")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--meshtopod", required=True)
    ap.add_argument("--corpus", default=os.environ.get("MESHTOPO_CORPUS"))
    ap.add_argument("names", nargs="*", default=["npm_bunny", "vcg_nonmanifold"])
    args = ap.parse_args()
    if not args.corpus:
        ap.error("need --corpus or MESHTOPO_CORPUS")
    if os.environ.get("MESHTOPO_NETNS") != "1":
        print("run me through netns-run", file=sys.stderr)
        return 2
    cli = args.meshtopo

    # --help of every command, before any daemon runs.
    for cmd in ("send", "query", "list", "watch"):
        p = run(cli, cmd, "--help")
        check(p is not None and p.returncode == 0 and p.stdout.startswith(f"usage: meshtopo {cmd}"),
              f"meshtopo {cmd} --help exits 0")

    # Nothing is running yet: no answer is exit 6.
    p = run(cli, "list", "--timeout-ms", "200", "--retries", "0")
    check(p is not None and p.returncode == 6, f"list without a daemon exits 6 "
          f"(got {p and p.returncode})")

    log = tempfile.NamedTemporaryFile(prefix="meshtopod-", suffix=".log", delete=False)
    daemon = subprocess.Popen([args.meshtopod, "--heartbeat-ms", "100", "--workers", "2"],
                              stderr=log, stdout=subprocess.DEVNULL)
    watcher = None
    watch_out = None
    try:
        p = run(cli, "watch", "--count", "1", "--timeout-ms", "10000")
        if not check(p is not None and p.returncode == 0 and
                     p.stdout.startswith("MESHTOPO_STATUS meshtopod pid "),
                     "watch --count 1 sees the heartbeat"):
            return 1

        # The watcher writes to a file (a pipe would fill up with heartbeats).
        watch_out = tempfile.NamedTemporaryFile(prefix="meshtopo-watch-", suffix=".jsonl",
                                                delete=False)
        watcher = subprocess.Popen([cli, "watch", "--json", "--timeout-ms", "30000"],
                                   stdout=watch_out, stderr=subprocess.PIPE, text=True)
        # Let its subscription settle: wait until it has printed one heartbeat.
        deadline = time.monotonic() + 10
        first = ""
        while not first and time.monotonic() < deadline and watcher.poll() is None:
            time.sleep(0.05)
            with open(watch_out.name, encoding="utf-8") as f:
                first = f.readline()
        check(first.endswith("\n") and json.loads(first)["type"] == "status_t",
              "watch --json prints a status_t line")

        expected = {}
        for name in args.names:
            expected[name] = check_mesh(cli, args.corpus, name)

        # A second submission is a new version; --version 1 still answers.
        name = args.names[0]
        ack = run_json(cli, "send", os.path.join(args.corpus, expected[name]["file"]),
                       "--id", name, "--json")
        check(ack is not None and ack["version"] == 2, f"{name}: resubmission is version 2")
        got = run_json(cli, "query", name, "valence", "0", "--version", "1", "--json")
        check(got is not None and got["version"] == 1, f"{name}: query --version 1 answers v1")

        listed = run_json(cli, "list", "--json")
        if listed is not None:
            held = {(m["mesh_id"], m["version"]): m for m in listed["meshes"]}
            for n, exp in expected.items():
                m = held.get((n, 1))
                check(m is not None and m["num_verts"] == exp["V"] and m["num_faces"] == exp["F"],
                      f"list --json holds {n} version 1 with V {exp['V']}, F {exp['F']}")
            check((name, 2) in held, f"list --json holds {name} version 2")

        check_geometry(cli, args.corpus)

        p = run(cli, "query", "no_such_mesh", "ring", "0")
        check(p is not None and p.returncode == 5 and "no_such_mesh" in p.stderr,
              f"query of an unknown mesh exits 5 naming it (got {p and p.returncode}: "
              f"{p and p.stderr.strip()})")
        p = run(cli, "query", name, "kind-that-is-not")
        check(p is not None and p.returncode == 2, "an unknown query kind is a usage error (2)")
        p = run(cli, "send", os.path.join(args.corpus, "no-such-file.off"), "--id", "x")
        check(p is not None and p.returncode == 3, "send of a missing file exits 3")

        # The watcher saw every build's report; SIGINT stops it with exit 0.
        watcher.send_signal(signal.SIGINT)
        try:
            watcher.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            watcher.kill()
            watcher.communicate()
        check(watcher.returncode == 0, f"watch stops on SIGINT with 0 (got {watcher.returncode})")
        watch_out.close()
        with open(watch_out.name, encoding="utf-8") as f:
            out = f.read()
        reports = [json.loads(l)["message"] for l in out.splitlines()
                   if json.loads(l)["type"] == "topology_t"]
        seen = {(r["mesh_id"], r["version"]) for r in reports}
        for n in args.names:
            check((n, 1) in seen, f"watch saw the TOPOLOGY report of {n} version 1")
        watcher = None
    finally:
        if watch_out is not None:
            watch_out.close()
            os.unlink(watch_out.name)
        if watcher is not None:
            watcher.kill()
            watcher.wait()
        daemon.send_signal(signal.SIGTERM)
        try:
            rc = daemon.wait(timeout=15)
        except subprocess.TimeoutExpired:
            daemon.kill()
            rc = daemon.wait()
        log.close()
        check(rc == 0, f"meshtopod exits 0 after SIGTERM (got {rc})")
        if failures:
            with open(log.name, encoding="utf-8", errors="replace") as f:
                print("meshtopod log:\n" + f.read())
        os.unlink(log.name)

    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
