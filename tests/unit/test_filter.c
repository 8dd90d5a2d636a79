/* Normal-map filtering (ggx_filter.h): the texel's lobe, the filter of a constant map, EM's monotone objective, the
 * optimum against perturbations and the engines' baselines, the rule's accuracy, weights, bad input and threads.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "ggx/ggx_filter.h"
#include "normal_filters.h"
#include "testlib.h"

static ggx_vec3 random_normal(rng *r, double max_tilt)
{
    double th = rng_range(r, 0.0, max_tilt), ph = rng_range(r, 0.0, 2.0 * GGX_PI);
    return t_dir(th, ph);
}

static void lobe_ok(ggx_shape *s, ggx_vec3 n, double ax, double ay, double phi)
{
    ggx_status st = ggx_texel_lobe(s, n, ax, ay, phi);
    CHECK(st == GGX_OK, "ggx_texel_lobe(%g %g %g, %g, %g, %g): %s", n.x, n.y, n.z, ax, ay, phi, ggx_status_str(st));
}

/* P22 of the GGX of (ax, ay) with its x axis at phi, translated by t: written out. */
static double p22_translated(const double t[2], double ax, double ay, double phi, double x, double y)
{
    double dx = x - t[0], dy = y - t[1], c = cos(phi), s = sin(phi);
    double u = (c * dx + s * dy) / ax, v = (-s * dx + c * dy) / ay;
    double q = 1.0 + u * u + v * v;
    return 1.0 / (GGX_PI * ax * ay * q * q);
}

/* The texel's lobe is GGX translated to the slope of its normal: P22 against the written-out form at random slopes
 * near and far from the lobe; the normal's length does not matter; n = +z with phi = 0 is ggx_shape_aniso. */
static void texel_lobe_form(void **state)
{
    (void)state;
    rng r = {11};
    double worst = 0.0;
    for (int i = 0; i < 2000; i++) {
        ggx_vec3 n = random_normal(&r, 1.4);
        double ax = exp(rng_range(&r, log(1e-3), log(2.0))), ay = exp(rng_range(&r, log(1e-3), log(2.0)));
        double phi = rng_range(&r, -GGX_PI, GGX_PI), t[2] = {-n.x / n.z, -n.y / n.z};
        ggx_shape s, s2;
        lobe_ok(&s, n, ax, ay, phi);
        lobe_ok(&s2, t_scale(n, i % 2 ? 1e-3 : 1e3), ax, ay, phi);
        for (int k = 0; k < 8; k++) {
            double sc = k < 4 ? fmax(ax, ay) : 10.0 * fmax(ax, ay);
            double x = t[0] + sc * rng_range(&r, -3, 3), y = t[1] + sc * rng_range(&r, -3, 3);
            double tol = slopes_bound(ax, ay); /* ggx_shape_from_slopes' bound */
            double want = p22_translated(t, ax, ay, phi, x, y), got = ggx_p22(&s, x, y);
            worst = fmax(worst, fabs(got - want) / want / tol);
            CHECK_CLOSE(got, want, tol, 0, "lobe (%g %g %g) alphas %g %g phi %g at (%g, %g)", n.x, n.y, n.z, ax, ay,
                        phi, x, y);
            CHECK_CLOSE(ggx_p22(&s2, x, y), got, tol, 0, "the normal's length changed the lobe");
        }
    }
    printf("texel lobes: P22 within %.2g of the bound 1e-12 + 2e-15 kappa^2 of GGX translated\n", worst);
    ggx_shape a, b;
    lobe_ok(&a, t_vec(0, 0, 1), 0.2, 0.6, 0.0);
    CHECK(ggx_shape_aniso(&b, 0.2, 0.6) == GGX_OK, "aniso");
    for (int k = 0; k < 64; k++) {
        ggx_vec3 m = random_normal(&r, 1.5);
        CHECK_CLOSE(ggx_ndf(&a, m), ggx_ndf(&b, m), 1e-13, 0, "n = +z, phi = 0 is not ggx_shape_aniso");
    }
}

static void texel_lobe_errors(void **state)
{
    (void)state;
    ggx_shape s, keep;
    lobe_ok(&keep, t_vec(0.1, 0.2, 1), 0.3, 0.3, 0);
    s = keep;
    const ggx_vec3 up = {0, 0, 1};
    CHECK(ggx_texel_lobe(NULL, up, 0.3, 0.3, 0) == GGX_ERR_NULL, "NULL out");
    CHECK(ggx_texel_lobe(&s, t_vec(NAN, 0, 1), 0.3, 0.3, 0) == GGX_ERR_NONFINITE, "NaN normal");
    CHECK(ggx_texel_lobe(&s, t_vec(0, 0, INFINITY), 0.3, 0.3, 0) == GGX_ERR_NONFINITE, "infinite normal");
    CHECK(ggx_texel_lobe(&s, up, NAN, 0.3, 0) == GGX_ERR_NONFINITE, "NaN alpha");
    CHECK(ggx_texel_lobe(&s, up, 0.3, 0.3, INFINITY) == GGX_ERR_NONFINITE, "infinite phi");
    CHECK(ggx_texel_lobe(&s, t_vec(0, 0, 0), 0.3, 0.3, 0) == GGX_ERR_RANGE, "zero normal");
    CHECK(ggx_texel_lobe(&s, t_vec(1, 0, 0), 0.3, 0.3, 0) == GGX_ERR_RANGE, "normal in the tangent plane");
    CHECK(ggx_texel_lobe(&s, t_vec(0, 0.3, -1), 0.3, 0.3, 0) == GGX_ERR_RANGE, "normal below");
    CHECK(ggx_texel_lobe(&s, t_vec(1, 0, 1e-300), 0.3, 0.3, 0) == GGX_ERR_RANGE, "slope beyond the matrix scale");
    CHECK(ggx_texel_lobe(&s, up, 0.0, 0.3, 0) == GGX_ERR_ALPHA, "alpha 0");
    CHECK(ggx_texel_lobe(&s, up, 0.3, -1, 0) == GGX_ERR_ALPHA, "alpha < 0");
    CHECK(ggx_texel_lobe(&s, up, 0.3, 2 * GGX_ALPHA_MAX, 0) == GGX_ERR_ALPHA, "alpha above the maximum");
    CHECK(memcmp(&s, &keep, sizeof s) == 0, "out changed on error");
    /* alphas below the minimum are raised to it */
    ggx_shape lo, mn;
    lobe_ok(&lo, up, 1e-9, 1e-9, 0);
    lobe_ok(&mn, up, GGX_ALPHA_MIN, GGX_ALPHA_MIN, 0);
    CHECK_CLOSE(ggx_p22(&lo, 1e-5, 0), ggx_p22(&mn, 1e-5, 0), 1e-12, 0, "alpha 1e-9 is not raised to GGX_ALPHA_MIN");
}

