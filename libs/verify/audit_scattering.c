/* The seed audit: masking and scattering (blog Part 1's Smith integral, Walter eq 7 and 49-50, Engstad's BRDF and
 * G approximation), each checked by an independent evaluation: Smith's integral by quadrature in slope space, the
 * transmission masking by the albedo of the BSDF built with it, the weight from the BRDF and the pdf.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "audit_internal.h"

/* ---- blog Part 1: Lambda(v) = (1/mu) int_mu^inf (q - mu) P2(q) dq, P2 the marginal of P22 ----
 * The slope s of a facet along the azimuth e = (cos phi, sin phi) of v (slopes x~ = -mx/mz as ggx_p22 takes them):
 * m.v < 0 exactly where s > mu = cot theta_v, and P2 is the marginal of s; the seed writes the marginal of the y
 * slope q, which is s for phi = 90 degrees only. The double integral over the slope plane, int int (s - mu)+ P22,
 * becomes an integral over normals with P22 dx dy = D(m) m_z d omega and (s - mu) m_z sin theta = -(m.v): Lambda =
 * int (-m.v)+ D(m) d omega / cos theta, evaluated by quadrature (the lobe-following rule of quad_hemisphere; in
 * slope space the narrow ridges of anisotropic shapes need more panels than the adaptive rule has), independently
 * of the closed form ggx_lambda that it is compared with. */
typedef struct smith_ctx {
    const ggx_shape *s;
    ggx_vec3 v;
} smith_ctx;
static double smith_f(ggx_vec3 m, void *vc)
{
    const smith_ctx *c = vc;
    return -t_dot(m, c->v) * ggx_ndf(c->s, m);
}
static double smith_lambda(const ggx_shape *s, double theta, double phi)
{
    smith_ctx c = {s, t_dir(theta, phi)};
    ggx_vec3 cut = t_scale(c.v, -1);
    return quad_hemisphere(s, smith_f, &c, &cut, 1, 1e-12, NULL) / cos(theta);
}
static void smith_row(audit_row *r, int k, const ggx_shape *s)
{
    static const double thetas[3] = {0.5, 1.0, 1.4}, phis[4] = {0, 0.7853981633974483, 1.5707963267948966, 2.3};
    double lit = 0, cor = 0, lit_phi = 0, cor_th = 0, cor_phi = 0, blog = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            ggx_vec3 v = t_dir(thetas[i], phis[j]);
            double g = 1 / (1 + ggx_lambda(s, v)); /* the ellipsoid's G1 without the min (eq 32) */
            double gl = 1 / (1 + smith_lambda(s, thetas[i], 0.5 * GGX_PI)),
                   gc = 1 / (1 + smith_lambda(s, thetas[i], phis[j]));
            if (fabs(gl - g) > lit) lit = fabs(gl - g), lit_phi = phis[j];
            if (fabs(gc - g) > cor) cor = fabs(gc - g), cor_th = thetas[i], cor_phi = phis[j];
            /* blog Part 2's G1 as a ratio of projected areas, against Smith's */
            double av = sqrt(t_dot(t_matvec((const double(*)[3])s->a, v), t_matvec((const double(*)[3])s->a, v)));
            blog = fmax(blog, fabs(2 * s->an_len * v.z / (av + s->an_len * v.z) - gc));
        }
    if (lit < 1e-7)
        au_set(r, k, AUDIT_HOLDS, "G1 = 1 / (1 + Lambda) by the quadrature equals eq 32's within %.1e at 12 views",
               lit);
    else if (cor < 1e-7)
        au_set(
            r, k, AUDIT_CORRECTED,
            "as written (the y slope's marginal) it is Lambda at phi_v = 90 degrees only: G1 off "
            "by %.3g at phi %.2f rad; with P2 the marginal of the slope along v's azimuth it holds within %.1e at 12 "
            "views",
            lit, lit_phi, cor);
    else
        au_set(r, k, AUDIT_FAILS,
               "even with P2 along v's azimuth, G1 = 1 / (1 + Lambda) differs from the ellipsoid's "
               "(eq 32) by %.3g at theta %.1f, phi %.2f rad: Smith's integral counts the facets facing away from v, "
               "which the skewed ellipsoid's mean normal (not n) shifts",
               cor, cor_th, cor_phi);
    au_append(r, k, "; blog Part 2's ratio of projected areas against Smith's G1: %.1e", blog);
}

