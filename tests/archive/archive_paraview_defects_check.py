#!/usr/bin/python3
"""Archive files coloured by defect kind in Debian's ParaView 5.11, headless:
tools/vtk/paraview_defects.py run by pvbatch under
`xvfb-run -a -s "-screen 0 1280x1024x24"` on a non-manifold corpus mesh
(vcg_nonmanifold, by face) and one with bowtie vertices
(cgal_many_umbrellas, by vertex). The lookup table must be categorical with
an annotation per bitmask value naming its kinds (the names read from the
file's per-kind arrays, format 8), the scalar bar shown, and the screenshot
a real picture: its size, many colours, and each category's colour in it
(the legend's swatches are unlit, so exact). Exit 77 (skipped) when pvbatch,
ParaView's Python modules or xvfb-run are missing.

usage: archive_paraview_defects_check.py --fixture PATH --corpus DIR --script PATH
           [--picture PNG] [--keep DIR]
--picture copies the vcg_nonmanifold screenshot there (how
docs/pictures/paraview-defects.png is made).
"""
import argparse
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

failures = []

SERVER = "-screen 0 1280x1024x24"  # 24-bit TrueColor: GLX has no visual at depth 8
SIZE = (1024, 768)

# mesh, colour the vertices?, expected annotations {value: label}.
CASES = [
    ("vcg_nonmanifold", False,
     {0: "no defect", 40: "nonmanifold_edge + nonmanifold_vertex",
      56: "nonmanifold_edge + nonmanifold_vertex + same_direction_edge"}),
    ("cgal_many_umbrellas", True, {0: "no defect", 32: "nonmanifold_vertex"}),
]


def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def read_png(path):
    """(width, height, [(r, g, b)]) of an 8-bit RGB or RGBA PNG, not
    interlaced (what ParaView writes), decoded with zlib alone."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        raise ValueError(f"PNG depth {depth}, colour type {colour}, interlace {interlace}")
    bpp = 3 if colour == 2 else 4
    raw, stride = zlib.decompress(idat), width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    pixels = [tuple(row[x * bpp:x * bpp + 3]) for row in rows for x in range(width)]
    return width, height, pixels


# What pvbatch or xvfb-run print when the X server they were handed is not
# there to connect to: xvfb-run -a picks the first display number without a
# lock file, so an X server of another process starting or stopping on that
# number at the same moment (a concurrent test, another user's xvfb-run)
# can take it away. Not this test's subject: tried once more.
X_RACE = ("bad X server connection", "Xvfb failed to start")


def pvbatch_under_xvfb(command, env):
    for attempt in range(2):
        p = subprocess.run(command, env=env, capture_output=True, text=True, timeout=300)
        if p.returncode == 0 or not any(text in p.stderr for text in X_RACE) or attempt:
            return p
        print("note: the X server went away under pvbatch (another X server on the same "
              "display number?); trying once more")
    return p


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--fixture", required=True)
    ap.add_argument("--corpus", required=True)
    ap.add_argument("--script", required=True, help="tools/vtk/paraview_defects.py")
    ap.add_argument("--pvbatch", default=shutil.which("pvbatch"))
    ap.add_argument("--picture", help="copy the vcg_nonmanifold screenshot here")
    ap.add_argument("--keep", help="copy every screenshot into this directory")
    args = ap.parse_args()
    if not args.pvbatch or not os.path.exists(args.pvbatch):
        print("skip: pvbatch not found (Debian: apt install paraview python3-paraview)")
        return 77
    if not shutil.which("xvfb-run"):
        print("skip: xvfb-run not found (Debian: apt install xvfb); Debian's ParaView renders "
              "through GLX only")
        return 77
    probe = subprocess.run([args.pvbatch, "-c", "import paraview.simple"],
                           capture_output=True, text=True, timeout=120)
    if probe.returncode != 0:
        print("skip: pvbatch cannot import paraview (Debian: apt install python3-paraview; "
              "scripts/install-deps.sh --tests)")
        return 77
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    with tempfile.TemporaryDirectory(prefix="meshtopo-paraview-defects-") as tmp:
        for name, points, want in CASES:
            subprocess.run([args.fixture, tmp, name, "1",
                            os.path.join(args.corpus, name + ".off")], check=True)
            path = os.path.join(tmp, name + ".v1.hdf")
            out = os.path.join(tmp, name + ".png")
            command = ["xvfb-run", "-a", "-s", SERVER, args.pvbatch, args.script, path,
                       "--out", out, "--size", f"{SIZE[0]}x{SIZE[1]}"]
            p = pvbatch_under_xvfb(command + (["--points"] if points else []), env)
            results = [json.loads(line[len("RESULT "):]) for line in p.stdout.splitlines()
                       if line.startswith("RESULT ")]
            expect(p.returncode == 0 and len(results) == 1,
                   f"{name}: pvbatch under xvfb-run coloured it (exit {p.returncode}"
                   f"{', ' + p.stderr.strip()[-800:] if p.returncode else ''})")
            if len(results) != 1:
                continue
            r = results[0]
            where = "vertices" if points else "faces"
            expect(r["array"] == "defects" and r["association"] == ("points" if points
                                                                   else "cells"),
                   f"{name}: coloured by the {where}' defects ({r['association']} "
                   f"{r['array']})")
            expect(r["categorical"] == 1, f"{name}: the lookup table is categorical")
            expect(r["scalar_bar"], f"{name}: the scalar bar (legend) is shown")
            got = {int(value): label for value, label in r["annotations"]}
            expect(got == want, f"{name}: the legend names the kinds of each value ({got})")
            names = {kind for value, label in want.items() if value
                     for kind in label.split(" + ")}
            legend = " ".join(got.values())
            expect(all(kind in legend for kind in names),
                   f"{name}: the legend holds {sorted(names)}")
            if not os.path.exists(out):
                expect(False, f"{name}: screenshot written")
                continue
            w, h, pixels = read_png(out)
            expect((w, h) == SIZE, f"{name}: the screenshot is {SIZE[0]}x{SIZE[1]} ({w}x{h})")
            background = max(set(pixels[:: 97]), key=pixels[:: 97].count)
            drawn = sum(1 for px in pixels if px != background)
            distinct = len(set(pixels))
            expect(drawn > 0.03 * w * h and distinct >= 50,
                   f"{name}: a picture, not a blank ({drawn} pixels drawn, {distinct} colours)")
            for value, rgb in zip(got, r["colours"]):
                count = pixels.count(tuple(rgb))
                expect(count >= 300, f"{name}: {count} pixels of the colour of '{got[value]}' "
                                     f"{tuple(rgb)} (its legend swatch at least)")
            if args.keep:
                os.makedirs(args.keep, exist_ok=True)
                shutil.copy(out, os.path.join(args.keep, f"paraview-defects-{name}.png"))
            if args.picture and name == "vcg_nonmanifold":
                shutil.copy(out, args.picture)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
