/* The seed audit: the ellipsoid's geometry (blog Part 1 and 2, Walter section 2, Engstad's ellipsoid map), each
 * claim checked on the actual surface x^T A^T A x = Ce^2 by means independent of the formula under test: points and
 * normals from the implicit function, curvature from finite differences of the Gauss map, areas by rays and by
 * surface integrals, normalisations by quadrature. SPDX-License-Identifier: MIT */
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
static void ata(const double A[3][3], double M[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) M[i][j] = A[0][i] * A[0][j] + A[1][i] * A[1][j] + A[2][i] * A[2][j];
}
static double det_of(const double A[3][3])
{
    return au_det3(t_matvec(A, t_vec(1, 0, 0)), t_matvec(A, t_vec(0, 1, 0)), t_matvec(A, t_vec(0, 0, 1)));
}
static ggx_vec3 random_unit(rng *g) { return t_dir(acos(1 - 2 * rng_uniform(g)), 2 * GGX_PI * rng_uniform(g)); }

/* ---- a point and its normal (blog Part 1 after eq:ellipsoid-k, eq:mag-gradient; Walter section 2) ---- */
static double err_normal_point(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    const double(*A)[3] = (const double(*)[3])K->A;
    double Ait[3][3], M[3][3];
    au_inv_t(A, Ait);
    ata(A, M);
    ggx_vec3 p = t_mattvec((const double(*)[3])Ait, random_unit(g)); /* A^-1 s: on the ellipsoid */
    ggx_vec3 grad = t_scale(t_matvec((const double(*)[3])M, p), 2);
    double gl = sqrt(t_dot(grad, grad));
    ggx_vec3 m = t_scale(grad, 1 / gl), q = t_matvec((const double(*)[3])Ait, m);
    double q2 = t_dot(q, q), pl = sqrt(t_dot(p, p));
    ggx_vec3 p_blog = t_scale(t_mattvec((const double(*)[3])Ait, q), 0.5 * gl); /* (1/2)||grad f|| A^-1 A^-T m */
    ggx_vec3 p_walter = au_point_of_normal((const double(*)[3])Ait, m);         /* A^-1 A^-T m / ||A^-T m|| */
    ggx_vec3 m_back = t_normalize(t_matvec((const double(*)[3])M, p_walter));   /* the normal there */
    ggx_vec3 m_minus = t_normalize(
        t_matvec((const double(*)[3])M, au_point_of_normal((const double(*)[3])Ait, t_scale(m, -1))));
    double e = fmax(vdist(p_blog, p) / pl, fabs(gl * gl * q2 / 4 - 1));
    e = fmax(e, fmax(vdist(p_walter, p) / pl, fmax(vdist(m_back, m), vdist(m_minus, t_scale(m, -1)))));
    snprintf(at, nat, "p = (%.3g, %.3g, %.3g)", p.x, p.y, p.z);
    return e;
}

