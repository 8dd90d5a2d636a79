"""libggx for Python: Walter's Ellipsoid NDF (anisotropic, rotated and skewed GGX) on numpy arrays.

Conventions are the C library's (include/ggx/ggx.h): local frame with the macro-surface normal n = +z, every
direction a unit vector pointing away from the surface, angles in radians. A shape is made once
(``Shape.iso``, ``Shape.aniso``, ``Shape.ellipsoid``, ``Shape.matrix``) and passed to the functions.

Arrays follow numpy's rules: directions are arrays of shape (..., 3), numbers arrays of shape (...); the leading
dimensions of all inputs broadcast together and give the result's shape (a direction result has shape (..., 3)).
Inputs are converted to float64. Results are float64 and, element by element, bit for bit what the C function
returns (each function names it). ``dtype=np.float32`` uses the float batch API (include/ggx/ggx_batch.h, SIMD) where
it has the function (ndf, g1, pdf_vndf, brdf, sample_ndf and sample_vndf with a batch sampler, sample_brdf), within
the accuracy that header states; elsewhere float32 results are the float64 ones rounded, and a result beyond
float32's range (an absolute area or curvature of a matrix far from unit scale) raises ValueError, never inf.

Errors raise ValueError: a shape or Fresnel term the library refuses (with its status message), inputs that do not
broadcast, a direction array whose last axis is not 3, a complex, non-numeric or masked input, an unknown sampler or
option. (Calling Shape() or Fresnel() directly, or a wrong number of arguments, is a TypeError, as in Python; an
array too large for memory is numpy's MemoryError.) Any real input, NaN and
infinities included, gives a finite result (the C library's contract): 0 outside the domain, the zero vector for a
sampler that has no sample.
"""

import collections
import ctypes
import decimal
import math
import numbers
import os
import weakref

import numpy as np

__all__ = [
    "Shape", "Fresnel", "Energy", "SamplerInfo", "BrdfSample", "DirectionSample", "samplers", "status_message",
    "ndf", "ndf_spherical", "p22", "gaussian_curvature", "projected_area", "lune_area", "lambda_", "g1", "g1_smith",
    "g1_tilted", "g1_risers",
    "g2", "pdf_ndf", "pdf_vndf", "brdf", "bsdf", "albedo", "albedo_avg", "bsdf_albedo", "albedo_iso_table",
    "albedo_avg_iso_table", "bsdf_albedo_iso_table", "albedo_aniso_table",
    "sample", "pdf", "sample_inverse", "sample_ndf", "sample_vndf", "sample_brdf",
    "pdf_brdf", "sample_bsdf", "pdf_bsdf", "reflect", "half_reflect", "batch_isa", "set_batch_threads",
    "FitInfo", "Surface", "fit_normals", "fit_normal_cells", "fit_heightfield", "read_surface", "render",
    "texel_lobe", "filter_lobes", "filter_kl", "mipmap",
]

# The native module; the library's own functions are found through it in libggx, which it links.
_lib = ctypes.CDLL(os.path.join(os.path.dirname(os.path.abspath(__file__)), "_ggx_native.so"))

_vp = ctypes.c_void_p
_sz = ctypes.c_size_t
_d = ctypes.c_double
_i = ctypes.c_int


class _In(ctypes.Structure):
    """An input array of the native loops: its address and the step in doubles between elements (0: broadcast)."""
    _fields_ = [("p", _vp), ("step", ctypes.c_ssize_t)]


_inp = ctypes.POINTER(_In)


def _proto(name, restype, *argtypes):
    f = getattr(_lib, name)
    f.restype = restype
    f.argtypes = list(argtypes)
    return f


#: The version of the libggx the package runs with, "MAJOR.MINOR.PATCH" (ggx_version).
__version__ = _proto("ggx_version", ctypes.c_char_p)().decode()
_status_str = _proto("ggx_status_str", ctypes.c_char_p, _i)
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

# The native loops (python/src/native.c).
_loop_s = {k: _proto("ggxpy_s_" + k, None, _vp, _vp, _sz, _inp, _vp) for k in ("v", "vv", "vvv", "dd")}
_loop_sf_vv = _proto("ggxpy_sf_vv", None, _vp, _vp, _vp, _sz, _inp, _vp)
_loop_bsdf = _proto("ggxpy_bsdf", None, _vp, _d, _i, _sz, _inp, _vp)
_loop_bsdf_albedo = _proto("ggxpy_bsdf_albedo", None, _vp, _d, _sz, _inp, _vp, _vp)
_loop_fresnel = _proto("ggxpy_fresnel", None, _vp, _sz, _inp, _vp)
_loop_vv_v = _proto("ggxpy_vv_v", None, _vp, _sz, _inp, _vp)
_loop_iso_table = _proto("ggxpy_albedo_iso_table", None, _i, _sz, _inp, _vp)
_loop_bsdf_iso_table = _proto("ggxpy_bsdf_albedo_iso_table", None, _sz, _inp, _vp)
_loop_aniso_table = _proto("ggxpy_albedo_aniso_table", None, _sz, _inp, _vp)
_loop_sampler_pdf = _proto("ggxpy_sampler_pdf", None, _i, _vp, _d, _sz, _inp, _vp)
_loop_sample = _proto("ggxpy_sample", None, _i, _vp, _sz, _inp, _vp)
_loop_inverse = _proto("ggxpy_inverse", None, _i, _vp, _sz, _inp, _vp)
_loop_reject = _proto("ggxpy_sample_reject", None, _i, _vp, _sz, _inp, _vp, _vp)
_loop_direction = _proto("ggxpy_sample_direction", None, _i, _vp, _vp, _d, _i, _sz, _inp, _vp, _vp, _vp, _vp)
_loop_energy_albedo = _proto("ggxpy_energy_albedo", None, _vp, _sz, _inp, _vp)
_loop_energy_pdf_ms = _proto("ggxpy_energy_pdf_ms", None, _vp, _sz, _inp, _vp)
_loop_ef_vv = _proto("ggxpy_ef_vv", None, _vp, _vp, _vp, _sz, _inp, _vp)
_loop_energy_sample = _proto("ggxpy_energy_sample", None, _i, _vp, _vp, _sz, _inp, _vp, _vp, _vp, _vp)

_energy_create = _proto("ggx_energy_create", _i, _vp, ctypes.POINTER(_vp))
_energy_free = _proto("ggx_energy_free", None, _vp)
_energy_albedo_avg = _proto("ggx_energy_albedo_avg", _d, _vp)
_albedo_avg_fn = {
    "separable": _proto("ggx_albedo_avg", _d, _vp),
    "height-correlated": _proto("ggx_albedo_avg_height_correlated", _d, _vp),
}
_albedo_avg_iso_table = _proto("ggx_albedo_avg_iso_table", _d, _d, _i)

# The float batch API (include/ggx/ggx_batch.h), called directly.
_batch_ndf = _proto("ggx_batch_ndf", None, _vp, _sz, _vp, _vp, _vp, _vp)
_batch_g1 = _proto("ggx_batch_g1", None, _vp, _sz, _vp, _vp, _vp, _vp, _vp, _vp, _vp)
_batch_pdf_vndf = _proto("ggx_batch_pdf_vndf", None, _vp, _sz, _vp, _vp, _vp, _vp, _vp, _vp, _vp)
_batch_brdf = _proto("ggx_batch_brdf", None, _vp, _sz, _vp, _vp, _vp, _vp, _vp, _vp, _vp, _vp)
_batch_normals = _proto("ggx_batch_sample_normals", _i, _i, _vp, _vp, _vp, _sz, _vp, _vp, _vp, _vp, _vp, _vp)
_batch_directions = _proto("ggx_batch_sample_directions", _i, _i, _vp, _vp, _vp, _vp, _vp, _sz, _vp, _vp, _vp, _vp,
                           _vp, _vp, _vp)
