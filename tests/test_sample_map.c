/* The samplers as maps from the unit square: finite-difference Jacobians equal 1 / pdf point by point (the seeds'
 * proofs, checked numerically), inverse maps round-trip, disk maps are uniform, and the edge cases (v = n exactly,
 * grazing v, v below the horizon, u at the ends of [0, 1)) are defined. SPDX-License-Identifier: MIT */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "samplers.h"

typedef struct map_entry {
    const char *name;
    vndf_fn vndf;                                            /* VNDF sampler, or */
    ndf_fn ndf;                                              /* NDF sampler */
    ggx_vec2 (*inv)(const ggx_shape *, ggx_vec3, ggx_vec3); /* inverse for VNDF samplers */
    int concentric;                                          /* seams of the concentric map to avoid */
} map_entry;

static ggx_vec2 stretch_inv_v(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    (void)v;
    return ggx_sample_ndf_stretch_inv(s, m);
}

static const map_entry MAPS[] = {
    {"caps", ggx_sample_vndf_caps, NULL, ggx_sample_vndf_caps_inv, 0},
    {"crescent", ggx_sample_vndf_crescent, NULL, ggx_sample_vndf_crescent_inv, 1},
    {"crescent-polar", ggx_sample_vndf_crescent_polar, NULL, ggx_sample_vndf_crescent_polar_inv, 0},
    {"heitz", ggx_sample_vndf_heitz, NULL, ggx_sample_vndf_heitz_inv, 0},
    {"stretch", NULL, ggx_sample_ndf_stretch, stretch_inv_v, 0},
    {"ellipse", NULL, ggx_sample_ndf_ellipse, NULL, 0},
    {"inversion", NULL, ggx_sample_ndf_inversion, NULL, 0},
    {"visible", NULL, ggx_sample_ndf_visible, NULL, 0},
};

static ggx_vec3 eval_map(const map_entry *e, const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    return e->vndf ? e->vndf(s, v, u1, u2) : e->ndf(s, u1, u2);
}

/* |dm/du1 x dm/du2| by central differences: the solid angle per unit area of the square, which must be 1 / pdf. */
static double fd_solid_angle(const map_entry *e, const ggx_shape *s, ggx_vec3 v, double u1, double u2, double h)
{
    ggx_vec3 a = t_add(eval_map(e, s, v, u1 + h, u2), t_scale(eval_map(e, s, v, u1 - h, u2), -1));
    ggx_vec3 b = t_add(eval_map(e, s, v, u1, u2 + h), t_scale(eval_map(e, s, v, u1, u2 - h), -1));
    ggx_vec3 c = t_cross(a, b);
    return sqrt(t_dot(c, c)) / (4 * h * h);
}

/* Step 1e-6 in u: truncation ~1e-12 times the map's curvature, rounding ~1e-10 relative; we require 1e-5. Points
 * within 0.02 of the square's edges or of the concentric map's seams, and samples within 2 degrees of the horizon
 * or of the lune's rim (where the map's derivatives blow up), are skipped. */