/* ---- Gaussian curvature: finite differences of the Gauss map against the implicit-surface formulas ---- */
static double det4(double a[4][4])
{
    double d = 0;
    for (int c = 0; c < 4; c++) {
        double m[3][3];
        for (int i = 1; i < 4; i++)
            for (int j = 0, jj = 0; j < 4; j++)
                if (j != c) m[i - 1][jj++] = a[i][j];
        double minor = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        d += (c % 2 ? -1 : 1) * a[0][c] * minor;
    }
    return d;
}
typedef struct patch {
    double A[3][3], Ait[3][3], ce; /* the ellipsoid x^T A^T A x = ce^2 */
    ggx_vec3 s, t1, t2;            /* the sphere point of the patch's centre and its tangents */
} patch;
static ggx_vec3 patch_point(const patch *c, double a, double b)
{
    ggx_vec3 s = t_normalize(t_add(c->s, t_add(t_scale(c->t1, a), t_scale(c->t2, b))));
    return t_scale(t_mattvec((const double(*)[3])c->Ait, s), c->ce); /* ce A^-1 s */
}
static ggx_vec3 patch_normal(const void *vc, double a, double b)
{
    const patch *c = vc;
    double M[3][3];
    ata((const double(*)[3])c->A, M);
    return t_normalize(t_matvec((const double(*)[3])M, patch_point(c, a, b)));
}
static ggx_vec3 patch_surface(const void *vc, double a, double b) { return patch_point(vc, a, b); }
/* K = (solid angle of the normals) / (area) of a small patch around ce A^-1 s. */
static double fd_curvature(patch *c, ggx_vec3 s)
{
    c->s = s;
    t_frame(s, &c->t1, &c->t2);
    return au_fd_jacobian(patch_normal, c, 0, 0, 1e-5) / au_fd_jacobian(patch_surface, c, 0, 0, 1e-5);
}
static double err_gauss_map(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    patch c;
    memcpy(c.A, K->A, sizeof c.A);
    au_inv_t((const double(*)[3])c.A, c.Ait);
    c.ce = 1;
    ggx_vec3 s = random_unit(g);
    double kfd = fd_curvature(&c, s), M[3][3], H[3][3], det = det_of((const double(*)[3])c.A);
    ata((const double(*)[3])c.A, M);
    ggx_vec3 p = patch_point(&c, 0, 0), gr = t_scale(t_matvec((const double(*)[3])M, p), 2);
    double g2 = t_dot(gr, gr), hinv_g[3], adj_form = 0, br[4][4];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) H[i][j] = 2 * M[i][j];
    /* Goldman (Walter eq 10): grad^T adj(H) grad, adj(H) by cofactors */
    for (int i = 0; i < 3; i++) {
        hinv_g[i] = 0;
        for (int j = 0; j < 3; j++) {
            int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3; /* adj = cofactor^T */
            hinv_g[i] += (H[i1][j1] * H[i2][j2] - H[i1][j2] * H[i2][j1]) * (&gr.x)[j];
        }
        adj_form += (&gr.x)[i] * hinv_g[i];
    }
    /* Brioschi (blog eq:ellipsoid-k): -det [[H, grad], [grad^T, 0]] */
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) br[i][j] = H[i][j];
        br[i][3] = br[3][i] = (&gr.x)[i];
    }
    br[3][3] = 0;
    double k_goldman = adj_form / (g2 * g2), k_brioschi = -det4(br) / (g2 * g2);
    /* the blog's closed forms with a^2 b^2 c^2 = 1 / |A|^2 and x^2/a^2 + y^2/b^2 + z^2/c^2 = p^T A^T A p */
    double k_blog = 16 * det * det * t_dot(p, t_matvec((const double(*)[3])M, p)) / (g2 * g2);
    double k_blog_surface = 16 * det * det / (g2 * g2);
    double e = fmax(fabs(k_goldman / kfd - 1), fabs(k_brioschi / kfd - 1));
    e = fmax(e, fmax(fabs(k_blog / kfd - 1), fabs(k_blog_surface / kfd - 1)));
    snprintf(at, nat, "p = (%.3g, %.3g, %.3g): finite differences %.6g, Goldman %.6g, Brioschi %.6g, closed form %.6g",
             p.x, p.y, p.z, kfd, k_goldman, k_brioschi, k_blog_surface);
    return e;
}

/* ---- the silhouette seen from v: {p : (A^T A v).p = 0}, and its projected area (Walter eq 23) ---- */
static double err_silhouette(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    double M[3][3], worst = 0;
    ata((const double(*)[3])K->A, M);
    ggx_vec3 v = random_unit(g), w = t_matvec((const double(*)[3])M, v), e1, e2, wn = t_normalize(w);
    t_frame(wn, &e1, &e2);
    for (int i = 0; i < 16; i++) { /* silhouette points: m.v = 0 */
        double t = 2 * GGX_PI * (i + rng_uniform(g)) / 16;
        ggx_vec3 q = t_add(t_scale(e1, cos(t)), t_scale(e2, sin(t)));
        ggx_vec3 p = t_scale(q, 1 / sqrt(t_dot(q, t_matvec((const double(*)[3])M, q))));
        worst = fmax(worst, fabs(t_dot(t_normalize(t_matvec((const double(*)[3])M, p)), v)));
    }
    /* the section of the ellipsoid by the plane: an ellipse of area pi / sqrt(det B), B = [e_i^T M e_j] */
    ggx_vec3 m1 = t_matvec((const double(*)[3])M, e1), m2 = t_matvec((const double(*)[3])M, e2);
    double b11 = t_dot(e1, m1), b12 = t_dot(e1, m2), b22 = t_dot(e2, m2), area = GGX_PI / sqrt(b11 * b22 - b12 * b12);
    double proj = area * fabs(t_dot(wn, v)),
           eq26 = GGX_PI * au_norm_of((const double(*)[3])K->A, v) / fabs(det_of((const double(*)[3])K->A));
    snprintf(at, nat, "v = (%.3g, %.3g, %.3g): A^T A v %.3g deg from v, section x cosine %.6g, eq 26 %.6g", v.x, v.y,
             v.z, acos(fmin(1.0, t_dot(wn, v))) * 180 / GGX_PI, proj, eq26);
    return fmax(worst, fabs(proj / eq26 - 1));
}

