/* What the subcommands of ggx microsurface share (cmd_microsurface.h): the tile of --heightfield, its fit, its
 * tracer and the model's shape. SPDX-License-Identifier: MIT */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd_microsurface.h"
#include "ggx/ggx_fit.h"
#include "surface.h"

/* --downsample K: K x K blocks averaged (NaN where any point of a block is missing; trailing rows and columns that
 * fill no block dropped), as ggx fit --downsample takes them; returns the coarse grid, h freed */
static double *downsampled(double *h, size_t *nx, size_t *ny, size_t k, const char *name)
{
    size_t cx = *nx / k, cy = *ny / k;
    if (cx < 3 || cy < 3) {
        free(h);
        die("--downsample %zu leaves fewer than 3 x 3 heights of %s's %zu x %zu", k, name, *nx, *ny);
    }
    double *c = malloc(cx * cy * sizeof *c);
    if (!c) {
        free(h);
        die("out of memory for %zu x %zu heights", cx, cy);
    }
    for (size_t j = 0; j < cy; j++)
        for (size_t i = 0; i < cx; i++) {
            double sum = 0.0;
            for (size_t b = 0; b < k; b++)
                for (size_t a = 0; a < k; a++) sum += h[(j * k + b) * *nx + i * k + a];
            c[j * cx + i] = sum / (double)(k * k);
        }
    free(h);
    *nx = cx, *ny = cy;
    return c;
}

/* 0 where the square tile h (n x n) wraps along both axes: the differences across its edges (raised by the tilt
 * times n for --tilted) like the inner ones of the same phase (a sawtooth's risers: the rows P - 1 mod P; else all),
 * their deviations from those ones' mean within 3 times those ones' RMS deviation; else the axis (1 x, 2 y) and the
 * ratio. tilt receives the tile's mean slope (--tilted; else 0). */
static int tile_wraps(const double *h, size_t n, size_t P, int tilted, double tilt[2], double *ratio)
{
    for (int ax = 0; ax < 2; ax++) {
        double sum = 0.0, ref = 0.0, ref2 = 0.0, cnt = 0.0, rcnt = 0.0;
        for (size_t y = 0; y < n; y++)
            for (size_t x = 0; x + 1 < n; x++) {
                double d = ax == 0 ? h[y * n + x + 1] - h[y * n + x] : h[(x + 1) * n + y] - h[x * n + y];
                sum += d, cnt += 1.0;
                if (!P || x % P == P - 1) ref += d, ref2 += d * d, rcnt += 1.0;
            }
        tilt[ax] = tilted ? sum / cnt : 0.0;
        double mean = ref / rcnt, var = fmax(ref2 / rcnt - mean * mean, 0.0), wrap = 0.0;
        for (size_t y = 0; y < n; y++) {
            double d = (ax == 0 ? h[y * n] - h[y * n + n - 1] : h[y] - h[(n - 1) * n + y]) + tilt[ax] * (double)n;
            wrap += (d - mean) * (d - mean) / (double)n;
        }
        if (wrap > 9.0 * var + 1e-300) {
            *ratio = sqrt(wrap / var);
            return ax + 1;
        }
    }
    return 0;
}

double *microsurface_heights_um(const options *o, size_t *nx_out, size_t *ny_out, double *dx_out, size_t *missing)
{
    surface_read_options ro = {SURFACE_HEIGHTS, 0};
    surface s;
    char err[512];
    if (surface_read(o->heightfield, &ro, &s, err, sizeof err) != 0) die("%s", err);
    /* a file's own spacing is metres, and its z_scale brings heights into the unit of that spacing; --spacing D is
     * micrometres, the heights (times the file's z_scale) then taken in the unit of D; --z-scale Z, micrometres */
    double um = o->have_spacing ? 1.0 : 1e6;
    double dx = o->have_spacing ? o->spacing[0] : s.dx * um, dy = o->have_spacing ? o->spacing[1] : s.dy * um;
    double zs = o->have_z_scale ? o->z_scale : s.z_scale > 0 ? s.z_scale * um : (s.dx > 0 ? 0 : 1);
    size_t nx = s.nx, ny = s.ny, k = o->downsample > 1 ? (size_t)o->downsample : 1;
    if (nx < 3 || ny < 3) {
        surface_free(&s);
        die("%s: %zu x %zu heights: at least 3 x 3 are needed", o->heightfield, nx, ny);
    }
    if (!(dx > 0 && dy > 0)) die("%s: the file gives no grid spacing: give --spacing D (micrometres)", o->heightfield);
    if (!(zs > 0)) die("%s: the file gives no height unit: give --z-scale Z (micrometres)", o->heightfield);
    /* a square grid: spacings equal to 1e-3 (an instrument's calibration differs by less; y's slopes then carry dy / dx
     * - 1 of error, far below the rays' noise), taken at dx */
    if (fabs(dx - dy) > 1e-3 * dx)
        die("%s: spacing %g x %g um: equal spacings are needed (to 1e-3)", o->heightfield, dx, dy);
    if (!(zs / dx >= DBL_MIN && zs / dx <= DBL_MAX))
        die("%s: the height unit %g over the grid spacing %g is %g, beyond the range of a double (%g to %g): give "
            "--spacing and --z-scale in nearer units",
            o->heightfield, zs, dx, zs / dx, DBL_MIN, DBL_MAX);
    double *h = s.h;
    s.h = NULL;
    surface_free(&s);
    if (k > 1) h = downsampled(h, &nx, &ny, k, o->heightfield);
    *missing = 0;
    for (size_t i = 0; i < nx * ny; i++) {
        if (!isfinite(h[i])) { /* missing (NaN) or no height */
            h[i] = NAN, ++*missing;
            continue;
        }
        h[i] *= zs;
    }
    if (*missing == nx * ny) {
        free(h); /* (die exits: nothing left to the leak checkers) */
        die("%s: all %zu x %zu heights are missing", o->heightfield, nx, ny);
    }
    *nx_out = nx, *ny_out = ny, *dx_out = dx * (double)k;
    return h;
}

