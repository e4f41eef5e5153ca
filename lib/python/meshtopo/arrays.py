"""numpy arrays in and out of the C library.

In: face lists are handed to the library as they are when their layout allows
(no copy): positions C-contiguous float64 of shape (V, 3); indices and counts
C-contiguous uint32 or int32 (int32 is read as the same 32 bits: a negative
index is out of range, as the library reports it). Anything else that holds
numbers of the right kind is converted (a copy): other integer types when
every value fits 32 bits, float32 and integer positions, non-contiguous or
byte-swapped arrays. Anything else raises TypeError or ValueError.

Out: arrays that live in the library's memory (a mesh's positions, its
report's components, a face list read from a file) are read-only numpy views
that keep their owner alive; a mesh's defect records are made once, read-only;
query answers are new arrays.
"""
import numpy as np

_U32_MAX = 0xFFFFFFFF

# Records of meshtopo/defect_record.h, report.h and query.h, laid out as the C
# compiler does (checked against the C sizes when the package loads).

# A defect record, the one defect schema of meshtopo's outputs (README.md
# "Defect records"; the archive's /meshtopo/report/defects has these members
# too): kind (a number, DEFECT_KINDS names it), vertices, faces, edge (two ids
# each), face_count, index (int64), position, face_size, distinct_vertices,
# fans, on_nonmanifold_edge (0 or 1), axis. A field that does not apply to the
# kind, and the unused end of vertices and faces, holds NONE (4294967295).
DEFECT_DTYPE = np.dtype([("kind", np.uint32), ("vertices", np.uint32, (2,)),
                         ("faces", np.uint32, (2,)), ("edge", np.uint32, (2,)),
                         ("face_count", np.uint32), ("index", np.int64),
                         ("position", np.uint32), ("face_size", np.uint32),
                         ("distinct_vertices", np.uint32), ("fans", np.uint32),
                         ("on_nonmanifold_edge", np.uint32), ("axis", np.uint32)], align=True)
# The report's compact defect (mt_defect: kind, a, b, c, meanings per kind),
# as the library lists it and meshtopod's answers carry it; the package turns
# it into DEFECT_DTYPE records with the library's mt_defect_to_records.
COMPACT_DEFECT_DTYPE = np.dtype([("kind", np.uint32), ("a", np.uint32), ("b", np.uint32),
                                 ("c", np.uint32)], align=True)
COMPONENT_DTYPE = np.dtype([("min_face", np.uint32), ("faces", np.uint32),
                            ("vertices", np.uint32), ("edges", np.uint64),
                            ("euler_characteristic", np.int64), ("boundary_edges", np.uint64),
                            ("boundary_loops", np.uint32), ("closed", np.bool_),
                            ("manifold", np.bool_), ("orientable", np.bool_),
                            ("genus", np.int32), ("genus_with_boundary", np.int32)], align=True)
FAN_DTYPE = np.dtype([("neighbor_begin", np.uint32), ("neighbor_count", np.uint32),
                      ("face_begin", np.uint32), ("face_count", np.uint32),
                      ("boundary", np.bool_)], align=True)


class _Memory:
    """Library memory seen by numpy: its array interface, and the object whose
    lifetime the memory follows."""

    def __init__(self, owner, address, nbytes):
        self.owner = owner
        self.__array_interface__ = {"version": 3, "shape": (nbytes,), "typestr": "|u1",
                                    "data": (address, True)}


def view(owner, address, count, dtype, shape=None):
    """A read-only array of `count` elements of dtype at `address`, in memory
    that `owner` keeps alive (the array keeps `owner` alive in turn). An
    empty array when count is 0 (the library may hold no memory then)."""
    dtype = np.dtype(dtype)
    shape = (count,) if shape is None else shape
    if count == 0 or not address:
        out = np.empty(shape, dtype)
    else:
        out = np.asarray(_Memory(owner, address, count * dtype.itemsize)).view(dtype)
        out = out.reshape(shape)
    out.flags.writeable = False
    return out


def address(array):
    """The address of an array's first element (0 when it is empty)."""
    return array.ctypes.data if array.size else 0


def _integer_array(name, values):
    """values as a C-contiguous uint32 array, without a copy when they are
    already C-contiguous native uint32 or int32."""
    array = np.asarray(values)
    if array.dtype.kind not in "iu":
        if array.size == 0 and array.dtype.kind == "f":
            array = array.astype(np.uint32)  # np.asarray([]) is float64
        else:
            raise TypeError("%s: expected integers, got an array of %s" % (name, array.dtype))
    native = array.dtype.isnative
    if array.dtype.itemsize == 4 and native and array.flags.c_contiguous:
        return array if array.dtype == np.uint32 else array.view(np.uint32)
    if array.size:
        lo, hi = int(array.min()), int(array.max())
        if lo < -(1 << 31) or hi > _U32_MAX:
            bad = lo if lo < -(1 << 31) else hi
            raise ValueError("%s: %d does not fit 32 bits (meshtopo ids are uint32; "
                             "a negative index must fit int32)" % (name, bad))
    # Negative values become their two's complement, as int32 ones are read.
    return np.ascontiguousarray(array.astype(np.int64).astype(np.uint32))


def as_positions(positions):
    """positions as a C-contiguous (V, 3) float64 array (no copy when it is one)."""
    array = np.asarray(positions)
    if array.dtype.kind not in "fiu":
        raise TypeError("positions: expected real numbers, got an array of %s" % array.dtype)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError("positions: expected shape (V, 3), got %s" % (array.shape,))
    if array.shape[0] > _U32_MAX:
        raise ValueError("positions: %d vertices exceed meshtopo's limit" % array.shape[0])
    if array.dtype == np.float64 and array.dtype.isnative and array.flags.c_contiguous:
        return array
    return np.ascontiguousarray(array, dtype=np.float64)


_face_sizes = {}  # face size -> the longest read-only array of it made so far


def uniform_counts(size, num_faces):
    """A read-only uint32 array of num_faces entries all equal to size (a view
    of a shared array, made once per size and grown as needed)."""
    shared = _face_sizes.get(size)
    if shared is None or len(shared) < num_faces:
        shared = np.full(max(num_faces, 1024), size, dtype=np.uint32)
        shared.flags.writeable = False
        _face_sizes[size] = shared
    return shared[:num_faces]


def as_faces(faces):
    """(counts, indices) of an (F, k) array of faces with k corners each."""
    array = np.asarray(faces)
    if array.ndim != 2:
        raise ValueError("faces: expected shape (F, k), got %s (use counts= and indices= "
                         "for faces of mixed sizes)" % (array.shape,))
    if array.shape[0] > _U32_MAX:
        raise ValueError("faces: %d faces exceed meshtopo's limit" % array.shape[0])
    indices = _integer_array("faces", array)
    return uniform_counts(array.shape[1], array.shape[0]), indices.reshape(-1)


def as_counts_indices(counts, indices):
    """counts and indices as 1-D uint32 arrays (no copy when they are C-contiguous
    uint32 or int32)."""
    counts = _integer_array("counts", counts)
    indices = _integer_array("indices", indices)
    if counts.ndim != 1 or indices.ndim != 1:
        raise ValueError("counts and indices: expected 1-D arrays, got shapes %s and %s"
                         % (counts.shape, indices.shape))
    if counts.shape[0] > _U32_MAX:
        raise ValueError("counts: %d faces exceed meshtopo's limit" % counts.shape[0])
    return counts, indices