/* ---- surface integrals (Walter eq 21-22, 27; blog eq:A_perp): over the sphere that A maps the ellipsoid to, where
 * dp = ||A^T s|| / |A| d omega_s and u.m = (s.A u) / ||A^T s||, by quadrature on the unit sphere in a frame with A u
 * along z; the other cut plane A v is a break point. ---- */
typedef struct surf_ctx {
    ggx_vec3 e1, e2, e3; /* e3 = A u / ||A u|| */
    ggx_vec3 au;
    double det;
} surf_ctx;
static double surf_f(ggx_vec3 sp, void *vc)
{
    const surf_ctx *c = vc;
    ggx_vec3 s = t_add(t_add(t_scale(c->e1, sp.x), t_scale(c->e2, sp.y)), t_scale(c->e3, sp.z));
    return t_dot(s, c->au) / c->det; /* X+(u.m) is sp.z >= 0 (the domain), X+(v.m) the cut */
}
static double surface_lune(const ggx_shape *sphere, const double A[3][3], ggx_vec3 u, ggx_vec3 v)
{
    surf_ctx c;
    c.au = t_matvec(A, u), c.e3 = t_normalize(c.au), c.det = fabs(det_of(A));
    t_frame(c.e3, &c.e1, &c.e2);
    ggx_vec3 av = t_matvec(A, v), cut = t_vec(t_dot(av, c.e1), t_dot(av, c.e2), t_dot(av, c.e3));
    return quad_hemisphere(sphere, surf_f, &c, &cut, 1, 1e-11, NULL);
}
static void surface_row(audit_row *r, int k, const double A[3][3], const ggx_shape *s)
{
    static const double dirs[4][2] = {{0.0, 0.0}, {0.7, 0.4}, {1.2, -2.0}, {1.5, 2.6}};
    ggx_shape sphere;
    ggx_shape_iso(&sphere, 1);
    double worst_rays = 0, worst_rays_sig = 0, worst_form = 0;
    int ok = 1;
    for (int i = 0; i < 4; i++) {
        ggx_vec3 u = t_dir(dirs[i][0], dirs[i][1]), v = i % 2 ? t_dir(1.0, 1.1) : N_UP;
        double sig, rays = au_ray_area(A, u, v, 1, 1000000, 401 + (uint64_t)i, &sig);
        double integral = surface_lune(&sphere, A, u, v), own = surface_lune(&sphere, A, u, u);
        ok &= fabs(integral - rays) <= 5 * sig;
        if (fabs(integral / rays - 1) > worst_rays) worst_rays = fabs(integral / rays - 1), worst_rays_sig = sig / rays;
        worst_form = fmax(worst_form,
                          fmax(fabs(integral / ggx_lune_area(s, u, v) - 1), fabs(own / ggx_projected_area(s, u) - 1)));
    }
    ok &= worst_form < 1e-8;
    au_set(r, k, ok ? AUDIT_HOLDS : AUDIT_FAILS,
           "the surface integrals against 10^6 rays at the ellipsoid from each of 4 "
           "directions: worst |integral / rays - 1| = %.1e (5 sigma = %.1e); against eq 26 and 28: %.1e",
           worst_rays, 5 * worst_rays_sig, worst_form);
}

/* ---- a spherical lune's projected area (Walter section 2.3), by rays at the unit sphere ---- */
static void lune_sphere_row(audit_row *r, int k, const double A[3][3])
{
    static const double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    rng g = {131};
    double worst = 0, worst_sig = 0;
    int ok = 1;
    for (int i = 0; i < 4; i++) {
        ggx_vec3 u = au_random_upper(&g), v = au_random_upper(&g);
        ggx_vec3 a = t_normalize(t_matvec(A, u)), b = t_normalize(t_matvec(A, v)); /* the lune's plane normals */
        double sig, rays = au_ray_area(I, b, a, 1, 1000000, 411 + (uint64_t)i, &sig),
                    want = GGX_PI / 2 * (1 + t_dot(a, b));
        ok &= fabs(rays - want) <= 5 * sig;
        if (fabs(rays / want - 1) > worst) worst = fabs(rays / want - 1), worst_sig = sig / want;
    }
    au_set(r, k, ok ? AUDIT_HOLDS : AUDIT_FAILS,
           "10^6 rays at the unit sphere for each of 4 lunes with plane normals A u, "
           "A v: worst |rays / formula - 1| = %.1e (%s 5 sigma = %.1e)",
           worst, ok ? "within" : "beyond", 5 * worst_sig);
}

