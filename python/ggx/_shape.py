"""The objects the functions take: Shape (Walter's ellipsoid matrix A, ggx_shape) with its constructors, and
Fresnel (ggx_fresnel); _shape and _fresnel check an argument of the public functions."""

import ctypes

import numpy as np

from ._native import _array, _call, _check, _d, _i, _inp, _proto, _real, _sz, _vp

_ellipsoid_matrix = _proto("ggx_ellipsoid_matrix", _i, _vp, _d, _d, _d, _d, _d)
_shape_ellipsoid = _proto("ggx_shape_ellipsoid", _i, _vp, _d, _d, _d, _d, _d)
_shape_matrix = _proto("ggx_shape_matrix", _i, _vp, _vp)
_shape_from_slopes = _proto("ggx_shape_from_slopes", _i, _vp, _d, _d, _d, _d, _d)
_shape_slopes = _proto("ggx_shape_slopes", _i, _vp, _vp, _vp)
_shape_ellipsoid_params = _proto("ggx_shape_ellipsoid_params", _i, _vp, _vp, _vp, _vp, _vp, _vp)
_shape_kind = _proto("ggxpy_shape_kind", _i, _vp)
_shape_canonical = _proto("ggxpy_shape_canonical", None, _vp, _vp)
_fresnel_setup = {
    "one": _proto("ggx_fresnel_one", _i, _vp),
    "dielectric": _proto("ggx_fresnel_dielectric", _i, _vp, _d),
    "conductor": _proto("ggx_fresnel_conductor", _i, _vp, _d, _d),
    "schlick": _proto("ggx_fresnel_schlick", _i, _vp, _d),
}
_fresnel_avg = _proto("ggx_fresnel_avg", _d, _vp)
_SHAPE_SIZE = _proto("ggxpy_sizeof_shape", _sz)()
_FRESNEL_SIZE = _proto("ggxpy_sizeof_fresnel", _sz)()
_loop_fresnel = _proto("ggxpy_fresnel", None, _vp, _sz, _inp, _vp)


class _MatrixAttribute:
    """Shape.matrix: on the class, the constructor Shape.matrix(A); on a shape, its matrix (read-only property)."""

    def __get__(self, shape, cls):
        if shape is None:
            return cls._from_matrix
        return shape._matrix

    def __set__(self, shape, value):
        raise AttributeError("a Shape is immutable; make a new one")


