/* NDF samplers: chi-square of every sampler against D(m)(m.n) over the sweep of shapes. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "samplers.h"

typedef struct named_ndf {
    const char *name;
    ndf_fn f;
    int unskewed_only;
} named_ndf;

static const named_ndf SAMPLERS[] = {
    {"stretch", ggx_sample_ndf_stretch, 0},
    {"ellipse", ggx_sample_ndf_ellipse, 0},
    {"inversion", ggx_sample_ndf_inversion, 1},
    {"visible", ggx_sample_ndf_visible, 0},
    {"default", ggx_sample_ndf, 0},
};

static void ndf_sweep(void **state)
{
    (void)state;
    double min_p = 1.0;
    int runs = 0;
    for (unsigned k = 0; k < sizeof SAMPLERS / sizeof SAMPLERS[0]; k++) {
        for (int i = 0; i < SWEEP_NSHAPES; i++) {
            ggx_shape s;
            make_shape(&s, SWEEP_SHAPES[i].p);
            if (SAMPLERS[k].unskewed_only && s.kind == GGX_SHAPE_SKEWED) {
                /* Outside its domain the closed-form inversion returns the zero vector (pdf 0). */
                ggx_vec3 m = SAMPLERS[k].f(&s, 0.3, 0.6);
                CHECK(m.x == 0 && m.y == 0 && m.z == 0, "%s on a skewed shape must return 0", SAMPLERS[k].name);
                continue;
            }
            normal_ctx c = {{&s, t_vec(0, 0, 1), verify_pdf_ndf}, NULL, SAMPLERS[k].f, NULL, 0, 0};
            char name[128];
            snprintf(name, sizeof name, "ndf %s, %s", SAMPLERS[k].name, SWEEP_SHAPES[i].name);
            run_normal_chi2(&c, name, 5000 + 100 * k + i, &min_p);
            runs++;
        }
    }
    printf("ndf: %d chi-square runs of 10^6 samples, smallest p-value %.4g\n", runs, min_p);
}

/* Negative control: the stretch sampler against the visible-normal pdf for an 80 degree view must be rejected. */
static void ndf_negative_control(void **state)
{
    (void)state;
    ggx_shape s;
    make_shape(&s, SWEEP_SHAPES[1].p);
    normal_ctx c = {{&s, sweep_view(80.0), ggx_pdf_vndf}, NULL, ggx_sample_ndf_stretch, NULL, 0, 0};
    chi2_problem p = {"ndf negative control", 1, normal_draw, normal_keys_key, normal_keys_density, &c};
    chi2_result r = chi2_run_scaled(&p, 99, 0.0);
    chi2_runs_done++;
    CHECK(r.pvalue < chi2_sidak(CHI2_SUITE_RUNS) || r.zero_cell_hits > 0, "not rejected: p = %.3g", r.pvalue);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(ndf_sweep), cmocka_unit_test(ndf_negative_control)};
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    printf("chi-square runs in this program: %d\n", chi2_runs_done);
    return rc;
}
