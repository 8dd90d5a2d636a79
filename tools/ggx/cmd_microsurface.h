/* The parts of ggx microsurface that its subcommands share (microsurface_open.c; the subcommands in
 * cmd_microsurface.c and cmd_microsurface_figure.c).
 * SPDX-License-Identifier: MIT */
#ifndef GGX_TOOL_CMD_MICROSURFACE_H
#define GGX_TOOL_CMD_MICROSURFACE_H

#include <stddef.h>

#include "cli.h"
#include "microsurface.h"

/* A measured surface traced as a patch (ms_patch_new): on 0 for a periodic tile. */
typedef struct microsurface_patch {
    int on;
    size_t nx, ny, missing, absent; /* its size, missing points and absent cells (a missing corner) */
    int downsample;                 /* --downsample's K (1: none) */
    double plane[2];                /* the least-squares plane's slopes taken off (levelled) */
    char why[200];                  /* why it is no tile: not square, missing points, not periodic along x or y */
} microsurface_patch;

/* The heights of --heightfield in micrometres (NaN for a missing point) on a grid of spacing *dx micrometres, equal
 * along x and y to 1e-3, box-averaged by --downsample K: a file's own spacing is metres (its heights times its
 * z_scale in the spacing's unit); --spacing D is micrometres, the heights (times the file's z_scale) then in D's unit;
 * --z-scale Z, micrometres per height unit. *missing: the
 * missing points. Dies with one line on bad input (no spacing or height unit, under 3 x 3, every point missing,
 * unequal spacings, a height unit over the spacing beyond a double's range). */
double *microsurface_heights_um(const options *o, size_t *nx, size_t *ny, double *dx, size_t *missing);
/* The height field of --heightfield in grid units (equal spacings to 1e-3; --downsample K box-averages it), a square
 * periodic tile checked to repeat as --tilted and --risers say, or else a patch (*pt), levelled; dies with
 * one line on bad input (no spacing or height unit, under 3 x 3, every point missing, heights beyond 1e6 spacings).
 * *n_out: the tile's size (a patch's nx). tilt: 0, 0 unless --tilted. */
double *microsurface_heights(const options *o, size_t *n_out, double tilt[2], microsurface_patch *pt);
/* The shape fitted to the facets off the risers (all of them where there are none; a patch's present ones). */
ggx_status microsurface_fit(const double *h, size_t nx, size_t ny, const size_t risers[2], ggx_shape *fit);
/* The surface of --heightfield (microsurface_heights), the risers of --risers (ms_find_risers) and its tracer: the
 * tile's, tilted for --tilted, or the patch's; dies with one line on error (--tilted with --risers too). */
ms_tracer *microsurface_open(const options *o, double **h, size_t *n, double tilt[2], size_t risers[2],
                             microsurface_patch *pt);
/* The model's shape: the one given (--alpha, --skew, --rotate, --matrix; *given = 1) or microsurface_fit's. */
ggx_status microsurface_model(const options *o, const double *h, const microsurface_patch *pt, size_t n,
                              const size_t risers[2], ggx_shape *s, int *given);
/* ggx microsurface figure. */
int microsurface_figure(int argc, char **argv);
/* ggx microsurface wave (cmd_microsurface_wave.c). */
int microsurface_wave(int argc, char **argv);

#endif
