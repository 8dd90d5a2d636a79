"""The native module and the helpers every part of the package shares: _ggx_native.so loaded with ctypes, _proto
(which declares one of its functions; each module declares those it calls), the conversion of arguments (real
numbers, float64 arrays, dtypes, choices), _Args (inputs broadcast and laid out for a native loop), the float32
rounding of results, status messages and the float batch API's settings."""

import ctypes
import decimal
import math
import numbers
import operator
import os

import numpy as np

# The native module; the library's own functions are found through it: in libggx, which it links, or in the module
# itself where the library is static.
_lib = ctypes.CDLL(os.path.join(os.path.dirname(os.path.abspath(__file__)), "_ggx_native.so"))

_vp = ctypes.c_void_p
_sz = ctypes.c_size_t
_d = ctypes.c_double
_i = ctypes.c_int


class _In(ctypes.Structure):
    """An input array of the native loops: its address, the step in elements between items (0: broadcast) and
    whether its elements are floats (float32) or doubles."""
    _fields_ = [("p", _vp), ("step", ctypes.c_ssize_t), ("f32", _i)]


_inp = ctypes.POINTER(_In)


def _proto(name, restype, *argtypes):
    f = getattr(_lib, name)
    f.restype = restype
    f.argtypes = list(argtypes)
    return f


#: The version of the libggx the package runs with, "MAJOR.MINOR.PATCH" (ggx_version).
__version__ = _proto("ggx_version", ctypes.c_char_p)().decode()
_status_str = _proto("ggx_status_str", ctypes.c_char_p, _i)

_FN = {}


def _fn(name):
    """The address of a C function of the library, for the native loops (looked up once)."""
    p = _FN.get(name)
    if p is None:
        p = _FN[name] = ctypes.cast(getattr(_lib, name), _vp).value
    return p


def status_message(status):
    """The library's one-line message for a status code (ggx_status_str; "unknown status" for other values)."""
    k = int(status)
    return _status_str(k if -2 ** 31 <= k < 2 ** 31 else -1).decode()


def _check(status):
    if status != 0:
        raise ValueError(status_message(status))


def _real(x, what):
    """A real number for a setup parameter (NaN and infinities pass: the library refuses them with its status)."""
    try:
        if isinstance(x, (numbers.Real, decimal.Decimal)):
            v = float(x)
            if math.isinf(v) and not (isinstance(x, float) or x != x or abs(x) == float("inf")):
                raise OverflowError  # a finite number beyond float64's range
            return v
        a = np.asarray(x)
        if a.shape != () or a.dtype.kind not in "biuf":
            raise TypeError
        return float(a)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{what}: expected a real number, got {x!r}") from None


class _NotAnInteger(TypeError, ValueError):
    """A count given as something other than an integer (a float, a bool, a string): a TypeError, and a ValueError
    as every argument error of the package."""


class _BeyondC(OverflowError, ValueError):
    """An integer beyond the range of the C type that takes it (which would wrap): an OverflowError, and a
    ValueError as every argument error of the package."""


_C_INT = (-2 ** 31, 2 ** 31 - 1)
_C_UINT64 = (0, 2 ** 64 - 1)


def _integer(x, what, lo=None, hi=None, c=_C_INT):
    """A count or other integer argument: a Python or numpy integer (a bool, float, string or other object is a
    TypeError), within the C type c's range (else OverflowError), and within [lo, hi] when given (else
    ValueError)."""
    if isinstance(x, (bool, np.bool_)):
        raise _NotAnInteger(f"{what}: expected an integer, got {x!r}")
    try:
        v = operator.index(x)
    except TypeError:
        raise _NotAnInteger(f"{what}: expected an integer, got {x!r}") from None
    if not c[0] <= v <= c[1]:
        raise _BeyondC(f"{what}: {v} is beyond the range of the C integer that takes it ({c[0]} to {c[1]})")
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        if hi is None:
            raise ValueError(f"{what}: expected an integer of at least {lo}, got {v}")
        if lo is None:
            raise ValueError(f"{what}: expected an integer of at most {hi}, got {v}")
        raise ValueError(f"{what}: expected an integer from {lo} to {hi}, got {v}")
    return v


def _cstring(x, what, path=False):
    """A string argument as the bytes a C function reads up to its NUL: a str (or, for a path, bytes or an
    os.PathLike; encoded as the file system does); an embedded NUL, which would cut it short, is an error."""
    if path:
        try:
            b = os.fsencode(os.fspath(x))
        except TypeError:
            raise ValueError(f"{what}: expected a path, got {x!r}") from None
    elif isinstance(x, str):
        b = x.encode()
    else:
        raise ValueError(f"{what}: expected a string, got {x!r}")
    if b"\0" in b:
        raise ValueError(f"{what}: embedded NUL character in {x!r}")
    return b


