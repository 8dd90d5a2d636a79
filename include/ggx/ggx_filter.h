/*
 * libggx filtering: the one ellipsoid closest to a mixture of ellipsoid lobes, for normal maps filtered exactly.
 *
 * SPDX-License-Identifier: MIT
 *
 * A texel of a tangent-space normal map with base roughness alpha is the lobe of a GGX surface on a tilted mean
 * plane: in slope space (ggx.h, ggx_shape_slopes) a Student t with location t = the slope of the texel's normal and
 * scale Sigma = alpha^2 I, which is exactly an ellipsoid NDF (a skewed one where the normal is tilted). A footprint
 * of texels is the mixture of their lobes, weighted by their areas. ggx_filter_lobes returns the ellipsoid that
 * maximises the mixture's expected log-likelihood, which is the one of least Kullback-Leibler divergence from it:
 * its skew carries the footprint's mean normal, so no shading normal is left (docs/design/filter.md).
 *
 * Threads: every function may be called from any number of threads at once.
 */
#ifndef GGX_GGX_FILTER_H
#define GGX_GGX_FILTER_H

#include <stddef.h>

#include "ggx/ggx.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The lobe of one texel: the shape whose slopes have location t = (-n.x / n.z, -n.y / n.z), the slope of the
 * texel's normal n (any length), and scale Sigma = Rz(phi) diag(alpha_x^2, alpha_y^2) Rz(phi)^T, the base
 * roughness with its axis x at angle phi (radians) in the tangent plane (phi = 0, alpha_x = alpha_y: isotropic).
 * For n = +z and phi = 0 it has ggx_shape_aniso's distribution; in general P22 of the result is the GGX P22 of
 * (alpha_x, alpha_y, phi) translated by t, within ggx_shape_from_slopes' 1e-12 + 2e-15 kappa^2 relative, kappa =
 * max(alpha_x, alpha_y, 1) / min(alpha_x, alpha_y, 1) (tests/unit/test_filter.c). Alphas below GGX_ALPHA_MIN are
 * raised to it. Errors: GGX_ERR_NULL; GGX_ERR_NONFINITE (n, an
 * alpha or phi NaN or infinite); GGX_ERR_RANGE (n.z <= 0: the normal not above the tangent plane); GGX_ERR_ALPHA
 * as for ggx_shape_aniso; GGX_ERR_SINGULAR or GGX_ERR_RANGE from ggx_shape_from_slopes where the lobe is not a shape:
 * a steep normal with a small alpha (|t| beyond about 1e4 alpha^(2/3): n.z 0.03 at alpha 1e-4, 5e-4 at alpha 0.1,
 * 1e-4 at alpha 1) or alphas far apart (1e-4 with 1e4). out is unchanged on error. */
ggx_status ggx_texel_lobe(ggx_shape *out, ggx_vec3 n, double alpha_x, double alpha_y, double phi);

/* Options; a zeroed struct (or NULL) means every default. */
typedef struct ggx_filter_options {
    int max_iterations; /* EM iterations at most; 0: 500 */
    double tolerance;   /* stop when an iteration moves t and Sigma by less than this in Sigma's own scale (the
                         * largest |dt_i| / sqrt(Sigma_ii), |dSigma_ij| / sqrt(Sigma_ii Sigma_jj)); 0: 1e-10 */
    int radial_nodes;   /* the quadrature of each lobe (below): Gauss-Legendre nodes in the radius, at least 2;
                         * 0: 8 (ggx_filter_kl: 32) */
    int angular_nodes;  /* and equally spaced angles, even, at least 4; 0: 16 (ggx_filter_kl: 64) */
    int threads;        /* POSIX threads for ggx_filter_downsample (results do not depend on it); 0: 1 */
} ggx_filter_options;
/* The fast mode, which ggx_filter_options_fast sets: radial_nodes 2, angular_nodes 4, max_iterations 1, one EM
 * step from the start of ggx_filter_lobes, 30 to 80 times faster than the defaults. Its KL from the mixture exceeds the converged fit's by
 * at most 0.005 nats on the footprints of tests/unit/test_filter.c (against 0.02 to 2.4 nats by which the engines'
 * filters exceed it there), and by up to 0.035 on random 2 x 2 footprints whose slopes spread over 8 alpha (alpha 0.05). */

