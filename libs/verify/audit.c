/* The seed audit: audit_run, the claims of the first 54 rows, and the writer. The later claims are in
 * libs/verify/audit_*.c by subject; their shared parts in libs/verify/audit_internal.h. SPDX-License-Identifier: MIT */
#include "audit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "audit_internal.h"
#include "ggx/ggx_samplers.h"

static double pdf_g1_form(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m) /* G1(v) D (m.v)+ / v.n, Walter's G1 */
{
    double mv = t_dot(m, v);
    return mv > 0 ? ggx_g1(s, v, m) * ggx_ndf(s, m) * mv / v.z : 0.0;
}

static ggx_vec3 literal_stretch(const double A[3][3], ggx_vec3 v, double u1, double u2) /* Engstad: normalize(A s) */
{
    (void)v;
    double r = sqrt(u1), ph = 2 * GGX_PI * u2;
    return t_normalize(t_matvec(A, t_vec(r * cos(ph), r * sin(ph), sqrt(1 - u1))));
}
/* Blog Part 2, eq theta_m_sample and phi_m_sample as written: tan theta = sqrt(u1 / (1 - u1))
 * sqrt(ax^2 cos^2 2 pi u2 + ay^2 sin^2 2 pi u2), phi = arctan((ay / ax) tan 2 pi u2), the principal value in
 * (-pi/2, pi/2), so m.x >= 0 for every u. The alphas are the norms of A's first two rows (A = S Rz). */
static ggx_vec3 literal_inversion(const double A[3][3], ggx_vec3 v, double u1, double u2)
{
    (void)v;
    double ax = hypot(A[0][0], hypot(A[0][1], A[0][2])), ay = hypot(A[1][0], hypot(A[1][1], A[1][2]));
    double t = 2 * GGX_PI * u2, c = cos(t), sn = sin(t);
    double th = atan(sqrt(u1 / (1 - u1)) * sqrt(ax * ax * c * c + ay * ay * sn * sn)), ph = atan(ay / ax * tan(t));
    return t_vec(sin(th) * cos(ph), sin(th) * sin(ph), cos(th));
}
ggx_vec3 verify_crescent_blog_s(const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    if (!(v.z > 0)) return t_vec(0, 0, 0);
    ggx_vec3 vs = t_normalize(t_matvec(s->a, v)), nt = t_normalize(t_matvec(s->ainv_t, t_vec(0, 0, 1)));
    double sc = 0.5 * (1.0 + t_dot(vs, nt)), l = hypot(vs.x, vs.y);
    ggx_vec3 e2 = l > 0 ? t_vec(vs.y / l, -vs.x / l, 0) : t_vec(0, 1, 0), e1 = t_cross(e2, vs);
    ggx_vec2 d = ggx_disk_concentric(u1, u2);
    double xb = sc * d.x + (1 - sc) * sqrt(fmax(0, 1 - d.y * d.y)), zb = sqrt(fmax(0, 1 - xb * xb - d.y * d.y));
    ggx_vec3 p = t_add(t_add(t_scale(e1, xb), t_scale(e2, d.y)), t_scale(vs, zb));
    if (p.z < 0) p.z = 0;
    return t_normalize(t_mattvec(s->a, p));
}


/* After a row's checks: a shape outside the seed's scope gets "not claimed", its evidence kept as what happens when
 * the claim is applied anyway. */
static void apply_scope(audit_row *r, const ggx_shape sh[AUDIT_SHAPES])
{
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        if (au_in_scope(r->scope, &sh[k]) || r->verdict[k] == AUDIT_NOT_CLAIMED) continue;
        char t[AUDIT_TEXT];
        snprintf(t, sizeof t, "%s", r->text[k]);
        au_set(r, k, AUDIT_NOT_CLAIMED, "applied anyway, it %s: %s", r->verdict[k] == AUDIT_FAILS ? "fails" : "holds",
               t);
    }
}

/* au_add into the table of ctx, which every group of rows below shares. */
static audit_row *add_row(const au_ctx *ctx, const char *id, const char *claim, const char *seed, const char *where,
                          audit_scope scope)
{
    return au_add(ctx->rows, ctx->nr, id, claim, seed, where, scope);
}

/* What the seeds claim of the library's samplers of normals, by registry id; the audit walks the registry and gives
 * a row to each sampler the seeds describe (the others are the library's own, checked by the sampling tests).
 * - literal: the seed's formula where it differs from the library's sampler; it is checked first and, where it
 *   fails, the library's sampler is checked as the form in which the claim holds (library says how);
 * - chi2_seed: the seed of the run for shape k is chi2_seed + 2k (+ 1 for the library's form after a literal);
 * - note_skewed: appended to the evidence for skewed shapes. */
typedef struct sampler_claim {
    const char *claim, *seed, *where;
    audit_scope scope;
    uint64_t chi2_seed;
    au_literal_fn literal;
    const char *library, *note_skewed;
} sampler_claim;

static const sampler_claim CLAIMS[GGX_SAMPLER_COUNT] = {
    [GGX_SAMPLER_STRETCH] = {"cosine hemisphere + elliptic stretch m = normalize(A s) has pdf D(m)(m.n)", SEED_STRETCH,
                             "Introduction; Analyzing the Normalizing Function", AUDIT_SCOPE_DIAGONAL, 81,
                             literal_stretch, "m = normalize(A^T c), c cosine-weighted about A n", NULL},
    [GGX_SAMPLER_ELLIPSE] = {"uniform point of the projected ellipse lifted to the ellipsoid has pdf D(m)(m.n)",
                             SEED_BLOG2, "Sampling the NDF (generalised Malley)", AUDIT_SCOPE_ANY, 84, NULL, NULL,
                             " (the silhouette ellipse of the general A, by its Schur complement)"},
    [GGX_SAMPLER_INVERSION] = {"closed-form theta_m, phi_m by inversion has pdf D(m)(m.n)", SEED_BLOG2,
                               "theta_m, phi_m sampling equations", AUDIT_SCOPE_DIAGONAL, 86, literal_inversion,
                               "phi = atan2(ay sin 2 pi u2, ax cos 2 pi u2) in the anisotropy's frame: the arctan as "
                               "written gives no m with m.x < 0",
                               NULL},
    [GGX_SAMPLER_CRESCENT] = {"crescent factor s = (1 + Av.An / (|Av| |An|)) / 2 gives the VNDF (version 3)",
                              SEED_WALTER, "eq 34-46", AUDIT_SCOPE_ANY, 88, NULL, NULL, NULL},
    [GGX_SAMPLER_HEITZ] =
        {"Heitz / Engstad five steps (frame, disk, squish by (1 + z)/2, lift, unstretch) give the VNDF", SEED_VNDF,
         "sections 1-3 (A diagonal, section 1.2)", AUDIT_SCOPE_DIAGONAL, 92, au_literal_heitz,
         "m = normalize(A'^T nh) in the canonical frame, A' n along n (Walter eq 46)", NULL},
};

/* The chi-square p-values of c's sampler at each view (the first view with the row's seed, so that its value is
 * the one-view audit's); returns the smallest, the evidence in text. */
static double chi2_views(au_actx *c, const ggx_vec3 *views, int nv, uint64_t seed, int progress, char *text, size_t nt)
{
    double pmin = 1;
    text[0] = 0;
    for (int j = 0; j < nv; j++) {
        c->keys.v = views[j];
        double p = au_chi2_p(c, seed + 1000 * (uint64_t)j, progress);
        pmin = fmin(pmin, p);
        size_t l = strlen(text);
        snprintf(text + l, nt - l,
                 nv == 1 ? "%.2g"
                 : j     ? ", %.2g at theta %.2f"
                         : "%.2g at theta %.2f",
                 p, acos(views[j].z));
    }
    return pmin;
}

/* One row per sampler of the family that the seeds describe, in the registry's order: its chi-square verdict for
 * each shape, at the view n for NDF samplers, for VNDF samplers at v and at a grazing view (86 degrees). A shape
 * outside the sampler's domain cannot be given to the formula at all. */
static void sampler_rows(const au_ctx *ctx, ggx_sampler_family family, ggx_vec3 v)
{
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *info = ggx_sampler_get((ggx_sampler_id)id);
        const sampler_claim *cl = &CLAIMS[id];
        if (info->family != family || !cl->claim || !info->sample) continue;
        audit_row *r = add_row(ctx, info->name, cl->claim, cl->seed, cl->where, cl->scope);
        const ggx_vec3 views[2] = {family == GGX_FAMILY_NDF ? t_vec(0, 0, 1) : v, t_dir(1.5, 2.0)};
        int nv = family == GGX_FAMILY_NDF ? 1 : 2;
        for (int k = 0; k < AUDIT_SHAPES; k++) {
            if (info->domain == GGX_DOMAIN_UNSKEWED && ctx->sh[k].kind == GGX_SHAPE_SKEWED) {
                au_set(r, k, AUDIT_NOT_CLAIMED, "cannot be applied (the formula has no skew parameters)");
                continue;
            }
            uint64_t seed = cl->chi2_seed + 2 * (uint64_t)k;
            au_actx c = {{&ctx->sh[k], views[0], info->pdf}, info->sample, cl->literal, ctx->A[k]};
            char ps[96], pl[96];
            double p_as_written = chi2_views(&c, views, nv, seed, ctx->progress, ps, sizeof ps);
            au_set(r, k, p_as_written >= au_alpha_level() ? AUDIT_HOLDS : AUDIT_FAILS, "chi-square p = %s", ps);
            if (cl->literal && r->verdict[k] == AUDIT_FAILS) {
                c.literal = NULL;
                double p = chi2_views(&c, views, nv, seed + 1, ctx->progress, pl, sizeof pl);
                if (p >= au_alpha_level() && au_in_scope(cl->scope, &ctx->sh[k]))
                    au_set(r, k, AUDIT_CORRECTED, "as written chi-square p = %s; holds as %s (p = %s)", ps, cl->library,
                           pl);
                else au_append(r, k, "; holds as %s (p = %s)", cl->library, pl);
            }
            if (cl->note_skewed && ctx->sh[k].kind == GGX_SHAPE_SKEWED) au_append(r, k, "%s", cl->note_skewed);
        }
    }
}

static double ndf_cos(ggx_vec3 m, void *ctx) { return ggx_ndf(ctx, m) * m.z; }

typedef struct vis_ctx {
    const ggx_shape *s;
    ggx_vec3 v;
    int use_g1;
} vis_ctx;
static double vis_f(ggx_vec3 m, void *vc)
{
    vis_ctx *c = vc;
    double mv = t_dot(m, c->v);
    if (mv <= 0) return 0.0;
    return (c->use_g1 ? ggx_g1(c->s, c->v, m) : 1.0) * ggx_ndf(c->s, m) * mv / c->v.z;
}


/* The integral of a VNDF built with the blog's G1 (vis_f without Walter's G1, times the blog's G1), and of
 * G1(v) D (m.v)+ / (v.n) with Walter's G1: both are 1 where the claim holds. */
static double blog_g1_integral(const ggx_shape *s, ggx_vec3 v)
{
    vis_ctx c = {s, v, 0};
    double vis = quad_hemisphere(s, vis_f, &c, &v, 1, 1e-11, NULL);
    ggx_vec3 av = t_matvec((const double(*)[3])s->a, v);
    return 2 * s->an_len * v.z / (sqrt(t_dot(av, av)) + s->an_len * v.z) * vis;
}
static double g1_form_integral(const ggx_shape *s, ggx_vec3 v)
{
    vis_ctx c = {s, v, 1};
    return quad_hemisphere(s, vis_f, &c, &v, 1, 1e-11, NULL);
}


