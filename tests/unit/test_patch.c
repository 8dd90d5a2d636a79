/* Measured patches (libs/microsurface/microsurface.h, ms_patch_new): a periodic Gaussian field cut to a finite,
 * non-square patch of 4 x 3 of its tiles traces like the periodic tile itself: the same facets, visible-normal bins
 * and BRDF within binomial noise at 0, 60 and 80 degrees, no ray leaving the patch; without the margin the patch
 * loses rays at its side and its G1 falls detectably (the negative control); a patch with a hole passes the rays
 * through it as stated; bad patches are refused. docs/design/microsurface.md, "Measured patches".
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "microsurface.h"
#include "testlib.h"

static const double PI = 3.14159265358979323846;

/* The periodic field of the tests (Beckmann alpha 0.5, correlation length 8: heights' sigma 2, a band of about 16
 * spacings, so that rays at 80 degrees cross about 90 spacings of it, less than a tile of 128): its tile h (n x n)
 * and tracer, or NULL (with one line) where the build has no Embree or no KISS FFT. */
static ms_tracer *periodic(size_t n, double *h)
{
    ms_gauss_spec sp = {n, 0.5, 0.5, 0.0, 8, 3};
    char err[300];
    if (ms_gauss(&sp, h, NULL, err, sizeof err) != 0) {
        CHECK(strstr(err, "not built") != NULL, "the field failed: %s", err);
        printf("patch: %s\n", err);
        return NULL;
    }
    ms_tracer *t = ms_tracer_new(h, n, NULL, err, sizeof err);
    if (!t) {
        CHECK(strstr(err, "not built") != NULL, "the tracer failed: %s", err);
        printf("patch: %s\n", err);
    }
    return t;
}

/* the periodic field's heights over kx x ky tiles and one more row and column: a patch of (kx n + 1) x (ky n + 1)
 * heights whose cells are those of kx x ky tiles, traced without wrap */
static double *crop(const double *h, size_t n, size_t kx, size_t ky)
{
    size_t nx = kx * n + 1, ny = ky * n + 1;
    double *p = malloc(nx * ny * sizeof *p);
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++) p[y * nx + x] = h[(y % n) * n + x % n];
    return p;
}

static ms_tracer *patch_or_fail(const double *p, size_t nx, size_t ny)
{
    char err[300];
    ms_tracer *t = ms_patch_new(p, nx, ny, err, sizeof err);
    CHECK(t != NULL, "the patch failed: %s", err);
    return t;
}

/* the unit view at theta, phi (degrees) */
static void view(double theta, double phi, double v[3])
{
    double th = theta * PI / 180.0, ph = phi * PI / 180.0;
    v[0] = sin(th) * cos(ph), v[1] = sin(th) * sin(ph), v[2] = cos(th);
}

/* |a - b| over the binomial standard error of the difference of two independent shares a of na and b of nb rays */
static double z_binomial(double a, long na, double b, long nb)
{
    double var = a * (1.0 - a) / (double)na + b * (1.0 - b) / (double)nb;
    return var > 0.0 ? fabs(a - b) / sqrt(var) : (a == b ? 0.0 : HUGE_VAL);
}

/* Rays per measurement: 2.5e5 (quick) or 1e6 (full) for G1, 1e5 or 4e5 for the BRDF. */
static long g1_rays(void) { return test_quick() ? 250000 : 1000000; }
static long brdf_rays(void) { return test_quick() ? 100000 : 400000; }

/* The crop against the tile. The patch is 4 x 3 tiles (non-square; its sides do not wrap), rays start over the
 * window of the tile [n, 2n] x [n, 2n], which leaves at least n = 128 spacings on every side: the margin downstream
 * that the rays need at 80 degrees (the band's fall, 12 spacings, times tan 80 degrees), and room for the reflected
 * rays on the others. The window's cells are the tile's, so the facets, their
 * areas per bin and g1 are the tile's to rounding (1e-9); the visible share of each of the 4 x 8 normal bins and each
 * of the 8 x 16 BRDF bins (single and all bounces) agree within k standard errors of the difference of two
 * independent binomial shares: k = 4 for the 96 normal bins (a family-wise false alarm of 96 x 6.3e-5 = 0.6 %), 4.5
 * for the 768 BRDF bins (768 x 6.8e-6 = 0.5 %); the jittered grids stratify the rays, so the binomial error is an
 * upper bound (the largest differences measured: 1.4 sigma for the normals, 2.8 for the BRDF). No ray leaves the
 * patch in G1 (the margin's promise); in the BRDF a reflected ray may leave within the band, near the horizontal:
 * none at normal incidence, under 0.04 % at 60 and 80 degrees (asserted under 0.1 %). */
