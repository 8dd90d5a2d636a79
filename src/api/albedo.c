/* Directional and average albedo of the BRDF with F = 1, by deterministic quadrature in the sphere space of the
 * shape (docs/design/albedo.md has the derivation). SPDX-License-Identifier: MIT
 *
 * E(v) = int f_r(v, w) w.z dw over w.z > 0. With w = reflect(v, h), dw = 4 (v.h) dh, and h the normal of the
 * unit sphere at k under m = A^T k / ||A^T k|| (D(m) dm = ||A^T k|| / (pi ||An||) dk, v.m = (Av).k / ||A^T k||):
 *
 *   E(v) = ||Av|| / (v.z ||An||) * int_C (v'.k) / pi * G(v, w(k)) dk,   v' = Av / ||Av||,
 *
 * where G is G1(v) G1(w) (separable, eq 5) or G2 height-correlated, and C is the set of k with w.z > 0. In h,
 * w.z > 0 reads 2 (v.h) h.z - v.z |h|^2 > 0, a quadratic form of signature (+, -, -); in k it is k^T Q k > 0 with
 * Q = A M A^T, a convex cone around the eigenvector P of Q's positive eigenvalue (and w.z > 0 with v.z > 0 implies
 * v.h > 0 and h.z > 0: the cone lies inside the visible lune). On the meridian of azimuth psi about P, k leaves the
 * cone at tan^2 t = lambda_P / -(lambda_1 cos^2 psi + lambda_2 sin^2 psi). The integrand is smooth in (t, psi)
 * except where G1(w) reaches 1 (the min of eq 32, skewed shapes only), which is found by bisection and made a
 * break point, and it falls to 0 at the cone's edge within a layer of width ~alpha, which a geometric split of the
 * meridian towards its end resolves. */
#include <math.h>
#include <pthread.h>

#include "common/eig3.h"
#include "common/gauss.h"
#include "internal.h"

enum { MAX_PANELS = 400, KINK_SCAN = 16 };
/* The accuracy aimed at: 1e-6 absolute is promised, the quadrature is asked for 100 times better. */
#define ALBEDO_TOL 1e-8
static gq_rule rule;
static pthread_once_t gl_once = PTHREAD_ONCE_INIT;
static void gl_compute(void) { gq_rule_init(&rule); }

typedef gq_fn fn1;

static double adapt(fn1 f, void *ctx, const double *br, int nb, double abs_tol)
{
    gq_panel ps[MAX_PANELS];
    return gq_adapt(&rule, f, ctx, br, nb, abs_tol, ps, MAX_PANELS);
}

/* The cone of the reflection's horizon in sphere space: Q = A M A^T with h^T M h = 2 (v.h) h.z - v.z |h|^2, so that
 * k^T Q k > 0 where the reflection of v about the normal of k is above the horizon (shared by ggx_albedo's domain
 * and the dielectric's kinks). */
static void horizon_cone(const ggx_shape *s, ggx_vec3 v, double Q[3][3])
{
    const double M[3][3] = {{-v.z, 0, v.x}, {0, -v.z, v.y}, {v.x, v.y, v.z}};
    double AM[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) AM[i][j] = s->a[i][0] * M[0][j] + s->a[i][1] * M[1][j] + s->a[i][2] * M[2][j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) Q[i][j] = AM[i][0] * s->a[j][0] + AM[i][1] * s->a[j][1] + AM[i][2] * s->a[j][2];
}

typedef struct albedo_ctx {
    const ggx_shape *s;
    ggx_vec3 v, vp, P, E1, E2;
    double lp, l1, l2; /* eigenvalues of Q: lp > 0 > l1 <= l2 */
    int hc, skewed, depth;
    double inner_tol;
    double cp, sp, T; /* the current meridian */
} albedo_ctx;

static ggx_vec3 v3(double x, double y, double z)
{
    ggx_vec3 r = {x, y, z};
    return r;
}

/* The point at fraction x of the current meridian, and its w. Returns k. */
static ggx_vec3 meridian_point(const albedo_ctx *c, double x, ggx_vec3 *h, ggx_vec3 *w)
{
    double t = x * c->T, st = sin(t), ct = cos(t);
    ggx_vec3 k = v3(ct * c->P.x + st * (c->cp * c->E1.x + c->sp * c->E2.x),
                    ct * c->P.y + st * (c->cp * c->E1.y + c->sp * c->E2.y),
                    ct * c->P.z + st * (c->cp * c->E1.z + c->sp * c->E2.z));
    *h = ggx_k_normalize_d(ggx_k_atmul_d(c->s, k));
    *w = ggx_reflect_d(c->v, *h);
    return k;
}

