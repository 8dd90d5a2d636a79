/* The rows of the albedo tables, written once: the per-shape tables (src/api/energy.c) and the shipped isotropic
 * tables (src/tables/iso_grid.h) place their views at theta = (pi / 2)(1 - y^2), y in [0, 1]: dense towards
 * grazing, linear in theta at n. The shipped table's rows include the per-shape table's (every second one), which
 * ggx_energy_create relies on. SPDX-License-Identifier: MIT */
#ifndef GGX_COMMON_ALBEDO_ROWS_H
#define GGX_COMMON_ALBEDO_ROWS_H

#include <math.h>

static inline double rows_theta_of_y(double y) { return 0.5 * 3.14159265358979323846 * (1.0 - y * y); }

/* The row coordinate of a polar angle theta in [0, pi / 2] (0 at and beyond the horizon). */
static inline double rows_y_of_theta(double th)
{
    double y2 = 1.0 - th * (2.0 / 3.14159265358979323846);
    return y2 > 0 ? sqrt(y2) : 0.0;
}

#endif
