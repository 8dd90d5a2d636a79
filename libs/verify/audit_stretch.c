/* The seed audit: Engstad's Elliptic Stretch (engstad-stretch), the identities and formulas of its derivation, each checked
 * at random points of every shape of a kind (libs/verify/audit_internal.h). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "audit_internal.h"

/* ---- vector identities: the same for every shape ---- */
static ggx_vec3 random_vec(rng *g)
{
    return t_vec(2 * rng_uniform(g) - 1, 2 * rng_uniform(g) - 1, 2 * rng_uniform(g) - 1);
}
static double vdiff(ggx_vec3 a, ggx_vec3 b, double scale)
{
    ggx_vec3 d = t_add(a, t_scale(b, -1));
    return sqrt(t_dot(d, d)) / scale;
}
static double err_vector_identities(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)K, (void)ctx;
    ggx_vec3 a = random_vec(g), b = random_vec(g), c = random_vec(g);
    double la = sqrt(t_dot(a, a)), lb = sqrt(t_dot(b, b)), lc = sqrt(t_dot(c, c)), abc = t_dot(a, t_cross(b, c));
    double u = rng_uniform(g), v = rng_uniform(g);
    ggx_vec3 s = au_map_cosine(NULL, u, v);
    double e[4] = {
        fabs(sqrt(t_dot(s, s)) - 1),
        vdiff(t_cross(a, t_cross(b, c)), t_add(t_scale(b, t_dot(a, c)), t_scale(c, -t_dot(a, b))), la * lb * lc),
        vdiff(t_cross(t_cross(a, b), t_cross(a, c)), t_scale(a, abc), la * la * lb * lc),
        vdiff(t_cross(t_cross(a, t_cross(b, a)), t_cross(a, t_cross(c, a))), t_scale(a, t_dot(a, a) * abc),
              la * la * la * la * la * lb * lc)};
    double worst = 0;
    for (int i = 0; i < 4; i++) worst = fmax(worst, e[i]);
    snprintf(at, nat, "a (%.3g, %.3g, %.3g)", a.x, a.y, a.z);
    return worst;
}

/* ---- det(m_, m_u, m_v) = ax ay det(s, s_u, s_v), m_ = A s: derivatives by central differences ---- */
static double err_det_scale(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    const double h = 1e-6, (*A)[3] = (const double(*)[3])K->A;
    double u = 0.05 + 0.9 * rng_uniform(g), v = rng_uniform(g);
    ggx_vec3 s = au_map_cosine(NULL, u, v);
    ggx_vec3 su = t_scale(t_add(au_map_cosine(NULL, u + h, v), t_scale(au_map_cosine(NULL, u - h, v), -1)), 0.5 / h);
    ggx_vec3 sv = t_scale(t_add(au_map_cosine(NULL, u, v + h), t_scale(au_map_cosine(NULL, u, v - h), -1)), 0.5 / h);
    double ds = au_det3(s, su, sv), dm = au_det3(t_matvec(A, s), t_matvec(A, su), t_matvec(A, sv));
    double det = au_det3(t_matvec(A, t_vec(1, 0, 0)), t_matvec(A, t_vec(0, 1, 0)), t_matvec(A, t_vec(0, 0, 1)));
    snprintf(at, nat, "(u, v) = (%.3g, %.3g)", u, v);
    return fabs(dm / (fabs(det) * ds) - 1);
}

