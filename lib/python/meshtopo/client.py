"""meshtopo.Client: submit meshes to a running meshtopod and query them over
LCM, through the C client library (meshtopo/client.h): timeouts, retries,
chunked transfer of large meshes and reassembly of large answers happen
there. Answers come back as numpy arrays in the shapes meshtopo.Mesh gives
for the same query on a local build."""
import collections
import json
import weakref

import numpy as np

from . import _lib
from .arrays import COMPACT_DEFECT_DTYPE, FAN_DTYPE, address
from .errors import STATUS, check
from .face_list import FaceList
from .mesh import Ring, defect_records

# The answer to a submission: the version the daemon built, the content hash
# of the mesh (msgs/mesh_t.lcm), and its topology report as a dict (the
# summary of `meshtopo send --json`'s "report", with "num_defects"), or None.
Ack = collections.namedtuple("Ack", "version content_hash report")

_NOT_FOUND = _lib.STATUS_CODES["NOT_FOUND"]  # an item's status_code_t (msgs/status_code_t.lcm)

# Every query kind (meshtopo.QueryKind), from the C library's table
# (meshtopo/query_kinds.h), in query_t order.
QUERY_KINDS = _lib.QUERY_KINDS
QueryKind = _lib.QueryKind


def query_kind(key):
    """The QueryKind named key: its name ("ring", as `meshtopo query` takes
    it), its query_t constant's name ("VERTEX_RING") or its number. Raises
    ValueError for any other key."""
    for k in QUERY_KINDS:
        if key in (k.name, k.wire_name) or (not isinstance(key, str) and key == k.number):
            return k
    raise ValueError("meshtopo: no query kind %r (kinds: %s)"
                     % (key, ", ".join(k.name for k in QUERY_KINDS)))


class Reply:
    """One query's answer as flat arrays (msgs/reply_t.lcm has what each kind
    puts where): item i has status item_status[i] (0 OK, else a
    status_code_t) and groups item_groups[i] .. item_groups[i + 1]; group g
    has the flag group_boundary[g], values[group_values[g] : group_values[g +
    1]] and values2[group_values2[g] : group_values2[g + 1]]. values and
    values2 are int32 as on the wire; reals float64. `version` is the
    version answered."""

    def __init__(self, pointer):
        sizes = (_lib.c_size * 6)()
        _lib.mt_py_reply_sizes(pointer, sizes)
        items, groups, nv, nv2, nreals, _ = sizes
        self.version = _lib.mt_py_reply_version(pointer)
        self.item_status = np.empty(items, np.int32)
        self.item_groups = np.empty(items + 1, np.uint64)
        self.group_boundary = np.empty(groups, np.bool_)
        self.group_values = np.empty(groups + 1, np.uint64)
        self.values = np.empty(nv, np.int32)
        self.group_values2 = np.empty(groups + 1, np.uint64)
        self.values2 = np.empty(nv2, np.int32)
        self.reals = np.empty(nreals, np.float64)
        arrays = (self.item_status, self.item_groups, self.group_boundary, self.group_values,
                  self.values, self.group_values2, self.values2, self.reals)
        _lib.mt_py_reply_flatten(pointer, *[address(a) or None for a in arrays])

    @property
    def num_items(self):
        return len(self.item_status)

    def groups(self, item):
        """range of the group indices of one item."""
        return range(int(self.item_groups[item]), int(self.item_groups[item + 1]))

    def group(self, g):
        """(values, values2) of group g as uint32 ids (the 32 bits they carry)."""
        v = self.values[self.group_values[g]:self.group_values[g + 1]].view(np.uint32)
        v2 = self.values2[self.group_values2[g]:self.group_values2[g + 1]].view(np.uint32)
        return v, v2


class _ClientHandle:
    def __init__(self, pointer):
        self.pointer = pointer
        self._finalizer = weakref.finalize(self, _lib.mt_client_destroy, pointer)

    def close(self):
        self._finalizer()


def _encode(text):
    return None if text is None else text.encode()


