"""python.arrays: numpy arrays in and out without copies where the binding
promises it (checked by buffer addresses), conversions where it does not,
and views over the library's memory that keep it alive."""
import gc

import numpy as np
import pytest

import meshtopo
from conftest import corpus_file


def grid(n=8, dtype=np.int32):
    """An n x n grid of squares, two triangles each: positions (V, 3), faces (F, 3)."""
    ij = np.stack(np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij"), -1)
    positions = np.concatenate([ij.reshape(-1, 2), np.zeros(((n + 1) ** 2, 1))], 1)
    v = (np.arange(n)[:, None] * (n + 1) + np.arange(n)[None, :]).reshape(-1)
    tri = np.concatenate([np.stack([v, v + n + 1, v + 1], 1),
                          np.stack([v + 1, v + n + 1, v + n + 2], 1)])
    return np.ascontiguousarray(positions, dtype=np.float64), tri.astype(dtype)


def addr(a):
    return a.__array_interface__["data"][0]


@pytest.mark.parametrize("dtype", [np.int32, np.uint32])
def test_faces_are_handed_over_without_copy(dtype):
    positions, faces = grid(dtype=dtype)
    fl = meshtopo.FaceList(positions, faces)
    assert addr(fl.positions) == addr(positions)
    assert addr(fl.indices) == addr(faces)
    s = fl.struct()  # what mt_mesh_build reads
    assert s.positions == addr(positions) and s.face_indices == addr(faces)
    assert s.num_faces == len(faces) and s.num_indices == faces.size
    assert np.all(fl.counts == 3)
    mesh = meshtopo.Mesh(fl)
    assert mesh.report()["F_valid"] == len(faces)


@pytest.mark.parametrize("dtype", [np.int32, np.uint32])
def test_counts_and_indices_are_handed_over_without_copy(dtype):
    positions, faces = grid()
    counts = np.full(len(faces), 3, dtype=dtype)
    indices = faces.reshape(-1).astype(dtype)
    fl = meshtopo.FaceList(positions, counts=counts, indices=indices)
    s = fl.struct()
    assert s.face_sizes == addr(counts) and s.face_indices == addr(indices)
    assert s.positions == addr(positions)


@pytest.mark.parametrize("variant", ["int64", "int16", "fortran", "strided", "byteswapped",
                                     "float32_positions", "list"])
def test_other_layouts_are_converted(variant):
    positions, faces = grid()
    reference = meshtopo.Mesh(positions, faces).report()
    p, f = positions, faces
    if variant == "int64":
        f = faces.astype(np.int64)
    elif variant == "int16":
        f = faces.astype(np.int16)
    elif variant == "fortran":
        f = np.asfortranarray(faces)
    elif variant == "strided":
        f = np.repeat(faces, 2, axis=0)[::2]
        p = np.repeat(positions, 2, axis=0)[::2]
    elif variant == "byteswapped":
        f = faces.astype(faces.dtype.newbyteorder(">"))
    elif variant == "float32_positions":
        p = positions.astype(np.float32)
    elif variant == "list":
        p, f = positions.tolist(), faces.tolist()
    fl = meshtopo.FaceList(p, f)
    assert fl.indices.dtype == np.uint32 and fl.indices.flags.c_contiguous
    assert fl.positions.dtype == np.float64 and fl.positions.flags.c_contiguous
    assert meshtopo.Mesh(fl).report() == reference


def test_negative_int32_and_int64_indices_are_out_of_range_not_wrapped():
    positions, faces = grid(2)
    for dtype in (np.int32, np.int64):
        f = faces.astype(dtype)
        f[0, 1] = -1
        r = meshtopo.Mesh(positions, f).report()
        assert r["out_of_range_indices"] == 1 and r["F_valid"] == len(faces) - 1


def test_mesh_positions_are_a_view_of_the_library_copy():
    positions, faces = grid()
    mesh = meshtopo.Mesh(positions, faces)
    a, b = mesh.positions, mesh.positions
    assert addr(a) == addr(b) != addr(positions)  # the library keeps its own copy
    assert not a.flags.writeable and not a.flags.owndata
    np.testing.assert_array_equal(a, positions)
    with pytest.raises(ValueError):
        a[0, 0] = 1.0


def test_report_arrays_are_views_that_keep_the_mesh_alive():
    mesh = meshtopo.Mesh.read(corpus_file("vcg_nonmanifold"))
    defects, components = mesh.defects, mesh.components
    assert len(defects) > 0 and len(components) > 0
    assert addr(defects) == addr(mesh.defects) and addr(components) == addr(mesh.components)
    assert not components.flags.writeable and not components.flags.owndata
    assert not defects.flags.writeable  # records made once, from the report's list
    kept = defects.copy(), components.copy(), mesh.positions.copy()
    positions = mesh.positions
    del mesh
    gc.collect()
    garbage = [np.full(4096, 7.0) for _ in range(64)]  # reuse freed memory, if any
    assert np.array_equal(defects, kept[0]) and np.array_equal(components, kept[1])
    assert np.array_equal(positions, kept[2])
    del garbage


def test_a_file_is_read_into_views_without_copy():
    fl = meshtopo.read_face_list(corpus_file("npm_bunny"))
    for a in (fl.positions, fl.counts, fl.indices):
        assert not a.flags.owndata and not a.flags.writeable
    s = fl.struct()
    assert s.positions == addr(fl.positions) and s.face_indices == addr(fl.indices)
    assert meshtopo.Mesh(fl).report()["V"] == len(fl.positions)


def test_mesh_read_keeps_the_positions_the_reader_read(monkeypatch):
    """Mesh.read builds with mt_mesh_build_taking_positions: the mesh's
    positions are the very array the reader filled, holding the file's
    values, and stay valid once the reader's list is gone."""
    read = meshtopo.mesh.read_face_list
    filled = []

    def spy(path):
        fl = read(path)
        filled.append((addr(fl.positions), fl.positions.copy()))
        return fl

    monkeypatch.setattr(meshtopo.mesh, "read_face_list", spy)
    mesh = meshtopo.Mesh.read(corpus_file("npm_bunny"))
    gc.collect()
    garbage = [np.full(4096, 7.0) for _ in range(64)]  # reuse freed memory, if any
    assert addr(mesh.positions) == filled[0][0]
    assert np.array_equal(mesh.positions, filled[0][1])
    assert mesh.report()["V"] == len(filled[0][1])
    del garbage


def test_closed_mesh_refuses_queries_but_views_survive():
    positions, faces = grid(2)
    with meshtopo.Mesh(positions, faces) as mesh:
        p = mesh.positions
    with pytest.raises(ValueError):
        mesh.ring(0)
    np.testing.assert_array_equal(p, positions)
