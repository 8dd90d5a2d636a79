/* The numerical contract of include/ggx/ggx.h, proven by an adversarial table and by property tests over random
 * inputs: evaluations finite and >= 0 (Lambda: finite), samplers a unit vector with a finite pdf > 0 or the zero
 * vector (pdf 0), direction samples valid or marked invalid with pdf 0, the weight bound, reciprocity.
 * GGX_TEST_SCALE (default 1) scales the random counts (the sanitizer build uses 0.1). SPDX-License-Identifier: MIT */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "testlib.h"

typedef ggx_vec3 (*vndf_fn)(const ggx_shape *, ggx_vec3, double, double);
typedef ggx_vec3 (*ndf_fn)(const ggx_shape *, double, double);
static const struct {
    const char *name;
    vndf_fn f;
} VNDF[] = {{"caps", ggx_sample_vndf_caps},       {"crescent", ggx_sample_vndf_crescent},
            {"crescent-polar", ggx_sample_vndf_crescent_polar}, {"heitz", ggx_sample_vndf_heitz},
            {"default", ggx_sample_vndf}};
static const struct {
    const char *name;
    ndf_fn f;
} NDF[] = {{"stretch", ggx_sample_ndf_stretch}, {"ellipse", ggx_sample_ndf_ellipse},
           {"inversion", ggx_sample_ndf_inversion}, {"visible", ggx_sample_ndf_visible}};

static long n_checked;

/* The contract for one shape and one (v, m) pair: every evaluation. */
static void check_evals(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m, const char *what)
{
    ggx_fresnel f;
    ggx_fresnel_conductor(&f, 0.2, 3.9);
    double r[] = {ggx_ndf(s, m),           ggx_gaussian_curvature(s, m), ggx_projected_area(s, v),
                  ggx_lune_area(s, v, m),  ggx_g1(s, v, m),              ggx_g1_smith(s, v),
                  ggx_g2(s, v, m, m),      ggx_g2_height_correlated(s, v, m, m),
                  ggx_pdf_vndf(s, v, m),   ggx_pdf_ndf(s, m),           ggx_brdf_eval(s, &f, v, m),
                  ggx_pdf_brdf(s, v, m),   ggx_bsdf_eval(s, 1.5, v, m, GGX_RADIANCE),
                  ggx_bsdf_eval(s, 1 / 1.5, m, v, GGX_IMPORTANCE), ggx_pdf_bsdf(s, 1.5, v, m),
                  ggx_p22(s, m.x, m.y),    ggx_ndf_spherical(s, acos(fmin(1, fabs(m.z))), atan2(m.y, m.x))};
    for (unsigned i = 0; i < sizeof r / sizeof r[0]; i++)
        CHECK(isfinite(r[i]) && r[i] >= 0, "%s: function %u = %g for v (%.17g,%.17g,%.17g) m (%.17g,%.17g,%.17g)", what, i,
              r[i], v.x, v.y, v.z, m.x, m.y, m.z);
    CHECK(isfinite(ggx_lambda(s, v)), "%s: Lambda", what);
    CHECK(ggx_g1(s, v, m) <= 1.0, "%s: G1 > 1", what);
    n_checked += 18;
}

/* A sampler's output: the zero vector (invalid), or a unit vector with a finite pdf > 0. */
static void check_normal(ggx_vec3 m, double pdf, int must_be_invalid, const char *what, ggx_vec3 v, double u1, double u2)
{
    n_checked++;
    int zero = m.x == 0 && m.y == 0 && m.z == 0;
    if (must_be_invalid) {
        CHECK(zero, "%s: v (%.17g,%.17g,%.17g) outside the domain gave (%g,%g,%g)", what, v.x, v.y, v.z, m.x, m.y, m.z);
        return;
    }
    CHECK(!zero, "%s: no sample for v (%.17g,%.17g,%.17g) u (%.17g, %.17g)", what, v.x, v.y, v.z, u1, u2);
    CHECK(fabs(sqrt(t_dot(m, m)) - 1) <= 1e-12 && m.z >= 0, "%s: m (%.17g,%.17g,%.17g) not a unit upper normal, u (%.17g, %.17g)",
          what, m.x, m.y, m.z, u1, u2);
    CHECK(isfinite(pdf) && pdf > 0, "%s: pdf %g at m (%.17g,%.17g,%.17g), v (%.17g,%.17g,%.17g), u (%.17g, %.17g)", what, pdf, m.x,
          m.y, m.z, v.x, v.y, v.z, u1, u2);
}

