/* The inline double kernels (ggx_inline.h, _d) against the exported double API that calls them (which may run an FMA
 * build of the same source): every sampler of normals of the registry, D, the VNDF pdf and the BRDF, on shapes
 * whose condition number kappa (alpha_x, alpha_y and 1 for ggx_shape_ellipsoid) runs from 1 to 1e8, u at the ends
 * of a float generator's range, views from n to grazing: within 1e-14 kappa^2, ggx_inline.h's bound (per
 * component of a normal, relative for values). The reported shape (1e3, 0.1, 1, 0.5, 0) with the ellipse at
 * u = (1 - 2^-24, 0.25) differs by 1.6e-9: kappa^2 = 1e8 allows 1e-6. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "ggx/ggx_inline.h"
#include "ggx/ggx_samplers.h"
#include "testlib.h"

#define BOUND 1e-14 /* times kappa^2 */

/* The registry's samplers of normals as inline _d calls, generated from the one list. */
#define CALL_NDF(stem) ((void)v, ggx_##stem##_d(s, a, b))
#define CALL_VNDF(stem) ggx_##stem##_d(s, v, a, b)
#define CALL_REJECTION(stem) ((void)s, (void)v, (void)a, (void)b, t_vec(0, 0, 0))
#define CALL_DIRECTION(stem) ((void)s, (void)v, (void)a, (void)b, t_vec(0, 0, 0))
#define X(ID, name, stem, fam, dom, batch, inv, help)                                                                  \
    static ggx_vec3 inline_##stem(const ggx_shape *s, ggx_vec3 v, double a, double b) { return CALL_##fam(stem); }
GGX_SAMPLER_LIST(X)
#undef X
typedef ggx_vec3 (*inline_fn)(const ggx_shape *, ggx_vec3, double, double);
static const inline_fn INLINE[] = {
#define X(ID, name, stem, fam, dom, batch, inv, help) inline_##stem,
    GGX_SAMPLER_LIST(X)
#undef X
};

static double worst_ratio; /* the largest difference / kappa^2 seen */

static void check_shape(const ggx_shape *s, double kappa, ggx_vec3 v, const char *what)
{
    const double us[] = {0.0, 0x1p-24, 0.25, 0.5, 0.75, 1.0 - 0x1p-24};
    const int nu = (int)(sizeof us / sizeof us[0]);
    double tol = BOUND * kappa * kappa;
    ggx_fresnel f;
    ggx_fresnel_conductor(&f, 0.2, 3.9);
    for (int i = 0; i < GGX_SAMPLER_COUNT; i++) {
        const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)i);
        if (e->family != GGX_FAMILY_NDF && e->family != GGX_FAMILY_VNDF) continue;
        if (e->domain == GGX_DOMAIN_UNSKEWED && s->kind == GGX_SHAPE_SKEWED) continue;
        for (int a = 0; a < nu; a++)
            for (int b = 0; b < nu; b++) {
                ggx_vec3 m1 = e->sample(s, v, us[a], us[b]), m2 = INLINE[i](s, v, us[a], us[b]);
                double d = fmax(fabs(m1.x - m2.x), fmax(fabs(m1.y - m2.y), fabs(m1.z - m2.z)));
                if (d / (kappa * kappa) > worst_ratio) worst_ratio = d / (kappa * kappa);
                CHECK(d <= tol, "%s, %s, u = (%.9g, %.9g): inline and exported differ by %.3g > %.3g", what, e->name,
                      us[a], us[b], d, tol);
                /* values: where m is at least 0.01 from the horizon and from edge-on to v (a dot product near 0
                 * has an absolute rounding error, so its relative one grows as 1 / (m.v)) */
                if (!(m1.z >= 0.01 && t_dot(m1, v) >= 0.01 && v.z >= 0.01)) continue;
                double vals[3][2] = {
                    {ggx_ndf(s, m1), ggx_ndf_d(s, m1)},
                    {ggx_pdf_vndf(s, v, m1), ggx_pdf_vndf_d(s, v, m1)},
                    {ggx_brdf_eval(s, &f, v, ggx_reflect(v, m1)), ggx_brdf_eval_d(s, &f, v, ggx_reflect(v, m1))}};
                for (int k = 0; k < 3; k++) {
                    double r = fabs(vals[k][0] - vals[k][1]) / fmax(fabs(vals[k][0]), 1e-300);
                    if (r / (kappa * kappa) > worst_ratio) worst_ratio = r / (kappa * kappa);
                    CHECK(r <= tol, "%s: value %d differs by %.3g relative > %.3g", what, k, r, tol);
                }
            }
    }
}

static void kernels_agree(void **state)
{
    (void)state;
    ggx_shape s;
    /* the reported case */
    CHECK(ggx_shape_ellipsoid(&s, 1e3, 0.1, 1.0, 0.5, 0) == GGX_OK, "setup");
    check_shape(&s, 1e4, t_vec(0, 0, 1), "(1e3, 0.1, 1, 0.5, 0)");
    rng r = {12};
    int n = (int)(4000 * test_scale()) + 20;
    for (int t = 0; t < n; t++) {
        double l1 = -4 + 8 * rng_uniform(&r), l2 = l1 + 8 * rng_uniform(&r) - 4;
        l2 = fmin(4, fmax(-4, l2));
        double ax = pow(10, l1), ay = pow(10, l2), tx = 0, ty = 0, tz = 6.3 * rng_uniform(&r);
        if (rng_uniform(&r) < 0.7) tx = 2.4 * rng_uniform(&r) - 1.2, ty = 2.4 * rng_uniform(&r) - 1.2;
        if (ggx_shape_ellipsoid(&s, ax, ay, tx, ty, tz) != GGX_OK) continue;
        double hi = fmax(fmax(ax, ay), 1), lo = fmin(fmin(ax, ay), 1);
        double th = t < n / 4 ? acos(1e-6 + 0.01 * rng_uniform(&r)) : acos(rng_uniform(&r)), ph = 6.3 * rng_uniform(&r);
        char what[96];
        snprintf(what, sizeof what, "(%.4g, %.4g, %.3g, %.3g, %.3g)", ax, ay, tx, ty, tz);
        check_shape(&s, hi / lo, t_vec(sin(th) * cos(ph), sin(th) * sin(ph), cos(th)), what);
    }
    printf("inline _d against the exported API: largest difference / kappa^2 = %.3g (bound %.0e)\n", worst_ratio,
           BOUND);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(kernels_agree)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