_batch_get_isa = _proto("ggx_batch_get_isa", _i)
_batch_isa_name = _proto("ggx_batch_isa_name", ctypes.c_char_p, _i)
_batch_set_threads = _proto("ggx_batch_set_threads", _i, _i)


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


def _array(x, what):
    """x as a float64 array of real numbers: a complex value (which would lose its imaginary part), a string or
    other non-number, or a masked array (whose mask would be ignored) is an error."""
    if isinstance(x, np.ma.MaskedArray):
        raise ValueError(f"{what}: masked arrays are not supported (use .filled() or select the valid elements)")
    try:
        a = np.asarray(x)
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


_MODES = {"radiance": 0, "importance": 1}
_MASKINGS = {"separable": 0, "height-correlated": 1}


class _Args:
    """Inputs converted, broadcast and laid out for a native loop: .shape (the broadcast leading shape), .n, .ins
    (the _In array), and .arrays (kept alive for the call). Each spec is (value, name, width): width 3 for
    directions, 1 for numbers."""

    def __init__(self, *specs):
        arrays = []
        for value, what, width in specs:
            a = _array(value, what)
            if width == 3 and (a.ndim == 0 or a.shape[-1] != 3):
                raise ValueError(f"{what}: expected an array of shape (..., 3), got shape {a.shape}")
            arrays.append(a)
        lead = [a.shape[:-1] if w == 3 else a.shape for a, (_, _, w) in zip(arrays, specs)]
        try:
            self.shape = np.broadcast_shapes(*lead)
        except ValueError:
            names = ", ".join(f"{what} {s}" for (_, what, _), s in zip(specs, lead))
            raise ValueError(f"inputs do not broadcast together: {names}") from None
        self.n = math.prod(self.shape)
        self.widths = [w for _, _, w in specs]
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

    def out(self, *tail, dtype=np.float64):
        return np.empty(self.shape + tail, dtype=dtype)

    def soa32(self, k, role=None):
        """Input k as float32 arrays of n elements (x, y, z for a direction), for the batch API. Values beyond
        float's range become infinities (0 for an evaluation, as in float64). role "u": a u below 1 that rounds to 1
        becomes the largest float below 1 (the batch samplers take u in [0, 1)). role "view": a sampler's view is
        normalised in float64 first, since the samplers depend on its direction only (a view of length 1e-50 or
        1e300 would underflow or overflow in float)."""
        width = self.widths[k]
        a = self.arrays[k].reshape(-1, width)
        if role == "view":
            big = np.max(np.abs(a), axis=1, keepdims=True)
            with np.errstate(invalid="ignore", divide="ignore"):
                b = a / big
                a = b / np.sqrt(np.sum(b * b, axis=1, keepdims=True))
            a = np.where(np.isfinite(a).all(axis=1, keepdims=True), a, 0.0)  # zero, infinite, NaN: no view
        full = np.broadcast_to(a, (self.n, width))
        with np.errstate(over="ignore"):
            cols = [np.ascontiguousarray(full[:, c], dtype=np.float32) for c in range(width)]
        if role == "u":
            below_one = full[:, 0] < 1
            cols[0][below_one & (cols[0] >= 1)] = _U32_MAX
        return cols


_U32_MAX = np.nextafter(np.float32(1), np.float32(0))


def _ptr(a):
    return a.ctypes.data


def _call(loop, head, specs, dtype=np.float64):
    """The common wrapper: inputs converted and broadcast, loop(*head, n, inputs, out) run, the result in dtype."""
    a = _Args(*specs)
    out = a.out()
    if a.n:
        loop(*head, a.n, a.ins, _ptr(out))
    return _as(_scalar(out), dtype)


def _scalar(out):
    """numpy's convention: a 0-d result is returned as a numpy scalar."""
    return out[()] if out.ndim == 0 else out


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


# --- Evaluations -------------------------------------------------------------------------------------------------

def _eval(cname, shape, *specs):
    """A double function of the shape and of directions (width 3) or numbers (width 1), through its native loop."""
    s = _shape(shape)
    a = _Args(*specs)
    out = a.out()
    key = "".join("v" if w == 3 else "d" for _, _, w in specs)
    if a.n:
        _loop_s[key](_fn(cname), s._buf, a.n, a.ins, _ptr(out))
    return a, out


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


def _batch_eval(batch, shape, dt, cname, *specs, pre=()):
    """A function that the float batch API has: its batch loop for float32, the double loop otherwise."""
    dt = _dtype(dt)
    if dt == np.float64:
        return _scalar(_eval(cname, shape, *specs)[1])
    s = _shape(shape)
    a = _Args(*specs)
    out = a.out(dtype=np.float32)
    if a.n:
        cols = [c for k in range(len(specs)) for c in a.soa32(k)]
        batch(_ptr(out), a.n, s._buf, *[p._buf for p in pre], *[_ptr(c) for c in cols])
    return _scalar(out)


def ndf(shape, m, dtype=np.float64):
    """D(m) (ggx_ndf, Walter eq 1): >= 0, 0 for m.z < 0."""
    return _batch_eval(_batch_ndf, shape, dtype, "ggx_ndf", (m, "m", 3))


def ndf_spherical(shape, theta, phi, dtype=np.float64):
    """D(m) sin(theta) for m at the spherical angles (theta, phi) (ggx_ndf_spherical)."""
    return _as(_scalar(_eval("ggx_ndf_spherical", shape, (theta, "theta", 1), (phi, "phi", 1))[1]), dtype)


def p22(shape, slope_x, slope_y, dtype=np.float64):
    """The slope-space distribution P22 (ggx_p22)."""
    return _as(_scalar(_eval("ggx_p22", shape, (slope_x, "slope_x", 1), (slope_y, "slope_y", 1))[1]), dtype)


def gaussian_curvature(shape, m, dtype=np.float64):
    """Gaussian curvature of the ellipsoid where its normal is m (ggx_gaussian_curvature, eq 20)."""
    return _as(_scalar(_eval("ggx_gaussian_curvature", shape, (m, "m", 3))[1]), dtype)


def projected_area(shape, u, dtype=np.float64):
    """Projected area of the ellipsoid seen from u (ggx_projected_area, eq 26)."""
    return _as(_scalar(_eval("ggx_projected_area", shape, (u, "u", 3))[1]), dtype)


def lune_area(shape, u, v, dtype=np.float64):
    """Projected area seen from u of the lune {m.u >= 0, m.v >= 0} (ggx_lune_area, eq 28)."""
    return _as(_scalar(_eval("ggx_lune_area", shape, (u, "u", 3), (v, "v", 3))[1]), dtype)


def lambda_(shape, u, dtype=np.float64):
    """Smith's Lambda(u) and its lune-area generalisation for skewed shapes (ggx_lambda); 0 for u.z <= 0."""
    return _as(_scalar(_eval("ggx_lambda", shape, (u, "u", 3))[1]), dtype)


def g1(shape, u, m, dtype=np.float64):
    """Walter's masking G1(u, m) (ggx_g1, eq 6 / 32): in [0, 1]; 0 for u.z <= 0 or u.m <= 0."""
    return _batch_eval(_batch_g1, shape, dtype, "ggx_g1", (u, "u", 3), (m, "m", 3))


def g1_smith(shape, u, dtype=np.float64):
    """1 / (1 + Lambda(u)) (ggx_g1_smith)."""
    return _as(_scalar(_eval("ggx_g1_smith", shape, (u, "u", 3))[1]), dtype)


def g1_tilted(shape, u, m, dtype=np.float64):
    """Masking of a skewed shape read as GGX on a tilted mean plane (ggx_g1_tilted): in [0, 1]; ggx_g1 for unskewed
    shapes; 0 for u.z <= 0, u at or below the mean plane, or u.m < 0."""
    return _as(_scalar(_eval("ggx_g1_tilted", shape, (u, "u", 3), (m, "m", 3))[1]), dtype)


