/* The fit of a source of slopes: the four models of ggx_fit_info fitted to the same samples, their BIC, and the
 * goodness of fit of the chosen one. SPDX-License-Identifier: MIT */
#include <string.h>

#include "common/chi2_tail.h"
#include "fit.h"

ggx_status fit_settings(const ggx_fit_options *opt, fit_data *d, ggx_fit_model *model)
{
    ggx_fit_options o;
    memset(&o, 0, sizeof o);
    if (opt) o = *opt;
    if (o.model != GGX_FIT_ELLIPSOID && o.model != GGX_FIT_ANISOTROPIC && o.model != GGX_FIT_ISOTROPIC)
        return GGX_ERR_RANGE;
    if (o.threads < 0 || o.threads > 256 || o.max_iterations < 0 || !(o.tolerance >= 0.0)) return GGX_ERR_RANGE;
    d->threads = o.threads ? o.threads : 1;
    d->max_iterations = o.max_iterations ? o.max_iterations : 1000;
    d->tolerance = o.tolerance > 0.0 ? o.tolerance : 1e-6;
    d->progress = o.progress;
    d->progress_ctx = o.progress_ctx;
    d->full_em = o.full_em != 0;
    *model = o.model;
    return GGX_OK;
}

/* The Gaussian (Beckmann) fit from the sums a of a moments pass about c (near the mean, so that a large mean slope
 * costs no accuracy): the weighted mean and covariance and the log-likelihood per sample. */
/* The weighted mean and covariance (about the mean) from the sums a of a moments pass about c. */
static void gaussian_moments(const double a[FIT_MOMENT_SUMS], const double c[2], double mean[2], double cov[3])
{
    double dx = a[1] / a[0], dy = a[2] / a[0]; /* the mean less c */
    mean[0] = c[0] + dx, mean[1] = c[1] + dy;
    cov[0] = a[3] / a[0] - dx * dx, cov[1] = a[4] / a[0] - dx * dy, cov[2] = a[5] / a[0] - dy * dy;
}

static void fit_gaussian(const fit_data *d, const double a[FIT_MOMENT_SUMS], const double c[2], double mean[2],
                         double cov[3], double *ll)
{
    double s[3];
    gaussian_moments(a, c, mean, s);
    memcpy(cov, s, sizeof s);
    fit_clamp_sigma(cov, 0.5 * fit_floor(d, mean));
    double p[3];
    fit_inverse(cov, p);
    double quad = p[0] * s[0] + 2.0 * p[1] * s[1] + p[2] * s[2]; /* E[r^T C^-1 r] = tr(C^-1 S) */
    *ll = -log(2.0 * GGX_PI) - 0.5 * fit_log_det(cov) - 0.5 * quad - 3.0 * d->mean_lc;
}

/* The Gaussian fit of cells (fit.h, "censored"): EM from the moments' fit (mean, cov), each pass weighting the
 * cells' points by their shares under the current Gaussian, until the parameters move by less than 1e-10 of their
 * scale (the iterate kept) or 1000 passes; its log-likelihood per sample, the mean log P(cell). */
static ggx_status fit_gaussian_cells(const fit_data *d, double mean[2], double cov[3], double *ll)
{
    for (int it = 0; it < 1000; it++) {
        fit_point at = {{mean[0], mean[1]}, {0, 0, 0}, {0, 0, 0}, 0, 1};
        if (!fit_inverse(cov, at.p)) return GGX_ERR_SINGULAR;
        double a[FIT_MOMENT_SUMS];
        ggx_status st = fit_pass(d->src, d->threads, FIT_PASS_MOMENTS, &at, a);
        if (st != GGX_OK) return st;
        *ll = -log(2.0 * GGX_PI) - 0.5 * fit_log_det(cov) + a[6] / a[0]; /* at (mean, cov) */
        double mn[2], cn[3];
        gaussian_moments(a, mean, mn, cn);
        fit_clamp_sigma(cn, 0.5 * fit_floor(d, mn));
        if (fit_change(mean, cov, mn, cn) <= 1e-10 || it == 999) break; /* (mean, cov) and its likelihood kept */
        memcpy(mean, mn, sizeof mn);
        memcpy(cov, cn, sizeof cn);
    }
    return GGX_OK;
}

