/* The figure of a fit (figure_fit.h): the measured NDF beside the fitted one (top views on one colour scale) and their
 * difference, the slopes' histogram about the fitted location with the fitted P22's contours, and the radial profile
 * of the standardised slopes against GGX and the fitted Student t. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure.h"
#include "figure_fit.h"

enum { RES = 160, BINS = FIGURE_FIT_BINS }; /* pixels across each panel's histogram; the profile's bins */

/* The top view: a normal m at (m.x, m.y) of the unit disk. The fraction of samples (of D(m)(m.n) dω) in a pixel of
 * area dA is D(m) dA (dω = dA / m.z), so counts / (W dA) estimate D itself. */
typedef struct panels {
    double top[RES][RES];   /* weighted counts, top view */
    double slope[RES][RES]; /* weighted counts, slope space about t, +-4 sqrt(largest eigenvalue of Sigma) */
    double w_sum, half;     /* total weight; the slope panel's half width */
    double t[2];
    double l[3];       /* L (00, 10, 11), Sigma = L L^T: z = L^-1 (x~ - t) */
    double prof[BINS]; /* weighted counts by the angle atan |z| of the standardised normal */
    double fitted[RES][RES], resid[RES][RES], model[RES][RES]; /* fitted D, measured - fitted, fitted P22 */
} panels;

static void add(panels *p, double x, double y, double w)
{
    if (!(w > 0) || !isfinite(x) || !isfinite(y)) return;
    double k = 1.0 / sqrt(1.0 + x * x + y * y), mx = -x * k, my = -y * k;
    int i = (int)floor((mx + 1.0) * 0.5 * RES), j = (int)floor((1.0 - my) * 0.5 * RES);
    if (i >= 0 && i < RES && j >= 0 && j < RES) p->top[j][i] += w;
    int u = (int)floor((x - p->t[0] + p->half) / (2 * p->half) * RES);
    int v = (int)floor((p->t[1] + p->half - y) / (2 * p->half) * RES);
    if (u >= 0 && u < RES && v >= 0 && v < RES) p->slope[v][u] += w;
    double zx = (x - p->t[0]) / p->l[0], zy = (y - p->t[1] - p->l[1] * zx) / p->l[2];
    int b = (int)floor(atan(hypot(zx, zy)) / (90.0 * DEG) * BINS);
    if (b >= 0 && b < BINS) p->prof[b] += w;
    p->w_sum += w;
}

/* One panel of values on the colour scale [0, vmax] (or [-vmax, vmax] diverging for the residual). */
static void draw_grid(cairo_t *cr, double x0, double y0, double size, double vals[RES][RES], double vmax, int signed_,
                      int disk)
{
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, RES, RES);
    unsigned char *px = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img);
    for (int j = 0; j < RES; j++)
        for (int i = 0; i < RES; i++) {
            double cx = (i + 0.5) / RES * 2 - 1, cy = 1 - (j + 0.5) / RES * 2, rgb[3];
            int inside = !disk || cx * cx + cy * cy <= 1.0;
            if (signed_) { /* blue below, red above, white at 0 */
                double t = fmax(-1.0, fmin(1.0, vals[j][i] / vmax));
                rgb[0] = t > 0 ? 1.0 : 1.0 + t, rgb[1] = 1.0 - fabs(t), rgb[2] = t < 0 ? 1.0 : 1.0 - t;
            } else {
                colormap(vals[j][i] / vmax, rgb);
            }
            uint32_t a = inside ? 255u : 0u;
            uint32_t c = a << 24 | (uint32_t)(rgb[0] * 255 + 0.5) << 16 | (uint32_t)(rgb[1] * 255 + 0.5) << 8 |
                         (uint32_t)(rgb[2] * 255 + 0.5);
            memcpy(px + (size_t)j * (size_t)stride + 4 * (size_t)i, &c, 4);
        }
    paint_image(cr, img, x0, y0, size / RES);
}