static double inner_f(double x, void *vc)
{
    const albedo_ctx *c = vc;
    ggx_vec3 h, w;
    ggx_vec3 k = meridian_point(c, x, &h, &w);
    if (!(w.z > 0)) return 0.0; /* only at the edge, by rounding */
    double g = c->hc ? ggx_g2_height_correlated_d(c->s, c->v, w, h) : ggx_k_g1_dir_d(c->s, w);
    return g * ggx_k_dot_d(k, c->vp) * sin(x * c->T) * c->T;
}

static double kink_f(double x, const albedo_ctx *c)
{
    ggx_vec3 h, w;
    meridian_point(c, x, &h, &w);
    return ggx_g1_smith_d(c->s, w) - 1.0;
}

/* The root of kink_f in [a, b] where it changes sign (Illinois false position, to 1e-12 of the meridian). */
static double kink_root(const albedo_ctx *c, double a, double fa, double b, double fb)
{
    int side = 0;
    for (int it = 0; it < 60 && b - a > 1e-12; it++) {
        double x = (a * fb - b * fa) / (fb - fa);
        if (!(x > a && x < b)) x = 0.5 * (a + b);
        double fx = kink_f(x, c);
        if ((fx > 0) == (fb > 0)) {
            b = x;
            fb = fx;
            if (side == -1) fa *= 0.5;
            side = -1;
        } else {
            a = x;
            fa = fx;
            if (side == 1) fb *= 0.5;
            side = 1;
        }
    }
    return 0.5 * (a + b);
}

/* The integral along the meridian of azimuth psi (t from 0 to the cone's edge T, substituted t = x T). */
static double outer_f(double psi, void *vc)
{
    albedo_ctx *c = vc;
    c->cp = cos(psi);
    c->sp = sin(psi);
    double mu = c->l1 * c->cp * c->cp + c->l2 * c->sp * c->sp;
    c->T = atan(sqrt(c->lp / -mu));
    if (!(c->T > 0)) return 0.0;
    double br[2 + 64 + KINK_SCAN];
    int nb = 0;
    br[nb++] = 0.0;
    /* Geometric split towards the edge: the layer where G1(w) falls to 0 has a width ~alpha. */
    for (int i = 1; i <= c->depth; i++) br[nb++] = 1.0 - ldexp(1.0, -i);
    if (c->skewed) { /* where G1_smith(w) crosses 1, the min of eq 32 has a kink */
        double xa = 0.0, fa = kink_f(0.0, c);
        for (int i = 1; i <= KINK_SCAN; i++) {
            double xb = (double)i / KINK_SCAN, fb = i == KINK_SCAN ? -1.0 : kink_f(xb, c);
            if ((fa > 0) != (fb > 0)) br[nb++] = kink_root(c, xa, fa, xb, fb);
            xa = xb;
            fa = fb;
        }
    }
    br[nb++] = 1.0;
    /* insertion sort: the kinks among the geometric points */
    for (int i = 1; i < nb; i++)
        for (int j = i; j > 0 && br[j] < br[j - 1]; j--) {
            double t = br[j];
            br[j] = br[j - 1];
            br[j - 1] = t;
        }
    return adapt(inner_f, c, br, nb, c->inner_tol);
}

double ggx_internal_albedo_scale(const ggx_shape *s, ggx_vec3 v)
{
    return ggx_k_len_d(ggx_k_amul_d(s, v)) / (v.z * s->an_len) * ggx_k_g1_dir_d(s, v);
}