class Client:
    """Client(lcm_url=None, *, prefix=None, timeout_ms=0, retries=0, source=None)

    A connection to meshtopod over LCM (lcm_url None: LCM's default,
    LCM_DEFAULT_URL or udpm multicast). prefix: channel prefix (default
    "MESHTOPO_"); timeout_ms per attempt and retries after it (0: the C
    library's defaults, 1000 ms and 3); source: the node name sent with
    submissions. Calls wait for their answer and raise meshtopo.Error with
    the library's message ("timeout: ...", "NOT_FOUND: ..." with the
    daemon's text) when there is none or it is an error. close() or a with
    block stops the client's thread.
    """

    def __init__(self, lcm_url=None, *, prefix=None, timeout_ms=0, retries=0, source=None):
        pointer = _lib.c_ptr()
        diag = _lib.Diag()
        code = _lib.mt_py_client_create(_encode(lcm_url), _encode(prefix), int(timeout_ms),
                                        int(retries), _encode(source), pointer, diag)
        check(code, diag)
        self._handle = _ClientHandle(pointer.value)

    def close(self):
        if self._handle is not None:
            self._handle.close()
            self._handle = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @property
    def _ptr(self):
        if self._handle is None:
            raise ValueError("meshtopo.Client: the client is closed")
        return self._handle.pointer

    def wait_daemon(self, timeout_ms=0):
        """Waits for a daemon's heartbeat (do this before the first request: a
        fresh LCM socket may miss its first messages). Raises meshtopo.Error
        ("timeout: no heartbeat ...") when none comes."""
        diag = _lib.Diag()
        check(_lib.mt_client_wait_daemon(self._ptr, int(timeout_ms), None, diag), diag)

    def submit(self, mesh_id, positions=None, faces=None, *, counts=None, indices=None,
               num_verts=None, strict=False):
        """Submits a face list (arrays as for meshtopo.FaceList, or a FaceList)
        as a new version of mesh `mesh_id` and waits for the ack. Returns an
        Ack; raises meshtopo.Error when the daemon refuses it (strict and a
        defect, too large, ...) or does not answer."""
        face_list = positions if isinstance(positions, FaceList) else FaceList(
            positions, faces, counts=counts, indices=indices, num_verts=num_verts)
        version, content_hash = _lib.c_i32(), _lib.c_i64()
        report = _lib.c_ptr()
        diag = _lib.Diag()
        code = _lib.mt_py_client_submit(self._ptr, mesh_id.encode(), face_list.struct(),
                                        int(bool(strict)), version, content_hash, report, diag)
        parsed = None
        if report.value:
            try:
                parsed = json.loads(_lib.ctypes.string_at(report.value).decode("utf-8"))
            finally:
                _lib.mt_report_json_free(report.value)
        check(code, diag)
        return Ack(version.value, content_hash.value & 0xFFFFFFFFFFFFFFFF, parsed)

    def query(self, mesh_id, kind, ids=(), version=0):
        """Sends one query for a batch of ids and returns its Reply. kind: a
        kind of meshtopo.QUERY_KINDS by name ("ring", or "VERTEX_RING") or
        number; its `ids` and `pairs` say what ids it takes, its `reply`
        what the Reply holds."""
        if isinstance(kind, str):
            kind = query_kind(kind).number
        ids = np.ascontiguousarray(np.asarray(ids, dtype=np.int64).astype(np.uint32)) \
            if len(ids) else np.empty(0, np.uint32)
        pointer = _lib.c_ptr()
        diag = _lib.Diag()
        code = _lib.mt_py_client_query(self._ptr, _encode(mesh_id), int(version), int(kind),
                                       address(ids) or None, len(ids), pointer, diag)
        try:
            check(code, diag)
            return Reply(pointer.value)
        finally:
            _lib.mt_py_reply_free(pointer.value)

    # ---- the queries, answered as meshtopo.Mesh answers them ------------------

    def rings(self, mesh_id, verts, version=0):
        """One-rings of a batch of vertices: a list of Ring(neighbors, faces,
        fans), as Mesh.ring gives them."""
        reply = self.query(mesh_id, _lib.QUERY_VERTEX_RING, list(verts), version)
        out = []
        for i in range(reply.num_items):
            neighbors, faces, fans = [], [], []
            for g in reply.groups(i):
                v, f = reply.group(g)
                fans.append((sum(map(len, neighbors)), len(v), sum(map(len, faces)), len(f),
                             bool(reply.group_boundary[g])))
                neighbors.append(v)
                faces.append(f)
            out.append(Ring(np.concatenate(neighbors) if neighbors else np.empty(0, np.uint32),
                            np.concatenate(faces) if faces else np.empty(0, np.uint32),
                            np.array(fans, dtype=FAN_DTYPE)))
        return out

    def ring(self, mesh_id, vert, version=0):
        """One vertex's Ring(neighbors, faces, fans), as Mesh.ring."""
        return self.rings(mesh_id, [vert], version)[0]

    def face_neighbors(self, mesh_id, face, version=0):
        """(faces, offsets) across each side of a face, as Mesh.face_neighbors.
        Raises meshtopo.Error (MT_ERR_NOT_FOUND) for a face the build rejected."""
        reply = self.query(mesh_id, _lib.QUERY_FACE_NEIGHBORS, [face], version)
        _check_item(reply, 0, "face %d" % face)
        faces = [reply.group(g)[0] for g in reply.groups(0)]
        offsets = np.zeros(len(faces) + 1, np.uint32)
        offsets[1:] = np.cumsum([len(f) for f in faces])
        return (np.concatenate(faces) if faces else np.empty(0, np.uint32)), offsets

    def edge_faces(self, mesh_id, a, b, version=0):
        """(n,) uint32: the faces having {a, b} as a side, ascending; empty
        when none has (as Mesh.edge_faces)."""
        reply = self.query(mesh_id, _lib.QUERY_EDGE_FACES, [a, b], version)
        if reply.item_status[0] == _NOT_FOUND:
            return np.empty(0, np.uint32)
        return np.concatenate([reply.group(g)[0] for g in reply.groups(0)])

    def boundary_loops(self, mesh_id, version=0):
        """(verts, offsets): the boundary loops, as Mesh.boundary_loops."""
        reply = self.query(mesh_id, _lib.QUERY_BOUNDARY_LOOPS, (), version)
        loops = [reply.group(g)[0] for i in range(reply.num_items) for g in reply.groups(i)]
        offsets = np.zeros(len(loops) + 1, np.uint32)
        offsets[1:] = np.cumsum([len(v) for v in loops])
        return (np.concatenate(loops) if loops else np.empty(0, np.uint32)), offsets

    def face_components(self, mesh_id, version=0):
        """(F,) uint32: every face record's component, meshtopo.NONE for a
        rejected record (as Mesh.face_components)."""
        reply = self.query(mesh_id, _lib.QUERY_COMPONENTS, (), version)
        out = np.full(reply.num_items, _lib.NONE, np.uint32)
        for i in range(reply.num_items):
            if reply.item_status[i] == 0:
                out[i] = reply.group(reply.groups(i)[0])[0][0]
        return out

    def defects(self, mesh_id, version=0):
        """The defects the daemon lists, as DEFECT_DTYPE records (as
        Mesh.defects; the daemon may list fewer than it found)."""
        reply = self.query(mesh_id, _lib.QUERY_DEFECTS, (), version)
        rows = []
        for kind in range(reply.num_items):
            for g in reply.groups(kind):
                abc = reply.group(g)[0].reshape(-1, 3)  # the report's a, b, c (uint32)
                rows.extend((kind, a, b, c) for a, b, c in abc.tolist())
        compact = np.array(rows, dtype=COMPACT_DEFECT_DTYPE)
        return defect_records(address(compact), len(compact))

    def list(self, mesh_id=None):
        """The mesh versions the daemon holds (of one id, or all): a list of
        dicts with mesh_id, version, source, utime, num_verts, num_faces,
        num_defects and content_hash."""
        pointer = _lib.c_ptr()
        diag = _lib.Diag()
        code = _lib.mt_py_client_query(self._ptr, _encode(mesh_id or ""), 0,
                                       _lib.QUERY_LIST_MESHES, None, 0, pointer, diag)
        try:
            check(code, diag)
            sizes = (_lib.c_size * 6)()
            _lib.mt_py_reply_sizes(pointer.value, sizes)
            out = []
            for i in range(sizes[5]):
                mid, src = _lib.c_char_p(), _lib.c_char_p()
                ver, nv, nf = _lib.c_i32(), _lib.c_i32(), _lib.c_i32()
                utime, nd, chash = _lib.c_i64(), _lib.c_i64(), _lib.c_i64()
                _lib.mt_py_reply_listed(pointer.value, i, mid, src, ver, utime, nv, nf, nd, chash)
                out.append({"mesh_id": mid.value.decode(), "version": ver.value,
                            "source": src.value.decode(), "utime": utime.value,
                            "num_verts": nv.value, "num_faces": nf.value,
                            "num_defects": nd.value,
                            "content_hash": chash.value & 0xFFFFFFFFFFFFFFFF})
            return out
        finally:
            _lib.mt_py_reply_free(pointer.value)


def _check_item(reply, item, what):
    status = int(reply.item_status[item])
    if status == _NOT_FOUND:
        check(STATUS["MT_ERR_NOT_FOUND"], context=what)
    elif status != 0:
        check(STATUS["MT_ERR_INVALID_ARG"], context="%s: item status %d" % (what, status))
