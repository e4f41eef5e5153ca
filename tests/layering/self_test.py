#!/usr/bin/env python3
"""Proof that check_layering.py fails when it should, and only then.

Compiles tiny C files with the project's C compiler into objects laid out as
CMake lays them out (<dir>/CMakeFiles/<target>.dir/<source>.o), writes an
object list for them and runs the checker:
  planted  library `lib`: a.c and b.c call each other, c.c calls daemon/ and
           reads tools/, e.c calls LCM and the library `other` and includes
           their headers (forbidden with --forbid lib=other,lcm); daemon/:
           d1.c -> d2.c -> d3.c -> d1.c across two targets. The checker must
           report exactly these, and nothing about the library `other` that
           calls `lib`, nor about main.c or tools/.
  clean    the same files without the back-calls and e.c: every unit passes.
  core     the core's family order (FAMILY_ORDERS in the checker), on files
           laid out as lib/core/src/<family>/: planted, base/ calls map/,
           report/ calls build/build.c (the orchestrator above it), base/'s
           header includes mesh/'s, and a file sits in no family; none of
           them closes a cycle, so only the order can refuse them, and it
           must refuse all four; the same families used downwards pass.

usage: self_test.py --cc CC --nm NM --checker check_layering.py
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

# (role, unit, target, directory, source path below it, text)
COMMON = [
    ("library", "other", "other", "other", "o.c",
     "int a_fn(int);\nint o_fn(void) { return a_fn(3); }\n"),
    ("daemon", "daemon", "daemon_x", "daemon", "d1.c",
     "int d2_fn(int);\nint d_counter;\n"
     "int d_helper(int x) { return x + d_counter; }\n"
     "int d1_fn(int x) { return x > 0 ? d2_fn(x - 1) : 0; }\n"),
    ("daemon", "daemon", "daemon_y", "daemon", "d2.c",
     "int d3_fn(int);\nint d2_fn(int x) { return x > 0 ? d3_fn(x - 1) : 0; }\n"),
    ("daemon", "daemon", "daemon_main", "daemon", "main.c",
     "int d1_fn(int);\nint main(void) { return d1_fn(3); }\n"),
    ("tools", "tools", "tool", "tools", "t.c",
     "const int t_table[2] = {1, 2};\nint a_fn(int);\nint d1_fn(int);\n"
     "int t_fn(void) { return a_fn(1) + d1_fn(2); }\n"),
]
# Headers e.c includes: an LCM type's and one of the library `other` (below
# its include/ folder, as the checker looks for a unit's headers).
HEADERS = [
    ("include/lcmtypes/meshtopo_mesh_t.h",
     "typedef struct { int num_verts; } meshtopo_mesh_t;\n"
     "int meshtopo_mesh_t_encode(void *buf, int offset, int maxlen, const meshtopo_mesh_t *m);\n"),
    ("other/include/meshtopo/other.h", "int o_fn(void);\n"),
]
# A static helper of the same name in two files: local symbols link nothing.
PLANTED = COMMON + [
    ("library", "lib", "lib_a", "lib", "src/e.c",
     "#include \"lcmtypes/meshtopo_mesh_t.h\"\n#include <meshtopo/other.h>\n"
     "int lcm_publish(void *lcm, const char *channel, const void *data, unsigned size);\n"
     "int e_fn(void)\n{\n    meshtopo_mesh_t m = {0};\n"
     "    return lcm_publish(0, \"X\", &m, 0) + meshtopo_mesh_t_encode(0, 0, 0, &m) + o_fn();\n}\n"),
    ("library", "lib", "lib_a", "lib", "src/a.c",
     "int b_fn(int);\nstatic int helper(int x) { return x - 1; }\n"
     "int a_fn(int x) { return x > 0 ? b_fn(helper(x)) : 0; }\n"),
    ("library", "lib", "lib_a", "lib", "src/b.c",
     "int a_fn(int);\nstatic int helper(int x) { return x - 1; }\n"
     "int b_fn(int x) { return x > 0 ? a_fn(helper(x)) : 1; }\n"),
    ("library", "lib", "lib_a", "lib", "src/c.c",
     "extern int d_counter;\nextern const int t_table[2];\nint d_helper(int);\n"
     "int c_fn(int x) { return d_helper(x) + d_counter + t_table[x & 1]; }\n"),
    ("daemon", "daemon", "daemon_y", "daemon", "d3.c",
     "int d1_fn(int);\nint c_fn(int);\n"
     "int d3_fn(int x) { return x > 0 ? d1_fn(x - 1) : c_fn(x); }\n"),
]
CLEAN = COMMON + [
    ("library", "lib", "lib_a", "lib", "src/a.c",
     "int b_fn(int);\nstatic int helper(int x) { return x - 1; }\n"
     "int a_fn(int x) { return x > 0 ? b_fn(helper(x)) : 0; }\n"),
    ("library", "lib", "lib_a", "lib", "src/b.c",
     "int c_fn(int);\nstatic int helper(int x) { return x - 1; }\n"
     "int b_fn(int x) { return x > 0 ? c_fn(helper(x)) : 1; }\n"),
    ("library", "lib", "lib_a", "lib", "src/c.c", "int c_fn(int x) { return 2 * x; }\n"),
    ("daemon", "daemon", "daemon_y", "daemon", "d3.c",
     "int c_fn(int);\nint d3_fn(int x) { return c_fn(x); }\n"),
]

A, B, C = "selftest/lib/src/a.c", "selftest/lib/src/b.c", "selftest/lib/src/c.c"
E = "selftest/lib/src/e.c"
FORBID = ("--forbid", "lib=other,lcm")
D1, D2, D3 = "selftest/daemon/d1.c", "selftest/daemon/d2.c", "selftest/daemon/d3.c"
T = "selftest/tools/t.c"


def no_problem(role, files, links):
    return {"role": role, "files": files, "links": links, "cycles": [], "upward": [],
            "forbidden": []}


PLANTED_EXPECTED = {
    "daemon": {
        "role": "daemon", "files": 4, "links": 4,
        "cycles": [{
            "files": [D1, D2, D3],
            "example": [D1, D2, D3, D1],
            "links": [{"from": D1, "to": D2, "symbols": ["d2_fn"]},
                      {"from": D2, "to": D3, "symbols": ["d3_fn"]},
                      {"from": D3, "to": D1, "symbols": ["d1_fn"]}],
        }],
        "upward": [],
        "forbidden": [],
    },
    "lib": {
        "role": "library", "files": 4, "links": 2,
        "cycles": [{
            "files": [A, B],
            "example": [A, B, A],
            "links": [{"from": A, "to": B, "symbols": ["b_fn"]},
                      {"from": B, "to": A, "symbols": ["a_fn"]}],
        }],
        "upward": [{"from": C, "to": D1, "unit": "daemon", "symbols": ["d_counter", "d_helper"]},
                   {"from": C, "to": T, "unit": "tools", "symbols": ["t_table"]}],
        "forbidden": [{"from": E, "unit": "lcm",
                       "symbols": ["lcm_publish", "meshtopo_mesh_t_encode"],
                       "includes": ["lcmtypes/meshtopo_mesh_t.h"]},
                      {"from": E, "unit": "other", "symbols": ["o_fn"],
                       "includes": ["meshtopo/other.h"]}],
    },
    "other": no_problem("library", 1, 0),
}
CLEAN_EXPECTED = {
    "daemon": no_problem("daemon", 4, 3),
    "lib": no_problem("library", 3, 2),
    "other": no_problem("library", 1, 0),
}

# The core's families: (path below lib/core/src, text); .c files are compiled.
CORE_COMMON = [
    ("mesh/mesh_internal.h", "int mesh_count(int);\n"),
    ("mesh/mesh.c", "#include \"mesh/mesh_internal.h\"\nint base_alloc(int);\n"
     "int mesh_count(int x) { return base_alloc(x) + 1; }\n"),
    ("build/build.c", "int report_phase(int);\nint mesh_count(int);\n"
     "int core_build(int x) { return report_phase(mesh_count(x)); }\n"),
    ("map/map.c", "int mesh_count(int);\nint map_fn(int x) { return mesh_count(x); }\n"),
]
CORE_PLANTED = CORE_COMMON + [
    ("base/base.h", "#include \"mesh/mesh_internal.h\"\nint base_alloc(int);\n"),
    ("base/alloc.c", "int base_alloc(int x) { return x; }\n"),
    ("base/extra.c", "int map_fn(int);\nint base_more(int x) { return map_fn(x); }\n"),
    ("report/report.c", "#include \"mesh/mesh_internal.h\"\n"
     "int report_phase(int x) { return mesh_count(x); }\n"),
    ("report/report_text.c", "int core_build(int);\n"
     "int report_again(int x) { return core_build(x); }\n"),
    ("stray.c", "int stray_fn(int x) { return x; }\n"),
]
CORE_CLEAN = CORE_COMMON + [
    ("base/base.h", "int base_alloc(int);\n"),
    ("base/alloc.c", "int base_alloc(int x) { return x; }\n"),
    ("report/report.c", "#include \"mesh/mesh_internal.h\"\n"
     "int report_phase(int x) { return mesh_count(x); }\n"),
]
CORE = "lib/core/src/"
CORE_EXPECTED_AGAINST = [
    {"kind": "outside", "from": CORE + "stray.c"},
    {"kind": "call", "from": CORE + "base/extra.c", "from_family": "base",
     "to": CORE + "map/map.c", "to_family": "map", "symbols": ["map_fn"]},
    {"kind": "call", "from": CORE + "report/report_text.c", "from_family": "report",
     "to": CORE + "build/build.c", "to_family": "build.c", "symbols": ["core_build"]},
    {"kind": "include", "from": CORE + "base/base.h", "from_family": "base",
     "to": CORE + "mesh/mesh_internal.h", "to_family": "mesh", "line": 1,
     "include": "mesh/mesh_internal.h"},
]

failures = []


def check(condition, what):
    print("%s: %s" % ("ok" if condition else "FAILED", what))
    if not condition:
        failures.append(what)


def build(cc, root, files):
    """Compile files under root; write and return the object list's path."""
    lines = []
    # Sources below root/selftest, as their names in the object list say, so
    # that --root root finds them.
    for path, text in HEADERS:
        header = os.path.join(root, "selftest", path)
        os.makedirs(os.path.dirname(header), exist_ok=True)
        with open(header, "w", encoding="utf-8") as f:
            f.write(text)
    includes = ["-I", os.path.join(root, "selftest", "include"),
                "-I", os.path.join(root, "selftest", "other", "include")]
    for role, unit, target, directory, source, text in files:
        src = os.path.join(root, "selftest", directory, source)
        # tools/ objects go below a directory named with ": ", which nm's
        # `path: symbol` lines make ambiguous: the checker reads them one by one.
        build_dir = "build: tools" if role == "tools" else "build"
        obj = os.path.join(root, build_dir, directory, "CMakeFiles", target + ".dir", source + ".o")
        os.makedirs(os.path.dirname(src), exist_ok=True)
        os.makedirs(os.path.dirname(obj), exist_ok=True)
        with open(src, "w", encoding="utf-8") as f:
            f.write(text)
        subprocess.run([cc, "-std=c11", "-O0", "-fno-common", *includes, "-c", "-o", obj, src],
                       check=True)
        lines.append("\t".join([role, unit, target, "selftest/" + directory, obj]))
    # A target without objects gives an empty path: skipped.
    lines.append("\t".join(["library", "empty", "empty", "selftest/empty", ""]))
    list_path = os.path.join(root, "objects.txt")
    with open(list_path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    return list_path


def build_core(cc, root, files):
    """The core's files under root/lib/core/src, objects where CMake puts
    them; returns the object list's path."""
    lines = []
    for source, text in files:
        src = os.path.join(root, "lib", "core", "src", source)
        os.makedirs(os.path.dirname(src), exist_ok=True)
        with open(src, "w", encoding="utf-8") as f:
            f.write(text)
    for source, _ in files:
        if not source.endswith(".c"):
            continue
        src = os.path.join(root, "lib", "core", "src", source)
        obj = os.path.join(root, "build", "lib", "core", "CMakeFiles", "meshtopo_core.dir", "src",
                           source + ".o")
        os.makedirs(os.path.dirname(obj), exist_ok=True)
        subprocess.run([cc, "-std=c11", "-O0", "-fno-common", "-I",
                        os.path.join(root, "lib", "core", "src"), "-c", "-o", obj, src], check=True)
        lines.append("\t".join(["library", "core", "meshtopo_core", "lib/core", obj]))
    list_path = os.path.join(root, "objects.txt")
    with open(list_path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    return list_path


def check_core(args, tmp):
    planted_root = os.path.join(tmp, "core-planted")
    clean_root = os.path.join(tmp, "core-clean")
    planted = build_core(args.cc, planted_root, CORE_PLANTED)
    clean = build_core(args.cc, clean_root, CORE_CLEAN)

    status, out, err = run(args, planted, "--unit", "core", "--root", planted_root, "--json")
    check(status == 1, "core planted: exit status %d (expected 1) %s" % (status, err.strip()))
    try:
        got = json.loads(out)["core"]
    except (json.JSONDecodeError, KeyError):
        got = {}
    check(got.get("against_order") == CORE_EXPECTED_AGAINST,
          "core planted: exactly the uses against the family order")
    check("cycles" in got and not got["cycles"] and not got["upward"],
          "core planted: no cycle, nothing upward: the order alone refuses it")
    if got.get("against_order") != CORE_EXPECTED_AGAINST:
        print("expected:\n%s\ngot:\n%s" % (json.dumps(CORE_EXPECTED_AGAINST, indent=2), out))

    status, out, _ = run(args, planted, "--unit", "core", "--root", planted_root)
    print(out, end="")
    check(status == 1, "core planted fails as text")
    for text in ("layering core: FAIL", "4 use(s) against the family order",
                 "family order: base < mesh (uses base) < build (uses base, mesh) < report",
                 "%sbase/extra.c (base) calls %smap/map.c (map), a family it may not use: map_fn"
                 % (CORE, CORE),
                 "%sreport/report_text.c (report) calls %sbuild/build.c (build.c), a family it may "
                 "not use: core_build" % (CORE, CORE),
                 "%sbase/base.h:1 (base) includes \"mesh/mesh_internal.h\" (mesh), a family it "
                 "may not use" % CORE,
                 "%sstray.c is in no family of the order" % CORE):
        check(text in out, "core planted prints %r" % text)

    status, out, err = run(args, clean, "--unit", "core", "--root", clean_root)
    print(out, end="")
    check(status == 0 and out.startswith("layering core: OK") and
          "families in order: base <" in out,
          "core clean passes: the same families used downwards %s" % err.strip())
    status, _, err = run(args, clean, "--unit", "core")
    check(status == 2 and "--root is needed" in err, "core without --root: exit 2")


def run(args, list_path, *extra):
    proc = subprocess.run([sys.executable, args.checker, "--objects", list_path, "--nm", args.nm,
                           *extra], capture_output=True, text=True, timeout=60)
    return proc.returncode, proc.stdout, proc.stderr


def run_json(args, list_path, name, expected_status, expected, *extra):
    status, out, err = run(args, list_path, "--json", *extra)
    check(status == expected_status,
          "%s: exit status %d (expected %d) %s" % (name, status, expected_status, err.strip()))
    try:
        got = json.loads(out)
    except json.JSONDecodeError:
        got = None
    check(got == expected, "%s: exactly the expected report" % name)
    if got != expected:
        print("expected:\n%s\ngot:\n%s" % (json.dumps(expected, indent=2, sort_keys=True), out))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cc", required=True)
    parser.add_argument("--nm", default="nm")
    parser.add_argument("--checker", required=True)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="layering-self-test-") as tmp:
        planted = build(args.cc, os.path.join(tmp, "planted"), PLANTED)
        clean = build(args.cc, os.path.join(tmp, "clean"), CLEAN)

        check_core(args, tmp)

        planted_root = os.path.join(tmp, "planted")
        run_json(args, planted, "planted", 1, PLANTED_EXPECTED, *FORBID, "--root", planted_root)
        run_json(args, clean, "clean", 0, CLEAN_EXPECTED, *FORBID, "--root",
                 os.path.join(tmp, "clean"))
        # Without --root only symbols are checked; without --forbid, the
        # built-in table, which names none of these units.
        status, out, _ = run(args, planted, "--unit", "lib", *FORBID)
        print(out, end="")
        check(status == 1 and "%s must not use lcm: symbols lcm_publish meshtopo_mesh_t_encode\n"
              % E in out and "%s must not use other: symbols o_fn\n" % E in out,
              "planted --forbid lib=other,lcm names e.c's symbols, no #include without --root")
        status, out, _ = run(args, planted, "--unit", "lib", *FORBID, "--root", planted_root)
        check(status == 1 and "symbols lcm_publish meshtopo_mesh_t_encode; #include "
              "lcmtypes/meshtopo_mesh_t.h" in out and "forbidden reference(s)" in out,
              "planted --root names e.c's #include of an LCM type")
        status, out, _ = run(args, planted, "--unit", "other", "--json", "--root", planted_root)
        check(status == 0 and json.loads(out)["other"]["forbidden"] == [],
              "the built-in table forbids nothing to the self-test's units")

        # The text report names the files and the symbols that link them.
        status, out, _ = run(args, planted, "--unit", "lib")
        print(out, end="")
        check(status == 1, "planted --unit lib fails")
        for text in ("layering lib: FAIL", "cycle 1: 2 files reference each other: %s %s" % (A, B),
                     "%s -> %s: b_fn" % (A, B), "%s -> %s: a_fn" % (B, A),
                     "%s references %s (daemon): d_counter d_helper" % (C, D1),
                     "%s references %s (tools): t_table" % (C, T)):
            check(text in out, "planted --unit lib prints %r" % text)
        status, out, _ = run(args, planted, "--unit", "daemon")
        print(out, end="")
        check(status == 1 and "%s -> %s: d1_fn" % (D3, D1) in out,
              "planted --unit daemon fails on d1.c -> d2.c -> d3.c -> d1.c")
        status, out, _ = run(args, planted, "--unit", "other")
        print(out, end="")
        check(status == 0 and out.startswith("layering other: OK"),
              "planted --unit other passes (a library may call another library)")
        status, out, _ = run(args, clean)
        print(out, end="")
        check(status == 0 and "FAIL" not in out, "clean passes as text")

        # Inputs that are not there are an error of their own (exit 2), not a pass.
        status, _, err = run(args, planted, "--unit", "tools")
        check(status == 2 and "unit 'tools'" in err, "--unit tools: not a checked unit")
        status, _, err = run(args, os.path.join(tmp, "missing.txt"))
        check(status == 2, "a missing object list: exit 2")
        with open(os.path.join(tmp, "unbuilt.txt"), "w", encoding="utf-8") as f:
            f.write("library\tlib\tlib_a\tselftest/lib\t%s\n" % os.path.join(tmp, "nowhere.c.o"))
        status, _, err = run(args, os.path.join(tmp, "unbuilt.txt"))
        check(status == 2 and "build the project first" in err, "an unbuilt object: exit 2")
        # An unbuilt object of another unit leaves that unit's links out, with a warning.
        with open(planted, encoding="utf-8") as f:
            listed = f.read()
        with open(os.path.join(tmp, "partly.txt"), "w", encoding="utf-8") as f:
            f.write(listed + "daemon\tdaemon\tdaemon_y\tselftest/daemon\t%s\n"
                    % os.path.join(tmp, "d4.c.o"))
        status, out, err = run(args, os.path.join(tmp, "partly.txt"), "--unit", "lib")
        check(status == 1 and "references %s (daemon)" % D1 in out and
              "warning: 1 object(s) of daemon not built (selftest/daemon/d4.c)" in err,
              "an unbuilt object of another unit: a warning, the unit still checked")
        status, _, err = run(args, os.path.join(tmp, "partly.txt"), "--unit", "daemon")
        check(status == 2 and "build the project first" in err,
              "an unbuilt object of the unit checked: exit 2")
    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
