/* Albedo: ggx_albedo and ggx_albedo_avg (separable and height-correlated) against closed forms at alpha = 1 for
 * every rotation, against an independent quadrature over the outgoing direction, against Monte Carlo with the
 * library's BRDF sampler, and on the edges of their domain. SPDX-License-Identifier: MIT */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

#include "testlib.h"

/* The promise of ggx.h: 1e-6 absolute. */
#define PROMISE 1e-6

static double albedo_of(const ggx_shape *s, ggx_vec3 v, int hc)
{
    return hc ? ggx_albedo_height_correlated(s, v) : ggx_albedo(s, v);
}

/* f_r(v, w) with F = 1 and the chosen G, times w.z. */
static double fr_cos(const ggx_shape *s, ggx_vec3 v, ggx_vec3 w, int hc)
{
    if (!hc) {
        ggx_fresnel f;
        ggx_fresnel_one(&f);
        return ggx_brdf_eval(s, &f, v, w) * w.z;
    }
    ggx_vec3 h = ggx_half_reflect(v, w);
    if (!(v.z > 0 && w.z > 0)) return 0.0;
    return ggx_ndf(s, h) * ggx_g2_height_correlated(s, v, w, h) / (4 * v.z);
}

/* ---- independent quadrature: over w in polar coordinates about n, break points at the mirror direction ---- */
typedef struct wq_ctx {
    const ggx_shape *s;
    ggx_vec3 v;
    double theta;
    int hc;
} wq_ctx;

static double wq_phi(double phi, void *vc)
{
    wq_ctx *c = vc;
    return fr_cos(c->s, c->v, t_dir(c->theta, phi), c->hc) * sin(c->theta);
}

static double wq_theta(double theta, void *vc)
{
    wq_ctx *c = vc;
    c->theta = theta;
    double pr = atan2(-c->v.y, -c->v.x);
    return quad_adapt(wq_phi, c, pr - GGX_PI, pr, 1e-12) + quad_adapt(wq_phi, c, pr, pr + GGX_PI, 1e-12);
}

static double albedo_over_w(const ggx_shape *s, ggx_vec3 v, int hc)
{
    wq_ctx c = {s, v, 0.0, hc};
    double tr = acos(v.z);
    return quad_adapt(wq_theta, &c, 0.0, tr, 1e-11) + quad_adapt(wq_theta, &c, tr, 0.5 * GGX_PI, 1e-11);
}

/* At alpha_x = alpha_y = 1 the ellipsoid is the unit sphere for every rotation: D = 1 / pi, Lambda(u) =
 * (1 / u.z - 1) / 2. Separable: E = G1(v) / (4 pi v.z) int G1(w) dw = 2 (1 - ln 2) / (1 + v.z);
 * height-correlated: E = int_0^1 mu_o / (mu + mu_o) dmu_o = 1 - mu ln(1 + 1 / mu). Averages 4 (1 - ln 2)^2 and
 * 4 (1 - ln 2) / 3. */
static void closed_forms_alpha_one(void **state)
{
    (void)state;
    rng r = {77};
    double worst = 0.0;
    for (int i = 0; i < 6; i++) {
        ggx_shape s;
        double tx = i ? rng_range(&r, -1.5, 1.5) : 0.0, ty = i ? rng_range(&r, -1.5, 1.5) : 0.0;
        CHECK(ggx_shape_ellipsoid(&s, 1.0, 1.0, tx, ty, rng_range(&r, -3, 3)) == GGX_OK, "shape");
        for (int j = 0; j < 8; j++) {
            double th = j < 7 ? j * 0.25 : 0.5 * GGX_PI - 1e-4;
            ggx_vec3 v = t_dir(th, rng_range(&r, 0, 2 * GGX_PI));
            double mu = v.z;
            double sep = 2 * (1 - log(2.0)) / (1 + mu), hc = 1 - mu * log1p(1 / mu);
            double a = ggx_albedo(&s, v), b = ggx_albedo_height_correlated(&s, v);
            CHECK_CLOSE(a, sep, 0, PROMISE, "separable, rotation (%g, %g) view %g", tx, ty, th);
            CHECK_CLOSE(b, hc, 0, PROMISE, "height-correlated, rotation (%g, %g) view %g", tx, ty, th);
            worst = fmax(worst, fmax(fabs(a - sep), fabs(b - hc)));
        }
        if (i < 2) {
            double l2 = log(2.0);
            CHECK_CLOSE(ggx_albedo_avg(&s), 4 * (1 - l2) * (1 - l2), 0, PROMISE, "E_avg separable");
            CHECK_CLOSE(ggx_albedo_avg_height_correlated(&s), 4 * (1 - l2) / 3, 0, PROMISE, "E_avg correlated");
        }
    }
    printf("alpha = 1, 6 rotations x 8 views: largest error %.2e\n", worst);
}

