#!/usr/bin/env python3
"""daemon.store_owner: one owner per mesh version, read from the objects.

The store (mesh_store.c) and the memory budget reference no symbol of the
archive catalog or writer (they reach them only through the hooks daemon.c
installs), and no file the store calls by name or through a hook calls the
store's add, put, fetch, remove or version reservation: only submit.c puts,
only the store adds. Prints the references read with nm.

usage: check_store_owner.py --nm NM OBJECT...
"""
import argparse
import os
import subprocess
import sys

STORE_ENTRY = ("mtd_store_add", "mtd_store_put", "mtd_store_fetch", "mtd_store_remove",
               "mtd_store_remove_unless", "mtd_store_reserve_version")
# Files the store calls: by name (the budget) or through a hook (the writer's
# policy, the catalog's backing).
CALLED_BY_STORE = ("memory_budget.c", "archive_writer.c", "archive_catalog.c")
STORE = ("mesh_store.c", "memory_budget.c")
HOOK_PREFIXES = ("mtd_catalog_", "mtd_writer_")


def undefined(nm, path):
    out = subprocess.run([nm, "-g", "--undefined-only", path], check=True,
                         capture_output=True, text=True).stdout
    return sorted({line.split()[-1] for line in out.splitlines() if line.strip()})


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--nm", default="nm")
    ap.add_argument("objects", nargs="+")
    args = ap.parse_args()
    by_source = {}
    for path in args.objects:
        name = os.path.basename(path)
        for suffix in (".o", ".obj"):
            if name.endswith(suffix):
                name = name[: -len(suffix)]
        by_source[name] = undefined(args.nm, path)
    problems = []
    for name in STORE + CALLED_BY_STORE + ("submit.c",):
        if name not in by_source:
            problems.append("%s: no object given" % name)
    for name in STORE:
        for sym in by_source.get(name, ()):
            if sym.startswith(HOOK_PREFIXES):
                problems.append("%s calls %s by name" % (name, sym))
    for name in CALLED_BY_STORE:
        for sym in by_source.get(name, ()):
            if sym in STORE_ENTRY:
                problems.append("%s is called by the store and calls %s" % (name, sym))
    for name in sorted(by_source):
        refs = [s for s in by_source[name] if s.startswith(("mtd_store_", "mtd_entry_",
                                                             "mtd_budget_") + HOOK_PREFIXES)]
        print("%-18s -> %s" % (name, " ".join(refs) or "-"))
    if "mtd_store_put" not in by_source.get("submit.c", ()):
        problems.append("submit.c does not put built meshes into the store")
    for p in problems:
        print("FAIL " + p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
