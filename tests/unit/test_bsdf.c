/* Scattering: BRDF reciprocity and albedo, the rough-dielectric BSDF's generalised reciprocity, adjoint and
 * energy, the half-vector Jacobians by finite differences, and Snell's law. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "testlib.h"

static ggx_vec3 random_dir_sphere(rng *r)
{
    ggx_vec3 v = random_view(r);
    if (rng_uniform(r) < 0.5) v.z = -v.z;
    return v;
}

/* Walter eq 4 with eq 5 is symmetric in (wi, wo): relative 1e-12 covers the few roundings that differ between
 * the two orders (the half vector and the G1 product are computed identically up to operand order). */
static void brdf_reciprocity(void **state)
{
    (void)state;
    rng r = {41};
    ggx_fresnel f;
    CHECK(ggx_fresnel_conductor(&f, 0.2, 3.9) == GGX_OK, "fresnel");
    int nonzero = 0;
    for (int i = 0; i < 100000; i++) {
        shape_params p = random_shape(&r, 0.6);
        ggx_shape s;
        make_shape(&s, p);
        ggx_vec3 a = random_view(&r), b = random_view(&r);
        double fab = ggx_brdf_eval(&s, &f, a, b), fba = ggx_brdf_eval(&s, &f, b, a);
        CHECK_CLOSE(fab, fba, 1e-12, 0, "(%g,%g,%g,%g,%g) a (%.17g,%.17g,%.17g) b (%.17g,%.17g,%.17g)", p.ax, p.ay,
                    p.tx, p.ty, p.tz, a.x, a.y, a.z, b.x, b.y, b.z);
        nonzero += fab > 0;
        ggx_vec3 below = t_vec(b.x, b.y, -b.z);
        CHECK(ggx_brdf_eval(&s, &f, a, below) == 0.0 && ggx_brdf_eval(&s, &f, below, a) == 0.0, "below horizon");
    }
    CHECK(nonzero > 90000, "only %d nonzero BRDF values", nonzero);
}

/* Directional albedo of the BRDF with F = 1 for fixed wi, integrated over the half vector h (cut at wi.h >= 0):
 * the integral of f(wi, wo) wo.z d wo = the integral of f(wi, wo(h)) wo.z / J(h) dh with J = d omega_h / d omega_o
 * from ggx_jacobian_reflect (itself checked by finite differences below). <= 1 for every shape and view; for
 * unskewed shapes the deficit is the masking loss, so it must stay above 0.5 at moderate roughness (a missing
 * factor 4 or a missing G1 would be caught). */
typedef struct alb_ctx {
    const ggx_shape *s;
    const ggx_fresnel *f;
    ggx_vec3 wi;
    double eta;
    int transmit; /* BSDF: 0 reflection part, 1 transmission part */
} alb_ctx;
static double brdf_albedo_f(ggx_vec3 h, void *vc)
{
    alb_ctx *c = vc;
    ggx_vec3 wo = ggx_reflect(c->wi, h);
    if (!(wo.z > 0)) return 0.0;
    return ggx_brdf_eval(c->s, c->f, c->wi, wo) * wo.z / ggx_jacobian_reflect(wo, h);
}
static void brdf_albedo(void **state)
{
    (void)state;
    rng r = {42};
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    double highest = 0.0;
    for (int i = 0; i < 24; i++) {
        int skewed = i >= 12;
        shape_params p = random_shape(&r, skewed ? 0.6 : 0.0);
        ggx_shape s;
        make_shape(&s, p);
        alb_ctx c = {&s, &one, random_view(&r), 0, 0};
        if (i % 6 == 0) c.wi = t_vec(0, 0, 1);
        double a = quad_hemisphere(&s, brdf_albedo_f, &c, &c.wi, 1, 1e-6, NULL);
        CHECK(a <= 1.0 + 1e-5, "albedo %.12g > 1: (%g,%g,%g,%g,%g) wi (%g,%g,%g)", a, p.ax, p.ay, p.tx, p.ty, p.tz,
              c.wi.x, c.wi.y, c.wi.z);
        if (a > highest) highest = a;
        if (!skewed && c.wi.z > 0.5 && p.ax < 0.5 && p.ay < 0.5) CHECK(a > 0.9, "albedo %.6f too low", a);
    }
    printf("BRDF albedo with F = 1: highest %.9f over 24 shapes and views\n", highest);
}

/* Generalised reciprocity of the radiance BSDF: f(wi, wo) / eta_o^2 = f(wo, wi) / eta_i^2 on all four side
 * combinations, and the importance mode is the adjoint f*(wi, wo) = f(wo, wi). */
