/* The exported double API of evaluation: each function is the double kernel of the same stem (ggx_inline.h).
 * SPDX-License-Identifier: MIT */
#include "internal.h"

GGX_API GGX_HOT double ggx_ndf(const ggx_shape *s, ggx_vec3 m) { return ggx_ndf_d(s, m); }
GGX_API GGX_HOT double ggx_ndf_spherical(const ggx_shape *s, double theta, double phi)
{
    return ggx_ndf_spherical_d(s, theta, phi);
}
GGX_API GGX_HOT double ggx_p22(const ggx_shape *s, double slope_x, double slope_y)
{
    return ggx_p22_d(s, slope_x, slope_y);
}
GGX_API GGX_HOT double ggx_gaussian_curvature(const ggx_shape *s, ggx_vec3 m) { return ggx_gaussian_curvature_d(s, m); }
GGX_API GGX_HOT double ggx_projected_area(const ggx_shape *s, ggx_vec3 u) { return ggx_projected_area_d(s, u); }
GGX_API GGX_HOT double ggx_lune_area(const ggx_shape *s, ggx_vec3 u, ggx_vec3 v) { return ggx_lune_area_d(s, u, v); }
GGX_API GGX_HOT double ggx_lambda(const ggx_shape *s, ggx_vec3 u) { return ggx_lambda_d(s, u); }
GGX_API GGX_HOT double ggx_g1_smith(const ggx_shape *s, ggx_vec3 u) { return ggx_g1_smith_d(s, u); }
GGX_API GGX_HOT double ggx_g1(const ggx_shape *s, ggx_vec3 u, ggx_vec3 m) { return ggx_g1_d(s, u, m); }
GGX_API GGX_HOT double ggx_g1_tilted(const ggx_shape *s, ggx_vec3 u, ggx_vec3 m) { return ggx_g1_tilted_d(s, u, m); }
GGX_API GGX_HOT double ggx_g1_risers(const ggx_shape *s, ggx_vec3 u, ggx_vec3 m) { return ggx_g1_risers_d(s, u, m); }
GGX_API GGX_HOT double ggx_g2(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 m)
{
    return ggx_g2_d(s, wi, wo, m);
}
GGX_API GGX_HOT double ggx_g2_height_correlated(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 m)
{
    return ggx_g2_height_correlated_d(s, wi, wo, m);
}
GGX_API GGX_HOT double ggx_pdf_vndf(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m) { return ggx_pdf_vndf_d(s, v, m); }
GGX_API GGX_HOT double ggx_pdf_ndf(const ggx_shape *s, ggx_vec3 m) { return ggx_pdf_ndf_d(s, m); }

GGX_API GGX_HOT ggx_vec3 ggx_half_reflect(ggx_vec3 wi, ggx_vec3 wo) { return ggx_half_reflect_d(wi, wo); }
GGX_API GGX_HOT ggx_vec3 ggx_half_refract(ggx_vec3 wi, ggx_vec3 wo, double eta_i, double eta_o)
{
    return ggx_half_refract_d(wi, wo, eta_i, eta_o);
}
GGX_API GGX_HOT double ggx_jacobian_reflect(ggx_vec3 wo, ggx_vec3 h) { return ggx_jacobian_reflect_d(wo, h); }
GGX_API GGX_HOT double ggx_jacobian_refract(ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 h, double eta_i, double eta_o)
{
    return ggx_jacobian_refract_d(wi, wo, h, eta_i, eta_o);
}
GGX_API GGX_HOT ggx_vec3 ggx_reflect(ggx_vec3 w, ggx_vec3 m) { return ggx_reflect_d(w, m); }
GGX_API GGX_HOT int ggx_refract(ggx_vec3 w, ggx_vec3 m, double eta, ggx_vec3 *out)
{
    return ggx_refract_d(w, m, eta, out);
}

GGX_API GGX_HOT double ggx_brdf_eval(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo)
{
    return ggx_brdf_eval_d(s, GGX_FRESNEL_OR_ONE(f), wi, wo);
}
GGX_API GGX_HOT double ggx_bsdf_eval(const ggx_shape *s, double eta, ggx_vec3 wi, ggx_vec3 wo, ggx_transport mode)
{
    return ggx_bsdf_eval_d(s, eta, wi, wo, mode);
}
