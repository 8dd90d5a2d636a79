"""Normal-map filtering (include/ggx/ggx_filter.h): a texel's lobe, the one ellipsoid closest to a mixture of
lobes, the KL divergence between them, and the mip chain of a normal map."""

import ctypes

import numpy as np

from ._native import _array, _check, _d, _i, _integer, _proto, _real, _sz, _vp
from ._shape import _SHAPE_SIZE, Shape, _shape, _shape_slopes


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
_filter_downsample = _proto("ggx_filter_downsample", _i, _vp, _vp, _vp, _vp, _sz, _sz, ctypes.POINTER(_FilterOptions))
_filter_options_fast = _proto("ggx_filter_options_fast", _i, ctypes.POINTER(_FilterOptions))
_texel_lobes = _proto("ggx_texel_lobes", _i, _vp, _vp, _vp, _sz, _d, _d, _d, _vp)
_texel_lobes_roughness = _proto("ggx_texel_lobes_roughness", _i, _vp, _vp, _vp, _vp, _vp, _sz, _d, _vp)


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
        o.max_iterations = _integer(max_iterations, "max_iterations")
    if tolerance is not None:
        o.tolerance = _real(tolerance, "tolerance")
    if nodes is not None:
        if isinstance(nodes, (str, bytes)) or np.ndim(nodes) != 1 or len(nodes) != 2:
            raise ValueError(f"nodes: expected (radial, angular), got {nodes!r}")
        o.radial_nodes, o.angular_nodes = _integer(nodes[0], "nodes[0]"), _integer(nodes[1], "nodes[1]")
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
            m = _array(m, name)
            m = np.broadcast_to(m, (h, w)) if m.ndim == 0 else m
            if m.shape != (h, w):
                raise ValueError(f"{name}: a roughness map of shape {m.shape}, the normal map is {(h, w)}")
            maps.append(np.ascontiguousarray(m, dtype=np.float64).reshape(-1))
        _check(_texel_lobes_roughness(lobes.ctypes.data, weights.ctypes.data, n.ctypes.data, maps[0].ctypes.data,
                                      None if maps[1] is None else maps[1].ctypes.data, h * w, 0.0, None))
    o = _filter_options(max_iterations, tolerance, nodes, fast)
    o.threads = _integer(threads, "threads", 1, 256)
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