class Shape:
    """A microfacet shape: Walter's ellipsoid matrix A (ggx_shape). Immutable; safe to share between threads.

    Make one with Shape.iso(alpha), Shape.aniso(ax, ay), Shape.ellipsoid(ax, ay, theta_x=0, theta_y=0, theta_z=0)
    (radians; A = diag(ax, ay, 1) Rx Ry Rz, Walter eq 2-3) or Shape.matrix(A) (any invertible 3 x 3 A, row-major).
    Alphas in (0, 1e4] (below 1e-4 raised to 1e-4), skews |theta_x|, |theta_y| <= pi/2; a refused shape raises
    ValueError with the library's message.

    Properties: matrix, the A given (read-only 3 x 3 float64; diag(alpha_x, alpha_y, 1) Rx Ry Rz for the
    alpha-based constructors, from ggx_ellipsoid_matrix); canonical_matrix, the Q A the library stores; kind.
    Shapes pickle (by their constructor and parameters) and compare equal when made by the same call.
    """

    __slots__ = ("_buf", "_matrix", "_repr", "_args", "__weakref__")

    def __init__(self, *args, **kwargs):
        raise TypeError("make a Shape with Shape.iso, Shape.aniso, Shape.ellipsoid or Shape.matrix")

    @classmethod
    def _new(cls, matrix, setup, text, args):
        self = object.__new__(cls)
        self._buf = ctypes.create_string_buffer(_SHAPE_SIZE)
        _check(setup(self._buf))
        # over immutable bytes: numpy refuses to make such an array (or any view of it) writeable again
        self._matrix = np.frombuffer(np.array(matrix, dtype=np.float64).reshape(3, 3).tobytes()).reshape(3, 3)
        self._repr = text
        self._args = args
        return self

    @classmethod
    def ellipsoid(cls, ax, ay, theta_x=0.0, theta_y=0.0, theta_z=0.0):
        """Walter's ellipsoid (ggx_shape_ellipsoid): anisotropic GGX of roughness (ax, ay) rotated by theta_z and
        skewed by theta_x, theta_y (radians)."""
        p = [_real(ax, "ax"), _real(ay, "ay"), _real(theta_x, "theta_x"),
             _real(theta_y, "theta_y"), _real(theta_z, "theta_z")]
        a = (_d * 9)()
        _check(_ellipsoid_matrix(a, *p))
        text = f"Shape.ellipsoid({p[0]!r}, {p[1]!r}, theta_x={p[2]!r}, theta_y={p[3]!r}, theta_z={p[4]!r})"
        return cls._new(list(a), lambda b: _shape_ellipsoid(b, *p), text, ("ellipsoid", tuple(p)))

    @classmethod
    def aniso(cls, ax, ay):
        """Anisotropic GGX along x and y (ggx_shape_aniso): A = diag(ax, ay, 1)."""
        s = cls.ellipsoid(ax, ay)
        p = s._args[1]
        s._repr = f"Shape.aniso({p[0]!r}, {p[1]!r})"
        s._args = ("aniso", p[:2])
        return s

    @classmethod
    def iso(cls, alpha):
        """Isotropic GGX of roughness alpha (ggx_shape_iso)."""
        s = cls.ellipsoid(alpha, alpha)
        s._repr = f"Shape.iso({s._args[1][0]!r})"
        s._args = ("iso", s._args[1][:1])
        return s

    @classmethod
    def _from_matrix(cls, A):
        """Any invertible A (ggx_shape_matrix): c A and Q A (c != 0, Q orthogonal) are the same distribution."""
        a = _array(A, "A")
        if a.shape != (3, 3):
            raise ValueError(f"A: expected a 3 x 3 matrix, got shape {a.shape}")
        a = np.ascontiguousarray(a)
        rows = "[" + ", ".join("[" + ", ".join(repr(float(x)) for x in r) + "]" for r in a) + "]"
        return cls._new(a, lambda b: _shape_matrix(b, a.ctypes.data), f"Shape.matrix({rows})",
                        ("matrix", (tuple(map(tuple, a.tolist())),)))

    @classmethod
    def from_slopes(cls, t, sigma):
        """The shape whose micro-normals' slopes have location t = (t_x, t_y) and scale Sigma = (sxx, sxy, syy) or a
        2 x 2 matrix (ggx_shape_from_slopes): P22 = 1 / (pi sqrt(det Sigma) (1 + (x - t)^T Sigma^-1 (x - t))^2).
        Its matrix is the canonical one the library builds."""
        tv = _array(t, "t").reshape(-1)
        sv = _array(sigma, "sigma")
        if tv.shape != (2,):
            raise ValueError(f"t: expected 2 numbers, got shape {np.shape(t)}")
        if sv.shape == (2, 2):
            if sv[0, 1] != sv[1, 0]:
                raise ValueError("sigma: the 2 x 2 matrix is not symmetric")
            sv = np.array([sv[0, 0], sv[0, 1], sv[1, 1]])
        if sv.shape != (3,):
            raise ValueError(f"sigma: expected (sxx, sxy, syy) or a 2 x 2 matrix, got shape {np.shape(sigma)}")
        p = [float(tv[0]), float(tv[1]), float(sv[0]), float(sv[1]), float(sv[2])]
        probe = ctypes.create_string_buffer(_SHAPE_SIZE)
        _check(_shape_from_slopes(probe, *p))
        a = np.empty((3, 3))
        _shape_canonical(probe, a.ctypes.data)
        text = f"Shape.from_slopes(({p[0]!r}, {p[1]!r}), ({p[2]!r}, {p[3]!r}, {p[4]!r}))"
        return cls._new(a, lambda b: _shape_from_slopes(b, *p), text,
                        ("from_slopes", ((p[0], p[1]), (p[2], p[3], p[4]))))

    def slopes(self):
        """(t, sigma): the location (2,) and scale (Sigma_xx, Sigma_xy, Sigma_yy) of the slopes' Student t
        (ggx_shape_slopes); t = 0 exactly for unskewed shapes."""
        t, sg = np.empty(2), np.empty(3)
        _check(_shape_slopes(self._buf, t.ctypes.data, sg.ctypes.data))
        return t, sg

    def ellipsoid_params(self):
        """(alpha_x, alpha_y, theta_x, theta_y, theta_z) of Shape.ellipsoid giving the same distribution
        (ggx_shape_ellipsoid_params; radians)."""
        v = [_d() for _ in range(5)]
        _check(_shape_ellipsoid_params(self._buf, *[ctypes.byref(x) for x in v]))
        return tuple(x.value for x in v)

    matrix = _MatrixAttribute()

    @property
    def canonical_matrix(self):
        """The canonical Q A the library stores (ggx_shape.a): the same distribution, with A n along +z."""
        a = np.empty((3, 3))
        _shape_canonical(self._buf, a.ctypes.data)
        a.flags.writeable = False
        return a

    @property
    def kind(self):
        """'diagonal' (anisotropic GGX along x, y), 'unskewed' (rotated in the tangent plane) or 'skewed'."""
        return ("diagonal", "unskewed", "skewed")[_shape_kind(self._buf)]

    def __repr__(self):
        return self._repr

    def __reduce__(self):
        kind, p = self._args
        return (getattr(Shape, kind), p)

    def __eq__(self, other):
        return isinstance(other, Shape) and self._args == other._args

    def __hash__(self):
        return hash(self._args)  # consistent with ==: hash(-0.0) == hash(0.0)


