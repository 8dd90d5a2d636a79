/* The seed audit: the steps of the seeds' samplers (blog Part 2's ellipse and crescent, Walter's version 1 and
 * version 3 eq 34-46, Engstad's proof), each checked by the sampler's own distribution (chi-square against the
 * density the seed states) or by finite differences of its map. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "audit_internal.h"

static const ggx_vec3 N_UP = {0, 0, 1};

static double vdist(ggx_vec3 a, ggx_vec3 b)
{
    ggx_vec3 d = t_add(a, t_scale(b, -1));
    return sqrt(t_dot(d, d));
}

/* ---- blog Part 2, sampling normals: the ellipse of semi-axes a = 1/ax, b = 1/ay sampled uniformly, lifted to
 * z = c sqrt(1 - xi1), with the normal m = (sqrt(xi1) cos(2 pi xi2) / a ... ) as written ---- */
typedef struct ell_ctx {
    double a, b;
} ell_ctx;
static ggx_vec3 map_ellipse(const void *vc, double x1, double x2)
{
    const ell_ctx *c = vc;
    double r = sqrt(x1), t = 2 * GGX_PI * x2;
    return t_vec(c->a * r * cos(t), c->b * r * sin(t), 0);
}
static double err_lift(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    const double(*A)[3] = (const double(*)[3])K->A;
    double ax, ay;
    au_kin_alphas(K, &ax, &ay);
    ell_ctx c = {1 / ax, 1 / ay};
    double x1 = 0.02 + 0.96 * rng_uniform(g), x2 = rng_uniform(g), r = sqrt(x1), t = 2 * GGX_PI * x2;
    ggx_vec3 p = t_vec(c.a * r * cos(t), c.b * r * sin(t), sqrt(1 - x1)); /* c = 1 */
    ggx_vec3 ap = t_matvec(A, p), normal = t_normalize(t_mattvec(A, ap)); /* the shape's normal at p */
    ggx_vec3 m = t_normalize(t_vec(r * cos(t) / c.a, r * sin(t) / c.b, sqrt(1 - x1)));
    double on = fabs(t_dot(ap, ap) - 1); /* p on the shape's ellipsoid */
    double jac = au_fd_jacobian(map_ellipse, &c, x1, x2, 1e-6), want = GGX_PI * c.a * c.b;
    double area = GGX_PI * au_norm_of(A, N_UP) /
                  fabs(au_det3(t_matvec(A, t_vec(1, 0, 0)), t_matvec(A, t_vec(0, 1, 0)), t_matvec(A, N_UP)));
    snprintf(at, nat, "xi = (%.3g, %.3g): p on the ellipsoid to %.1e, m off the normal by %.3g", x1, x2, on,
             vdist(m, normal));
    return fmax(fmax(on, vdist(m, normal)), fmax(fabs(jac / want - 1), fabs(want / area - 1)));
}

/* ---- sphere space (blog Part 2): a uniform disk projected onto the sphere along v' has density (m'.v') / pi; the
 * crescent map of the disk, lifted, has (m'.v') / (pi s) on the lune. On the unit sphere (A = I) the first is the
 * NDF sampler's pdf D (m.n) with v' = n, the second the VNDF of the sphere, ggx_pdf_vndf. ---- */
static ggx_vec3 disk_projected(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    (void)s, (void)v;
    double r = sqrt(u1), t = 2 * GGX_PI * u2;
    return t_vec(r * cos(t), r * sin(t), sqrt(fmax(0, 1 - u1)));
}
static ggx_vec3 crescent_sphere(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    (void)s;
    static const double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    return au_literal_heitz(I, v, u1, u2);
}

/* ---- Walter eq 34-37: the concentric map, uniform on the disk (its signed Jacobian pi everywhere, one sign: the
 * wedges neither overlap nor fold) ---- */
