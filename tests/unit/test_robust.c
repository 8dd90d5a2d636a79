/* The numerical contract of include/ggx/ggx.h, proven by an adversarial table and by property tests over random
 * inputs: evaluations finite and >= 0 (Lambda: finite), samplers a unit vector with a finite pdf > 0 or the zero
 * vector (pdf 0), direction samples valid or marked invalid with pdf 0, the weight bound, reciprocity.
 * GGX_TEST_SCALE (default 1) scales the random counts (the sanitizer build uses 0.1). SPDX-License-Identifier: MIT */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "samplers.h"

#include "ggx/ggx_inline.h"
#include "ggx/ggx_samplers.h"

static long n_checked;

/* The contract for one shape and one (v, m) pair: every evaluation. */
static void check_evals(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m, const char *what)
{
    ggx_fresnel f;
    ggx_fresnel_conductor(&f, 0.2, 3.9);
    double r[] = {ggx_ndf(s, m),
                  ggx_gaussian_curvature(s, m),
                  ggx_projected_area(s, v),
                  ggx_lune_area(s, v, m),
                  ggx_g1(s, v, m),
                  ggx_g1_smith(s, v),
                  ggx_g1_tilted(s, v, m),
                  ggx_g1_risers(s, v, m),
                  ggx_g2(s, v, m, m),
                  ggx_g2_height_correlated(s, v, m, m),
                  ggx_pdf_vndf(s, v, m),
                  ggx_pdf_ndf(s, m),
                  ggx_brdf_eval(s, &f, v, m),
                  ggx_pdf_brdf(s, v, m),
                  ggx_bsdf_eval(s, 1.5, v, m, GGX_RADIANCE),
                  ggx_bsdf_eval(s, 1 / 1.5, m, v, GGX_IMPORTANCE),
                  ggx_pdf_bsdf(s, 1.5, v, m),
                  ggx_p22(s, m.x, m.y),
                  ggx_ndf_spherical(s, acos(fmin(1, fabs(m.z))), atan2(m.y, m.x))};
    for (unsigned i = 0; i < sizeof r / sizeof r[0]; i++)
        CHECK(isfinite(r[i]) && r[i] >= 0, "%s: function %u = %g for v (%.17g,%.17g,%.17g) m (%.17g,%.17g,%.17g)", what,
              i, r[i], v.x, v.y, v.z, m.x, m.y, m.z);
    CHECK(isfinite(ggx_lambda(s, v)), "%s: Lambda", what);
    CHECK(ggx_g1(s, v, m) <= 1.0 && ggx_g1_tilted(s, v, m) <= 1.0 && ggx_g1_risers(s, v, m) <= 1.0, "%s: G1 > 1", what);
    n_checked += 20;
}

/* A sampler's output: the zero vector (invalid), or a unit vector with a finite pdf > 0. may_be_invalid: the zero
 * vector is allowed too (a rejection sampler's exhausted budget). */
static void check_normal(ggx_vec3 m, double pdf, int must_be_invalid, int may_be_invalid, const char *what, ggx_vec3 v,
                         double u1, double u2)
{
    n_checked++;
    int zero = m.x == 0 && m.y == 0 && m.z == 0;
    if (must_be_invalid) {
        CHECK(zero, "%s: v (%.17g,%.17g,%.17g) outside the domain gave (%g,%g,%g)", what, v.x, v.y, v.z, m.x, m.y, m.z);
        return;
    }
    if (zero && may_be_invalid) return;
    CHECK(!zero, "%s: no sample for v (%.17g,%.17g,%.17g) u (%.17g, %.17g)", what, v.x, v.y, v.z, u1, u2);
    CHECK(fabs(sqrt(t_dot(m, m)) - 1) <= 1e-12 && m.z >= 0,
          "%s: m (%.17g,%.17g,%.17g) not a unit upper normal, u (%.17g, %.17g)", what, m.x, m.y, m.z, u1, u2);
    CHECK(isfinite(pdf) && pdf > 0, "%s: pdf %g at m (%.17g,%.17g,%.17g), v (%.17g,%.17g,%.17g), u (%.17g, %.17g)",
          what, pdf, m.x, m.y, m.z, v.x, v.y, v.z, u1, u2);
}

