"""The float32 path (python/src/native.c, ggxpy_f32) and the renderer's API: float32 inputs read in place, results
equal to the C batch API's on the same floats, out= arrays, sample_eval, and threads that change no result."""
import ctypes

import numpy as np
import pytest

import ggx
from ggx._native import _lib

S = ggx.Shape.ellipsoid(0.3, 0.6, 0.4, -0.3, 0.5)
F = ggx.Fresnel.conductor(0.2, 3.9)


def upper(r, n):
    d = r.normal(size=(n, 3))
    d[:, 2] = np.abs(d[:, 2]) + 0.05
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def same(a, b):
    return np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True)


def test_float32_inputs_are_read_in_place():
    m = upper(np.random.default_rng(1), 10).astype(np.float32)
    a = ggx._Args((m, "m", 3), (m[:, 0], "u", 1))
    assert np.shares_memory(a.arrays[0], m) and a.ins[0].f32 == 1 and a.ins[0].step == 3
    # the float64 loops read the floats: the same values as the float64 copy gives
    assert same(ggx.ndf(S, m), ggx.ndf(S, m.astype(np.float64)))
    assert same(ggx.lambda_(S, m), ggx.lambda_(S, m.astype(np.float64)))
    # and the float32 path reads doubles as the floats they round to
    assert same(ggx.ndf(S, m, dtype=np.float32), ggx.ndf(S, m.astype(np.float64), dtype=np.float32))


def test_float32_path_is_the_batch_api():
    r = np.random.default_rng(2)
    n = 1500  # three chunks, the last partial
    v, m = upper(r, n).astype(np.float32), upper(r, n).astype(np.float32)
    u1, u2 = r.random(n).astype(np.float32), r.random(n).astype(np.float32)
    P = ctypes.c_void_p
    keep = [np.ascontiguousarray(a[:, k]) for a in (v, m) for k in range(3)]
    pv, pm = [P(x.ctypes.data) for x in keep[:3]], [P(x.ctypes.data) for x in keep[3:]]
    out = [np.empty(n, np.float32) for _ in range(5)]
    po = [P(x.ctypes.data) for x in out]
    sb, fb, N = ctypes.cast(S._buf, P), ctypes.cast(F._buf, P), ctypes.c_size_t(n)
    _lib.ggx_batch_pdf_vndf(po[0], N, sb, *pv, *pm)
    assert same(ggx.pdf_vndf(S, v, m, dtype=np.float32), out[0])
    _lib.ggx_batch_brdf(po[0], N, sb, fb, *pv, *pm)
    assert same(ggx.brdf(S, v, m, F, dtype=np.float32), out[0])
    brdf_id = next(e.id for e in ggx.samplers() if e.name == "brdf")
    _lib.ggx_batch_sample_directions(brdf_id, *po, N, sb, fb, *pv, P(u1.ctypes.data), P(u2.ctypes.data))
    got = ggx.sample_brdf(S, v, u1, u2, F, dtype=np.float32)
    # the views are renormalised in double: within an ulp of the unit floats given here
    assert np.max(np.abs(got.w - np.stack(out[:3], axis=-1))) <= 1e-5
    assert np.allclose(got.pdf, out[3], rtol=1e-5) and np.allclose(got.weight, out[4], atol=1e-5)