/* The texels of a map: each the slopes of ggx_texel_lobe's lobe, the refused normals rejected with weight 0 and the
 * placeholder, counted; a bad roughness writes nothing. */
static void texel_lobes(void **state)
{
    (void)state;
    const ggx_vec3 n[6] = {{0.2, -0.1, 1}, {NAN, 0, 1}, {0, 0, 0}, {0.3, 0, -1}, {1, 0, 0}, {0, 0, 5}};
    double lobes[6 * GGX_LOBE_PARAMS], w[6], keep[6 * GGX_LOBE_PARAMS];
    size_t rejected = 99;
    CHECK(ggx_texel_lobes(lobes, w, n, 6, 0.2, 0.4, 0.3, &rejected) == GGX_OK && rejected == 4, "%zu rejected",
          rejected);
    for (int i = 0; i < 6; i++) {
        const double *c = lobes + GGX_LOBE_PARAMS * i;
        ggx_shape s;
        ggx_status st = ggx_texel_lobe(&s, n[i], 0.2, 0.4, 0.3);
        CHECK(w[i] == (st == GGX_OK), "texel %d: weight %g, ggx_texel_lobe %s", i, w[i], ggx_status_str(st));
        if (st == GGX_OK) {
            double t[2], sg[3];
            ggx_shape_slopes(&s, t, sg);
            CHECK_CLOSE(c[0], t[0], 1e-14, 1e-15, "t_x");
            CHECK_CLOSE(c[2], sg[0], 1e-13, 0, "sigma_xx");
            CHECK_CLOSE(c[3], sg[1], 1e-12, 1e-15, "sigma_xy");
        } else CHECK(c[0] == 0 && c[1] == 0 && c[2] == 1 && c[3] == 0 && c[4] == 1, "placeholder of texel %d", i);
    }
    memcpy(keep, lobes, sizeof keep);
    CHECK(ggx_texel_lobes(lobes, w, n, 6, 0.0, 0.4, 0.3, NULL) == GGX_ERR_ALPHA, "alpha 0");
    CHECK(ggx_texel_lobes(lobes, w, n, 6, 0.2, NAN, 0.3, NULL) == GGX_ERR_NONFINITE, "NaN alpha");
    CHECK(memcmp(keep, lobes, sizeof keep) == 0, "written on error");
    CHECK(ggx_texel_lobes(NULL, w, n, 6, 0.2, 0.4, 0, NULL) == GGX_ERR_NULL, "NULL lobes");
    CHECK(ggx_texel_lobes(lobes, w, n, 0, 0.2, 0.4, 0, &rejected) == GGX_OK && rejected == 0, "no texels");
    /* exactly what ggx_texel_lobe refuses: a steep normal with a tiny alpha is not a shape, nor are alphas far apart */
    const ggx_vec3 steep[2] = {{1, 0, 0.03}, {0, 0, 1}};
    ggx_shape tmp;
    CHECK(ggx_texel_lobe(&tmp, steep[0], 1e-4, 1e-4, 0) != GGX_OK, "the steep lobe is a shape");
    CHECK(ggx_texel_lobes(lobes, w, steep, 2, 1e-4, 1e-4, 0, &rejected) == GGX_OK && rejected == 1 && w[0] == 0 &&
              w[1] == 1,
          "steep normal: %zu rejected", rejected);
    CHECK(ggx_texel_lobe(&tmp, steep[1], 1e-4, 1e4, 0) != GGX_OK, "alphas 1e-4 and 1e4 make a shape");
    CHECK(ggx_texel_lobes(lobes, w, steep, 2, 1e-4, 1e4, 0, NULL) != GGX_OK, "alphas 1e-4 and 1e4 accepted");
}

/* A roughness map: texel i has ggx_texel_lobe's lobe of its own roughness (every texel also checked against
 * ggx_texel_lobe's verdict on a sweep from alpha 1e-4 to 1e4 and normals to 1e-6 above the horizon, where
 * ggx_texel_lobes' fast acceptance must agree with ggx_shape_from_slopes), 0 is raised to GGX_ALPHA_MIN, and a
 * negative, NaN, infinite or too large value rejects the texel. */
