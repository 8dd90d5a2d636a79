"""The Python fits and readers (ggx.fit_normals, ggx.fit_heightfield, ggx.read_surface, Shape.from_slopes) against
the promises of their docstrings and the C library's results."""

import math
import pickle
import struct
import zlib

import numpy as np
import pytest

import ggx


def normals_of(shape, n, seed):
    u = np.random.default_rng(seed).random((2, n))
    return ggx.sample_ndf(shape, u[0], u[1])


def test_slopes_round_trip_and_closed_forms():
    s = ggx.Shape.ellipsoid(0.3, 0.1, 0.4, -0.2, 0.7)
    t, sg = s.slopes()
    b = ggx.Shape.from_slopes(t, sg)
    m = normals_of(s, 200, 1)
    assert np.allclose(ggx.ndf(b, m), ggx.ndf(s, m), rtol=1e-12, atol=0)
    t2, sg2 = b.slopes()
    assert np.allclose(t2, t, rtol=1e-13) and np.allclose(sg2, sg, rtol=1e-13)
    # a 2 x 2 sigma is the same shape; unskewed shapes have t = 0 and isotropic sigma = alpha^2 I
    assert np.array_equal(ggx.Shape.from_slopes(t, [[sg[0], sg[1]], [sg[1], sg[2]]]).slopes()[1], sg2)
    t0, s0 = ggx.Shape.iso(0.4).slopes()
    assert t0.tolist() == [0.0, 0.0] and np.allclose(s0, [0.16, 0.0, 0.16], rtol=1e-15)
    assert pickle.loads(pickle.dumps(b)) == b
    ax, ay, tx, ty, tz = s.ellipsoid_params()
    assert np.allclose([ax, ay, tx, ty, tz], [0.3, 0.1, 0.4, -0.2, 0.7], atol=1e-12)


@pytest.mark.parametrize("bad", [([0, 0], [-1, 0, 1]), ([0, 0], [1, 2, 1]), ([np.nan, 0], [1, 0, 1])])
def test_from_slopes_refuses(bad):
    with pytest.raises(ValueError):
        ggx.Shape.from_slopes(*bad)
    with pytest.raises(ValueError):
        ggx.Shape.from_slopes([0, 0, 0], [1, 0, 1])
    with pytest.raises(ValueError):
        ggx.Shape.from_slopes([0, 0], [[1, 0.5], [0.4, 1]])


def test_fit_normals_recovers_and_reports():
    s = ggx.Shape.ellipsoid(0.3, 0.1, 0.4, -0.2, 0.7)
    t, sg = s.slopes()
    m = normals_of(s, 20000, 2)
    f, info = ggx.fit_normals(m)
    assert info.converged and info.best == "ellipsoid" and info.used == 20000
    z = (np.concatenate([info.t, info.sigma]) - np.concatenate([t, sg])) / info.std_error
    assert np.all(np.abs(z) < 5), z
    assert np.allclose(f.slopes()[0], info.t, rtol=1e-13) and np.allclose(f.slopes()[1], info.sigma, rtol=1e-13)
    assert info.covariance.shape == (5, 5) and np.allclose(np.sqrt(np.diag(info.covariance)), info.std_error)
    assert set(info.models) == {"ellipsoid", "anisotropic", "isotropic", "beckmann"}
    assert info.models["ellipsoid"]["bic"] < info.models["beckmann"]["bic"]
    assert 0.0 <= info.gof_pvalue <= 1.0 and info.gof_dof == 16 * 16 - 6
    # the model family, the weights (2 = a replicated normal), threads (bit for bit) and the ignored counts
    _, iso = ggx.fit_normals(m, model="isotropic")
    assert iso.t.tolist() == [0.0, 0.0] and iso.sigma[0] == iso.sigma[2] and iso.std_error[0] == 0.0
    w = np.where(np.arange(1000) % 2 == 0, 2.0, 1.0)
    _, a = ggx.fit_normals(m[:1000], weights=w, tolerance=1e-10)
    _, b = ggx.fit_normals(np.repeat(m[:1000], w.astype(int), axis=0), tolerance=1e-10)
    assert np.allclose(a.sigma, b.sigma, rtol=1e-9) and np.allclose(a.t, b.t, rtol=1e-9, atol=1e-12)
    _, t3 = ggx.fit_normals(m, threads=3)
    assert np.array_equal(t3.sigma, info.sigma)
    mm = np.vstack([m[:100], [[1, 0, 0], [0, 0, -1], [np.nan, 0, 1]]])
    _, c = ggx.fit_normals(mm)
    assert (c.used, c.ignored_horizon, c.ignored_nonfinite) == (100, 2, 1)
    # the tails: GGX's samples give nu = 2 within 4 standard errors, the family's likelihood at least GGX's
    tl = info.tails
    assert set(tl) == {"nu", "nu_std_error", "log_likelihood", "bic", "t", "sigma", "iterations", "converged",
                       "subsample"}
    assert tl["converged"] and not tl["subsample"] and isinstance(tl["iterations"], int)
    assert abs(tl["nu"] - 2.0) <= 4 * tl["nu_std_error"], tl
    assert tl["log_likelihood"] >= info.models["ellipsoid"]["log_likelihood"] - 1e-12
    assert tl["t"].shape == (2,) and tl["sigma"].shape == (3,)