/* ---- Walter eq 7: G for transmission from G1 of the directions flipped to the upper side ----
 * Checked in the BTDF it is made for: Walter 2007 eq 21 written out here with eq 7's G (h of eq 16 by hand, the
 * Fresnel term the library's) against ggx_bsdf_eval at transmitted pairs, from above and from below; without the
 * sign flip G1(omega, h) of a direction below the horizon is 0, so the transmission would vanish (the control). */
static double btdf_eq21(const ggx_shape *s, double eta, ggx_vec3 wi, ggx_vec3 wo, int flip)
{
    double ei = wi.z > 0 ? 1 : eta, eo = wo.z > 0 ? 1 : eta; /* eta = eta_below / eta_above */
    ggx_vec3 h = t_normalize(t_add(t_scale(wi, -ei), t_scale(wo, -eo)));
    if (h.z < 0) h = t_scale(h, -1);
    double ih = t_dot(wi, h), oh = t_dot(wo, h);
    if (!(ih * oh < 0)) return 0; /* a transmitted pair has wi and wo on opposite sides of the facet */
    ggx_vec3 a = flip && wi.z < 0 ? t_scale(wi, -1) : wi, b = flip && wo.z < 0 ? t_scale(wo, -1) : wo;
    double G = ggx_g1(s, a, h) * ggx_g1(s, b, h), d = ei * ih + eo * oh;
    return fabs(ih * oh) * eo * eo * (1 - ggx_fresnel_dielectric_eval(fabs(ih), eo / ei)) * ggx_ndf(s, h) * G /
           (fabs(wi.z * wo.z) * d * d);
}
static void eq7_row(audit_row *r, int k, const ggx_shape *s)
{
    rng g = {161};
    double worst = 0, lib_sum = 0, noflip_sum = 0;
    int pairs = 0;
    for (int i = 0; i < 20000; i++) {
        ggx_vec3 wi = au_random_upper(&g), wo = au_random_upper(&g);
        if (i & 1) wi.z = -wi.z; /* light from below */
        else wo.z = -wo.z;
        double eta = i % 4 < 2 ? 1.5 : 1 / 1.5, lib = ggx_bsdf_eval(s, eta, wi, wo, GGX_RADIANCE);
        double lit = btdf_eq21(s, eta, wi, wo, 1);
        if (lib > 0 || lit > 0) worst = fmax(worst, fabs(lit - lib) / fmax(lit, lib)), pairs++;
        lib_sum += lib, noflip_sum += btdf_eq21(s, eta, wi, wo, 0);
    }
    /* tolerance 1e-6: near total internal reflection 1 - F is small and carries the rounding of F relatively */
    au_set(r, k, worst < 1e-6 ? AUDIT_HOLDS : AUDIT_FAILS,
           "Walter 2007 eq 21 with eq 7's G against ggx_bsdf_eval at %d "
           "transmitted pairs from both sides (eta 1.5 and 1/1.5): largest relative difference %.1e; without the sign "
           "flip the transmission sums to %.3g of its value (G1 of a direction below the horizon is 0)",
           pairs, worst, lib_sum > 0 ? noflip_sum / lib_sum : 0.0);
}