static void roughness_map(void **state)
{
    (void)state;
    enum { N = 9 };
    const ggx_vec3 n[N] = {{0.2, -0.1, 1}, {0, 0, 1}, {0.3, 0.3, 1}, {0, 0.1, 1}, {0.1, 0, 1},
                           {0, 0, 1},      {0, 0, 1}, {0, 0, 1},     {0, 0, 1}};
    const double ax[N] = {0.2, 1e-4, 0.0, 3.0, -0.1, NAN, INFINITY, 2e4, 0.5};
    const double ay[N] = {0.4, 1e-4, 0.0, 0.3, 0.2, 0.2, 0.2, 0.2, -0.5};
    double lobes[N * GGX_LOBE_PARAMS], w[N];
    size_t rejected = 99;
    for (int aniso = 0; aniso < 2; aniso++) {
        CHECK(ggx_texel_lobes_roughness(lobes, w, n, ax, aniso ? ay : NULL, N, 0.3, &rejected) == GGX_OK, "map");
        CHECK(rejected == (aniso ? 5u : 4u), "%zu rejected", rejected);
        for (int i = 0; i < N; i++) {
            double x = fmax(ax[i], 1e-4), y = aniso ? fmax(ay[i], 1e-4) : x; /* fmax: NaN gives 1e-4, refused below */
            ggx_shape s;
            ggx_status st = isnan(ax[i]) || ax[i] < 0 || (aniso && ay[i] < 0) ? GGX_ERR_ALPHA
                                                                              : ggx_texel_lobe(&s, n[i], x, y, 0.3);
            CHECK(w[i] == (st == GGX_OK), "texel %d (aniso %d): weight %g, ggx_texel_lobe %s", i, aniso, w[i],
                  ggx_status_str(st));
            if (st != GGX_OK) continue;
            double c[GGX_LOBE_PARAMS], one[GGX_LOBE_PARAMS], w1;
            ggx_shape_slopes(&s, c, c + 2);
            CHECK(ggx_texel_lobes(one, &w1, &n[i], 1, x, y, 0.3, NULL) == GGX_OK && w1 == 1, "one texel");
            CHECK(memcmp(one, lobes + GGX_LOBE_PARAMS * i, sizeof one) == 0, "texel %d differs from ggx_texel_lobes",
                  i);
            for (int k = 0; k < GGX_LOBE_PARAMS; k++)
                CHECK_CLOSE(lobes[GGX_LOBE_PARAMS * i + k], c[k], 1e-12, 1e-15 * sqrt(c[2] * c[4]), "entry %d", k);
        }
    }
    double keep[N * GGX_LOBE_PARAMS];
    memcpy(keep, lobes, sizeof keep);
    CHECK(ggx_texel_lobes_roughness(lobes, w, n, ax, ay, N, NAN, NULL) == GGX_ERR_NONFINITE, "NaN phi");
    CHECK(ggx_texel_lobes_roughness(lobes, w, n, NULL, ay, N, 0, NULL) == GGX_ERR_NULL, "NULL alpha_x");
    CHECK(ggx_texel_lobes_roughness(lobes, NULL, n, ax, ay, N, 0, NULL) == GGX_ERR_NULL, "NULL weight");
    CHECK(memcmp(keep, lobes, sizeof keep) == 0, "written on error");
    /* the acceptance sweep: log-spaced alphas and tilts, both roughness paths against ggx_texel_lobe */
    int accepted = 0, refused = 0;
    for (int a = 0; a <= 32; a++)
        for (int b = 0; b <= 32; b += 4)
            for (int z = 0; z <= 24; z++) {
                double alx = pow(10.0, -4.0 + a / 4.0), aly = pow(10.0, -4.0 + b), nz = pow(10.0, -z / 4.0);
                ggx_vec3 m = {1.0, 0.5, nz};
                ggx_shape s;
                double c[GGX_LOBE_PARAMS], wt, wr;
                int ok = ggx_texel_lobe(&s, m, alx, aly, 0.7) == GGX_OK;
                CHECK(ggx_texel_lobes(c, &wt, &m, 1, alx, aly, 0.7, NULL) == GGX_OK || !ok, "texel_lobes");
                CHECK(ggx_texel_lobes_roughness(c, &wr, &m, &alx, &aly, 1, 0.7, NULL) == GGX_OK, "roughness");
                if (ggx_texel_lobes(c, &wt, &m, 1, alx, aly, 0.7, NULL) != GGX_OK) wt = 0;
                CHECK(wt == ok && wr == ok, "alpha %g, %g, n.z %g: ggx_texel_lobe %d, texel_lobes %g, roughness %g",
                      alx, aly, nz, ok, wt, wr);
                ok ? accepted++ : refused++;
            }
    CHECK(accepted > 100 && refused > 100, "the sweep crosses the boundary: %d accepted, %d refused", accepted,
          refused);
}

static double ndf_rel_diff(const ggx_shape *a, const ggx_shape *b, rng *r)
{
    double worst = 0.0;
    for (int k = 0; k < 64; k++) {
        ggx_vec3 m = k % 2 ? ggx_sample_ndf(b, rng_uniform(r), rng_uniform(r)) : random_normal(r, 1.5);
        double da = ggx_ndf(a, m), db = ggx_ndf(b, m);
        if (db > 0) worst = fmax(worst, fabs(da - db) / db);
    }
    return worst;
}

/* A constant map (n equal lobes, any weights) is filtered exactly: the rule integrates a lobe's E step at the lobe
 * itself exactly, so the lobe is EM's fixed point and its start; D equal to 1e-12, KL 0 to rounding, for every rule. */
static void constant_map(void **state)
{
    (void)state;
    rng r = {12};
    const int rules[][2] = {{2, 4}, {8, 16}, {32, 64}}; /* 2 x 4: the smallest rule accepted */
    double worst = 0.0;
    for (int c = 0; c < 24; c++) {
        ggx_vec3 n = random_normal(&r, c < 12 ? 0.8 : 1.4);
        double ax = exp(rng_range(&r, log(1e-3), log(2.0))), ay = c % 3 ? ax : exp(rng_range(&r, log(1e-3), log(2.0)));
        ggx_shape lobe[16];
        double w[16];
        lobe_ok(&lobe[0], n, ax, ay, rng_range(&r, 0, GGX_PI));
        int nl = c % 2 ? 16 : 1;
        for (int i = 0; i < nl; i++) lobe[i] = lobe[0], w[i] = rng_range(&r, 0.1, 3.0);
        for (int k = 0; k < 3; k++) {
            ggx_filter_options o = {0};
            o.radial_nodes = rules[k][0], o.angular_nodes = rules[k][1];
            ggx_shape f;
            ggx_filter_info info;
            CHECK(ggx_filter_lobes(&f, lobe, w, (size_t)nl, &o, &info) == GGX_OK, "filter");
            double bound = slopes_bound(ax, ay), d = ndf_rel_diff(&f, &lobe[0], &r) / bound;
            worst = fmax(worst, d);
            CHECK(d <= 1.0, "constant map (%g %g %g), alphas %g %g, %d lobes, rule %dx%d: D off by %.3g of the bound",
                  n.x, n.y, n.z, ax, ay, nl, rules[k][0], rules[k][1], d);
            CHECK(info.converged && info.iterations <= 3, "%d iterations", info.iterations);
            double kl;
            CHECK(ggx_filter_kl(&f, lobe, w, (size_t)nl, &o, &kl) == GGX_OK, "kl");
            /* a sum of log-density differences, each within D's bound */
            CHECK(fabs(kl) <= bound, "KL of the exact filter %.3g", kl);
        }
    }
    printf("constant maps: D of the filtered lobe within %.2g of the bound 1e-12 + 2e-15 kappa^2\n", worst);
}

