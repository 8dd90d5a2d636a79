/* Half vectors, their Jacobians, and the microfacet BRDF and rough-dielectric BSDF.
 * SPDX-License-Identifier: MIT */
#include "internal.h"

static ggx_vec3 normalize_up(ggx_vec3 h)
{
    double l = v3_len(h);
    if (!(l > 0.0) || !isfinite(l)) return v3(0.0, 0.0, 0.0);
    return v3_scale(h, (h.z < 0.0 ? -1.0 : 1.0) / l);
}

ggx_vec3 ggx_half_reflect(ggx_vec3 wi, ggx_vec3 wo) { return normalize_up(v3_add(wi, wo)); }

ggx_vec3 ggx_half_refract(ggx_vec3 wi, ggx_vec3 wo, double eta_i, double eta_o)
{
    return normalize_up(v3_neg(v3_add(v3_scale(wi, eta_i), v3_scale(wo, eta_o)))); /* Walter 2007 eq 16 */
}

double ggx_jacobian_reflect(ggx_vec3 wo, ggx_vec3 h)
{
    return finite_or_zero(1.0 / (4.0 * fabs(v3_dot(wo, h))));
}

double ggx_jacobian_refract(ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 h, double eta_i, double eta_o)
{
    double li = v3_dot(wi, wi);
    if (!(li > 0.0 && li < HUGE_VAL)) return 0.0; /* wi enters only through the denominator */
    double d = eta_i * v3_dot(wi, h) + eta_o * v3_dot(wo, h);
    return finite_or_zero(eta_o * eta_o * fabs(v3_dot(wo, h)) / (d * d));
}

ggx_vec3 ggx_reflect(ggx_vec3 w, ggx_vec3 m) { return v3_sub(v3_scale(m, 2.0 * v3_dot(w, m)), w); }

int ggx_refract(ggx_vec3 w, ggx_vec3 m, double eta, ggx_vec3 *out)
{
    *out = v3(0.0, 0.0, 0.0);
    double c = v3_dot(w, m);
    if (!(eta > 0.0 && eta < HUGE_VAL) || !(c != 0.0) || !isfinite(c)) return 0;
    if (c < 0.0) { /* orient the facet towards the incident side */
        m = v3_neg(m);
        c = -c;
    }
    double sin2_t = (1.0 - c * c) / eta / eta; /* eta^2 may underflow */
    if (sin2_t >= 1.0) return 0; /* total internal reflection */
    double ct = sqrt(1.0 - sin2_t);
    ggx_vec3 t = v3_sub(v3_scale(m, c / eta - ct), v3_scale(w, 1.0 / eta));
    /* Unit in exact arithmetic; for a large index ratio the terms cancel and lose eta times the rounding. */
    double l = v3_len(t);
    if (!(l > 0.0 && l < HUGE_VAL)) return 0;
    *out = v3_scale(t, 1.0 / l);
    return 1;
}

double ggx_brdf_eval(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo)
{
    if (!(wi.z > 0.0 && wo.z > 0.0)) return 0.0;
    ggx_vec3 h = ggx_half_reflect(wi, wo);
    double hi = v3_dot(wi, h);
    if (!(hi > 0.0)) return 0.0; /* wi + wo = 0 cannot happen above the horizon; NaN can */
    double g = ggx_g2(s, wi, wo, h);
    if (g == 0.0) return 0.0;
    return finite_or_zero(ggx_ndf(s, h) * g * ggx_fresnel_eval(f, hi) / (4.0 * wi.z * wo.z)); /* eq 4 */
}

/* f(wi -> wo) in the radiance convention. */
static double bsdf_radiance(const ggx_shape *s, double eta, ggx_vec3 wi, ggx_vec3 wo)
{
    if (!(eta > 0.0 && eta < HUGE_VAL)) return 0.0;
    if (!(wi.z != 0.0 && wo.z != 0.0)) return 0.0; /* also NaN */
    int wi_up = wi.z > 0.0, wo_up = wo.z > 0.0;
    double eta_i = wi_up ? 1.0 : eta, eta_o = wo_up ? 1.0 : eta;
    ggx_vec3 ui = wi_up ? wi : v3_neg(wi), uo = wo_up ? wo : v3_neg(wo); /* eq 7: sgn(w.n) w */
    double cos_i = fabs(wi.z), cos_o = fabs(wo.z);
    double eta_rel = wi_up ? eta : 1.0 / eta; /* index across the interface relative to wi's side */

    if (wi_up == wo_up) { /* reflection on wi's side */
        ggx_vec3 h = ggx_half_reflect(wi, wo);
        double g = ggx_g2(s, ui, uo, h); /* X+ terms reject facets that face away from either direction */
        if (g == 0.0) return 0.0;
        /* |wi.h| = |wo.h| in exact arithmetic; their mean makes f exactly reciprocal in floating point too. */
        double F = ggx_fresnel_dielectric_eval(0.5 * (fabs(v3_dot(wi, h)) + fabs(v3_dot(wo, h))), eta_rel);
        return finite_or_zero(F * ggx_ndf(s, h) * g / (4.0 * cos_i * cos_o));
    }

    ggx_vec3 h = ggx_half_refract(wi, wo, eta_i, eta_o);
    double hi = v3_dot(wi, h), ho = v3_dot(wo, h);
    double g = ggx_g2(s, ui, uo, h); /* with h.z >= 0, requires wi and wo on opposite sides of the facet */
    if (g == 0.0) return 0.0;
    double denom = eta_i * hi + eta_o * ho;
    /* Fresnel transmittance is the same from both sides of a Snell pair. Evaluating it from the side of lower
     * index is better conditioned (no cancellation near the critical angle) and makes f exactly reciprocal. */
    double T = eta >= 1.0 ? 1.0 - ggx_fresnel_dielectric_eval(wi_up ? hi : ho, eta)
                          : 1.0 - ggx_fresnel_dielectric_eval(wi_up ? ho : hi, 1.0 / eta);
    return finite_or_zero(fabs(hi * ho) * eta_o * eta_o * T * ggx_ndf(s, h) * g /
                          (cos_i * cos_o * denom * denom)); /* Walter 2007 eq 21 */
}

double ggx_bsdf_eval(const ggx_shape *s, double eta, ggx_vec3 wi, ggx_vec3 wo, ggx_transport mode)
{
    return mode == GGX_IMPORTANCE ? bsdf_radiance(s, eta, wo, wi) : bsdf_radiance(s, eta, wi, wo);
}
