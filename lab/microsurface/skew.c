/* Skewed microsurfaces: a ramp under a field (a tilted patch or a sawtooth with risers), and the masking forms that
 * the tracer decides between for them, besides the library's ggx_g1, ggx_g1_tilted and ggx_g1_risers (microsurface.h; docs/design/microsurface.md, "Skewed surfaces").
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "microsurface.h"

int ms_ramp(double *h, size_t n, double tx, double ty, size_t period, char *err, size_t errn)
{
    size_t P = period ? period : n;
    if (!(isfinite(tx) && isfinite(ty) && fabs(tx) <= 100.0 && fabs(ty) <= 100.0) || P < 2 || n % P != 0) {
        snprintf(err, errn, "ramp: finite slopes of at most 100 and a period from 2 that divides the size");
        return -1;
    }
    for (size_t y = 0; y < n; y++)
        for (size_t x = 0; x < n; x++) h[y * n + x] += tx * (double)(x % P) + ty * (double)(y % P);
    return 0;
}

double ms_g1_vertical_facets(const ggx_shape *s, const double v[3])
{
    if (!(v[2] > 0.0)) return 0.0;
    double t[2], sigma[3];
    ggx_shape_slopes(s, t, sigma);
    double tv = t[0] * v[0] + t[1] * v[1];
    double lit = v[2] * (1.0 + ggx_lambda(s, (ggx_vec3){v[0], v[1], v[2]})); /* the lune's projected area, eq 28 */
    return v[2] / (lit + fmax(tv, 0.0));
}
