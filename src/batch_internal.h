/* Internal: the float shape and the kernel table of one instruction-set build. SPDX-License-Identifier: MIT */
#ifndef GGX_BATCH_INTERNAL_H
#define GGX_BATCH_INTERNAL_H

#include <stddef.h>

#include "ggx/ggx.h"

typedef struct fshape {
    float a[3][3], ait[3][3]; /* canonical A' and A'^{-T}: A' n = an_len z */
    float an_len, ndf_scale;
    int diagonal;
    int fkind; /* Fresnel */
    float feta, fk, ff0;
} fshape;

typedef struct batch_kernels {
    void (*ndf)(float *, size_t, const fshape *, const float *, const float *, const float *);
    void (*g1)(float *, size_t, const fshape *, const float *, const float *, const float *, const float *,
               const float *, const float *);
    void (*pdf_vndf)(float *, size_t, const fshape *, const float *, const float *, const float *, const float *,
                     const float *, const float *);
    void (*sample_vndf)(float *, float *, float *, size_t, const fshape *, const float *, const float *,
                        const float *, const float *, const float *);
    void (*sample_vndf_aniso)(float *, float *, float *, size_t, const float *, const float *, const float *,
                              const float *, const float *, const float *, const float *);
    void (*sample_ndf)(float *, float *, float *, size_t, const fshape *, const float *, const float *);
    void (*brdf)(float *, size_t, const fshape *, const float *, const float *, const float *, const float *,
                 const float *, const float *);
    void (*sample_brdf)(float *, float *, float *, float *, float *, size_t, const fshape *, const float *,
                        const float *, const float *, const float *, const float *);
} batch_kernels;

extern const batch_kernels ggx_kernels_scalar;
extern const batch_kernels ggx_kernels_avx2;
extern const batch_kernels ggx_kernels_avx512;

#endif
