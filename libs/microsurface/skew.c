/* Skewed microsurfaces: a ramp under a field (a tilted patch or a sawtooth with risers), the GGX surface of a skewed
 * shape, and the vertical-facet masking form that the tracer sets beside the library's ggx_g1, ggx_g1_tilted and
 * ggx_g1_risers (microsurface.h; docs/design/microsurface.md, "Skewed surfaces"). SPDX-License-Identifier: MIT */
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

int ms_ggx_skewed(const ggx_shape *s, ms_ggx_spec *spec, size_t period, double *h, double t[2], char *err, size_t errn)
{
    /* the skewed shape's slopes: the scale Sigma as the unskewed shape's alphas and rotation, and t */
    double sig[3], ax, ay, tz;
    ggx_shape flat;
    ggx_shape_slopes(s, t, sig);
    if (ggx_shape_from_slopes(&flat, 0.0, 0.0, sig[0], sig[1], sig[2]) != GGX_OK) {
        snprintf(err, errn, "skewed surface: the shape's scale is outside the alphas a surface can have");
        return -1;
    }
    ggx_shape_ellipsoid_params(&flat, &ax, &ay, NULL, NULL, &tz);
    spec->alpha_x = ax, spec->alpha_y = ay, spec->phi = tz;
    if (ms_ggx(spec, h, err, errn) != 0) return -1;
    return ms_ramp(h, spec->n, t[0], t[1], period, err, errn);
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