static void check_dir_sample(ggx_sample x, const char *what, ggx_vec3 v)
{
    n_checked++;
    if (x.event == GGX_EVENT_INVALID) {
        CHECK(x.pdf == 0 && x.weight == 0 && x.w.x == 0 && x.w.y == 0 && x.w.z == 0, "%s: invalid sample not zeroed",
              what);
        return;
    }
    CHECK(fabs(sqrt(t_dot(x.w, x.w)) - 1) <= 1e-12, "%s: |w| - 1 = %g", what, sqrt(t_dot(x.w, x.w)) - 1);
    CHECK(isfinite(x.pdf) && x.pdf > 0 && isfinite(x.weight) && x.weight >= 0,
          "%s: pdf %g weight %g for v (%.17g,%.17g,%.17g)", what, x.pdf, x.weight, v.x, v.y, v.z);
}

/* The random numbers of a rejection sampler: u1, u2, u3 of the case in turn, then a stream from them, so that the
 * hard values come first and the sampler can still accept. */
typedef struct ustream {
    double u[3];
    int i;
    rng r;
} ustream;
static double ustream_next(void *vs)
{
    ustream *st = vs;
    return st->i < 3 ? st->u[st->i++] : rng_uniform(&st->r);
}

static int transmits[GGX_SAMPLER_COUNT]; /* per sampler, from sampler_transmits (main) */

static double clamp_u(double u) { return u > 0 ? (u < 1 ? u : 1) : 0; } /* NaN: 0 */
static int same_vec(ggx_vec3 a, ggx_vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

/* Direction samplers run with both settings: F = 1, eta 1.5, radiance; a conductor, eta 1 / 1.5, importance. The
 * weight of reflection sampling (a sampler that does not transmit) is <= 1 (eq 52; 1e-12 for rounding). */
static void check_samplers(const ggx_shape *s, ggx_vec3 v, double u1, double u2, double u3, int rejection_too,
                           const char *what)
{
    int bad_v = !(v.z > 0);
    char name[160];
    ggx_fresnel fresnels[2];
    ggx_fresnel_one(&fresnels[0]);
    ggx_fresnel_conductor(&fresnels[1], 0.2, 3.9);
    const double etas[2] = {1.5, 1 / 1.5};
    const ggx_transport modes[2] = {GGX_RADIANCE, GGX_IMPORTANCE};
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
        snprintf(name, sizeof name, "%s %s", what, e->name);
        if (e->family == GGX_FAMILY_DIRECTION) {
            for (int k = 0; k < 2; k++) {
                ggx_sample x = e->sample_direction(s, &fresnels[k], etas[k], v, u1, u2, u3, modes[k]);
                check_dir_sample(x, name, v);
                if (!(isfinite(u1) && isfinite(u2) && isfinite(u3))) {
                    ggx_sample c = e->sample_direction(s, &fresnels[k], etas[k], v, clamp_u(u1), clamp_u(u2),
                                                       clamp_u(u3), modes[k]);
                    CHECK(same_vec(x.w, c.w) && x.pdf == c.pdf && x.weight == c.weight && x.event == c.event,
                          "%s: u (%g, %g, %g) gave another sample than the clamped u, setting %d", name, u1, u2, u3, k);
                }
                if (!transmits[id])
                    CHECK(x.weight <= 1 + 1e-12, "%s: weight %.17g > 1 (eq 52), setting %d, v (%.17g,%.17g,%.17g)",
                          name, x.weight, k, v.x, v.y, v.z);
            }
            continue;
        }
        if (e->domain == GGX_DOMAIN_UNSKEWED && s->kind == GGX_SHAPE_SKEWED) continue;
        int ndf = e->family == GGX_FAMILY_NDF, rejection = e->family == GGX_FAMILY_REJECTION;
        if (rejection && !rejection_too) continue;
        ggx_vec3 m;
        if (rejection) {
            ustream st = {{u1, u2, u3}, 0, {(uint64_t)id}};
            unsigned trials;
            m = e->sample_reject(s, v, ustream_next, &st, &trials);
        } else {
            m = e->sample(s, v, u1, u2);
            /* ggx.h: a NaN u is read as 0 and u outside [0, 1] is clamped, so the sample is that of the clamped u */
            if (!(isfinite(u1) && isfinite(u2))) {
                ggx_vec3 c = e->sample(s, v, clamp_u(u1), clamp_u(u2));
                CHECK(same_vec(m, c), "%s: u (%g, %g) gave (%.17g,%.17g,%.17g), clamped u (%.17g,%.17g,%.17g)", name,
                      u1, u2, m.x, m.y, m.z, c.x, c.y, c.z);
            }
        }
        /* The zero vector is allowed where the visible part of the truncated ellipsoid is a sliver below 1e-9 of
         * its silhouette (ggx.h), which only an ill-conditioned A gives. */
        int zero = m.x == 0 && m.y == 0 && m.z == 0, sliver = 0;
        if (zero && !ndf && !bad_v) sliver = ggx_lune_area(s, v, t_vec(0, 0, 1)) < 1e-9 * ggx_projected_area(s, v);
        check_normal(m, e->pdf(s, v, m), !ndf && bad_v, rejection || sliver, name, v, u1, u2);
    }
}

