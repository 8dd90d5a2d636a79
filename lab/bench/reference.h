/* Plain transcriptions of the formulas libggx implements, for the benchmark only (see reference.c).
 * SPDX-License-Identifier: MIT */
#ifndef GGX_BENCH_REFERENCE_H
#define GGX_BENCH_REFERENCE_H

#include "ggx/ggx.h"

/* The names of the transcriptions: lab/bench/isa_v3.c compiles this file a second time for x86-64-v3 with a suffix. */
#ifndef REF_FN
#define REF_FN(name) name
#endif

/* Matrices are row-major and canonical (A n along +z, n = +z), as ggx_shape stores them in a and ainv_t. */

/* Spherical-cap VNDF sampler for any A, double, libm sin/cos. */
ggx_vec3 REF_FN(ref_caps_vndf_d)(const double A[3][3], ggx_vec3 v, double u1, double u2);

/* Dupuy & Benyoub 2023 listing in float for A = diag(ax, ay, 1); the normal is written to out. */
void REF_FN(ref_caps_vndf_f_diag)(float ax, float ay, float vx, float vy, float vz, float u1, float u2, float out[3]);

/* Walter eq 6 masking. */
double REF_FN(ref_g1_eq6)(const double A[3][3], ggx_vec3 u, ggx_vec3 m);

/* Walter eq 33 visible-normal density; AinvT = A^{-T} and det = |det A| precomputed by the caller. */
double REF_FN(ref_pdf_vndf_eq33)(const double A[3][3], const double AinvT[3][3], double det, ggx_vec3 v, ggx_vec3 m);

/* sqrtf(x) + sinf(2 pi u1) + cosf(2 pi u1): the libm calls every float sampler makes, as a floor. */
float REF_FN(ref_sqrt_sincos_f)(float u1, float x);

#endif
