/* Numerical verification shared by the tests and the `ggx` tool: a deterministic RNG, vector helpers, adaptive
 * quadrature over the hemisphere of micro-normals (lobe-aware: it integrates in the sphere space of a shape), and the
 * sphere-space keys of normals. No test framework here. SPDX-License-Identifier: MIT */
#ifndef GGX_VERIFY_H
#define GGX_VERIFY_H

#include <stdint.h>

#include "ggx/ggx.h"


/* ---- RNG: splitmix64, fixed seeds everywhere ---- */
typedef struct rng {
    uint64_t s;
} rng;
double rng_uniform(rng *r);                   /* [0, 1) */
double rng_range(rng *r, double a, double b); /* [a, b) */

/* ---- vectors ---- */
ggx_vec3 t_vec(double x, double y, double z);
ggx_vec3 t_dir(double theta, double phi); /* spherical angles, radians */
ggx_vec3 t_normalize(ggx_vec3 v);
double t_dot(ggx_vec3 a, ggx_vec3 b);
ggx_vec3 t_cross(ggx_vec3 a, ggx_vec3 b);
ggx_vec3 t_add(ggx_vec3 a, ggx_vec3 b);
ggx_vec3 t_scale(ggx_vec3 a, double k);
ggx_vec3 t_matvec(const double M[3][3], ggx_vec3 v);
ggx_vec3 t_mattvec(const double M[3][3], ggx_vec3 v); /* M^T v */
void t_frame(ggx_vec3 n, ggx_vec3 *e1, ggx_vec3 *e2); /* orthonormal e1, e2 perpendicular to unit n */

/* ---- quadrature ---- */
typedef double (*t_integrand)(ggx_vec3 m, void *ctx);
/* Integral of f(m) dm over {m : m.n >= 0 and m.cut_k >= 0 for all k}, by nested adaptive Gauss-Legendre in the
 * sphere space of shape s (m = normalize(A^T m'), d omega_m = |A| / ||A^T m'||^3 d omega_m'), where the NDF of s is
 * a smooth cosine lobe. The cut planes become great circles there and are passed as break points, so integrands
 * that are smooth on the domain converge fast however sharp the lobe is in m. rel_tol is relative to the
 * integral. Counts integrand calls in *calls when non-NULL. */
double quad_hemisphere(const ggx_shape *s, t_integrand f, void *ctx, const ggx_vec3 *cuts, int ncuts, double rel_tol,
                       long *calls);
/* Adaptive Gauss-Legendre on [a, b] for a 1D function (used by quad_hemisphere; exposed for its self-test). */
typedef double (*t_fn1)(double x, void *ctx);
double quad_adapt(t_fn1 f, void *ctx, double a, double b, double abs_tol);
double quad_gl(t_fn1 f, void *ctx, double a, double b); /* one fixed Gauss-Legendre panel */
int quad_gl_order(void);

/* Sphere-space key of a normal, k = normalize(A^{-T} m), and back: m = normalize(A^T k) with
 * *jacobian = d omega_m / d omega_k = |A| / ||A^T k||^3. */
ggx_vec3 key_of_normal(const ggx_shape *s, ggx_vec3 m);
ggx_vec3 normal_of_key(const ggx_shape *s, ggx_vec3 k, double *jacobian);

#endif