/* A row checked by ray shooting for each shape: the worst |rays / formula - 1| over the directions, within 5 sigma. */
static void verdict_rays(audit_row *r, int k, const double A[3][3], const ggx_shape *s, int lune)
{
    static const double dirs[4][2] = {{0.0, 0.0}, {0.7, 0.4}, {1.2, -2.0}, {1.5, 2.6}};
    const ggx_vec3 v = t_dir(1.0, 1.1), n = t_vec(0, 0, 1);
    double worst = 0, worst_sig = 0;
    int ok = 1;
    for (int i = 0; i < 4; i++) {
        ggx_vec3 u = t_dir(dirs[i][0], dirs[i][1]), w = lune ? (i % 2 ? v : n) : u;
        double sig, got = au_ray_area(A, u, w, lune, 1000000, 301 + (uint64_t)i, &sig);
        double want = lune ? ggx_lune_area(s, u, w) : ggx_projected_area(s, u);
        ok &= fabs(got - want) <= 5 * sig;
        if (fabs(got / want - 1) > worst) worst = fabs(got / want - 1), worst_sig = sig / want;
    }
    au_set(r, k, ok ? AUDIT_HOLDS : AUDIT_FAILS,
           "10^6 rays at the ellipsoid from each of 4 directions%s: worst |rays / formula - 1| = "
           "%.1e (%s 5 sigma = %.1e)",
           lune ? " (lunes with v = n and v at 57 degrees)" : "", worst, ok ? "within" : "beyond", 5 * worst_sig);
}


/* The visible-normal pdf of engstad-vndf-proof as written, D(m) (m.v) G1(v) / (v.n) on {m.v > 0} with D's formula (no
 * indicator of m.n > 0), over the lower half: D's formula is even, so that part is the integral over the upper
 * hemisphere of D(m) (-m.v)+. */
typedef struct lower_ctx {
    double ax, ay;
    ggx_vec3 v;
} lower_ctx;
static double lower_f(ggx_vec3 m, void *vc)
{
    lower_ctx *c = vc;
    double mv = -t_dot(m, c->v);
    return mv > 0 ? au_ggx_formula(c->ax, c->ay, m) * mv : 0.0;
}
/* The mean normal int_{m.n > 0} D(m) m dm, one component at a time. */
typedef struct mean_ctx {
    const ggx_shape *s;
    int axis;
} mean_ctx;
static double mean_f(ggx_vec3 m, void *vc)
{
    mean_ctx *c = vc;
    /* shifted to stay positive (the quadrature's tolerance is relative): 1 + m_axis, or 1 for axis 3 */
    return ggx_ndf(c->s, m) * (1 + (c->axis == 0 ? m.x : c->axis == 1 ? m.y : c->axis == 2 ? m.z : 0.0));
}


/* The mean of m under the VNDF pdf for v, its polar angle (radians): how far the visible normals lean. */
typedef struct vmean_ctx {
    const ggx_shape *s;
    ggx_vec3 v;
    int axis;
} vmean_ctx;
static double vmean_f(ggx_vec3 m, void *vc)
{
    vmean_ctx *c = vc;
    return ggx_pdf_vndf(c->s, c->v, m) * (1 + (c->axis == 0 ? m.x : c->axis == 1 ? m.y : c->axis == 2 ? m.z : 0.0));
}
static double vndf_lean(const ggx_shape *s, ggx_vec3 v)
{
    double c[4];
    for (int a = 0; a < 4; a++) {
        vmean_ctx mc = {s, v, a};
        c[a] = quad_hemisphere(s, vmean_f, &mc, &v, 1, 1e-10, NULL);
    }
    ggx_vec3 mean = t_vec(c[0] - c[3], c[1] - c[3], c[2] - c[3]);
    return atan2(hypot(mean.x, mean.y), mean.z);
}

/* Maps whose Jacobians the seeds state. */
static ggx_vec3 map_slope(const void *ctx, double x, double y) /* slopes (x, y) -> normalize(x, y, 1) */
{
    (void)ctx;
    return t_normalize(t_vec(x, y, 1));
}
static ggx_vec3 map_squish(const void *ctx, double sx, double t) /* the crescent squish of the disk, factor *ctx */
{
    double z = *(const double *)ctx;
    return t_vec(sx, (1 - z) * sqrt(1 - sx * sx) + z * t, 0);
}
typedef struct stretch_ctx {
    const double (*A)[3];
    ggx_vec3 s, t1, t2; /* the direction s and its tangent frame */
} stretch_ctx;
static ggx_vec3 map_stretch(const void *ctx, double a,
                            double b) /* s -> m = normalize(A^T s), s moved in its tangent plane */
{
    const stretch_ctx *c = ctx;
    ggx_vec3 s = t_normalize(t_add(c->s, t_add(t_scale(c->t1, a), t_scale(c->t2, b))));
    return t_normalize(t_mattvec(c->A, s));
}
typedef struct reflect_ctx {
    ggx_vec3 psi, m, t1, t2;
} reflect_ctx;
static ggx_vec3 map_reflect(const void *ctx, double a, double b) /* m -> omega = 2 (psi.m) m - psi */
{
    const reflect_ctx *c = ctx;
    ggx_vec3 m = t_normalize(t_add(c->m, t_add(t_scale(c->t1, a), t_scale(c->t2, b))));
    return t_add(t_scale(m, 2 * t_dot(c->psi, m)), t_scale(c->psi, -1));
}

/* Walter eq 33 as written: (A_e(n) / A_l(psi, n)) X+(m.psi) D(m) |m.psi|, from the projected areas. */
typedef struct eq33_ctx {
    const ggx_shape *s;
    ggx_vec3 v;
} eq33_ctx;
static double eq33_f(ggx_vec3 m, void *vc)
{
    eq33_ctx *c = vc;
    double mv = t_dot(m, c->v);
    return mv > 0 ? ggx_projected_area(c->s, t_vec(0, 0, 1)) / ggx_lune_area(c->s, c->v, t_vec(0, 0, 1)) *
                        ggx_ndf(c->s, m) * mv
                  : 0.0;
}
static double eq33_integral(const ggx_shape *s, ggx_vec3 v)
{
    eq33_ctx c = {s, v};
    return quad_hemisphere(s, eq33_f, &c, &v, 1, 1e-11, NULL);
}
static ggx_vec3 map_normalize(const void *ctx, double a, double b) /* p(a, b) = p0 + a t1 + b t2 -> p / ||p|| */
{
    const ggx_vec3 *f = ctx; /* p0, t1, t2 */
    return t_normalize(t_add(f[0], t_add(t_scale(f[1], a), t_scale(f[2], b))));
}