/* E(v) for a unit v with v.z > 0 (hc: height-correlated G2), to an absolute error of about tol. */
static double albedo(const ggx_shape *s, ggx_vec3 v, int hc, double tol)
{
    pthread_once(&gl_once, gl_compute);
    albedo_ctx c;
    c.s = s;
    c.v = v;
    c.hc = hc;
    c.skewed = s->kind == GGX_SHAPE_SKEWED;
    ggx_vec3 av = ggx_k_amul_d(s, v);
    double lav = ggx_k_len_d(av);
    c.vp = ggx_k_scale_d(av, 1.0 / lav);
    double pre = (hc ? lav / (v.z * s->an_len) : ggx_internal_albedo_scale(s, v)) / GGX_PI;
    if (!(pre > 0 && pre <= 1e300)) return 0.0;

    double Q[3][3], E[3][3];
    horizon_cone(s, v, Q);
    ggx_eig3(Q, E);
    int ip = 0;
    for (int i = 1; i < 3; i++)
        if (Q[i][i] > Q[ip][ip]) ip = i;
    int i1 = (ip + 1) % 3, i2 = (ip + 2) % 3;
    if (Q[i1][i1] > Q[i2][i2]) { /* l1 the most negative: the cone is widest towards E2 */
        int t = i1;
        i1 = i2;
        i2 = t;
    }
    c.lp = Q[ip][ip];
    c.l1 = Q[i1][i1];
    c.l2 = Q[i2][i2];
    if (!(c.lp > 0) || !(c.l2 < 0)) return 0.0;
    c.P = v3(E[ip][0], E[ip][1], E[ip][2]);
    if (ggx_k_dot_d(c.P, c.vp) < 0) c.P = ggx_k_neg_d(c.P);
    c.E1 = v3(E[i1][0], E[i1][1], E[i1][2]);
    c.E2 = ggx_k_cross_d(c.P, c.E1);

    /* The edge layer: G1(w) falls from ~1 to 0 over w.z ~ the smallest roughness, sigma_min(A) / ||An||. */
    double blk = sqrt(s->a[0][0] * s->a[0][0] + s->a[0][1] * s->a[0][1] + s->a[1][0] * s->a[1][0] +
                      s->a[1][1] * s->a[1][1]);
    double sig = s->det / (s->an_len * s->an_len * blk);
    int depth = 2;
    while (depth < 40 && ldexp(1.0, -depth) > 0.25 * sig) depth++;
    c.depth = depth;

    double abs_tol = tol / pre;
    c.inner_tol = 0.02 * abs_tol;
    /* psi = pi/2 (E2) is where the cone is widest and, for grazing views, sharpest in psi */
    const double br[] = {
        0, 0.25 * GGX_PI, 0.5 * GGX_PI, 0.75 * GGX_PI, GGX_PI, 1.25 * GGX_PI, 1.5 * GGX_PI, 1.75 * GGX_PI, 2 * GGX_PI};
    return pre * adapt(outer_f, &c, br, 9, 0.5 * abs_tol);
}

double ggx_internal_albedo(const ggx_shape *s, ggx_vec3 v, int hc, double tol) { return albedo(s, v, hc, tol); }

int ggx_internal_is_isotropic(const ggx_shape *s)
{
    return s->kind != GGX_SHAPE_SKEWED && fabs(s->alpha_x - s->alpha_y) <= 1e-12 * fabs(s->alpha_x);
}

/* ---- The rough dielectric: R(v) + T(v) = int f(v -> w) |w.z| dw over both sides (ggx_bsdf_eval) ----
 * Light from v (either side; u = sgn(v.z) v) meets the facets m with u.m > 0 in proportion D_u(m) dm, which in
 * sphere space is P(u) / pi (u'.k) dk on the lune {k.z > 0, u'.k > 0} (as above), and leaves by reflection with
 * probability F and masking G1(sgn w_r), or by refraction with 1 - F and G1(-sgn w_t) (Walter 2007, eq 7). The lune
 * is integrated on meridians from its pole u', each ending where k.z = 0; the integrand is continuous, with kinks
 * where w_r or w_t reaches the horizon, at total internal reflection and where Walter's min acts. */
typedef struct bsdf_ctx {
    const ggx_shape *s;
    ggx_vec3 v, up, E1, E2; /* v as given, the lune's pole u' = A u / |A u| and a frame about it */
    double eta_rel, sgn, cp, sp, T, inner_tol;
    int part; /* 0: reflection, 1: transmission, 2: both (their sum in one quadrature) */
    int nq;
    double q[3][3][3]; /* the kink cones k^T q k = 0 (bsdf_kinks) */
} bsdf_ctx;

