#!/usr/bin/python3
"""`meshtopo render` without a display (DISPLAY removed: the renderer starts
its own Xvfb): pictures of corpus meshes, a clean one (npm_bunny), one with
holes (cgal_elephant_with_holes), a non-manifold one (vcg_nonmanifold) and
one with rejected faces and flipped ones (assimp_malformed), read back with VTK's PNG reader.
Each picture has the size asked for; the marker colours (README, `meshtopo
help render`) are there for the defects each mesh has and absent for the
clean mesh; an archive file (.hdf, and .vtkhdf as earlier versions named
them) renders too; bad options and missing files exit 2 and 3. Run with
/usr/bin/python3 (python3-vtk9); exit 77 without the vtk module.

--markers (ctest cli.render_markers) checks instead that the defect markers
are drawn over the red boundary lines in every view: vcg_nonmanifold from
each of the seven directions shows magenta, and from the front, where its
non-manifold edge lies edge-on behind a boundary edge on the same line of
sight, the magenta line is drawn at its full width. Hidden under the
(narrower) red line it left a magenta fringe one pixel high.

usage: render_check.py --meshtopo PATH --fixture PATH --corpus DIR [--keep DIR] [--markers]
"""
import argparse
import os
import shutil
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


# Marker colours as they land in the picture: lines and points are unlit
# (exact), faces are shaded (a multiple of their colour).
def is_red(r, g, b):
    return r >= 215 and g <= 40 and b <= 40


def is_magenta(r, g, b):
    return r >= 215 and b >= 215 and g <= 40


def is_orange(r, g, b):
    return r >= 215 and 100 <= g <= 180 and b <= 40


def is_yellow(r, g, b):
    return r >= 60 and 0.75 * r <= g <= 0.95 * r and b <= 0.15 * r


def is_blue(r, g, b):
    return b >= 100 and r <= 0.4 * b and 0.35 * b <= g <= 0.65 * b


MARKERS = {"red": is_red, "magenta": is_magenta, "orange": is_orange, "yellow": is_yellow,
           "blue": is_blue}


def picture(path):
    """(width, height, {marker: pixel count}) of a PNG."""
    reader = vtk.vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    scalars = image.GetPointData().GetScalars()
    counts = dict.fromkeys(MARKERS, 0)
    comps = scalars.GetNumberOfComponents()
    for i in range(scalars.GetNumberOfTuples()):
        px = scalars.GetTuple(i)
        r, g, b = px[0], px[1] if comps > 1 else px[0], px[2] if comps > 2 else px[0]
        for name, test in MARKERS.items():
            if test(r, g, b):
                counts[name] += 1
    return w, h, counts


def is_magenta_at(scalars, comps, i):
    px = scalars.GetTuple(i)
    return comps >= 3 and is_magenta(px[0], px[1], px[2])


def thick_magenta_columns(path, least=3):
    """Columns of a PNG holding `least` or more magenta pixels one above the
    other: a horizontal magenta line drawn at full width (3.5 px times the
    picture's scale) rather than a fringe showing beside a line over it."""
    reader = vtk.vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    scalars = image.GetPointData().GetScalars()
    comps = scalars.GetNumberOfComponents()
    columns = 0
    for x in range(w):
        run = best = 0
        for y in range(h):
            run = run + 1 if is_magenta_at(scalars, comps, y * w + x) else 0
            best = max(best, run)
        columns += best >= least
    return columns


def check_markers(args, tmp):
    """The markers over the boundary lines: magenta in every view of
    vcg_nonmanifold; from the front, its non-manifold edge (vertices 7-8,
    in the plane y = 1 seen edge-on, behind the boundary edge 8-10 at
    z = 2) a full-width magenta line about 130 px long at 600x600, its
    two vertices' squares about 14 px each."""
    mesh = os.path.join(args.corpus, "vcg_nonmanifold.off")
    for view in ("iso", "front", "back", "left", "right", "top", "bottom"):
        out = os.path.join(tmp, f"markers-{view}.png")
        p = render(args.meshtopo, mesh, out, "--view", view, "--size", "600x600")
        expect(p.returncode == 0 and os.path.exists(out),
               f"{view}: rendered (exit {p.returncode}, {p.stderr.strip()})")
        if p.returncode != 0 or not os.path.exists(out):
            continue
        _, _, counts = picture(out)
        expect(counts["magenta"] >= 300 and counts["red"] >= 300,
               f"{view}: {counts['magenta']} magenta pixels over {counts['red']} red, at least "
               "300 of each")
        if view == "front":
            columns = thick_magenta_columns(out)
            expect(columns >= 100, f"front: the non-manifold edge drawn over the boundary line "
                                   f"({columns} columns of full-width magenta, at least 100)")
        if args.keep:
            os.makedirs(args.keep, exist_ok=True)
            shutil.copy(out, os.path.join(args.keep, f"vcg_nonmanifold-{view}.png"))


