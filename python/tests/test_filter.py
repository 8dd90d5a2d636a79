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