static void jacobians(void **state)
{
    (void)state;
    rng r = {61};
    long checked = 0;
    double worst = 0.0;
    for (unsigned k = 0; k < sizeof MAPS / sizeof MAPS[0]; k++) {
        for (int i = 0; i < SWEEP_NSHAPES; i++) {
            ggx_shape s;
            make_shape(&s, SWEEP_SHAPES[i].p);
            if (MAPS[k].ndf == ggx_sample_ndf_inversion && s.kind == GGX_SHAPE_SKEWED) continue;
            for (int j = 0; j < SWEEP_NVIEWS; j++) {
                ggx_vec3 v = sweep_view(SWEEP_VIEWS_DEG[j]);
                if (MAPS[k].ndf && j > 0) break;
                for (int t = 0; t < 60; t++) {
                    double u1 = rng_range(&r, 0.02, 0.98), u2 = rng_range(&r, 0.02, 0.98);
                    double a = 2 * u1 - 1, b = 2 * u2 - 1;
                    if (MAPS[k].concentric && (fabs(fabs(a) - fabs(b)) < 0.02 || fabs(a) < 0.02 || fabs(b) < 0.02)) continue;
                    ggx_vec3 m = eval_map(&MAPS[k], &s, v, u1, u2);
                    double pdf = MAPS[k].vndf ? ggx_pdf_vndf(&s, v, m) : ggx_pdf_ndf(&s, m);
                    double mv = MAPS[k].vndf ? t_dot(m, v) : 1.0;
                    if (m.z < 0.035 || mv < 0.035) continue;
                    double fd = fd_solid_angle(&MAPS[k], &s, v, u1, u2, 1e-6);
                    CHECK_CLOSE(fd * pdf, 1.0, 1e-5, 0, "%s, %s, view %g, u (%.17g, %.17g)", MAPS[k].name,
                                SWEEP_SHAPES[i].name, SWEEP_VIEWS_DEG[j], u1, u2);
                    if (fabs(fd * pdf - 1) > worst) worst = fabs(fd * pdf - 1);
                    checked++;
                }
            }
        }
    }
    CHECK(checked > 5000, "only %ld points checked", checked);
    printf("jacobians: %ld points, largest |J pdf - 1| = %.3g\n", checked, worst);
}

/* u -> m -> u round trips for the invertible maps (phi wraps at 0 and 1). */
static void inverses(void **state)
{
    (void)state;
    rng r = {62};
    long checked = 0;
    for (unsigned k = 0; k < sizeof MAPS / sizeof MAPS[0]; k++) {
        if (!MAPS[k].inv) continue;
        for (int i = 0; i < SWEEP_NSHAPES; i++) {
            ggx_shape s;
            make_shape(&s, SWEEP_SHAPES[i].p);
            for (int j = 0; j < SWEEP_NVIEWS; j++) {
                ggx_vec3 v = sweep_view(SWEEP_VIEWS_DEG[j]);
                for (int t = 0; t < 200; t++) {
                    double u1 = rng_range(&r, 0.01, 0.99), u2 = rng_range(&r, 0.01, 0.99);
                    ggx_vec3 m = eval_map(&MAPS[k], &s, v, u1, u2);
                    ggx_vec2 u = MAPS[k].inv(&s, v, m);
                    double d1 = fabs(u.x - u1), d2 = fabs(u.y - u2);
                    if (MAPS[k].vndf == ggx_sample_vndf_caps) d1 = fmin(d1, 1 - d1); /* phi = 2 pi u1 wraps */
                    else if (!MAPS[k].concentric) d2 = fmin(d2, 1 - d2);                /* phi = 2 pi u2 wraps */
                    CHECK(d1 < 1e-7 && d2 < 1e-7, "%s, %s, view %g: u (%.12g, %.12g) -> (%.12g, %.12g)", MAPS[k].name,
                          SWEEP_SHAPES[i].name, SWEEP_VIEWS_DEG[j], u1, u2, u.x, u.y);
                    checked++;
                }
            }
        }
    }
    /* Disk maps: inverse round trips, and the images fill the disk. */
    for (int t = 0; t < 100000; t++) {
        double u1 = rng_uniform(&r), u2 = rng_uniform(&r);
        ggx_vec2 d = ggx_disk_concentric(u1, u2), e = ggx_disk_polar(u1, u2);
        CHECK(d.x * d.x + d.y * d.y <= 1 + 1e-15 && e.x * e.x + e.y * e.y <= 1 + 1e-15, "inside the disk");
        ggx_vec2 ud = ggx_disk_concentric_inv(d), ue = ggx_disk_polar_inv(e);
        CHECK(fabs(ud.x - u1) < 1e-12 && fabs(ud.y - u2) < 1e-12, "concentric inverse (%g, %g)", u1, u2);
        CHECK(fabs(ue.x - u1) < 1e-12 && (fabs(ue.y - u2) < 1e-12 || fabs(fabs(ue.y - u2) - 1) < 1e-12), "polar inverse");
        checked++;
    }
    /* The samplers' own cos/sin of 2 pi t (a quarter-turn polynomial) against libm: the polar map at r = 1. */
    double worst = 0.0;
    for (int t = 0; t <= 1000000; t++) {
        double u = t / 1e6;
        ggx_vec2 d = ggx_disk_polar(1.0, u);
        worst = fmax(worst, fmax(fabs(d.x - cos(2 * T_PI * u)), fabs(d.y - sin(2 * T_PI * u))));
    }
    /* 1e-15: the libm reference takes cos of the rounded 2 pi t, itself off by up to ~7e-16 near t = 1. */
    CHECK(worst <= 1e-15, "sincos of 2 pi t: error %g", worst);
    printf("inverse maps: %ld round trips; sincos(2 pi t) largest error %.2g\n", checked, worst);
}

