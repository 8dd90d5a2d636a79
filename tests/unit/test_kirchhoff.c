/* The Kirchhoff BRDF of a height field (libs/microsurface/kirchhoff.h): a plane is a mirror that keeps all the power
 * in its specular bin; the formula is reciprocal; the specular spike keeps the Debye-Waller share of a smooth
 * surface; the binned BRDF approaches the geometric-optics BRDF of the same slopes as sigma_h / lambda grows; the
 * FFT's bins meet a fine quadrature of the directly summed formula; bad input is refused with its reason.
 * Quick tier (GGX_TEST_SCALE < 1): 256^2 fields; the full tier adds the shortest wavelength and a 512^2 field.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "kirchhoff.h"
#include "microsurface.h"
#include "testlib.h"

static const double PI_ = 3.14159265358979323846;

/* 0 (with one line) where the build has no KISS FFT: then only the refusal is checked */
static int fft_built(void)
{
    double h[4] = {0, 0, 0, 0};
    ms_kirchhoff_spec s = {h, 2, 2, 1.0, 0.5, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0};
    ms_kirchhoff k;
    char err[256];
    if (ms_kirchhoff_setup(&s, &k, err, sizeof err) == 0) {
        ms_kirchhoff_free(&k);
        return 1;
    }
    CHECK(strstr(err, "not built") != NULL, "a valid spec refused: %s", err);
    printf("kirchhoff: %s\n", err);
    return 0;
}

static double *gauss_field(size_t n, double alpha, double corr, uint64_t seed)
{
    double *h = malloc(n * n * sizeof *h);
    char err[256];
    ms_gauss_spec gs = {n, alpha, alpha, 0.0, corr, seed};
    CHECK(h && ms_gauss(&gs, h, NULL, err, sizeof err) == 0, "field: %s", err);
    return h;
}

/* the relative L2 distance of a from b over bins */
static double rel_l2(const double *a, const double *b, int bins)
{
    double e = 0.0, q = 0.0;
    for (int i = 0; i < bins; i++) e += (a[i] - b[i]) * (a[i] - b[i]), q += b[i] * b[i];
    return sqrt(e / q);
}

/* A plane, lit from the centre of a bin's mirror (ring 2 of 8, sector 0 of 16): the coherent share is 1, the total
 * 1 to the float FFT's rounding (Parseval: 1e-5 allows 100 times the measured 7e-8), and the Hann window keeps
 * 0.999 of it in the specular bin (the spike's main lobe, 2 cells of lambda / (N dx) = 0.008, is 0.05 from the
 * bin's edges; measured 0.99996). Negative control: a window of 2 % taper diffracts from its steep edges, so the
 * same bin holds visibly less (measured 0.9987); a wrong normalisation (no obliquity) would not sum to 1. The point
 * evaluator integrated over the directions matches the bins' total. */
static void flat_mirror(void **state)
{
    (void)state;
    if (!fft_built()) return;
    enum { N = 256, R = 8, S = 16 };
    double *h = calloc(N * N, sizeof *h), share[R * S];
    double th = asin(sqrt(2.5 / R)), ph = PI_ + PI_ / S;
    ms_kirchhoff_spec s = {h, N, N, 0.25, 0.5, {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)}, 0, 1, 0, 0, 0, 2, 0, 0};
    ms_kirchhoff k;
    char err[256];
    CHECK(ms_kirchhoff_setup(&s, &k, err, sizeof err) == 0, "%s", err);
    double tot = ms_kirchhoff_bin(&k, R, S, share), wo[3] = {-s.wi[0], -s.wi[1], s.wi[2]};
    int b = ms_bin(wo, R, S);
    CHECK_CLOSE(k.coherent, 1.0, 0.0, 1e-12, "coherent share of a plane");
    CHECK_CLOSE(tot, 1.0, 0.0, 1e-5, "total share of a plane");
    CHECK(share[b] > 0.999, "specular bin %d holds %.6f", b, share[b]);
    printf("flat mirror: total %.8f, specular bin %.6f\n", tot, share[b]);
    ms_kirchhoff_free(&k);
    s.taper = 0.02;
    CHECK(ms_kirchhoff_setup(&s, &k, err, sizeof err) == 0, "%s", err);
    double tot2 = ms_kirchhoff_bin(&k, R, S, share);
    printf("flat mirror, taper 0.02: total %.8f, specular bin %.6f\n", tot2, share[b]);
    CHECK(share[b] < 0.9995, "a steep-edged window should diffract out of the bin: %.6f", share[b]);
    ms_kirchhoff_free(&k);
    free(h);
}

