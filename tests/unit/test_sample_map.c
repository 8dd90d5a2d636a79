/* The samplers as maps from the unit square: finite-difference Jacobians equal 1 / pdf point by point (the seeds'
 * proofs, checked numerically), inverse maps round-trip, disk maps are uniform, and the edge cases (v = n exactly,
 * grazing v, v below the horizon, u at the ends of [0, 1)) are defined. SPDX-License-Identifier: MIT */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "samplers.h"

/* The registry's samplers of normals (NDF and VNDF families), in the table's shared signature. */
static int is_map(const ggx_sampler_info *info)
{
    return info->family == GGX_FAMILY_NDF || info->family == GGX_FAMILY_VNDF;
}
static int skip_shape(const ggx_sampler_info *info, const ggx_shape *s)
{
    return info->domain == GGX_DOMAIN_UNSKEWED && s->kind == GGX_SHAPE_SKEWED;
}
/* NDF samplers ignore the view: one view (n) is enough. */
static int views_of(const ggx_sampler_info *info) { return info->family == GGX_FAMILY_NDF ? 1 : SWEEP_NVIEWS; }

/* |dm/du1 x dm/du2| by central differences: the solid angle per unit area of the square, which must be 1 / pdf. */
static double fd_solid_angle(const ggx_sampler_info *e, const ggx_shape *s, ggx_vec3 v, double u1, double u2, double h)
{
    ggx_vec3 a = t_add(e->sample(s, v, u1 + h, u2), t_scale(e->sample(s, v, u1 - h, u2), -1));
    ggx_vec3 b = t_add(e->sample(s, v, u1, u2 + h), t_scale(e->sample(s, v, u1, u2 - h), -1));
    ggx_vec3 c = t_cross(a, b);
    return sqrt(t_dot(c, c)) / (4 * h * h);
}

/* The same for samplers of reflected directions (the registry's DIRECTION samplers that do not transmit: reflection
 * sampling and bounded reflection sampling): |dwo/du1 x dwo/du2| = 1 / pdf of wo, with F = 1; points as below,
 * and directions within 2 degrees of the horizon skipped. */
static ggx_vec3 dir_at(const ggx_sampler_info *e, const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    ggx_fresnel one = {GGX_FRESNEL_ONE, 0, 0, 0};
    return e->sample_direction(s, &one, 1.5, v, u1, u2, 0.5, GGX_RADIANCE).w;
}
static void direction_jacobians(void **state)
{
    (void)state;
    rng r = {62};
    double worst = 0.0;
    long total = 0;
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
        if (e->family != GGX_FAMILY_DIRECTION || sampler_transmits(e)) continue;
        long checked = 0;
        for (int i = 0; i < SWEEP_NSHAPES; i++) {
            ggx_shape s;
            make_shape(&s, SWEEP_SHAPES[i].p);
            for (int j = 0; j < SWEEP_NVIEWS; j++) {
                ggx_vec3 v = sweep_view(SWEEP_VIEWS_DEG[j]);
                if (v.z < 0.035) continue;
                for (int t = 0; t < 60; t++) {
                    double u1 = rng_range(&r, 0.02, 0.98), u2 = rng_range(&r, 0.02, 0.98), h = 1e-6;
                    ggx_vec3 w = dir_at(e, &s, v, u1, u2), ws[4];
                    if (w.z < 0.035) continue;
                    ws[0] = dir_at(e, &s, v, u1 + h, u2), ws[1] = dir_at(e, &s, v, u1 - h, u2);
                    ws[2] = dir_at(e, &s, v, u1, u2 + h), ws[3] = dir_at(e, &s, v, u1, u2 - h);
                    if (ws[0].z < 0.035 || ws[1].z < 0.035 || ws[2].z < 0.035 || ws[3].z < 0.035) continue;
                    ggx_vec3 c = t_cross(t_add(ws[0], t_scale(ws[1], -1)), t_add(ws[2], t_scale(ws[3], -1)));
                    double fd = sqrt(t_dot(c, c)) / (4 * h * h), pdf = e->pdf_direction(&s, 1.5, v, w);
                    CHECK_CLOSE(fd * pdf, 1.0, 1e-5, 0, "%s, %s, view %g, u (%.17g, %.17g)", e->name,
                                SWEEP_SHAPES[i].name, SWEEP_VIEWS_DEG[j], u1, u2);
                    if (fabs(fd * pdf - 1) > worst) worst = fabs(fd * pdf - 1);
                    checked++;
                }
            }
        }
        CHECK(checked >= 500, "%s: only %ld points checked", e->name, checked);
        total += checked;
    }
    CHECK(total > 0, "no reflection sampler in the registry");
    printf("direction jacobians: %ld points, largest |J pdf - 1| = %.3g\n", total, worst);
}

