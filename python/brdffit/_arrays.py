"""_arrays: checking the arrays handed to the library.

Every array is checked before its memory reaches C: a real dtype (else
TypeError naming the argument), the expected shape (else ValueError with
the shapes), and C-contiguous float64 (a copy is made when the caller's
array is not). Nothing the caller passes can make the library read outside
an array.
"""

import numpy as np

from ._lib import ffi


def real(name, x):
    """x as a C-contiguous float64 array (no copy when it already is one).
    Accepts anything numpy turns into integers or floats; raises TypeError
    for complex, boolean, object or text data."""
    try:
        a = np.asarray(x)
    except Exception as exc:  # ragged lists and the like
        raise TypeError("%s: not an array of numbers (%s)" % (name, exc))
    if a.dtype.kind not in "iuf":
        raise TypeError("%s: expected real numbers, got dtype %s"
                        % (name, a.dtype))
    return np.require(a, np.float64, "C")  # keeps 0-d arrays 0-d


def matrix(name, x, cols):
    """x as an (n, cols) float64 array with n >= 1; a 1-D x of length cols
    is one row. Raises ValueError for any other shape."""
    a = real(name, x)
    if a.ndim == 1 and a.shape[0] == cols:
        a = a.reshape(1, cols)
    if a.ndim != 2 or a.shape[1] != cols or a.shape[0] == 0:
        raise ValueError("%s: expected shape (n, %d) with n >= 1, got %s"
                         % (name, cols, a.shape))
    return a


def doubles(a):
    """A `double *` to the float64 C-contiguous array a (kept alive by the
    returned cdata)."""
    assert a.dtype == np.float64 and a.flags.c_contiguous
    return ffi.from_buffer("double[]", a)


def copy_doubles(ptr, shape):
    """A read-only numpy copy of shape float64 values at ptr."""
    n = int(np.prod(shape))
    out = np.frombuffer(ffi.buffer(ptr, 8 * n), dtype=np.float64).copy()
    out = out.reshape(shape)
    out.flags.writeable = False
    return out
