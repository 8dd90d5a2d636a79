/* The SGGX samplers (ggx_sggx.h): visible normals as sphere-space points cosine-distributed about H wi, and the
 * specular and diffuse phase functions through them. Proofs: docs/design/sggx.md. SPDX-License-Identifier: MIT */
#include "internal.h"
#include "sggx_internal.h"

/* A vector along a cosine-distributed unit vector about t / k, for k = ||t|| > 0: t + k s, s uniform on the unit
 * sphere (z = 1 - 2 u1, the azimuth 2 pi u2), which is k (a + s) with a = t / k; normalised, a + s has the density
 * (a.w) / pi on the hemisphere a.w > 0 (docs/design/sggx.md). No frame and no division. Where s is within 2^-20 of
 * -a (probability 2^-42; the direction of a + s would be rounding), t itself: the centre of the hemisphere. */
static ggx_vec3 cosine_about(ggx_vec3 t, double k, double u1, double u2)
{
    double c, sn;
    u1 = ggx_k_clamp01_d(u1);
    ggx_k_sincos_turn_d(ggx_k_clamp01_d(u2), &c, &sn);
    double r = 2.0 * k * sqrt(u1 * (1.0 - u1)); /* k sqrt(1 - z^2), without cancellation */
    ggx_vec3 v = {t.x + r * c, t.y + r * sn, t.z + k * (1.0 - 2.0 * u1)};
    return ggx_k_dot_d(v, v) >= 0x1p-40 * (k * k) ? v : t;
}

GGX_API GGX_HOT ggx_vec3 ggx_sggx_sample_vndf(const ggx_sggx *f, ggx_vec3 wi, double u1, double u2)
{
    ggx_vec3 t = ggx_k_mul_d(f->half, wi); /* k a, a the unit sphere-space view */
    double l2 = ggx_k_dot_d(t, t);
    if (!(l2 >= 1e-200 && l2 <= 1e200)) { /* a tiny, huge, zero or NaN wi: its direction (or the zero vector) */
        t = ggx_k_mul_d(f->half, ggx_k_unit_d(wi));
        l2 = ggx_k_dot_d(t, t);
        if (!(l2 > 0)) return ggx_k_zero3_d();
    }
    return ggx_k_normalize_d(ggx_k_mul_d(f->half, cosine_about(t, sqrt(l2), u1, u2)));
}

/* The mirror direction 2 (w.m) m - w is normalised once, which makes it that of w's direction for any w. */
GGX_API GGX_HOT ggx_vec3 ggx_sggx_sample_specular(const ggx_sggx *f, ggx_vec3 wi, double u1, double u2)
{
    ggx_vec3 m = ggx_sggx_sample_vndf(f, wi, u1, u2);
    if (ggx_k_is_zero_d(m)) return m;
    return ggx_k_normalize_d(ggx_k_sub_d(ggx_k_scale_d(m, 2.0 * ggx_k_dot_d(wi, m)), wi));
}

GGX_API GGX_HOT ggx_vec3 ggx_sggx_sample_diffuse(const ggx_sggx *f, ggx_vec3 wi, double u1, double u2, double u3,
                                                 double u4)
{
    ggx_vec3 m = ggx_sggx_sample_vndf(f, wi, u1, u2);
    if (ggx_k_is_zero_d(m)) return m;
    return ggx_k_normalize_d(cosine_about(m, 1.0, u3, u4));
}
