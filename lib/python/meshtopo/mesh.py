"""meshtopo.Mesh: a half-edge mesh built by the C library from a face list,
with its topology report and queries. Every answer comes from the library;
ids are the caller's vertex and face ids."""
import collections
import json
import os
import weakref

import numpy as np

from . import _lib
from .arrays import COMPONENT_DTYPE, DEFECT_DTYPE, FAN_DTYPE, address, view
from .errors import STATUS, check
from .face_list import FaceList, read_face_list

# One vertex's one-ring: neighbors and faces in rotational order, fan after
# fan ((n,) uint32 each); fans: FAN_DTYPE records (neighbor_begin,
# neighbor_count, face_begin, face_count, boundary) ranging over them.
Ring = collections.namedtuple("Ring", "neighbors faces fans")

_ERR_BUFFER_TOO_SMALL = STATUS["MT_ERR_BUFFER_TOO_SMALL"]
_ERR_NOT_FOUND = STATUS["MT_ERR_NOT_FOUND"]


def _u32(name, value):
    value = int(value)
    if not 0 <= value <= 0xFFFFFFFF:
        raise ValueError("%s %d is not a meshtopo id (0 .. 2^32 - 2)" % (name, value))
    return value


def defect_records(defects, count):
    """(count,) DEFECT_DTYPE records, read-only, of the `count` mt_defect at
    address `defects`, made by the library (mt_defect_to_records)."""
    out = np.empty(count, DEFECT_DTYPE)
    if count:
        _lib.mt_defect_to_records(defects, count, address(out))
    out.flags.writeable = False
    return out


class _Handle:
    """Owns an mt_mesh; destroys it when nothing (the Mesh, an array viewing
    its memory) refers to the handle any more."""

    def __init__(self, pointer):
        self.pointer = pointer
        weakref.finalize(self, _lib.mt_mesh_destroy, pointer)


