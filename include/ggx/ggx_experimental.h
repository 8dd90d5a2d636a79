/*
 * libggx — the research entry points: every sampler of normals the seeds describe, beside the defaults that ggx.h
 * declares (ggx_sample_ndf, ggx_sample_vndf), with the unit-square maps they build on and their inverses. They exist
 * to reproduce and compare the seeds' methods (the registry ggx_samplers.h lists them, `ggx check` and the tests run
 * each against its pdf); a renderer needs only the defaults. Their names and contracts are as tested as the stable
 * API's, but a later minor release may add to them or change them where a seed's method is better served otherwise.
 * Included by ggx.h, at its end (it needs ggx.h's types): programs include ggx.h.
 *
 * SPDX-License-Identifier: MIT
 */
#ifndef GGX_GGX_EXPERIMENTAL_H
#define GGX_GGX_EXPERIMENTAL_H

#ifndef GGX_GGX_H
#error "include ggx/ggx.h: it declares the types these functions take, and includes this header"
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Uniform maps from the unit square to the unit disk (area-preserving up to the factor pi):
 * polar r = sqrt(u1), phi = 2 pi u2; concentric (Shirley-Chiu 1997, Walter eq 34-37), lower distortion. */
ggx_vec2 ggx_disk_polar(double u1, double u2);
ggx_vec2 ggx_disk_concentric(double u1, double u2);
/* Inverses: a point of the closed unit disk to (u1, u2) in [0, 1]^2. */
ggx_vec2 ggx_disk_polar_inv(ggx_vec2 d);
ggx_vec2 ggx_disk_concentric_inv(ggx_vec2 d);

/* Engstad's elliptic stretch: a cosine-weighted direction c about the pole of sphere space, m = normalize(A^T c)
 * (for diagonal A, m = normalize(ax cx, ay cy, cz)). Any shape. */
ggx_vec3 ggx_sample_ndf_stretch(const ggx_shape *s, double u1, double u2);
ggx_vec2 ggx_sample_ndf_stretch_inv(const ggx_shape *s, ggx_vec3 m);

/* Blog Part 2: a uniform point of the ellipsoid's silhouette seen from n (an ellipse in the tangent plane, polar
 * map), lifted onto the upper surface of the ellipsoid, and the surface normal there. Any shape. */
ggx_vec3 ggx_sample_ndf_ellipse(const ggx_shape *s, double u1, double u2);

/* Blog Part 2 closed form: phi = atan2(ay sin 2 pi u2, ax cos 2 pi u2),
 * tan theta = sqrt(u1 / (1 - u1)) sqrt(ax^2 cos^2 2 pi u2 + ay^2 sin^2 2 pi u2), in the shape's tangent frame.
 * Unskewed shapes only (GGX_SHAPE_DIAGONAL, GGX_SHAPE_UNSKEWED); a skewed shape gives the zero vector. */
ggx_vec3 ggx_sample_ndf_inversion(const ggx_shape *s, double u1, double u2);

/* The general method: visible-normal sampling from v = n (eq 33 with v = n is D(m) m.z). Any shape. */
ggx_vec3 ggx_sample_ndf_visible(const ggx_shape *s, double u1, double u2);

/* Spherical caps (Dupuy & Benyoub 2023) extended to any A: with v' = normalize(A v), c uniform on the cap
 * {c.z >= -v'.z} (phi = 2 pi u1, c.z = (1 - u2)(1 + v'.z) - v'.z), m = normalize(A^T (v' + c)). No frame. */
ggx_vec3 ggx_sample_vndf_caps(const ggx_shape *s, ggx_vec3 v, double u1, double u2);
ggx_vec2 ggx_sample_vndf_caps_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);

/* Walter's version 3, the crescent (eq 34-46): disk point, compress-and-skew by s = (1 + A v.A n / (|A v| |A n|)) / 2
 * (eq 38), frame e3 = A v, e1 towards A n, lift, m = normalize(A^T p). Concentric disk map (as Walter recommends),
 * or polar. Any shape. */
ggx_vec3 ggx_sample_vndf_crescent(const ggx_shape *s, ggx_vec3 v, double u1, double u2);
ggx_vec3 ggx_sample_vndf_crescent_polar(const ggx_shape *s, ggx_vec3 v, double u1, double u2);
ggx_vec2 ggx_sample_vndf_crescent_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);
ggx_vec2 ggx_sample_vndf_crescent_polar_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);

/* Heitz 2018 / Engstad's five steps: stretch v, frame T1 = z x v', polar disk, squish by (1 + v'.z) / 2, lift,
 * unstretch. Derived for diagonal A; valid for every shape here because the canonical A puts the truncation at
 * z = 0 of sphere space (the seed audit checks it on skewed shapes). */
ggx_vec3 ggx_sample_vndf_heitz(const ggx_shape *s, ggx_vec3 v, double u1, double u2);
ggx_vec2 ggx_sample_vndf_heitz_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);

/* A source of uniform numbers in [0, 1) for the rejection samplers. */
typedef double (*ggx_uniform_fn)(void *state);

/* Walter's versions 1 and 2 (rejection). Version 1 shoots rays along -v from uniform points of the disk of the
 * ellipsoid's bounding sphere (radius 1 / sigma_min(A)) and keeps the first hit if m.n >= 0; version 2 draws uniform
 * points of the silhouette in sphere space, lifts them onto the sphere and keeps those with m.n >= 0. Each
 * candidate uses two numbers from next(state); *trials (if not NULL) receives the number of candidates drawn (the
 * acceptance rate is 1 / mean(trials)). After 100000 rejected candidates the zero vector is returned: version 1 needs
 * about alpha^2 candidates viewed from n for alpha >> 1, so from alpha ~1e3 most samples near n give up
 * (docs/design/kernels.md, "What version 1 costs"). */
ggx_vec3 ggx_sample_vndf_walter_v1(const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next, void *state, unsigned *trials);
ggx_vec3 ggx_sample_vndf_walter_v2(const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next, void *state, unsigned *trials);

#ifdef __cplusplus
}
#endif

#endif /* GGX_GGX_EXPERIMENTAL_H */