/* Shapes of the sweep: the seeds' anisotropic one, small and large alpha, anisotropy 1:10 rotated, skews to 0.5 rad
 * with small alpha (where G1 reaches 1 and E falls to 1e-4). */
static const shape_params sweep[] = {
    {0.15, 0.5, 0, 0, 0},    {0.01, 0.01, 0, 0, 0},       {0.05, 0.05, 0, 0, 0},
    {2.0, 2.0, 0, 0, 0},     {1.0, 0.1, 0, 0, 0.7},       {0.3, 0.1, 0.4, -0.3, 1.0},
    {0.6, 0.6, 0.5, 0.5, 0}, {0.05, 0.5, 0.5, -0.5, 2.0}, {0.001, 0.003, 0.1, 0.2, 0},
};

static void against_quadrature_over_w(void **state)
{
    (void)state;
    const double ths[] = {0.0, 0.5, 1.2, 1.5, 89.5 * GGX_PI / 180};
    double worst = 0.0;
    int n = 0;
    for (size_t i = 0; i < sizeof sweep / sizeof sweep[0]; i++) {
        ggx_shape s;
        make_shape(&s, sweep[i]);
        for (int j = 0; j < 5; j++)
            for (int hc = 0; hc < 2; hc++) {
                ggx_vec3 v = t_dir(ths[j], 0.7);
                double e = albedo_of(&s, v, hc), ref = albedo_over_w(&s, v, hc);
                CHECK_CLOSE(e, ref, 0, PROMISE, "shape (%g,%g,%g,%g,%g) view %g %s", sweep[i].ax, sweep[i].ay,
                            sweep[i].tx, sweep[i].ty, sweep[i].tz, ths[j], hc ? "height-correlated" : "separable");
                CHECK(e >= 0 && e <= 1, "range");
                worst = fmax(worst, fabs(e - ref));
                n++;
            }
    }
    /* Negative control: the reference tells the two maskings apart where they differ by far less than 1e-3. */
    ggx_shape s;
    CHECK(ggx_shape_iso(&s, 0.5) == GGX_OK, "shape");
    ggx_vec3 v = t_dir(1.0, 0.3);
    double d = fabs(albedo_over_w(&s, v, 0) - ggx_albedo_height_correlated(&s, v));
    CHECK(d > 100 * PROMISE, "the check cannot tell separable from height-correlated G (%.3g)", d);
    printf("%d albedos against quadrature over w: largest difference %.2e (separable vs correlated: %.2e)\n", n, worst,
           d);
}

/* ---- the rough dielectric: ggx_bsdf_albedo ---- */
#define BSDF_PROMISE 1e-5

/* int f(v -> w) |w.z| dw over one side (side = +1 above, -1 below) by nested adaptive quadrature in (theta, phi)
 * about the normal of that side, with break points at the lobe's peak: the mirror direction on v's side, the
 * direction refracted through n on the other. */
typedef struct bq_ctx {
    const ggx_shape *s;
    ggx_vec3 v;
    double eta, theta, side, peak_phi;
} bq_ctx;

static double bq_phi(double phi, void *vc)
{
    bq_ctx *c = vc;
    ggx_vec3 w = t_dir(c->theta, phi);
    w.z *= c->side;
    return ggx_bsdf_eval(c->s, c->eta, c->v, w, GGX_RADIANCE) * fabs(w.z) * sin(c->theta);
}

static double bq_theta(double theta, void *vc)
{
    bq_ctx *c = vc;
    c->theta = theta;
    return quad_adapt(bq_phi, c, c->peak_phi - GGX_PI, c->peak_phi, 1e-11) +
           quad_adapt(bq_phi, c, c->peak_phi, c->peak_phi + GGX_PI, 1e-11);
}

