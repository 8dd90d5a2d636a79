/*
 * libggx batch API: float, struct-of-arrays, for wavefront renderers.
 *
 * SPDX-License-Identifier: MIT
 *
 * Conventions are those of ggx.h (n = +z, unit directions pointing away from the surface). Every function here:
 * - takes the destination arrays first, then the count n (any n >= 0; no alignment required; n = 0 does nothing),
 *   then the shape (one per batch, from the double API's ggx_shape), then the input arrays;
 * - reads input arrays and writes output arrays of n floats; outputs must not overlap inputs;
 * - expects unit direction inputs (not checked) and meets the contract of ggx.h in float: finite results >= 0,
 *   exactly 0 outside the domain (below the horizon, NaN), samplers a unit vector or the zero vector. Unlike the
 *   double API, a NaN or infinite u gives the zero vector (an invalid sample) rather than being read as 0.
 * Accuracy against the double API, on every instruction-set path, for alpha >= 0.05, skews to 0.5 rad and inputs
 * with m.z, v.z >= 0.02 (tests/unit/test_batch.c: n from 0 to 300, misaligned pointers; tests/unit/test_float_regress.c):
 * - ggx_batch_ndf, _g1, _brdf and _pdf_vndf: relative error <= 2e-5 (_pdf_vndf where m.v >= 0.01: the pdf is
 *   proportional to m.v, which a float dot product resolves to ~1e-7 absolute);
 * - sampled directions: within 1e-4 per component of the double sampler's for the same (u1, u2), for every sampler
 *   of the registry, u at the ends of [0, 1) and views at n;
 * - sample pdfs within 1e-4 relative and weights within 2e-4 absolute of ggx_sample_brdf's.
 * Known exceptions: for shapes with an alpha above ~1 and alpha ratios above ~3 at views near grazing (wi.z ~ 0.02),
 * a few samples whose reflection passes close to the horizon amplify float rounding beyond these bounds, up to
 * 5.4e-4 in direction, 8.7e-4 relative in pdf and 1.2e-3 in weight for ggx_sample_brdf, and 7.7e-4, 5.3e-3 and
 * 3.4e-3 for ggx_sample_brdf_bounded, whose cap ends there for u2 near 1 (docs/design/kernels.md, "Float against
 * double").
 * Every function is a loop over the float kernels of ggx_inline.h (the same source as the double API), compiled for a
 * scalar baseline and for AVX2 + FMA (and AVX-512 where the compiler can), chosen at run time by a CPU check. The
 * shape is converted by ggx_shapef_from (normalised), so every shape the double API accepts works, at any scale.
 */
#ifndef GGX_GGX_BATCH_H
#define GGX_GGX_BATCH_H

#include <stddef.h>

#include "ggx/ggx.h"
#include "ggx/ggx_samplers.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum ggx_batch_isa {
    GGX_ISA_AUTO = 0,   /* the best the CPU supports (default) */
    GGX_ISA_SCALAR = 1, /* the baseline build (x86-64: SSE2), no run-time requirement */
    GGX_ISA_AVX2 = 2,   /* AVX2 + FMA */
    GGX_ISA_AVX512 = 3  /* AVX-512 F + VL */
} ggx_batch_isa;

/* Forces an instruction-set path for all later batch calls (process-wide). GGX_ERR_RANGE when the CPU or the build
 * does not support it (the current path is kept).
 * Threads: every function of this header may be called from any number of threads at once. The path is chosen once
 * (on the first batch call or query, whichever thread makes it); ggx_batch_set_isa and ggx_batch_set_threads may run
 * beside batch calls, and each batch call uses the path and thread count it reads when it starts. All paths give
 * results within the bounds above, so a change of path mid-program changes results only within them. */
ggx_status ggx_batch_set_isa(ggx_batch_isa isa);
/* The path in use (never GGX_ISA_AUTO). */
ggx_batch_isa ggx_batch_get_isa(void);
/* Whether a path is compiled in and supported by this CPU. */
int ggx_batch_isa_available(ggx_batch_isa isa);
const char *ggx_batch_isa_name(ggx_batch_isa isa);

/* Worker threads for large batches (n >= 65536): 1 (default) runs on the calling thread; more split the batch into
 * contiguous chunks run by POSIX threads. GGX_ERR_RANGE outside [1, 256]. */