/* Footprints: a two-tilt checkerboard (slopes +-tilt in x) and random bump maps (normals of a sum of random waves,
 * 4 to 64 texels). */
typedef struct footprint {
    const char *name;
    int n;
    ggx_shape lobe[64];
    ggx_vec3 normal[64];
    double w[64], alpha;
} footprint;

static void checkerboard(footprint *f, double tilt, double alpha)
{
    f->name = tilt < 0.5 ? "checker 0.3" : "checker 1", f->n = 2, f->alpha = alpha;
    f->normal[0] = t_normalize(t_vec(tilt, 0, 1)), f->normal[1] = t_normalize(t_vec(-tilt, 0, 1));
    for (int i = 0; i < 2; i++) lobe_ok(&f->lobe[i], f->normal[i], alpha, alpha, 0), f->w[i] = 1.0;
}

static void bumps(footprint *f, rng *r, int side, double amplitude, double alpha)
{
    f->name = "bumps", f->n = side * side, f->alpha = alpha;
    double kx[3], ky[3], ph[3];
    for (int j = 0; j < 3; j++)
        kx[j] = rng_range(r, -2, 2), ky[j] = rng_range(r, -2, 2), ph[j] = rng_range(r, 0, 2 * GGX_PI);
    for (int i = 0; i < f->n; i++) {
        double x = i % side, y = i / side, gx = 0, gy = 0;
        for (int j = 0; j < 3; j++) {
            double c = amplitude * cos(kx[j] * x + ky[j] * y + ph[j]);
            gx += c * kx[j], gy += c * ky[j];
        }
        f->normal[i] = t_normalize(t_vec(-gx, -gy, 1));
        lobe_ok(&f->lobe[i], f->normal[i], alpha, alpha, 0);
        f->w[i] = 1.0;
    }
}

/* The baselines (libs/verify/normal_filters.h) as shapes of the tangent frame: their lobes about the renormalised
 * mean normal, rotated from the shading frame; sigma, our fit's scale, for the one without skew. */
static void baseline(const footprint *f, int kind, const double sigma[3], ggx_shape *s)
{
    ggx_vec3 m = {0, 0, 0};
    double W = 0;
    for (int i = 0; i < f->n; i++) m = t_add(m, t_scale(f->normal[i], f->w[i])), W += f->w[i];
    nf_lobe b;
    CHECK(nf_baseline((nf_kind)kind, t_scale(m, 1.0 / W), f->alpha * f->alpha, sigma, &b) == 0, "baseline");
    CHECK(nf_tangent_shape(&b, s) == GGX_OK, "baseline shape");
}

static double kl_of(const ggx_shape *s, const footprint *f)
{
    double kl;
    ggx_filter_options o = {0};
    o.radial_nodes = 32, o.angular_nodes = 64;
    CHECK(ggx_filter_kl(s, f->lobe, f->w, (size_t)f->n, &o, &kl) == GGX_OK, "kl");
    return kl;
}

static void footprints(footprint *fs, int *count)
{
    rng r = {13};
    int n = 0;
    const double alphas[] = {0.05, 0.2, 0.5};
    for (int a = 0; a < 3; a++) checkerboard(&fs[n++], 0.3, alphas[a]);
    for (int a = 0; a < 3; a++) checkerboard(&fs[n++], 1.0, alphas[a]);
    for (int side = 2; side <= 8; side *= 2)
        for (int a = 0; a < 3; a++) bumps(&fs[n++], &r, side, 0.15, alphas[a]);
    *count = n;
}
enum { MAX_FOOTPRINTS = 16 };

/* EM never lowers the objective: the log-likelihood after k iterations, k = 1 to 40 (each run from the same start,
 * so run k ends at iterate k), never falls by more than the rounding of its sums. */
static void em_monotone(void **state)
{
    (void)state;
    footprint fs[MAX_FOOTPRINTS];
    int nf;
    footprints(fs, &nf);
    for (int i = 0; i < nf; i++) {
        double last = -HUGE_VAL;
        for (int k = 1; k <= 40; k++) {
            ggx_filter_options o = {0};
            o.max_iterations = k;
            ggx_shape s;
            ggx_filter_info info;
            CHECK(ggx_filter_lobes(&s, fs[i].lobe, fs[i].w, (size_t)fs[i].n, &o, &info) == GGX_OK, "filter");
            CHECK(info.log_likelihood >= last - 1e-13 * fabs(last),
                  "%s %d, alpha %g: iteration %d lowered log L from "
                  "%.17g to %.17g",
                  fs[i].name, fs[i].n, fs[i].alpha, k, last, info.log_likelihood);
            last = info.log_likelihood;
            if (info.iterations < k) break; /* converged before k */
        }
    }
}

/* The filter is the best ellipsoid: its KL from the mixture is below that of every shape 1e-3 away in any of the
 * five parameters (a local maximum of the objective: a wrong M step or sign moves it) and below every baseline's,
 * which are members of the family (ours without skew equals ours where the footprint's mean normal is n). The fast
 * mode gives up at most FAST_KL_EXCESS nats (ggx_filter.h) and stays below
 * every baseline. The margins are printed. */