/* Pearson's statistic of the chosen fit on equal-probability cells of the standardised slopes (ggx_fit.h). */
static ggx_status goodness_of_fit(const fit_data *d, const fit_result *r, int parameters, ggx_fit_info *info)
{
    info->gof_chi2 = info->gof_pvalue = NAN;
    if (d->src->censored) return GGX_OK; /* no test of cells here: ggx_fit_normal_cells */
    int K = (int)floor(sqrt(d->n_eff / 20.0));
    if (K > FIT_MAX_CELLS) K = FIT_MAX_CELLS;
    int dof = K * K - 1 - parameters;
    info->gof_cells = K;
    info->gof_dof = dof > 0 ? dof : 0;
    info->gof_chi2 = info->gof_pvalue = NAN;
    if (dof < 1) return GGX_OK;
    double l00 = sqrt(r->sigma[0]), l10 = r->sigma[1] / l00, l11 = sqrt(fmax(r->sigma[2] - l10 * l10, 0.0));
    if (!(l11 > 0.0)) return GGX_OK;
    fit_point at = {{r->t[0], r->t[1]}, {0, 0, 0}, {1.0 / l00, -l10 / (l00 * l11), 1.0 / l11}, K, 0};
    double cells[FIT_MAX_CELLS * FIT_MAX_CELLS];
    ggx_status st = fit_pass(d->src, d->threads, FIT_PASS_CELLS, &at, cells);
    if (st != GGX_OK) return st;
    double e = d->n_eff / (K * K), x2 = 0.0, scale = d->n_eff / d->w_sum;
    for (int i = 0; i < K * K; i++) x2 += (cells[i] * scale - e) * (cells[i] * scale - e) / e;
    info->gof_chi2 = x2;
    info->gof_pvalue = ggx_chi2_upper(x2, dof);
    return GGX_OK;
}

/* A subsample of a source: piece b of the FIT_SUBSAMPLE_N / FIT_PIECE is the parent's whole piece
 * floor(b * pieces / sub_pieces) of FIT_PIECE samples, spread evenly from the first to the last (over a height
 * field's rows, every row's cells in turn). The passes read chunks aligned on FIT_CHUNK, a whole number of pieces. */
typedef struct subsample {
    const fit_source *parent;
    size_t pieces; /* the parent's whole pieces */
} subsample;

static double fill_subsample(const void *ctx, const fit_point *at, size_t i0, size_t k, double *x, double *y, double *w)
{
    const subsample *c = ctx;
    const size_t np = FIT_SUBSAMPLE_N / FIT_PIECE;
    double own = 0.0;
    for (size_t a = 0; a < k; a += FIT_PIECE) {
        size_t b = (i0 + a) / FIT_PIECE, pb = (size_t)((double)b * (double)c->pieces / (double)np);
        size_t kk = k - a < FIT_PIECE ? k - a : FIT_PIECE;
        own += c->parent->fill(c->parent->ctx, at, pb * FIT_PIECE, kk, x + a, y + a, w + a);
    }
    return own;
}

/* W, n_eff, the mean log cos theta and the mean slope of a source's samples, from one moments pass about c, whose
 * sums go to a. */
static ggx_status fit_constants(fit_data *d, const double c[2], double a[FIT_MOMENT_SUMS])
{
    fit_point at = {{c[0], c[1]}, {0, 0, 0}, {0, 0, 0}, 1, 0}; /* cells = 1: with the log cos theta */
    ggx_status st = fit_pass(d->src, d->threads, FIT_PASS_MOMENTS, &at, a);
    if (st != GGX_OK) return st;
    if (!(a[0] > 0.0)) return GGX_ERR_DATA;
    d->w_sum = a[0];
    d->n_eff = d->src->censored ? d->src->n_eff : a[0] * a[0] / a[7];
    d->mean_lc = d->src->censored ? 0.0 : a[6] / a[0]; /* censored: the cells' probabilities need no Jacobian */
    d->mean0[0] = c[0] + a[1] / a[0], d->mean0[1] = c[1] + a[2] / a[0];
    return GGX_OK;
}

/* A fit held at the floor (Sigma's eigenvalues at it) with its lobe away from n can be a shape whose ellipsoid
 * alphas fall below GGX_ALPHA_MIN, which the shape's constructors raise (ggx_shape_ellipsoid, ggx_ellipsoid_matrix):
 * its printed alphas, matrix and (t, Sigma) would be three shapes. r becomes the nearest shape they keep, its alphas
 * raised to GGX_ALPHA_MIN (t kept, Sigma that shape's, the likelihood there, the covariance 0 as for any fit held at
 * the floor). */