def render(meshtopo, source, out, *options):
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    return subprocess.run([meshtopo, "render", source, "--out", out, *options], env=env,
                          capture_output=True, text=True, timeout=240)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meshtopo", required=True)
    ap.add_argument("--fixture", required=True)
    ap.add_argument("--corpus", required=True)
    ap.add_argument("--keep", help="copy the pictures into this directory")
    ap.add_argument("--markers", action="store_true",
                    help="only check that markers are drawn over the boundary lines")
    args = ap.parse_args()
    if args.markers:
        with tempfile.TemporaryDirectory(prefix="meshtopo-render-markers-") as tmp:
            check_markers(args, tmp)
        if failures:
            print(f"{len(failures)} check(s) failed")
            return 1
        return 0
    # mesh, view, size, markers that must be there (at least n pixels),
    # markers that must not (the mesh has no such defect).
    cases = [
        ("npm_bunny", "top", "640x480", {}, list(MARKERS)),
        ("cgal_elephant_with_holes", "iso", "800x600", {"red": 500, "yellow": 100},
         ["magenta", "orange", "blue"]),
        ("vcg_nonmanifold", "iso", "600x600", {"magenta": 60, "red": 300},
         ["orange", "yellow", "blue"]),
        ("assimp_malformed", "iso", "500x400", {"orange": 40, "red": 100, "blue": 1000},
         ["magenta", "yellow"]),
    ]
    with tempfile.TemporaryDirectory(prefix="meshtopo-render-check-") as tmp:
        for name, view, size, present, absent in cases:
            mesh = os.path.join(args.corpus, name + ".off")
            out = os.path.join(tmp, name + ".png")
            p = render(args.meshtopo, mesh, out, "--view", view, "--size", size)
            expect(p.returncode == 0 and os.path.exists(out),
                   f"{name}: rendered without a display (exit {p.returncode}, {p.stderr.strip()})")
            if p.returncode != 0 or not os.path.exists(out):
                continue
            w, h, counts = picture(out)
            expect(f"{w}x{h}" == size, f"{name}: the picture is {size} ({w}x{h})")
            for colour, least in present.items():
                expect(counts[colour] >= least,
                       f"{name}: {counts[colour]} {colour} pixels, at least {least}")
            for colour in absent:
                expect(counts[colour] == 0, f"{name}: no {colour} pixels ({counts[colour]})")
            if args.keep:
                os.makedirs(args.keep, exist_ok=True)
                shutil.copy(out, os.path.join(args.keep, name + ".png"))

        # Archive files, as written and by the name earlier versions gave them.
        archive = os.path.join(tmp, "archive")
        subprocess.run([args.fixture, archive, "nm", "1",
                        os.path.join(args.corpus, "vcg_nonmanifold.off")], check=True)
        for file_name in ("nm.v1.hdf", "nm.v1.vtkhdf"):
            if file_name.endswith(".vtkhdf"):
                os.rename(os.path.join(archive, "nm.v1.hdf"), os.path.join(archive, file_name))
            out = os.path.join(tmp, file_name + ".png")
            p = render(args.meshtopo, os.path.join(archive, file_name), out, "--size", "400x300")
            ok = p.returncode == 0 and os.path.exists(out)
            expect(ok, f"archive file {file_name} rendered (exit {p.returncode}, "
                       f"{p.stderr.strip()})")
            if ok:
                w, h, counts = picture(out)
                expect((w, h) == (400, 300) and counts["magenta"] > 0 and counts["red"] > 0,
                       f"{file_name}: 400x300 with magenta and red markers ({counts})")

        # Errors: usage (2) and unreadable input (3), nothing written.
        bunny = os.path.join(args.corpus, "npm_bunny.off")
        bad = os.path.join(tmp, "bad.png")
        for options, code, what in (([], 2, "no --out"), (["--view", "diagonal"], 2, "bad view"),
                                    (["--size", "8x8"], 2, "size too small"),
                                    (["--size", "800"], 2, "size without height")):
            p = subprocess.run([args.meshtopo, "render", bunny, *options] +
                               (["--out", bad] if what != "no --out" else []),
                               capture_output=True, text=True, timeout=60)
            expect(p.returncode == code and not os.path.exists(bad),
                   f"{what}: exit {code} ({p.returncode}, {p.stderr.strip()})")
        p = render(args.meshtopo, os.path.join(tmp, "missing.off"), bad)
        expect(p.returncode == 3 and "missing.off" in p.stderr, f"missing file: exit 3 ({p.stderr.strip()})")
        p = render(args.meshtopo, bunny, os.path.join(tmp, "no-such-dir", "x.png"))
        expect(p.returncode == 3 and "no-such-dir" in p.stderr,
               f"unwritable picture: exit 3 ({p.returncode}, {p.stderr.strip()})")
        p = subprocess.run([args.meshtopo, "help", "render"], capture_output=True, text=True)
        expect(p.returncode == 0 and "magenta" in p.stdout and "--view" in p.stdout,
               "help render lists the colours and options")
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
