#!/usr/bin/env python3
"""Exit codes and messages of the `meshtopo` command line.

  read_errors  a missing file and malformed files (written here, at test time)
               give exit 3 and a message on stderr naming the file
  usage        help, --version, unknown commands and options, bad id lists
  exit_codes   --fail-on-defect (1), --strict (4), --json-defects, readable output
  self_intersections  inspect --self-intersections, text and JSON
  stdin        inspect - reads standard input (plain and gzip)
  module       archive, replay and render come from a module loaded only for
               them: inspect never loads HDF5, archive ls does; a program
               without its module still inspects and says what is missing

usage: cli_check.py --meshtopo PATH --corpus DIR
                    {read_errors,usage,exit_codes,self_intersections}
"""
import argparse
import gzip
import json
import os
import re
import subprocess
import sys
import tempfile

failures = []


# The keys of every defect record in JSON, in order (README.md "Defect records").
DEFECT_RECORD_KEYS = ["kind", "vertices", "faces", "edge", "face_count", "index", "position",
                      "face_size", "distinct_vertices", "fans", "on_nonmanifold_edge", "axis",
                      "description"]

def run(meshtopo, *args):
    proc = subprocess.run([meshtopo, *args], capture_output=True, text=True, timeout=120)
    return proc.returncode, proc.stdout, proc.stderr


def parse_json(text):
    """The JSON document in text, or {} when it is not one (the check then fails)."""
    try:
        doc = json.loads(text)
    except json.JSONDecodeError:
        return {}
    return doc if isinstance(doc, dict) else {}


def expect(cond, what, code=None, out="", err=""):
    if cond:
        print(f"ok   {what}")
        return
    failures.append(what)
    print(f"FAIL {what}")
    if code is not None:
        print(f"     exit code {code}")
    if out:
        print("     stdout: " + out[:600].replace("\n", "\n             "))
    if err:
        print("     stderr: " + err[:600].replace("\n", "\n             "))


def check_read_errors(meshtopo, corpus):
    with tempfile.TemporaryDirectory(prefix="meshtopo-cli-") as tmp:
        missing = os.path.join(tmp, "no_such_mesh.off")
        code, out, err = run(meshtopo, "inspect", missing)
        expect(code == 3 and missing in err and out == "",
               "missing file: exit 3, stderr names it, nothing on stdout", code, out, err)

        code, out, err = run(meshtopo, "inspect", missing, "--json")
        expect(code == 3 and missing in err and out == "",
               "missing file with --json: exit 3, no JSON printed", code, out, err)

        malformed = {
            "bad_coordinate.off": "OFF\n3 1 0\n0 0 0\n1 0 zz\n0 1 0\n3 0 1 2\n",
            "truncated.off": "OFF\n4 2 0\n0 0 0\n1 0 0\n",
            "bad_counts.off": "OFF\nthree 1 0\n0 0 0\n",
            "bad_face.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
            "garbage.ply": "ply\nformat ascii 1.0\nelement vertex nonsense\nend_header\n",
        }
        for name, text in malformed.items():
            path = os.path.join(tmp, name)
            with open(path, "w", encoding="ascii") as f:
                f.write(text)
            code, out, err = run(meshtopo, "inspect", path)
            expect(code == 3 and path in err and out == "",
                   f"malformed {name}: exit 3, stderr names the file", code, out, err)

        directory = tmp
        code, out, err = run(meshtopo, "inspect", directory)
        expect(code == 3 and directory in err, "a directory as FILE: exit 3, named", code, out,
               err)


