"""Loading libmeshtopo-python.so with ctypes and declaring the C functions and
structs the package calls (meshtopo/core.h, io.h, report_json.h, client.h,
msgs.h, query_kinds.h and lib/python/src/python_api.h). Nothing is compiled at
import time. The query kinds and status codes are read from the library's
tables (meshtopo/query_kinds.h, meshtopo/protocol.h), never written here.

The shared object is looked up, in order: the path in the environment variable
MESHTOPO_PYTHON_LIBRARY (a build tree's lib/python/libmeshtopo-python.so);
next to this file (an installed package); the dynamic loader's search path.
"""
import collections
import ctypes
import os

LIBRARY_NAME = "libmeshtopo-python.so"
LIBRARY_ENV = "MESHTOPO_PYTHON_LIBRARY"

# The sentinel of "no element" (MT_NONE in meshtopo/status.h).
NONE = 0xFFFFFFFF

def _find_library():
    path = os.environ.get(LIBRARY_ENV)
    if path:
        return path
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), LIBRARY_NAME)
    if os.path.exists(here):
        return here
    return LIBRARY_NAME


def _load():
    path = _find_library()
    try:
        return ctypes.CDLL(path)
    except OSError as e:
        raise ImportError(
            "meshtopo: cannot load %s (%s). Build it (cmake --build BUILD --target "
            "meshtopo_python) and set %s to its path, or install meshtopo "
            "(cmake --install BUILD)." % (path, e, LIBRARY_ENV)) from e


lib = _load()

c_u32 = ctypes.c_uint32
c_i32 = ctypes.c_int32
c_u64 = ctypes.c_uint64
c_i64 = ctypes.c_int64
c_size = ctypes.c_size_t
c_ptr = ctypes.c_void_p
c_bool = ctypes.c_bool
c_int = ctypes.c_int
c_char_p = ctypes.c_char_p


class Diag(ctypes.Structure):
    _fields_ = [("status", c_int), ("message", ctypes.c_char * 512), ("line", c_u64),
                ("byte_offset", c_u64), ("element", c_u32)]


class FaceListStruct(ctypes.Structure):
    _fields_ = [("num_verts", c_u32), ("num_faces", c_u32), ("num_indices", c_u64),
                ("positions", c_ptr), ("face_sizes", c_ptr), ("face_indices", c_ptr)]


class BuildOptions(ctypes.Structure):
    _fields_ = [("strict", c_bool), ("threads", c_u32), ("workspace", c_ptr)]


class RingStruct(ctypes.Structure):
    _fields_ = [("neighbors", c_ptr), ("neighbors_capacity", c_size), ("faces", c_ptr),
                ("faces_capacity", c_size), ("fans", c_ptr), ("fans_capacity", c_size),
                ("num_neighbors", c_size), ("num_faces", c_size), ("num_fans", c_size)]


class MeshView(ctypes.Structure):
    _fields_ = [("num_verts", c_u32), ("num_verts_internal", c_u32), ("num_faces", c_u32),
                ("num_half_edges", c_u32), ("he_head", c_ptr), ("he_next", c_ptr),
                ("he_face", c_ptr), ("face_he", c_ptr), ("vert_he", c_ptr),
                ("positions", c_ptr)]


class ReportStruct(ctypes.Structure):
    _fields_ = [
        ("num_verts", c_u32), ("num_faces", c_u32), ("num_faces_valid", c_u32),
        ("num_edges", c_u64), ("num_half_edges", c_u64),
        ("boundary_edges", c_u64), ("boundary_loops", c_u32),
        ("boundary_loops_ambiguous", c_bool), ("boundary_loop_lengths", c_ptr),
        ("nonmanifold_edges", c_u64), ("inconsistent_orientation_edges", c_u64),
        ("duplicate_directed_edges", c_u64), ("nonmanifold_vertices", c_u32),
        ("bowtie_vertices", c_u32), ("isolated_vertices", c_u32),
        ("unreferenced_vertices", c_u32), ("degenerate_faces", c_u32),
        ("duplicate_faces", c_u32), ("out_of_range_indices", c_u64),
        ("faces_with_out_of_range_indices", c_u32), ("nonfinite_vertices", c_u32),
        ("connected_components", c_u32), ("vertex_connected_components", c_u32),
        ("euler_characteristic", c_i64), ("closed", c_bool), ("manifold", c_bool),
        ("orientable", c_bool), ("consistently_oriented", c_bool), ("genus", c_i32),
        ("components", c_ptr), ("num_face_size_bins", c_size), ("face_size_histogram", c_ptr),
        ("num_edge_use_bins", c_size), ("edge_use_histogram", c_ptr),
        ("num_defects", c_size), ("defects", c_ptr)]


class LcmField(ctypes.Structure):
    """lcm_field_t (lcm/lcm_coretypes.h): one field of a generated message
    struct, as lcm-gen's typeinfo describes it."""
    _fields_ = [("name", c_char_p), ("type", c_int), ("typestr", c_char_p), ("num_dim", c_int),
                ("dim_size", c_i32 * 50), ("dim_is_variable", ctypes.c_int8 * 50),
                ("data", c_ptr)]


