/* SPDX-License-Identifier: MIT */
#include "samplers.h"

#include <math.h>
#include <stdio.h>

const sweep_shape SWEEP_SHAPES[] = {
    {"iso 0.05", {0.05, 0.05, 0, 0, 0}},          {"iso 0.3", {0.3, 0.3, 0, 0, 0}},
    {"iso 1", {1.0, 1.0, 0, 0, 0}},               {"iso 2", {2.0, 2.0, 0, 0, 0}},
    {"aniso 0.05:0.5", {0.05, 0.5, 0, 0, 0}},     {"aniso 1:0.1 rot", {1.0, 0.1, 0, 0, 0.7}},
    {"skew 0.3:1", {0.3, 1.0, 0.5, -0.3, 0.4}},   {"skew 0.05:0.3", {0.05, 0.3, -0.5, 0.5, 1.2}},
    {"skew 2:0.2", {2.0, 0.2, 0.3, 0.5, -0.8}},
};
const int SWEEP_NSHAPES = sizeof SWEEP_SHAPES / sizeof SWEEP_SHAPES[0];
const double SWEEP_VIEWS_DEG[] = {0.0, 30.0, 80.0, 89.5};
const int SWEEP_NVIEWS = sizeof SWEEP_VIEWS_DEG / sizeof SWEEP_VIEWS_DEG[0];
int chi2_runs_done = 0;

ggx_vec3 sweep_view(double theta_deg)
{
    if (theta_deg == 0.0) return t_vec(0, 0, 1);
    return t_dir(theta_deg * T_PI / 180.0, 0.7);
}

static double uniform_cb(void *state) { return rng_uniform((rng *)state); }

int normal_draw(void *vc, rng *r, ggx_vec3 *m)
{
    normal_ctx *c = vc;
    double u1 = rng_uniform(r), u2 = rng_uniform(r);
    c->draws++;
    if (c->vndf) *m = c->vndf(c->keys.s, c->keys.v, u1, u2);
    else if (c->ndf) *m = c->ndf(c->keys.s, u1, u2);
    else {
        unsigned t;
        *m = c->reject(c->keys.s, c->keys.v, uniform_cb, r, &t);
        c->trials += t;
    }
    return t_dot(*m, *m) > 0.5;
}

chi2_result chi2_run_scaled(const chi2_problem *p, uint64_t seed, double alpha)
{
    long n = chi2_samples();
    int nt, np;
    chi2_grid(n, &nt, &np);
    return chi2_run(p, n, nt, np, seed, alpha);
}

chi2_result run_normal_chi2(normal_ctx *c, const char *name, uint64_t seed, double *min_p)
{
    chi2_problem p = {name, 1, normal_draw, normal_keys_key, normal_keys_density, c};
    double alpha = chi2_sidak(CHI2_SUITE_RUNS);
    chi2_result r = chi2_run_scaled(&p, seed, alpha);
    chi2_runs_done++;
    CHECK(r.zero_cell_hits == 0, "%s: %ld samples where the pdf is zero", name, r.zero_cell_hits);
    CHECK(r.pvalue >= alpha, "%s: chi2 %.1f, dof %d, p = %.3g < %.3g (histogram in chi2_*.csv)", name, r.stat, r.dof,
          r.pvalue, alpha);
    if (min_p && r.pvalue < *min_p) *min_p = r.pvalue;
    return r;
}
