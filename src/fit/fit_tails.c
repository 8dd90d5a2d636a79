/* The Student-t slope family of free nu (ggx_fit_tails): ECM from the ellipsoid's GGX fit, its information by
 * differences of the analytic gradient (docs/design/fit.md, "How far from GGX"). SPDX-License-Identifier: MIT */
#include <math.h>
#include <string.h>

#include "fit.h"

/* eta = log(g - 1) = log(nu / 2), held in [log 0.05, log 5000]: nu in [0.1, 1e4] */
#define ETA_MIN (-2.995732273553991)
#define ETA_MAX 8.517193191416238
enum { TAILS_P = 6, TAILS_MAX_ITERATIONS = 500 };

/* One E-step pass at (t, Sigma, eta): the pass at P / (g - 1) makes c = 1 / (1 + delta / (g - 1)) and sum w log(1 +
 * delta / (g - 1)), from which come the log-likelihood per sample, the M step's sums (a) and, when g is not NULL, the
 * gradient of the total log-likelihood in units of W over (t_x, t_y, Sigma_xx, Sigma_xy, Sigma_yy, eta):
 *   d/dt = 2 k P sum w c r,  d/dSigma = -W P / 2 + k P (sum w c r r^T) P  (k = g / (g - 1)),
 *   d/deta = g (W - sum w c) - (g - 1) sum w log(1 + delta / (g - 1)). */
static ggx_status tails_pass(const fit_data *d, const double t[2], const double s[3], double eta,
                             double a[FIT_ESTEP_SUMS], double *ll, double g[TAILS_P])
{
    double gm1 = exp(eta), gam = 1.0 + gm1, k = gam / gm1, p[3];
    if (!fit_inverse(s, p)) return GGX_ERR_SINGULAR;
    fit_point at = {{t[0], t[1]}, {p[0] / gm1, p[1] / gm1, p[2] / gm1}, {0, 0, 0}, 0, 0};
    ggx_status st = fit_pass(d->src, d->threads, FIT_PASS_ESTEP, &at, a);
    if (st != GGX_OK) return st;
    const double W = a[0];
    *ll = -log(GGX_PI) - 0.5 * fit_log_det(s) - gam * a[7] / W - 3.0 * d->mean_lc;
    if (!g) return GGX_OK;
    const double S[3] = {a[4], a[5], a[6]};
    g[0] = 2.0 * k * (p[0] * a[2] + p[1] * a[3]), g[1] = 2.0 * k * (p[1] * a[2] + p[2] * a[3]);
    double ps00 = p[0] * S[0] + p[1] * S[1], ps01 = p[0] * S[1] + p[1] * S[2];
    double ps10 = p[1] * S[0] + p[2] * S[1], ps11 = p[1] * S[1] + p[2] * S[2];
    double q00 = ps00 * p[0] + ps01 * p[1], q01 = ps00 * p[1] + ps01 * p[2], q11 = ps10 * p[1] + ps11 * p[2];
    g[2] = -0.5 * W * p[0] + k * q00;
    g[3] = 2.0 * (-0.5 * W * p[1] + k * q01);
    g[4] = -0.5 * W * p[2] + k * q11;
    g[5] = gam * (W - a[1]) - gm1 * a[7];
    return GGX_OK;
}

/* The Hessian of the total log-likelihood (scaled to n_eff) at th = (t, Sigma, eta) by central differences of the
 * gradient, steps of 1e-4 of each parameter's scale; its negative's inverse in cov, the Newton decrement in *dec.
 * Returns 0 when -H is not positive definite (cov then NaN). */
static ggx_status tails_information(const fit_data *d, const double th[TAILS_P], double cov[TAILS_P][TAILS_P],
                                    double *dec, int *passes)
{
    double a[FIT_ESTEP_SUMS], ll, g0[TAILS_P], nh[FIT_MAX_P][FIT_MAX_P], inv[FIT_MAX_P][FIT_MAX_P];
    ggx_status st = tails_pass(d, th, th + 2, th[5], a, &ll, g0);
    if (st != GGX_OK) return st;
    const double scale = d->n_eff / a[0], ex = sqrt(th[2]), ey = sqrt(th[4]);
    const double h[TAILS_P] = {1e-4 * ex, 1e-4 * ey, 1e-4 * th[2], 1e-4 * ex * ey, 1e-4 * th[4], 1e-4};
    double D[TAILS_P][TAILS_P];
    for (int j = 0; j < TAILS_P; j++) {
        double tp[TAILS_P], tm[TAILS_P], gp[TAILS_P], gm[TAILS_P];
        memcpy(tp, th, sizeof tp), memcpy(tm, th, sizeof tm);
        tp[j] += h[j], tm[j] -= h[j];
        if ((st = tails_pass(d, tp, tp + 2, tp[5], a, &ll, gp)) != GGX_OK) return st;
        if ((st = tails_pass(d, tm, tm + 2, tm[5], a, &ll, gm)) != GGX_OK) return st;
        for (int i = 0; i < TAILS_P; i++) D[i][j] = (gp[i] - gm[i]) / (2.0 * h[j]) * scale;
    }
    *passes += 1 + 2 * TAILS_P;
    for (int i = 0; i < TAILS_P; i++)
        for (int j = 0; j < TAILS_P; j++) nh[i][j] = -0.5 * (D[i][j] + D[j][i]);
    *dec = HUGE_VAL;
    for (int i = 0; i < TAILS_P; i++)
        for (int j = 0; j < TAILS_P; j++) cov[i][j] = NAN;
    if (!fit_spd_inverse(TAILS_P, nh, inv)) return GGX_OK;
    double lam2 = 0.0;
    for (int i = 0; i < TAILS_P; i++)
        for (int j = 0; j < TAILS_P; j++) lam2 += g0[i] * scale * inv[i][j] * g0[j] * scale, cov[i][j] = inv[i][j];
    *dec = sqrt(fmax(lam2, 0.0));
    return GGX_OK;
}