def test_fit_normals_refuses():
    m = normals_of(ggx.Shape.iso(0.2), 100, 3)
    with pytest.raises(ValueError, match="too few usable samples"):
        ggx.fit_normals(m[:4])
    with pytest.raises(ValueError):
        ggx.fit_normals(m, weights=-np.ones(100))
    with pytest.raises(ValueError):
        ggx.fit_normals(m, model="beckmann")
    with pytest.raises(ValueError):
        ggx.fit_normals(m[:, :2])
    with pytest.raises(ValueError):
        ggx.fit_normals(m, threads=0)


def test_fit_heightfield_tilt_and_levelling():
    rng = np.random.default_rng(4)
    fx, gy = np.cumsum(rng.normal(0, 0.2, 150)), np.cumsum(rng.normal(0, 0.1, 120))
    x, y = np.meshgrid(np.arange(150) * 0.5, np.arange(120) * 0.5)
    h = (fx[None, :] + gy[:, None]) * 0.5 + 0.3 * x - 0.2 * y
    _, lev = ggx.fit_heightfield(h, spacing=0.5)
    _, kept = ggx.fit_heightfield(h, spacing=(0.5, 0.5), keep_tilt=True)
    assert lev.best == "beckmann" and lev.used == 4 * 149 * 119
    # levelling removes the least-squares plane of the heights (numpy's lstsq here): the mean slopes differ by its
    # gradient exactly, and the walks' own trend leaves the levelled mean small
    A = np.column_stack([np.ones(h.size), x.ravel(), y.ravel()])
    plane = np.linalg.lstsq(A, h.ravel(), rcond=None)[0][1:]
    assert np.allclose(kept.models["beckmann"]["t"] - lev.models["beckmann"]["t"], plane, rtol=0, atol=1e-10)
    assert np.allclose(plane, [0.3, -0.2], atol=0.03) and np.allclose(lev.models["beckmann"]["t"], 0, atol=0.01)
    assert np.allclose(lev.models["beckmann"]["sigma"][[0, 2]], [0.04, 0.01], rtol=0.25)
    _, ds = ggx.fit_heightfield(h, spacing=0.5, downsample=3)
    assert ds.used == 4 * 49 * 39
    with pytest.raises(ValueError):
        ggx.fit_heightfield(h[0], spacing=1)
    with pytest.raises(ValueError):
        ggx.fit_heightfield(h, spacing=0)


