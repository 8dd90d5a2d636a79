/* Shared test helpers: deterministic RNG, random shapes and directions, adaptive quadrature over the hemisphere of
 * micro-normals (lobe-aware: it integrates in the sphere space of a shape), and tolerance checks that print the
 * inputs that broke them. SPDX-License-Identifier: MIT */
#ifndef GGX_TESTLIB_H
#define GGX_TESTLIB_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ggx/ggx.h"
#include "verify.h"

/* ---- shapes ---- */
typedef struct shape_params {
    double ax, ay, tx, ty, tz;
} shape_params;
/* The random family: alpha in [0.02, 2] (log-uniform), ratio up to 1:10, theta_z any,
 * |theta_x|, |theta_y| <= max_skew. */
shape_params random_shape(rng *r, double max_skew);
void make_shape(ggx_shape *s, shape_params p); /* fails the test if setup fails */
/* Random direction above the horizon; with probability 1/4 a grazing one (cos theta in [1e-6, 1e-2]). */
ggx_vec3 random_view(rng *r);
/* A standard normal variate (Box-Muller) and a Gamma(a, 1) variate (Marsaglia and Tsang; a < 1 by a Gamma(a + 1)
 * times u^(1 / a)), independent of the library. */
double rng_gauss(rng *r);
double rng_gamma(rng *r, double a);
/* The normal of a slope drawn from the bivariate Student t of nu degrees of freedom and scale Sigma / 2 about t
 * (GGX's P22 at nu = 2; ggx_fit_tails), as a normal over the square root of a chi-square:
 * x = t + L g sqrt(nu / (2 chi2_nu)), Sigma = L L^T (sg: xx, xy, yy), chi2_nu = 2 Gamma(nu / 2). */
ggx_vec3 student_t_normal(rng *r, const double t[2], const double sg[3], double nu);

/* kappa(A) = max(ax, ay, 1) / min(ax, ay, 1) of ggx_shape_ellipsoid's A (its singular values are ax, ay and 1), and
 * ggx.h's bound on D rebuilt from (t, Sigma), 1e-12 + 2e-15 kappa^2 relative (ggx_shape_slopes, tests/unit/test_slopes.c):
 * the kappa^2 term is the rounding of Sigma's entries, which carry det Sigma to about 1e-16 cond(Sigma). */
double shape_kappa(double ax, double ay);
double slopes_bound(double ax, double ay);

/* ---- scale of the statistical tests ---- */
/* GGX_TEST_SCALE from the environment (default 1; make test runs the quick tier at 0.2, the sanitizer build 0.1). */
double test_scale(void);
/* The quick tier: GGX_TEST_SCALE below 1. A test over a list of cases then runs the subset that keeps one case of
 * each kind it covers (every function, sampler and variant still runs); the full tier, at 1 and above, runs all. */
int test_quick(void);
/* Samples for a chi-square run (10^6 at scale 1) and its grid (100 x 200 at scale 1, so that cells expect ~50). */
long chi2_samples(void);
void chi2_grid(long n, int *ntheta, int *nphi);

/* ---- the suite's one chi-square budget (tests/support/chi2_budget.c) ----
 * Every chi-square check of the suite that must pass is made at one per-run level, test_chi2_level(): the Sidak
 * level for a family-wise 0.01 over the sum of the shares tests/support/chi2_budget.c lists for each ctest entry. A negative
 * control, which must be rejected, compares with the same level and is not counted. */
double test_chi2_level(void);
int chi2_accepts(double p);        /* p >= test_chi2_level(); counts one check */
void chi2_budget_spend(long runs); /* counts runs judged elsewhere at test_chi2_level() (the seed audit's) */
/* At a program's end: prints the count and returns 1 (the program fails) when it exceeds the share of the entry
 * "program argv[1]" (of every entry of the program when argc <= 1). */
int chi2_budget_end(const char *program, int argc, char **argv);

/* ---- checks ---- */
/* |got - want| <= abs_tol + rel_tol |want|; on failure prints what and fails the test. */
#define CHECK_CLOSE(got, want, rel_tol, abs_tol, ...)                                                                  \
    check_close_impl((got), (want), (rel_tol), (abs_tol), __FILE__, __LINE__, __VA_ARGS__)
void check_close_impl(double got, double want, double rel_tol, double abs_tol, const char *file, int line,
                      const char *fmt, ...);
/* Fails with a formatted message when cond is false. */
#define CHECK(cond, ...) check_impl((cond) ? 1 : 0, #cond, __FILE__, __LINE__, __VA_ARGS__)
void check_impl(int ok, const char *expr, const char *file, int line, const char *fmt, ...);

#endif
