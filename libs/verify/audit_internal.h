/* The seed audit's shared parts: the row vocabulary, the chi-square runs, and the geometric checks that the claim
 * files (libs/verify/audit*.c) use. Internal to the verification library. SPDX-License-Identifier: MIT */
#ifndef GGX_AUDIT_INTERNAL_H
#define GGX_AUDIT_INTERNAL_H

#include <stdint.h>

#include "audit.h"
#include "chi2.h"

/* The seeds, by their short names in docs/references.md. */
#define SEED_BLOG2 "ellipsoidal-ggx-2" /* "The Ellipsoidal Nature of GGX distribution", Part 2 */
#define SEED_STRETCH "engstad-stretch" /* Engstad, "Elliptic Stretch" */
#define SEED_BLOG1 "ellipsoidal-ggx-1" /* "The Ellipsoidal Nature of GGX distribution", Part 1 */
#define SEED_WALTER                                                                                                    \
    "walter-ellipsoid" /* Walter, Dong, Marschner, Greenberg, "The Ellipsoid Normal Distribution Function" */
#define SEED_VNDF "engstad-vndf-proof" /* Engstad, "Proof of the Sampling Method for Visible GGX" */

/* What every claim file's rows see: the table, the three shapes (as given and as the library's shapes). */
typedef struct au_ctx {
    audit_row *rows;
    int *nr;
    const ggx_shape *sh;     /* [AUDIT_SHAPES] */
    const double (*A)[3][3]; /* [AUDIT_SHAPES], Walter's A as given */
    int progress;
} au_ctx;

/* ---- rows ---- */
/* A new row, every verdict "not claimed: not checked" until set; aborts beyond AUDIT_MAX_ROWS. */
audit_row *au_add(audit_row *rows, int *n, const char *id, const char *claim, const char *seed, const char *where,
                  audit_scope scope);
