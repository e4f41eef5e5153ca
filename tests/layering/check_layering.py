#!/usr/bin/env python3
"""Layering of meshtopo's source files, read from the symbols of the built objects.

For every object file, `nm` gives the global symbols it defines (T, D, B, R, ...)
and the ones it leaves undefined (U). Object a "references" object b when a
needs a symbol b defines. Four rules, per unit (a library, or daemon/ as one):

  cycle      the files of one unit reference each other directly or through a
             cycle: each unit's file graph must be acyclic, so every file can
             be read, tested and replaced bottom-up;
  upward     a library object references a symbol defined in daemon/ or tools/
             (role `daemon`, `program` or `tools` in the object list);
  forbidden  a unit of FORBIDDEN (or --forbid) references a unit it must not
             stand on, or LCM itself: a symbol defined there, an LCM symbol
             (lcm_*, the generated meshtopo_*_t functions) wherever it is
             defined, or, with --root, an #include of that unit's headers
             (below its include/) or of LCM's (lcm/, lcmtypes/) in any .c or
             .h file of the unit's source directories. The archive knows
             nothing of LCM (DESIGN.md), and neither does what it stands on.
  order      in a unit whose files are ordered in families (FAMILY_ORDERS: the
             core's folders, base < mesh < build < report < ...), a file
             references a symbol of, or includes a header of, a family it may
             not use, or lies outside every family. Includes are read from the
             sources (--root); a file's family is its folder, or the file
             itself where FAMILY_ORDERS names it.

The object list (tests/layering/CMakeLists.txt writes it with file(GENERATE)
from $<TARGET_OBJECTS:...>) has one object per line, tab-separated:

    role  unit  target  source-prefix  object-path

role is `library`, `daemon`, `program` (a program's part checked on its own,
such as the CLI's archive commands) or `tools`; source-prefix is the target's source
directory relative to the project, and the object's path below
CMakeFiles/<target>.dir/ is its source's path below that directory.

usage: check_layering.py --objects LIST [--nm NM] [--unit UNIT]... [--root DIR]
                         [--forbid UNIT=OTHER,...]... [--json]
exit status: 0 no problem, 1 problems (printed), 2 the list or nm failed, or
an object of a checked unit is not built (other units' are skipped, with a
warning).
"""
import argparse
import json
import os
import re
import subprocess
import sys

ROLES = ("library", "daemon", "program", "tools")
# Roles whose units are checked for cycles; tools/ is only a forbidden target.
CHECKED_ROLES = ("library", "daemon", "program")
# Roles a library must not reference.
UPWARD_ROLES = ("daemon", "program", "tools")
# Bookkeeping the sanitizers and the toolchain add to every object: not calls.
IGNORED_PREFIXES = ("__asan", "___asan", "__odr_asan", "__ubsan", "__sanitizer", "__tsan",
                    "__msan", "__sancov", "__llvm", "__start_", "__stop_")
# nm types of a reference: U, and w or v, weak references that may stay
# undefined. Any other uppercase type (T, D, B, R, C, W, V, ...) is a global
# definition; other lowercase types are local symbols, which link nothing.
UNDEFINED_TYPES = ("U", "w", "v")
# What a unit must not reference: other units, and "lcm" (LCM's symbols and
# headers, the generated message types included).
FORBIDDEN = {
    "core": ("io", "json", "ident", "archive", "msgs", "client", "python", "lcm"),
    "ident": ("io", "json", "archive", "msgs", "client", "python", "lcm"),
    "archive": ("msgs", "client", "python", "lcm"),
}
LCM = "lcm"
# LCM's symbols: its library's and lcm-gen's output for package meshtopo
# (meshtopo_mesh_t_encode, __meshtopo_mesh_t_get_hash, ...).
LCM_SYMBOL = re.compile(r"^_*(lcm_|meshtopo_\w+_t(_|$))")
# LCM's headers, and the headers msgs/ generates beside its own.
LCM_HEADER = re.compile(r"^(lcm|lcmtypes)/")
GENERATED_HEADERS = {"msgs": ("meshtopo/msgs_types.h",)}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)

