/* The fits' internals: a source of slopes, the passes over it (src/fit/fit_pass.c), EM for the Student-t models
 * (src/fit/fit_em.c) and the observed information (src/fit/fit_information.c). SPDX-License-Identifier: MIT */
#ifndef GGX_FIT_INTERNAL_H
#define GGX_FIT_INTERNAL_H

#include <stddef.h>

#include "api/internal.h"
#include "ggx/ggx_fit.h"

/* Samples are read in chunks of FIT_CHUNK into the pass's buffers; the sums are taken over units of FIT_UNIT samples
 * and the units' sums added in order, so results do not depend on the thread count. A subsample is made of pieces
 * of FIT_PIECE samples. */
enum { FIT_CHUNK = 1024, FIT_UNIT = 65536, FIT_PIECE = 64, FIT_MAX_CELLS = 16 };

typedef struct fit_point fit_point;

/* A source of slope samples: fill writes the slopes (x, y) and the weight w (0 for a sample to skip, with finite
 * slopes) of samples [i0, i0 + k), k <= FIT_CHUNK, in any order fixed by (i0, k) (every sum is over a whole range).
 * i0 is a multiple of FIT_PIECE. (The normal's cos theta is 1 / sqrt(1 + x^2 + y^2).) unit_weights: every weight is
 * 0 or 1 and the source's samples are counted by fit_run (used = W, the others ignored as non-finite).
 *
 * censored: the samples are the quadrature points of cells of slopes (src/fit/fit_cells.c), FIT_CELL_POINTS per
 * cell, a cell never split between ranges. fill weights a cell's points by their shares of its probability under
 * the density at `at` (the Student t of (at->t, at->p), or the Gaussian when at->gaussian), times the cell's weight,
 * and returns that density's part of the log-likelihood of the range's cells: L = sum_c n_c log sum_k a_k f_k, with
 * f_k = (1 + delta_k)^-2 (Student t) or exp(-delta_k / 2) (Gaussian). The passes put -L / 2 in the place of the sum
 * of w log(1 + delta) (ESTEP, HESSIAN) and L in that of the sum of w log cos theta (MOMENTS), so that every formula
 * of the likelihood holds with mean_lc = 0. n_eff is the cells' (from their weights). Other sources return 0. */
typedef struct fit_source {
    double (*fill)(const void *ctx, const fit_point *at, size_t i0, size_t k, double *x, double *y, double *w);
    const void *ctx;
    size_t n;
    int unit_weights;
    int censored;
    double n_eff; /* censored sources: (sum n_c)^2 / sum of the texels' squared weights */
    double floor; /* Sigma's eigenvalues are held at or above the larger of this and GGX_ALPHA_MIN^2 (cells: the
                   * narrowest lobe their quadrature resolves) */
} fit_source;

enum { FIT_CELL_POINTS = 64 };

typedef enum fit_pass_kind {
    FIT_PASS_MOMENTS, /* about c = at->t: W, sum w r (2), sum w r r^T (3), sum w log cos theta (0 unless at->cells
                       * is 1), sum w^2 */
    FIT_PASS_ESTEP,   /* at (t, P = Sigma^-1), with c_i = 1 / (1 + delta_i): W, sum w c, sum w c r (2), sum w c r r^T
                       * (3), sum w log(1 + delta) */
    FIT_PASS_HESSIAN, /* at (t, P): the sums of fit_information.c (FIT_HESSIAN_SUMS) */
    FIT_PASS_CELLS /* at (t, L^-1): the weighted counts of the cells x cells grid of ggx_fit_info's goodness of fit */
} fit_pass_kind;

enum { FIT_MOMENT_SUMS = 8, FIT_ESTEP_SUMS = 8, FIT_HESSIAN_SUMS = 23 };

struct fit_point {
    double t[2];
    double p[3];    /* Sigma^-1 (xx, xy, yy) for ESTEP and HESSIAN */
    double linv[3]; /* L^-1 (lower triangular: 00, 10, 11) with Sigma = L L^T, for CELLS */
    int cells;
    int gaussian; /* censored sources: the density of the cells' shares is the Gaussian of mean t and inverse
                     * covariance p (MOMENTS); else the Student t */
};

