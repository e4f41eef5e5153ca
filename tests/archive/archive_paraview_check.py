#!/usr/bin/python3
"""Every corpus mesh archived (archive_fixture, as meshtopod archives it)
and opened in Debian's ParaView (pvbatch from the paraview package, with
python3-paraview) by its file name alone: ParaView must pick its VTKHDF
reader for the archive's ".hdf" names, and show as many points as the mesh
has vertices, as many cells as faces the build kept, and the topology
arrays of format 6 with a value per cell or point, of the documented types.
Expected counts come from `meshtopo inspect --json` (V, F_valid). Exit 77
(skipped) when pvbatch is not installed.

usage: archive_paraview_check.py --meshtopo PATH --fixture PATH --corpus DIR [--pvbatch PATH]
"""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

failures = []

VTK_INT, VTK_UNSIGNED_INT, VTK_UNSIGNED_CHAR, VTK_LONG, VTK_LONG_LONG = 6, 7, 3, 8, 16
CELL_ARRAYS = {"component": VTK_INT, "defects": VTK_UNSIGNED_INT,
               "touches_boundary": VTK_UNSIGNED_CHAR,
               "orientation_consistent": VTK_UNSIGNED_CHAR}
POINT_ARRAYS = {"boundary": VTK_UNSIGNED_CHAR, "non_manifold": VTK_UNSIGNED_CHAR,
                "defects": VTK_UNSIGNED_INT}


def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--fixture", required=True)
    ap.add_argument("--corpus", required=True)
    ap.add_argument("--pvbatch", default=shutil.which("pvbatch"))
    args = ap.parse_args()
    if not args.pvbatch or not os.path.exists(args.pvbatch):
        print("skip: pvbatch not found (Debian: apt install paraview python3-paraview)")
        return 77
    # pvbatch runs its scripts with ParaView's Python modules, which Debian
    # ships apart (python3-paraview, which conflicts with python3-vtk9).
    probe = subprocess.run([args.pvbatch, "-c", "import paraview.simple"],
                           capture_output=True, text=True, timeout=120)
    if probe.returncode != 0:
        print("skip: pvbatch cannot import paraview (Debian: apt install python3-paraview; "
              "scripts/install-deps.sh --tests)")
        return 77
    meshes = sorted(glob.glob(os.path.join(args.corpus, "*.off")) +
                    glob.glob(os.path.join(args.corpus, "*.off.gz")))
    expect(len(meshes) >= 20, f"{len(meshes)} corpus meshes")
    with tempfile.TemporaryDirectory(prefix="meshtopo-paraview-") as tmp:
        expected = {}
        for mesh in meshes:
            name = os.path.basename(mesh).split(".")[0]
            subprocess.run([args.fixture, tmp, name, "1", mesh, "--self-intersections"],
                           check=True)
            report = json.loads(subprocess.run([args.meshtopo, "inspect", mesh, "--json"],
                                               check=True, capture_output=True,
                                               text=True).stdout)
            path = os.path.join(tmp, name + ".v1.hdf")
            expect(os.path.exists(path), f"{name}: archived as {os.path.basename(path)}")
            expected[path] = (name, report["V"], report["F_valid"])
        listing = os.path.join(tmp, "files.json")
        with open(listing, "w", encoding="utf-8") as f:
            json.dump(sorted(expected), f)
        env = dict(os.environ)
        env.pop("DISPLAY", None)
        p = subprocess.run([args.pvbatch, os.path.join(os.path.dirname(__file__),
                                                       "paraview_open.py"), listing],
                           capture_output=True, text=True, env=env, timeout=600)
        results = [json.loads(line[len("RESULT "):]) for line in p.stdout.splitlines()
                   if line.startswith("RESULT ")]
        expect(p.returncode == 0 and len(results) == len(expected),
               f"pvbatch answered for {len(results)} of {len(expected)} files (exit "
               f"{p.returncode}{', ' + p.stderr.strip()[-500:] if p.returncode else ''})")
        for r in results:
            name, nv, nf = expected[r["path"]]
            if "error" in r:
                expect(False, f"{name}: opened by its name ({r['error']})")
                continue
            expect(r["reader"] == "HDFReader", f"{name}: ParaView chose its VTKHDF reader "
                                              f"({r['reader']})")
            expect(r["points"] == nv and r["cells"] == nf,
                   f"{name}: {r['points']} points, {r['cells']} cells ({nv}, {nf})")
            cell_arrays = dict(CELL_ARRAYS, self_intersecting=VTK_UNSIGNED_CHAR)
            ids = r["cell_data"].get("original_face_id")
            expect(ids is not None and ids[:2] == [nf, 1] and ids[2] in (VTK_LONG, VTK_LONG_LONG),
                   f"{name}: original_face_id has {nf} 64-bit values ({ids})")
            for group, wanted, rows in ((r["cell_data"], cell_arrays, nf),
                                        (r["point_data"], POINT_ARRAYS, nv)):
                for key, kind in wanted.items():
                    got = group.get(key)
                    expect(got == [rows, 1, kind],
                           f"{name}: {key} has {rows} values of VTK type {kind} ({got})")
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