def test_out_arrays():
    r = np.random.default_rng(3)
    n = 700
    v, u1, u2 = upper(r, n), r.random(n), r.random(n)
    for dt in (np.float64, np.float32):
        vv, a, b = v.astype(dt), u1.astype(dt), u2.astype(dt)
        o = np.empty(n, dt)
        assert ggx.pdf_vndf(S, vv, vv, dtype=dt, out=o) is o and same(o, ggx.pdf_vndf(S, vv, vv, dtype=dt))
        assert ggx.ndf(S, vv, dtype=dt, out=o) is o and same(o, ggx.ndf(S, vv, dtype=dt))
        assert ggx.pdf_brdf(S, vv, vv[::-1], dtype=dt, out=o) is o and same(o, ggx.pdf_brdf(S, vv, vv[::-1], dtype=dt))
        m = np.empty((n, 3), dt)
        assert ggx.sample_vndf(S, vv, a, b, dtype=dt, out=m) is m and same(m, ggx.sample_vndf(S, vv, a, b, dtype=dt))
        outs = (np.empty((n, 3), dt), np.empty(n, dt), np.empty(n, dt))
        got, ref = ggx.sample_brdf(S, vv, a, b, F, dtype=dt, out=outs), ggx.sample_brdf(S, vv, a, b, F, dtype=dt)
        assert all(x is y for x, y in zip(got, outs)) and all(same(x, y) for x, y in zip(got, ref))
        outs4 = outs + (np.empty(n, dt),)
        got = ggx.sample_eval(S, vv, a, b, F, dtype=dt, out=outs4)
        assert all(x is y for x, y in zip(got, outs4))
        assert all(same(x, y) for x, y in zip(got, ggx.sample_eval(S, vv, a, b, F, dtype=dt)))
    o = np.empty(n)
    for bad in (np.empty(n, np.float32), np.empty(n + 1), np.empty(2 * n)[::2], o.reshape(1, n), [0.0] * n):
        with pytest.raises(ValueError, match="out"):
            ggx.ndf(S, v, out=bad)
    with pytest.raises(ValueError, match="memory"):
        ggx.sample_vndf(S, v, u1, u2, out=v)
    with pytest.raises(ValueError, match="out"):
        ggx.sample_brdf(S, v, u1, u2, out=(np.empty((n, 3)), o, o))  # pdf and weight the same array
    with pytest.raises(ValueError, match="out"):
        ggx.pdf("bsdf", S, v, v, dtype=np.float32, out=np.empty(n, np.float32))  # rounded from float64: no out=


def test_sample_eval():
    r = np.random.default_rng(4)
    n = 2000
    v, u1, u2 = upper(r, n), r.random(n), r.random(n)
    for bounded in (False, True):
        e = ggx.sample_eval(S, v, u1, u2, F, bounded=bounded)
        b = ggx.sample_brdf(S, v, u1, u2, F, bounded=bounded)
        assert same(e.w, b.w) and same(e.pdf, b.pdf) and same(e.weight, b.weight)
        assert same(e.f, ggx.brdf(S, v, b.w, F))  # bit for bit the C API's
        e32 = ggx.sample_eval(S, v, u1, u2, F, bounded=bounded, dtype=np.float32)
        b32 = ggx.sample_brdf(S, v, u1, u2, F, bounded=bounded, dtype=np.float32)
        assert all(x.dtype == np.float32 for x in e32)
        assert same(e32.w, b32.w) and same(e32.pdf, b32.pdf) and same(e32.weight, b32.weight)
        ok = (e.pdf > 0) & (e32.pdf > 0)
        assert np.mean(ok) > 0.5 and np.max(np.abs(e32.f[ok] / e.f[ok] - 1)) <= 1e-4
        assert np.all(e32.f[e32.pdf == 0] == 0)
    one = ggx.sample_eval(S, [0, 0, 1], 0.3, 0.6)
    assert one.w.shape == (3,) and np.ndim(one.f) == 0


def test_threads_change_no_result():
    r = np.random.default_rng(5)
    n = 70_001  # above the threshold of the threaded path
    v = upper(r, n).astype(np.float32)
    u1, u2 = r.random(n), r.random(n)
    calls = [lambda: ggx.sample_eval(S, v, u1, u2, F, dtype=np.float32), lambda: ggx.ndf(S, v, dtype=np.float32),
             lambda: ggx.sample_vndf(S, v, u1, u2, dtype=np.float32)]
    one = [c() for c in calls]
    try:
        ggx.set_batch_threads(3)
        three = [c() for c in calls]
    finally:
        ggx.set_batch_threads(1)
    for a, b in zip(one, three):
        for x, y in zip(a if isinstance(a, tuple) else (a,), b if isinstance(b, tuple) else (b,)):
            assert same(x, y)


def test_fresnel_indices_beyond_float():
    """A conductor or dielectric index beyond float's range (or far from 1 in double) keeps F near 1 in both paths:
    the float path is not 0 where float cannot hold eta or k, and the double path not 0 where eta^2 k^2 overflows."""
    r = np.random.default_rng(5)
    v, m = upper(r, 600), upper(r, 600)
    for f in (ggx.Fresnel.conductor(1e200, 1e200), ggx.Fresnel.conductor(0.5, 1e160),
              ggx.Fresnel.conductor(1e-200, 0.0), ggx.Fresnel.dielectric(1e300), ggx.Fresnel.dielectric(1e-300)):
        one = ggx.brdf(S, v, m, ggx.Fresnel.one())
        assert np.allclose(ggx.brdf(S, v, m, f), one, rtol=1e-12, atol=0), f
        assert np.allclose(ggx.brdf(S, v, m, f, dtype=np.float32), one, rtol=2e-5, atol=0), f