/* The integrand's kinks on the lune, each a quadratic cone k^T Q k = 0 in sphere space (u = sgn(v.z) v, Au = A'u,
 * a = ||A n||, so that m.z = a k.z / |A'^T k| and u.m = Au.k / |A'^T k|; each equation below is multiplied by
 * |A'^T k|^2):
 *   the reflection's horizon, 2 (u.m) m.z = u.z:            a (Au z^T + z Au^T) - u.z A'A'^T (horizon_cone);
 *   total internal reflection (eta_rel < 1), (u.m)^2 = 1 - eta_rel^2:   Au Au^T - (1 - eta_rel^2) A'A'^T;
 *   the refraction's horizon, eta_r (u.m) - s = eta_r u.z / m.z with eta_r = 1 / eta_rel and s the refracted
 *   cosine, squared (which admits roots of the other sign, harmless as extra break points):
 *     (eta_rel^2 - 1) a^2 z z^T + u.z a (Au z^T + z Au^T) - u.z^2 A'A'^T, i.e. u.z times the reflection's cone plus
 *     (eta_rel^2 - 1) a^2 z z^T.
 * On a meridian k = cos t u' + sin t d each is a quadratic in tan t, solved in closed form (bsdf_outer), so the
 * panels start at the kinks instead of bisecting towards them: ggx_bsdf_albedo is about 10 times faster and the
 * dielectric's tables build 3 to 3.5 times faster (docs/design/albedo.md, docs/design/energy.md). */
static void bsdf_kinks(bsdf_ctx *c, ggx_vec3 u)
{
    const ggx_shape *s = c->s;
    double a = s->an_len, er2 = c->eta_rel * c->eta_rel;
    horizon_cone(s, u, c->q[0]);
    for (int i = 0; i < 3;
         i++) /* the refraction's horizon: u.z times the reflection's, plus (eta_rel^2 - 1) a^2 zz^T */
        for (int j = 0; j < 3; j++) c->q[1][i][j] = u.z * c->q[0][i][j];
    c->q[1][2][2] += (er2 - 1) * a * a;
    c->nq = 2;
    if (er2 < 1) { /* total internal reflection */
        ggx_vec3 au = ggx_k_amul_d(s, u);
        double au3[3] = {au.x, au.y, au.z};
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double aat = s->a[i][0] * s->a[j][0] + s->a[i][1] * s->a[j][1] + s->a[i][2] * s->a[j][2];
                c->q[2][i][j] = au3[i] * au3[j] - (1 - er2) * aat;
            }
        c->nq = 3;
    }
}

static double qform(double q[3][3], ggx_vec3 x, ggx_vec3 y)
{
    double xs[3] = {x.x, x.y, x.z}, ys[3] = {y.x, y.y, y.z}, r = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) r += xs[i] * q[i][j] * ys[j];
    return r;
}

static double bsdf_inner(double x, void *vc)
{
    const bsdf_ctx *c = vc;
    double t = x * c->T, st = sin(t), ct = cos(t);
    ggx_vec3 k = v3(ct * c->up.x + st * (c->cp * c->E1.x + c->sp * c->E2.x),
                    ct * c->up.y + st * (c->cp * c->E1.y + c->sp * c->E2.y),
                    ct * c->up.z + st * (c->cp * c->E1.z + c->sp * c->E2.z));
    ggx_vec3 m = ggx_k_normalize_d(ggx_k_atmul_d(c->s, k));
    double vm = c->sgn * ggx_k_dot_d(c->v, m);
    if (!(vm > 0) || !(m.z > 0)) return 0.0;
    double F = ggx_fresnel_dielectric_eval_d(vm, c->eta_rel), g = 0.0;
    if (c->part != 1) {
        ggx_vec3 w = ggx_reflect_d(c->v, m);
        if (c->sgn * w.z > 0) g = F * ggx_k_g1_dir_d(c->s, ggx_k_scale_d(w, c->sgn));
    }
    if (c->part != 0 && F < 1) {
        ggx_vec3 w;
        if (ggx_refract_d(c->v, m, c->eta_rel, &w) && c->sgn * w.z < 0)
            g += (1 - F) * ggx_k_g1_dir_d(c->s, ggx_k_scale_d(w, -c->sgn));
    }
    return g * ct * st * c->T;
}

