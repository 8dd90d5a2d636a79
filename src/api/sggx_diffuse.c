/* The diffuse flakes' phase function of SGGX, evaluated deterministically (ggx_sggx.h; the derivation, with the
 * names used here, is docs/design/sggx.md, "The diffuse phase function"):
 *
 *   f(wi, wo) = sigma(wo) / pi^2 * integral over the lune L = {a.u >= 0, b.u >= 0} of (a.u)(b.u) / sigma(u) du,
 *
 * a, b the unit vectors along H wi, H wo (H = S^(1/2)). In the lune's coordinates u = cos t c + sin t d(psi), with
 * c normal to a and b, d(psi) = cos psi a + sin psi e (e = c x a) and psi in [gamma - pi/2, pi/2] (gamma the angle
 * from a to b), the integral is that of cos psi cos(psi - gamma) J(psi), where J(psi), the integral over t in
 * [0, pi] of sin^3 t / sqrt(Q(t)) along one great semicircle, is elementary (jsemi below), and the integral over psi
 * is adaptive Gauss-Kronrod on panels split where the semicircles pass nearest the flattest directions of S (where
 * J has its peaks). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stddef.h>

#include "internal.h"
#include "sggx_internal.h"

/* phi(z) = atan(sqrt z) / sqrt z for z > 0, atanh(sqrt -z) / sqrt -z for -1 < z < 0, 1 at 0 (its series near 0);
 * atanh(r) as log((1 + r) / (1 - r)) / 2, a quarter of the time of libm's atanh (r >= 0.03 here: no cancellation). */
static double phi_z(double z)
{
    if (fabs(z) < 1e-3) return 1.0 + z * (-1.0 / 3 + z * (1.0 / 5 + z * (-1.0 / 7 + z * (1.0 / 9))));
    double r = sqrt(fabs(z));
    return z > 0 ? atan(r) / r : 0.5 * log((1.0 + r) / (1.0 - r)) / r;
}

/* 2 mu^2 / X^4 times the integral over the half circle of the terms of one eigen-direction (the design document's
 * K(X^2, mu, mu')): with z = (mu' - mu) X^2 / mu and Y^2 = 1 - X^2, 1 / (1 + z) + phi(z) + (3 Y^2 - X^2) psi(z),
 * where psi(z) = (phi(z) - 1 / (1 + z)) / z > 0 (its series near 0). */
static double kterm(double x2, double y2, double mu, double mu_other)
{
    double z = (mu_other - mu) * x2 / mu, ph = phi_z(z), r = 1.0 / (1.0 + z);
    double ps = fabs(z) < 1e-3 ? 2.0 / 3 + z * (-4.0 / 5 + z * (6.0 / 7 + z * (-8.0 / 9 + z * (10.0 / 11))))
                               : (ph - r) / z;
    return r + ph + (3.0 * y2 - x2) * ps;
}

/* J = integral over t in [0, pi] of sin^3 t / sqrt(p cos^2 t + 2 q cos t sin t + r sin^2 t) for the positive
 * definite form with p > 0 and determinant dt = p r - q^2 > 0 (given, computed without cancellation): J = p^(7/2)
 * times the integral over the upper half circle of w_2^3 / (w^T P w)^2, P = [dt, -q sqrt(dt); -q sqrt(dt), p^2 + q^2]
 * in the eigenbasis of P (eigenvalues mu1 >= mu2, e_2's squared components g1, g2). */