static void bsdf_reciprocity(void **state)
{
    (void)state;
    rng r = {43};
    int counts[2] = {0, 0};
    for (int i = 0; i < 100000; i++) {
        shape_params p = random_shape(&r, i % 2 ? 0.6 : 0.0);
        ggx_shape s;
        make_shape(&s, p);
        double eta = i % 3 == 0 ? 1.0 / 1.5 : 1.5;
        ggx_vec3 a = random_dir_sphere(&r), b = random_dir_sphere(&r);
        double ea = a.z > 0 ? 1.0 : eta, eb = b.z > 0 ? 1.0 : eta;
        double fab = ggx_bsdf_eval(&s, eta, a, b, GGX_RADIANCE), fba = ggx_bsdf_eval(&s, eta, b, a, GGX_RADIANCE);
        CHECK_CLOSE(fab / (eb * eb), fba / (ea * ea), 1e-10, 0, "eta %g a (%.17g,%.17g,%.17g) b (%.17g,%.17g,%.17g)",
                    eta, a.x, a.y, a.z, b.x, b.y, b.z);
        CHECK(ggx_bsdf_eval(&s, eta, a, b, GGX_IMPORTANCE) == fba, "adjoint");
        if (fab > 0) counts[(a.z > 0) != (b.z > 0)]++;
    }
    CHECK(counts[0] > 10000 && counts[1] > 5000, "reflect %d transmit %d nonzero", counts[0], counts[1]);
}

/* Energy of the rough dielectric for fixed wi (above and below the interface): the integral over wo of
 * f(wi, wo) |wo.z| <= 1, as the sum of a reflection and a transmission integral over h. With moderate roughness
 * and wi near the normal, masking losses are small, so it must be > 0.9: dropping eta_o^2 from eq 21 (the
 * importance form used as radiance) gives ~0.47 entering glass and fails. */
static double bsdf_albedo_f(ggx_vec3 h, void *vc)
{
    alb_ctx *c = vc;
    ggx_vec3 wi = c->wi, wo;
    double eta_i = wi.z > 0 ? 1.0 : c->eta;
    double eta_o = c->transmit ? (wi.z > 0 ? c->eta : 1.0) : eta_i;
    if (c->transmit) {
        if (!ggx_refract(wi, h, eta_o / eta_i, &wo)) return 0.0;
        if (!((wo.z > 0) != (wi.z > 0))) return 0.0;
        return ggx_bsdf_eval(c->s, c->eta, wi, wo, GGX_RADIANCE) * fabs(wo.z) /
               ggx_jacobian_refract(wi, wo, h, eta_i, eta_o);
    }
    wo = ggx_reflect(wi, h);
    if (!((wo.z > 0) == (wi.z > 0))) return 0.0;
    return ggx_bsdf_eval(c->s, c->eta, wi, wo, GGX_RADIANCE) * fabs(wo.z) / ggx_jacobian_reflect(wo, h);
}
static void bsdf_energy(void **state)
{
    (void)state;
    rng r = {44};
    for (int i = 0; i < 16; i++) {
        shape_params p = random_shape(&r, i >= 8 ? 0.5 : 0.0);
        int near_normal = i % 4 <= 1; /* from above (i even) and from inside (i odd) */
        if (near_normal) p.ax = p.ay = 0.2;
        ggx_shape s;
        make_shape(&s, p);
        ggx_vec3 wi = near_normal ? t_dir(i % 8 < 4 ? 0.2 : 0.5, 1.0) : random_view(&r);
        if (i % 2) wi.z = -wi.z; /* from inside */
        ggx_vec3 flip = wi.z > 0 ? wi : t_scale(wi, -1);
        alb_ctx c = {&s, NULL, wi, 1.5, 0};
        double refl = quad_hemisphere(&s, bsdf_albedo_f, &c, &flip, 1, 1e-6, NULL);
        c.transmit = 1;
        double tran = quad_hemisphere(&s, bsdf_albedo_f, &c, &flip, 1, 1e-6, NULL);
        CHECK(refl + tran <= 1.0 + 1e-5, "albedo %.9f + %.9f > 1 (%g,%g,%g,%g,%g) wi (%g,%g,%g)", refl, tran, p.ax,
              p.ay, p.tx, p.ty, p.tz, wi.x, wi.y, wi.z);
        if (near_normal && i < 8) CHECK(refl + tran > 0.9, "albedo %.6f + %.6f too low, wi.z %g", refl, tran, wi.z);
        if (near_normal)
            printf("BSDF energy, alpha 0.2, skew %s, wi.z %+.3f: R %.6f + T %.6f = %.6f\n", i >= 8 ? "0.5" : "0", wi.z,
                   refl, tran, refl + tran);
    }
}

/* Solid-angle Jacobian of a map g: S^2 -> S^2 at h by central differences in a tangent frame: the ratio of the
 * areas spanned by the image and the preimage of two small steps. */