static double bsdf_side_over_w(const ggx_shape *s, double eta, ggx_vec3 v, double side)
{
    int same = (side > 0) == (v.z > 0);
    double tv = acos(fabs(v.z)), tp = tv;
    if (!same) { /* Snell through n: sin t = sin tv * eta_v / eta_t */
        double rel = v.z > 0 ? 1 / eta : eta, st = sin(tv) * rel;
        tp = st < 1 ? asin(st) : 0.5 * GGX_PI;
    }
    bq_ctx c = {s, v, eta, 0, side, atan2(-v.y, -v.x) + (same ? 0 : GGX_PI)};
    return quad_adapt(bq_theta, &c, 0.0, tp, 1e-10) + quad_adapt(bq_theta, &c, tp, 0.5 * GGX_PI, 1e-10);
}

static void bsdf_albedo_deterministic(void **state)
{
    (void)state;
    /* eta = 1: no reflection (F = 0) and transmission straight through every facet: T = G1(u)^2 / G1_smith(u), the
     * limit of the BSDF's albedo (the BSDF itself is a delta there). For unskewed shapes G1(u). */
    const shape_params eq1[] = {{0.3, 0.3, 0, 0, 0}, {0.1, 0.6, 0, 0, 1.0}, {0.2, 0.5, 0.5, -0.3, 0.4}};
    double worst = 0.0;
    for (int i = 0; i < 3; i++) {
        ggx_shape s;
        make_shape(&s, eq1[i]);
        for (int j = 0; j < 4; j++) {
            ggx_vec3 v = t_dir(0.1 + 0.45 * j, 0.7 + j);
            if (j & 1) v.z = -v.z;
            ggx_vec3 u = v.z > 0 ? v : t_vec(-v.x, -v.y, -v.z); /* sgn(v.z) v */
            double r, t, e = ggx_bsdf_albedo(&s, 1.0, v, &r, &t);
            double g = ggx_g1(&s, u, u), want = g * g / ggx_g1_smith(&s, u);
            CHECK(r <= 1e-12 && e == r + t, "eta = 1 reflects nothing (F = 0 up to rounding): R = %g", r);
            CHECK_CLOSE(t, want, 0, BSDF_PROMISE, "eta = 1, shape %d, view %d", i, j);
            worst = fmax(worst, fabs(t - want));
        }
    }
    /* against quadrature of ggx_bsdf_eval over both sides */
    const shape_params sh[] = {{0.3, 0.3, 0, 0, 0}, {0.2, 0.6, 0, 0, 0.5}, {0.4, 0.25, 0.4, -0.3, 1.0}};
    const double etas[] = {1.5, 1 / 1.5, 1.33};
    double worst_q = 0.0;
    for (int i = 0; i < 3; i++) {
        ggx_shape s;
        make_shape(&s, sh[i]);
        for (int j = 0; j < 4; j++) {
            double eta = etas[(i + j) % 3];
            ggx_vec3 v = t_dir(0.2 + 0.4 * j, 0.3 + j);
            if (j >= 2) v.z = -v.z;
            double r, t, e = ggx_bsdf_albedo(&s, eta, v, &r, &t);
            double side = v.z > 0 ? 1 : -1;
            double rq = bsdf_side_over_w(&s, eta, v, side), tq = bsdf_side_over_w(&s, eta, v, -side);
            /* Light from the denser side: the map from facets to refracted directions folds at the critical angle,
             * where the transmitted lobe has an integrable 1 / sqrt edge in w that the quadrature over w resolves
             * only to ~1e-5 (at grazing: 1.6e-5, while 4e8 Monte Carlo samples agree with ggx_bsdf_albedo to 7e-7,
             * docs/design/albedo.md). There the reference is trusted to 1e-4. */
            double rel = v.z > 0 ? eta : 1 / eta, ref_tol = rel < 1 ? 1e-4 : BSDF_PROMISE;
            CHECK_CLOSE(r, rq, 0, ref_tol, "R, shape %d, eta %g, view %d", i, eta, j);
            CHECK_CLOSE(t, tq, 0, ref_tol, "T, shape %d, eta %g, view %d", i, eta, j);
            CHECK(e <= 1 && e == r + t, "R + T = %g", e);
            worst_q = fmax(worst_q, fmax(fabs(r - rq), fabs(t - tq)));
            printf("  shape %d eta %.3f view (%.3f, %.3f, %.3f): R %.9f (over w %+.1e), T %.9f (over w %+.1e)\n", i,
                   eta, v.x, v.y, v.z, r, r - rq, t, t - tq);
        }
    }
    /* A skewed shape and a view whose sphere-space view A'u points below the horizon: the lune's meridians then
     * enter it part-way, where the integrand jumps (only refraction leaves a horizontal facet). Without that point
     * as a break point the quadrature ran into its panel limit: T was 1.07e-5 off the quadrature over w for eta 1.5
     * and 2.2e-5 for 1 / 1.5, and a call took up to a second. Now 3.4e-7 and 1.6e-7; eta 1.5 is held to 2e-6, six
     * times that, so that a partial regression fails too. */
    {
        ggx_shape s;
        make_shape(&s, (shape_params){0.05, 0.3, -0.5, 0.5, 0});
        ggx_vec3 v = t_dir(1.35, 1.5);
        double apz = s.a[2][0] * v.x + s.a[2][1] * v.y + s.a[2][2] * v.z;
        CHECK(apz < 0, "the case lost its point: (A'u).z = %g", apz);
        for (int k = 0; k < 2; k++) {
            double eta = k ? 1 / 1.5 : 1.5, r, t;
            ggx_bsdf_albedo(&s, eta, v, &r, &t);
            double rq = bsdf_side_over_w(&s, eta, v, 1), tq = bsdf_side_over_w(&s, eta, v, -1);
            double ref_tol = k ? 1e-4 : 2e-6; /* k = 1: light from the denser side, as above */
            CHECK_CLOSE(r, rq, 0, ref_tol, "R, A'u below the horizon, eta %g", eta);
            CHECK_CLOSE(t, tq, 0, ref_tol, "T, A'u below the horizon, eta %g", eta);
            worst_q = fmax(worst_q, fmax(fabs(r - rq), fabs(t - tq)));
            printf("  A'u below the horizon, eta %.3f: R %.9f (over w %+.1e), T %.9f (over w %+.1e)\n", eta, r, r - rq,
                   t, t - tq);
        }
    }
    /* edges */
    ggx_shape s;
    make_shape(&s, (shape_params){0.3, 0.3, 0, 0, 0});
    double r = 7, t = 7;
    CHECK(ggx_bsdf_albedo(&s, 1.5, t_vec(1, 0, 0), &r, &t) == 0 && r == 0 && t == 0, "horizon");
    CHECK(ggx_bsdf_albedo(&s, 0.0, t_vec(0, 0, 1), &r, &t) == 0 && r == 0 && t == 0, "eta 0");
    CHECK(ggx_bsdf_albedo(&s, NAN, t_vec(0, 0, 1), NULL, NULL) == 0, "eta NaN");
    CHECK(ggx_bsdf_albedo(&s, 1.5, t_vec(NAN, 0, 1), NULL, NULL) == 0, "NaN view");
    CHECK(ggx_bsdf_albedo(NULL, 1.5, t_vec(0, 0, 1), &r, &t) == 0 && r == 0 && t == 0, "NULL shape");
    CHECK(ggx_bsdf_albedo(&s, 1.5, t_vec(0, 0, 5), NULL, NULL) == ggx_bsdf_albedo(&s, 1.5, t_vec(0, 0, 1), NULL, NULL),
          "v normalised");
    printf("bsdf albedo: eta = 1 closed form %.2e, against quadrature over w %.2e\n", worst, worst_q);
}