static ggx_status representable(const fit_data *d, ggx_fit_model model, fit_result *r)
{
    ggx_shape s;
    double ax, ay, tx, ty, tz, dec;
    ggx_status st = ggx_shape_from_slopes(&s, r->t[0], r->t[1], r->sigma[0], r->sigma[1], r->sigma[2]);
    if (st != GGX_OK) return st;
    ggx_shape_ellipsoid_params(&s, &ax, &ay, &tx, &ty, &tz);
    if (fmin(ax, ay) >= GGX_ALPHA_MIN * (1.0 - 1e-7)) return GGX_OK; /* to rounding: at the floor exactly */
    if ((st = ggx_shape_ellipsoid(&s, fmax(ax, GGX_ALPHA_MIN), fmax(ay, GGX_ALPHA_MIN), tx, ty, tz)) != GGX_OK)
        return st;
    /* its Sigma, at the fitted t (the round trip through the angles moves t by about 1e-9) */
    double t[2];
    if ((st = ggx_shape_slopes(&s, t, r->sigma)) != GGX_OK) return st;
    r->sigma[1] += 0.0; /* -0 as 0 */
    if ((st = fit_information(d, model, r->t, r->sigma, &r->log_likelihood, &dec, r->cov, NULL)) != GGX_OK) return st;
    memset(r->cov, 0, sizeof r->cov);
    return GGX_OK;
}