/* ---- Walter eq 49-50: the weight of a reflection sample, f_r |omega.n| / p_o, in closed form ---- */
static double err_weight(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    const ggx_fresnel *f = ctx;
    const ggx_vec3 n = {0, 0, 1};
    ggx_vec3 psi = au_random_upper(g);
    ggx_sample smp = ggx_sample_brdf(&K->s, f, psi, rng_uniform(g), rng_uniform(g));
    snprintf(at, nat, "psi = (%.3g, %.3g, %.3g)", psi.x, psi.y, psi.z);
    if (smp.event == GGX_EVENT_INVALID) return 0; /* below the horizon: no weight (row "below") */
    ggx_vec3 om = smp.w, m = ggx_half_reflect(psi, om);
    double w50 = ggx_g1(&K->s, psi, m) * ggx_g1(&K->s, om, m) * ggx_fresnel_eval(f, t_dot(psi, m)) *
                 ggx_lune_area(&K->s, psi, n) / (fabs(psi.z) * ggx_projected_area(&K->s, n));
    double w49 = ggx_brdf_eval(&K->s, f, psi, om) * fabs(om.z) / ggx_pdf_brdf(&K->s, psi, om);
    return fmax(fabs(smp.weight / w50 - 1), fabs(w49 / w50 - 1));
}

/* ---- Engstad: G(v, omega) = 1 / (1 + Lambda(v) + Lambda(omega)) >= G1(v) G1(omega), as Lambda >= 0 ---- */
static double err_g_approx(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    ggx_vec3 v = au_view_near_n(g), w = au_random_upper(g);
    double lv = ggx_lambda(&K->s, v), lw = ggx_lambda(&K->s, w), g2 = 1 / (1 + lv + lw);
    double g11 = 1 / ((1 + lv) * (1 + lw));
    snprintf(at, nat, "Lambda %.3g and %.3g: G %.5g < G1 G1 %.5g", lv, lw, g2, g11);
    return fmax(0, g11 / g2 - 1); /* how far G falls below the product */
}

/* ---- Engstad: f_r = F G D(h) / (4 (v.n)(omega.n)), zero unless both are above ---- */
static double err_brdf_form(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    const ggx_fresnel *f = ctx;
    ggx_vec3 v = au_random_upper(g), w = au_random_upper(g);
    if (rng_uniform(g) < 0.2) w.z = -w.z;
    ggx_vec3 h = t_normalize(t_add(v, w));
    double lit = v.z > 0 && w.z > 0
                     ? ggx_fresnel_eval(f, t_dot(v, h)) * ggx_g2(&K->s, v, w, h) * ggx_ndf(&K->s, h) / (4 * v.z * w.z)
                     : 0.0;
    double lib = ggx_brdf_eval(&K->s, f, v, w);
    snprintf(at, nat, "v = (%.3g, %.3g, %.3g), omega = (%.3g, %.3g, %.3g)", v.x, v.y, v.z, w.x, w.y, w.z);
    return lit == 0 && lib == 0 ? 0 : fabs(lit - lib) / fmax(lit, lib);
}

/* ---- Engstad: a normal facing away from v (v.m < 0, m.n > 0, v.n > 0) reflects v below the horizon ---- */
static double err_reflect(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    long *away = ctx;
    ggx_vec3 v = au_random_upper(g), m = ggx_sample_ndf(&K->s, rng_uniform(g), rng_uniform(g));
    double vm = t_dot(v, m);
    snprintf(at, nat, "v = (%.3g, %.3g, %.3g), m = (%.3g, %.3g, %.3g)", v.x, v.y, v.z, m.x, m.y, m.z);
    if (!(vm < 0)) return 0;
    if (!K->searching) (*away)++;
    ggx_vec3 om = t_add(t_scale(m, 2 * vm), t_scale(v, -1));
    return om.z < 0 ? 0 : 1 + om.z;
}