/* ECM: each iteration one pass at (t, Sigma, eta) gives the M step of (t, Sigma) at that eta (PX-EM's update, the
 * same for every nu: fit_mstep) and d/deta; a second pass at eta + 1e-3 gives its difference, and eta takes the
 * Newton step of that one-dimensional profile (at most 1 in eta, within its range). */
/* The tails not fitted: nu, its error, the likelihood and BIC NaN. */
static void unfitted(ggx_fit_tails *out)
{
    memset(out, 0, sizeof *out);
    out->nu = out->nu_std_error = out->log_likelihood = out->bic = NAN;
}

static ggx_status tails_run(const fit_data *d, const double t0[2], const double sigma0[3], ggx_fit_tails *out)
{
    unfitted(out);
    if (d->src->censored) return GGX_OK;
    double t[2] = {t0[0], t0[1]}, s[3] = {sigma0[0], sigma0[1], sigma0[2]}, eta = 0.0, ll = 0.0;
    int passes = 0, it;
    ggx_status st;
    for (it = 1; it <= TAILS_MAX_ITERATIONS; it++) {
        double a[FIT_ESTEP_SUMS], g[TAILS_P], b[FIT_ESTEP_SUMS], llb, gb[TAILS_P];
        if ((st = tails_pass(d, t, s, eta, a, &ll, g)) != GGX_OK) return st;
        if ((st = tails_pass(d, t, s, eta + 1e-3, b, &llb, gb)) != GGX_OK) return st;
        passes += 2;
        double tn[2], sn[3], curv = (gb[5] - g[5]) / 1e-3, de = curv < 0.0 ? -g[5] / curv : (g[5] > 0 ? 1.0 : -1.0);
        de = fmax(-1.0, fmin(1.0, de));
        double en = fmax(ETA_MIN, fmin(ETA_MAX, eta + de));
        fit_mstep(a, t, GGX_FIT_ELLIPSOID, tn, sn);
        if (fit_clamp_sigma(sn, fit_floor(d, tn))) return GGX_OK; /* at the floor: nothing to measure */
        double ch = fmax(fit_change(t, s, tn, sn), fabs(en - eta));
        memcpy(t, tn, sizeof t), memcpy(s, sn, sizeof s);
        eta = en;
        if (ch <= 1e-3 / sqrt(fmax(d->n_eff, 1.0))) break;
    }
    double th[TAILS_P] = {t[0], t[1], s[0], s[1], s[2], eta}, cov[TAILS_P][TAILS_P], dec, a[FIT_ESTEP_SUMS];
    if ((st = tails_information(d, th, cov, &dec, &passes)) != GGX_OK) return st;
    if ((st = tails_pass(d, t, s, eta, a, &ll, NULL)) != GGX_OK) return st;
    passes++;
    const double nu = fmin(fmax(2.0 * exp(eta), 0.1), 1e4); /* the range exactly, whatever exp rounds to */
    int at_end = eta <= ETA_MIN + 1e-9 || eta >= ETA_MAX - 1e-9;
    out->nu = nu;
    out->nu_std_error = at_end ? NAN : nu * sqrt(cov[5][5]); /* d nu = nu d eta */
    out->log_likelihood = ll;
    out->bic = -2.0 * d->n_eff * ll + TAILS_P * log(d->n_eff);
    out->t[0] = t[0], out->t[1] = t[1];
    memcpy(out->sigma, s, sizeof out->sigma);
    out->iterations = passes;
    out->converged = dec <= 1e-2 || at_end;
    return GGX_OK;
}

/* A start held at the floor, or a step that leaves Sigma singular (any failure but memory), leaves the tails unfitted,
 * never the fit. */
ggx_status fit_tails(const fit_data *d, const double t0[2], const double sigma0[3], int held, ggx_fit_tails *out)
{
    ggx_status st = held ? GGX_ERR_SINGULAR : tails_run(d, t0, sigma0, out);
    if (st == GGX_OK || st == GGX_ERR_MEMORY) return st;
    unfitted(out);
    return GGX_OK;
}
