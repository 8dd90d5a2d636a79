/*
 * libggx fits: the shape A of measured normals and height fields, by maximum likelihood.
 *
 * SPDX-License-Identifier: MIT
 *
 * Every fit works in slope space (ggx.h, ggx_shape_slopes): the slopes x~ = (-m.x / m.z, -m.y / m.z) of normals
 * drawn with density D(m) (m.n) follow P22(x~) = 1 / (pi sqrt(det Sigma) (1 + (x~ - t)^T Sigma^-1 (x~ - t))^2),
 * a Student t with 2 degrees of freedom, so fitting A is fitting the location t and the scale Sigma
 * (docs/design/fit.md). Each normal is a sample of D(m) (m.n): a facet of a height field, a texel of a normal map,
 * with a weight proportional to its projected area (m.n times its area). Normals need not be unit length (only the
 * direction is used).
 *
 * Likelihoods are of the normals' density over solid angle, D(m) (m.n) = P22(x~) / cos^3 theta_m, averaged over the
 * samples with their weights ("per sample"). Weights are relative: a fit scales them to sum to Kish's effective
 * sample size n_eff = (sum w)^2 / sum w^2 (n for equal weights), which sets the standard errors and the BIC.
 * Standard errors and the goodness of fit assume independent samples: the facets of a height field are correlated
 * over its correlation length, so there they are lower bounds.
 *
 * Threads: every function may be called from any number of threads at once. Results do not depend on
 * ggx_fit_options.threads (the sums run over fixed blocks, added in one order).
 */
#ifndef GGX_GGX_FIT_H
#define GGX_GGX_FIT_H

#include <stddef.h>

#include "ggx/ggx.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The models a fit compares. The first three are shapes (ellipsoid NDFs); Beckmann is not. */
typedef enum ggx_fit_model {
    GGX_FIT_ELLIPSOID = 0,   /* the full ellipsoid: t and Sigma, 5 parameters */
    GGX_FIT_ANISOTROPIC = 1, /* rotated anisotropic GGX: t = 0, Sigma any, 3 parameters */
    GGX_FIT_ISOTROPIC = 2,   /* isotropic GGX: t = 0, Sigma = alpha^2 I, 1 parameter */
    GGX_FIT_BECKMANN = 3,    /* Gaussian slopes with a mean and a covariance (Beckmann's NDF, rotated, anisotropic
                              * and located), 5 parameters */
    GGX_FIT_MODELS = 4
} ggx_fit_model;

/* Called after each EM iteration with the iteration's number (from 1) and the log-likelihood per sample of the
 * iterate it started from (of the subsample, in the first stage of a large fit: ggx_fit_options.full_em), and after
 * each Newton step of the second stage with the log-likelihood of all samples at the new iterate; a nonzero return
 * stops the fit (ggx_fit_info.converged is then 0). */
typedef int (*ggx_fit_progress_fn)(void *ctx, int iteration, double log_likelihood);

/* Options; a zeroed struct (or NULL) means every default. */
typedef struct ggx_fit_options {
    ggx_fit_model model;          /* the family of `out`: GGX_FIT_ELLIPSOID (default), _ANISOTROPIC or _ISOTROPIC */
    int max_iterations;           /* EM iterations at most per model; 0: 1000 */
    double tolerance;             /* stop when the Newton decrement of the total log-likelihood is below it: one more
                                  * Newton step would move the parameters by about that many standard errors and
                                  * raise log L by about half its square; 0: 1e-6 */
    int threads;                  /* POSIX threads for the passes over the samples; 0: 1 */
    ggx_fit_progress_fn progress; /* may be NULL */
    void *progress_ctx;
    int full_em; /* 0 (default): above 2^22 samples, EM runs on 2^20 of them (pieces of 64 spread
                                  * evenly over the data) and Newton steps on all samples finish the fit (each
                                  * accepted step keeps the likelihood within rounding; the decrement is measured on
                                  * all samples; the other models of the comparison to a decrement of 1e-2, their
                                  * total log-likelihood within 5e-5 of its maximum);
                                  * 1: EM on all samples throughout */
} ggx_fit_options;

