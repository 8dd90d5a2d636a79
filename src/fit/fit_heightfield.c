/* ggx_fit_heightfield: the facets of a piecewise-linear height field as a source of slopes, levelled by the
 * least-squares plane and optionally downsampled. SPDX-License-Identifier: MIT */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fit.h"

typedef struct grid {
    const double *h;
    size_t nx, ny;
    double dx, dy;
    double px, py; /* the plane's gradient, removed from every slope */
} grid;

/* The levelled differences of cell (i, j): a = (h10 - h00) / dx, b = (h11 - h01) / dx, c = (h01 - h00) / dy,
 * d = (h11 - h10) / dy, less the plane's gradient. Returns 0 (and zeros) when a height is not finite or a slope's
 * square overflows: the cell's four facets are skipped, and counted so, by one rule for the fit and its counts. */
static int cell_diffs(const grid *g, size_t i, size_t j, double *a, double *b, double *c, double *d)
{
    const double *r0 = g->h + j * g->nx + i, *r1 = r0 + g->nx;
    const double idx = 1.0 / g->dx, idy = 1.0 / g->dy;
    *a = (r0[1] - r0[0]) * idx - g->px, *b = (r1[1] - r1[0]) * idx - g->px;
    *c = (r1[0] - r0[0]) * idy - g->py, *d = (r1[1] - r0[1]) * idy - g->py;
    if (isfinite(*a * *a + *b * *b + *c * *c + *d * *d)) return 1;
    *a = *b = *c = *d = 0.0;
    return 0;
}

/* Sample k is facet k % 4 of cell k / 4 (cells row by row): the four pairs of the cell's x differences
 * a = (h10 - h00) / dx, b = (h11 - h01) / dx with its y differences c = (h01 - h00) / dy, d = (h11 - h10) / dy:
 * (a, c) and (b, d) are the triangles of the diagonal 00-11, (a, d) and (b, c) those of 10-01. */
static void fill_grid(const void *ctx, size_t i0, size_t k, double *x, double *y, double *w)
{
    const grid *g = ctx;
    size_t cx = g->nx - 1, cell = i0 / 4, i = cell % cx, j = cell / cx;
    int f = (int)(i0 % 4);
    size_t s = 0;
    double a, b, c, d, ok;
    /* whole cells, four facets each (the passes read chunks aligned on 4) */
    if (f == 0) {
        for (; s + 4 <= k; s += 4) {
            ok = cell_diffs(g, i, j, &a, &b, &c, &d);
            x[s] = a, y[s] = c, x[s + 1] = b, y[s + 1] = d, x[s + 2] = a, y[s + 2] = d, x[s + 3] = b, y[s + 3] = c;
            w[s] = w[s + 1] = w[s + 2] = w[s + 3] = ok;
            if (++i == cx) i = 0, j++;
        }
    }
    /* the rest facet by facet (a range that starts or ends inside a cell: ggx_heightfield_facets) */
    ok = a = b = c = d = 0.0;
    for (size_t t = s; t < k; t++) {
        if (t == s || f == 0) ok = cell_diffs(g, i, j, &a, &b, &c, &d);
        x[t] = f == 0 || f == 2 ? a : b, y[t] = f == 0 || f == 3 ? c : d, w[t] = ok;
        if (++f == 4) {
            f = 0;
            if (++i == cx) i = 0, j++;
        }
    }
}

/* The gradient of the least-squares plane through the finite heights (centred sums, so a large mean height or
 * offset grid costs no accuracy); 0 when the finite heights do not determine a plane. */
static void plane_gradient(const grid *g, double *px, double *py)
{
    double n = 0, sx = 0, sy = 0, sh = 0;
    for (size_t j = 0; j < g->ny; j++)
        for (size_t i = 0; i < g->nx; i++) {
            double h = g->h[j * g->nx + i];
            if (!isfinite(h)) continue;
            n += 1.0, sx += (double)i, sy += (double)j, sh += h;
        }
    *px = *py = 0.0;
    if (n < 3.0) return;
    double mx = sx / n, my = sy / n, mh = sh / n, cxx = 0, cxy = 0, cyy = 0, cxh = 0, cyh = 0;
    for (size_t j = 0; j < g->ny; j++)
        for (size_t i = 0; i < g->nx; i++) {
            double h = g->h[j * g->nx + i];
            if (!isfinite(h)) continue;
            double u = (double)i - mx, v = (double)j - my, e = h - mh;
            cxx += u * u, cxy += u * v, cyy += v * v, cxh += u * e, cyh += v * e;
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
    *g = (grid){h, nx, ny, dx, dy, 0.0, 0.0};
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
        *g = (grid){c, cnx, cny, dx * (double)k, dy * (double)k, 0.0, 0.0};
        *coarse = c;
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
    for (size_t j = 0; j + 1 < g.ny; j++)
        for (size_t i = 0; i + 1 < g.nx; i++) {
            double a, b, c, d;
            if (cell_diffs(&g, i, j, &a, &b, &c, &d))
                inf->used += 4;
            else
                inf->ignored_nonfinite += 4;
        }
    st = GGX_ERR_DATA;
    if (inf->used >= 5) {
        fit_source src = {fill_grid, &g, 4 * (g.nx - 1) * (g.ny - 1)};
        ggx_shape s;
        st = fit_run(&src, opt, &s, inf);
        if (st == GGX_OK) *out = s;
    }
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
    double x[FIT_CHUNK], y[FIT_CHUNK], w[FIT_CHUNK];
    for (size_t at = 0; at < count; at += FIT_CHUNK) {
        size_t k = count - at < FIT_CHUNK ? count - at : FIT_CHUNK;
        fill_grid(&g, first + at, k, x, y, w);
        for (size_t i = 0; i < k; i++) {
            slopes[2 * (at + i)] = w[i] != 0.0 ? x[i] : NAN;
            slopes[2 * (at + i) + 1] = w[i] != 0.0 ? y[i] : NAN;
        }
    }
    free(coarse);
    return GGX_OK;
}