static void check_dir_sample(ggx_sample x, const char *what, ggx_vec3 v)
{
    n_checked++;
    if (x.event == GGX_EVENT_INVALID) {
        CHECK(x.pdf == 0 && x.weight == 0 && x.w.x == 0 && x.w.y == 0 && x.w.z == 0, "%s: invalid sample not zeroed", what);
        return;
    }
    CHECK(fabs(sqrt(t_dot(x.w, x.w)) - 1) <= 1e-12, "%s: |w| - 1 = %g", what, sqrt(t_dot(x.w, x.w)) - 1);
    CHECK(isfinite(x.pdf) && x.pdf > 0 && isfinite(x.weight) && x.weight >= 0, "%s: pdf %g weight %g for v (%.17g,%.17g,%.17g)",
          what, x.pdf, x.weight, v.x, v.y, v.z);
}

static void check_samplers(const ggx_shape *s, ggx_vec3 v, double u1, double u2, double u3, const char *what)
{
    int bad_v = !(v.z > 0);
    char name[160];
    for (unsigned k = 0; k < sizeof VNDF / sizeof VNDF[0]; k++) {
        ggx_vec3 m = VNDF[k].f(s, v, u1, u2);
        snprintf(name, sizeof name, "%s %s", what, VNDF[k].name);
        check_normal(m, ggx_pdf_vndf(s, v, m), bad_v, name, v, u1, u2);
    }
    for (unsigned k = 0; k < sizeof NDF / sizeof NDF[0]; k++) {
        if (NDF[k].f == ggx_sample_ndf_inversion && s->kind == GGX_SHAPE_SKEWED) continue;
        ggx_vec3 m = NDF[k].f(s, u1, u2);
        snprintf(name, sizeof name, "%s %s", what, NDF[k].name);
        check_normal(m, ggx_pdf_ndf(s, m), 0, name, v, u1, u2);
    }
    ggx_fresnel one = {GGX_FRESNEL_ONE, 0, 0, 0};
    ggx_sample b = ggx_sample_brdf(s, &one, v, u1, u2);
    check_dir_sample(b, "brdf", v);
    if (b.event != GGX_EVENT_INVALID) CHECK(b.weight <= 1 + 1e-12, "%s: brdf weight %.17g > 1 (eq 52)", what, b.weight);
    check_dir_sample(ggx_sample_bsdf(s, 1.5, v, u1, u2, u3, GGX_RADIANCE), "bsdf 1.5", v);
    check_dir_sample(ggx_sample_bsdf(s, 1 / 1.5, v, u1, u2, u3, GGX_IMPORTANCE), "bsdf 1/1.5", v);
}

static const shape_params EXTREMES[] = {
    {GGX_ALPHA_MIN, GGX_ALPHA_MIN, 0, 0, 0}, {10, 10, 0, 0, 0},          {1e-4, 0.1, 0, 0, 0.3},
    {10, 0.01, 0, 0, 1.0},                   {0.3, 0.6, 1.5707963267948966, -1.5707963267948966, 0.2},
    {1e-4, 1e-4, 1.2, -0.7, 0.0},            {10, 10, 0.6, 0.6, 2.0},    {0.5, 0.5, 0, 0, 0},
};