static void crop_matches_tile(void **state)
{
    (void)state;
    size_t n = 128;
    double *h = malloc(n * n * sizeof *h);
    ms_tracer *tt = periodic(n, h);
    if (!tt) {
        free(h);
        return;
    }
    size_t nx = 4 * n + 1, ny = 3 * n + 1;
    double *p = crop(h, n, 4, 3);
    ms_tracer *tp = patch_or_fail(p, nx, ny);
    double w[4] = {(double)n, (double)n, 2.0 * (double)n, 2.0 * (double)n};
    const double thetas[3] = {0.0, 60.0, 80.0};
    char err[400];
    for (int i = 0; i < 3; i++) {
        double v[3], auto_w[4];
        view(thetas[i], 30.0, v);
        CHECK(ms_patch_window(tp, v, 0, auto_w, err, sizeof err) == 0, "%s", err);
        CHECK(auto_w[0] <= w[0] && auto_w[1] <= w[1],
              "the tile's window lacks the margin at %g degrees: the "
              "automatic window starts at %g, %g",
              thetas[i], auto_w[0], auto_w[1]);
        ms_g1 a, b;
        CHECK(ms_measure_g1(tt, h, n, v, g1_rays(), 4, 8, NULL, 2, &a, err, sizeof err) == 0, "%s", err);
        CHECK(ms_patch_g1(tp, v, w, g1_rays(), 4, 8, 2, &b, err, sizeof err) == 0, "%s", err);
        CHECK_CLOSE(b.g1, a.g1, 1e-9, 0, "g1 at %g degrees", thetas[i]);
        CHECK(b.left == 0 && b.holes == 0 && b.missed == 0, "rays lost at %g degrees: %ld left, %ld holes", thetas[i],
              b.left, b.holes);
        double zmax = 0.0;
        for (int k = 0; k < 32; k++) {
            CHECK_CLOSE(b.area[k], a.area[k], 1e-9, 1e-15, "bin %d's area at %g degrees", k, thetas[i]);
            double z = z_binomial(a.visible[k] / v[2], a.rays, b.visible[k] / v[2], b.rays);
            CHECK(z <= 4.0, "bin %d at %g degrees: visible %.6g (tile) against %.6g (patch), %.2f sigma", k, thetas[i],
                  a.visible[k], b.visible[k], z);
            zmax = fmax(zmax, z);
        }
        ms_brdf ba, bb;
        CHECK(ms_measure_brdf(tt, n, v, brdf_rays(), 8, 16, 100, 2, &ba, err, sizeof err) == 0, "%s", err);
        CHECK(ms_patch_brdf(tp, v, w, brdf_rays(), 8, 16, 100, 2, &bb, err, sizeof err) == 0, "%s", err);
        CHECK(bb.lost == 0 && bb.left <= bb.rays / 1000, "BRDF at %g degrees: %ld lost, %ld of %ld left", thetas[i],
              bb.lost, bb.left, bb.rays);
        double zb = 0.0;
        for (int k = 0; k < 128; k++) {
            double z1 = z_binomial(ba.single[k], ba.rays, bb.single[k], bb.rays);
            double z2 = z_binomial(ba.all[k], ba.rays, bb.all[k], bb.rays);
            CHECK(z1 <= 4.5 && z2 <= 4.5,
                  "BRDF bin %d at %g degrees: single %.6g against %.6g (%.2f sigma), all %.6g "
                  "against %.6g (%.2f sigma)",
                  k, thetas[i], ba.single[k], bb.single[k], z1, ba.all[k], bb.all[k], z2);
            zb = fmax(zb, fmax(z1, z2));
        }
        printf("crop at %g degrees: g1 %.6f, the largest bin difference %.2f sigma (G1), %.2f sigma (BRDF); BRDF rays "
               "left %ld of %ld\n",
               thetas[i], b.g1, zmax, zb, bb.left, bb.rays);
        ms_g1_free(&a), ms_g1_free(&b), ms_brdf_free(&ba), ms_brdf_free(&bb);
    }
    ms_tracer_free(tp), ms_tracer_free(tt);
    free(p), free(h);
}

