/* The tabulated BRDF (libs/predict/brdf_table.h): the cells' projected solid angles fill the disk; a direction's cell
 * holds it; at an incidence of the grid and a cell's centre the table returns what was stored; between incidences the
 * shifted lobes reproduce the model's BRDF (relative L2 over random pairs, against the blend at a fixed wo that the
 * shift replaces, which must do worse); bad grids are refused. The predictions (libs/predict/predict.h): the tracer's
 * binning by a caller's function is its own binning; a plane's traced and wave BRDFs are the mirror's; a rough field
 * many wavelengths deep gives the same BRDF by geometric and wave optics and its fitted model's; bad heights are
 * refused. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "brdf_table.h"
#include "ggx/ggx.h"
#include "ggx/ggx_fit.h"
#include "kirchhoff.h"
#include "microsurface.h"
#include "predict.h"
#include "testlib.h"

#define DEG (GGX_PI / 180)

static void fill_model(brdf_table *t, const ggx_shape *s)
{
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    for (int k = 0; k < brdf_table_count(t); k++) {
        ggx_vec3 wi = brdf_table_incidence(t, k);
        float *lobe = brdf_table_lobe(t, k, 0);
        for (int c = 0; c < t->res * t->res; c++)
            lobe[c] = t->area[c] > 0 ? (float)ggx_brdf_eval(s, &one, wi, brdf_table_cell_dir(t, c)) : 0.0f;
    }
}

static void cells(void **state)
{
    (void)state;
    brdf_table t;
    char err[200];
    double th[3] = {0, 30 * DEG, 60 * DEG};
    CHECK(brdf_table_init(&t, 3, th, 4, 64, 1, err, sizeof err) == 0, "%s", err);
    double sum = 0;
    for (int c = 0; c < 64 * 64; c++) sum += t.area[c];
    /* the rim cells counted on 16 x 16 points each: about 4 res cells on the rim, each off by up to h^2 / 256 */
    CHECK(fabs(sum - GGX_PI) < 4 * 64 * (2.0 / 64) * (2.0 / 64) / 256 * 4, "disk %.9g", sum);
    rng r = {3};
    for (int i = 0; i < 1000; i++) {
        double u = rng_uniform(&r), p = 2 * GGX_PI * rng_uniform(&r), s = sqrt(u);
        double wo[3] = {s * cos(p), s * sin(p), sqrt(1 - u)};
        int c = brdf_table_cell(&t, wo);
        CHECK(c >= 0 && t.area[c] > 0, "direction %d in cell %d of area %g", i, c, c >= 0 ? t.area[c] : -1);
        ggx_vec3 d = brdf_table_cell_dir(&t, c);
        CHECK(fabs(d.x - wo[0]) <= 1.0 / 64 + 1e-12 && fabs(d.y - wo[1]) <= 1.0 / 64 + 1e-12, "cell centre");
    }
    double below[3] = {0.1, 0.1, -0.2}, nan[3] = {NAN, 0, 1};
    CHECK(brdf_table_cell(&t, below) == -1 && brdf_table_cell(&t, nan) == -1, "below or NaN given a cell");
    brdf_table_free(&t);
}

/* The mean relative error |f_table - f| / f over random pairs weighted by f (an L1 of the lobe), shifted or not. */
static double table_error(const brdf_table *t, const ggx_shape *s, int shifted)
{
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    rng r = {11};
    double num = 0, den = 0;
    for (int i = 0; i < 20000; i++) {
        double ti = rng_uniform(&r) * 75 * DEG, pi = 2 * GGX_PI * rng_uniform(&r);
        double u = rng_uniform(&r), p = 2 * GGX_PI * rng_uniform(&r), q = sqrt(u);
        ggx_vec3 wi = {sin(ti) * cos(pi), sin(ti) * sin(pi), cos(ti)}, wo = {q * cos(p), q * sin(p), sqrt(1 - u)};
        double f = ggx_brdf_eval(s, &one, wi, wo), g[3];
        if (shifted) brdf_table_eval(t, wi, wo, g);
        else {
            /* the blend at a fixed wo: the same table read without the shift (one lobe per incidence at wo) */
            ggx_vec3 w0 = wo;
            brdf_table_eval(t, wi, w0, g);
            double th = acos(wi.z), best = HUGE_VAL;
            int kb = 0;
            for (int k = 0; k < brdf_table_count(t); k++) {
                ggx_vec3 wk = brdf_table_incidence(t, k);
                double d = acos(fmin(1, wk.x * wi.x + wk.y * wi.y + wk.z * wi.z));
                if (d < best) best = d, kb = k;
            }
            (void)th;
            g[0] = t->area[brdf_table_cell(t, (double[3]){wo.x, wo.y, wo.z})] > 0
                       ? brdf_table_lobe(t, kb, 0)[brdf_table_cell(t, (double[3]){wo.x, wo.y, wo.z})]
                       : 0;
        }
        num += fabs(g[0] - f), den += f;
    }
    return num / den;
}

