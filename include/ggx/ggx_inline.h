/*
 * libggx inline API: the library's per-element kernels, for renderers that inline their microfacet code into the
 * integrator, and for GPU code. SPDX-License-Identifier: MIT
 *
 * Every formula of the library is written once, in include/ggx/kernel/, over a precision type, and instantiated
 * here twice: for float (names ending in _f, on ggx_shapef, ggx_vec3f) and for double (names ending in _d, on
 * ggx_shape, ggx_vec3). The exported double API of ggx.h calls the _d kernels and the batch API of ggx_batch.h loops
 * over the _f kernels, so the three give the same results up to the precision of the type. The inline functions need
 * no link to libggx; they use only <math.h> (sqrt, floor, fabs; trigonometric functions only in the setup-like
 * ggx_ndf_spherical_* and the inverse maps). Under a CUDA compiler every kernel is __host__ __device__.
 *
 * Names: ggx_<function>_f / ggx_<function>_d for each function of ggx.h taking a shape (ggx_ndf_f, ggx_g1_f,
 * ggx_pdf_vndf_f, ggx_sample_vndf_f, ggx_brdf_eval_f, ...) and for the shape-free ones (ggx_reflect_f,
 * ggx_fresnel_dielectric_eval_f, ggx_disk_concentric_f, ...). Their domains, edge cases and contract are those of
 * the function of the same stem in ggx.h, with these differences for float:
 * - ggx_shapef is normalised (A' divided by ||A n||), so that every shape the double API accepts converts without
 *   overflow or underflow; absolute areas and the curvature (ggx_projected_area_f, ggx_lune_area_f,
 *   ggx_gaussian_curvature_f) are those of the normalised matrix. Everything else is scale-free and equal to the
 *   double API's result.
 * - Accuracy against the double API with the same (float) inputs, for alpha >= 0.05, skews to 0.5 rad and
 *   directions with z >= 0.02 (tests/unit/test_float_regress.c, every sampler of the registry): the bounds of
 *   ggx_batch.h. The _d kernels agree with the double API (which may run an FMA build of the same source) to
 *   1e-14 kappa^2, kappa the condition number of A (max / min of alpha_x, alpha_y and 1 for ggx_shape_ellipsoid):
 *   per component of a sampled normal, and relative for D, the VNDF pdf and the BRDF where the normal is at least
 *   0.01 from the horizon and from edge-on to the view (a dot product near 0 keeps only an absolute accuracy). So
 *   1e-12 for kappa <= 10; rounding differences grow with kappa^2 near the rim (docs/design/kernels.md, "Float
 *   against double").
 * - Rim steps, margins and view-length ranges are those of kernel/traits.h for float.
 * Names beginning ggx_k_ are internal steps of the kernels, not API.
 * All functions are reentrant and thread-safe (they only read their arguments).
 */
#ifndef GGX_GGX_INLINE_H
#define GGX_GGX_INLINE_H

#include <float.h>
#include <math.h>

#include "ggx/ggx.h"
#include "ggx/kernel/maps.h"

/* GGX_HD qualifies every kernel. A program may define it before including this header (the library defines it to
 * force inlining in its own loops, so that they vectorise). */
/* GGX_UNUSED: nvcc's host pass hands static inline functions to the host compiler in a form that clang reports as
 * unused (-Wunused-function); the attribute keeps a program that uses a few kernels warning-free. */
#if defined(__GNUC__) || defined(__clang__)
#define GGX_UNUSED __attribute__((unused))
#else
#define GGX_UNUSED
#endif
#if defined(__CUDACC__)
#ifndef GGX_HD
#define GGX_HD static inline __host__ __device__ GGX_UNUSED
#endif
#define GGX_COLD static inline __host__ __device__ __noinline__ GGX_UNUSED
#define GGX_HDI static __host__ __device__ __forceinline__ GGX_UNUSED
#elif defined(__GNUC__)
#ifndef GGX_HD
#define GGX_HD static inline
#endif
/* The rare slow paths stay out of line, so that the hot path of every sampler inlines small. */
#define GGX_COLD static __attribute__((noinline, cold, unused))
/* The steps with out-parameters inline always: out of line (GCC's choice where a program calls a sampler from several
 * places) their results would pass through memory. */