/* The hardest shapes: alpha at GGX_ALPHA_MIN and GGX_ALPHA_MAX (alone, and skewed), the ratio 1:1e7 (at alpha_min
 * the largest ratio that GGX_SINGULAR_TOL lets through, within a factor 10), skews to pi/2,
 * and (below, in adversarial) matrices c A' scaled towards both ends of GGX_MATRIX_SCALE_MAX. */
static const shape_params EXTREMES[] = {
    {GGX_ALPHA_MIN, GGX_ALPHA_MIN, 0, 0, 0},
    {10, 10, 0, 0, 0},
    {1e-4, 0.1, 0, 0, 0.3},
    {10, 0.01, 0, 0, 1.0},
    {0.3, 0.6, 1.5707963267948966, -1.5707963267948966, 0.2},
    {1e-4, 1e-4, 1.2, -0.7, 0.0},
    {10, 10, 0.6, 0.6, 2.0},
    {0.5, 0.5, 0, 0, 0},
    {GGX_ALPHA_MAX, GGX_ALPHA_MAX, 0, 0, 0},
    {GGX_ALPHA_MIN, 1e3, 0, 0, 0.3},
    {GGX_ALPHA_MAX, 1.0, 1.2, -0.7, 0.4},
};
static const double SCALES[] = {1e-49, 1e-30, 1e30, 4e49}; /* ||c A'||_F stays inside [1e-50, 1e50] */
enum { NEXTREMES = sizeof EXTREMES / sizeof EXTREMES[0], NSCALES = sizeof SCALES / sizeof SCALES[0] };

/* Shape k: EXTREMES[k], then SCALES[k - NEXTREMES] times the canonical matrix of a skewed shape (ggx_shape_matrix). */
static void extreme_shape(ggx_shape *s, unsigned k, char *what, size_t size)
{
    if (k < NEXTREMES) {
        make_shape(s, EXTREMES[k]);
        snprintf(what, size, "shape %u (%g, %g, %g, %g, %g)", k, EXTREMES[k].ax, EXTREMES[k].ay, EXTREMES[k].tx,
                 EXTREMES[k].ty, EXTREMES[k].tz);
        return;
    }
    ggx_shape base;
    make_shape(&base, (shape_params){0.3, 0.6, 0.4, -0.3, 0.5});
    double c = SCALES[k - NEXTREMES], A[3][3];
    for (int i = 0; i < 9; i++) A[i / 3][i % 3] = c * base.a[i / 3][i % 3];
    ggx_status st = ggx_shape_matrix(s, (const double(*)[3])A);
    CHECK(st == GGX_OK, "ggx_shape_matrix(%g A'): %s", c, ggx_status_str(st));
    snprintf(what, size, "shape %u (%g times ellipsoid (0.3, 0.6, 0.4, -0.3, 0.5))", k, c);
}

static void adversarial(void **state)
{
    (void)state;
    const double us[] = {0.0, 1e-300, 0.5, 1.0 - DBL_EPSILON / 2, 1.0, NAN, INFINITY, -INFINITY};
    enum { NU = sizeof us / sizeof us[0] };
    const double cz[] = {1.0, 1.0 - DBL_EPSILON / 2, 1e-8, 0.0, -1e-8, -1.0};
    ggx_vec3 views[16];
    int nv = 0;
    for (unsigned i = 0; i < sizeof cz / sizeof cz[0]; i++) {
        double sn = sqrt(fmax(0, 1 - cz[i] * cz[i]));
        views[nv++] = t_vec(sn * cos(0.4), sn * sin(0.4), cz[i]);
    }
    views[nv++] = t_vec(0, 0, 1);
    views[nv++] = t_vec(0, 0, -1);
    views[nv++] = t_vec(1, 0, 0);
    const ggx_vec3 ms[] = {t_vec(0, 0, 1),  t_vec(1, 0, 0),
                           t_vec(0, -1, 0), t_normalize(t_vec(0.3, 0.2, 0.9)),
                           t_vec(0, 0, -1), t_normalize(t_vec(1, 1, 1e-9))};
    long cases = 0;
    for (unsigned k = 0; k < NEXTREMES + NSCALES; k++) {
        ggx_shape s;
        char what[128];
        extreme_shape(&s, k, what, sizeof what);
        for (int i = 0; i < nv; i++) {
            for (unsigned j = 0; j < sizeof ms / sizeof ms[0]; j++) {
                check_evals(&s, views[i], ms[j], what);
                check_evals(&s, ms[j], views[i], what);
                cases += 2;
            }
            for (int a = 0; a < NU; a++)
                for (int b = 0; b < NU; b++) {
                    check_samplers(&s, views[i], us[a], us[b], us[(a + b) % NU], a == b, what);
                    cases++;
                }
        }
    }
    printf("adversarial: %ld cases, %ld contract checks\n", cases, n_checked);
}

