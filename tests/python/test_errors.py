"""python.errors: bad input never crashes; it raises TypeError / ValueError
for arrays of the wrong kind, or meshtopo.Error carrying the library's status
name and message (the same text `meshtopo inspect` prints)."""
import math
import subprocess

import numpy as np
import pytest

import meshtopo
from test_arrays import grid


def cli_error(cli, *args):
    """The message `meshtopo inspect` prints for a failure, without its prefix."""
    p = subprocess.run([cli, "inspect", *args], capture_output=True, text=True, timeout=60)
    assert p.returncode != 0
    line = p.stderr.strip().splitlines()[0]
    assert line.startswith("meshtopo inspect: ")
    return line[len("meshtopo inspect: "):]


def test_unreadable_file_gives_the_library_message(cli, tmp_path):
    path = tmp_path / "bad.off"
    path.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\nnot-a-number 1 0\n3 0 1 2\n")
    with pytest.raises(meshtopo.Error) as e:
        meshtopo.Mesh.read(str(path))
    assert e.value.status == "MT_ERR_PARSE"
    assert e.value.message == cli_error(cli, str(path))
    assert e.value.message.startswith(str(path) + ":5: ")  # file and line


def test_missing_file(cli, tmp_path):
    path = str(tmp_path / "missing.off")
    with pytest.raises(meshtopo.Error) as e:
        meshtopo.read_face_list(path)
    assert e.value.status == "MT_ERR_IO" and path in e.value.message


def test_strict_build_names_the_defect(cli, tmp_path):
    positions, faces = grid(2)
    faces[1] = faces[0]  # a duplicate face
    path = tmp_path / "dup.off"
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(positions), len(faces)))
        for p in positions:
            f.write("%r %r %r\n" % tuple(p))
        for t in faces:
            f.write("3 %d %d %d\n" % tuple(t))
    with pytest.raises(meshtopo.Error) as e:
        meshtopo.Mesh(positions, faces, strict=True)
    assert e.value.status == "MT_ERR_DEFECT"
    assert e.value.message in cli_error(cli, str(path), "--strict")
    assert meshtopo.Mesh(positions, faces).report()["F_valid"] == len(faces)


def test_inconsistent_sizes_give_the_library_message():
    positions, faces = grid(2)
    counts = np.full(len(faces), 3, np.uint32)
    with pytest.raises(meshtopo.Error) as e:
        meshtopo.Mesh(positions, counts=counts, indices=faces.reshape(-1)[:-1])
    assert e.value.status == "MT_ERR_INVALID_ARG" and e.value.message
    counts[0] = 0xFFFFFFFF  # -1 as int32
    with pytest.raises(meshtopo.Error):
        meshtopo.Mesh(positions, counts=counts, indices=faces.reshape(-1))


def test_nan_positions_are_reported_or_refused():
    positions, faces = grid(2)
    positions[4, 1] = math.nan
    positions[5, 2] = math.inf
    mesh = meshtopo.Mesh(positions, faces)
    bad = mesh.defects[mesh.defects["kind"] ==
                       meshtopo.DEFECT_KINDS.index("nonfinite_coordinate")]
    assert bad["vertices"].tolist() == [[4, meshtopo.NONE], [5, meshtopo.NONE]]
    assert bad["axis"].tolist() == [1, 2] and set(bad["fans"].tolist()) == {meshtopo.NONE}
    with pytest.raises(meshtopo.Error) as e:
        meshtopo.Mesh(positions, faces, strict=True)
    assert e.value.status == "MT_ERR_DEFECT" and "4" in e.value.message


def test_out_of_range_indices_are_reported():
    positions, faces = grid(2)
    faces[2, 0] = 1000
    r = meshtopo.Mesh(positions, faces).report()
    assert r["out_of_range_indices"] == 1 and r["faces_with_out_of_range_indices"] == 1


@pytest.mark.parametrize("positions, faces, error", [
    ("positions-as-text", None, TypeError),
    (np.zeros((4, 2)), np.array([[0, 1, 2]]), ValueError),
    (np.zeros((4, 3)), np.array([[0.0, 1.0, 2.0]]), TypeError),
    (np.zeros((4, 3)), np.array([0, 1, 2]), ValueError),
    (np.zeros((4, 3)), np.array([[0, 1, 2]], dtype=bool), TypeError),
    (np.zeros((4, 3)), np.array([[0, 1, 1 << 40]]), ValueError),
    (np.zeros((4, 3), dtype=complex), np.array([[0, 1, 2]]), TypeError),
    (np.zeros((4, 3)), np.array([["a", "b", "c"]]), TypeError),
])
def test_wrong_arrays_raise(positions, faces, error):
    if isinstance(positions, str):
        positions = np.array([["x", "y", "z"]])
        faces = np.array([[0, 0, 0]])
    with pytest.raises(error):
        meshtopo.Mesh(positions, faces)


def test_argument_mistakes_raise():
    positions, faces = grid(2)
    with pytest.raises(TypeError):
        meshtopo.Mesh(positions)
    with pytest.raises(TypeError):
        meshtopo.Mesh(positions, faces, counts=[3], indices=[0, 1, 2])
    with pytest.raises(TypeError):
        meshtopo.Mesh(None, faces)
    with pytest.raises(ValueError):
        meshtopo.Mesh(positions, faces, num_verts=3)
    mesh = meshtopo.Mesh(None, faces, num_verts=len(positions))
    assert mesh.positions is None


def test_queries_with_bad_ids():
    positions, faces = grid(2)
    faces[0] = [0, 0, 1]  # degenerate: rejected by the build
    mesh = meshtopo.Mesh(positions, faces)
    with pytest.raises(meshtopo.Error) as e:
        mesh.ring(len(positions))
    assert e.value.status == "MT_ERR_OUT_OF_RANGE"
    assert e.value.message.endswith(meshtopo.errors.strerror(e.value.code))
    with pytest.raises(meshtopo.Error) as e:
        mesh.face_neighbors(0)
    assert e.value.status == "MT_ERR_NOT_FOUND"
    with pytest.raises(meshtopo.Error) as e:
        mesh.face_verts(len(faces))
    assert e.value.status == "MT_ERR_OUT_OF_RANGE"
    with pytest.raises(ValueError):
        mesh.ring(-1)
    assert mesh.face_components()[0] == meshtopo.NONE
    assert len(mesh.edge_faces(0, 8)) == 0