static void interpolation(void **state)
{
    (void)state;
    double th[7] = {0, 15 * DEG, 30 * DEG, 45 * DEG, 60 * DEG, 72 * DEG, 82 * DEG};
    ggx_shape shapes[3];
    ggx_shape_iso(&shapes[0], 0.3);
    ggx_shape_ellipsoid(&shapes[1], 0.2, 0.45, 0, 0, 30 * DEG);
    ggx_shape_ellipsoid(&shapes[2], 0.25, 0.35, 15 * DEG, -10 * DEG, 20 * DEG);
    for (int i = 0; i < 3; i++) {
        brdf_table t;
        char err[200];
        CHECK(brdf_table_init(&t, 7, th, 12, 128, 1, err, sizeof err) == 0, "%s", err);
        fill_model(&t, &shapes[i]);
        /* on the grid: the stored value at a cell centre */
        for (int k = 0; k < brdf_table_count(&t); k += 5) {
            ggx_vec3 wi = brdf_table_incidence(&t, k);
            for (int c = 0; c < 128 * 128; c += 97) {
                if (!(t.area[c] == 4.0 / (128 * 128))) continue;
                double g[3];
                brdf_table_eval(&t, wi, brdf_table_cell_dir(&t, c), g);
                double want = brdf_table_lobe(&t, k, 0)[c];
                CHECK(fabs(g[0] - want) <= 1e-5 * want + 1e-12, "incidence %d cell %d: %.9g, want %.9g", k, c, g[0],
                      want);
                CHECK(g[1] == g[0] && g[2] == g[0], "one channel copied");
            }
        }
        if (i == 0) {
            /* an incidence not known: its albedo and distances NaN; read at its own direction (where it is the only
             * one of its four) from the nearest known one, never 0 */
            int k = 2 * 12 + 5;
            t.known[k] = 0;
            ggx_vec3 wi = brdf_table_incidence(&t, k);
            double g[3], mirror[3] = {-wi.x, -wi.y, wi.z};
            ggx_vec3 wo = brdf_table_cell_dir(&t, brdf_table_cell(&t, mirror));
            brdf_table_eval(&t, wi, wo, g);
            CHECK(isnan(brdf_table_albedo(&t, k, 0)) && isnan(brdf_table_l2(&t, 0, &t, 0, k)), "unknown values");
            CHECK(g[0] > 0, "an unknown incidence read as %g", g[0]);
            t.known[k] = 1;
        }
        double e = table_error(&t, &shapes[i], 1), e0 = table_error(&t, &shapes[i], 0);
        printf("shape %d: shifted lobes' mean relative error %.4f, the nearest incidence at a fixed wo %.4f\n", i, e,
               e0);
        /* measured 0.070, 0.074, 0.093 for 7 x 12 incidences (0.055 to 0.075 with 24 to 48 azimuths): what is left
         * is the lobe's change of shape with the incidence (its width in wo_xy scales with wi.z + wo.z) */
        CHECK(e < 0.12, "the shifted table is %.3g off the model", e);
        CHECK(e0 > 2 * e, "the fixed-wo reading (%.3g) is not worse than the shifted one (%.3g)", e0, e);
        brdf_table_free(&t);
    }
}

/* Filled with the model's cell means: each incidence's albedo is ggx_albedo's (a quadrature of 128^2 cells of 4 x 4
 * points; the rim's cells counted by their points inside), and the L2 distance of a table scaled by s from the table
 * is |s - 1|. */