def check_usage(meshtopo, corpus):
    code, out, err = run(meshtopo)
    expect(code == 2 and "usage" in err and out == "", "no arguments: usage on stderr, exit 2",
           code, out, err)
    code, out, err = run(meshtopo, "frobnicate")
    expect(code == 2 and "usage" in err and "frobnicate" in err and out == "",
           "unknown command: usage on stderr, exit 2", code, out, err)
    code, out, err = run(meshtopo, "--help")
    expect(code == 0 and "inspect" in out and "exit codes" in out,
           "--help lists commands and exit codes", code, out, err)
    code, out, err = run(meshtopo, "help", "inspect")
    expect(code == 0 and "--vertices" in out and "--fail-on-defect" in out,
           "help inspect shows the options", code, out, err)
    code2, out2, err2 = run(meshtopo, "inspect", "--help")
    expect(code2 == 0 and out2 == out, "inspect --help equals help inspect", code2, out2, err2)
    code, out, err = run(meshtopo, "help", "nosuch")
    expect(code == 2 and "nosuch" in err, "help of an unknown command: exit 2", code, out, err)
    code, out, err = run(meshtopo, "--version")
    expect(code == 0 and out.startswith("meshtopo ") and out.strip() != "meshtopo",
           "--version prints a version", code, out, err)

    mesh = os.path.join(corpus, "cgal_tetrahedron.off")
    cases = [
        ("inspect without FILE", ["inspect"]),
        ("inspect with two files", ["inspect", mesh, mesh]),
        ("unknown option", ["inspect", mesh, "--bogus"]),
        ("single-dash unknown option", ["inspect", mesh, "-x"]),
        ("--vertices without a value", ["inspect", mesh, "--vertices"]),
        ("--vertices not a number", ["inspect", mesh, "--vertices=a,b"]),
        ("--vertices negative", ["inspect", mesh, "--vertices=-1"]),
        ("--vertices out of range", ["inspect", mesh, "--vertices=4"]),
        ("--vertices trailing comma", ["inspect", mesh, "--vertices=1,"]),
        ("--vertices backwards range", ["inspect", mesh, "--vertices=3-1"]),
        ("--faces out of range", ["inspect", mesh, "--json", "--faces", "0,9"]),
        ("--limit not a number", ["inspect", mesh, "--limit", "many"]),
        ("flag with a value", ["inspect", mesh, "--json=yes"]),
        ("unknown --format", ["inspect", mesh, "--format", "stl"]),
    ]
    for what, args in cases:
        code, out, err = run(meshtopo, *args)
        expect(code == 2 and err.strip() != "" and out == "", f"{what}: exit 2 with a message",
               code, out, err)

    code, out, err = run(meshtopo, "inspect", "--json", "--", mesh)
    expect(code == 0 and parse_json(out).get("V") == 4, "options before FILE and -- work", code,
           out, err)
    code, out, err = run(meshtopo, "inspect", mesh, "--json", "--vertices", "0-2,0",
                         "--faces=")
    doc = parse_json(out) if code == 0 else {}
    expect(code == 0 and [q["vertex"] for q in doc.get("vertex_queries", [])] == [0, 1, 2, 0]
           and doc.get("face_queries") == [],
           "ranges, repeats and an empty list are taken as given", code, out, err)


