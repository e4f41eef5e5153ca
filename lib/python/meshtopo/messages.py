"""Safe decoding of meshtopo's LCM messages received from the network, through
the C library: meshtopo.decode_message(kind, data) runs the bytes through
mt_msgs_decode (msgs/include/meshtopo/msgs.h: every array and string length is
checked against the bytes before anything is allocated) and the rules the C
client applies to what it decodes, then returns the message as a dict. Bytes
that are not a well-formed message of the type raise meshtopo.Error
(MT_ERR_CORRUPT) naming the field and the sizes, e.g.
"reply_t.item_status: 2147483647 values need 2147483647 bytes, 10 left".

    kind = meshtopo.channel_type(channel)         # "reply_t" for R_REPLY, ...
    msg = meshtopo.decode_message(kind, data)    # {"utime": ..., "values": array, ...}

Fields come out as numpy would hold them: integer and real scalars as int and
float, booleans as bool, strings as str, arrays of numbers as numpy arrays of
the field's width (int8 ... int64, float64, bool), byte arrays as bytes, arrays
of strings as lists, nested messages (an ack_t's or reply_t's reports) as
dicts in a list."""
import ctypes

import numpy as np

from . import _lib
from .errors import STATUS, Error, check

# lcm_field_type_t of lcm/lcm_coretypes.h, in its order.
(_INT8, _INT16, _INT32, _INT64, _BYTE, _FLOAT, _DOUBLE, _STRING, _BOOLEAN,
 _USER_TYPE) = range(10)
_DTYPES = {_INT8: np.int8, _INT16: np.int16, _INT32: np.int32, _INT64: np.int64,
           _FLOAT: np.float32, _DOUBLE: np.float64, _BOOLEAN: np.bool_}
_CTYPES = {_INT8: ctypes.c_int8, _INT16: ctypes.c_int16, _INT32: ctypes.c_int32,
           _INT64: ctypes.c_int64, _BYTE: ctypes.c_uint8, _FLOAT: ctypes.c_float,
           _DOUBLE: ctypes.c_double, _BOOLEAN: ctypes.c_int8}


def _type(name):
    """The C type descriptor of a type name ("reply_t", "meshtopo.reply_t")."""
    pointer = _lib.mt_py_msgs_type(name.encode())
    if not pointer:
        raise ValueError("meshtopo: no message type %r" % name)
    return pointer


def _name(type_pointer):
    return _lib.mt_py_msgs_type_name(type_pointer).decode()


def message_type(data):
    """The type name whose 8-byte fingerprint starts `data` ("reply_t",
    "ack_t", ...), or None: what a reassembled answer (reply_part_t pieces)
    holds. Only the fingerprint is read; decode_message checks the rest."""
    data = bytes(data)
    pointer = _lib.mt_msgs_type_of(data, len(data))
    return _name(pointer) if pointer else None


def channel_type(channel, prefix="MESHTOPO_"):
    """The type name `channel` carries (one type per channel): PREFIX +
    SUBMIT, SUBMIT_CHUNK, QUERY, QUERY_PULL, TOPOLOGY, STATUS, or a reply
    channel + _ACK, _REPLY, _PART, _TRANSFER; None for any other channel."""
    pointer = _lib.mt_py_msgs_channel_type(prefix.encode(), channel.encode())
    return _name(pointer) if pointer else None


def answer_hash(data):
    """reply_part_t.answer_hash of the whole encoded answer (mt_msgs_answer_hash:
    64-bit FNV-1a over big-endian 8-byte words), as a signed int64 like the field."""
    data = bytes(data)
    return ctypes.c_int64(_lib.mt_msgs_answer_hash(data, len(data))).value


def decode_message(kind, data):
    """Decodes bytes received on an LCM channel as a dict of the message's
    fields. kind: a type name ("reply_t" or "meshtopo.reply_t"), or None to
    take the type from the fingerprint (message_type). data: bytes-like, the
    whole message. Raises meshtopo.Error (status MT_ERR_CORRUPT) when the
    bytes are not one well-formed message of the type or break its rules:
    wrong fingerprint, a length past the bytes or negative, a string without
    its NUL, bytes left over, reply_t offsets that do not describe its arrays,
    a topology report listing more than it counts, a reply_part_t off the part
    grid, more than MISSING_MAX missing ranges. ValueError for an unknown
    kind."""
    data = bytes(data)
    if kind is None:
        kind = message_type(data)
        if kind is None:
            raise Error(STATUS["MT_ERR_CORRUPT"],
                        "%d bytes: no meshtopo type has their fingerprint" % len(data))
    type_pointer = _type(kind)
    msg = _lib.c_ptr()
    diag = _lib.Diag()
    check(_lib.mt_py_msgs_decode(type_pointer, data, len(data), msg, diag), diag)
    try:
        return _fields(type_pointer, msg.value)
    finally:
        _lib.mt_py_msgs_free(type_pointer, msg.value)


def _scalar(kind, address):
    if kind == _STRING:
        return ctypes.cast(address, ctypes.POINTER(ctypes.c_char_p))[0].decode("utf-8", "replace")
    value = _CTYPES[kind].from_address(address).value
    return bool(value) if kind == _BOOLEAN else value


def _fields(type_pointer, msg):
    out = {}
    for i in range(_lib.mt_py_msgs_num_fields(type_pointer)):
        f = _lib.LcmField()
        if _lib.mt_py_msgs_field(type_pointer, msg, i, f) != 0:
            raise RuntimeError("meshtopo: field %d of %s has no description" % (i, _name(type_pointer)))
        name = f.name.decode()
        if f.num_dim > 1:
            raise NotImplementedError("meshtopo: %s has %d dimensions" % (name, f.num_dim))
        nested = _type(f.typestr.decode()) if f.type == _USER_TYPE else None
        if f.num_dim == 0:
            out[name] = _fields(nested, f.data) if nested else _scalar(f.type, f.data)
            continue
        n = f.dim_size[0]
        # A variable array is a pointer in the struct (data points to it); a fixed one is inline.
        base = ctypes.c_void_p.from_address(f.data).value if f.dim_is_variable[0] else f.data
        if n == 0 or not base:
            out[name] = b"" if f.type == _BYTE else [] if f.type in (_STRING, _USER_TYPE) \
                else np.empty(0, _DTYPES[f.type])
        elif nested:
            size = _lib.mt_py_msgs_struct_size(nested)
            out[name] = [_fields(nested, base + k * size) for k in range(n)]
        elif f.type == _STRING:
            out[name] = [_scalar(_STRING, base + k * ctypes.sizeof(ctypes.c_char_p)) for k in range(n)]
        elif f.type == _BYTE:
            out[name] = ctypes.string_at(base, n)
        else:
            dtype = np.dtype(_DTYPES[f.type])
            out[name] = np.frombuffer(ctypes.string_at(base, n * dtype.itemsize), dtype).copy()
    return out