/* f(wi, wo) = f(wo, wi) for the directly summed formula on a rough patch (sigma_h / lambda 0.24): pairs over the
 * hemisphere agree to 1e-9 relative (the same phases summed in the same order; only the normalisation of the two
 * directions' rounding differs). Negative control: the values vary by orders of magnitude across the pairs, so the
 * check does not pass on a constant. The FFT evaluator, whose phase is held at its level, is reciprocal only to
 * its level's and the grid's error, which the binned checks below bound. */
static void reciprocity(void **state)
{
    (void)state;
    if (!fft_built()) return;
    enum { N = 48 };
    double *h = gauss_field(N, 0.3, 4, 7);
    rng r = {11};
    double lo = INFINITY, hi = 0.0;
    for (int i = 0; i < 12; i++) {
        ggx_vec3 a = random_view(&r), b = random_view(&r);
        if (a.z < 0.05 || b.z < 0.05) continue;
        double va[3] = {a.x, a.y, a.z}, vb[3] = {b.x, b.y, b.z};
        ms_kirchhoff_spec s = {h, N, N, 1.0, 5.0, {a.x, a.y, a.z}, 0, 1, 0, 0, 0, 1, 0, 0};
        ms_kirchhoff ka, kb;
        char err[256];
        CHECK(ms_kirchhoff_setup(&s, &ka, err, sizeof err) == 0, "%s", err);
        s.wi[0] = b.x, s.wi[1] = b.y, s.wi[2] = b.z;
        CHECK(ms_kirchhoff_setup(&s, &kb, err, sizeof err) == 0, "%s", err);
        double fab = ms_kirchhoff_brdf_exact(&ka, vb), fba = ms_kirchhoff_brdf_exact(&kb, va);
        CHECK_CLOSE(fab, fba, 1e-9, 0.0, "f(a, b) against f(b, a), pair %d", i);
        lo = fmin(lo, fab), hi = fmax(hi, fab);
        ms_kirchhoff_free(&ka), ms_kirchhoff_free(&kb);
    }
    CHECK(hi > 10.0 * lo, "the pairs' values span %g to %g only", lo, hi);
    free(h);
}

/* The window-weighted variance of the prepared heights (the spike's weights are W^2) */
static double window_var(const ms_kirchhoff *k)
{
    double s = 0.0, s1 = 0.0, s2 = 0.0;
    for (size_t y = 0; y < k->ny; y++)
        for (size_t x = 0; x < k->nx; x++) {
            double w = k->wx[x] * k->wx[x] * k->wy[y] * k->wy[y], v = k->hp[y * k->nx + x];
            s += w, s1 += w * v, s2 += w * v * v;
        }
    return s2 / s - (s1 / s) * (s1 / s);
}

/* sigma_h << lambda: the coherent share is the Debye-Waller (Rayleigh) factor exp(-(2 k cos_i sigma)^2) of the
 * window-weighted height variance, to 2 % in its logarithm (Gaussian heights have no fourth cumulant; a sample's
 * is of order sqrt(24 / 1000) sigma^4, a 0.3 % change at a phase RMS of 0.6), and the FFT's own specular cell,
 * against a plane's, holds that share within 0.01 (the halo spreads over some thousand cells). Negative control:
 * the phase of wi.z alone (no factor 2, the sign error of a transmitted wave) misses by a factor 4. */
