/* The grid of the shipped isotropic table of the rough dielectric's albedo R + T (src/tables/bsdf_iso.inc), shared
 * by its generator (lab/gen_tables) and its lookup (src/api/tables.c). SPDX-License-Identifier: MIT
 *
 * The table is indexed by the relative index eta_r that the light meets: eta for light from above, 1 / eta from
 * below (an isotropic ellipsoid is symmetric about the tangent plane, so light from below through eta is light from
 * above through 1 / eta). Two halves, never interpolated across eta_r = 1 (where the transmission becomes a delta):
 * h = 0 for eta_r > 1, h = 1 for eta_r < 1, each over s = |eta_r - 1| / (eta_r + 1) in [BSDF_S0, BSDF_S1]
 * (eta_r in [1.05, 3] and [1 / 3, 1 / 1.05]).
 * - Rows: the views of the isotropic conductor table (iso_grid.h), 65 at theta = (pi / 2)(1 - y^2), so that a row of
 *   this table is a row of the per-shape tables of ggx_bsdf_energy_create.
 * - Columns in alpha: BSDF_NA log-uniform from BSDF_AMIN to BSDF_AMAX.
 * - Columns in eta_r: BSDF_NE per half, uniform in s^(1/4). As eta_r -> 1 the critical angle of the side that can
 *   reflect totally moves to grazing like 2 sqrt(s), and E changes fastest there; measured on alpha 0.02 to 1 with
 *   24 nodes per half, the largest Catmull-Rom error between nodes was 1.3e-2 uniform in s, 2.5e-3 uniform in
 *   sqrt(s), 1.1e-3 uniform in log s (worse at large s) and 8.3e-4 uniform in s^(1/4) (docs/design/energy.md).
 * The values are I = E / P(v), P the closed-form factor of ggx_albedo's E (internal.h), stored as float: the
 * interpolation error (1e-4 and more) is far above float's rounding. */
#ifndef GGX_TABLES_BSDF_GRID_H
#define GGX_TABLES_BSDF_GRID_H

#include <math.h>

#include "iso_grid.h"

enum { BSDF_NY = ISO_NY, BSDF_NA = 33, BSDF_NE = 24 };
#define BSDF_AMIN 1e-2
/* The table keeps within 1e-3 of the quadrature from this alpha; below it, near the critical angle of the denser
 * side, up to 1.2e-3 was found (docs/design/energy.md). */
#define BSDF_PROMISE_AMIN 0.025
#define BSDF_AMAX 2.0
#define BSDF_ETA0 1.05
#define BSDF_ETA1 3.0
#define BSDF_S0 (0.05 / 2.05) /* eta_r = BSDF_ETA0 */
#define BSDF_S1 0.5           /* eta_r = BSDF_ETA1 */

static inline double bsdf_alpha_of_x(double x) { return BSDF_AMIN * pow(BSDF_AMAX / BSDF_AMIN, x); }
static inline double bsdf_x_of_alpha(double a) { return log(a / BSDF_AMIN) / log(BSDF_AMAX / BSDF_AMIN); }

/* eta_r of the coordinate z in [0, 1] of half h. */
static inline double bsdf_eta_of_z(int h, double z)
{
    double q0 = sqrt(sqrt(BSDF_S0)), q = q0 + (sqrt(sqrt(BSDF_S1)) - q0) * z, s = (q * q) * (q * q);
    double e = (1.0 + s) / (1.0 - s);
    return h ? 1.0 / e : e;
}
/* Whether eta_r is in the table: [BSDF_ETA0, BSDF_ETA1] or its inverse, tested on eta_r itself (z, computed with
 * rounding, could read a node a few ulps outside). */
static inline int bsdf_eta_in(double eta_r)
{
    return (eta_r >= BSDF_ETA0 && eta_r <= BSDF_ETA1) || (eta_r * BSDF_ETA0 <= 1.0 && eta_r * BSDF_ETA1 >= 1.0);
}
/* The half and the coordinate z of eta_r > 0, eta_r != 1 (z outside [0, 1] beyond the table's range). */
static inline double bsdf_z_of_eta(double eta_r, int *h)
{
    *h = eta_r < 1.0;
    double s = fabs(eta_r - 1.0) / (eta_r + 1.0), q0 = sqrt(sqrt(BSDF_S0));
    return (sqrt(sqrt(s)) - q0) / (sqrt(sqrt(BSDF_S1)) - q0);
}

#endif
