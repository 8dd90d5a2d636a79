"""SGGX microflakes (ggx_sggx.h): Flakes, the distribution of a symmetric positive definite matrix S or of a shape's
own ellipsoid (S = A^T A), and its functions over arrays of directions: D, the projected area sigma, the VNDF
sampler and the specular and diffuse phase functions with their samplers. Each is the C function per element
(float64; dtype=np.float32 rounds the result)."""

import ctypes

import numpy as np

from ._native import _Args, _array, _as, _call, _check, _d, _dtype, _fn, _inp, _proto, _ptr, _scalar, _sz, _vp
from ._shape import _shape

_from_matrix = _proto("ggx_sggx_from_matrix", ctypes.c_int, _vp, _vp)
_from_shape = _proto("ggx_sggx_from_shape", ctypes.c_int, _vp, _vp)
_fields = _proto("ggxpy_sggx_fields", None, _vp, _vp, _vp, _vp)
_SGGX_SIZE = _proto("ggxpy_sizeof_sggx", _sz)()
_loop_v = _proto("ggxpy_sggx_v", None, _vp, _vp, _sz, _inp, _vp)
_loop_vv = _proto("ggxpy_sggx_vv", None, _vp, _vp, _sz, _inp, _vp)
_loop_sample2 = _proto("ggxpy_sggx_sample2", None, _vp, _vp, _sz, _inp, _vp)
_loop_sample4 = _proto("ggxpy_sggx_sample4", None, _vp, _sz, _inp, _vp)


class Flakes:
    """An SGGX flake distribution (ggx_sggx): the flakes of the ellipsoid x^T S x = 1. Immutable; safe to share
    between threads.

    Make one with Flakes(S) (S symmetric positive definite, 3 x 3, row-major; ggx_sggx_from_matrix) or
    Flakes.from_shape(shape) (S = A^T A, the flakes of the shape's own ellipsoid; ggx_sggx_from_shape). A refused S
    raises ValueError with the library's message.

    Properties (read-only float64): matrix, S as the library keeps it (symmetrised); eigenvalues, ascending; axes,
    the unit eigenvectors as rows. Flakes pickle by their matrix.
    """

    __slots__ = ("_buf", "_matrix", "_eig", "_axes", "__weakref__")

    def __init__(self, S):
        a = _array(S, "S")
        if a.shape != (3, 3):
            raise ValueError(f"S: expected a 3 x 3 matrix, got shape {a.shape}")
        c = np.ascontiguousarray(a)
        self._setup(lambda b: _from_matrix(b, c.ctypes.data))

    def _setup(self, make):
        buf = ctypes.create_string_buffer(_SGGX_SIZE)
        _check(make(buf))
        s, e, x = (_d * 9)(), (_d * 3)(), (_d * 9)()
        _fields(buf, s, e, x)
        self._buf = buf
        # over immutable bytes, so that numpy refuses to make them writeable
        self._matrix = np.frombuffer(bytes(s)).reshape(3, 3)
        self._eig = np.frombuffer(bytes(e))
        self._axes = np.frombuffer(bytes(x)).reshape(3, 3)

    @classmethod
    def from_shape(cls, shape):
        """The flakes of the shape's own ellipsoid (ggx_sggx_from_shape): S = A^T A, so that D(m) = sigma(n) ndf(m)
        on the upper hemisphere."""
        s = _shape(shape)
        self = object.__new__(cls)
        self._setup(lambda b: _from_shape(b, s._buf))
        return self

    @property
    def matrix(self):
        return self._matrix

    @property
    def eigenvalues(self):
        return self._eig

    @property
    def axes(self):
        return self._axes

    def __repr__(self):
        rows = "[" + ", ".join("[" + ", ".join(repr(float(x)) for x in r) + "]" for r in self._matrix) + "]"
        return f"Flakes({rows})"

    def __reduce__(self):
        return (Flakes, (self._matrix.tolist(),))

    def __eq__(self, other):
        return isinstance(other, Flakes) and bool(np.array_equal(self._matrix, other._matrix))

    def __hash__(self):
        return hash(self._matrix.tobytes())


