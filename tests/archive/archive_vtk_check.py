#!/usr/bin/python3
"""Archived corpus meshes opened with VTK 9.1's vtkHDFReader (Debian's
python3-vtk9): the right numbers of points and cells, a cell's vertex ids,
and CellData original_face_id mapping cells back to faces. Run with
/usr/bin/python3; exit 77 without the vtk module.

usage: archive_vtk_check.py --fixture PATH --corpus DIR
"""
import argparse
import os
import subprocess
import sys
import tempfile

try:
    import vtk
except ImportError:
    print("skip: vtk not installed for", sys.executable)
    sys.exit(77)

failures = []


def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def read_off(path):
    with open(path, encoding="ascii") as f:
        words = [w for line in f for w in line.split("#")[0].split()]
    nv, nf = int(words[1]), int(words[2])
    pos = 4 + 3 * nv
    faces = []
    for _ in range(nf):
        n = int(words[pos])
        faces.append([int(w) for w in words[pos + 1:pos + 1 + n]])
        pos += 1 + n
    return nv, faces


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--fixture", required=True)
    ap.add_argument("--corpus", required=True)
    args = ap.parse_args()
    names = ["cgal_torus_quad", "vcg_nonmanifold", "trimesh_notenoughindices", "npm_teapot",
             "assimp_malformed", "vcg_quad5"]
    with tempfile.TemporaryDirectory(prefix="meshtopo-vtk-") as tmp:
        for name in names:
            mesh = os.path.join(args.corpus, name + ".off")
            if not os.path.exists(mesh):
                continue
            subprocess.run([args.fixture, tmp, name, "1", mesh], check=True)
            nv, faces = read_off(mesh)
            kept = [i for i, fc in enumerate(faces)
                    if len(fc) >= 3 and len(set(fc)) == len(fc) and all(0 <= v < nv for v in fc)]
            path = os.path.join(tmp, name + ".v1.vtkhdf")
            reader = vtk.vtkHDFReader()
            expect(reader.CanReadFile(path) == 1, f"{name}: vtkHDFReader can read it")
            reader.SetFileName(path)
            reader.Update()
            out = reader.GetOutput()
            expect(out.GetNumberOfPoints() == nv, f"{name}: {nv} points")
            expect(out.GetNumberOfCells() == len(kept), f"{name}: {len(kept)} cells")
            ids = out.GetCellData().GetArray("original_face_id")
            expect(ids is not None and ids.GetNumberOfTuples() == len(kept),
                   f"{name}: CellData original_face_id")
            if kept and ids is not None:
                c = len(kept) // 2
                cell = out.GetCell(c)
                got = [cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]
                face = int(ids.GetValue(c))
                expect(face == kept[c] and got == faces[face],
                       f"{name}: cell {c} is face {kept[c]} {faces[kept[c]]}, got {face} {got}")
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
