"""meshtopo.FaceList: a mesh as the library takes it (mt_face_list): positions,
face sizes (counts) and the flat vertex indices, the USD-style
face_vertex_counts / face_vertex_indices. Its arrays are exactly what the
library reads: the caller's own arrays when their layout allows (see
meshtopo.arrays), or views over the library's memory for a file read with
meshtopo.read_face_list."""
import os
import weakref

import numpy as np

from . import _lib
from .arrays import address, as_counts_indices, as_faces, as_positions, view
from .errors import check


class FaceList:
    """FaceList(positions, faces=None, *, counts=None, indices=None, num_verts=None)

    positions: (V, 3) float64 array, or None for a mesh without geometry
        (then num_verts gives the vertex count).
    faces: (F, k) integer array, every face with k corners; or else
    counts: (F,) face sizes and indices: (sum(counts),) vertex ids.

    Not copied when C-contiguous with these dtypes: positions float64,
    faces / counts / indices uint32 or int32 (see meshtopo.arrays for what is
    converted). Attributes: positions ((V, 3) float64 or None), counts ((F,)
    uint32), indices ((N,) uint32), num_verts.
    """

    def __init__(self, positions, faces=None, *, counts=None, indices=None, num_verts=None):
        if faces is not None and (counts is not None or indices is not None):
            raise TypeError("FaceList: give faces, or counts and indices, not both")
        if faces is None and (counts is None or indices is None):
            raise TypeError("FaceList: give faces (F, k), or counts and indices")
        self.positions = None if positions is None else as_positions(positions)
        if faces is not None:
            self.counts, self.indices = as_faces(faces)
        else:
            self.counts, self.indices = as_counts_indices(counts, indices)
        if self.positions is not None:
            if num_verts is not None and int(num_verts) != len(self.positions):
                raise ValueError("num_verts %d differs from the %d positions"
                                 % (num_verts, len(self.positions)))
            self.num_verts = len(self.positions)
        elif num_verts is None:
            raise TypeError("FaceList: without positions, give num_verts")
        else:
            self.num_verts = int(num_verts)
            if not 0 <= self.num_verts <= 0xFFFFFFFF:
                raise ValueError("num_verts %d is out of meshtopo's range" % self.num_verts)
        self._owner = None  # library memory holding the arrays (read_face_list)

    @property
    def num_faces(self):
        return len(self.counts)

    def struct(self):
        """The mt_face_list pointing at this list's arrays (kept alive by self)."""
        s = _lib.FaceListStruct()
        s.num_verts = self.num_verts
        s.num_faces = len(self.counts)
        s.num_indices = len(self.indices)
        s.positions = address(self.positions) if self.positions is not None else None
        s.face_sizes = address(self.counts) or None
        s.face_indices = address(self.indices) or None
        return s

    def __repr__(self):
        return "FaceList(num_verts=%d, num_faces=%d, num_indices=%d%s)" % (
            self.num_verts, len(self.counts), len(self.indices),
            "" if self.positions is not None else ", no positions")


class _ReadList:
    """A face list the library allocated (mt_read_file); freed with it."""

    def __init__(self, struct):
        self.struct = struct
        self._finalizer = weakref.finalize(self, _lib.mt_face_list_free, struct)


def read_face_list(path):
    """Reads an OFF, OBJ, PLY or STL file (gzip-compressed too; format from the
    content) into a FaceList whose arrays are read-only views over the memory
    the library read it into (no copy). Raises meshtopo.Error with the
    library's message (file, line, problem) when it cannot be read."""
    diag = _lib.Diag()
    struct = _lib.FaceListStruct()
    code = _lib.mt_read_file(os.fsencode(path), 0, struct, diag)
    check(code, diag)
    owner = _ReadList(struct)
    fl = FaceList.__new__(FaceList)
    fl.num_verts = struct.num_verts
    fl.positions = (view(owner, struct.positions, 3 * struct.num_verts, np.float64,
                         (struct.num_verts, 3)) if struct.positions else None)
    fl.counts = view(owner, struct.face_sizes, struct.num_faces, np.uint32)
    fl.indices = view(owner, struct.face_indices, struct.num_indices, np.uint32)
    fl._owner = owner
    return fl
