/* NDF samplers: chi-square of every NDF sampler of the registry (exported double API) against D(m)(m.n) over the
 * sweep of shapes, and a negative control. The other variants run the same sweep in test_variants.c.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "samplers.h"

static const unsigned FAMILIES = FAMILY_BIT(GGX_FAMILY_NDF);

static void ndf_sweep(void **state)
{
    (void)state;
    int shapes[16];
    for (int i = 0; i < SWEEP_NSHAPES; i++) shapes[i] = i;
    double min_p = 1.0;
    int runs = chi2_sweep(VARIANT_EXPORTED, FAMILIES, shapes, SWEEP_NSHAPES, NULL, 0, 5000, &min_p);
    printf("ndf: %d chi-square runs of 10^6 samples, smallest p-value %.4g\n", runs, min_p);
}

/* Every registered NDF sampler was in the sweep. */
static void ndf_coverage(void **state)
{
    (void)state;
    check_chi2_coverage(VARIANT_EXPORTED, FAMILIES);
}

/* Negative control: the stretch sampler against the visible-normal pdf for an 80 degree view must be rejected. */
static double pdf_vndf(const normal_ctx *c, ggx_vec3 m) { return ggx_pdf_vndf(c->s, c->v, m); }
static void ndf_negative_control(void **state)
{
    (void)state;
    ggx_shape s;
    make_shape(&s, SWEEP_SHAPES[1].p);
    normal_ctx c = normal_ctx_of(VARIANT_EXPORTED, GGX_SAMPLER_STRETCH, &s, sweep_view(80.0));
    c.pdf = pdf_vndf;
    chi2_result r = run_normal_chi2_unchecked(&c, "ndf negative control", 99);
    CHECK(r.pvalue < test_chi2_level() || r.zero_cell_hits > 0, "not rejected: p = %.3g", r.pvalue);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(ndf_sweep), cmocka_unit_test(ndf_coverage),
                                       cmocka_unit_test(ndf_negative_control)};
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    return rc | chi2_budget_end("sample_ndf", argc, argv);
}