#define FAST_KL_EXCESS 0.01 /* twice the most it gives up here (0.0049 nats: bumps of 4 texels, alpha 0.05) */
static void optimum_and_baselines(void **state)
{
    (void)state;
    footprint fs[MAX_FOOTPRINTS];
    int nf;
    footprints(fs, &nf);
    ggx_filter_options o = {0};
    o.radial_nodes = 32, o.angular_nodes = 64;
    for (int i = 0; i < nf; i++) {
        const footprint *f = &fs[i];
        ggx_shape s;
        ggx_filter_info info;
        CHECK(ggx_filter_lobes(&s, f->lobe, f->w, (size_t)f->n, &o, &info) == GGX_OK && info.converged, "filter");
        double ours = kl_of(&s, f), t[2], sg[3];
        ggx_shape_slopes(&s, t, sg);
        for (int p = 0; p < 5; p++)
            for (int sign = -1; sign <= 1; sign += 2) {
                double tp[2] = {t[0], t[1]}, sp[3] = {sg[0], sg[1], sg[2]}, h = 1e-3 * sign;
                if (p < 2) tp[p] += h * sqrt(sg[p == 0 ? 0 : 2]);
                else if (p == 3) sp[1] += h * sqrt(sg[0] * sg[2]);
                else sp[p - 2] *= 1.0 + h;
                ggx_shape q;
                CHECK(ggx_shape_from_slopes(&q, tp[0], tp[1], sp[0], sp[1], sp[2]) == GGX_OK, "perturbed");
                double kq = kl_of(&q, f);
                CHECK(kq > ours, "%s %d alpha %g: parameter %d moved by %g lowers KL %.12g to %.12g", f->name, f->n,
                      f->alpha, p, h, ours, kq);
            }
        /* the fast mode (ggx_filter.h): one iteration over 2 x 4 nodes per lobe */
        ggx_filter_options fast = {0};
        fast.tolerance = 1e-3, fast.threads = 3; /* kept by ggx_filter_options_fast */
        CHECK(ggx_filter_options_fast(&fast) == GGX_OK && fast.radial_nodes == 2 && fast.angular_nodes == 4 &&
                  fast.max_iterations == 1 && fast.tolerance == 1e-3 && fast.threads == 3,
              "ggx_filter_options_fast");
        CHECK(ggx_filter_options_fast(NULL) == GGX_ERR_NULL, "NULL options");
        ggx_shape sf;
        CHECK(ggx_filter_lobes(&sf, f->lobe, f->w, (size_t)f->n, &fast, NULL) == GGX_OK, "fast");
        double kf = kl_of(&sf, f);
        CHECK(kf >= ours - 1e-12 && kf <= ours + FAST_KL_EXCESS,
              "%s %d alpha %g: the fast mode's KL %.6g is not "
              "within %g above ours %.6g",
              f->name, f->n, f->alpha, kf, FAST_KL_EXCESS, ours);
        printf("%-12s %2d texels, alpha %.2f: KL ours %.5f, fast mode %.5f", f->name, f->n, f->alpha, ours, kf);
        for (int b = 0; b < NF_BASELINES; b++) {
            ggx_shape q;
            baseline(f, b, sg, &q);
            double kb = kl_of(&q, f);
            /* ours without skew is ours where the mean normal is n (symmetric footprints): equal there */
            CHECK(kb >= ours - 1e-12 * ours && (b == NF_UNSKEWED || kb > kf),
                  "%s %d alpha %g: %s has KL %.6g below "
                  "ours %.6g or the fast mode's %.6g",
                  f->name, f->n, f->alpha, nf_name[b], kb, ours, kf);
            printf(", %s %.5f", nf_name[b], kb);
        }
        printf("\n");
    }
}

/* The default rule against 64 x 128 nodes: the fitted parameters in Sigma's scale (the tolerance's measure), within
 * the bounds of docs/design/filter.md. */
static void rule_accuracy(void **state)
{
    (void)state;
    footprint fs[MAX_FOOTPRINTS];
    int nf;
    footprints(fs, &nf);
    double worst = 0.0;
    for (int i = 0; i < nf; i++) {
        const footprint *f = &fs[i];
        ggx_filter_options fine = {0};
        fine.radial_nodes = 64, fine.angular_nodes = 128;
        ggx_shape a, b;
        CHECK(ggx_filter_lobes(&a, f->lobe, f->w, (size_t)f->n, NULL, NULL) == GGX_OK, "default");
        CHECK(ggx_filter_lobes(&b, f->lobe, f->w, (size_t)f->n, &fine, NULL) == GGX_OK, "fine");
        double ta[2], sa[3], tb[2], sb[3];
        ggx_shape_slopes(&a, ta, sa), ggx_shape_slopes(&b, tb, sb);
        double e = fmax(fabs(ta[0] - tb[0]) / sqrt(sb[0]), fabs(ta[1] - tb[1]) / sqrt(sb[2]));
        e = fmax(e, fmax(fabs(sa[0] - sb[0]) / sb[0], fabs(sa[2] - sb[2]) / sb[2]));
        e = fmax(e, fabs(sa[1] - sb[1]) / sqrt(sb[0] * sb[2]));
        /* the bound (docs/design/filter.md): 1e-3 while the lobes' slopes spread over at most 3 alpha, 1.5e-2 beyond */
        double spread = 0.0;
        for (int p = 0; p < f->n; p++)
            for (int q = 0; q < p; q++) {
                double dx = f->normal[p].x / f->normal[p].z - f->normal[q].x / f->normal[q].z;
                double dy = f->normal[p].y / f->normal[p].z - f->normal[q].y / f->normal[q].z;
                spread = fmax(spread, sqrt(dx * dx + dy * dy) / f->alpha);
            }
        double bound = spread <= 3.0 ? 1e-3 : 1.5e-2;
        printf("  %-12s %2d texels, alpha %.2f, spread %5.1f alpha: %.3g\n", f->name, f->n, f->alpha, spread, e);
        CHECK(e <= bound, "%s %d alpha %g: default rule off by %.3g (bound %g)", f->name, f->n, f->alpha, e, bound);
        worst = fmax(worst, e);
    }
    printf("default rule (8 x 16) against 64 x 128: parameters within %.3g\n", worst);
}

/* Weights are relative (any scale gives the same bits), NULL means equal, and a zero weight drops its lobe. */
static void weights(void **state)
{
    (void)state;
    footprint f;
    rng r = {14};
    bumps(&f, &r, 4, 0.2, 0.1);
    for (int i = 0; i < f.n; i++) f.w[i] = rng_range(&r, 0.5, 2.0);
    ggx_shape a, b, c;
    double w[64], ones[64];
    CHECK(ggx_filter_lobes(&a, f.lobe, f.w, (size_t)f.n, NULL, NULL) == GGX_OK, "filter");
    for (double scale = 1e-300; scale < 1e301; scale *= 1e150) {
        for (int i = 0; i < f.n; i++) w[i] = f.w[i] * scale;
        CHECK(ggx_filter_lobes(&b, f.lobe, w, (size_t)f.n, NULL, NULL) == GGX_OK, "scaled");
        CHECK_CLOSE(ggx_p22(&b, 0.1, 0.2), ggx_p22(&a, 0.1, 0.2), 1e-13, 0, "weights scaled by %g", scale);
    }
    for (int i = 0; i < f.n; i++) ones[i] = 1.0;
    CHECK(ggx_filter_lobes(&b, f.lobe, NULL, (size_t)f.n, NULL, NULL) == GGX_OK, "NULL weights");
    CHECK(ggx_filter_lobes(&c, f.lobe, ones, (size_t)f.n, NULL, NULL) == GGX_OK, "ones");
    CHECK(memcmp(&b, &c, sizeof b) == 0, "NULL weights are not equal weights");
    /* lobes 8.. with weight 0 against the first 8 alone */
    for (int i = 0; i < f.n; i++) w[i] = i < 8 ? f.w[i] : 0.0;
    CHECK(ggx_filter_lobes(&b, f.lobe, w, (size_t)f.n, NULL, NULL) == GGX_OK, "zeros");
    CHECK(ggx_filter_lobes(&c, f.lobe, f.w, 8, NULL, NULL) == GGX_OK, "first 8");
    CHECK(memcmp(&b, &c, sizeof b) == 0, "a zero weight did not drop its lobe");
}

