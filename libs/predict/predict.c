/* A measured surface's appearance predicted (predict.h). SPDX-License-Identifier: MIT */
#include "predict.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "kirchhoff.h"
#include "microsurface.h"

/* Incidence k of the model (F = 1): each cell's share of ggx_sample_brdf's weights on a jittered 512 x 512 grid of
 * (u1, u2), over the cell's projected solid angle: the cell's mean of f exactly in expectation, however narrow the
 * lobe (a quadrature on points of the cell misses a lobe narrower than it). */
static int model_incidence(const ggx_shape *m, int k, brdf_table *t, char *err, size_t errn)
{
    enum { G = 512 };
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    ggx_vec3 wi = brdf_table_incidence(t, k);
    float *lobe = brdf_table_lobe(t, k, 0);
    int cells = t->res * t->res;
    double *sum = calloc((size_t)cells, sizeof *sum);
    if (!sum) {
        snprintf(err, errn, "predict: out of memory");
        return -1;
    }
    uint64_t z = 0x9E3779B97F4A7C15ull * (uint64_t)(k + 1);
    for (int i = 0; i < G; i++)
        for (int j = 0; j < G; j++) {
            /* splitmix64 for the jitter */
            uint64_t a = (z += 0x9E3779B97F4A7C15ull);
            a = (a ^ (a >> 30)) * 0xBF58476D1CE4E5B9ull, a = (a ^ (a >> 27)) * 0x94D049BB133111EBull, a ^= a >> 31;
            double u1 = (i + (double)(a >> 40) * 0x1.0p-24) / G, u2 = (j + (double)(a & 0xFFFFFF) * 0x1.0p-24) / G;
            ggx_sample smp = ggx_sample_brdf(m, &one, wi, u1, u2);
            if (!(smp.pdf > 0) || !(smp.weight > 0)) continue;
            double wo[3] = {smp.w.x, smp.w.y, smp.w.z};
            int c = brdf_table_cell(t, wo);
            if (c >= 0) sum[c] += smp.weight;
        }
    for (int c = 0; c < cells; c++) lobe[c] = t->area[c] > 0 ? (float)(sum[c] / ((double)G * G * t->area[c])) : 0.0f;
    free(sum);
    return 0;
}

/* The traced rays' outgoing directions into the tables' cells. */
static int table_bin(const void *ctx, const double wo[3]) { return brdf_table_cell(ctx, wo); }

/* Incidence k traced: each cell's share of the rays over its projected solid angle, after one reflection and after
 * any number. */
static int trace_incidence(const predict_spec *s, ms_tracer *tr, int k, predict_result *r, char *err, size_t errn)
{
    ggx_vec3 w = brdf_table_incidence(&r->traced, k);
    double wi[3] = {w.x, w.y, w.z}, win[4];
    char why[300];
    if (ms_patch_window(tr, wi, 1, win, why, sizeof why) != 0) { /* too grazing for the patch's band: not known */
        r->traced.known[k] = r->all.known[k] = 0;
        r->untraced++;
        return 0;
    }
    ms_binning b = {r->traced.res * r->traced.res, table_bin, &r->traced};
    ms_brdf br;
    if (ms_patch_brdf_binned(tr, wi, NULL, s->rays, &b, s->bounces, s->threads, &br, err, errn) != 0) return -1;
    /* the shares of the rays whose way is known: those that fell through a missing region or left the patch's side
     * would have met surface the scan does not hold */
    float *single = brdf_table_lobe(&r->traced, k, 0), *all = brdf_table_lobe(&r->all, k, 0);
    long known = br.rays - br.lost - br.left;
    double scale = known > 0 ? (double)br.rays / (double)known : 0.0;
    for (int c = 0; c < b.bins; c++) {
        double a = r->traced.area[c];
        single[c] = a > 0 ? (float)(scale * br.single[c] / a) : 0.0f;
        all[c] = a > 0 ? (float)(scale * br.all[c] / a) : 0.0f;
    }
    r->rays += br.rays, r->left += br.left, r->lost += br.lost, r->capped += br.capped;
    if (k == 0) memcpy(r->window, br.window, sizeof r->window);
    ms_brdf_free(&br);
    return 0;
}

