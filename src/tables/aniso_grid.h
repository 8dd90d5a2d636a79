/* The grid of the shipped anisotropic albedo table (src/tables/albedo_aniso.inc), shared by its generator
 * (lab/gen_tables), its lookup (src/api/tables.c) and the per-shape tables of ggx_energy_create, whose nodes are
 * nodes of this grid. SPDX-License-Identifier: MIT
 *
 * E(v) of ggx_albedo (separable G) for the diagonal shape (alpha_x, alpha_y), v in the shape's frame.
 * - Rows: the per-shape tables' 33 views at theta = (pi / 2)(1 - y^2), y = i / 32 (common/albedo_rows.h).
 * - Columns: 33 azimuths phi = W(psi), psi = (pi / 2) p / 32, from the axis of alpha_x, W the columns' warp
 *   (common/albedo_rows.h: denser at both axes). E is even about both tangent axes, so a quarter turn holds every
 *   view; these are the per-shape tables' columns 0 to 32 of 128.
 * - Roughnesses: ANI_NA values from ANI_AMIN to ANI_AMAX uniform in u = ln alpha + ANI_C alpha, and one more beyond
 *   each end (computed, not extrapolated: extrapolated ends left 2.3e-3 in the last cell), so index a in
 *   [-1, ANI_NA]. u is log-uniform at small alpha and denser towards alpha = 2, where E bends most: with 17 nodes
 *   the largest Catmull-Rom error between nodes along alpha_y (alpha_x 0.01 to 0.7, 66 views) was 7.3e-4
 *   log-uniform, 3.4e-4 with ANI_C = 0.7, which left 1.1e-3 at alpha 0.02 at grazing; hence 21 nodes and
 *   ANI_C = 0.5 (docs/design/energy.md).
 *   E(alpha_x, alpha_y, phi) = E(alpha_y, alpha_x, pi / 2 - phi), so only the pairs a_x <= a_y are stored, pair
 *   ani_pair(a_x, a_y).
 * The values are I = E / P(v), P the closed-form factor of ggx_albedo's E (internal.h), stored as float. */
#ifndef GGX_TABLES_ANISO_GRID_H
#define GGX_TABLES_ANISO_GRID_H

#include <math.h>

enum { ANI_NY = 33, ANI_NP = 33, ANI_NA = 21, ANI_NV = ANI_NA + 2, ANI_PAIRS = ANI_NV * (ANI_NV + 1) / 2 };
#define ANI_AMIN 1e-2
#define ANI_AMAX 2.0
#define ANI_C 0.5

static inline double ani_u(double alpha) { return log(alpha) + ANI_C * alpha; }
/* The coordinate of alpha (0 at ANI_AMIN, ANI_NA - 1 at ANI_AMAX). */
static inline double ani_index_of_alpha(double alpha)
{
    return (ani_u(alpha) - ani_u(ANI_AMIN)) / (ani_u(ANI_AMAX) - ani_u(ANI_AMIN)) * (ANI_NA - 1);
}
/* alpha of index a in [-1, ANI_NA] (the ends are the ghosts): Newton's method on the increasing, concave ln alpha +
 * ANI_C alpha = u from below, to rounding (the generator's nodes; the lookup needs only ani_index_of_alpha). */
static inline double ani_alpha_of(double a)
{
    double u = ani_u(ANI_AMIN) + (ani_u(ANI_AMAX) - ani_u(ANI_AMIN)) * a / (ANI_NA - 1),
           x = exp(u) / (1.0 + ANI_C * exp(u));
    for (int k = 0; k < 60; k++) x -= (log(x) + ANI_C * x - u) / (1.0 / x + ANI_C);
    return x;
}
/* The stored pair of indices ax <= ay, both in [-1, ANI_NA]. */
static inline int ani_pair(int ax, int ay) { return (ay + 1) * (ay + 2) / 2 + ax + 1; }

#endif