def _array(x, what, keep32=False):
    """x as a float64 array of real numbers (keep32: a float32 array stays as it is, for the loops that read floats
    in place): a complex value (which would lose its imaginary part), a string or other non-number, or a masked array
    (whose mask would be ignored) is an error. A float64 or float32 array is checked by its dtype alone (O(1))."""
    if isinstance(x, np.ma.MaskedArray):
        raise ValueError(f"{what}: masked arrays are not supported (use .filled() or select the valid elements)")
    if type(x) is np.ndarray and (x.dtype == np.float64 or (keep32 and x.dtype == np.float32)):
        return x
    try:
        a = np.asarray(x)
        if keep32 and a.dtype == np.float32:
            return a
        if a.dtype.kind == "O":
            if not all(isinstance(e, numbers.Real) for e in a.flat):
                raise TypeError
        elif a.dtype.kind not in "biuf":
            raise TypeError
        d = np.asarray(a, dtype=np.float64)
        if a.dtype.kind in "fO" and a.dtype != np.float64 and a.dtype != np.float32 and a.dtype != np.float16:
            with np.errstate(invalid="ignore"):
                if np.any(np.isinf(d) & ~np.isinf(a.astype(np.longdouble))):
                    raise OverflowError  # a finite long double or Python number beyond float64's range
        return d
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{what}: expected real numbers, got {x!r}") from None


def _dtype(dtype):
    try:
        dt = np.dtype(dtype)
    except TypeError:
        raise ValueError(f"dtype: expected float64 or float32, got {dtype!r}") from None
    if dt not in (np.dtype(np.float64), np.dtype(np.float32)):
        raise ValueError(f"dtype: expected float64 or float32, got {dt}")
    return dt


def _choice(value, choices, what):
    if not isinstance(value, str) or value not in choices:
        raise ValueError(f"{what}: expected one of {', '.join(map(repr, choices))}, got {value!r}")
    return choices[value] if isinstance(choices, dict) else value


# The transport modes of the BSDF, for bsdf and the sampler "bsdf".
_MODES = {"radiance": 0, "importance": 1}


class _Args:
    """Inputs converted, broadcast and laid out for a native loop: .shape (the broadcast leading shape), .n, .ins
    (the _In array), and .arrays (kept alive for the call). Each spec is (value, name, width): width 3 for
    directions, 1 for numbers. float64 and float32 arrays are read in place (the loops read either); other real
    dtypes are converted to float64 once. A single item broadcast and a C-contiguous array of the full shape cost no
    copy; other layouts are copied once."""

    def __init__(self, *specs):
        arrays = []
        for value, what, width in specs:
            a = _array(value, what, keep32=True)
            if width == 3 and (a.ndim == 0 or a.shape[-1] != 3):
                raise ValueError(f"{what}: expected an array of shape (..., 3), got shape {a.shape}")
            arrays.append(a)
        lead = [a.shape[:-1] if w == 3 else a.shape for a, (_, _, w) in zip(arrays, specs)]
        try:
            self.shape = lead[0] if all(x == lead[0] for x in lead) else np.broadcast_shapes(*lead)
        except ValueError:
            names = ", ".join(f"{what} {s}" for (_, what, _), s in zip(specs, lead))
            raise ValueError(f"inputs do not broadcast together: {names}") from None
        self.n = math.prod(self.shape)
        self.ins = (_In * max(len(specs), 1))()
        self.arrays = []
        for k, (a, (_, _, width)) in enumerate(zip(arrays, specs)):
            core = lead[k]
            if math.prod(core) == 1:  # one value for every element: no copy
                a = np.ascontiguousarray(a.reshape(width))
                step = 0
            else:
                if core != self.shape or not a.flags.c_contiguous:
                    full = self.shape + ((3,) if width == 3 else ())
                    a = np.ascontiguousarray(np.broadcast_to(a, full))
                step = width
            self.arrays.append(a)
            self.ins[k].p = a.ctypes.data
            self.ins[k].step = step
            self.ins[k].f32 = a.dtype == np.float32

    def out(self, *tail, dtype=np.float64, out=None, what="out"):
        """A new result array (shape + tail), or out checked to be one: a writeable C-contiguous array of that shape
        and dtype sharing no memory with the inputs (a loop that reuses its arrays allocates nothing)."""
        shape = self.shape + tail
        if out is None:
            return np.empty(shape, dtype=dtype)
        if not (isinstance(out, np.ndarray) and out.dtype == dtype and out.shape == shape and out.flags.c_contiguous
                and out.flags.writeable):
            got = f"{out.dtype} {out.shape}" if isinstance(out, np.ndarray) else repr(type(out).__name__)
            raise ValueError(f"{what}: expected a writeable C-contiguous {np.dtype(dtype)} array of shape {shape}, "
                             f"got {got}")
        if any(np.may_share_memory(out, x) for x in self.arrays):
            raise ValueError(f"{what}: shares memory with an input")
        return out

    def outs(self, out, *specs):
        """The result arrays of specs ((tail, dtype) each): new, or the tuple out checked element by element."""
        if out is None:
            return [self.out(*tail, dtype=dt) for tail, dt in specs]
        if not isinstance(out, (tuple, list)) or len(out) != len(specs):
            raise ValueError(f"out: expected a tuple of {len(specs)} arrays, got {type(out).__name__}")
        res = [self.out(*tail, dtype=dt, out=o, what=f"out[{k}]") for k, ((tail, dt), o) in enumerate(zip(specs, out))]
        if len({id(r) for r in res}) != len(res) or any(np.may_share_memory(x, y) for i, x in enumerate(res)
                                                        for y in res[i + 1:]):
            raise ValueError("out: the arrays share memory")
        return res