static void debye_waller(void **state)
{
    (void)state;
    if (!fft_built()) return;
    enum { N = 256 };
    double *h = gauss_field(N, 0.3, 8, 3), *flat = calloc(N * N, sizeof *flat);
    const double lams[3] = {200.0, 60.0, 30.0}, th = 0.5;
    for (int i = 0; i < 3; i++) {
        ms_kirchhoff_spec s = {h, N, N, 1.0, lams[i], {sin(th), 0.0, cos(th)}, 0, 1, 0, 0, 0, 2, 0, 0};
        ms_kirchhoff k, kf;
        char err[256];
        CHECK(ms_kirchhoff_setup(&s, &k, err, sizeof err) == 0, "%s", err);
        s.h = flat;
        CHECK(ms_kirchhoff_setup(&s, &kf, err, sizeof err) == 0, "%s", err);
        double kk = 2.0 * PI_ / lams[i], g = 2.0 * kk * cos(th), var = window_var(&k);
        double want = -g * g * var, got = log(k.coherent), wrong = -(g / 2) * (g / 2) * var;
        CHECK_CLOSE(got, want, 0.02, 0.0, "log coherent share at lambda %g", lams[i]);
        CHECK(fabs(got - wrong) > 0.5 * fabs(want), "the wrong phase factor passes at lambda %g", lams[i]);
        double cell = k.power[0] / kf.power[0];
        CHECK_CLOSE(cell, k.coherent, 0.0, 0.01, "the FFT's specular cell against the plane's at lambda %g", lams[i]);
        printf("Debye-Waller: lambda %g, phase RMS %.3f: coherent %.5f, exp(-(2 k cos sigma)^2) %.5f, FFT cell "
               "%.5f\n",
               lams[i], g * sqrt(var), k.coherent, exp(want), cell);
        ms_kirchhoff_free(&k), ms_kirchhoff_free(&kf);
    }
    free(h), free(flat);
}

/* As sigma_h / lambda grows at fixed slopes (Beckmann alpha 0.3, correlation length 8 spacings, lambda shortened),
 * the binned wave BRDF approaches the geometric-optics single-scattering BRDF of the same windowed slopes
 * (ms_kirchhoff_geometric). Measured relative L2 over 8 x 16 bins, 256^2 field: 3.4 at 0.06 (spike), 0.29 at 0.2,
 * 0.093 at 0.6, 0.049 at 1.2, 0.037 at 1.5 (the speckle's scatter of a 256^2 patch is its floor). Asserted: below
 * 0.06 from sigma/lambda 1.5 on (full tier: 512^2 at 2, below 0.04), above 1 at 0.06 (the negative control: the
 * spike is no geometric feature), decreasing along the sequence within 10 % steps, and the totals within 1 % from
 * sigma/lambda 0.5 on (at 0.06 the wave's is 0.979 against 0.995: the halo's light near the horizon). */
static void geometric_limit(void **state)
{
    (void)state;
    if (!fft_built()) return;
    enum { R = 8, S = 16 };
    int full = !test_quick();
    size_t n = full ? 512 : 256;
    double *h = gauss_field(n, 0.3, 8, 1), share[R * S], geo[R * S], prev = INFINITY;
    const double lams[6] = {20.0, 6.0, 2.0, 1.0, 0.8, 0.6};
    int cases = full ? 6 : 5;
    for (int i = 0; i < cases; i++) {
        ms_kirchhoff_spec s = {h, n, n, 1.0, lams[i], {sin(0.5), 0.0, cos(0.5)}, 0, 0, 0, 0, 0, 2, 0, 0};
        ms_kirchhoff k;
        char err[256];
        CHECK(ms_kirchhoff_setup(&s, &k, err, sizeof err) == 0, "%s", err);
        double tw = ms_kirchhoff_bin(&k, R, S, share), tg = ms_kirchhoff_geometric(&k, R, S, geo);
        double l2 = rel_l2(share, geo, R * S), ratio = k.sigma_h / lams[i];
        printf("geometric limit: sigma/lambda %.3f (upsample %d, aliased %.4f): L2 %.4f, totals wave %.4f geometric "
               "%.4f\n",
               ratio, k.upsample, k.aliased, l2, tw, tg);
        CHECK(l2 < prev * 1.1, "L2 %.4f grew from %.4f at sigma/lambda %.3f", l2, prev, ratio);
        if (i == 0) CHECK(l2 > 1.0, "the spike passes as geometric at sigma/lambda %.3f: %.4f", ratio, l2);
        if (ratio >= 1.5) CHECK(l2 < (full ? 0.04 : 0.06), "L2 %.4f at sigma/lambda %.3f", l2, ratio);
        if (ratio >= 0.5) CHECK_CLOSE(tw, tg, 0.01, 0.0, "total shares at sigma/lambda %.3f", ratio);
        prev = l2;
        ms_kirchhoff_free(&k);
    }
    free(h);
}

