#!/usr/bin/python3
"""An archived mesh read with h5py under the documented names, without
meshtopo's code: /VTKHDF (Version [1, 0], Type "UnstructuredGrid", counts,
Points, Connectivity, Offsets, Types as uint8, CellData/original_face_id)
and /meshtopo (provenance attributes, the face list exactly as in the OFF
file, the report). Then the topology arrays of /VTKHDF (format 6) of
corpus meshes against answers worked out here from the OFF file alone
(boundary, orientation, components, non-manifold edges) and against the
corpus's reference answers (non-manifold and isolated vertices), with their
types and attributes, and (format 8) the per-kind arrays defect_<key> against
the bits of the defects bitmasks. Run with Debian's /usr/bin/python3; exit 77 without
h5py.

usage: archive_h5py_check.py --fixture PATH --corpus DIR
"""
import argparse
import os
import subprocess
import sys
import tempfile

try:
    import h5py
    import numpy as np
except ImportError:
    print("skip: h5py/numpy not installed for", sys.executable)
    sys.exit(77)

failures = []


def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def read_off(path):
    """Vertices and faces of a plain ASCII OFF file."""
    with open(path, encoding="ascii") as f:
        words = [w for line in f for w in line.split("#")[0].split()]
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    pos = 4
    verts = [[float(words[pos + 3 * i + k]) for k in range(3)] for i in range(nv)]
    pos += 3 * nv
    faces = []
    for _ in range(nf):
        n = int(words[pos])
        faces.append([int(w) for w in words[pos + 1:pos + 1 + n]])
        pos += 1 + n
    return verts, faces


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def oracle(nv, faces):
    """What the topology arrays must hold, from the face list alone: per
    kept face whether it touches a boundary edge, whether its orientation
    agrees with every neighbour across a two-face edge, its component
    (numbered by smallest face) and whether it is on a non-manifold edge;
    per vertex whether it ends a boundary edge or a non-manifold edge."""
    kept = [i for i, fc in enumerate(faces)
            if len(fc) >= 3 and len(set(fc)) == len(fc) and all(0 <= v < nv for v in fc)]
    uses = {}
    for f in kept:
        fc = faces[f]
        for i in range(len(fc)):
            a, b = fc[i], fc[(i + 1) % len(fc)]
            uses.setdefault((min(a, b), max(a, b)), []).append((f, a, b))
    parent = {f: f for f in kept}

    def find(f):
        while parent[f] != f:
            parent[f] = parent[parent[f]]
            f = parent[f]
        return f

    for edge_uses in uses.values():
        for f, _, _ in edge_uses[1:]:
            ra, rb = find(edge_uses[0][0]), find(f)
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
    roots = sorted({find(f) for f in kept})  # a root is its class's smallest face
    number = {r: i for i, r in enumerate(roots)}
    touches, consistent, component, on_nm_edge = [], [], [], []
    boundary, nm_end = [0] * nv, [0] * nv
    for key, edge_uses in uses.items():
        if len(edge_uses) == 1:
            boundary[key[0]] = boundary[key[1]] = 1
        if len(edge_uses) > 2:
            nm_end[key[0]] = nm_end[key[1]] = 1
    for f in kept:
        fc = faces[f]
        t, c, n = 0, 1, 0
        for i in range(len(fc)):
            a, b = fc[i], fc[(i + 1) % len(fc)]
            edge_uses = uses[(min(a, b), max(a, b))]
            t |= len(edge_uses) == 1
            n |= len(edge_uses) > 2
            if len(edge_uses) == 2 and all(u[1:] == (a, b) for u in edge_uses):
                c = 0
        touches.append(int(t))
        consistent.append(c)
        component.append(number[find(f)])
        on_nm_edge.append(int(n))
    return kept, touches, consistent, component, on_nm_edge, boundary, nm_end


