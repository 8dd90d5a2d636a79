/* The observed information of the Student-t models: the gradient and Hessian of the log-likelihood in
 * (t_x, t_y, Sigma_xx, Sigma_xy, Sigma_yy), in closed form from one pass (docs/design/fit.md), restricted to a
 * model's free parameters; from them the Newton decrement and the covariance. SPDX-License-Identifier: MIT */
#include <string.h>

#include "fit.h"

int fit_model_parameters(ggx_fit_model model)
{
    return model == GGX_FIT_ANISOTROPIC ? 3 : model == GGX_FIT_ISOTROPIC ? 1 : 5;
}

/* Sigma scaled by its largest diagonal entry first, so that neither the determinant nor the inverse overflows or
 * underflows for any finite Sigma (a Gaussian's covariance with an outlier may reach 1e300). */
int fit_inverse(const double s[3], double p[3])
{
    double m = fmax(fabs(s[0]), fabs(s[2]));
    if (!(m > 0.0) || !(m < HUGE_VAL)) return 0;
    double a = s[0] / m, b = s[1] / m, c = s[2] / m, det = a * c - b * b;
    if (!(det > 0.0) || !(a > 0.0)) return 0;
    p[0] = c / det / m, p[1] = -b / det / m, p[2] = a / det / m;
    return 1;
}

double fit_log_det(const double s[3])
{
    double m = fmax(fabs(s[0]), fabs(s[2]));
    double a = s[0] / m, b = s[1] / m, c = s[2] / m;
    return 2.0 * log(m) + log(a * c - b * b);
}

/* The model's free parameters as columns of J (5 x k). */
static int free_directions(ggx_fit_model model, double J[5][5])
{
    memset(J, 0, sizeof(double) * 25);
    if (model == GGX_FIT_ISOTROPIC) {
        J[2][0] = J[4][0] = 1.0; /* Sigma = s I */
        return 1;
    }
    int k = 0;
    for (int i = model == GGX_FIT_ANISOTROPIC ? 2 : 0; i < 5; i++) J[i][k++] = 1.0;
    return k;
}

int fit_cholesky(int k, double a[FIT_MAX_P][FIT_MAX_P], double l[FIT_MAX_P][FIT_MAX_P])
{
    memset(l, 0, sizeof(double) * FIT_MAX_P * FIT_MAX_P);
    for (int j = 0; j < k; j++) {
        double d = a[j][j];
        for (int m = 0; m < j; m++) d -= l[j][m] * l[j][m];
        if (!(d > 0.0)) return 0;
        l[j][j] = sqrt(d);
        for (int i = j + 1; i < k; i++) {
            double v = a[i][j];
            for (int m = 0; m < j; m++) v -= l[i][m] * l[j][m];
            l[i][j] = v / l[j][j];
        }
    }
    return 1;
}

int fit_spd_inverse(int k, double a[FIT_MAX_P][FIT_MAX_P], double inv[FIT_MAX_P][FIT_MAX_P])
{
    double l[FIT_MAX_P][FIT_MAX_P];
    if (!fit_cholesky(k, a, l)) return 0;
    for (int c = 0; c < k; c++) { /* solve L L^T x = e_c */
        double y[FIT_MAX_P], x[FIT_MAX_P];
        for (int i = 0; i < k; i++) {
            double v = i == c;
            for (int m = 0; m < i; m++) v -= l[i][m] * y[m];
            y[i] = v / l[i][i];
        }
        for (int i = k - 1; i >= 0; i--) {
            double v = y[i];
            for (int m = i + 1; m < k; m++) v -= l[m][i] * x[m];
            x[i] = v / l[i][i];
        }
        for (int i = 0; i < k; i++) inv[i][c] = x[i];
    }
    return 1;
}

/* The gradient of sum w log p from W, Cq = sum w c q and ce = sum w c e (docs/design/fit.md), written once for the
 * information pass and the gradient pass. */
static void gradient(double W, const double Cq[2], const double ce[3], const double p[3], double g[5])
{
    const double trPE[3] = {p[0], 2.0 * p[1], p[2]};
    g[0] = 4.0 * Cq[0], g[1] = 4.0 * Cq[1];
    for (int ab = 0; ab < 3; ab++) g[2 + ab] = -0.5 * W * trPE[ab] + 2.0 * ce[ab];
}