/* Sets a row's verdict for shape k and its evidence (printf-style); au_append adds to the evidence. */
void au_set(audit_row *r, int k, audit_verdict v, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
void au_append(audit_row *r, int k, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Whether the seed's scope covers shape s. */
int au_in_scope(audit_scope scope, const ggx_shape *s);

/* ---- chi-square ---- */
typedef ggx_vec3 (*au_vndf_fn)(const ggx_shape *, ggx_vec3, double, double);
/* A sampler as a seed writes it, in terms of the matrix A it is given. */
typedef ggx_vec3 (*au_literal_fn)(const double A[3][3], ggx_vec3 v, double u1, double u2); /* v: the view (VNDF) */
typedef struct au_actx {
    normal_keys keys;      /* first: the chi-square key and density come from normal_keys_* */
    au_vndf_fn f;          /* sampler (for NDF samplers v is n) */
    au_literal_fn literal; /* or, when set, the seed's literal form applied to A */
    const double (*A)[3];
} au_actx;
/* chi-square p-value of the sampler of c against its pdf (0 when a sample has zero pdf); a dot on stderr when
 * progress is set. Quiet: a claim that fails is an answer, not a failure to keep a histogram of. */
double au_chi2_p(au_actx *c, uint64_t seed, int progress);
double au_chi2_sampler(const ggx_shape *s, ggx_vec3 v, au_vndf_fn f, verify_pdf_fn pdf, uint64_t seed, int progress);
/* The same for a sampler that draws from a random stream (rejection samplers): draw as in chi2_problem. */
double au_chi2_draw(const ggx_shape *s, ggx_vec3 v, int (*draw)(void *ctx, rng *r, ggx_vec3 *m), void *ctx,
                    verify_pdf_fn pdf, uint64_t seed, int progress);
/* The significance level of one run: the suite's Sidak-corrected level. */
double au_alpha_level(void);
void au_set_alpha_level(double alpha); /* this thread's level; negative: the command's, chi2_sidak(CHI2_SUITE_RUNS) */
/* holds if p >= au_alpha_level(), else fails; the evidence is the p-value. */
void au_verdict_p(audit_row *r, int k, double p);
/* rng_uniform as the library's callback (the rejection samplers' random stream). */
double au_uniform_cb(void *st);

/* ---- geometry ---- */
/* The inverse transpose of the user's A, by cofactors (the audit checks the seeds' formulas on the matrix given,
 * independently of the library's canonical frame). */
void au_inv_t(const double A[3][3], double Ait[3][3]);
/* Areas by shooting rays at the ellipsoid x^T A^T A x = 1 itself (Ce = 1), not by integrating D: N rays along -u
 * through the rectangle that bounds its shadow (half-widths ||A^-T e|| along e1, e2 perpendicular to u: the
 * ellipsoid's support function); a ray hits where (p + l u)^T M (p + l u) = 1 has a root, M = A^T A, and the point
 * seen from u is the larger root, whose outward normal M x faces u. With lune set, only hits whose normal has
 * m.v >= 0 count (Walter eq 28's lune). Returns the shadow's area; *sigma its Monte Carlo standard error. */
double au_ray_area(const double A[3][3], ggx_vec3 u, ggx_vec3 v, int lune, long N, uint64_t seed, double *sigma);
double au_norm_of(const double M[3][3], ggx_vec3 v); /* ||M v|| */
/* The alphas of an unskewed shape (the formulas the seeds write for a diagonal A, in x and y); 0 for a skewed one. */
int au_diag_alphas(const ggx_shape *s, double *ax, double *ay);
/* The same for a row: a skewed shape gets "cannot be applied" and 0. */
int au_alphas_or_skip(audit_row *r, int k, const ggx_shape *s, double *ax, double *ay);
/* A random direction of the upper hemisphere, cos theta uniform in [0.02, 1]. */
ggx_vec3 au_random_upper(rng *g);
/* A view for inequalities that fail first near n (by a term of first order in the tilt of A^T A n): half of them
 * au_random_upper, half within 0.5 rad of n, concentrated toward it. */
ggx_vec3 au_view_near_n(rng *g);
/* Anisotropic GGX as the seeds write it: 1 / (pi ax ay (mx^2/ax^2 + my^2/ay^2 + mz^2)^2). */
double au_ggx_formula(double ax, double ay, ggx_vec3 m);
/* The surface point of the ellipsoid x^T A^T A x = 1 whose outward normal is m: p = A^-1 A^-T m / ||A^-T m|| (the
 * gradient 2 A^T A p is along m). */
ggx_vec3 au_point_of_normal(const double Ait[3][3], ggx_vec3 m);
/* Eigenvalues of a symmetric n x n matrix (n <= 9) by Jacobi rotations, into ev (unsorted). */
void au_sym_eigenvalues(int nn, double M[9][9], double *ev);
/* Finite-difference area Jacobian |d m / d(a, b)| of a map from the plane to the unit sphere (or to the plane, with
 * z = 0), by central differences of step h. */
typedef ggx_vec3 (*au_map2_fn)(const void *ctx, double a, double b);
double au_fd_jacobian(au_map2_fn f, const void *ctx, double a, double b, double h);
/* Engstad's cosine-weighted hemisphere s(u, v) = (sqrt(u) cos 2 pi v, sqrt(u) sin 2 pi v, sqrt(1 - u)) (ctx unused). */
ggx_vec3 au_map_cosine(const void *ctx, double u, double v);
/* The determinant of the columns a, b, c. */
double au_det3(ggx_vec3 a, ggx_vec3 b, ggx_vec3 c);

/* Engstad's VNDF proof (Heitz 2018's five steps) as written, with the matrix A it is given: the view stretched,
 * vh = normalize(A v); frame T1 = normalize(z x vh), T2 = vh x T1; polar disk point (t1, t2); squish t2 by
 * s = (1 + vh.z) / 2; lift onto the hemisphere about vh; back to the ellipsoid with m = normalize(A nh), the same
 * A. Right for a diagonal (symmetric) A; the library un-stretches with A'^T in the canonical frame (Walter eq 46).
 * With A = I it is the blog's crescent map in sphere space. */
ggx_vec3 au_literal_heitz(const double A[3][3], ggx_vec3 v, double u1, double u2);

/* ---- claims about every view ---- */
/* A claim about every view is checked on a grid of views, not one: 6 polar angles from 0.3 to 1.5 rad (86 degrees)
 * times 8 azimuths. f returns the claim's value at view v (an integral that is 1 where it holds); the verdict: holds
 * if |f - 1| < tol at every view, else fails with the worst view and the failing view nearest n. The evidence reads
 * "<what> integrates to ...". */
enum { AU_VIEW_THETAS = 6, AU_VIEW_PHIS = 8, AU_VIEWS = AU_VIEW_THETAS * AU_VIEW_PHIS };
void au_verdict_views(audit_row *r, int k, double (*f)(const ggx_shape *, ggx_vec3), const ggx_shape *s, double tol,
                      const char *what);

/* ---- claims about every shape of a kind ---- */
enum { AU_KIN = 24 };
/* Shape i of the family of the audit's shape s0 (Walter's A0): i = 0 is s0 itself; the others are random shapes of
 * the same kind (diagonal, theta_z-rotated or skewed), A = S Rx Ry Rz (ggx_ellipsoid_matrix) with the alphas
 * log-uniform in [0.05, 2], theta_z uniform, and for skewed shapes theta_x, theta_y uniform in +-[0.02, 0.6] rad.
 * offdiag: how far A^T A is from diagonal, ||off-diagonal part|| / trace (0 for diagonal shapes): counterexamples
 * are ordered by it, the smallest being the failing shape nearest to a diagonal one. */
typedef struct au_kin {
    double A[3][3];
    ggx_shape s;
    double offdiag;
    double params[5]; /* ax, ay, theta_x, theta_y, theta_z of a random shape */
    int has_params;   /* 0 for the audit's own shape (given as a matrix) */
    int searching;    /* 1 while the smallest counterexample is searched for: err functions keep tallies out */
    char label[120];
} au_kin;
void au_kin_shape(const ggx_shape *s0, const double A0[3][3], int i, uint64_t seed, au_kin *out);
/* The alphas of Walter's A = S R as the seeds' formulas take them: the norms of A's first two rows (the library's
 * shape may name the same ellipsoid by swapped alphas and a quarter turn). */
void au_kin_alphas(const au_kin *K, double *ax, double *ay);
/* An identity or inequality claimed at every point of every shape of a kind: err returns the claim's error at one
 * random point of shape K (0 where it holds exactly, NaN where it cannot be evaluated counts as a failure) and
 * writes the point into at. The verdict for shape k: holds if every error is <= tol over `points` points on each of
 * AU_KIN shapes; else fails, with the counterexample on the smallest failing shape (least |theta_z| for a rotated
 * kind, least offdiag for a skewed one), whose skew (or rotation) is then halved 30 times, reporting the smallest
 * scale at which the claim still fails (the smallest counterexample found; libs/verify/audit_util.c says how). */
typedef double (*au_err_fn)(const au_kin *K, rng *g, void *ctx, char *at, size_t nat);
void au_verdict_kin(audit_row *r, int k, const ggx_shape *s0, const double A0[3][3], au_err_fn err, void *ctx,
                    int points, double tol, const char *what);
/* A row of such a claim: au_verdict_kin for each of the audit's shapes; with unskewed_only a skewed shape gets
 * "cannot be applied" (the seed's formula takes ax, ay). */
void au_kin_row(const au_ctx *c, audit_row *r, int unskewed_only, au_err_fn err, void *ctx, int points, double tol,
                const char *what);
/* The same claim checked over the family, returning the largest error (for rows that combine several claims). */
double au_kin_worst(const ggx_shape *s0, const double A0[3][3], au_err_fn err, void *ctx, int points, double tol,
                    char *example, size_t nexample);

/* ---- the rows of each subject (libs/verify/audit_*.c), in the order audit_run calls them ---- */
void au_rows_ellipsoid(const au_ctx *c);
void au_rows_sampling(const au_ctx *c);
void au_rows_scattering(const au_ctx *c);
void au_rows_stretch(const au_ctx *c);

#endif