class Fresnel:
    """A Fresnel term (ggx_fresnel): Fresnel.one() (F = 1), Fresnel.dielectric(eta), Fresnel.conductor(eta, k),
    Fresnel.schlick(f0). f(cos_i) evaluates it elementwise (ggx_fresnel_eval); f.avg is F_avg
    (ggx_fresnel_avg)."""

    __slots__ = ("_buf", "_repr", "_args")

    def __init__(self, *args, **kwargs):
        raise TypeError("make a Fresnel with Fresnel.one, .dielectric, .conductor or .schlick")

    @classmethod
    def _new(cls, kind, *params):
        self = object.__new__(cls)
        self._buf = ctypes.create_string_buffer(_FRESNEL_SIZE)
        _check(_fresnel_setup[kind](self._buf, *params))
        self._repr = f"Fresnel.{kind}({', '.join(repr(p) for p in params)})"
        self._args = (kind, params)
        return self

    def __reduce__(self):
        return (getattr(Fresnel, self._args[0]), self._args[1])

    @classmethod
    def one(cls):
        return cls._new("one")

    @classmethod
    def dielectric(cls, eta):
        return cls._new("dielectric", _real(eta, "eta"))

    @classmethod
    def conductor(cls, eta, k):
        return cls._new("conductor", _real(eta, "eta"), _real(k, "k"))

    @classmethod
    def schlick(cls, f0):
        return cls._new("schlick", _real(f0, "f0"))

    @property
    def avg(self):
        return _fresnel_avg(self._buf)

    def __call__(self, cos_i, dtype=np.float64):
        return _call(_loop_fresnel, (self._buf,), [(cos_i, "cos_i", 1)], dtype)

    def __repr__(self):
        return self._repr


_ONE = Fresnel.one()


def _fresnel(f):
    if f is None:
        return _ONE
    if not isinstance(f, Fresnel):
        raise ValueError(f"fresnel: expected a ggx.Fresnel or None, got {f!r}")
    return f


def _shape(s):
    if not isinstance(s, Shape):
        raise ValueError(f"shape: expected a ggx.Shape, got {s!r}")
    return s
