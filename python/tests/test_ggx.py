"""The Python package against the C API and against its own promises (the docstrings of python/ggx).

The C reference is libggx.so (GGX_LIBGGX, set by ctest), called element by element through ctypes with structs by
value (libffi), a path independent of the package's native loops; both are built from the same objects, so float64
results must be equal bit for bit. Run: ctest -R python (or PYTHONPATH=<build>/python GGX_LIBGGX=<build>/libggx.so
python3 -m pytest python/tests).
"""

import ctypes
import math
import os
import pickle
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import ggx

LIB = os.environ.get("GGX_LIBGGX")


# --- The C reference ----------------------------------------------------------------------------------------------

class Vec3(ctypes.Structure):
    _fields_ = [("x", ctypes.c_double), ("y", ctypes.c_double), ("z", ctypes.c_double)]


class Vec2(ctypes.Structure):
    _fields_ = [("x", ctypes.c_double), ("y", ctypes.c_double)]


class Sample(ctypes.Structure):
    _fields_ = [("w", Vec3), ("pdf", ctypes.c_double), ("weight", ctypes.c_double), ("event", ctypes.c_int)]


@pytest.fixture(scope="module")
def c():
    assert LIB, "GGX_LIBGGX must name libggx.so (ctest sets it)"
    lib = ctypes.CDLL(LIB)
    P, D, I = ctypes.c_void_p, ctypes.c_double, ctypes.c_int
    sig = {
        "ggx_ndf": (D, P, Vec3), "ggx_pdf_ndf": (D, P, Vec3), "ggx_lambda": (D, P, Vec3),
        "ggx_g1_smith": (D, P, Vec3), "ggx_projected_area": (D, P, Vec3), "ggx_gaussian_curvature": (D, P, Vec3),
        "ggx_albedo": (D, P, Vec3), "ggx_albedo_height_correlated": (D, P, Vec3),
        "ggx_g1": (D, P, Vec3, Vec3), "ggx_g1_tilted": (D, P, Vec3, Vec3), "ggx_g1_risers": (D, P, Vec3, Vec3),
        "ggx_pdf_vndf": (D, P, Vec3, Vec3), "ggx_lune_area": (D, P, Vec3, Vec3),
        "ggx_pdf_brdf": (D, P, Vec3, Vec3), "ggx_pdf_brdf_bounded": (D, P, Vec3, Vec3),
        "ggx_pdf_brdf_bounded_azimuth": (D, P, Vec3, Vec3),
        "ggx_g2": (D, P, Vec3, Vec3, Vec3), "ggx_g2_height_correlated": (D, P, Vec3, Vec3, Vec3),
        "ggx_ndf_spherical": (D, P, D, D), "ggx_p22": (D, P, D, D),
        "ggx_brdf_eval": (D, P, P, Vec3, Vec3), "ggx_bsdf_eval": (D, P, D, Vec3, Vec3, I),
        "ggx_pdf_bsdf": (D, P, D, Vec3, Vec3),
        "ggx_bsdf_albedo": (D, P, D, Vec3, ctypes.POINTER(D), ctypes.POINTER(D)),
        "ggx_sample_brdf": (Sample, P, P, Vec3, D, D), "ggx_sample_brdf_bounded": (Sample, P, P, Vec3, D, D),
        "ggx_sample_brdf_bounded_azimuth": (Sample, P, P, Vec3, D, D),
        "ggx_sample_bsdf": (Sample, P, D, Vec3, D, D, D, I),
        "ggx_fresnel_eval": (D, P, D), "ggx_albedo_iso_table": (D, D, D, I),
        "ggx_bsdf_albedo_iso_table": (D, D, D, D), "ggx_albedo_aniso_table": (D, D, D, Vec3),
        "ggx_shape_ellipsoid": (I, P, D, D, D, D, D), "ggx_shape_matrix": (I, P, P),
        "ggx_fresnel_conductor": (I, P, D, D), "ggx_fresnel_one": (I, P),
        "ggx_energy_create": (I, P, ctypes.POINTER(P)), "ggx_energy_free": (None, P),
        "ggx_energy_albedo": (D, P, Vec3), "ggx_brdf_compensated_eval": (D, P, P, Vec3, Vec3),
        "ggx_brdf_ms_eval": (D, P, P, Vec3, Vec3), "ggx_pdf_brdf_ms": (D, P, Vec3, Vec3),
        "ggx_pdf_brdf_compensated": (D, P, P, Vec3, Vec3),
        "ggx_sample_brdf_compensated": (Sample, P, P, Vec3, D, D, D), "ggx_sample_brdf_ms": (Sample, P, P, Vec3, D, D),
    }
    # the registry's samplers of normals, by the C function each entry names (ggx_sampler_info.function)
    for e in ggx.samplers():
        if e.family == "ndf":
            sig[e.function] = (Vec3, P, D, D)
            if e.inverse:
                sig[e.function + "_inv"] = (Vec2, P, Vec3)
        elif e.family == "vndf":
            sig[e.function] = (Vec3, P, Vec3, D, D)
            if e.inverse:
                sig[e.function + "_inv"] = (Vec2, P, Vec3, Vec3)
    sig["ggx_sampler_get"] = (P, I)
    sig["ggx_sampler_find"] = (P, ctypes.c_char_p)
    sig["ggx_albedo_avg"] = (D, P)
    sig["ggx_albedo_avg_height_correlated"] = (D, P)
    sig["ggx_albedo_avg_iso_table"] = (D, D, I)
    sig["ggx_fresnel_avg"] = (D, P)
    sig["ggx_energy_albedo_avg"] = (D, P)
    for name, (res, *args) in sig.items():
        f = getattr(lib, name)
        f.restype, f.argtypes = res, args
    return lib


def cshape(c, p):
    buf = ctypes.create_string_buffer(4096)
    assert c.ggx_shape_ellipsoid(buf, *p) == 0
    return buf


def v3(a):
    return Vec3(*map(float, a))


SHAPES = [(0.15, 0.5, 0.0, 0.0, 0.0), (0.3, 0.3, 0.0, 0.0, 0.0), (0.2, 0.7, 0.0, 0.0, 0.6),
          (0.3, 0.6, 0.4, -0.3, 0.5), (0.05, 1.3, -0.5, 0.2, 2.0)]


def rng(seed=1):
    return np.random.default_rng(seed)


def upper(r, n, grazing=True):
    """n unit directions of the upper hemisphere, some exactly at n and some within 1e-9 of the horizon."""
    d = r.normal(size=(n, 3))
    d[:, 2] = np.abs(d[:, 2])
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    d[0] = (0, 0, 1)
    if grazing:
        d[1] = (math.sqrt(1 - 1e-18), 0, 1e-9)
    return d