/* Monte Carlo with ggx_sample_bsdf in the importance mode, whose weight is f(v -> w) |w.z| / pdf: the mean weights
 * of reflected and transmitted samples are R and T. Within 5 standard errors + 1e-5. */
static void bsdf_albedo_monte_carlo(void **state)
{
    (void)state;
    const shape_params sh[] = {{0.05, 0.05, 0, 0, 0}, {0.1, 0.5, 0, 0, 0.3}, {0.2, 0.6, 0.4, 0.2, 1.0}};
    const double etas[] = {1.5, 1 / 1.5, 1.33};
    long n = (long)(1e6 * test_scale());
    for (int i = 0; i < 3; i++) {
        ggx_shape s;
        make_shape(&s, sh[i]);
        for (int j = 0; j < 4; j++) {
            double eta = etas[(i + j) % 3];
            ggx_vec3 v = t_dir(j < 2 ? 0.5 : 1.4, 0.7);
            if (j & 1) v.z = -v.z;
            double r, t;
            ggx_bsdf_albedo(&s, eta, v, &r, &t);
            rng g = {(uint64_t)(100 + 10 * i + j)};
            double sr = 0, sr2 = 0, st = 0, st2 = 0;
            for (long k = 0; k < n; k++) {
                double u1 = rng_uniform(&g), u2 = rng_uniform(&g), u3 = rng_uniform(&g);
                ggx_sample x = ggx_sample_bsdf(&s, eta, v, u1, u2, u3, GGX_IMPORTANCE);
                if (x.event == GGX_EVENT_REFLECT) sr += x.weight, sr2 += x.weight * x.weight;
                if (x.event == GGX_EVENT_TRANSMIT) st += x.weight, st2 += x.weight * x.weight;
            }
            double mr = sr / (double)n, mt = st / (double)n;
            double er = sqrt(fmax(0, sr2 / (double)n - mr * mr) / (double)n),
                   et = sqrt(fmax(0, st2 / (double)n - mt * mt) / (double)n);
            CHECK_CLOSE(r, mr, 0, 5 * er + 1e-5, "R, shape %d, eta %g, view %d", i, eta, j);
            CHECK_CLOSE(t, mt, 0, 5 * et + 1e-5, "T, shape %d, eta %g, view %d", i, eta, j);
        }
    }
}