/* Step 1e-6 in u: truncation ~1e-12 times the map's curvature, rounding ~1e-10 relative; we require 1e-5. Points
 * within 0.02 of the square's edges or of the seams of the concentric disk map (which some samplers use; the
 * registry does not say which, so they are skipped for all), and samples within 2 degrees of the horizon or of the
 * lune's rim (where the map's derivatives blow up), are skipped. */
static void jacobians(void **state)
{
    (void)state;
    rng r = {61};
    long checked = 0;
    double worst = 0.0;
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
        if (!is_map(e)) continue;
        long before = checked;
        for (int i = 0; i < SWEEP_NSHAPES; i++) {
            ggx_shape s;
            make_shape(&s, SWEEP_SHAPES[i].p);
            if (skip_shape(e, &s)) continue;
            for (int j = 0; j < views_of(e); j++) {
                ggx_vec3 v = sweep_view(SWEEP_VIEWS_DEG[j]);
                for (int t = 0; t < 60; t++) {
                    double u1 = rng_range(&r, 0.02, 0.98), u2 = rng_range(&r, 0.02, 0.98);
                    double a = 2 * u1 - 1, b = 2 * u2 - 1;
                    if (fabs(fabs(a) - fabs(b)) < 0.02 || fabs(a) < 0.02 || fabs(b) < 0.02) continue;
                    ggx_vec3 m = e->sample(&s, v, u1, u2);
                    double pdf = e->pdf(&s, v, m);
                    double mv = e->family == GGX_FAMILY_VNDF ? t_dot(m, v) : 1.0;
                    if (m.z < 0.035 || mv < 0.035) continue;
                    double fd = fd_solid_angle(e, &s, v, u1, u2, 1e-6);
                    CHECK_CLOSE(fd * pdf, 1.0, 1e-5, 0, "%s, %s, view %g, u (%.17g, %.17g)", e->name,
                                SWEEP_SHAPES[i].name, SWEEP_VIEWS_DEG[j], u1, u2);
                    if (fabs(fd * pdf - 1) > worst) worst = fabs(fd * pdf - 1);
                    checked++;
                }
            }
        }
        CHECK(checked - before >= 100, "%s: only %ld points checked", e->name, checked - before);
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
    int inverses_tested = 0;
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
        if (!e->inverse) continue;
        CHECK(is_map(e), "%s: an inverse for a sampler outside the NDF and VNDF families", e->name);
        inverses_tested++;
        for (int i = 0; i < SWEEP_NSHAPES; i++) {
            ggx_shape s;
            make_shape(&s, SWEEP_SHAPES[i].p);
            if (skip_shape(e, &s)) continue;
            for (int j = 0; j < SWEEP_NVIEWS; j++) {
                ggx_vec3 v = sweep_view(SWEEP_VIEWS_DEG[j]);
                for (int t = 0; t < 200; t++) {
                    double u1 = rng_range(&r, 0.01, 0.99), u2 = rng_range(&r, 0.01, 0.99);
                    ggx_vec3 m = e->sample(&s, v, u1, u2);
                    ggx_vec2 u = e->inverse(&s, v, m);
                    /* An angle phi = 2 pi u wraps at 0 and 1: distances are taken around the circle. With u in
                     * [0.01, 0.99] and the inverse in [0, 1], that can only excuse a wrap, never a wrong u. */
                    double d1 = fabs(u.x - u1), d2 = fabs(u.y - u2);
                    d1 = fmin(d1, 1 - d1), d2 = fmin(d2, 1 - d2);
                    CHECK(u.x >= 0 && u.x <= 1 && u.y >= 0 && u.y <= 1 && d1 < 1e-7 && d2 < 1e-7,
                          "%s, %s, view %g: u (%.12g, %.12g) -> (%.12g, %.12g)", e->name, SWEEP_SHAPES[i].name,
                          SWEEP_VIEWS_DEG[j], u1, u2, u.x, u.y);
                    checked++;
                }
            }
        }
    }
    CHECK(inverses_tested > 0, "no sampler with an inverse in the registry");
    /* Disk maps: inverse round trips, and the images fill the disk. */
    for (int t = 0; t < 100000; t++) {
        double u1 = rng_uniform(&r), u2 = rng_uniform(&r);
        ggx_vec2 d = ggx_disk_concentric(u1, u2), e = ggx_disk_polar(u1, u2);
        CHECK(d.x * d.x + d.y * d.y <= 1 + 1e-15 && e.x * e.x + e.y * e.y <= 1 + 1e-15, "inside the disk");
        ggx_vec2 ud = ggx_disk_concentric_inv(d), ue = ggx_disk_polar_inv(e);
        CHECK(fabs(ud.x - u1) < 1e-12 && fabs(ud.y - u2) < 1e-12, "concentric inverse (%g, %g)", u1, u2);
        CHECK(fabs(ue.x - u1) < 1e-12 && (fabs(ue.y - u2) < 1e-12 || fabs(fabs(ue.y - u2) - 1) < 1e-12),
              "polar inverse");
        checked++;
    }
    /* The samplers' own cos/sin of 2 pi t (a quarter-turn polynomial) against libm: the polar map at r = 1. */
    double worst = 0.0;
    for (int t = 0; t <= 1000000; t++) {
        double u = t / 1e6;
        ggx_vec2 d = ggx_disk_polar(1.0, u);
        worst = fmax(worst, fmax(fabs(d.x - cos(2 * GGX_PI * u)), fabs(d.y - sin(2 * GGX_PI * u))));
    }
    /* 1e-15: the libm reference takes cos of the rounded 2 pi t, itself off by up to ~7e-16 near t = 1. */
    CHECK(worst <= 1e-15, "sincos of 2 pi t: error %g", worst);
    printf("inverse maps: %ld round trips; sincos(2 pi t) largest error %.2g\n", checked, worst);
}