def test_read_surface(tmp_path):
    # a Gwyddion Simple Field written here, by its documented layout
    h = np.arange(12, dtype=np.float32).reshape(3, 4) * 1e-7
    hdr = b"Gwyddion Simple Field 1.0\nXRes = 4\nYRes = 3\nXReal = 4e-6\nYReal = 3e-6\nXYUnits = m\nZUnits = m\n"
    p = tmp_path / "h.gsf"
    p.write_bytes(hdr + b"\0" * (4 - len(hdr) % 4) + b"".join(struct.pack("<f", v) for v in h.flat))
    s = ggx.read_surface(p)
    assert s.kind == "heights" and s.data.shape == (3, 4) and np.array_equal(s.data, h.astype(np.float64))
    assert s.spacing == pytest.approx((1e-6, 1e-6)) and s.z_scale == 1.0
    c = tmp_path / "n.csv"
    c.write_text("x,y,z,weight\n0,0,1,2\n0.1,0,1,1\n")
    n = ggx.read_surface(c, kind="normals")
    assert n.data.shape == (2, 3) and n.weights.tolist() == [2.0, 1.0]
    with pytest.raises(ValueError, match="truncated"):
        (tmp_path / "t.gsf").write_bytes(hdr + b"\0\0")
        ggx.read_surface(tmp_path / "t.gsf")
    with pytest.raises(ValueError, match="holds heights"):
        ggx.read_surface(p, kind="normals")
    with pytest.raises(ValueError):
        ggx.read_surface(tmp_path / "missing.x3p")


def _student_normals(rng, t, sigma, n):
    """Normals whose slopes are the Student t of (t, sigma), independently of the library."""
    L = np.linalg.cholesky(np.array([[sigma[0], sigma[1]], [sigma[1], sigma[2]]]))
    g = rng.standard_normal((n, 2)) / np.sqrt(2.0 * rng.exponential(size=(n, 1)))
    s = np.asarray(t) + g @ L.T
    m = np.column_stack([-s[:, 0], -s[:, 1], np.ones(n)])
    return m / np.linalg.norm(m, axis=1, keepdims=True)


def test_fit_normal_cells_quantised_map(tmp_path):
    rng = np.random.default_rng(8)
    sigma = (0.006 ** 2, 0.2 * 0.006 * 0.004, 0.004 ** 2)
    m = _student_normals(rng, (0.0, 0.0), sigma, 20000)
    levels = np.clip(np.round((m + 1.0) / 2.0 * 255.0), 0, 255)
    uv = 2.0 * levels[:, :2] / 255.0 - 1.0
    shape, info = ggx.fit_normal_cells(uv, 2.0 / 255.0)
    for i, k in ((0, 2), (1, 3), (2, 4)):
        assert abs(info.sigma[i] - sigma[i]) <= 4.0 * info.std_error[k]
    assert info.converged and math.isnan(info.gof_pvalue) and info.used == 20000
    # the centres fitted as normals overestimate sigma_yy by many standard errors
    c = np.column_stack([uv, np.sqrt(np.maximum(0.0, 1.0 - (uv ** 2).sum(axis=1)))])
    _, pinfo = ggx.fit_normals(c)
    assert (pinfo.sigma[2] - sigma[2]) / pinfo.std_error[4] > 10.0
    # an RGB PNG of the same levels: read_surface gives its decoded red and green as uv, the same fit
    w, h = 200, 100
    raw = b"".join(b"\0" + levels[j * w:(j + 1) * w].astype(np.uint8).tobytes() for j in range(h))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    p = tmp_path / "map.png"
    p.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                  chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
    s = ggx.read_surface(p, kind="normals")
    assert s.bits == 8 and s.uv.shape == (h, w, 2) and np.array_equal(s.uv.reshape(-1, 2), uv)
    _, again = ggx.fit_normal_cells(s.uv, 2.0 / 255.0)
    assert again.sigma == pytest.approx(info.sigma, rel=1e-12)
    down = ggx.read_surface(p, kind="normals", y_down=True)
    assert np.array_equal(down.uv[..., 1], -s.uv[..., 1])
    with pytest.raises(ValueError):
        ggx.fit_normal_cells(uv, 0.0)
    with pytest.raises(ValueError):
        ggx.fit_normal_cells(uv[:, :1], 2.0 / 255.0)