def check_exit_codes(meshtopo, corpus):
    clean = os.path.join(corpus, "cgal_tetrahedron.off")
    messy = os.path.join(corpus, "assimp_malformed.off")

    code, out, err = run(meshtopo, "inspect", clean, "--fail-on-defect")
    expect(code == 0 and "defects: none" in out, "clean mesh with --fail-on-defect: exit 0",
           code, out, err)
    code, out, err = run(meshtopo, "inspect", messy)
    expect(code == 0 and "out-of-range" in out and "face 5" in out,
           "messy mesh: exit 0, readable defects with face ids", code, out, err)
    code, out, err = run(meshtopo, "inspect", messy, "--fail-on-defect")
    expect(code == 1 and "out-of-range" in out, "messy mesh with --fail-on-defect: report, exit 1",
           code, out, err)
    code, out, err = run(meshtopo, "inspect", messy, "--json", "--fail-on-defect")
    expect(code == 1 and parse_json(out).get("F_valid") == 3,
           "--json with --fail-on-defect: JSON printed, exit 1", code, out, err)
    code, out, err = run(meshtopo, "inspect", messy, "--strict")
    expect(code == 4 and messy in err and out == "", "--strict on a messy mesh: exit 4, named",
           code, out, err)
    code, out, err = run(meshtopo, "inspect", clean, "--strict", "--json")
    expect(code == 0 and parse_json(out).get("closed") is True, "--strict on a clean mesh: exit 0",
           code, out, err)

    code, out, err = run(meshtopo, "inspect", messy, "--json-defects")
    doc = parse_json(out) if code == 0 else {}
    defects = doc.get("defects", [])
    kinds = {d.get("kind") for d in defects}
    oor = [d for d in defects if d.get("kind") == "out_of_range_index"]
    expect(code == 0 and list(doc)[-1] == "defects" and "out_of_range_index" in kinds
           and "degenerate_face" in kinds and len(oor) == doc.get("faces_with_out_of_range_indices")
           and all(list(d) == DEFECT_RECORD_KEYS for d in defects),
           "--json-defects: a defects array at the end, one record per bad face", code, out, err)
    expect(all(len(d["faces"]) == 1 and d["vertices"] == [] and d["edge"] is None
               and isinstance(d["index"], int) and isinstance(d["position"], int)
               and d["fans"] is None for d in oor),
           "--json-defects: an out-of-range record names its face, index and position",
           code, out, err)
    code, out, err = run(meshtopo, "inspect", messy, "--json")
    expect(code == 0 and "V" in parse_json(out) and "defects" not in parse_json(out), "--json alone has no defects key",
           code, out, err)

    # "file" is the basename, escaped as JSON (quotes, backslash, control characters,
    # invalid UTF-8 as U+FFFD).
    with tempfile.TemporaryDirectory(prefix="meshtopo-cli-") as tmp:
        with open(clean, "rb") as f:
            data = f.read()
        for name, want in [('we"ird\\na\tme \u00e9.off', 'we"ird\\na\tme \u00e9.off'),
                           (b"bad\xffutf8.off", "bad\ufffdutf8.off")]:
            path = os.path.join(os.fsencode(tmp), os.fsencode(name))
            with open(path, "wb") as f:
                f.write(data)
            proc = subprocess.run([os.fsencode(meshtopo), b"inspect", path, b"--json"],
                                  capture_output=True, timeout=120)
            try:
                doc = json.loads(proc.stdout.decode("utf-8"))
            except (UnicodeDecodeError, json.JSONDecodeError):
                doc = {}
            expect(proc.returncode == 0 and doc.get("file") == want,
                   f"--json escapes the file name {want!r}", proc.returncode,
                   proc.stdout.decode("utf-8", "replace"), proc.stderr.decode("utf-8", "replace"))

    code, out, err = run(meshtopo, "inspect", messy, "--vertices", "6", "--faces", "2,0")
    expect(code == 0 and "vertex 6" in out and "face 2" in out and "face 0" in out
           and "left out" in out,
           "readable one-ring and face neighbours, rejected face explained", code, out, err)
    code, out, err = run(meshtopo, "inspect", messy, "--json", "--faces", "0")
    doc = parse_json(out) if code == 0 else {}
    expect(code == 0 and doc.get("face_queries") == [{"face": 0, "adjacent_faces": None}],
           "--json: a rejected face has adjacent_faces null", code, out, err)


def check_stdin(meshtopo, corpus):
    """inspect - reads standard input: the same report as the file, gzip too;
    a malformed input names standard input and the line."""
    path = os.path.join(corpus, "npm_bunny.off")
    code, want, err = run(meshtopo, "inspect", path, "--json")
    with open(path, "rb") as f:
        data = f.read()
    for what, stdin in (("plain", data), ("gzip", gzip.compress(data))):
        proc = subprocess.run([meshtopo, "inspect", "-", "--json"], input=stdin,
                              capture_output=True, timeout=120)
        got, expected = parse_json(proc.stdout.decode()), parse_json(want)
        got.pop("file", None)
        expected.pop("file", None)
        expect(proc.returncode == 0 and got == expected and got,
               f"inspect - ({what}) gives the file's report", proc.returncode,
               proc.stdout.decode(), proc.stderr.decode())
    proc = subprocess.run([meshtopo, "inspect", "-"], input=b"OFF\n3 1 0\n0 0 0\n1 0 0\n",
                          capture_output=True, timeout=60)
    err = proc.stderr.decode()
    expect(proc.returncode == 3 and re.search(r"standard input:\d+: ", err),
           "inspect - on a truncated OFF: exit 3 naming standard input and the line",
           proc.returncode, proc.stdout.decode(), err)