/* ---- Ce cancels (Walter eq 9, 20, 26, 29): D = 1 / (A_e(n) K_g) on the ellipsoid of any radius Ce, with A_e(n)
 * by rays and K_g by finite differences of its Gauss map ---- */
static void ce_row(audit_row *r, int k, const double A[3][3], const ggx_shape *s)
{
    static const double ces[3] = {0.3, 2.5, 0}; /* 0: eq 29's Ce */
    double det = fabs(det_of(A)), worst = 0, worst_sig = 0, ae29 = 0, ae29_sig = 0;
    int ok = 1;
    rng g = {141};
    for (int i = 0; i < 3; i++) {
        double ce = ces[i] > 0 ? ces[i] : sqrt(det / (GGX_PI * au_norm_of(A, N_UP))), Ac[3][3], sig;
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) Ac[a][b] = A[a][b] / ce; /* x^T A^T A x = ce^2 */
        double ae = au_ray_area((const double(*)[3])Ac, N_UP, N_UP, 0, 1000000, 421 + (uint64_t)i, &sig);
        if (ces[i] == 0) {
            ae29 = ae, ae29_sig = sig;
            ok &= fabs(ae - 1) <= 5 * sig;
            continue;
        }
        patch c;
        memcpy(c.A, A, sizeof c.A);
        au_inv_t(A, c.Ait);
        c.ce = ce;
        for (int j = 0; j < 20; j++) {
            ggx_vec3 m = au_random_upper(&g), sp = t_normalize(t_matvec((const double(*)[3])c.Ait, m)); /* A^-T m */
            double d = 1 / (ae * fd_curvature(&c, sp)), want = ggx_ndf(s, m);
            worst = fmax(worst, fabs(d / want - 1)), worst_sig = fmax(worst_sig, sig / ae);
            ok &= fabs(d / want - 1) <= 5 * sig / ae + 1e-6;
        }
    }
    au_set(r, k, ok ? AUDIT_HOLDS : AUDIT_FAILS,
           "for Ce = 0.3 and 2.5, 1 / (A_e(n) K_g) (rays, finite differences) "
           "against D at 20 normals: worst %.1e (5 sigma = %.1e); eq 29's Ce gives A_e(n) = %.5f +- %.5f",
           worst, 5 * worst_sig, ae29, ae29_sig);
}

/* ---- semi-axes: 1 / alpha along the rotated axes (blog Part 1, after the anisotropic D) ---- */
static double err_semi_axes(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)g, (void)ctx;
    double M[3][3], E[9][9] = {{0}}, ev[9], al[3];
    ata((const double(*)[3])K->A, M);
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) E[i][j] = M[i][j];
        al[i] = sqrt(K->A[i][0] * K->A[i][0] + K->A[i][1] * K->A[i][1] + K->A[i][2] * K->A[i][2]); /* A = S R */
    }
    au_sym_eigenvalues(3, E, ev);
    double e = 0;
    for (int i = 0; i < 3; i++) { /* the semi-axis along R^T e_i (row i of A over alpha_i) is 1 / alpha_i */
        ggx_vec3 d = t_vec(K->A[i][0] / al[i], K->A[i][1] / al[i], K->A[i][2] / al[i]);
        double len = 1 / sqrt(t_dot(d, t_matvec((const double(*)[3])M, d)));
        e = fmax(e, fabs(len * al[i] - 1));
        double best = INFINITY; /* and an eigenvalue of A^T A is alpha_i^2 */
        for (int j = 0; j < 3; j++) best = fmin(best, fabs(ev[j] / (al[i] * al[i]) - 1));
        e = fmax(e, best);
    }
    snprintf(at, nat, "semi-axes %.4g, %.4g, %.4g", 1 / al[0], 1 / al[1], 1 / al[2]);
    return e;
}