# Units whose files form families in a fixed order: the unit's source folder
# (relative to the project) and its families, lowest first, each with the
# folders or files it holds (relative to that folder; the longest match
# wins) and the families it may use besides itself. A use is a reference to
# a symbol another file defines or an #include "..." of another file.
#
# The core (lib/core/README.md): base < mesh < build < report < build.c <
# query < geometry < edit < generate, and map beside them on base and mesh.
# build.c runs the build's phases, the report last, so it sits above report
# while the state and phases of build/ sit below it.
FAMILY_ORDERS = {
    "core": ("lib/core/src", [
        ("base", ("base/",), ()),
        ("mesh", ("mesh/",), ("base",)),
        ("build", ("build/",), ("base", "mesh")),
        ("report", ("report/",), ("base", "mesh", "build")),
        ("build.c", ("build/build.c",), ("base", "mesh", "build", "report")),
        ("query", ("query/",), ("base", "mesh")),
        ("geometry", ("geometry/",), ("base", "mesh", "query")),
        ("edit", ("edit/",),
         ("base", "mesh", "build", "report", "build.c", "query", "geometry")),
        ("generate", ("generate/",),
         ("base", "mesh", "build", "report", "build.c", "query", "geometry", "edit")),
        ("map", ("map/",), ("base", "mesh", "build.c", "query")),
    ]),
}
INCLUDE_SUFFIXES = (".c", ".h")
INCLUDE_RE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


class Fail(Exception):
    """An error in the inputs (object list, nm): exit status 2."""


class Obj:
    def __init__(self, role, unit, target, source, path, prefix=""):
        self.role = role
        self.unit = unit
        self.target = target
        self.source = source
        self.path = path
        self.prefix = prefix
        self.defined = set()
        self.undefined = set()


def source_name(prefix, target, path):
    """The source file an object was compiled from, relative to the project.

    CMake names an object after its source's path below the target's source
    directory (or build directory for generated files, `..` written `__`):
    .../CMakeFiles/<target>.dir/src/build.c.o comes from <prefix>/src/build.c.
    """
    marker = "/CMakeFiles/%s.dir/" % target
    norm = path.replace(os.sep, "/")
    if marker in norm:
        rel = norm.split(marker, 1)[1]
    else:
        rel = os.path.basename(norm)
    for suffix in (".o", ".obj"):
        if rel.endswith(suffix):
            rel = rel[: -len(suffix)]
            break
    rel = "/".join(".." if part == "__" else part for part in rel.split("/"))
    name = os.path.normpath(os.path.join(prefix, rel)) if prefix not in ("", ".") else rel
    return name.replace(os.sep, "/")


def read_list(list_path):
    objs = []
    try:
        with open(list_path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise Fail("cannot read the object list %s: %s" % (list_path, e))
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        fields = line.split("\t")
        if len(fields) != 5 or fields[0] not in ROLES:
            raise Fail("%s:%d: expected `role unit target prefix object`, tab-separated, "
                       "role one of %s: %r" % (list_path, number, "/".join(ROLES), line))
        role, unit, target, prefix, path = fields
        if not path:
            continue  # a target without objects
        objs.append(Obj(role, unit, target, source_name(prefix, target, path), path, prefix))
    if not objs:
        raise Fail("%s lists no objects" % list_path)
    return objs


def drop_unbuilt(objs, checked_units):
    """The objects that exist. A missing object of a checked unit is an error;
    one of another unit is left out with a warning, so that a unit's result
    does not hang on another unit's build."""
    built = []
    missing = {}
    for o in objs:
        if os.path.isfile(o.path):
            built.append(o)
        elif o.unit in checked_units:
            raise Fail("object %s of target %s does not exist: build the project first"
                       % (o.path, o.target))
        else:
            missing.setdefault(o.unit, []).append(o.source)
    for unit, sources in sorted(missing.items()):
        sys.stderr.write("check_layering: warning: %d object(s) of %s not built (%s): "
                         "references to them are not checked\n"
                         % (len(sources), unit, " ".join(sorted(sources))))
    return built


def add_symbol(obj, name, kind):
    if name.startswith(IGNORED_PREFIXES):
        return
    if kind in UNDEFINED_TYPES:
        obj.undefined.add(name)
    elif kind.isupper():
        obj.defined.add(name)


def run_nm(nm, paths):
    try:
        proc = subprocess.run([nm, "-P", "-A", *paths], capture_output=True, text=True,
                              timeout=120)
    except OSError as e:
        raise Fail("cannot run %s: %s" % (nm, e))
    if proc.returncode != 0:
        raise Fail("%s -P -A failed: %s" % (nm, proc.stderr.strip()))
    return proc.stdout.splitlines()


def read_symbols(nm, objs):
    """Fill each object's defined and undefined symbols from `nm -P -A`.

    One nm for all objects: lines read `path: name type [value size]`.
    """
    by_path = {o.path: o for o in objs}
    batch = [o.path for o in objs if ": " not in o.path]
    for line in run_nm(nm, batch) if batch else []:
        path, _, rest = line.partition(": ")
        fields = rest.split()
        if path in by_path and len(fields) >= 2:
            add_symbol(by_path[path], fields[0], fields[1])
    for o in objs:
        if ": " in o.path:  # would be ambiguous in a batch
            for line in run_nm(nm, [o.path]):
                fields = line[len(o.path) + 2:].split()
                if len(fields) >= 2:
                    add_symbol(o, fields[0], fields[1])


def strongly_connected(nodes, edges):
    """Tarjan's strongly connected components, iteratively; edges: node -> set."""
    index = {}
    low = {}
    on_stack = set()
    stack = []
    components = []
    counter = 0
    for root in nodes:
        if root in index:
            continue
        work = [(root, iter(sorted(edges.get(root, ()))))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            advanced = False
            for child in children:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(edges.get(child, ())))))
                    advanced = True
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            if advanced:
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                components.append(sorted(component))
    return components