/* One model of the comparison, fitted to the same samples. */
typedef struct ggx_fit_model_result {
    double log_likelihood; /* per sample, at the fitted parameters */
    double bic;            /* -2 n_eff log_likelihood + parameters ln n_eff: lower is better supported */
    int parameters;        /* free parameters: 5, 3, 1, 5 */
    int iterations;        /* EM iterations (0 for Beckmann, whose fit is closed-form) */
    double t[2], sigma[3]; /* the fitted location and scale (Sigma_xx, Sigma_xy, Sigma_yy); for Beckmann the slopes'
                            * mean and covariance (alpha_x^2 / 2 etc. for Beckmann's alphas) */
} ggx_fit_model_result;

/* The Student-t slope family of free tails (Ribardiere et al.'s STD; docs/design/fit.md, "How far from GGX"), fitted
 * to the same samples by maximum likelihood:
 *     P(x~) = (1 + delta / (g - 1))^-g / (pi sqrt(det Sigma)),   g = 1 + nu / 2,
 * delta = (x~ - t)^T Sigma^-1 (x~ - t): the bivariate Student t of nu degrees of freedom and scale Sigma / 2. At
 * nu = 2 it is GGX's P22 (the shapes' family), as nu grows it tends to Beckmann's Gaussian of covariance Sigma / 2;
 * nu < 2 has heavier tails than GGX (a peak sharper than its shoulders), nu > 2 lighter (a flatter peak). Not a shape:
 * t and Sigma are its location and scale, and ggx_fit_info's shape is the model asked for. */
typedef struct ggx_fit_tails {
    double nu;           /* in [0.1, 1e4]; NaN when not fitted: cells of a normal map (ggx_fit_normal_cells), whose
                          * shares are of the nu = 2 density, or a fit held at GGX_ALPHA_MIN */
    double nu_std_error; /* from the observed information of (t, Sigma, nu), scaled to n_eff (a lower bound for
                          * correlated samples, as every standard error of a fit); NaN at the range's ends */
    double log_likelihood, bic; /* per sample, of the normals' density as ggx_fit_info's; 6 parameters */
    double t[2], sigma[3];
    int iterations; /* passes over the samples */
    int converged;  /* the Newton decrement of (t, Sigma, log(nu)) below 1e-2 at the end */
    int subsample;  /* 1: fitted on ggx_fit_options.full_em's subsample of 2^20 (inputs above 2^22 samples), its
                     * standard error that estimate's */
} ggx_fit_tails;

typedef struct ggx_fit_info {
    int iterations;        /* EM iterations of the model of `out` */
    int converged;         /* 1 when the closing iterate met the tolerance */
    double stationarity;   /* the Newton decrement sqrt(g^T (-H)^-1 g) of the total log-likelihood at the closing
                            * iterate (g, H its gradient and Hessian in the model's free parameters) */
    double log_likelihood; /* per sample, of `out` */
    double t[2], sigma[3]; /* the fit in slope space: out = ggx_shape_from_slopes of them (ggx_shape_slopes(out)
                            * gives them back to rounding) */
    /* Standard errors of t_x, t_y, Sigma_xx, Sigma_xy, Sigma_yy from the observed information (the inverse of -H at
     * the fit, H scaled to n_eff); 0 for parameters the model fixes, and all 0 when `clamped`. covariance is the
     * full 5 x 5 matrix in the same order. */
    double std_error[5];
    double covariance[5][5];
    /* Goodness of fit of `out`: the slopes standardised by the fit, z = L^-1 (x~ - t) with Sigma = L L^T, have
     * u = |z|^2 / (1 + |z|^2) and the angle of z uniform and independent exactly when the model holds; a
     * cells x cells grid of equal-probability cells in (u, angle) (cells = floor(sqrt(n_eff / 20)), at most 16,
     * so each cell expects at least 20), Pearson's statistic on the weighted counts scaled to n_eff, and its
     * chi-square p-value with cells^2 - 1 - parameters degrees of freedom. gof_pvalue is NaN (and gof_dof 0)
     * when n_eff is too small for that many degrees of freedom to be at least 1 (n_eff < 180 for the ellipsoid). */
    double gof_chi2, gof_pvalue;
    int gof_cells, gof_dof;
    size_t used;              /* samples used */
    size_t ignored_horizon;   /* m.z <= 0: no slope (below or on the horizon, the zero vector) */
    size_t ignored_nonfinite; /* a component or the weight NaN or infinite */
    size_t ignored_weight;    /* weight 0 */
    double effective_n;       /* n_eff */
    int clamped;              /* an eigenvalue of Sigma was held at GGX_ALPHA_MIN^2 (e.g. all normals equal) */
    ggx_fit_model_result models[GGX_FIT_MODELS]; /* every model fitted to the same samples, indexed by ggx_fit_model */
    ggx_fit_model best;                          /* the model of least BIC (of the four above) */
    ggx_fit_tails tails;                         /* how far the slopes' tails are from GGX's */
} ggx_fit_info;