/* Monte Carlo with ggx_sample_brdf (F = 1): the mean weight is E(v), a different code path (the sampler, its pdf,
 * the BRDF); and for E_avg, views drawn with density v.z / pi. Within 5 standard errors. */
static void against_monte_carlo(void **state)
{
    (void)state;
    ggx_fresnel f;
    ggx_fresnel_one(&f);
    rng r = {2024};
    long N = (long)(400000 * test_scale());
    double dn = (double)N;
    double worst = 0.0;
    for (size_t i = 0; i < sizeof sweep / sizeof sweep[0]; i++) {
        ggx_shape s;
        make_shape(&s, sweep[i]);
        ggx_vec3 v = t_dir(1.0, 2.0);
        double s1 = 0, s2 = 0;
        for (long k = 0; k < N; k++) {
            double w = ggx_sample_brdf(&s, &f, v, rng_uniform(&r), rng_uniform(&r)).weight;
            s1 += w;
            s2 += w * w;
        }
        double m = s1 / dn, se = sqrt(fmax(s2 / dn - m * m, 0) / dn) + 1e-12, e = ggx_albedo(&s, v);
        /* + 1e-5: at alpha 1e-3 the weights are ~1 with a standard error of 1e-6, and the sampler's weights differ
         * from f cos / true density by a few 1e-6 there (the quadrature over w confirms ggx_albedo to 1e-9) */
        CHECK(fabs(e - m) <= 5 * se + 1e-5, "shape %zu: E %.7f, Monte Carlo %.7f +- %.1e", i, e, m, se);
        worst = fmax(worst, fabs(e - m) / se);
    }
    printf("Monte Carlo E (%ld samples each): largest deviation %.2f standard errors\n", N, worst);
}

/* E_avg against Monte Carlo: views drawn with density v.z / pi, then a BRDF sample. A skewed E_avg takes about
 * 15 s (docs/design/albedo.md), so part 3 runs it alone; the quick tier's skewed shape is a rougher one (about 6 s). */
