/* Golden values: every evaluation function at fixed inputs, stored with 17 significant digits. A change in any
 * formula shows up here even where the property tests would still pass. Regenerate deliberately with
 * `test_golden --print` and review the diff. Tolerance 1e-13 relative: the stored values were produced by this
 * code; the margin only absorbs compilers that contract a*b+c into FMA. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "testlib.h"

enum { NVALUES = 4 * 19 + 6 };

static void compute(double *out)
{
    ggx_shape sh[4];
    const double A[3][3] = {{0.4, 0.1, -0.05}, {0.02, 0.25, 0.1}, {-0.1, 0.2, 1.1}};
    if (ggx_shape_iso(&sh[0], 0.35) != GGX_OK || ggx_shape_ellipsoid(&sh[1], 0.15, 0.5, 0, 0, 0.6) != GGX_OK ||
        ggx_shape_ellipsoid(&sh[2], 0.2, 0.45, 0.3, -0.2, 1.1) != GGX_OK || ggx_shape_matrix(&sh[3], A) != GGX_OK)
        fail_msg("setup");
    ggx_fresnel f;
    ggx_fresnel_conductor(&f, 0.2, 3.9);
    const ggx_vec3 wi = t_dir(0.7, 0.3), wo = t_dir(0.4, 2.8), m = t_dir(0.25, -0.4), gr = t_dir(1.55, 1.0);
    const ggx_vec3 in = t_dir(GGX_PI - 0.3, 2.0);
    int k = 0;
    for (int i = 0; i < 4; i++) {
        const ggx_shape *s = &sh[i];
        out[k++] = ggx_ndf(s, m);
        out[k++] = ggx_ndf_spherical(s, 0.9, 2.2);
        out[k++] = ggx_p22(s, 0.3, -0.7);
        out[k++] = ggx_gaussian_curvature(s, in);
        out[k++] = ggx_projected_area(s, gr);
        out[k++] = ggx_lune_area(s, gr, t_vec(0, 0, 1));
        out[k++] = ggx_g1(s, wi, m);
        out[k++] = ggx_g1(s, gr, m);
        out[k++] = ggx_lambda(s, wo);
        out[k++] = ggx_g1_smith(s, gr);
        out[k++] = ggx_g2_height_correlated(s, wi, wo, m);
        out[k++] = ggx_pdf_vndf(s, wi, m);
        out[k++] = ggx_pdf_vndf(s, gr, m);
        out[k++] = ggx_brdf_eval(s, &f, wi, wo);
        out[k++] = ggx_brdf_eval(s, &f, gr, wo);
        out[k++] = ggx_bsdf_eval(s, 1.5, wi, wo, GGX_RADIANCE);
        out[k++] = ggx_bsdf_eval(s, 1.5, wi, in, GGX_RADIANCE);
        out[k++] = ggx_bsdf_eval(s, 1.5, in, wi, GGX_RADIANCE);
        out[k++] = ggx_bsdf_eval(s, 1 / 1.33, in, t_dir(GGX_PI - 0.5, 2.5), GGX_IMPORTANCE);
    }
    out[k++] = ggx_fresnel_dielectric_eval(0.3, 1.5);
    out[k++] = ggx_fresnel_dielectric_eval(0.9, 1 / 1.5);
    out[k++] = ggx_fresnel_conductor_eval(0.3, 0.2, 3.9);
    out[k++] = ggx_fresnel_schlick_eval(0.3, 0.04);
    out[k++] = ggx_jacobian_refract(wi, in, ggx_half_refract(wi, in, 1, 1.5), 1, 1.5);
    out[k++] = ggx_jacobian_reflect(wo, ggx_half_reflect(wi, wo));
    if (k != NVALUES) fail_msg("count %d", k);
}

static const double golden[NVALUES] = {
#include "golden_values.inc"
};

static void golden_values(void **state)
{
    (void)state;
    double v[NVALUES];
    compute(v);
    int nonzero = 0;
    for (int i = 0; i < NVALUES; i++) {
        CHECK_CLOSE(v[i], golden[i], 1e-13, 0, "value %d (shape %d, function %d)", i, i / 19, i % 19);
        nonzero += v[i] != 0.0;
    }
    CHECK(nonzero >= NVALUES - 8, "only %d of %d golden values are nonzero", nonzero, NVALUES);
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--print") == 0) {
        double v[NVALUES];
        compute(v);
        for (int i = 0; i < NVALUES; i++) printf("%.17g,\n", v[i]);
        return 0;
    }
    const struct CMUnitTest tests[] = {cmocka_unit_test(golden_values)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