ggx_status fit_gradient(const fit_data *d, const double t[2], const double sigma[3], double *log_likelihood,
                        double g[5])
{
    fit_point at = {{t[0], t[1]}, {0, 0, 0}, {0, 0, 0}, 0, 0};
    if (!fit_inverse(sigma, at.p)) return GGX_ERR_SINGULAR;
    double a[FIT_ESTEP_SUMS];
    ggx_status st = fit_pass(d->src, d->threads, FIT_PASS_ESTEP, &at, a);
    if (st != GGX_OK) return st;
    /* from the E step's sums about t: sum w c q = P sum w c r, sum w c q q^T = P (sum w c r r^T) P */
    const double *p = at.p, S[3] = {a[4], a[5], a[6]};
    double Cq[2] = {p[0] * a[2] + p[1] * a[3], p[1] * a[2] + p[2] * a[3]};
    double ps00 = p[0] * S[0] + p[1] * S[1], ps01 = p[0] * S[1] + p[1] * S[2];
    double ps10 = p[1] * S[0] + p[2] * S[1], ps11 = p[1] * S[1] + p[2] * S[2];
    double q00 = ps00 * p[0] + ps01 * p[1], q01 = ps00 * p[1] + ps01 * p[2], q11 = ps10 * p[1] + ps11 * p[2];
    double ce[3] = {q00, 2.0 * q01, q11};
    gradient(a[0], Cq, ce, p, g);
    double scale = d->n_eff / a[0];
    for (int i = 0; i < 5; i++) g[i] *= scale;
    *log_likelihood = -log(GGX_PI) - 0.5 * fit_log_det(sigma) - 2.0 * a[7] / a[0] - 3.0 * d->mean_lc;
    return GGX_OK;
}

/* The point samples' gradient and Hessian of sum w log p in closed form from one pass at (t, P) (docs/design/fit.md,
 * "Observed information"), in the units of W (*W receives it). */
static ggx_status point_hessian(const fit_data *d, const fit_point *at, const double sigma[3], double *ll, double g[5],
                                double H[5][5], double *Wout)
{
    double a[FIT_HESSIAN_SUMS];
    ggx_status st = fit_pass(d->src, d->threads, FIT_PASS_HESSIAN, at, a);
    if (st != GGX_OK) return st;
    const double W = a[0], C1 = a[1], Cq[2] = {a[2], a[3]};
    const double Cqq[2][2] = {{a[4], a[5]}, {a[5], a[6]}}, C2qq[2][2] = {{a[7], a[8]}, {a[8], a[9]}};
    const double C2qe[2][3] = {{a[10], a[11], a[12]}, {a[13], a[14], a[15]}};
    const double C2ee[3][3] = {{a[16], a[17], a[18]}, {a[17], a[19], a[20]}, {a[18], a[20], a[21]}};
    const double ce[3] = {a[4], 2.0 * a[5], a[6]}; /* sum w c e */
    const double P[2][2] = {{at->p[0], at->p[1]}, {at->p[1], at->p[2]}};
    const double E[3][2][2] = {{{1, 0}, {0, 0}}, {{0, 1}, {1, 0}}, {{0, 0}, {0, 1}}};
    *ll = -log(GGX_PI) - 0.5 * fit_log_det(sigma) - 2.0 * a[22] / W - 3.0 * d->mean_lc;

    /* Gradient and Hessian of sum w log p (docs/design/fit.md, "Observed information"). */
    double PE[3][2][2]; /* P E_ab */
    for (int ab = 0; ab < 3; ab++)
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) PE[ab][i][j] = P[i][0] * E[ab][0][j] + P[i][1] * E[ab][1][j];
    gradient(W, Cq, ce, at->p, g);
    for (int i = 0; i < 2; i++) {
        for (int j = 0; j < 2; j++) H[i][j] = 8.0 * C2qq[i][j] - 4.0 * C1 * P[i][j];
        for (int ab = 0; ab < 3; ab++) {
            double pq = PE[ab][i][0] * Cq[0] + PE[ab][i][1] * Cq[1];
            H[i][2 + ab] = H[2 + ab][i] = 4.0 * C2qe[i][ab] - 4.0 * pq;
        }
    }
    for (int ab = 0; ab < 3; ab++) {
        for (int cd = 0; cd < 3; cd++) {
            double tr_pp = 0.0, tr_q = 0.0; /* tr(P E_cd P E_ab), tr(E_ab P E_cd Cqq) */
            for (int i = 0; i < 2; i++)
                for (int j = 0; j < 2; j++) {
                    tr_pp += PE[cd][i][j] * PE[ab][j][i];
                    double m = 0.0; /* (E_ab P E_cd)[i][j] */
                    for (int k = 0; k < 2; k++) m += E[ab][i][k] * PE[cd][k][j];
                    tr_q += m * Cqq[j][i];
                }
            H[2 + ab][2 + cd] = 0.5 * W * tr_pp + 2.0 * C2ee[ab][cd] - 4.0 * tr_q;
        }
    }
    *Wout = W;
    return GGX_OK;
}

/* For cells (fit.h, "censored"): the gradient is exact (the cells' shares at (t, Sigma) make fit_gradient's the
 * gradient of sum n_c log P(cell), Fisher's identity), and the Hessian its central differences along the columns of
 * L, the Cholesky factor of the points' covariance with the same shares (the inverse of the first term of Louis's
 * formula, which is larger than the cells' information): steps of 1e-2 of L e_k move the parameters by a hundredth of
 * their uncertainty in whitened coordinates, inside the cone of positive definite Sigma however correlated it is
 * (steps along Sigma_xy alone, relative to Sigma's diagonal, left it), truncation about 1e-4 relative. H L = D gives
 * H = D L^-1, symmetrised; scaled to n_eff. Where the points' information is not positive definite: steps of 1e-4
 * of each parameter's scale along the axes. */