class QueryKindStruct(ctypes.Structure):
    """mt_msgs_query_kind (meshtopo/query_kinds.h): one row of the query-kind table."""
    _fields_ = [("kind", c_i32), ("wire_name", c_char_p), ("name", c_char_p), ("ids", c_int),
                ("pairs", c_bool), ("space", c_int), ("of", c_char_p), ("reply", c_int),
                ("reals_per_item", c_i32), ("geometry", c_bool), ("on_worker", c_bool)]


def _declare(name, restype, *argtypes):
    fn = getattr(lib, name)
    fn.restype = restype
    fn.argtypes = list(argtypes)
    return fn


P = ctypes.POINTER
mt_strerror = _declare("mt_strerror", c_char_p, c_int)
mt_py_status_name = _declare("mt_py_status_name", c_char_p, c_int)
mt_py_sizeof = _declare("mt_py_sizeof", c_size, c_char_p)
mt_defect_key = _declare("mt_defect_key", c_char_p, c_int)
mt_defect_to_records = _declare("mt_defect_to_records", None, c_ptr, c_size, c_ptr)

mt_mesh_build = _declare("mt_mesh_build", c_int, P(FaceListStruct), P(BuildOptions), P(c_ptr),
                         P(Diag))
mt_mesh_build_taking_positions = _declare("mt_mesh_build_taking_positions", c_int,
                                          P(FaceListStruct), P(BuildOptions), P(c_ptr), P(Diag))
mt_mesh_destroy = _declare("mt_mesh_destroy", None, c_ptr)
mt_mesh_report = _declare("mt_mesh_report", P(ReportStruct), c_ptr)
mt_mesh_num_verts = _declare("mt_mesh_num_verts", c_u32, c_ptr)
mt_mesh_num_faces = _declare("mt_mesh_num_faces", c_u32, c_ptr)
mt_mesh_get_view = _declare("mt_mesh_get_view", None, c_ptr, P(MeshView))
mt_mesh_validate = _declare("mt_mesh_validate", c_int, c_ptr, P(Diag))
mt_face_list_free = _declare("mt_face_list_free", None, P(FaceListStruct))
mt_read_file = _declare("mt_read_file", c_int, c_char_p, c_int, P(FaceListStruct), P(Diag))

mt_vert_ring = _declare("mt_vert_ring", c_int, c_ptr, c_u32, P(RingStruct))
mt_face_verts = _declare("mt_face_verts", c_int, c_ptr, c_u32, c_ptr, c_size, P(c_size))
mt_face_neighbors = _declare("mt_face_neighbors", c_int, c_ptr, c_u32, c_ptr, c_size, c_ptr,
                             c_size, P(c_size), P(c_size))
mt_edge_faces = _declare("mt_edge_faces", c_int, c_ptr, c_u32, c_u32, c_ptr, c_size, P(c_size))
mt_boundary_loops = _declare("mt_boundary_loops", c_int, c_ptr, c_ptr, c_size, c_ptr, c_size,
                             P(c_size), P(c_size))
mt_py_face_components = _declare("mt_py_face_components", c_size, c_ptr, c_ptr, c_size)

mt_report_json_inspect = _declare("mt_report_json_inspect", c_int, c_ptr, c_char_p, P(c_ptr),
                                  P(c_size), P(Diag))
mt_report_json_free = _declare("mt_report_json_free", None, c_ptr)

mt_py_client_create = _declare("mt_py_client_create", c_int, c_char_p, c_char_p, c_int, c_int,
                               c_char_p, P(c_ptr), P(Diag))
mt_client_destroy = _declare("mt_client_destroy", None, c_ptr)
mt_client_wait_daemon = _declare("mt_client_wait_daemon", c_int, c_ptr, c_int, c_ptr, P(Diag))
mt_py_client_submit = _declare("mt_py_client_submit", c_int, c_ptr, c_char_p,
                               P(FaceListStruct), c_int, P(c_i32), P(c_i64), P(c_ptr), P(Diag))
mt_py_client_query = _declare("mt_py_client_query", c_int, c_ptr, c_char_p, c_i32, c_i32, c_ptr,
                              c_size, P(c_ptr), P(Diag))
mt_py_reply_free = _declare("mt_py_reply_free", None, c_ptr)
mt_py_reply_version = _declare("mt_py_reply_version", c_i32, c_ptr)
mt_py_reply_sizes = _declare("mt_py_reply_sizes", None, c_ptr, c_ptr)
mt_py_reply_flatten = _declare("mt_py_reply_flatten", None, c_ptr, c_ptr, c_ptr, c_ptr, c_ptr,
                               c_ptr, c_ptr, c_ptr, c_ptr)