/* Sets o's rule and iterations to the fast mode above, leaving its tolerance and threads. Errors: GGX_ERR_NULL. */
ggx_status ggx_filter_options_fast(ggx_filter_options *o);

typedef struct ggx_filter_info {
    int iterations;        /* EM iterations made */
    int converged;         /* 1 when the last iteration met the tolerance */
    double log_likelihood; /* the mixture's expected log P22 of the result (slope space), by the quadrature */
} ggx_filter_info;

/* The single ellipsoid closest to the mixture of n lobes with weights weight[i] >= 0 (relative; NULL: equal): the
 * maximiser of sum_i w_i E_i[log P22_out(x~)], E_i the expectation over lobe i's slopes, equivalently the least KL
 * divergence from the mixture (ggx_filter_kl). By EM for the Student t (PX-EM, the fits' M-step; ggx_fit.h) with
 * each lobe's expectations by a product rule in its own standardised slopes: radial_nodes Gauss-Legendre nodes in s,
 * where u = 1 - (1 - s)^2 is the lobe's radial probability, times angular_nodes equal angles. The rule integrates
 * the E-step of a lobe at its own parameters exactly, so n equal lobes (a constant normal map) give that lobe back
 * to rounding: D within ggx_shape_from_slopes' 1e-12 + 2e-15 kappa^2 relative (tests/unit/test_filter.c); its error for
 * distinct lobes, measured against 64 x 128 nodes, is in docs/design/filter.md. Each iteration never lowers the
 * objective as the rule computes it (to rounding). Starts from t = the weighted mean of the lobes' t_i, Sigma = the
 * weighted mean of Sigma_i + (t_i - t)(t_i - t)^T. Sigma's eigenvalues are held in [GGX_ALPHA_MIN^2,
 * GGX_ALPHA_MAX^2]. info may be NULL. Errors: GGX_ERR_NULL (out or lobes NULL); GGX_ERR_RANGE (n = 0, a weight
 * negative, NaN or infinite, all weights 0 or their sum overflowing, or a bad option: iterations or nodes below 0, 1
 * radial node, 2 angular nodes or an odd count, more than 1024 radial or 4096 angular nodes, a tolerance NaN or
 * below 0, threads below 0 or above 1024); GGX_ERR_MEMORY; GGX_ERR_ALPHA, GGX_ERR_SINGULAR or GGX_ERR_RANGE from
 * ggx_shape_from_slopes when the result is not a shape. out is unchanged on error. */
ggx_status ggx_filter_lobes(ggx_shape *out, const ggx_shape *lobes, const double *weight, size_t n,
                            const ggx_filter_options *opt, ggx_filter_info *info);

/* KL(mixture || s) = sum_i w_i E_i[log(mix(x~) / P22_s(x~))] in slope space, by the rule of ggx_filter_lobes for
 * each lobe (32 x 64 nodes unless opt sets them); mix is the weighted mixture of the lobes' P22 (weights as there).
 * The exact integral is >= 0; the rule's error, which can take it below 0, is that of integrating log mix: rounding
 * for equal lobes, about 5e-3 where a narrow lobe of small weight sits inside a wide one (alpha 0.03 at weight 3 %
 * inside alpha 1: 0.0026 against 0.0072 at 128 x 256; 8 x 16 gives -0.013). O(n^2) in the lobes. Errors:
 * GGX_ERR_NULL (s, lobes or kl NULL), GGX_ERR_RANGE and GGX_ERR_MEMORY as ggx_filter_lobes. */
