"""_streams: C FILE * streams over Python memory, for the library's
readers and writers that take one (libc's fmemopen and open_memstream,
declared in _lib.LIBC_CDEF). The library reads and writes the text; this
module only hands it over.
"""

from ._lib import ffi, libc


def read_from(text, read):
    """Calls read(fp) with fp a read-only FILE * over text (str) and
    returns its result; the stream is closed afterwards."""
    buf = ffi.new("char[]", text.encode("utf-8"))
    fp = libc.fmemopen(buf, len(buf) - 1, b"r")
    if fp == ffi.NULL:
        raise MemoryError("cannot open an in-memory stream")
    try:
        return read(fp)
    finally:
        libc.fclose(fp)


def written_by(write):
    """The text that write(fp) writes into a FILE * (open_memstream), as
    (status, text): status is write's return value (a BF_* code)."""
    ptr = ffi.new("char **")
    size = ffi.new("size_t *")
    fp = libc.open_memstream(ptr, size)
    if fp == ffi.NULL:
        raise MemoryError("cannot open an in-memory stream")
    try:
        status = write(fp)
    finally:
        closed = libc.fclose(fp)  # fills ptr and size
        try:
            data = ffi.unpack(ptr[0], size[0]) if ptr[0] != ffi.NULL \
                else b""
        finally:
            libc.free(ptr[0])
    if closed != 0 and status == 0:
        raise MemoryError("an in-memory stream could not be written")
    return status, data.decode("utf-8")