static ggx_vec3 map_concentric_walter(const void *vc, double x1, double x2)
{
    (void)vc;
    double a = 2 * x1 - 1, b = 2 * x2 - 1;
    if (a == 0 && b == 0) return t_vec(0, 0, 0);
    if (fabs(a) > fabs(b)) return t_vec(a * cos(GGX_PI * b / (4 * a)), a * sin(GGX_PI * b / (4 * a)), 0);
    return t_vec(b * sin(GGX_PI * a / (4 * b)), b * cos(GGX_PI * a / (4 * b)), 0);
}
static double err_concentric(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)K, (void)ctx;
    const double h = 1e-7;
    double x1 = rng_uniform(g), x2 = rng_uniform(g);
    if (fabs(fabs(2 * x1 - 1) - fabs(2 * x2 - 1)) < 1e-5) return 0; /* the wedges' seams: no derivative there */
    ggx_vec3 da = t_scale(
        t_add(map_concentric_walter(NULL, x1 + h, x2), t_scale(map_concentric_walter(NULL, x1 - h, x2), -1)), 0.5 / h);
    ggx_vec3 db = t_scale(
        t_add(map_concentric_walter(NULL, x1, x2 + h), t_scale(map_concentric_walter(NULL, x1, x2 - h), -1)), 0.5 / h);
    double jac = da.x * db.y - da.y * db.x; /* signed */
    ggx_vec3 d = map_concentric_walter(NULL, x1, x2);
    snprintf(at, nat, "xi = (%.4g, %.4g): signed Jacobian %.6g", x1, x2, jac);
    return fmax(fabs(jac / GGX_PI - 1), fmax(0, t_dot(d, d) - 1));
}