#define GGX_HDI static inline __attribute__((always_inline, unused))
#else
#ifndef GGX_HD
#define GGX_HD static inline
#endif
#define GGX_COLD static inline
#define GGX_HDI static inline
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ggx_vec3f {
    float x, y, z;
} ggx_vec3f;

typedef struct ggx_vec2f {
    float x, y;
} ggx_vec2f;

/* A shape in float: ggx_shape's canonical A' divided by ||A n|| (so a = [B 0; r 1] with A' n = z) and what the
 * kernels need. Same field names as ggx_shape, read-only; made by ggx_shapef_from. */
typedef struct ggx_shapef {
    float a[3][3];      /* A' / ||A n||, row-major */
    float ainv_t[3][3]; /* its inverse transpose */
    float det;          /* its |det| */
    float an_len;       /* its ||A n|| = 1 */
    float ndf_scale;    /* 1 / (pi det an_len), the constant of Walter eq 1 (scale-free) */
    float alpha_x, alpha_y, tangent_cos, tangent_sin; /* as in ggx_shape */
    ggx_shape_kind kind;
    float a_frob2; /* ||a||_F^2, the sum of the squares of a's entries (the caps sampler's proof reads it) */
} ggx_shapef;

/* A Fresnel term in float: same fields as ggx_fresnel. */
typedef struct ggx_fresnelf {
    ggx_fresnel_kind kind;
    float eta, k, f0;
    double eta_wide; /* eta in double, for the dielectric term's square-root singularity in 1 - sin^2 / eta^2 at the
                      * critical angle (docs/design/kernels.md, "Precision traits") */
} ggx_fresnelf;

/* A direction sample in float: same fields as ggx_sample. */
typedef struct ggx_samplef {
    ggx_vec3f w;
    float pdf;
    float weight;
    ggx_event event;
} ggx_samplef;

/* The float shape of s (from a successful ggx_shape_* call). Normalised in double before rounding to float: for
 * every shape the double API accepts, every field is finite and nonzero where the double one is. */
static inline GGX_UNUSED void ggx_shapef_from(ggx_shapef *out, const ggx_shape *s)
{
    double k = 1.0 / s->an_len, det = s->det * k * k * k;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            out->a[i][j] = (float)(s->a[i][j] * k);
            out->ainv_t[i][j] = (float)(s->ainv_t[i][j] * s->an_len);
        }
    }
    out->a[0][2] = out->a[1][2] = 0.0f;
    out->a[2][2] = 1.0f;
    out->ainv_t[2][0] = out->ainv_t[2][1] = 0.0f;
    out->ainv_t[2][2] = 1.0f;
    out->det = (float)det;
    out->an_len = 1.0f;
    out->ndf_scale = (float)(1.0 / (GGX_PI * det));
    out->alpha_x = (float)s->alpha_x, out->alpha_y = (float)s->alpha_y;
    out->tangent_cos = (float)s->tangent_cos, out->tangent_sin = (float)s->tangent_sin;
    out->kind = s->kind;
    double f2 = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) f2 += (double)out->a[i][j] * out->a[i][j];
    out->a_frob2 = (float)f2;
}

/* The float Fresnel term of f. Indices beyond float's range keep their F: a conductor's eta and k are scaled by one
 * factor so that the larger is within [1e-30, 1e30] (F depends on their scale only within rounding there, see
 * fresnel_conductor_eval), an eta that float would round to 0 raised to FLT_MIN, and a dielectric's eta is clamped to [FLT_MIN, FLT_MAX] (F is 1 within rounding beyond
 * both; eta_wide keeps the exact index for the critical angle). */