static double bsdf_outer(double psi, void *vc)
{
    bsdf_ctx *c = vc;
    c->cp = cos(psi);
    c->sp = sin(psi);
    double d = c->cp * c->E1.z + c->sp * c->E2.z; /* k.z = cos t u'.z + sin t d */
    /* A skewed A can put the pole below the horizon (u'.z < 0): the meridian then enters the lune at t0 = atan(-u'.z
     * / d), where the integrand jumps from 0 (refraction only: the reflection of a horizontal facet is below the
     * horizon), or not at all. */
    if (!(c->up.z > 0) && !(d > 0)) return 0.0;
    c->T = d < 0 ? atan2(c->up.z, -d) : 0.5 * GGX_PI;
    double x0 = c->up.z < 0 ? atan2(-c->up.z, d) / c->T : 0.0;
    /* the fixed points, then the kinks (bsdf_kinks): roots of q_c tau^2 + 2 q_b tau + q_a = 0 with tau = tan t.
     * Between the kinks the integrand is smooth but for the layer of width ~alpha where G1 falls towards the lune's
     * edge, which 0.875 starts (fewer fixed points let the error estimate be fooled; more cost 1.5x, docs/design/albedo.md) */
    double br[4 + 6] = {x0};
    int nb = 1;
    for (int i = 1; i < 4; i++) {
        static const double fixed[] = {0.0, 0.5, 0.875, 1.0};
        if (fixed[i] > x0) br[nb++] = fixed[i];
    }
    int nfixed = nb;
    ggx_vec3 dv = v3(c->cp * c->E1.x + c->sp * c->E2.x, c->cp * c->E1.y + c->sp * c->E2.y,
                     c->cp * c->E1.z + c->sp * c->E2.z);
    for (int i = 0; i < c->nq; i++) {
        double qa = qform(c->q[i], c->up, c->up), qb = qform(c->q[i], c->up, dv), qc = qform(c->q[i], dv, dv);
        double disc = qb * qb - qa * qc;
        if (!(disc >= 0)) continue;
        double r = -qb - (qb >= 0 ? 1 : -1) * sqrt(disc), taus[2] = {r / qc, qa / r}; /* without cancellation */
        for (int j = 0; j < 2; j++) {
            double x = atan(taus[j]) / c->T;
            if (x > x0 + 1e-9 && x < 1 - 1e-9) br[nb++] = x;
        }
    }
    for (int i = nfixed; i < nb; i++) /* insertion into the sorted list */
        for (int j = i; j > 0 && br[j - 1] > br[j]; j--) {
            double t = br[j];
            br[j] = br[j - 1];
            br[j - 1] = t;
        }
    return adapt(bsdf_inner, c, br, nb, c->inner_tol);
}

static double bsdf_part(const ggx_shape *s, ggx_vec3 v, double eta, int part, double tol)
{
    pthread_once(&gl_once, gl_compute);
    bsdf_ctx c;
    c.s = s;
    c.v = v;
    c.sgn = v.z > 0 ? 1.0 : -1.0;
    c.eta_rel = v.z > 0 ? eta : 1.0 / eta;
    c.part = part;
    ggx_vec3 u = ggx_k_scale_d(v, c.sgn);
    double pre = ggx_internal_albedo_scale(s, u) / GGX_PI;
    if (!(pre > 0 && pre <= 1e300)) return 0.0;
    c.up = ggx_k_normalize_d(ggx_k_amul_d(s, u));
    /* a frame about u': E1 towards the horizon's nearest point (the meridian psi = 0 is the shortest) */
    ggx_vec3 z = v3(0, 0, 1);
    ggx_vec3 e1 = ggx_k_sub_d(ggx_k_scale_d(c.up, c.up.z), z);
    double l = ggx_k_len_d(e1);
    c.E1 = l > 1e-12 ? ggx_k_scale_d(e1, 1.0 / l) : v3(1, 0, 0);
    c.E2 = ggx_k_cross_d(c.up, c.E1);
    bsdf_kinks(&c, u);
    double abs_tol = tol / pre;
    c.inner_tol = 0.02 * abs_tol;
    const double br[] = {
        0, 0.25 * GGX_PI, 0.5 * GGX_PI, 0.75 * GGX_PI, GGX_PI, 1.25 * GGX_PI, 1.5 * GGX_PI, 1.75 * GGX_PI, 2 * GGX_PI};
    return pre * adapt(bsdf_outer, &c, br, 9, 0.5 * abs_tol);
}

double ggx_internal_bsdf_albedo(const ggx_shape *s, double eta, ggx_vec3 v, double tol)
{
    return bsdf_part(s, v, eta, 2, tol);
}

