/* Shared pieces of the sampling tests: the sweep of shapes and views, chi-square problems for normals keyed in the
 * sphere space of the shape, and the chi-square sweep of the registry's samplers of normals over any variant
 * (variants.h), with per-sampler counts of runs so that each program can prove that every registered sampler of the
 * families it sweeps was tested. SPDX-License-Identifier: MIT */
#ifndef GGX_SAMPLERS_H
#define GGX_SAMPLERS_H

#include "chi2.h"
#include "testlib.h"
#include "variants.h"

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

/* A chi-square problem for a sampler of normals: the sampler is sampler id of variant var (drawn in blocks, so that
 * batch variants run whole vectors), or custom (a sampler outside the registry, for the negative controls); the
 * density is pdf, or the pdf that the sampler claims in that variant when pdf is NULL. */
typedef struct normal_ctx normal_ctx;
typedef double (*normal_pdf_fn)(const normal_ctx *c, ggx_vec3 m);
enum { NORMAL_BLOCK = 512 };
struct normal_ctx {
    const ggx_shape *s;
    ggx_vec3 v;
    const variant *var;
    ggx_sampler_id id;
    vndf_fn custom;
    normal_pdf_fn pdf;
    long trials, draws; /* rejection samplers: the acceptance rate is draws / trials */
    ggx_vec3 block[NORMAL_BLOCK];
    int next, filled;
};
/* A context for sampler id of var on shape s and view v (pdf NULL, custom NULL). */
normal_ctx normal_ctx_of(const variant *var, ggx_sampler_id id, const ggx_shape *s, ggx_vec3 v);

/* Runs one chi-square test of a sampler of normals with 10^6 samples on 100 x 200 cells, checks it against the
 * Sidak level (a failure prints name and writes chi2_<name>.csv) and records the smallest p-value in *min_p. */
chi2_result run_normal_chi2(normal_ctx *c, const char *name, uint64_t seed, double *min_p);
/* The same run, not checked and writing no table: for the negative controls, which must be rejected. */
chi2_result run_normal_chi2_unchecked(normal_ctx *c, const char *name, uint64_t seed);

/* chi2_run with chi2_samples() samples on the chi2_grid() for them. */
chi2_result chi2_run_scaled(const chi2_problem *p, uint64_t seed, double alpha);

/* Bit sets of sampler families (1u << GGX_FAMILY_...). */
#define FAMILY_BIT(f) (1u << (f))

/* The chi-square sweep of variant var over every registry sampler of the given families that var has: each over
 * the shapes SWEEP_SHAPES[shapes[i]] (skewed ones left out for samplers of the UNSKEWED domain, where they must give
 * the zero vector) and the views SWEEP_VIEWS_DEG[views[j]] (NDF samplers, which ignore the view: n only). Seed of
 * a run: seed_base + 100 k + 10 shapes[i] + views[j] (NDF: seed_base + 100 k + shapes[i]), k the sampler's rank
 * among the registry's samplers of these families, so that a run of any variant uses the same random numbers as
 * the exported double run of the same sampler, shape and view. Returns the number of runs. */
int chi2_sweep(const variant *var, unsigned families, const int *shapes, int nshapes, const int *views, int nviews,
               uint64_t seed_base, double *min_p);

/* Whether a DIRECTION sampler transmits: its own pdf is nonzero for the direction refracted through n from a view at
 * 30 degrees with eta 1.5 (reflection sampling gives 0 there). The registry does not say; the sweeps of the rough
 * dielectric and the weight bound of reflection sampling (Walter eq 52) are chosen by this. */
int sampler_transmits(const ggx_sampler_info *info);

/* Chi-square runs made so far by this program: in all, and per variant and sampler. */
extern int chi2_runs_by[VARIANT_COUNT][GGX_SAMPLER_COUNT];
/* Fails unless every registry sampler of the given families that var has got at least one chi-square run: a
 * registered sampler that no sweep reaches (a domain that excludes every swept shape, a family left out) fails. */
void check_chi2_coverage(const variant *var, unsigned families);

/* int f(w) |w.z| dw over the upper hemisphere (below = 0) or the lower one, by nested adaptive quadrature in
 * (theta, phi): 8 panels of theta to tolerance 1e-8, each line 8 panels of phi to 1e-9. For the energy tables'
 * smooth multiple-scattering lobes (tests/unit/test_energy.c, tests/unit/test_energy_bsdf.c). */
double hemisphere_cos_quad(double (*f)(ggx_vec3 w, void *ctx), void *ctx, int below);

/* Chi-square of a sampler of directions whose pdf has jumps (the energy tables' cells), which the harness's per-cell
 * Gauss-Legendre does not resolve where the pdf is steep (alpha = 0.01 at grazing: chi2 = 15196 for 10000 dof for a
 * correct sampler). The bins are uniform in (t = w.z^2, phi), where the cosine-weighted measure is uniform, on each
 * side of the surface (sides = 1: w.z > 0 only; 2: both); each bin's expected count is a midpoint sum of pdf over
 * 100 x 8 points (a jump inside a bin moves the sum by at most its height over 100 of the bin's widths). Bins
 * expecting fewer than 5 samples are pooled. chi2_samples() draws; invalid draws are not binned. Returns the
 * p-value and writes the degrees of freedom. */
typedef struct binned_problem {
    int (*draw)(void *ctx, rng *r, ggx_vec3 *w); /* 0: an invalid sample */
    double (*pdf)(void *ctx, ggx_vec3 w);        /* per solid angle */
    int sides;
    void *ctx;
} binned_problem;
double binned_chi2(const binned_problem *p, uint64_t seed, int *dof);

#endif