/* ---- skew moves the peak of D to R^T z (Walter section 1): the maximum found by search ---- */
static double neg_d(const ggx_shape *s, double th, double ph) { return -ggx_ndf(s, t_dir(th, ph)); }
static ggx_vec3 argmax_d(const ggx_shape *s)
{
    double bt = 0, bp = 0, best = 0;
    for (int i = 0; i <= 60; i++)
        for (int j = 0; j < 120; j++) {
            double th = 0.5 * GGX_PI * i / 60, ph = 2 * GGX_PI * j / 120, d = -neg_d(s, th, ph);
            if (d > best) best = d, bt = th, bp = ph;
        }
    for (double h = 0.02; h > 1e-13; h *= 0.5) /* pattern search, halving the step */
        for (int moved = 1; moved;) {
            moved = 0;
            static const int dt[4] = {1, -1, 0, 0}, dp[4] = {0, 0, 1, -1};
            for (int q = 0; q < 4; q++) {
                double th = fmin(0.5 * GGX_PI, fabs(bt + dt[q] * h)), ph = bp + dp[q] * h / fmax(sin(bt), 1e-3);
                double d = -neg_d(s, th, ph);
                if (d > best) best = d, bt = th, bp = ph, moved = 1;
            }
        }
    return t_dir(bt, bp);
}
static void skew_max_row(audit_row *r, int k, const ggx_shape *s0, const double A0[3][3])
{
    double worst = 0, shift = 0;
    int shapes = 0;
    for (int i = 0; i < AU_KIN; i++) {
        au_kin K;
        au_kin_shape(s0, A0, i, 0x5eed, &K);
        double al[3];
        for (int a = 0; a < 3; a++) al[a] = sqrt(K.A[a][0] * K.A[a][0] + K.A[a][1] * K.A[a][1] + K.A[a][2] * K.A[a][2]);
        if (!(al[0] < 0.9 && al[1] < 0.9)) continue; /* the claim is for ax, ay < 1 */
        ggx_vec3 want = t_vec(K.A[2][0] / al[2], K.A[2][1] / al[2], K.A[2][2] / al[2]); /* R^T z: A's last row */
        ggx_vec3 got = argmax_d(&K.s);
        worst = fmax(worst, acos(fmin(1.0, t_dot(got, want)))), shift = fmax(shift, acos(fmin(1.0, want.z)));
        shapes++;
    }
    au_set(r, k, worst < 1e-5 ? AUDIT_HOLDS : AUDIT_FAILS,
           "the maximum of D found by search is R^T z within %.1e rad on "
           "%d shapes of this kind with alphas < 0.9; it lies up to %.3g degrees from n",
           worst, shapes, shift * 180 / GGX_PI);
}

/* ---- D along any direction u (blog Part 1 eq:NDF_norm and the eq after eq:A_perp_expression; Part 2 D(m, v)):
 * D(m, u) = abc / (pi ||A u|| (m^T A^-1 A^-T m)^2), abc = 1 / |A|, over the whole half-sphere m.u > 0 (the lower
 * part by m -> -m, D being even) ---- */
typedef struct du_ctx {
    double A[3][3], Ait[3][3], det;
    ggx_vec3 u;
    double sign;
} du_ctx;
static double d_u(const du_ctx *c, ggx_vec3 m)
{
    ggx_vec3 q = t_matvec((const double(*)[3])c->Ait, m);
    double q2 = t_dot(q, q);
    return 1 / (c->det * GGX_PI * au_norm_of((const double(*)[3])c->A, c->u) * q2 * q2);
}
static double du_f(ggx_vec3 m, void *vc)
{
    const du_ctx *c = vc;
    ggx_vec3 mm = t_scale(m, c->sign);
    return d_u(c, mm) * t_dot(mm, c->u);
}
static double err_d_u(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    du_ctx c;
    memcpy(c.A, K->A, sizeof c.A);
    au_inv_t((const double(*)[3])c.A, c.Ait);
    c.det = fabs(det_of((const double(*)[3])c.A));
    c.u = random_unit(g);
    double I = 0;
    for (int half = 0; half < 2; half++) {
        c.sign = half ? -1 : 1;
        ggx_vec3 cut = t_scale(c.u, c.sign);
        I += quad_hemisphere(&K->s, du_f, &c, &cut, 1, 1e-10, NULL);
    }
    /* Part 2: D(m, v) = (||A n|| / ||A v||) D(m) at a random m */
    ggx_vec3 m = au_random_upper(g);
    double dmv = d_u(&c, m), want = au_norm_of((const double(*)[3])c.A, N_UP) /
                                    au_norm_of((const double(*)[3])c.A, c.u) * ggx_ndf(&K->s, m);
    snprintf(at, nat, "u = (%.3g, %.3g, %.3g): integral %.9f", c.u.x, c.u.y, c.u.z, I);
    return fmax(fabs(I - 1), fabs(dmv / want - 1));
}