ggx_status ggx_batch_set_threads(int threads);

/* D(m) (ggx_ndf). */
void ggx_batch_ndf(float *d, size_t n, const ggx_shape *s, const float *mx, const float *my, const float *mz);

/* G1(u, m) (ggx_g1, Walter eq 6). */
void ggx_batch_g1(float *g1, size_t n, const ggx_shape *s, const float *ux, const float *uy, const float *uz,
                  const float *mx, const float *my, const float *mz);

/* The VNDF pdf of m for view v (ggx_pdf_vndf, Walter eq 33). */
void ggx_batch_pdf_vndf(float *pdf, size_t n, const ggx_shape *s, const float *vx, const float *vy, const float *vz,
                        const float *mx, const float *my, const float *mz);

/* Visible normals by spherical caps (ggx_sample_vndf_caps) for any shape; diagonal shapes take a faster path.
 * Views at or below the horizon give the zero vector. */
void ggx_batch_sample_vndf(float *mx, float *my, float *mz, size_t n, const ggx_shape *s, const float *vx,
                           const float *vy, const float *vz, const float *u1, const float *u2);

/* Visible normals of per-element anisotropic GGX (alpha_x[i], alpha_y[i], R = I): roughness from a texture. */
void ggx_batch_sample_vndf_aniso(float *mx, float *my, float *mz, size_t n, const float *alpha_x, const float *alpha_y,
                                 const float *vx, const float *vy, const float *vz, const float *u1, const float *u2);

/* Normals with pdf D(m) m.z by the elliptic stretch (ggx_sample_ndf_stretch). */
void ggx_batch_sample_ndf(float *mx, float *my, float *mz, size_t n, const ggx_shape *s, const float *u1,
                          const float *u2);

/* Normals from any sampler of the registry (ggx_samplers.h) with batch = 1 and family NDF or VNDF, in float: the
 * loop of that sampler's kernel (ggx_<stem>_f of ggx_inline.h). NDF samplers ignore the view (vx, vy, vz may be
 * NULL). GGX_ERR_RANGE for another sampler, GGX_ERR_NULL for a NULL array when n > 0; nothing is written then.
 * The accuracy bound above for sampled directions is tested for every batch sampler. */
ggx_status ggx_batch_sample_normals(ggx_sampler_id sampler, float *mx, float *my, float *mz, size_t n,
                                    const ggx_shape *s, const float *vx, const float *vy, const float *vz,
                                    const float *u1, const float *u2);

/* The BRDF f_r(wi, wo) (ggx_brdf_eval) with the Fresnel term f (any kind). */
void ggx_batch_brdf(float *f_r, size_t n, const ggx_shape *s, const ggx_fresnel *f, const float *wix, const float *wiy,
                    const float *wiz, const float *wox, const float *woy, const float *woz);

/* Reflection sampling (ggx_sample_brdf): direction, pdf and weight; invalid samples are written as w = 0, pdf = 0,
 * weight = 0. */
void ggx_batch_sample_brdf(float *wox, float *woy, float *woz, float *pdf, float *weight, size_t n, const ggx_shape *s,
                           const ggx_fresnel *f, const float *wix, const float *wiy, const float *wiz, const float *u1,
                           const float *u2);

/* Directions from any sampler of the registry with batch = 1 and family DIRECTION: reflection sampling
 * (GGX_SAMPLER_BRDF, as ggx_batch_sample_brdf) and bounded reflection sampling (GGX_SAMPLER_BRDF_BOUNDED, the loop of
 * ggx_sample_brdf_bounded_f: ggx_sample_brdf_bounded in float), with the same outputs and bounds as
 * ggx_batch_sample_brdf. f NULL means F = 1. GGX_ERR_RANGE for another sampler, GGX_ERR_NULL for a NULL array or
 * shape when n > 0; nothing is written then. */
ggx_status ggx_batch_sample_directions(ggx_sampler_id sampler, float *wox, float *woy, float *woz, float *pdf,
                                       float *weight, size_t n, const ggx_shape *s, const ggx_fresnel *f,
                                       const float *wix, const float *wiy, const float *wiz, const float *u1,
                                       const float *u2);

#ifdef __cplusplus
}
#endif

#endif /* GGX_GGX_BATCH_H */