static int avg_first, avg_last;
static void average_against_monte_carlo(void **state)
{
    (void)state;
    ggx_fresnel f;
    ggx_fresnel_one(&f);
    rng r = {2025};
    long N = (long)(1000000 * test_scale());
    double dn = (double)N, worst = 0.0;
    const shape_params avg_shapes[] = {
        {0.15, 0.5, 0, 0, 0}, {0.3, 0.3, 0, 0, 0}, {1.0, 0.1, 0, 0, 0.7}, {0.3, 0.1, 0.4, -0.3, 1.0}};
    const shape_params quick_skewed = {0.3, 0.6, 0.4, -0.3, 0.7};
    for (int i = avg_first; i <= avg_last; i++) {
        ggx_shape s;
        make_shape(&s, i == 3 && test_quick() ? quick_skewed : avg_shapes[i]);
        for (int hc = 0; hc < 2 - (i == 3); hc++) {
            double s1 = 0, s2 = 0;
            for (long k = 0; k < N; k++) {
                ggx_vec2 d = ggx_disk_concentric(rng_uniform(&r), rng_uniform(&r)); /* cosine-weighted view */
                double z2 = 1 - d.x * d.x - d.y * d.y;
                ggx_vec3 v = t_vec(d.x, d.y, sqrt(z2 > 0 ? z2 : 0));
                double w;
                if (!hc) {
                    w = ggx_sample_brdf(&s, &f, v, rng_uniform(&r), rng_uniform(&r)).weight;
                } else { /* height-correlated: VNDF samples weighted by G2 / G1(v) */
                    ggx_vec3 m = ggx_sample_vndf(&s, v, rng_uniform(&r), rng_uniform(&r));
                    ggx_vec3 wo = ggx_reflect(v, m);
                    w = wo.z > 0 ? ggx_g2_height_correlated(&s, v, wo, m) / ggx_g1_smith(&s, v) : 0.0;
                }
                s1 += w;
                s2 += w * w;
            }
            double m = s1 / dn, se = sqrt(fmax(s2 / dn - m * m, 0) / dn) + 1e-12;
            double e = hc ? ggx_albedo_avg_height_correlated(&s) : ggx_albedo_avg(&s);
            CHECK(fabs(e - m) <= 5 * se, "E_avg shape %d %s: %.7f, Monte Carlo %.7f +- %.1e", i,
                  hc ? "height-correlated" : "separable", e, m, se);
            worst = fmax(worst, fabs(e - m) / se);
        }
    }
    printf("Monte Carlo E_avg (%ld samples each): largest deviation %.2f standard errors\n", N, worst);
}

/* E_avg of a shape rotated by theta_z only equals the unrotated shape's (E(phi) is shifted); the isotropic path
 * (E independent of phi) equals the general one. */
static void average_symmetries(void **state)
{
    (void)state;
    ggx_shape a, b;
    CHECK(ggx_shape_aniso(&a, 0.2, 0.6) == GGX_OK, "shape");
    CHECK(ggx_shape_ellipsoid(&b, 0.2, 0.6, 0, 0, 1.1) == GGX_OK, "shape");
    CHECK_CLOSE(ggx_albedo_avg(&a), ggx_albedo_avg(&b), 0, PROMISE, "theta_z rotation");
    /* A = S Rz(theta_z): D_b(m) = D_a(Rz m), so E_b(v) = E_a(Rz v) */
    CHECK_CLOSE(ggx_albedo(&a, t_dir(1.0, 0.3)), ggx_albedo(&b, t_dir(1.0, 0.3 - 1.1)), 0, PROMISE, "E rotates");
    /* nearly isotropic anisotropic shape: the quarter-turn rule must agree with the isotropic shortcut */
    CHECK(ggx_shape_aniso(&a, 0.4, 0.4 * (1 + 1e-9)) == GGX_OK, "shape");
    CHECK(ggx_shape_iso(&b, 0.4) == GGX_OK, "shape");
    CHECK_CLOSE(ggx_albedo_avg(&a), ggx_albedo_avg(&b), 0, PROMISE, "isotropic shortcut");
    /* a scaled matrix describes the same distribution */
    static const double Ac[3][3] = {{0.3e-3, 0, 0}, {0, 0.7e-3, 0.1e-3}, {0, 0, 1e-3}},
                        Bc[3][3] = {{0.3e3, 0, 0}, {0, 0.7e3, 0.1e3}, {0, 0, 1e3}};
    CHECK(ggx_shape_matrix(&a, Ac) == GGX_OK && ggx_shape_matrix(&b, Bc) == GGX_OK, "matrix shapes");
    CHECK_CLOSE(ggx_albedo(&a, t_dir(0.8, 1.0)), ggx_albedo(&b, t_dir(0.8, 1.0)), 0, PROMISE, "scale");
}

