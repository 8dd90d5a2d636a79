/*
 * libggx — the ellipsoid as a volume of microflakes: the SGGX distribution (Heitz, Dupuy, Crassin, Dachsbacher 2015,
 * "The SGGX microflake distribution"). Derivations, proofs and the checks behind each statement: docs/design/sggx.md.
 * Included by ggx.h, at its end (it needs ggx.h's types): programs include ggx.h.
 *
 * SPDX-License-Identifier: MIT
 *
 * Conventions
 * - A flake distribution is a symmetric positive definite 3x3 matrix S. Its flakes are the surface elements of the
 *   ellipsoid x^T S x = 1 (two-sided: D(-m) = D(m)); directions live in any frame the caller chooses (the medium's),
 *   all unit vectors pointing AWAY from the scattering point, as everywhere in libggx.
 * - D is Heitz's, D(m) = 1 / (pi sqrt(|S|) (m^T S^-1 m)^2) on the whole sphere, normalised as Heitz normalises it:
 *   the projected area of the flakes seen from w is
 *       sigma(w) = integral of D(m) max(0, w.m) dm = sqrt(w^T S w)    (= 1/2 of the integral of D(m) |w.m| dm),
 *   and the integral of D over the sphere is not 1 but the ellipsoid's area times sqrt(|S|) / pi (4 for S = I).
 *   S and c S (c > 0) scatter alike; sigma and D scale with sqrt(c), the extinction of a medium of flake density rho
 *   is rho sigma(w).
 * - The phase functions f(wi, wo) are densities of wo per unit solid angle, normalised to 1 over the sphere for every
 *   wi. wi is the direction the particle came from and wo the one it leaves along, both pointing away from the
 *   point: a ray travelling along d that scatters has wi = -d. This is Heitz's own convention (his omega_i and
 *   omega_o are our wi and wo); in a path tracer that starts at the camera, wi points back towards the camera.
 *   Reciprocity: sigma(wi) f(wi, wo) = sigma(wo) f(wo, wi).
 * - Setup functions validate and return a ggx_status (the output unchanged on failure); hot functions validate
 *   nothing beyond what is stated. A NaN or infinite component of a direction gives 0 (evaluations) or the zero
 *   vector (samplers); so does a zero direction. Directions are not normalised: non-unit input is a precondition
 *   violation with a finite, meaningless result (the samplers and sigma's homogeneity excepted, as stated).
 * - Random numbers u are read in [0, 1]: NaN is read as 0, values outside are clamped. Every sampler returns a unit
 *   vector (| ||w|| - 1 | <= 1e-12) for u in [0, 1 - 2^-24] and for u = 1.
 * - Float, batch and inline forms are not provided yet; everything here is double.
 */
#ifndef GGX_GGX_SGGX_H
#define GGX_GGX_SGGX_H

#ifndef GGX_GGX_H
#error "include ggx/ggx.h: it declares the types these functions take, and includes this header"
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* A flake distribution: a complete type, kept by value and copied freely; every field is read-only, set only by
 * ggx_sggx_from_*. It stores S with what every function needs precomputed. */
typedef struct ggx_sggx {
    double s[3][3];        /* S, symmetric, row-major, as given (symmetrised) */
    double half[3][3];     /* S^(1/2), the symmetric square root: sigma(w) = ||S^(1/2) w|| */
    double half_inv[3][3]; /* S^(-1/2): m^T S^-1 m = ||S^(-1/2) m||^2 */
    double axes[3][3];     /* rows: the unit eigenvectors of S, eigenvalues ascending */
    double eig[3];         /* the eigenvalues of S, ascending, > 0 */
    double ndf_scale;      /* 1 / (pi sqrt(|S|)) */
} ggx_sggx;

/* The distribution of matrix S (row-major, S[row][col]). S must be symmetric (|S_ij - S_ji| <= 1e-12 max|S_kl|; the
 * mean of the two is kept), positive definite with lambda_min > GGX_SINGULAR_TOL lambda_max, and of trace in
 * [GGX_MATRIX_SCALE_MAX^-2, GGX_MATRIX_SCALE_MAX^2]. Errors: GGX_ERR_NULL, GGX_ERR_NONFINITE, GGX_ERR_RANGE (not
 * symmetric, or the trace out of range), GGX_ERR_SINGULAR (an eigenvalue <= GGX_SINGULAR_TOL lambda_max: singular,
 * indefinite or too ill-conditioned). */
ggx_status ggx_sggx_from_matrix(ggx_sggx *f, const double S[3][3]);

/* The flakes of a shape's own ellipsoid x^T A^T A x = 1 (Walter eq 8, Ce = 1): S = A^T A, so that on the upper
 * hemisphere D_sggx(m) = sigma(n) ggx_ndf(s, m) with sigma(n) = ||A n|| (docs/design/sggx.md: A^T A, not A A^T nor
 * an inverse; tested to 1e-12 relative on skewed and rotated shapes), and sigma(w) = |A| ggx_projected_area(s, w) / pi.
 * Every shape whose A has sigma_min(A)^2 > GGX_SINGULAR_TOL sigma_max(A)^2 (the others, such as alphas 1e-3 and 1e3
 * together, give GGX_ERR_SINGULAR). Errors: GGX_ERR_NULL, GGX_ERR_SINGULAR. */
