"""The samplers: the registry of the C library (ggx_samplers.h) read once at import, sample and pdf of any sampler by
name, its inverse, and the named wrappers for normals, reflection and the rough dielectric."""

import collections
import ctypes

import numpy as np

from ._native import (_MODES, _Args, _as, _call, _choice, _d, _dtype, _i, _inp, _proto, _ptr, _real, _run32,
                      _scalar, _sz, _vp)
from ._shape import _fresnel, _shape

# The native loops (python/src/native.c), each running the sampler of the registry it is given by index.
_loop_sampler_pdf = _proto("ggxpy_sampler_pdf", None, _i, _vp, _d, _sz, _inp, _vp)
_loop_sample = _proto("ggxpy_sample", None, _i, _vp, _sz, _inp, _vp)
_loop_inverse = _proto("ggxpy_inverse", None, _i, _vp, _sz, _inp, _vp)
_loop_reject = _proto("ggxpy_sample_reject", None, _i, _vp, _sz, _inp, _vp, _vp)
_loop_direction = _proto("ggxpy_sample_direction", None, _i, _vp, _vp, _d, _i, _sz, _inp, _vp, _vp, _vp, _vp)
_loop_sample_eval = _proto("ggxpy_sample_eval", None, _i, _vp, _vp, _sz, _inp, _vp, _vp, _vp, _vp, _vp)

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
           return_trials=False, out=None):
    """Any sampler of the registry by name (samplers()).

    ndf, vndf: the normals m (..., 3) for (u1, u2) in [0, 1) (outside: clamped, NaN: 0) and view v (ignored by NDF
    samplers; pass None); the zero vector where there is no sample. rejection: the same, with each element's
    candidates drawn from a stream seeded by the bits of (u1, u2) (splitmix64), so equal inputs give equal normals;
    return_trials=True also returns the number of candidates per element. direction: a DirectionSample from the
    known direction v (u3 chooses reflection or refraction for 'bsdf'; fresnel is used by the reflection samplers,
    eta and mode by 'bsdf'). dtype=np.float32 runs batch samplers in float (ggx_batch_sample_normals,
    ggx_batch_sample_directions for 'brdf' and 'brdf-bounded'): the view is normalised in double first, u is rounded
    to float (a u below 1 that rounds to 1 becomes the largest float below 1), and a NaN or infinite u gives the zero
    vector (an invalid sample), as ggx_batch.h states; the other samplers give their float64 result rounded.
    out: the array m (normals) or the tuple (w, pdf, weight, event) (directions) to write, of the result's shapes and
    dtypes (event int8), for batch samplers in float32 and every non-rejection sampler in float64; they are returned.
    """
    s = _shape(shape)
    e = _sampler(method, _FAMILIES, s)
    dt = _dtype(dtype)
    v = _view(v, e)
    fast = dt == np.float64 or e.batch
    if out is not None and (not fast or e.family == "rejection"):
        raise ValueError(f"out: sampler '{e.name}' in {dt} makes its result in float64 first; out= is not taken")
    if e.family in ("ndf", "vndf", "rejection"):
        a = _Args((v, "v", 3), (u1, "u1", 1), (u2, "u2", 1))
        if e.family == "rejection":
            m, trials = a.out(3), a.out()
            if a.n:
                _loop_reject(e.id, s._buf, a.n, a.ins, _ptr(m), _ptr(trials))
            m = m if dt == np.float64 else m.astype(dt)
            return (m, _scalar(trials.astype(np.int64))) if return_trials else m
        m = a.out(3, dtype=dt if fast else np.float64, out=out)
        if dt == np.float32 and e.batch:
            _run32("normals", a, [m], s, sampler=e.id)
        elif a.n:
            _loop_sample(e.id, s._buf, a.n, a.ins, _ptr(m))
        return m if fast else m.astype(dt)
    f = _fresnel(fresnel)
    md = _choice(mode, _MODES, "mode")
    et = _real(eta, "eta")
    a = _Args((v, "v", 3), (u1, "u1", 1), (u2, "u2", 1), (u3, "u3", 1))
    fdt = dt if fast else np.float64
    no_event = out is not None and len(out) == 4 and out[3] is None  # sample_brdf's: the events are not wanted
    specs = [((3,), fdt), ((), fdt), ((), fdt)] + ([] if no_event else [((), np.int8)])
    w, pdf_, weight, *event = a.outs(out if not no_event else out[:3], *specs)
    event = event[0] if event else None
    if dt == np.float32 and e.batch:
        _run32("directions", a, [w, pdf_, weight, event], s, f, sampler=e.id)
    elif a.n:
        if event is None:
            event = a.out(dtype=np.int8)
        _loop_direction(e.id, s._buf, f._buf, et, md, a.n, a.ins, _ptr(w), _ptr(pdf_), _ptr(weight), _ptr(event))
    if not fast:
        w, pdf_, weight = w.astype(dt), pdf_.astype(dt), weight.astype(dt)
    if out is not None:
        return DirectionSample(w, pdf_, weight, event)
    return DirectionSample(w, _scalar(pdf_), _scalar(weight), _scalar(event))


SampleEval = collections.namedtuple("SampleEval", "w pdf weight f")
SampleEval.__doc__ = """sample_eval's result: the sampled directions w (..., 3), their pdfs, their weights
f |w.z| / pdf, and the BRDF f_r(wi, w) of each (0 for an invalid sample, whose w, pdf and weight are 0)."""