/* ---- claims about every point of every shape of a kind, checked on the families of libs/verify/audit_util.c ---- */
static const ggx_vec3 N_UP = {0, 0, 1};
static double err_ggx(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    ggx_vec3 m = t_dir(acos(rng_uniform(g)), 2 * GGX_PI * rng_uniform(g));
    snprintf(at, nat, "m = (%.3g, %.3g, %.3g)", m.x, m.y, m.z);
    double ax, ay;
    au_kin_alphas(K, &ax, &ay);
    return fabs(ggx_ndf(&K->s, m) / au_ggx_formula(ax, ay, m) - 1);
}
static double err_p22(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    ggx_vec3 m = au_random_upper(g);
    double ax, ay;
    au_kin_alphas(K, &ax, &ay);
    double p = -m.x / m.z, q = -m.y / m.z, t = 1 + p * p / (ax * ax) + q * q / (ay * ay);
    double lit = 1 / (GGX_PI * ax * ay * t * t) / (m.z * m.z * m.z * m.z);
    snprintf(at, nat, "m = (%.3g, %.3g, %.3g)", m.x, m.y, m.z);
    return fabs(lit / ggx_ndf(&K->s, m) - 1);
}
static double err_unit_norms(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)g, (void)ctx;
    double Ait[3][3];
    au_inv_t((const double(*)[3])K->A, Ait);
    double a = au_norm_of((const double(*)[3])K->A, N_UP), b = au_norm_of((const double(*)[3])Ait, N_UP);
    snprintf(at, nat,
             "||An|| = %.6g, ||A^-T n|| = %.6g, product %.6g (>= 1 by Cauchy-Schwarz, 1 only where A^T A n is "
             "along n)",
             a, b, a * b);
    return fmax(fabs(a - 1), fabs(b - 1));
}
static double err_sm_su(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    double *largest = ctx;
    ggx_vec3 u = au_view_near_n(g);
    double x = au_norm_of((const double(*)[3])K->A, N_UP) * u.z / au_norm_of((const double(*)[3])K->A, u);
    if (!K->searching) *largest = fmax(*largest, x);
    snprintf(at, nat, "||An|| (v.n) / ||Av|| = %.4f at theta %.2f, phi %.2f rad", x, acos(u.z), atan2(u.y, u.x));
    return fmax(0, x - 1);
}
static double err_invariance(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    double cA[3][3], QA[3][3];
    ggx_vec3 q0 = t_normalize(t_vec(0.3, -0.5, 0.8)), q1, q2;
    t_frame(q0, &q1, &q2);
    q2 = t_scale(q2, -1); /* columns q0, q1, q2 of Q with det Q = -1: a reflection, the hard case */
    const double Q[3][3] = {{q0.x, q1.x, q2.x}, {q0.y, q1.y, q2.y}, {q0.z, q1.z, q2.z}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            cA[i][j] = 3.7 * K->A[i][j];
            QA[i][j] = 0;
            for (int l = 0; l < 3; l++) QA[i][j] += Q[i][l] * K->A[l][j];
        }
    ggx_shape sc, sq;
    if (ggx_shape_matrix(&sc, (const double(*)[3])cA) != GGX_OK ||
        ggx_shape_matrix(&sq, (const double(*)[3])QA) != GGX_OK)
        return NAN;
    ggx_vec3 m = au_random_upper(g);
    double d = ggx_ndf(&K->s, m);
    snprintf(at, nat, "m = (%.3g, %.3g, %.3g)", m.x, m.y, m.z);
    return fmax(fabs(ggx_ndf(&sc, m) / d - 1), fabs(ggx_ndf(&sq, m) / d - 1));
}
static double err_rotate_z(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    /* the shape's own S and rotation Rz = S^-1 A (A = S Rz): the alphas are the norms of A's first two rows */
    const double(*A)[3] = (const double(*)[3])K->A;
    double ax, ay;
    au_kin_alphas(K, &ax, &ay);
    ggx_shape S;
    ggx_shape_aniso(&S, ax, ay);
    ggx_vec3 m = au_random_upper(g), am = t_matvec(A, m), rm = t_vec(am.x / ax, am.y / ay, am.z);
    snprintf(at, nat, "m = (%.3g, %.3g, %.3g), theta_z = %.4g rad", m.x, m.y, m.z, atan2(-A[0][1], A[0][0]));
    return fabs(ggx_ndf(&S, rm) / ggx_ndf(&K->s, m) - 1);
}
static double err_min_inactive(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    double *largest = ctx;
    ggx_vec3 u = au_view_near_n(g);
    double x = ggx_projected_area(&K->s, N_UP) * u.z / ggx_lune_area(&K->s, u, N_UP);
    if (!K->searching) *largest = fmax(*largest, x);
    snprintf(at, nat, "A_e(n) |u.n| / A_l(u, n) = %.4f at theta %.2f, phi %.2f rad: the min clips G1 (footnote 4)", x,
             acos(u.z), atan2(u.y, u.x));
    return fmax(0, x - 1);
}
static double err_curvature(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    /* independently: the Gauss map's Jacobian by finite differences, K = d(solid angle) / d(area), with the normal
     * moved by unit-speed tangent steps and the surface point found from the normal */
    double Ait[3][3];
    au_inv_t((const double(*)[3])K->A, Ait);
    ggx_vec3 m = au_random_upper(g), t1, t2;
    t_frame(m, &t1, &t2);
    const double h = 1e-5;
    ggx_vec3 pa = t_add(
        au_point_of_normal((const double(*)[3])Ait, t_normalize(t_add(m, t_scale(t1, h)))),
        t_scale(au_point_of_normal((const double(*)[3])Ait, t_normalize(t_add(m, t_scale(t1, -h)))), -1));
    ggx_vec3 pb = t_add(
        au_point_of_normal((const double(*)[3])Ait, t_normalize(t_add(m, t_scale(t2, h)))),
        t_scale(au_point_of_normal((const double(*)[3])Ait, t_normalize(t_add(m, t_scale(t2, -h)))), -1));
    ggx_vec3 c = t_cross(pa, pb);
    double kfd = 4 * h * h / sqrt(t_dot(c, c)), q = au_norm_of((const double(*)[3])Ait, m);
    snprintf(at, nat, "m = (%.3g, %.3g, %.3g)", m.x, m.y, m.z);
    return fabs(K->s.det * K->s.det * q * q * q * q / kfd - 1);
}
static double err_cross(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    const double(*A)[3] = (const double(*)[3])K->A;
    double Ait[3][3];
    au_inv_t(A, Ait);
    ggx_vec3 a = au_random_upper(g), b = au_random_upper(g);
    ggx_vec3 l = t_cross(t_matvec(A, a), t_matvec(A, b)),
             rr = t_scale(t_matvec((const double(*)[3])Ait, t_cross(a, b)), K->s.det);
    ggx_vec3 d = t_add(l, t_scale(rr, -1));
    snprintf(at, nat, "a = (%.3g, %.3g, %.3g)", a.x, a.y, a.z);
    return sqrt(t_dot(d, d) / t_dot(l, l));
}
static double err_sphere_normal(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    const double(*A)[3] = (const double(*)[3])K->A;
    double Ait[3][3];
    au_inv_t(A, Ait);
    ggx_vec3 m = au_random_upper(g), vv = au_random_upper(g);
    ggx_vec3 mp = t_normalize(t_matvec((const double(*)[3])Ait, m));
    ggx_vec3 Ap = t_normalize(t_matvec(A, au_point_of_normal((const double(*)[3])Ait, m)));
    ggx_vec3 d = t_add(mp, t_scale(Ap, -1)), vp = t_normalize(t_matvec(A, vv));
    double lhs = t_dot(mp, vp), rhs = t_dot(m, vv) / (au_norm_of(A, vv) * au_norm_of((const double(*)[3])Ait, m));
    snprintf(at, nat, "m = (%.3g, %.3g, %.3g)", m.x, m.y, m.z);
    return fmax(sqrt(t_dot(d, d)), fabs(lhs - rhs));
}
static double err_sggx(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    double Ait[3][3];
    au_inv_t((const double(*)[3])K->A, Ait);
    ggx_vec3 m = au_random_upper(g), q = t_matvec((const double(*)[3])Ait, m); /* m^T S^-1 m = ||A^-T m||^2 */
    double qq = t_dot(q, q), d_sggx = 1 / (GGX_PI * K->s.det * qq * qq);
    snprintf(at, nat, "m = (%.3g, %.3g, %.3g)", m.x, m.y, m.z);
    return fabs(d_sggx / (au_norm_of((const double(*)[3])K->A, N_UP) * ggx_ndf(&K->s, m)) - 1);
}
static double err_det_sr(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)g, (void)ctx;
    /* S's entries are the norms of A's rows (R's rows are unit vectors) */
    double rn[3];
    for (int i = 0; i < 3; i++)
        rn[i] = sqrt(K->A[i][0] * K->A[i][0] + K->A[i][1] * K->A[i][1] + K->A[i][2] * K->A[i][2]);
    snprintf(at, nat, "|det A| = %.6g, ax ay = %.6g", K->s.det, rn[0] * rn[1] * rn[2]);
    return fabs(K->s.det / (rn[0] * rn[1] * rn[2]) - 1);
}
static double err_an_is_n(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)g, (void)ctx;
    ggx_vec3 an = t_matvec((const double(*)[3])K->A, N_UP), d = t_add(an, t_scale(N_UP, -1));
    snprintf(at, nat, "A n = (%.4g, %.4g, %.4g)", an.x, an.y, an.z);
    return sqrt(t_dot(d, d));
}

/* ---- the NDF, the ellipsoid's projected areas, G1 ---- */
static void rows_ndf_areas_g1(const au_ctx *ctx)
{
    audit_row *r;
    const ggx_vec3 v_clip = t_dir(1.2, 2.5); /* a view at which Walter's min is active */

    r = add_row(ctx, "norm", "D(m) is normalised: the integral of D(m)(m.n) is 1", SEED_WALTER ", " SEED_BLOG1,
                "Walter eq 1, 9; blog Part 1", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        /* the shape reaches ndf_cos through quad_hemisphere's void pointer; ndf_cos only reads it */
        double I = quad_hemisphere(&ctx->sh[k], ndf_cos, (void *)&ctx->sh[k], NULL, 0, 1e-11, NULL);
        au_set(r, k, fabs(I - 1) < 1e-9 ? AUDIT_HOLDS : AUDIT_FAILS, "|integral - 1| = %.1e", fabs(I - 1));
    }

    r = add_row(ctx, "ggx", "R = I gives anisotropic GGX 1 / (pi ax ay (mx^2/ax^2 + my^2/ay^2 + mz^2)^2)",
                SEED_WALTER ", " SEED_BLOG1, "Walter section 1; blog Part 1", AUDIT_SCOPE_DIAGONAL);
    au_kin_row(ctx, r, 1, err_ggx, NULL, 50, 1e-12,
               "the formula in x and y (for a rotated A, not in its rotated axes) "
               "against D: relative difference");

    r = add_row(ctx, "area", "projected area of the ellipsoid seen from u: pi ||Au|| / |A|",
                SEED_WALTER ", " SEED_BLOG1, "Walter eq 26; blog Part 1 eq A_perp_expression", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) verdict_rays(r, k, ctx->A[k], &ctx->sh[k], 0);

    r = add_row(ctx, "lune",
                "projected area of the lune m.u >= 0, m.v >= 0: pi (||Au|| ||Av|| + Au.Av) / (2 |A| ||Av||)",
                SEED_WALTER, "eq 28", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) verdict_rays(r, k, ctx->A[k], &ctx->sh[k], 1);

    r = add_row(ctx, "g1-blog", "G1 = 2 ||An|| (v.n) / (||Av|| + ||An|| (v.n)), a ratio of projected areas", SEED_BLOG2,
                "masking as a ratio of projected areas", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++)
        au_verdict_views(r, k, blog_g1_integral, &ctx->sh[k], 1e-6, "the VNDF built with it");

    r = add_row(ctx, "g1-walter", "G1 = min(1, 2 ||An||^2 |u.n| / (||Au|| ||An|| + Au.An)) X+(u.m) conserves energy",
                SEED_WALTER, "eq 6, 31-32", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        vis_ctx c = {&ctx->sh[k], v_clip, 1};
        double W = quad_hemisphere(&ctx->sh[k], vis_f, &c, &v_clip, 1, 1e-11, NULL);
        au_set(r, k, W <= 1 + 1e-9 ? AUDIT_HOLDS : AUDIT_FAILS, "weak furnace %.6f%s", W,
               W < 1 - 1e-6 ? " < 1: the min is active" : " = 1");
    }
}

/* The blog's Jacobian against finite differences of m' = normalize(A^-T m), then the pdf it leads to. */
static void jacobian_blog_row(audit_row *r, int k, const ggx_shape *s, ggx_vec3 v)
{
    rng g = {72};
    double worst_blog = 0, worst_true = 0;
    for (int i = 0; i < 200; i++) {
        ggx_vec3 m = t_dir(acos(0.2 + 0.8 * rng_uniform(&g)), 2 * GGX_PI * rng_uniform(&g)), t1, t2;
        t_frame(m, &t1, &t2);
        const double h = 1e-6;
        ggx_vec3 a = t_add(key_of_normal(s, t_normalize(t_add(m, t_scale(t1, h)))),
                           t_scale(key_of_normal(s, t_normalize(t_add(m, t_scale(t1, -h)))), -1));
        ggx_vec3 b = t_add(key_of_normal(s, t_normalize(t_add(m, t_scale(t2, h)))),
                           t_scale(key_of_normal(s, t_normalize(t_add(m, t_scale(t2, -h)))), -1));
        ggx_vec3 c = t_cross(a, b);
        double fd = sqrt(t_dot(c, c)) / (4 * h * h);
        ggx_vec3 q = t_matvec((const double(*)[3])s->ainv_t, m);
        double ql = sqrt(t_dot(q, q));
        worst_blog = fmax(worst_blog, fabs(s->det * ql / fd - 1));
        worst_true = fmax(worst_true, fabs(1.0 / (s->det * ql * ql * ql) / fd - 1));
    }
    /* The same derivation also writes D(m, v) = |A| D_s(m', v') / ||Av||, off by ||A^-T m||^4 where its
     * Jacobian is off by |A|^2 ||A^-T m||^4 the other way: its final p(m) = D(m, v) (m.v) / s, with its
     * D(m, v) = |A| / (pi ||Av|| ||A^-T m||^4) and Walter's s (A n; the blog's A^-T n is row crescent-blog), is
     * the VNDF pdf times the constant |A|^2 at every m: exact if that |A| is read as 1 / |A| (Walter eq 1). */
    double lo = INFINITY, hi = 0;
    ggx_vec3 av = t_matvec((const double(*)[3])s->a, v), an = t_matvec((const double(*)[3])s->a, N_UP);
    double avl = sqrt(t_dot(av, av)), sw = 0.5 * (1 + t_dot(av, an) / (avl * sqrt(t_dot(an, an))));
    for (int i = 0; i < 200; i++) {
        ggx_vec3 m = t_dir(acos(rng_uniform(&g)), 2 * GGX_PI * rng_uniform(&g)),
                 q = t_matvec((const double(*)[3])s->ainv_t, m);
        double mv = t_dot(m, v), ql = sqrt(t_dot(q, q));
        if (!(mv > 0)) continue;
        double p_blog = s->det / (GGX_PI * avl * ql * ql * ql * ql) * mv / sw;
        double x = p_blog / ggx_pdf_vndf(s, v, m) / (s->det * s->det);
        lo = fmin(lo, x), hi = fmax(hi, x);
    }
    au_set(r, k, worst_blog < 1e-6 ? AUDIT_HOLDS : AUDIT_FAILS,
           "off by up to %.0f %% (finite differences, 200 normals); 1 / (|A| ||A^-T m||^3) holds to %.0e. Its D(m, v) "
           "step errs by the inverse factor: the final p(m) = D(m,v)(m.v)/s is |A|^2 VNDF to %.0e",
           100 * worst_blog, worst_true, fmax(fabs(lo - 1), fabs(hi - 1)));
}

