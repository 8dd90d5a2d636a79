/* libggx kernels: the precision traits. Included by ggx_inline.h before each instantiation of the kernels, with
 * GGX_K_PRECISION set to 32 or 64; kernel/untraits.h undoes it. Every precision-dependent choice of the kernels is
 * here, each with its reason; the derivations of the constants: docs/design/kernels.md, "Precision traits".
 * SPDX-License-Identifier: MIT */
#if GGX_K_PRECISION == 32
#define ggx_r float
#define ggx_v3 ggx_vec3f
#define ggx_v2 ggx_vec2f
#define GGX_SH ggx_shapef
#define GGX_FR ggx_fresnelf
#define GGX_SMP ggx_samplef
#define GGX_FN(name) ggx_##name##_f
#define GGX_C(x) x##f
#define GGX_SQRT sqrtf
#define GGX_FLOOR floorf
#define GGX_FABS fabsf
#define GGX_SIN sinf
#define GGX_COS cosf
#define GGX_ACOS acosf
#define GGX_ATAN atanf
#define GGX_ATAN2 atan2f
/* The largest finite value: results above it are overflow and become 0 by the contract. */
#define GGX_HUGE FLT_MAX
/* The conductor's |eta + i k| is scaled into [TINY, BIG] (fresnel_conductor_eval): (BIG^2)^2 stays below FLT_MAX and
 * TINY^4 above FLT_MIN, and F is 1 within 4e-8 beyond them. */
#define GGX_COND_BIG GGX_C(1e8)
#define GGX_COND_TINY GGX_C(1e-8)
/* The fast paths' "not final" marker. */
#define GGX_NAN ((float)NAN)
#define GGX_ROUND_MAGIC 12582912.0f  /* 1.5 2^23: x + it - it rounds x to an integer for |x| < 2^22 */
#define GGX_QUARTER_MAGIC 3145728.0f /* 1.5 2^21: x + it - it rounds x to a multiple of 1/4 for |x| < 2^20 */
/* Rim step in sphere space: samples on the rim of the lune (pdf 0) are moved inside by this much, as in double, so
 * that the float sampler follows the double one to the rim (m.v is verified after the move). */
#define GGX_RIM_STEP GGX_C(9.313225746154785e-10) /* 2^-30 */
/* A sampled normal must face the view by this much (m.v >= margin) to have a pdf > 0 in float and in double: far
 * above the rounding of a float dot product of unit vectors (~2e-7). */
#define GGX_MARGIN GGX_C(9.5367431640625e-07) /* 2^-20 */
/* Doublings of the rim step before giving up: 2^-30 * 2^34 covers the whole lune. */
#define GGX_RIM_TRIES 34
/* Squared view lengths the fast path takes as they are (||A v||^2 then stays below FLT_MAX for every ggx_shapef);
 * anything else is rescaled first. */
#define GGX_L2_MIN GGX_C(1e-20)
#define GGX_L2_MAX GGX_C(1e4)
/* The caps fast path's shortest views (k_lune_core_span): as the others (GGX_L2_MIN). */
#define GGX_L2_FAST GGX_L2_MIN
/* The floor of the fast path's facing check (k_lune_core_span), on bar = margin^2 |v|^2 mu.mu: a normal number that
 * keeps mu.mu far above float's subnormals (docs/design/kernels.md, "The fast path's facing check"). Views shorter
 * than about 1e-6 (for |A| ~ 1) take the slow path. */
#define GGX_FACE_FLOOR(bar, mu2) ((bar) >= GGX_C(1e-37))
/* sin and cos of x in [-pi/4, pi/4] by minimax polynomials of degree 7 and 8: the float evaluation is within 6.9e-8
 * of sin and cos (tests/unit/test_float_regress.c checks it against libm; the fit: docs/design/kernels.md, "The turn
 * sincos"). */
