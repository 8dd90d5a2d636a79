/* The exported double API: the kernels of ggx_inline.h and the export macro. SPDX-License-Identifier: MIT */
#ifndef GGX_API_INTERNAL_H
#define GGX_API_INTERNAL_H

/* The library inlines every kernel into its exported functions and batch loops (no call overhead, and loops the
 * compiler can vectorise). */
#if defined(__GNUC__)
#define GGX_HD static inline __attribute__((always_inline, unused))
#endif
#include "ggx/ggx_inline.h"
#include "ggx/ggx_samplers.h"

/* Every public function is defined with GGX_API; the library is built with hidden visibility, so libggx.so exports
 * exactly the public ggx_* API (tests/packaging/exports.sh checks it). */
#if defined(__GNUC__)
#define GGX_API __attribute__((visibility("default")))
#else
#define GGX_API
#endif

/* The per-element functions of the double API are compiled twice, for the baseline instruction set and for x86-64-v3
 * (AVX2 + FMA), and the loader picks one per process (GNU ifunc, resolved once at load time: nothing to race). With
 * FMA contraction (-ffp-contract=fast in CMakeLists.txt) the kernels' dot products and polynomials take one rounding
 * where the baseline takes two: results differ between the two builds in the last bits only (within the accuracy
 * each header states; tests/test_golden runs against both builds). -DGGX_NO_CLONES builds the baseline only, and so
 * does clang: clang 14 names the resolver of a hidden function's clones name.ifunc and leaves name itself undefined. */
#if !defined(GGX_NO_CLONES) && defined(__GNUC__) && !defined(__clang__) && defined(__ELF__) && defined(__x86_64__) &&  \
    !defined(__CUDACC__)
#define GGX_HOT __attribute__((target_clones("arch=x86-64-v3", "default")))
/* GGX_HOT and an x86-64-v4 (AVX-512) clone: for the fits' passes, whose reductions hold more sums than AVX2's 16
 * registers (a 4096^2 height field's fit runs in about half the time) */
#define GGX_HOT_WIDE __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define GGX_HOT
#define GGX_HOT_WIDE
#endif

/* F = 1, what a NULL const ggx_fresnel * means in every exported function that takes one (ggx.h, "Conventions");
 * the value ggx_fresnel_one sets. From src/api/fresnel.c. */
extern const ggx_fresnel ggx_internal_fresnel_one;
#define GGX_FRESNEL_OR_ONE(f) ((f) ? (f) : &ggx_internal_fresnel_one)

/* From src/api/albedo.c, for the energy tables (src/api/energy.c): E(v) of a unit v with v.z > 0 to an absolute
 * error of about tol (hc: height-correlated G2), and the separable factor of ggx_albedo's E,
 * P(v) = ||A v|| G1(v) / (v.z ||A n||), which carries E's steepest dependence on the view: E = P(v) I(v) with I
 * smooth (docs/design/albedo.md). v.z > 0. */
double ggx_internal_albedo(const ggx_shape *s, ggx_vec3 v, int hc, double tol);
double ggx_internal_albedo_scale(const ggx_shape *s, ggx_vec3 v);
/* From src/api/albedo.c: R + T of ggx_bsdf_albedo in one quadrature, for a unit v with v.z != 0, to an absolute
 * error of about tol (the energy tables of the rough dielectric, src/api/energy_bsdf.c). */
double ggx_internal_bsdf_albedo(const ggx_shape *s, double eta, ggx_vec3 v, double tol);
/* Whether E depends on the view's polar angle only: unskewed with alpha_x = alpha_y (to 1e-12). */
int ggx_internal_is_isotropic(const ggx_shape *s);
/* From src/api/tables.c: I = E / P of the shipped isotropic table (separable G) at row coordinate y in [0, 1]
 * (theta = (pi / 2)(1 - y^2)) for alpha; returns 0 (and writes nothing) for alpha outside the table's range. */
int ggx_internal_iso_table_i(double alpha, double y, double *i_value);
/* From src/api/tables.c: I = E / P of the shipped table of the rough dielectric's R + T for isotropic shapes at row
 * coordinate y, alpha and the relative index eta_r the light meets (eta from above, 1 / eta from below); returns 0
 * (and writes nothing) outside the table's range. */
int ggx_internal_bsdf_iso_table_i(double alpha, double eta_r, double y, double *i_value);
/* From src/api/tables.c: I = E / P of the shipped anisotropic table (separable G) of the diagonal shape
 * (alpha_x, alpha_y) at row coordinate y and warped azimuth psi in [0, pi / 2] from the axis of alpha_x
 * (cols_psi_of_xy, common/albedo_rows.h); returns 0 (and writes nothing) for a roughness outside the table's range. */
int ggx_internal_aniso_table_i(double alpha_x, double alpha_y, double y, double psi, double *i_value);
/* From src/api/tables.c: whether the shipped anisotropic table serves (alpha_x, alpha_y): both in its roughness
 * range and the anisotropy within its promise (1:20). */
int ggx_internal_aniso_table_serves(double alpha_x, double alpha_y);

#endif