/* Fits the shape of n normals m (weights `weight`, or all 1 when NULL) by maximum likelihood in the family
 * opt->model, by EM (PX-EM: the Student t's weights 2 / (1 + delta_i), delta_i = (x~_i - t)^T Sigma^-1 (x~_i - t),
 * and the scale's update divided by their sum, Liu, Rubin and Wu 1998; the likelihood never decreases), until the
 * Newton decrement is below opt->tolerance or opt->max_iterations (above 2^22 samples, EM on a subsample and then
 * Newton steps that each raise the likelihood of all samples: ggx_fit_options.full_em). Samples below the horizon, non-finite or of
 * weight 0 are ignored and counted. info (may be NULL) receives the fit's statistics and the comparison of all four
 * models. Sigma's eigenvalues are held at GGX_ALPHA_MIN^2 or above (info->clamped says when that binds); a lobe held
 * there away from n whose ellipsoid alphas would fall below GGX_ALPHA_MIN is the shape with them raised to it (*out,
 * info->t and info->sigma are one shape).
 * Errors: GGX_ERR_NULL (out NULL, or m NULL with n > 0); GGX_ERR_RANGE (a negative weight; opt->model Beckmann or
 * unknown; opt->threads outside [0, 256] or max_iterations, tolerance negative); GGX_ERR_DATA (fewer than 5 usable
 * samples); GGX_ERR_MEMORY; GGX_ERR_ALPHA (the fitted Sigma has an eigenvalue above GGX_ALPHA_MAX^2: slopes
 * near the horizon, rougher than any shape); GGX_ERR_SINGULAR (|t| so large that the shape is refused, as
 * ggx_shape_from_slopes).
 * On error out is unchanged and info is zeroed (its used and ignored counts filled, of all n samples). Never NaN in
 * out. */
ggx_status ggx_fit_normals(ggx_shape *out, const ggx_vec3 *m, const double *weight, size_t n,
                           const ggx_fit_options *opt, ggx_fit_info *info);

/* The log-likelihood per sample of n normals (weights as in ggx_fit_normals) under the shape s: the weighted mean of
 * log(D(m) (m.n)) over the usable samples, -HUGE_VAL when there are none. Errors as ggx_fit_normals, through *ll
 * (s, m or ll NULL: GGX_ERR_NULL). */
ggx_status ggx_fit_log_likelihood(const ggx_shape *s, const ggx_vec3 *m, const double *weight, size_t n, double *ll);

/* Fits the shape of normals known only to a cell of their components, the texels of a quantised normal map: texel
 * i's unit normal has n_x in [uv[2 i] - q / 2, uv[2 i] + q / 2] and n_y in [uv[2 i + 1] - q / 2, uv[2 i + 1] + q / 2],
 * and n_z = sqrt(1 - n_x^2 - n_y^2) (the part of the square outside the unit disk holds no normal). For a map that
 * stores (n + 1) / 2 in b-bit integers, uv is the decoded 2 level / (2^b - 1) - 1 of the red and green channels
 * (green negated for a map whose y points down) and q = 2 / (2^b - 1); a blue channel adds a constraint that is not
 * used. The likelihood is that of the cells, the product over texels of P(cell) = the integral of D(m) dn_x dn_y over
 * the texel's square, by an 8 x 8 Gauss-Legendre rule in (n_x, n_y): unlike ggx_fit_normals on the cells' centres,
 * it does not overestimate alpha when alpha is near q (docs/design/fit.md, "Quantised normal maps"). Sigma's
 * eigenvalues are held at (0.4 q)^2 (1 + |t|^2)^3 or above (info->clamped says when that binds), where the rule's
 * relative error in P(cell) is 1e-4 at every t, falling fast above the floor (below it the error grows without
 * bound). A square counts as inside the disk when one of the rule's points is. Texels with the same (uv, q) share one
 * cell, so the cost grows with the distinct cells (at most 65 536 for 8-bit maps), not the texels.
 * info as in ggx_fit_normals, except: log_likelihood (and each model's) is the mean of log P(cell) over the texels,
 * a probability, not the density of ggx_fit_normals; the goodness of fit is not computed (gof_chi2 and gof_pvalue
 * NaN, gof_cells and gof_dof 0); Beckmann's fit is its cells' likelihood too (EM). Texels whose square has no point
 * inside the unit disk are ignored as at the horizon.
 * Errors: as ggx_fit_normals (uv NULL with n > 0: GGX_ERR_NULL); GGX_ERR_RANGE for q not in (0, 2];
 * GGX_ERR_NONFINITE for q NaN or infinite. */