static double uniform_cb(void *st) { return rng_uniform((rng *)st); }

/* Defined behaviour at the edges, for every sampler of normals of the registry: v = n exactly and v.z = 1e-8 give
 * unit normals with pdf > 0; v on the horizon (and below it) gives the zero vector; u in {0, tiny, 1 - ulp, 1}
 * gives unit normals, never NaN. Rejection samplers: the zero vector below the horizon, unit normals at v = n and
 * v.z = 1e-8. */
static void edge_cases(void **state)
{
    (void)state;
    const double us[] = {0.0, 1e-300, 0.5, 1.0 - DBL_EPSILON / 2, 1.0};
    const ggx_vec3 views[] = {t_vec(0, 0, 1), t_dir(GGX_PI / 2 - 1e-8, 0.3), t_vec(0.6, 0.8, 0),
                              t_dir(GGX_PI / 2 + 0.1, 0.2)};
    long n = 0;
    for (int i = 0; i < SWEEP_NSHAPES; i++) {
        ggx_shape s;
        make_shape(&s, SWEEP_SHAPES[i].p);
        for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
            const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
            if (skip_shape(e, &s) || e->family == GGX_FAMILY_DIRECTION) continue;
            for (unsigned j = 0; j < 4; j++) {
                if (e->family == GGX_FAMILY_NDF && j > 0) break;
                int above = j < 2;
                if (e->family == GGX_FAMILY_REJECTION) {
                    rng r = {63};
                    unsigned trials;
                    ggx_vec3 m = e->sample_reject(&s, views[j], uniform_cb, &r, &trials);
                    n++;
                    CHECK(above ? fabs(t_dot(m, m) - 1) < 1e-12 && e->pdf(&s, views[j], m) > 0
                                : m.x == 0 && m.y == 0 && m.z == 0,
                          "%s, %s, view %u: m (%g,%g,%g)", e->name, SWEEP_SHAPES[i].name, j, m.x, m.y, m.z);
                    continue;
                }
                for (int a = 0; a < 5; a++) {
                    for (int b = 0; b < 5; b++) {
                        ggx_vec3 m = e->sample(&s, views[j], us[a], us[b]);
                        n++;
                        if (!above) {
                            CHECK(m.x == 0 && m.y == 0 && m.z == 0, "%s: view %u on or below the horizon must give 0",
                                  e->name, j);
                            continue;
                        }
                        CHECK(fabs(t_dot(m, m) - 1) < 1e-12 && m.z >= 0 && e->pdf(&s, views[j], m) > 0,
                              "%s, %s, view %u, u (%g, %g): m (%g,%g,%g)", e->name, SWEEP_SHAPES[i].name, j, us[a],
                              us[b], m.x, m.y, m.z);
                    }
                }
            }
        }
        /* v = n: the VNDF is the NDF's pdf D(m) m.z. */
        ggx_vec3 m = ggx_sample_vndf(&s, views[0], 0.37, 0.81);
        CHECK_CLOSE(ggx_pdf_vndf(&s, views[0], m), ggx_pdf_ndf(&s, m), 1e-12, 0, "v = n");
    }
    printf("edge cases: %ld samples checked\n", n);
}