mt_py_reply_listed = _declare("mt_py_reply_listed", None, c_ptr, c_size, P(c_char_p),
                              P(c_char_p), P(c_i32), P(c_i64), P(c_i32), P(c_i32), P(c_i64),
                              P(c_i64))

# Messages (python_msgs.c, meshtopo/msgs.h, meshtopo/answer_hash.h); buffers as bytes.
mt_msgs_type_of = _declare("mt_msgs_type_of", c_ptr, c_char_p, c_size)
mt_msgs_answer_hash = _declare("mt_msgs_answer_hash", c_u64, c_char_p, c_size)
mt_py_msgs_type = _declare("mt_py_msgs_type", c_ptr, c_char_p)
mt_py_msgs_type_name = _declare("mt_py_msgs_type_name", c_char_p, c_ptr)
mt_py_msgs_struct_size = _declare("mt_py_msgs_struct_size", c_size, c_ptr)
mt_py_msgs_num_fields = _declare("mt_py_msgs_num_fields", c_int, c_ptr)
mt_py_msgs_field = _declare("mt_py_msgs_field", c_int, c_ptr, c_ptr, c_int, P(LcmField))
mt_py_msgs_channel_type = _declare("mt_py_msgs_channel_type", c_ptr, c_char_p, c_char_p)
mt_py_msgs_decode = _declare("mt_py_msgs_decode", c_int, c_ptr, c_char_p, c_size, P(c_ptr),
                             P(Diag))
mt_py_msgs_free = _declare("mt_py_msgs_free", None, c_ptr, c_ptr)

# The protocol's tables (meshtopo/query_kinds.h, meshtopo/protocol.h).
mt_msgs_query_kind_count = _declare("mt_msgs_query_kind_count", c_size)
mt_msgs_query_kind_at = _declare("mt_msgs_query_kind_at", P(QueryKindStruct), c_size)
mt_msgs_ids_rule_name = _declare("mt_msgs_ids_rule_name", c_char_p, c_int)
mt_msgs_id_space_name = _declare("mt_msgs_id_space_name", c_char_p, c_int)
mt_msgs_reply_shape_name = _declare("mt_msgs_reply_shape_name", c_char_p, c_int)
mt_msgs_code_name = _declare("mt_msgs_code_name", c_char_p, c_i32)

# One query kind, as the C table has it: number (query_t's constant),
# wire_name ("VERTEX_RING"), name ("ring", as `meshtopo query` takes it), ids
# ("needed", "optional", "none"), pairs (ids are vertex pairs naming edges),
# space (what bounds an id: "vertex", "face", "defect_kind", "none"), of (what
# an item names), reply ("per_id", "per_loop", "mesh", "report", "list"),
# reals_per_item (None: it varies), geometry (needs positions), on_worker.
QueryKind = collections.namedtuple(
    "QueryKind", "number wire_name name ids pairs space of reply reals_per_item geometry "
    "on_worker")


def _query_kinds():
    kinds = []
    for i in range(mt_msgs_query_kind_count()):
        k = mt_msgs_query_kind_at(i).contents
        kinds.append(QueryKind(
            k.kind, k.wire_name.decode(), k.name.decode(),
            mt_msgs_ids_rule_name(k.ids).decode(), bool(k.pairs),
            mt_msgs_id_space_name(k.space).decode(), k.of.decode(),
            mt_msgs_reply_shape_name(k.reply).decode(),
            None if k.reals_per_item < 0 else k.reals_per_item, bool(k.geometry),
            bool(k.on_worker)))
    return tuple(kinds)


def _status_codes():
    codes = {}
    code = 0
    while True:
        name = mt_msgs_code_name(code).decode()
        if name == "UNKNOWN_CODE" or code > 1024:
            return codes
        codes[name] = code
        code += 1


def check_layout(name, size):
    """Raises ImportError when a mirrored struct's size differs from the C one."""
    expected = mt_py_sizeof(name.encode())
    if expected != size:
        raise ImportError("meshtopo: %s is %d bytes in %s but %d in the package: the shared "
                          "object and the package come from different versions"
                          % (name, expected, LIBRARY_NAME, size))


for _name, _struct in (("mt_diag", Diag), ("mt_face_list", FaceListStruct),
                       ("mt_build_options", BuildOptions), ("mt_ring", RingStruct),
                       ("mt_mesh_view", MeshView), ("mt_report", ReportStruct),
                       ("lcm_field_t", LcmField), ("mt_msgs_query_kind", QueryKindStruct)):
    check_layout(_name, ctypes.sizeof(_struct))

# Every query kind of the C table, in query_t order, and QUERY_<WIRE_NAME> =
# its number for each (QUERY_VERTEX_RING, ...).
QUERY_KINDS = _query_kinds()
for _kind in QUERY_KINDS:
    globals()["QUERY_" + _kind.wire_name] = _kind.number

# status_code_t values by name ("OK": 0, "NOT_FOUND": ...), from the C table.
STATUS_CODES = _status_codes()
