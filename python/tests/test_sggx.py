"""The SGGX bindings (python/ggx/_sggx.py): every function against the C API bit for bit, broadcasting, dtypes and
out=, the Flakes object (errors, properties, pickling), and the samplers against their densities in a few moments."""

import ctypes
import os
import pickle

import numpy as np
import pytest

import ggx

LIB = os.environ.get("GGX_LIBGGX")


class Vec3(ctypes.Structure):
    _fields_ = [("x", ctypes.c_double), ("y", ctypes.c_double), ("z", ctypes.c_double)]


@pytest.fixture(scope="module")
def c():
    assert LIB, "GGX_LIBGGX must name libggx.so (ctest sets it)"
    lib = ctypes.CDLL(LIB)
    P, D, I = ctypes.c_void_p, ctypes.c_double, ctypes.c_int
    sig = {
        "ggx_sggx_from_matrix": (I, P, P), "ggx_sggx_from_shape": (I, P, P), "ggx_shape_ellipsoid": (I, P, D, D, D, D, D),
        "ggx_sggx_ndf": (D, P, Vec3), "ggx_sggx_sigma": (D, P, Vec3),
        "ggx_sggx_phase_specular": (D, P, Vec3, Vec3), "ggx_sggx_phase_diffuse": (D, P, Vec3, Vec3),
        "ggx_sggx_sample_vndf": (Vec3, P, Vec3, D, D), "ggx_sggx_sample_specular": (Vec3, P, Vec3, D, D),
        "ggx_sggx_sample_diffuse": (Vec3, P, Vec3, D, D, D, D),
    }
    for name, (res, *args) in sig.items():
        f = getattr(lib, name)
        f.restype, f.argtypes = res, args
    return lib