/* ---- D as a density over (theta, phi) (blog Part 1, last equation): the Jacobian sin theta by finite
 * differences, and the integral of D cos theta sin theta over the rectangle by nested adaptive quadrature ---- */
typedef struct sph_ctx {
    const ggx_shape *s;
    double th;
} sph_ctx;
static double sph_phi(double ph, void *vc)
{
    const sph_ctx *c = vc;
    return ggx_ndf(c->s, t_dir(c->th, ph)) * cos(c->th) * sin(c->th);
}
static double sph_theta(double th, void *vc)
{
    sph_ctx c = {((const sph_ctx *)vc)->s, th};
    return quad_adapt(sph_phi, &c, 0, 2 * GGX_PI, 1e-13);
}
static ggx_vec3 map_angles(const void *ctx, double th, double ph)
{
    (void)ctx;
    return t_dir(th, ph);
}
static void sin_row(audit_row *r, int k, const ggx_shape *s)
{
    sph_ctx c = {s, 0};
    double I = quad_adapt(sph_theta, &c, 0, 0.5 * GGX_PI, 1e-12), worst = 0;
    rng g = {151};
    for (int i = 0; i < 200; i++) {
        double th = 0.01 + 1.55 * rng_uniform(&g), ph = 2 * GGX_PI * rng_uniform(&g);
        worst = fmax(worst, fabs(au_fd_jacobian(map_angles, NULL, th, ph, 1e-6) / sin(th) - 1));
    }
    au_set(r, k, fabs(I - 1) < 1e-8 && worst < 1e-8 ? AUDIT_HOLDS : AUDIT_FAILS,
           "|dm / d(theta, phi)| = sin theta within "
           "%.1e (finite differences, 200 points); the double integral in (theta, phi) is 1 %+.1e",
           worst, I - 1);
}

/* ---- Engstad's ellipsoid map (engstad-vndf-proof): normalize(A s) is the normal at A^-1 s, normalize(A^T s) ---- */
static double err_ellipsoid_map(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    ggx_vec3 s = random_unit(g);
    if (s.z < 0) s.z = -s.z;
    double Ait[3][3], M[3][3];
    au_inv_t((const double(*)[3])K->A, Ait);
    ata((const double(*)[3])K->A, M);
    ggx_vec3 p = t_mattvec((const double(*)[3])Ait, s), normal = t_normalize(t_matvec((const double(*)[3])M, p));
    snprintf(at, nat, "s = (%.3g, %.3g, %.3g)", s.x, s.y, s.z);
    return vdist(t_normalize(t_matvec((const double(*)[3])K->A, s)), normal);
}

