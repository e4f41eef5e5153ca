#!/usr/bin/python3
"""An archive written with Blosc LZ4 compression (mt_archive_write_options,
meshtopod's default when HDF5 finds the plugin) read by other people's
tools with Debian's filter package (hdf5-filter-plugin-blosc-serial): h5py
sees filter 32001 on the large datasets and reads them back equal to an
uncompressed archive of the same mesh, and VTK 9.1's vtkHDFReader loads the
mesh with its cells and topology arrays. The file is smaller than the
uncompressed one. Run with /usr/bin/python3; exit 77 without h5py or vtk.

usage: archive_compressed_check.py --fixture PATH
"""
import argparse
import os
import subprocess
import sys
import tempfile

# ParaView's VTK modules (python3-paraview, which the test dependencies
# install in place of python3-vtk9) link the MPI build of HDF5, whose plugin
# directory Debian's filter packages leave empty: as the README tells
# ParaView's users, point HDF5_PLUGIN_PATH at the serial build's plugins,
# which that HDF5 loads too. h5py and python3-vtk9 (serial HDF5) find them
# without it.
if "HDF5_PLUGIN_PATH" not in os.environ:
    import glob
    found = glob.glob("/usr/lib/*/hdf5/serial/plugins")
    if found:
        os.environ["HDF5_PLUGIN_PATH"] = found[0]

try:
    import h5py
    import numpy as np
    import vtk
except ImportError as e:
    print("skip:", e, "for", sys.executable)
    sys.exit(77)

BLOSC = 32001
failures = []


def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def write_grid(path, n):
    """An n x n grid of quads split into triangles, with a hole (the middle
    quad left out) so that the topology arrays are not all one value."""
    faces = []
    for i in range(n - 1):
        for j in range(n - 1):
            if i == j == n // 2:
                continue
            a, b, c, d = i * n + j, i * n + j + 1, (i + 1) * n + j + 1, (i + 1) * n + j
            faces += [(a, b, c), (a, c, d)]
    with open(path, "w", encoding="ascii") as f:
        f.write("OFF\n%d %d 0\n" % (n * n, len(faces)))
        for i in range(n):
            for j in range(n):
                f.write("%r %r %r\n" % (j * 0.01, i * 0.01, 0.001 * ((i * 7 + j * 13) % 11)))
        for face in faces:
            f.write("3 %d %d %d\n" % face)
    return n * n, faces


def datasets(h5file):
    out = {}
    h5file.visititems(lambda name, obj: out.__setitem__(name, obj)
                      if isinstance(obj, h5py.Dataset) else None)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--fixture", required=True)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="meshtopo-lz4-") as tmp:
        mesh = os.path.join(tmp, "grid.off")
        nv, faces = write_grid(mesh, 120)
        subprocess.run([args.fixture, tmp, "plain", "1", mesh], check=True)
        subprocess.run([args.fixture, tmp, "packed", "1", mesh, "--compression", "lz4"],
                       check=True)
        plain = os.path.join(tmp, "plain.v1.hdf")
        packed = os.path.join(tmp, "packed.v1.hdf")
        expect(os.path.getsize(packed) < os.path.getsize(plain) / 2,
               "lz4: %d bytes against %d uncompressed" %
               (os.path.getsize(packed), os.path.getsize(plain)))
        with h5py.File(plain, "r") as p, h5py.File(packed, "r") as q:
            a, b = datasets(p), datasets(q)
            expect(sorted(a) == sorted(b), "h5py: the same datasets in both files")
            filtered = [n for n, d in b.items()
                        if d.chunks is not None and str(BLOSC) in d._filters]
            expect("VTKHDF/Connectivity" in filtered and "meshtopo/halfedge/next" in filtered,
                   "h5py: large datasets carry filter %d (%d of them)" % (BLOSC, len(filtered)))
            same = [n for n in a if n in b and a[n].shape == b[n].shape and
                    np.array_equal(a[n][()], b[n][()])]
            expect(len(same) == len(a), "h5py: every dataset reads back equal (%d of %d)"
                   % (len(same), len(a)))
        reader = vtk.vtkHDFReader()
        reader.SetFileName(packed)
        reader.Update()
        out = reader.GetOutput()
        expect(out.GetNumberOfPoints() == nv and out.GetNumberOfCells() == len(faces),
               "vtkHDFReader: %d points and %d cells" % (nv, len(faces)))
        cell = out.GetCell(len(faces) // 2)
        expect([cell.GetPointId(k) for k in range(3)] == list(faces[len(faces) // 2]),
               "vtkHDFReader: a cell's vertex ids")
        touches = out.GetCellData().GetArray("touches_boundary")
        expect(touches is not None and touches.GetNumberOfTuples() == len(faces) and
               0 < sum(int(touches.GetValue(i)) for i in range(len(faces))) < len(faces),
               "vtkHDFReader: touches_boundary, some faces on the boundary")
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