/* The Student t of info->tails at the standardised slope z (its density over slopes times |L|: per unit area of z). */
static double tails_density(const ggx_fit_info *info, const double l[3], double zx, double zy)
{
    const ggx_fit_tails *tl = &info->tails;
    double x = info->t[0] + l[0] * zx - tl->t[0], y = info->t[1] + l[1] * zx + l[2] * zy - tl->t[1];
    double det = tl->sigma[0] * tl->sigma[2] - tl->sigma[1] * tl->sigma[1], g1 = 0.5 * tl->nu;
    double delta = (tl->sigma[2] * x * x - 2.0 * tl->sigma[1] * x * y + tl->sigma[0] * y * y) / det;
    return pow(1.0 + delta / g1, -(1.0 + g1)) / (GGX_PI * sqrt(det)) * l[0] * l[2];
}

/* The radial profile: D of the standardised normals by their angle (the samples' weight in a ring of angles over its
 * projected solid angle, pi (sin^2 b - sin^2 a); NaN for an empty ring) and the Student t's azimuthal mean over 64
 * azimuths at whole degrees (NaN when not fitted). */
static void profile_values(const panels *p, const ggx_fit_info *info, double measured[FIGURE_FIT_BINS],
                           double tails[90])
{
    for (int b = 0; b < BINS; b++) {
        double a = b * 90.0 / BINS * DEG, e = (b + 1) * 90.0 / BINS * DEG;
        double ring = GGX_PI * (sin(e) * sin(e) - sin(a) * sin(a));
        measured[b] = p->prof[b] > 0 ? p->prof[b] / (p->w_sum * ring) : NAN;
    }
    for (int k = 0; k < 90; k++) {
        double r = tan(k * DEG), c2 = 1.0 / (1.0 + r * r), sum = 0.0;
        for (int a = 0; a < 64; a++)
            sum += tails_density(info, p->l, r * cos(2 * GGX_PI * a / 64), r * sin(2 * GGX_PI * a / 64));
        tails[k] = isfinite(info->tails.nu) ? sum / 64 / (c2 * c2) : NAN;
    }
}

static void draw_profile(cairo_t *cr, const theme *th, double x, double y, double w, double h, const panels *p,
                         const ggx_fit_info *info)
{
    double measured[BINS], tails[90];
    profile_values(p, info, measured, tails);
    plot_series sr[3];
    memset(sr, 0, sizeof sr);
    snprintf(sr[0].label, sizeof sr[0].label, "measured");
    sr[0].marks = 1;
    for (int b = 0; b < BINS; b++)
        if (isfinite(measured[b])) sr[0].x[sr[0].n] = (b + 0.5) * 90.0 / BINS, sr[0].y[sr[0].n++] = measured[b];
    snprintf(sr[1].label, sizeof sr[1].label, "GGX (the fit): 1 / pi");
    snprintf(sr[2].label, sizeof sr[2].label, "Student t, nu %.3g +- %.2g", info->tails.nu, info->tails.nu_std_error);
    for (int k = 0; k < 90; k++) {
        sr[1].x[sr[1].n] = k, sr[1].y[sr[1].n++] = 1.0 / GGX_PI;
        if (isfinite(tails[k])) sr[2].x[sr[2].n] = k, sr[2].y[sr[2].n++] = tails[k];
    }
    plot_axes ax = {
        "angle of the standardised normal, atan |L^-1 (x~ - t)| (degrees)", "D (standardised)", 1, 0, 1, 90.0};
    plot_draw(cr, th, x, y, w, h, 15, sr, sr[2].n ? 3 : 2, &ax);
}