ggx_status ggx_fit_normal_cells(ggx_shape *out, const double *uv, const double *weight, size_t n, double q,
                                const ggx_fit_options *opt, ggx_fit_info *info);

/* Height fields: heights h[j * nx + i] at (i dx, j dy) on a regular nx x ny grid (nx, ny >= 2). */
typedef struct ggx_heightfield_options {
    int keep_tilt;  /* 0 (default): the least-squares plane is removed first (levelling, as surface metrology does),
                     * so the fit's t is the surface's skew about its mean plane (0 for a stationary random surface);
                     * 1: the heights are used as given, and a tilt becomes t */
    int downsample; /* k >= 2: heights averaged over k x k blocks first (spacing k dx, k dy; trailing rows and
                     * columns that do not fill a block are dropped), since a measured NDF depends on the scale at
                     * which the slopes are taken; 0 or 1: none */
} ggx_heightfield_options;

/* Fits the shape of the facets of the height field. The surface is piecewise linear over each cell's two triangles;
 * both triangulations are used (the two diagonals), each triangle weighted by its projected area, dx dy / 4: the four
 * facet slopes of a cell are then the four pairs of its x and y differences, ((h10 - h00) or (h11 - h01)) / dx with
 * ((h01 - h00) or (h11 - h10)) / dy, and no diagonal is preferred (one triangulation alone would tie the NDF's
 * anisotropy to its diagonal). Heights more than 1e6 times the span of the finite heights' 1st to 99th percentiles
 * from their median (from an even subsample of at most 65 536) are missing, as a non-finite one is: such a height
 * is no measurement, and one finite 1e308 would otherwise overflow the levelling plane and every slope. Cells with a
 * missing height, or whose levelled slopes' squares overflow, are ignored (counted in ignored_nonfinite); levelling
 * uses the other heights. opt and info as in ggx_fit_normals; hopt may be NULL.
 * Errors: GGX_ERR_NULL; GGX_ERR_RANGE (nx or ny below 2, nx * ny overflowing, dx or dy not positive, downsample
 * negative or leaving fewer than 2 x 2 heights); GGX_ERR_NONFINITE (dx or dy NaN or infinite); as ggx_fit_normals. */
ggx_status ggx_fit_heightfield(ggx_shape *out, const double *h, size_t nx, size_t ny, double dx, double dy,
                               const ggx_heightfield_options *hopt, const ggx_fit_options *opt, ggx_fit_info *info);

/* The slopes (x~, y~) of facets [first, first + count) of the height field, as ggx_fit_heightfield takes them
 * (facet k % 4 of cell k / 4, cells row by row; levelled or downsampled by hopt), into slopes[2 k], slopes[2 k + 1];
 * NaN for a cell with a missing height. *total (may be NULL) receives the number of facets,
 * 4 (nx' - 1)(ny' - 1) for the grid after downsampling. Costs a pass over the heights for the levelling plane on
 * every call, so read large ranges. Errors: as ggx_fit_heightfield; GGX_ERR_RANGE for a range past *total. */
ggx_status ggx_heightfield_facets(double *slopes, size_t first, size_t count, const double *h, size_t nx, size_t ny,
                                  double dx, double dy, const ggx_heightfield_options *hopt, size_t *total);

#ifdef __cplusplus
}
#endif

#endif