def dirs(r, n):
    d = r.normal(size=(n, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def same(a, b):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and a.tobytes() == b.tobytes()


S_SKEW = [[0.30, 0.05, -0.02], [0.05, 0.12, 0.03], [-0.02, 0.03, 1.0]]


def flakes_and_c(c, which):
    """A Flakes object and the C library's ggx_sggx of the same distribution."""
    buf = ctypes.create_string_buffer(4096)
    if which == "matrix":
        a = np.array(S_SKEW, dtype=np.float64)
        assert c.ggx_sggx_from_matrix(buf, a.ctypes.data) == 0
        return ggx.Flakes(S_SKEW), buf
    sh = ctypes.create_string_buffer(4096)
    assert c.ggx_shape_ellipsoid(sh, 0.05, 0.4, 0.3, -0.2, 0.8) == 0
    assert c.ggx_sggx_from_shape(buf, sh) == 0
    return ggx.Flakes.from_shape(ggx.Shape.ellipsoid(0.05, 0.4, 0.3, -0.2, 0.8)), buf


@pytest.mark.parametrize("which", ["matrix", "shape"])
def test_functions_match_c_bit_for_bit(c, which):
    f, g = flakes_and_c(c, which)
    r = np.random.default_rng(53)
    n = 64
    wi, wo = dirs(r, n), dirs(r, n)
    u = r.random(size=(4, n))
    v = lambda a: Vec3(*map(float, a))
    want = {
        "ndf": [c.ggx_sggx_ndf(g, v(x)) for x in wo],
        "sigma": [c.ggx_sggx_sigma(g, v(x)) for x in wi],
        "spec": [c.ggx_sggx_phase_specular(g, v(a), v(b)) for a, b in zip(wi, wo)],
        "diff": [c.ggx_sggx_phase_diffuse(g, v(a), v(b)) for a, b in zip(wi[:16], wo[:16])],
    }
    assert same(ggx.sggx_ndf(f, wo), want["ndf"])
    assert same(ggx.sggx_sigma(f, wi), want["sigma"])
    assert same(ggx.sggx_phase_specular(f, wi, wo), want["spec"])
    assert same(ggx.sggx_phase_diffuse(f, wi[:16], wo[:16]), want["diff"])
    for name, cf, k in (("vndf", c.ggx_sggx_sample_vndf, 2), ("specular", c.ggx_sggx_sample_specular, 2),
                        ("diffuse", c.ggx_sggx_sample_diffuse, 4)):
        got = getattr(ggx, "sggx_sample_" + name)(f, wi, *u[:k])
        ref = [cf(g, v(wi[i]), *map(float, u[:k, i])) for i in range(n)]
        assert same(got, [[w.x, w.y, w.z] for w in ref]), name


def test_broadcasting_dtype_and_out():
    f = ggx.Flakes(S_SKEW)
    r = np.random.default_rng(7)
    wi = dirs(r, 1)[0]
    u1, u2 = r.random((5, 4)), r.random((5, 4))
    m = ggx.sggx_sample_vndf(f, wi, u1, u2)
    assert m.shape == (5, 4, 3)
    assert np.allclose(np.linalg.norm(m, axis=-1), 1.0, atol=1e-12)
    assert np.all(m @ wi > 0)
    one = ggx.sggx_sample_vndf(f, wi, u1[2, 3], u2[2, 3])
    assert one.shape == (3,) and same(one, m[2, 3])
    # float32 rounds the float64 result; out= writes in place
    s32 = ggx.sggx_sigma(f, m, dtype=np.float32)
    assert s32.dtype == np.float32 and same(s32, ggx.sggx_sigma(f, m).astype(np.float32))
    out = np.empty((5, 4))
    assert ggx.sggx_ndf(f, m, out=out) is out and same(out, ggx.sggx_ndf(f, m))
    assert isinstance(ggx.sggx_sigma(f, wi), np.float64)
    with pytest.raises(ValueError):
        ggx.sggx_ndf(f, np.ones((4, 2)))
    with pytest.raises(ValueError):
        ggx.sggx_phase_specular(f, np.ones((4, 3)), np.ones((5, 3)))
    with pytest.raises(ValueError):
        ggx.sggx_sample_vndf(f, wi, u1, u2, dtype=np.float32, out=np.empty((5, 4, 3)))
    with pytest.raises(ValueError):
        ggx.sggx_ndf(ggx.Shape.iso(0.3), wi)


def test_flakes_object():
    f = ggx.Flakes(S_SKEW)
    assert np.allclose(f.matrix, S_SKEW, rtol=0, atol=0)
    assert np.all(np.diff(f.eigenvalues) >= 0)
    # the axes are S's unit eigenvectors: S x = lambda x for each row
    for lam, x in zip(f.eigenvalues, f.axes):
        assert np.allclose(np.array(S_SKEW) @ x, lam * x, atol=1e-14)
    with pytest.raises(ValueError):
        f.matrix[0, 0] = 2.0
    g = pickle.loads(pickle.dumps(f))
    assert g == f and hash(g) == hash(f) and same(ggx.sggx_ndf(g, [0, 0, 1]), ggx.sggx_ndf(f, [0, 0, 1]))
    assert repr(f).startswith("Flakes([[")
    # S = A^T A from a shape; sigma(n) = ||A n||
    sh = ggx.Shape.ellipsoid(0.2, 0.5, 0.3, -0.2, 0.1)
    fs = ggx.Flakes.from_shape(sh)
    a = sh.matrix
    assert np.allclose(fs.matrix, a.T @ a, rtol=1e-14, atol=0)
    assert abs(ggx.sggx_sigma(fs, [0, 0, 1]) - np.linalg.norm(a @ [0, 0, 1])) < 1e-14
    for bad, msg in (([[1, 0, 0], [0, 1, 2], [0, 2, 1]], "singular"), ([[1, 0.5, 0], [0, 1, 0], [0, 0, 1]], None),
                     ([[1, 0], [0, 1]], "3 x 3"), ([[np.nan, 0, 0], [0, 1, 0], [0, 0, 1]], None)):
        with pytest.raises(ValueError) as e:
            ggx.Flakes(bad)
        assert msg is None or msg in str(e.value)
    with pytest.raises(ValueError):
        ggx.Flakes.from_shape("not a shape")


def test_samplers_against_their_densities():
    """The mean of a function over each sampler's draws against its integral with the density (midpoint rule over
    the sphere): D_wi's first moment and both phase functions' means of wo, within 5 standard errors."""
    f = ggx.Flakes(S_SKEW)
    r = np.random.default_rng(11)
    wi = dirs(r, 1)[0]
    n = 200000
    u = r.random((4, n))
    k = 256
    z = -1 + (np.arange(k) + 0.5) * 2 / k
    ph = (np.arange(2 * k) + 0.5) * np.pi / k
    q = np.sqrt(1 - z * z)
    grid = np.stack([np.outer(q, np.cos(ph)), np.outer(q, np.sin(ph)), np.outer(z, np.ones(2 * k))], -1).reshape(-1, 3)
    dw = (2 / k) * (np.pi / k)
    vndf_pdf = np.maximum(grid @ wi, 0) * ggx.sggx_ndf(f, grid) / ggx.sggx_sigma(f, wi)
    cases = [(ggx.sggx_sample_vndf(f, wi, u[0], u[1]), vndf_pdf),
             (ggx.sggx_sample_specular(f, wi, u[0], u[1]), ggx.sggx_phase_specular(f, wi, grid)),
             (ggx.sggx_sample_diffuse(f, wi, *u), None)]
    for draws, pdf in cases:
        assert np.allclose(np.linalg.norm(draws, axis=-1), 1.0, atol=1e-12)
        if pdf is None:  # the diffuse phase function costs microseconds a call: a coarser grid
            kk = 24
            zz = -1 + (np.arange(kk) + 0.5) * 2 / kk
            pp = (np.arange(2 * kk) + 0.5) * np.pi / kk
            qq = np.sqrt(1 - zz * zz)
            g2 = np.stack([np.outer(qq, np.cos(pp)), np.outer(qq, np.sin(pp)), np.outer(zz, np.ones(2 * kk))],
                          -1).reshape(-1, 3)
            p2 = ggx.sggx_phase_diffuse(f, wi, g2)
            assert abs(p2.sum() * (2 / kk) * (np.pi / kk) - 1) < 2e-3
            want = (g2 * p2[:, None]).sum(0) * (2 / kk) * (np.pi / kk)
        else:
            assert abs(pdf.sum() * dw - 1) < 2e-3
            want = (grid * pdf[:, None]).sum(0) * dw
        mean, se = draws.mean(0), draws.std(0) / np.sqrt(n)
        assert np.all(np.abs(mean - want) < 5 * se + 2e-3), (mean, want, se)