def _flakes(f):
    if not isinstance(f, Flakes):
        raise ValueError(f"flakes: expected a ggx.Flakes, got {f!r}")
    return f


def sggx_ndf(flakes, m, dtype=np.float64, out=None):
    """D(m) = 1 / (pi sqrt(|S|) (m^T S^-1 m)^2) on the whole sphere (ggx_sggx_ndf); 0 for a zero or NaN m."""
    return _call(_loop_v, (_fn("ggx_sggx_ndf"), _flakes(flakes)._buf), [(m, "m", 3)], dtype, out=out)


def sggx_sigma(flakes, w, dtype=np.float64, out=None):
    """sigma(w) = sqrt(w^T S w), the flakes' projected area seen from w (ggx_sggx_sigma); homogeneous in w."""
    return _call(_loop_v, (_fn("ggx_sggx_sigma"), _flakes(flakes)._buf), [(w, "w", 3)], dtype, out=out)


def sggx_phase_specular(flakes, wi, wo, dtype=np.float64, out=None):
    """The specular flakes' phase function D(h) / (4 sigma(wi)), h = normalize(wi + wo) (ggx_sggx_phase_specular):
    a density of wo per unit solid angle; wi and wo unit, both pointing away from the point."""
    return _call(_loop_vv, (_fn("ggx_sggx_phase_specular"), _flakes(flakes)._buf), [(wi, "wi", 3), (wo, "wo", 3)],
                 dtype, out=out)


def sggx_phase_diffuse(flakes, wi, wo, dtype=np.float64, out=None):
    """The diffuse flakes' phase function (ggx_sggx_phase_diffuse), evaluated deterministically to the accuracy its
    header states: a density of wo per unit solid angle."""
    return _call(_loop_vv, (_fn("ggx_sggx_phase_diffuse"), _flakes(flakes)._buf), [(wi, "wi", 3), (wo, "wo", 3)],
                 dtype, out=out)


def _sample(loop, head, specs, dtype, out):
    a = _Args(*specs)
    dt = _dtype(dtype)
    if out is not None and dt != np.float64:
        raise ValueError("out: this function computes in float64; out= is taken with dtype=np.float64")
    w = a.out(3, out=out)
    if a.n:
        loop(*head, a.n, a.ins, _ptr(w))
    return w if out is not None else _as(_scalar(w), dtype)


def sggx_sample_vndf(flakes, wi, u1, u2, dtype=np.float64, out=None):
    """Visible normals m, pdf max(0, wi.m) D(m) / sigma(wi) (ggx_sggx_sample_vndf); the zero vector for a zero or
    NaN wi. Arrays (..., 3) of wi broadcast against u1, u2."""
    return _sample(_loop_sample2, (_fn("ggx_sggx_sample_vndf"), _flakes(flakes)._buf),
                   [(wi, "wi", 3), (u1, "u1", 1), (u2, "u2", 1)], dtype, out)


def sggx_sample_specular(flakes, wi, u1, u2, dtype=np.float64, out=None):
    """wo with the pdf sggx_phase_specular(flakes, wi, wo) (ggx_sggx_sample_specular; the weight is 1)."""
    return _sample(_loop_sample2, (_fn("ggx_sggx_sample_specular"), _flakes(flakes)._buf),
                   [(wi, "wi", 3), (u1, "u1", 1), (u2, "u2", 1)], dtype, out)


def sggx_sample_diffuse(flakes, wi, u1, u2, u3, u4, dtype=np.float64, out=None):
    """wo with the pdf sggx_phase_diffuse(flakes, wi, wo) (ggx_sggx_sample_diffuse; the weight is 1): a visible
    normal from u1, u2, then a cosine lobe about it from u3, u4."""
    return _sample(_loop_sample4, (_flakes(flakes)._buf,),
                   [(wi, "wi", 3), (u1, "u1", 1), (u2, "u2", 1), (u3, "u3", 1), (u4, "u4", 1)], dtype, out)
