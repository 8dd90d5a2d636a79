/* ggx_fit_heightfield: the facets of a piecewise-linear height field as a source of slopes, levelled by the
 * least-squares plane and optionally downsampled. SPDX-License-Identifier: MIT */
#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fit.h"

typedef struct grid {
    const double *h;
    size_t nx, ny;
    double dx, dy;
    double px, py; /* the plane's gradient, removed from every slope */
    double lo, hi; /* heights outside [lo, hi] (and NaN) are missing: the outlier fence */
} grid;

/* The facets of cells [c0, c0 + nc) (cells row by row), planar: x[f nc + m], y[f nc + m] and w[f nc + m] are facet f
 * of cell c0 + m. A cell's levelled differences are a = (h10 - h00) / dx, b = (h11 - h01) / dx, c = (h01 - h00) / dy,
 * d = (h11 - h10) / dy, less the plane's gradient; its facets pair them as (a, c) and (b, d), the triangles of the
 * diagonal 00-11, and (a, d) and (b, c), those of 10-01. A cell with a non-finite height or one outside the fence,
 * or whose slopes' squares overflow, gets zero slopes and weight 0 (one rule for the fit and its counts). */
GGX_HOT_WIDE static void cells_fill(const grid *g, size_t c0, size_t nc, double *x, double *y, double *w)
{
    const size_t cx = g->nx - 1;
    const double idx = 1.0 / g->dx, idy = 1.0 / g->dy, px = g->px, py = g->py, lo = g->lo, hi = g->hi;
    for (size_t m = 0; m < nc;) {
        size_t cell = c0 + m, i0 = cell % cx, run = cx - i0 < nc - m ? cx - i0 : nc - m;
        const double *r0 = g->h + (cell / cx) * g->nx + i0, *r1 = r0 + g->nx;
        double *x0 = x + m, *x1 = x0 + nc, *x2 = x1 + nc, *x3 = x2 + nc;
        double *y0 = y + m, *y1 = y0 + nc, *y2 = y1 + nc, *y3 = y2 + nc;
        double *w0 = w + m, *w1 = w0 + nc, *w2 = w1 + nc, *w3 = w2 + nc;
#pragma omp simd
        for (size_t i = 0; i < run; i++) {
            double a = (r0[i + 1] - r0[i]) * idx - px, b = (r1[i + 1] - r1[i]) * idx - px;
            double c = (r1[i] - r0[i]) * idy - py, d = (r1[i + 1] - r0[i + 1]) * idy - py;
            int ok = a * a + b * b + c * c + d * d <= DBL_MAX && /* false for NaN and infinity */
                     r0[i] >= lo && r0[i] <= hi && r0[i + 1] >= lo && r0[i + 1] <= hi && r1[i] >= lo && r1[i] <= hi &&
                     r1[i + 1] >= lo && r1[i + 1] <= hi;
            a = ok ? a : 0.0, b = ok ? b : 0.0, c = ok ? c : 0.0, d = ok ? d : 0.0;
            x0[i] = a, y0[i] = c, x1[i] = b, y1[i] = d, x2[i] = a, y2[i] = d, x3[i] = b, y3[i] = c;
            w0[i] = w1[i] = w2[i] = w3[i] = ok ? 1.0 : 0.0;
        }
        m += run;
    }
}

/* The fit's source: samples [i0, i0 + k) are cells [i0 / 4, (i0 + k) / 4), facets planar (cells_fill). The passes
 * and the subsample read ranges aligned on FIT_PIECE, and n is a multiple of 4, so i0 and k are multiples of 4. */
