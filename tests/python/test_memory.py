"""python.memory: the library's memory is released by the objects that own it:
10,000 builds (with reports, queries, views, a file read and a refused build
each round) leave the process's resident set size flat."""
import gc


import meshtopo
from conftest import corpus_file
from test_arrays import grid

ROUNDS = 10_000
WARM_UP = 500
# Allowed growth of VmRSS over the 10,000 rounds. One leaked mesh of this
# grid is about 40 KB, one leaked report text 3 KB: a leak of either in
# every round would add 30 MB or more.
SLACK_BYTES = 2 << 20


def rss_bytes():
    with open("/proc/self/status", encoding="ascii") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    raise AssertionError("no VmRSS in /proc/self/status")


def one_round(positions, faces, bad_faces, path):
    mesh = meshtopo.Mesh(positions, faces)
    report = mesh.report()
    ring = mesh.ring(5)
    p, d, c = mesh.positions, mesh.defects, mesh.components
    loops = mesh.boundary_loops()
    labels = mesh.face_components()
    mesh.close()
    try:
        meshtopo.Mesh(positions, bad_faces, strict=True)
    except meshtopo.Error:
        pass
    small = meshtopo.Mesh.read(path)
    return report["F_valid"] + len(ring.neighbors) + len(p) + len(d) + len(c) + \
        len(loops[0]) + len(labels) + small.report()["F"]


def test_rss_stays_flat_over_10000_builds():
    positions, faces = grid(16)
    bad_faces = faces.copy()
    bad_faces[3] = bad_faces[2]
    path = corpus_file("cgal_tetrahedron")
    expected = one_round(positions, faces, bad_faces, path)
    for _ in range(WARM_UP):
        one_round(positions, faces, bad_faces, path)
    gc.collect()
    before = rss_bytes()
    for _ in range(ROUNDS):
        assert one_round(positions, faces, bad_faces, path) == expected
    gc.collect()
    after = rss_bytes()
    print("VmRSS before %.1f MiB, after %d rounds %.1f MiB (growth %+d KiB)"
          % (before / 2**20, ROUNDS, after / 2**20, (after - before) // 1024))
    assert after - before < SLACK_BYTES