GGX_API double ggx_bsdf_albedo(const ggx_shape *s, double eta, ggx_vec3 v, double *reflected, double *transmitted)
{
    double r = 0.0, t = 0.0, l = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (s && l > 0 && l <= 1e300 && eta > 0 && eta <= 1e300) {
        v = v3(v.x / l, v.y / l, v.z / l);
        if (v.z != 0) {
            r = bsdf_part(s, v, eta, 0, ALBEDO_TOL);
            t = bsdf_part(s, v, eta, 1, ALBEDO_TOL);
            r = r >= 0 ? (r <= 1 ? r : 1) : 0;
            t = t >= 0 ? (t <= 1 - r ? t : 1 - r) : 0;
        }
    }
    if (reflected) *reflected = r;
    if (transmitted) *transmitted = t;
    return r + t;
}


static double albedo_public(const ggx_shape *s, ggx_vec3 v, int hc)
{
    double l = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (!(l > 0 && l <= 1e300)) return 0.0;
    v = v3(v.x / l, v.y / l, v.z / l);
    if (!(v.z > 0)) return 0.0;
    double e = albedo(s, v, hc, ALBEDO_TOL);
    return e >= 0 ? (e <= 1 ? e : 1) : 0;
}

GGX_API double ggx_albedo(const ggx_shape *s, ggx_vec3 v) { return albedo_public(s, v, 0); }
GGX_API double ggx_albedo_height_correlated(const ggx_shape *s, ggx_vec3 v) { return albedo_public(s, v, 1); }

/* ---- E_avg = (1 / pi) int_0^2pi int_0^1 E(mu, phi) mu dmu dphi ----
 * E is smooth in the view except where G1(v) reaches 1 (skewed shapes): those views are break points. It is
 * integrated over the polar angle, not over mu (for skewed shapes E has a gradient at n, so E(mu) has a square-root
 * cusp at mu = 1), with theta = (pi / 2) y (2 - y), which turns the term mu^2 ln mu of E mu at grazing into
 * (1 - y)^5 ln(1 - y). Each smooth piece is integrated by
 * Gauss-Legendre of orders 8, 16, 32, 64 until two agree, and phi by the trapezoid rule on the period (spectral
 * for smooth periodic E), doubled until two agree. */

typedef struct avg_ctx {
    const ggx_shape *s;
    int hc;
    double cp, sp, tol;
} avg_ctx;

static ggx_vec3 avg_view(const avg_ctx *c, double y)
{
    double th = 0.5 * GGX_PI * y * (2 - y), st = sin(th);
    return v3(st * c->cp, st * c->sp, cos(th));
}

static double avg_y(double y, void *vc)
{
    const avg_ctx *c = vc;
    ggx_vec3 v = avg_view(c, y);
    if (!(v.z > 0)) return 0.0;
    double st = sqrt(v.x * v.x + v.y * v.y);
    return albedo(c->s, v, c->hc, 0.1 * c->tol) * v.z * st * GGX_PI * (1 - y); /* E cos(theta) sin(theta) dtheta */
}

/* Gauss-Legendre of order n on [a, b] (nodes by gl_nodes; n <= 64). */
static double gl_fixed(fn1 f, void *ctx, double a, double b, int n)
{
    double xs[64], ws[64], sum = 0.0, c = 0.5 * (a + b), h = 0.5 * (b - a);
    gq_nodes(n, xs, ws);
    for (int i = 0; i < n; i++) sum += ws[i] * f(c + h * xs[i], ctx);
    return sum * h;
}

static double smooth_1d(fn1 f, void *ctx, double a, double b, double tol)
{
    double prev = gl_fixed(f, ctx, a, b, 8), cur = prev;
    for (int n = 16; n <= 64; n *= 2) {
        cur = gl_fixed(f, ctx, a, b, n);
        if (fabs(cur - prev) <= tol) return cur;
        prev = cur;
    }
    return cur; /* not converged to tol: the view integrand's own quadrature noise (~ALBEDO_TOL) is the floor */
}