static double jsemi(double p, double q, double dt)
{
    double a = dt, d = p * p + q * q, b2 = q * q * dt, ad = a - d;
    double R = sqrt(ad * ad + 4.0 * b2);
    double mu1 = 0.5 * (a + d + R), mu2 = dt * p * p / mu1;
    double g1, g2; /* e_2 . v1 and e_2 . v2, squared; v1 = (cos th, sin th) with tan 2 th = 2 b / (a - d) */
    if (!(R > 0)) {
        g1 = 0.0, g2 = 1.0;
    } else if (ad >= 0) {
        g2 = (R + ad) / (2.0 * R), g1 = 2.0 * b2 / (R * (R + ad));
    } else {
        g1 = (R - ad) / (2.0 * R), g2 = 2.0 * b2 / (R * (R - ad));
    }
    double I = 0.0;
    if (g1 > 0) I += g1 * g1 / (mu1 * mu1) * kterm(g1, g2, mu1, mu2);
    if (g2 > 0) I += g2 * g2 / (mu2 * mu2) * kterm(g2, g1, mu2, mu1);
    return I * p * p * p * sqrt(p);
}

/* What J(psi) needs, per call: the products with H and H^-1 of the lune's frame, S scaled to lambda_max = 1. */
typedef struct lune {
    ggx_vec3 hc, ha, he, ia, ie; /* H c, H a, H e, H^-1 a, H^-1 e */
    double p, det, cg, sg;       /* c^T S c, |S|, cos gamma, sin gamma */
} lune;

/* cos psi cos(psi - gamma) J(psi). The form of the semicircle, in its basis (c, d): p = |H c|^2, q = (H c).(H d),
 * and the determinant |S| |H^-1 (c x d)|^2 (the cofactor form of det, no cancellation), c x d = cos psi e - sin psi a. */
static double integrand(const lune *L, double psi)
{
    double cp = cos(psi), sp = sin(psi);
    ggx_vec3 hd = ggx_k_add_d(ggx_k_scale_d(L->ha, cp), ggx_k_scale_d(L->he, sp));
    ggx_vec3 in = ggx_k_sub_d(ggx_k_scale_d(L->ie, cp), ggx_k_scale_d(L->ia, sp));
    double q = ggx_k_dot_d(L->hc, hd), dt = L->det * ggx_k_dot_d(in, in);
    double w = cp * (cp * L->cg + sp * L->sg);
    return w > 0 ? w * jsemi(L->p, q, dt) : 0.0;
}

