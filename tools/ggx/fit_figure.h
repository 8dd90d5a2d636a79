/* The figure of ggx fit (tools/ggx/fit_figure.c). SPDX-License-Identifier: MIT */
#ifndef GGX_TOOL_FIT_FIGURE_H
#define GGX_TOOL_FIT_FIGURE_H

#include <stddef.h>

#include "canvas.h"
#include "cli.h"
#include "ggx/ggx_fit.h"

/* The fitted samples as slopes: read fills x, y and the weight w (0: skip) of samples [at, at + k), k <= 1024. */
typedef struct fit_samples {
    void (*read)(const void *ctx, size_t at, size_t k, double *x, double *y, double *w);
    const void *ctx;
    size_t n;
    int cells; /* the samples are texels fitted as cells (ggx_fit_normal_cells): no goodness of fit */
} fit_samples;

/* Writes the figure in format fmt (figure_format_of of --figure): measured and fitted D(m) in top views on one colour
 * scale, their difference, and the slopes' histogram about t with the fitted P22's contours. Dies on error. */
void fit_figure_write(const char *path, canvas_format fmt, const fit_samples *src, const ggx_shape *fit,
                      const ggx_fit_info *info, const char *family, const char *title);

#endif
