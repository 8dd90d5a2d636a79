/* The README's example: evaluate the ellipsoid NDF model for a skewed shape at a few directions.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "ggx/ggx.h"


static ggx_vec3 dir(double theta_deg, double phi_deg)
{
    double t = theta_deg * GGX_PI / 180.0, p = phi_deg * GGX_PI / 180.0;
    ggx_vec3 v = {sin(t) * cos(p), sin(t) * sin(p), cos(t)};
    return v;
}

int main(void)
{
    const double deg = GGX_PI / 180.0;
    ggx_shape s;
    ggx_fresnel f;
    ggx_status st = ggx_shape_ellipsoid(&s, 0.15, 0.5, 10.0 * deg, -5.0 * deg, 30.0 * deg);
    if (st != GGX_OK || (st = ggx_fresnel_conductor(&f, 0.2, 3.9)) != GGX_OK) {
        fprintf(stderr, "ggx_example: %s\n", ggx_status_str(st));
        return 2;
    }
    printf("libggx %d.%d.%d example: ellipsoid NDF, alpha = (0.15, 0.5), theta = (10, -5, 30) deg (skewed),\n"
           "conductor Fresnel eta = 0.2 + 3.9i. Angles in degrees; wi is fixed at (theta 40, phi 0).\n\n",
           GGX_VERSION_MAJOR, GGX_VERSION_MINOR, GGX_VERSION_PATCH);
    printf("%-14s %14s %14s %14s %14s %14s\n", "wo (th, ph)", "D(h)", "G1(wi,h)", "G1(wo,h)", "pdf_vndf(h)", "BRDF");
    ggx_vec3 wi = dir(40.0, 0.0);
    const double wo_angles[][2] = {{0, 0}, {40, 180}, {60, 180}, {20, 90}, {75, 200}, {89, 180}};
    for (unsigned k = 0; k < sizeof wo_angles / sizeof wo_angles[0]; k++) {
        ggx_vec3 wo = dir(wo_angles[k][0], wo_angles[k][1]);
        ggx_vec3 h = ggx_half_reflect(wi, wo);
        char label[32];
        snprintf(label, sizeof label, "(%g, %g)", wo_angles[k][0], wo_angles[k][1]);
        printf("%-14s %14.6g %14.6g %14.6g %14.6g %14.6g\n", label, ggx_ndf(&s, h), ggx_g1(&s, wi, h),
               ggx_g1(&s, wo, h), ggx_pdf_vndf(&s, wi, h), ggx_brdf_eval(&s, &f, wi, wo));
    }
    printf("\nProjected area A_e(n) = %.6g, lune area A_l(wi, n) = %.6g (Ce = 1), Lambda(wi) = %.6g\n",
           ggx_projected_area(&s, (ggx_vec3){0, 0, 1}), ggx_lune_area(&s, wi, (ggx_vec3){0, 0, 1}), ggx_lambda(&s, wi));
    return 0;
}