/* The registry's pdf of each sampler of normals is its family's: ggx_pdf_ndf (whatever the view) for NDF samplers,
 * ggx_pdf_vndf for VNDF and rejection samplers; bit for bit, at random shapes, views away from n (where the two
 * agree) and normals. */
static void registry_pdfs(void **state)
{
    (void)state;
    rng r = {65};
    for (int t = 0; t < 2000; t++) {
        ggx_shape s;
        make_shape(&s, random_shape(&r, 0.5));
        ggx_vec3 v = random_view(&r), m = random_view(&r);
        for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
            const ggx_sampler_info *e = ggx_sampler_get((ggx_sampler_id)id);
            if (e->family == GGX_FAMILY_DIRECTION) continue;
            double want = e->family == GGX_FAMILY_NDF ? ggx_pdf_ndf(&s, m) : ggx_pdf_vndf(&s, v, m);
            CHECK(e->pdf(&s, v, m) == want,
                  "%s: registry pdf %.17g, family pdf %.17g at v (%.17g, %.17g, %.17g), "
                  "m (%.17g, %.17g, %.17g)",
                  e->name, e->pdf(&s, v, m), want, v.x, v.y, v.z, m.x, m.y, m.z);
        }
    }
}

/* The defaults are the registry's samplers they name: ggx_sample_ndf is stretch, ggx_sample_vndf is caps (bit for
 * bit, so the sweeps of those samplers cover them). */
static void defaults(void **state)
{
    (void)state;
    const ggx_sampler_info *ndf = ggx_sampler_get(GGX_SAMPLER_STRETCH), *vndf = ggx_sampler_get(GGX_SAMPLER_CAPS);
    rng r = {64};
    for (int t = 0; t < 10000; t++) {
        ggx_shape s;
        make_shape(&s, random_shape(&r, 0.5));
        ggx_vec3 v = random_view(&r);
        double u1 = rng_uniform(&r), u2 = rng_uniform(&r);
        ggx_vec3 a = ggx_sample_ndf(&s, u1, u2), b = ndf->sample(&s, v, u1, u2);
        ggx_vec3 c = ggx_sample_vndf(&s, v, u1, u2), d = vndf->sample(&s, v, u1, u2);
        CHECK(a.x == b.x && a.y == b.y && a.z == b.z && c.x == d.x && c.y == d.y && c.z == d.z,
              "defaults differ from stretch / caps at u (%.17g, %.17g), v (%.17g, %.17g, %.17g)", u1, u2, v.x, v.y,
              v.z);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(jacobians),     cmocka_unit_test(inverses),
                                       cmocka_unit_test(edge_cases),    cmocka_unit_test(defaults),
                                       cmocka_unit_test(registry_pdfs), cmocka_unit_test(direction_jacobians)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
