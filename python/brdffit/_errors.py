"""_errors: the library's error codes as Python exceptions.

Every failing call raises a BrdffitError subclass carrying the library's
code (``code``, ``code_name``) and, for loaders and the study, where and why
(``file``, ``line``, ``reason``); ``str(exc)`` is the library's own
"file:line: problem" text (bf_error_format). Each subclass also derives
from the built-in exception a Python caller expects, so ``except
ValueError`` or ``except OSError`` work too.
"""

from ._lib import ffi, lib, text


class BrdffitError(Exception):
    """A libbrdffit call failed.

    Attributes:
        code: the library's BF_E* code (int).
        code_name: its name, e.g. "BF_EPARSE".
        file: the file the problem is in ("" when none).
        line: its 1-based line (0 when none: the file as a whole).
        reason: the library's short description of the problem.
    """

    def __init__(self, message, code=0, file="", line=0, reason=""):
        super().__init__(message)
        self.code = code
        self.code_name = CODE_NAMES.get(code, "BF_E?")
        self.file = file
        self.line = line
        self.reason = reason or message


class InvalidArgumentError(BrdffitError, ValueError):
    """BF_EINVAL: an argument is invalid (a parameter outside its domain, an
    angle outside the hemisphere, a bad size)."""


class DomainError(BrdffitError, ValueError):
    """BF_EDOM: outside the domain of a model or function (a curve or a
    sample that cannot be normalised)."""


class OutOfMemoryError(BrdffitError, MemoryError):
    """BF_ENOMEM: the library ran out of memory."""


class LoadError(BrdffitError, OSError):
    """BF_EIO: a file could not be opened, read or written."""


class ParseError(BrdffitError, ValueError):
    """BF_EPARSE: a malformed input file; file and line say where."""


class ConvergenceError(BrdffitError, RuntimeError):
    """BF_ENOCONV: an iterative method did not converge."""


class NotFoundError(BrdffitError, LookupError):
    """BF_ENOTFOUND: a named item (model, material, channel) does not
    exist."""


class DomainWarning(RuntimeWarning):
    """A model is undefined at some configurations (BF_EDOM from
    evaluate): the values there are NaN, the others are filled."""


_CLASSES = {1: InvalidArgumentError, 2: DomainError, 3: OutOfMemoryError,
            4: LoadError, 5: ParseError, 6: ConvergenceError,
            7: NotFoundError}
CODE_NAMES = {0: "BF_OK", 1: "BF_EINVAL", 2: "BF_EDOM", 3: "BF_ENOMEM",
              4: "BF_EIO", 5: "BF_EPARSE", 6: "BF_ENOCONV",
              7: "BF_ENOTFOUND"}


def new_error():
    """A zeroed bf_error for a call that reports where it failed."""
    return ffi.new("bf_error *")


def error(code, err=None, context=None):
    """The exception for library code `code`: its text is err's "file:line:
    msg" (bf_error_format) when err (a bf_error) was filled, else
    bf_strerror(code); context, when given, prefixes it ("fit: ...")."""
    cls = _CLASSES.get(code, BrdffitError)
    file, line = "", 0
    reason = message = text(lib.bf_strerror(code))
    if err is not None and (err.msg[0] != b"\0" or err.file[0] != b"\0"):
        buf = ffi.new("char[]", 1024)
        message = text(lib.bf_error_format(err, buf, len(buf)))
        reason, file, line = text(err.msg), text(err.file), int(err.line)
    if context:
        message = "%s: %s" % (context, message)
    return cls(message, code, file, line, reason)


def check(code, err=None, context=None):
    """Raises error(code, err, context) unless code is BF_OK."""
    if code != 0:
        raise error(code, err, context)
