/*
 * libggx — GGX as the normal distribution of a truncated ellipsoid.
 *
 * SPDX-License-Identifier: MIT
 *
 * Conventions (stated once, used everywhere)
 * - Local frame: the macro-surface normal is n = +z; the tangent axes x and y are the axes of alpha_x and alpha_y.
 * - Every direction (m, u, v, wi, wo) is a unit vector in that frame pointing AWAY from the surface.
 * - The shape matrix is Walter's A (Walter et al. 2014, eq 2): A = S R with S = diag(alpha_x, alpha_y, 1) and
 *   R = Rx(theta_x) Ry(theta_y) Rz(theta_z) (eq 3). R = I gives anisotropic GGX (GTR2aniso), alpha_x = alpha_y
 *   isotropic GGX; theta_z rotates the anisotropy in the tangent plane, theta_x and theta_y skew the distribution (its
 *   peak moves away from n).
 * - The ellipsoid size constant is Ce = 1 (Walter eq 30) wherever an absolute area or curvature is returned.
 * - Angles are in radians.
 * - A NULL const ggx_fresnel * means F = 1 (GGX_FRESNEL_ONE) in every function of ggx.h and ggx_batch.h that takes
 *   one. The inline kernels of ggx_inline.h take a valid pointer (ggx_fresnelf_from needs one).
 * - "Unskewed" means that A^T A n is parallel to n (theta_x = theta_y = 0 for ggx_shape_ellipsoid). For unskewed
 *   shapes the Smith identities of GGX hold; for skewed shapes the ellipsoid forms of Walter are used throughout.
 * - Setup functions (ggx_shape_*, ggx_fresnel_*) validate their input and return a ggx_status; on failure the
 *   output is left unchanged. Hot functions (everything taking a const ggx_shape *) do no allocation and no
 *   validation beyond what is stated; the shape must come from a successful setup call.
 * - Threads: any number of threads may call any function at once; the objects passed by const pointer are only read.
 *
 * The numerical contract (tests/unit/test_robust.c: an adversarial table and 10^7 random inputs per function;
 * tests/fuzz/: raw bytes to every function under AddressSanitizer and UndefinedBehaviorSanitizer)
 * - Evaluations return a finite value >= 0 for any input (ggx_lambda: finite, and negative only for skewed shapes);
 *   outside the documented domain (a direction below the horizon where that is not allowed, a zero vector) exactly 0.
 * - NaN: a NaN or infinite component in a direction, or a NaN parameter of a hot function, gives 0 (evaluations),
 *   the zero vector (samplers) or an invalid sample. NaN random numbers u are read as 0; u outside [0, 1] is clamped.
 * - Non-unit directions are not normalised (a precondition, not checked, to keep hot paths lean): the result is the
 *   formula at that vector, meaningless but finite and >= 0. The samplers' view v is the exception: they depend on
 *   its direction only.
 * - Samplers of normals return a unit vector (| ||m|| - 1 | <= 1e-12) with a finite pdf > 0 under the matching pdf
 *   function, or the zero vector when no sample exists (view at or below the horizon, a skewed shape for
 *   ggx_sample_ndf_inversion, an exhausted rejection budget, or a visible part of the truncated ellipsoid below
 *   1e-9 of its silhouette, A_l(v, n) < 1e-9 A_e(v): a view within ~1e-9 of grazing it, which only an
 *   ill-conditioned A produces). Points on the rim of the lune, which would give a normal on the horizon or edge-on
 *   to the view (pdf 0), are moved inside (by 2^-30 in sphere space, a set of probability about 1e-9).
 * - Direction samples are either valid (unit w, finite pdf > 0, finite weight >= 0; the reflection weight is <= 1
 *   exactly, eq 52) or marked GGX_EVENT_INVALID with w = 0, pdf = 0, weight = 0.
 * - Shapes: alpha in [GGX_ALPHA_MIN, GGX_ALPHA_MAX] (tested from 1e-4 to 10 with ratios to 1:1000), skews up to
 *   GGX_SKEW_MAX; matrices must be well-conditioned (GGX_SINGULAR_TOL) and of moderate scale (GGX_MATRIX_SCALE_MAX).
 * - Accuracy: double precision with a fixed, short sequence of operations, checked against independent evaluations
 *   (closed-form GGX, quadrature of the defining integrals, finite differences, complex-arithmetic Fresnel) at the
 *   tolerances stated in each block.
 */
#ifndef GGX_GGX_H
#define GGX_GGX_H