def example_cycle(component, edges):
    """One shortest cycle through the component's first file (breadth-first)."""
    start = component[0]
    members = set(component)
    came_from = {}
    frontier = [start]
    while frontier:
        following = []
        for node in frontier:
            for child in sorted(edges.get(node, ())):
                if child not in members:
                    continue
                if child == start:
                    path = [node]
                    while path[-1] != start:
                        path.append(came_from[path[-1]])
                    return list(reversed(path)) + [start]
                if child not in came_from:
                    came_from[child] = node
                    following.append(child)
        frontier = following
    return [start]


def family_of(order, source):
    """The family of a source file (relative to the project) in a unit's
    order: None when the file is not below the order's folder, "" when it is
    but no family holds it."""
    root, families = order
    prefix = root.rstrip("/") + "/"
    if not source.startswith(prefix):
        return None
    rel = source[len(prefix):]
    best, best_len = "", -1
    for name, places, _ in families:
        for place in places:
            matches = rel.startswith(place) if place.endswith("/") else rel == place
            if matches and len(place) > best_len:
                best, best_len = name, len(place)
    return best


def order_text(order):
    """The order in one line: `base < mesh (uses base) < ...`, lowest first."""
    lines = []
    for name, _, uses in order[1]:
        lines.append("%s (uses %s)" % (name, ", ".join(uses)) if uses else name)
    return " < ".join(lines)


def read_includes(root_dir, order):
    """The C files below the order's folder and their #include "...":
    (files, [(file, line, text, target)]), target the included file relative
    to the project, or None when it is not found there (a public header)."""
    folder = os.path.join(root_dir, order[0])
    if not os.path.isdir(folder):
        raise Fail("no folder %s: --root must be the project's source directory" % folder)
    files = []
    found = []
    for dirpath, dirnames, filenames in os.walk(folder):
        dirnames.sort()
        for filename in sorted(filenames):
            if not filename.endswith(INCLUDE_SUFFIXES):
                continue
            path = os.path.join(dirpath, filename)
            source = os.path.relpath(path, root_dir).replace(os.sep, "/")
            files.append(source)
            try:
                with open(path, encoding="utf-8", errors="replace") as f:
                    lines = f.read().splitlines()
            except OSError as e:
                raise Fail("cannot read %s: %s" % (path, e))
            for number, line in enumerate(lines, 1):
                m = INCLUDE_RE.match(line)
                if not m:
                    continue
                target = None
                # As the compiler looks: the including file's folder, then the
                # unit's source folder (its include directory).
                for base in (dirpath, folder):
                    candidate = os.path.normpath(os.path.join(base, m.group(1)))
                    if os.path.isfile(candidate):
                        target = os.path.relpath(candidate, root_dir).replace(os.sep, "/")
                        break
                found.append((source, number, m.group(1), target))
    return files, found


def check_order(unit, mine, edges, symbols, root_dir):
    """The uses against the unit's family order: calls (edges between its
    objects) and includes (read below root_dir); [] when it has no order."""
    order = FAMILY_ORDERS[unit]
    allowed = {name: set(uses) | {name} for name, _, uses in order[1]}
    problems = []
    if root_dir is None:
        raise Fail("unit %s has a family order: --root is needed to read its includes" % unit)
    files, includes = read_includes(root_dir, order)
    for source in sorted({o.source for o in mine} | set(files)):
        if family_of(order, source) == "":
            problems.append({"kind": "outside", "from": source})
    for a in sorted(edges):
        fa = family_of(order, a)
        for b in sorted(edges[a]):
            fb = family_of(order, b)
            if fa and fb and fb not in allowed[fa]:
                problems.append({"kind": "call", "from": a, "from_family": fa, "to": b,
                                 "to_family": fb, "symbols": sorted(symbols[(a, b)])})
    for source, line, text, target in includes:
        fa = family_of(order, source)
        fb = family_of(order, target) if target else None
        if fa and fb and fb not in allowed[fa]:
            problems.append({"kind": "include", "from": source, "from_family": fa,
                             "to": target, "to_family": fb, "line": line, "include": text})
    return problems