/* The height field of --heightfield in grid units (microsurface_heights_um over its spacing): a square periodic tile
 * (checked to repeat as --tilted and --risers say), or else a patch (pt->on: not square, missing points, or edges
 * that do not wrap), levelled (its least-squares plane taken off). */
double *microsurface_heights(const options *o, size_t *n_out, double tilt[2], microsurface_patch *pt)
{
    memset(pt, 0, sizeof *pt);
    tilt[0] = tilt[1] = 0.0;
    size_t nx, ny, k = o->downsample > 1 ? (size_t)o->downsample : 1;
    double dx, sum = 0.0, big = 0.0;
    double *h = microsurface_heights_um(o, &nx, &ny, &dx, &pt->missing);
    for (size_t i = 0; i < nx * ny; i++)
        if (!isnan(h[i])) h[i] /= dx, sum += h[i];
    double mean = sum / (double)(nx * ny - pt->missing);
    size_t P = (size_t)o->risers;
    if (P && nx == ny && (P > nx / 2 || nx % P != 0)) {
        free(h);
        die("--risers %zu: a period that divides the size %zu and is at most half of it", P, nx);
    }
    int axis = 0;
    double ratio = 0.0;
    if (nx != ny) snprintf(pt->why, sizeof pt->why, "not square");
    else if (pt->missing) snprintf(pt->why, sizeof pt->why, "%zu missing points", pt->missing);
    else if ((axis = tile_wraps(h, nx, P, o->tilted, tilt, &ratio)) != 0)
        snprintf(pt->why, sizeof pt->why,
                 "not periodic along %c (the differences across its edges %.3g times the inner ones' RMS deviation; "
                 "a tilted patch: --tilted; a sawtooth: --risers P)",
                 axis == 1 ? 'x' : 'y', ratio);
    /* single precision: a patch's heights (levelled below) to 0.06 within 1e6 of their mean, a tile's (whose tall
     * spikes the work limit weighs) within its range */
    double limit = pt->why[0] ? 1e6 : 1e30;
    for (size_t i = 0; i < nx * ny; i++)
        if (!isnan(h[i])) big = fmax(big, fabs(h[i] - mean));
    if (!(big <= limit)) {
        free(h);
        die("%s: heights %.3g grid spacings from their mean, beyond the tracer's single precision (at most %g; "
            "check --z-scale)",
            o->heightfield, big, limit);
    }
    if (pt->why[0]) {
        if (o->tilted || P) {
            free(h);
            die("%s: %s: --tilted and --risers take a periodic tile (without them it is traced as a patch)",
                o->heightfield, pt->why);
        }
        pt->on = 1, pt->nx = nx, pt->ny = ny, pt->downsample = (int)k;
        double plane[3];
        ms_level(h, nx, ny, 0, plane);
        pt->plane[0] = plane[0], pt->plane[1] = plane[1];
    }
    *n_out = nx;
    return h;
}

/* The fitted shape of the facets off the risers (ms_facet_normals), or of all the facets as given (not levelled:
 * the tracer traces them as they are); a patch's cells with a missing corner are left out (ggx_fit_heightfield). */
ggx_status microsurface_fit(const double *h, size_t nx, size_t ny, const size_t risers[2], ggx_shape *fit)
{
    ggx_heightfield_options ho = {1, 0};
    if (!risers[0] && !risers[1]) return ggx_fit_heightfield(fit, h, nx, ny, 1.0, 1.0, &ho, NULL, NULL);
    size_t n = nx;
    ggx_vec3 *m = malloc(4 * (n - 1) * (n - 1) * sizeof *m);
    if (!m) die("out of memory for the facets of %zu x %zu heights", n, n);
    ggx_status st = ggx_fit_normals(fit, m, NULL, ms_facet_normals(h, n, risers, m), NULL, NULL);
    free(m);
    return st;
}

ms_tracer *microsurface_open(const options *o, double **h, size_t *n, double tilt[2], size_t risers[2],
                             microsurface_patch *pt)
{
    if (o->tilted && o->risers) die("--tilted and --risers: a surface is one or the other");
    *h = microsurface_heights(o, n, tilt, pt);
    char err[400];
    risers[0] = risers[1] = 0;
    if (!pt->on && ms_find_risers(*h, *n, (size_t)o->risers, risers, err, sizeof err) != 0) {
        free(*h); /* (die exits: nothing left to the leak checkers) */
        die("%s", err);
    }
    ms_tracer *t = pt->on ? ms_patch_new(*h, pt->nx, pt->ny, err, sizeof err)
                          : ms_tracer_new(*h, *n, o->tilted ? tilt : NULL, err, sizeof err);
    if (!t) {
        free(*h); /* (die exits: nothing left to the leak checkers) */
        die("%s: %s", o->heightfield, err);
    }
    if (pt->on) ms_tracer_patch(t, NULL, NULL, NULL, NULL, &pt->absent);
    return t;
}

ggx_status microsurface_model(const options *o, const double *h, const microsurface_patch *pt, size_t n,
                              const size_t risers[2], ggx_shape *s, int *given)
{
    *given = o->have_alpha || o->have_skew || o->have_rotate || o->have_matrix;
    if (!*given) return pt->on ? microsurface_fit(h, pt->nx, pt->ny, risers, s) : microsurface_fit(h, n, n, risers, s);
    shape_from_options(o, s);
    return GGX_OK;
}