static double fill_grid(const void *ctx, const fit_point *at, size_t i0, size_t k, double *x, double *y, double *w)
{
    (void)at;
    cells_fill(ctx, i0 / 4, k / 4, x, y, w);
    return 0.0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The outlier fence [lo, hi]: the median of the finite heights plus or minus 1e6 times their span between the 1st
 * and 99th percentiles (from an even subsample of at most 65 536 heights; where that span is 0, the subsample's span
 * without its two extremes). A height that far out is not a measurement of the surface: such heights are missing
 * to the levelling and the facets, so one absurd finite value (1e308, say) cannot overflow the plane's sums or
 * every slope. Ordinary data have none (the fit is then as without a fence). */
static ggx_status outlier_fence(grid *g)
{
    g->lo = -DBL_MAX, g->hi = DBL_MAX;
    size_t count = g->nx * g->ny, stride = count / 65536 + 1, m = 0;
    double *a = malloc((count / stride + 1) * sizeof *a);
    if (!a) return GGX_ERR_MEMORY;
    for (size_t k = 0; k < count; k += stride)
        if (fabs(g->h[k]) <= DBL_MAX) a[m++] = g->h[k];
    if (m >= 3) {
        qsort(a, m, sizeof *a, cmp_double);
        double med = a[m / 2], span = a[(m - 1) * 99 / 100] - a[(m - 1) / 100];
        if (!(span > 0.0)) span = a[m - 2] - a[1];
        if (span > 0.0 && span <= DBL_MAX) {
            double f = 1e6 * span;
            g->lo = med - f, g->hi = med + f; /* an overflow to infinity leaves that side open */
        }
    }
    free(a);
    return GGX_OK;
}

/* The gradient of the least-squares plane through the finite heights inside the fence (centred sums, so a large mean height or
 * offset grid costs no accuracy); 0 when the finite heights do not determine a plane. */
GGX_HOT_WIDE static void plane_gradient(const grid *g, double *px, double *py)
{
    double n = 0, sx = 0, sy = 0, sh = 0;
    for (size_t j = 0; j < g->ny; j++) {
        const double *r = g->h + j * g->nx;
        double rn = 0, rx = 0, rh = 0;
#pragma omp simd reduction(+ : rn, rx, rh)
        for (size_t i = 0; i < g->nx; i++) {
            int ok = r[i] >= g->lo && r[i] <= g->hi;
            rn += ok ? 1.0 : 0.0, rx += ok ? (double)i : 0.0, rh += ok ? r[i] : 0.0;
        }
        n += rn, sx += rx, sy += rn * (double)j, sh += rh;
    }
    *px = *py = 0.0;
    if (n < 3.0) return;
    double mx = sx / n, my = sy / n, mh = sh / n, cxx = 0, cxy = 0, cyy = 0, cxh = 0, cyh = 0;
    for (size_t j = 0; j < g->ny; j++) {
        const double *r = g->h + j * g->nx;
        const double v = (double)j - my;
        double rn = 0, ru = 0, ruu = 0, ruh = 0, reh = 0;
#pragma omp simd reduction(+ : rn, ru, ruu, ruh, reh)
        for (size_t i = 0; i < g->nx; i++) {
            int ok = r[i] >= g->lo && r[i] <= g->hi;
            double u = ok ? (double)i - mx : 0.0, e = ok ? r[i] - mh : 0.0;
            rn += ok ? 1.0 : 0.0, ru += u, ruu += u * u, ruh += u * e, reh += e;
        }
        cxx += ruu, cxy += v * ru, cyy += v * v * rn, cxh += ruh, cyh += v * reh;
    }
    double det = cxx * cyy - cxy * cxy;
    if (!(det > 1e-12 * cxx * cyy)) return;
    *px = (cyy * cxh - cxy * cyh) / det / g->dx; /* per grid step, then per unit length */
    *py = (cxx * cyh - cxy * cxh) / det / g->dy;
}

/* The grid the facets come from: validated, downsampled (into *coarse, freed by the caller) and levelled. */
static ggx_status grid_setup(grid *g, double **coarse, const double *h, size_t nx, size_t ny, double dx, double dy,
                             const ggx_heightfield_options *hopt)
{
    *coarse = NULL;
    if (!h) return GGX_ERR_NULL;
    if (!isfinite(dx) || !isfinite(dy)) return GGX_ERR_NONFINITE;
    if (nx < 2 || ny < 2 || !(dx > 0.0) || !(dy > 0.0) || nx > SIZE_MAX / 4 / ny) return GGX_ERR_RANGE;
    ggx_heightfield_options ho = {0, 0};
    if (hopt) ho = *hopt;
    if (ho.downsample < 0) return GGX_ERR_RANGE;
    *g = (grid){h, nx, ny, dx, dy, 0.0, 0.0, -DBL_MAX, DBL_MAX};
    if (ho.downsample >= 2) {
        size_t k = (size_t)ho.downsample, cnx = nx / k, cny = ny / k;
        if (cnx < 2 || cny < 2) return GGX_ERR_RANGE;
        double *c = malloc(cnx * cny * sizeof *c);
        if (!c) return GGX_ERR_MEMORY;
        for (size_t j = 0; j < cny; j++)
            for (size_t i = 0; i < cnx; i++) {
                double sum = 0.0;
                for (size_t b = 0; b < k; b++)
                    for (size_t a = 0; a < k; a++) sum += h[(j * k + b) * nx + i * k + a];
                c[j * cnx + i] = sum / (double)(k * k); /* NaN when any height of the block is */
            }
        *g = (grid){c, cnx, cny, dx * (double)k, dy * (double)k, 0.0, 0.0, -DBL_MAX, DBL_MAX};
        *coarse = c;
    }
    ggx_status st = outlier_fence(g);
    if (st != GGX_OK) {
        free(*coarse);
        *coarse = NULL;
        return st;
    }
    if (!ho.keep_tilt) plane_gradient(g, &g->px, &g->py);
    return GGX_OK;
}

GGX_API ggx_status ggx_fit_heightfield(ggx_shape *out, const double *h, size_t nx, size_t ny, double dx, double dy,
                                       const ggx_heightfield_options *hopt, const ggx_fit_options *opt,
                                       ggx_fit_info *info)
{
    ggx_fit_info local;
    ggx_fit_info *inf = info ? info : &local;
    memset(inf, 0, sizeof *inf);
    if (!out) return GGX_ERR_NULL;
    fit_data check;
    ggx_fit_model model;
    grid g;
    double *coarse;
    ggx_status st = grid_setup(&g, &coarse, h, nx, ny, dx, dy, hopt);
    if (st == GGX_OK) st = fit_settings(opt, &check, &model);
    if (st != GGX_OK) {
        free(coarse);
        return st;
    }
    /* unit weights: used and ignored are counted by fit_run */
    fit_source src = {fill_grid, &g, 4 * (g.nx - 1) * (g.ny - 1), 1, 0, 0.0, 0.0};
    ggx_shape s;
    st = fit_run(&src, opt, &s, inf);
    if (st == GGX_OK) *out = s;
    if (st != GGX_OK) {
        size_t used = inf->used, bad = inf->ignored_nonfinite;
        memset(inf, 0, sizeof *inf);
        inf->used = used, inf->ignored_nonfinite = bad;
    }
    free(coarse);
    return st;
}

GGX_API ggx_status ggx_heightfield_facets(double *slopes, size_t first, size_t count, const double *h, size_t nx,
                                          size_t ny, double dx, double dy, const ggx_heightfield_options *hopt,
                                          size_t *total)
{
    if (!slopes && count > 0) return GGX_ERR_NULL;
    grid g;
    double *coarse;
    ggx_status st = grid_setup(&g, &coarse, h, nx, ny, dx, dy, hopt);
    if (st != GGX_OK) {
        free(coarse);
        return st;
    }
    size_t n = 4 * (g.nx - 1) * (g.ny - 1);
    if (total) *total = n;
    if (first > n || count > n - first) {
        free(coarse);
        return GGX_ERR_RANGE;
    }
    /* the cells that hold the range, FIT_CHUNK / 4 at a time, put in the order facet k % 4 of cell k / 4 */
    double x[FIT_CHUNK], y[FIT_CHUNK], w[FIT_CHUNK];
    for (size_t k = first; k < first + count;) {
        size_t c0 = k / 4, nc = (first + count - 1) / 4 - c0 + 1;
        nc = nc < FIT_CHUNK / 4 ? nc : FIT_CHUNK / 4;
        cells_fill(&g, c0, nc, x, y, w);
        for (; k < first + count && k / 4 < c0 + nc; k++) {
            size_t at = (k % 4) * nc + (k / 4 - c0);
            slopes[2 * (k - first)] = w[at] != 0.0 ? x[at] : NAN;
            slopes[2 * (k - first) + 1] = w[at] != 0.0 ? y[at] : NAN;
        }
    }
    free(coarse);
    return GGX_OK;
}