def g1_risers(shape, u, m, dtype=np.float64):
    """Masking of a skewed shape on a sawtooth of ramps and vertical risers (ggx_g1_risers): the least of
    g1_smith and the tilted base's term, in [0, 1]."""
    return _as(_scalar(_eval("ggx_g1_risers", shape, (u, "u", 3), (m, "m", 3))[1]), dtype)


def g2(shape, wi, wo, m, height_correlated=False, dtype=np.float64):
    """Shadowing-masking: separable G1(wi, m) G1(wo, m) (ggx_g2, eq 5) or height-correlated
    (ggx_g2_height_correlated)."""
    name = "ggx_g2_height_correlated" if height_correlated else "ggx_g2"
    return _as(_scalar(_eval(name, shape, (wi, "wi", 3), (wo, "wo", 3), (m, "m", 3))[1]), dtype)


def pdf_ndf(shape, m, dtype=np.float64):
    """D(m) m.z (ggx_pdf_ndf): the density of the NDF samplers."""
    return _as(_scalar(_eval("ggx_pdf_ndf", shape, (m, "m", 3))[1]), dtype)


def pdf_vndf(shape, v, m, dtype=np.float64):
    """The density of visible normals D_v(m) for view v (ggx_pdf_vndf, Walter eq 33); 0 for v.z <= 0."""
    return _batch_eval(_batch_pdf_vndf, shape, dtype, "ggx_pdf_vndf", (v, "v", 3), (m, "m", 3))


def brdf(shape, wi, wo, fresnel=None, dtype=np.float64):
    """The microfacet BRDF f_r(wi, wo) (ggx_brdf_eval, Walter eq 4 with G of eq 5); fresnel None means F = 1."""
    f = _fresnel(fresnel)
    dt = _dtype(dtype)
    if dt == np.float32:
        return _batch_eval(_batch_brdf, shape, dt, "ggx_brdf_eval", (wi, "wi", 3), (wo, "wo", 3), pre=(f,))
    return _call(_loop_sf_vv, (_fn("ggx_brdf_eval"), _shape(shape)._buf, f._buf), [(wi, "wi", 3), (wo, "wo", 3)])


def bsdf(shape, eta, wi, wo, mode="radiance", dtype=np.float64):
    """The rough-dielectric BSDF (ggx_bsdf_eval, Walter 2007): eta = index below / index above; wi, wo on either
    side; mode 'radiance' or 'importance' (the adjoint)."""
    head = (_shape(shape)._buf, _real(eta, "eta"), _choice(mode, _MODES, "mode"))
    return _call(_loop_bsdf, head, [(wi, "wi", 3), (wo, "wo", 3)], dtype)


def albedo(shape, v, masking="separable", dtype=np.float64):
    """Directional albedo E(v) with F = 1 (ggx_albedo, or ggx_albedo_height_correlated for
    masking='height-correlated'): deterministic quadrature, absolute error <= 1e-6, a quadrature per element (slow: milliseconds)."""
    name = "ggx_albedo" if _choice(masking, _MASKINGS, "masking") == 0 else "ggx_albedo_height_correlated"
    return _as(_scalar(_eval(name, shape, (v, "v", 3))[1]), dtype)


def albedo_avg(shape, masking="separable"):
    """E_avg = (1/pi) int E(v) v.z dv (ggx_albedo_avg or ggx_albedo_avg_height_correlated); a float."""
    return _albedo_avg_fn[_choice(masking, _MASKINGS, "masking") and "height-correlated" or "separable"](
        _shape(shape)._buf)


def bsdf_albedo(shape, eta, v, dtype=np.float64):
    """Reflected and transmitted albedo (R, T) of the rough dielectric for light from v, on either side
    (ggx_bsdf_albedo): absolute error <= 1e-5; milliseconds per element."""
    s = _shape(shape)
    e = _real(eta, "eta")
    a = _Args((v, "v", 3))
    r, t = a.out(), a.out()
    if a.n:
        _loop_bsdf_albedo(s._buf, e, a.n, a.ins, _ptr(r), _ptr(t))
    return _as((_scalar(r), _scalar(t)), dtype)


def albedo_iso_table(alpha, mu, masking="separable", dtype=np.float64):
    """E(mu) of isotropic GGX from the shipped table (ggx_albedo_iso_table): within 1e-3 for mu >= 0.0175."""
    g = _choice(masking, _MASKINGS, "masking")
    return _call(_loop_iso_table, (g,), [(alpha, "alpha", 1), (mu, "mu", 1)], dtype)


def bsdf_albedo_iso_table(alpha, eta, mu, dtype=np.float64):
    """R + T of the isotropic rough dielectric from the shipped table (ggx_bsdf_albedo_iso_table); mu > 0: light
    from above, mu < 0: from below. Within 1e-3 for alpha >= 0.02 and |mu| >= 0.0175."""
    return _call(_loop_bsdf_iso_table, (), [(alpha, "alpha", 1), (eta, "eta", 1), (mu, "mu", 1)], dtype)


def albedo_aniso_table(alpha_x, alpha_y, v, dtype=np.float64):
    """E(v) of anisotropic GGX (separable G) from the shipped table (ggx_albedo_aniso_table), v in the shape's frame:
    within 1e-3 for v.z >= 0.0175."""
    return _call(_loop_aniso_table, (), [(alpha_x, "alpha_x", 1), (alpha_y, "alpha_y", 1), (v, "v", 3)], dtype)


def albedo_avg_iso_table(alpha, masking="separable"):
    """E_avg(alpha) of isotropic GGX from the shipped table (ggx_albedo_avg_iso_table); a float."""
    return _albedo_avg_iso_table(_real(alpha, "alpha"), _choice(masking, _MASKINGS, "masking"))


# --- The registry of samplers ------------------------------------------------------------------------------------

SamplerInfo = collections.namedtuple("SamplerInfo", "id name family domain batch inverse help function")
SamplerInfo.__doc__ = """A sampler of the library's registry (ggx_samplers.h): family 'ndf', 'vndf', 'rejection'
or 'direction'; domain 'any' or 'unskewed'; batch: the float batch API has it; inverse: sample_inverse works;
function: the name of its C function (ggx_sampler_info.function)."""

_FAMILIES = ("ndf", "vndf", "rejection", "direction")


def _registry():
    out = []
    cp = ctypes.POINTER(ctypes.c_char_p)
    desc = _proto("ggxpy_sampler_desc", _i, _i, cp, cp, cp, ctypes.POINTER(_i), ctypes.POINTER(_i),
                  ctypes.POINTER(_i), ctypes.POINTER(_i))
    name, hlp, fn = ctypes.c_char_p(), ctypes.c_char_p(), ctypes.c_char_p()
    fam, dom, bat, inv = _i(), _i(), _i(), _i()
    k = 0
    while desc(k, ctypes.byref(name), ctypes.byref(hlp), ctypes.byref(fn), ctypes.byref(fam), ctypes.byref(dom),
               ctypes.byref(bat), ctypes.byref(inv)):
        out.append(SamplerInfo(k, name.value.decode(), _FAMILIES[fam.value], ("any", "unskewed")[dom.value],
                               bool(bat.value), bool(inv.value), hlp.value.decode(), fn.value.decode()))
        k += 1
    return tuple(out)


_SAMPLERS = _registry()
_BY_NAME = {e.name: e for e in _SAMPLERS}


def samplers(family=None):
    """The registry's samplers (SamplerInfo tuples), all or those of one family."""
    if family is not None:
        _choice(family, _FAMILIES, "family")
    return [e for e in _SAMPLERS if family is None or e.family == family]


def _sampler(method, families, shape):
    e = _BY_NAME.get(method) if isinstance(method, str) else None
    if e is None or e.family not in families:
        names = [x.name for x in _SAMPLERS if x.family in families]
        raise ValueError(f"method: expected one of {', '.join(names)}, got {method!r}")
    if e.domain == "unskewed" and shape.kind == "skewed":
        raise ValueError(f"sampler '{method}' applies to unskewed shapes only; this shape is skewed")
    return e