static double avg_phi(double phi, avg_ctx *c)
{
    c->cp = cos(phi);
    c->sp = sin(phi);
    double br[2 + 8];
    int nb = 0;
    br[nb++] = 0.0;
    if (c->s->kind == GGX_SHAPE_SKEWED) { /* y where G1_smith(v) crosses 1: a kink of the min in eq 32 */
        enum { SCAN = 16 };
        double ya = 0.0, fa = ggx_g1_smith_d(c->s, avg_view(c, 1e-9)) - 1.0; /* G1_smith(n) = 1 exactly */
        for (int i = 1; i <= SCAN && nb < 8; i++) {
            double yb = (double)i / SCAN, fb = i == SCAN ? -1.0 : ggx_g1_smith_d(c->s, avg_view(c, yb)) - 1.0;
            if ((fa > 0) != (fb > 0)) {
                double lo = ya, hi = yb;
                for (int it = 0; it < 60 && hi - lo > 1e-15; it++) {
                    double m = 0.5 * (lo + hi);
                    if ((ggx_g1_smith_d(c->s, avg_view(c, m)) - 1.0 > 0) == (fa > 0)) lo = m;
                    else hi = m;
                }
                br[nb++] = 0.5 * (lo + hi);
            }
            ya = yb;
            fa = fb;
        }
    }
    br[nb++] = 1.0;
    double sum = 0.0;
    for (int i = 0; i + 1 < nb; i++) sum += smooth_1d(avg_y, c, br[i], br[i + 1], c->tol / (nb - 1));
    return sum;
}

/* E_avg's steps, and each E inside it, aim at 1e-7 (1e-6 promised): the line integrals over mu have weights that
 * sum to 2, the trapezoid rule's difference between levels bounds the coarser level's error. */
#define AVG_TOL 1e-7
#define SKEW_PHI_ORDER 32
#define SKEW_LINE_TOL 1e-6

static double avg_phi_fn(double phi, void *vc) { return avg_phi(phi, vc); }

static double albedo_avg(const ggx_shape *s, int hc)
{
    pthread_once(&gl_once, gl_compute);
    avg_ctx c = {s, hc, 1.0, 0.0, AVG_TOL};
    double r;
    int iso = ggx_internal_is_isotropic(s);
    if (iso) {
        r = 2.0 * avg_phi(0.0, &c); /* E does not depend on the view's azimuth */
    } else if (s->kind != GGX_SHAPE_SKEWED) {
        /* E is smooth, periodic and even about the tangent axes: the trapezoid rule on a quarter turn from the
         * axis of alpha_x, with half weights at its ends, is the full-period rule (spectral); doubled until two
         * levels agree. */
        double p0 = atan2(s->tangent_sin, s->tangent_cos), span = 0.5 * GGX_PI, prev;
        int n = 4; /* intervals */
        double sum = 0.5 * (avg_phi(p0, &c) + avg_phi(p0 + span, &c));
        for (int i = 1; i < n; i++) sum += avg_phi(p0 + span * i / n, &c);
        r = sum * span / n;
        while (n < 1024) {
            for (int i = 1; i < 2 * n; i += 2) sum += avg_phi(p0 + span * i / (2 * n), &c);
            n *= 2;
            prev = r;
            r = sum * span / n;
            if (fabs(r - prev) * (4.0 / GGX_PI) <= AVG_TOL) break;
        }
        r *= 4.0 / GGX_PI;
    } else {
        /* Skewed: G1_smith(v) = 1 on a curve through n (G1_smith(n) = 1 exactly, with a non-zero gradient there),
         * tangent at n to the azimuth phi_k perpendicular to that gradient; the line integrals are smooth in phi
         * on either side of phi_k and phi_k + pi, so each half turn is one piece. Inside, E has weaker
         * singularities (where the kink of G1(w) meets the cone's edge) and the orders converge algebraically:
         * a fixed order, whose error against doubled orders is measured in docs/design/albedo.md, keeps the cost at
         * seconds. */
        const double eps = 1e-6;
        c.cp = 1.0;
        c.sp = 0.0;
        double gx = ggx_g1_smith_d(s, avg_view(&c, eps)) - 1.0;
        c.cp = 0.0;
        c.sp = 1.0;
        double gy = ggx_g1_smith_d(s, avg_view(&c, eps)) - 1.0;
        double pk = atan2(gy, gx) + 0.5 * GGX_PI;
        c.tol = SKEW_LINE_TOL;
        r = (gl_fixed(avg_phi_fn, &c, pk, pk + GGX_PI, SKEW_PHI_ORDER) +
             gl_fixed(avg_phi_fn, &c, pk + GGX_PI, pk + 2 * GGX_PI, SKEW_PHI_ORDER)) /
            GGX_PI;
    }
    return r >= 0 ? (r <= 1 ? r : 1) : 0;
}

GGX_API double ggx_albedo_avg(const ggx_shape *s) { return albedo_avg(s, 0); }
GGX_API double ggx_albedo_avg_height_correlated(const ggx_shape *s) { return albedo_avg(s, 1); }