ggx_status ggx_sggx_from_shape(ggx_sggx *f, const ggx_shape *s);

/* D(m) = 1 / (pi sqrt(|S|) (m^T S^-1 m)^2), unit m anywhere on the sphere; D(-m) = D(m). Zero m or NaN: 0. */
double ggx_sggx_ndf(const ggx_sggx *f, ggx_vec3 w);

/* sigma(w) = sqrt(w^T S w) = ||S^(1/2) w||, the projected area of the flakes seen from w (per unit flake density),
 * sigma(-w) = sigma(w). Homogeneous: any w gives ||w|| sigma(w / ||w||); zero or NaN: 0. */
double ggx_sggx_sigma(const ggx_sggx *f, ggx_vec3 w);

/* The distribution of normals visible from wi, pdf D_wi(m) = max(0, wi.m) D(m) / sigma(wi) (which integrates to 1
 * over the sphere): with H = S^(1/2) and a = H wi / ||H wi||, a sphere-space point cosine-distributed about a, drawn
 * as a + s with s uniform on the unit sphere (z = 1 - 2 u1, azimuth 2 pi u2; no frame), and m = normalize(H (a + s)).
 * Any wi != 0 (only its direction matters); wi.m > 0 for every u. The s within 2^-20 of -a (probability 2^-42, where
 * a + s would be rounding) give the normal at a, normalize(S wi). */
ggx_vec3 ggx_sggx_sample_vndf(const ggx_sggx *f, ggx_vec3 wi, double u1, double u2);

/* The specular flakes' phase function, f(wi, wo) = D(h) / (4 sigma(wi)) with h = normalize(wi + wo): the flake
 * whose mirror reflection takes the incoming particle from wi to wo. Integrates to 1 over wo; reciprocal. wo = -wi
 * exactly (h undefined, a set of measure zero) gives 0. */
double ggx_sggx_phase_specular(const ggx_sggx *f, ggx_vec3 wi, ggx_vec3 wo);

/* Samples ggx_sggx_phase_specular exactly: m = ggx_sggx_sample_vndf(f, wi, u1, u2), wo = 2 (wi.m) m - wi normalised,
 * whose pdf is ggx_sggx_phase_specular(f, wi, wo) (the weight is 1). Unit wi (the normalisation makes wo the mirror of
 * wi's direction for any moderate length). */
ggx_vec3 ggx_sggx_sample_specular(const ggx_sggx *f, ggx_vec3 wi, double u1, double u2);

/* The diffuse (Lambertian) flakes' phase function, f(wi, wo) = integral of D_wi(m) max(0, wo.m) / pi dm, evaluated
 * deterministically: reduced to sphere space, f = sigma(wo) / pi^2 times the integral over the lune
 * {u : (H wi).u >= 0, (H wo).u >= 0} of (a.u)(b.u) / sigma(u) (a, b the unit H wi, H wo), whose inner integral along
 * the lune's great semicircles is elementary and whose outer one is adaptive Gauss-Kronrod, split where the
 * semicircles pass nearest S's flattest directions (docs/design/sggx.md). Accuracy: relative error below 1e-4 (tested
 * against an independent adaptive quadrature over 40 random S with eigenvalue ratios to 1e-4 and shapes skewed and
 * rotated down to alpha = 1e-3, measured 2.6e-9; measured 5.2e-6 at most against the same algorithm at tolerance
 * 1e-13 over 8000 pairs, eigenvalue ratios down to 1e-8). Cost (timed in docs/performance.md): 15 evaluations of
 * the inner integral for a nearly isotropic S, about 40 for strongly anisotropic ones. Only the directions of wi, wo
 * matter. Integrates to 1 over wo; reciprocal; f(wi, -wi) = 0 (no flake faces both). */
double ggx_sggx_phase_diffuse(const ggx_sggx *f, ggx_vec3 wi, ggx_vec3 wo);

/* Samples ggx_sggx_phase_diffuse exactly: m = ggx_sggx_sample_vndf(f, wi, u1, u2), then wo cosine-distributed about
 * m, drawn as m + s normalised with s uniform on the unit sphere from u3, u4 (as the VNDF sampler draws a + s; wo = m
 * where s is within 2^-20 of -m), so that the pdf of wo is ggx_sggx_phase_diffuse(f, wi, wo) (the weight is 1). Any
 * wi != 0. */
ggx_vec3 ggx_sggx_sample_diffuse(const ggx_sggx *f, ggx_vec3 wi, double u1, double u2, double u3, double u4);

#ifdef __cplusplus
}
#endif

#endif /* GGX_GGX_SGGX_H */