/* ---- Walter eq 38-41: the squeeze along x by s and the lift (the image: the lune's crescent) ---- */
typedef struct sq_ctx {
    double s;
} sq_ctx;
static ggx_vec3 map_squeeze(const void *vc, double xa, double ya)
{
    double s = ((const sq_ctx *)vc)->s;
    return t_vec(s * xa + (1 - s) * sqrt(1 - ya * ya), ya, 0);
}
/* Walter's frame (eq 42-44) for the view psi: e3 = A psi / ||A psi||, e2 = A psi x A n / ||.||, e1 = e2 x e3. */
static void walter_frame(const double A[3][3], ggx_vec3 psi, ggx_vec3 *e1, ggx_vec3 *e2, ggx_vec3 *e3)
{
    *e3 = t_normalize(t_matvec(A, psi));
    *e2 = t_normalize(t_cross(t_matvec(A, psi), t_matvec(A, N_UP)));
    *e1 = t_cross(*e2, *e3);
}
/* The lune point pc of eq 34-45 for the disk point (xa, ya) and the squeeze s. */
static ggx_vec3 walter_pc(const double A[3][3], ggx_vec3 psi, double xa, double ya)
{
    ggx_vec3 e1, e2, e3, an = t_normalize(t_matvec(A, N_UP));
    walter_frame(A, psi, &e1, &e2, &e3);
    double s = 0.5 * (1 + t_dot(e3, an)), xb = s * xa + (1 - s) * sqrt(1 - ya * ya);
    double zb = sqrt(fmax(0, 1 - xb * xb - ya * ya));
    return t_add(t_add(t_scale(e1, xb), t_scale(e2, ya)), t_scale(e3, zb));
}
static void random_disk(rng *g, double *x, double *y)
{
    double r = sqrt(rng_uniform(g)), t = 2 * GGX_PI * rng_uniform(g);
    *x = r * cos(t), *y = r * sin(t);
}
static double err_squeeze(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    const double(*A)[3] = (const double(*)[3])K->A;
    ggx_vec3 psi = au_random_upper(g), ap = t_normalize(t_matvec(A, psi)), an = t_normalize(t_matvec(A, N_UP));
    sq_ctx c = {0.5 * (1 + t_dot(ap, an))};
    double xa, ya;
    random_disk(g, &xa, &ya);
    double jac = au_fd_jacobian(map_squeeze, &c, xa, ya, 1e-7);
    ggx_vec3 pc = walter_pc(A, psi, xa, ya);
    double below = fmax(0, -t_dot(pc, an)); /* in the lune: pc.An >= 0 */
    snprintf(at, nat, "psi = (%.3g, %.3g, %.3g), disk point (%.3g, %.3g): Jacobian %.6g, s %.6g", psi.x, psi.y, psi.z,
             xa, ya, jac, c.s);
    return fmax(fabs(jac / c.s - 1), below);
}
static double err_frame(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    const double(*A)[3] = (const double(*)[3])K->A;
    double Ait[3][3];
    au_inv_t(A, Ait);
    ggx_vec3 psi = au_random_upper(g), e1, e2, e3, an = t_normalize(t_matvec(A, N_UP));
    walter_frame(A, psi, &e1, &e2, &e3);
    ggx_vec3 e2b = t_normalize(t_matvec((const double(*)[3])Ait, t_cross(psi, N_UP)));
    ggx_vec3 closest = t_normalize(t_add(an, t_scale(e3, -t_dot(an, e3)))); /* the unit vector _|_ e3 nearest A n */
    snprintf(at, nat, "psi = (%.3g, %.3g, %.3g)", psi.x, psi.y, psi.z);
    return fmax(vdist(e2, e2b), vdist(e1, closest));
}
typedef struct lp_ctx {
    double typo; /* the largest distance between m and the normal at A pc (the text's reading) */
} lp_ctx;
static double err_lune_point(const au_kin *K, rng *g, void *vc, char *at, size_t nat)
{
    lp_ctx *c = vc;
    const double(*A)[3] = (const double(*)[3])K->A;
    double M[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) M[i][j] = A[0][i] * A[0][j] + A[1][i] * A[1][j] + A[2][i] * A[2][j];
    ggx_vec3 psi = au_random_upper(g);
    double xa, ya, Ait[3][3];
    random_disk(g, &xa, &ya);
    au_inv_t(A, Ait);
    ggx_vec3 pc = walter_pc(A, psi, xa, ya), m = t_normalize(t_mattvec(A, pc));
    ggx_vec3 p = t_mattvec((const double(*)[3])Ait, pc); /* A^-1 pc, on the ellipsoid */
    ggx_vec3 normal = t_normalize(t_matvec((const double(*)[3])M, p));
    ggx_vec3 q = t_matvec(A, pc), typo_normal = t_normalize(t_matvec((const double(*)[3])M, q));
    if (!K->searching) c->typo = fmax(c->typo, vdist(typo_normal, m));
    double e = fmax(fabs(t_dot(pc, pc) - 1), fmax(0, -t_dot(m, N_UP)));
    e = fmax(e, fmax(fmax(0, -t_dot(m, psi)), vdist(normal, m)));
    e = fmax(e, fabs(t_dot(t_matvec(A, p), t_matvec(A, p)) - 1));
    snprintf(at, nat, "psi = (%.3g, %.3g, %.3g), disk point (%.3g, %.3g)", psi.x, psi.y, psi.z, xa, ya);
    return e;
}

/* ---- Walter version 1: rays at the ellipsoid from a bounding sphere's disk, against eq 33 (ggx_pdf_vndf) ---- */
static int draw_v1(void *vc, rng *r, ggx_vec3 *m)
{
    const ggx_shape *s = ((const normal_keys *)vc)->s;
    unsigned tries;
    *m = ggx_sample_vndf_walter_v1(s, ((const normal_keys *)vc)->v, au_uniform_cb, r, &tries);
    return t_dot(*m, *m) > 0.5;
}

