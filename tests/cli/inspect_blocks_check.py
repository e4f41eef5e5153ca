#!/usr/bin/env python3
"""`meshtopo inspect --blocks SIZE FILE` equals `meshtopo inspect --weld exact FILE`.

For every corpus mesh (*.off, *.off.gz in --corpus), and a mesh made here
with -0.0, NaN, Inf, repeated and unreferenced positions, duplicate,
degenerate and out-of-range faces, and three sizes (tiny:
the bounding box diagonal / 64, so many blocks and seams; medium: / 4;
huge: 1e9, at most one block per octant) the --blocks JSON (with
--json-defects) is compared with --weld exact's:
  - every id-free key exactly (counts, histograms, loop lengths, flags,
    genus, "file"); the text output has the same line keys too;
  - ids: the map numbers vertices and faces in the order its blocks came,
    not the file's, so the test computes the translation itself from the
    file: blocks are cut as block_split.h says (face centroid over in-range
    corners, floor(c / SIZE), outliers in one block, ascending key, faces in
    file order, block vertices in first-use order then unreferenced ones),
    a map vertex is the exact-weld class (-0.0 == 0.0, NaN/Inf never welded)
    of its first block copy, a weld vertex the class in file order, a weld
    face the file face. Translated, the defect lists must be equal as
    multisets (without "description", and without "index" of
    out_of_range_index: the map's union writes an out-of-range entry as
    MT_NONE - r, map.h; a non-manifold edge's ends compared as a set, as
    each side writes the lower id first), nonmanifold_vertices_list_head must name
    non-manifold vertices, and the --blocks query answers must equal
    --weld exact's answers for the translated vertices and faces;
  - components and component_genera as multisets without min_face_index
    (its component order follows face ids);
  - "weld": mode, eps and vertices_after equal; vertices_before counts the
    blocks' vertices (merged = before - after); nonmanifold_after_weld are
    non-manifold vertices (relative to the blocks, not the file).
Also: bad SIZEs (0, -1, nan, inf, abc, empty) and --blocks with --weld
are usage errors (exit 2) naming --blocks; a file without positions is
refused (exit 3) with a clear message.
Usage: inspect_blocks_check.py --meshtopo PATH --corpus DIR
"""
import argparse
import collections
import glob
import gzip
import json
import math
import os
import subprocess
import sys
import tempfile

failures = []
INT32_MIN = -2**31
OUTLIER = (INT32_MIN, INT32_MIN, INT32_MIN)
CELL_LIMIT = 2.0**30


def expect(ok, what, detail=""):
    if not ok:
        print("FAIL " + what)
        failures.append(what)
        if detail:
            print("     " + str(detail)[:2000].replace("\n", "\n     "))
    return ok