def sample_eval(shape, wi, u1, u2, fresnel=None, bounded=False, dtype=np.float64, out=None):
    """A renderer's step in one call: reflection sampling (ggx_sample_brdf, or ggx_sample_brdf_bounded) with its
    pdf and weight, and the BRDF of the sampled direction (ggx_brdf_eval), as a SampleEval (w, pdf, weight, f).
    The same values as sample_brdf and brdf(shape, wi, w); dtype=np.float32 runs the float batch API
    (ggx_batch_sample_directions, then ggx_batch_brdf on each chunk while it is in the cache). out: a tuple of 4
    arrays (w (..., 3), pdf, weight, f; of the dtype) to write instead of new ones, so that a loop allocates
    nothing."""
    s = _shape(shape)
    e = _BY_NAME["brdf-bounded" if bounded else "brdf"]
    f = _fresnel(fresnel)
    dt = _dtype(dtype)
    a = _Args((wi, "wi", 3), (u1, "u1", 1), (u2, "u2", 1))
    w, pdf_, weight, fr = a.outs(out, ((3,), dt), ((), dt), ((), dt), ((), dt))
    if dt == np.float32:
        _run32("sample_eval", a, [w, pdf_, weight, None, fr], s, f, sampler=e.id)
    elif a.n:
        event = np.empty(a.n, np.int8)
        _loop_sample_eval(e.id, s._buf, f._buf, a.n, a.ins, _ptr(w), _ptr(pdf_), _ptr(weight), _ptr(event), _ptr(fr))
    if out is not None:
        return SampleEval(w, pdf_, weight, fr)
    return SampleEval(w, _scalar(pdf_), _scalar(weight), _scalar(fr))


def _view(v, e):
    """The view for sampler e: None only for NDF samplers, which ignore it."""
    if v is None:
        if e.family != "ndf":
            raise ValueError(f"v: sampler '{e.name}' needs a view")
        return _NO_VIEW
    return v


def pdf(method, shape, v, m, eta=1.5, dtype=np.float64, out=None):
    """The density of a registry sampler (ggx_sampler_info.pdf or .pdf_direction): of the normal m for view v
    (ndf, vndf, rejection; v ignored by NDF samplers, None allowed there), or of the direction m from v (direction
    samplers; eta for 'bsdf'). dtype=np.float32 runs float kernels for the VNDF samplers' pdf (ggx_batch_pdf_vndf)
    and the reflection samplers' (the float kernels of ggx_pdf_brdf and ggx_pdf_brdf_bounded); the others give
    their float64 result rounded. out: the array to write (float64, or float32 where float kernels run)."""
    s = _shape(shape)
    e = _sampler(method, _FAMILIES, s)
    et = _real(eta, "eta")
    dt = _dtype(dtype)
    specs = [(_view(v, e), "v", 3), (m, "m", 3)]
    if dt == np.float32 and e.family in ("vndf", "rejection", "direction") and (e.family != "direction" or e.batch):
        a = _Args(*specs)
        res = a.out(dtype=np.float32, out=out)
        if e.family == "direction":
            _run32("pdf_brdf", a, [res], s, sampler=e.id)
        else:
            _run32("pdf_vndf", a, [res], s)
        return res if out is not None else _scalar(res)
    return _call(_loop_sampler_pdf, (e.id, s._buf, et), specs, dtype, out=out)


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


def sample_ndf(shape, u1, u2, method="stretch", dtype=np.float64, out=None):
    """Normals with density D(m) m.z (pdf_ndf) by an NDF sampler of the registry (default: the elliptic
    stretch, ggx_sample_ndf_stretch); out as sample's."""
    _sampler(method, ("ndf",), _shape(shape))
    return sample(method, shape, None, u1, u2, dtype=dtype, out=out)


def sample_vndf(shape, v, u1, u2, method="caps", dtype=np.float64, out=None):
    """Visible normals for view v with density pdf_vndf by a VNDF or rejection sampler of the registry (default:
    spherical caps, ggx_sample_vndf_caps); the zero vector for v.z <= 0. out as sample's."""
    _sampler(method, ("vndf", "rejection"), _shape(shape))
    return sample(method, shape, v, u1, u2, dtype=dtype, out=out)


def sample_brdf(shape, wi, u1, u2, fresnel=None, bounded=False, dtype=np.float64, out=None):
    """Reflection sampling (ggx_sample_brdf, Walter eq 47-50, or ggx_sample_brdf_bounded): a BrdfSample
    (w, pdf, weight); the weight is <= 1 (eq 52). out: a tuple (w, pdf, weight) of arrays to write."""
    name = "brdf-bounded" if bounded else "brdf"
    if out is None:
        r = sample(name, shape, wi, u1, u2, fresnel=fresnel, dtype=dtype)
        return BrdfSample(r.w, r.pdf, r.weight)
    if not isinstance(out, (tuple, list)) or len(out) != 3:
        raise ValueError(f"out: expected a tuple of 3 arrays, got {type(out).__name__}")
    r = sample(name, shape, wi, u1, u2, fresnel=fresnel, dtype=dtype, out=(*out, None))
    return BrdfSample(r.w, r.pdf, r.weight)


def pdf_brdf(shape, wi, wo, bounded=False, dtype=np.float64, out=None):
    """The pdf of sample_brdf (ggx_pdf_brdf or ggx_pdf_brdf_bounded)."""
    return pdf("brdf-bounded" if bounded else "brdf", shape, wi, wo, dtype=dtype, out=out)


def sample_bsdf(shape, eta, v, u1, u2, u3, mode="radiance", dtype=np.float64):
    """Rough-dielectric sampling (ggx_sample_bsdf): a DirectionSample from the known direction v (either side)."""
    return sample("bsdf", shape, v, u1, u2, u3, eta=eta, mode=mode, dtype=dtype)


def pdf_bsdf(shape, eta, v, w, dtype=np.float64):
    """The pdf of sample_bsdf giving w from v (ggx_pdf_bsdf)."""
    return pdf("bsdf", shape, v, w, eta=eta, dtype=dtype)