void au_rows_ellipsoid(const au_ctx *c)
{
    audit_row *r;
    r = au_add(c->rows, c->nr, "normal-point",
               "the normal at p is m = grad f / ||grad f||, grad f = 2 A^T A p, with "
               "||grad f||^2 = 4 / (m^T A^-1 A^-T m); each m occurs at the one point p = A^-1 A^-T m / ||A^-T m|| = "
               "(1/2) ||grad f|| A^-1 A^-T m",
               SEED_BLOG1 ", " SEED_WALTER,
               "blog Part 1 eq:mag-gradient and after "
               "eq:ellipsoid-k; Walter section 2",
               AUDIT_SCOPE_ANY);
    au_kin_row(c, r, 0, err_normal_point, NULL, 200, 1e-12,
               "at random surface points: the largest relative "
               "difference");

    r = au_add(c->rows, c->nr, "gauss-map",
               "Gaussian curvature K = grad f^T adj(H) grad f / ||grad f||^4 = -det [[H, grad "
               "f], [grad f^T, 0]] / ||grad f||^4 = 16 / (a^2 b^2 c^2 ||grad f||^4) on the surface; the Gauss map's "
               "Jacobian d omega / dA is K",
               SEED_BLOG1 ", " SEED_WALTER,
               "blog Part 1 eq:d-generic, eq:ellipsoid-k; "
               "Walter eq 10",
               AUDIT_SCOPE_ANY);
    au_kin_row(c, r, 0, err_gauss_map, NULL, 20, 1e-6,
               "against the finite-difference Gauss map (solid angle of the normals over the area of a patch), "
               "with "
               "a^2 b^2 c^2 = 1 / |A|^2:");

    r = au_add(c->rows, c->nr, "silhouette",
               "the points with m.v = 0 are the plane (A^T A v).p = 0 (A^T A v not along v); "
               "that ellipse's area times its cosine to v is the projected area A_e(v)",
               SEED_BLOG2 ", " SEED_WALTER, "blog Part 2 Figure 1; Walter eq 23", AUDIT_SCOPE_ANY);
    au_kin_row(c, r, 0, err_silhouette, NULL, 50, 1e-12,
               "m.v at 16 points of the section and the section's "
               "projected area against eq 26:");

    r = au_add(c->rows, c->nr, "surface-integrals",
               "A_e(u) = int X+(u.m) (u.m) dp and A_l(u, v) = int X+(u.m) X+(v.m) (u.m) "
               "dp over the surface, A_e(u) = A_l(u, u)",
               SEED_WALTER ", " SEED_BLOG1,
               "Walter eq 21-22, 27; blog Part 1 "
               "eq:A_perp",
               AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) surface_row(r, k, c->A[k], &c->sh[k]);

    r = au_add(c->rows, c->nr, "lune-sphere",
               "a unit-sphere lune projects along one of its plane normals to (pi/2)(1 + cos "
               "theta_l), cos theta_l = (Au).(Av) / (||Au|| ||Av||)",
               SEED_WALTER, "section 2.3", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) lune_sphere_row(r, k, c->A[k]);

    r = au_add(c->rows, c->nr, "ce-cancels",
               "D = 1 / (A_e(n) K_g) for the ellipsoid of any radius Ce (the Ce factors "
               "cancel); Ce = sqrt(|A| / (pi ||An||)) gives A_e(n) = 1",
               SEED_WALTER, "eq 9, 20, 26, 29", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) ce_row(r, k, c->A[k], &c->sh[k]);

    r = au_add(c->rows, c->nr, "semi-axes",
               "the equivalent ellipsoid has semi-axis 1 / alpha along each rough direction "
               "(smoother is longer), 1 along the third",
               SEED_BLOG1, "text after the anisotropic D", AUDIT_SCOPE_DIAGONAL);
    au_kin_row(c, r, 0, err_semi_axes, NULL, 1, 1e-12,
               "semi-axes along the rows of R and the eigenvalues of A^T A "
               "(A = S R: algebra): relative difference");

    r = au_add(c->rows, c->nr, "skew-max", "theta_x, theta_y move the maximum of D from n to R^T z (for ax, ay < 1)",
               SEED_WALTER, "section 1 after eq 3", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) skew_max_row(r, k, &c->sh[k], c->A[k]);

    r = au_add(c->rows, c->nr, "ndf-along-u",
               "D(m, u) = abc / (pi ||A u|| (m^T A^-1 A^-T m)^2) integrates to 1 against "
               "(m.u) over m.u > 0 for any u; D(m, v) = (||An|| / ||Av||) D(m)",
               SEED_BLOG1 ", " SEED_BLOG2,
               "blog Part 1 eq:NDF_norm and after eq:A_perp_expression; Part 2 'According to part 1'",
               AUDIT_SCOPE_DIAGONAL);
    au_kin_row(c, r, 0, err_d_u, NULL, 2, 1e-8,
               "with abc = 1 / |A|: the quadrature's |integral - 1| and the Part 2 "
               "ratio,");

    r = au_add(c->rows, c->nr, "sin-jacobian",
               "D(theta, phi) = D(m) |dm / d(theta, phi)| = D(m) sin theta, so the integral "
               "of D(m) cos theta sin theta d theta d phi is 1",
               SEED_BLOG1, "last equation", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) sin_row(r, k, &c->sh[k]);

    r = au_add(c->rows, c->nr, "ellipsoid-map",
               "m = A s / ||A s|| is the normal of the ellipsoid p^T A^T A p = 1 at p = "
               "A^-1 s",
               SEED_VNDF, "Use of the diagonal A matrix", AUDIT_SCOPE_DIAGONAL);
    au_kin_row(c, r, 0, err_ellipsoid_map, NULL, 200, 1e-12, "against normalize(A^T A p): distance");
}
