"""Albedo: the directional and average albedo by quadrature, the shipped tables, and Energy, a shape's albedo table
with Kulla-Conty energy compensation."""

import ctypes
import weakref

import numpy as np

from ._evaluate import _eval
from ._native import _Args, _as, _call, _check, _choice, _d, _fn, _i, _inp, _proto, _ptr, _real, _scalar, _sz, _vp
from ._sample import BrdfSample
from ._shape import _fresnel, _shape

# The native loops (python/src/native.c).
_loop_bsdf_albedo = _proto("ggxpy_bsdf_albedo", None, _vp, _d, _sz, _inp, _vp, _vp)
_loop_iso_table = _proto("ggxpy_albedo_iso_table", None, _i, _sz, _inp, _vp)
_loop_bsdf_iso_table = _proto("ggxpy_bsdf_albedo_iso_table", None, _sz, _inp, _vp)
_loop_aniso_table = _proto("ggxpy_albedo_aniso_table", None, _sz, _inp, _vp)
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

_MASKINGS = {"separable": 0, "height-correlated": 1}


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


# --- Energy compensation -----------------------------------------------------------------------------------------

class Energy:
    """A shape's albedo table and Kulla-Conty energy compensation (ggx_energy_create; docs/design/energy.md).

    Building it takes microseconds for shapes read from the shipped tables, 3 to 7 s for other unskewed shapes and
    7 to 14 s for skewed ones; it is immutable after that and safe to share between threads. Every shape gets a
    table; where its albedo has a feature finer than the table's nodes (a sharp skewed lobe), the table's cells there
    lie above E, so the compensation loses a little energy there but never adds any. Directions need not be unit;
    fresnel None means F = 1.
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