/* ---- the samplers of normals, the VNDF and the blog's derivation of it ---- */
static void rows_samplers(const au_ctx *ctx, ggx_vec3 v)
{
    audit_row *r;

    sampler_rows(ctx, GGX_FAMILY_NDF, v);

    r = add_row(ctx, "vndf-g1", "VNDF pdf = G1(v) D(m) (m.v)+ / (v.n)", SEED_BLOG2 ", " SEED_VNDF,
                "blog Part 2 (VNDF); Engstad's proof, final pdf", AUDIT_SCOPE_ANY);
    /* every view of the grid for each shape; where it holds also the caps sampler against it (chi-square) */
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        au_verdict_views(r, k, g1_form_integral, &ctx->sh[k], 1e-6, "with Walter's G1 it");
        if (r->verdict[k] != AUDIT_HOLDS) continue;
        double p = au_chi2_sampler(&ctx->sh[k], v, ggx_sample_vndf_caps, pdf_g1_form, 87 + 2 * (uint64_t)k,
                                   ctx->progress);
        if (p < au_alpha_level()) au_verdict_p(r, k, p);
        else au_append(r, k, "; the caps sampler against it: chi-square p = %.2g", p);
    }

    sampler_rows(ctx, GGX_FAMILY_VNDF, v);

    r = add_row(ctx, "crescent-blog", "crescent factor with A^-T n: s = (1 + Av.A^-T n / (|Av| |A^-T n|)) / 2",
                SEED_BLOG2, "VNDF sampling, the crescent's squish factor", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        au_verdict_p(
            r, k,
            au_chi2_sampler(&ctx->sh[k], v, verify_crescent_blog_s, ggx_pdf_vndf, 90 + 2 * (uint64_t)k, ctx->progress));
        if (ctx->sh[k].kind == GGX_SHAPE_SKEWED)
            au_append(r, k,
                      " in Walter's construction (truncation m.n >= 0); the blog's s belongs with its own truncation, "
                      "the ellipsoid cut by z = 0 in position space, where its pdf holds (row pm-blog)");
    }

    r = add_row(ctx, "jacobian-blog",
                "solid-angle Jacobian |d omega' / d omega| = |A| ||A^-T m|| for m' = normalize(A^-T m)", SEED_BLOG2,
                "VNDF pdf derivation", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) jacobian_blog_row(r, k, &ctx->sh[k], v);
}

/* ---- sampling the reflection: its weight, directions below the horizon, rejection ---- */
static void rows_reflection_sampling(const au_ctx *ctx, ggx_vec3 v)
{
    audit_row *r;

    r = add_row(ctx, "weight", "reflection weight G1 G1 F A_l(v,n) / (|v.n| A_e(n)) never exceeds 1", SEED_WALTER,
                "eq 49-52", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        rng g = {73};
        double wmax = 0, ratio_min = 2;
        ggx_fresnel one = {GGX_FRESNEL_ONE, 0, 0, 0};
        for (int i = 0; i < 200000; i++) {
            double c = rng_uniform(&g), ph = 2 * GGX_PI * rng_uniform(&g);
            ggx_vec3 wi = t_vec(sqrt(1 - c * c) * cos(ph), sqrt(1 - c * c) * sin(ph), c);
            ggx_sample smp = ggx_sample_brdf(&ctx->sh[k], &one, wi, rng_uniform(&g), rng_uniform(&g));
            if (smp.event == GGX_EVENT_INVALID) continue;
            wmax = fmax(wmax, smp.weight);
            ratio_min = fmin(ratio_min, smp.weight / ggx_g1(&ctx->sh[k], smp.w, ggx_half_reflect(wi, smp.w)));
        }
        audit_verdict vd = wmax <= 1 + 1e-12 ? AUDIT_HOLDS : AUDIT_FAILS;
        if (ratio_min > 1 - 1e-9)
            au_set(r, k, vd, "largest weight 1 %+.0e over 2e5 samples; weight = G1(wo) F to %.0e", wmax - 1,
                   fabs(1 - ratio_min));
        else
            au_set(r, k, vd, "largest weight 1 %+.0e over 2e5 samples; weight / G1(wo) F goes down to %.3f", wmax - 1,
                   ratio_min);
    }

    r = add_row(ctx, "below", "reflected directions can fall below the horizon, so w.n > 0 must be checked", SEED_VNDF,
                "the rejection check w.n > 0", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        rng g = {74};
        long below = 0, n_all = 200000;
        ggx_fresnel one = {GGX_FRESNEL_ONE, 0, 0, 0};
        ggx_vec3 wi = t_dir(80 * GGX_PI / 180, 0.3);
        for (long i = 0; i < n_all; i++)
            below += ggx_sample_brdf(&ctx->sh[k], &one, wi, rng_uniform(&g), rng_uniform(&g)).event ==
                     GGX_EVENT_INVALID;
        au_set(r, k, below > 0 ? AUDIT_HOLDS : AUDIT_FAILS,
               "%.1f %% of reflections below the horizon at an 80 degree view", 100.0 * (double)below / (double)n_all);
    }

    r = add_row(ctx, "rejection",
                "version 2 (ellipsoid as its own bound) rejects less than version 1 (bounding sphere)", SEED_WALTER,
                "section 4, versions 1 and 2", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        rng g = {75};
        unsigned t;
        double t1 = 0, t2 = 0;
        const int N = 100000;
        for (int i = 0; i < N; i++) {
            ggx_sample_vndf_walter_v1(&ctx->sh[k], v, au_uniform_cb, &g, &t);
            t1 += t;
            ggx_sample_vndf_walter_v2(&ctx->sh[k], v, au_uniform_cb, &g, &t);
            t2 += t;
        }
        double want2 = ggx_lune_area(&ctx->sh[k], v, N_UP) / ggx_projected_area(&ctx->sh[k], v), got2 = N / t2;
        int match = fabs(got2 - want2) < 5 * sqrt(want2 * (1 - want2) / N) + 1e-9;
        au_set(r, k, N / t1 <= got2 && match ? AUDIT_HOLDS : AUDIT_FAILS,
               "acceptance %.3f vs %.3f; v2 %s A_l(v,n)/A_e(v) = %.3f", N / t1, got2,
               match ? "matches" : "differs from", want2);
    }
}

static void rows_blog(const au_ctx *ctx)
{
    audit_row *r;

    /* ---- blog Part 1 ---- */
    r = add_row(ctx, "p22",
                "D(m) = P22(p, q) / cos^4 theta with P22 = 1 / (pi ax ay (1 + p^2/ax^2 + q^2/ay^2)^2), p, q the slopes",
                SEED_BLOG1, "eq (1) and eq:p_22", AUDIT_SCOPE_DIAGONAL);
    au_kin_row(ctx, r, 1, err_p22, NULL, 50, 1e-9,
               "the slopes along x and y (for a rotated A, not its rotated axes), "
               "against Walter eq 1: relative difference");

    /* ---- blog Part 2 ---- */
    r = add_row(ctx, "unit-norms", "with n = +z, ||An|| = ||A^-T n|| = 1 (the step from the blog's pdf to the G1 form)",
                SEED_BLOG2, "text before eq:g1-equality", AUDIT_SCOPE_ANY);
    au_kin_row(ctx, r, 0, err_unit_norms, NULL, 1, 1e-12, "| ||An|| - 1 | and | ||A^-T n|| - 1 |:");

    r = add_row(ctx, "sm-lt-su", "for any v not along n, S_m < S_u, i.e. ||An|| (v.n) < ||Av||", SEED_BLOG2,
                "text after eq:masked-projection", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double largest = 0;
        au_verdict_kin(r, k, &ctx->sh[k], ctx->A[k], err_sm_su, &largest, 2000, 1e-12,
                       "||An|| (v.n) / ||Av|| - 1 where positive:");
        au_append(r, k,
                  "; the largest ratio %.4f (Walter footnote 4: the microsurface's projected area can be below the "
                  "footprint's)",
                  largest);
    }

    r = add_row(ctx, "su",
                "S_u, the area that the visible upper half projects along v, = (A_perp(v) + A_perp(n) (v.n)) / 2",
                SEED_BLOG2, "eq:unmasked-projection", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        static const double dirs[3][2] = {{0.7, 0.4}, {1.2, -2.0}, {1.5, 2.6}};
        double worst = 0, worst_sig = 0;
        int ok = 1;
        for (int i = 0; i < 3; i++) {
            ggx_vec3 u = t_dir(dirs[i][0], dirs[i][1]);
            double sig, got = au_ray_area(ctx->A[k], u, N_UP, 1, 1000000, 311 + (uint64_t)i, &sig);
            double lit = 0.5 * (ggx_projected_area(&ctx->sh[k], u) + ggx_projected_area(&ctx->sh[k], N_UP) * u.z);
            ok &= fabs(got - lit) <= 5 * sig;
            if (fabs(lit / got - 1) > worst) worst = fabs(lit / got - 1), worst_sig = sig / got;
        }
        au_set(r, k, ok ? AUDIT_HOLDS : AUDIT_FAILS,
               "against 10^6 rays at the ellipsoid from each of 3 views: worst |formula / "
               "rays - 1| = %.1e (5 sigma = %.1e)%s",
               worst, 5 * worst_sig, ok ? "" : "; Walter eq 28's A_l(v, n) holds (row lune)");
    }
}

