# Checks the files `meshtopo-bench all` wrote into one directory: bench.md
# has the table (one row per case and library), bench.csv has the expected
# columns and one row per library and case with every library measured,
# build-time.svg parses as XML and holds one polyline per library and order;
# meshtopo's heap growth per face matches its structure's size.
# Used by the bench.all_quick ctest: check_results.py DIR [CORPUS]. A corpus
# mesh missing from CORPUS is not expected (the benchmark leaves it out).
# Exit 0 when well-formed.
import csv
import os
import sys
import xml.etree.ElementTree as ET

COLUMNS = (
    "mesh,order,faces,library,version,state,threads,reps,verts,edges,faces_built,"
    "boundary_loops,components,build_ms_median,build_ms_min,build_ms_max,build_ratio,"
    "ns_per_face,ring_ms_median,ring_ratio,ring_neighbours,ring_neighbours_per_s,"
    "adj_ms_median,adj_ratio,adj_neighbours,adj_neighbours_per_s,loops_ms_median,"
    "components_ms_median,heap_bytes_per_face,structure_bytes_per_face"
).split(",")
MESHES = ("npm_bunny", "igl_fertility", "grid", "torus")
ORDERS = ("ordered", "permuted")
ALWAYS = (
    "meshtopo-1t",
    "meshtopo-2t",
    "meshtopo-1t-new",
    "meshtopo-2t-new",
    "memcpy-fresh",
    "memcpy-reused",
)
PEERS = ("OpenMesh", "CGAL", "CGAL-soup")


def fail(message):
    print("check_results: " + message)
    sys.exit(1)


def main():
    if len(sys.argv) not in (2, 3):
        fail("usage: check_results.py DIR [CORPUS]")
    out = sys.argv[1]
    meshes = MESHES
    if len(sys.argv) == 3:
        meshes = tuple(m for m in MESHES if m in ("grid", "torus")
                       or os.path.exists(os.path.join(sys.argv[2], m + ".off")))

    with open(out + "/bench.csv", newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = list(reader)
    if header != COLUMNS:
        fail("bench.csv columns differ: %s" % header)
    cases = []
    libraries = []
    seen = set()
    for row in rows:
        if len(row) != len(COLUMNS):
            fail("bench.csv row has %d fields, not %d: %s" % (len(row), len(COLUMNS), row))
        r = dict(zip(COLUMNS, row))
        key = (r["mesh"], r["order"], r["library"])
        if key in seen:
            fail("bench.csv repeats %s" % (key,))
        seen.add(key)
        if (r["mesh"], r["order"]) not in cases:
            cases.append((r["mesh"], r["order"]))
        if r["library"] not in libraries:
            libraries.append(r["library"])
        if r["state"] == "failed":
            fail("%s failed on %s, %s" % (r["library"], r["mesh"], r["order"]))
        if r["state"] == "ok":
            if not float(r["build_ms_median"]) > 0:
                fail("no build time for %s" % (key,))
            if r["library"] not in ("memcpy-fresh", "memcpy-reused"):
                for col in ("verts", "faces_built", "ring_neighbours_per_s", "adj_neighbours_per_s"):
                    if not float(r[col]) > 0:
                        fail("%s is empty for %s" % (col, key))
            # The heap a meshtopo mesh holds is its structure, whether its arrays are
            # new memory or were recycled through the build workspace (empty where
            # the heap cannot be measured, as under AddressSanitizer).
            if r["library"].startswith("meshtopo") and r["heap_bytes_per_face"] != "":
                heap = float(r["heap_bytes_per_face"])
                structure = float(r["structure_bytes_per_face"])
                if abs(heap - structure) > 0.1 * structure:
                    fail("%s holds %.1f heap bytes per face, its structure %.1f"
                         % (key, heap, structure))
    if len(cases) != len(meshes) * len(ORDERS):
        fail("bench.csv has %d cases, expected %d: %s" % (len(cases), len(meshes) * len(ORDERS),
                                                          cases))
    for mesh in meshes:
        for order in ORDERS:
            if not any(c[0].startswith(mesh) and c[1] == order for c in cases):
                fail("bench.csv has no %s, %s" % (mesh, order))
    for lib in ALWAYS:
        if lib not in libraries:
            fail("bench.csv has no %s rows" % lib)
    for lib in libraries:
        if lib not in ALWAYS and lib not in PEERS:
            fail("bench.csv has an unknown library %s" % lib)
    if len(rows) != len(cases) * len(libraries):
        fail("bench.csv has %d rows, expected one per library and case (%d)"
             % (len(rows), len(cases) * len(libraries)))

    with open(out + "/bench.md") as f:
        md = f.read().splitlines()
    table = [line for line in md if line.startswith("| ")]
    if len(table) != 1 + len(rows):
        fail("bench.md has %d table lines, expected %d" % (len(table), 1 + len(rows)))
    width = table[0].count("|")
    for line in table:
        if line.count("|") != width:
            fail("bench.md row with %d cells: %s" % (line.count("|") - 1, line))
    if not any(line.startswith("- command: `meshtopo-bench all") for line in md):
        fail("bench.md does not name the command")

    root = ET.parse(out + "/build-time.svg").getroot()
    if root.tag != "{http://www.w3.org/2000/svg}svg":
        fail("build-time.svg is not an SVG document: %s" % root.tag)
    lines = root.findall("{http://www.w3.org/2000/svg}polyline")
    measured = {(r[3], r[1]) for r in rows if r[5] == "ok"}
    if len(lines) != len(measured):
        fail("build-time.svg has %d lines, expected %d (one per library and order)"
             % (len(lines), len(measured)))
    for line in lines:
        points = line.get("points").split()
        if len(points) != len(meshes):
            fail("a line of build-time.svg has %d points, expected %d" % (len(points), len(meshes)))
    print("check_results: %d cases x %d libraries, Markdown, CSV and SVG well-formed"
          % (len(cases), len(libraries)))


main()
