"""meshtopo: mesh topology for robots, from Python.

Builds half-edge meshes from numpy face lists with meshtopo's C library
(through ctypes; no compiler needed), reports every defect, answers
adjacency queries with numpy arrays, talks to a running meshtopod
through the C client library, and decodes meshtopo's LCM messages received
by other means safely (decode_message, through the C decoder).

    import numpy as np, meshtopo
    mesh = meshtopo.Mesh(positions, faces)      # (V, 3) float64, (F, 3) int32
    mesh.report()["genus"], mesh.ring(0).neighbors, mesh.defects
"""
from . import _lib
from .arrays import COMPACT_DEFECT_DTYPE, COMPONENT_DTYPE, DEFECT_DTYPE, FAN_DTYPE
from .client import QUERY_KINDS, Ack, Client, QueryKind, Reply, query_kind
from .errors import STATUS, Error
from .face_list import FaceList, read_face_list
from .mesh import Mesh, Ring, read
from .messages import answer_hash, channel_type, decode_message, message_type

__version__ = "0.1.0"

# "No element" (MT_NONE): a rejected face's component, and the like.
NONE = _lib.NONE


def _defect_kinds():
    kinds = []
    while True:
        key = _lib.mt_defect_key(len(kinds))
        if key is None or key.decode() == "unknown_defect" or len(kinds) > 64:
            return tuple(kinds)
        kinds.append(key.decode())


# Defect kind names by number (the `kind` of Mesh.defects), from the library's table.
DEFECT_KINDS = _defect_kinds()

for _name, _dtype in (("mt_defect", COMPACT_DEFECT_DTYPE), ("mt_defect_record", DEFECT_DTYPE),
                      ("mt_component_info", COMPONENT_DTYPE), ("mt_fan", FAN_DTYPE)):
    _lib.check_layout(_name, _dtype.itemsize)

__all__ = ["Mesh", "FaceList", "Ring", "Client", "Ack", "Reply", "Error", "read",
           "read_face_list", "STATUS", "NONE", "DEFECT_KINDS", "DEFECT_DTYPE",
           "COMPONENT_DTYPE", "FAN_DTYPE", "decode_message", "message_type", "channel_type",
           "answer_hash", "QUERY_KINDS", "QueryKind", "query_kind"]