/* Runs a pass; sums must hold the pass's count (cells^2 for CELLS). GGX_ERR_MEMORY or GGX_OK. */
ggx_status fit_pass(const fit_source *src, int threads, fit_pass_kind kind, const fit_point *at, double *sums);

/* What every model's fit shares: the samples and their constants. */
typedef struct fit_data {
    const fit_source *src;
    int threads;
    double w_sum;    /* W */
    double n_eff;    /* W^2 / sum w^2 */
    double mean_lc;  /* sum w log cos theta / W */
    double mean0[2]; /* the mean slope, from the same pass (about 0) */
    int max_iterations;
    double tolerance;
    ggx_fit_progress_fn progress;
    void *progress_ctx;
    int full_em;  /* ggx_fit_options.full_em */
    double floor; /* the least eigenvalue of Sigma: the source's floor, at least GGX_ALPHA_MIN^2 */
} fit_data;

/* One fitted Student-t model. */
typedef struct fit_result {
    double t[2], sigma[3];
    double log_likelihood; /* per sample */
    double stationarity;
    double cov[5][5];
    int iterations, converged, clamped;
    int stopped; /* the progress callback stopped the fit */
} fit_result;

/* The least eigenvalue of Sigma for a lobe at t: d->floor, times (1 + |t|^2)^3 for cells (fit.h, "censored"), whose
 * squares map to cells (1 + |t|^2)^(3/2) times wider in slope near t than near n (dx~ dy~ = dn_x dn_y / n_z^4 radially
 * n_z^-3): their rule then resolves a lobe at the floor equally well at every t. */
static inline double fit_floor(const fit_data *d, const double t[2])
{
    if (!d->src->censored) return d->floor;
    double k = 1.0 + t[0] * t[0] + t[1] * t[1];
    return d->floor * k * k * k;
}

/* The free parameters of a model: 5, 3 or 1 (Beckmann: 5). */
int fit_model_parameters(ggx_fit_model model);
/* Raises Sigma's eigenvalues to floor (eigenvectors kept); returns whether it changed Sigma. */
int fit_clamp_sigma(double sigma[3], double floor);
/* The same, and lowers them to hi: Sigma's eigenvalues held in [lo, hi]. */
int fit_clamp_sigma_range(double sigma[3], double lo, double hi);
/* The largest change from (t, s) to (tn, sn) in the scale of s: |dt_i| / sqrt(s_ii), |ds_ij| / sqrt(s_ii s_jj)
 * (EM's step, for its stopping rules). */
double fit_change(const double t[2], const double s[3], const double tn[2], const double sn[3]);
/* Sigma^-1 of (xx, xy, yy); 0 when not positive definite. */
int fit_inverse(const double sigma[3], double p[3]);
/* log det Sigma without overflow, for a positive definite Sigma. */
double fit_log_det(const double sigma[3]);
/* The Cholesky factor L (lower triangular, a = L L^T) of a symmetric k x k matrix (k <= FIT_MAX_P), and the inverse of
 * a symmetric positive definite one by it; 0 when not positive definite. */
enum { FIT_MAX_P = 6 };
int fit_cholesky(int k, double a[FIT_MAX_P][FIT_MAX_P], double l[FIT_MAX_P][FIT_MAX_P]);
int fit_spd_inverse(int k, double a[FIT_MAX_P][FIT_MAX_P], double inv[FIT_MAX_P][FIT_MAX_P]);

/* The M step of PX-EM for the Student-t models (docs/design/fit.md) from the sums a of an E step taken about t (the
 * FIT_PASS_ESTEP layout: W, sum w c, sum w c r (2), sum w c r r^T (3), ...; r = x~ - t, c = 1 / (1 + delta)):
 * t' = t + sum w c r / sum w c and Sigma' = 2 sum w c (r - dt)(r - dt)^T / sum w c, with t' = t for the models
 * without a location and Sigma' = tr(Sigma') / 2 I for the isotropic one. Shared by fit_em and ggx_filter_lobes. */