/* The panels' sums over the samples (NULL when out of memory). */
static panels *read_panels(const fit_samples *src, const ggx_fit_info *info)
{
    panels *p = calloc(1, sizeof *p);
    if (!p) return NULL;
    double half = 0.5 * (info->sigma[0] - info->sigma[2]);
    double lmax = 0.5 * (info->sigma[0] + info->sigma[2]) + sqrt(half * half + info->sigma[1] * info->sigma[1]);
    p->half = 4.0 * sqrt(lmax), p->t[0] = info->t[0], p->t[1] = info->t[1];
    p->l[0] = sqrt(info->sigma[0]), p->l[1] = info->sigma[1] / p->l[0];
    p->l[2] = sqrt(fmax(info->sigma[2] - p->l[1] * p->l[1], 1e-300));
    double xs[1024], ys[1024], ws[1024];
    for (size_t at = 0; at < src->n; at += 1024) {
        size_t k = src->n - at < 1024 ? src->n - at : 1024;
        src->read(src->ctx, at, k, xs, ys, ws);
        for (size_t i = 0; i < k; i++) add(p, xs[i], ys[i], ws[i]);
    }
    return p;
}

int figure_fit_profile(const fit_samples *src, const ggx_fit_info *info, double measured[FIGURE_FIT_BINS],
                       double tails[90])
{
    panels *p = read_panels(src, info);
    if (!p) return -1;
    profile_values(p, info, measured, tails);
    free(p);
    return 0;
}