#ifdef __cplusplus
extern "C" {
#endif

#include "ggx/ggx_version.h"

/* pi, spelled once for the library, its tools and tests ((float)GGX_PI is float's nearest value). */
#ifndef GGX_PI
#define GGX_PI 3.14159265358979323846
#endif

/* Roughness below GGX_ALPHA_MIN is raised to GGX_ALPHA_MIN by the alpha-based constructors (a mirror is a
 * delta distribution that a density cannot represent). Roughness above GGX_ALPHA_MAX is refused. */
#define GGX_ALPHA_MIN 1e-4
#define GGX_ALPHA_MAX 1e4
/* Largest |theta_x|, |theta_y| accepted by ggx_shape_ellipsoid (radians): pi / 2. */
#define GGX_SKEW_MAX 1.5707963267948966
/* ggx_shape_matrix refuses A when |det A| <= GGX_SINGULAR_TOL * ||A||_F^3 (roughly sigma_min^2 / sigma_max^2 for a
 * matrix with two small singular values). */
#define GGX_SINGULAR_TOL 1e-12
/* ggx_shape_matrix refuses A when ||A||_F is outside [1 / GGX_MATRIX_SCALE_MAX, GGX_MATRIX_SCALE_MAX], where D and
 * the areas, computed from |A| ~ ||A||^3, would underflow or overflow (c A describes the same distribution). */
#define GGX_MATRIX_SCALE_MAX 1e50

typedef struct ggx_vec3 {
    double x, y, z;
} ggx_vec3;

typedef enum ggx_status {
    GGX_OK = 0,
    GGX_ERR_NULL,      /* a required pointer argument is NULL */
    GGX_ERR_NONFINITE, /* a parameter is NaN or infinite */
    GGX_ERR_ALPHA,     /* a roughness is <= 0 or > GGX_ALPHA_MAX */
    GGX_ERR_ANGLE,     /* |theta_x| or |theta_y| > GGX_SKEW_MAX */
    GGX_ERR_SINGULAR,  /* the shape matrix is singular or too close to singular */
    GGX_ERR_ETA,       /* an index of refraction is <= 0 or above 1e300 (or 1 where a function refuses it) */
    GGX_ERR_RANGE,     /* a parameter is outside its documented range (e.g. Schlick f0 outside [0, 1]) */
    GGX_ERR_MEMORY,    /* memory could not be allocated (ggx_energy_create) */
    GGX_ERR_DATA       /* too few usable samples to fit (ggx_fit.h: fewer than 5 normals above the horizon with
                          * finite components and a positive weight) */
} ggx_status;

/* One-line English description of a status ("ok" for GGX_OK); never NULL, also for unknown values. */
const char *ggx_status_str(ggx_status status);

/* ------------------------------------------------------------------------------------------------------------
 * Shapes
 * ------------------------------------------------------------------------------------------------------------ */

typedef enum ggx_shape_kind {
    GGX_SHAPE_DIAGONAL = 0, /* A = diag(alpha_x, alpha_y, 1) up to scale and sign: anisotropic GGX, axes x and y */
    GGX_SHAPE_UNSKEWED = 1, /* A^T A n parallel to n (e.g. theta_z only): rotated anisotropic GGX */
    GGX_SHAPE_SKEWED = 2    /* general ellipsoid: A^T A n not parallel to n */
} ggx_shape_kind;

/* A shape: a complete type, kept by value and copied freely; every field is read-only, set only by ggx_shape_*.
 * It stores a canonical A' = Q A (Q the rotation taking A n to +z; A' = -A' when det A < 0), which gives exactly the
 * distributions and areas of A (Walter section 1) and has A' n = ||A n|| z. */
typedef struct ggx_shape {
    double a[3][3];      /* A', row-major */
    double ainv_t[3][3]; /* A'^{-T} */
    double det;          /* |det A| > 0 */
    ggx_vec3 an;         /* A' n = (0, 0, ||A n||) */
    double an_len;       /* ||A n|| */
    double ndf_scale;    /* 1 / (pi |A| ||A n||), the constant of Walter eq 1 */
    /* For GGX_SHAPE_DIAGONAL and GGX_SHAPE_UNSKEWED: the shape is anisotropic GGX with roughness (alpha_x, alpha_y)
     * along the tangent axes rotated by phi0 from x, y: x' = c x + s y, y' = -s x + c y with c = tangent_cos,
     * s = tangent_sin (1 and 0 for DIAGONAL). For GGX_SHAPE_SKEWED all four are 0. */
    double alpha_x, alpha_y, tangent_cos, tangent_sin;
    ggx_shape_kind kind;
} ggx_shape;

/* Isotropic GGX of roughness alpha (A = diag(alpha, alpha, 1)); alpha in (0, GGX_ALPHA_MAX], raised to GGX_ALPHA_MIN
 * below it. Errors: GGX_ERR_NULL, GGX_ERR_NONFINITE, GGX_ERR_ALPHA (never GGX_ERR_SINGULAR). */
ggx_status ggx_shape_iso(ggx_shape *s, double alpha);

/* Anisotropic GGX (GTR2aniso), R = I: A = diag(alpha_x, alpha_y, 1). Domain and errors as ggx_shape_iso, and
 * GGX_ERR_SINGULAR (alphas far apart, such as 1e-4 with 1e4) when alpha_x alpha_y <= GGX_SINGULAR_TOL
 * (alpha_x^2 + alpha_y^2 + 1)^(3/2). */
ggx_status ggx_shape_aniso(ggx_shape *s, double alpha_x, double alpha_y);

/* Walter's ellipsoid, A = diag(alpha_x, alpha_y, 1) Rx(theta_x) Ry(theta_y) Rz(theta_z) (eq 2-3): theta_z any finite
 * angle, |theta_x|, |theta_y| <= GGX_SKEW_MAX, alphas as in ggx_shape_iso.
 * Errors: GGX_ERR_NULL, GGX_ERR_NONFINITE, GGX_ERR_ALPHA, GGX_ERR_ANGLE, GGX_ERR_SINGULAR (as ggx_shape_aniso). */
ggx_status ggx_shape_ellipsoid(ggx_shape *s, double alpha_x, double alpha_y, double theta_x, double theta_y,
                               double theta_z);

/* The matrix A of ggx_shape_ellipsoid (eq 2-3), row-major, as a user writes it (the shape stores Q A instead). Same
 * domain, alpha below GGX_ALPHA_MIN raised to it; ggx_shape_matrix of the result is ggx_shape_ellipsoid's shape, bit
 * for bit (tests/unit/test_errors.c). Each entry is within 2 ulp of the exact product of the sines and cosines of the
 * rounded angles. Errors: GGX_ERR_NULL (A NULL), GGX_ERR_NONFINITE (an angle or alpha NaN or infinite),
 * GGX_ERR_ALPHA, GGX_ERR_ANGLE; never GGX_ERR_SINGULAR. A is unchanged on error. */
ggx_status ggx_ellipsoid_matrix(double A[3][3], double alpha_x, double alpha_y, double theta_x, double theta_y,
                                double theta_z);

/* Any invertible A, row-major (A[row][col], so A n is the last column). A, c A (c != 0) and Q A (Q orthogonal) give
 * the same distributions (a negative determinant is handled by using -A); absolute areas (ggx_projected_area,
 * ggx_lune_area) and the curvature depend on the scale of A (Ce = 1).
 * Errors: GGX_ERR_NULL, GGX_ERR_NONFINITE, GGX_ERR_SINGULAR (|det A| <= GGX_SINGULAR_TOL ||A||_F^3), GGX_ERR_RANGE
 * (||A||_F outside [1 / GGX_MATRIX_SCALE_MAX, GGX_MATRIX_SCALE_MAX]). */
ggx_status ggx_shape_matrix(ggx_shape *s, const double A[3][3]);

/* The location t = (t_x, t_y) and scale sigma = (Sigma_xx, Sigma_xy, Sigma_yy) of the shape's slopes, a Student t
 * with 2 degrees of freedom (P22 of ggx_fit.h; docs/design/slopes.md): t is the slope of the mean normal A^T A n (0
 * exactly for unskewed shapes), Sigma = alpha^2 I for isotropic GGX, and the shapes are exactly the pairs (t, Sigma)
 * with Sigma positive definite. Each entry is within a few ulp of the products of the stored A'; D rebuilt from them
 * matches ggx_ndf to 1e-12 + 2e-15 kappa(A)^2 relative, kappa(A) = max(ax, ay, 1) / min(ax, ay, 1) for
 * ggx_shape_ellipsoid (tests/unit/test_slopes.c: alphas from 1e-3 to 10, skews to GGX_SKEW_MAX). Errors: GGX_ERR_NULL
 * (any pointer NULL). */
ggx_status ggx_shape_slopes(const ggx_shape *s, double t[2], double sigma[3]);

/* The shape whose slopes have location (tx, ty) and scale Sigma = [sxx sxy; sxy syy]: A = [B 0; -t^T 1] with
 * B = Sigma^(1/2), the symmetric square root, so that ggx_shape_slopes gives back (t, Sigma) to rounding. An
 * eigenvalue of Sigma below GGX_ALPHA_MIN^2 is raised to it (its eigenvector is kept). Errors: GGX_ERR_NULL;
 * GGX_ERR_NONFINITE (an argument NaN or infinite); GGX_ERR_ALPHA (Sigma not positive semi-definite: sxx < 0, syy < 0
 * or sxx syy < sxy^2 beyond rounding, or an eigenvalue above GGX_ALPHA_MAX^2); GGX_ERR_SINGULAR and GGX_ERR_RANGE as
 * for ggx_shape_matrix (|t| or the eigenvalues' ratio too large). s is unchanged on error. */
ggx_status ggx_shape_from_slopes(ggx_shape *s, double tx, double ty, double sxx, double sxy, double syy);

/* The parameters of ggx_shape_ellipsoid that give the same distribution as s: D from them equals ggx_ndf(s, .) to
 * 1e-12 kappa(A) relative (kappa as for ggx_shape_slopes; tested on random shapes). Of the equivalent sets it returns
 * the one whose third axis (the row of R with eigenvalue 1 of A^T A) is the principal axis of A^T A nearest to n, so
 * |theta_x|, |theta_y| < pi / 2 strictly, and of the four quarter turns about it the one with the smallest |theta_z|
 * (below pi / 2); theta_z = 0 for alpha_x = alpha_y (to 1e-12 relative). A shape made by ggx_shape_ellipsoid from
 * such parameters gives them back to about 1e-13 kappa(A)^2 (tested with |theta_x|, |theta_y| <= 0.45 and
 * |theta_z| <= 0.5). alpha_x or alpha_y may be below GGX_ALPHA_MIN for a shape from ggx_shape_matrix. Any output
 * pointer may be NULL. Errors: GGX_ERR_NULL (s NULL). */
ggx_status ggx_shape_ellipsoid_params(const ggx_shape *s, double *alpha_x, double *alpha_y, double *theta_x,
                                      double *theta_y, double *theta_z);

/* ------------------------------------------------------------------------------------------------------------
 * The distribution of normals
 * ------------------------------------------------------------------------------------------------------------ */

/* D(m) = X+(m.n) / (pi |A| ||A n|| ||A^{-T} m||^4) (Walter eq 1), unit m; m.z < 0 gives 0 (X+(0) = 1: the horizon
 * itself is inside).
 * Normalised: the integral of D(m) (m.n) over the hemisphere is 1 for every A (tested to 1e-9 relative). For R = I it
 * is 1 / (pi ax ay (mx^2/ax^2 + my^2/ay^2 + mz^2)^2), anisotropic GGX. */
double ggx_ndf(const ggx_shape *s, ggx_vec3 m);

/* D(theta, phi) = D(m) sin(theta), m = (sin theta cos phi, sin theta sin phi, cos theta): the NDF as a density over
 * the spherical angles (blog Part 1). theta in [0, pi/2] (else 0), phi any. */
double ggx_ndf_spherical(const ggx_shape *s, double theta, double phi);

/* P22(x~, y~) = D(m) cos^4(theta_m) for the slopes x~ = -mx/mz, y~ = -my/mz of m (blog Part 1); for any A
 * it is 1 / (pi |A| ||A n|| ||A^{-T} (-x~, -y~, 1)||^4); integrates to 1 over the plane. Any finite slopes. */
double ggx_p22(const ggx_shape *s, double slope_x, double slope_y);

/* Gaussian curvature of the ellipsoid x^T A^T A x = 1 (Ce = 1) where the outward normal is m:
 * Kg(m) = |A|^2 ||A^{-T} m||^4 (Walter eq 20), on the whole sphere (m.z of any sign); zero m gives 0.
 * D(m) = 1 / (A_perp_e(n) Kg(m)) for m.z >= 0 (eq 9). Tested against finite differences of the Gauss map. */
double ggx_gaussian_curvature(const ggx_shape *s, ggx_vec3 m);

/* Projected area of the ellipsoid seen from direction u (Ce = 1): pi ||A u|| / |A| (eq 26). Any unit u. */
double ggx_projected_area(const ggx_shape *s, ggx_vec3 u);

/* Projected area, seen from u, of the ellipsoidal lune {m.u >= 0 and m.v >= 0} (Ce = 1):
 * pi (||A u|| ||A v|| + (A u).(A v)) / (2 |A| ||A v||) (eq 28); ggx_lune_area(s, u, u) = ggx_projected_area(s, u).
 * Any unit u, v; a zero v gives 0. With v = n it is the truncated microsurface: the integral of
 * X+(m.u) D(m) (m.u) dm = A_perp_l(u, n) / A_perp_e(n) (tested by quadrature, grazing u included). */
double ggx_lune_area(const ggx_shape *s, ggx_vec3 u, ggx_vec3 v);

/* ------------------------------------------------------------------------------------------------------------
 * Masking
 * ------------------------------------------------------------------------------------------------------------ */

/* Walter's ellipsoid masking term, eq 6 / eq 32:
 * G1(u, m) = min(1, A_perp_e(n) |u.n| / A_perp_l(u, n)) X+(u.m)
 *          = min(1, 2 ||A n||^2 |u.n| / (||A u|| ||A n|| + (A u).(A n))) X+(u.m), in [0, 1].
 * Domain: u.z > 0 (u.z <= 0 gives 0; for transmission pass the direction flipped to the upper side, eq 7). For
 * unskewed shapes the min is never active and G1 = 1 / (1 + Lambda(u)) with the GGX Lambda. */
double ggx_g1(const ggx_shape *s, ggx_vec3 u, ggx_vec3 m);

/* A_perp_l(u, n) / (A_perp_e(n) u.z) - 1, the direction-only part of eq 32 without the min: for unskewed shapes
 * Smith's GGX Lambda(u) = (sqrt(1 + alpha(phi)^2 tan^2 theta) - 1) / 2 (blog Part 1), for skewed shapes its
 * lune-area generalisation, which may be negative (where Walter's min clips G1 to 1). u.z <= 0 gives 0. */
double ggx_lambda(const ggx_shape *s, ggx_vec3 u);

/* Smith form G1 = 1 / (1 + Lambda(u)), without the back-facing test or the min: ggx_g1 with u.m > 0 for unskewed
 * shapes; may exceed 1 for skewed shapes. u.z <= 0 gives 0. */
double ggx_g1_smith(const ggx_shape *s, ggx_vec3 u);

/* Masking of a skewed shape read as GGX on a tilted mean plane (a patch of a tilted surface, a normal-mapped texel):
 * G1(u, m) = 2 (A u).(A n) / (||A u|| ||A n|| + (A u).(A n)) X+(u.m), the projected area of the ellipsoid's cut (the
 * plane perpendicular to A^T A n, eq 23) towards u over the lune's (eq 28), in [0, 1]; exactly ggx_g1 for unskewed
 * shapes. It is Smith's G1 of the unskewed shape of the same scale Sigma (ggx_shape_slopes) seen from
 * (u_xy, u.z - t . u_xy), the view sheared with the plane of slope t. Domain: u.z > 0 above the mean plane,
 * (A u).(A n) > 0; else 0 (also for a zero or non-finite m). Traced on explicit GGX patches (alpha 0.3 and 0.6)
 * tilted by |t| = 0.33 and 0.22 (docs/design/microsurface.md, "Skewed surfaces"), it holds within 2 % where the
 * sheared view is within 80 degrees of the tilted plane's normal and within 4.5 % to 88 degrees (as Smith's G1 does
 * on the untilted surfaces); ggx_g1 is off there by up to a factor of 5. */
double ggx_g1_tilted(const ggx_shape *s, ggx_vec3 u, ggx_vec3 m);

/* Masking of a skewed shape on a flat surface made by Walter's remedy (section 5.1): ramps of the skewed NDF that
 * step back down on vertical risers (a sawtooth). G1(u, m) = min(ggx_g1_smith(s, u), the tilted base's term of
 * ggx_g1_tilted) X+(u.m), in [0, 1]: where the risers face away from u they shadow the ramps as eq 32 without its
 * min says; where they face u they are seen unmasked and the ramps keep the tilted plane's masking. It is the limit
 * of ramps long against the roughness: traced on sawtooths of period 512 (docs/design/microsurface.md), within
 * 2 % with the risers behind, at every view to 80 degrees, and within 4 % with the risers in front where the
 * sheared view is within 76 degrees of the ramps' normal; nearer their plane the ramps' ends, unmasked by the
 * roughness beyond a riser's top, raise the traced G1 above it (33 % at 88 degrees). Domain and edge cases as
 * ggx_g1_tilted. */
double ggx_g1_risers(const ggx_shape *s, ggx_vec3 u, ggx_vec3 m);

/* Separable shadowing-masking G = G1(wi, m) G1(wo, m) (eq 5). Both directions above the horizon; else 0. */
double ggx_g2(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 m);

/* Height-correlated Smith shadowing-masking X+(wi.m) X+(wo.m) / (1 + L(wi) + L(wo)), L = max(Lambda, 0) (the
 * standard form for unskewed shapes, where Lambda >= 0; the clamp is the counterpart of Walter's min for skewed
 * shapes), in [0, 1]. Both directions above the horizon; else 0. */
double ggx_g2_height_correlated(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 m);

/* Density of visible normals for view v (Walter eq 33), a pdf over the solid angle of m:
 * D_v(m) = A_perp_e(n) / A_perp_l(v, n) X+(m.v) D(m) (m.v); integrates to 1 for every A and every v above the
 * horizon; G1(v) D(m) (m.v) / (v.n) for unskewed shapes. v.z <= 0 gives 0. */
double ggx_pdf_vndf(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);

/* ------------------------------------------------------------------------------------------------------------
 * Fresnel
 * ------------------------------------------------------------------------------------------------------------ */

/* Exact unpolarised Fresnel reflectance of a dielectric interface, eta = eta_transmitted / eta_incident > 0,
 * cos_i = |cosine| of the incidence angle (the sign is ignored, values above 1 are clamped); 1 under total
 * internal reflection. Tested against the complex-amplitude Fresnel equations and textbook values. */
double ggx_fresnel_dielectric_eval(double cos_i, double eta);

/* Exact unpolarised Fresnel reflectance of a conductor with complex relative index eta + i k (eta > 0, k >= 0),
 * cos_i as above. k = 0 reduces to ggx_fresnel_dielectric_eval without total internal reflection (eta >= 1). */
double ggx_fresnel_conductor_eval(double cos_i, double eta, double k);

/* Schlick's approximation f0 + (1 - f0) (1 - cos_i)^5, cos_i as above. */
double ggx_fresnel_schlick_eval(double cos_i, double f0);

typedef enum ggx_fresnel_kind {
    GGX_FRESNEL_ONE = 0, /* F = 1: a perfect reflector (used for energy tests) */
    GGX_FRESNEL_DIELECTRIC,
    GGX_FRESNEL_CONDUCTOR,
    GGX_FRESNEL_SCHLICK
} ggx_fresnel_kind;

/* A Fresnel term, one wavelength / channel. Zero-initialised it is GGX_FRESNEL_ONE. */
typedef struct ggx_fresnel {
    ggx_fresnel_kind kind;
    double eta; /* DIELECTRIC, CONDUCTOR: relative index (inside / outside) */
    double k;   /* CONDUCTOR: extinction coefficient */
    double f0;  /* SCHLICK: reflectance at normal incidence */
} ggx_fresnel;

ggx_status ggx_fresnel_one(ggx_fresnel *f);
ggx_status ggx_fresnel_dielectric(ggx_fresnel *f, double eta);          /* eta > 0 finite, else GGX_ERR_ETA */
ggx_status ggx_fresnel_conductor(ggx_fresnel *f, double eta, double k); /* eta > 0, k >= 0 finite */
ggx_status ggx_fresnel_schlick(ggx_fresnel *f, double f0);              /* f0 in [0, 1], else GGX_ERR_RANGE */

/* F(cos_i) for the configured term, in [0, 1]. */
double ggx_fresnel_eval(const ggx_fresnel *f, double cos_i);

/* ------------------------------------------------------------------------------------------------------------
 * Half vectors and their Jacobians (Walter et al. 2007)
 * ------------------------------------------------------------------------------------------------------------ */

/* Reflection half vector normalize(wi + wo), flipped to the upper hemisphere (h.z >= 0); (0,0,0) when
 * wi + wo = 0. */
ggx_vec3 ggx_half_reflect(ggx_vec3 wi, ggx_vec3 wo);

/* Generalised half vector of refraction -(eta_i wi + eta_o wo) normalised, flipped to h.z >= 0 (Walter 2007
 * eq 16), eta_i, eta_o the indices on the sides of wi and wo; (0,0,0) when it is zero. */
ggx_vec3 ggx_half_refract(ggx_vec3 wi, ggx_vec3 wo, double eta_i, double eta_o);

/* d omega_h / d omega_o for reflection: 1 / (4 |wo.h|) (Walter 2007 eq 14); 0 when wo.h = 0. */
double ggx_jacobian_reflect(ggx_vec3 wo, ggx_vec3 h);

/* d omega_h / d omega_o for refraction: eta_o^2 |wo.h| / (eta_i (wi.h) + eta_o (wo.h))^2 (Walter 2007 eq 17); 0 when
 * the denominator is 0. Both Jacobians are tested against finite differences of the maps. */
double ggx_jacobian_refract(ggx_vec3 wi, ggx_vec3 wo, ggx_vec3 h, double eta_i, double eta_o);

/* Mirror reflection of w about the unit normal m: 2 (w.m) m - w. Any w, m. */
ggx_vec3 ggx_reflect(ggx_vec3 w, ggx_vec3 m);

/* Refraction of w through a facet with unit normal m, eta = eta_transmitted / eta_incident (the side of w is the
 * incident side; m may face either way): writes the unit refracted direction (on the far side of the facet) to *out
 * and returns 1, or writes (0,0,0) and returns 0 under total internal reflection, for w.m = 0, eta outside (0, inf)
 * or NaN input. Snell's law holds to 1e-15 (tested). */
int ggx_refract(ggx_vec3 w, ggx_vec3 m, double eta, ggx_vec3 *out);

/* ------------------------------------------------------------------------------------------------------------
 * Scattering functions
 * ------------------------------------------------------------------------------------------------------------ */

/* Microfacet BRDF (Walter eq 4 with G of eq 5):
 * f_r(wi, wo) = D(h) G1(wi, h) G1(wo, h) F(wi.h) / (4 |wi.n| |wo.n|),  h = normalize(wi + wo).
 * Reflection only: wi.z <= 0 or wo.z <= 0 gives 0. Reciprocal: f_r(wi, wo) = f_r(wo, wi) (tested to 1e-12). With
 * F = 1 the directional albedo (ggx_albedo) is <= 1 for every shape and wi, and <= G1(wi) for unskewed shapes. */
double ggx_brdf_eval(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo);

/* Which quantity the BSDF transports (Veach 1997, Walter 2007 section 5.2). */
typedef enum ggx_transport {
    GGX_RADIANCE = 0,  /* f(wi -> wo): radiance arriving along wi (from the light) leaves along wo */
    GGX_IMPORTANCE = 1 /* the adjoint: f*(wi, wo) = f(wo -> wi), for light tracing / importance */
} ggx_transport;

/* Rough dielectric BSDF (Walter et al. 2007) on both sides of an interface whose lower side (z < 0) has index
 * eta = eta_below / eta_above > 0 relative to the upper side (eta != 1 for a meaningful transmission; eta = 1 is
 * allowed and gives reflection only from the Fresnel term, which is then 0). wi: towards the light, wo: towards the
 * viewer, each on either side (z != 0).
 * - Same side: reflection, F(|wi.h|) D(h) G / (4 |wi.n| |wo.n|) with h = ggx_half_reflect.
 * - Opposite sides: transmission with h = ggx_half_refract (eta_i, eta_o the indices on the sides of wi, wo):
 *   |wi.h| |wo.h| eta_o^2 (1 - F(|wi.h|)) D(h) G / (|wi.n| |wo.n| (eta_i wi.h + eta_o wo.h)^2)   (Walter 2007 eq 21).
 * G is eq 7, G1(sgn(wi.n) wi, h) G1(sgn(wo.n) wo, h); F is the exact dielectric Fresnel with the relative index seen
 * from wi's side. Configurations that no microfacet produces (h below the horizon, wi.h and wo.h on the wrong sides)
 * give 0. Radiance convention: f(wi, wo) / eta_o^2 = f(wo, wi) / eta_i^2 (generalised reciprocity), and for fixed
 * wi the integral of f(wi, wo) |wo.n| over all wo is <= 1; GGX_IMPORTANCE returns f(wo, wi). wi.z = 0 or wo.z = 0,
 * or eta outside (0, inf), gives 0. */
double ggx_bsdf_eval(const ggx_shape *s, double eta, ggx_vec3 wi, ggx_vec3 wo, ggx_transport mode);

/* ------------------------------------------------------------------------------------------------------------
 * Energy: albedo (docs/design/albedo.md)
 *
 * Integrals by deterministic adaptive quadrature (no randomness, no tables, no allocation): setup-time functions,
 * microseconds to milliseconds per call, not per-sample ones (docs/performance.md, "Albedo and energy compensation").
 * ------------------------------------------------------------------------------------------------------------ */

/* Directional albedo of ggx_brdf_eval with F = 1 (separable G, eq 5): E(v) = int f_r(v, w) w.z dw over the upper
 * hemisphere, for any shape and v.z > 0 (v is normalised first; a zero, non-finite or v.z <= 0 vector gives 0). In
 * [0, 1], absolute error <= 1e-6 (tests/unit/test_albedo.c: against an independent quadrature over w, the closed form
 * 2 (1 - ln 2) / (1 + v.z) at alpha_x = alpha_y = 1 for every rotation, and Monte Carlo with ggx_sample_brdf). */
double ggx_albedo(const ggx_shape *s, ggx_vec3 v);

/* The same for the height-correlated G2 (ggx_g2_height_correlated in place of eq 5), the masking most renderers
 * use: f_r = D(h) G2(v, w, h) / (4 v.z w.z); 1 - v.z ln(1 + 1 / v.z) at alpha_x = alpha_y = 1. Domain and accuracy
 * as ggx_albedo. */
double ggx_albedo_height_correlated(const ggx_shape *s, ggx_vec3 v);

/* Albedo of the rough dielectric ggx_bsdf_eval for light arriving from v on either side (v.z != 0; v is
 * normalised): *reflected = int f(v -> w) |w.z| dw over v's side, *transmitted the same over the other side; returns
 * their sum (<= 1; the rest is lost to multiple scattering). eta as for ggx_bsdf_eval; either output pointer may be
 * NULL. Absolute error <= 1e-5 (docs/design/albedo.md: against a quadrature of ggx_bsdf_eval over w, to 6.4e-7 where
 * the light comes from the less dense side, against Monte Carlo with ggx_sample_bsdf, and against the limit at
 * eta = 1, T = G1(u)^2 / G1_smith(u), u = sgn(v.z) v, R = 0, a delta that ggx_bsdf_eval gives as 0). v.z = 0, a
 * zero or non-finite v, eta outside (0, 1e300] or s NULL: 0 and both outputs 0. */
double ggx_bsdf_albedo(const ggx_shape *s, double eta, ggx_vec3 v, double *reflected, double *transmitted);

/* Average albedo E_avg = (1 / pi) int E(v) v.z dv over the upper hemisphere (Kulla & Conty 2017), of ggx_albedo
 * and of ggx_albedo_height_correlated: in [0, 1], absolute error <= 1e-6; 4 (1 - ln 2)^2 and 4 (1 - ln 2) / 3 at
 * alpha_x = alpha_y = 1. Cost: tens of albedo evaluations for isotropic shapes, a few hundred otherwise. */
double ggx_albedo_avg(const ggx_shape *s);
double ggx_albedo_avg_height_correlated(const ggx_shape *s);

/* ------------------------------------------------------------------------------------------------------------
 * Sampling
 *
 * Every sampler maps (u1, u2) in [0, 1)^2 (values outside are clamped into [0, 1]) to a unit vector whose density
 * (per solid angle) is the pdf named in its block; the tests check each one by a chi-square goodness-of-fit test
 * against that pdf and by finite-difference Jacobians |dm / d(u1, u2)| = 1 / pdf. A sampler that cannot produce a
 * sample (view below the horizon, shape outside its domain) returns the zero vector, whose pdf is 0.
 * The inverse maps return the (u1, u2) that produce a given m (round trip to 1e-9 away from the map's seams).
 * ------------------------------------------------------------------------------------------------------------ */

typedef struct ggx_vec2 {
    double x, y;
} ggx_vec2;

/* --- Normals with pdf D(m) (m.n) (ggx_pdf_ndf) --- */

/* D(m) m.z for m.z >= 0, else 0. */
double ggx_pdf_ndf(const ggx_shape *s, ggx_vec3 m);

/* The library's default NDF sampler (ggx_sample_ndf_stretch). Any shape. */
ggx_vec3 ggx_sample_ndf(const ggx_shape *s, double u1, double u2);

/* --- Visible normals with pdf ggx_pdf_vndf(s, v, m) (Walter eq 33) ---
 * Domain: v.z > 0 (v.z <= 0 gives the zero vector); v = n exactly and grazing v are handled. */

/* The library's default VNDF sampler (ggx_sample_vndf_caps). Any shape. */
ggx_vec3 ggx_sample_vndf(const ggx_shape *s, ggx_vec3 v, double u1, double u2);

/* The seeds' other samplers of normals, each with the same pdf as the default of its kind, the unit-square maps
 * they build on and their inverses: ggx_experimental.h (included below). */

/* --- Directions --- */

typedef enum ggx_event {
    GGX_EVENT_INVALID = 0, /* no direction: below the horizon, total internal reflection chosen away, bad input */
    GGX_EVENT_REFLECT = 1,
    GGX_EVENT_TRANSMIT = 2
} ggx_event;

/* A sampled direction w with its pdf (per solid angle of w) and weight f |w.n| / pdf. Invalid samples have
 * event GGX_EVENT_INVALID, w = 0, pdf = 0 and weight = 0. */
typedef struct ggx_sample {
    ggx_vec3 w;
    double pdf;
    double weight;
    ggx_event event;
} ggx_sample;

/* Reflection sampling (Walter eq 47-50): m from ggx_sample_vndf(s, wi), wo = reflect(wi, m),
 * pdf = D_v(m) / (4 |wi.m|) (eq 48), weight = f_r(wi, wo) wo.z / pdf = G1(wi) G1(wo) F A_l(wi, n) / (wi.z A_e(n))
 * (eq 50), which is <= 1 (eq 52, checked by the tests). wo below the horizon: invalid. wi.z <= 0: invalid. */
ggx_sample ggx_sample_brdf(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, double u1, double u2);
/* The pdf of ggx_sample_brdf for a given pair; 0 unless wi.z > 0 and wo.z > 0. */
double ggx_pdf_brdf(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo);

/* Bounded reflection sampling for any shape (docs/design/bounded-vndf.md; after Eto & Tokuyoshi 2023): as
 * ggx_sample_brdf, but the caps sampler's cap starts at a height b below which every cap point reflects wi below the
 * horizon (for isotropic shapes the lowest one that reflects above it: no invalid samples at wi = n, nor at any view
 * for alpha = 1), so fewer samples are invalid. pdf = ggx_pdf_brdf / kappa, kappa = (1 - b) / (1 + vs.z) in (0, 1]
 * (proved in the document and by tests/unit/test_sample_dir.c), weight = kappa x ggx_sample_brdf's weight (<= 1, eq 52).
 * Same domain, invalid samples and contract as ggx_sample_brdf; u1, u2 in [0, 1) (clamped). */
ggx_sample ggx_sample_brdf_bounded(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, double u1, double u2);
/* The pdf of ggx_sample_brdf_bounded for a given pair: ggx_pdf_brdf / kappa, since every removed cap point reflects
 * below the horizon; 0 unless wi.z > 0 and wo.z > 0. Relative accuracy as ggx_pdf_brdf. */
double ggx_pdf_brdf_bounded(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo);

/* Bounded reflection sampling with a bound per azimuth of the cap point, for any shape (docs/design/bounded-vndf.md,
 * "A bound per azimuth of the cap point"): as ggx_sample_brdf_bounded, but the cap's lower end b(phi) depends on the
 * cap point's azimuth phi = 2 pi u1 (no invalid samples for an unskewed shape at wi = n; fewer than
 * ggx_sample_brdf_bounded's for anisotropic shapes, at a higher cost: docs/performance.md). pdf = ggx_pdf_brdf /
 * kappa(phi), kappa(phi) = (1 - b(phi)) / (1 + vs.z) in (0, ggx_sample_brdf_bounded's kappa], weight = kappa(phi) x
 * ggx_sample_brdf's weight (<= 1): the variance is never above ggx_sample_brdf's. b(phi), and so the pdf, jumps
 * across some curves of directions; near them and near the cap's pole (where phi is ill-conditioned) the float
 * sampler (ggx_inline.h) may take another bound than the double one: it agrees within 1e-4 per direction component,
 * 2e-4 relative in pdf and 4e-4 in weight for all but a fraction 1e-3 of samples (tests/unit/test_sample_dir.c). Same
 * domain, invalid samples and contract as ggx_sample_brdf; u1, u2 in [0, 1) (clamped). */
ggx_sample ggx_sample_brdf_bounded_azimuth(const ggx_shape *s, const ggx_fresnel *f, ggx_vec3 wi, double u1, double u2);
/* The pdf of ggx_sample_brdf_bounded_azimuth for a given pair: ggx_pdf_brdf / kappa(phi), phi the azimuth of the cap
 * point of wo's half vector (phi = 0 at the pole, a single point); 0 unless wi.z > 0 and wo.z > 0. At a direction
 * the sampler drew, it agrees with the sample's pdf within 1e-6 relative for u2 >= 1e-3 (tests/unit/test_sample_dir.c).
 * Near the pole of the cap (u2 kappa -> 0) the recovered azimuth is ill-conditioned: up to 2e-5 there, and up to a
 * few percent for shapes whose alphas differ by a factor 1e5 or more. */
double ggx_pdf_brdf_bounded_azimuth(const ggx_shape *s, ggx_vec3 wi, ggx_vec3 wo);

/* Rough-dielectric sampling (Walter 2007 section 5.3): from the known direction v (either side), m from the VNDF
 * of sgn(v.z) v, then reflection with probability F(|v.m|) (u3 < F) or refraction otherwise (total internal
 * reflection always reflects). pdf = D_v(m) (F / (4 |v.m|) or (1 - F) eta_w^2 |w.m| / (eta_v v.m + eta_w w.m)^2).
 * weight = ggx_bsdf_eval(s, eta, w, v, mode) |w.z| / pdf: for a camera path (GGX_RADIANCE) v is towards the camera
 * and w towards the light; for a light path (GGX_IMPORTANCE) v is towards the light. A direction that ends on the
 * wrong side of the surface is invalid. v.z = 0 or eta outside (0, inf): invalid. */
ggx_sample ggx_sample_bsdf(const ggx_shape *s, double eta, ggx_vec3 v, double u1, double u2, double u3,
                           ggx_transport mode);
/* The pdf of ggx_sample_bsdf producing w from v. */
double ggx_pdf_bsdf(const ggx_shape *s, double eta, ggx_vec3 v, ggx_vec3 w);

/* ------------------------------------------------------------------------------------------------------------
 * Energy: shipped albedo tables (docs/design/energy.md)
 *
 * Generated by lab/gen_tables (make tables) from the quadratures and read by interpolation, in a fraction of a
 * microsecond against the quadrature's milliseconds (docs/performance.md). No allocation.
 * ------------------------------------------------------------------------------------------------------------ */

/* Which shadowing-masking an albedo belongs to. */
typedef enum ggx_masking {
    GGX_MASKING_SEPARABLE = 0,        /* G = G1(wi) G1(wo), eq 5: ggx_brdf_eval, ggx_albedo */
    GGX_MASKING_HEIGHT_CORRELATED = 1 /* ggx_g2_height_correlated: ggx_albedo_height_correlated */
} ggx_masking;

/* E(mu) of isotropic GGX of roughness alpha, mu = cos theta of the view: ggx_albedo (or
 * ggx_albedo_height_correlated) within 1e-3 absolute for mu >= 0.0175 (89 degrees; the largest errors are in
 * docs/design/energy.md). alpha outside [1e-3, 2] (but accepted by ggx_shape_iso) is computed by the quadrature
 * instead (milliseconds). mu <= 0, NaN, or an alpha that ggx_shape_iso rejects: 0; mu > 1 reads as 1. In [0, 1]. Any
 * other masking value reads as GGX_MASKING_SEPARABLE. */
double ggx_albedo_iso_table(double alpha, double mu, ggx_masking g);
/* E_avg(alpha) likewise (ggx_albedo_avg, ggx_albedo_avg_height_correlated), within 1e-5. */
double ggx_albedo_avg_iso_table(double alpha, ggx_masking g);
/* R + T of the rough dielectric ggx_bsdf_eval for isotropic GGX of roughness alpha (ggx_bsdf_albedo's sum), for
 * light arriving with cos theta = mu: mu > 0 from above, mu < 0 from below; eta as for ggx_bsdf_albedo. Read from a
 * shipped table for alpha in [1e-2, 2] and a relative index met by the light (eta from above, 1 / eta from below) in
 * [1.05, 3] or [1 / 3, 1 / 1.05]: within 1e-3 absolute of ggx_bsdf_albedo for |mu| >= 0.0175 (89 degrees) and
 * alpha >= 0.025; below that, near the critical angle of light meeting the denser side with eta_r near 1 / 1.05,
 * errors reach 1.2e-3 (docs/design/energy.md). Outside the table's range (but accepted by ggx_shape_iso and
 * ggx_bsdf_albedo) it computes the quadrature instead (milliseconds). mu = 0, NaN, eta outside (0, 1e300] or an alpha
 * that ggx_shape_iso rejects: 0; |mu| > 1 reads as 1. In [0, 1]. */
double ggx_bsdf_albedo_iso_table(double alpha, double eta, double mu);
/* E(v) of anisotropic GGX (ggx_shape_aniso(alpha_x, alpha_y): ggx_albedo, separable G) at a view v in the shape's
 * frame (x along alpha_x; v need not be unit; a rotated shape's view is first turned into its frame), read from a
 * shipped table (docs/design/energy.md, "Shipped anisotropic table") for alphas in [1e-2, 2] and alpha_x / alpha_y
 * in [1/20, 20]: within 1.1e-3 absolute of ggx_albedo for v.z >= 0.0175 (89 degrees), the largest errors at 89
 * degrees with alphas near 0.02. Per-shape tables (ggx_energy_create) share its layout and these errors. Other
 * alphas accepted by ggx_shape_aniso: the quadrature instead (milliseconds). v.z <= 0, a zero or non-finite v, or
 * alphas that ggx_shape_aniso rejects: 0. In [0, 1]. */
double ggx_albedo_aniso_table(double alpha_x, double alpha_y, ggx_vec3 v);

/* ------------------------------------------------------------------------------------------------------------
 * Energy compensation (docs/design/energy.md; Kulla & Conty 2017, for every shape)
 *
 * The single-scattering BRDF loses 1 - E(wi) (F = 1) to light that bounces more than once among the facets. The
 * multiple-scattering lobe returns it, reciprocally:
 *   f_ms(wi, wo) = F_ms (1 - E(wi)) (1 - E(wo)) / (pi (1 - E_avg)),  F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)),
 * with E a per-shape table of ggx_albedo (separable G, the library's BRDF) built by ggx_energy_create and read by
 * interpolation, and E_avg the table's own average. With F = 1 the compensated albedo is then 1 + (E - E_table)(wi):
 * never above 1 + 1e-3, for every shape and every view (tests/unit/test_energy_domain.c tries alpha 1e-3 to 10,
 * anisotropy to 1:200, skews to pi / 2 and views to 89.9 degrees), and within 1e-3 of 1 for views with wi.z >= 0.0175
 * (89 degrees) wherever E has no feature narrower than the table's nodes; for unskewed anisotropic shapes read from
 * the shipped table, within that table's 1.1e-3. Where E has such a feature (the mirror horizon of a sharp skewed
 * lobe, the azimuth at grazing of extreme anisotropy) the table's cells around it are guarded: they hold a value not
 * below E, so that the compensation there returns less than all of the lost energy (up to a few percent of the light,
 * over a band of views about as wide as a cell) but never adds energy (docs/design/energy.md has the losses). F_avg is the cosine-weighted average of F (ggx_fresnel_avg): one
 * channel, one wavelength, as everywhere in this API.
 * A NULL ggx_fresnel means F = 1. Directions need not be unit (they are normalised); wi.z <= 0 or wo.z <= 0, zero or
 * non-finite vectors give 0 or an invalid sample. An energy object is read-only after creation: any number of
 * threads may use one at once.
 * ------------------------------------------------------------------------------------------------------------ */

/* A shape's albedo table (opaque; about 100 KB for anisotropic and skewed shapes, 1.6 KB for isotropic ones). */
typedef struct ggx_energy ggx_energy;

/* Builds the table of shape s (copied; s may be freed after; docs/design/energy.md, "The table"), for every shape.
 * Isotropic shapes with alpha in [1e-3, 2] and unskewed anisotropic ones with both alphas in [1e-2, 2] and anisotropy
 * to 1:20 read it from the shipped tables (microseconds); the others compute it by ggx_albedo's quadrature (seconds:
 * docs/performance.md; build tables once per material, at scene setup) and guard the cells where the interpolation
 * falls below ggx_albedo (docs/design/energy.md, "Where the table cannot follow E").
 * Errors: GGX_ERR_NULL (s or out NULL), GGX_ERR_MEMORY; *out is NULL then. */
ggx_status ggx_energy_create(const ggx_shape *s, ggx_energy **out);
/* Frees e (NULL is allowed). */
void ggx_energy_free(ggx_energy *e);
/* The shape e was built for; NULL for e NULL. */
const ggx_shape *ggx_energy_shape(const ggx_energy *e);

/* E(v) from the table, in [0, 1]: never below ggx_albedo(s, v) by more than 1e-3; within 1e-3 of it for
 * v.z >= 0.0175 (89 degrees) outside the guarded cells, 1.1e-3 for unskewed anisotropic shapes read from the shipped
 * table (their nodes and errors are ggx_albedo_aniso_table's). v.z <= 0: 0. */
double ggx_energy_albedo(const ggx_energy *e, ggx_vec3 v);
/* E_avg of the table: (1 / pi) int E(v) v.z dv of its interpolant, within 1e-3 of ggx_albedo_avg. */
double ggx_energy_albedo_avg(const ggx_energy *e);

/* F_avg = 2 int_0^1 F(mu) mu dmu: 1 for GGX_FRESNEL_ONE (and f NULL), f0 + (1 - f0) / 21 for Schlick; 16-point
 * Gauss-Legendre otherwise (for a dielectric with eta < 1 in the transmitted cosine, past total internal
 * reflection): relative error below 1e-9 (tested against adaptive quadrature). In [0, 1]. */
double ggx_fresnel_avg(const ggx_fresnel *f);

/* The multiple-scattering lobe f_ms(wi, wo) above. Reciprocal to 1e-12. */
double ggx_brdf_ms_eval(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo);
/* Samples the lobe's shape (1 - E(wo)) wo.z, piecewise constant over the table's cells (wi only needs wi.z > 0):
 * pdf = ggx_pdf_brdf_ms, weight = f_ms wo.z / pdf, close to F_ms (1 - E(wi)). u1, u2 in [0, 1) (clamped). */
ggx_sample ggx_sample_brdf_ms(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, double u1, double u2);
double ggx_pdf_brdf_ms(const ggx_energy *e, ggx_vec3 wi, ggx_vec3 wo);

/* The energy-compensated BRDF, the entry point a renderer calls in place of ggx_brdf_eval:
 * ggx_brdf_eval(shape, f, wi, wo) + ggx_brdf_ms_eval(e, f, wi, wo). Reciprocal to 1e-12. Two table lookups; F_avg of
 * the last 4 conductor or dielectric terms is remembered per thread (the cost: docs/performance.md). */
double ggx_brdf_compensated_eval(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo);
/* Samples it: with probability p = F_avg E(wi) / (F_avg E(wi) + F_ms (1 - E(wi))) (u3 < p) the single-scattering
 * lobe by ggx_sample_brdf_bounded, else the multiple-scattering lobe; pdf = p ggx_pdf_brdf_bounded + (1 - p)
 * ggx_pdf_brdf_ms (ggx_pdf_brdf_compensated), weight = ggx_brdf_compensated_eval wo.z / pdf. A single-scattering
 * draw below the horizon is invalid, as for ggx_sample_brdf_bounded. u1, u2, u3 in [0, 1) (clamped). */
ggx_sample ggx_sample_brdf_compensated(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, double u1, double u2,
                                       double u3);
double ggx_pdf_brdf_compensated(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo);

/* ------------------------------------------------------------------------------------------------------------
 * Energy compensation of the rough dielectric (docs/design/energy.md; Kulla & Conty 2017, for every shape)
 *
 * ggx_bsdf_eval loses, for light arriving from wi on side a (0: above, 1: below the surface), 1 - E_a(wi) of its
 * energy, E_a = R + T of ggx_bsdf_albedo. The multiple-scattering lobes on both sides return it: for wi on side a
 * and wo on side b, in the radiance convention,
 *   f_ms(wi, wo) = c_ab (1 - E_a(wi)) (1 - E_b(wo)),
 * with c_ab fixed at setup so that int f_ms(wi, wo) |wo.z| dwo = 1 - E_a(wi) from both sides, a share x_a of it
 * transmitted (x_a <= 1 - F_avg,a, the average Fresnel transmittance from side a, with equality on the side that
 * loses more), and f_ms(wi, wo) / eta_o^2 = f_ms(wo, wi) / eta_i^2, the generalised reciprocity of ggx_bsdf_eval
 * (derivation: docs/design/energy.md).
 * E_a is a per-(shape, eta) table of ggx_bsdf_albedo for each side, built by ggx_bsdf_energy_create and read by
 * interpolation, so that a non-absorbing interface keeps R + T = 1 + (E_a - E_a,table)(wi): never above 1 + 1e-3 from
 * either side, and within 1e-3 of 1 for views with |wi.z| >= 0.0175 (89 degrees) outside the guarded cells, for every
 * (shape, eta) (tests/unit/test_energy_bsdf.c and tests/unit/test_energy_domain.c try isotropic alpha 0.05 to 1,
 * anisotropic to 1:10, rotated, skewed, random shapes as the conductor's; eta 1.001 to 2.5 and below 1). Tables whose
 * nodes are computed are guarded as the conductor's are.
 * Sides, directions and modes as for ggx_bsdf_eval: eta = eta_below / eta_above, directions point away from the
 * surface on either side, GGX_IMPORTANCE gives the adjoint f(wo, wi). Directions need not be unit (they are
 * normalised); w.z = 0, zero or non-finite vectors give 0 or an invalid sample; e NULL gives 0 or an invalid sample.
 * An object is read-only after creation: any number of threads may use one at once.
 * ------------------------------------------------------------------------------------------------------------ */

/* The albedo tables of a shape and an index of refraction (opaque; about 400 KB for anisotropic and skewed shapes,
 * 3 KB for isotropic ones). */
typedef struct ggx_bsdf_energy ggx_bsdf_energy;

/* Builds the tables of shape s (copied) and eta for both sides, of ggx_bsdf_albedo's R + T by quadrature, the two
 * sides on two threads (seconds: docs/performance.md; build them once per material, at scene setup); isotropic
 * shapes with alpha in [0.025, 2] and eta or 1 / eta in [1.05, 3] read them from the shipped table of
 * ggx_bsdf_albedo_iso_table instead (microseconds).
 * Errors: GGX_ERR_NULL (s or out NULL), GGX_ERR_NONFINITE (eta NaN or infinite), GGX_ERR_ETA (eta <= 0, above 1e300,
 * or exactly 1, where the transmission is a delta that ggx_bsdf_eval does not represent), GGX_ERR_MEMORY; *out is
 * NULL then. */
ggx_status ggx_bsdf_energy_create(const ggx_shape *s, double eta, ggx_bsdf_energy **out);
/* Frees e (NULL is allowed). */
void ggx_bsdf_energy_free(ggx_bsdf_energy *e);
/* The shape and the eta e was built for; NULL and 0 for e NULL. */
const ggx_shape *ggx_bsdf_energy_shape(const ggx_bsdf_energy *e);
double ggx_bsdf_energy_eta(const ggx_bsdf_energy *e);

/* E(v) = R + T of light arriving from v (either side) from the table, in [0, 1]: never below ggx_bsdf_albedo's sum by
 * more than 1e-3; within 1e-3 of it for |v.z| >= 0.0175 (89 degrees) outside the guarded cells (the largest errors
 * are in docs/design/energy.md). v.z = 0: 0. */
double ggx_bsdf_energy_albedo(const ggx_bsdf_energy *e, ggx_vec3 v);
/* E_avg of one side's table, (1 / pi) int E(v) |v.z| dv over that side: below = 0 for light from above, else from
 * below. */
double ggx_bsdf_energy_albedo_avg(const ggx_bsdf_energy *e, int below);

/* The multiple-scattering lobes f_ms(wi, wo) above (either side each), for the transport mode. Generalised
 * reciprocity to 1e-12: f_ms(wi, wo) / eta_o^2 = f_ms(wo, wi) / eta_i^2 (radiance). */
double ggx_bsdf_ms_eval(const ggx_bsdf_energy *e, ggx_vec3 wi, ggx_vec3 wo, ggx_transport mode);
/* Samples the lobes from the known direction v (as for ggx_sample_bsdf: for GGX_RADIANCE v is towards the camera,
 * w towards the light): the other side with probability x_a (u3 < x_a), then (1 - E(w)) |w.z| on that side,
 * piecewise constant over the table's cells (u1, u2). pdf = ggx_pdf_bsdf_ms, weight =
 * ggx_bsdf_ms_eval(e, w, v, mode) |w.z| / pdf; event GGX_EVENT_REFLECT or GGX_EVENT_TRANSMIT by the side of w.
 * u1, u2, u3 in [0, 1) (clamped). */
ggx_sample ggx_sample_bsdf_ms(const ggx_bsdf_energy *e, ggx_vec3 v, double u1, double u2, double u3,
                              ggx_transport mode);
double ggx_pdf_bsdf_ms(const ggx_bsdf_energy *e, ggx_vec3 v, ggx_vec3 w);

/* The energy-compensated rough dielectric, the entry point a renderer calls in place of ggx_bsdf_eval:
 * ggx_bsdf_eval(shape, eta, wi, wo, mode) + ggx_bsdf_ms_eval(e, wi, wo, mode). Generalised reciprocity to 1e-12;
 * with it a non-absorbing interface passes the white furnace within 1e-3 from both sides (above). */
double ggx_bsdf_compensated_eval(const ggx_bsdf_energy *e, ggx_vec3 wi, ggx_vec3 wo, ggx_transport mode);
/* Samples it from the known direction v (either side; conventions of ggx_sample_bsdf): with probability
 * p = E(v) of the table (u3 < p) the single-scattering lobe by ggx_sample_bsdf (u1, u2 and u3 / p), else the
 * multiple-scattering lobes as ggx_sample_bsdf_ms (u1, u2 and (u3 - p) / (1 - p)); pdf = p ggx_pdf_bsdf +
 * (1 - p) ggx_pdf_bsdf_ms (ggx_pdf_bsdf_compensated), weight = ggx_bsdf_compensated_eval(e, w, v, mode) |w.z| / pdf,
 * which for GGX_IMPORTANCE averages to the albedo R + T = 1 of a non-absorbing interface. A single-scattering draw
 * that ggx_sample_bsdf marks invalid is invalid. u1, u2, u3 in [0, 1) (clamped). */
ggx_sample ggx_sample_bsdf_compensated(const ggx_bsdf_energy *e, ggx_vec3 v, double u1, double u2, double u3,
                                       ggx_transport mode);
double ggx_pdf_bsdf_compensated(const ggx_bsdf_energy *e, ggx_vec3 v, ggx_vec3 w);

#ifdef __cplusplus
}
#endif

/* The research entry points (the seeds' other samplers): declared apart so that what this header shows is the stable
 * API, and included so that every program written against ggx.h keeps compiling. */
#include "ggx_experimental.h"
/* The ellipsoid as a volume of microflakes (SGGX): flake distributions, their phase functions and samplers. */
#include "ggx_sggx.h"

#endif /* GGX_GGX_H */