class Mesh:
    """Mesh(positions, faces=None, *, counts=None, indices=None, num_verts=None,
    strict=False, threads=0)

    Builds the half-edge mesh of a face list: `positions` (V, 3) and `faces`
    (F, k), or `counts` (F,) and `indices` (sum(counts),) for faces of mixed
    sizes (meshtopo.FaceList says which layouts are not copied; a FaceList
    may be passed as `positions`). Messy meshes are kept and their defects
    reported; `strict=True` refuses any defect. `threads`: 0 as many as pay
    off, 1 the calling thread, 2 two threads. Raises meshtopo.Error with the
    library's message when the build fails, TypeError / ValueError for
    arrays of the wrong kind. The library's memory is freed when the mesh
    and every array viewing it are gone, or at close() / the end of a with
    block.
    """

    def __init__(self, positions=None, faces=None, *, counts=None, indices=None,
                 num_verts=None, strict=False, threads=0, file_name=None):
        if isinstance(positions, FaceList):
            if faces is not None or counts is not None or indices is not None:
                raise TypeError("Mesh: give a FaceList or arrays, not both")
            face_list = positions
        else:
            face_list = FaceList(positions, faces, counts=counts, indices=indices,
                                 num_verts=num_verts)
        self._build(_lib.mt_mesh_build, face_list.struct(), strict, threads)
        self.file_name = file_name

    def _build(self, build, struct, strict, threads):
        options = _lib.BuildOptions()
        options.strict = bool(strict)
        options.threads = _u32("threads", threads)
        pointer = _lib.c_ptr()
        diag = _lib.Diag()
        code = build(struct, options, pointer, diag)
        check(code, diag)
        self._handle = _Handle(pointer.value)
        self._defects = None

    @classmethod
    def read(cls, path, *, strict=False, threads=0):
        """Reads an OFF, OBJ, PLY or STL file (gzip too) and builds it, as
        `meshtopo inspect FILE` does; report()["file"] is the file's name.
        The mesh keeps the positions the reader read instead of a copy."""
        face_list = read_face_list(path)
        mesh = cls.__new__(cls)
        # On the reader's own list, which then no longer frees the positions
        # (the views of face_list, dropped here, would not see them go).
        mesh._build(_lib.mt_mesh_build_taking_positions, face_list._owner.struct, strict,
                    threads)
        mesh.file_name = os.path.basename(os.fsdecode(path))
        return mesh

    # ---- lifetime -----------------------------------------------------------

    def close(self):
        """Lets go of the library's mesh: it is freed now, or when the last
        array viewing its memory goes. The mesh cannot be used afterwards."""
        self._handle = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @property
    def _ptr(self):
        if self._handle is None:
            raise ValueError("meshtopo.Mesh: the mesh is closed")
        return self._handle.pointer

    # ---- counts and arrays in the library's memory --------------------------

    @property
    def num_verts(self):
        """Vertices as given to the build (the caller's id range)."""
        return _lib.mt_mesh_num_verts(self._ptr)

    @property
    def num_faces(self):
        """Face records as given to the build, rejected ones included."""
        return _lib.mt_mesh_num_faces(self._ptr)

    def _report_struct(self):
        return _lib.mt_mesh_report(self._ptr).contents

    @property
    def positions(self):
        """(V, 3) float64, read-only view of the mesh's positions: its copy
        of those it was built from, or for Mesh.read those the file was read
        into (None without geometry)."""
        v = _lib.MeshView()
        _lib.mt_mesh_get_view(self._ptr, v)
        if not v.positions:
            return None
        return view(self._handle, v.positions, 3 * v.num_verts, np.float64, (v.num_verts, 3))

    @property
    def defects(self):
        """Every defect the build found, as (N,) DEFECT_DTYPE records (README.md
        "Defect records": kind, vertices, faces, edge, face_count, index,
        position, face_size, distinct_vertices, fans, on_nonmanifold_edge,
        axis; NONE where a field does not apply), grouped by kind, then by
        first id. meshtopo.DEFECT_KINDS names the kinds. Read-only, made by
        the library from the report's list on first use."""
        if self._defects is None:
            r = self._report_struct()
            self._defects = defect_records(r.defects, r.num_defects)
        return self._defects

    @property
    def components(self):
        """Edge-connected components of valid faces, ordered by smallest face,
        as COMPONENT_DTYPE records (faces, vertices, edges,
        euler_characteristic, boundary_edges, boundary_loops, closed,
        manifold, orientable, genus, genus_with_boundary; -1 genus when
        undefined): a read-only view of the report's list."""
        r = self._report_struct()
        return view(self._handle, r.components, r.connected_components, COMPONENT_DTYPE)

    @property
    def boundary_loop_lengths(self):
        """(loops,) uint32 edge counts of the boundary-edge graph's parts,
        ascending (DEFINITIONS.md): a read-only view of the report's list."""
        r = self._report_struct()
        return view(self._handle, r.boundary_loop_lengths, r.boundary_loops, np.uint32)

    # ---- the report -----------------------------------------------------------

    def report(self):
        """The topology report as a dict with the keys of `meshtopo inspect FILE
        --json` (the corpus answers' keys, tests/corpus/DEFINITIONS.md), written
        by the same C code: counts, histograms, boundary loops, flags, genus,
        components, the default vertex_queries and face_queries, and "file"
        (the file's name for Mesh.read, else None)."""
        text = _lib.c_ptr()
        size = _lib.c_size()
        diag = _lib.Diag()
        name = None if self.file_name is None else os.fsencode(self.file_name)
        code = _lib.mt_report_json_inspect(self._ptr, name, text, size, diag)
        check(code, diag)
        try:
            return json.loads(_lib.ctypes.string_at(text.value, size.value).decode("utf-8"))
        finally:
            _lib.mt_report_json_free(text.value)

    def validate(self):
        """Checks every invariant of the half-edge structure; raises
        meshtopo.Error naming the first broken one."""
        diag = _lib.Diag()
        check(_lib.mt_mesh_validate(self._ptr, diag), diag)

    # ---- queries ----------------------------------------------------------------

    def ring(self, vert):
        """One-ring of a vertex: Ring(neighbors, faces, fans), in rotational
        order fan by fan (counter-clockwise for consistently oriented faces);
        an isolated vertex has empty arrays. Raises meshtopo.Error
        (MT_ERR_OUT_OF_RANGE) for an id past num_verts."""
        vert = _u32("vertex", vert)
        ring = _lib.RingStruct()
        code = _lib.mt_vert_ring(self._ptr, vert, ring)
        if code not in (0, _ERR_BUFFER_TOO_SMALL):
            check(code, context="vertex %d" % vert)
        neighbors = np.empty(ring.num_neighbors, np.uint32)
        faces = np.empty(ring.num_faces, np.uint32)
        fans = np.empty(ring.num_fans, FAN_DTYPE)
        ring.neighbors, ring.neighbors_capacity = address(neighbors) or None, len(neighbors)
        ring.faces, ring.faces_capacity = address(faces) or None, len(faces)
        ring.fans, ring.fans_capacity = address(fans) or None, len(fans)
        check(_lib.mt_vert_ring(self._ptr, vert, ring), context="vertex %d" % vert)
        return Ring(neighbors, faces, fans)

    def face_verts(self, face):
        """(k,) uint32: the face's vertex ids in its stored order. Raises
        meshtopo.Error (MT_ERR_NOT_FOUND) for a face the build rejected."""
        face = _u32("face", face)
        count = _lib.c_size()
        code = _lib.mt_face_verts(self._ptr, face, None, 0, count)
        if code not in (0, _ERR_BUFFER_TOO_SMALL):
            check(code, context="face %d" % face)
        out = np.empty(count.value, np.uint32)
        check(_lib.mt_face_verts(self._ptr, face, address(out) or None, len(out), count),
              context="face %d" % face)
        return out

    def face_neighbors(self, face):
        """Faces across each side of a face, as CSR: (faces, offsets), both
        uint32; side i (from corner i to i + 1) has faces[offsets[i] :
        offsets[i + 1]] (several across a non-manifold edge, none on a
        boundary). Raises meshtopo.Error for a rejected face or a bad id."""
        face = _u32("face", face)
        num_faces, num_edges = _lib.c_size(), _lib.c_size()
        code = _lib.mt_face_neighbors(self._ptr, face, None, 0, None, 0, num_faces, num_edges)
        if code not in (0, _ERR_BUFFER_TOO_SMALL):
            check(code, context="face %d" % face)
        faces = np.empty(num_faces.value, np.uint32)
        offsets = np.empty(num_edges.value + 1, np.uint32)
        check(_lib.mt_face_neighbors(self._ptr, face, address(faces) or None, len(faces),
                                     address(offsets), len(offsets), num_faces, num_edges),
              context="face %d" % face)
        return faces, offsets

    def edge_faces(self, a, b):
        """(n,) uint32: the valid faces (ascending) having {a, b} as a side;
        empty when none has."""
        a, b = _u32("vertex", a), _u32("vertex", b)
        count = _lib.c_size()
        code = _lib.mt_edge_faces(self._ptr, a, b, None, 0, count)
        if code == _ERR_NOT_FOUND:  # no valid face has the edge
            return np.empty(0, np.uint32)
        if code not in (0, _ERR_BUFFER_TOO_SMALL):
            check(code, context="edge %d-%d" % (a, b))
        out = np.empty(count.value, np.uint32)
        check(_lib.mt_edge_faces(self._ptr, a, b, address(out) or None, len(out), count),
              context="edge %d-%d" % (a, b))
        return out

    def boundary_loops(self):
        """The boundary loops as CSR: (verts, offsets), both uint32; loop i is
        verts[offsets[i] : offsets[i + 1]], walked with the faces on its left
        (the half-edge boundary rings, meshtopo/query.h)."""
        num_verts, num_loops = _lib.c_size(), _lib.c_size()
        code = _lib.mt_boundary_loops(self._ptr, None, 0, None, 0, num_verts, num_loops)
        if code not in (0, _ERR_BUFFER_TOO_SMALL):
            check(code)
        verts = np.empty(num_verts.value, np.uint32)
        offsets = np.empty(num_loops.value + 1, np.uint32)
        check(_lib.mt_boundary_loops(self._ptr, address(verts) or None, len(verts),
                                     address(offsets), len(offsets), num_verts, num_loops))
        return verts, offsets

    def face_components(self):
        """(F,) uint32: each face record's component (an index into
        `components`), meshtopo.NONE for a record the build rejected."""
        out = np.empty(self.num_faces, np.uint32)
        _lib.mt_py_face_components(self._ptr, address(out) or None, len(out))
        return out

    def __repr__(self):
        if self._handle is None:
            return "Mesh(closed)"
        r = self._report_struct()
        return "Mesh(V=%d, F=%d, E=%d, components=%d, defects=%d)" % (
            r.num_verts, r.num_faces, r.num_edges, r.connected_components, r.num_defects)


def read(path, *, strict=False, threads=0):
    """meshtopo.read(path): Mesh.read(path)."""
    return Mesh.read(path, strict=strict, threads=threads)