static void adversarial(void **state)
{
    (void)state;
    const double us[] = {0.0, 1e-300, 0.5, 1.0 - DBL_EPSILON / 2, 1.0};
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
    const ggx_vec3 ms[] = {t_vec(0, 0, 1), t_vec(1, 0, 0), t_vec(0, -1, 0), t_normalize(t_vec(0.3, 0.2, 0.9)),
                           t_vec(0, 0, -1), t_normalize(t_vec(1, 1, 1e-9))};
    long cases = 0;
    for (unsigned k = 0; k < sizeof EXTREMES / sizeof EXTREMES[0]; k++) {
        ggx_shape s;
        make_shape(&s, EXTREMES[k]);
        char what[64];
        snprintf(what, sizeof what, "shape %u", k);
        for (int i = 0; i < nv; i++) {
            for (unsigned j = 0; j < sizeof ms / sizeof ms[0]; j++) {
                check_evals(&s, views[i], ms[j], what);
                check_evals(&s, ms[j], views[i], what);
                cases += 2;
            }
            for (int a = 0; a < 5; a++)
                for (int b = 0; b < 5; b++) {
                    check_samplers(&s, views[i], us[a], us[b], us[(a + b) % 5], what);
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
    p.tz = rng_range(r, -T_PI, T_PI);
    return p;
}
static ggx_vec3 any_dir(rng *r)
{
    double c = rng_uniform(r) < 0.1 ? (rng_uniform(r) - 0.5) * 1e-6 : rng_range(r, -1, 1);
    double sn = sqrt(fmax(0, 1 - c * c)), ph = rng_range(r, 0, 2 * T_PI);
    return t_vec(sn * cos(ph), sn * sin(ph), c);
}

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
        check_samplers(&s, v, rng_uniform(&r), rng_uniform(&r), rng_uniform(&r), "random");
    }
    printf("properties: %ld evaluations and %ld samples checked (GGX_TEST_SCALE %g)\n", evals, n_checked, test_scale());
}


/* The inputs the fuzzers found, each once a contract violation (see tests/fuzz/), kept as regressions. */
static void fuzz_regressions(void **state)
{
    (void)state;
    ggx_shape s;
    /* 1. A view a denormal above the horizon: eq 33 computed via 1/v.z overflowed to pdf 0. */
    make_shape(&s, (shape_params){0.3, 0.6, 0.4, -0.3, 0.5});
    ggx_vec3 v = t_vec(1.0, 3.4e-317, 3.4e-317);
    ggx_vec3 m = ggx_sample_vndf_caps(&s, v, 0.0, 0.796875);
    check_normal(m, ggx_pdf_vndf(&s, v, m), 0, "denormal view", v, 0, 0.796875);
    /* 2. eta = 3.8e-311: eta^2 underflowed and Fresnel became 0/0. */
    double F = ggx_fresnel_dielectric_eval(-5.5e303, 3.80261645741e-311);
    CHECK(isfinite(F) && F >= 0 && F <= 1, "Fresnel with a denormal eta: %g", F);
    /* 3. A huge, non-unit view: the direction samplers reflected the raw vector. */
    make_shape(&s, (shape_params){0.3, 0.6, 0.4, 0.0, 0.0});
    check_dir_sample(ggx_sample_bsdf(&s, 0.5, t_vec(-2.68e154, 3.06e-57, -2.35e-185), 0.3, 0.4, 0.5, GGX_RADIANCE), "huge view", v);
    /* 4. A grazing view whose sphere-space z rounds to 0 was taken for "no view". */
    make_shape(&s, (shape_params){GGX_ALPHA_MIN, 10, 0, 0, 0});
    v = t_normalize(t_vec(-0.30018382352934053, 0.5, 5e-324));
    m = ggx_sample_vndf_caps(&s, v, 1.5e-47, 0.0);
    check_normal(m, ggx_pdf_vndf(&s, v, m), 0, "sphere-space z = 0", v, 0, 0);
    /* 5. alpha 1e-4 with a skew: rounding in A^T p flipped the sign of m.v. */
    make_shape(&s, (shape_params){6.98e-11, 0.6, 0.4, -0.30018310546875, 0.0});
    v = t_normalize(t_vec(-1.1248561337499643e+60 / 1e60, 0.0, 0.15 / 1e60));
    m = ggx_sample_vndf_caps(&s, v, 0.3, 1.0);
    check_normal(m, ggx_pdf_vndf(&s, v, m), 0, "ill-conditioned skew", v, 0.3, 1.0);
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
    m = ggx_sample_vndf_caps(&s, v, 0.99609375, 0.99609375);
    if (m.x == 0 && m.y == 0 && m.z == 0)
        CHECK(ggx_lune_area(&s, v, t_vec(0, 0, 1)) < 1e-9 * ggx_projected_area(&s, v), "zero vector outside the sliver case");
    else
        check_normal(m, ggx_pdf_vndf(&s, v, m), 0, "near-rank-2", v, 0.99609375, 0.99609375);
    /* 8. An unskewed matrix with a nearly singular tangent block: the small eigenvalue came out as sqrt(< 0). */
    const double B[3][3] = {{-5.872759415309048e-21, -5.872761767629815e-21, 1.39855083927075e-310},
                            {-5.8727593981205925e-21, -5.872761767629815e-21, 3.2544e-320},
                            {3.983693430645e-312, 0.0, -5.872759398102019e-21}};
    CHECK(ggx_shape_matrix(&s, B) == GGX_OK && s.kind != GGX_SHAPE_SKEWED, "near-singular tangent block");
    CHECK(isfinite(s.alpha_x) && isfinite(s.alpha_y) && s.alpha_y >= 0, "alphas %g %g", s.alpha_x, s.alpha_y);
    m = ggx_sample_ndf_inversion(&s, 3.9e-305, 0.99609375);
    check_normal(m, ggx_pdf_ndf(&s, m), 0, "inversion, near-singular tangent block", t_vec(0, 0, 1), 0, 0.99609375);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(adversarial), cmocka_unit_test(properties), cmocka_unit_test(fuzz_regressions)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
