"""ggx.render against the promises of its docstring: the image of the C renderer (libs/render/render.h), the white
furnace, a distant light as the BRDF, thread invariance, PFM environments, and bad arguments as ValueError."""

import math
import struct

import numpy as np
import pytest

import ggx


def test_furnace_compensated_is_one():
    s = ggx.Shape.ellipsoid(0.3, 0.6, 0, 0, math.radians(30))
    img, var = ggx.render(s, light="white", compensate=True, spp=256, size=24, threads=2, variance=True)
    assert img.shape == (24, 24, 3) and img.dtype == np.float32
    se = math.sqrt(var[..., 1].sum()) / img[..., 1].size
    assert abs(img[..., 1].mean() - 1) <= 1e-3 + 4 * se
    assert np.all(np.abs(img - 1) <= 5 * np.sqrt(var) + 2e-3)


def test_distant_light_on_the_plane_is_the_brdf():
    # the plane's view at the image centre is the camera's direction: azimuth 60 deg, 35 deg up
    s = ggx.Shape.ellipsoid(0.2, 0.45, 0.1, 0.05, 0.7)
    f = ggx.Fresnel.conductor(0.2, 3.5)
    th, ph = math.radians(50), math.radians(-140)
    img = ggx.render(s, f, scene="plane", light=("point", th, ph, 2.5), spp=1, size=(33, 33), jitter=False, threads=1)
    v = np.array([math.cos(math.radians(35)) * math.cos(math.radians(60)),
                  math.cos(math.radians(35)) * math.sin(math.radians(60)), math.sin(math.radians(35))])
    l = np.array([math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)])
    want = ggx.brdf(s, l, v, fresnel=f) * l[2] * 2.5
    assert img[16, 16, 0] == pytest.approx(want, rel=1e-6)


def test_threads_do_not_change_the_image():
    s = ggx.Shape.ellipsoid(0.15, 0.5)
    a = ggx.render(s, spp=4, size=(40, 24), threads=1, seed=3)
    b = ggx.render(s, spp=4, size=(40, 24), threads=3, seed=3)
    c = ggx.render(s, spp=4, size=(40, 24), threads=3, seed=4)
    assert np.array_equal(a, b) and not np.array_equal(a, c)


def test_pfm_environment(tmp_path):
    # a 4 x 2 PFM, bottom row first: the upper row 2, the lower row 0.5 -> a sphere lit brighter from above
    p = tmp_path / "env.pfm"
    rows = [[0.5] * 12, [2.0] * 12]
    p.write_bytes(b"PF\n4 2\n-1.0\n" + b"".join(struct.pack("<12f", *r) for r in rows))
    img = ggx.render(ggx.Shape.iso(0.3), light=str(p), spp=16, size=32, threads=2)
    assert img[0, 0, 0] == pytest.approx(2.0) and img[-1, 0, 0] == pytest.approx(0.5)
    assert img[10, 16, 1] > img[22, 16, 1]


def test_bad_arguments():
    s = ggx.Shape.iso(0.2)
    for kw, msg in [({"scene": "cube"}, "scene"), ({"strategy": "luck"}, "strategy"), ({"spp": 0}, "spp"),
                    ({"light": "/nonexistent/env.exr"}, "cannot read"), ({"sampler": "magic"}, "unknown sampler"),
                    ({"fresnel": ggx.Fresnel.dielectric(1.5), "sampler": "caps"}, "own sampler"),
                    ({"light": ("point", math.nan, 0)}, "finite"),
                    ({"light": ("point", 0, 0, 1e308)}, "does not fit single precision")]:
        args = {"size": 8, "spp": 1, **kw}
        with pytest.raises(ValueError, match=msg):
            ggx.render(s, **args)