static void bad_input(void **state)
{
    (void)state;
    footprint f;
    checkerboard(&f, 0.3, 0.2);
    ggx_shape s, keep;
    lobe_ok(&keep, t_vec(0, 0, 1), 0.5, 0.5, 0);
    s = keep;
    double kl, w[2] = {1, 1};
    CHECK(ggx_filter_lobes(NULL, f.lobe, w, 2, NULL, NULL) == GGX_ERR_NULL, "NULL out");
    CHECK(ggx_filter_lobes(&s, NULL, w, 2, NULL, NULL) == GGX_ERR_NULL, "NULL lobes");
    CHECK(ggx_filter_kl(&s, f.lobe, w, 2, NULL, NULL) == GGX_ERR_NULL, "NULL kl");
    CHECK(ggx_filter_kl(NULL, f.lobe, w, 2, NULL, &kl) == GGX_ERR_NULL, "NULL shape");
    CHECK(ggx_filter_lobes(&s, f.lobe, w, 0, NULL, NULL) == GGX_ERR_RANGE, "no lobes");
    const double bad[][2] = {{-1, 1}, {NAN, 1}, {INFINITY, 1}, {0, 0}, {1e308, 1e308}};
    for (int i = 0; i < 5; i++) {
        CHECK(ggx_filter_lobes(&s, f.lobe, bad[i], 2, NULL, NULL) == GGX_ERR_RANGE, "weights %g %g", bad[i][0],
              bad[i][1]);
        CHECK(ggx_filter_kl(&keep, f.lobe, bad[i], 2, NULL, &kl) == GGX_ERR_RANGE, "kl weights %g %g", bad[i][0],
              bad[i][1]);
    }
    ggx_filter_options opts[10];
    memset(opts, 0, sizeof opts);
    opts[0].max_iterations = -1, opts[1].radial_nodes = -1, opts[2].angular_nodes = 15;
    opts[3].radial_nodes = 1025, opts[4].angular_nodes = 4098, opts[5].tolerance = NAN;
    opts[6].radial_nodes = 1, opts[7].angular_nodes = 2, opts[8].threads = -1, opts[9].threads = 1025;
    for (int i = 0; i < 10; i++)
        CHECK(ggx_filter_lobes(&s, f.lobe, w, 2, &opts[i], NULL) == GGX_ERR_RANGE, "option %d", i);
    CHECK(memcmp(&s, &keep, sizeof s) == 0, "out changed on error");
    /* the largest alpha: Sigma's eigenvalues stay within GGX_ALPHA_MAX^2, so the fit is a shape and so is the next
     * level's input (four tilts of alpha 1e4 once gave Sigma one ulp above it) */
    {
        const ggx_vec3 nm[4] = {{0.15728856207331002, 0.0078913520762041497, 1},
                                {0.15590093740100125, -0.10727196553970171, 1},
                                {0.27695781402218228, -0.060201280044757423, 1},
                                {0.17742503232504159, 0.15906748503268131, 1}};
        ggx_shape big[4], fit;
        for (int i = 0; i < 4; i++) lobe_ok(&big[i], nm[i], 1e4, 1e4, 0);
        CHECK(ggx_filter_lobes(&fit, big, NULL, 4, NULL, NULL) == GGX_OK, "alpha 1e4: the fit is not a shape");
        double lv[4 * GGX_LOBE_PARAMS], wv[4], o1[GGX_LOBE_PARAMS], w1;
        CHECK(ggx_texel_lobes(lv, wv, nm, 4, 1e4, 1e4, 0, NULL) == GGX_OK, "alpha 1e4 lobes");
        CHECK(ggx_filter_downsample(o1, &w1, lv, wv, 2, 2, NULL) == GGX_OK, "alpha 1e4 level");
        ggx_shape q;
        CHECK(ggx_shape_from_slopes(&q, o1[0], o1[1], o1[2], o1[3], o1[4]) == GGX_OK,
              "alpha 1e4: Sigma %.17g, %.17g "
              "is not a shape",
              o1[2], o1[4]);
    }
    /* the extremes that are allowed: two radial nodes and four angles, one iteration */
    ggx_filter_options tiny = {0};
    tiny.radial_nodes = 2, tiny.angular_nodes = 4, tiny.max_iterations = 1;
    ggx_filter_info info;
    CHECK(ggx_filter_lobes(&s, f.lobe, w, 2, &tiny, &info) == GGX_OK && info.iterations == 1, "smallest rule");
}

/* A map's lobes as GGX_LOBE_PARAMS doubles per texel. */
static void params_of(const ggx_shape *s, double *c) { ggx_shape_slopes(s, c, c + 2); }

/* The chain of a constant map, of a size that is no power of two (13 x 7 -> 7 x 4 -> 4 x 2 -> 2 x 1 -> 1 x 1): every
 * level is the texel's lobe, each entry to the bound of ggx_shape_from_slopes' round trip. */
