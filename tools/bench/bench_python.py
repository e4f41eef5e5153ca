#!/usr/bin/env python3
"""The Python binding's build cost against the C library's, in one run.

Builds the benchmark's triangle grid (mt_gen_grid, sized as meshtopo-bench
sizes it: 707 x 707 cells, 999,698 triangles, for 1M faces), copied into
numpy arrays as a user holds them: positions (V, 3) float64 and faces (F, 3)
int32. Then, alternating, times

  C       one foreign call to mt_mesh_build on a face list pointing at those
          arrays (the library's own time: the call costs microseconds);
  Python  meshtopo.Mesh(positions, faces): checking the arrays, handing them
          over without copies, the build and the Mesh object,

each with the same build options (threads as given; no workspace, so every
build takes new memory), the mesh destroyed outside the timed span. Prints
the median of each and their ratio, for the grid in its natural order and
shuffled (mt_face_list_permute), as scans arrive.

usage: bench_python.py [--faces N] [--repetitions R] [--threads T]
       (with MESHTOPO_PYTHON_LIBRARY pointing at a build's
       libmeshtopo-python.so, or an installed package)
"""
import argparse
import ctypes
import math
import os
import statistics
import sys
import time

try:
    import meshtopo
except ImportError:
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                    "lib", "python"))
    import meshtopo
import numpy as np
from meshtopo import _lib


def grid_size(faces):
    """nx, ny as meshtopo-bench chooses them (tools/bench/bench_input.c)."""
    cells = max(faces, 2) / 2.0
    x = max(math.floor(math.sqrt(cells)), 1)
    y = max(math.floor(cells / x + 0.5), 1)
    return int(x), int(y)


def grid_arrays(faces, permuted):
    """The grid as fresh numpy arrays: positions (V, 3) float64, faces (F, 3) int32."""
    gen = _lib._declare("mt_gen_grid", _lib.c_int, _lib.c_u32, _lib.c_u32, _lib.c_bool,
                        _lib.P(_lib.FaceListStruct))
    permute = _lib._declare("mt_face_list_permute", _lib.c_int, _lib.P(_lib.FaceListStruct),
                            _lib.c_u64, _lib.P(_lib.Diag))
    nx, ny = grid_size(faces)
    fl = _lib.FaceListStruct()
    meshtopo.errors.check(gen(nx, ny, True, fl))
    try:
        if permuted:
            meshtopo.errors.check(permute(fl, 1, None))
        positions = np.ctypeslib.as_array(ctypes.cast(fl.positions, _lib.P(ctypes.c_double)),
                                          (fl.num_verts, 3)).copy()
        indices = np.ctypeslib.as_array(ctypes.cast(fl.face_indices, _lib.P(ctypes.c_uint32)),
                                        (fl.num_faces, 3)).astype(np.int32)
    finally:
        _lib.mt_face_list_free(fl)
    return "grid %dx%d" % (nx, ny), positions, indices


def face_list(positions, faces):
    """The mt_face_list of the arrays, as a C program would set it up (its
    face sizes made once, outside the timings)."""
    counts = np.full(len(faces), 3, np.uint32)
    fl = _lib.FaceListStruct(len(positions), len(faces), faces.size, positions.ctypes.data,
                             counts.ctypes.data, faces.ctypes.data)
    return fl, counts


def time_c(fl, threads):
    options = _lib.BuildOptions(False, threads, None)
    mesh, diag = _lib.c_ptr(), _lib.Diag()
    t0 = time.perf_counter()
    code = _lib.mt_mesh_build(fl, options, mesh, diag)
    t1 = time.perf_counter()
    meshtopo.errors.check(code, diag)
    _lib.mt_mesh_destroy(mesh.value)
    return t1 - t0


def time_python(positions, faces, threads):
    t0 = time.perf_counter()
    mesh = meshtopo.Mesh(positions, faces, threads=threads)
    t1 = time.perf_counter()
    mesh.close()
    return t1 - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--faces", type=int, default=1_000_000)
    ap.add_argument("--repetitions", type=int, default=9)
    ap.add_argument("--threads", type=int, default=0,
                    help="build threads, as mt_build_options (0: as many as pay off)")
    args = ap.parse_args()
    print("%-16s %-9s %9s %11s %11s %7s" % ("mesh", "order", "faces", "C ms", "Python ms",
                                            "ratio"))
    worst = 0.0
    for permuted in (False, True):
        name, positions, faces = grid_arrays(args.faces, permuted)
        fl, counts = face_list(positions, faces)
        time_c(fl, args.threads)  # warm up both paths once
        time_python(positions, faces, args.threads)
        c_times, py_times = [], []
        for _ in range(args.repetitions):
            c_times.append(time_c(fl, args.threads))
            py_times.append(time_python(positions, faces, args.threads))
        c_ms = statistics.median(c_times) * 1e3
        py_ms = statistics.median(py_times) * 1e3
        worst = max(worst, py_ms / c_ms)
        print("%-16s %-9s %9d %11.1f %11.1f %7.3f" % (name, "shuffled" if permuted else
                                                       "natural", len(faces), c_ms, py_ms,
                                                       py_ms / c_ms))
    print("medians of %d alternated repetitions, threads=%d; ratio = Python / C (largest %.3f)"
          % (args.repetitions, args.threads, worst))


if __name__ == "__main__":
    main()