def read_off(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as f:
        words = f.read().split()
    assert words[0] == "OFF", path
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


def cell(pos, face, size):
    """block_split.c's cell_of, in the same floating-point operations."""
    c = [0.0, 0.0, 0.0]
    k = 0
    for v in face:
        if 0 <= v < len(pos):
            for a in range(3):
                c[a] += pos[v][a]
            k += 1
    if k == 0:
        return OUTLIER
    q = []
    for a in range(3):
        y = c[a] / k / size
        if not math.isfinite(y):
            return OUTLIER
        x = math.floor(y)
        if x < -CELL_LIMIT or x > CELL_LIMIT:
            return OUTLIER
        q.append(x)
    return tuple(q)


def weld_class(pos, v):
    p = pos[v]
    if not all(math.isfinite(x) for x in p):
        return ("never welded", v)
    return tuple(0.0 if x == 0 else x for x in p)


def translation(pos, faces, size):
    """Map ids -> weld ids: (vertex list, face list, number of blocks)."""
    nv = len(pos)
    used = [False] * nv
    items = []
    for f, face in enumerate(faces):
        for v in face:
            if 0 <= v < nv:
                used[v] = True
        items.append((cell(pos, face, size), 0, f))
    for v in range(nv):
        if not used[v]:
            items.append((cell(pos, [v], size), 1, v))
    items.sort()
    weld_id = {}
    for v in range(nv):
        weld_id.setdefault(weld_class(pos, v), len(weld_id))
    vmap, fmap, seen = [], [], set()
    blocks = 0
    i = 0
    while i < len(items):
        j = i
        while j < len(items) and items[j][0] == items[i][0]:
            j += 1
        blocks += 1
        copies, local = [], set()
        for _, kind, x in items[i:j]:
            if kind == 0:
                fmap.append(x)
                for v in faces[x]:
                    if 0 <= v < nv and v not in local:
                        local.add(v)
                        copies.append(v)
        copies += [x for _, kind, x in items[i:j] if kind == 1]
        for v in copies:
            c = weld_class(pos, v)
            if c not in seen:
                seen.add(c)
                vmap.append(weld_id[c])
        i = j
    return vmap, fmap, blocks


def inspect(meshtopo, *args):
    return subprocess.run([meshtopo, "inspect", *args], capture_output=True, text=True)


def inspect_json(meshtopo, what, *args):
    p = inspect(meshtopo, *args)
    if not expect(p.returncode == 0, what + ": exit 0", p.stderr):
        return None
    return json.loads(p.stdout)


def canon(x):
    return json.dumps(x, sort_keys=True)


def multiset(items):
    return collections.Counter(canon(x) for x in items)


ID_KEYS = {"weld", "nonmanifold_vertices_list_head", "components", "component_genera",
           "vertex_queries", "face_queries", "defects"}


def translate_defect(d, vmap, fmap):
    d = dict(d)
    d.pop("description", None)
    if d.get("kind") == "out_of_range_index":
        d.pop("index", None)
    tv = lambda v: vmap[v] if 0 <= v < len(vmap) else ("bad vertex", v)
    tf = lambda f: fmap[f] if 0 <= f < len(fmap) else ("bad face", f)
    d["vertices"] = [tv(v) for v in d.get("vertices") or []]
    d["faces"] = sorted(tf(f) for f in d.get("faces") or [])
    if d.get("edge") is not None:
        d["edge"] = [tv(v) for v in d["edge"]]
    if d.get("kind") == "nonmanifold_edge":
        # An undirected edge, written lower id first in each numbering.
        d["vertices"] = sorted(d["vertices"], key=str)
        d["edge"] = sorted(d["edge"], key=str)
    return d


def strip_component(c):
    c = dict(c)
    c.pop("min_face_index", None)
    return c


def line_keys(text):
    return [line.split(":", 1)[0] for line in text.splitlines()
            if line and not line.startswith(" ") and ":" in line]


def check_mesh(meshtopo, path):
    name = os.path.basename(path)
    pos, faces = read_off(path)
    weld = inspect_json(meshtopo, name + " --weld exact", path, "--weld", "exact",
                        "--json-defects")
    if weld is None:
        return
    plain = inspect_json(meshtopo, name + " unwelded", path, "--json")
    if plain is None or not expect(plain["V"] == len(pos) and plain["F"] == len(faces),
                                   name + ": the test reads the file as meshtopo does",
                                   (plain and (plain["V"], plain["F"]), len(pos), len(faces))):
        return
    weld_nm = {d["vertices"][0] for d in weld["defects"] if d["kind"] == "nonmanifold_vertex"}
    finite = [p for p in pos if all(math.isfinite(x) for x in p)]
    diag = 1.0
    if finite:
        diag = math.dist([min(p[a] for p in finite) for a in range(3)],
                         [max(p[a] for p in finite) for a in range(3)]) or 1.0
    for label, size in (("tiny", diag / 64), ("medium", diag / 4), ("huge", 1e9)):
        what = "%s --blocks %r (%s)" % (name, size, label)
        size_text = repr(size)
        blocks = inspect_json(meshtopo, what, "--blocks", size_text, path, "--json-defects")
        if blocks is None:
            continue
        vmap, fmap, nblocks = translation(pos, faces, float(size_text))
        if not expect(len(vmap) == blocks["V"] and len(fmap) == blocks["F"],
                      what + ": the translation covers the map",
                      (len(vmap), len(fmap), blocks["V"], blocks["F"])):
            continue
        # id-free keys
        keys = set(weld) | set(blocks)
        for k in sorted(keys - ID_KEYS):
            expect(weld.get(k) == blocks.get(k), "%s: key %s" % (what, k),
                   "weld %s\nblocks %s" % (canon(weld.get(k))[:300], canon(blocks.get(k))[:300]))
        expect(list(weld) == list(blocks), what + ": same keys in the same order",
               (list(weld), list(blocks)))
        # weld
        wb, ww = blocks.get("weld", {}), weld["weld"]
        expect(wb.get("mode") == ww["mode"] and wb.get("eps") == ww["eps"] and
               wb.get("vertices_after") == ww["vertices_after"] and
               wb.get("merged") == wb.get("vertices_before", 0) - wb.get("vertices_after", 0) and
               set(wb) == set(ww), what + ": weld", (wb, ww))
        expect({vmap[v] for v in wb.get("nonmanifold_after_weld", [])} <= weld_nm,
               what + ": weld.nonmanifold_after_weld are non-manifold vertices")
        # components
        expect(multiset(strip_component(c) for c in blocks["components"]) ==
               multiset(strip_component(c) for c in weld["components"]),
               what + ": components (multiset, without min_face_index)")
        expect(multiset(blocks["component_genera"]) == multiset(weld["component_genera"]),
               what + ": component_genera (multiset)")
        # defects and the list head, translated
        mine = multiset(translate_defect(d, vmap, fmap) for d in blocks["defects"])
        theirs = multiset(translate_defect(d, list(range(len(vmap))), list(range(len(fmap))))
                          for d in weld["defects"])
        expect(mine == theirs, what + ": defects, translated (multiset)",
               "only --blocks: %s\nonly --weld: %s" % (list((mine - theirs).elements())[:5],
                                                      list((theirs - mine).elements())[:5]))
        head = blocks["nonmanifold_vertices_list_head"]
        expect(len(head) == len(weld["nonmanifold_vertices_list_head"]) and
               {vmap[v] for v in head} <= weld_nm, what + ": nonmanifold_vertices_list_head")
        # queries: --weld exact asked about the translated elements
        vq = [vmap[q["vertex"]] for q in blocks["vertex_queries"]]
        fq = [fmap[q["face"]] for q in blocks["face_queries"]]
        args = [path, "--weld", "exact", "--json"]
        if vq:
            args += ["--vertices", ",".join(map(str, vq))]
        if fq:
            args += ["--faces", ",".join(map(str, fq))]
        asked = inspect_json(meshtopo, what + ": --weld exact on the translated queries", *args)
        if asked is not None:
            mine_v = [{"vertex": vmap[q["vertex"]],
                       "neighbors": sorted(vmap[w] for w in q["neighbors"]),
                       "faces": sorted(fmap[f] for f in q["faces"])}
                      for q in blocks["vertex_queries"]]
            mine_f = [{"face": fmap[q["face"]],
                       "adjacent_faces": None if q["adjacent_faces"] is None else
                       sorted(fmap[g] for g in q["adjacent_faces"])}
                      for q in blocks["face_queries"]]
            expect(mine_v == asked["vertex_queries"], what + ": vertex queries, translated",
                   (mine_v, asked["vertex_queries"]))
            expect(mine_f == asked["face_queries"], what + ": face queries, translated",
                   (mine_f, asked["face_queries"]))
        # the text report: same line keys, the block count as computed here
        if label == "tiny":
            t_blocks = inspect(meshtopo, "--blocks", size_text, path)
            t_weld = inspect(meshtopo, path, "--weld", "exact")
            expect(t_blocks.returncode == 0 and
                   line_keys(t_blocks.stdout) == line_keys(t_weld.stdout),
                   what + ": text has the line keys of --weld exact",
                   (t_blocks.stderr, line_keys(t_blocks.stdout), line_keys(t_weld.stdout)))
            expect("map of %d block" % nblocks in t_blocks.stdout,
                   what + ": text names %d blocks" % nblocks)
        print("ok   %s: %d blocks, V %d, F %d" % (what, nblocks, blocks["V"], blocks["F"]))


def check_usage(meshtopo, corpus):
    mesh = os.path.join(corpus, "cgal_tetrahedron.off")
    for bad in ("0", "-1", "-0", "nan", "inf", "abc", "", "1x", "1e999"):
        p = inspect(meshtopo, "--blocks", bad, mesh)
        expect(p.returncode == 2 and "--blocks" in p.stderr and p.stdout == "",
               "--blocks %r is a usage error" % bad, (p.returncode, p.stderr))
    p = inspect(meshtopo, "--blocks", "1", "--weld", "exact", mesh)
    expect(p.returncode == 2 and "--blocks" in p.stderr, "--blocks with --weld: usage error",
           (p.returncode, p.stderr))
    p = inspect(meshtopo, "--help")
    expect(p.returncode == 0 and "--blocks" in p.stdout and "union" in p.stdout,
           "--help explains --blocks", p.stdout[-800:])
    with tempfile.TemporaryDirectory(prefix="meshtopo-blocks-") as tmp:
        nopos = os.path.join(tmp, "nopos.ply")
        with open(nopos, "w") as f:
            f.write("ply\nformat ascii 1.0\nelement vertex 3\nproperty float red\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                    "1\n2\n3\n3 0 1 2\n")
        p = inspect(meshtopo, "--blocks", "1", nopos)
        expect(p.returncode == 3 and "nopos.ply" in p.stderr and "x, y, z" in p.stderr,
               "a file without positions is refused", (p.returncode, p.stderr))
    print("ok   usage errors")


def edge_cases_off():
    """A mesh with what the corpus lacks: -0.0 next to 0.0, repeated
    positions under other ids, NaN and Inf vertices shared by faces,
    unreferenced vertices (one at a used position), a duplicate face,
    degenerate and out-of-range records."""
    pos, faces = [], []
    for y in range(5):
        for x in range(5):
            pos.append(("-0" if x == 0 else str(x * 0.25), str(y * 0.25), "0"))
    for y in range(4):
        for x in range(4):
            a = 5 * y + x
            faces.append([a, a + 1, a + 6, a + 5])
    pos += [("0.25", "0.25", "0"), ("0.5", "0.5", "-0.0")]  # 25, 26: copies of 6, 12
    faces += [[25, 7, 11], [26, 13, 17]]
    pos += [("nan", "2", "0"), ("inf", "2", "1"), ("1", "2", "0")]  # 27, 28, 29
    faces += [[27, 28, 29], [28, 27, 20], [29, 24, 27]]
    pos += [("0.75", "0.75", "0"), ("nan", "0", "0"), ("5", "5", "5")]  # unreferenced
    faces += [[0, 1, 6, 5], [1, 1, 2], [3, 40, 4], [4, 4294967295, 40], [7]]
    lines = ["OFF", "%d %d 0" % (len(pos), len(faces))]
    lines += [" ".join(p) for p in pos]
    lines += [" ".join(str(v) for v in [len(f)] + f) for f in faces]
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--corpus", required=True)
    a = ap.parse_args()
    meshes = sorted(glob.glob(os.path.join(a.corpus, "*.off")) +
                    glob.glob(os.path.join(a.corpus, "*.off.gz")))
    expect(len(meshes) >= 10, "the corpus has meshes", meshes)
    check_usage(a.meshtopo, a.corpus)
    for path in meshes:
        check_mesh(a.meshtopo, path)
    with tempfile.TemporaryDirectory(prefix="meshtopo-blocks-") as tmp:
        path = os.path.join(tmp, "edge_cases.off")
        with open(path, "w") as f:
            f.write(edge_cases_off())
        check_mesh(a.meshtopo, path)
    if failures:
        print("%d failure(s)" % len(failures))
        return 1
    print("all ok (%d meshes)" % len(meshes))
    return 0


if __name__ == "__main__":
    sys.exit(main())
