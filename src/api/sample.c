/* The exported double API of sampling: each function is the double kernel of the same stem (ggx_inline.h).
 * SPDX-License-Identifier: MIT */
#include "internal.h"

GGX_API GGX_HOT ggx_vec2 ggx_disk_polar(double u1, double u2) { return ggx_disk_polar_d(u1, u2); }
GGX_API GGX_HOT ggx_vec2 ggx_disk_concentric(double u1, double u2) { return ggx_disk_concentric_d(u1, u2); }
GGX_API GGX_HOT ggx_vec2 ggx_disk_polar_inv(ggx_vec2 d) { return ggx_disk_polar_inv_d(d); }
GGX_API GGX_HOT ggx_vec2 ggx_disk_concentric_inv(ggx_vec2 d) { return ggx_disk_concentric_inv_d(d); }

GGX_API GGX_HOT ggx_vec3 ggx_sample_ndf(const ggx_shape *s, double u1, double u2)
{
    return ggx_sample_ndf_d(s, u1, u2);
}
GGX_API GGX_HOT ggx_vec3 ggx_sample_ndf_stretch(const ggx_shape *s, double u1, double u2)
{
    return ggx_sample_ndf_stretch_d(s, u1, u2);
}
GGX_API GGX_HOT ggx_vec2 ggx_sample_ndf_stretch_inv(const ggx_shape *s, ggx_vec3 m)
{
    return ggx_sample_ndf_stretch_inv_d(s, m);
}
GGX_API GGX_HOT ggx_vec3 ggx_sample_ndf_ellipse(const ggx_shape *s, double u1, double u2)
{
    return ggx_sample_ndf_ellipse_d(s, u1, u2);
}
GGX_API GGX_HOT ggx_vec3 ggx_sample_ndf_inversion(const ggx_shape *s, double u1, double u2)
{
    return ggx_sample_ndf_inversion_d(s, u1, u2);
}
GGX_API GGX_HOT ggx_vec3 ggx_sample_ndf_visible(const ggx_shape *s, double u1, double u2)
{
    return ggx_sample_ndf_visible_d(s, u1, u2);
}

GGX_API GGX_HOT ggx_vec3 ggx_sample_vndf(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    return ggx_sample_vndf_d(s, v, u1, u2);
}
GGX_API GGX_HOT ggx_vec3 ggx_sample_vndf_caps(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    return ggx_sample_vndf_caps_d(s, v, u1, u2);
}
GGX_API GGX_HOT ggx_vec2 ggx_sample_vndf_caps_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    return ggx_sample_vndf_caps_inv_d(s, v, m);
}
GGX_API GGX_HOT ggx_vec3 ggx_sample_vndf_crescent(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    return ggx_sample_vndf_crescent_d(s, v, u1, u2);
}
GGX_API GGX_HOT ggx_vec3 ggx_sample_vndf_crescent_polar(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    return ggx_sample_vndf_crescent_polar_d(s, v, u1, u2);
}
GGX_API GGX_HOT ggx_vec2 ggx_sample_vndf_crescent_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    return ggx_sample_vndf_crescent_inv_d(s, v, m);
}
GGX_API GGX_HOT ggx_vec2 ggx_sample_vndf_crescent_polar_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    return ggx_sample_vndf_crescent_polar_inv_d(s, v, m);
}
GGX_API GGX_HOT ggx_vec3 ggx_sample_vndf_heitz(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    return ggx_sample_vndf_heitz_d(s, v, u1, u2);
}
GGX_API GGX_HOT ggx_vec2 ggx_sample_vndf_heitz_inv(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    return ggx_sample_vndf_heitz_inv_d(s, v, m);
}
GGX_API GGX_HOT ggx_vec3 ggx_sample_vndf_walter_v1(const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next, void *state,
                                                   unsigned *trials)
{
    return ggx_sample_vndf_walter_v1_d(s, v, next, state, trials);
}
GGX_API GGX_HOT ggx_vec3 ggx_sample_vndf_walter_v2(const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next, void *state,
                                                   unsigned *trials)
{
    return ggx_sample_vndf_walter_v2_d(s, v, next, state, trials);
}

GGX_API GGX_HOT ggx_sample ggx_sample_brdf(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, double u1, double u2)
{
    return ggx_sample_brdf_d(s, GGX_FRESNEL_OR_ONE(f), wi, u1, u2);
}
GGX_API GGX_HOT double ggx_pdf_brdf(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo) { return ggx_pdf_brdf_d(s, wi, wo); }
GGX_API GGX_HOT ggx_sample ggx_sample_brdf_bounded(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, double u1,
                                                   double u2)
{
    return ggx_sample_brdf_bounded_d(s, GGX_FRESNEL_OR_ONE(f), wi, u1, u2);
}
GGX_API GGX_HOT double ggx_pdf_brdf_bounded(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo)
{
    return ggx_pdf_brdf_bounded_d(s, wi, wo);
}
GGX_API GGX_HOT ggx_sample ggx_sample_brdf_bounded_azimuth(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi,
                                                           double u1, double u2)
{
    return ggx_sample_brdf_bounded_azimuth_d(s, GGX_FRESNEL_OR_ONE(f), wi, u1, u2);
}
GGX_API GGX_HOT double ggx_pdf_brdf_bounded_azimuth(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo)
{
    return ggx_pdf_brdf_bounded_azimuth_d(s, wi, wo);
}
GGX_API GGX_HOT ggx_sample ggx_sample_bsdf(const ggx_shape *s, double eta, ggx_vec3 v, double u1, double u2, double u3,
                                           ggx_transport mode)
{
    return ggx_sample_bsdf_d(s, eta, v, u1, u2, u3, mode);
}
GGX_API GGX_HOT double ggx_pdf_bsdf(const ggx_shape *s, double eta, ggx_vec3 v, ggx_vec3 w)
{
    return ggx_pdf_bsdf_d(s, eta, v, w);
}