/* Random inputs: shapes over the whole documented domain (alpha from GGX_ALPHA_MIN to 10, ratios to 1:1000, skews
 * to pi/2), directions uniform on the sphere with a share of grazing ones, u uniform. 10^7 evaluations of each
 * function and 10^7 samples of each sampler at scale 1. */
static shape_params wide_shape(rng *r)
{
    shape_params p;
    p.ax = exp(rng_range(r, log(GGX_ALPHA_MIN), log(10.0)));
    p.ay = fmin(10.0, fmax(GGX_ALPHA_MIN, p.ax * exp(rng_range(r, log(1e-3), log(1e3)))));
    double skew = rng_uniform(r) < 0.3 ? 0.0 : 1.5707963267948966;
    p.tx = rng_range(r, -skew, skew);
    p.ty = rng_range(r, -skew, skew);
    p.tz = rng_range(r, -GGX_PI, GGX_PI);
    return p;
}
static ggx_vec3 any_dir(rng *r)
{
    double c = rng_uniform(r) < 0.1 ? (rng_uniform(r) - 0.5) * 1e-6 : rng_range(r, -1, 1);
    double sn = sqrt(fmax(0, 1 - c * c)), ph = rng_range(r, 0, 2 * GGX_PI);
    return t_vec(sn * cos(ph), sn * sin(ph), c);
}

/* Rejection samplers take up to 10^5 trials where the visible part is a small fraction of their bound (alpha
 * 1e-4 with a ratio 1:1000, grazing views): they run on every REJECTION_EVERY-th random sample (10^4 at scale 1)
 * and on the diagonal u1 = u2 of the adversarial table, to keep the program's time. */
enum { REJECTION_EVERY = 1000 };

static void properties(void **state)
{
    (void)state;
    rng r = {91};
    long n_eval = (long)(1e7 * test_scale()), n_samp = (long)(1e7 * test_scale());
    n_checked = 0;
    ggx_shape s;
    for (long i = 0; i < n_eval; i++) {
        if (i % 64 == 0) make_shape(&s, wide_shape(&r));
        ggx_vec3 v = any_dir(&r), m = any_dir(&r);
        check_evals(&s, v, m, "random");
        /* reciprocity (BRDF exact up to rounding; BSDF generalised) */
        ggx_fresnel one = {GGX_FRESNEL_ONE, 0, 0, 0};
        double a = ggx_brdf_eval(&s, &one, v, m), b = ggx_brdf_eval(&s, &one, m, v);
        CHECK(fabs(a - b) <= 1e-10 * fmax(a, b), "BRDF reciprocity %.17g %.17g", a, b);
    }
    long evals = n_checked;
    n_checked = 0;
    for (long i = 0; i < n_samp; i++) {
        if (i % 16 == 0) make_shape(&s, wide_shape(&r));
        ggx_vec3 v = any_dir(&r);
        check_samplers(&s, v, rng_uniform(&r), rng_uniform(&r), rng_uniform(&r), i % REJECTION_EVERY == 0, "random");
    }
    printf("properties: %ld evaluations and %ld samples checked (GGX_TEST_SCALE %g)\n", evals, n_checked, test_scale());
}


/* The premise of the float caps proof (lune.inc, above k_lune_core_span), from the computed lune point p and the
 * float shape's entries in double: p.z^2 >= K ||A||_F L with K = 2.02 (66 u + 4.08 (margin + u)), u = 2^-24, L =
 * ||A v||. The sampler tests the cheaper p.z >= T L and p.z^2 >= C ||A||_F^2 (traits), whose product implies it
 * where T sqrt(C) >= K (2^-14 against 1.63e-5). The outcome check below cannot see a weakened test: the bound is a
 * worst case that real roundings stay far from. Here a test of the wrong constant, or of a wrong ||A||_F^2
 * (ggx_shapef's a_frob2), claims inputs whose premise fails: with p.z = c T L, c in [1, 1.5], the sampler claims
 * the proof for ||A||_F / L <= 4 c, the a_frob2 / 64 mutant (or a C 64 times too small) up to 32 c, and the premise
 * fails above 15 c^2, so such a mutant fails for ratios between 15 and 48. near counts the proved inputs within that
 * factor 1.5 of T L, and band the inputs placed there whose ratio is in [23, 32] (where such a mutant claims the
 * proof and the premise fails for c below 1.24 to 1.46, a good share of [1, 1.5]), which caps_proof requires to be
 * many, so that the placement cannot silently stop working. */