/* The domain: views at and below the horizon, NaN, zero and non-unit vectors, grazing views, extreme alpha. */
static void domain_edges(void **state)
{
    (void)state;
    ggx_shape s;
    CHECK(ggx_shape_aniso(&s, 0.15, 0.5) == GGX_OK, "shape");
    const ggx_vec3 zero = {0, 0, 0}, below = {0.6, 0, -0.8}, horizon = {1, 0, 0}, nanv = {NAN, 0, 1},
                   infv = {0, INFINITY, 1};
    for (int hc = 0; hc < 2; hc++) {
        CHECK(albedo_of(&s, zero, hc) == 0 && albedo_of(&s, below, hc) == 0 && albedo_of(&s, horizon, hc) == 0,
              "outside the domain gives 0");
        CHECK(albedo_of(&s, nanv, hc) == 0 && albedo_of(&s, infv, hc) == 0, "NaN and Inf give 0");
        ggx_vec3 v = t_dir(1.1, 0.4);
        CHECK(albedo_of(&s, t_scale(v, 37.0), hc) == albedo_of(&s, v, hc), "only the direction matters");
    }
    rng r = {5};
    const double alphas[][2] = {{1e-4, 1e-4}, {1e-4, 1e-1}, {1e4, 1e4}, {10, 0.01}};
    for (int i = 0; i < 4; i++) {
        CHECK(ggx_shape_aniso(&s, alphas[i][0], alphas[i][1]) == GGX_OK, "shape");
        for (int j = 0; j < 6; j++) {
            ggx_vec3 v = j < 2 ? t_dir(0.5 * GGX_PI - pow(10.0, -3 - 3 * j), 0.3) : random_view(&r);
            for (int hc = 0; hc < 2; hc++) {
                double e = albedo_of(&s, v, hc);
                CHECK(e >= 0 && e <= 1, "alpha (%g, %g) view z %g: E = %g", alphas[i][0], alphas[i][1], v.z, e);
            }
        }
    }
    /* smallest alpha: E = 1 - the masking loss, which vanishes except at grazing */
    CHECK(ggx_shape_iso(&s, 1e-4) == GGX_OK, "shape");
    CHECK_CLOSE(ggx_albedo(&s, t_dir(0.7, 0)), 1.0, 0, 1e-6, "mirror-like");
}

/* Thread safety: the quadrature's node tables are computed once (pthread_once); concurrent first calls give the
 * same values as a serial call. */
typedef struct thread_arg {
    double out[4];
} thread_arg;
static void *thread_main(void *p)
{
    thread_arg *a = p;
    ggx_shape s;
    ggx_shape_aniso(&s, 0.15, 0.5);
    for (int i = 0; i < 4; i++) a->out[i] = ggx_albedo(&s, t_dir(0.3 * i, 0.2));
    return NULL;
}
static void threads(void **state)
{
    (void)state;
    enum { NT = 8 };
    pthread_t th[NT];
    thread_arg args[NT];
    for (int i = 0; i < NT; i++) CHECK(pthread_create(&th[i], NULL, thread_main, &args[i]) == 0, "thread");
    for (int i = 0; i < NT; i++) pthread_join(th[i], NULL);
    ggx_shape s;
    ggx_shape_aniso(&s, 0.15, 0.5);
    for (int i = 0; i < NT; i++)
        for (int k = 0; k < 4; k++)
            CHECK(args[i].out[k] == ggx_albedo(&s, t_dir(0.3 * k, 0.2)), "thread %d view %d differs", i, k);
}

/* Parts, run as separate ctest entries: 1 the deterministic checks, 2 Monte Carlo of E and of
 * the unskewed E_avg, 3 the skewed E_avg; 0 everything. */
int main(int argc, char **argv)
{
    int part = argc > 1 ? atoi(argv[1]) : 0;
    const struct CMUnitTest first[] = {
        cmocka_unit_test(threads),
        cmocka_unit_test(closed_forms_alpha_one),
        cmocka_unit_test(domain_edges),
        cmocka_unit_test(average_symmetries),
        cmocka_unit_test(against_quadrature_over_w),
        cmocka_unit_test(bsdf_albedo_deterministic),
    };
    const struct CMUnitTest second[] = {cmocka_unit_test(against_monte_carlo),
                                        cmocka_unit_test(average_against_monte_carlo),
                                        cmocka_unit_test(bsdf_albedo_monte_carlo)};
    const struct CMUnitTest third[] = {cmocka_unit_test(average_against_monte_carlo)};
    int rc = 0;
    if (part == 0 || part == 1) rc |= cmocka_run_group_tests_name("deterministic", first, NULL, NULL);
    avg_first = 0;
    avg_last = 2;
    if (part == 0 || part == 2) rc |= cmocka_run_group_tests_name("Monte Carlo", second, NULL, NULL);
    avg_first = avg_last = 3;
    if (part == 0 || part == 3) rc |= cmocka_run_group_tests_name("skewed average", third, NULL, NULL);
    return rc;
}