def unit_headers(unit, objs, root):
    """The names a file #includes a unit's headers by: the files below the
    include/ folders of the unit's source directories, and what it generates."""
    names = set(GENERATED_HEADERS.get(unit, ()))
    for prefix in sorted({o.prefix for o in objs if o.unit == unit}):
        include = os.path.join(root, prefix, "include")
        for directory, _, files in os.walk(include):
            for name in files:
                if name.endswith(".h"):
                    rel = os.path.relpath(os.path.join(directory, name), include)
                    names.add(rel.replace(os.sep, "/"))
    return names


def forbidden_includes(unit, objs, root, banned):
    """{(file, banned unit): set of included names} over every .c and .h file
    of the unit's source directories."""
    headers = {b: unit_headers(b, objs, root) for b in banned if b != LCM}
    found = {}
    for prefix in sorted({o.prefix for o in objs if o.unit == unit}):
        top = os.path.join(root, prefix)
        for directory, subdirs, files in os.walk(top):
            subdirs.sort()
            for name in sorted(files):
                if not name.endswith((".c", ".h")):
                    continue
                path = os.path.join(directory, name)
                try:
                    with open(path, encoding="utf-8", errors="replace") as f:
                        text = f.read()
                except OSError as e:
                    raise Fail("cannot read %s: %s" % (path, e))
                source = os.path.relpath(path, root).replace(os.sep, "/")
                for included in INCLUDE.findall(text):
                    for b in banned:
                        if (LCM_HEADER.match(included) if b == LCM
                                else included in headers[b]):
                            found.setdefault((source, b), set()).add(included)
    return found


def check_unit(unit, objs, definers, forbidden=None, root=None):
    """The problems of one unit: {"files", "links", "cycles", "upward", "forbidden"}."""
    forbidden = FORBIDDEN if forbidden is None else forbidden
    banned = forbidden.get(unit, ())
    mine = [o for o in objs if o.unit == unit]
    role = mine[0].role
    edges = {}
    symbols = {}  # (from, to) -> set of symbols
    upward = {}  # (from, to, to unit) -> set of symbols
    refused = {}  # (from, banned unit) -> {"symbols": set, "includes": set}
    for o in mine:
        for name in o.undefined:
            for d in definers.get(name, ()):
                if d.unit == unit and d is not o:
                    edges.setdefault(o.source, set()).add(d.source)
                    symbols.setdefault((o.source, d.source), set()).add(name)
                elif role == "library" and d.role in UPWARD_ROLES:
                    upward.setdefault((o.source, d.source, d.unit), set()).add(name)
            owners = {d.unit for d in definers.get(name, ()) if d.unit != unit}
            hits = sorted(owners & set(banned))
            if not hits and LCM in banned and LCM_SYMBOL.match(name):
                hits = [LCM]
            for b in hits:
                refused.setdefault((o.source, b), {"symbols": set(), "includes": set()})[
                    "symbols"].add(name)
    if banned and root:
        for key, names in forbidden_includes(unit, objs, root, banned).items():
            refused.setdefault(key, {"symbols": set(), "includes": set()})["includes"] |= names
    nodes = sorted({o.source for o in mine})
    cycles = []
    for component in strongly_connected(nodes, edges):
        if len(component) < 2:
            continue
        links = [{"from": a, "to": b, "symbols": sorted(symbols[(a, b)])}
                 for a in component for b in sorted(edges.get(a, ())) if b in component]
        cycles.append({"files": component, "example": example_cycle(component, edges),
                       "links": links})
    cycles.sort(key=lambda c: c["files"])
    result = {
        "role": role,
        "files": len(nodes),
        "links": len(symbols),
        "cycles": cycles,
        "upward": [{"from": a, "to": b, "unit": u, "symbols": sorted(s)}
                   for (a, b, u), s in sorted(upward.items())],
        "forbidden": [{"from": a, "unit": b, "symbols": sorted(r["symbols"]),
                       "includes": sorted(r["includes"])}
                      for (a, b), r in sorted(refused.items())],
    }
    if unit in FAMILY_ORDERS:
        result["order"] = order_text(FAMILY_ORDERS[unit])
        result["against_order"] = check_order(unit, mine, edges, symbols, root)
    return result


def failed(result):
    return bool(result["cycles"] or result["upward"] or result["forbidden"] or
                result.get("against_order"))