static long premise_checked, near, band;
/* ||A||_F^2 and ||A v||^2 of the float shape, in double. */
static void frob_len_f(const ggx_shapef *sf, ggx_vec3f v, double *f2, double *l2)
{
    *f2 = 0, *l2 = 0;
    for (int i = 0; i < 3; i++) {
        double ai = 0;
        for (int j = 0; j < 3; j++) {
            *f2 += (double)sf->a[i][j] * sf->a[i][j];
            ai += (double)sf->a[i][j] * (j == 0 ? v.x : j == 1 ? v.y : v.z);
        }
        *l2 += ai * ai;
    }
}
static void proof_premise_f(const ggx_shapef *sf, ggx_vec3f v, float u1, float u2, const char *what)
{
    ggx_vec3f av = ggx_k_amul_f(sf, v), sv;
    float k;
    ggx_vec3f p = ggx_k_lune_point_scaled_f(GGX_K_MAP_CAPS, av, ggx_k_len_f(av), u1, u2, 1 - u2, 1, &k, &sv);
    double f2, l2;
    frob_len_f(sf, v, &f2, &l2);
    double u = ldexp(1.0, -24), margin = ldexp(1.0, -20), K = 2.02 * (66 * u + 4.08 * (margin + u));
    double lhs = (double)p.z * p.z, rhs = K * sqrt(f2) * sqrt(l2);
    CHECK(lhs >= rhs,
          "float proof claimed without its premise: %s, v (%.9g, %.9g, %.9g), u (%.9g, %.9g): p.z^2 %.4g < "
          "K ||A||_F L %.4g",
          what, v.x, v.y, v.z, u1, u2, lhs, rhs);
    near += p.z < 1.5 * ldexp(1.0, -6) * sqrt(l2);
    premise_checked++;
}

/* The scalar float caps sampler returns m without the ellipsoid-space check where a bound proves that the check
 * would pass (k_lune_core_span, *proved; the double sampler has no proof: GGX_CAPS_PROOF). Over the extreme shapes
 * (alpha 1e-4 with skews to pi/2, ratio 1:1e7, scaled matrices) and random ones, views of length 1/2 to 2 including
 * grazing ones, and u2 up to 1 - 2^-52: wherever the proof holds the check holds too and the sampler returns that
 * very m; and the proof's premise holds (proof_premise_f), with u2 placed where p.z is near the proof's T ||A v||,
 * half of those with views swept towards A's most contracted direction, where the C term acts. The proof must also
 * cover most inputs, or it would be vacuous; the double fast path must never claim it. */