# The float32 path (python/src/native.c, ggxpy_f32): one call runs a float batch function of ggx_batch.h over the
# inputs in chunks, with the worker threads set_batch_threads sets.
_f32 = _proto("ggxpy_f32", _i, _i, _i, _vp, _vp, _sz, _inp, _vp, _vp, _vp, _vp, _vp, _i)
_F32 = {"ndf": 0, "g1": 1, "pdf_vndf": 2, "brdf": 3, "normals": 4, "directions": 5, "sample_eval": 6, "pdf_brdf": 7}
_THREADS = [1]


def _run32(op, a, outs, shape, fresnel=None, sampler=0):
    """The float32 path's op on _Args a, writing the arrays outs (None: not wanted) in the op's order."""
    if a.n:
        p = [None if o is None else o.ctypes.data for o in outs] + [None] * (5 - len(outs))
        _check(_f32(_F32[op], sampler, shape._buf, None if fresnel is None else fresnel._buf, a.n, a.ins, *p,
                    _THREADS[0]))


def _ptr(a):
    return a.ctypes.data


def _call(loop, head, specs, dtype=np.float64, out=None):
    """The common wrapper: inputs converted and broadcast, loop(*head, n, inputs, out) run, the result in dtype
    (into out when given, for float64)."""
    a = _Args(*specs)
    if out is not None and _dtype(dtype) != np.float64:
        raise ValueError("out: this function computes in float64; out= is taken with dtype=np.float64")
    res = a.out(out=out)
    if a.n:
        loop(*head, a.n, a.ins, _ptr(res))
    return res if out is not None else _as(_scalar(res), dtype)


def _scalar(out):
    """numpy's convention: a 0-d result is returned as a numpy scalar."""
    return out[()] if out.ndim == 0 else out


def _as(x, dtype):
    """A float64 result (array, numpy scalar, or a tuple of them) in the requested dtype: the rounded result for
    float32, where the batch API has no loop for the function."""
    dt = _dtype(dtype)
    if dt == np.float64:
        return x
    if isinstance(x, tuple):
        items = [_as(e, dtype) if np.asarray(e).dtype == np.float64 else e for e in x]
        return type(x)(*items) if hasattr(x, "_fields") else tuple(items)
    a = np.asarray(x)
    if a.dtype == np.float64:
        big = np.abs(a[np.isfinite(a)])
        if big.size and big.max() > np.finfo(np.float32).max:
            raise ValueError(f"a result ({big.max():.6g}) is beyond float32's range (absolute areas and curvatures "
                             "scale with A): use dtype=np.float64")
    return _scalar(a.astype(np.float32))


# --- The float batch API's settings (include/ggx/ggx_batch.h) ----------------------------------------------------

_batch_get_isa = _proto("ggx_batch_get_isa", _i)
_batch_isa_name = _proto("ggx_batch_isa_name", ctypes.c_char_p, _i)
_batch_set_threads = _proto("ggx_batch_set_threads", _i, _i)


def batch_isa():
    """The instruction set the float batch API uses ('scalar', 'avx2' or 'avx512'; ggx_batch_get_isa)."""
    return _batch_isa_name(_batch_get_isa()).decode()


def set_batch_threads(threads):
    """Worker threads of the float batch API, and of the package's float32 path, for arrays of 65536 elements or
    more (ggx_batch_set_threads; an integer from 1 to 256; the results do not depend on it)."""
    t = _integer(threads, "threads", 1, 256)
    _check(_batch_set_threads(t))
    _THREADS[0] = t
