/* The rows of the albedo tables, written once: the per-shape tables (src/api/energy.c) and the shipped isotropic
 * tables (src/tables/iso_grid.h) place their views at theta = (pi / 2)(1 - y^2), y in [0, 1]: dense towards
 * grazing, linear in theta at n. The shipped table's rows include the per-shape table's (every second one), which
 * ggx_energy_create relies on. SPDX-License-Identifier: MIT */
#ifndef GGX_COMMON_ALBEDO_ROWS_H
#define GGX_COMMON_ALBEDO_ROWS_H

#include "ggx/ggx.h"

#include <math.h>

static inline double rows_theta_of_y(double y) { return 0.5 * GGX_PI * (1.0 - y * y); }

/* The row coordinate of a polar angle theta in [0, pi / 2] (0 at and beyond the horizon). */
static inline double rows_y_of_theta(double th)
{
    double y2 = 1.0 - th * (2.0 / GGX_PI);
    return y2 > 0 ? sqrt(y2) : 0.0;
}

/* The columns of the per-shape tables of unskewed shapes and of the shipped anisotropic table: azimuths phi (from
 * the axis of alpha_x) at uniform psi, warped by tan 2 phi = k tan 2 psi. The warp keeps every symmetry of an
 * unskewed E (phi -> -phi, pi - phi, pi + phi map psi alike) and is k times denser at both tangent axes, where E at
 * grazing changes fastest with the azimuth near the axis of the smaller alpha: with k = 1/2 the interpolation error
 * of (0.0171, 0.3426) at 89 degrees fell from 2.7e-3 to 8.5e-4, of (0.1, 1) from 5.4e-4 to 1.3e-4, and stayed at
 * 1.9e-5 for (0.3, 0.45) (docs/design/energy.md). */
#define COLS_WARP_K 0.5

/* phi of psi: psi plus the warp's correction, written without wrapping (its atan2 stays in (-pi/2, pi/2)). */
static inline double cols_phi_of_psi(double psi, double k)
{
    double s = sin(2.0 * psi), c = cos(2.0 * psi);
    return psi + 0.5 * atan2((k - 1.0) * s * c, c * c + k * s * s);
}

/* psi in (-pi, pi] of the direction (x, y) in the tangent plane (any length, not both 0): the inverse warp
 * tan 2 psi = tan 2 phi / k, in phi's quadrant (a signed zero x is put on its side). */
static inline double cols_psi_of_xy(double x, double y, double k)
{
    double psi = 0.5 * atan2(2.0 * x * y, k * (x * x - y * y));
    if (signbit(x)) psi += psi > 0 ? -GGX_PI : GGX_PI;
    return psi;
}

#endif