static double uniform_cb(void *st) { return rng_uniform((rng *)st); }

/* Defined behaviour at the edges: v = n exactly and v.z = 1e-8 give unit normals with pdf > 0; v below the
 * horizon (and on it) gives the zero vector; u in {0, tiny, 1 - ulp, 1} gives unit normals, never NaN. */
static void edge_cases(void **state)
{
    (void)state;
    const double us[] = {0.0, 1e-300, 0.5, 1.0 - DBL_EPSILON / 2, 1.0};
    const ggx_vec3 views[] = {t_vec(0, 0, 1), t_dir(T_PI / 2 - 1e-8, 0.3), t_vec(0.6, 0.8, 0)};
    long n = 0;
    for (int i = 0; i < SWEEP_NSHAPES; i++) {
        ggx_shape s;
        make_shape(&s, SWEEP_SHAPES[i].p);
        for (unsigned k = 0; k < sizeof MAPS / sizeof MAPS[0]; k++) {
            if (MAPS[k].ndf == ggx_sample_ndf_inversion && s.kind == GGX_SHAPE_SKEWED) continue;
            for (unsigned j = 0; j < 3; j++) {
                if (MAPS[k].ndf && j > 0) break;
                for (int a = 0; a < 5; a++) {
                    for (int b = 0; b < 5; b++) {
                        ggx_vec3 m = eval_map(&MAPS[k], &s, views[j], us[a], us[b]);
                        n++;
                        if (j == 2) {
                            CHECK(m.x == 0 && m.y == 0 && m.z == 0, "%s: view on the horizon must give 0", MAPS[k].name);
                            continue;
                        }
                        CHECK(fabs(t_dot(m, m) - 1) < 1e-12 && m.z >= 0, "%s, %s, view %u, u (%g, %g): m (%g,%g,%g)",
                              MAPS[k].name, SWEEP_SHAPES[i].name, j, us[a], us[b], m.x, m.y, m.z);
                    }
                }
            }
        }
        ggx_vec3 below = t_dir(T_PI / 2 + 0.1, 0.2);
        rng r = {63};
        unsigned trials;
        CHECK(ggx_sample_vndf(&s, below, 0.3, 0.3).z == 0 && ggx_sample_vndf_walter_v1(&s, below, uniform_cb, &r, &trials).z == 0 &&
                  ggx_sample_vndf_walter_v2(&s, below, uniform_cb, &r, &trials).z == 0,
              "below the horizon");
        ggx_vec3 m1 = ggx_sample_vndf_walter_v1(&s, views[0], uniform_cb, &r, &trials);
        ggx_vec3 m2 = ggx_sample_vndf_walter_v2(&s, views[1], uniform_cb, &r, &trials);
        CHECK(fabs(t_dot(m1, m1) - 1) < 1e-12 && fabs(t_dot(m2, m2) - 1) < 1e-12, "rejection samplers at the edges");
        /* v = n: the VNDF is the NDF's pdf D(m) m.z. */
        ggx_vec3 m = ggx_sample_vndf(&s, views[0], 0.37, 0.81);
        CHECK_CLOSE(ggx_pdf_vndf(&s, views[0], m), ggx_pdf_ndf(&s, m), 1e-12, 0, "v = n");
    }
    printf("edge cases: %ld samples checked\n", n);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(jacobians), cmocka_unit_test(inverses),
                                       cmocka_unit_test(edge_cases)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