BrdfSample = collections.namedtuple("BrdfSample", "w pdf weight")
BrdfSample.__doc__ = """Sampled directions w (..., 3), their pdfs (per solid angle) and weights f |w.z| / pdf;
invalid samples (below the horizon) have w = 0, pdf = 0, weight = 0."""
DirectionSample = collections.namedtuple("DirectionSample", "w pdf weight event")
DirectionSample.__doc__ = """As BrdfSample, with the event of each sample (int8): 0 invalid, 1 reflection,
2 transmission."""

_NO_VIEW = (0.0, 0.0, 1.0)


def sample(method, shape, v, u1, u2, u3=0.0, fresnel=None, eta=1.5, mode="radiance", dtype=np.float64,
           return_trials=False):
    """Any sampler of the registry by name (samplers()).

    ndf, vndf: the normals m (..., 3) for (u1, u2) in [0, 1) (outside: clamped, NaN: 0) and view v (ignored by NDF
    samplers; pass None); the zero vector where there is no sample. rejection: the same, with each element's
    candidates drawn from a stream seeded by the bits of (u1, u2) (splitmix64), so equal inputs give equal normals;
    return_trials=True also returns the number of candidates per element. direction: a DirectionSample from the
    known direction v (u3 chooses reflection or refraction for 'bsdf'; fresnel is used by the reflection samplers,
    eta and mode by 'bsdf'). dtype=np.float32 runs batch samplers in float (ggx_batch_sample_normals,
    ggx_batch_sample_directions for 'brdf' and 'brdf-bounded'): the view is normalised in float64 first, u is rounded to float (a u below 1
    that rounds to 1 becomes the largest float below 1), and a NaN or infinite u gives the zero vector (an invalid
    sample), as ggx_batch.h states; the other samplers give their float64 result rounded.
    """
    s = _shape(shape)
    e = _sampler(method, _FAMILIES, s)
    dt = _dtype(dtype)
    v = _view(v, e)
    if e.family in ("ndf", "vndf", "rejection"):
        a = _Args((v, "v", 3), (u1, "u1", 1), (u2, "u2", 1))
        if e.family == "rejection":
            m, trials = a.out(3), a.out()
            if a.n:
                _loop_reject(e.id, s._buf, a.n, a.ins, _ptr(m), _ptr(trials))
            m = m if dt == np.float64 else m.astype(dt)
            return (m, _scalar(trials.astype(np.int64))) if return_trials else m
        if dt == np.float32 and e.batch:
            m = a.out(3, dtype=np.float32)
            if a.n:
                (vx, vy, vz), (q1,), (q2,) = a.soa32(0, "view"), a.soa32(1, "u"), a.soa32(2, "u")
                cols = [np.empty(a.n, np.float32) for _ in range(3)]
                _check(_batch_normals(e.id, *[_ptr(c) for c in cols], a.n, s._buf, _ptr(vx), _ptr(vy), _ptr(vz),
                                      _ptr(q1), _ptr(q2)))
                m.reshape(-1, 3)[:] = np.stack(cols, axis=-1)
            return m
        m = a.out(3)
        if a.n:
            _loop_sample(e.id, s._buf, a.n, a.ins, _ptr(m))
        return m if dt == np.float64 else m.astype(dt)
    f = _fresnel(fresnel)
    md = _choice(mode, _MODES, "mode")
    et = _real(eta, "eta")
    a = _Args((v, "v", 3), (u1, "u1", 1), (u2, "u2", 1), (u3, "u3", 1))
    if dt == np.float32 and e.batch:
        w, pdf_, weight = a.out(3, dtype=np.float32), a.out(dtype=np.float32), a.out(dtype=np.float32)
        if a.n:
            (vx, vy, vz), (q1,), (q2,) = a.soa32(0, "view"), a.soa32(1, "u"), a.soa32(2, "u")
            cols = [np.empty(a.n, np.float32) for _ in range(3)]
            _check(_batch_directions(e.id, *[_ptr(c) for c in cols], _ptr(pdf_), _ptr(weight), a.n, s._buf, f._buf,
                                     _ptr(vx), _ptr(vy), _ptr(vz), _ptr(q1), _ptr(q2)))
            w.reshape(-1, 3)[:] = np.stack(cols, axis=-1)
        event = np.where(pdf_ > 0, 1, 0).astype(np.int8)
        return DirectionSample(w, _scalar(pdf_), _scalar(weight), _scalar(event))
    w, pdf_, weight, event = a.out(3), a.out(), a.out(), a.out(dtype=np.int8)
    if a.n:
        _loop_direction(e.id, s._buf, f._buf, et, md, a.n, a.ins, _ptr(w), _ptr(pdf_), _ptr(weight), _ptr(event))
    if dt == np.float32:
        w, pdf_, weight = w.astype(dt), pdf_.astype(dt), weight.astype(dt)
    return DirectionSample(w, _scalar(pdf_), _scalar(weight), _scalar(event))


def _view(v, e):
    """The view for sampler e: None only for NDF samplers, which ignore it."""
    if v is None:
        if e.family != "ndf":
            raise ValueError(f"v: sampler '{e.name}' needs a view")
        return _NO_VIEW
    return v


def pdf(method, shape, v, m, eta=1.5, dtype=np.float64):
    """The density of a registry sampler (ggx_sampler_info.pdf or .pdf_direction): of the normal m for view v
    (ndf, vndf, rejection; v ignored by NDF samplers, None allowed there), or of the direction m from v (direction
    samplers; eta for 'bsdf')."""
    s = _shape(shape)
    e = _sampler(method, _FAMILIES, s)
    return _call(_loop_sampler_pdf, (e.id, s._buf, _real(eta, "eta")), [(_view(v, e), "v", 3), (m, "m", 3)], dtype)


def sample_inverse(method, shape, v, m, dtype=np.float64):
    """The (u1, u2) that give the normal m (..., 2), for samplers with an inverse (SamplerInfo.inverse)."""
    s = _shape(shape)
    e = _sampler(method, ("ndf", "vndf"), s)
    if not e.inverse:
        raise ValueError(f"sampler '{method}' has no inverse")
    a = _Args((_view(v, e), "v", 3), (m, "m", 3))
    out = a.out(2)
    if a.n:
        _loop_inverse(e.id, s._buf, a.n, a.ins, _ptr(out))
    return _as(out, dtype)


def sample_ndf(shape, u1, u2, method="stretch", dtype=np.float64):
    """Normals with density D(m) m.z (pdf_ndf) by an NDF sampler of the registry (default: the elliptic
    stretch, ggx_sample_ndf_stretch)."""
    _sampler(method, ("ndf",), _shape(shape))
    return sample(method, shape, None, u1, u2, dtype=dtype)


def sample_vndf(shape, v, u1, u2, method="caps", dtype=np.float64):
    """Visible normals for view v with density pdf_vndf by a VNDF or rejection sampler of the registry (default:
    spherical caps, ggx_sample_vndf_caps); the zero vector for v.z <= 0."""
    _sampler(method, ("vndf", "rejection"), _shape(shape))
    return sample(method, shape, v, u1, u2, dtype=dtype)


def sample_brdf(shape, wi, u1, u2, fresnel=None, bounded=False, dtype=np.float64):
    """Reflection sampling (ggx_sample_brdf, Walter eq 47-50, or ggx_sample_brdf_bounded): a BrdfSample
    (w, pdf, weight); the weight is <= 1 (eq 52)."""
    r = sample("brdf-bounded" if bounded else "brdf", shape, wi, u1, u2, fresnel=fresnel, dtype=dtype)
    return BrdfSample(r.w, r.pdf, r.weight)


def pdf_brdf(shape, wi, wo, bounded=False, dtype=np.float64):
    """The pdf of sample_brdf (ggx_pdf_brdf or ggx_pdf_brdf_bounded)."""
    return pdf("brdf-bounded" if bounded else "brdf", shape, wi, wo, dtype=dtype)