static void caps_proof(void **state)
{
    (void)state;
    rng r = {77};
    long n = (long)(2e6 * test_scale()), proved_f = 0, ok_f = 0, total = 0;
    ggx_shape s;
    ggx_shapef sf;
    char what[160];
    for (long i = 0; i < n; i++) {
        if (i % 64 == 0) {
            unsigned k = (unsigned)(i / 64) % (2 * (NEXTREMES + NSCALES));
            if (k < NEXTREMES + NSCALES) extreme_shape(&s, k, what, sizeof what);
            else make_shape(&s, wide_shape(&r)), snprintf(what, sizeof what, "random shape");
            ggx_shapef_from(&sf, &s);
        }
        ggx_vec3 v = random_view(&r);
        double len = (i % 3 == 0) ? 0.5 : (i % 3 == 1 ? 1.0 : 1.999);
        v = t_vec(v.x * len, v.y * len, v.z * len);
        double u1 = rng_uniform(&r), u2 = rng_uniform(&r);
        if (i % 4 == 0) u2 = 1 - ldexp(1.0, -(int)(1 + i / 4 % 52)); /* towards the rim */
        if (i % 4 == 3) { /* views near A's most contracted direction, where ||A||_F / ||A v|| is largest and the C
                           * term of the proof acts: power iteration with A^-1 A^-T, then a random share 10^-8 to 1
                           * of the random view, which sweeps the ratio */
            ggx_vec3 r0 = v;
            for (int it = 0; it < 30; it++) {
                ggx_vec3 w = ggx_k_binvmul_d(&s, v); /* A'^-T v; then A'^-1 w, the transpose's product */
                double(*b)[3] = s.ainv_t;
                v = ggx_k_normalize_d(t_vec(b[0][0] * w.x + b[1][0] * w.y + b[2][0] * w.z,
                                            b[0][1] * w.x + b[1][1] * w.y + b[2][1] * w.z,
                                            b[0][2] * w.x + b[1][2] * w.y + b[2][2] * w.z));
            }
            if (v.z < 0) v = ggx_k_neg_d(v);
            double t = pow(10.0, -8 * rng_uniform(&r));
            v = ggx_k_scale_d(ggx_k_normalize_d(ggx_k_add_d(v, ggx_k_scale_d(r0, t))), len);
        }
        if (i % 4 == 1 || i % 4 == 3) { /* p.z within a factor 1.5 of the proof's T L */
            ggx_vec3f vf = {(float)v.x, (float)v.y, (float)v.z}, av = ggx_k_amul_f(&sf, vf);
            double vsz = av.z / (double)ggx_k_len_f(av);
            u2 = 1 - ldexp(1.0, -6) * (1 + 0.5 * u2) / (1 + vsz); /* 2^-6: GGX_PROOF_T in float */
        }
        if (i % 4 == 3) {
            ggx_vec3f vf = {(float)v.x, (float)v.y, (float)v.z};
            double f2, l2;
            frob_len_f(&sf, vf, &f2, &l2);
            band += f2 >= 23.0 * 23.0 * l2 && f2 <= 32.0 * 32.0 * l2;
        }
        int ok, pr;
        ggx_k_lune_core_p_d(&s, v, u1, u2, GGX_K_MAP_CAPS, &ok, &pr);
        CHECK(!pr, "the double sampler claimed a proof: %s", what);
        ggx_vec3f vf = {(float)v.x, (float)v.y, (float)v.z};
        float f1 = (float)u1, f2 = (float)u2;
        ggx_vec3f mf = ggx_k_lune_core_p_f(&sf, vf, f1, f2, GGX_K_MAP_CAPS, &ok, &pr);
        if (pr) {
            ggx_vec3f wf = ggx_sample_vndf_caps_f(&sf, vf, f1, f2);
            double mv = ((double)mf.x * vf.x + (double)mf.y * vf.y + (double)mf.z * vf.z) /
                        sqrt((double)vf.x * vf.x + (double)vf.y * vf.y + (double)vf.z * vf.z);
            CHECK(ok && mf.x == wf.x && mf.y == wf.y && mf.z == wf.z && mv > 0 && mf.z >= 0,
                  "float proof without the check: %s, v (%.9g, %.9g, %.9g), u (%.9g, %.9g): ok %d, m.v %.3g", what,
                  vf.x, vf.y, vf.z, f1, f2, ok, mv);
            proof_premise_f(&sf, vf, f1, f2, what);
        }
        proved_f += pr, ok_f += ok;
        total++;
    }
    printf("caps proof: %ld inputs; float proved %ld of %ld checked good; premise checked %ld times, %ld within 1.5 "
           "T ||A v||; %ld placed with ||A||_F / ||A v|| in [23, 32]\n",
           total, proved_f, ok_f, premise_checked, near, band);
    CHECK(100 * near > total && 1000 * band > total, "too few proved inputs near the proof's bound");
    CHECK(10 * proved_f > 5 * ok_f, "the proof covers too few inputs");
}

/* The inputs the fuzzers found, each once a contract violation (see tests/fuzz/), kept as regressions; those found
 * on one sampler of normals are run on every sampler of the registry (check_samplers). */
