#!/usr/bin/env python3
"""protocol.every_kind: every query kind of the one table (meshtopo/query_kinds.h)
is declared in msgs/query_t.lcm, exposed by Python, answered by meshtopod and
taken by the meshtopo CLI by its name.

Reads the kinds from the table through the Python package (meshtopo.QUERY_KINDS,
which reads the C table) and from the .lcm file, and checks they are the same.
Then, inside netns-run, starts meshtopod, sends corpus meshes with `meshtopo
send`, and for every kind and mesh: asks it through meshtopo.Client by name and
by number (the reply holds what the table says: items per id or pair, one item
about the mesh, none for the report and the listing; reals per item), through
`meshtopo query ID NAME ...` in text and --json (the listing through `meshtopo
list`), and checks that the daemon refuses what the table says the kind does not
take (no ids, ids, an odd count of pair ids, an id past the mesh's counts).
Stops the daemon it started, by its PID.

usage: every_kind_check.py --meshtopo PATH --meshtopod PATH --corpus DIR [NAME...]
  (MESHTOPO_PYTHON_LIBRARY names libmeshtopo-python.so; the package is read from
  lib/python of this tree)
"""
import argparse
import json
import os
import signal
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "lib", "python"))
sys.path.insert(0, HERE)

import meshtopo  # noqa: E402
from check_kind_numbers import read_kinds  # noqa: E402

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)
    return ok


