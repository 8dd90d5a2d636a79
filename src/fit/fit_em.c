/* EM for the Student-t models of slopes (nu = 2): PX-EM with the scale's update divided by the sum of the weights
 * (docs/design/fit.md), with Sigma's eigenvalues held at a floor; stopped by the Newton decrement.
 * SPDX-License-Identifier: MIT */
#include <string.h>

#include "fit.h"

int fit_clamp_sigma_range(double s[3], double lo, double hi)
{
    double half = 0.5 * (s[0] - s[2]), rad = hypot(half, s[1]), mean = 0.5 * (s[0] + s[2]);
    double l1 = mean + rad, l2 = mean - rad;
    if (l2 >= lo && l1 <= hi && isfinite(l1)) return 0;
    double phi = 0.5 * atan2(2.0 * s[1], s[0] - s[2]), c = cos(phi), sn = sin(phi);
    if (!(l1 >= lo)) l1 = lo;
    if (!(l2 >= lo)) l2 = lo;
    if (l1 > hi) l1 = hi;
    if (l2 > hi) l2 = hi;
    s[0] = l1 * c * c + l2 * sn * sn;
    s[1] = (l1 - l2) * c * sn;
    s[2] = l1 * sn * sn + l2 * c * c;
    return 1;
}

int fit_clamp_sigma(double s[3], double floor) { return fit_clamp_sigma_range(s, floor, HUGE_VAL); }

double fit_change(const double t[2], const double s[3], const double tn[2], const double sn[3])
{
    double ex = sqrt(s[0]), ey = sqrt(s[2]);
    double c = fmax(fabs(tn[0] - t[0]) / ex, fabs(tn[1] - t[1]) / ey);
    c = fmax(c, fabs(sn[0] - s[0]) / s[0]);
    c = fmax(c, fabs(sn[1] - s[1]) / (ex * ey));
    return fmax(c, fabs(sn[2] - s[2]) / s[2]);
}

ggx_status fit_em(const fit_data *d, ggx_fit_model model, const double t0[2], const double sigma0[3], fit_result *r)
{
    memset(r, 0, sizeof *r);
    double t[2] = {t0[0], t0[1]}, s[3] = {sigma0[0], sigma0[1], sigma0[2]};
    if (model != GGX_FIT_ELLIPSOID) t[0] = t[1] = 0.0;
    if (model == GGX_FIT_ISOTROPIC) s[0] = s[2] = 0.5 * (s[0] + s[2]), s[1] = 0.0;
    r->clamped = fit_clamp_sigma(s, fit_floor(d, t));
    /* the parameter change under which the decrement is computed: an EM step moves the parameters by a fraction of
     * their distance to the maximum, which is about decrement / sqrt(n_eff) in their own scale */
    double check_below = 0.5 * d->tolerance / sqrt(fmax(d->n_eff, 1.0));
    for (int it = 1;; it++) {
        fit_point at = {{t[0], t[1]}, {0, 0, 0}, {0, 0, 0}, 0, 0};
        fit_inverse(s, at.p);
        double a[FIT_ESTEP_SUMS];
        ggx_status st = fit_pass(d->src, d->threads, FIT_PASS_ESTEP, &at, a);
        if (st != GGX_OK) return st;
        double ll = -log(GGX_PI) - 0.5 * fit_log_det(s) - 2.0 * a[7] / a[0] - 3.0 * d->mean_lc;
        r->iterations = it;
        if (d->progress && d->progress(d->progress_ctx, it, ll)) {
            r->stopped = 1;
            break;
        }
        double tn[2], sn[3];
        fit_mstep(a, t, model, tn, sn);
        int clamped = fit_clamp_sigma(sn, fit_floor(d, tn));
        double ch = fit_change(t, s, tn, sn);
        memcpy(t, tn, sizeof t);
        memcpy(s, sn, sizeof s);
        r->clamped = clamped;
        if (clamped && ch <= 1e-12) {
            r->converged = 1; /* held at the floor: no free direction left to measure */
            break;
        }
        if (ch <= check_below || it >= d->max_iterations) {
            double dec;
            st = fit_information(d, model, t, s, &r->log_likelihood, &dec, r->cov, NULL);
            if (st != GGX_OK) return st;
            r->stationarity = dec;
            if (dec <= d->tolerance) {
                r->converged = 1;
                break;
            }
            if (it >= d->max_iterations) break;
            check_below = ch * 0.1;
        }
    }
    memcpy(r->t, t, sizeof t);
    memcpy(r->sigma, s, sizeof s);
    if (r->clamped || !r->converged) { /* the closing iterate's likelihood and information */
        double dec;
        ggx_status st = fit_information(d, model, t, s, &r->log_likelihood, &dec, r->cov, NULL);
        if (st != GGX_OK) return st;
        r->stationarity = r->clamped ? 0.0 : dec;
        if (r->clamped) memset(r->cov, 0, sizeof r->cov);
    }
    return GGX_OK;
}

