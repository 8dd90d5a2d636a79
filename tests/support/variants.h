/* The variants of the library's math under test, behind one table of function pointers with double-typed,
 * block-wise signatures, so that one test body runs over all of them (as cglm and SLEEF test their inline and
 * compiled builds with one body):
 * - "exported": the double API of ggx.h (the samplers through the registry's table, ggx_sampler_get);
 * - "inline-d": the double kernels of ggx_inline.h (ggx_<stem>_d on ggx_shape), compiled into the test;
 * - "inline-f": the float kernels of ggx_inline.h (ggx_<stem>_f on the ggx_shapef of ggx_shapef_from), inputs
 *   rounded to float and results widened;
 * - "batch-scalar", "batch-avx2", "batch-avx512": the float batch API of ggx_batch.h on that instruction set
 *   (variant_available says whether ggx_batch_set_isa accepts it on this CPU and build).
 * The samplers of each variant come from GGX_SAMPLER_LIST, so a new registry line is in every variant that has it.
 * SPDX-License-Identifier: MIT */
#ifndef GGX_TEST_VARIANTS_H
#define GGX_TEST_VARIANTS_H

#include <stddef.h>

#include "ggx/ggx_batch.h"
#include "ggx/ggx_samplers.h"

typedef struct variant variant;
struct variant {
    const char *name;
    int precision;           /* 64 or 32: which accuracy bounds apply (ggx_batch.h states the float ones) */
    ggx_batch_isa isa;       /* batch variants: the instruction set; GGX_ISA_AUTO for the others */
    int nonfinite_u_invalid; /* 1: a NaN or infinite u gives the zero vector (ggx_batch.h); 0: NaN is read as 0
                              * and u is clamped into [0, 1] (ggx.h, and the inline kernels) */
    /* Whether the variant has sampler id: 1 for a sampler of normals run by sample (NDF and VNDF families),
     * 2 for a rejection sampler run by sample_reject, 3 for a direction sampler (exported only: the registry's
     * sample_direction and pdf_direction, which test_sample_dir.c runs), 0 when it has none. */
    int (*has)(const variant *vr, ggx_sampler_id id);
    /* n normals of sampler id for views v[i] (NDF samplers ignore them) and random numbers (u1[i], u2[i]). */
    void (*sample)(const variant *vr, ggx_sampler_id id, const ggx_shape *s, size_t n, const ggx_vec3 *v,
                   const double *u1, const double *u2, ggx_vec3 *m);
    /* One normal of rejection sampler id (as ggx_sample_vndf_walter_v1). */
    ggx_vec3 (*sample_reject)(const variant *vr, ggx_sampler_id id, const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next,
                              void *state, unsigned *trials);
    /* The pdf that sampler id claims (its family's: D(m) m.n for NDF, Walter eq 33 for VNDF and REJECTION). */
    void (*sampler_pdf)(const variant *vr, ggx_sampler_id id, const ggx_shape *s, size_t n, const ggx_vec3 *v,
                        const ggx_vec3 *m, double *pdf);
    /* Evaluations: D(m), G1(u, m), the VNDF pdf D_v(m), the BRDF f_r(wi, wo). */
    void (*ndf)(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *m, double *d);
    void (*g1)(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *u, const ggx_vec3 *m, double *g);
    void (*pdf_vndf)(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *v, const ggx_vec3 *m,
                     double *pdf);
    void (*brdf)(const variant *vr, const ggx_shape *s, const ggx_fresnel *f, size_t n, const ggx_vec3 *wi,
                 const ggx_vec3 *wo, double *fr);
    /* The default samplers of each variant (ggx_sample_vndf, ggx_sample_ndf and their twins; the batch API's
     * ggx_batch_sample_vndf and ggx_batch_sample_ndf), and reflection sampling (ggx_sample_brdf, or with bounded
     * ggx_sample_brdf_bounded; the batch API's ggx_batch_sample_directions). */
    void (*sample_vndf)(const variant *vr, const ggx_shape *s, size_t n, const ggx_vec3 *v, const double *u1,
                        const double *u2, ggx_vec3 *m);
    void (*sample_ndf)(const variant *vr, const ggx_shape *s, size_t n, const double *u1, const double *u2,
                       ggx_vec3 *m);
    void (*sample_brdf)(const variant *vr, int bounded, const ggx_shape *s, const ggx_fresnel *f, size_t n,
                        const ggx_vec3 *wi, const double *u1, const double *u2, ggx_sample *out);
    /* Per-element anisotropic GGX (ggx_batch_sample_vndf_aniso); NULL where the variant has no such function. */
    void (*sample_vndf_aniso)(const variant *vr, size_t n, const double *alpha_x, const double *alpha_y,
                              const ggx_vec3 *v, const double *u1, const double *u2, ggx_vec3 *m);
};

enum { VARIANT_COUNT = 6 };
extern const variant VARIANTS[VARIANT_COUNT];
#define VARIANT_EXPORTED (&VARIANTS[0]) /* the reference: the exported double API */

/* Whether the variant runs here (batch variants: the instruction set is compiled in and the CPU has it). */
int variant_available(const variant *vr);
/* Its index in VARIANTS. */
int variant_index(const variant *vr);

#endif