/* Incidence k by wave optics at the three wavelengths: each cell's share of the power over its projected solid
 * angle. */
static int wave_incidence(const predict_spec *s, const double *h, int k, predict_result *r, char *err, size_t errn)
{
    ggx_vec3 w = brdf_table_incidence(&r->wave, k);
    int cells = r->wave.res * r->wave.res;
    ms_binning b = {cells, table_bin, &r->wave};
    double *share = malloc((size_t)cells * sizeof *share);
    if (!share) {
        snprintf(err, errn, "predict: out of memory");
        return -1;
    }
    for (int c = 0; c < 3; c++) {
        ms_kirchhoff kc;
        /* heights levelled already; a tenth of the light may alias (the upsampling that keeps 99.9 % leaves too small
         * a window to hold the surface's slopes: docs/design/predict.md), on the largest centred window that fits */
        ms_kirchhoff_spec ks = {.h = h,
                                .nx = s->nx,
                                .ny = s->ny,
                                .dx = s->dx,
                                .wavelength = ms_kirchhoff_rgb_um[c],
                                .wi = {w.x, w.y, w.z},
                                .keep_tilt = 1,
                                .max_points = s->wave_points ? s->wave_points : (size_t)1 << 22,
                                .threads = s->threads,
                                .alias = 0.1,
                                .crop = 1};
        if (ms_kirchhoff_setup(&ks, &kc, err, errn) != 0) {
            free(share);
            return -1;
        }
        r->aliased = fmax(r->aliased, kc.aliased);
        if (k == 0 && c == 2) r->upsample = kc.upsample, memcpy(r->wave_window, kc.crop, sizeof r->wave_window);
        ms_kirchhoff_binned(&kc, &b, share);
        ms_kirchhoff_free(&kc);
        float *lobe = brdf_table_lobe(&r->wave, k, c);
        for (int i = 0; i < cells; i++) lobe[i] = r->wave.area[i] > 0 ? (float)(share[i] / r->wave.area[i]) : 0.0f;
    }
    free(share);
    return 0;
}

void predict_free(predict_result *r)
{
    brdf_table_free(&r->traced), brdf_table_free(&r->all), brdf_table_free(&r->wave), brdf_table_free(&r->model);
}