/* The negative control: a patch of 3 x 2 tiles at 80 degrees with rays over all of it (no margin). Its cells are the
 * tiles',
 * so its facets are still the tile's, but the rays that start within the band's fall of its downstream sides leave
 * it: the traced G1 (visible over front-facing area) falls short of the facets' g1 by their share, far beyond the
 * binomial standard error of that share (asserted: over 10 of them); and with those rays dropped instead (the
 * visible shares of the rays that hit), the visible normals' bins still differ from the tile's by more than the
 * 4 sigma that the crop meets (the rays that stay are those that hit early: high, front-facing facets). */
static void no_margin_rejected(void **state)
{
    (void)state;
    size_t n = 128;
    double *h = malloc(n * n * sizeof *h);
    ms_tracer *tt = periodic(n, h);
    if (!tt) {
        free(h);
        return;
    }
    double *p = crop(h, n, 3, 2);
    ms_tracer *tp = patch_or_fail(p, 3 * n + 1, 2 * n + 1);
    double v[3], all[4] = {0.0, 0.0, 3.0 * (double)n, 2.0 * (double)n};
    view(80.0, 30.0, v);
    char err[400];
    ms_g1 a, b;
    CHECK(ms_measure_g1(tt, h, n, v, g1_rays(), 4, 8, NULL, 2, &a, err, sizeof err) == 0, "%s", err);
    CHECK(ms_patch_g1(tp, v, all, g1_rays(), 4, 8, 2, &b, err, sizeof err) == 0, "%s", err);
    CHECK_CLOSE(b.g1, a.g1, 1e-9, 0, "the facets' g1");
    double q = (double)b.left / (double)b.rays, se = sqrt(q * (1.0 - q) / (double)b.rays);
    double bias = 1.0 - b.g1_off_risers / a.g1_off_risers;
    CHECK(q > 10.0 * se && bias > 10.0 * se,
          "no margin at 80 degrees: %ld of %ld rays left (%.4f, standard error "
          "%.2g), the traced G1 %.6f against the tile's %.6f",
          b.left, b.rays, q, se, b.g1_off_risers, a.g1_off_risers);
    double zmax = 0.0;
    long kept = b.rays - b.left;
    for (int k = 0; k < 32; k++) {
        double kept_share = b.visible[k] / v[2] * (double)b.rays / (double)kept;
        zmax = fmax(zmax, z_binomial(a.visible[k] / v[2], a.rays, kept_share, kept));
    }
    CHECK(zmax > 4.0,
          "the left rays dropped: the bins within %.2f sigma of the tile's, which the crop's test would "
          "accept",
          zmax);
    printf("no margin at 80 degrees: %.4f of the rays left (standard error %.2g), traced G1 %.6f against %.6f (%.1f %% "
           "low); dropped, the largest bin difference %.1f sigma\n",
           q, se, b.g1_off_risers, a.g1_off_risers, 100.0 * bias, zmax);
    ms_g1_free(&a), ms_g1_free(&b);
    ms_tracer_free(tp), ms_tracer_free(tt);
    free(p), free(h);
}

/* A hole: the heights within 10 spacings of the window's centre missing. Cells with a missing corner are absent
 * (ms_patch_present against the heights), no hit ever lies in one (20,000 rays from random origins at 0 to 75
 * degrees); rays straight down fall through exactly the absent cells, so at normal incidence the share of the rays
 * counted in holes is binomial about the window's absent share (within 4 standard errors); a ray down the hole's
 * centre returns -1; the BRDF counts the rays through the hole as lost, and every ray is binned, lost, left or
 * capped. The results are the same on 1 and 2 threads. */
