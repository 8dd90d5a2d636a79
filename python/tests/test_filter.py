"""The Python normal-map filter (ggx.texel_lobe, ggx.filter_lobes, ggx.filter_kl) against the library's contracts:
a constant map filtered exactly, the best ellipsoid beating a lobe about the mean normal, weights, bad input."""
import numpy as np
import pytest

import ggx


def test_texel_lobe_is_ggx_translated():
    n = np.array([0.3, -0.2, 1.0])
    lobe = ggx.texel_lobe(n, 0.2, 0.4, 0.5)
    t = -n[:2] / n[2]
    c, s = np.cos(0.5), np.sin(0.5)
    for x, y in [(0.0, 0.0), (0.5, 0.1), (-1.0, 2.0)]:
        dx, dy = x - t[0], y - t[1]
        u, v = (c * dx + s * dy) / 0.2, (-s * dx + c * dy) / 0.4
        want = 1.0 / (np.pi * 0.2 * 0.4 * (1 + u * u + v * v) ** 2)
        assert ggx.p22(lobe, x, y) == pytest.approx(want, rel=1e-12)
    assert ggx.texel_lobe([0, 0, 1], 0.3).kind == "diagonal"


def test_constant_map_is_exact():
    lobe = ggx.texel_lobe([0.4, 0.1, 1.0], 0.15, 0.3, 1.0)
    f, info = ggx.filter_lobes([lobe] * 9, weights=np.linspace(1, 2, 9))
    assert info["converged"] and info["iterations"] <= 3
    u = np.random.default_rng(1).random((2, 64))
    m = ggx.sample_ndf(lobe, u[0], u[1])
    np.testing.assert_allclose(ggx.ndf(f, m), ggx.ndf(lobe, m), rtol=1e-12)
    assert abs(ggx.filter_kl(f, [lobe] * 9)) < 1e-12


def test_checkerboard_beats_the_mean_normal_lobe():
    a, b = ggx.texel_lobe([0.3, 0, 1], 0.1), ggx.texel_lobe([-0.3, 0, 1], 0.1)
    f, _ = ggx.filter_lobes([a, b])
    t, sigma = f.slopes()
    assert abs(t[0]) < 1e-12 and sigma[0] > 4 * sigma[2]  # wide across the tilts, narrow along them
    flat = ggx.texel_lobe([0, 0, 1], 0.1)
    assert ggx.filter_kl(f, [a, b]) < 0.5 * ggx.filter_kl(flat, [a, b])


def test_bad_input():
    a = ggx.texel_lobe([0, 0, 1], 0.3)
    with pytest.raises(ValueError):
        ggx.filter_lobes([])
    with pytest.raises(ValueError):
        ggx.filter_lobes([a, a], weights=[1.0])
    with pytest.raises(ValueError):
        ggx.filter_lobes([a, a], weights=[-1.0, 1.0])
    with pytest.raises(ValueError):
        ggx.filter_lobes([a], nodes=(8, 15))
    with pytest.raises(ValueError):
        ggx.texel_lobe([0, 0, -1], 0.3)
    with pytest.raises(ValueError):
        ggx.filter_lobes([a, "not a shape"])


def test_mipmap_chain():
    rng = np.random.default_rng(3)
    # a constant map: every level the texel's lobe, sizes 7 x 5 -> 4 x 3 -> 2 x 2 -> 1 x 1
    n = np.tile([0.2, -0.1, 1.0], (5, 7, 1))
    chain = ggx.mipmap(n, 0.3)
    assert [lv[0].shape[:2] for lv in chain] == [(5, 7), (3, 4), (2, 2), (1, 1)]
    want = ggx.texel_lobe([0.2, -0.1, 1.0], 0.3).slopes()
    for lobes, w in chain:
        np.testing.assert_allclose(lobes[..., 0], want[0][0], rtol=1e-12)
        np.testing.assert_allclose(lobes[..., 2], want[1][0], rtol=1e-12)
    assert chain[-1][1][0, 0] == 35.0
    # a level's texel is filter_lobes of its box; a rejected texel has weight 0 and counts nowhere
    m = rng.normal(0, 0.2, (4, 4, 3))
    m[..., 2] = 1.0
    m[0, 0] = [1.0, 0.0, -0.5]
    chain = ggx.mipmap(m, 0.1, threads=2)
    assert chain[0][1][0, 0] == 0.0 and chain[1][1][0, 0] == 3.0
    box = [ggx.texel_lobe(m[j, i], 0.1) for j in (0, 1) for i in (0, 1) if (i, j) != (0, 0)]
    f, _ = ggx.filter_lobes(box)
    t, sigma = f.slopes()
    np.testing.assert_allclose(chain[1][0][0, 0, :2], t, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(chain[1][0][0, 0, 2:], sigma, rtol=1e-9)
    with pytest.raises(ValueError):
        ggx.mipmap(np.zeros((4, 4)), 0.1)
    with pytest.raises(ValueError):
        ggx.mipmap(np.zeros((4, 4, 2)), 0.1)
    with pytest.raises(ValueError):
        ggx.mipmap(n, 0.0)


def test_mipmap_roughness_map_and_fast_mode():
    rng = np.random.default_rng(5)
    m = rng.normal(0, 0.2, (6, 5, 3))
    m[..., 2] = 1.0
    # a roughness map: level 0 is each texel's own lobe; a constant map is the scalar alpha, level for level
    r = rng.uniform(0.05, 0.5, (6, 5))
    chain = ggx.mipmap(m, r)
    for j, i in ((0, 0), (3, 2), (5, 4)):
        t, sigma = ggx.texel_lobe(m[j, i], r[j, i]).slopes()
        np.testing.assert_allclose(chain[0][0][j, i, 2:], sigma, rtol=1e-12)
    same, scalar = ggx.mipmap(m, np.full((6, 5), 0.3)), ggx.mipmap(m, 0.3)
    for (a, wa), (b, wb) in zip(same, scalar):
        np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(wa, wb)
    # anisotropic maps, a 0 raised to 1e-4, a NaN texel rejected
    r2 = r.copy()
    r2[0, 0], r2[1, 1] = 0.0, np.nan
    chain = ggx.mipmap(m, r2, alpha_y=2 * r)
    assert chain[0][1][0, 0] == 1.0 and chain[0][1][1, 1] == 0.0
    t, sigma = ggx.texel_lobe(m[3, 2], r[3, 2], 2 * r[3, 2]).slopes()
    np.testing.assert_allclose(chain[0][0][3, 2, 2:], sigma, rtol=1e-12)
    with pytest.raises(ValueError):
        ggx.mipmap(m, np.full((5, 6), 0.3))
    with pytest.raises(ValueError):
        ggx.mipmap(m, None, alpha_y=r)
    # the fast mode: one EM step over 2 x 4 nodes, the same as those options given by hand, and near the exact fit
    fast, manual, exact = ggx.mipmap(m, 0.1, fast=True), ggx.mipmap(m, 0.1, max_iterations=1, nodes=(2, 4)), \
        ggx.mipmap(m, 0.1)
    for (a, _), (b, _) in zip(fast, manual):
        np.testing.assert_array_equal(a, b)
    assert not np.array_equal(fast[1][0], exact[1][0])
    np.testing.assert_allclose(fast[1][0][..., [2, 4]], exact[1][0][..., [2, 4]], rtol=0.3)