def sample_bsdf(shape, eta, v, u1, u2, u3, mode="radiance", dtype=np.float64):
    """Rough-dielectric sampling (ggx_sample_bsdf): a DirectionSample from the known direction v (either side)."""
    return sample("bsdf", shape, v, u1, u2, u3, eta=eta, mode=mode, dtype=dtype)


def pdf_bsdf(shape, eta, v, w, dtype=np.float64):
    """The pdf of sample_bsdf giving w from v (ggx_pdf_bsdf)."""
    return pdf("bsdf", shape, v, w, eta=eta, dtype=dtype)


# --- Geometry ----------------------------------------------------------------------------------------------------

def _geometry(cname, a_, b_, names, dtype):
    a = _Args((a_, names[0], 3), (b_, names[1], 3))
    out = a.out(3)
    if a.n:
        _loop_vv_v(_fn(cname), a.n, a.ins, _ptr(out))
    return _as(out, dtype)


def reflect(w, m, dtype=np.float64):
    """The mirror reflection 2 (w.m) m - w of w about the unit normal m (ggx_reflect); any w, m."""
    return _geometry("ggx_reflect", w, m, ("w", "m"), dtype)


def half_reflect(wi, wo, dtype=np.float64):
    """The reflection half vector normalize(wi + wo) flipped to h.z >= 0, the zero vector where wi + wo = 0
    (ggx_half_reflect)."""
    return _geometry("ggx_half_reflect", wi, wo, ("wi", "wo"), dtype)


# --- Energy compensation -----------------------------------------------------------------------------------------

class Energy:
    """A shape's albedo table and Kulla-Conty energy compensation (ggx_energy_create; docs/design/energy.md).

    Building it takes microseconds for shapes read from the shipped tables, 3 to 7 s for other unskewed shapes and
    7 to 30 s for skewed ones; it is immutable after that and safe to share between threads. A shape whose albedo has
    a feature finer than the table resolves (a sharp skewed lobe) raises ValueError (GGX_ERR_RANGE): render it
    without compensation. Directions need not be unit; fresnel None means F = 1.
    """

    __slots__ = ("_handle", "_shape", "_finalizer", "__weakref__")

    def __init__(self, shape):
        self._shape = _shape(shape)
        h = _vp()
        _check(_energy_create(self._shape._buf, ctypes.byref(h)))
        self._handle = h.value
        self._finalizer = weakref.finalize(self, _energy_free, h.value)

    @property
    def shape(self):
        return self._shape

    def __repr__(self):
        return f"Energy({self._shape!r})"

    def __reduce__(self):
        return (Energy, (self._shape,))  # pickling rebuilds the table from the shape

    def __copy__(self):
        return self  # immutable: a copy would share the table anyway

    def __deepcopy__(self, memo):
        return self

    def albedo(self, v, dtype=np.float64):
        """E(v) from the table (ggx_energy_albedo): within 1e-3 of albedo(shape, v)."""
        return _call(_loop_energy_albedo, (self._handle,), [(v, "v", 3)], dtype)

    def albedo_avg(self):
        """E_avg of the table (ggx_energy_albedo_avg); a float."""
        return _energy_albedo_avg(self._handle)

    def _ef(self, cname, wi, wo, fresnel, dtype):
        head = (_fn(cname), self._handle, _fresnel(fresnel)._buf)
        return _call(_loop_ef_vv, head, [(wi, "wi", 3), (wo, "wo", 3)], dtype)

    def brdf_ms(self, wi, wo, fresnel=None, dtype=np.float64):
        """The multiple-scattering lobe f_ms (ggx_brdf_ms_eval)."""
        return self._ef("ggx_brdf_ms_eval", wi, wo, fresnel, dtype)

    def brdf_compensated(self, wi, wo, fresnel=None, dtype=np.float64):
        """brdf + brdf_ms (ggx_brdf_compensated_eval): with F = 1 its albedo is 1 within the table's error."""
        return self._ef("ggx_brdf_compensated_eval", wi, wo, fresnel, dtype)

    def pdf_brdf_compensated(self, wi, wo, fresnel=None, dtype=np.float64):
        """The pdf of sample_brdf_compensated (ggx_pdf_brdf_compensated)."""
        return self._ef("ggx_pdf_brdf_compensated", wi, wo, fresnel, dtype)

    def pdf_brdf_ms(self, wi, wo, dtype=np.float64):
        """The pdf of sample_brdf_ms (ggx_pdf_brdf_ms)."""
        return _call(_loop_energy_pdf_ms, (self._handle,), [(wi, "wi", 3), (wo, "wo", 3)], dtype)

    def _sample(self, compensated, wi, u1, u2, u3, fresnel):
        f = _fresnel(fresnel)
        a = _Args((wi, "wi", 3), (u1, "u1", 1), (u2, "u2", 1), (u3, "u3", 1))
        w, p, weight, event = a.out(3), a.out(), a.out(), a.out(dtype=np.int8)
        if a.n:
            _loop_energy_sample(compensated, self._handle, f._buf, a.n, a.ins, _ptr(w), _ptr(p), _ptr(weight),
                                _ptr(event))
        return BrdfSample(w, _scalar(p), _scalar(weight))

    def sample_brdf_ms(self, wi, u1, u2, fresnel=None):
        """Samples the multiple-scattering lobe (ggx_sample_brdf_ms): a BrdfSample."""
        return self._sample(0, wi, u1, u2, 0.0, fresnel)

    def sample_brdf_compensated(self, wi, u1, u2, u3, fresnel=None):
        """Samples the compensated BRDF (ggx_sample_brdf_compensated): a BrdfSample."""
        return self._sample(1, wi, u1, u2, u3, fresnel)


def batch_isa():
    """The instruction set the float batch API uses ('scalar', 'avx2' or 'avx512'; ggx_batch_get_isa)."""
    return _batch_isa_name(_batch_get_isa()).decode()


def set_batch_threads(threads):
    """Worker threads of the float batch API for arrays of 65536 elements or more (ggx_batch_set_threads;
    an integer from 1 to 256)."""
    t = _real(threads, "threads")
    if not (1 <= t <= 256 and t == int(t)):
        raise ValueError(f"threads: expected an integer from 1 to 256, got {threads!r}")
    _check(_batch_set_threads(int(t)))


# ---- fits (include/ggx/ggx_fit.h) and measured surfaces ----

_fit_normals = _proto("ggxpy_fit_normals", _i, _vp, _vp, _vp, _sz, _i, _i, _i, _d, _vp)
_fit_normal_cells = _proto("ggxpy_fit_normal_cells", _i, _vp, _vp, _vp, _sz, _d, _i, _i, _i, _d, _vp)
_surface_uv = _proto("ggxpy_surface_uv", _i, _vp, _vp)
_fit_heightfield = _proto("ggxpy_fit_heightfield", _i, _vp, _vp, _sz, _sz, _d, _d, _i, _i, _i, _i, _i, _d, _vp)
_surface_read = _proto("ggxpy_surface_read", _vp, ctypes.c_char_p, _i, _i, _vp, ctypes.c_char_p, _sz)
_surface_copy = _proto("ggxpy_surface_copy", None, _vp, _vp, _vp)
_surface_close = _proto("ggxpy_surface_close", None, _vp)
# the flat layout of ggx_fit_info, as the native module lists it (python/src/native.c, FIT_FIELDS)
_FIT_FIELDS = [(f.split(":")[0], int(f.split(":")[1]))
               for f in _proto("ggxpy_fit_fields", ctypes.c_char_p)().decode().strip(",").split(",")]
_FIT_SIZE = sum(n for _, n in _FIT_FIELDS)
_FIT_MODELS = ("ellipsoid", "anisotropic", "isotropic", "beckmann")
_FIT_SHAPE_MODELS = {"ellipsoid": 0, "anisotropic": 1, "isotropic": 2}
_INT_FIELDS = {"iterations", "gof_cells", "gof_dof", "used", "ignored_horizon", "ignored_nonfinite",
               "ignored_weight"}