/* ---- Walter ---- */
static void rows_walter(const au_ctx *ctx)
{
    audit_row *r;

    r = add_row(ctx, "invariance", "D is unchanged by A -> c A and A -> Q A, Q orthogonal (with |A| read as |det A|)",
                SEED_WALTER, "section 1, after eq 1", AUDIT_SCOPE_ANY);
    au_kin_row(ctx, r, 0, err_invariance, NULL, 50, 1e-12, "the relative change of D (c = 3.7, Q a reflection):");

    r = add_row(ctx, "rotate-z", "theta_z rotates the distribution in the tangent plane: D_{S Rz}(m) = D_S(Rz m)",
                SEED_WALTER, "eq 3 and text", AUDIT_SCOPE_ROTATED);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double ax, ay;
        if (!au_diag_alphas(&ctx->sh[k], &ax, &ay)) {
            au_set(r, k, AUDIT_NOT_CLAIMED, "cannot be applied (a skewed A is not S Rz)");
            continue;
        }
        au_verdict_kin(r, k, &ctx->sh[k], ctx->A[k], err_rotate_z, NULL, 50, 1e-12, "relative difference");
    }

    r = add_row(ctx, "min-inactive",
                "for theta_x = theta_y = 0 the min in G1 never acts: A_e(n) |u.n| <= A_l(u, n) for all u", SEED_WALTER,
                "eq 31 and text", AUDIT_SCOPE_ROTATED);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double largest = 0;
        au_verdict_kin(r, k, &ctx->sh[k], ctx->A[k], err_min_inactive, &largest, 2000, 1e-12,
                       "A_e(n) |u.n| / A_l(u, n) - 1 where positive:");
        au_append(r, k, "; the largest ratio %.6f", largest);
    }

    r = add_row(ctx, "mean-normal", "the average microsurface normal, int_{m.n > 0} D(m) m dm, points along A^T A n",
                SEED_WALTER, "section 5.1", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double c[4];
        for (int a = 0; a < 4; a++) {
            mean_ctx mc = {&ctx->sh[k], a};
            c[a] = quad_hemisphere(&ctx->sh[k], mean_f, &mc, NULL, 0, 1e-11, NULL);
        }
        for (int a = 0; a < 3; a++) c[a] -= c[3];
        ggx_vec3 got = t_normalize(t_vec(c[0], c[1], c[2])),
                 want = t_normalize(t_mattvec(ctx->A[k], t_matvec(ctx->A[k], N_UP)));
        ggx_vec3 x = t_cross(got, want);
        double ang = atan2(sqrt(t_dot(x, x)), t_dot(got, want));
        au_set(r, k, ang < 1e-7 ? AUDIT_HOLDS : AUDIT_FAILS,
               "angle between the quadrature's mean normal and A^T A n %.1e rad; "
               "the mean normal leans %.4g degrees from n",
               ang, acos(fmin(1.0, got.z)) * 180 / GGX_PI);
    }

    r = add_row(ctx, "reciprocity", "the BRDF (eq 4 with G of eq 5, 6) is reciprocal: f_r(i, o) = f_r(o, i)",
                SEED_WALTER, "section 1.1", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        rng g = {81};
        double worst = 0;
        ggx_fresnel fr;
        ggx_fresnel_dielectric(&fr, 1.5);
        for (int i = 0; i < 10000; i++) {
            ggx_vec3 wi = au_random_upper(&g), wo = au_random_upper(&g);
            double a = ggx_brdf_eval(&ctx->sh[k], &fr, wi, wo), b = ggx_brdf_eval(&ctx->sh[k], &fr, wo, wi);
            if (a > 0 || b > 0) worst = fmax(worst, fabs(a - b) / fmax(a, b));
        }
        au_set(r, k, worst < 1e-12 ? AUDIT_HOLDS : AUDIT_FAILS,
               "largest relative difference over 10^4 pairs %.1e (dielectric "
               "Fresnel 1.5)",
               worst);
    }

    r = add_row(ctx, "energy", "with G of eq 5, 6 the BRDF conserves energy: the albedo (F = 1) is at most 1",
                SEED_WALTER, "section 1.1", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double emax = 0, at = 0, lo = 1;
        for (int i = 0; i < 12; i++) {
            ggx_vec3 u = t_dir(0.1 + 1.45 * i / 11.0, 0.9 * i);
            double e = ggx_albedo(&ctx->sh[k], u);
            if (e > emax) emax = e, at = acos(u.z);
            lo = fmin(lo, e);
        }
        au_set(r, k, emax <= 1 + 1e-6 ? AUDIT_HOLDS : AUDIT_FAILS,
               "albedo from %.4f to %.4f over 12 views (largest at theta %.2f "
               "rad)",
               lo, emax, at);
    }
}

static void rows_engstad(const au_ctx *ctx)
{
    audit_row *r;

    /* ---- Engstad, Elliptic Stretch ---- */
    r = add_row(ctx, "stretch-omega", "cosine-weighting toward omega, then stretching: p(m) = |m.omega| D(m) / ||m_||",
                SEED_STRETCH, "GGX composition (end)", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double ax, ay;
        if (!au_alphas_or_skip(r, k, &ctx->sh[k], &ax, &ay)) continue;
        /* at omega = n the composition is the plain stretch, whose pdf is D(m) (m.n) (row stretch); ||m_|| =
         * 1 / ||S^-1 m|| and the pre-stretch s = S^-1 m / ||S^-1 m|| */
        rng g = {82};
        double worst_lit = 0, worst_fix = 0;
        for (int i = 0; i < 1000; i++) {
            ggx_vec3 m = au_random_upper(&g);
            double sinv = sqrt(m.x * m.x / (ax * ax) + m.y * m.y / (ay * ay) + m.z * m.z),
                   d = au_ggx_formula(ax, ay, m);
            double lit = m.z * d * sinv, fix = (m.z / sinv) * d * sinv, want = ggx_pdf_ndf(&ctx->sh[k], m);
            worst_lit = fmax(worst_lit, fabs(lit / want - 1)), worst_fix = fmax(worst_fix, fabs(fix / want - 1));
        }
        if (worst_lit < 1e-9)
            au_set(r, k, AUDIT_HOLDS, "at omega = n: largest relative difference from D(m) (m.n) %.1e", worst_lit);
        else
            au_set(r, k, worst_fix < 1e-9 ? AUDIT_CORRECTED : AUDIT_FAILS,
                   "at omega = n it is off D(m) (m.n) by up to %.0f %%; "
                   "with the cosine of the pre-stretch direction, p(m) = |s.omega| D(m) / ||m_||, by %.0e",
                   100 * worst_lit, worst_fix);
    }

    /* ---- Engstad, visible GGX ---- */
    r = add_row(ctx, "disk-concentric",
                "the concentric map as written (polar(a, pi b / 4a) if |a| > |b|, polar(b, pi a / 4b) "
                "if |a| < |b|, else (a, b)) is uniform on the disk, Jacobian pi",
                SEED_VNDF, "step 2, sample a disk", AUDIT_SCOPE_ANY);
    {
        rng g = {83};
        long N = 200000, top_lit = 0, top_fix = 0, off = 0;
        for (long i = 0; i < N; i++) {
            double a = 2 * rng_uniform(&g) - 1, b = 2 * rng_uniform(&g) - 1, sx, sy, fx, fy;
            if (fabs(a) > fabs(b)) sx = fx = a * cos(GGX_PI * b / (4 * a)), sy = fy = a * sin(GGX_PI * b / (4 * a));
            else if (fabs(a) < fabs(b)) {
                sx = b * cos(GGX_PI * a / (4 * b)), sy = b * sin(GGX_PI * a / (4 * b));
                fx = b * cos(GGX_PI / 2 - GGX_PI * a / (4 * b)), fy = b * sin(GGX_PI / 2 - GGX_PI * a / (4 * b));
            } else sx = fx = a, sy = fy = b;
            top_lit += fabs(sy) > fabs(sx), top_fix += fabs(fy) > fabs(fx);
            off += sx * sx + sy * sy > 1 + 1e-12;
        }
        /* (a, b) with |a| = |b| != 0 lies off the disk: a set of measure zero, hit here only if the sampler hits it */
        double f_lit = (double)top_lit / (double)N, f_fix = (double)top_fix / (double)N, sig = sqrt(0.25 / (double)N);
        for (int k = 0; k < AUDIT_SHAPES; k++)
            au_set(r, k, fabs(f_fix - 0.5) < 5 * sig ? AUDIT_CORRECTED : AUDIT_FAILS,
                   "as written no point reaches the top and "
                   "bottom quarters |t| > |s| (fraction %.4f of 2e5, uniform: 0.5; %ld off the disk); with the second "
                   "branch "
                   "polar(b, pi/2 - pi a / 4b) the fraction is %.4f",
                   f_lit, off, f_fix);
    }

    r = add_row(ctx, "vndf-support",
                "p_vGGX(m) = D(m) (m.v) G1(v) / (v.n) on {m.v > 0} integrates to 1 (D as written, with "
                "no m.n > 0)",
                SEED_VNDF, "vGGX Sampling", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double ax, ay;
        if (!au_diag_alphas(&ctx->sh[k], &ax, &ay) || ctx->sh[k].kind != GGX_SHAPE_DIAGONAL) {
            au_set(r, k, AUDIT_NOT_CLAIMED, "cannot be applied (the seed's D is written for a diagonal A)");
            continue;
        }
        ggx_vec3 vv = t_dir(75 * GGX_PI / 180, 0);
        lower_ctx lc = {ax, ay, vv};
        ggx_vec3 cut = t_scale(vv, -1);
        double lower = quad_hemisphere(&ctx->sh[k], lower_f, &lc, &cut, 1, 1e-10, NULL) *
                       ggx_g1(&ctx->sh[k], vv, N_UP) / vv.z;
        double upper = g1_form_integral(&ctx->sh[k], vv);
        au_set(r, k, fabs(1 + lower - 1) < 1e-6 ? AUDIT_HOLDS : AUDIT_CORRECTED,
               "at theta_v = 75 degrees it integrates to %.4f; "
               "holds with m.n > 0 in the support (%.6f)",
               upper + lower, upper);
    }

    r = add_row(ctx, "lambda-zz",
                "Lambda(v) = -1/2 + sqrt((ax^2 vx^2 + ay^2 vy^2) / vz^2 + 1) / 2 and G1 = 2 z_z / (1 + z_z), "
                "z_z = v.n / ||Av||",
                SEED_VNDF, "vGGX Sampling; Solving for z_z", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double ax, ay;
        if (!au_alphas_or_skip(r, k, &ctx->sh[k], &ax, &ay)) continue;
        rng g = {84};
        double wl = 0, wz = 0;
        for (int i = 0; i < 1000; i++) {
            ggx_vec3 u = au_random_upper(&g);
            double lam = -0.5 + 0.5 * sqrt((ax * ax * u.x * u.x + ay * ay * u.y * u.y) / (u.z * u.z) + 1);
            double zz = u.z / au_norm_of(ctx->A[k], u), g1 = ggx_g1(&ctx->sh[k], u, N_UP);
            wl = fmax(wl, fabs(1 / (1 + lam) / g1 - 1)), wz = fmax(wz, fabs(2 * zz / (1 + zz) / g1 - 1));
        }
        au_set(r, k, fmax(wl, wz) < 1e-9 ? AUDIT_HOLDS : AUDIT_FAILS,
               "largest relative difference from Walter's G1: the Lambda form "
               "%.1e, the z_z form %.1e, over 1000 views",
               wl, wz);
    }
}

static void dof_row(audit_row *r, int k, const ggx_shape *s, const double A[3][3])
{
    /* the rank of the Jacobian of (D(m_1), ..., D(m_40)) with respect to A's 9 entries, by central differences:
     * the eigenvalues of J^T J, counted above 1e-8 of the largest */
    enum { NM = 40 };
    double J[NM][9], JTJ[9][9], ev[9];
    rng g = {86};
    ggx_vec3 ms[NM];
    for (int i = 0; i < NM; i++) ms[i] = au_random_upper(&g);
    int bad = 0;
    for (int e = 0; e < 9; e++) {
        double Ap[3][3], Am[3][3], h = 1e-6;
        memcpy(Ap, A, sizeof Ap), memcpy(Am, A, sizeof Am);
        Ap[e / 3][e % 3] += h, Am[e / 3][e % 3] -= h;
        ggx_shape sp, sm;
        bad |= ggx_shape_matrix(&sp, (const double(*)[3])Ap) != GGX_OK ||
               ggx_shape_matrix(&sm, (const double(*)[3])Am) != GGX_OK;
        for (int i = 0; i < NM && !bad; i++)
            J[i][e] = (ggx_ndf(&sp, ms[i]) - ggx_ndf(&sm, ms[i])) / (2 * h) / ggx_ndf(s, ms[i]);
    }
    if (bad) {
        au_set(r, k, AUDIT_FAILS, "a perturbed A was refused");
        return;
    }
    for (int a = 0; a < 9; a++)
        for (int b = 0; b < 9; b++) {
            JTJ[a][b] = 0;
            for (int i = 0; i < NM; i++) JTJ[a][b] += J[i][a] * J[i][b];
        }
    au_sym_eigenvalues(9, JTJ, ev);
    double top = 0;
    for (int i = 0; i < 9; i++) top = fmax(top, ev[i]);
    int rank = 0;
    double gap_lo = INFINITY, gap_hi = 0; /* the smallest kept and the largest dropped eigenvalue */
    for (int i = 0; i < 9; i++) {
        if (ev[i] > 1e-8 * top) rank++, gap_lo = fmin(gap_lo, ev[i] / top);
        else gap_hi = fmax(gap_hi, ev[i] / top);
    }
    au_set(r, k, rank == 5 ? AUDIT_HOLDS : AUDIT_FAILS,
           "rank of d D(m_i) / d A over 40 normals: %d (eigenvalues of J^T J: "
           "smallest kept %.1e, largest dropped %.1e of the largest)",
           rank, gap_lo, gap_hi);
}