/* ---- blog Part 2 eq:pm with its own s (A^-T n): p(m) = (1/s)(||An|| / ||Av||) D(m)(m.v) on m.v > 0 ----
 * The blog truncates the ellipsoid by the plane z = 0 through its centre in position space (hence its s with
 * A^-T n): its support is {m : (A^-T n).(A^-T m) >= 0, m.v > 0}, with D's formula untruncated. That support is
 * Walter's half m.n >= 0 for unskewed shapes only. The integral is taken in sphere space, m' = A^-T m / ||.||, over
 * the lune {m'.c >= 0, m'.v' >= 0} (c = A^-T n / ||.||, v' = A v / ||.||) with d omega_m = |A| / ||A^T m'||^3
 * d omega_m', by quadrature on the unit sphere in a frame with c along z. */
typedef struct pm_ctx {
    const ggx_shape *s;
    ggx_vec3 v, e1, e2, e3;
    double k;
    int walter; /* 1: on Walter's half m.n >= 0 (ggx_ndf, truncated), integrated in m directly */
} pm_ctx;
static double pm_density(const pm_ctx *c, ggx_vec3 m) /* eq:pm with D's formula */
{
    ggx_vec3 q = t_matvec((const double(*)[3])c->s->ainv_t, m);
    double q2 = t_dot(q, q), mv = t_dot(m, c->v);
    return mv > 0 ? c->k * c->s->ndf_scale / (q2 * q2) * mv : 0.0;
}
static double pm_f(ggx_vec3 mp, void *vc)
{
    const pm_ctx *c = vc;
    if (c->walter) return mp.z >= 0 ? pm_density(c, mp) : 0.0;
    ggx_vec3 sp = t_add(t_add(t_scale(c->e1, mp.x), t_scale(c->e2, mp.y)), t_scale(c->e3, mp.z)); /* m' */
    ggx_vec3 at = t_mattvec((const double(*)[3])c->s->a, sp);
    double l = sqrt(t_dot(at, at));
    return pm_density(c, t_scale(at, 1 / l)) * c->s->det / (l * l * l);
}
static double pm_integral_side(const ggx_shape *s, ggx_vec3 v, int walter)
{
    const double(*A)[3] = (const double(*)[3])s->a; /* canonical: the norms and s are those of Walter's A */
    ggx_vec3 av = t_matvec(A, v), nt = t_matvec((const double(*)[3])s->ainv_t, N_UP);
    double lav = sqrt(t_dot(av, av)), sb = 0.5 * (1 + t_dot(av, nt) / (lav * sqrt(t_dot(nt, nt))));
    pm_ctx c = {s, v, {0, 0, 0}, {0, 0, 0}, t_normalize(nt), au_norm_of(A, N_UP) / (lav * sb), walter};
    if (walter) return quad_hemisphere(s, pm_f, &c, &v, 1, 1e-11, NULL);
    t_frame(c.e3, &c.e1, &c.e2);
    ggx_shape sphere;
    ggx_shape_iso(&sphere, 1);
    ggx_vec3 cut = t_vec(t_dot(av, c.e1), t_dot(av, c.e2), t_dot(av, c.e3));
    return quad_hemisphere(&sphere, pm_f, &c, &cut, 1, 1e-11, NULL);
}
static double pm_integral(const ggx_shape *s, ggx_vec3 v) { return pm_integral_side(s, v, 0); }