static ggx_status cells_hessian(const fit_data *d, const fit_point *at, const double t[2], const double sigma[3],
                                double *ll, double g[5], double H[5][5])
{
    ggx_status st = fit_gradient(d, t, sigma, ll, g);
    if (st != GGX_OK) return st;
    double gp_[5], Hp[5][5], W, llp, nh[FIT_MAX_P][FIT_MAX_P], inv[FIT_MAX_P][FIT_MAX_P], L[FIT_MAX_P][FIT_MAX_P];
    if ((st = point_hessian(d, at, sigma, &llp, gp_, Hp, &W)) != GGX_OK) return st;
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++) nh[i][j] = -Hp[i][j] * d->n_eff / W;
    if (!fit_spd_inverse(5, nh, inv) || !fit_cholesky(5, inv, L)) {
        const double ex = sqrt(sigma[0]), ey = sqrt(sigma[2]);
        const double h[5] = {1e-4 * ex, 1e-4 * ey, 1e-4 * sigma[0], 1e-4 * ex * ey, 1e-4 * sigma[2]};
        memset(L, 0, sizeof L);
        for (int i = 0; i < 5; i++) L[i][i] = h[i] / 1e-2;
    }
    double D[5][5];
    for (int k = 0; k < 5; k++) {
        double th[2][5], gp[5], gm[5], lp, pinv[3], step = 1e-2;
        for (int half = 0;; half++, step *= 0.5) {
            const double th0[5] = {t[0], t[1], sigma[0], sigma[1], sigma[2]};
            for (int i = 0; i < 5; i++) th[0][i] = th0[i] + step * L[i][k], th[1][i] = th0[i] - step * L[i][k];
            if ((fit_inverse(th[0] + 2, pinv) && fit_inverse(th[1] + 2, pinv)) || half == 60) break;
        }
        if ((st = fit_gradient(d, th[0], th[0] + 2, &lp, gp)) != GGX_OK) return st;
        if ((st = fit_gradient(d, th[1], th[1] + 2, &lp, gm)) != GGX_OK) return st;
        for (int i = 0; i < 5; i++) D[i][k] = (gp[i] - gm[i]) / (2.0 * step);
    }
    /* H = D L^-1: solve X L = D row by row (L lower triangular: back substitution over the columns) */
    double X[5][5];
    for (int i = 0; i < 5; i++)
        for (int c = 4; c >= 0; c--) {
            double v = D[i][c];
            for (int m = c + 1; m < 5; m++) v -= X[i][m] * L[m][c];
            X[i][c] = v / L[c][c];
        }
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++) H[i][j] = 0.5 * (X[i][j] + X[j][i]);
    return GGX_OK;
}

ggx_status fit_information(const fit_data *d, ggx_fit_model model, const double t[2], const double sigma[3],
                           double *log_likelihood, double *decrement, double cov[5][5], double step[5])
{
    if (step) memset(step, 0, 5 * sizeof *step);
    fit_point at = {{t[0], t[1]}, {0, 0, 0}, {0, 0, 0}, 0, 0};
    memset(cov, 0, sizeof(double) * 25);
    *decrement = HUGE_VAL;
    if (!fit_inverse(sigma, at.p)) return GGX_ERR_SINGULAR;
    double g[5], H[5][5], scale = 1.0, W = 1.0;
    ggx_status st = d->src->censored ? cells_hessian(d, &at, t, sigma, log_likelihood, g, H)
                                     : point_hessian(d, &at, sigma, log_likelihood, g, H, &W);
    if (st != GGX_OK) return st;
    if (!d->src->censored) scale = d->n_eff / W;
    /* In the model's free parameters, scaled from W to n_eff. */
    double J[5][5], nh[FIT_MAX_P][FIT_MAX_P], gf[5], inv[FIT_MAX_P][FIT_MAX_P];
    int k = free_directions(model, J);
    for (int p = 0; p < k; p++) {
        gf[p] = 0.0;
        for (int i = 0; i < 5; i++) gf[p] += J[i][p] * g[i] * scale;
        for (int q = 0; q < k; q++) {
            double v = 0.0;
            for (int i = 0; i < 5; i++)
                for (int j = 0; j < 5; j++) v += J[i][p] * H[i][j] * J[j][q];
            nh[p][q] = -v * scale;
        }
    }
    if (!fit_spd_inverse(k, nh, inv)) return GGX_OK;
    double lam2 = 0.0;
    for (int p = 0; p < k; p++)
        for (int q = 0; q < k; q++) lam2 += gf[p] * inv[p][q] * gf[q];
    *decrement = sqrt(fmax(lam2, 0.0));
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++) {
            double v = 0.0;
            for (int p = 0; p < k; p++)
                for (int q = 0; q < k; q++) v += J[i][p] * inv[p][q] * J[j][q];
            cov[i][j] = v;
        }
    if (step) /* (-H)^-1 g in the free parameters, mapped to the five */
        for (int i = 0; i < 5; i++) {
            double v = 0.0;
            for (int p = 0; p < k; p++)
                for (int q = 0; q < k; q++) v += J[i][p] * inv[p][q] * gf[q];
            step[i] = v;
        }
    return GGX_OK;
}