static void hole(void **state)
{
    (void)state;
    size_t n = 128;
    double *h = malloc(n * n * sizeof *h);
    ms_tracer *tt = periodic(n, h);
    if (!tt) {
        free(h);
        return;
    }
    ms_tracer_free(tt);
    size_t nx = 3 * n + 1, ny = 2 * n + 1, missing = 0, absent = 0;
    double *p = crop(h, n, 3, 2), c = 1.5 * (double)n;
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++)
            if (hypot((double)x - c, (double)y - c) <= 10.0) p[y * nx + x] = NAN, missing++;
    ms_tracer *tp = patch_or_fail(p, nx, ny);
    size_t got_missing, got_absent, window_absent = 0;
    CHECK(ms_tracer_patch(tp, NULL, NULL, NULL, &got_missing, &got_absent) == 1, "a patch");
    for (size_t y = 0; y + 1 < ny; y++)
        for (size_t x = 0; x + 1 < nx; x++) {
            const double *q = p + y * nx + x;
            int gone = isnan(q[0]) || isnan(q[1]) || isnan(q[nx]) || isnan(q[nx + 1]);
            CHECK(ms_patch_present(tp, x, y) == !gone, "cell %zu, %zu", x, y);
            absent += (size_t)gone;
            if (x >= n && x < 2 * n && y >= n && y < 2 * n) window_absent += (size_t)gone;
        }
    CHECK(got_missing == missing && got_absent == absent, "missing %zu (want %zu), absent %zu (want %zu)", got_missing,
          missing, got_absent, absent);
    uint64_t s = 99;
    long hits = 0;
    for (int i = 0; i < 20000; i++) {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        double u = (double)(s >> 11) * 0x1p-53, v[3], o[3];
        view(75.0 * u, 360.0 * u * 7.0, v);
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        o[0] = c - 15.0 + 30.0 * (double)(s >> 11) * 0x1p-53;
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        o[1] = c - 15.0 + 30.0 * (double)(s >> 11) * 0x1p-53;
        o[2] = ms_patch_top(tp);
        double d[3] = {-v[0], -v[1], -v[2]};
        ms_hit hit;
        if (ms_trace(tp, o, d, &hit) != 1) continue;
        hits++;
        CHECK(ms_patch_present(tp, hit.cell % nx, hit.cell / nx), "ray %d hit absent cell %zu", i, hit.cell);
    }
    CHECK(hits > 10000, "only %ld of 20000 rays near the hole hit", hits);
    double down[3] = {0.0, 0.0, -1.0}, o[3] = {c + 0.3, c + 0.2, ms_patch_top(tp)};
    ms_hit hit;
    CHECK(ms_trace(tp, o, down, &hit) == -1, "a ray down the hole's centre");
    double v0[3] = {0.0, 0.0, 1.0}, w[4] = {(double)n, (double)n, 2.0 * (double)n, 2.0 * (double)n};
    char err[400];
    ms_g1 r1, r2;
    CHECK(ms_patch_g1(tp, v0, w, g1_rays(), 4, 8, 2, &r1, err, sizeof err) == 0, "%s", err);
    CHECK(ms_patch_g1(tp, v0, w, g1_rays(), 4, 8, 1, &r2, err, sizeof err) == 0, "%s", err);
    double want = (double)window_absent / (double)(n * n), se = sqrt(want * (1.0 - want) / (double)r1.rays);
    double got = (double)r1.holes / (double)r1.rays;
    CHECK(fabs(got - want) <= 4.0 * se && r1.left == 0,
          "holes %.5f of the rays, the window's absent share %.5f "
          "(standard error %.2g); %ld left",
          got, want, se, r1.left);
    CHECK(r1.holes == r2.holes && memcmp(r1.visible, r2.visible, 32 * sizeof *r1.visible) == 0, "threads changed it");
    ms_brdf b;
    double v60[3];
    view(60.0, 30.0, v60);
    CHECK(ms_patch_brdf(tp, v60, w, brdf_rays() / 4, 8, 16, 100, 2, &b, err, sizeof err) == 0, "%s", err);
    double binned = 0.0;
    for (int k = 0; k < 128; k++) binned += b.all[k] * (double)b.rays;
    CHECK(b.lost > 0 && fabs(binned + (double)(b.lost + b.left + b.capped) - (double)b.rays) < 0.5,
          "BRDF with a hole: %ld lost, %ld left, %ld capped, %.0f binned of %ld", b.lost, b.left, b.capped, binned,
          b.rays);
    printf(
        "hole: %zu missing points, %zu absent cells; at normal incidence %.5f of the rays fell through (the window's "
        "absent share %.5f); BRDF at 60 degrees: %ld of %ld rays lost\n",
        missing, absent, got, want, b.lost, b.rays);
    ms_g1_free(&r1), ms_g1_free(&r2), ms_brdf_free(&b);
    ms_tracer_free(tp);
    free(p), free(h);
}