/* Gauss-Kronrod 7-15 (the Kronrod nodes, then the weights of both rules). */
static const double XK[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                             0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                             0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                             0.207784955007898467600689403773245, 0.0};
static const double WK[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                             0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                             0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                             0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
static const double WG[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                             0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

/* A panel of the outer integral, in the variable y of its map: psi = y (eps = 0), or psi = x0 + sgn eps sinh(y),
 * which spreads a peak of width ~eps at x0 over y in [0, asinh(L / eps)], where G(psi) ~ 1 / sqrt(eps^2 + x^2)
 * becomes flat. */
typedef struct panel {
    double x0, sgn, eps, y0, y1, v, e;
} panel;

static double mapped(const lune *L, const panel *P, double y)
{
    if (P->eps == 0) return integrand(L, y);
    double ex = exp(y), ix = 1.0 / ex;
    return integrand(L, P->x0 + P->sgn * P->eps * 0.5 * (ex - ix)) * P->eps * 0.5 * (ex + ix);
}

/* The Kronrod estimate of the panel's integral into P->v and |Kronrod - Gauss| into P->e. */
static void gk15(const lune *L, panel *P)
{
    double c = 0.5 * (P->y0 + P->y1), h = 0.5 * (P->y1 - P->y0), f0 = mapped(L, P, c);
    double k = WK[7] * f0, g = WG[3] * f0;
    for (int i = 0; i < 7; i++) {
        double fs = mapped(L, P, c - h * XK[i]) + mapped(L, P, c + h * XK[i]);
        k += WK[i] * fs;
        if (i % 2 == 1) g += WG[i / 2] * fs;
    }
    P->v = k * h;
    P->e = fabs((k - g) * h);
}

enum { MAX_PANELS = 128, MAX_CUTS = 10 };
/* The adaptive rule stops when the estimated error (the Gauss rule's, which overstates the Kronrod rule's by orders
 * of magnitude on these smooth panels) is below this fraction of the integral: the header's accuracy is measured at
 * this value (a tolerance of 1e-3 lets errors of 4e-4 through). */
#ifndef DIFFUSE_RTOL
#define DIFFUSE_RTOL 1e-4
#endif
/* Cuts are made where an eigenvalue of S is below this fraction of the next one (milder S give smooth integrands). */
#ifndef CUT_RATIO
#define CUT_RATIO 0.25
#endif

/* A peak of G: at psi = at, of width eps. */
typedef struct cut {
    double at, eps;
} cut;

/* Adds a panel from a to b, graded about the peak k (plain for k NULL or a peak too far or too wide to matter):
 * psi = k->at + sgn eps sinh(y), with sgn = +1 for a peak at or left of a, -1 at or right of b. */
static void add_panel(const lune *L, panel *P, int *n, double a, double b, const cut *k)
{
    panel p = {0};
    if (k && k->eps < b - a && (k->at <= a ? a - k->at : k->at - b) < b - a) {
        p.x0 = k->at, p.eps = k->eps;
        p.sgn = k->at <= a ? 1.0 : -1.0;
        double ya = asinh(p.sgn * (a - k->at) / k->eps), yb = asinh(p.sgn * (b - k->at) / k->eps);
        p.y0 = fmin(ya, yb), p.y1 = fmax(ya, yb);
    } else {
        p.y0 = a, p.y1 = b;
    }
    gk15(L, &p);
    P[(*n)++] = p;
}

/* The peak nearest x on its left (side -1: at <= x) or right (side +1: at >= x), or NULL. */
static const cut *nearest(const cut *k, int nk, double x, int side)
{
    const cut *best = NULL;
    for (int i = 0; i < nk; i++)
        if (side * (k[i].at - x) >= 0 && (!best || fabs(k[i].at - x) < fabs(best->at - x))) best = &k[i];
    return best;
}

/* The integral over [lo, hi]: split at the peaks inside, each part graded about the peak nearest its ends, then halving (in y) the panel of largest error until the sum of the errors meets
 * DIFFUSE_RTOL. A part with peaks near both ends is halved, each half graded about its own. */
static double outer(const lune *L, double lo, double hi, const cut *k, int nk)
{
    panel P[MAX_PANELS];
    int n = 0;
    double a = lo;
    for (int i = 0; i <= nk; i++) {
        double b = i < nk ? fmin(k[i].at, hi) : hi; /* peaks left of lo are skipped, those right of hi end at hi */
        if (!(b > a)) continue;
        const cut *ka = nearest(k, nk, a, -1), *kb = nearest(k, nk, b, +1);
        int near_a = ka && a - ka->at < b - a, near_b = kb && kb->at - b < b - a;
        if (near_a && near_b) {
            double m = 0.5 * (a + b);
            add_panel(L, P, &n, a, m, ka);
            add_panel(L, P, &n, m, b, kb);
        } else {
            add_panel(L, P, &n, a, b, near_a ? ka : near_b ? kb : NULL);
        }
        a = b;
    }
    for (;;) {
        double total = 0.0, err = 0.0;
        int worst = 0;
        for (int i = 0; i < n; i++) {
            total += P[i].v, err += P[i].e;
            if (P[i].e > P[worst].e) worst = i;
        }
        if (err <= DIFFUSE_RTOL * total || n == MAX_PANELS) return total;
        P[n] = P[worst];
        P[worst].y1 = P[n].y0 = 0.5 * (P[worst].y0 + P[worst].y1);
        gk15(L, &P[worst]);
        gk15(L, &P[n]);
        n++;
    }
}

/* Adds the peaks at psi + j pi, j = -2..2 (the semicircles through +-dir), sorted; those outside [lo, hi] still
 * grade the panels at the ends. */
static void add_cut(cut *k, int *n, double psi, double eps)
{
    for (int j = -2; j <= 2; j++) {
        int i = (*n)++;
        k[i].at = psi + j * GGX_PI, k[i].eps = eps;
        for (; i > 0 && k[i].at < k[i - 1].at; i--) {
            cut t = k[i];
            k[i] = k[i - 1];
            k[i - 1] = t;
        }
    }
}

/* The width in psi of the peak of G at the semicircle through the axis ax (or whose plane is nearest the plane
 * normal to ax, for the ridge): sqrt(ratio + s^2) / sqrt(1 - s^2), s = |c.ax| (s = 0 for the point peak, whose
 * semicircle passes through ax). */
static double cut_width(double ratio, double s)
{
    double s2 = fmin(s * s, 1.0 - 1e-12);
    return sqrt((ratio + s2) / (1.0 - s2));
}

GGX_API GGX_HOT double ggx_sggx_phase_diffuse(const ggx_sggx *f, ggx_vec3 wi, ggx_vec3 wo)
{
    ggx_vec3 a = ggx_k_normalize_d(ggx_k_mul_d(f->half, ggx_k_unit_d(wi)));
    ggx_vec3 hb = ggx_k_mul_d(f->half, ggx_k_unit_d(wo));
    ggx_vec3 b = ggx_k_normalize_d(hb);
    if (ggx_k_is_zero_d(a) || ggx_k_is_zero_d(b)) return 0.0;
    ggx_vec3 axb = ggx_k_cross_d(a, b), c, e;
    double sg = ggx_k_len_d(axb), cg = ggx_k_dot_d(a, b);
    if (sg > 1e-12) {
        c = ggx_k_scale_d(axb, 1.0 / sg);
        e = ggx_k_cross_d(c, a);
    } else {
        if (cg < 0) return 0.0; /* wo = -wi: the lune is empty */
        ggx_k_perp_frame_d(a, &c, &e);
    }
    double gamma = atan2(sg, cg), lo = gamma - 0.5 * GGX_PI, hi = 0.5 * GGX_PI;
    if (!(hi - lo > 0)) return 0.0;
    /* S / lambda_max: H scales by lambda_max^(-1/2), H^-1 by lambda_max^(1/2), |S| by lambda_max^-3 */
    double lmax = f->eig[2], rs = 1.0 / sqrt(lmax), ri = sqrt(lmax);
    lune L;
    L.hc = ggx_k_scale_d(ggx_k_mul_d(f->half, c), rs);
    L.ha = ggx_k_scale_d(ggx_k_mul_d(f->half, a), rs);
    L.he = ggx_k_scale_d(ggx_k_mul_d(f->half, e), rs);
    L.ia = ggx_k_scale_d(ggx_k_mul_d(f->half_inv, a), ri);
    L.ie = ggx_k_scale_d(ggx_k_mul_d(f->half_inv, e), ri);
    L.p = ggx_k_dot_d(L.hc, L.hc);
    L.det = (f->eig[0] / lmax) * (f->eig[1] / lmax);
    L.cg = cg, L.sg = sg;
    /* the cuts: the semicircle through the flattest axis (e1: J's point peak) and the one whose plane is nearest the
     * plane normal to the longest axis (e3: the plane of small sigma, J's ridge when lambda_1 ~ lambda_2) */
    cut cuts[MAX_CUTS];
    int ncuts = 0;
    ggx_vec3 e1 = {f->axes[0][0], f->axes[0][1], f->axes[0][2]}, e3 = {f->axes[2][0], f->axes[2][1], f->axes[2][2]};
    double r1 = f->eig[0] / f->eig[1], r3 = f->eig[1] / f->eig[2];
    if (r1 < CUT_RATIO) add_cut(cuts, &ncuts, atan2(ggx_k_dot_d(e1, e), ggx_k_dot_d(e1, a)), cut_width(r1, 0.0));
    if (r3 < CUT_RATIO)
        add_cut(cuts, &ncuts, atan2(-ggx_k_dot_d(a, e3), ggx_k_dot_d(e, e3)), cut_width(r3, ggx_k_dot_d(c, e3)));
    double integral = outer(&L, lo, hi, cuts, ncuts);
    return ggx_k_finite0_d(ggx_k_len_d(hb) * rs * integral / (GGX_PI * GGX_PI));
}