int figure_fit_draw(canvas *c, const fit_samples *src, const ggx_shape *fit, const ggx_fit_info *info,
                    const char *family, const char *title)
{
    panels *p = read_panels(src, info);
    if (!p) return -1;
    /* measured and fitted D on the top view; the slope histogram's density against P22 */
    double cell = 2.0 / RES, scell = 2 * p->half / RES, vmax = 0.0, rmax = 0.0, smax = 0.0;
    for (int j = 0; j < RES; j++)
        for (int i = 0; i < RES; i++) {
            double cx = (i + 0.5) * cell - 1, cy = 1 - (j + 0.5) * cell, r2 = cx * cx + cy * cy;
            p->top[j][i] /= p->w_sum * cell * cell;
            p->fitted[j][i] = r2 < 1.0 ? ggx_ndf(fit, (ggx_vec3){cx, cy, sqrt(1.0 - r2)}) : 0.0;
            vmax = fmax(vmax, p->fitted[j][i]);
            double sx = p->t[0] - p->half + (i + 0.5) * scell, sy = p->t[1] + p->half - (j + 0.5) * scell;
            p->slope[j][i] /= p->w_sum * scell * scell;
            p->model[j][i] = ggx_p22(fit, sx, sy);
            smax = fmax(smax, fmax(p->model[j][i], p->slope[j][i]));
        }
    for (int j = 0; j < RES; j++)
        for (int i = 0; i < RES; i++) {
            p->resid[j][i] = p->top[j][i] - p->fitted[j][i];
            rmax = fmax(rmax, fabs(p->resid[j][i]));
        }
    if (!(vmax > 0)) vmax = 1.0;
    if (!(rmax > 0)) rmax = 1.0;
    if (!(smax > 0)) smax = 1.0;

    const int W = FIGURE_FIT_W, H = FIGURE_FIT_H;
    cairo_t *cr = c->cr;
    const theme *th = c->th;
    set_rgb(cr, th->fg);
    text_font(cr, 20, 1);
    text_at(cr, W / 2.0, 30, 0.5, 0.5, title);
    text_font(cr, 14, 0);
    char line[400];
    double ax, ay, tx, ty, tz;
    ggx_shape_ellipsoid_params(fit, &ax, &ay, &tx, &ty, &tz);
    snprintf(line, sizeof line, "fit: --alpha %.4g,%.4g --skew %.4g,%.4g --rotate %.4g (the %s family)", ax, ay,
             tx / DEG + 0.0, ty / DEG + 0.0, tz / DEG + 0.0, family); /* + 0.0: no "-0" */
    text_at(cr, W / 2.0, 58, 0.5, 0.5, line);
    snprintf(line, sizeof line, "t = (%.4g, %.4g), Sigma = (%.4g, %.4g, %.4g); model of least BIC: %s", info->t[0],
             info->t[1], info->sigma[0], info->sigma[1], info->sigma[2],
             (const char *const[]){"ellipsoid", "anisotropic GGX", "isotropic GGX", "Beckmann"}[info->best]);
    text_at(cr, W / 2.0, 80, 0.5, 0.5, line);
    const double S = 420, X0 = 70, X1 = 590, Y0 = 115, Y1 = 612;
    struct {
        double x, y;
        const char *label;
    } lab[4] = {{X0, Y0, "measured D(m), top view (x right, y up)"},
                {X1, Y0, "fitted D(m), same colour scale"},
                {X0, Y1, "measured - fitted (red above, blue below)"},
                {X1, Y1, "slopes about t, +-4 sqrt(lambda_max): density and fitted P22 contours"}};
    draw_grid(cr, X0, Y0 + 20, S, p->top, vmax, 0, 1);
    draw_grid(cr, X1, Y0 + 20, S, p->fitted, vmax, 0, 1);
    draw_grid(cr, X0, Y1 + 20, S, p->resid, rmax, 1, 1);
    draw_grid(cr, X1, Y1 + 20, S, p->slope, smax, 0, 0);
    set_rgb(cr, th->fg);
    for (int k = 0; k < 4; k++) text_at(cr, lab[k].x, lab[k].y, 0.0, 0.5, lab[k].label);
    colour_bar(cr, th, X1 + S + 12, Y0 + 20, 14, S, vmax, 0, 0, "D", 12);
    snprintf(line, sizeof line, "residual scale +-%.3g (D up to %.3g)", rmax, vmax);
    text_at(cr, X0, Y1 + S + 42, 0.0, 0.5, line);
    /* the fitted P22's contours: ellipses delta = f^(-1/2) - 1 at f = 1/2, 1/10, 1/100 of the peak */
    double l00 = p->l[0], l10 = p->l[1], l11 = p->l[2];
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_set_line_width(cr, 1.4);
    const double fr[3] = {0.5, 0.1, 0.01};
    for (int k = 0; k < 3; k++) {
        double r = sqrt(1.0 / sqrt(fr[k]) - 1.0);
        for (int a = 0; a <= 200; a++) {
            double ph = 2 * (180.0 * DEG) * a / 200, zx = r * cos(ph), zy = r * sin(ph);
            double sx = l00 * zx, sy = l10 * zx + l11 * zy; /* L z */
            double X = X1 + (sx + p->half) / (2 * p->half) * S, Y = Y1 + 20 + (p->half - sy) / (2 * p->half) * S;
            if (a == 0) cairo_move_to(cr, X, Y);
            else cairo_line_to(cr, X, Y);
        }
        cairo_stroke(cr);
    }
    set_rgb(cr, th->fg);
    snprintf(line, sizeof line, "contours at 1/2, 1/10, 1/100 of the peak; half width %.3g in slope", p->half);
    text_at(cr, X1, Y1 + S + 42, 0.0, 0.5, line);
    const double Y2 = Y1 + S + 80;
    text_at(cr, X0, Y2, 0.0, 0.5,
            "the NDF's radial profile in the fit's standardised slopes z = L^-1 (x~ - t), Sigma = L L^T: there GGX's D "
            "is 1 / pi at every angle");
    draw_profile(cr, th, X0 - 20, Y2 + 16, W - 2 * X0 + 40, 400, p, info);
    if (info->gof_dof > 0)
        snprintf(line, sizeof line, "goodness of fit: chi-square %.1f, %d dof, p = %.3g; %zu samples", info->gof_chi2,
                 info->gof_dof, info->gof_pvalue, info->used);
    else if (src->cells)
        snprintf(line, sizeof line, "%zu texels fitted as cells (no goodness of fit for cells)", info->used);
    else snprintf(line, sizeof line, "%zu samples (too few for the goodness of fit)", info->used);
    text_at(cr, W / 2.0, H - 22, 0.5, 0.5, line);
    free(p);
    return 0;
}
