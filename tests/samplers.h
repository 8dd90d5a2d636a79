/* Shared pieces of the sampling tests: the sweep of shapes and views, the samplers under test, and chi-square
 * problems for normals keyed in the sphere space of the shape. SPDX-License-Identifier: MIT */
#ifndef GGX_SAMPLERS_H
#define GGX_SAMPLERS_H

#include "chi2.h"
#include "testlib.h"

typedef struct sweep_shape {
    const char *name;
    shape_params p;
} sweep_shape;

/* alpha in {0.05, 0.3, 1, 2}, ratios up to 1:10, theta_z, and skews up to 0.5 rad. */
extern const sweep_shape SWEEP_SHAPES[];
extern const int SWEEP_NSHAPES;
/* Views at 0 (exactly n), 30, 80 and 89.5 degrees from n (phi = 0.7 rad). */
extern const double SWEEP_VIEWS_DEG[];
extern const int SWEEP_NVIEWS;
ggx_vec3 sweep_view(double theta_deg);

typedef ggx_vec3 (*vndf_fn)(const ggx_shape *, ggx_vec3, double, double);
typedef ggx_vec3 (*ndf_fn)(const ggx_shape *, double, double);
typedef ggx_vec3 (*reject_fn)(const ggx_shape *, ggx_vec3, ggx_uniform_fn, void *, unsigned *);

/* Sampler of normals under test: exactly one of vndf, ndf, reject is set. */
typedef struct normal_ctx {
    normal_keys keys; /* shape, view and the pdf the sampler is claimed to have; first, for normal_keys_* */
    vndf_fn vndf;
    ndf_fn ndf;
    reject_fn reject;
    long trials, draws;
} normal_ctx;

int normal_draw(void *ctx, rng *r, ggx_vec3 *m);

/* Runs one chi-square test of a normal sampler with 10^6 samples on 100 x 200 cells, checks it against the Sidak
 * level and records the smallest p-value in *min_p. Returns the result. */
chi2_result run_normal_chi2(normal_ctx *c, const char *name, uint64_t seed, double *min_p);

/* chi2_run with chi2_samples() samples on the chi2_grid() for them. */
chi2_result chi2_run_scaled(const chi2_problem *p, uint64_t seed, double alpha);

/* Number of chi-square runs made so far by this program. */
extern int chi2_runs_done;

#endif
