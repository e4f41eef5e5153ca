"""python.corpus: the binding's report agrees with `meshtopo inspect FILE --json`
(run from the same build) on every corpus mesh, read from the file and built
from numpy arrays; the binding's queries agree with the report's."""
import json
import subprocess

import numpy as np
import pytest

import meshtopo
from conftest import corpus_file, corpus_meshes

MESHES = corpus_meshes()


def inspect_json(cli, path):
    p = subprocess.run([cli, "inspect", path, "--json"], capture_output=True, text=True,
                       timeout=600)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


def arrays_of(face_list):
    """Fresh numpy arrays (not the library's) holding a face list."""
    positions = np.array(face_list.positions, dtype=np.float64)
    counts = np.array(face_list.counts, dtype=np.uint32)
    indices = np.array(face_list.indices, dtype=np.uint32)
    return positions, counts, indices


def test_corpus_is_there():
    assert len(MESHES) >= 20, "corpus not found (MESHTOPO_CORPUS)"


@pytest.mark.parametrize("name", MESHES)
def test_report_equals_inspect_json(cli, name):
    path = corpus_file(name)
    expected = inspect_json(cli, path)
    mesh = meshtopo.Mesh.read(path)
    mesh.validate()
    got = mesh.report()
    assert list(got) == list(expected)  # the same keys in the same order
    assert got == expected


@pytest.mark.parametrize("name", MESHES)
def test_mesh_from_numpy_equals_inspect_json(cli, name):
    path = corpus_file(name)
    expected = inspect_json(cli, path)
    positions, counts, indices = arrays_of(meshtopo.read_face_list(path))
    if len(counts) and np.all(counts == counts[0]):
        mesh = meshtopo.Mesh(positions, indices.reshape(len(counts), counts[0]))
    else:
        mesh = meshtopo.Mesh(positions, counts=counts, indices=indices)
    mesh.validate()
    got = mesh.report()
    assert got.pop("file") is None
    expected.pop("file")
    assert got == expected


@pytest.mark.parametrize("name", MESHES)
def test_queries_agree_with_report(cli, name):
    mesh = meshtopo.Mesh.read(corpus_file(name))
    report = mesh.report()
    for q in report["vertex_queries"]:
        ring = mesh.ring(q["vertex"])
        assert sorted(set(ring.neighbors.tolist())) == q["neighbors"]
        assert sorted(set(ring.faces.tolist())) == q["faces"]
        assert int(ring.fans["neighbor_count"].sum()) == len(ring.neighbors)
        assert int(ring.fans["face_count"].sum()) == len(ring.faces)
    for q in report["face_queries"]:
        if q["adjacent_faces"] is None:
            with pytest.raises(meshtopo.Error) as e:
                mesh.face_neighbors(q["face"])
            assert e.value.status == "MT_ERR_NOT_FOUND"
            continue
        faces, offsets = mesh.face_neighbors(q["face"])
        assert offsets[0] == 0 and offsets[-1] == len(faces)
        assert len(offsets) == len(mesh.face_verts(q["face"])) + 1
        assert sorted(set(faces.tolist()) - {q["face"]}) == q["adjacent_faces"]
        corners = mesh.face_verts(q["face"])
        for i in range(len(corners)):
            across = set(faces[offsets[i]:offsets[i + 1]].tolist())
            on_edge = set(mesh.edge_faces(corners[i], corners[(i + 1) % len(corners)]).tolist())
            assert across == on_edge - {q["face"]}
    components = mesh.components
    assert len(components) == report["connected_components"]
    for got, want in zip(components, report["components"]):
        assert int(got["faces"]) == want["faces"] and int(got["edges"]) == want["edges"]
        assert int(got["min_face"]) == want["min_face_index"]
        assert (int(got["genus"]) if got["genus"] >= 0 else None) == want["genus"]
    labels = mesh.face_components()
    valid = labels != meshtopo.NONE
    assert int(valid.sum()) == report["F_valid"]
    assert np.bincount(labels[valid], minlength=len(components)).tolist() == \
        components["faces"].tolist()
    assert mesh.boundary_loop_lengths.tolist() == report["boundary_loops"]["lengths"]
    verts, offsets = mesh.boundary_loops()
    assert offsets[0] == 0 and offsets[-1] == len(verts)
    if report["manifold"] and report["consistently_oriented"]:
        # Else the half-edge rings also run along seams (meshtopo/query.h).
        assert len(offsets) - 1 == report["boundary_loops"]["count"]
        assert sorted(np.diff(offsets).tolist()) == report["boundary_loops"]["lengths"]
    kinds = [meshtopo.DEFECT_KINDS[k] for k in mesh.defects["kind"]]
    assert kinds.count("nonmanifold_vertex") == report["nonmanifold_vertices"]
    assert kinds.count("isolated_vertex") == report["isolated_vertices"]
    assert kinds.count("degenerate_face") == report["degenerate_faces"]


# Every field of a defect record, in order (README.md "Defect records").
RECORD_FIELDS = ["kind", "vertices", "faces", "edge", "face_count", "index", "position",
                 "face_size", "distinct_vertices", "fans", "on_nonmanifold_edge", "axis"]


def record_as_json(record):
    """A DEFECT_DTYPE record as `inspect --json-defects` writes it (no description)."""
    none = meshtopo.NONE
    out = {"kind": meshtopo.DEFECT_KINDS[record["kind"]]}
    for key in ("vertices", "faces"):
        out[key] = [int(i) for i in record[key] if i != none]
    out["edge"] = None if record["edge"][0] == none else [int(i) for i in record["edge"]]
    for key in RECORD_FIELDS[4:]:
        value = int(record[key])
        out[key] = None if value == none else value
    if out["on_nonmanifold_edge"] is not None:
        out["on_nonmanifold_edge"] = bool(out["on_nonmanifold_edge"])
    return out


@pytest.mark.parametrize("name", [n for n in MESHES if n in (
    "assimp_malformed", "vcg_nonmanifold", "cgal_many_umbrellas", "trimesh_notenoughindices",
    "vcg_moebius")])
def test_defects_are_the_records_inspect_json_lists(cli, name):
    path = corpus_file(name)
    p = subprocess.run([cli, "inspect", path, "--json-defects"], capture_output=True, text=True,
                       timeout=600)
    assert p.returncode == 0, p.stderr
    expected = json.loads(p.stdout)["defects"]
    assert all(list(d) == RECORD_FIELDS + ["description"] for d in expected)
    got = [record_as_json(r) for r in meshtopo.Mesh.read(path).defects]
    assert got == [{k: d[k] for k in RECORD_FIELDS} for d in expected]
    assert list(meshtopo.DEFECT_DTYPE.names) == RECORD_FIELDS
