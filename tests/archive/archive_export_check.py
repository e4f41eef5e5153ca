#!/usr/bin/python3
"""`meshtopo archive export` to the VTK formats and to PLY with defect
colours, on corpus meshes archived with archive_fixture: .vtu (read with
VTK's XML reader) and .hdf / .vtkhdf (VTK's vtkHDFReader) have a point per
vertex, a cell per kept face and the topology arrays, self_intersecting
only with --self-intersections; the PLY keeps the face list exactly as
submitted (positions bit for bit, rejected faces too) and colours each
vertex and face as `meshtopo render` marks them (non-manifold magenta,
boundary red, rejected orange, self-intersecting yellow, flipped blue).
Run with /usr/bin/python3 (python3-vtk9); exit 77 without the vtk module.

usage: archive_export_check.py --meshtopo PATH --fixture PATH --corpus DIR
"""
import argparse
import os
import struct
import subprocess
import sys
import tempfile

try:
    import vtk
except ImportError:
    print("skip: vtk not installed for", sys.executable)
    sys.exit(77)

failures = []

GREY, RED, MAGENTA = (184, 184, 184), (255, 0, 0), (255, 0, 255)
ORANGE, YELLOW, BLUE = (255, 140, 0), (255, 220, 0), (70, 130, 255)
TOPOLOGY = {"cell": ["component", "defects", "touches_boundary", "orientation_consistent",
                     "original_face_id"],
            "point": ["boundary", "non_manifold", "defects"]}


def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def read_off(path):
    with open(path, encoding="ascii") as f:
        words = [w for line in f for w in line.split("#")[0].split()]
    nv, nf = int(words[1]), int(words[2])
    verts = [float(w) for w in words[4:4 + 3 * nv]]
    pos = 4 + 3 * nv
    faces = []
    for _ in range(nf):
        n = int(words[pos])
        faces.append([int(w) for w in words[pos + 1:pos + 1 + n]])
        pos += 1 + n
    return verts, faces


