"""Fits of a shape to measured micro-normals, quantised normal maps and height fields (include/ggx/ggx_fit.h),
and read_surface, the ggx command's readers of measured surfaces."""

import collections
import ctypes
import os

import numpy as np

from ._native import _array, _check, _choice, _cstring, _d, _i, _integer, _proto, _real, _sz, _vp
from ._shape import _SHAPE_SIZE, Shape

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
    covariance) and tails: {"nu", "nu_std_error", "log_likelihood", "bic", "t", "sigma", "iterations", "converged",
    "subsample"}, the Student-t slope family of free nu (GGX at nu = 2; ggx_fit_tails: nu NaN for fit_normal_cells)."""

    def __init__(self, flat):
        at, raw = 0, {}
        for name, n in _FIT_FIELDS:
            raw[name] = flat[at:at + n].copy()
            at += n
        for name, v in raw.items():
            if name.startswith(("model_", "tails_")):
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
        self.tails = {name[6:]: (v if len(v) > 1 else int(v[0]) if name == "tails_iterations"
                                 else bool(v[0]) if name in ("tails_converged", "tails_subsample") else float(v[0]))
                      for name, v in raw.items() if name.startswith("tails_")}

    def __repr__(self):
        return (f"FitInfo(best={self.best!r}, t={self.t.tolist()}, sigma={self.sigma.tolist()}, "
                f"log_likelihood={self.log_likelihood!r}, iterations={self.iterations}, converged={self.converged})")


def _fit_settings(model, threads, max_iterations, tolerance):
    m = _choice(model, _FIT_SHAPE_MODELS, "model")
    t = _integer(threads, "threads", 1, 256)
    it = 0 if max_iterations is None else _integer(max_iterations, "max_iterations", 0)
    tol = 0.0 if tolerance is None else _real(tolerance, "tolerance")
    if not tol >= 0:
        raise ValueError(f"tolerance: expected a non-negative number, got {tolerance!r}")
    return m, t, it, tol


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
    ds = _integer(downsample, "downsample", 0)
    md, t, it, tol = _fit_settings(model, threads, max_iterations, tolerance)
    buf = ctypes.create_string_buffer(_SHAPE_SIZE)
    flat = np.zeros(_FIT_SIZE)
    st = _fit_heightfield(buf, a.ctypes.data, a.shape[1], a.shape[0], float(sp[0]), float(sp[1]), int(bool(keep_tilt)),
                          ds, md, t, it, tol, flat.ctypes.data)
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
    h = _surface_read(_cstring(path, "path", path=True), want, int(bool(y_down)),
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
