/* The upper tail of the chi-square distribution, written once for the fit's goodness of fit (src/fit/) and the
 * verification library's chi-square tests (libs/verify/chi2.c). Header-only, static; no global state (lgamma's signgam
 * is avoided: dof / 2 is an integer or a half-integer, whose log-gamma is a sum of logs). SPDX-License-Identifier: MIT */
#ifndef GGX_COMMON_CHI2_TAIL_H
#define GGX_COMMON_CHI2_TAIL_H

#include "ggx/ggx.h"

#include <math.h>

/* log Gamma(k / 2) for an integer k >= 1: Gamma(1/2) = sqrt(pi), Gamma(1) = 1, Gamma(a + 1) = a Gamma(a). */
static inline double ggx_log_gamma_half(int k)
{
    double a = (k % 2) ? 0.5 : 1.0, lg = (k % 2) ? 0.5 * log(GGX_PI) : 0.0;
    for (; a < 0.5 * k - 0.25; a += 1.0) lg += log(a);
    return lg;
}

/* Regularised lower incomplete gamma P(a, x) by its series, for x < a + 1; lga = log Gamma(a). */
static inline double ggx_gamma_p_series(double a, double x, double lga)
{
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 100000; n++) {
        term *= x / (a + n);
        sum += term;
        if (fabs(term) < 1e-16 * fabs(sum)) break;
    }
    return sum * exp(-x + a * log(x) - lga);
}

/* Regularised upper incomplete gamma Q(a, x) by its continued fraction (modified Lentz), for x >= a + 1. */
static inline double ggx_gamma_q_cf(double a, double x, double lga)
{
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 100000; i++) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        double del = d * c;
        h *= del;
        if (fabs(del - 1.0) < 1e-16) break;
    }
    return exp(-x + a * log(x) - lga) * h;
}

/* P(X >= x) for X chi-square with dof >= 1 degrees of freedom: Q(dof / 2, x / 2); 1 for x <= 0 or NaN. Relative
 * accuracy about 1e-14 in Q (the series and fraction stop at 1e-16 per term). */
static inline double ggx_chi2_upper(double x, int dof)
{
    if (!(x > 0.0)) return 1.0;
    double a = 0.5 * dof, y = 0.5 * x, lga = ggx_log_gamma_half(dof);
    return y < a + 1.0 ? 1.0 - ggx_gamma_p_series(a, y, lga) : ggx_gamma_q_cf(a, y, lga);
}

#endif
