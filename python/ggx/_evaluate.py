"""Evaluations of a shape: D, P22, the ellipsoid's curvature and areas, Lambda and the masking terms, the pdfs of
the NDF and VNDF, the BRDF and the rough-dielectric BSDF (float32 through the batch API where it has the function),
and the geometry helpers reflect and half_reflect."""

import numpy as np

from ._native import (_MODES, _Args, _as, _call, _choice, _d, _dtype, _fn, _i, _inp, _proto, _ptr, _real, _run32,
                      _scalar, _sz, _vp)
from ._shape import _fresnel, _shape

# The native loops (python/src/native.c).
_loop_s = {k: _proto("ggxpy_s_" + k, None, _vp, _vp, _sz, _inp, _vp) for k in ("v", "vv", "vvv", "dd")}
_loop_sf_vv = _proto("ggxpy_sf_vv", None, _vp, _vp, _vp, _sz, _inp, _vp)
_loop_bsdf = _proto("ggxpy_bsdf", None, _vp, _d, _i, _sz, _inp, _vp)
_loop_vv_v = _proto("ggxpy_vv_v", None, _vp, _sz, _inp, _vp)



def _eval(cname, shape, *specs, out=None):
    """A double function of the shape and of directions (width 3) or numbers (width 1), through its native loop."""
    s = _shape(shape)
    a = _Args(*specs)
    res = a.out(out=out)
    key = "".join("v" if w == 3 else "d" for _, _, w in specs)
    if a.n:
        _loop_s[key](_fn(cname), s._buf, a.n, a.ins, _ptr(res))
    return a, res


def _batch_eval(op, shape, dt, cname, *specs, fresnel=None, out=None):
    """A function that the float batch API has: the float32 path for float32, the double loop otherwise (or, for
    brdf, ggxpy_sf_vv with the Fresnel term). The result, or out when given."""
    dt = _dtype(dt)
    s = _shape(shape)
    if dt == np.float64:
        if fresnel is None:
            res = _eval(cname, s, *specs, out=out)[1]
        else:
            a = _Args(*specs)
            res = a.out(out=out)
            if a.n:
                _loop_sf_vv(_fn(cname), s._buf, fresnel._buf, a.n, a.ins, _ptr(res))
    else:
        a = _Args(*specs)
        res = a.out(dtype=np.float32, out=out)
        _run32(op, a, [res], s, fresnel)
    return res if out is not None else _scalar(res)


def ndf(shape, m, dtype=np.float64, out=None):
    """D(m) (ggx_ndf, Walter eq 1): >= 0, 0 for m.z < 0."""
    return _batch_eval("ndf", shape, dtype, "ggx_ndf", (m, "m", 3), out=out)


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


def g1(shape, u, m, dtype=np.float64, out=None):
    """Walter's masking G1(u, m) (ggx_g1, eq 6 / 32): in [0, 1]; 0 for u.z <= 0 or u.m <= 0."""
    return _batch_eval("g1", shape, dtype, "ggx_g1", (u, "u", 3), (m, "m", 3), out=out)


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


def pdf_vndf(shape, v, m, dtype=np.float64, out=None):
    """The density of visible normals D_v(m) for view v (ggx_pdf_vndf, Walter eq 33); 0 for v.z <= 0."""
    return _batch_eval("pdf_vndf", shape, dtype, "ggx_pdf_vndf", (v, "v", 3), (m, "m", 3), out=out)


def brdf(shape, wi, wo, fresnel=None, dtype=np.float64, out=None):
    """The microfacet BRDF f_r(wi, wo) (ggx_brdf_eval, Walter eq 4 with G of eq 5); fresnel None means F = 1."""
    return _batch_eval("brdf", shape, dtype, "ggx_brdf_eval", (wi, "wi", 3), (wo, "wo", 3), fresnel=_fresnel(fresnel),
                       out=out)


def bsdf(shape, eta, wi, wo, mode="radiance", dtype=np.float64):
    """The rough-dielectric BSDF (ggx_bsdf_eval, Walter 2007): eta = index below / index above; wi, wo on either
    side; mode 'radiance' or 'importance' (the adjoint)."""
    head = (_shape(shape)._buf, _real(eta, "eta"), _choice(mode, _MODES, "mode"))
    return _call(_loop_bsdf, head, [(wi, "wi", 3), (wo, "wo", 3)], dtype)


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