def anywhere(r, n):
    d = r.normal(size=(n, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def same(a, b):
    """Bit-for-bit equal (0.0 and -0.0 told apart)."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and a.tobytes() == b.tobytes()


N = 200


@pytest.mark.parametrize("p", SHAPES)
def test_evaluations_match_c_bit_for_bit(c, p):
    r = rng(hash(p) % 1000)
    s, cs = ggx.Shape.ellipsoid(*p), cshape(c, p)
    a, b, m = anywhere(r, N), upper(r, N), anywhere(r, N)
    one = [("ndf", "ggx_ndf"), ("pdf_ndf", "ggx_pdf_ndf"), ("lambda_", "ggx_lambda"), ("g1_smith", "ggx_g1_smith"),
           ("projected_area", "ggx_projected_area"), ("gaussian_curvature", "ggx_gaussian_curvature")]
    for py, cn in one:
        want = [getattr(c, cn)(cs, v3(x)) for x in a]
        assert same(getattr(ggx, py)(s, a), want), py
    two = [("g1", "ggx_g1"), ("pdf_vndf", "ggx_pdf_vndf"), ("lune_area", "ggx_lune_area"),
           ("g1_tilted", "ggx_g1_tilted"), ("g1_risers", "ggx_g1_risers")]
    for py, cn in two:
        want = [getattr(c, cn)(cs, v3(x), v3(y)) for x, y in zip(b, m)]
        assert same(getattr(ggx, py)(s, b, m), want), py
    for hc, cn in ((False, "ggx_g2"), (True, "ggx_g2_height_correlated")):
        want = [getattr(c, cn)(cs, v3(x), v3(y), v3(z)) for x, y, z in zip(b, a, m)]
        assert same(ggx.g2(s, b, a, m, height_correlated=hc), want), cn
    th, ph = r.uniform(0, 1.6, N), r.uniform(-7, 7, N)
    assert same(ggx.ndf_spherical(s, th, ph), [c.ggx_ndf_spherical(cs, x, y) for x, y in zip(th, ph)])
    assert same(ggx.p22(s, ph, th), [c.ggx_p22(cs, x, y) for x, y in zip(ph, th)])
    f, cf = ggx.Fresnel.conductor(0.2, 3.9), ctypes.create_string_buffer(256)
    assert c.ggx_fresnel_conductor(cf, 0.2, 3.9) == 0
    assert same(ggx.brdf(s, b, a, f), [c.ggx_brdf_eval(cs, cf, v3(x), v3(y)) for x, y in zip(b, a)])
    one_f = ctypes.create_string_buffer(256)
    c.ggx_fresnel_one(one_f)
    assert same(ggx.brdf(s, b, a), [c.ggx_brdf_eval(cs, one_f, v3(x), v3(y)) for x, y in zip(b, a)])
    for mode, k in (("radiance", 0), ("importance", 1)):
        assert same(ggx.bsdf(s, 1.5, a, m, mode=mode), [c.ggx_bsdf_eval(cs, 1.5, v3(x), v3(y), k) for x, y in zip(a, m)])
    assert same(ggx.pdf_bsdf(s, 1.33, a, m), [c.ggx_pdf_bsdf(cs, 1.33, v3(x), v3(y)) for x, y in zip(a, m)])
    for bounded, cn in ((False, "ggx_pdf_brdf"), (True, "ggx_pdf_brdf_bounded")):
        assert same(ggx.pdf_brdf(s, b, a, bounded=bounded), [getattr(c, cn)(cs, v3(x), v3(y)) for x, y in zip(b, a)])
    cos = r.uniform(-1.5, 1.5, N)
    assert same(f(cos), [c.ggx_fresnel_eval(cf, x) for x in cos])


def test_albedo_matches_c(c):
    r = rng(7)
    for p in (SHAPES[0], SHAPES[3]):
        s, cs = ggx.Shape.ellipsoid(*p), cshape(c, p)
        v = upper(r, 4, grazing=False)
        assert same(ggx.albedo(s, v), [c.ggx_albedo(cs, v3(x)) for x in v])
        assert same(ggx.albedo(s, v, masking="height-correlated"),
                    [c.ggx_albedo_height_correlated(cs, v3(x)) for x in v])
        w = anywhere(r, 3)
        R, T = ggx.bsdf_albedo(s, 1.5, w)
        rr, tt = ctypes.c_double(), ctypes.c_double()
        for k, x in enumerate(w):
            c.ggx_bsdf_albedo(cs, 1.5, v3(x), ctypes.byref(rr), ctypes.byref(tt))
            assert R[k] == rr.value and T[k] == tt.value
    s, cs = ggx.Shape.iso(0.3), cshape(c, SHAPES[1])  # E_avg: tens of albedos for an isotropic shape, not hundreds
    assert ggx.albedo_avg(s) == c.ggx_albedo_avg(cs)
    assert ggx.albedo_avg(s, "height-correlated") == c.ggx_albedo_avg_height_correlated(cs)
    for a in (1e-3, 0.013, 0.5, 2.0, 3.0):
        for g, k in (("separable", 0), ("height-correlated", 1)):
            assert ggx.albedo_avg_iso_table(a, g) == c.ggx_albedo_avg_iso_table(a, k)
    for f, setup in ((ggx.Fresnel.conductor(0.2, 3.9), lambda b: c.ggx_fresnel_conductor(b, 0.2, 3.9)),
                     (ggx.Fresnel.one(), c.ggx_fresnel_one)):
        b = ctypes.create_string_buffer(256)
        setup(b)
        assert f.avg == c.ggx_fresnel_avg(b)
    al, mu = r.uniform(1e-3, 2, N), r.uniform(-0.1, 1.1, N)
    for g, k in (("separable", 0), ("height-correlated", 1)):
        assert same(ggx.albedo_iso_table(al, mu, g), [c.ggx_albedo_iso_table(x, y, k) for x, y in zip(al, mu)])
    # the dielectric's table, from both sides, inside its range (alpha 1e-2 to 2, eta_r 1.05 to 3 and inverse)
    al, eta, mu = r.uniform(1e-2, 2, N), r.uniform(1.05, 3, N), r.uniform(-1.1, 1.1, N)
    eta = np.where(r.uniform(size=N) < 0.5, eta, 1 / eta)
    assert same(ggx.bsdf_albedo_iso_table(al, eta, mu),
                [c.ggx_bsdf_albedo_iso_table(x, e, y) for x, e, y in zip(al, eta, mu)])
    assert ggx.bsdf_albedo_iso_table(0.3, 1.5, 0.0) == 0.0
    # the anisotropic table, inside its range (alphas 1e-2 to 2), views of any length and side
    ax, ay, v = r.uniform(1e-2, 2, N), r.uniform(1e-2, 2, N), r.normal(size=(N, 3))
    assert same(ggx.albedo_aniso_table(ax, ay, v),
                [c.ggx_albedo_aniso_table(x, y, Vec3(*map(float, w))) for x, y, w in zip(ax, ay, v)])


def test_registry_is_the_librarys(c):
    """The package's list is the C registry's: the same names at the same ids, and nothing past its end."""
    entries = ggx.samplers()
    assert [e.id for e in entries] == list(range(len(entries))) and len(entries) >= 13
    for e in entries:
        assert c.ggx_sampler_find(e.name.encode()) == c.ggx_sampler_get(e.id), e.name
        assert hasattr(c, e.function), e.function  # the function it names is exported
    assert c.ggx_sampler_get(len(entries)) is None
    assert {e.family for e in entries} == {"ndf", "vndf", "rejection", "direction"}
    assert all(e.family == "ndf" for e in ggx.samplers("ndf"))


@pytest.mark.parametrize("p", SHAPES)
def test_samplers_match_c_bit_for_bit(c, p):
    r = rng(11)
    s, cs = ggx.Shape.ellipsoid(*p), cshape(c, p)
    v = upper(r, N)
    v[2] = (0, 0, -1)  # below: the zero vector
    u1, u2 = r.random(N), r.random(N)
    u1[:4] = (0.0, 1 - 2 ** -53, 1.0, np.nan)
    u2[:4] = (1 - 2 ** -53, 0.0, -3.0, 0.5)
    for e in ggx.samplers():
        if e.domain == "unskewed" and s.kind == "skewed":
            with pytest.raises(ValueError, match="unskewed"):
                ggx.sample(e.name, s, v, u1, u2)
            continue
        if e.family == "ndf":
            fn = getattr(c, e.function)
            got = ggx.sample_ndf(s, u1, u2, method=e.name)
            want = [(q.x, q.y, q.z) for q in (fn(cs, x, y) for x, y in zip(u1, u2))]
            assert same(got, want), e.name
            assert same(ggx.pdf(e.name, s, None, got), [c.ggx_pdf_ndf(cs, v3(m)) for m in got])
        elif e.family == "vndf":
            fn = getattr(c, e.function)
            got = ggx.sample_vndf(s, v, u1, u2, method=e.name)
            want = [(q.x, q.y, q.z) for q in (fn(cs, v3(x), a, b) for x, a, b in zip(v, u1, u2))]
            assert same(got, want), e.name
            assert same(ggx.pdf(e.name, s, v, got), [c.ggx_pdf_vndf(cs, v3(x), v3(m)) for x, m in zip(v, got)])
            if e.inverse:
                inv = getattr(c, e.function + "_inv")
                uu = ggx.sample_inverse(e.name, s, v, got)
                assert same(uu, [(q.x, q.y) for q in (inv(cs, v3(x), v3(m)) for x, m in zip(v, got))]), e.name
        elif e.family == "direction":
            fr = ggx.Fresnel.conductor(0.2, 3.9)
            cf = ctypes.create_string_buffer(256)
            c.ggx_fresnel_conductor(cf, 0.2, 3.9)
            u3 = r.random(N)
            got = ggx.sample(e.name, s, v, u1, u2, u3, fresnel=fr, eta=1.5, mode="importance")
            if e.function == "ggx_sample_bsdf":  # the dielectric's signature: eta, u3 and the mode
                want = [c.ggx_sample_bsdf(cs, 1.5, v3(x), a, b, d, 1) for x, a, b, d in zip(v, u1, u2, u3)]
            else:
                want = [getattr(c, e.function)(cs, cf, v3(x), a, b) for x, a, b in zip(v, u1, u2)]
            assert same(got.w, [(q.w.x, q.w.y, q.w.z) for q in want]), e.name
            assert same(got.pdf, [q.pdf for q in want]) and same(got.weight, [q.weight for q in want]), e.name
            assert list(got.event) == [q.event for q in want], e.name
    # the stretch's inverse (an NDF sampler with one)
    m = ggx.sample_ndf(s, u1, u2)
    assert same(ggx.sample_inverse("stretch", s, None, m),
                [(q.x, q.y) for q in (c.ggx_sample_ndf_stretch_inv(cs, v3(x)) for x in m)])


def test_rejection_samplers_are_seeded_by_u():
    s = ggx.Shape.ellipsoid(*SHAPES[3])
    v = (0.5, 0.1, math.sqrt(1 - 0.26))
    r = rng(3)
    u1, u2 = r.random(1000), r.random(1000)
    for name in ("walter-v1", "walter-v2"):
        m, trials = ggx.sample_vndf(s, v, u1, u2, method=name), ggx.sample(name, s, v, u1, u2, return_trials=True)[1]
        assert same(m, ggx.sample_vndf(s, v, u1, u2, method=name))  # deterministic
        assert np.all(np.abs(np.linalg.norm(m, axis=1) - 1) < 1e-12)
        assert np.all(ggx.pdf_vndf(s, v, m) > 0) and np.all(trials >= 1)
        assert len({tuple(x) for x in m}) == 1000  # every element its own stream
        # the same (u1, u2) gives the same normal, wherever it sits in the array
        assert same(ggx.sample_vndf(s, v, u1[::-1], u2[::-1], method=name), m[::-1])


def test_energy_matches_c(c):
    p = SHAPES[0]
    s, cs = ggx.Shape.ellipsoid(*p), cshape(c, p)
    e = ggx.Energy(s)
    h = ctypes.c_void_p()
    assert c.ggx_energy_create(cs, ctypes.byref(h)) == 0
    try:
        r = rng(5)
        wi, wo = upper(r, N), upper(r, N)
        f, cf = ggx.Fresnel.conductor(0.2, 3.9), ctypes.create_string_buffer(256)
        c.ggx_fresnel_conductor(cf, 0.2, 3.9)
        assert same(e.albedo(wi), [c.ggx_energy_albedo(h, v3(x)) for x in wi])
        for py, cn in (("brdf_ms", "ggx_brdf_ms_eval"), ("brdf_compensated", "ggx_brdf_compensated_eval"),
                       ("pdf_brdf_compensated", "ggx_pdf_brdf_compensated")):
            assert same(getattr(e, py)(wi, wo, f), [getattr(c, cn)(h, cf, v3(x), v3(y)) for x, y in zip(wi, wo)]), py
        assert same(e.pdf_brdf_ms(wi, wo), [c.ggx_pdf_brdf_ms(h, v3(x), v3(y)) for x, y in zip(wi, wo)])
        u1, u2, u3 = r.random(N), r.random(N), r.random(N)
        got = e.sample_brdf_compensated(wi, u1, u2, u3, f)
        want = [c.ggx_sample_brdf_compensated(h, cf, v3(x), a, b, d) for x, a, b, d in zip(wi, u1, u2, u3)]
        assert same(got.w, [(q.w.x, q.w.y, q.w.z) for q in want]) and same(got.pdf, [q.pdf for q in want])
        got = e.sample_brdf_ms(wi, u1, u2, f)
        want = [c.ggx_sample_brdf_ms(h, cf, v3(x), a, b) for x, a, b in zip(wi, u1, u2)]
        assert same(got.w, [(q.w.x, q.w.y, q.w.z) for q in want]) and same(got.weight, [q.weight for q in want])
        assert e.albedo_avg() == c.ggx_energy_albedo_avg(h) and abs(e.albedo_avg() - ggx.albedo_avg(s)) < 1e-3
        # the table within 1e-3 of the quadrature (docstring)
        v = upper(r, 12, grazing=False)
        v = v[v[:, 2] >= 0.0175]
        assert np.max(np.abs(e.albedo(v) - ggx.albedo(s, v))) < 1e-3
    finally:
        c.ggx_energy_free(h)


# --- Shapes, Fresnel terms, errors -------------------------------------------------------------------------------

def test_shapes():
    s = ggx.Shape.ellipsoid(0.3, 0.6, 0.4, -0.3, 0.5)
    # the keyword names
    assert ggx.Shape.ellipsoid(ax=0.3, ay=0.6, theta_x=0.4, theta_y=-0.3, theta_z=0.5) == s
    assert ggx.Shape.aniso(ax=0.1, ay=0.2) == ggx.Shape.aniso(0.1, 0.2) and ggx.Shape.iso(alpha=0.2).kind == "diagonal"
    assert s.kind == "skewed" and repr(s).startswith("Shape.ellipsoid(0.3, 0.6")
    assert ggx.Shape.iso(0.3).kind == "diagonal" and ggx.Shape.aniso(0.1, 0.2).kind == "diagonal"
    assert ggx.Shape.ellipsoid(0.1, 0.2, theta_z=0.7).kind == "unskewed"
    A = s.matrix
    assert A.shape == (3, 3) and not A.flags.writeable
    # A = S R: the rows of A / (ax, ay, 1) are orthonormal, det R = 1
    R = A / np.array([0.3, 0.6, 1.0])[:, None]
    assert np.allclose(R @ R.T, np.eye(3), rtol=0, atol=1e-15) and abs(np.linalg.det(R) - 1) < 1e-15
    with pytest.raises(ValueError):
        A[0, 0] = 1
    with pytest.raises(AttributeError):
        s.matrix = np.eye(3)
    # the canonical matrix: A n along +z, the same distribution as the given A
    Q = s.canonical_matrix
    assert abs(Q[0, 2]) < 1e-15 and abs(Q[1, 2]) < 1e-15 and Q[2, 2] > 0
    t = ggx.Shape.matrix(A)
    assert t.kind == "skewed" and np.array_equal(t.matrix, A) and repr(t).startswith("Shape.matrix([[")
    m = anywhere(rng(2), 100)
    assert np.allclose(ggx.ndf(t, m), ggx.ndf(s, m), rtol=1e-12, atol=0)
    assert np.allclose(ggx.ndf(ggx.Shape.matrix(-2.5 * A), m), ggx.ndf(t, m), rtol=1e-12, atol=0)
    for x in (s, t, ggx.Shape.iso(0.2), ggx.Shape.aniso(0.1, 0.3)):
        y = pickle.loads(pickle.dumps(x))
        assert y == x and repr(y) == repr(x) and same(ggx.ndf(y, m), ggx.ndf(x, m))
    assert ggx.Shape.iso(1e-7).matrix[0, 0] == 1e-4  # raised to GGX_ALPHA_MIN, as the library does
    with pytest.raises(TypeError):
        ggx.Shape()


@pytest.mark.parametrize("make,status", [
    (lambda: ggx.Shape.iso(0.0), 3), (lambda: ggx.Shape.iso(-1), 3), (lambda: ggx.Shape.iso(2e4), 3),
    (lambda: ggx.Shape.iso(float("nan")), 2), (lambda: ggx.Shape.aniso(0.1, float("inf")), 2),
    (lambda: ggx.Shape.ellipsoid(0.1, 0.1, 1.6), 4), (lambda: ggx.Shape.ellipsoid(0.1, 0.1, 0, -1.6), 4),
    (lambda: ggx.Shape.ellipsoid(0.1, 0.1, theta_z=float("nan")), 2),
    (lambda: ggx.Shape.aniso(1e-4, 1e4), 5), (lambda: ggx.Shape.matrix([[1, 2, 3], [2, 4, 6], [0, 0, 1]]), 5),
    (lambda: ggx.Shape.matrix(np.eye(3) * 1e60), 7), (lambda: ggx.Shape.matrix([[1, 0, 0], [0, np.nan, 0], [0, 0, 1]]), 2),
    (lambda: ggx.Fresnel.dielectric(0.0), 6), (lambda: ggx.Fresnel.conductor(-1, 0), 6),
    (lambda: ggx.Fresnel.schlick(1.5), 7), (lambda: ggx.Energy(ggx.Shape.iso(0.3)).albedo([0, 0]), None),
])
def test_errors_carry_the_librarys_message(make, status):
    with pytest.raises(ValueError) as err:
        make()
    if status is not None:
        assert str(err.value) == ggx.status_message(status)


def each_raises_value_error(cases):
    """Every call in cases raises ValueError; a failure names the first that does not."""
    for k, f in enumerate(cases):
        try:
            f()
        except ValueError:
            continue
        pytest.fail(f"case {k} did not raise ValueError")


def test_other_errors():
    s = ggx.Shape.iso(0.3)
    cases = [
        lambda: ggx.ndf(s, [1, 2]), lambda: ggx.ndf(s, 0.5), lambda: ggx.ndf(s, np.zeros((4, 2))),
        lambda: ggx.g1(s, np.zeros((4, 3)), np.zeros((5, 3))), lambda: ggx.ndf(s, ["a", "b", "c"]),
        lambda: ggx.ndf(s, [1j, 0, 1]), lambda: ggx.ndf("shape", [0, 0, 1]), lambda: ggx.ndf(s, [0, 0, 1], dtype="int32"),
        lambda: ggx.ndf(s, [0, 0, 1], dtype="nonsense"), lambda: ggx.sample_vndf(s, [0, 0, 1], 0.5, 0.5, "nope"),
        lambda: ggx.sample_vndf(s, [0, 0, 1], 0.5, 0.5, "stretch"), lambda: ggx.sample_ndf(s, 0.5, 0.5, "caps"),
        lambda: ggx.sample("caps", s, None, 0.5, 0.5), lambda: ggx.sample_inverse("heitz", s, [0, 0, 1], [[0, 0]]),
        lambda: ggx.sample_inverse("ellipse", s, None, [0, 0, 1]), lambda: ggx.bsdf(s, 1.5, [0, 0, 1], [0, 0, -1], "x"),
        lambda: ggx.albedo(s, [0, 0, 1], masking="smith"), lambda: ggx.brdf(s, [0, 0, 1], [0, 0, 1], fresnel=0.5),
        lambda: ggx.Shape.iso("rough"), lambda: ggx.Shape.iso([0.1, 0.2]), lambda: ggx.Shape.matrix(np.eye(2)),
        lambda: ggx.Fresnel.schlick(None), lambda: ggx.set_batch_threads(0), lambda: ggx.set_batch_threads(1.5),
        lambda: ggx.samplers("nonsense"), lambda: ggx.Energy("shape"),
    ]
    each_raises_value_error(cases)


def test_fresnel():
    f = ggx.Fresnel.schlick(0.04)
    assert repr(f) == "Fresnel.schlick(0.04)"
    assert f(1.0) == pytest.approx(0.04, rel=1e-15) and f(0.0) == 1.0
    assert f.avg == pytest.approx(0.04 + 0.96 / 21, rel=1e-14)
    assert ggx.Fresnel.one()(np.linspace(0, 1, 5)).tolist() == [1.0] * 5
    d = ggx.Fresnel.dielectric(1.5)
    assert d(1.0) == pytest.approx(0.04, rel=1e-12)  # ((1.5 - 1) / (1.5 + 1))^2
    assert ggx.Fresnel.dielectric(1 / 1.5)(0.1) == 1.0  # total internal reflection


# --- Arrays: broadcasting, layouts, dtypes, no NaN ----------------------------------------------------------------

def test_broadcasting_and_layouts():
    s = ggx.Shape.ellipsoid(*SHAPES[3])
    r = rng(4)
    v = upper(r, 4).reshape(4, 1, 3)
    m = upper(r, 5)
    got = ggx.pdf_vndf(s, v, m)
    assert got.shape == (4, 5)
    for i in range(4):
        for j in range(5):
            assert got[i, j] == ggx.pdf_vndf(s, v[i, 0], m[j])
    assert isinstance(ggx.ndf(s, [0, 0, 1]), np.float64) and np.ndim(ggx.ndf(s, [0, 0, 1])) == 0
    assert ggx.ndf(s, np.zeros((0, 3))).shape == (0,)
    assert ggx.sample_vndf(s, v, 0.5, np.zeros((0,))).shape == (4, 0, 3)
    assert ggx.sample_vndf(s, [0, 0, 1], 0.25, 0.5).shape == (3,)
    assert ggx.sample_vndf(s, [0, 0, 1], [[0.25]], [0.5, 0.7]).shape == (1, 2, 3)
    # non-contiguous and transposed inputs give the contiguous results
    big = upper(r, 60)
    strided = np.asfortranarray(big)[::2]
    assert same(ggx.ndf(s, strided), ggx.ndf(s, np.ascontiguousarray(strided)))
    soa = np.ascontiguousarray(big.T)  # (3, 60): a view of it transposed is (60, 3) with strides (8, 480)
    assert same(ggx.g1(s, soa.T, big[::-1]), ggx.g1(s, big, big[::-1]))
    u = r.random((60,))
    assert same(ggx.sample_vndf(s, big, u[::-1], u), ggx.sample_vndf(s, big, u[::-1].copy(), u))
    # integers and float32 inputs are converted to float64; lists work
    assert same(ggx.ndf(s, [[0, 0, 1]]), ggx.ndf(s, np.array([[0.0, 0.0, 1.0]])))
    m32 = big.astype(np.float32)
    assert same(ggx.ndf(s, m32), ggx.ndf(s, m32.astype(np.float64)))
    # inputs are never written
    before = big.copy()
    ggx.sample_brdf(s, big, u, u)
    assert same(big, before)


def test_float32_range():
    # absolute areas and curvatures scale with A: beyond float32's range they raise, never inf or a warning
    import warnings
    for scale, fine in ((1e-20, False), (1e20, True), (1e-3, True)):
        s = ggx.Shape.matrix(np.eye(3) * scale)
        for f, args in ((ggx.projected_area, ([0, 0, 1],)), (ggx.lune_area, ([0, 0, 1], [0, 0.6, 0.8])),
                        (ggx.gaussian_curvature, ([0, 0, 1],))):
            hi = f(s, *args)
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                if hi <= np.finfo(np.float32).max:
                    lo = f(s, *args, dtype=np.float32)
                    # rounded: relative 2^-24 for normal floats, within half the smallest subnormal below them
                    assert np.isfinite(lo) and abs(lo - hi) <= max(6e-8 * hi, 7.1e-46), f.__name__
                else:
                    with pytest.raises(ValueError, match="beyond float32's range"):
                        f(s, *args, dtype=np.float32)
        assert fine or ggx.projected_area(s, [0, 0, 1]) > 1e38  # the case of the report is among them


def test_float32_batch_path():
    r = rng(8)
    for p in SHAPES:
        s = ggx.Shape.ellipsoid(*p)
        v = upper(r, 400, grazing=False)
        v = v[v[:, 2] > 0.02]
        m = ggx.sample_vndf(s, v, r.random(len(v)), r.random(len(v)))
        ok = np.sum(m * v, axis=1) >= 0.01
        for f, args in ((ggx.ndf, (m,)), (ggx.g1, (v, m)), (ggx.pdf_vndf, (v, m)), (ggx.brdf, (v, v[::-1]))):
            lo, hi = f(s, *args, dtype=np.float32), f(s, *args)
            assert lo.dtype == np.float32 and lo.shape == hi.shape
            err = np.abs(lo - hi) / np.maximum(hi, 1e-30)
            assert np.all(err[ok if f is ggx.pdf_vndf else slice(None)] <= 2e-5), f.__name__
        u1, u2 = r.random(len(v)), r.random(len(v))
        for e in ggx.samplers():
            if not e.batch or e.family not in ("ndf", "vndf"):
                continue
            if e.domain == "unskewed" and s.kind == "skewed":
                continue
            lo = ggx.sample(e.name, s, v, u1, u2, dtype=np.float32)
            hi = ggx.sample(e.name, s, v, u1, u2)
            assert lo.dtype == np.float32 and np.max(np.abs(lo - hi)) <= 1e-4, e.name
        for bounded in (False, True):
            lo = ggx.sample_brdf(s, v, u1, u2, bounded=bounded, dtype=np.float32)
            hi = ggx.sample_brdf(s, v, u1, u2, bounded=bounded)
            both = (lo.pdf > 0) & (hi.pdf > 0)
            assert np.mean(both) > 0.5
            assert np.max(np.abs(lo.w[both] - hi.w[both])) <= 1e-4
            assert np.max(np.abs(lo.pdf[both] / hi.pdf[both] - 1)) <= 1e-4
            assert np.max(np.abs(lo.weight[both] - hi.weight[both])) <= 2e-4
            # their pdfs by the float kernels, and the VNDF samplers' pdf by the batch API's
            name = "brdf-bounded" if bounded else "brdf"
            plo, phi = ggx.pdf_brdf(s, v, hi.w, bounded=bounded, dtype=np.float32), ggx.pdf_brdf(s, v, hi.w, bounded=bounded)
            assert plo.dtype == np.float32 and same(plo, ggx.pdf(name, s, v, hi.w, dtype=np.float32))
            assert np.max(np.abs(plo[both] / phi[both] - 1)) <= 1e-4, name
        assert same(ggx.pdf("caps", s, v, m, dtype=np.float32), ggx.pdf_vndf(s, v, m, dtype=np.float32))
    # samplers without a batch loop: the float64 result, rounded
    s = ggx.Shape.ellipsoid(*SHAPES[3])
    u = upper(r, 50)
    for name in ("ellipse", "bsdf", "walter-v2"):
        lo, hi = ggx.sample(name, s, u, u[:, 0], u[:, 1], 0.5, dtype=np.float32), ggx.sample(name, s, u, u[:, 0], u[:, 1], 0.5)
        if isinstance(lo, tuple):
            assert lo.w.dtype == np.float32 and same(lo.w, hi.w.astype(np.float32)) and same(lo.pdf, hi.pdf.astype(np.float32))
        else:
            assert lo.dtype == np.float32 and same(lo, hi.astype(np.float32)), name


def test_no_nan_for_any_input():
    r = rng(9)
    specials = np.array([0.0, -0.0, 1.0, -1.0, np.nan, np.inf, -np.inf, 1e300, -1e300, 1e-300, 5e-324])
    d = np.concatenate([r.choice(specials, size=(300, 3)), r.normal(size=(300, 3)) * 10.0 ** r.integers(-8, 8, (300, 1))])
    u = np.concatenate([r.choice(specials, 300), r.uniform(-2, 3, 300)])
    for p in SHAPES + [(1e-4, 1e-4, 0, 0, 0), (1e4, 1e4, 0, 0, 0), (1e-4, 2.0, 1.5, -1.5, 3.0)]:
        s = ggx.Shape.ellipsoid(*p)
        values = [ggx.ndf(s, d), ggx.g1(s, d, d[::-1]), ggx.pdf_vndf(s, d, d[::-1]), ggx.brdf(s, d, d[::-1]),
                  ggx.bsdf(s, 1.5, d, d[::-1]), ggx.lune_area(s, d, d[::-1]), ggx.ndf(s, d, dtype=np.float32),
                  ggx.pdf_vndf(s, d, d[::-1], dtype=np.float32), ggx.brdf(s, d, d[::-1], dtype=np.float32)]
        dirs = []
        for e in ggx.samplers():
            if e.domain == "unskewed" and s.kind == "skewed":
                continue
            r_ = ggx.sample(e.name, s, d, u, u[::-1], u, eta=1.5)
            if e.family == "direction":
                values += [r_.pdf, r_.weight]
                dirs.append(r_.w)
                assert np.all((r_.pdf > 0) == (r_.event > 0)), e.name
            else:
                dirs.append(r_)
            if e.batch:
                q = ggx.sample(e.name, s, d, u, u[::-1], dtype=np.float32)
                dirs.append(q.w if e.family == "direction" else q)
        assert np.all(np.isfinite(ggx.lambda_(s, d)))
        for k, o in enumerate(values):
            assert np.all(np.isfinite(o)) and np.all(o >= 0), (p, k)
        for k, o in enumerate(dirs):
            norm = np.linalg.norm(o.astype(np.float64), axis=-1)
            assert np.all((norm == 0) | (np.abs(norm - 1) < 1e-5)), (p, k)


# --- A chi-square test of sample_vndf, in numpy -------------------------------------------------------------------

def chi2_pvalue(stat, dof):
    """Upper tail of the chi-square distribution, Wilson-Hilferty: accurate to ~1e-3 in p for dof >= 30."""
    z = ((stat / dof) ** (1 / 3) - (1 - 2 / (9 * dof))) / math.sqrt(2 / (9 * dof))
    return 0.5 * math.erfc(z / math.sqrt(2))


def vndf_chi2(shape, v, m, pdf, nz=24, nphi=48, order=5):
    """Pearson's statistic of normals m against the density pdf(m) over cells of equal solid angle (uniform in
    m.z and in phi). Expected counts from an order x order Gauss-Legendre rule of pdf in each cell; cells expecting
    fewer than 5 are pooled. Returns (p-value, integral of pdf over the hemisphere)."""
    n = len(m)
    zi = np.clip((m[:, 2] * nz).astype(int), 0, nz - 1)
    pi_ = np.clip(((np.arctan2(m[:, 1], m[:, 0]) / (2 * np.pi) % 1.0) * nphi).astype(int), 0, nphi - 1)
    counts = np.bincount(zi * nphi + pi_, minlength=nz * nphi).astype(float)
    x, w = np.polynomial.legendre.leggauss(order)
    x, w = (x + 1) / 2, w / 2  # on [0, 1], weights summing to 1
    z = ((np.arange(nz)[:, None] + x) / nz).reshape(-1)
    ph = ((np.arange(nphi)[:, None] + x) / nphi * 2 * np.pi).reshape(-1)
    Z, PH = np.meshgrid(z, ph, indexing="ij")
    st = np.sqrt(1 - Z * Z)
    dens = pdf(shape, v, np.stack([st * np.cos(PH), st * np.sin(PH), Z], axis=-1))
    dens = dens.reshape(nz, order, nphi, order) * w[None, :, None, None] * w[None, None, None, :]
    cell = dens.sum(axis=(1, 3)) * (1 / nz) * (2 * np.pi / nphi)
    integral = cell.sum()
    expected = cell.reshape(-1) * n
    big = expected >= 5
    stat = np.sum((counts[big] - expected[big]) ** 2 / expected[big])
    rest_c, rest_e = counts[~big].sum(), expected[~big].sum()
    dof = int(big.sum())
    if rest_e > 0:
        stat += (rest_c - rest_e) ** 2 / rest_e
    else:
        dof -= 1
    return chi2_pvalue(stat, dof), integral


@pytest.mark.parametrize("p,view", [((0.5, 0.8, 0, 0, 0), (0.0, 0.0, 1.0)), ((0.6, 0.4, 0, 0, 0.6), (60, 20)),
                                     ((0.5, 0.7, 0.3, -0.2, 0.4), (75, 200))])
def test_sample_vndf_chi_square(p, view):
    s = ggx.Shape.ellipsoid(*p)
    if len(view) == 2:
        t, f = np.radians(view)
        view = (np.sin(t) * np.cos(f), np.sin(t) * np.sin(f), np.cos(t))
    r = rng(12)
    n = 400000
    m = ggx.sample_vndf(s, view, r.random(n), r.random(n))
    pval, integral = vndf_chi2(s, view, m, ggx.pdf_vndf)
    assert abs(integral - 1) < 1e-4, integral  # the pdf is normalised (and the quadrature good enough)
    assert pval > 1e-4, pval
    # negative control: the same normals against the density of another view must be rejected
    other = (0.0, 0.0, 1.0) if view[2] < 0.99 else (0.5, 0.0, math.sqrt(0.75))
    bad, _ = vndf_chi2(s, view, m, lambda sh, v, mm: ggx.pdf_vndf(sh, other, mm))
    assert bad < 1e-12, bad
    # and against the density of a shape 5% rougher
    rough = ggx.Shape.ellipsoid(p[0] * 1.05, p[1] * 1.05, *p[2:])
    bad, _ = vndf_chi2(s, view, m, lambda sh, v, mm: ggx.pdf_vndf(rough, v, mm))
    assert bad < 1e-12, bad


def test_million_vndf_samples_run_as_one_native_loop():
    """A million samples in one call cost far less than a million calls: the arrays go to the native loop whole. The
    bound is relative to per-element calls timed in the same run, so a loaded machine slows both alike."""
    s = ggx.Shape.ellipsoid(0.3, 0.6, 0.4, -0.3, 0.5)
    r = rng(13)
    n = 1_000_000
    v = upper(r, n)
    u1, u2 = r.random(n), r.random(n)
    best = min(_timed(lambda: ggx.sample_vndf(s, v, u1, u2)) for _ in range(3))
    best32 = min(_timed(lambda: ggx.sample_vndf(s, v, u1, u2, dtype=np.float32)) for _ in range(3))
    k = 2000
    one = min(_timed(lambda: [ggx.sample_vndf(s, v[i], u1[i], u2[i]) for i in range(k)]) for _ in range(3)) / k
    print(f"1e6 VNDF samples: {best * 1e3:.1f} ms (float64), {best32 * 1e3:.1f} ms (float32); "
          f"one call {one * 1e6:.1f} us, so 1e6 calls {one * n:.1f} s")
    assert best < one * n / 20 and best32 < one * n / 20


def _timed(f):
    t = time.perf_counter()
    f()
    return time.perf_counter() - t


def test_threads_share_shapes():
    s = ggx.Shape.ellipsoid(*SHAPES[3])
    r = rng(14)
    v, u1, u2 = upper(r, 20000), r.random(20000), r.random(20000)
    want = ggx.sample_vndf(s, v, u1, u2)
    got = [None] * 8

    def work(k):
        got[k] = ggx.sample_vndf(s, v, u1, u2)

    ts = [threading.Thread(target=work, args=(k,)) for k in range(8)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert all(same(g, want) for g in got)


def test_example_draws_the_seed_figure(tmp_path):
    example = os.path.join(os.path.dirname(__file__), "..", "examples", "seed_figures.py")
    with open(example) as fh:
        assert len(fh.read().splitlines()) < 30
    out = tmp_path / "fig.png"
    env = dict(os.environ, MPLBACKEND="Agg")
    text = subprocess.run([sys.executable, example, str(out)], check=True, timeout=120, capture_output=True,
                          text=True, env=env).stdout
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20000
    # the VNDF peaks of the seed's shape at theta_v = 75 degrees (ggx plot gives 4.106 and 3.749): the figure's data
    peaks = [float(line.split("peak ")[1].split(",")[0]) for line in text.splitlines()]
    assert peaks == [4.106, 3.749], text


def test_readme_python_block():
    readme = os.path.join(os.path.dirname(__file__), "..", "..", "README.md")
    with open(readme) as fh:
        text = fh.read()
    block = text.split("## Python", 1)[1].split("```python\n", 1)[1].split("```", 1)[0]
    out = subprocess.run([sys.executable, "-c", block], check=True, capture_output=True, text=True, timeout=60).stdout
    mean_pdf, e = map(float, out.split())
    assert 1.5 < mean_pdf < 1.7 and abs(e - 0.759274) < 1e-5  # E[pdf] = 1.583 (this seed); E(n) = 0.75927


def test_hostile_regressions():
    """What an adversarial review of the package found (each was broken before its fix)."""
    import copy
    from fractions import Fraction
    # Energy: copies share the (immutable) table; pickling rebuilds it from the shape (it used to copy the pointer)
    e = ggx.Energy(ggx.Shape.iso(0.3))
    assert copy.copy(e) is e and copy.deepcopy(e) is e
    e2 = pickle.loads(pickle.dumps(e))
    assert e2 is not e and e2.shape == e.shape and e2.albedo([0, 0, 1]) == e.albedo([0, 0, 1])
    del e, e2
    # a shape whose albedo has a feature finer than the table's nodes (anisotropy 1:200, beyond the shipped table's
    # 1:20, which it used to read, 2.4e-2 off at 89 degrees; then refused) gets a guarded table: never below E by more
    # than 1e-3, at the view that was off and at 89.9 degrees
    sharp = ggx.Shape.aniso(0.01, 2)
    e = ggx.Energy(sharp)
    for theta in (np.radians(89.0), np.radians(89.9)):
        v = np.array([np.sin(theta) * np.cos(0.012), np.sin(theta) * np.sin(0.012), np.cos(theta)])
        assert e.albedo(v) >= ggx.albedo(sharp, v) - 1e-3
    del e
    # a small matrix with a short view: the caps' fast path overflowed to infinities (a library bug)
    tiny = ggx.Shape.matrix(np.eye(3) * 1e-49)
    for z in (1e-62, 1e-70, 1e-100):
        d = ggx.sample_vndf(tiny, [0, 0, z], 0.3, 0.7) - ggx.sample_vndf(tiny, [0, 0, 1], 0.3, 0.7)
        assert np.max(np.abs(d)) <= 1e-12, z  # the slow path's normal, not the fast path's bits
    # float32: a u below 1 that rounds to 1.0f is taken as the largest float below 1 (it gave n instead of a rim
    # normal), within the batch bound of the double sampler at that u
    s = ggx.Shape.aniso(0.3, 0.6)
    top = float(np.nextafter(np.float32(1), np.float32(0)))
    for e in ggx.samplers():
        if not e.batch or e.family not in ("ndf", "vndf"):
            continue
        name, v = e.name, None if e.family == "ndf" else [0, 0, 1]
        lo = ggx.sample(name, s, v, 0.25, 0.99999999, dtype=np.float32)
        assert same(lo, ggx.sample(name, s, v, 0.25, top, dtype=np.float32)), name
        assert np.max(np.abs(lo - ggx.sample(name, s, v, 0.25, top))) <= 1e-4, name
    # float32 samplers normalise the view in float64 first: lengths that float cannot hold give the unit view's normal
    for z in (1e300, 1e-50):
        assert same(ggx.sample_vndf(s, [0, 0, z], 0.3, 0.7, dtype=np.float32),
                    ggx.sample_vndf(s, [0, 0, 1], 0.3, 0.7, dtype=np.float32))
    assert same(ggx.sample_brdf(s, [0, 0, 1e300], 0.3, 0.7, dtype=np.float32).w,
                ggx.sample_brdf(s, [0, 0, 1], 0.3, 0.7, dtype=np.float32).w)
    # equal shapes hash equal (0.0 and -0.0 compare equal)
    assert len({ggx.Shape.ellipsoid(0.3, 0.3, 0.0), ggx.Shape.ellipsoid(0.3, 0.3, -0.0)}) == 1
    negzero = np.diag([0.3, 0.3, 1.0])
    negzero[0, 1] = -0.0
    assert len({ggx.Shape.matrix(np.diag([0.3, 0.3, 1.0])), ggx.Shape.matrix(negzero)}) == 1
    # the matrix cannot be made writeable again
    m = ggx.Shape.iso(0.3).matrix
    with pytest.raises(ValueError):
        m.flags.writeable = True
    # errors that were OverflowError or TypeError
    bad = [lambda: ggx.ndf(s, [10 ** 400, 0, 1]), lambda: ggx.sample_vndf(s, [0, 0, 1], 10 ** 400, 0.5),
           lambda: ggx.bsdf(s, 1.5, [0, 0, 1], [0, 0, 1], mode=[]), lambda: ggx.albedo(s, [0, 0, 1], masking={}),
           lambda: ggx.sample_vndf(s, [0, 0, 1], 0.5, 0.5, method=["caps"]), lambda: ggx.sample(["caps"], s, None, 0, 0),
           lambda: ggx.set_batch_threads(float("inf")), lambda: ggx.set_batch_threads(float("nan")),
           lambda: ggx.set_batch_threads(2 ** 32 + 4), lambda: ggx.set_batch_threads(-(2 ** 32) + 4),
           lambda: ggx.ndf(s, np.array(["0", "0", "1"], dtype=object)),
           lambda: ggx.ndf(s, np.array([np.complex128(0.1 + 5j), 0, 1], dtype=object)),
           lambda: ggx.ndf(s, np.ma.masked_array([0.0, 0, 1], mask=[1, 0, 0])),
           lambda: ggx.pdf("caps", s, None, [0, 0, 1]), lambda: ggx.sample_inverse("caps", s, None, [0, 0, 1])]
    each_raises_value_error(bad)
    assert ggx.status_message(2 ** 40) == "unknown status" and ggx.status_message(0) == "ok"
    assert ggx.Shape.iso(Fraction(1, 4)) == ggx.Shape.iso(0.25)
    assert same(ggx.ndf(s, np.array([0, 0, 1], dtype=object)), ggx.ndf(s, [0.0, 0.0, 1.0]))
    ggx.set_batch_threads(1)


def test_geometry_matches_c(c):
    c.ggx_reflect.restype, c.ggx_reflect.argtypes = Vec3, [Vec3, Vec3]
    c.ggx_half_reflect.restype, c.ggx_half_reflect.argtypes = Vec3, [Vec3, Vec3]
    r = rng(21)
    a, b = anywhere(r, N), anywhere(r, N)
    b[0] = -a[0]  # wi + wo = 0: the zero half vector
    for py, cn in ((ggx.reflect, c.ggx_reflect), (ggx.half_reflect, c.ggx_half_reflect)):
        assert same(py(a, b), [(q.x, q.y, q.z) for q in (cn(v3(x), v3(y)) for x, y in zip(a, b))]), cn
    assert same(ggx.half_reflect(a[0], b[0]), [0.0, 0.0, 0.0]) or np.all(ggx.half_reflect(a[0], b[0]) == 0)


def test_dtype_everywhere():
    """Every array function takes dtype: float32 results are the batch API's or the float64 ones rounded."""
    s = ggx.Shape.ellipsoid(*SHAPES[3])
    r = rng(22)
    u, m = upper(r, 20), upper(r, 20)
    calls = [lambda d: ggx.ndf_spherical(s, m[:, 2], m[:, 0], dtype=d), lambda d: ggx.p22(s, m[:, 0], m[:, 1], dtype=d),
             lambda d: ggx.gaussian_curvature(s, m, dtype=d), lambda d: ggx.projected_area(s, u, dtype=d),
             lambda d: ggx.lune_area(s, u, m, dtype=d), lambda d: ggx.lambda_(s, u, dtype=d),
             lambda d: ggx.g1_smith(s, u, dtype=d), lambda d: ggx.g2(s, u, m, m, dtype=d),
             lambda d: ggx.pdf_ndf(s, m, dtype=d), lambda d: ggx.bsdf(s, 1.5, u, -m, dtype=d),
             lambda d: ggx.albedo(s, u[:2], dtype=d), lambda d: ggx.albedo_iso_table(0.3, u[:, 2], dtype=d),
             lambda d: ggx.pdf("ellipse", s, u, m, dtype=d), lambda d: ggx.sample_inverse("caps", s, u, m, dtype=d),
             lambda d: ggx.pdf_bsdf(s, 1.5, u, m, dtype=d),
             lambda d: ggx.reflect(u, m, dtype=d), lambda d: ggx.half_reflect(u, m, dtype=d),
             lambda d: ggx.Fresnel.schlick(0.04)(u[:, 2], dtype=d), lambda d: ggx.bsdf_albedo(s, 1.5, u[:2], dtype=d),
             lambda d: ggx.sample_bsdf(s, 1.5, u, 0.3, 0.6, 0.5, dtype=d).w]
    for k, f in enumerate(calls):
        hi, lo = f(np.float64), f(np.float32)
        for h, l in zip(hi if isinstance(hi, tuple) else (hi,), lo if isinstance(lo, tuple) else (lo,)):
            assert np.asarray(h).dtype == np.float64 and np.asarray(l).dtype == np.float32, k
            assert same(np.asarray(h).astype(np.float32), l), k


def test_other_promises(tmp_path):
    s = ggx.Shape.ellipsoid(*SHAPES[3])
    from decimal import Decimal
    assert ggx.Shape.iso(Decimal("0.25")) == ggx.Shape.iso(0.25)
    for bad in (lambda: ggx.Shape.iso(Decimal("1e400")), lambda: ggx.ndf(s, np.array([1e400, 0, 1], dtype=np.longdouble))
                if np.finfo(np.longdouble).max > 1e400 else ggx.Shape.iso(10 ** 400)):
        with pytest.raises(ValueError):
            bad()
    f = ggx.Fresnel.conductor(0.2, 3.9)
    g = pickle.loads(pickle.dumps(f))
    assert repr(g) == repr(f) and g(0.3) == f(0.3)
    # a single direction or number is read in place (step 0), a C-contiguous input of the full shape too
    big = upper(rng(23), 50)
    a = ggx._Args((big, "m", 3), ([0.0, 0.0, 1.0], "v", 3), (0.5, "u", 1))
    assert np.shares_memory(a.arrays[0], big) and a.ins[1].step == 0 and a.ins[2].step == 0
    # ctypes releases the GIL during a native call: another thread runs meanwhile
    v = upper(rng(24), 300, grazing=False)
    done, ticks = threading.Event(), [0]

    def count():
        while not done.is_set():
            ticks[0] += 1

    t = threading.Thread(target=count)
    t.start()
    t0 = time.perf_counter()
    ggx.albedo(s, v)  # one native call of ~0.1 s or more
    elapsed = time.perf_counter() - t0
    done.set()
    t.join()
    assert elapsed > 0.02 and ticks[0] > 1000, (elapsed, ticks[0])


@pytest.mark.parametrize("name", [e.name for e in ggx.samplers("rejection")])
def test_rejection_samplers_chi_square(name):
    """The rejection samplers' streams seeded by (u1, u2) give the VNDF: chi-square, with a negative control."""
    p = (0.5, 0.7, 0.3, -0.2, 0.4)
    s = ggx.Shape.ellipsoid(*p)
    view = (math.sin(1.1) * math.cos(0.5), math.sin(1.1) * math.sin(0.5), math.cos(1.1))
    r = rng(25)
    m = ggx.sample_vndf(s, view, r.random(200000), r.random(200000), method=name)
    pval, _ = vndf_chi2(s, view, m, ggx.pdf_vndf)
    assert pval > 1e-4, pval
    rough = ggx.Shape.ellipsoid(p[0] * 1.05, p[1] * 1.05, *p[2:])
    bad, _ = vndf_chi2(s, view, m, lambda sh, v, mm: ggx.pdf_vndf(rough, v, mm))
    assert bad < 1e-12, bad
