/* The parts of ggx microsurface that its subcommands share (microsurface_open.c; the subcommands in
 * cmd_microsurface.c and cmd_microsurface_figure.c).
 * SPDX-License-Identifier: MIT */
#ifndef GGX_TOOL_CMD_MICROSURFACE_H
#define GGX_TOOL_CMD_MICROSURFACE_H

#include <stddef.h>

#include "cli.h"
#include "microsurface.h"

/* The height field of --heightfield in grid units, checked to repeat as --tilted and --risers say (dies with one
 * line otherwise), and the tilt (0, 0 unless --tilted). */
double *microsurface_heights(const options *o, size_t *n_out, double tilt[2]);
/* The shape fitted to the facets off the risers (all of them where there are none). */
ggx_status microsurface_fit(const double *h, size_t n, const size_t risers[2], ggx_shape *fit);
/* The tile of --heightfield (microsurface_heights), the risers of --risers (ms_find_risers) and its tracer, tilted
 * for --tilted; dies with one line on error (--tilted with --risers too). */
ms_tracer *microsurface_open(const options *o, double **h, size_t *n, double tilt[2], size_t risers[2]);
/* The model's shape: the one given (--alpha, --skew, --rotate, --matrix; *given = 1) or microsurface_fit's. */
ggx_status microsurface_model(const options *o, const double *h, size_t n, const size_t risers[2], ggx_shape *s,
                              int *given);
/* ggx microsurface figure. */
int microsurface_figure(int argc, char **argv);
/* ggx microsurface wave (cmd_microsurface_wave.c). */
int microsurface_wave(int argc, char **argv);

#endif