class FitInfo:
    """What a fit measured (ggx_fit_info): iterations, converged, stationarity (the Newton decrement),
    log_likelihood (per sample), t (2,), sigma (3,), std_error (5,: t_x, t_y, sigma_xx, sigma_xy, sigma_yy; 0 for
    parameters the model fixes), covariance (5, 5), gof_chi2, gof_pvalue (NaN when too few samples), gof_cells,
    gof_dof, used, ignored_horizon, ignored_nonfinite, ignored_weight, effective_n, clamped, best (the model name of
    least BIC) and models: {name: {"log_likelihood", "bic", "parameters", "iterations", "t", "sigma"}} for
    "ellipsoid", "anisotropic", "isotropic" and "beckmann" (Beckmann's t and sigma are the slopes' mean and
    covariance)."""

    def __init__(self, flat):
        at, raw = 0, {}
        for name, n in _FIT_FIELDS:
            raw[name] = flat[at:at + n].copy()
            at += n
        for name, v in raw.items():
            if name.startswith("model_"):
                continue
            if name in _INT_FIELDS:
                setattr(self, name, int(v[0]))
            elif name in ("converged", "clamped"):
                setattr(self, name, bool(v[0]))
            elif name == "best":
                setattr(self, name, _FIT_MODELS[int(v[0])])
            elif len(v) == 1:
                setattr(self, name, float(v[0]))
            else:
                setattr(self, name, v.reshape(5, 5) if name == "covariance" else v)
        self.models = {m: {"log_likelihood": float(raw["model_log_likelihood"][k]),
                           "bic": float(raw["model_bic"][k]),
                           "parameters": int(raw["model_parameters"][k]),
                           "iterations": int(raw["model_iterations"][k]),
                           "t": raw["model_t"][2 * k:2 * k + 2],
                           "sigma": raw["model_sigma"][3 * k:3 * k + 3]} for k, m in enumerate(_FIT_MODELS)}

    def __repr__(self):
        return (f"FitInfo(best={self.best!r}, t={self.t.tolist()}, sigma={self.sigma.tolist()}, "
                f"log_likelihood={self.log_likelihood!r}, iterations={self.iterations}, converged={self.converged})")


def _fit_settings(model, threads, max_iterations, tolerance):
    m = _choice(model, _FIT_SHAPE_MODELS, "model")
    t = _real(threads, "threads")
    if not (1 <= t <= 256 and t == int(t)):
        raise ValueError(f"threads: expected an integer from 1 to 256, got {threads!r}")
    it = 0 if max_iterations is None else _real(max_iterations, "max_iterations")
    if not (0 <= it <= 2 ** 31 - 1 and it == int(it)):
        raise ValueError(f"max_iterations: expected a non-negative integer, got {max_iterations!r}")
    tol = 0.0 if tolerance is None else _real(tolerance, "tolerance")
    if not tol >= 0:
        raise ValueError(f"tolerance: expected a non-negative number, got {tolerance!r}")
    return m, int(t), int(it), tol


def _fitted(status, buf, flat):
    _check(status)
    info = FitInfo(flat)
    shape = Shape.from_slopes(info.t, info.sigma)
    return shape, info


def _fit_samples(values, width, name, weights):
    """values as a contiguous (n, width) array and weights as (n,) or None, for the fits."""
    a = _array(values, name)
    if a.ndim < 1 or a.shape[-1] != width:
        raise ValueError(f"{name}: expected an array of shape (..., {width}), got shape {a.shape}")
    a = np.ascontiguousarray(a.reshape(-1, width))
    w = None
    if weights is not None:
        w = _array(weights, "weights")
        if w.size != a.shape[0]:
            raise ValueError(f"weights: expected shape {np.shape(values)[:-1]}, got {w.shape}")
        w = np.ascontiguousarray(w.reshape(-1))
    return a, w


def fit_normals(m, weights=None, model="ellipsoid", threads=1, max_iterations=None, tolerance=None):
    """(shape, info): the maximum-likelihood shape of micro-normals m (array (..., 3), each a sample of D(m)(m.n);
    any length, only the direction counts) with optional weights (projected areas, shape (...)), in the family
    model ("ellipsoid", "anisotropic" or "isotropic"), by EM (ggx_fit_normals). Normals at or below the horizon,
    non-finite or of weight 0 are ignored and counted in info; a negative weight or fewer than 5 usable normals
    raise ValueError."""
    mm, w = _fit_samples(m, 3, "m", weights)
    md, t, it, tol = _fit_settings(model, threads, max_iterations, tolerance)
    buf = ctypes.create_string_buffer(_SHAPE_SIZE)
    flat = np.zeros(_FIT_SIZE)
    st = _fit_normals(buf, mm.ctypes.data, None if w is None else w.ctypes.data, mm.shape[0], md, t, it, tol,
                      flat.ctypes.data)
    return _fitted(st, buf, flat)


def fit_normal_cells(uv, q, weights=None, model="ellipsoid", threads=1, max_iterations=None, tolerance=None):
    """(shape, info): the shape of a quantised normal map whose texels are cells of normals (ggx_fit_normal_cells):
    uv (array (..., 2)) each texel's decoded (n_x, n_y), the centre of a square of side q (2 / 255 for 8-bit maps,
    whose levels read_surface gives as Surface.uv) holding its unit normal; the likelihood is that of the cells, so a
    lobe near the levels' spacing is not overestimated as ggx.fit_normals of the centres does. info.log_likelihood is
    the mean log P(cell); no goodness of fit (NaN). Weights, model and the rest as fit_normals."""
    a, w = _fit_samples(uv, 2, "uv", weights)
    qq = _real(q, "q")
    md, t, it, tol = _fit_settings(model, threads, max_iterations, tolerance)
    buf = ctypes.create_string_buffer(_SHAPE_SIZE)
    flat = np.zeros(_FIT_SIZE)
    st = _fit_normal_cells(buf, a.ctypes.data, None if w is None else w.ctypes.data, a.shape[0], qq, md, t, it,
                           tol, flat.ctypes.data)
    return _fitted(st, buf, flat)


def fit_heightfield(h, spacing=(1.0, 1.0), keep_tilt=False, downsample=0, model="ellipsoid", threads=1,
                    max_iterations=None, tolerance=None):
    """(shape, info): the shape of the facets of a height field h[y, x] (2D, at least 2 x 2; heights in the
    spacing's unit) with spacing (dx, dy) (ggx_fit_heightfield): both triangulations of each cell, levelled by the
    least-squares plane unless keep_tilt (then the tilt is the skew), averaged over downsample x downsample blocks
    first when downsample >= 2. Cells with a non-finite height are ignored and counted."""
    a = _array(h, "h")
    if a.ndim != 2:
        raise ValueError(f"h: expected a 2D array of heights, got shape {a.shape}")
    a = np.ascontiguousarray(a)
    sp = _array(spacing, "spacing").reshape(-1)
    if sp.shape == (1,):
        sp = np.array([sp[0], sp[0]])
    if sp.shape != (2,):
        raise ValueError(f"spacing: expected (dx, dy), got {spacing!r}")
    ds = _real(downsample, "downsample")
    if not (0 <= ds <= 2 ** 31 - 1 and ds == int(ds)):
        raise ValueError(f"downsample: expected a non-negative integer, got {downsample!r}")
    md, t, it, tol = _fit_settings(model, threads, max_iterations, tolerance)
    buf = ctypes.create_string_buffer(_SHAPE_SIZE)
    flat = np.zeros(_FIT_SIZE)
    st = _fit_heightfield(buf, a.ctypes.data, a.shape[1], a.shape[0], float(sp[0]), float(sp[1]), int(bool(keep_tilt)),
                          int(ds), md, t, it, tol, flat.ctypes.data)
    return _fitted(st, buf, flat)


Surface = collections.namedtuple("Surface", ["kind", "data", "spacing", "z_scale", "weights", "bits", "uv"],
                                 defaults=(None,))