def check_topology(fixture, corpus, tmp, name):
    """One corpus mesh archived; its topology arrays against the oracle and
    the reference answers."""
    import json
    mesh = os.path.join(corpus, name + ".off")
    verts, faces = read_off(mesh)
    nv = len(verts)
    with open(os.path.join(corpus, name + ".expected.json"), encoding="utf-8") as f:
        ref = json.load(f)
    subprocess.run([fixture, tmp, name, "1", mesh], check=True)
    kept, touches, consistent, component, on_nm_edge, boundary, nm_end = oracle(nv, faces)
    nme = 1 << 3  # nonmanifold_edge in the bits attribute, checked below
    with h5py.File(os.path.join(tmp, name + ".v1.hdf"), "r") as f:
        cd, pd = f["VTKHDF/CellData"], f["VTKHDF/PointData"]
        kinds = {"component": np.int32, "defects": np.uint32, "touches_boundary": np.uint8,
                 "orientation_consistent": np.uint8}
        for key, kind in kinds.items():
            expect(key in cd and cd[key].dtype == kind and cd[key].shape == (len(kept),),
                   f"{name}: CellData/{key} is {np.dtype(kind).name}, one per cell")
            expect(len(text(cd[key].attrs.get("description", ""))) > 20,
                   f"{name}: CellData/{key} has a description")
        for key, kind in {"boundary": np.uint8, "non_manifold": np.uint8,
                          "defects": np.uint32}.items():
            expect(key in pd and pd[key].dtype == kind and pd[key].shape == (nv,),
                   f"{name}: PointData/{key} is {np.dtype(kind).name}, one per point")
        bits = [text(b) for b in cd["defects"].attrs["bits"]]
        expect(bits[3] == "nonmanifold_edge" and bits == [text(b) for b in pd["defects"].attrs["bits"]],
               f"{name}: defects bits named, bit 3 nonmanifold_edge")
        expect("self_intersecting" not in cd and
               text(cd.attrs["self_intersecting"]).startswith("not computed"),
               f"{name}: self_intersecting not computed, and said so")
        expect(list(cd["touches_boundary"][()]) == touches, f"{name}: touches_boundary")
        expect(list(cd["orientation_consistent"][()]) == consistent,
               f"{name}: orientation_consistent")
        expect(list(cd["component"][()]) == component, f"{name}: component")
        expect(list((cd["defects"][()] & nme) != 0) == [bool(x) for x in on_nm_edge],
               f"{name}: cells on non-manifold edges")
        expect(list(pd["boundary"][()]) == boundary, f"{name}: point boundary")
        expect(list((pd["defects"][()] & nme) != 0) == [bool(x) for x in nm_end],
               f"{name}: points ending non-manifold edges")
        nm = [v for v in range(nv) if pd["non_manifold"][v]]
        head = ref["nonmanifold_vertices_list_head"]
        expect(len(nm) == ref["nonmanifold_vertices"] and nm[:len(head)] == head,
               f"{name}: non_manifold points are the reference's {ref['nonmanifold_vertices']}")
        isolated = int(np.count_nonzero(pd["defects"][()] & (1 << 6)))
        expect(isolated == ref["isolated_vertices"], f"{name}: {isolated} isolated vertices")
        # Format 8: one 0/1 array per kind beside each bitmask, named by the
        # bits attribute, attribute bit its index.
        for group, rows, where in ((cd, len(kept), "CellData"), (pd, nv, "PointData")):
            mask = group["defects"][()]
            for k, key in enumerate(bits):
                a = group.get("defect_" + key)
                expect(a is not None and a.dtype == np.uint8 and a.shape == (rows,) and
                       int(a.attrs["bit"]) == k and key in text(a.attrs["description"]) and
                       np.array_equal(a[()], ((mask >> k) & 1).astype(np.uint8)),
                       f"{name}: {where}/defect_{key} is bit {k} of defects")