/* ---- Engstad's proof: the total Jacobian of u -> m (his five steps with A), z and the simplified form ---- */
typedef struct tj_ctx {
    const double (*A)[3];
    ggx_vec3 v;
} tj_ctx;
static ggx_vec3 map_heitz(const void *vc, double u1, double u2)
{
    const tj_ctx *c = vc;
    return au_literal_heitz(c->A, c->v, u1, u2);
}
static double err_total_vndf(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    tj_ctx c = {(const double(*)[3])K->A, au_random_upper(g)};
    double u1 = 0.02 + 0.96 * rng_uniform(g), u2 = rng_uniform(g), Ait[3][3];
    au_inv_t(c.A, Ait);
    ggx_vec3 m = map_heitz(&c, u1, u2), av = t_matvec(c.A, c.v);
    double ax, ay;
    au_kin_alphas(K, &ax, &ay);
    double fd = au_fd_jacobian(map_heitz, &c, u1, u2, 1e-6), axy = ax * ay;
    /* A^-1 m as the seed writes it (= A^-T m for a diagonal A) */
    ggx_vec3 ai = t_mattvec((const double(*)[3])Ait, m);
    double lai = sqrt(t_dot(ai, ai)), lav = sqrt(t_dot(av, av)), mv = t_dot(m, c.v), zz = av.z / lav;
    double z = mv / (lai * lav), z_direct = t_dot(t_scale(ai, 1 / lai), t_scale(av, 1 / lav)); /* s.z_hat */
    double j1 = axy * lai * lai * lai / z * 0.5 * (1 + zz) * GGX_PI;
    double j2 = GGX_PI * axy * lai * lai * lai * lai * c.v.z / (mv * ggx_g1(&K->s, c.v, m));
    snprintf(at, nat, "v = (%.3g, %.3g, %.3g), u = (%.3g, %.3g): finite differences %.6g, the two forms %.6g, %.6g",
             c.v.x, c.v.y, c.v.z, u1, u2, fd, j1, j2);
    return fmax(fmax(fabs(j1 / fd - 1), fabs(j2 / fd - 1)), fabs(z - z_direct));
}

/* ---- (x, y) -> (x, y, sqrt(1 - x^2 - y^2)) has area Jacobian 1 / z ---- */
static ggx_vec3 map_project(const void *vc, double x, double y)
{
    (void)vc;
    return t_vec(x, y, sqrt(1 - x * x - y * y));
}
static double err_project(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)K, (void)ctx;
    double x, y;
    random_disk(g, &x, &y);
    x *= 0.99, y *= 0.99;
    double z = sqrt(1 - x * x - y * y);
    snprintf(at, nat, "(x, y) = (%.3g, %.3g)", x, y);
    return fabs(au_fd_jacobian(map_project, NULL, x, y, 1e-7) * z - 1);
}

