/* GGX-slope fields: a Gaussian scale mixture of a Gaussian field (microsurface.h; docs/design/microsurface.md).
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "microsurface.h"

/* the indices of u sorted by value (a merge sort on size_t indices: no global state for a comparator) */
static void order(const double *u, size_t *idx, size_t *tmp, size_t lo, size_t hi)
{
    if (hi - lo < 2) return;
    size_t mid = lo + (hi - lo) / 2;
    order(u, idx, tmp, lo, mid), order(u, idx, tmp, mid, hi);
    size_t a = lo, b = mid, k = lo;
    while (a < mid && b < hi) tmp[k++] = u[idx[a]] <= u[idx[b]] ? idx[a++] : idx[b++];
    while (a < mid) tmp[k++] = idx[a++];
    while (b < hi) tmp[k++] = idx[b++];
    for (k = lo; k < hi; k++) idx[k] = tmp[k];
}

int ms_ggx(const ms_ggx_spec *sp, double *h, char *err, size_t errn)
{
    size_t n = sp->n, count = n * n;
    double mix = sp->mix_len > 0.0 ? sp->mix_len : 8.0 * sp->corr_len;
    if (!(mix >= sp->corr_len && mix <= (double)n / 4.0)) {
        snprintf(err, errn,
                 "GGX surface: the mixing length %g must be in [the correlation length, size / 4]: give a "
                 "larger size or a shorter correlation length",
                 mix);
        return -1;
    }
    /* G: slopes N(0, Sigma), Sigma = R diag(alpha_x^2, alpha_y^2) R^T, i.e. Beckmann of sqrt(2) alpha */
    ms_gauss_spec g = {n, sqrt(2.0) * sp->alpha_x, sqrt(2.0) * sp->alpha_y, sp->phi, sp->corr_len, sp->seed};
    if (sp->alpha_x > 10.0 / sqrt(2.0) || sp->alpha_y > 10.0 / sqrt(2.0)) {
        snprintf(err, errn, "GGX surface: the alphas must be in [0.001, 7]");
        return -1;
    }
    if (ms_gauss(&g, h, NULL, err, errn) != 0) return -1;
    double *u = malloc(count * sizeof *u);
    size_t *idx = malloc(count * sizeof *idx), *tmp = malloc(count * sizeof *tmp);
    if (!u || !idx || !tmp) {
        free(u), free(idx), free(tmp);
        snprintf(err, errn, "GGX surface: out of memory");
        return -1;
    }
    ms_gauss_spec w = {n, 0.3, 0.3, 0.0, mix, sp->seed ^ 0x5DEECE66Dull}; /* only its order matters */
    if (ms_gauss(&w, u, NULL, err, errn) != 0) {
        free(u), free(idx), free(tmp);
        return -1;
    }
    for (size_t i = 0; i < count; i++) idx[i] = i;
    order(u, idx, tmp, 0, count);
    /* the texel of rank r gets W = the chi^2_2 quantile of (r + 1/2) / count, W = -2 log(1 - p) */
    for (size_t r = 0; r < count; r++) {
        double q = 1.0 - ((double)r + 0.5) / (double)count;
        h[idx[r]] /= sqrt(-2.0 * log(q));
    }
    free(u), free(idx), free(tmp);
    return 0;
}
