"""meshtopo.Error: the one exception the library's failures raise, carrying the
status name of meshtopo/status.h ("MT_ERR_INVALID_ARG") and the library's own
message (its mt_diag text, or mt_strerror's when a call has no diagnostics)."""
from . import _lib

def _status_table():
    names = {}
    for code in range(256):
        name = _lib.mt_py_status_name(code).decode()
        if name == "MT_UNKNOWN_STATUS":
            break
        names[name] = code
    return names


# Status name -> code, from the library's status table ({"MT_OK": 0, ...}).
STATUS = _status_table()
MT_OK = STATUS["MT_OK"]


class Error(Exception):
    """A meshtopo call failed. `status` is the status name, `code` its number,
    `message` the library's text."""

    def __init__(self, code, message):
        self.code = int(code)
        self.status = _lib.mt_py_status_name(self.code).decode()
        self.message = message
        super().__init__("%s: %s" % (self.status, message))


def strerror(code):
    return _lib.mt_strerror(code).decode()


def diag_message(code, diag):
    """The diag's message, or the status text when the call left none."""
    text = diag.message.decode("utf-8", "replace")
    return text if text else strerror(code)


def check(code, diag=None, context=None):
    """Raises Error unless code is MT_OK."""
    if code == MT_OK:
        return
    message = diag_message(code, diag) if diag is not None else strerror(code)
    if context:
        message = "%s: %s" % (context, message)
    raise Error(code, message)
