#!/usr/bin/env python3
"""Corpus conformance of `meshtopo inspect --json` against NAME.expected.json.

Runs the CLI twice on the corpus mesh: without --vertices/--faces (so the
tool's own choice of queried elements is checked too) and with the expected
file's elements passed explicitly. Every key of the expected file except
oracle_version must be present with exactly the same value (bools are not
ints, key order included); every mismatch is printed with its key path and
both values. Exit 0 when both runs match, 1 otherwise.

usage: corpus_check.py --meshtopo PATH --corpus DIR NAME
       (or the MESHTOPO_CLI / MESHTOPO_CORPUS environment variables)
"""
import argparse
import json
import os
import subprocess
import sys

IGNORED_KEYS = {"oracle_version"}


def same_type(a, b):
    # JSON kinds: bool, number, string, null, array, object (bool is not a number here)
    def kind(x):
        if isinstance(x, bool):
            return "bool"
        if isinstance(x, (int, float)):
            return "number"
        return type(x).__name__
    return kind(a) == kind(b)


def show(value):
    text = json.dumps(value)
    return text if len(text) <= 200 else text[:200] + "..."


def compare(expected, actual, path, out):
    """Appends one line per difference to out."""
    if not same_type(expected, actual):
        out.append(f"{path}: expected {show(expected)}, got {show(actual)}")
        return
    if isinstance(expected, dict):
        for key, value in expected.items():
            if key in IGNORED_KEYS:
                continue
            sub = f"{path}.{key}" if path else key
            if key not in actual:
                out.append(f"{sub}: expected {show(value)}, missing")
            else:
                compare(value, actual[key], sub, out)
        for key in actual:
            if key not in expected:
                sub = f"{path}.{key}" if path else key
                out.append(f"{sub}: unexpected key, got {show(actual[key])}")
        # key order (of the keys both have; missing and extra keys are reported above)
        want = [k for k in expected if k not in IGNORED_KEYS and k in actual]
        have = [k for k in actual if k in want]
        if want != have:
            out.append(f"{path or '(top)'}: key order differs: expected {want}, got {have}")
    elif isinstance(expected, list):
        if len(expected) != len(actual):
            out.append(f"{path}: expected {len(expected)} items {show(expected)}, "
                       f"got {len(actual)} items {show(actual)}")
        # compare the common prefix too, to show where the lists start to differ
        for i, (e, a) in enumerate(zip(expected, actual)):
            compare(e, a, f"{path}[{i}]", out)
    elif expected != actual:
        out.append(f"{path}: expected {show(expected)}, got {show(actual)}")


def run_inspect(meshtopo, mesh_path, extra):
    cmd = [meshtopo, "inspect", mesh_path, "--json"] + extra
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if proc.returncode != 0:
        return None, (f"`{' '.join(cmd)}` exited with {proc.returncode}\n"
                      f"stderr: {proc.stderr.strip()}")
    try:
        return json.loads(proc.stdout), None
    except json.JSONDecodeError as e:
        return None, f"`{' '.join(cmd)}` printed invalid JSON: {e}\n{proc.stdout[:500]}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--meshtopo", default=os.environ.get("MESHTOPO_CLI"))
    ap.add_argument("--corpus", default=os.environ.get("MESHTOPO_CORPUS"))
    ap.add_argument("name")
    args = ap.parse_args()
    if not args.meshtopo or not args.corpus:
        ap.error("need --meshtopo and --corpus (or MESHTOPO_CLI / MESHTOPO_CORPUS)")

    expected_path = os.path.join(args.corpus, args.name + ".expected.json")
    with open(expected_path, encoding="utf-8") as f:
        expected = json.load(f)
    mesh_path = os.path.join(args.corpus, expected["file"])

    verts = ",".join(str(q["vertex"]) for q in expected["vertex_queries"])
    faces = ",".join(str(q["face"]) for q in expected["face_queries"])
    runs = [
        ("default queries", []),
        ("explicit queries", [f"--vertices={verts}", f"--faces={faces}"]),
    ]
    failed = False
    for label, extra in runs:
        actual, error = run_inspect(args.meshtopo, mesh_path, extra)
        if error:
            print(f"{args.name} ({label}): {error}")
            failed = True
            continue
        diffs = []
        compare(expected, actual, "", diffs)
        if diffs:
            failed = True
            print(f"{args.name} ({label}): {len(diffs)} mismatching key(s)")
            for line in diffs:
                print("  " + line)
        else:
            print(f"{args.name} ({label}): all keys match")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