#define GGX_SIN_POLY(x, x2)                                                                                            \
    ((x) * (1.0f + (x2) * (-1.666665077e-01f + (x2) * (8.331978694e-03f + (x2) * -1.949564612e-04f))))
#define GGX_COS_POLY(x2)                                                                                               \
    (1.0f + (x2) * (-0.5f + (x2) * (4.166662320e-02f + (x2) * (-1.388676348e-03f + (x2)*2.439045602e-05f))))
/* The caps' sphere-space normal h = vs + c cancels near the rim of the lune (c near -vs): where ||h||^2 < 2^-12 its
 * float direction is off by more than ~1e-5, so those elements take the slow path, which the float kernels run in
 * double. */
#define GGX_H2_MIN GGX_C(2.44140625e-4) /* 2^-12 */
/* The scalar caps sampler's proof that a normal meets the contract without the ellipsoid-space check
 * (k_lune_core_span): p.z >= GGX_PROOF_T ||A v|| and p.z^2 >= GGX_PROOF_C ||A||_F^2 for a view of length in
 * [1/2, 2]. proof: docs/design/kernels.md, "The caps fast path's proof". */
#define GGX_PROOF_T GGX_C(0.015625)
#define GGX_PROOF_C GGX_C(1.52587890625e-05) /* 2^-16 */
/* ||A||_F^2 for the proof: stored in the float shape (ggx_shapef_from), summed per call in double (ggx_shape has
 * no field for it). The float shape's a33 is 1 exactly (normalised: A' n = z), so its products skip it. */
#define GGX_FROB2(s) ((s)->a_frob2)
/* The proof is used in float, where the check it skips waits for the tiny-h test and the slow-path flags
 * (docs/performance.md, "Choices inside the kernels"). */
#define GGX_CAPS_PROOF 1
/* The plane bound's fraction is divided out in float (k_bound_frac): its terms go with ||A' wn||^5. */
#define GGX_BOUND_DIVIDE 1
#define GGX_A33(s) GGX_C(1.0)
#define GGX_B33(s) GGX_C(1.0)
#define GGX_SLOW_WIDE 1
/* The dielectric's index as the wide type (ggx_fresnelf keeps it in double too). */
#define GGX_ETA_WIDE(f) ((f)->eta_wide)
/* The wide type: the one place where float is not enough. Near the critical angle the dielectric Fresnel term has a
 * square-root singularity in 1 - sin^2 / eta^2, so sin^2 of the incident angle is formed in double from the float
 * inputs (differences and products of floats are exact in double). */
#define ggx_rw double
#elif GGX_K_PRECISION == 64
#define ggx_r double
#define ggx_v3 ggx_vec3
#define ggx_v2 ggx_vec2
#define GGX_SH ggx_shape
#define GGX_FR ggx_fresnel
#define GGX_SMP ggx_sample
#define GGX_FN(name) ggx_##name##_d
#define GGX_C(x) x
#define GGX_SQRT sqrt
#define GGX_FLOOR floor
#define GGX_FABS fabs
#define GGX_SIN sin
#define GGX_COS cos
#define GGX_ACOS acos
#define GGX_ATAN atan
#define GGX_ATAN2 atan2
#define GGX_HUGE DBL_MAX
/* As in float: (BIG^2)^2 far below DBL_MAX, TINY^4 far above DBL_MIN, F is 1 within 4e-30 beyond them. */
#define GGX_COND_BIG 1e30
#define GGX_COND_TINY 1e-30
#define GGX_NAN ((double)NAN)
#define GGX_ROUND_MAGIC 6755399441055744.0   /* 1.5 2^52 */
#define GGX_QUARTER_MAGIC 1688849860263936.0 /* 1.5 2^50 */
/* 2^-30: far above the rounding of a double dot product (1e-16); the moved set has probability ~1e-9. */
#define GGX_RIM_STEP 9.313225746154785e-10
/* 2^-48: far above the rounding of a dot product of unit vectors (~1e-16). */
#define GGX_MARGIN 3.552713678800501e-15
#define GGX_RIM_TRIES 64
/* Views whose squared length is in this range are used as they are (A v cannot overflow for the accepted shapes,
 * ||A|| <= 1e50); others are rescaled by their largest component first. */
