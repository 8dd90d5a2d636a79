"""libggx for Python: Walter's Ellipsoid NDF (anisotropic, rotated and skewed GGX) on numpy arrays.

Conventions are the C library's (include/ggx/ggx.h): local frame with the macro-surface normal n = +z, every
direction a unit vector pointing away from the surface, angles in radians. A shape is made once
(``Shape.iso``, ``Shape.aniso``, ``Shape.ellipsoid``, ``Shape.matrix``) and passed to the functions.

Arrays follow numpy's rules: directions are arrays of shape (..., 3), numbers arrays of shape (...); the leading
dimensions of all inputs broadcast together and give the result's shape (a direction result has shape (..., 3)).
Inputs are converted to float64. Results are float64 and, element by element, bit for bit what the C function
returns (each function names it). ``dtype=np.float32`` uses the float batch API (include/ggx/ggx_batch.h, SIMD) where
it has the function (ndf, g1, pdf_vndf, brdf, sample_ndf and sample_vndf with a batch sampler, sample_brdf), within
the accuracy that header states; elsewhere float32 results are the float64 ones rounded, and a result beyond
float32's range (an absolute area or curvature of a matrix far from unit scale) raises ValueError, never inf.

Errors raise ValueError: a shape or Fresnel term the library refuses (with its status message), inputs that do not
broadcast, a direction array whose last axis is not 3, a complex, non-numeric or masked input, an unknown sampler or
option. (Calling Shape() or Fresnel() directly, or a wrong number of arguments, is a TypeError, as in Python; an
array too large for memory is numpy's MemoryError.) Any real input, NaN and
infinities included, gives a finite result (the C library's contract): 0 outside the domain, the zero vector for a
sampler that has no sample.
"""

# The package imported these here when it was one file, so they became ggx.np, ggx.os and so on; kept, so that no
# name of ggx disappears (the modules import what they use themselves).
import collections
import ctypes
import decimal
import math
import numbers
import os
import weakref

import numpy as np

# The package is in modules by topic, and this file only gathers their public names. A module imports only from
# those before it in this order, so there is no cycle: _native (the native module, the helpers every module shares),
# _shape (Shape, Fresnel), _evaluate, _sample, _albedo (_evaluate's loop, _sample's BrdfSample), then _fit, _filter
# and _render.
from ._albedo import (Energy, albedo, albedo_aniso_table, albedo_avg, albedo_avg_iso_table, albedo_iso_table,
                      bsdf_albedo, bsdf_albedo_iso_table)
from ._evaluate import (bsdf, brdf, g1, g1_risers, g1_smith, g1_tilted, g2, gaussian_curvature, half_reflect,
                        lambda_, lune_area, ndf, ndf_spherical, p22, pdf_ndf, pdf_vndf, projected_area, reflect)
from ._filter import filter_kl, filter_lobes, mipmap, texel_lobe
from ._fit import FitInfo, Surface, fit_heightfield, fit_normal_cells, fit_normals, read_surface
from ._native import __version__, batch_isa, set_batch_threads, status_message
from ._native import _Args  # python/tests/test_ggx.py makes one directly
from ._render import render
from ._sample import (BrdfSample, DirectionSample, SampleEval, SamplerInfo, pdf, pdf_brdf, pdf_bsdf, sample, sample_brdf,
                      sample_eval,
                      sample_bsdf, sample_inverse, sample_ndf, sample_vndf, samplers)
from ._sggx import (Flakes, sggx_ndf, sggx_phase_diffuse, sggx_phase_specular, sggx_sample_diffuse,
                    sggx_sample_specular, sggx_sample_vndf, sggx_sigma)
from ._shape import Fresnel, Shape

__all__ = [
    "Shape", "Fresnel", "Energy", "SamplerInfo", "BrdfSample", "DirectionSample", "samplers", "status_message",
    "ndf", "ndf_spherical", "p22", "gaussian_curvature", "projected_area", "lune_area", "lambda_", "g1", "g1_smith",
    "g1_tilted", "g1_risers",
    "g2", "pdf_ndf", "pdf_vndf", "brdf", "bsdf", "albedo", "albedo_avg", "bsdf_albedo", "albedo_iso_table",
    "albedo_avg_iso_table", "bsdf_albedo_iso_table", "albedo_aniso_table",
    "sample", "pdf", "sample_inverse", "sample_ndf", "sample_vndf", "sample_brdf", "sample_eval", "SampleEval",
    "pdf_brdf", "sample_bsdf", "pdf_bsdf", "reflect", "half_reflect", "batch_isa", "set_batch_threads",
    "FitInfo", "Surface", "fit_normals", "fit_normal_cells", "fit_heightfield", "read_surface", "render",
    "texel_lobe", "filter_lobes", "filter_kl", "mipmap",
    "Flakes", "sggx_ndf", "sggx_sigma", "sggx_sample_vndf", "sggx_phase_specular", "sggx_sample_specular",
    "sggx_phase_diffuse", "sggx_sample_diffuse",
]

# The public objects say they are ggx's, as they did in one file: their reprs, help and pickles name ggx.Shape, not
# the module that defines it, so pickles stay readable whatever the layout.
for _name in __all__:
    globals()[_name].__module__ = __name__
del _name