/* ---- the ellipsoid's curvature, the degrees of freedom of A, the lean of the visible normals ---- */
static void rows_curvature_dof_lean(const au_ctx *ctx)
{
    audit_row *r;

    r = add_row(ctx, "curvature",
                "Gaussian curvature of the ellipsoid at the point with normal m: K(m) = |A|^2 ||A^-T m||^4",
                SEED_WALTER ", " SEED_BLOG1, "Walter eq 20; blog Part 1 eq:k_g", AUDIT_SCOPE_ANY);
    au_kin_row(ctx, r, 0, err_curvature, NULL, 20, 1e-6,
               "against the Gauss map's finite-difference Jacobian: "
               "relative difference");

    r = add_row(ctx, "dof", "of the 9 entries of A only 5 are useful degrees of freedom (3 of rotation, 2 of scale)",
                SEED_WALTER, "section 1", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) dof_row(r, k, &ctx->sh[k], ctx->A[k]);

    r = add_row(ctx, "vndf-phi90",
                "at theta_v = 75 degrees the VNDF leans toward the view more for phi_v = 90 than for phi_v = "
                "0, since ay > ax (figures 1-8)",
                SEED_VNDF, "figures, alpha (0.15, 0.5)", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double l0 = vndf_lean(&ctx->sh[k], t_dir(75 * GGX_PI / 180, 0)),
               l90 = vndf_lean(&ctx->sh[k], t_dir(75 * GGX_PI / 180, GGX_PI / 2));
        double ax = hypot(ctx->A[k][0][0], hypot(ctx->A[k][0][1], ctx->A[k][0][2])),
               ay = hypot(ctx->A[k][1][0], hypot(ctx->A[k][1][1], ctx->A[k][1][2]));
        int want = ay > ax;
        au_set(r, k, (l90 > l0) == want ? AUDIT_HOLDS : AUDIT_FAILS,
               "mean visible normal %.2f degrees from n for phi_v = 0, %.2f "
               "for phi_v = 90 (n leans %.2f degrees without a view)",
               l0 * 180 / GGX_PI, l90 * 180 / GGX_PI,
               acos(fmin(1.0, t_normalize(t_mattvec(ctx->A[k], t_matvec(ctx->A[k], N_UP))).z)) * 180 / GGX_PI);
    }
}

/* ---- Jacobians the seeds state, by finite differences of the maps themselves ---- */
static void rows_map_jacobians(const au_ctx *ctx)
{
    audit_row *r;

    r = add_row(ctx, "cosine-jacobian",
                "the cosine-weighted map s(u, v) has |ds / d(u, v)| = pi / s_z, so p(s) = (s.n) / pi", SEED_STRETCH,
                "Cosine-Weighted Half-Sphere", AUDIT_SCOPE_ANY);
    {
        rng g = {87};
        double worst = 0;
        for (int i = 0; i < 1000; i++) {
            double u = 0.01 + 0.98 * rng_uniform(&g), w = rng_uniform(&g);
            worst = fmax(worst, fabs(au_fd_jacobian(au_map_cosine, NULL, u, w, 1e-6) / (GGX_PI / sqrt(1 - u)) - 1));
        }
        for (int k = 0; k < AUDIT_SHAPES; k++)
            au_set(r, k, worst < 1e-6 ? AUDIT_HOLDS : AUDIT_FAILS,
                   "largest relative difference from the finite-difference "
                   "Jacobian %.1e over 1000 points (the map does not depend on A)",
                   worst);
    }

    r = add_row(ctx, "slope-jacobian", "the slope map m = normalize(x, y, 1) has |dm / d(x, y)| = m_z^3", SEED_STRETCH,
                "Relation to slope-space", AUDIT_SCOPE_ANY);
    {
        rng g = {88};
        double worst = 0;
        for (int i = 0; i < 1000; i++) {
            double x = 6 * rng_uniform(&g) - 3, y = 6 * rng_uniform(&g) - 3;
            ggx_vec3 m = map_slope(NULL, x, y);
            worst = fmax(worst, fabs(au_fd_jacobian(map_slope, NULL, x, y, 1e-6) / (m.z * m.z * m.z) - 1));
        }
        for (int k = 0; k < AUDIT_SHAPES; k++)
            au_set(r, k, worst < 1e-6 ? AUDIT_HOLDS : AUDIT_FAILS,
                   "largest relative difference from the finite-difference "
                   "Jacobian %.1e over 1000 slopes in [-3, 3]^2 (the map does not depend on A)",
                   worst);
    }

    r = add_row(ctx, "squish-jacobian", "the crescent squish (s, t) -> (s, (1 - z) sqrt(1 - s^2) + z t) has Jacobian z",
                SEED_VNDF ", " SEED_BLOG2 ", " SEED_WALTER, "the VNDF proof, step 3; blog Part 2; Walter eq 38-41",
                AUDIT_SCOPE_ANY);
    {
        rng g = {89};
        double worst = 0;
        for (int i = 0; i < 1000; i++) {
            double z = 0.5 + 0.5 * rng_uniform(&g), sx = 1.8 * rng_uniform(&g) - 0.9, t = 1.8 * rng_uniform(&g) - 0.9;
            worst = fmax(worst, fabs(au_fd_jacobian(map_squish, &z, sx, t, 1e-6) / z - 1));
        }
        for (int k = 0; k < AUDIT_SHAPES; k++)
            au_set(r, k, worst < 1e-6 ? AUDIT_HOLDS : AUDIT_FAILS,
                   "largest relative difference from the finite-difference "
                   "Jacobian %.1e over 1000 points, z in [1/2, 1]",
                   worst);
    }

    r = add_row(ctx, "stretch-jacobian",
                "the elliptic stretch m = normalize(A s) has solid-angle Jacobian |dm / ds| = ax ay "
                "||A^-1 m||^3",
                SEED_STRETCH ", " SEED_VNDF, "GGX composition; the VNDF proof, Elliptic Stretch", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double ax, ay;
        if (!au_alphas_or_skip(r, k, &ctx->sh[k], &ax, &ay)) continue;
        /* the map of the shape itself, m = normalize(A^T s) (A^T = A for a diagonal A), against the literal form
         * in x, y and against |A| ||A^-T m||^3 (the form for any A) */
        double Ait[3][3];
        au_inv_t(ctx->A[k], Ait);
        rng g = {90};
        double worst_lit = 0, worst_gen = 0;
        for (int i = 0; i < 1000; i++) {
            stretch_ctx c = {ctx->A[k], au_random_upper(&g), {0, 0, 0}, {0, 0, 0}};
            t_frame(c.s, &c.t1, &c.t2);
            double J = au_fd_jacobian(map_stretch, &c, 0, 0, 1e-6);
            ggx_vec3 m = map_stretch(&c, 0, 0);
            double qd = sqrt(m.x * m.x / (ax * ax) + m.y * m.y / (ay * ay) + m.z * m.z),
                   q = au_norm_of((const double(*)[3])Ait, m);
            worst_lit = fmax(worst_lit, fabs(ax * ay * qd * qd * qd / J - 1));
            worst_gen = fmax(worst_gen, fabs(ctx->sh[k].det * q * q * q / J - 1));
        }
        au_set(r, k, worst_lit < 1e-6 ? AUDIT_HOLDS : AUDIT_FAILS,
               "largest relative difference from the finite-difference Jacobian "
               "%.1e over 1000 directions (for any A, |A| ||A^-T m||^3 with m = normalize(A^T s): %.1e)",
               worst_lit, worst_gen);
    }

    r = add_row(ctx, "reflect-jacobian", "the reflection omega = 2 (psi.m) m - psi has |d omega / dm| = 4 |psi.m|",
                SEED_WALTER, "eq 47-48", AUDIT_SCOPE_ANY);
    {
        rng g = {91};
        double worst = 0;
        for (int i = 0; i < 1000; i++) {
            reflect_ctx c = {au_random_upper(&g), au_random_upper(&g), {0, 0, 0}, {0, 0, 0}};
            if (t_dot(c.psi, c.m) < 0.05) continue;
            t_frame(c.m, &c.t1, &c.t2);
            worst = fmax(worst, fabs(au_fd_jacobian(map_reflect, &c, 0, 0, 1e-6) / (4 * t_dot(c.psi, c.m)) - 1));
        }
        for (int k = 0; k < AUDIT_SHAPES; k++)
            au_set(r, k, worst < 1e-6 ? AUDIT_HOLDS : AUDIT_FAILS,
                   "largest relative difference from the finite-difference "
                   "Jacobian %.1e over 1000 pairs (the map does not depend on A)",
                   worst);
    }
}

/* ---- identities at random points, on the matrix given ---- */
static void rows_identities(const au_ctx *ctx)
{
    audit_row *r;

    r = add_row(ctx, "cross-product", "(M a) x (M b) = |M| M^-T (a x b) for a non-singular M", SEED_WALTER, "eq 25",
                AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        au_verdict_kin(r, k, &ctx->sh[k], ctx->A[k], err_cross, NULL, 50, 1e-12, "with M = A: relative difference");
        au_append(r, k, " (det A > 0 here: with det < 0 the right side flips sign)");
    }

    r = add_row(ctx, "sphere-normal",
                "m' = A^-T m / ||A^-T m|| is the sphere's normal at A p, p the ellipsoid point with normal m; "
                "m'.v' = (m.v) / (||Av|| ||A^-T m||)",
                SEED_BLOG2, "eq:m-to-m-prime, eq:mv-sphere-to-ellipsoid", AUDIT_SCOPE_ANY);
    au_kin_row(ctx, r, 0, err_sphere_normal, NULL, 50, 1e-12, "difference");

    r = add_row(ctx, "half-cut",
                "the half of the ellipsoid with m.n > 0 is the half cut by the plane through its centre "
                "perpendicular to A^T A n",
                SEED_WALTER, "sections 2.3, 5.1", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double Ait[3][3];
        au_inv_t(ctx->A[k], Ait);
        rng g = {94};
        long disagree = 0;
        ggx_vec3 ata = t_mattvec(ctx->A[k], t_matvec(ctx->A[k], N_UP));
        for (int i = 0; i < 100000; i++) {
            ggx_vec3 sp = t_dir(acos(2 * rng_uniform(&g) - 1), 2 * GGX_PI * rng_uniform(&g));
            ggx_vec3 p = t_mattvec((const double(*)[3])Ait, sp); /* A^-1 s: a point of the ellipsoid */
            ggx_vec3 m = t_normalize(t_mattvec(ctx->A[k], t_matvec(ctx->A[k], p)));
            disagree += (m.z > 0) != (t_dot(ata, p) > 0);
        }
        au_set(r, k, disagree == 0 ? AUDIT_HOLDS : AUDIT_FAILS, "%ld of 10^5 random surface points on the wrong side",
               disagree);
    }

    r = add_row(ctx, "g1-pdf-identity",
                "(1/s) ||An|| / ||Av|| = 2 ||An|| ||A^-T n|| / (||Av|| ||A^-T n|| + v.n), with the blog's "
                "s and (Av).(A^-T n) = v.n",
                SEED_BLOG2, "eq:g1-pdf", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double Ait[3][3];
        au_inv_t(ctx->A[k], Ait);
        rng g = {95};
        double worst = 0;
        for (int i = 0; i < 1000; i++) {
            ggx_vec3 vv = au_random_upper(&g), av = t_matvec(ctx->A[k], vv),
                     an_t = t_matvec((const double(*)[3])Ait, N_UP);
            double avl = sqrt(t_dot(av, av)), atl = sqrt(t_dot(an_t, an_t)), anl = au_norm_of(ctx->A[k], N_UP);
            double sb = 0.5 * (1 + t_dot(av, an_t) / (avl * atl));
            double lhs = anl / avl / sb, rhs = 2 * anl * atl / (avl * atl + vv.z);
            worst = fmax(worst, fabs(lhs / rhs - 1));
        }
        au_set(r, k, worst < 1e-12 ? AUDIT_HOLDS : AUDIT_FAILS,
               "largest relative difference %.1e over 1000 views (an identity for "
               "every A; the next step needs ||An|| ||A^-T n|| = 1, row unit-norms)",
               worst);
    }

    r = add_row(ctx, "vndf-frame",
                "z = Av / ||Av||, x = (-z_y, z_x, 0) / ||.||, y = z x x is orthonormal with y.n >= 0", SEED_VNDF,
                "step 1, make a frame", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        rng g = {96};
        double worst = 0, ymin = 1;
        for (int i = 0; i < 1000; i++) {
            ggx_vec3 z = t_normalize(t_matvec(ctx->A[k], au_random_upper(&g))), x = t_normalize(t_vec(-z.y, z.x, 0)),
                     y = t_cross(z, x);
            worst = fmax(worst, fmax(fabs(t_dot(x, z)), fmax(fabs(t_dot(y, y) - 1), fabs(t_dot(x, y)))));
            ymin = fmin(ymin, y.z);
        }
        au_set(r, k, worst < 1e-12 && ymin >= 0 ? AUDIT_HOLDS : AUDIT_FAILS,
               "orthonormal to %.0e over 1000 views; smallest y.n "
               "%.3f",
               fmax(worst, 1e-17), ymin);
    }
}