typedef int (*sphere_map)(ggx_vec3 h, const void *ctx, ggx_vec3 *out);
static double fd_jacobian(sphere_map g, const void *ctx, ggx_vec3 h)
{
    const double e = 1e-6;
    ggx_vec3 t1, t2, o[4], in[4];
    t_frame(h, &t1, &t2);
    const double d[4][2] = {{e, 0}, {-e, 0}, {0, e}, {0, -e}};
    for (int k = 0; k < 4; k++) {
        in[k] = t_normalize(t_add(h, t_add(t_scale(t1, d[k][0]), t_scale(t2, d[k][1]))));
        if (!g(in[k], ctx, &o[k])) return NAN;
    }
    ggx_vec3 da = t_add(o[0], t_scale(o[1], -1)), db = t_add(o[2], t_scale(o[3], -1));
    ggx_vec3 ha = t_add(in[0], t_scale(in[1], -1)), hb = t_add(in[2], t_scale(in[3], -1));
    ggx_vec3 co = t_cross(da, db), ch = t_cross(ha, hb);
    return sqrt(t_dot(co, co) / t_dot(ch, ch)); /* d omega_o / d omega_h */
}
typedef struct map_ctx {
    ggx_vec3 wi;
    double eta;
} map_ctx;
static int map_reflect(ggx_vec3 h, const void *vc, ggx_vec3 *out)
{
    *out = ggx_reflect(((const map_ctx *)vc)->wi, h);
    return 1;
}
static int map_refract(ggx_vec3 h, const void *vc, ggx_vec3 *out)
{
    const map_ctx *c = vc;
    return ggx_refract(c->wi, h, c->eta, out);
}

/* Walter 2007 eq 14 and 17 against finite differences (step 1e-6 in h: truncation ~1e-12, rounding ~1e-10
 * relative, so 1e-6 relative is a safe bound; a wrong factor such as a missing eta_o^2 is off by 125 %). Also
 * Snell's law and the generalised half vector recovering h. */
static void jacobians_and_snell(void **state)
{
    (void)state;
    rng r = {45};
    for (int i = 0; i < 5000; i++) {
        ggx_vec3 wi = random_view(&r), h = t_dir(acos(rng_range(&r, 0.05, 1)), rng_range(&r, -GGX_PI, GGX_PI));
        if (t_dot(wi, h) < 1e-3) continue;
        map_ctx c = {wi, 0};
        ggx_vec3 wo = ggx_reflect(wi, h);
        CHECK_CLOSE(1.0 / ggx_jacobian_reflect(wo, h), fd_jacobian(map_reflect, &c, h), 1e-6, 0, "reflect");
        double eta = i % 2 ? 1.5 : 1 / 1.5;
        if (i % 4 >= 2) wi = t_scale(wi, -1), h = t_scale(h, 1); /* from inside: wi below, h still up */
        c.wi = wi;
        c.eta = eta;
        ggx_vec3 wt;
        if (!ggx_refract(wi, h, eta, &wt)) continue;
        double eta_i = 1.0, eta_o = eta;
        /* Near the critical angle the map's derivative diverges and differences lose their accuracy. */
        if (fabs(t_dot(wt, h)) < 0.1) continue;
        CHECK_CLOSE(1.0 / ggx_jacobian_refract(wi, wt, h, eta_i, eta_o), fd_jacobian(map_refract, &c, h), 1e-6, 0,
                    "refract eta %g", eta);
        /* Snell: eta_i sin_i = eta_o sin_t, tangential parts opposite, unit length, far side of the facet. */
        double ci = t_dot(wi, h), ct = t_dot(wt, h);
        CHECK_CLOSE(sqrt(1 - ci * ci), eta * sqrt(1 - ct * ct), 1e-12, 1e-14, "Snell");
        CHECK(ci * ct < 0, "far side");
        CHECK_CLOSE(t_dot(wt, wt), 1.0, 4e-15, 0, "unit");
        ggx_vec3 hh = ggx_half_refract(wi, wt, eta_i, eta_o);
        ggx_vec3 hu = h.z >= 0 ? h : t_scale(h, -1);
        CHECK_CLOSE(t_dot(hh, hu), 1.0, 1e-12, 0, "half vector recovers h");
    }
    ggx_vec3 out;
    CHECK(!ggx_refract(t_dir(1.2, 0), t_vec(0, 0, 1), 1 / 1.5, &out) && out.z == 0, "TIR reported");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(brdf_reciprocity), cmocka_unit_test(brdf_albedo),         cmocka_unit_test(bsdf_reciprocity),
        cmocka_unit_test(bsdf_energy),      cmocka_unit_test(jacobians_and_snell),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