#define GGX_L2_MIN 1e-200
#define GGX_L2_MAX 1e200
/* The double shape is not normalised (matrices are accepted at any scale), so the facing check's floor is on mu.mu
 * itself, and the fast path takes views from |v|^2 = GGX_L2_FAST, so that bar is a normal number
 * (docs/design/kernels.md, "The fast path's facing check"). Shorter views take the slow path. */
#define GGX_L2_FAST 1e-28
#define GGX_FACE_FLOOR(bar, mu2) ((mu2) >= 1e-250)
/* Taylor series to x^15 and x^16 on [-pi/4, pi/4]: remainders below 7e-17, under double rounding. */
#define GGX_SIN_POLY(x, x2)                                                                                            \
    ((x) * (1.0 + (x2) * (-1.0 / 6 +                                                                                   \
                          (x2) * (1.0 / 120 + (x2) * (-1.0 / 5040 +                                                    \
                                                      (x2) * (1.0 / 362880 +                                           \
                                                              (x2) * (-1.0 / 39916800 +                                \
                                                                      (x2) * (1.0 / 6227020800.0 +                     \
                                                                              (x2) * (-1.0 / 1307674368000.0)))))))))
#define GGX_COS_POLY(x2)                                                                                               \
    (1.0 +                                                                                                             \
     (x2) * (-0.5 + (x2) * (1.0 / 24 + (x2) * (-1.0 / 720 +                                                            \
                                               (x2) * (1.0 / 40320 +                                                   \
                                                       (x2) * (-1.0 / 3628800 +                                        \
                                                               (x2) * (1.0 / 479001600.0 +                             \
                                                                       (x2) * (-1.0 / 87178291200.0 +                  \
                                                                               (x2) * (1.0 / 20922789888000.0)))))))))
#define GGX_H2_MIN 0.0 /* double resolves h down to the rim step */
/* No proof in double: ggx_shape has no field for ||A||_F^2, and summing it per call costs more than the check's wait
 * that the proof saves (docs/performance.md, "Choices inside the kernels"). */
#define GGX_CAPS_PROOF 0
#define GGX_BOUND_DIVIDE 0
#define GGX_A33(s) ((s)->a[2][2]) /* = an_len: A' n = (0, 0, ||A n||) */
#define GGX_B33(s) ((s)->ainv_t[2][2])
#define GGX_SLOW_WIDE 0
#define GGX_ETA_WIDE(f) ((f)->eta)
#define ggx_rw double
#else
#error "GGX_K_PRECISION must be 32 or 64"
#endif
/* The bounded reflection sampler's sigma2 (k_bound_sigma2) is computed in double for both precisions and lowered by
 * 2^-20 relative: far above the rounding of its Newton step near a simple root. */
#define GGX_BOUND_SAFETY 9.5367431640625e-07
/* The bounded samplers' kappa is raised by 2^-46 before use (k_bound_frac, k_bound_frac_az): the cap's start
 * b = 1 - kappa (1 + vs.z) moves down by 128 ulps of 1, above the roundings of kappa and of the cap's height
 * (docs/design/kernels.md, "The bounded samplers' guards"). Both precisions compute kappa in double; the float
 * kernels then round it to float, as they round the cap point. */
#define GGX_KAPPA_SLACK 1.4210854715202004e-14
/* The per-azimuth bound's tolerance for a root at the start of its piece (k_bound_first): 2^-40. */
#define GGX_BOUND_TOL 9.094947017729282e-13
/* The per-azimuth bound's margin (k_bound_kappa_az): a point is removed only where the bound is below 2^-40 times
 * the sum of its terms' sizes, some 2^12 times their rounding. */
#define GGX_BOUND_MARGIN 9.094947017729282e-13