def check_self_intersections(meshtopo, corpus):
    """inspect --self-intersections: the JSON counts and lists, the readable
    section, --fail-on-defect counting what it finds; absent without it."""
    joined = os.path.join(corpus, "trimesh_joined_tetrahedra.off")
    code, out, err = run(meshtopo, "inspect", joined, "--json", "--self-intersections")
    doc = parse_json(out)
    lists = doc.get("self_intersections", {})
    expect(code == 0 and doc.get("self_intersecting_pairs") == len(lists.get("face_pairs", [1, 2]))
           and doc.get("non_simple_faces") == len(lists.get("faces", [1]))
           and doc.get("self_intersecting_boundary_loops") == len(lists.get("boundary_loops", [1]))
           and doc["self_intersecting_pairs"] > 0
           and all(a < b for a, b in lists["face_pairs"]),
           "--self-intersections --json: counts match their lists, pairs a < b", code, out, err)
    code, out, err = run(meshtopo, "inspect", joined, "--json")
    expect(code == 0 and "self_intersecting_pairs" not in parse_json(out),
           "--json without --self-intersections has no geometric keys", code, out, err)
    code, out, err = run(meshtopo, "inspect", joined, "--self-intersections")
    expect(code == 0 and "self-intersections: " in out and "pass through" in out,
           "--self-intersections readable: a section naming the faces", code, out, err)
    code, out, err = run(meshtopo, "inspect", joined, "--self-intersections", "--fail-on-defect")
    expect(code == 1, "--fail-on-defect counts self-intersections: exit 1", code, out, err)
    tet = os.path.join(corpus, "cgal_tetrahedron.off")
    code, out, err = run(meshtopo, "inspect", tet, "--self-intersections", "--fail-on-defect")
    expect(code == 0 and "self-intersections: 0 face pairs" in out,
           "a clean tetrahedron: 0 pairs, exit 0", code, out, err)


def loaded_libraries(meshtopo, *args):
    """The code and the shared objects the dynamic loader loaded for `meshtopo args`."""
    env = dict(os.environ, LD_DEBUG="files")
    proc = subprocess.run([meshtopo, *args], capture_output=True, text=True, timeout=120, env=env)
    return proc.returncode, set(re.findall(r"file=(\S+) \[0\];", proc.stderr)), proc.stderr


def check_module(meshtopo, corpus):
    mesh = os.path.join(corpus, "cgal_tetrahedron.off")
    with tempfile.TemporaryDirectory() as tmp:
        code, libs, err = loaded_libraries(meshtopo, "inspect", mesh)
        names = " ".join(sorted(libs))
        expect(code == 0 and "libc.so" in names and "hdf5" not in names
               and "archive-commands" not in names,
               "inspect loads neither HDF5 nor the archive module", code, names, "")
        code, libs, err = loaded_libraries(meshtopo, "archive", "ls", tmp)
        names = " ".join(sorted(libs))
        expect(code == 0 and "meshtopo-archive-commands.so" in names and "hdf5" in names,
               "archive ls loads the archive module and HDF5", code, names, "")
        # The program alone, away from its module: inspect works, the archive
        # commands fail with exit 7 naming what could not be loaded.
        alone = os.path.join(tmp, "meshtopo")
        with open(meshtopo, "rb") as src, open(alone, "wb") as dst:
            dst.write(src.read())
        os.chmod(alone, 0o755)
        code, out, err = run(alone, "inspect", mesh, "--json")
        expect(code == 0 and parse_json(out).get("V") == 4, "without the module: inspect works",
               code, out, err)
        for args in (["archive", "ls", tmp], ["replay", tmp], ["help", "render"]):
            code, out, err = run(alone, *args)
            expect(code == 7 and "cannot load the archive commands" in err
                   and "meshtopo-archive-commands.so" in err and out == "",
                   f"without the module: {args[0]} exits 7 naming the module", code, out, err)
        code, out, err = run(alone, "--help")
        expect(code == 0 and re.search(r"archive +cannot load the archive commands", out),
               "without the module: --help says so in place of the summaries", code, out, err)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meshtopo", default=os.environ.get("MESHTOPO_CLI"))
    ap.add_argument("--corpus", default=os.environ.get("MESHTOPO_CORPUS"))
    ap.add_argument("check",
                    choices=["read_errors", "usage", "exit_codes", "self_intersections", "stdin",
                             "module"])
    args = ap.parse_args()
    if not args.meshtopo or not args.corpus:
        ap.error("need --meshtopo and --corpus (or MESHTOPO_CLI / MESHTOPO_CORPUS)")
    {"read_errors": check_read_errors, "usage": check_usage,
     "exit_codes": check_exit_codes,
     "self_intersections": check_self_intersections, "stdin": check_stdin,
     "module": check_module}[args.check](args.meshtopo, args.corpus)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
