/* Catmull-Rom interpolation, written once for the albedo tables (src/api/energy.c, src/api/tables.c).
 * SPDX-License-Identifier: MIT */
#ifndef GGX_COMMON_INTERP_H
#define GGX_COMMON_INTERP_H

/* The cubic through p[1] (f = 0) and p[2] (f = 1) with slopes (p[2] - p[0]) / 2 and (p[3] - p[1]) / 2: exact for
 * quadratics, C1 across cells. */
static inline double catmull_rom(const double p[4], double f)
{
    return p[1] +
           0.5 * f *
               (p[2] - p[0] + f * (2 * p[0] - 5 * p[1] + 4 * p[2] - p[3] + f * (3 * (p[1] - p[2]) + p[3] - p[0])));
}

#endif