void au_rows_sampling(const au_ctx *c)
{
    audit_row *r;
    const ggx_vec3 v = t_dir(1.2, -0.6);
    ggx_shape sphere;
    ggx_shape_iso(&sphere, 1);

    r = au_add(c->rows, c->nr, "lift",
               "x = a sqrt(xi1) cos 2 pi xi2, y = b sqrt(xi1) sin 2 pi xi2 is uniform on the ellipse "
               "of area pi a b = A_perp(n); z = c sqrt(1 - xi1) lifts it to the ellipsoid, whose normal there is "
               "normalize(sqrt(xi1) cos 2 pi xi2 / a, sqrt(xi1) sin 2 pi xi2 / b, sqrt(1 - xi1) / c)",
               SEED_BLOG2, "Sampling Normals (first eqnarrays)", AUDIT_SCOPE_DIAGONAL);
    au_kin_row(c, r, 1, err_lift, NULL, 100, 1e-6,
               "with a = 1/ax, b = 1/ay, c = 1 on the shape's ellipsoid (point, "
               "normal, Jacobian pi a b, area):");

    r = au_add(c->rows, c->nr, "sphere-disk",
               "a uniform unit disk _|_ v' projected onto the unit sphere along v' has "
               "density p_s(m') = (m'.v') / pi on m'.v' > 0",
               SEED_BLOG2, "eq p_s(m')", AUDIT_SCOPE_ANY);
    {
        double p = au_chi2_sampler(&sphere, N_UP, disk_projected, verify_pdf_ndf, 501, c->progress);
        for (int k = 0; k < AUDIT_SHAPES; k++) {
            au_verdict_p(r, k, p);
            au_append(r, k, " (sphere space, the same for every A)");
        }
    }

    r = au_add(c->rows, c->nr, "crescent-sphere",
               "the crescent map t1' = t1, t2' = (1 - s) sqrt(1 - t1^2) + s t2 of the "
               "disk, lifted, lies in the lune and has density p_c(m') = p_s(m') / s = (m'.v') / (pi s)",
               SEED_BLOG2, "after 'Eq.(11) of the VNDF sampling article'; eq:m-prime-pdf", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) { /* v' = A v in the canonical sphere space of shape k (A n along z) */
        ggx_vec3 vs = t_normalize(t_matvec((const double(*)[3])c->sh[k].a, v));
        au_verdict_p(r, k, au_chi2_sampler(&sphere, vs, crescent_sphere, ggx_pdf_vndf, 503 + (uint64_t)k, c->progress));
        au_append(r, k, " (at v' = normalize(A v) = (%.3f, %.3f, %.3f))", vs.x, vs.y, vs.z);
    }

    r = au_add(c->rows, c->nr, "concentric-walter",
               "a = 2 xi1 - 1, b = 2 xi2 - 1; (a cos(pi b / 4a), a sin(pi b / 4a)) if "
               "|a| > |b|, else (b sin(pi a / 4b), b cos(pi a / 4b)); (0, 0) at the centre: uniform on the unit disk",
               SEED_WALTER, "eq 34-37", AUDIT_SCOPE_ANY);
    {
        /* one to one: 16 cells of equal area (8 wedges, 2 rings) each receive 1/16 of 1.6e5 points, within 5 sigma */
        rng g = {521};
        long cnt[16] = {0}, n_pts = 160000;
        for (long i = 0; i < n_pts; i++) {
            ggx_vec3 d = map_concentric_walter(NULL, rng_uniform(&g), rng_uniform(&g));
            double a = atan2(d.y, d.x) + GGX_PI;
            int w = (int)(a / (GGX_PI / 4)) & 7, ring = d.x * d.x + d.y * d.y >= 0.5;
            cnt[w + 8 * ring]++;
        }
        double want = (double)n_pts / 16.0, sig = sqrt(want * (1 - 1 / 16.0)), worst = 0;
        for (int c16 = 0; c16 < 16; c16++) worst = fmax(worst, fabs((double)cnt[c16] - want) / sig);
        for (int k = 0; k < AUDIT_SHAPES; k++) {
            au_verdict_kin(r, k, &c->sh[k], c->A[k], err_concentric, NULL, 400, 1e-6,
                           "the signed finite-difference Jacobian against +pi (one orientation: no fold) and |d| <= 1 "
                           "(no A involved):");
            au_append(r, k, "; 16 equal-area cells (8 wedges, 2 rings) get 1/16 of 1.6e5 points each within %.1f sigma",
                      worst);
            if (worst > 5) r->verdict[k] = AUDIT_FAILS;
        }
    }

    r = au_add(c->rows, c->nr, "squeeze-walter",
               "s = (1 + A psi.A n / (||A psi|| ||An||)) / 2; xb = s xa + (1 - s) sqrt(1 - "
               "ya^2), yb = ya has |d(xb, yb) / d(xa, ya)| = s and, lifted, lands in the lune",
               SEED_WALTER, "eq 38-41", AUDIT_SCOPE_ANY);
    au_kin_row(c, r, 0, err_squeeze, NULL, 100, 1e-7, "the finite-difference Jacobian against s and pc.An >= 0:");

    r = au_add(c->rows, c->nr, "frame-eq42",
               "e3 = A psi / ||A psi||, e2 = A psi x A n / ||.|| = A^-T (psi x n) / ||.|| (det A "
               "> 0), e1 = e2 x e3 is the unit vector _|_ e3 nearest A n",
               SEED_WALTER, "eq 42-44", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        au_verdict_kin(r, k, &c->sh[k], c->A[k], err_frame, NULL, 200, 1e-12, "both forms of e2, and e1:");
        /* the condition det A > 0: with a reflection (det < 0) the two forms of e2 are opposite */
        double QA[3][3], Ait[3][3];
        memcpy(QA, c->A[k], sizeof QA);
        for (int j = 0; j < 3; j++) QA[0][j] = -QA[0][j];
        au_inv_t((const double(*)[3])QA, Ait);
        ggx_vec3 psi = t_dir(0.9, 0.4), e1, e2, e3;
        walter_frame((const double(*)[3])QA, psi, &e1, &e2, &e3);
        double d = t_dot(e2, t_normalize(t_matvec((const double(*)[3])Ait, t_cross(psi, N_UP))));
        au_append(r, k, "; with det A < 0 (first row negated) e2 . e2' = %.3f (opposite: the condition is needed)", d);
    }

    r = au_add(c->rows, c->nr, "lune-point",
               "pc = xb e1 + yb e2 + zb e3 is a unit vector of the lune (pc.An >= 0, pc.A psi "
               ">= 0); m = A^T pc / ||A^T pc|| is the normal at A^-1 pc (the text says A pc)",
               SEED_WALTER, "eq 45-46", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        lp_ctx lc = {0};
        au_verdict_kin(r, k, &c->sh[k], c->A[k], err_lune_point, &lc, 100, 1e-12,
                       "|pc| = 1, m.n >= 0, m.psi >= 0, A^-1 pc on the ellipsoid with normal m:");
        au_append(r, k, "; read as the point A pc (the text), the normal there is off m by up to %.3g", lc.typo);
    }

    r = au_add(c->rows, c->nr, "walter-v1",
               "rays along -psi through uniform points of a bounding sphere's disk, kept where "
               "they hit with m.n >= 0 and m.psi >= 0, give m with the pdf of eq 33",
               SEED_WALTER, "section 4, version 1", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        normal_keys nk = {&c->sh[k], v, ggx_pdf_vndf};
        au_verdict_p(r, k, au_chi2_draw(&c->sh[k], v, draw_v1, &nk, ggx_pdf_vndf, 511 + (uint64_t)k, c->progress));
    }

    r = au_add(c->rows, c->nr, "pm-blog",
               "the crescent sampler's pdf p(m) = (1/s)(||An|| / ||Av||) D(m)(m.v), with the "
               "blog's s = (1 + Av.A^-T n / (||Av|| ||A^-T n||)) / 2, integrates to 1 over its support",
               SEED_BLOG2, "eq:pm", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        au_verdict_views(r, k, pm_integral, &c->sh[k], 1e-6,
                         "on the blog's support (the ellipsoid cut by z = 0), p(m)");
        if (c->sh[k].kind != GGX_SHAPE_SKEWED) continue; /* the supports differ for skewed shapes only */
        double lo = INFINITY, hi = 0;
        for (int i = 0; i < 6; i++) {
            double x = pm_integral_side(&c->sh[k], t_dir(0.3 + 0.24 * i, 2.75 - 1.1 * i), 1);
            lo = fmin(lo, x), hi = fmax(hi, x);
        }
        au_append(r, k, "; on Walter's half m.n >= 0 (a different truncation) it integrates to %.3f to %.3f at 6 views",
                  lo, hi);
    }

    r = au_add(c->rows, c->nr, "vndf-total-jacobian",
               "the five steps' |dm / du| = ax ay ||A^-1 m||^3 (1/z)((1 + z_z)/2) pi "
               "with z = (m.v) / (||A^-1 m|| ||Av||) = s.z_hat, = pi ax ay ||A^-1 m||^4 (v.n) / ((m.v) G1(v))",
               SEED_VNDF, "Proof of the PDF; Solving for z; Total Jacobian Determinant", AUDIT_SCOPE_DIAGONAL);
    au_kin_row(c, r, 1, err_total_vndf, NULL, 50, 1e-6,
               "against the finite-difference Jacobian of the steps as "
               "written (and z two ways):");

    r = au_add(c->rows, c->nr, "project-jacobian",
               "(x, y) -> (x, y, sqrt(1 - x^2 - y^2)) has area Jacobian 1 / z (the frame "
               "rotation keeps areas)",
               SEED_VNDF, "Project the point", AUDIT_SCOPE_ANY);
    au_kin_row(c, r, 0, err_project, NULL, 50, 1e-7, "against finite differences (no A involved):");
}
