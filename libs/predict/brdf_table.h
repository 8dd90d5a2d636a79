/* A BRDF known at a set of incidences: for each incident direction wi of a grid (polar angles given, azimuths equally
 * spaced), its values over the outgoing directions on a res x res grid of the projected directions wo_xy in the unit
 * disk (cells of equal projected solid angle (2 / res)^2, the disk's rim cutting the outer ones), per channel. Traced
 * and wave-optics predictions land in it (their shares of the power per cell over the cell's projected solid angle)
 * and lit spheres read it back at any (wi, wo). SPDX-License-Identifier: MIT */
#ifndef GGX_PREDICT_BRDF_TABLE_H
#define GGX_PREDICT_BRDF_TABLE_H

#include <stddef.h>

#include "ggx/ggx.h"

enum { BRDF_TABLE_MAX_THETA = 32, BRDF_TABLE_MAX_CHANNELS = 3 };

typedef struct brdf_table {
    int n_theta, n_phi, res, channels;
    double theta[BRDF_TABLE_MAX_THETA]; /* the incidences' polar angles (radians, increasing, in [0, pi / 2)) */
    float *f;                           /* n_theta n_phi incidences x channels x res^2 cells, row y of wo_xy first */
    double *area;                       /* res^2: each cell's projected solid angle inside the disk (0 outside) */
    unsigned char *known;               /* per incidence: 1 (the start) where its values are known, 0 where not */
} brdf_table;

/* Incidence k = it n_phi + ip has polar angle theta[it] and azimuth 2 pi ip / n_phi. n_theta in [1, 32], n_phi in
 * [1, 360], res in [4, 4096], channels 1 or 3; the values start at 0. Returns 0, or -1 with a one-line reason. */
int brdf_table_init(brdf_table *t, int n_theta, const double *theta, int n_phi, int res, int channels, char *err,
                    size_t errn);
void brdf_table_free(brdf_table *t);
int brdf_table_count(const brdf_table *t); /* n_theta n_phi */
/* The unit incident direction of incidence k. */
ggx_vec3 brdf_table_incidence(const brdf_table *t, int k);
/* The values of incidence k, channel ch: res^2 floats. */
float *brdf_table_lobe(const brdf_table *t, int k, int ch);
/* The cell of a direction above the surface (wo.z > 0; its wo_xy in the disk), or -1 below it or for NaN. */
int brdf_table_cell(const brdf_table *t, const double wo[3]);
/* The unit direction through a cell's centre (the centre's wo_xy; for a rim cell whose centre is outside the disk,
 * pulled radially onto the disk's rim less 1e-9). */
ggx_vec3 brdf_table_cell_dir(const brdf_table *t, int cell);
/* f(wi, wo) per channel (the rest of f[3] copies channel 0 when channels is 1), 0 where either is below the surface.
 * Between the incidences: bilinear in (theta_i, phi_i) over the four nearest (the first or last row beyond the
 * grid's polar angles; the weights of those not known given to the known ones; where none of the four is known, the
 * nearest known incidence alone; 0 where none is known), each lobe read at wo_xy + wi_xy - wi_k,xy, bilinearly between cell centres: a lobe moves with
 * its incidence as the specular direction does (exact for the Kirchhoff form's shift, within the interpolation for
 * geometric lobes), where blending at a fixed wo would split it in two. */
void brdf_table_eval(const brdf_table *t, ggx_vec3 wi, ggx_vec3 wo, double f[3]);

/* Fills every incidence's cells with f's mean over ss x ss points of the cell's part inside the disk (each point at
 * the centre of its sub-square; those outside the disk left out), f(ctx, wi, wo, out) writing the table's channels.
 * ss in [1, 16]. */
typedef void (*brdf_table_fn)(const void *ctx, ggx_vec3 wi, ggx_vec3 wo, double f[3]);
void brdf_table_fill(brdf_table *t, brdf_table_fn f, const void *ctx, int ss);
/* The same for incidence k alone. */
void brdf_table_fill_incidence(brdf_table *t, int k, brdf_table_fn f, const void *ctx, int ss);
/* Incidence k's directional albedo in channel ch: the sum over the cells of f times their projected solid angle (NaN
 * where it is not known). */
double brdf_table_albedo(const brdf_table *t, int k, int ch);
/* The relative L2 distance over the outgoing directions of incidence k between a's channel ca and b's channel cb
 * (tables of one grid): ||a - b|| / ||b||, the norms weighted by the cells' projected solid angles; NaN where b is 0
 * everywhere, the grids differ or either incidence is not known. */
double brdf_table_l2(const brdf_table *a, int ca, const brdf_table *b, int cb, int k);

#endif