/* One accepted step from (t, s) along dir, halving up to 8 times; 0 when none keeps log L (within rounding). */
static int line_step(const fit_data *d, double t[2], double s[3], const double dir[5], double *ll, double g[5])
{
    /* near the optimum a step's gain, about decrement^2 / (2 n_eff) per sample, is far below the rounding of the
     * per-sample mean: accept within that rounding */
    double slack = 1e-13 * fmax(1.0, fabs(*ll)), lam = 1.0;
    for (int half = 0; half < 8; half++, lam *= 0.5) {
        double tn[2] = {t[0] + lam * dir[0], t[1] + lam * dir[1]};
        double sn[3] = {s[0] + lam * dir[2], s[1] + lam * dir[3], s[2] + lam * dir[4]}, pinv[3], lln, gn[5];
        if (!fit_inverse(sn, pinv) || fit_clamp_sigma(sn, fit_floor(d, tn))) continue; /* outside the cone: shorter */
        if (fit_gradient(d, tn, sn, &lln, gn) != GGX_OK) return 0;
        if (lln >= *ll - slack) {
            memcpy(t, tn, sizeof tn), memcpy(s, sn, sizeof sn), memcpy(g, gn, 5 * sizeof *g);
            *ll = lln;
            return 1;
        }
    }
    return 0;
}

ggx_status fit_newton(const fit_data *d, const fit_data *sub, ggx_fit_model model, fit_result *r, int exact)
{
    double ll, g[5], C[5][5], ratio = sub->n_eff / d->n_eff;
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++) C[i][j] = r->cov[i][j] * ratio; /* the subsample's (-H)^-1 at the full size */
    ggx_status st = fit_gradient(d, r->t, r->sigma, &ll, g);
    if (st != GGX_OK) return st;
    double dec = HUGE_VAL;
    int stopped = 0;
    r->converged = 0;
    int have_c = 0; /* the subsample's information was positive definite */
    for (int i = 0; i < 5; i++) have_c |= C[i][i] > 0.0;
    if (!have_c) exact = 1; /* no stand-in for the Hessian: measure it */
    for (int it = 0; have_c && it < d->max_iterations; it++) {
        double dir[5], lam2 = 0.0;
        for (int i = 0; i < 5; i++) {
            dir[i] = 0.0;
            for (int j = 0; j < 5; j++) dir[i] += C[i][j] * g[j];
            lam2 += g[i] * dir[i];
        }
        dec = sqrt(fmax(lam2, 0.0));
        if (dec <= d->tolerance) break;
        if (!line_step(d, r->t, r->sigma, dir, &ll, g)) break;
        r->iterations++;
        if (d->progress && d->progress(d->progress_ctx, r->iterations, ll)) {
            stopped = 1;
            break;
        }
    }
    r->log_likelihood = ll;
    r->stationarity = dec;
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++) r->cov[i][j] = C[i][j];
    if (!exact || stopped) {
        r->converged = !stopped && dec <= d->tolerance;
        if (stopped) { /* the closing iterate's likelihood and information, as every stopped fit reports */
            st = fit_information(d, model, r->t, r->sigma, &r->log_likelihood, &r->stationarity, r->cov, NULL);
            if (st != GGX_OK) return st;
        }
        return GGX_OK;
    }
    /* the exact information at the closing iterate; exact Newton steps while it says the tolerance is not met */
    double step[5];
    for (int it = 0; it < 20; it++) {
        st = fit_information(d, model, r->t, r->sigma, &r->log_likelihood, &dec, r->cov, step);
        if (st != GGX_OK) return st;
        r->stationarity = dec;
        if (dec <= d->tolerance || !isfinite(dec)) break;
        ll = r->log_likelihood;
        if (!line_step(d, r->t, r->sigma, step, &ll, g)) break;
        r->iterations++;
        if (d->progress && d->progress(d->progress_ctx, r->iterations, ll)) {
            st = fit_information(d, model, r->t, r->sigma, &r->log_likelihood, &dec, r->cov, NULL);
            r->stationarity = dec;
            r->converged = 0;
            return st;
        }
    }
    r->converged = dec <= d->tolerance;
    return GGX_OK;
}
