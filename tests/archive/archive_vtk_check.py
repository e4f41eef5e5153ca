#!/usr/bin/python3
"""Archived corpus meshes opened with VTK 9.1's vtkHDFReader (Debian's
python3-vtk9): the right numbers of points and cells, a cell's vertex ids,
CellData original_face_id mapping cells back to faces, and the topology
arrays (format 6) visible to VTK with a value per cell or point, of the
documented types, arrays HDF5 never stored (one value throughout) read as
that value; self_intersecting when the archive was asked for it. Run with
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


CELL_ARRAYS = {"component": vtk.VTK_INT, "defects": vtk.VTK_UNSIGNED_INT,
               "touches_boundary": vtk.VTK_UNSIGNED_CHAR,
               "orientation_consistent": vtk.VTK_UNSIGNED_CHAR}
POINT_ARRAYS = {"boundary": vtk.VTK_UNSIGNED_CHAR, "non_manifold": vtk.VTK_UNSIGNED_CHAR,
                "defects": vtk.VTK_UNSIGNED_INT}


def values(array):
    return [int(array.GetValue(i)) for i in range(array.GetNumberOfTuples())]


def check_topology(name, out, nv, cells, faces, kept):
    for group, arrays, rows in ((out.GetCellData(), CELL_ARRAYS, cells),
                                (out.GetPointData(), POINT_ARRAYS, nv)):
        for key, kind in arrays.items():
            a = group.GetArray(key)
            expect(a is not None and a.GetNumberOfTuples() == rows and
                   a.GetNumberOfComponents() == 1 and a.GetDataType() == kind,
                   f"{name}: {key} has {rows} values of VTK type {kind}")
    expect(out.GetCellData().GetArray("self_intersecting") is None,
           f"{name}: no self_intersecting unless asked for")
    # Values VTK reads, against the face list: boundary edges (used by one
    # kept face) and the orientation across two-face edges.
    uses = {}
    for f in kept:
        fc = faces[f]
        for i in range(len(fc)):
            a, b = fc[i], fc[(i + 1) % len(fc)]
            uses.setdefault((min(a, b), max(a, b)), []).append((a, b))
    touches = [int(any(len(uses[(min(a, b), max(a, b))]) == 1
                       for a, b in zip(faces[f], faces[f][1:] + faces[f][:1]))) for f in kept]
    consistent = [int(not any(len(u) == 2 and u[0] == u[1]
                              for u in (uses[(min(a, b), max(a, b))]
                                        for a, b in zip(faces[f], faces[f][1:] + faces[f][:1]))))
                  for f in kept]
    cd = out.GetCellData()
    if cd.GetArray("touches_boundary") is not None:
        expect(values(cd.GetArray("touches_boundary")) == touches, f"{name}: touches_boundary")
    if cd.GetArray("orientation_consistent") is not None:
        expect(values(cd.GetArray("orientation_consistent")) == consistent,
               f"{name}: orientation_consistent")


def check_self_intersections(fixture, tmp):
    """The octahedron of test_archive's topology_self_intersections (top apex
    pushed through face 4): faces 1 to 4 meet another face."""
    path = os.path.join(tmp, "octahedron.off")
    with open(path, "w", encoding="ascii") as f:
        f.write("OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0.5 0.5 -0.5\n0 0 -1\n")
        for face in ((0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4),
                     (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)):
            f.write("3 %d %d %d\n" % face)
    subprocess.run([fixture, tmp, "octahedron", "1", path, "--self-intersections"], check=True)
    reader = vtk.vtkHDFReader()
    reader.SetFileName(os.path.join(tmp, "octahedron.v1.hdf"))
    reader.Update()
    a = reader.GetOutput().GetCellData().GetArray("self_intersecting")
    expect(a is not None and a.GetDataType() == vtk.VTK_UNSIGNED_CHAR and
           values(a) == [0, 1, 1, 1, 1, 0, 0, 0],
           "octahedron pushed through: self_intersecting is 1 on faces 1 to 4")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--fixture", required=True)
    ap.add_argument("--corpus", required=True)
    args = ap.parse_args()
    names = ["cgal_torus_quad", "vcg_nonmanifold", "trimesh_notenoughindices", "npm_teapot",
             "assimp_malformed", "vcg_quad5", "cgal_elephant_with_holes",
             "trimesh_multibody_stl_welded"]
    with tempfile.TemporaryDirectory(prefix="meshtopo-vtk-") as tmp:
        for name in names:
            mesh = os.path.join(args.corpus, name + ".off")
            if not os.path.exists(mesh):
                continue
            subprocess.run([args.fixture, tmp, name, "1", mesh], check=True)
            nv, faces = read_off(mesh)
            kept = [i for i, fc in enumerate(faces)
                    if len(fc) >= 3 and len(set(fc)) == len(fc) and all(0 <= v < nv for v in fc)]
            path = os.path.join(tmp, name + ".v1.hdf")
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
            check_topology(name, out, nv, len(kept), faces, kept)
            if kept and ids is not None:
                c = len(kept) // 2
                cell = out.GetCell(c)
                got = [cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]
                face = int(ids.GetValue(c))
                expect(face == kept[c] and got == faces[face],
                       f"{name}: cell {c} is face {kept[c]} {faces[kept[c]]}, got {face} {got}")
        check_self_intersections(args.fixture, tmp)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
