/* A direction's albedo tabulated over the upper hemisphere, with the sampling distribution of the multiple-
 * scattering lobe it defines: written once for the energy compensation of the conductor (src/api/energy.c) and of
 * the rough dielectric (src/api/energy_bsdf.c). SPDX-License-Identifier: MIT */
#ifndef GGX_API_ENERGY_TABLE_H
#define GGX_API_ENERGY_TABLE_H

#include <stddef.h>

#include "internal.h"

/* E(v) = P(v) I(v) over unit views v with v.z > 0 (P = ggx_internal_albedo_scale). nm rows in y, np columns in
 * phi, read by Catmull-Rom interpolation (src/api/energy_table.c has the node layout and its measured error). */
typedef struct energy_table {
    const ggx_shape *s; /* the owner's copy of the shape */
    int nm;             /* rows */
    int np;             /* columns: 1 (isotropic) or a full turn */
    double phi0;        /* azimuth of column 0 */
    double cos0, sin0;  /* cos phi0, sin phi0 */
    double warp;        /* the columns' warp k (common/albedo_rows.h); 1: uniform azimuths */
    double e_avg;       /* (1 / pi) int E w.z dw of the interpolant */
    double total;       /* sum of the cell weights int (1 - E) dt dphi = 2 pi (1 - e_avg) */
    double *tab;        /* nm x np values of I, row-major */
    double *pad;        /* the same with ghost nodes around it: (nm + 2) x pw, pw = np + 3 (1 if np = 1) */
    int pw;
    double *cdf;   /* (nm - 1) np + 1 cumulative cell weights, cdf[0] = 0 */
    double *guard; /* 2 (nm - 1) np: per cell the guard's lift of I (NaN: not guarded; infinite: the constant cap),
                       * then its cap (energy_table.c: guard_cells, and the grazing band) */
} energy_table;

/* E of the table's shape at a unit view v with v.z > 0, divided by P(v); y is the view's row coordinate
 * (theta = (pi / 2)(1 - y^2)), for a caller that reads rows of a shipped table instead. */
typedef double (*energy_node_fn)(void *ctx, ggx_vec3 v, double y);

/* The number of doubles ggx_internal_etab_build needs for shape s, nm rows (nm >= 4) and np_full columns on a full turn
 * (a multiple of 4; isotropic shapes need one column). */
size_t ggx_internal_etab_size(const ggx_shape *s, int nm, int np_full);
/* Fills t for shape s (kept by pointer: it must outlive t) with nm rows and np_full columns in storage of
 * ggx_internal_etab_size(s, nm, np_full) doubles, calling node once per distinct node (the symmetries of unskewed shapes
 * fill the rest). warp: the columns' warp k for an unskewed s (1: uniform azimuths; skewed shapes always have 1).
 * check: compare the interpolant with node() where the nodes show a feature, and guard the cells where it falls below
 * E (energy_table.c, guard_cells); node must then compute E, not interpolate a table. */
void ggx_internal_etab_build(energy_table *t, const ggx_shape *s, int nm, int np_full, double warp, int check,
                             double *storage, energy_node_fn node, void *ctx);
/* E at a unit v with v.z > 0, in [0, 1]: the interpolant, or in a guarded cell a value not below E there. */
double ggx_internal_etab_albedo(const energy_table *t, ggx_vec3 v);
/* The piecewise-constant density, per solid angle, that follows (1 - E(w)) w.z over the table's cells, at a unit w
 * with w.z > 0, and a direction drawn from it (the zero vector when 1 - E vanishes everywhere). */
double ggx_internal_etab_pdf(const energy_table *t, ggx_vec3 w);
ggx_vec3 ggx_internal_etab_sample(const energy_table *t, double u1, double u2);

/* A unit direction with z > 0, or 0 for a zero, non-finite or lower-hemisphere one. */
int ggx_internal_unit_up(ggx_vec3 w, ggx_vec3 *out);
/* u clamped to [0, 1). */
double ggx_internal_clamp01(double u);
/* The invalid sample. */
ggx_sample ggx_internal_invalid_sample(void);

#endif