/* ---- Walter's forms: eq 33, SGGX, the Hessian ---- */
static void rows_walter_forms(const au_ctx *ctx)
{
    audit_row *r;

    r = add_row(ctx, "vndf-eq33", "p_h(m) = (A_e(n) / A_l(psi, n)) X+(m.psi) D(m) |m.psi| integrates to 1 over m",
                SEED_WALTER, "eq 33 (as fixed in May 2016)", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) au_verdict_views(r, k, eq33_integral, &ctx->sh[k], 1e-6, "it");

    r = add_row(ctx, "sggx",
                "the ellipsoid NDF is SGGX with S = A^T A: D_SGGX(m) = 1 / (pi sqrt|S| (m^T S^-1 m)^2) = ||An|| D(m)",
                SEED_WALTER, "section 5.2", AUDIT_SCOPE_ANY);
    au_kin_row(ctx, r, 0, err_sggx, NULL, 50, 1e-12, "relative difference");

    r = add_row(ctx, "hessian", "with H = 2 A^T A: |H| = 8 |A|^2, adj(H) = |H| H^-1 and m^T H^-1 m = ||A^-T m||^2 / 2",
                SEED_WALTER, "eq 11-19", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double H[3][3], Hinv_t[3][3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                H[i][j] = 0;
                for (int l = 0; l < 3; l++) H[i][j] += 2 * ctx->A[k][l][i] * ctx->A[k][l][j];
            }
        au_inv_t((const double(*)[3])H, Hinv_t); /* H symmetric: H^-T = H^-1 */
        double detH = H[0][0] * (H[1][1] * H[2][2] - H[1][2] * H[2][1]) -
                      H[0][1] * (H[1][0] * H[2][2] - H[1][2] * H[2][0]) +
                      H[0][2] * (H[1][0] * H[2][1] - H[1][1] * H[2][0]);
        double worst = fabs(detH / (8 * ctx->sh[k].det * ctx->sh[k].det) - 1);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) { /* the adjugate by cofactors against |H| H^-1 */
                int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
                double adj = H[i1][j1] * H[i2][j2] - H[i1][j2] * H[i2][j1];
                worst = fmax(worst, fabs(adj - detH * Hinv_t[i][j]) / fabs(detH) * 1e0);
            }
        double Ait[3][3];
        au_inv_t(ctx->A[k], Ait);
        rng g = {98};
        for (int i = 0; i < 1000; i++) {
            ggx_vec3 m = au_random_upper(&g), hm = t_matvec((const double(*)[3])Hinv_t, m),
                     q = t_matvec((const double(*)[3])Ait, m);
            worst = fmax(worst, fabs(t_dot(m, hm) / (0.5 * t_dot(q, q)) - 1));
        }
        au_set(r, k, worst < 1e-10 ? AUDIT_HOLDS : AUDIT_FAILS,
               "largest relative difference %.1e (|H|, the adjugate, 1000 normals)", worst);
    }
}

/* ---- the stretch's forms: the normalization, its inverse, the equal-area grid ---- */
static void rows_stretch_forms(const au_ctx *ctx)
{
    audit_row *r;

    r = add_row(ctx, "normalize-derivative",
                "d(p / ||p||) = p x (dp x p) / ||p||^3, and the normalizing Jacobian |d p^ / d(u, v)| "
                "= |p.(p_u x p_v)| / ||p||^3",
                SEED_STRETCH, "Differentiation; the Normalizing Jacobian formula", AUDIT_SCOPE_ANY);
    {
        rng g = {99};
        double worst = 0;
        for (int i = 0; i < 1000; i++) {
            ggx_vec3 f[3] = {t_scale(au_random_upper(&g), 0.5 + 2 * rng_uniform(&g)), au_random_upper(&g),
                             au_random_upper(&g)};
            f[1] = t_scale(f[1], 2 * rng_uniform(&g) - 1), f[2] = t_scale(f[2], 2 * rng_uniform(&g) - 1);
            double pl = sqrt(t_dot(f[0], f[0])), J = au_fd_jacobian(map_normalize, f, 0, 0, 1e-6);
            double want = fabs(t_dot(f[0], t_cross(f[1], f[2]))) / (pl * pl * pl);
            if (want > 1e-3) worst = fmax(worst, fabs(J / want - 1));
            ggx_vec3 d = t_scale(t_add(map_normalize(f, 1e-6, 0), t_scale(map_normalize(f, -1e-6, 0), -1)), 0.5e6);
            ggx_vec3 dw = t_scale(t_cross(f[0], t_cross(f[1], f[0])), 1 / (pl * pl * pl)),
                     e = t_add(d, t_scale(dw, -1));
            worst = fmax(worst, sqrt(t_dot(e, e)) / fmax(1e-3, sqrt(t_dot(dw, dw))));
        }
        for (int k = 0; k < AUDIT_SHAPES; k++)
            au_set(r, k, worst < 1e-6 ? AUDIT_HOLDS : AUDIT_FAILS,
                   "largest relative difference from finite differences %.1e over "
                   "1000 random planes (the formula does not depend on A)",
                   worst);
    }

    r = add_row(ctx, "stretch-inverse",
                "s = A^-1 m / ||A^-1 m|| inverts m = A s / ||A s||, and |s_z| = |m_z| ||m_||, "
                "mx^2/ax^2 + my^2/ay^2 + mz^2 = 1 / ||m_||^2 (m_ = A s)",
                SEED_VNDF ", " SEED_STRETCH,
                "the VNDF proof, Elliptic Stretch; Elliptic "
                "Stretch",
                AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double ax, ay;
        if (!au_alphas_or_skip(r, k, &ctx->sh[k], &ax, &ay)) continue;
        double Ait[3][3];
        au_inv_t(ctx->A[k], Ait);
        rng g = {100};
        double worst = 0;
        for (int i = 0; i < 1000; i++) {
            ggx_vec3 sv = au_random_upper(&g), mb = t_matvec(ctx->A[k], sv), m = t_normalize(mb);
            ggx_vec3 back = t_normalize(t_mattvec((const double(*)[3])Ait, m)),
                     d = t_add(back, t_scale(sv, -1)); /* A^-1 m */
            double ml = sqrt(t_dot(mb, mb)), q = m.x * m.x / (ax * ax) + m.y * m.y / (ay * ay) + m.z * m.z;
            worst = fmax(worst,
                         fmax(sqrt(t_dot(d, d)), fmax(fabs(fabs(sv.z) / (fabs(m.z) * ml) - 1), fabs(q * ml * ml - 1))));
        }
        au_set(r, k, worst < 1e-12 ? AUDIT_HOLDS : AUDIT_FAILS, "largest difference %.1e over 1000 directions%s", worst,
               ctx->sh[k].kind == GGX_SHAPE_UNSKEWED ? " (the norm in x, y, not the rotated axes)" : "");
    }

    r = add_row(ctx, "equal-area-grid",
                "the 10 x 10 grid of the unit square maps to 100 cells of equal probability under "
                "D(m)(m.n) (the figures, alpha 0.15, 0.5)",
                SEED_STRETCH, "Visualization", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        /* normals drawn by an independent sampler (the ellipse lift), mapped back to the unit square by the stretch's
         * inverse; the 100 cells' counts against 1/100 each (chi-square, 99 degrees of freedom) */
        rng g = {101};
        enum { NS = 200000 };
        long cells[100] = {0};
        for (int i = 0; i < NS; i++) {
            ggx_vec2 u = ggx_sample_ndf_stretch_inv(
                &ctx->sh[k], ggx_sample_ndf_ellipse(&ctx->sh[k], rng_uniform(&g), rng_uniform(&g)));
            int a = (int)(u.x * 10), b = (int)(u.y * 10);
            cells[(a < 0 ? 0 : a > 9 ? 9 : a) * 10 + (b < 0 ? 0 : b > 9 ? 9 : b)]++;
        }
        double x2 = 0, e = NS / 100.0;
        for (int i = 0; i < 100; i++) x2 += ((double)cells[i] - e) * ((double)cells[i] - e) / e;
        /* 99 degrees of freedom: mean 99, sd 14; beyond 99 + 6 sd = 183 the cells are not equal */
        au_set(r, k, x2 < 183 ? AUDIT_HOLDS : AUDIT_FAILS,
               "chi-square %.1f over the 100 cells with 99 degrees of freedom (2e5 normals "
               "from the ellipse lift, mapped back by the stretch's inverse)",
               x2);
    }
}