/* ---- the stretch's total Jacobian |dm / d(u, v)| for m = normalize(A s(u, v)), in the seed's three forms ---- */
typedef struct jac_ctx {
    const double (*A)[3];
} jac_ctx;
static ggx_vec3 map_cos_stretch(const void *ctx, double u, double v)
{
    return t_normalize(t_matvec(((const jac_ctx *)ctx)->A, au_map_cosine(NULL, u, v)));
}
static double err_total_jacobian(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    jac_ctx c = {(const double(*)[3])K->A};
    double ax, ay;
    au_kin_alphas(K, &ax, &ay);
    double u = 0.05 + 0.9 * rng_uniform(g), v = rng_uniform(g), axy = ax * ay;
    ggx_vec3 s = au_map_cosine(NULL, u, v), mu = t_matvec(c.A, s), m = t_normalize(mu);
    double l = sqrt(t_dot(mu, mu)), fd = au_fd_jacobian(map_cos_stretch, &c, u, v, 1e-6);
    double f1 = GGX_PI * axy / (fabs(s.z) * l * l * l), f2 = GGX_PI * axy / (fabs(m.z) * l * l * l * l);
    double f3 = 1 / (fabs(m.z) * ggx_ndf(&K->s, m));
    snprintf(at, nat, "(u, v) = (%.3g, %.3g): finite differences %.5g, the three forms %.5g, %.5g, %.5g", u, v, fd, f1,
             f2, f3);
    return fmax(fabs(f1 / fd - 1), fmax(fabs(f2 / fd - 1), fabs(f3 / fd - 1)));
}

/* ---- a stretch in slope space, normalize(ax m~x, ay m~y, 1) with m~ = m / m_z, is the ellipsoid's stretch
 * normalize(A^T m) ---- */
static double err_slope_stretch(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    ggx_vec3 m = au_random_upper(g);
    double ax, ay;
    au_kin_alphas(K, &ax, &ay);
    ggx_vec3 a = t_normalize(t_vec(ax * m.x / m.z, ay * m.y / m.z, 1));
    ggx_vec3 b = t_normalize(t_mattvec((const double(*)[3])K->A, m));
    snprintf(at, nat, "m = (%.3g, %.3g, %.3g)", m.x, m.y, m.z);
    return vdiff(a, b, 1);
}

/* ---- D in slope space: (m~x^2 + m~y^2 + 1)^2 / (pi ax ay (m~x^2/ax^2 + m~y^2/ay^2 + 1)^2) = P22 / m_z^4 ---- */
static double err_d_slope(const au_kin *K, rng *g, void *ctx, char *at, size_t nat)
{
    (void)ctx;
    ggx_vec3 m = au_random_upper(g);
    double ax, ay;
    au_kin_alphas(K, &ax, &ay);
    double x = m.x / m.z, y = m.y / m.z, t = x * x / (ax * ax) + y * y / (ay * ay) + 1;
    double q = x * x + y * y + 1, d1 = q * q / (GGX_PI * ax * ay * t * t), p22 = 1 / (GGX_PI * ax * ay * t * t);
    double d2 = p22 / (m.z * m.z * m.z * m.z), d = ggx_ndf(&K->s, m);
    snprintf(at, nat, "m = (%.3g, %.3g, %.3g): D %.5g, the slope forms %.5g, %.5g", m.x, m.y, m.z, d, d1, d2);
    return fmax(fabs(d1 / d - 1), fabs(d2 / d - 1));
}

/* ---- isotropic D = alpha^2 / (pi (cos^2 theta (alpha^2 - 1) + 1)^2), on isotropic shapes of each kind ---- */
static void iso_row(audit_row *r, int k, const ggx_shape *s0)
{
    rng g = {121};
    double worst = 0, wa = 0;
    ggx_vec3 wm = t_vec(0, 0, 1);
    for (int i = 0; i < AU_KIN; i++) {
        double a = 0.05 * pow(40.0, rng_uniform(&g)), tz = GGX_PI * (2 * rng_uniform(&g) - 1);
        double tx = s0->kind == GGX_SHAPE_SKEWED ? 0.02 + 0.58 * rng_uniform(&g) : 0, ty = -0.5 * tx;
        ggx_shape s;
        if (ggx_shape_ellipsoid(&s, a, a, tx, ty, s0->kind == GGX_SHAPE_DIAGONAL ? 0 : tz) != GGX_OK) continue;
        for (int j = 0; j < 50; j++) {
            ggx_vec3 m = au_random_upper(&g);
            double c2 = m.z * m.z, q1 = 1 - c2 + a * a * c2, q2 = c2 * (a * a - 1) + 1;
            double d = ggx_ndf(&s, m),
                   e = fmax(fabs(a * a / (GGX_PI * q1 * q1) / d - 1), fabs(a * a / (GGX_PI * q2 * q2) / d - 1));
            if (e > worst) worst = e, wa = a, wm = m;
        }
    }
    if (worst < 1e-12)
        au_set(r, k, AUDIT_HOLDS,
               "largest relative difference from D %.1e at 50 normals on each of %d isotropic shapes%s", worst, AU_KIN,
               s0->kind == GGX_SHAPE_DIAGONAL ? "" : " rotated by theta_z");
    else
        au_set(r, k, AUDIT_FAILS,
               "off D by up to %.3g on isotropic shapes tilted by theta_x, theta_y (alpha %.3g, m = "
               "(%.3g, %.3g, %.3g))",
               worst, wa, wm.x, wm.y, wm.z);
}