def run(*argv, timeout=60):
    try:
        return subprocess.run(list(argv), capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None


def sample_ids(kind):
    """Ids the kind takes, valid on every mesh used here (3 vertices, 2 faces)."""
    if kind.ids == "none":
        return []
    if kind.space == "defect_kind":
        return [0, 1]
    if kind.pairs:
        return [0, 1, 1, 2]
    if kind.space == "face":
        return [0, 1]
    return [0, 1, 2]


def expected_items(kind, ids):
    """Items the reply holds, or None when the mesh decides (boundary loops)."""
    if kind.reply in ("report", "list"):
        return 0
    if kind.reply == "mesh":
        return 1
    if kind.reply == "per_loop":
        return None
    return len(ids) // 2 if kind.pairs else len(ids)


def refused(client, mesh, kind, ids, code):
    try:
        client.query(mesh, kind.number, ids)
    except meshtopo.Error as e:
        return code in str(e)
    return False


def check_table_against_lcm():
    declared = read_kinds(REPO)
    exposed = {k.wire_name: k.number for k in meshtopo.QUERY_KINDS}
    check(exposed == declared, "the table's kinds are query_t.lcm's: %s" %
          ", ".join("%s=%d" % kv for kv in sorted(declared.items(), key=lambda kv: kv[1])))
    names = [k.name for k in meshtopo.QUERY_KINDS]
    check(len(set(names)) == len(names), "kind names are unique: %s" % ", ".join(names))
    for k in meshtopo.QUERY_KINDS:
        check(meshtopo.query_kind(k.name) is k and meshtopo.query_kind(k.number) is k and
              meshtopo.query_kind(k.wire_name) is k and
              getattr(meshtopo._lib, "QUERY_" + k.wire_name) == k.number,
              "Python exposes %s (%s, %d)" % (k.name, k.wire_name, k.number))
    try:
        meshtopo.query_kind("no-such-kind")
        check(False, "query_kind refuses an unknown name")
    except ValueError:
        check(True, "query_kind refuses an unknown name")


def check_mesh(cli, client, mesh, num_verts):
    for kind in meshtopo.QUERY_KINDS:
        ids = sample_ids(kind)
        label = "%s: %s %s" % (mesh, kind.name, " ".join(map(str, ids)))
        # The daemon answers it, asked by name and by number.
        try:
            by_name = client.query(mesh, kind.name, ids)
            by_number = client.query(mesh, kind.number, ids)
        except meshtopo.Error as e:
            check(False, "%s: meshtopod answers (%s)" % (label, e))
            continue
        want = expected_items(kind, ids)
        check(by_name.num_items == by_number.num_items and
              (want is None or by_name.num_items == want),
              "%s: meshtopod answers %d item(s)%s" % (label, by_name.num_items,
                                                     "" if want is None else " of %d" % want))
        if kind.reals_per_item is not None:
            check(len(by_name.reals) == kind.reals_per_item * by_name.num_items,
                  "%s: %d real(s) per item" % (label, kind.reals_per_item))
        # The CLI takes it by name (the listing is `meshtopo list`).
        if kind.reply == "list":
            p = run(cli, "list", "--json")
            listed = json.loads(p.stdout) if p is not None and p.returncode == 0 else None
            check(listed is not None and any(m["mesh_id"] == mesh for m in listed["meshes"]),
                  "%s: `meshtopo list --json` lists it" % label)
            p = run(cli, "query", mesh, kind.name)
            check(p is not None and p.returncode == 2,
                  "%s: `meshtopo query` leaves the listing to `meshtopo list` (exit 2)" % label)
        else:
            args = [str(i) for i in ids]
            p = run(cli, "query", mesh, kind.name, *args, "--json")
            got = json.loads(p.stdout) if p is not None and p.returncode == 0 else None
            check(got is not None and got["kind"] == kind.name and got["mesh_id"] == mesh,
                  "%s: `meshtopo query --json` takes it (%s)" %
                  (label, p and p.returncode))
            if got is not None and kind.reply not in ("report",):
                check(len(got["items"]) == by_name.num_items,
                      "%s: the CLI prints every item" % label)
            p = run(cli, "query", mesh, kind.name, *args)
            check(p is not None and p.returncode == 0 and
                  (p.stdout or by_name.num_items == 0),
                  "%s: `meshtopo query` prints it (%s)" % (label, p and p.returncode))
        # The daemon refuses what the table says the kind does not take.
        if kind.ids == "needed":
            check(refused(client, mesh, kind, [], "BAD_REQUEST"),
                  "%s: without ids: BAD_REQUEST" % label)
        if kind.ids == "none":
            check(refused(client, mesh, kind, [0], "BAD_REQUEST"),
                  "%s: with an id: BAD_REQUEST" % label)
        if kind.pairs:
            check(refused(client, mesh, kind, [0, 1, 2], "BAD_REQUEST"),
                  "%s: an odd count of pair ids: BAD_REQUEST" % label)
        if kind.space == "vertex":
            check(refused(client, mesh, kind, [0, num_verts], "OUT_OF_RANGE"),
                  "%s: vertex %d: OUT_OF_RANGE" % (label, num_verts))
        if kind.space == "defect_kind":
            check(refused(client, mesh, kind, [len(meshtopo.DEFECT_KINDS)], "BAD_REQUEST"),
                  "%s: defect kind %d: BAD_REQUEST" % (label, len(meshtopo.DEFECT_KINDS)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--meshtopod", required=True)
    ap.add_argument("--corpus", required=True)
    ap.add_argument("names", nargs="*",
                    default=["vcg_nonmanifold", "npm_bunny", "cgal_elephant_with_holes"])
    args = ap.parse_args()

    check_table_against_lcm()
    if os.environ.get("MESHTOPO_NETNS") != "1":
        print("run me through netns-run for the daemon and CLI checks", file=sys.stderr)
        return 2

    log = tempfile.NamedTemporaryFile(prefix="meshtopod-", suffix=".log", delete=False)
    daemon = subprocess.Popen([args.meshtopod, "--heartbeat-ms", "100", "--workers", "2"],
                              stdout=subprocess.DEVNULL, stderr=log)
    try:
        p = run(args.meshtopo, "watch", "--count", "1", "--timeout-ms", "10000")
        if not check(p is not None and p.returncode == 0, "meshtopod's heartbeat"):
            return 1
        with meshtopo.Client(timeout_ms=5000, retries=3, source="every-kind") as client:
            client.wait_daemon(10_000)
            for name in args.names:
                p = run(args.meshtopo, "send", os.path.join(args.corpus, name + ".off"), "--id",
                        name, "--json", "--quiet")
                ack = json.loads(p.stdout) if p is not None and p.returncode == 0 else None
                if check(ack is not None, "%s: sent" % name):
                    check_mesh(args.meshtopo, client, name, ack["report"]["V"])
    finally:
        daemon.send_signal(signal.SIGTERM)
        try:
            rc = daemon.wait(timeout=20)
        except subprocess.TimeoutExpired:
            daemon.kill()
            rc = daemon.wait()
        log.close()
        check(rc == 0, "meshtopod exits 0 after SIGTERM (got %s)" % rc)
        if failures:
            with open(log.name, encoding="utf-8", errors="replace") as f:
                print("meshtopod log:\n" + f.read())
        os.unlink(log.name)
    print("%d failure(s)" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
