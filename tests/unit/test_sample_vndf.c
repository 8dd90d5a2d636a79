/* Visible-normal samplers: chi-square goodness of fit of every VNDF and rejection sampler of the registry (exported
 * double API) against Walter eq 33 over the sweep of shapes and views, with negative controls that must fail. The
 * other variants (inline, float, batch) run the same sweep in test_variants.c. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "audit.h"
#include "samplers.h"

static const unsigned FAMILIES = FAMILY_BIT(GGX_FAMILY_VNDF) | FAMILY_BIT(GGX_FAMILY_REJECTION);

/* The sweep's shapes: all, or half of them ("0": the even ones, "1": the odd ones), so that ctest runs the two halves
 * as two tests, in parallel, each short enough to show the suite alive. Each half has every sampler. */
static int half = -1;

static void vndf_sweep(void **state)
{
    (void)state;
    int shapes[16], views[8], nshapes = 0;
    for (int i = 0; i < SWEEP_NSHAPES; i++)
        if (half < 0 || i % 2 == half) shapes[nshapes++] = i;
    for (int j = 0; j < SWEEP_NVIEWS; j++) views[j] = j;
    double min_p = 1.0;
    int runs = chi2_sweep(VARIANT_EXPORTED, FAMILIES, shapes, nshapes, views, SWEEP_NVIEWS, 1000, &min_p);
    printf("vndf: %d shapes, %d chi-square runs of 10^6 samples, smallest p-value %.4g (Sidak level %.3g)\n", nshapes,
           runs, min_p, test_chi2_level());
}

/* Every registered VNDF and rejection sampler was in the sweep. */
static void vndf_coverage(void **state)
{
    (void)state;
    check_chi2_coverage(VARIANT_EXPORTED, FAMILIES);
}

/* Negative controls. (1) The caps sampler tested against D(m)(m.v)/(v.n), the VNDF pdf with the masking term
 * dropped, must be rejected. (2) A crescent sampler whose factor s is computed from A^{-T} n (the blog's eq for s)
 * instead of A n (Walter eq 38) must be rejected on a skewed shape. A harness that cannot fail proves nothing. */
static double pdf_no_g1(const normal_ctx *c, ggx_vec3 m)
{
    double mv = t_dot(m, c->v);
    return mv > 0 ? ggx_ndf(c->s, m) * mv / c->v.z : 0.0;
}
static void negative_controls(void **state)
{
    (void)state;
    double alpha = test_chi2_level();
    ggx_shape s;
    make_shape(&s, SWEEP_SHAPES[1].p);
    normal_ctx c = normal_ctx_of(VARIANT_EXPORTED, GGX_SAMPLER_CAPS, &s, sweep_view(80.0));
    c.pdf = pdf_no_g1;
    chi2_result r = run_normal_chi2_unchecked(&c, "negative control G1 dropped", 77);
    CHECK(r.pvalue < alpha, "the VNDF pdf without G1 was not rejected: p = %.3g", r.pvalue);
    printf("negative control, pdf with G1 dropped (iso 0.3, view 80): chi2 %.4g, dof %d, p = %.3g\n", r.stat, r.dof,
           r.pvalue);
    ggx_shape k;
    make_shape(&k, SWEEP_SHAPES[6].p);
    normal_ctx c2 = normal_ctx_of(VARIANT_EXPORTED, GGX_SAMPLER_CAPS, &k, sweep_view(30.0));
    c2.custom = verify_crescent_blog_s;
    r = run_normal_chi2_unchecked(&c2, "negative control s from A^-T n", 78);
    CHECK(r.pvalue < alpha, "the crescent with s from A^-T n was not rejected: p = %.3g", r.pvalue);
    printf("negative control, crescent s from A^-T n (skew 0.3:1, view 30): chi2 %.4g, dof %d, p = %.3g\n", r.stat,
           r.dof, r.pvalue);
    /* The same wrong sampler is indistinguishable on an unskewed shape (A n and A^{-T} n are both along n). */
    make_shape(&k, SWEEP_SHAPES[4].p);
    r = run_normal_chi2_unchecked(&c2, "negative control s from A^-T n, unskewed", 79);
    CHECK(chi2_accepts(r.pvalue), "unskewed: p = %.3g", r.pvalue);
}

int main(int argc, char **argv)
{
    if (argc > 1) half = argv[1][0] == '1';
    const struct CMUnitTest tests[] = {cmocka_unit_test(vndf_sweep), cmocka_unit_test(vndf_coverage),
                                       cmocka_unit_test(negative_controls)};
    const struct CMUnitTest second_half[] = {cmocka_unit_test(vndf_sweep), cmocka_unit_test(vndf_coverage)};
    /* the negative controls run with the first half (or the whole) */
    int rc = half == 1 ? cmocka_run_group_tests_name("second half", second_half, NULL, NULL)
                       : cmocka_run_group_tests(tests, NULL, NULL);
    return rc | chi2_budget_end("sample_vndf", argc, argv);
}