Surface.__doc__ = """A measured surface (read_surface): kind "heights" (data (ny, nx)) or "normals" (data (ny, nx, 3),
or (n, 3) for a CSV list); spacing (dx, dy) where the file gives it, else None; z_scale, the factor that brings the
file's heights into the spacing's unit, where the file says (else None); weights (n,) of a CSV list, else None; bits
8 or 16 for PNG, else 0; uv (ny, nx, 2) for a PNG normal map, each texel's decoded red and green (the centre of its
cell of normals for fit_normal_cells, q = 2 / (2**bits - 1)), else None."""


def read_surface(path, kind="heights", y_down=False):
    """A height field or normals from a file, by the readers of the ggx command (.x3p, .gsf, .txt/.asc, .xyz, .png,
    .exr; normals from .png/.exr normal maps or .csv lists): kind "heights" or "normals"; y_down for DirectX normal
    maps (each texel at its level: bits says the quantisation). A malformed or unreadable file
    raises ValueError with the reader's one-line reason."""
    want = _choice(kind, {"heights": 0, "normals": 1}, "kind")
    meta = np.zeros(9)
    err = ctypes.create_string_buffer(600)
    h = _surface_read(os.fsencode(os.fspath(path)), want, int(bool(y_down)),
                      meta.ctypes.data, err, 600)
    if not h:
        raise ValueError(err.value.decode(errors="replace"))
    try:
        nx, ny = int(meta[0]), int(meta[1])
        normals = bool(meta[7])
        data = np.empty((ny, nx, 3) if normals else (ny, nx))
        w = np.empty(nx * ny) if meta[8] else None
        _surface_copy(h, data.ctypes.data, None if w is None else w.ctypes.data)
        uv = np.empty((ny, nx, 2)) if _surface_uv(h, None) else None
        if uv is not None:
            _surface_uv(h, uv.ctypes.data)
    finally:
        _surface_close(h)
    if normals and ny == 1:
        data = data.reshape(nx, 3)
    spacing = (float(meta[2]), float(meta[3])) if meta[2] > 0 else None
    return Surface("normals" if normals else "heights", data, spacing, float(meta[4]) if meta[4] > 0 else None, w,
                   int(meta[5]), uv)


# ---- images of the material (libs/render/render.h, docs/design/render.md) ----

_render = _proto("ggxpy_render", _i, _vp, _vp, ctypes.c_char_p, _i, _i, _i, ctypes.c_char_p, _vp, _d, _i, _i, _i,
                 _i, _i, ctypes.c_ulonglong, _i, _i, _vp, _vp, ctypes.c_char_p, _sz)


def render(shape, fresnel=None, scene="sphere", light="sky", spp=64, size=(256, 256), compensate=False,
           sampler=None, strategy="mis", depth=32, seed=1, threads=None, jitter=True, variance=False):
    """The image `ggx render` makes, as a float32 array (height, width, 3) of linear RGB radiance, the top row first.

    shape: a ggx.Shape; fresnel: a ggx.Fresnel or None (F = 1), Fresnel.dielectric(eta) for rough glass;
    scene "sphere" or "plane"; light "sky" (the built-in sky), "white" (the furnace, L = 1), a path to an OpenEXR,
    .hdr or PFM latitude-longitude environment, or ("point", theta, phi[, E]) for a distant light from those angles
    (radians, world frame) of irradiance E (default 1); size (width, height); sampler a registry name (None:
    brdf-bounded; the glass always uses bsdf); strategy "mis", "light" or "bsdf"; threads None for the processors
    online (the image does not depend on it); jitter False puts every sample at its pixel's centre. With
    variance=True also returns the variance of each pixel's mean. Bad arguments raise ValueError with the
    renderer's one-line reason."""
    s, f = _shape(shape), _fresnel(fresnel)
    w, h = (int(size), int(size)) if np.ndim(size) == 0 else (int(size[0]), int(size[1]))
    for v, what in ((w, "width"), (h, "height"), (spp, "spp"), (depth, "depth")):
        if not (1 <= int(v) <= 1 << 20):
            raise ValueError(f"{what}: {v} is not from 1 to 2^20")
    if w * h > 1 << 26:
        raise ValueError(f"size: {w} x {h} pixels is too large")
    scene_id = _choice(scene, {"sphere": 0, "plane": 1}, "scene")
    strategy_id = _choice(strategy, {"mis": 0, "light": 1, "bsdf": 2}, "strategy")
    direction, irradiance, path = np.array([0.0, 0.0, 1.0]), 1.0, None
    if isinstance(light, str) and light in ("sky", "white"):
        light_id = 0 if light == "sky" else 1
    elif isinstance(light, (tuple, list)) and len(light) in (3, 4) and light[0] == "point":
        th, ph = float(light[1]), float(light[2])
        irradiance = float(light[3]) if len(light) == 4 else 1.0
        direction = np.array([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)])
        if not (np.all(np.isfinite(direction)) and irradiance >= 0):
            raise ValueError(f"light: {light!r} needs finite angles and an irradiance >= 0")
        light_id = 3
    elif isinstance(light, (str, bytes, os.PathLike)):
        light_id, path = 2, os.fsencode(os.fspath(light))
    else:
        raise ValueError(f"light: expected 'sky', 'white', a path or ('point', theta, phi[, E]), got {light!r}")
    if threads is None:
        threads = os.cpu_count() or 1
    if not (1 <= int(threads) <= 256):
        raise ValueError(f"threads: {threads} is not from 1 to 256")
    img = np.empty((h, w, 3), dtype=np.float32)
    var = np.empty((h, w, 3), dtype=np.float32) if variance else None
    err = ctypes.create_string_buffer(600)
    rc = _render(s._buf, f._buf, None if sampler is None else str(sampler).encode(), int(bool(compensate)), scene_id,
                 light_id, path, direction.ctypes.data, irradiance, strategy_id, w, h, int(spp), int(depth),
                 int(seed) & (2 ** 64 - 1), int(threads), int(bool(jitter)), img.ctypes.data,
                 None if var is None else var.ctypes.data, err, 600)
    if rc != 0:
        raise ValueError(err.value.decode(errors="replace"))
    return (img, var) if variance else img


# --- Normal-map filtering (ggx_filter.h) ---------------------------------------------------------------------------

class _Vec3(ctypes.Structure):
    _fields_ = [("x", _d), ("y", _d), ("z", _d)]


class _FilterOptions(ctypes.Structure):
    _fields_ = [("max_iterations", _i), ("tolerance", _d), ("radial_nodes", _i), ("angular_nodes", _i),
                ("threads", _i)]


class _FilterInfo(ctypes.Structure):
    _fields_ = [("iterations", _i), ("converged", _i), ("log_likelihood", _d)]


_texel_lobe = _proto("ggx_texel_lobe", _i, _vp, _Vec3, _d, _d, _d)
_filter_lobes = _proto("ggx_filter_lobes", _i, _vp, _vp, _vp, _sz, ctypes.POINTER(_FilterOptions),
                       ctypes.POINTER(_FilterInfo))
_filter_kl = _proto("ggx_filter_kl", _i, _vp, _vp, _vp, _sz, ctypes.POINTER(_FilterOptions), ctypes.POINTER(_d))


def texel_lobe(normal, alpha_x, alpha_y=None, phi=0.0):
    """The lobe of one normal-map texel (ggx_texel_lobe): GGX of roughness (alpha_x, alpha_y; alpha_y defaults to
    alpha_x) with its x axis at phi (radians) in the tangent plane, translated in slope space to the slope of the
    texel's normal (any length, n.z > 0): a skewed ellipsoid where the normal is tilted."""
    n = _array(normal, "normal").reshape(-1)
    if n.shape != (3,):
        raise ValueError(f"normal: expected 3 numbers, got shape {np.shape(normal)}")
    ax = _real(alpha_x, "alpha_x")
    ay = ax if alpha_y is None else _real(alpha_y, "alpha_y")
    ph = _real(phi, "phi")
    probe = ctypes.create_string_buffer(_SHAPE_SIZE)
    v = _Vec3(float(n[0]), float(n[1]), float(n[2]))
    _check(_texel_lobe(probe, v, ax, ay, ph))
    t, sg = np.zeros(2), np.zeros(3)
    _check(_shape_slopes(probe, t.ctypes.data, sg.ctypes.data))
    return Shape.from_slopes(t, sg)