static void chain_constant(void **state)
{
    (void)state;
    ggx_shape lobe;
    lobe_ok(&lobe, t_vec(0.5, -0.3, 1), 0.1, 0.25, 0.4);
    static double a[13 * 7 * GGX_LOBE_PARAMS], b[13 * 7 * GGX_LOBE_PARAMS];
    double c[GGX_LOBE_PARAMS];
    params_of(&lobe, c);
    size_t w = 13, h = 7;
    for (size_t i = 0; i < w * h; i++) memcpy(a + GGX_LOBE_PARAMS * i, c, sizeof c);
    const size_t sizes[][2] = {{7, 4}, {4, 2}, {2, 1}, {1, 1}};
    for (int level = 0; level < 4; level++) {
        CHECK(ggx_filter_downsample(b, NULL, a, NULL, w, h, NULL) == GGX_OK, "level %d", level + 1);
        w = (w + 1) / 2, h = (h + 1) / 2;
        CHECK(w == sizes[level][0] && h == sizes[level][1], "size");
        for (size_t i = 0; i < w * h; i++)
            for (int k = 0; k < GGX_LOBE_PARAMS; k++)
                CHECK_CLOSE(b[GGX_LOBE_PARAMS * i + k], c[k], 1e-13, 1e-13 * sqrt(c[2] * c[4]),
                            "level %d texel %zu entry %d", level + 1, i, k);
        memcpy(a, b, w * h * sizeof c);
    }
}

/* Each texel of a level is ggx_filter_lobes of its box, the boxes cut at an odd last column and row (5 x 3 ->
 * 3 x 2: boxes 2 x 2, 1 x 2, 2 x 1, 1 x 1), the same for any thread count, bit for bit; bad input leaves out
 * untouched. The chain's two steps against the exact filter of all 16 base texels of a 4 x 4 map: KL printed. */
static void chain_boxes(void **state)
{
    (void)state;
    footprint f;
    rng r = {15};
    bumps(&f, &r, 8, 0.2, 0.1);
    static double in[64 * GGX_LOBE_PARAMS], out[16 * GGX_LOBE_PARAMS], out3[16 * GGX_LOBE_PARAMS];
    for (int i = 0; i < 15; i++) params_of(&f.lobe[i], in + GGX_LOBE_PARAMS * i); /* 5 x 3 of the first 15 */
    CHECK(ggx_filter_downsample(out, NULL, in, NULL, 5, 3, NULL) == GGX_OK, "5 x 3");
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 3; x++) {
            ggx_shape box[4], s;
            int n = 0;
            for (int dy = 0; dy < 2 && 2 * y + dy < 3; dy++)
                for (int dx = 0; dx < 2 && 2 * x + dx < 5; dx++) box[n++] = f.lobe[(2 * y + dy) * 5 + 2 * x + dx];
            CHECK(ggx_filter_lobes(&s, box, NULL, (size_t)n, NULL, NULL) == GGX_OK, "box");
            double c[GGX_LOBE_PARAMS];
            params_of(&s, c);
            for (int k = 0; k < GGX_LOBE_PARAMS; k++)
                CHECK_CLOSE(out[GGX_LOBE_PARAMS * (y * 3 + x) + k], c[k], 1e-12, 1e-12 * sqrt(c[2] * c[4]),
                            "texel (%d, %d) of %d lobes, entry %d", x, y, n, k);
        }
    for (int threads = 2; threads <= 7; threads += 5) {
        ggx_filter_options o = {0};
        o.threads = threads;
        CHECK(ggx_filter_downsample(out3, NULL, in, NULL, 5, 3, &o) == GGX_OK, "threads");
        CHECK(memcmp(out3, out, 6 * GGX_LOBE_PARAMS * sizeof *out) == 0, "%d threads changed the level", threads);
    }
    /* bad input */
    memcpy(out3, out, sizeof out3);
    double bad[4 * GGX_LOBE_PARAMS];
    memcpy(bad, in, sizeof bad);
    CHECK(ggx_filter_downsample(NULL, NULL, in, NULL, 5, 3, NULL) == GGX_ERR_NULL, "NULL out");
    CHECK(ggx_filter_downsample(out3, NULL, NULL, NULL, 5, 3, NULL) == GGX_ERR_NULL, "NULL in");
    CHECK(ggx_filter_downsample(out3, NULL, in, NULL, 0, 3, NULL) == GGX_ERR_RANGE, "width 0");
    CHECK(ggx_filter_downsample(out3, NULL, in, NULL, (size_t)-1, 3, NULL) == GGX_ERR_RANGE, "overflowing size");
    bad[7] = NAN;
    CHECK(ggx_filter_downsample(out3, NULL, bad, NULL, 2, 2, NULL) == GGX_ERR_RANGE, "NaN texel");
    bad[7] = in[7], bad[GGX_LOBE_PARAMS * 3 + 3] = 10.0;
    CHECK(ggx_filter_downsample(out3, NULL, bad, NULL, 2, 2, NULL) == GGX_ERR_RANGE, "Sigma not positive definite");
    ggx_filter_options odd = {0};
    odd.angular_nodes = 3;
    CHECK(ggx_filter_downsample(out3, NULL, in, NULL, 5, 3, &odd) == GGX_ERR_RANGE, "odd angular nodes");
    CHECK(memcmp(out3, out, sizeof out3) == 0, "out written on error");
    /* weights: a 2 x 2 map weighted (1, 0; 2, 0) is the filter of texels 0 and 2 weighted 1 and 2, of weight 3; a
     * texel of weight 0 may hold anything; a box of weight 0 is the placeholder; a negative weight is refused */
    double wts[4] = {1, 0, 2, 0}, wo[1], two[2 * GGX_LOBE_PARAMS], w2[2] = {1, 2};
    memcpy(bad, in, sizeof bad);
    bad[GGX_LOBE_PARAMS * 1] = NAN;
    CHECK(ggx_filter_downsample(out3, wo, bad, wts, 2, 2, NULL) == GGX_OK && wo[0] == 3.0, "weighted box");
    memcpy(two, in, GGX_LOBE_PARAMS * sizeof *in),
        memcpy(two + GGX_LOBE_PARAMS, in + 2 * GGX_LOBE_PARAMS, GGX_LOBE_PARAMS * sizeof *in);
    ggx_shape pair[2], ref;
    for (int i = 0; i < 2; i++)
        CHECK(ggx_shape_from_slopes(&pair[i], two[5 * i], two[5 * i + 1], two[5 * i + 2], two[5 * i + 3],
                                    two[5 * i + 4]) == GGX_OK,
              "pair");
    CHECK(ggx_filter_lobes(&ref, pair, w2, 2, NULL, NULL) == GGX_OK, "reference");
    double c[GGX_LOBE_PARAMS];
    params_of(&ref, c);
    for (int k = 0; k < GGX_LOBE_PARAMS; k++)
        CHECK_CLOSE(out3[k], c[k], 1e-9, 1e-9 * sqrt(c[2] * c[4]), "weighted box entry %d", k);
    double zeros[4] = {0, 0, 0, 0};
    CHECK(ggx_filter_downsample(out3, wo, bad, zeros, 2, 2, NULL) == GGX_OK && wo[0] == 0.0 && out3[0] == 0.0 &&
              out3[1] == 0.0 && out3[2] == 1.0 && out3[3] == 0.0 && out3[4] == 1.0,
          "empty box");
    wts[1] = -1;
    CHECK(ggx_filter_downsample(out3, wo, in, wts, 2, 2, NULL) == GGX_ERR_RANGE, "negative weight");
    double big[4] = {1e308, 1e308, 1e308, 1e308};
    CHECK(ggx_filter_downsample(out3, wo, in, big, 2, 2, NULL) == GGX_ERR_RANGE, "weights whose sum overflows");
    memcpy(bad, in, sizeof bad);
    bad[0] = 1e300;
    CHECK(ggx_filter_downsample(out3, wo, bad, NULL, 2, 2, NULL) == GGX_ERR_RANGE, "a slope of 1e300");
    memcpy(bad, in, sizeof bad);
    bad[2] = bad[4] = 1e200, bad[3] = 0;
    CHECK(ggx_filter_downsample(out3, wo, bad, NULL, 2, 2, NULL) == GGX_ERR_RANGE, "Sigma of 1e200");
    /* the widest lobes tilted apart: the result's Sigma held at GGX_ALPHA_MAX^2, a shape */
    ggx_shape wide[2];
    lobe_ok(&wide[0], t_vec(1, 0, 1), GGX_ALPHA_MAX, GGX_ALPHA_MAX, 0);
    lobe_ok(&wide[1], t_vec(-1, 0, 1), GGX_ALPHA_MAX, GGX_ALPHA_MAX, 0);
    params_of(&wide[0], bad), params_of(&wide[1], bad + GGX_LOBE_PARAMS);
    ggx_shape q;
    CHECK(ggx_filter_downsample(out3, wo, bad, NULL, 2, 1, NULL) == GGX_OK &&
              ggx_shape_from_slopes(&q, out3[0], out3[1], out3[2], out3[3], out3[4]) == GGX_OK,
          "the widest lobes' filter is not a shape: Sigma %g %g %g", out3[2], out3[3], out3[4]);
    CHECK(ggx_filter_lobes(&q, wide, NULL, 2, NULL, NULL) == GGX_OK, "the widest lobes' filter");
    wts[1] = INFINITY;
    CHECK(ggx_filter_downsample(out3, wo, in, wts, 2, 2, NULL) == GGX_ERR_RANGE, "infinite weight");
    /* two steps of the chain against the exact filter of the 16 base texels of a 4 x 4 map */
    for (int i = 0; i < 16; i++) params_of(&f.lobe[i], in + GGX_LOBE_PARAMS * i);
    CHECK(ggx_filter_downsample(out, NULL, in, NULL, 4, 4, NULL) == GGX_OK &&
              ggx_filter_downsample(out3, NULL, out, NULL, 2, 2, NULL) == GGX_OK,
          "two levels");
    ggx_shape chain, exact;
    CHECK(ggx_shape_from_slopes(&chain, out3[0], out3[1], out3[2], out3[3], out3[4]) == GGX_OK, "chain's lobe");
    CHECK(ggx_filter_lobes(&exact, f.lobe, NULL, 16, NULL, NULL) == GGX_OK, "exact");
    footprint base = f;
    base.n = 16;
    double k_chain = kl_of(&chain, &base), k_exact = kl_of(&exact, &base);
    CHECK(k_chain >= k_exact - 1e-12, "the chain's lobe is closer than the exact filter: %.6g < %.6g", k_chain,
          k_exact);
    printf("4 x 4 bumps (alpha 0.1): KL of the exact filter %.5f, of two chain steps %.5f\n", k_exact, k_chain);
}

