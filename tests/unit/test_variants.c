/* Every variant of the samplers of normals (variants.h: inline double, inline float, the batch API on each
 * instruction set the CPU has) against its own pdf: the chi-square body of test_sample_ndf.c and
 * test_sample_vndf.c, on a reduced sweep to keep time (3 shapes: iso 0.05, the sharpest lobe; aniso 1:0.1 rotated;
 * skew 0.05:0.3, sharp and skewed; x 2 views: exactly n and 89.5 degrees, the most grazing of the sweep), with the
 * seeds of the exported runs of the same sampler, shape and view, so that p-values compare. A negative control per
 * variant, and the proof that every registered sampler is in every variant that should have it and got runs.
 * Agreement with the exported double API and non-finite u: tests/test_float_regress.c. Argument: "inline" or
 * "batch" for half of the variants. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "samplers.h"

static const unsigned FAMILIES = FAMILY_BIT(GGX_FAMILY_NDF) | FAMILY_BIT(GGX_FAMILY_VNDF) |
                                 FAMILY_BIT(GGX_FAMILY_REJECTION);
static const int SHAPES[] = {0, 5, 7};
static const int VIEWS[] = {0, 3};

/* The variants this run tests: "inline" (the inline kernels), "batch" (the batch API) or all but the exported
 * reference (no argument); ctest runs the two halves as two tests, in parallel. */
static const char *selection;
static int selected(const variant *vr)
{
    if (vr == VARIANT_EXPORTED) return 0;
    if (!selection) return 1;
    return strcmp(selection, vr->isa == GGX_ISA_AUTO ? "inline" : "batch") == 0;
}

static void variant_sweeps(void **state)
{
    (void)state;
    for (int k = 0; k < VARIANT_COUNT; k++) {
        const variant *vr = &VARIANTS[k];
        if (!selected(vr)) continue;
        if (!variant_available(vr)) {
            CHECK(ggx_batch_set_isa(vr->isa) == GGX_ERR_RANGE, "%s: unavailable but accepted", vr->name);
            printf("%s: not available on this CPU or build\n", vr->name);
            continue;
        }
        double min_p = 1.0;
        int runs = chi2_sweep(vr, FAMILY_BIT(GGX_FAMILY_NDF), SHAPES, 3, VIEWS, 2, 5000, &min_p);
        runs += chi2_sweep(vr, FAMILY_BIT(GGX_FAMILY_VNDF) | FAMILY_BIT(GGX_FAMILY_REJECTION), SHAPES, 3, VIEWS, 2,
                           1000, &min_p);
        printf("%s: %d chi-square runs, smallest p-value %.4g (Sidak level %.3g)\n", vr->name, runs, min_p,
               test_chi2_level());
    }
    ggx_batch_set_isa(GGX_ISA_AUTO);
}

/* The first VNDF sampler of the variant against its D(m) (m.v) / (v.n), the VNDF pdf with G1 dropped, must be
 * rejected (iso 0.3, view 80, as the exported control of test_sample_vndf.c): each variant's path through the
 * harness can fail. */
static double pdf_no_g1(const normal_ctx *c, ggx_vec3 m)
{
    double d, mv = t_dot(m, c->v);
    c->var->ndf(c->var, c->s, 1, &m, &d);
    return mv > 0 ? d * mv / c->v.z : 0.0;
}
static void variant_negative_controls(void **state)
{
    (void)state;
    ggx_shape s;
    make_shape(&s, SWEEP_SHAPES[1].p);
    for (int k = 0; k < VARIANT_COUNT; k++) {
        const variant *vr = &VARIANTS[k];
        if (!selected(vr) || !variant_available(vr)) continue;
        int id = 0;
        while (id < GGX_SAMPLER_COUNT && !(ggx_sampler_get((ggx_sampler_id)id)->family == GGX_FAMILY_VNDF &&
                                           vr->has(vr, (ggx_sampler_id)id) == 1))
            id++;
        CHECK(id < GGX_SAMPLER_COUNT, "%s has no VNDF sampler", vr->name);
        normal_ctx c = normal_ctx_of(vr, (ggx_sampler_id)id, &s, sweep_view(80.0));
        c.pdf = pdf_no_g1;
        char name[96];
        snprintf(name, sizeof name, "%s negative control G1 dropped", vr->name);
        chi2_result r = run_normal_chi2_unchecked(&c, name, 77);
        CHECK(r.pvalue < test_chi2_level(), "%s: %s against the pdf without G1 was not rejected: p = %.3g", vr->name,
              ggx_sampler_get((ggx_sampler_id)id)->name, r.pvalue);
        printf("%s negative control (%s, pdf with G1 dropped): chi2 %.4g, dof %d, p = %.3g\n", vr->name,
               ggx_sampler_get((ggx_sampler_id)id)->name, r.stat, r.dof, r.pvalue);
    }
    ggx_batch_set_isa(GGX_ISA_AUTO);
}

/* The registry is whole, every variant has the samplers it should (the inline kernels every sampler of normals,
 * the batch API those marked batch), and each of them got chi-square runs above. */
static void coverage(void **state)
{
    (void)state;
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *info = ggx_sampler_get((ggx_sampler_id)id);
        CHECK(info && info->id == (ggx_sampler_id)id && ggx_sampler_find(info->name) == info, "registry entry %d", id);
        /* the families some sweep knows: chi-square here and in test_sample_*.c, directions in test_sample_dir.c */
        CHECK(info->family == GGX_FAMILY_NDF || info->family == GGX_FAMILY_VNDF ||
                  info->family == GGX_FAMILY_REJECTION || info->family == GGX_FAMILY_DIRECTION,
              "sampler %s: family %d is swept by no test", info->name, (int)info->family);
        int normal = info->family == GGX_FAMILY_NDF || info->family == GGX_FAMILY_VNDF;
        int want_inline = normal ? 1 : info->family == GGX_FAMILY_REJECTION ? 2 : 0;
        for (int k = 0; k < VARIANT_COUNT; k++) {
            const variant *vr = &VARIANTS[k];
            int want = vr->isa == GGX_ISA_AUTO ? want_inline : (info->batch && normal);
            if (vr == VARIANT_EXPORTED && info->family == GGX_FAMILY_DIRECTION) want = 3;
            CHECK(vr->has(vr, (ggx_sampler_id)id) == want, "%s: sampler %s: has %d, want %d", vr->name, info->name,
                  vr->has(vr, (ggx_sampler_id)id), want);
        }
    }
    int tested = 0;
    for (int k = 0; k < VARIANT_COUNT; k++)
        if (selected(&VARIANTS[k]) && variant_available(&VARIANTS[k])) {
            check_chi2_coverage(&VARIANTS[k], FAMILIES);
            tested++;
        }
    CHECK(tested > 0, "no variant selected by '%s'", selection ? selection : "");
}

int main(int argc, char **argv)
{
    selection = argc > 1 ? argv[1] : NULL;
    const struct CMUnitTest tests[] = {cmocka_unit_test(variant_sweeps), cmocka_unit_test(variant_negative_controls),
                                       cmocka_unit_test(coverage)};
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    return rc | chi2_budget_end("variants", argc, argv);
}