# The members of a defect record, in order (README.md "Defect records").
RECORD_FIELDS = ["kind", "vertices", "faces", "edge", "face_count", "index", "position",
                 "face_size", "distinct_vertices", "fans", "on_nonmanifold_edge", "axis"]
NONE = 0xFFFFFFFF


def check_defect_records(d, num_defects, verts, faces):
    """/meshtopo/report/defects of a mesh whose defects are bad faces
    (degenerate, out-of-range indices): defect records, described, naming
    the right faces."""
    expect(list(d.dtype.names) == RECORD_FIELDS, f"defects members {d.dtype.names}")
    expect(num_defects == d.shape[0] and d.shape[0] > 0, "defects listed")
    description = text(d.attrs["description"])
    expect(all(f"{name}: " in description for name in RECORD_FIELDS) and
           "4294967295" in description, "defects description names every member")
    keys = {v: k for k, v in h5py.check_enum_dtype(d.dtype["kind"]).items()}
    rows = d[()]
    seen = set()
    for row in rows:
        kind = keys[int(row["kind"])]
        seen.add(kind)
        face = faces[int(row["faces"][0])]
        applies = {"out_of_range_index": {"faces", "index", "position"},
                   "degenerate_face": {"faces", "face_size", "distinct_vertices"}}.get(kind)
        expect(applies is not None, f"only face defects here, not {kind}")
        if applies is None:
            continue
        for name in RECORD_FIELDS[1:]:
            value = row[name]
            if name in ("vertices", "faces", "edge"):
                empty = list(value) == [NONE, NONE] if name != "faces" else value[1] == NONE
                expect(empty, f"{kind}: {name} holds no ids but the face")
            elif name not in applies:
                expect(int(value) == NONE, f"{kind}: {name} does not apply and is NONE")
        if kind == "out_of_range_index":
            pos = int(row["position"])
            expect(face[pos] == int(row["index"]) and not 0 <= face[pos] < len(verts),
                   "out_of_range_index: index is the bad entry at position")
        else:
            expect(int(row["face_size"]) == len(face) and
                   int(row["distinct_vertices"]) == len(set(face)),
                   "degenerate_face: face_size and distinct_vertices")
    expect("degenerate_face" in seen, f"defect kinds {seen}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--fixture", required=True)
    ap.add_argument("--corpus", required=True)
    args = ap.parse_args()
    # A defective corpus mesh: out-of-range indices and degenerate faces.
    mesh = os.path.join(args.corpus, "trimesh_notenoughindices.off")
    verts, faces = read_off(mesh)
    with tempfile.TemporaryDirectory(prefix="meshtopo-h5py-") as tmp:
        subprocess.run([args.fixture, tmp, "arm 1. x", "3", mesh], check=True)
        names = os.listdir(tmp)
        expect(len(names) == 1 and names[0].endswith(".hdf"), f"one .hdf file: {names}")
        with h5py.File(os.path.join(tmp, names[0]), "r") as f:
            g = f["VTKHDF"]
            expect(list(g.attrs["Version"]) == [1, 0] and g.attrs["Version"].dtype == np.int64,
                   "VTKHDF Version is int64 [1, 0]")
            t = g.attrs["Type"]
            expect((t.decode() if isinstance(t, bytes) else t) == "UnstructuredGrid",
                   "VTKHDF Type is UnstructuredGrid")
            kept = [i for i, fc in enumerate(faces)
                    if len(fc) >= 3 and len(set(fc)) == len(fc) and all(0 <= v < len(verts) for v in fc)]
            expect(g["NumberOfPoints"][0] == len(verts), "NumberOfPoints")
            expect(g["NumberOfCells"][0] == len(kept), f"NumberOfCells = {len(kept)} kept faces")
            expect(g["Types"].dtype == np.uint8, "Types are uint8")
            expect(g["Points"].shape == (len(verts), 3), "Points shape")
            expect(np.array_equal(g["Points"][()], np.array(verts).reshape(-1, 3)),
                   "Points equal the OFF vertices")
            offs = g["Offsets"][()]
            conn = g["Connectivity"][()]
            ids = g["CellData/original_face_id"][()]
            expect(list(ids) == kept, "original_face_id lists the kept faces")
            expect(all(list(conn[offs[c]:offs[c + 1]]) == faces[ids[c]] for c in range(len(kept))),
                   "each cell's connectivity is its original face")
            m = f["meshtopo"]
            for key in ("mesh_id", "version", "utime", "source", "content_hash",
                        "format_version", "num_verts", "num_faces", "num_indices"):
                expect(key in m.attrs, f"meshtopo attribute {key}")
            mid = m.attrs["mesh_id"]
            expect((mid.decode() if isinstance(mid, bytes) else mid) == "arm 1. x", "mesh_id")
            expect(int(m.attrs["version"]) == 3, "version")
            counts = m["face_vertex_counts"][()]
            flat = m["face_vertex_indices"][()]
            expect(list(counts) == [len(fc) for fc in faces], "face_vertex_counts as submitted")
            expect(list(flat) == [v for fc in faces for v in fc],
                   "face_vertex_indices as submitted, rejected faces too")
            expect(np.array_equal(m["positions"][()], np.array(verts).reshape(-1, 3)),
                   "positions as submitted")
            # The half-edge arrays (format 2) read without meshtopo: the ring of
            # each kept face, from face_halfedge along next, passes through the
            # face's vertices in order (tail of h = head of its twin h ^ 1).
            expect(int(m.attrs["format_version"]) == 8, "format_version 8")
            h = m["halfedge"]
            for key in ("head", "next", "face", "face_halfedge", "vertex_halfedge",
                        "copy_original", "copies_sorted", "bundle_offsets", "bundle_edges",
                        "bundled_sorted", "bundled_bundle", "vertex_component"):
                expect(key in h and h[key].dtype == np.uint32, f"halfedge/{key} is uint32")
            head, nxt, hface = h["head"][()], h["next"][()], h["face"][()]
            fhe, orig = h["face_halfedge"][()], h["copy_original"][()]
            expect(len(head) == int(h.attrs["num_half_edges"]), "halfedge/head length")
            # Format 4: the digest a reload checks the arrays against, documented.
            expect("digest" in h.attrs and h.attrs["digest"].dtype == np.uint64 and
                   "digest" in str(h.attrs["description"]), "halfedge digest (uint64, described)")

            def caller(v):
                return int(v) if v < len(verts) else int(orig[v - len(verts)])

            rings_ok = True
            for fi in kept:
                e, ring = int(fhe[fi]), []
                for _ in range(len(faces[fi])):
                    rings_ok = rings_ok and int(hface[e]) == fi
                    ring.append(caller(head[e ^ 1]))
                    e = int(nxt[e])
                rings_ok = rings_ok and ring == faces[fi] and e == int(fhe[fi])
            expect(rings_ok, "each kept face's half-edge ring is its vertex list")
            r = m["report"]
            expect(int(r.attrs["num_faces"]) == len(faces), "report num_faces")
            expect(int(r.attrs["num_faces_valid"]) == len(kept), "report num_faces_valid")
            check_defect_records(r["defects"], int(r.attrs["num_defects"]), verts, faces)
    with tempfile.TemporaryDirectory(prefix="meshtopo-h5py-") as tmp:
        for name in ["trimesh_notenoughindices", "vcg_nonmanifold", "cgal_many_umbrellas",
                     "assimp_malformed", "vcg_quad5", "trimesh_joined_tetrahedra",
                     "trimesh_multibody_stl_welded", "cgal_blobby_3cc", "cgal_elephant_with_holes",
                     "vcg_moebius", "cgal_prim"]:
            if os.path.exists(os.path.join(args.corpus, name + ".off")):
                check_topology(args.fixture, args.corpus, tmp, name)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
