"""Images of the material: render, the image `ggx render` makes (libs/render/render.h, docs/design/render.md)."""

import ctypes
import os

import numpy as np

from ._native import _C_UINT64, _choice, _cstring, _d, _i, _integer, _proto, _real, _sz, _vp
from ._shape import _fresnel, _shape

_render = _proto("ggxpy_render", _i, _vp, _vp, ctypes.c_char_p, _i, _i, _i, ctypes.c_char_p, _vp, _d, _i, _i, _i,
                 _i, _i, ctypes.c_ulonglong, _i, _i, _vp, _vp, ctypes.c_char_p, _sz)


def render(shape, fresnel=None, scene="sphere", light="sky", spp=64, size=(256, 256), compensate=False,
           sampler=None, strategy="mis", depth=32, seed=1, threads=None, jitter=True, variance=False):
    """The image `ggx render` makes, as a float32 array (height, width, 3) of linear RGB radiance, the top row first.

    shape: a ggx.Shape; fresnel: a ggx.Fresnel or None (F = 1), Fresnel.dielectric(eta) for rough glass;
    scene "sphere" or "plane"; light "sky" (the built-in sky), "white" (the furnace, L = 1), a path to an OpenEXR,
    .hdr or PFM latitude-longitude environment, or ("point", theta, phi[, E]) for a distant light from those angles
    (radians, world frame) of irradiance E (default 1); size (width, height); sampler a registry name (None:
    brdf-bounded; the glass always uses bsdf); strategy "mis", "light" or "bsdf"; threads None for the processors
    online (the image does not depend on it); jitter False puts every sample at its pixel's centre. With
    variance=True also returns the variance of each pixel's mean. Bad arguments raise ValueError with the
    renderer's one-line reason."""
    s, f = _shape(shape), _fresnel(fresnel)
    if np.ndim(size) == 1 and len(size) == 2:
        w, h = _integer(size[0], "width", 1, 1 << 20), _integer(size[1], "height", 1, 1 << 20)
    else:
        w = h = _integer(size, "size", 1, 1 << 20)
    spp, depth = _integer(spp, "spp", 1, 1 << 20), _integer(depth, "depth", 1, 1 << 20)
    seed = _integer(seed, "seed", c=_C_UINT64)
    if w * h > 1 << 26:
        raise ValueError(f"size: {w} x {h} pixels is too large")
    scene_id = _choice(scene, {"sphere": 0, "plane": 1}, "scene")
    strategy_id = _choice(strategy, {"mis": 0, "light": 1, "bsdf": 2}, "strategy")
    direction, irradiance, path = np.array([0.0, 0.0, 1.0]), 1.0, None
    if isinstance(light, str) and light in ("sky", "white"):
        light_id = 0 if light == "sky" else 1
    elif isinstance(light, (tuple, list)) and len(light) in (3, 4) and light[0] == "point":
        th, ph = _real(light[1], "light theta"), _real(light[2], "light phi")
        irradiance = _real(light[3], "light irradiance") if len(light) == 4 else 1.0
        direction = np.array([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)])
        if not (np.all(np.isfinite(direction)) and irradiance >= 0):
            raise ValueError(f"light: {light!r} needs finite angles and an irradiance >= 0")
        light_id = 3
    elif isinstance(light, (str, bytes, os.PathLike)):
        light_id, path = 2, _cstring(light, "light", path=True)
    else:
        raise ValueError(f"light: expected 'sky', 'white', a path or ('point', theta, phi[, E]), got {light!r}")
    if threads is None:
        threads = os.cpu_count() or 1
    threads = _integer(threads, "threads", 1, 256)
    img = np.empty((h, w, 3), dtype=np.float32)
    var = np.empty((h, w, 3), dtype=np.float32) if variance else None
    err = ctypes.create_string_buffer(600)
    rc = _render(s._buf, f._buf, None if sampler is None else _cstring(sampler, "sampler"), int(bool(compensate)), scene_id,
                 light_id, path, direction.ctypes.data, irradiance, strategy_id, w, h, spp, depth,
                 seed, threads, int(bool(jitter)), img.ctypes.data,
                 None if var is None else var.ctypes.data, err, 600)
    if rc != 0:
        raise ValueError(err.value.decode(errors="replace"))
    return (img, var) if variance else img
