#!/usr/bin/env python3
"""`meshtopo inspect FILE --weld exact|EPS` (STL soups and any other format).

Checks, from files made here: a binary STL soup of the corpus bunny welds
back to the bunny's vertex count, closed; two tetrahedra written as ASCII
STL that touch at one corner weld into a mesh whose shared vertex the weld
made non-manifold (JSON "weld"."nonmanifold_after_weld" and the readable
line); --weld EPS merges an OFF file's near-duplicate vertices and leaves
farther ones; a bad --weld value is a usage error (exit 2).
Usage: inspect_weld_check.py --meshtopo PATH --corpus DIR
"""
import argparse
import json
import os
import struct
import subprocess
import sys
import tempfile

failures = []


def expect(ok, what, detail=""):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)
        if detail:
            print("     " + str(detail).replace("\n", "\n     "))


def read_off(path):
    words = open(path).read().split()
    nv, nf = int(words[1]), int(words[2])
    at = 4
    pos = [tuple(float(w) for w in words[at + 3 * i:at + 3 * i + 3]) for i in range(nv)]
    at += 3 * nv
    faces = []
    for _ in range(nf):
        n = int(words[at])
        faces.append([int(w) for w in words[at + 1:at + 1 + n]])
        at += 1 + n
    return pos, faces


def binary_stl(pos, faces):
    out = b"solid but binary".ljust(80, b" ") + struct.pack("<I", len(faces))
    for f in faces:
        out += struct.pack("<3f", 0, 0, 0)
        for v in f:
            out += struct.pack("<3f", *pos[v])
        out += b"\0\0"
    return out


def ascii_stl(pos, faces):
    text = "solid tetrahedra\n"
    for f in faces:
        text += " facet normal 0 0 0\n  outer loop\n"
        for v in f:
            text += "   vertex %r %r %r\n" % pos[v]
        text += "  endloop\n endfacet\n"
    return text + "endsolid tetrahedra\n"


def run(meshtopo, *args):
    return subprocess.run([meshtopo, "inspect", *args], capture_output=True, text=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--corpus", required=True)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="meshtopo-weld-") as tmp:
        pos, faces = read_off(os.path.join(a.corpus, "npm_bunny.off"))
        bunny = os.path.join(tmp, "bunny.stl")
        open(bunny, "wb").write(binary_stl(pos, faces))
        p = run(a.meshtopo, bunny, "--json")
        d = json.loads(p.stdout) if p.returncode == 0 else {}
        expect(d.get("V") == 3 * len(faces) and "weld" not in d,
               "bunny STL soup unwelded: V = 3 F, no \"weld\" key", p.stderr)
        p = run(a.meshtopo, bunny, "--weld", "exact", "--json")
        d = json.loads(p.stdout) if p.returncode == 0 else {}
        w = d.get("weld", {})
        expect(w == {"mode": "exact", "eps": 0, "vertices_before": 3 * len(faces),
                     "vertices_after": len(pos), "merged": 3 * len(faces) - len(pos),
                     "nonmanifold_after_weld": []} and d.get("V") == len(pos)
               and d.get("closed") is True,
               "bunny STL soup --weld exact: the bunny's %d vertices, closed" % len(pos),
               p.stdout[-2000:] + p.stderr)

        # two tetrahedra touching at one corner (vertex 0 and 4 at the origin)
        tpos = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0),
                (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, -1.0)]
        tet = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]]
        tfaces = tet + [[v + 4 for v in f] for f in tet]
        touch = os.path.join(tmp, "touching.stl")
        open(touch, "w").write(ascii_stl(tpos, tfaces))
        p = run(a.meshtopo, touch, "--weld", "exact", "--json")
        d = json.loads(p.stdout) if p.returncode == 0 else {}
        w = d.get("weld", {})
        expect(w.get("vertices_before") == 24 and w.get("vertices_after") == 7
               and w.get("merged") == 17 and w.get("nonmanifold_after_weld") == [0],
               "touching tetrahedra --weld exact: 7 vertices, vertex 0 made non-manifold", p.stdout + p.stderr)
        p = run(a.meshtopo, touch, "--weld", "exact")
        expect(p.returncode == 0 and "17 of 24 vertices merged, 7 left; 1 made non-manifold by "
               "the weld: 0\n" in p.stdout, "touching tetrahedra, readable weld line",
               p.stdout + p.stderr)

        # any format: an OFF triangle pair with near-duplicates 1e-7 apart
        off = os.path.join(tmp, "near.off")
        open(off, "w").write("OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n1e-7 1 0\n1 1e-7 0\n1 1 0\n"
                             "3 0 1 2\n3 3 4 5\n")
        p = run(a.meshtopo, off, "--weld", "1e-5", "--json")
        d = json.loads(p.stdout) if p.returncode == 0 else {}
        w = d.get("weld", {})
        expect(w.get("mode") == "distance" and w.get("eps") == 1e-5 and w.get("merged") == 2
               and d.get("boundary_edges") == 4, "OFF near-duplicates --weld 1e-5: 2 merged",
               p.stdout + p.stderr)
        p = run(a.meshtopo, off, "--weld", "1e-8", "--json")
        d = json.loads(p.stdout) if p.returncode == 0 else {}
        expect(d.get("weld", {}).get("merged") == 0, "OFF --weld 1e-8: none merged",
               p.stdout + p.stderr)
        for bad in ("-1", "0", "nan", "inf", "exactly", ""):
            p = run(a.meshtopo, off, "--weld", bad)
            expect(p.returncode == 2 and "--weld" in p.stderr, "--weld '%s': usage error" % bad,
                   p.stderr)
    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