/* Refusals: too small (2 x 2), no cell present, heights beyond single precision, a view too grazing for the band,
 * a window outside the patch, risers, the light from a bin. */
static void bad_patches(void **state)
{
    (void)state;
    char err[400];
    double four[4] = {0, 1, 2, 3}, *nan9 = malloc(9 * sizeof *nan9), big[9];
    for (int i = 0; i < 9; i++) nan9[i] = NAN, big[i] = i == 4 ? 1e300 : 0.0;
    ms_tracer *t = ms_patch_new(four, 2, 2, err, sizeof err);
    if (!t && strstr(err, "not built")) {
        printf("patch: %s\n", err);
        free(nan9);
        return;
    }
    CHECK(!t && strstr(err, "size"), "2 x 2 accepted (%s)", err);
    t = ms_patch_new(nan9, 3, 3, err, sizeof err);
    CHECK(!t && strstr(err, "no cell"), "all missing accepted (%s)", err);
    nan9[0] = 0.0;
    t = ms_patch_new(big, 3, 3, err, sizeof err);
    CHECK(!t && strstr(err, "1e6"), "1e300 accepted (%s)", err);
    double *p = malloc(32 * 16 * sizeof *p);
    for (int i = 0; i < 32 * 16; i++) p[i] = (i * 7919 % 13) * 0.5;
    t = ms_patch_new(p, 32, 16, err, sizeof err);
    CHECK(t != NULL, "%s", err);
    double v[3], w[4], out[4] = {-1.0, 0.0, 10.0, 10.0};
    view(89.0, 90.0, v);
    ms_g1 r;
    ms_brdf b;
    CHECK(ms_patch_window(t, v, 0, w, err, sizeof err) == -1 && strstr(err, "window"), "89 degrees over 16 rows (%s)",
          err);
    CHECK(ms_measure_g1(t, NULL, 0, v, 1000, 1, 1, NULL, 1, &r, err, sizeof err) == -1, "89 degrees measured");
    view(30.0, 0.0, v);
    CHECK(ms_patch_g1(t, v, out, 1000, 1, 1, 1, &r, err, sizeof err) == -1 && strstr(err, "window"), "(%s)", err);
    size_t risers[2] = {4, 0};
    CHECK(ms_measure_g1(t, NULL, 0, v, 1000, 1, 1, risers, 1, &r, err, sizeof err) == -1, "risers on a patch");
    CHECK(ms_measure_brdf_from_bin(t, 0, 0, 1000, 2, 2, 10, 1, &b, err, sizeof err) == -1, "from a bin on a patch");
    CHECK(ms_measure_g1(t, NULL, 0, v, 1000, 1, 1, NULL, 1, &r, err, sizeof err) == 0, "%s", err);
    ms_g1_free(&r);
    ms_tracer_free(t);
    free(p), free(nan9);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(crop_matches_tile),
        cmocka_unit_test(no_margin_rejected),
        cmocka_unit_test(hole),
        cmocka_unit_test(bad_patches),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    return rc | chi2_budget_end("patch", argc, argv);
}
