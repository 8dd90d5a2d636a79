/* The inline float sampler and the float listing it is measured against, compiled for x86-64-v3 (AVX2 and FMA, with
 * FMA contraction), as a renderer built for that level compiles both. At the baseline x86-64 level the listing's
 * sincosf and fmaf are libm calls that glibc dispatches at run time to FMA code, where the inline header's
 * polynomials are compiled without FMA: the baseline rows of the bench compare different instruction sets, these
 * compare the same one. Both are reached through one call from bench.c. SPDX-License-Identifier: MIT */
#define REF_FN(name) name##_v3
#include "reference.c"

#include "isa_v3.h"

int bench_v3_supported(void)
{
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
}

float bench_v3_vndf_f_z(const ggx_shapef *s, const float v[3], float u1, float u2)
{
    ggx_vec3f w = {v[0], v[1], v[2]};
    return ggx_sample_vndf_f(s, w, u1, u2).z;
}

float bench_v3_listing_z(float ax, float ay, const float v[3], float u1, float u2)
{
    float m[3];
    REF_FN(ref_caps_vndf_f_diag)(ax, ay, v[0], v[1], v[2], u1, u2, m);
    return m[2];
}