def print_unit(unit, result, out):
    cycles, upward, refused = result["cycles"], result["upward"], result["forbidden"]
    against = result.get("against_order", [])
    if not failed(result):
        extra = "; no references into daemon/ or tools/" if result["role"] == "library" else ""
        if "order" in result:
            extra += "; families in order: %s" % result["order"]
        out.write("layering %s: OK: %d files, %d links between them, no cycle%s\n"
                  % (unit, result["files"], result["links"], extra))
        return
    upward_count = ""
    if result["role"] == "library":
        upward_count = ", %d reference(s) into daemon/ or tools/" % len(upward)
    if "order" in result:
        upward_count += ", %d use(s) against the family order" % len(against)
    forbidden_count = ", %d forbidden reference(s)" % len(refused) if refused else ""
    out.write("layering %s: FAIL: %d files, %d cycle(s)%s%s\n"
              % (unit, result["files"], len(cycles), upward_count, forbidden_count))
    if against:
        out.write("  family order: %s\n" % result["order"])
    for use in against:
        if use["kind"] == "outside":
            out.write("  %s is in no family of the order: add its folder to FAMILY_ORDERS\n"
                      % use["from"])
        elif use["kind"] == "call":
            out.write("  %s (%s) calls %s (%s), a family it may not use: %s\n"
                      % (use["from"], use["from_family"], use["to"], use["to_family"],
                         " ".join(use["symbols"])))
        else:
            out.write("  %s:%d (%s) includes \"%s\" (%s), a family it may not use\n"
                      % (use["from"], use["line"], use["from_family"], use["include"],
                         use["to_family"]))
    for number, cycle in enumerate(cycles, 1):
        out.write("  cycle %d: %d files reference each other: %s\n"
                  % (number, len(cycle["files"]), " ".join(cycle["files"])))
        out.write("    for example: %s\n" % " -> ".join(cycle["example"]))
        for link in cycle["links"]:
            out.write("    %s -> %s: %s\n" % (link["from"], link["to"], " ".join(link["symbols"])))
    for ref in upward:
        out.write("  %s references %s (%s): %s\n"
                  % (ref["from"], ref["to"], ref["unit"], " ".join(ref["symbols"])))
    for ref in refused:
        what = ["symbols " + " ".join(ref["symbols"])] if ref["symbols"] else []
        what += ["#include " + " ".join(ref["includes"])] if ref["includes"] else []
        out.write("  %s must not use %s: %s\n" % (ref["from"], ref["unit"], "; ".join(what)))


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--objects", required=True, help="the object list (see above)")
    parser.add_argument("--nm", default="nm", help="nm program (default: nm)")
    parser.add_argument("--unit", action="append", default=[],
                        help="check this unit only (repeatable; default: every library "
                             "and daemon unit)")
    parser.add_argument("--root", default=None,
                        help="the project's source directory: where the includes of units "
                             "with a family order or forbidden dependencies are read "
                             "(default: not read)")
    parser.add_argument("--forbid", action="append", default=[], metavar="UNIT=OTHER,...",
                        help="UNIT must not reference OTHER (a unit, or lcm); replaces the "
                             "built-in table (repeatable)")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    args = parser.parse_args(argv)
    forbidden = None
    if args.forbid:
        forbidden = {}
        for rule in args.forbid:
            unit, _, others = rule.partition("=")
            if not unit or not others:
                parser.error("--forbid %r: expected UNIT=OTHER,..." % rule)
            forbidden[unit] = tuple(o for o in others.split(",") if o)
    try:
        objs = read_list(args.objects)
        checked = sorted({o.unit for o in objs if o.role in CHECKED_ROLES})
        for unit in args.unit:
            if unit not in checked:
                raise Fail("unit %r has no objects in %s (units: %s)"
                           % (unit, args.objects, " ".join(checked)))
        objs = drop_unbuilt(objs, args.unit or checked)
        read_symbols(args.nm, objs)
    except Fail as e:
        sys.stderr.write("check_layering: %s\n" % e)
        return 2
    definers = {}
    for o in objs:
        for name in o.defined:
            definers.setdefault(name, []).append(o)
    try:
        results = {unit: check_unit(unit, objs, definers, forbidden, args.root)
                   for unit in (args.unit or checked)}
    except Fail as e:
        sys.stderr.write("check_layering: %s\n" % e)
        return 2
    if args.json:
        json.dump(results, sys.stdout, indent=2, sort_keys=True)
        sys.stdout.write("\n")
    else:
        for unit, result in results.items():
            print_unit(unit, result, sys.stdout)
    return 1 if any(failed(r) for r in results.values()) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
