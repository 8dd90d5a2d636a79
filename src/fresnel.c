/* Fresnel reflectance: exact dielectric, exact conductor, Schlick. SPDX-License-Identifier: MIT */
#include "internal.h"

static double clamp_cos(double c)
{
    c = fabs(c);
    return c < 1.0 ? c : 1.0;
}

double ggx_fresnel_dielectric_eval(double cos_i, double eta)
{
    if (!(eta > 0.0 && eta < HUGE_VAL) || isnan(cos_i)) return 0.0;
    double ci = clamp_cos(cos_i);
    double sin2_t = (1.0 - ci * ci) / eta / eta; /* Snell; two divisions: eta^2 may underflow where eta does not */
    if (sin2_t >= 1.0) return 1.0;                 /* total internal reflection */
    double ct = sqrt(1.0 - sin2_t);
    double rs = (ci - eta * ct) / (ci + eta * ct);
    double rp = (eta * ci - ct) / (eta * ci + ct);
    return 0.5 * (rs * rs + rp * rp);
}

double ggx_fresnel_conductor_eval(double cos_i, double eta, double k)
{
    if (!(eta > 0.0 && eta < HUGE_VAL && k >= 0.0 && k < HUGE_VAL) || isnan(cos_i)) return 0.0;
    /* Real form of the complex Fresnel equations: with (a + i b)^2 = (eta + i k)^2 - sin^2,
     * a^2 + b^2 = sqrt((eta^2 - k^2 - sin^2)^2 + 4 eta^2 k^2) and a^2 = (a^2 + b^2 + eta^2 - k^2 - sin^2) / 2. */
    double c = clamp_cos(cos_i), c2 = c * c, s2 = 1.0 - c2;
    double t0 = eta * eta - k * k - s2;
    double a2b2 = sqrt(t0 * t0 + 4.0 * eta * eta * k * k);
    double a2 = 0.5 * (a2b2 + t0);
    double a = sqrt(a2 > 0.0 ? a2 : 0.0);
    double rs = (a2b2 - 2.0 * a * c + c2) / (a2b2 + 2.0 * a * c + c2);
    double t1 = c2 * a2b2, t2 = 2.0 * a * c * s2, t3 = s2 * s2;
    double rp = rs * (t1 - t2 + t3) / (t1 + t2 + t3);
    return finite_or_zero(0.5 * (rs + rp));
}

double ggx_fresnel_schlick_eval(double cos_i, double f0)
{
    if (isnan(cos_i) || !(f0 >= 0.0 && f0 <= 1.0)) return 0.0;
    double m = 1.0 - clamp_cos(cos_i);
    double m2 = m * m;
    return f0 + (1.0 - f0) * m2 * m2 * m;
}

ggx_status ggx_fresnel_one(ggx_fresnel *f)
{
    if (!f) return GGX_ERR_NULL;
    ggx_fresnel t = {GGX_FRESNEL_ONE, 1.0, 0.0, 1.0};
    *f = t;
    return GGX_OK;
}

ggx_status ggx_fresnel_dielectric(ggx_fresnel *f, double eta)
{
    if (!f) return GGX_ERR_NULL;
    if (!isfinite(eta)) return GGX_ERR_NONFINITE;
    if (!(eta > 0.0)) return GGX_ERR_ETA;
    ggx_fresnel t = {GGX_FRESNEL_DIELECTRIC, eta, 0.0, 0.0};
    *f = t;
    return GGX_OK;
}

ggx_status ggx_fresnel_conductor(ggx_fresnel *f, double eta, double k)
{
    if (!f) return GGX_ERR_NULL;
    if (!isfinite(eta) || !isfinite(k)) return GGX_ERR_NONFINITE;
    if (!(eta > 0.0) || !(k >= 0.0)) return GGX_ERR_ETA;
    ggx_fresnel t = {GGX_FRESNEL_CONDUCTOR, eta, k, 0.0};
    *f = t;
    return GGX_OK;
}

ggx_status ggx_fresnel_schlick(ggx_fresnel *f, double f0)
{
    if (!f) return GGX_ERR_NULL;
    if (!isfinite(f0)) return GGX_ERR_NONFINITE;
    if (!(f0 >= 0.0 && f0 <= 1.0)) return GGX_ERR_RANGE;
    ggx_fresnel t = {GGX_FRESNEL_SCHLICK, 1.0, 0.0, f0};
    *f = t;
    return GGX_OK;
}

double ggx_fresnel_eval(const ggx_fresnel *f, double cos_i)
{
    switch (f->kind) {
    case GGX_FRESNEL_ONE: return 1.0;
    case GGX_FRESNEL_DIELECTRIC: return ggx_fresnel_dielectric_eval(cos_i, f->eta);
    case GGX_FRESNEL_CONDUCTOR: return ggx_fresnel_conductor_eval(cos_i, f->eta, f->k);
    case GGX_FRESNEL_SCHLICK: return ggx_fresnel_schlick_eval(cos_i, f->f0);
    }
    return 0.0;
}
