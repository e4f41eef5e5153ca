"""python.client: meshtopo.Client against a real meshtopod over LCM, inside
the private network namespace of tests/netns/netns-run (the test refuses to
run outside it). Starts meshtopod, waits for its heartbeat, submits corpus
meshes from numpy arrays and checks every answer against the same mesh
built locally; then stops the daemon it started, by its PID."""
import os
import signal
import subprocess
import tempfile

import numpy as np
import pytest

import meshtopo
from conftest import corpus_file
from readme_blocks import client_example, local_example

pytestmark = pytest.mark.skipif(
    os.environ.get("MESHTOPO_NETNS") != "1",
    reason="runs only inside tests/netns/netns-run (a private network namespace)")

MESHES = ("npm_bunny", "vcg_nonmanifold", "assimp_malformed")


@pytest.fixture(scope="module")
def daemon():
    path = os.environ.get("MESHTOPOD")
    if not path:
        pytest.fail("MESHTOPOD is not set: run the tests through ctest (python.client)")
    log = tempfile.NamedTemporaryFile(prefix="meshtopod-", suffix=".log", delete=False)
    proc = subprocess.Popen([path, "--heartbeat-ms", "100", "--workers", "2"],
                            stdout=log, stderr=subprocess.STDOUT)
    try:
        yield proc
    finally:
        proc.send_signal(signal.SIGTERM)
        try:
            rc = proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            proc.kill()
            rc = proc.wait()
        log.close()
        with open(log.name, encoding="utf-8", errors="replace") as f:
            text = f.read()
        os.unlink(log.name)
        assert rc == 0, "meshtopod exited %s:\n%s" % (rc, text)


@pytest.fixture(scope="module")
def client(daemon):
    with meshtopo.Client(timeout_ms=2000, retries=3, source="python-test") as c:
        c.wait_daemon(10_000)
        yield c


def local_and_arrays(name):
    fl = meshtopo.read_face_list(corpus_file(name))
    positions = np.array(fl.positions)
    counts, indices = np.array(fl.counts), np.array(fl.indices).view(np.int32)
    return meshtopo.Mesh(fl), positions, counts, indices


@pytest.mark.parametrize("name", MESHES)
def test_submit_and_query_agree_with_local_build(client, name):
    local, positions, counts, indices = local_and_arrays(name)
    report = local.report()
    ack = client.submit(name, positions, counts=counts, indices=indices)
    assert ack.version >= 1 and ack.content_hash != 0
    for key in ("V", "F", "F_valid", "E", "half_edges", "face_size_histogram",
                "edge_use_histogram", "boundary_edges", "boundary_loops", "nonmanifold_edges",
                "nonmanifold_vertices", "connected_components", "euler_characteristic",
                "closed", "manifold", "orientable", "genus", "components"):
        assert ack.report[key] == report[key], key
    assert ack.report["num_defects"] == len(local.defects)

    verts = [q["vertex"] for q in report["vertex_queries"]]
    for v, ring in zip(verts, client.rings(name, verts)):
        want = local.ring(v)
        np.testing.assert_array_equal(ring.neighbors, want.neighbors)
        np.testing.assert_array_equal(ring.faces, want.faces)
        assert ring.fans.tolist() == want.fans.tolist()
    for q in report["face_queries"]:
        if q["adjacent_faces"] is None:
            with pytest.raises(meshtopo.Error) as e:
                client.face_neighbors(name, q["face"])
            assert e.value.status == "MT_ERR_NOT_FOUND"
            continue
        got, want = client.face_neighbors(name, q["face"]), local.face_neighbors(q["face"])
        np.testing.assert_array_equal(got[0], want[0])
        np.testing.assert_array_equal(got[1], want[1])
        corners = local.face_verts(q["face"])
        np.testing.assert_array_equal(client.edge_faces(name, corners[0], corners[1]),
                                      local.edge_faces(corners[0], corners[1]))
    got, want = client.boundary_loops(name), local.boundary_loops()
    np.testing.assert_array_equal(got[0], want[0])
    np.testing.assert_array_equal(got[1], want[1])
    np.testing.assert_array_equal(client.face_components(name), local.face_components())
    remote = client.defects(name)  # records: compared byte for byte (they hold subarrays)
    assert remote.dtype == local.defects.dtype and remote.tobytes() == local.defects.tobytes()


def test_list_holds_the_submitted_meshes(client):
    local, positions, counts, indices = local_and_arrays("cgal_tetrahedron")
    faces = indices.reshape(-1, 3)
    first = client.submit("tetra", positions, faces)
    second = client.submit("tetra", meshtopo.FaceList(positions, faces))
    assert second.version == first.version + 1
    assert second.content_hash == first.content_hash
    listed = [m for m in client.list("tetra")]
    assert sorted(m["version"] for m in listed) == [first.version, second.version]
    assert all(m["num_verts"] == 4 and m["num_faces"] == 4 and m["source"] == "python-test"
               for m in listed)


def test_daemon_errors_carry_its_message(client):
    with pytest.raises(meshtopo.Error) as e:
        client.ring("no-such-mesh", 0)
    assert "no-such-mesh" in e.value.message
    _, positions, _, indices = local_and_arrays("cgal_tetrahedron")
    client.submit("tetra-ids", positions, indices.reshape(-1, 3))
    with pytest.raises(meshtopo.Error) as e:
        client.ring("tetra-ids", 4)
    assert e.value.status == "MT_ERR_OUT_OF_RANGE" and e.value.message
    positions, faces = np.zeros((4, 3)), np.array([[0, 1, 2], [0, 1, 2]], np.int32)
    with pytest.raises(meshtopo.Error) as e:
        client.submit("refused", positions, faces, strict=True)
    assert e.value.status == "MT_ERR_DEFECT" and e.value.message
    with pytest.raises(meshtopo.Error) as e:
        client.submit("bad/id", positions, faces)
    assert e.value.status == "MT_ERR_INVALID_ARG"


def test_readme_client_example(client, capsys):
    namespace = {}
    exec(local_example()[0], namespace)
    capsys.readouterr()
    exec(client_example(), namespace)
    local = meshtopo.Mesh(namespace["positions"], namespace["faces"])
    assert capsys.readouterr().out == "1 %d %s\n" % (
        local.report()["boundary_edges"], local.ring(4).neighbors)