def _lobes(lobes, weights):
    """The lobes (a sequence of ggx.Shape) as one buffer of shapes, and the weights as a float64 array or None."""
    shapes = list(lobes) if not isinstance(lobes, Shape) else [lobes]
    if not shapes:
        raise ValueError("lobes: expected at least one ggx.Shape")
    buf = ctypes.create_string_buffer(b"".join(_shape(x)._buf.raw for x in shapes), _SHAPE_SIZE * len(shapes))
    w = None
    if weights is not None:
        w = np.ascontiguousarray(_array(weights, "weights").reshape(-1))
        if w.size != len(shapes):
            raise ValueError(f"weights: expected {len(shapes)} weights, got {w.size}")
    return buf, len(shapes), w


def _filter_options(max_iterations, tolerance, nodes, fast=False):
    o = _FilterOptions(0, 0.0, 0, 0, 0)
    if fast:  # ggx_filter_options_fast: one EM step over 2 x 4 nodes, unless these are given
        _check(_filter_options_fast(ctypes.byref(o)))
    if max_iterations is not None:
        o.max_iterations = int(max_iterations)
    if tolerance is not None:
        o.tolerance = _real(tolerance, "tolerance")
    if nodes is not None:
        if len(nodes) != 2:
            raise ValueError(f"nodes: expected (radial, angular), got {nodes!r}")
        o.radial_nodes, o.angular_nodes = int(nodes[0]), int(nodes[1])
    return o


def filter_lobes(lobes, weights=None, max_iterations=None, tolerance=None, nodes=None):
    """(shape, info): the one ellipsoid closest to the mixture of lobes (a sequence of ggx.Shape, such as
    texel_lobe's of a footprint's texels) with optional relative weights, the least KL divergence from it
    (ggx_filter_lobes, by EM). nodes = (radial, angular) sets each lobe's quadrature (default 8 x 16). info is a
    dict: iterations, converged, log_likelihood (the mixture's expected log P22 of the result)."""
    buf, n, w = _lobes(lobes, weights)
    o = _filter_options(max_iterations, tolerance, nodes)
    out = ctypes.create_string_buffer(_SHAPE_SIZE)
    info = _FilterInfo(0, 0, 0.0)
    _check(_filter_lobes(out, buf, None if w is None else w.ctypes.data, n, ctypes.byref(o), ctypes.byref(info)))
    t, sg = np.zeros(2), np.zeros(3)
    _check(_shape_slopes(out, t.ctypes.data, sg.ctypes.data))
    return Shape.from_slopes(t, sg), {"iterations": info.iterations, "converged": bool(info.converged),
                                      "log_likelihood": info.log_likelihood}


def filter_kl(shape, lobes, weights=None, nodes=None):
    """KL(mixture || shape) in nats (ggx_filter_kl): how far shape is from the mixture of lobes, by each lobe's
    quadrature (nodes as in filter_lobes)."""
    buf, n, w = _lobes(lobes, weights)
    o = _filter_options(None, None, nodes)
    kl = _d(0.0)
    _check(_filter_kl(_shape(shape)._buf, buf, None if w is None else w.ctypes.data, n, ctypes.byref(o),
                      ctypes.byref(kl)))
    return kl.value


_filter_downsample = _proto("ggx_filter_downsample", _i, _vp, _vp, _vp, _vp, _sz, _sz, ctypes.POINTER(_FilterOptions))
_filter_options_fast = _proto("ggx_filter_options_fast", _i, ctypes.POINTER(_FilterOptions))
_texel_lobes = _proto("ggx_texel_lobes", _i, _vp, _vp, _vp, _sz, _d, _d, _d, _vp)
_texel_lobes_roughness = _proto("ggx_texel_lobes_roughness", _i, _vp, _vp, _vp, _vp, _vp, _sz, _d, _vp)

def mipmap(normal_map, alpha, alpha_y=None, threads=1, max_iterations=None, tolerance=None, nodes=None, fast=False):
    """The mip chain of a tangent-space normal map (array (h, w, 3) of normals, any length) of base roughness alpha
    (alpha_y along y, default alpha): a list of (lobes, weights) per level from the full size down to 1 x 1, lobes
    an array (h, w, 5) of each texel's slope location and scale (t_x, t_y, sigma_xx, sigma_xy, sigma_yy;
    Shape.from_slopes takes them) and weights (h, w) the texels behind each texel. alpha (and alpha_y) may be a
    number or a roughness map, an array (h, w): ggx_texel_lobes_roughness (0 raised to 1e-4; a negative, NaN or
    infinite value rejects its texel). Level 0 is ggx_texel_lobes of the normals: a normal that is not finite or
    not above the tangent plane is rejected (weight 0). Each coarser level is ggx_filter_downsample of the one
    above (boxes of 2 x 2, cut at an odd last column or row); options as filter_lobes, threads splitting the rows;
    fast=True: ggx_filter.h's fast mode (one EM step over 2 x 4 nodes), unless max_iterations or nodes say
    otherwise."""
    a = _array(normal_map, "normal_map")
    if a.ndim != 3 or a.shape[2] != 3 or a.shape[0] < 1 or a.shape[1] < 1:
        raise ValueError(f"normal_map: expected an array (h, w, 3) of normals, got shape {a.shape}")
    h, w = a.shape[0], a.shape[1]
    n = np.ascontiguousarray(a.reshape(-1, 3), dtype=np.float64)
    lobes, weights = np.zeros((h * w, 5)), np.zeros(h * w)
    if np.ndim(alpha) == 0 and (alpha_y is None or np.ndim(alpha_y) == 0):
        ax = _real(alpha, "alpha")
        ay = ax if alpha_y is None else _real(alpha_y, "alpha_y")
        _check(_texel_lobes(lobes.ctypes.data, weights.ctypes.data, n.ctypes.data, h * w, ax, ay, 0.0, None))
    else:
        if alpha is None:
            raise ValueError("alpha: a number or a roughness map (h, w) is required")
        maps = []
        for name, m in (("alpha", alpha), ("alpha_y", alpha_y)):
            if m is None:
                maps.append(None)
                continue
            m = np.broadcast_to(np.asarray(m, dtype=np.float64), (h, w)) if np.ndim(m) == 0 else np.asarray(m)
            if m.shape != (h, w):
                raise ValueError(f"{name}: a roughness map of shape {m.shape}, the normal map is {(h, w)}")
            maps.append(np.ascontiguousarray(m, dtype=np.float64).reshape(-1))
        _check(_texel_lobes_roughness(lobes.ctypes.data, weights.ctypes.data, n.ctypes.data, maps[0].ctypes.data,
                                      None if maps[1] is None else maps[1].ctypes.data, h * w, 0.0, None))
    o = _filter_options(max_iterations, tolerance, nodes, fast)
    o.threads = int(threads)
    chain = [(lobes.reshape(h, w, 5), weights.reshape(h, w))]
    while h > 1 or w > 1:
        h2, w2 = (h + 1) // 2, (w + 1) // 2
        out, wo = np.zeros((h2 * w2, 5)), np.zeros(h2 * w2)
        src, ws = np.ascontiguousarray(chain[-1][0]), np.ascontiguousarray(chain[-1][1])
        _check(_filter_downsample(out.ctypes.data, wo.ctypes.data, src.ctypes.data, ws.ctypes.data, w, h,
                                  ctypes.byref(o)))
        chain.append((out.reshape(h2, w2, 5), wo.reshape(h2, w2)))
        h, w = h2, w2
    return chain