static inline GGX_UNUSED void ggx_fresnelf_from(ggx_fresnelf *out, const ggx_fresnel *f)
{
    double eta = f->eta, k = f->k, m = eta > k ? eta : k;
    if (f->kind == GGX_FRESNEL_CONDUCTOR && m > 0 && m <= DBL_MAX) {
        double sc = m > 1e30 ? 1e30 / m : m < 1e-30 ? 1e-30 / m : 1.0;
        eta *= sc, k *= sc;
        if (eta > 0 && eta < FLT_MIN) eta = FLT_MIN; /* a positive eta stays positive in float */
    }
    if (f->kind == GGX_FRESNEL_DIELECTRIC && eta > 0 && eta <= DBL_MAX)
        eta = eta > FLT_MAX ? FLT_MAX : eta < FLT_MIN ? FLT_MIN : eta;
    out->kind = f->kind;
    out->eta = (float)eta, out->k = (float)k, out->f0 = (float)f->f0;
    out->eta_wide = f->eta;
}

/* Every public kernel, declared by its full name (the definitions in ggx/kernel/ build their names by token pasting):
 * float and double twins side by side. The contract of each is that of the function of the same stem in ggx.h, with
 * the differences for float above. */
/* ---- function index: generated by lab/gen_inline_index.py from the kernels; do not edit ---- */
GGX_HD float ggx_ndf_f(const ggx_shapef *s, ggx_vec3f m);
GGX_HD double ggx_ndf_d(const ggx_shape *s, ggx_vec3 m);
GGX_HD float ggx_ndf_spherical_f(const ggx_shapef *s, float theta, float phi);
GGX_HD double ggx_ndf_spherical_d(const ggx_shape *s, double theta, double phi);
GGX_HD float ggx_p22_f(const ggx_shapef *s, float slope_x, float slope_y);
GGX_HD double ggx_p22_d(const ggx_shape *s, double slope_x, double slope_y);
GGX_HD float ggx_gaussian_curvature_f(const ggx_shapef *s, ggx_vec3f m);
GGX_HD double ggx_gaussian_curvature_d(const ggx_shape *s, ggx_vec3 m);
GGX_HD float ggx_projected_area_f(const ggx_shapef *s, ggx_vec3f u);
GGX_HD double ggx_projected_area_d(const ggx_shape *s, ggx_vec3 u);
GGX_HD float ggx_lune_area_f(const ggx_shapef *s, ggx_vec3f u, ggx_vec3f v);
GGX_HD double ggx_lune_area_d(const ggx_shape *s, ggx_vec3 u, ggx_vec3 v);
GGX_HD float ggx_lambda_f(const ggx_shapef *s, ggx_vec3f u);
GGX_HD double ggx_lambda_d(const ggx_shape *s, ggx_vec3 u);
GGX_HD float ggx_g1_smith_f(const ggx_shapef *s, ggx_vec3f u);
GGX_HD double ggx_g1_smith_d(const ggx_shape *s, ggx_vec3 u);
GGX_HD float ggx_g1_f(const ggx_shapef *s, ggx_vec3f u, ggx_vec3f m);
GGX_HD double ggx_g1_d(const ggx_shape *s, ggx_vec3 u, ggx_vec3 m);
GGX_HD float ggx_g1_tilted_f(const ggx_shapef *s, ggx_vec3f u, ggx_vec3f m);
GGX_HD double ggx_g1_tilted_d(const ggx_shape *s, ggx_vec3 u, ggx_vec3 m);
GGX_HD float ggx_g1_risers_f(const ggx_shapef *s, ggx_vec3f u, ggx_vec3f m);
GGX_HD double ggx_g1_risers_d(const ggx_shape *s, ggx_vec3 u, ggx_vec3 m);
GGX_HD float ggx_g2_f(const ggx_shapef *s, ggx_vec3f wi, ggx_vec3f wo, ggx_vec3f m);
GGX_HD double ggx_g2_d(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 m);
GGX_HD float ggx_g2_height_correlated_f(const ggx_shapef *s, ggx_vec3f wi, ggx_vec3f wo, ggx_vec3f m);
GGX_HD double ggx_g2_height_correlated_d(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 m);
GGX_HD float ggx_pdf_vndf_f(const ggx_shapef *s, ggx_vec3f v, ggx_vec3f m);
GGX_HD double ggx_pdf_vndf_d(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);
GGX_HD float ggx_pdf_ndf_f(const ggx_shapef *s, ggx_vec3f m);
GGX_HD double ggx_pdf_ndf_d(const ggx_shape *s, ggx_vec3 m);
GGX_HD float ggx_fresnel_dielectric_eval_f(float cos_i, float eta);
GGX_HD double ggx_fresnel_dielectric_eval_d(double cos_i, double eta);
GGX_HD float ggx_fresnel_conductor_eval_f(float cos_i, float eta_in, float k_in);
GGX_HD double ggx_fresnel_conductor_eval_d(double cos_i, double eta_in, double k_in);
GGX_HD float ggx_fresnel_schlick_eval_f(float cos_i, float f0);
GGX_HD double ggx_fresnel_schlick_eval_d(double cos_i, double f0);
GGX_HD float ggx_fresnel_eval_f(const ggx_fresnelf *f, float cos_i);
GGX_HD double ggx_fresnel_eval_d(const ggx_fresnel *f, double cos_i);
GGX_HD ggx_vec3f ggx_half_reflect_f(ggx_vec3f wi, ggx_vec3f wo);
GGX_HD ggx_vec3 ggx_half_reflect_d(ggx_vec3 wi, ggx_vec3 wo);
GGX_HD ggx_vec3f ggx_half_refract_f(ggx_vec3f wi, ggx_vec3f wo, float eta_i, float eta_o);
GGX_HD ggx_vec3 ggx_half_refract_d(ggx_vec3 wi, ggx_vec3 wo, double eta_i, double eta_o);
GGX_HD float ggx_jacobian_reflect_f(ggx_vec3f wo, ggx_vec3f h);
GGX_HD double ggx_jacobian_reflect_d(ggx_vec3 wo, ggx_vec3 h);
GGX_HD float ggx_jacobian_refract_f(ggx_vec3f wi, ggx_vec3f wo, ggx_vec3f h, float eta_i, float eta_o);
GGX_HD double ggx_jacobian_refract_d(ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 h, double eta_i, double eta_o);
GGX_HD ggx_vec3f ggx_reflect_f(ggx_vec3f w, ggx_vec3f m);
GGX_HD ggx_vec3 ggx_reflect_d(ggx_vec3 w, ggx_vec3 m);
GGX_HD int ggx_refract_f(ggx_vec3f w, ggx_vec3f m, float eta, ggx_vec3f *out);
GGX_HD int ggx_refract_d(ggx_vec3 w, ggx_vec3 m, double eta, ggx_vec3 *out);
GGX_HD float ggx_brdf_eval_f(const ggx_shapef *s, const ggx_fresnelf *f, ggx_vec3f wi, ggx_vec3f wo);
GGX_HD double ggx_brdf_eval_d(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo);
GGX_HD float ggx_bsdf_eval_f(const ggx_shapef *s, float eta, ggx_vec3f wi, ggx_vec3f wo, ggx_transport mode);
GGX_HD double ggx_bsdf_eval_d(const ggx_shape *s, double eta, ggx_vec3 wi, ggx_vec3 wo, ggx_transport mode);
GGX_HD ggx_vec2f ggx_disk_polar_f(float u1, float u2);
GGX_HD ggx_vec2 ggx_disk_polar_d(double u1, double u2);
GGX_HD ggx_vec2f ggx_disk_polar_inv_f(ggx_vec2f d);
GGX_HD ggx_vec2 ggx_disk_polar_inv_d(ggx_vec2 d);
GGX_HD ggx_vec2f ggx_disk_concentric_f(float u1, float u2);
GGX_HD ggx_vec2 ggx_disk_concentric_d(double u1, double u2);
GGX_HD ggx_vec2f ggx_disk_concentric_inv_f(ggx_vec2f d);
GGX_HD ggx_vec2 ggx_disk_concentric_inv_d(ggx_vec2 d);
GGX_HD ggx_vec3f ggx_sample_ndf_stretch_f(const ggx_shapef *s, float u1, float u2);
GGX_HD ggx_vec3 ggx_sample_ndf_stretch_d(const ggx_shape *s, double u1, double u2);
GGX_HD ggx_vec3f ggx_sample_ndf_visible_f(const ggx_shapef *s, float u1, float u2);
GGX_HD ggx_vec3 ggx_sample_ndf_visible_d(const ggx_shape *s, double u1, double u2);
GGX_HD ggx_vec3f ggx_sample_ndf_f(const ggx_shapef *s, float u1, float u2);
GGX_HD ggx_vec3 ggx_sample_ndf_d(const ggx_shape *s, double u1, double u2);
GGX_HD ggx_vec3f ggx_sample_vndf_caps_f(const ggx_shapef *s, ggx_vec3f v, float u1, float u2);
GGX_HD ggx_vec3 ggx_sample_vndf_caps_d(const ggx_shape *s, ggx_vec3 v, double u1, double u2);
GGX_HD ggx_vec3f ggx_sample_vndf_f(const ggx_shapef *s, ggx_vec3f v, float u1, float u2);
GGX_HD ggx_vec3 ggx_sample_vndf_d(const ggx_shape *s, ggx_vec3 v, double u1, double u2);
GGX_HD ggx_vec3f ggx_sample_vndf_crescent_f(const ggx_shapef *s, ggx_vec3f v, float u1, float u2);
GGX_HD ggx_vec3 ggx_sample_vndf_crescent_d(const ggx_shape *s, ggx_vec3 v, double u1, double u2);
GGX_HD ggx_vec3f ggx_sample_vndf_crescent_polar_f(const ggx_shapef *s, ggx_vec3f v, float u1, float u2);
GGX_HD ggx_vec3 ggx_sample_vndf_crescent_polar_d(const ggx_shape *s, ggx_vec3 v, double u1, double u2);
GGX_HD ggx_vec3f ggx_sample_vndf_heitz_f(const ggx_shapef *s, ggx_vec3f v, float u1, float u2);
GGX_HD ggx_vec3 ggx_sample_vndf_heitz_d(const ggx_shape *s, ggx_vec3 v, double u1, double u2);
GGX_HD ggx_vec3f ggx_sample_ndf_ellipse_f(const ggx_shapef *s, float u1, float u2);
GGX_HD ggx_vec3 ggx_sample_ndf_ellipse_d(const ggx_shape *s, double u1, double u2);
GGX_HD ggx_vec3f ggx_sample_ndf_inversion_f(const ggx_shapef *s, float u1, float u2);
GGX_HD ggx_vec3 ggx_sample_ndf_inversion_d(const ggx_shape *s, double u1, double u2);
GGX_HD ggx_vec2f ggx_sample_ndf_stretch_inv_f(const ggx_shapef *s, ggx_vec3f m);
GGX_HD ggx_vec2 ggx_sample_ndf_stretch_inv_d(const ggx_shape *s, ggx_vec3 m);
GGX_HD ggx_vec2f ggx_sample_vndf_caps_inv_f(const ggx_shapef *s, ggx_vec3f v, ggx_vec3f m);
GGX_HD ggx_vec2 ggx_sample_vndf_caps_inv_d(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);
GGX_HD ggx_vec2f ggx_sample_vndf_crescent_inv_f(const ggx_shapef *s, ggx_vec3f v, ggx_vec3f m);
GGX_HD ggx_vec2 ggx_sample_vndf_crescent_inv_d(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);
GGX_HD ggx_vec2f ggx_sample_vndf_crescent_polar_inv_f(const ggx_shapef *s, ggx_vec3f v, ggx_vec3f m);
GGX_HD ggx_vec2 ggx_sample_vndf_crescent_polar_inv_d(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);
GGX_HD ggx_vec2f ggx_sample_vndf_heitz_inv_f(const ggx_shapef *s, ggx_vec3f v, ggx_vec3f m);
GGX_HD ggx_vec2 ggx_sample_vndf_heitz_inv_d(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);
GGX_HD ggx_vec3f ggx_sample_vndf_walter_v1_f(const ggx_shapef *s, ggx_vec3f v, ggx_uniform_fn next, void *state,
                                             unsigned *trials);
