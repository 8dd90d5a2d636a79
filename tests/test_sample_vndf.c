/* Visible-normal samplers: chi-square goodness of fit of every VNDF sampler against Walter eq 33 over the sweep of
 * shapes and views, with negative controls that must fail. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "audit.h"
#include "samplers.h"

typedef struct named_vndf {
    const char *name;
    vndf_fn f;
    reject_fn rej;
} named_vndf;

static const named_vndf SAMPLERS[] = {
    {"caps", ggx_sample_vndf_caps, NULL},
    {"crescent", ggx_sample_vndf_crescent, NULL},
    {"crescent-polar", ggx_sample_vndf_crescent_polar, NULL},
    {"heitz", ggx_sample_vndf_heitz, NULL},
    {"walter-v1", NULL, ggx_sample_vndf_walter_v1},
    {"walter-v2", NULL, ggx_sample_vndf_walter_v2},
};

static void vndf_sweep(void **state)
{
    (void)state;
    double min_p = 1.0;
    int runs = 0;
    for (unsigned k = 0; k < sizeof SAMPLERS / sizeof SAMPLERS[0]; k++) {
        double acc_sum = 0.0;
        int acc_n = 0;
        for (int i = 0; i < SWEEP_NSHAPES; i++) {
            ggx_shape s;
            make_shape(&s, SWEEP_SHAPES[i].p);
            for (int j = 0; j < SWEEP_NVIEWS; j++) {
                normal_ctx c = {{&s, sweep_view(SWEEP_VIEWS_DEG[j]), ggx_pdf_vndf}, SAMPLERS[k].f, NULL, SAMPLERS[k].rej, 0, 0};
                char name[128];
                snprintf(name, sizeof name, "vndf %s, %s, view %g", SAMPLERS[k].name, SWEEP_SHAPES[i].name,
                         SWEEP_VIEWS_DEG[j]);
                run_normal_chi2(&c, name, 1000 + 100 * k + 10 * i + j, &min_p);
                runs++;
                if (c.reject) {
                    acc_sum += (double)c.draws / (double)c.trials;
                    acc_n++;
                }
            }
        }
        if (acc_n) printf("%s: mean acceptance rate %.3f over %d shape/view pairs\n", SAMPLERS[k].name, acc_sum / acc_n, acc_n);
    }
    printf("vndf: %d chi-square runs of 10^6 samples, smallest p-value %.4g (Sidak level %.3g)\n", runs, min_p,
           chi2_sidak(CHI2_SUITE_RUNS));
}

/* Negative controls. (1) The caps sampler tested against D(m)(m.v)/(v.n), the VNDF pdf with the masking term
 * dropped, must be rejected. (2) A crescent sampler whose factor s is computed from A^{-T} n (the blog's eq for s)
 * instead of A n (Walter eq 38) must be rejected on a skewed shape. A harness that cannot fail proves nothing. */
static double pdf_no_g1(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    double mv = t_dot(m, v);
    return mv > 0 ? ggx_ndf(s, m) * mv / v.z : 0.0;
}
static void negative_controls(void **state)
{
    (void)state;
    double alpha = chi2_sidak(CHI2_SUITE_RUNS);
    ggx_shape s;
    make_shape(&s, SWEEP_SHAPES[1].p);
    normal_ctx c = {{&s, sweep_view(80.0), pdf_no_g1}, ggx_sample_vndf_caps, NULL, NULL, 0, 0};
    chi2_problem p = {"negative control G1 dropped", 1, normal_draw, normal_keys_key, normal_keys_density, &c};
    chi2_result r = chi2_run_scaled(&p, 77, 0.0);
    chi2_runs_done++;
    CHECK(r.pvalue < alpha, "the VNDF pdf without G1 was not rejected: p = %.3g", r.pvalue);
    printf("negative control, pdf with G1 dropped (iso 0.3, view 80): chi2 %.4g, dof %d, p = %.3g\n", r.stat, r.dof,
           r.pvalue);
    ggx_shape k;
    make_shape(&k, SWEEP_SHAPES[6].p);
    normal_ctx c2 = {{&k, sweep_view(30.0), ggx_pdf_vndf}, verify_crescent_blog_s, NULL, NULL, 0, 0};
    chi2_problem p2 = {"negative control s from A^-T n", 1, normal_draw, normal_keys_key, normal_keys_density, &c2};
    r = chi2_run_scaled(&p2, 78, 0.0);
    chi2_runs_done++;
    CHECK(r.pvalue < alpha, "the crescent with s from A^-T n was not rejected: p = %.3g", r.pvalue);
    printf("negative control, crescent s from A^-T n (skew 0.3:1, view 30): chi2 %.4g, dof %d, p = %.3g\n", r.stat,
           r.dof, r.pvalue);
    /* The same wrong sampler is indistinguishable on an unskewed shape (A n and A^{-T} n are both along n). */
    make_shape(&k, SWEEP_SHAPES[4].p);
    r = chi2_run_scaled(&p2, 79, 0.0);
    chi2_runs_done++;
    CHECK(r.pvalue >= alpha, "unskewed: p = %.3g", r.pvalue);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(vndf_sweep), cmocka_unit_test(negative_controls)};
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    printf("chi-square runs in this program: %d\n", chi2_runs_done);
    return rc;
}