void au_rows_stretch(const au_ctx *c)
{
    audit_row *r;
    r = au_add(c->rows, c->nr, "vector-identities",
               "||s(u, v)|| = 1; a x (b x c) = (a.c) b - (a.b) c; (a x b) x (a x c) = "
               "(a.(b x c)) a; [a x (b x a)] x [a x (c x a)] = (a.a)(a.(b x c)) a",
               SEED_STRETCH, "Cosine-Weighted Half-Sphere; Jacobian Determinant; Derivation", AUDIT_SCOPE_ANY);
    for (int k = 0; k < AUDIT_SHAPES; k++)
        au_verdict_kin(r, k, &c->sh[k], c->A[k], err_vector_identities, NULL, 400, 1e-13,
                       "at random vectors (identities; no A involved): relative difference");

    r = au_add(c->rows, c->nr, "det-scale",
               "det(m_, m_u, m_v) = ax ay det(s, s_u, s_v) for the stretched m_ = (ax sx, ay sy, "
               "sz) = A s",
               SEED_STRETCH, "Elliptic Stretch", AUDIT_SCOPE_DIAGONAL);
    au_kin_row(c, r, 0, err_det_scale, NULL, 100, 1e-7,
               "with ax ay = |A| and m_ = A s (det(A X) = det A det X, an "
               "identity): relative difference");

    r = au_add(c->rows, c->nr, "stretch-total-jacobian",
               "the stretched cosine map has |dm / d(u, v)| = pi ax ay / (|s_z| "
               "||m_||^3) = pi ax ay / (|m_z| ||m_||^4) = 1 / (|m_z| D(m))",
               SEED_STRETCH, "Elliptic Stretch", AUDIT_SCOPE_DIAGONAL);
    au_kin_row(c, r, 1, err_total_jacobian, NULL, 100, 1e-6,
               "m = normalize(A s) against its finite-difference "
               "Jacobian: all three forms");

    r = au_add(c->rows, c->nr, "slope-stretch",
               "a stretch in slope space, normalize(ax m~x, ay m~y, 1) with m~ = m / m_z, "
               "is the ellipsoid's stretch",
               SEED_STRETCH, "Relation to slope-space", AUDIT_SCOPE_DIAGONAL);
    au_kin_row(c, r, 1, err_slope_stretch, NULL, 200, 1e-12,
               "against the ellipsoid's stretch normalize(A^T m) (for "
               "a diagonal A, normalize(k x) = normalize(x)): distance");

    r = au_add(c->rows, c->nr, "d-slope",
               "D(m~) = (m~x^2 + m~y^2 + 1)^2 / (pi ax ay (m~x^2/ax^2 + m~y^2/ay^2 + 1)^2) = "
               "P22(m~) / m_z^4",
               SEED_STRETCH, "Relation to slope-space", AUDIT_SCOPE_DIAGONAL);
    au_kin_row(c, r, 1, err_d_slope, NULL, 200, 1e-12, "against Walter eq 1 (slopes along x, y): relative difference");

    r = au_add(c->rows, c->nr, "iso",
               "for ax = ay = alpha: D = alpha^2 / (pi (1 - m_z^2 + alpha^2 m_z^2)^2) = alpha^2 / "
               "(pi (cos^2 theta (alpha^2 - 1) + 1)^2)",
               SEED_STRETCH, "Isotropic roughness", AUDIT_SCOPE_DIAGONAL);
    for (int k = 0; k < AUDIT_SHAPES; k++) iso_row(r, k, &c->sh[k]);
}