GGX_HD ggx_vec3 ggx_sample_vndf_walter_v1_d(const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next, void *state,
                                            unsigned *trials);
GGX_HD ggx_vec3f ggx_sample_vndf_walter_v2_f(const ggx_shapef *s, ggx_vec3f v, ggx_uniform_fn next, void *state,
                                             unsigned *trials);
GGX_HD ggx_vec3 ggx_sample_vndf_walter_v2_d(const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next, void *state,
                                            unsigned *trials);
GGX_HD float ggx_pdf_brdf_f(const ggx_shapef *s, ggx_vec3f wi, ggx_vec3f wo);
GGX_HD double ggx_pdf_brdf_d(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo);
GGX_HD ggx_samplef ggx_sample_brdf_f(const ggx_shapef *s, const ggx_fresnelf *f, ggx_vec3f wi, float u1, float u2);
GGX_HD ggx_sample ggx_sample_brdf_d(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, double u1, double u2);
GGX_HD ggx_samplef ggx_sample_brdf_bounded_f(const ggx_shapef *s, const ggx_fresnelf *f, ggx_vec3f wi, float u1,
                                             float u2);
GGX_HD ggx_sample ggx_sample_brdf_bounded_d(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, double u1,
                                            double u2);
GGX_HD float ggx_pdf_brdf_bounded_f(const ggx_shapef *s, ggx_vec3f wi, ggx_vec3f wo);
GGX_HD double ggx_pdf_brdf_bounded_d(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo);
GGX_HD ggx_samplef ggx_sample_brdf_bounded_azimuth_f(const ggx_shapef *s, const ggx_fresnelf *f, ggx_vec3f wi, float u1,
                                                     float u2);