/* ---- the seeds' formulas in ax, ay and A = S R ---- */
static void rows_diagonal_forms(const au_ctx *ctx)
{
    audit_row *r;

    r = add_row(ctx, "inversion-forms",
                "for the lifted normal: cos phi_m = ax cos 2 pi xi2 / N, sin phi_m = ay sin 2 pi xi2 / N and "
                "tan theta_m = sqrt(xi1 / (1 - xi1)) N = sqrt(xi1 / ((1 - xi1)(cos^2 phi_m / ax^2 + sin^2 phi_m / "
                "ay^2))), N^2 = "
                "ax^2 cos^2 + ay^2 sin^2",
                SEED_BLOG2, "Sampling Normals; eq:theta_m_sample", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        if (ctx->sh[k].kind != GGX_SHAPE_DIAGONAL) {
            au_set(r, k, AUDIT_NOT_CLAIMED, "cannot be applied (written in x and y for a diagonal A)");
            continue;
        }
        double ax = ctx->A[k][0][0], ay = ctx->A[k][1][1];
        rng g = {102};
        double worst = 0;
        for (int i = 0; i < 1000; i++) {
            double x1 = rng_uniform(&g), t = 2 * GGX_PI * rng_uniform(&g), c = cos(t), sn = sin(t);
            /* the normal at the point lifted from (a r cos t, b r sin t), a = 1 / ax, b = 1 / ay: the gradient A^T A p */
            ggx_vec3 p = t_vec(sqrt(x1) * c / ax, sqrt(x1) * sn / ay, sqrt(1 - x1));
            ggx_vec3 m = t_normalize(t_mattvec(ctx->A[k], t_matvec(ctx->A[k], p)));
            double N = sqrt(ax * ax * c * c + ay * ay * sn * sn), ph = atan2(m.y, m.x),
                   th = atan2(hypot(m.x, m.y), m.z);
            double inv = sqrt(x1 / ((1 - x1) * (cos(ph) * cos(ph) / (ax * ax) + sin(ph) * sin(ph) / (ay * ay))));
            worst = fmax(worst, fmax(fabs(cos(ph) - ax * c / N), fabs(sin(ph) - ay * sn / N)));
            worst = fmax(
                worst, fmax(fabs(tan(th) / (sqrt(x1 / (1 - x1)) * N) - 1), fabs(inv / (sqrt(x1 / (1 - x1)) * N) - 1)));
        }
        au_set(r, k, worst < 1e-9 ? AUDIT_HOLDS : AUDIT_FAILS,
               "largest difference %.1e over 1000 points (the angles from the "
               "ellipsoid's own normal, the gradient at the lifted point)",
               worst);
    }

    r = add_row(ctx, "spherical-form",
                "D = 1 / (pi ax ay cos^4 theta (1 + tan^2 theta (cos^2 phi / ax^2 + sin^2 phi / ay^2))^2)", SEED_BLOG1,
                "normal in spherical coordinates", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) {
        double ax, ay;
        if (!au_alphas_or_skip(r, k, &ctx->sh[k], &ax, &ay)) continue;
        rng g = {103};
        double worst = 0;
        for (int i = 0; i < 1000; i++) {
            double th = acos(0.02 + 0.98 * rng_uniform(&g)), ph = 2 * GGX_PI * rng_uniform(&g), c = cos(th),
                   t2 = tan(th) * tan(th);
            double q = 1 + t2 * (cos(ph) * cos(ph) / (ax * ax) + sin(ph) * sin(ph) / (ay * ay));
            worst = fmax(
                worst, fabs(1 / (GGX_PI * ax * ay * c * c * c * c * q * q) / ggx_ndf(&ctx->sh[k], t_dir(th, ph)) - 1));
        }
        au_set(r, k, worst < 1e-9 ? AUDIT_HOLDS : AUDIT_FAILS,
               "largest relative difference from Walter eq 1 %.1e over 1000 normals", worst);
    }

    r = add_row(ctx, "det-sr", "A = S R with R a rotation: |A| = |S| = ax ay", SEED_WALTER, "eq 2 and text",
                AUDIT_SCOPE_ANY);
    au_kin_row(ctx, r, 0, err_det_sr, NULL, 1, 1e-12, "|det A| against ax ay: relative difference");

    r = add_row(ctx, "an-is-n", "theta_x = theta_y = 0 gives A n = n, so ||An|| = 1", SEED_WALTER,
                "section 1, last sentence", AUDIT_SCOPE_ROTATED);
    au_kin_row(ctx, r, 0, err_an_is_n, NULL, 1, 1e-12, "|A n - n|:");
}

static int run_claims(const double A[AUDIT_SHAPES][3][3], audit_row *rows, int progress);

int audit_run(const double A[AUDIT_SHAPES][3][3], audit_row *rows, int progress)
{
    return audit_run_at(A, rows, progress, chi2_sidak(CHI2_SUITE_RUNS));
}

int audit_run_at(const double A[AUDIT_SHAPES][3][3], audit_row *rows, int progress, double alpha)
{
    au_set_alpha_level(alpha);
    int n = run_claims(A, rows, progress);
    au_set_alpha_level(-1);
    return n;
}

static int run_claims(const double A[AUDIT_SHAPES][3][3], audit_row *rows, int progress)
{
    ggx_shape sh[AUDIT_SHAPES];
    for (int k = 0; k < AUDIT_SHAPES; k++)
        if (ggx_shape_matrix(&sh[k], A[k]) != GGX_OK) return 0;
    const ggx_vec3 v = t_dir(1.2, -0.6);
    int nr = 0;
    const au_ctx ctx = {rows, &nr, sh, A, progress};

    rows_ndf_areas_g1(&ctx);
    rows_samplers(&ctx, v);
    rows_reflection_sampling(&ctx, v);
    rows_blog(&ctx);
    rows_walter(&ctx);
    rows_engstad(&ctx);
    rows_curvature_dof_lean(&ctx);
    rows_map_jacobians(&ctx);
    rows_identities(&ctx);
    rows_walter_forms(&ctx);
    rows_stretch_forms(&ctx);
    rows_diagonal_forms(&ctx);
    au_rows_ellipsoid(&ctx);
    au_rows_sampling(&ctx);
    au_rows_scattering(&ctx);
    au_rows_stretch(&ctx);
    /* a shape outside a claim's scope: not claimed, with what happens when applied anyway */
    for (int i = 0; i < nr; i++) apply_scope(&rows[i], sh);
    if (progress) fputc('\n', stderr);
    return nr;
}

const char *audit_verdict_name(audit_verdict v)
{
    static const char *const names[] = {"fails", "holds", "holds with a correction", "not claimed"};
    return names[v];
}

const char *audit_scope_name(audit_scope s)
{
    static const char *const names[] = {"diagonal A", "A = S Rz", "any A"};
    return names[s];
}

/* Markdown: a table cell, '|' escaped. */
static void md_cell(FILE *f, const char *text)
{
    fputs("| ", f);
    for (const char *c = text; *c; c++) {
        if (*c == '|') fputc('\\', f);
        fputc(*c, f);
    }
    fputc(' ', f);
}

/* CSV (RFC 4180): every field quoted, quotes doubled. */
static void csv_field(FILE *f, const char *text, int last)
{
    fputc('"', f);
    for (const char *c = text; *c; c++) {
        if (*c == '"') fputc('"', f);
        fputc(*c, f);
    }
    fputs(last ? "\"\n" : "\",", f);
}

/* JSON: a string, escaped. */
static void json_string(FILE *f, const char *text)
{
    fputc('"', f);
    for (const unsigned char *c = (const unsigned char *)text; *c; c++) {
        if (*c == '"' || *c == '\\') fprintf(f, "\\%c", *c);
        else if (*c < 0x20) fprintf(f, "\\u%04x", *c);
        else fputc(*c, f);
    }
    fputc('"', f);
}

void audit_write(FILE *f, audit_format fmt, const audit_row *rows, int n, const char *const labels[AUDIT_SHAPES])
{
    if (fmt == AUDIT_CSV) {
        fputs("id,seed,where,scope,claim,shape,verdict,evidence\n", f);
        for (int i = 0; i < n; i++)
            for (int k = 0; k < AUDIT_SHAPES; k++) {
                const audit_row *r = &rows[i];
                csv_field(f, r->id, 0), csv_field(f, r->seed, 0), csv_field(f, r->where, 0);
                csv_field(f, audit_scope_name(r->scope), 0), csv_field(f, r->claim, 0), csv_field(f, labels[k], 0);
                csv_field(f, audit_verdict_name(r->verdict[k]), 0), csv_field(f, r->text[k], 1);
            }
        return;
    }
    if (fmt == AUDIT_JSON) {
        fputs("[\n", f);
        for (int i = 0; i < n; i++) {
            const audit_row *r = &rows[i];
            fputs("  {\"id\": ", f), json_string(f, r->id);
            fputs(", \"seed\": ", f), json_string(f, r->seed);
            fputs(", \"where\": ", f), json_string(f, r->where);
            fputs(", \"scope\": ", f), json_string(f, audit_scope_name(r->scope));
            fputs(", \"claim\": ", f), json_string(f, r->claim);
            fputs(", \"verdicts\": [", f);
            for (int k = 0; k < AUDIT_SHAPES; k++) {
                fputs(k ? ", {\"shape\": " : "{\"shape\": ", f), json_string(f, labels[k]);
                fputs(", \"verdict\": ", f), json_string(f, audit_verdict_name(r->verdict[k]));
                fputs(", \"evidence\": ", f), json_string(f, r->text[k]);
                fputc('}', f);
            }
            fprintf(f, "]}%s\n", i + 1 < n ? "," : "");
        }
        fputs("]\n", f);
        return;
    }
    fprintf(f,
            "# Seed audit\n\n"
            "Written by `ggx audit` (its defaults; `ggx audit --format md > docs/audit.md`); `make test-full` "
            "checks that this file is the command's output and `make test` asserts every verdict "
            "(tests/unit/test_audit.c). Each claim names its seed by the short name of [references.md](references.md), "
            "where it is in that text, and the shapes the seed states it for. Verdicts: "
            "**holds**; **holds with a correction** (the seed's formula fails as written, the evidence states the "
            "form that holds); **fails** (with the counterexample found); **not claimed** for this shape (the "
            "evidence says what happens when it is applied anyway). Shapes: a claim about every point of every "
            "shape is checked at random points of %d shapes of each column's kind, the column's own and %d random "
            "ones (alphas 0.05 to 2, any theta_z, skews up to 0.6 rad); a failure reports the smallest "
            "counterexample found, on the failing shape whose A^T A is nearest to diagonal. Views: claims about "
            "every view are checked at 48 views (theta from 0.3 to 1.5 rad, 8 azimuths), or at random views; the "
            "samplers of visible normals at theta = 1.2 rad, phi = -0.6 and at the grazing theta = 1.5, phi = 2 "
            "(the other chi-square rows at the first; phi = 2.5 where Walter's min must be active). "
            "Chi-square: 10^6 samples, 100 x 200 equal-area cells in sphere space, Sidak level %.2g. Areas by rays "
            "shot at the ellipsoid itself, curvature and Jacobians by finite differences; more of them in "
            "tests/unit/test_ndf.c and tests/test_sample_map.c.\n\n",
            AU_KIN, AU_KIN - 1, au_alpha_level());
    fprintf(f, "| # | id | claim | seed, where | scope | %s | %s | %s |\n|---|---|---|---|---|---|---|---|\n",
            labels[0], labels[1], labels[2]);
    for (int i = 0; i < n; i++) {
        const audit_row *r = &rows[i];
        char where[256];
        snprintf(where, sizeof where, "%s (%s)", r->seed, r->where);
        fprintf(f, "| %d ", i + 1);
        md_cell(f, r->id), md_cell(f, r->claim), md_cell(f, where), md_cell(f, audit_scope_name(r->scope));
        for (int k = 0; k < AUDIT_SHAPES; k++) {
            char t[AUDIT_TEXT + 64];
            snprintf(t, sizeof t, "**%s**: %s", audit_verdict_name(r->verdict[k]), r->text[k]);
            md_cell(f, t);
        }
        fputs("|\n", f);
    }
}
