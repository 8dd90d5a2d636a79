/* The float sampler comparison of bench.c compiled for x86-64-v3 (lab/bench/isa_v3.c). SPDX-License-Identifier: MIT */
#ifndef GGX_BENCH_ISA_V3_H
#define GGX_BENCH_ISA_V3_H

#include "ggx/ggx_inline.h"

/* Whether this CPU runs x86-64-v3 code (AVX2, FMA, BMI2...): the two functions below may be called only then. */
int bench_v3_supported(void);
/* ggx_sample_vndf_f(s, v, u1, u2).z, the inline sampler compiled for x86-64-v3. */
float bench_v3_vndf_f_z(const ggx_shapef *s, const float v[3], float u1, float u2);
/* The Dupuy-Benyoub listing of lab/bench/reference.c for diag(ax, ay, 1), compiled for x86-64-v3: the normal's z. */
float bench_v3_listing_z(float ax, float ay, const float v[3], float u1, float u2);

#endif