GGX_HD ggx_sample ggx_sample_brdf_bounded_azimuth_d(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, double u1,
                                                    double u2);
GGX_HD float ggx_pdf_brdf_bounded_azimuth_f(const ggx_shapef *s, ggx_vec3f wi, ggx_vec3f wo);
GGX_HD double ggx_pdf_brdf_bounded_azimuth_d(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo);
GGX_HD ggx_samplef ggx_sample_bsdf_f(const ggx_shapef *s, float eta, ggx_vec3f v, float u1, float u2, float u3,
                                     ggx_transport mode);
GGX_HD ggx_sample ggx_sample_bsdf_d(const ggx_shape *s, double eta, ggx_vec3 v, double u1, double u2, double u3,
                                    ggx_transport mode);
GGX_HD float ggx_pdf_bsdf_f(const ggx_shapef *s, float eta, ggx_vec3f v, ggx_vec3f w);
GGX_HD double ggx_pdf_bsdf_d(const ggx_shape *s, double eta, ggx_vec3 v, ggx_vec3 w);
/* ---- end of the function index ---- */

/* Double first: the float kernels' rare slow paths call the double ones. */
#define GGX_K_PRECISION 64
#include "ggx/kernel/traits.h"
#include "ggx/kernel/all.inc"
#include "ggx/kernel/untraits.h"

#define GGX_K_PRECISION 32
#include "ggx/kernel/traits.h"
#include "ggx/kernel/all.inc"
#include "ggx/kernel/untraits.h"

#ifdef __cplusplus
}
#endif

#endif /* GGX_GGX_INLINE_H */
