#!/usr/bin/env python3
"""Layering of meshtopo's source files, read from the symbols of the built objects.

For every object file, `nm` gives the global symbols it defines (T, D, B, R, ...)
and the ones it leaves undefined (U). Object a "references" object b when a
needs a symbol b defines. Two rules, per unit (a library, or daemon/ as one):

  cycle    the files of one unit reference each other directly or through a
           cycle: each unit's file graph must be acyclic, so every file can be
           read, tested and replaced bottom-up;
  upward   a library object references a symbol defined in daemon/ or tools/
           (role `daemon` or `tools` in the object list).

The object list (tests/layering/CMakeLists.txt writes it with file(GENERATE)
from $<TARGET_OBJECTS:...>) has one object per line, tab-separated:

    role  unit  target  source-prefix  object-path

role is `library`, `daemon` or `tools`; source-prefix is the target's source
directory relative to the project, and the object's path below
CMakeFiles/<target>.dir/ is its source's path below that directory.

usage: check_layering.py --objects LIST [--nm NM] [--unit UNIT]... [--json]
exit status: 0 no problem, 1 problems (printed), 2 the list or nm failed, or
an object of a checked unit is not built (other units' are skipped, with a
warning).
"""
import argparse
import json
import os
import subprocess
import sys

ROLES = ("library", "daemon", "tools")
# Roles whose units are checked for cycles; tools/ is only a forbidden target.
CHECKED_ROLES = ("library", "daemon")
# Roles a library must not reference.
UPWARD_ROLES = ("daemon", "tools")
# Bookkeeping the sanitizers and the toolchain add to every object: not calls.
IGNORED_PREFIXES = ("__asan", "___asan", "__odr_asan", "__ubsan", "__sanitizer", "__tsan",
                    "__msan", "__sancov", "__llvm", "__start_", "__stop_")
# nm types of a reference: U, and w or v, weak references that may stay
# undefined. Any other uppercase type (T, D, B, R, C, W, V, ...) is a global
# definition; other lowercase types are local symbols, which link nothing.
UNDEFINED_TYPES = ("U", "w", "v")


class Fail(Exception):
    """An error in the inputs (object list, nm): exit status 2."""


class Obj:
    def __init__(self, role, unit, target, source, path):
        self.role = role
        self.unit = unit
        self.target = target
        self.source = source
        self.path = path
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
        objs.append(Obj(role, unit, target, source_name(prefix, target, path), path))
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


def check_unit(unit, objs, definers):
    """The problems of one unit: {"files", "links", "cycles", "upward"}."""
    mine = [o for o in objs if o.unit == unit]
    role = mine[0].role
    edges = {}
    symbols = {}  # (from, to) -> set of symbols
    upward = {}  # (from, to, to unit) -> set of symbols
    for o in mine:
        for name in o.undefined:
            for d in definers.get(name, ()):
                if d.unit == unit and d is not o:
                    edges.setdefault(o.source, set()).add(d.source)
                    symbols.setdefault((o.source, d.source), set()).add(name)
                elif role == "library" and d.role in UPWARD_ROLES:
                    upward.setdefault((o.source, d.source, d.unit), set()).add(name)
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
    return {
        "role": role,
        "files": len(nodes),
        "links": len(symbols),
        "cycles": cycles,
        "upward": [{"from": a, "to": b, "unit": u, "symbols": sorted(s)}
                   for (a, b, u), s in sorted(upward.items())],
    }


def print_unit(unit, result, out):
    cycles, upward = result["cycles"], result["upward"]
    if not cycles and not upward:
        extra = "; no references into daemon/ or tools/" if result["role"] == "library" else ""
        out.write("layering %s: OK: %d files, %d links between them, no cycle%s\n"
                  % (unit, result["files"], result["links"], extra))
        return
    upward_count = ""
    if result["role"] == "library":
        upward_count = ", %d reference(s) into daemon/ or tools/" % len(upward)
    out.write("layering %s: FAIL: %d files, %d cycle(s)%s\n"
              % (unit, result["files"], len(cycles), upward_count))
    for number, cycle in enumerate(cycles, 1):
        out.write("  cycle %d: %d files reference each other: %s\n"
                  % (number, len(cycle["files"]), " ".join(cycle["files"])))
        out.write("    for example: %s\n" % " -> ".join(cycle["example"]))
        for link in cycle["links"]:
            out.write("    %s -> %s: %s\n" % (link["from"], link["to"], " ".join(link["symbols"])))
    for ref in upward:
        out.write("  %s references %s (%s): %s\n"
                  % (ref["from"], ref["to"], ref["unit"], " ".join(ref["symbols"])))


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--objects", required=True, help="the object list (see above)")
    parser.add_argument("--nm", default="nm", help="nm program (default: nm)")
    parser.add_argument("--unit", action="append", default=[],
                        help="check this unit only (repeatable; default: every library "
                             "and daemon unit)")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    args = parser.parse_args(argv)
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
    results = {unit: check_unit(unit, objs, definers) for unit in (args.unit or checked)}
    if args.json:
        json.dump(results, sys.stdout, indent=2, sort_keys=True)
        sys.stdout.write("\n")
    else:
        for unit, result in results.items():
            print_unit(unit, result, sys.stdout)
    failed = any(r["cycles"] or r["upward"] for r in results.values())
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
