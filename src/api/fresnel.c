/* Fresnel terms: setup (validated) and evaluation (the kernels). SPDX-License-Identifier: MIT */
#include "internal.h"

GGX_API GGX_HOT double ggx_fresnel_dielectric_eval(double cos_i, double eta)
{
    return ggx_fresnel_dielectric_eval_d(cos_i, eta);
}
GGX_API GGX_HOT double ggx_fresnel_conductor_eval(double cos_i, double eta, double k)
{
    return ggx_fresnel_conductor_eval_d(cos_i, eta, k);
}
GGX_API GGX_HOT double ggx_fresnel_schlick_eval(double cos_i, double f0)
{
    return ggx_fresnel_schlick_eval_d(cos_i, f0);
}
const ggx_fresnel ggx_internal_fresnel_one = {GGX_FRESNEL_ONE, 1.0, 0.0, 1.0};

GGX_API GGX_HOT double ggx_fresnel_eval(const ggx_fresnel *f, double cos_i)
{
    return ggx_fresnel_eval_d(GGX_FRESNEL_OR_ONE(f), cos_i);
}

static ggx_status set(ggx_fresnel *f, ggx_fresnel_kind kind, double eta, double k, double f0)
{
    ggx_fresnel t = {kind, eta, k, f0};
    *f = t;
    return GGX_OK;
}

GGX_API GGX_HOT ggx_status ggx_fresnel_one(ggx_fresnel *f)
{
    if (!f) return GGX_ERR_NULL;
    *f = ggx_internal_fresnel_one;
    return GGX_OK;
}

GGX_API GGX_HOT ggx_status ggx_fresnel_dielectric(ggx_fresnel *f, double eta)
{
    if (!f) return GGX_ERR_NULL;
    if (!isfinite(eta)) return GGX_ERR_NONFINITE;
    if (!(eta > 0.0)) return GGX_ERR_ETA;
    return set(f, GGX_FRESNEL_DIELECTRIC, eta, 0.0, 0.0);
}

GGX_API GGX_HOT ggx_status ggx_fresnel_conductor(ggx_fresnel *f, double eta, double k)
{
    if (!f) return GGX_ERR_NULL;
    if (!isfinite(eta) || !isfinite(k)) return GGX_ERR_NONFINITE;
    if (!(eta > 0.0) || !(k >= 0.0)) return GGX_ERR_ETA;
    return set(f, GGX_FRESNEL_CONDUCTOR, eta, k, 0.0);
}

GGX_API GGX_HOT ggx_status ggx_fresnel_schlick(ggx_fresnel *f, double f0)
{
    if (!f) return GGX_ERR_NULL;
    if (!isfinite(f0)) return GGX_ERR_NONFINITE;
    if (!(f0 >= 0.0 && f0 <= 1.0)) return GGX_ERR_RANGE;
    return set(f, GGX_FRESNEL_SCHLICK, 1.0, 0.0, f0);
}