int predict_run(const predict_spec *s, predict_result *r, char *err, size_t errn)
{
    memset(r, 0, sizeof *r);
    if (!(s->nx >= 3 && s->ny >= 3 && s->dx > 0 && isfinite(s->dx))) {
        snprintf(err, errn, "predict: %zu x %zu heights of spacing %g: at least 3 x 3 and a positive spacing", s->nx,
                 s->ny, s->dx);
        return -1;
    }
    size_t n = s->nx * s->ny;
    double *h = malloc(n * sizeof *h), *g = malloc(n * sizeof *g);
    if (!h || !g) {
        free(h), free(g);
        snprintf(err, errn, "predict: out of memory for %zu x %zu heights", s->nx, s->ny);
        return -1;
    }
    memcpy(h, s->h, n * sizeof *h);
    size_t valid = ms_level(h, s->nx, s->ny, 0, NULL);
    double ss = 0;
    for (size_t i = 0; i < n; i++) {
        g[i] = h[i] / s->dx; /* the tracer's heights in grid spacings */
        if (isfinite(h[i])) ss += h[i] * h[i];
    }
    r->missing = 1.0 - (double)valid / (double)n, r->sigma_h = valid ? sqrt(ss / (double)valid) : NAN;
    int fail = brdf_table_init(&r->traced, s->n_theta, s->theta, s->n_phi, s->res, 1, err, errn) ||
               brdf_table_init(&r->all, s->n_theta, s->theta, s->n_phi, s->res, 1, err, errn) ||
               brdf_table_init(&r->model, s->n_theta, s->theta, s->n_phi, s->res, 1, err, errn) ||
               (s->wave && brdf_table_init(&r->wave, s->n_theta, s->theta, s->n_phi, s->res, 3, err, errn));
    ms_tracer *tr = fail ? NULL : ms_patch_new(g, s->nx, s->ny, err, errn);
    free(g);
    if (!tr) {
        free(h);
        predict_free(r);
        return -1;
    }
    int count = brdf_table_count(&r->traced);
    /* normal incidence is one incidence at every azimuth: computed once, copied */
    for (int k = 0; k < count && !fail; k++) {
        int copy = s->theta[k / s->n_phi] == 0 && k % s->n_phi != 0;
        if (copy) {
            size_t cells = (size_t)s->res * (size_t)s->res;
            memcpy(brdf_table_lobe(&r->traced, k, 0), brdf_table_lobe(&r->traced, 0, 0), cells * sizeof(float));
            memcpy(brdf_table_lobe(&r->all, k, 0), brdf_table_lobe(&r->all, 0, 0), cells * sizeof(float));
            memcpy(brdf_table_lobe(&r->model, k, 0), brdf_table_lobe(&r->model, 0, 0), cells * sizeof(float));
            r->traced.known[k] = r->traced.known[0], r->all.known[k] = r->all.known[0];
            r->model.known[k] = r->model.known[0];
            if (s->wave) r->wave.known[k] = r->wave.known[0];
            if (s->wave)
                for (int c = 0; c < 3; c++)
                    memcpy(brdf_table_lobe(&r->wave, k, c), brdf_table_lobe(&r->wave, 0, c), cells * sizeof(float));
            continue;
        }
        fail = trace_incidence(s, tr, k, r, err, errn);
        /* where the trace is not known, neither is the rest: every row is a mean over the same incidences */
        if (!fail && !r->traced.known[k]) {
            r->model.known[k] = 0;
            if (s->wave) r->wave.known[k] = 0;
            continue;
        }
        fail = fail || model_incidence(s->model, k, &r->model, err, errn) ||
               (s->wave && wave_incidence(s, h, k, r, err, errn));
        if (s->progress) s->progress(s->progress_ctx, k + 1, count);
    }
    ms_tracer_free(tr);
    free(h);
    if (fail) predict_free(r);
    return fail ? -1 : 0;
}

/* the mean of the finite values (NaN where there are none) */
static double mean_finite(const double *v, int n)
{
    double s = 0;
    int k = 0;
    for (int i = 0; i < n; i++)
        if (isfinite(v[i])) s += v[i], k++;
    return k ? s / k : NAN;
}

double predict_row_albedo(const brdf_table *t, int it, int ch)
{
    double v[360];
    for (int j = 0; j < t->n_phi; j++) v[j] = brdf_table_albedo(t, it * t->n_phi + j, ch);
    return mean_finite(v, t->n_phi);
}

double predict_row_l2(const brdf_table *a, int ca, const brdf_table *b, int cb, int it)
{
    double v[360];
    for (int j = 0; j < a->n_phi; j++) v[j] = brdf_table_l2(a, ca, b, cb, it * a->n_phi + j);
    return mean_finite(v, a->n_phi);
}

predict_incidence predict_incidence_of(const predict_result *r, int k)
{
    predict_incidence q = {brdf_table_albedo(&r->traced, k, 0),
                           brdf_table_albedo(&r->all, k, 0),
                           {NAN, NAN, NAN},
                           brdf_table_albedo(&r->model, k, 0),
                           brdf_table_l2(&r->model, 0, &r->traced, 0, k),
                           NAN,
                           NAN};
    if (r->wave.f) {
        for (int c = 0; c < 3; c++) q.albedo_wave[c] = brdf_table_albedo(&r->wave, k, c);
        q.l2_model_wave = brdf_table_l2(&r->model, 0, &r->wave, 1, k);
        q.l2_traced_wave = brdf_table_l2(&r->traced, 0, &r->wave, 1, k);
    }
    return q;
}