typedef struct model_ctx {
    const ggx_shape *s;
    double scale;
} model_ctx;
static void model_f(const void *ctx, ggx_vec3 wi, ggx_vec3 wo, double f[3])
{
    const model_ctx *m = ctx;
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    f[0] = m->scale * ggx_brdf_eval(m->s, &one, wi, wo);
}
static void albedo_and_l2(void **state)
{
    (void)state;
    double th[4] = {0, 30 * DEG, 60 * DEG, 80 * DEG};
    ggx_shape s;
    ggx_shape_ellipsoid(&s, 0.25, 0.4, 10 * DEG, 0, 30 * DEG);
    brdf_table a, b;
    char err[200];
    CHECK(brdf_table_init(&a, 4, th, 3, 128, 1, err, sizeof err) == 0 &&
              brdf_table_init(&b, 4, th, 3, 128, 1, err, sizeof err) == 0,
          "%s", err);
    model_ctx ma = {&s, 1}, mb = {&s, 1.25};
    brdf_table_fill(&a, model_f, &ma, 4);
    brdf_table_fill(&b, model_f, &mb, 4);
    for (int k = 0; k < brdf_table_count(&a); k++) {
        ggx_vec3 wi = brdf_table_incidence(&a, k);
        double e = brdf_table_albedo(&a, k, 0), want = ggx_albedo(&s, wi);
        /* measured within 4e-4 relative to 80 degrees */
        CHECK(fabs(e - want) < 2e-3 * want, "incidence %d: albedo %.6f, ggx_albedo %.6f", k, e, want);
        double l = brdf_table_l2(&b, 0, &a, 0, k), l0 = brdf_table_l2(&a, 0, &a, 0, k);
        CHECK(fabs(l - 0.25) < 1e-6 && l0 == 0, "L2 of the scaled table %.9g, of itself %.3g", l, l0);
    }
    brdf_table_free(&a);
    brdf_table_free(&b);
}

static void refused(void **state)
{
    (void)state;
    brdf_table t;
    char err[200] = "";
    double th[2] = {10 * DEG, 5 * DEG}, ok[1] = {0}, big[1] = {GGX_PI / 2};
    CHECK(brdf_table_init(&t, 2, th, 4, 16, 1, err, sizeof err) == -1 && strstr(err, "increasing"), "%s", err);
    CHECK(brdf_table_init(&t, 1, big, 4, 16, 1, err, sizeof err) == -1, "90 degrees taken");
    CHECK(brdf_table_init(&t, 1, ok, 4, 3, 1, err, sizeof err) == -1, "res 3 taken");
    CHECK(brdf_table_init(&t, 1, ok, 4, 16, 2, err, sizeof err) == -1, "2 channels taken");
    CHECK(brdf_table_init(&t, 0, ok, 4, 16, 1, err, sizeof err) == -1, "no polar angle taken");
}

/* ms_patch_brdf_binned with the tracer's own rings and sectors as the caller's binning: the same shares, bit for
 * bit, as ms_patch_brdf (one loop behind both). */
static void binned_is_rings(void **state)
{
    (void)state;
    enum { NX = 70, NY = 50 };
    static double h[NX * NY];
    rng r = {5};
    for (int i = 0; i < NX * NY; i++) h[i] = 0.6 * sin(0.31 * (i % NX)) * cos(0.23 * (i / NX)) + 0.2 * rng_uniform(&r);
    char err[300];
    ms_tracer *t = ms_patch_new(h, NX, NY, err, sizeof err);
    CHECK(t, "%s", err);
    double wi[3] = {0.5, 0.2, sqrt(1 - 0.29)};
    ms_brdf a, b;
    ms_ring_bins rb;
    ms_binning bins = ms_ring_binning(&rb, 6, 12);
    CHECK(ms_patch_brdf(t, wi, NULL, 20000, 6, 12, 50, 2, &a, err, sizeof err) == 0, "%s", err);
    CHECK(ms_patch_brdf_binned(t, wi, NULL, 20000, &bins, 50, 2, &b, err, sizeof err) == 0, "%s", err);
    CHECK(a.rays == b.rays && a.left == b.left && a.lost == b.lost && b.rings == 72 && b.sectors == 1, "counts");
    double tot = 0;
    for (int k = 0; k < 72; k++) {
        CHECK(a.single[k] == b.single[k] && a.all[k] == b.all[k], "bin %d: %g %g against %g %g", k, a.single[k],
              a.all[k], b.single[k], b.all[k]);
        tot += a.all[k];
    }
    CHECK(tot > 0.9, "only %g of the rays binned", tot);
    ms_brdf_free(&a), ms_brdf_free(&b);
    ms_tracer_free(t);
}