void au_rows_scattering(const au_ctx *c)
{
    audit_row *r;
    ggx_fresnel glass;
    ggx_fresnel_dielectric(&glass, 1.5);

    r = au_add(c->rows, c->nr, "smith-integral",
               "G1 = 1 / (1 + Lambda), Lambda(v) = (1/mu) int_mu^inf (q - mu) P2(q) dq, "
               "P2(q) = int P22(p, q) dp, mu = cot theta_v",
               SEED_BLOG1, "eqnarray after 'Smith model'", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) smith_row(r, k, &c->sh[k]);

    r = au_add(c->rows, c->nr, "eq7-transmission",
               "for transmission G = G1(sgn(psi.n) psi, m) G1(sgn(omega.n) omega, m) "
               "(eq 5 with the directions flipped to the upper side)",
               SEED_WALTER, "eq 7", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) eq7_row(r, k, &c->sh[k]);

    r = au_add(c->rows, c->nr, "weight-formula",
               "the reflection sample's weight f_r |omega.n| / p_o = G1(psi, m) G1(omega, m) "
               "F(psi.m) A_l(psi, n) / (|psi.n| A_e(n))",
               SEED_WALTER, "eq 49-50", AUDIT_SCOPE_ANY);
    au_kin_row(c, r, 0, err_weight, &glass, 200, 1e-12,
               "ggx_sample_brdf's weight and f_r |omega.n| / pdf against eq "
               "50 (Fresnel 1.5):");

    r = au_add(c->rows, c->nr, "g-approx",
               "G(v, omega) = 1 / (1 + Lambda(v) + Lambda(omega)) is approximated by G1(v) "
               "G1(omega), never above it (Lambda >= 0)",
               SEED_VNDF, "vGGX Sampling", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        au_verdict_kin(r, k, &c->sh[k], c->A[k], err_g_approx, NULL, 200, 1e-12,
                       "G1 G1 / G - 1 where the product exceeds G (Lambda >= 0 makes it an identity):");
        if (c->sh[k].kind == GGX_SHAPE_SKEWED)
            au_append(r, k,
                      "; Lambda here is eq 32 without Walter's min, negative at some views of a skewed shape: with "
                      "Lambda clipped at 0 (the min) it holds");
    }

    r = au_add(c->rows, c->nr, "brdf-form",
               "f_r = F G D(h) / (4 (v.n)(omega.n)), h = normalize(v + omega), zero unless v.n "
               "> 0 and omega.n > 0 (Walter eq 4)",
               SEED_VNDF, "vGGX Sampling", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        au_verdict_kin(r, k, &c->sh[k], c->A[k], err_brdf_form, &glass, 200, 1e-13,
                       "with G of eq 5 against ggx_brdf_eval (a fifth of the pairs below the horizon; a consistency "
                       "check of the form):");
        /* the seed's own G, 1 / (1 + Lambda(v) + Lambda(omega)), against eq 5's product */
        rng g = {171};
        double most = 0;
        for (int i = 0; i < 2000; i++) {
            ggx_vec3 v = au_random_upper(&g), w = au_random_upper(&g), h = t_normalize(t_add(v, w));
            double sep = ggx_g2(&c->sh[k], v, w, h);
            if (sep > 0) most = fmax(most, 1 / (1 + ggx_lambda(&c->sh[k], v) + ggx_lambda(&c->sh[k], w)) / sep - 1);
        }
        au_append(r, k,
                  "; with the seed's G = 1 / (1 + Lambda(v) + Lambda(omega)) f_r is up to %.0f %% above eq 5's "
                  "(row g-approx)",
                  100 * most);
    }

    r = au_add(c->rows, c->nr, "reflect-below",
               "omega = 2 (v.m) m - v; an NDF sample m with v.m < 0 (m.n > 0, v.n > 0) "
               "reflects v below the horizon",
               SEED_VNDF, "vGGX Sampling", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        long away = 0;
        au_verdict_kin(r, k, &c->sh[k], c->A[k], err_reflect, &away, 500, 0,
                       "omega.z of the back-facing samples (a sign argument: 2 (v.m) m.z - v.z < 0):");
        au_append(r, k, " (%ld of the %d NDF samples face away from v)", away, 500 * AU_KIN);
    }
}
