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

/* The height field of --heightfield in grid units (heights over the spacing, which must be equal along x and y),
 * checked to repeat as --tilted and --risers say, and the tilt (0, 0 unless --tilted). */
double *microsurface_heights(const options *o, size_t *n_out, double tilt[2])
{
    surface_read_options ro = {SURFACE_HEIGHTS, 0};
    surface s;
    char err[512];
    if (surface_read(o->heightfield, &ro, &s, err, sizeof err) != 0) die("%s", err);
    if (s.nx != s.ny) die("%s: %zu x %zu heights: the tracer takes a square periodic tile", o->heightfield, s.nx, s.ny);
    double dx = o->have_spacing ? o->spacing[0] : s.dx, dy = o->have_spacing ? o->spacing[1] : s.dy;
    double zs = o->have_z_scale ? o->z_scale : s.z_scale > 0 ? s.z_scale : (s.dx > 0 ? 0 : 1);
    if (!(dx > 0 && dy > 0)) die("%s: the file gives no grid spacing: give --spacing DX", o->heightfield);
    if (!(zs > 0)) die("%s: the file gives no height unit: give --z-scale Z", o->heightfield);
    if (fabs(dx - dy) > 1e-9 * dx) die("%s: spacing %g x %g: the tracer takes equal spacings", o->heightfield, dx, dy);
    if (!(zs / dx >= DBL_MIN && zs / dx <= DBL_MAX))
        die("%s: the height unit %g over the grid spacing %g is %g, beyond the range of a double (%g to %g): give "
            "--spacing and --z-scale in nearer units",
            o->heightfield, zs, dx, zs / dx, DBL_MIN, DBL_MAX);
    size_t n = s.nx, count = n * n, P = (size_t)o->risers;
    double *h = s.h;
    s.h = NULL;
    surface_free(&s);
    if (P && (P > n / 2 || n % P != 0)) {
        free(h);
        die("--risers %zu: a period that divides the size %zu and is at most half of it", P, n);
    }
    for (size_t i = 0; i < count; i++) {
        if (!isfinite(h[i])) {
            free(h); /* (die exits: nothing left to the leak checkers) */
            die("%s: height %zu is not finite", o->heightfield, i);
        }
        h[i] *= zs / dx;
    }
    /* the edges wrap: along each axis the differences across the tile's edge (raised by the tilt times n for a
     * tilted patch) are like the inner ones of the same phase (a sawtooth's risers: the rows P - 1 mod P; else all),
     * their deviations from those ones' mean within 3 times those ones' RMS deviation */
    for (int ax = 0; ax < 2; ax++) {
        double sum = 0.0, ref = 0.0, ref2 = 0.0, cnt = 0.0, rcnt = 0.0;
        for (size_t y = 0; y < n; y++)
            for (size_t x = 0; x + 1 < n; x++) {
                double d = ax == 0 ? h[y * n + x + 1] - h[y * n + x] : h[(x + 1) * n + y] - h[x * n + y];
                sum += d, cnt += 1.0;
                if (!P || x % P == P - 1) ref += d, ref2 += d * d, rcnt += 1.0;
            }
        tilt[ax] = o->tilted ? sum / cnt : 0.0;
        double mean = ref / rcnt, var = fmax(ref2 / rcnt - mean * mean, 0.0), wrap = 0.0;
        for (size_t y = 0; y < n; y++) {
            double d = (ax == 0 ? h[y * n] - h[y * n + n - 1] : h[y] - h[(n - 1) * n + y]) + tilt[ax] * (double)n;
            wrap += (d - mean) * (d - mean) / (double)n;
        }
        if (wrap > 9.0 * var + 1e-300) {
            double ratio = sqrt(wrap / var);
            free(h);
            die("%s: not periodic along %c (the differences across its edges are %.3g times the inner ones' RMS "
                "deviation): the tracer tiles the surface%s",
                o->heightfield, ax == 0 ? 'x' : 'y', ratio,
                o->tilted || P ? "" : " (a tilted patch: --tilted; a sawtooth: --risers P)");
        }
    }
    *n_out = n;
    return h;
}

/* The fitted shape of the facets off the risers (ms_facet_normals), or of all the facets as given (not levelled:
 * the tracer traces them as they are). */
ggx_status microsurface_fit(const double *h, size_t n, const size_t risers[2], ggx_shape *fit)
{
    ggx_heightfield_options ho = {1, 0};
    if (!risers[0] && !risers[1]) return ggx_fit_heightfield(fit, h, n, n, 1.0, 1.0, &ho, NULL, NULL);
    ggx_vec3 *m = malloc(4 * (n - 1) * (n - 1) * sizeof *m);
    if (!m) die("out of memory for the facets of %zu x %zu heights", n, n);
    ggx_status st = ggx_fit_normals(fit, m, NULL, ms_facet_normals(h, n, risers, m), NULL, NULL);
    free(m);
    return st;
}

ms_tracer *microsurface_open(const options *o, double **h, size_t *n, double tilt[2], size_t risers[2])
{
    if (o->tilted && o->risers) die("--tilted and --risers: a surface is one or the other");
    *h = microsurface_heights(o, n, tilt);
    char err[400];
    if (ms_find_risers(*h, *n, (size_t)o->risers, risers, err, sizeof err) != 0) {
        free(*h); /* (die exits: nothing left to the leak checkers) */
        die("%s", err);
    }
    ms_tracer *t = ms_tracer_new(*h, *n, o->tilted ? tilt : NULL, err, sizeof err);
    if (!t) {
        free(*h); /* (die exits: nothing left to the leak checkers) */
        die("%s", err);
    }
    return t;
}

ggx_status microsurface_model(const options *o, const double *h, size_t n, const size_t risers[2], ggx_shape *s,
                              int *given)
{
    *given = o->have_alpha || o->have_skew || o->have_rotate || o->have_matrix;
    if (!*given) return microsurface_fit(h, n, risers, s);
    shape_from_options(o, s);
    return GGX_OK;
}