/* Threads: eight at once filter the same footprints and get the same bits as one alone. */
typedef struct job {
    const footprint *fs;
    int n;
    ggx_shape out[MAX_FOOTPRINTS];
} job;
static void *run_job(void *p)
{
    job *j = p;
    for (int rep = 0; rep < 4; rep++)
        for (int i = 0; i < j->n; i++)
            ggx_filter_lobes(&j->out[i], j->fs[i].lobe, j->fs[i].w, (size_t)j->fs[i].n, NULL, NULL);
    return NULL;
}
static void threads(void **state)
{
    (void)state;
    static footprint fs[MAX_FOOTPRINTS];
    int nf;
    footprints(fs, &nf);
    static job ref, jobs[8];
    ref.fs = fs, ref.n = nf;
    run_job(&ref);
    pthread_t th[8];
    for (int k = 0; k < 8; k++) jobs[k].fs = fs, jobs[k].n = nf, pthread_create(&th[k], NULL, run_job, &jobs[k]);
    for (int k = 0; k < 8; k++) pthread_join(th[k], NULL);
    for (int k = 0; k < 8; k++)
        CHECK(memcmp(jobs[k].out, ref.out, (size_t)nf * sizeof ref.out[0]) == 0, "thread %d", k);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(texel_lobe_form),
        cmocka_unit_test(texel_lobe_errors),
        cmocka_unit_test(texel_lobes),
        cmocka_unit_test(roughness_map),
        cmocka_unit_test(constant_map),
        cmocka_unit_test(em_monotone),
        cmocka_unit_test(optimum_and_baselines),
        cmocka_unit_test(rule_accuracy),
        cmocka_unit_test(weights),
        cmocka_unit_test(bad_input),
        cmocka_unit_test(chain_constant),
        cmocka_unit_test(chain_boxes),
        cmocka_unit_test(threads),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    return rc | chi2_budget_end("filter", argc, argv);
}
