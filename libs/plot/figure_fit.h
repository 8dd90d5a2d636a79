/* The figure of a fit (figure_fit.c): the measured NDF beside the fitted one, their difference, the slopes' histogram
 * with the fitted P22's contours, and the radial profile of the standardised slopes against GGX and the Student-t
 * family of ggx_fit_tails. SPDX-License-Identifier: MIT */
#ifndef GGX_PLOT_FIGURE_FIT_H
#define GGX_PLOT_FIGURE_FIT_H

#include <stddef.h>

#include "canvas.h"
#include "ggx/ggx_fit.h"

/* The fitted samples as slopes: read fills x, y and the weight w (0: skip) of samples [at, at + k), k <= 1024. */
typedef struct fit_samples {
    void (*read)(const void *ctx, size_t at, size_t k, double *x, double *y, double *w);
    const void *ctx;
    size_t n;
    int cells; /* the samples are texels fitted as cells (ggx_fit_normal_cells): no goodness of fit */
} fit_samples;

/* The size of the figure's canvas, in canvas units; the radial profile's bins (of 2 degrees). */
enum { FIGURE_FIT_W = 1100, FIGURE_FIT_H = 1580, FIGURE_FIT_BINS = 45 };

/* Draws the figure of the fit of src (fit and info as the fit returned them; family the fitted model's name, title
 * the first line) onto c, a canvas of FIGURE_FIT_W x FIGURE_FIT_H: measured and fitted D(m) in top views on one colour
 * scale, their difference, the slopes' histogram about t with the fitted P22's contours, and the NDF's radial profile
 * in the standardised slopes z = L^-1 (x~ - t) (Sigma = L L^T), where GGX's D is 1 / pi at every angle, on a log
 * scale beside the fitted Student t's (info->tails, when fitted). Returns 0, or -1 when out of memory (nothing drawn). */
int figure_fit_draw(canvas *c, const fit_samples *src, const ggx_shape *fit, const ggx_fit_info *info,
                    const char *family, const char *title);

/* The radial profile the figure draws: measured[b], D of the standardised normals over the angles [2 b, 2 b + 2)
 * degrees (their weight over the ring's projected solid angle; NaN for an empty ring), and tails[k], the fitted Student
 * t's D at k degrees in the same coordinates (its mean over 64 azimuths; NaN when info->tails is not fitted). GGX's is
 * 1 / pi. Returns 0, or -1 when out of memory. */
int figure_fit_profile(const fit_samples *src, const ggx_fit_info *info, double measured[FIGURE_FIT_BINS],
                       double tails[90]);

#endif