/* The FFT's bins (one level, the slope mapping) against a fine quadrature of the directly summed formula (each
 * direction's own phase; midpoints a third of the FFT's cell apart in wo_xy) on a 48^2 patch at sigma_h / lambda
 * 0.28, where the spike is gone: within 0.15 relative L2 over 4 x 8 bins (measured 0.07 at 0.38), and the point
 * evaluator's integral over the same midpoints within 3 % of the bins' total. */
static void fft_against_exact(void **state)
{
    (void)state;
    if (!fft_built()) return;
    enum { N = 32, R = 4, S = 8 };
    double *h = gauss_field(N, 0.3, 4, 3), share[R * S], ex[R * S] = {0};
    /* upsampled 3 times: the sampled field's images, lambda / dx apart in (wi + wo)_xy, then stay 4 beyond the
     * hemisphere's reach of 2 (at upsample 1 the sum meets the first image and counts 1.37) */
    ms_kirchhoff_spec s = {h, N, N, 1.0, 2.0, {sin(0.6), 0.0, cos(0.6)}, 0, 3, 0, 0, 0, 1, 0, 0};
    ms_kirchhoff k;
    char err[256];
    CHECK(ms_kirchhoff_setup(&s, &k, err, sizeof err) == 0, "%s", err);
    double tot = ms_kirchhoff_bin(&k, R, S, share), du = k.wavelength / ((double)k.fft_nx * k.dx) / 3.0, te = 0.0,
           tp = 0.0;
    int m = (int)ceil(1.0 / du);
    for (int i = -m; i <= m; i++)
        for (int j = -m; j <= m; j++) {
            double wo[3] = {(i + 0.5) * du, (j + 0.5) * du, 0.0}, r2 = wo[0] * wo[0] + wo[1] * wo[1];
            if (r2 >= 1.0) continue;
            wo[2] = sqrt(1.0 - r2);
            double f = ms_kirchhoff_brdf_exact(&k, wo) * du * du;
            ex[ms_bin(wo, R, S)] += f, te += f, tp += ms_kirchhoff_brdf(&k, wo) * du * du;
        }
    double l2 = rel_l2(share, ex, R * S);
    printf("FFT against the summed formula: sigma/lambda %.3f, L2 %.4f, totals %.4f (FFT) %.4f (summed) %.4f "
           "(point evaluator)\n",
           k.sigma_h / k.wavelength, l2, tot, te, tp);
    CHECK(l2 < 0.15, "bins against the quadrature: L2 %.4f", l2);
    CHECK_CLOSE(te, tot, 0.03, 0.0, "totals");
    CHECK_CLOSE(tp, tot, 0.03, 0.0, "the point evaluator's integral");
    ms_kirchhoff_free(&k);
    free(h);
}