ggx_status fit_run(const fit_source *src, const ggx_fit_options *opt, ggx_shape *out, ggx_fit_info *info)
{
    fit_data d;
    memset(&d, 0, sizeof d);
    ggx_fit_model model;
    ggx_status st = fit_settings(opt, &d, &model);
    if (st != GGX_OK) return st;
    d.src = src;
    d.floor = fmax(src->floor, GGX_ALPHA_MIN * GGX_ALPHA_MIN);
    if (!src->unit_weights && info->used < 5) return GGX_ERR_DATA;
    /* Large inputs: EM on a subsample, Newton on all samples (ggx_fit_options.full_em). The subsample's moments come
     * first: its mean is the centre of the full moments pass, which then gives the Gaussian fit too. */
    subsample sc = {src, src->n / FIT_PIECE};
    fit_source sub_src = {
        fill_subsample, &sc, FIT_SUBSAMPLE_N, 0, src->censored, src->n_eff * (double)FIT_SUBSAMPLE_N / (double)src->n,
        src->floor};
    fit_data ds = d;
    ds.src = &sub_src;
    ds.tolerance = fmax(d.tolerance, 1e-2); /* the steps on all samples finish the fit */
    double a[FIT_MOMENT_SUMS], zero[2] = {0.0, 0.0};
    int two_stage = !d.full_em && src->n > FIT_SUBSAMPLE_MIN;
    if (two_stage) {
        st = fit_constants(&ds, zero, a);
        if (st == GGX_ERR_DATA) two_stage = 0; /* a subsample of skipped samples only */
        else if (st != GGX_OK) return st;
    }
    double centre[2] = {two_stage ? ds.mean0[0] : 0.0, two_stage ? ds.mean0[1] : 0.0};
    st = fit_constants(&d, centre, a);
    if (src->unit_weights) { /* the count from the first pass: W samples of weight 1 */
        info->used = st == GGX_OK ? (size_t)d.w_sum : 0;
        info->ignored_nonfinite = src->n - info->used;
        if (st == GGX_OK && info->used < 5) st = GGX_ERR_DATA;
    }
    if (st != GGX_OK) return st;
    info->effective_n = d.n_eff;

    double mean[2], cov[3], gll;
    if (!two_stage) { /* a second pass about the mean */
        fit_point at = {{d.mean0[0], d.mean0[1]}, {0, 0, 0}, {0, 0, 0}, 0, 0};
        if ((st = fit_pass(src, d.threads, FIT_PASS_MOMENTS, &at, a)) != GGX_OK) return st;
        centre[0] = d.mean0[0], centre[1] = d.mean0[1];
    }
    fit_gaussian(&d, a, centre, mean, cov, &gll);
    if (src->censored && (st = fit_gaussian_cells(&d, mean, cov, &gll)) != GGX_OK) return st;
    ggx_fit_model_result *mr = info->models;
    mr[GGX_FIT_BECKMANN] = (ggx_fit_model_result){gll, 0.0, 5, 0, {mean[0], mean[1]}, {cov[0], cov[1], cov[2]}};

    /* The three Student-t models start at t = 0 and Sigma = floor I (GGX_ALPHA_MIN^2), a start no outlier can move:
     * there every delta is large, the first M step weights each slope by about 1 / |x~|^2 and lands on a robust scale
     * (a start at the Gaussian's covariance, which one slope near the horizon can make 1e196, took hundreds of
     * iterations or overflowed). */
    const double t0[2] = {0.0, 0.0}, s0[3] = {d.floor, 0.0, d.floor};
    fit_result fr[3];
    for (int k = 0; k < 3; k++) {
        ggx_fit_model mk = (ggx_fit_model)k;
        fit_data dk = two_stage ? ds : d;
        if (mk != model) dk.progress = NULL;
        if ((st = fit_em(&dk, mk, t0, s0, &fr[k])) != GGX_OK) return st;
        if (two_stage && fr[k].stopped) { /* stopped in the first stage: the full samples' likelihood and
                                            * information at the iterate, as every stopped fit reports */
            double dec;
            if ((st = fit_information(&d, mk, fr[k].t, fr[k].sigma, &fr[k].log_likelihood, &dec, fr[k].cov, NULL)))
                return st;
            fr[k].stationarity = dec, fr[k].converged = 0;
        } else if (two_stage && !fr[k].clamped) {
            fit_data dn = d;
            /* the models compared need their likelihood only, to within decrement^2 / 2 <= 5e-5 of its maximum's
             * total (far below the BIC's differences); the fitted one its exact information too */
            if (mk != model) dn.progress = NULL, dn.tolerance = fmax(d.tolerance, 1e-2);
            if ((st = fit_newton(&dn, &ds, mk, &fr[k], mk == model)) != GGX_OK) return st;
        } else if (two_stage) { /* held at the floor: the full samples' likelihood and information there */
            double dec;
            if ((st = fit_information(&d, mk, fr[k].t, fr[k].sigma, &fr[k].log_likelihood, &dec, fr[k].cov, NULL)))
                return st;
            memset(fr[k].cov, 0, sizeof fr[k].cov);
        }
        if (fr[k].clamped && (st = representable(&d, mk, &fr[k])) != GGX_OK) return st;
        mr[k] = (ggx_fit_model_result){fr[k].log_likelihood,     0.0,
                                       fit_model_parameters(mk), fr[k].iterations,
                                       {fr[k].t[0], fr[k].t[1]}, {fr[k].sigma[0], fr[k].sigma[1], fr[k].sigma[2]}};
    }
    /* the tails from the ellipsoid's fit, on the samples its EM ran on */
    const fit_result *fe = &fr[GGX_FIT_ELLIPSOID];
    if ((st = fit_tails(two_stage ? &ds : &d, fe->t, fe->sigma, fe->clamped, &info->tails)) != GGX_OK) return st;
    info->tails.subsample = two_stage && !src->censored;
    info->best = GGX_FIT_ELLIPSOID;
    for (int k = 0; k < GGX_FIT_MODELS; k++) {
        mr[k].bic = -2.0 * d.n_eff * mr[k].log_likelihood + mr[k].parameters * log(d.n_eff);
        if (mr[k].bic < mr[info->best].bic) info->best = (ggx_fit_model)k;
    }

    const fit_result *r = &fr[model];
    ggx_shape s;
    if ((st = ggx_shape_from_slopes(&s, r->t[0], r->t[1], r->sigma[0], r->sigma[1], r->sigma[2])) != GGX_OK) return st;
    info->iterations = r->iterations;
    info->converged = r->converged;
    info->stationarity = r->stationarity;
    info->log_likelihood = r->log_likelihood;
    info->clamped = r->clamped;
    memcpy(info->t, r->t, sizeof info->t);
    memcpy(info->sigma, r->sigma, sizeof info->sigma);
    memcpy(info->covariance, r->cov, sizeof info->covariance);
    for (int i = 0; i < 5; i++) info->std_error[i] = sqrt(fmax(r->cov[i][i], 0.0));
    if ((st = goodness_of_fit(&d, r, fit_model_parameters(model), info)) != GGX_OK) return st;
    *out = s;
    return GGX_OK;
}
