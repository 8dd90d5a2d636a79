/* Internal: the loops of one instruction-set build of the batch API. SPDX-License-Identifier: MIT */
#ifndef GGX_BATCH_INTERNAL_H
#define GGX_BATCH_INTERNAL_H

#include <stddef.h>

#include "api/internal.h"

/* Every loop takes [begin, end) of the caller's arrays. */
typedef struct batch_args {
    const ggx_shapef *s;
    ggx_fresnelf f;
    int sampler; /* ggx_sampler_id for normals */
    float *out[5];
    const float *in[8];
} batch_args;

typedef void (*batch_loop)(const batch_args *a, size_t begin, size_t end);

typedef struct batch_kernels {
    batch_loop ndf, g1, pdf_vndf, normals, normals_aniso, brdf, sample_brdf;
} batch_kernels;

extern const batch_kernels ggx_kernels_scalar;
extern const batch_kernels ggx_kernels_avx2;
extern const batch_kernels ggx_kernels_avx512;

#endif
