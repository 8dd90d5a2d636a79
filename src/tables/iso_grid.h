/* The grid of the shipped isotropic albedo tables (src/tables/albedo_iso.inc), shared by their generator
 * (lab/gen_tables) and their lookup (src/api/tables.c). SPDX-License-Identifier: MIT
 *
 * Rows: views at y = i / (ISO_NY - 1), theta = (pi / 2)(1 - y^2) (mu = sin(pi y^2 / 2): dense towards grazing, linear
 * in theta at n; the energy tables' rows, docs/design/energy.md). Columns: alpha = ISO_AMIN (ISO_AMAX / ISO_AMIN)^x,
 * x = j / (ISO_NA - 1), log-uniform (E changes with the ratio of alpha to the view's height near grazing).
 * The values are I = E / P(v) with P the closed-form factor of ggx_albedo's E (internal.h). */
#ifndef GGX_TABLES_ISO_GRID_H
#define GGX_TABLES_ISO_GRID_H

#include <math.h>

#include "ggx/ggx.h"
#include "common/albedo_rows.h"

enum { ISO_NY = 65, ISO_NA = 97 };
#define ISO_AMIN 1e-3
#define ISO_AMAX 2.0

static inline double iso_alpha_of_x(double x) { return ISO_AMIN * pow(ISO_AMAX / ISO_AMIN, x); }
static inline double iso_x_of_alpha(double a) { return log(a / ISO_AMIN) / log(ISO_AMAX / ISO_AMIN); }
/* The view of row coordinate y in [0, 1] (in the x-z plane; isotropic E does not depend on the azimuth). */
static inline ggx_vec3 iso_view_of_y(double y)
{
    double th = rows_theta_of_y(y);
    ggx_vec3 v = {sin(th), 0.0, cos(th)};
    if (y >= 1.0) v.x = 0.0, v.z = 1.0;
    return v;
}
/* The row coordinate of cos theta = mu in [0, 1]. */
static inline double iso_y_of_mu(double mu) { return rows_y_of_theta(acos(mu < 1 ? (mu > 0 ? mu : 0) : 1)); }

#endif