static void fuzz_regressions(void **state)
{
    (void)state;
    ggx_shape s;
    /* 1. A view a denormal above the horizon: eq 33 computed via 1/v.z overflowed to pdf 0. */
    make_shape(&s, (shape_params){0.3, 0.6, 0.4, -0.3, 0.5});
    ggx_vec3 v = t_vec(1.0, 3.4e-317, 3.4e-317);
    check_samplers(&s, v, 0.0, 0.796875, 0.5, 1, "denormal view");
    /* 2. eta = 3.8e-311: eta^2 underflowed and Fresnel became 0/0. */
    double F = ggx_fresnel_dielectric_eval(-5.5e303, 3.80261645741e-311);
    CHECK(isfinite(F) && F >= 0 && F <= 1, "Fresnel with a denormal eta: %g", F);
    /* 3. A huge, non-unit view: the direction samplers reflected the raw vector. */
    make_shape(&s, (shape_params){0.3, 0.6, 0.4, 0.0, 0.0});
    check_dir_sample(ggx_sample_bsdf(&s, 0.5, t_vec(-2.68e154, 3.06e-57, -2.35e-185), 0.3, 0.4, 0.5, GGX_RADIANCE),
                     "huge view", v);
    /* 4. A grazing view whose sphere-space z rounds to 0 was taken for "no view". */
    make_shape(&s, (shape_params){GGX_ALPHA_MIN, 10, 0, 0, 0});
    v = t_normalize(t_vec(-0.30018382352934053, 0.5, 5e-324));
    check_samplers(&s, v, 1.5e-47, 0.0, 0.5, 1, "sphere-space z = 0");
    /* 5. alpha 1e-4 with a skew: rounding in A^T p flipped the sign of m.v. */
    make_shape(&s, (shape_params){6.98e-11, 0.6, 0.4, -0.30018310546875, 0.0});
    v = t_normalize(t_vec(-1.1248561337499643e+60 / 1e60, 0.0, 0.15 / 1e60));
    check_samplers(&s, v, 0.3, 1.0, 0.5, 1, "ill-conditioned skew");
    /* 6. Refraction out of eta = 3584: the refracted vector missed unit length by more than 1e-12. */
    make_shape(&s, (shape_params){GGX_ALPHA_MIN, GGX_ALPHA_MIN, 0, 0, 0});
    for (int i = 0; i < 1000; i++) {
        ggx_sample x = ggx_sample_bsdf(&s, 3584.0, t_vec(0, 1e-9, -1), i / 1000.0, 0.5, 0.99, GGX_RADIANCE);
        check_dir_sample(x, "eta 3584", v);
    }
    /* 7. A near-rank-2 matrix viewed 2e-97 above the horizon: the visible lune is ~4e-10 rad wide; the sampler
     * returns the zero vector, which the contract allows only where A_l(v, n) < 1e-9 A_e(v). */
    const double c = -1.3476555094338099e+28;
    const double A[3][3] = {{-1.3476555065836185e+28, c, c}, {c, -4.152681998449859e+28, c}, {c, c, c}};
    CHECK(ggx_shape_matrix(&s, A) == GGX_OK, "matrix");
    v = t_vec(-1.0, 0.0859375 / 4.27211095142165e+96, 0.99609375 / 4.27211095142165e+96);
    check_samplers(&s, v, 0.99609375, 0.99609375, 0.5, 1, "near-rank-2");
    /* 8. An unskewed matrix with a nearly singular tangent block: the small eigenvalue came out as sqrt(< 0). */
    const double B[3][3] = {{-5.872759415309048e-21, -5.872761767629815e-21, 1.39855083927075e-310},
                            {-5.8727593981205925e-21, -5.872761767629815e-21, 3.2544e-320},
                            {3.983693430645e-312, 0.0, -5.872759398102019e-21}};
    CHECK(ggx_shape_matrix(&s, B) == GGX_OK && s.kind != GGX_SHAPE_SKEWED, "near-singular tangent block");
    CHECK(isfinite(s.alpha_x) && isfinite(s.alpha_y) && s.alpha_y >= 0, "alphas %g %g", s.alpha_x, s.alpha_y);
    check_samplers(&s, t_vec(0, 0, 1), 3.9e-305, 0.99609375, 0.5, 1, "near-singular tangent block");
    /* 9. A small matrix (1e-49 A') with a short view (length 1e-70, its square still in the fast path's range): the
     * caps' mu = A^T p ~ 1e-168 had a squared length that underflowed to 0, and the sampler returned infinities
     * (found by the Python package's hostile test). Every sampler of normals gives the unit view's normal, for views
     * of any length, on the extreme shapes and on matrices scaled to both ends, also for u near the rim, where the
     * fast path's facing check decides (its products underflow for short views). (Views much nearer grazing are
     * ill-conditioned: the slow path's normalisation of the view, 1e-16, moves the crescent's normal by 4e-9 at a
     * view 1e-12 above the horizon of alpha 1e4.) */
    const double lengths[] = {1e-150, 1e-100, 1e-70, 1e-62, 1e-30, 1e30, 1e70, 1e100, 1e150};
    const double u2s[] = {0.7, 1 - 0x1p-20, 1 - 0x1p-34, 1 - 0x1p-53};
    const ggx_vec3 views[] = {t_normalize(t_vec(0.3, -0.2, 0.8)), t_normalize(t_vec(-0.6, 0.8, 0.05))};
    for (unsigned k = 0; k < NEXTREMES + NSCALES; k++) {
        char what[160];
        extreme_shape(&s, k, what, sizeof what);
        for (unsigned q = 0; q < sizeof views / sizeof views[0]; q++) {
            const ggx_vec3 unit = views[q];
            check_samplers(&s, unit, 0.3, 0.7, 0.5, 0, what);
            for (unsigned j = 0; j < sizeof lengths / sizeof lengths[0]; j++) {
                ggx_vec3 w = t_vec(unit.x * lengths[j], unit.y * lengths[j], unit.z * lengths[j]);
                for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
                    const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
                    if (!e->sample || e->family != GGX_FAMILY_VNDF) continue;
                    for (unsigned i = 0; i < sizeof u2s / sizeof u2s[0]; i++) {
                        ggx_vec3 a = e->sample(&s, w, 0.3, u2s[i]), b = e->sample(&s, unit, 0.3, u2s[i]);
                        double d = fmax(fabs(a.x - b.x), fmax(fabs(a.y - b.y), fabs(a.z - b.z)));
                        CHECK(d <= 1e-12,
                              "%s, %s, view (%g, %g, %g) of length %g, u2 1 - %g: (%g, %g, %g) against "
                              "the unit view's (%g, %g, %g), d %g",
                              what, e->name, unit.x, unit.y, unit.z, lengths[j], 1 - u2s[i], a.x, a.y, a.z, b.x, b.y,
                              b.z, d);
                    }
                }
            }
        }
    }
    /* 10. The same shapes scaled: every direction sampler of reflection gives the same direction and pdf for A' and
     * c A' (the distribution does not depend on the scale), also at the rim. With c a power of two every operation
     * of either path scales exactly, so the directions must agree to the last bit; a sample that takes the fast path
     * at one scale and the slow one at the other differs by 1e-16 to 1e-12. The pdfs agree to 1e-9 (the shape setup
     * of c A' is not exactly scaled: 1.5e-12 for alpha 1e4 skewed by 1.2 rad). The bounded samplers' fraction in
     * double (k_bound_frac) once had a denominator of the order of c^5, which sent scaled shapes to the slow path and
     * its cap height from u2 kappa (the direction moved by 3e-4 at u2 = 1 - 2^-51), and then a floor on bar rather
     * than mu.mu did so for c below 1e-12 (and for alpha 1e-4 near grazing at any scale: 1.2e-12). */
    const double cs[] = {0x1p-160, 0x1p-66, 0x1p66, 0x1p160};
    const double u2r[] = {0.7, 1 - 0x1p-20, 1 - 0x1p-40, 1 - 0x1p-51};
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    for (unsigned k = 0; k < NEXTREMES; k++) {
        char what[160];
        extreme_shape(&s, k, what, sizeof what);
        for (unsigned j = 0; j < sizeof cs / sizeof cs[0]; j++) {
            double M[3][3];
            ggx_shape sc;
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) M[a][b] = s.a[a][b] * cs[j];
            if (ggx_shape_matrix(&sc, (const double(*)[3])M) != GGX_OK) continue;
            const ggx_vec3 dirs[] = {t_vec(0, 0, 1), t_normalize(t_vec(0.3, -0.2, 0.8)),
                                     t_normalize(t_vec(-0.6, 0.8, 0.1))};
            for (unsigned q = 0; q < sizeof dirs / sizeof dirs[0]; q++)
                for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
                    const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
                    if (e->family != GGX_FAMILY_DIRECTION || transmits[id]) continue;
                    for (unsigned i = 0; i < sizeof u2r / sizeof u2r[0]; i++) {
                        ggx_sample a = e->sample_direction(&sc, &one, 1.5, dirs[q], 0.3, u2r[i], 0.5, GGX_RADIANCE);
                        ggx_sample b = e->sample_direction(&s, &one, 1.5, dirs[q], 0.3, u2r[i], 0.5, GGX_RADIANCE);
                        double d = fmax(fabs(a.w.x - b.w.x), fmax(fabs(a.w.y - b.w.y), fabs(a.w.z - b.w.z)));
                        double dp = b.pdf > 0 ? fabs(a.pdf - b.pdf) / b.pdf : fabs(a.pdf);
                        CHECK(a.event == b.event && d == 0 && dp <= 1e-9,
                              "%s times %g, %s, view %u, u2 1 - %g: (%g, "
                              "%g, %g) pdf %g against (%g, %g, %g) pdf %g: d %g, pdf %g relative",
                              what, cs[j], e->name, q, 1 - u2r[i], a.w.x, a.w.y, a.w.z, a.pdf, b.w.x, b.w.y, b.w.z,
                              b.pdf, d, dp);
                    }
                }
        }
    }
}

int main(void)
{
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
        transmits[id] = e->family == GGX_FAMILY_DIRECTION && sampler_transmits(e);
    }
    const struct CMUnitTest tests[] = {cmocka_unit_test(adversarial), cmocka_unit_test(properties),
                                       cmocka_unit_test(fuzz_regressions), cmocka_unit_test(caps_proof)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