def read_colored_ply(path):
    """The binary little-endian PLY meshtopo writes: positions, colours,
    faces and their colours."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    nv = int(next(l for l in header if l.startswith("element vertex")).split()[2])
    nf = int(next(l for l in header if l.startswith("element face")).split()[2])
    count_type = next(l for l in header if "vertex_indices" in l).split()[2]
    count_fmt = {"uchar": "B", "ushort": "H", "uint": "I"}[count_type]
    assert header.count("property uchar red") == 2, header
    pos, verts, vcolors, faces, fcolors = end, [], [], [], []
    for _ in range(nv):
        verts.extend(struct.unpack_from("<3d", data, pos))
        vcolors.append(tuple(data[pos + 24:pos + 27]))
        pos += 27
    for _ in range(nf):
        (n,) = struct.unpack_from("<" + count_fmt, data, pos)
        pos += struct.calcsize(count_fmt)
        faces.append(list(struct.unpack_from(f"<{n}i", data, pos)))
        pos += 4 * n
        fcolors.append(tuple(data[pos:pos + 3]))
        pos += 3
    assert pos == len(data), (pos, len(data))
    return verts, vcolors, faces, fcolors


def read_vtk(path):
    reader = vtk.vtkXMLUnstructuredGridReader() if path.endswith(".vtu") else vtk.vtkHDFReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def values(array):
    return [int(array.GetValue(i)) for i in range(array.GetNumberOfTuples())]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--fixture", required=True)
    ap.add_argument("--corpus", required=True)
    args = ap.parse_args()

    def export(d, mesh_id, out, *options):
        p = subprocess.run([args.meshtopo, "archive", "export", d, mesh_id, out, *options],
                           capture_output=True, text=True, timeout=300,
                           env=dict(os.environ, TMPDIR=scratch))
        return p.returncode, p.stderr.strip()

    with tempfile.TemporaryDirectory(prefix="meshtopo-export-") as tmp:
        scratch = os.path.join(tmp, "scratch")  # the tool's temporary files
        os.mkdir(scratch)
        d = os.path.join(tmp, "archive")
        meshes = {"nm": "vcg_nonmanifold", "bad": "assimp_malformed",
                  "holes": "cgal_elephant_with_holes", "flipped": "vcg_quad5"}
        for mesh_id, name in meshes.items():
            subprocess.run([args.fixture, d, mesh_id, "1",
                            os.path.join(args.corpus, name + ".off")], check=True)
        # An archive file named as earlier versions named them exports too.
        os.rename(os.path.join(d, "flipped.v1.hdf"), os.path.join(d, "flipped.v1.vtkhdf"))

        # ---- VTK formats: the holes mesh with and without its self-intersections.
        verts, faces = read_off(os.path.join(args.corpus, meshes["holes"] + ".off"))
        nv = len(verts) // 3
        selfx = {}
        for out_name, options in (("holes.vtu", ["--self-intersections"]),
                                  ("holes.hdf", ["--self-intersections"]),
                                  ("holes.vtkhdf", []), ("plain.vtu", [])):
            out = os.path.join(tmp, out_name)
            code, err = export(d, "holes", out, *options)
            expect(code == 0 and os.path.exists(out), f"export holes to {out_name} ({code}, {err})")
            if code != 0:
                continue
            grid = read_vtk(out)
            expect(grid.GetNumberOfPoints() == nv and grid.GetNumberOfCells() == len(faces),
                   f"{out_name}: {nv} points, {len(faces)} cells "
                   f"({grid.GetNumberOfPoints()}, {grid.GetNumberOfCells()})")
            for kind, names in TOPOLOGY.items():
                data = grid.GetCellData() if kind == "cell" else grid.GetPointData()
                rows = len(faces) if kind == "cell" else nv
                for key in names:
                    a = data.GetArray(key)
                    expect(a is not None and a.GetNumberOfTuples() == rows,
                           f"{out_name}: {kind} array {key} with {rows} values")
            a = grid.GetCellData().GetArray("self_intersecting")
            if options:
                expect(a is not None and sum(values(a)) > 0,
                       f"{out_name}: self_intersecting marks faces")
                if a is not None:
                    selfx[out_name] = values(a)
            else:
                expect(a is None, f"{out_name}: no self_intersecting unless asked for")
            cell = grid.GetCell(7)
            expect([cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())] == faces[7],
                   f"{out_name}: cell 7 is face 7")
        expect(len(selfx) == 2 and selfx["holes.vtu"] == selfx["holes.hdf"],
               ".vtu and .hdf agree on self_intersecting")

        # ---- PLY: the face list as submitted, coloured.
        for mesh_id, options in (("nm", []), ("bad", []), ("holes", ["--self-intersections"]),
                                 ("flipped", [])):
            out = os.path.join(tmp, mesh_id + ".ply")
            code, err = export(d, mesh_id, out, *options)
            expect(code == 0, f"export {mesh_id} to PLY ({code}, {err})")
            if code != 0:
                continue
            verts, faces = read_off(os.path.join(args.corpus, meshes[mesh_id] + ".off"))
            pverts, vcolors, pfaces, fcolors = read_colored_ply(out)
            expect(pverts == verts and pfaces == faces,
                   f"{mesh_id}.ply: the face list exactly as submitted")
            if mesh_id == "nm":
                # Edge 7-8 is used by faces 2, 3, 4; every other side is a boundary.
                expect(vcolors[7] == MAGENTA and vcolors[8] == MAGENTA,
                       f"nm: vertices 7 and 8 magenta ({vcolors[7]}, {vcolors[8]})")
                expect(all(vcolors[v] == RED for v in range(11) if v not in (7, 8)),
                       "nm: the other vertices end boundary edges: red")
                expect(fcolors == [GREY, GREY, MAGENTA, MAGENTA, MAGENTA],
                       f"nm: faces on the non-manifold edge magenta ({fcolors})")
            if mesh_id == "bad":
                rejected = [f for f, fc in enumerate(faces)
                            if len(set(fc)) < len(fc) or len(fc) < 3 or
                            any(not 0 <= v < len(verts) // 3 for v in fc)]
                expect(rejected and all(fcolors[f] == ORANGE for f in rejected),
                       f"bad: rejected faces {rejected} orange")
                corners = {v for f in rejected for v in faces[f] if 0 <= v < len(verts) // 3}
                expect(all(vcolors[v] in (ORANGE, MAGENTA) for v in corners),
                       f"bad: their corners {sorted(corners)} orange")
                expect(any(c == BLUE for c in fcolors), "bad: its flipped faces blue")
            if mesh_id == "holes":
                marked = [int(c == YELLOW) for c in fcolors]
                expect(marked == selfx.get("holes.vtu"),
                       "holes: yellow faces are the self_intersecting ones")
                expect(any(c == RED for c in vcolors) and GREY in vcolors,
                       "holes: boundary vertices red, others grey")
            if mesh_id == "flipped":
                expect(BLUE in fcolors, "flipped (an archive file named .vtkhdf): blue faces")

        # ---- usage errors
        code, err = export(d, "nm", os.path.join(tmp, "x.off"), "--self-intersections")
        expect(code == 2 and "--self-intersections" in err,
               f"--self-intersections with .off: exit 2 ({err})")
        code, err = export(d, "nm", os.path.join(tmp, "x.vtk"))
        expect(code == 2 and ".vtu" in err, f"unknown suffix: exit 2 naming the formats ({err})")
        code, err = export(d, "nm", os.path.join(tmp, "missing-dir", "x.vtu"))
        expect(code == 3, f"unwritable .vtu: exit 3 ({err})")
        code, err = export(d, "nm", os.path.join(tmp, "missing-dir", "x.hdf"))
        expect(code == 3 and "missing-dir" in err, f"unwritable .hdf: exit 3 ({err})")
        expect(not os.listdir(scratch),
               f"no temporary file left behind ({os.listdir(scratch)})")
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
