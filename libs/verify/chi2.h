/* Chi-square goodness-of-fit harness for samplers of directions. SPDX-License-Identifier: MIT
 *
 * A sampler's outputs are mapped to keys: a region index and a unit vector k. The key space is binned into equal-
 * area cells, ntheta slices of cos(theta) in [-1, 1] times nphi slices of phi, per region. Keys are chosen by each
 * test so that the lobe is wide in key space (the sphere space of the shape, normalize(A^{-T} m)), which keeps the
 * cells informative for sharp lobes; a bijective change of the sample space does not change what the test checks.
 * Expected counts integrate the key density over each cell (4 x 4 Gauss-Legendre, refined 64-fold in cells where
 * the density is zero at some nodes and not at others, with the 16-fold rule's difference as the error estimate).
 * Cells with expected count < 5 are pooled, as is the "invalid sample" category when its expected count is < 5; the
 * invalid category is left out when its expected count is below three times the quadrature's error estimate and the
 * observed one within that and its noise (it is not known better than that). Any sample whose key has zero density (a value the pdf
 * says is impossible) fails the run outright, as do invalid samples where the pdf integrates to 1. */
#ifndef GGX_CHI2_H
#define GGX_CHI2_H

#include "verify.h"

typedef struct chi2_problem {
    const char *name;
    int nregions;
    /* Draws one sample; returns 0 for an invalid sample (counted in the "invalid" category). */
    int (*draw)(void *ctx, rng *r, ggx_vec3 *w);
    /* Key of a valid sample; returns 0 if the sample has no key (it then counts as invalid). */
    int (*key)(void *ctx, ggx_vec3 w, int *region, ggx_vec3 *k);
    /* Density of keys per unit solid angle of k in region. */
    double (*density)(void *ctx, int region, ggx_vec3 k);
    void *ctx;
} chi2_problem;

typedef struct chi2_result {
    double stat, pvalue;
    int dof, bins;
    long invalid;
    double expected_invalid; /* N times (1 - integral of the density) */
    long zero_cell_hits;     /* samples at keys of zero density */
    double mass;             /* integral of the density over all cells */
} chi2_result;

/* Runs the test with n samples. On failure (pvalue < alpha or any zero-cell hit) writes chi2_<name>.csv with
 * region, itheta, iphi, observed, expected into the working directory, for the test that failed to show. */
chi2_result chi2_run(const chi2_problem *p, long n, int ntheta, int nphi, uint64_t seed, double alpha);
/* chi2_run that writes nothing: for the ggx command, which reports in its table, and the seed audit, whose failures
 * are expected answers. Both functions keep no state between calls (but the count of chi2_runs_made), so threads
 * may run them at once. */
chi2_result chi2_run_quiet(const chi2_problem *p, long n, int ntheta, int nphi, uint64_t seed, double alpha);

/* Keys for samplers of normals: k = normalize(A^{-T} m), the sphere space of the shape, where every lobe is wide;
 * the key density is pdf(s, v, m(k)) |A| / ||A^T k||^3. The ctx of a chi2_problem for such a sampler starts with a
 * normal_keys, so that normal_keys_key and normal_keys_density serve as its key and density. */
typedef double (*verify_pdf_fn)(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);
typedef struct normal_keys {
    const ggx_shape *s;
    ggx_vec3 v;
    verify_pdf_fn pdf; /* the density of m the sampler claims (ggx_pdf_vndf, verify_pdf_ndf, ...) */
} normal_keys;
int normal_keys_key(void *ctx, ggx_vec3 m, int *region, ggx_vec3 *k);
double normal_keys_density(void *ctx, int region, ggx_vec3 k);
/* ggx_pdf_ndf in the verify_pdf_fn signature (v ignored). */
double verify_pdf_ndf(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);

/* Upper tail of the chi-square distribution, Q(dof / 2, x / 2) (regularised incomplete gamma). */
double chi2_pvalue(double x, int dof);

/* Per-run significance for an overall level of 0.01 over `runs` runs (Sidak correction). */
double chi2_sidak(int runs);

/* The number of chi2_run and chi2_run_quiet calls this process has made, from any thread: what a test counts
 * against its share of the suite's chi-square budget (tests/support/testlib.h). */
long chi2_runs_made(void);

/* The number of runs behind the Sidak level at which `ggx audit` judges its chi-square runs (audit_run). The test
 * suite judges the audit at its own level instead (audit_run_at). */
#define CHI2_SUITE_RUNS 400

#endif