/* A small run: 2 polar angles x 3 azimuths, 24 x 24 cells. */
static int run(const double *h, size_t nx, size_t ny, double dx, const ggx_shape *model, const double th[2], int res,
               predict_result *r, char *err, size_t errn)
{
    predict_spec sp = {0};
    sp.h = h, sp.nx = nx, sp.ny = ny, sp.dx = dx, sp.model = model;
    sp.n_theta = 2, sp.theta[0] = th[0], sp.theta[1] = th[1], sp.n_phi = 3, sp.res = res;
    sp.rays = 40000, sp.bounces = 50, sp.wave = ms_kirchhoff_built(), sp.wave_points = (size_t)1 << 20, sp.threads = 2;
    return predict_run(&sp, r, err, errn);
}

/* A tilted plane with a hole (levelled first): every traced ray that does not fall through the hole leaves in the
 * mirror's cell, and the wave optics puts the power there too (to the Hann window's spread within the cell's
 * neighbours). */
static void plane(void **state)
{
    (void)state;
    enum { NX = 60, NY = 44 };
    static double h[NX * NY];
    int holes = 0;
    for (int y = 0; y < NY; y++)
        for (int x = 0; x < NX; x++) {
            double dx = x - 20.0, dy = y - 30.0;
            h[y * NX + x] = dx * dx + dy * dy < 9 ? NAN : 0.3 * x - 0.1 * y;
            holes += isnan(h[y * NX + x]);
        }
    ggx_shape s;
    ggx_shape_iso(&s, 0.1);
    predict_result r;
    char err[300];
    const double th[2] = {0, 35 * DEG};
    CHECK(run(h, NX, NY, 0.5, &s, th, 24, &r, err, sizeof err) == 0, "%s", err);
    CHECK(r.left == 0 && fabs(r.missing - (double)holes / (NX * NY)) < 1e-12, "left %ld, missing share %g", r.left,
          r.missing);
    for (int k = 0; k < brdf_table_count(&r.traced); k++) {
        ggx_vec3 wi = brdf_table_incidence(&r.traced, k);
        double mirror[3] = {-wi.x, -wi.y, wi.z};
        int c = brdf_table_cell(&r.traced, mirror);
        double in = brdf_table_lobe(&r.traced, k, 0)[c] * r.traced.area[c], e = brdf_table_albedo(&r.traced, k, 0);
        CHECK(fabs(in - e) < 1e-6 && e > 0.97 && e <= 1, "incidence %d: %g in the mirror's cell of albedo %g", k, in,
              e);
        for (int ch = 0; ch < 3 && r.wave.f; ch++) {
            double w = brdf_table_albedo(&r.wave, k, ch), near = 0;
            int ci = c % r.wave.res, cj = c / r.wave.res;
            for (int dj = -1; dj <= 1; dj++)
                for (int di = -1; di <= 1; di++) {
                    int q = (cj + dj) * r.wave.res + ci + di;
                    near += brdf_table_lobe(&r.wave, k, ch)[q] * r.wave.area[q];
                }
            CHECK(fabs(w - 1) < 1e-3 && near > 0.999 * w, "incidence %d colour %d: wave albedo %g, %g by the mirror", k,
                  ch, w, near);
        }
    }
    predict_free(&r);
}

/* A Gaussian field (Beckmann facets) whose heights are many wavelengths deep (sigma_h about 3 um, lambda 0.47 to 0.63 um): wave optics
 * approaches geometric optics (the relative L2 of the traced single scattering against the wave BRDF), and the
 * model fitted to the field is near both. Bounds: the measured distances (printed) with their speckle and ray
 * noise at this size, times about 1.5. */