static inline void fit_mstep(const double *a, const double t[2], ggx_fit_model model, double tn[2], double sn[3])
{
    double dt[2] = {0.0, 0.0};
    tn[0] = t[0], tn[1] = t[1];
    if (model == GGX_FIT_ELLIPSOID) {
        dt[0] = a[2] / a[1], dt[1] = a[3] / a[1];
        tn[0] = t[0] + dt[0], tn[1] = t[1] + dt[1];
    }
    sn[0] = 2.0 * (a[4] / a[1] - dt[0] * dt[0]);
    sn[1] = 2.0 * (a[5] / a[1] - dt[0] * dt[1]);
    sn[2] = 2.0 * (a[6] / a[1] - dt[1] * dt[1]);
    if (model == GGX_FIT_ISOTROPIC) sn[0] = sn[2] = 0.5 * (sn[0] + sn[2]), sn[1] = 0.0;
}

/* EM for the Student-t models (ELLIPSOID, ANISOTROPIC, ISOTROPIC), from (t0, sigma0). */
ggx_status fit_em(const fit_data *d, ggx_fit_model model, const double t0[2], const double sigma0[3], fit_result *r);

/* The observed information at (t, sigma) for the model's free parameters: the log-likelihood per sample, the Newton
 * decrement of the total log-likelihood (scaled to n_eff) and the covariance of the five parameters (zero rows for
 * fixed ones). The decrement is HUGE_VAL where -H is not positive definite. */
ggx_status fit_information(const fit_data *d, ggx_fit_model model, const double t[2], const double sigma[3],
                           double *log_likelihood, double *decrement, double cov[5][5], double step[5]);

/* The gradient of the total log-likelihood (scaled to n_eff) at (t, sigma) and the log-likelihood per sample, from
 * one E-step pass (cheaper than the information pass). */
ggx_status fit_gradient(const fit_data *d, const double t[2], const double sigma[3], double *log_likelihood,
                        double g[5]);

/* Steps on all of d's samples from the fit r of a subsample (whose covariance, scaled by the ratio of the effective
 * sizes, stands for the inverse Hessian: quasi-Newton steps, one E-step pass each), with backtracking so that each
 * accepted step keeps the log-likelihood within rounding of the last; then, when exact is set, the information pass
 * at the closing iterate and exact Newton steps until the decrement meets the tolerance. r->iterations counts the
 * steps too; without exact, r->cov and r->stationarity are the approximate ones. */
ggx_status fit_newton(const fit_data *d, const fit_data *sub, ggx_fit_model model, fit_result *r, int exact);

/* Above FIT_SUBSAMPLE_MIN samples the models are fitted by EM on FIT_SUBSAMPLE_N of them (pieces of FIT_PIECE spread
 * evenly over the data), then polished by fit_newton on all of them. */
enum { FIT_SUBSAMPLE_MIN = 1 << 22, FIT_SUBSAMPLE_N = 1 << 20 };

/* The Student-t family of free nu (ggx_fit_tails) on d's samples, from the ellipsoid's fit (t0, sigma0) at nu = 2;
 * not fitted (nu NaN) for censored sources (their cells' shares are of the nu = 2 density) or a start held at the
 * floor (held). */
ggx_status fit_tails(const fit_data *d, const double t0[2], const double sigma0[3], int held, ggx_fit_tails *out);

/* Validates opt (NULL: defaults) into d's settings; GGX_ERR_RANGE for a bad option. */
ggx_status fit_settings(const ggx_fit_options *opt, fit_data *d, ggx_fit_model *model);

/* The fit and the model comparison on a source whose ignored counts the caller has put in *info (info not NULL; its
 * other fields are written here). */
ggx_status fit_run(const fit_source *src, const ggx_fit_options *opt, ggx_shape *out, ggx_fit_info *info);

#endif