/* Bad input: each refused with -1 and a reason naming it. */
static void bad_input(void **state)
{
    (void)state;
    double h[16], nanh[16];
    for (int i = 0; i < 16; i++) h[i] = 0.01 * ((i * 7) % 5), nanh[i] = NAN;
    double few[16];
    for (int i = 0; i < 16; i++) few[i] = i < 3 ? 0.0 : NAN;
    double huge[16];
    for (int i = 0; i < 16; i++) huge[i] = i % 2 ? 1e300 : -1e300;
    struct {
        ms_kirchhoff_spec s;
        const char *why;
    } cases[] = {
        {{nanh, 4, 4, 1.0, 0.5, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0}, "missing"},
        {{few, 4, 4, 1.0, 0.5, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0}, "fewer than 2 x 2"},
        {{h, 4, 4, 1.0, 0.0, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0}, "wavelength"},
        {{h, 4, 4, 1.0, NAN, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0}, "wavelength"},
        {{h, 4, 4, 1.0, -1.0, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0}, "wavelength"},
        {{h, 4, 4, INFINITY, 0.5, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0}, "spacing"},
        {{h, 4, 4, 0.0, 0.5, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0}, "spacing"},
        {{huge, 4, 4, 1.0, 0.5, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0}, "absurd"},
        {{h, 4, 4, 1.0, 1e-14, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0}, "absurd"},
        {{h, 4, 4, 1.0, 0.5, {1, 0, 0}, 0, 1, 0, 0, 0, 1, 0, 0}, "above the plane"},
        {{h, 4, 4, 1.0, 0.5, {0, 0, 1}, 65, 1, 0, 0, 0, 1, 0, 0}, "levels"},
        {{h, 4, 4, 1.0, 0.5, {0, 0, 1}, 0, 17, 0, 0, 0, 1, 0, 0}, "upsample"},
        {{h, 4, 4, 1.0, 0.5, {0, 0, 1}, 0, 1, 1.5, 0, 0, 1, 0, 0}, "taper"},
        {{h, 4, 1, 1.0, 0.5, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0}, "2 x 2"},
        {{h, (size_t)1 << 15, (size_t)1 << 15, 1.0, 0.5, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0}, "memory"},
        {{h, 4, 4, 1.0, 0.5, {0, 0, 1}, 0, 1, 0, 0, 10, 1, 0, 0}, "memory"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        ms_kirchhoff k;
        char err[256] = "";
        CHECK(ms_kirchhoff_setup(&cases[i].s, &k, err, sizeof err) == -1, "case %zu accepted", i);
        CHECK(strstr(err, cases[i].why) != NULL && !strchr(err, '\n'), "case %zu: '%s' does not say '%s'", i, err,
              cases[i].why);
    }
    double share[4];
    ms_kirchhoff k;
    char err[256];
    ms_kirchhoff_spec ok = {h, 4, 4, 1.0, 0.5, {0, 0, 1}, 0, 1, 0, 0, 0, 1, 0, 0};
    if (ms_kirchhoff_setup(&ok, &k, err, sizeof err) == 0) {
        CHECK(isnan(ms_kirchhoff_bin(&k, 0, 4, share)), "0 rings accepted");
        ms_kirchhoff_free(&k);
    }
}

/* ms_level: a tilted plane with missing points levels to 0 (the missing ones left NaN), a surface on it keeps its
 * own heights less their own plane; points on one line keep their tilt (only the mean goes); keep_tilt removes the
 * mean alone. */
static void levelling(void **state)
{
    (void)state;
    enum { NX = 7, NY = 5 };
    double h[NX * NY], g[NX * NY];
    for (int y = 0; y < NY; y++)
        for (int x = 0; x < NX; x++) h[y * NX + x] = 3.0 + 0.25 * x - 0.5 * y, g[y * NX + x] = h[y * NX + x];
    h[3] = h[17] = NAN;
    double pl[3];
    CHECK(ms_level(h, NX, NY, 0, pl) == NX * NY - 2, "finite count");
    CHECK(fabs(pl[0] - 0.25) < 1e-12 && fabs(pl[1] + 0.5) < 1e-12 && fabs(pl[2] - (3.0 + 0.25 * 3 - 0.5 * 2)) < 1e-12,
          "plane %g %g %g", pl[0], pl[1], pl[2]);
    for (int i = 0; i < NX * NY; i++)
        CHECK(i == 3 || i == 17 ? isnan(h[i]) : fabs(h[i]) < 1e-12, "point %d: %g after levelling", i, h[i]);
    double mean = 0;
    for (int i = 0; i < NX * NY; i++) mean += g[i] / (NX * NY);
    CHECK(ms_level(g, NX, NY, 1, NULL) == NX * NY, "finite count");
    for (int y = 0; y < NY; y++)
        for (int x = 0; x < NX; x++)
            CHECK(fabs(g[y * NX + x] - (3.0 + 0.25 * x - 0.5 * y - mean)) < 1e-12,
                  "keep_tilt removed more than the mean");
    double line[NX * NY];
    for (int i = 0; i < NX * NY; i++) line[i] = NAN;
    for (int x = 0; x < NX; x++) line[2 * NX + x] = x;
    CHECK(ms_level(line, NX, NY, 0, NULL) == NX, "finite count on a line");
    for (int x = 0; x < NX; x++) CHECK(fabs(line[2 * NX + x] - (x - 3.0)) < 1e-12, "a line's tilt removed");
    double none[4] = {NAN, NAN, NAN, NAN};
    CHECK(ms_level(none, 2, 2, 0, NULL) == 0 && isnan(none[0]), "no finite point");
}

/* The grid's choice on a 200 x 150 patch whose steepest steps need upsampling: alias 0.1 asks for no more than the
 * default's 1e-3 (a smaller or equal U); within a point budget, crop keeps the chosen U on the largest centred
 * window that fits (reported in crop), where without crop U is lowered on the whole patch. */
static void grid_choice(void **state)
{
    (void)state;
    enum { NX = 200, NY = 150 };
    static double h[NX * NY];
    for (int y = 0; y < NY; y++)
        for (int x = 0; x < NX; x++) h[y * NX + x] = 0.8 * sin(0.37 * x) * cos(0.29 * y) + 0.3 * sin(0.11 * x * y / NX);
    ms_kirchhoff_spec sp = {.h = h, .nx = NX, .ny = NY, .dx = 1.0, .wavelength = 0.5, .wi = {0, 0, 1}, .threads = 2};
    ms_kirchhoff a, b, c, d;
    char err[300];
    CHECK(ms_kirchhoff_setup(&sp, &a, err, sizeof err) == 0, "%s", err);
    sp.alias = 0.1;
    CHECK(ms_kirchhoff_setup(&sp, &b, err, sizeof err) == 0, "%s", err);
    CHECK(b.upsample <= a.upsample && a.upsample >= 3 && b.aliased <= 0.1 + 1e-12 && a.aliased <= 1e-3 + 1e-12,
          "alias: U %d (%.4f aliased) against %d (%.4f)", b.upsample, b.aliased, a.upsample, a.aliased);
    CHECK(a.crop[0] == 0 && a.crop[1] == 0 && a.crop[2] == NX && a.crop[3] == NY, "no crop needed, one made");
    sp.alias = 0, sp.max_points = (size_t)1 << 16, sp.crop = 1;
    CHECK(ms_kirchhoff_setup(&sp, &c, err, sizeof err) == 0, "%s", err);
    CHECK(c.upsample == a.upsample && c.crop[2] < NX && c.crop[3] < NY && c.fft_nx * c.fft_ny <= sp.max_points &&
              c.crop[0] == (NX - c.crop[2]) / 2 && c.nx == (c.crop[2] - 1) * (size_t)c.upsample + 1,
          "crop: U %d, window %zu x %zu at %zu, %zu", c.upsample, c.crop[2], c.crop[3], c.crop[0], c.crop[1]);
    sp.crop = 0;
    CHECK(ms_kirchhoff_setup(&sp, &d, err, sizeof err) == 0, "%s", err);
    CHECK(d.upsample < a.upsample && d.crop[2] == NX && d.fft_nx * d.fft_ny <= sp.max_points, "no crop: U %d",
          d.upsample);
    ms_kirchhoff_free(&a), ms_kirchhoff_free(&b), ms_kirchhoff_free(&c), ms_kirchhoff_free(&d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(flat_mirror),     cmocka_unit_test(reciprocity),       cmocka_unit_test(debye_waller),
        cmocka_unit_test(geometric_limit), cmocka_unit_test(fft_against_exact), cmocka_unit_test(bad_input),
        cmocka_unit_test(levelling),       cmocka_unit_test(grid_choice),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
