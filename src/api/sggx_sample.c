/* The SGGX samplers (ggx_sggx.h): visible normals by a disk lifted onto the unit hemisphere of sphere space, and the
 * specular and diffuse phase functions through them. Proofs: docs/design/sggx.md. SPDX-License-Identifier: MIT */
#include "internal.h"
#include "sggx_internal.h"

/* A cosine-distributed unit vector about the unit vector a: a polar disk point in the plane normal to a, lifted. */
static ggx_vec3 lift_about(ggx_vec3 a, double u1, double u2)
{
    ggx_vec3 f1, f2;
    double q;
    ggx_k_perp_frame_d(a, &f1, &f2);
    ggx_vec2 d = ggx_k_disk_polar_q_d(u1, u2, &q);
    ggx_vec3 p = ggx_k_add_d(ggx_k_scale_d(f1, d.x), ggx_k_scale_d(f2, d.y));
    return ggx_k_normalize_d(ggx_k_add_d(p, ggx_k_scale_d(a, sqrt(q))));
}

GGX_API ggx_vec3 ggx_sggx_sample_vndf(const ggx_sggx *f, ggx_vec3 wi, double u1, double u2)
{
    ggx_vec3 a = ggx_k_normalize_d(ggx_k_mul_d(f->half, ggx_k_unit_d(wi)));
    if (ggx_k_is_zero_d(a)) return a;
    return ggx_k_normalize_d(ggx_k_mul_d(f->half, lift_about(a, u1, u2)));
}

GGX_API ggx_vec3 ggx_sggx_sample_specular(const ggx_sggx *f, ggx_vec3 wi, double u1, double u2)
{
    ggx_vec3 w = ggx_k_unit_d(wi), m = ggx_sggx_sample_vndf(f, w, u1, u2);
    if (ggx_k_is_zero_d(m)) return m;
    return ggx_k_normalize_d(ggx_k_sub_d(ggx_k_scale_d(m, 2.0 * ggx_k_dot_d(w, m)), w));
}

GGX_API ggx_vec3 ggx_sggx_sample_diffuse(const ggx_sggx *f, ggx_vec3 wi, double u1, double u2, double u3, double u4)
{
    ggx_vec3 m = ggx_sggx_sample_vndf(f, wi, u1, u2);
    if (ggx_k_is_zero_d(m)) return m;
    return lift_about(m, u3, u4);
}
