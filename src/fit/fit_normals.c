/* ggx_fit_normals and ggx_fit_log_likelihood: micro-normals as a source of slopes. SPDX-License-Identifier: MIT */
#include <string.h>

#include "fit.h"

typedef struct normals {
    const ggx_vec3 *m;
    const double *w;
    double w_scale; /* 1 / the largest weight, so that the sums of w and w^2 neither overflow nor underflow */
} normals;

/* Why a sample is not used: 0 used, 1 horizon, 2 non-finite, 3 zero weight, 4 negative weight. */
static int reason(const normals *c, size_t i, double *x, double *y, double *w)
{
    ggx_vec3 m = c->m[i];
    double wi = c->w ? c->w[i] : 1.0;
    if (!isfinite(m.x) || !isfinite(m.y) || !isfinite(m.z) || !isfinite(wi)) return 2;
    if (wi < 0.0) return 4;
    if (!(m.z > 0.0)) return 1;
    double sx = -m.x / m.z, sy = -m.y / m.z;
    if (!isfinite(sx * sx + sy * sy)) return 1; /* m.z so small that the slope or its square overflows: the horizon */
    if (wi == 0.0) return 3;
    *x = sx, *y = sy, *w = wi;
    return 0;
}

static double fill_normals(const void *ctx, const fit_point *at, size_t i0, size_t k, double *x, double *y, double *w)
{
    (void)at;
    const normals *c = ctx;
    for (size_t i = 0; i < k; i++)
        if (reason(c, i0 + i, &x[i], &y[i], &w[i]) != 0) x[i] = y[i] = w[i] = 0.0;
        else w[i] *= c->w_scale;
    return 0.0;
}

/* Counts the samples by reason into info and sets the weights' scale; GGX_ERR_RANGE when a weight is negative (the
 * counts then cover the other samples). */
static ggx_status count(normals *c, size_t n, ggx_fit_info *info)
{
    int negative = 0;
    double wmax = 0.0;
    for (size_t i = 0; i < n; i++) {
        double x, y, w;
        switch (reason(c, i, &x, &y, &w)) {
        case 0: info->used++, wmax = fmax(wmax, w); break;
        case 1: info->ignored_horizon++; break;
        case 2: info->ignored_nonfinite++; break;
        case 3: info->ignored_weight++; break;
        default: negative = 1;
        }
    }
    c->w_scale = wmax > 0.0 ? 1.0 / wmax : 1.0;
    if (!(c->w_scale < HUGE_VAL)) c->w_scale = 0x1p1000; /* a subnormal largest weight: brought near 1 */
    return negative ? GGX_ERR_RANGE : GGX_OK;
}

GGX_API ggx_status ggx_fit_normals(ggx_shape *out, const ggx_vec3 *m, const double *weight, size_t n,
                                   const ggx_fit_options *opt, ggx_fit_info *info)
{
    ggx_fit_info local;
    ggx_fit_info *inf = info ? info : &local;
    memset(inf, 0, sizeof *inf);
    if (!out || (!m && n > 0)) return GGX_ERR_NULL;
    fit_data check;
    ggx_fit_model model;
    ggx_status st = fit_settings(opt, &check, &model);
    if (st != GGX_OK) return st;
    normals c = {m, weight, 1.0};
    if ((st = count(&c, n, inf)) != GGX_OK) return st;
    if (inf->used < 5) return GGX_ERR_DATA;
    fit_source src = {fill_normals, &c, n, 0, 0, 0.0, 0.0};
    ggx_shape s;
    st = fit_run(&src, opt, &s, inf);
    if (st != GGX_OK) {
        ggx_fit_info keep = *inf;
        memset(inf, 0, sizeof *inf);
        inf->used = keep.used, inf->ignored_horizon = keep.ignored_horizon;
        inf->ignored_nonfinite = keep.ignored_nonfinite, inf->ignored_weight = keep.ignored_weight;
        return st;
    }
    *out = s;
    return GGX_OK;
}

GGX_API ggx_status ggx_fit_log_likelihood(const ggx_shape *s, const ggx_vec3 *m, const double *weight, size_t n,
                                          double *ll)
{
    if (!s || !ll || (!m && n > 0)) return GGX_ERR_NULL;
    normals c = {m, weight, 1.0};
    double sw = 0.0, sl = 0.0, wmax = 0.0;
    for (size_t i = 0; i < n; i++) { /* the weights' scale first, as in the fit */
        double x, y, w;
        int why = reason(&c, i, &x, &y, &w);
        if (why == 4) return GGX_ERR_RANGE;
        if (why == 0) wmax = fmax(wmax, w);
    }
    for (size_t i = 0; i < n; i++) {
        double x, y, w;
        int why = reason(&c, i, &x, &y, &w);
        if (why == 4) return GGX_ERR_RANGE;
        if (why != 0) continue;
        /* D(m) (m.n) of the unit normal along m, through ggx_pdf_ndf: independent of the slope form of the fit */
        double r = 1.0 / sqrt(1.0 + x * x + y * y);
        ggx_vec3 u = {-x * r, -y * r, r};
        w /= wmax;
        sw += w;
        sl += w * log(ggx_pdf_ndf(s, u));
    }
    *ll = sw > 0.0 ? sl / sw : -HUGE_VAL;
    return GGX_OK;
}