static void rough(void **state)
{
    (void)state;
    enum { N = 256 };
    static double h[N * N];
    char err[300];
    ms_gauss_spec gs = {N, 0.3, 0.3, 0, 16, 7};
    if (ms_gauss(&gs, h, NULL, err, sizeof err) != 0) {
        CHECK(strstr(err, "not built") != NULL, "%s", err);
        printf("predict: %s: the rough field is not tested\n", err);
        return;
    }
    for (int i = 0; i < N * N; i++) h[i] *= 0.5; /* grid units to micrometres at dx 0.5 um */
    ggx_shape fit;
    ggx_heightfield_options ho = {0, 0};
    CHECK(ggx_fit_heightfield(&fit, h, N, N, 0.5, 0.5, &ho, NULL, NULL) == GGX_OK, "fit");
    predict_result r;
    const double th[2] = {0, 40 * DEG};
    CHECK(run(h, N, N, 0.5, &fit, th, 6, &r, err, sizeof err) == 0, "%s", err);
    /* the white furnace of the trace: every bounce of the rays whose way is known leaves (F = 1, none capped) */
    for (int k = 0; k < brdf_table_count(&r.all); k++)
        CHECK(r.capped == 0 && fabs(brdf_table_albedo(&r.all, k, 0) - 1) < 1e-5, "incidence %d: every bounce %.7f", k,
              brdf_table_albedo(&r.all, k, 0));
    for (int it = 0; it < 2; it++) {
        double lm = predict_row_l2(&r.model, 0, &r.traced, 0, it), e = predict_row_albedo(&r.traced, it, 0);
        printf("rough field, theta_i %.0f: traced albedo %.4f, model %.4f; L2 model/traced %.3f", th[it] / DEG, e,
               predict_row_albedo(&r.model, it, 0), lm);
        /* GGX fitted to Beckmann facets: measured 0.30, 0.26 */
        CHECK(lm < 0.45, "the fitted model is %.3g from the traced BRDF", lm);
        if (r.wave.f) {
            double lw = predict_row_l2(&r.traced, 0, &r.wave, 1, it), ew = predict_row_albedo(&r.wave, it, 1);
            printf(", traced/wave %.3f, wave albedo %.4f (sigma_h %.2f um, %.1f %% aliased)", lw, ew, r.sigma_h,
                   100 * r.aliased);
            /* measured 0.170, 0.153: the Hann window weighs the field's middle, the trace its window uniformly */
            CHECK(lw < 0.3, "geometric and wave optics %.3g apart", lw);
            if (it) {
                /* the trace from phi 0 against the wave lobe from phi 120 degrees: the distance the comparison must
                 * tell from the right one's */
                ggx_vec3 a = brdf_table_incidence(&r.traced, 3), b = brdf_table_incidence(&r.wave, 4);
                CHECK(fabs(a.z - b.z) < 1e-12 && fabs(a.x - b.x) > 0.5, "incidences");
                double mism = 0, d = 0;
                const float *ft = brdf_table_lobe(&r.traced, 3, 0), *fw = brdf_table_lobe(&r.wave, 4, 1);
                for (int c = 0; c < r.traced.res * r.traced.res; c++) {
                    double q = (double)ft[c] - fw[c];
                    mism += q * q * r.traced.area[c], d += (double)ft[c] * ft[c] * r.traced.area[c];
                }
                mism = sqrt(mism / d);
                printf(" (against another azimuth's: %.3f)", mism);
                double right = brdf_table_l2(&r.traced, 0, &r.wave, 1, 3);
                CHECK(mism > 3 * right, "a wrong lobe %.3g is not told from the right one %.3g", mism, right);
            }
            CHECK(fabs(ew - e) < 0.03, "wave albedo %.4f, traced %.4f", ew, e);
        }
        printf("\n");
    }
    predict_free(&r);
}

static void bad_heights(void **state)
{
    (void)state;
    double h[16], none[16];
    for (int i = 0; i < 16; i++) h[i] = i % 3, none[i] = NAN;
    ggx_shape s;
    ggx_shape_iso(&s, 0.1);
    predict_result r;
    char err[300] = "";
    const double th[2] = {0, 30 * DEG};
    CHECK(run(h, 2, 8, 1, &s, th, 24, &r, err, sizeof err) == -1 && strstr(err, "3 x 3"), "2 x 8 taken: %s", err);
    CHECK(run(none, 4, 4, 1, &s, th, 24, &r, err, sizeof err) == -1, "no valid height taken");
    CHECK(run(h, 4, 4, NAN, &s, th, 24, &r, err, sizeof err) == -1, "a NaN spacing taken");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cells),   cmocka_unit_test(interpolation),   cmocka_unit_test(albedo_and_l2),
        cmocka_unit_test(refused), cmocka_unit_test(binned_is_rings), cmocka_unit_test(plane),
        cmocka_unit_test(rough),   cmocka_unit_test(bad_heights),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