ggx_status ggx_filter_kl(const ggx_shape *s, const ggx_shape *lobes, const double *weight, size_t n,
                         const ggx_filter_options *opt, double *kl);

/* A texel of a mip chain of lobes: GGX_LOBE_PARAMS doubles, (t_x, t_y, Sigma_xx, Sigma_xy, Sigma_yy), its slopes'
 * location and scale as ggx_shape_slopes gives them (and ggx_shape_from_slopes takes them back). */
enum { GGX_LOBE_PARAMS = 5 };

/* The texels of a map (level 0 of a chain): lobes[GGX_LOBE_PARAMS i] the slope parameters of ggx_texel_lobe of
 * normals[i] and weight[i] = 1, or, for a normal that ggx_texel_lobe refuses (NaN, infinite, zero, not above the
 * tangent plane, too steep), the placeholder of ggx_filter_downsample with weight 0: the texel is rejected, and
 * counted in *rejected when rejected is not NULL. Errors: GGX_ERR_NULL (lobes, weight or normals NULL);
 * GGX_ERR_NONFINITE, GGX_ERR_ALPHA or GGX_ERR_SINGULAR for the roughness as ggx_texel_lobe gives them at n = +z,
 * before anything is written. */
ggx_status ggx_texel_lobes(double *lobes, double *weight, const ggx_vec3 *normals, size_t n, double alpha_x,
                           double alpha_y, double phi, size_t *rejected);

/* ggx_texel_lobes with a roughness map: texel i has roughness alpha_x[i] along x and alpha_y[i] along y (alpha_y
 * NULL: alpha_x[i] along both), its axis x at the angle phi for every texel. A map value in [0, GGX_ALPHA_MIN) is
 * raised to GGX_ALPHA_MIN (a roughness map's 0 is a mirror); a texel whose value is negative, NaN, infinite or above
 * GGX_ALPHA_MAX, or whose lobe is not a shape, is rejected as a bad normal is (weight 0, counted in *rejected).
 * Errors: GGX_ERR_NULL (lobes, weight, normals or alpha_x NULL); GGX_ERR_NONFINITE (phi NaN or infinite), before
 * anything is written. */
ggx_status ggx_texel_lobes_roughness(double *lobes, double *weight, const ggx_vec3 *normals, const double *alpha_x,
                                     const double *alpha_y, size_t n, double phi, size_t *rejected);

/* One level of a mip chain: out, ceil(w / 2) x ceil(h / 2) texels, from in, w x h texels (both row-major, texel (x,
 * y) at GGX_LOBE_PARAMS (y w + x)). Each texel of out is ggx_filter_lobes of its box of in's texels (without the
 * round trip through ggx_shape), weighted by w_in (NULL: all 1): the 2 x 2 texels from (2x, 2y), cut to 2 x 1, 1 x 2
 * or 1 x 1 at an odd last column or row (so sizes that are not powers of two keep every texel once); a box of one
 * texel of nonzero weight is copied. w_out (may be NULL) receives each box's total weight: a texel of weight 0 (a
 * rejected normal) counts nowhere, and a box of nothing but such texels has weight 0 and the flat lobe of alpha 1 (t
 * = 0, Sigma = I) as a placeholder. Repeated down to 1 x 1 it builds the chain; a level is the filter of the level
 * above (the exact filter of all of a coarse texel's base texels is ggx_filter_lobes of them). opt: rule, tolerance
 * and threads; results do not depend on the thread count. Errors: GGX_ERR_NULL (out or in); GGX_ERR_RANGE (w or h 0,
 * the size overflowing, a weight negative, NaN or above 1e300, a texel of nonzero weight whose parameters
 * ggx_shape_from_slopes refuses, or a bad option as for ggx_filter_lobes), before anything is written;
 * GGX_ERR_MEMORY. */
ggx_status ggx_filter_downsample(double *out, double *w_out, const double *in, const double *w_in, size_t w, size_t h,
                                 const ggx_filter_options *opt);

#ifdef __cplusplus
}
#endif

#endif
