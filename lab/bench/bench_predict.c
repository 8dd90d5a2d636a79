/* Benchmark of a prediction (libs/predict/predict.h) at ggx predict's defaults (5 x 4 incidences, 127^2 cells,
 * 1,000,000 traced rays per incidence, the wave optics at three wavelengths on at most 2^22 FFT points): seconds of
 * the fit, the trace and the wave optics on the public rubber scan (860 x 634) and on a 1197 x 940 window of a
 * generated Gaussian field (alpha 0.2, correlation length 16, spacing 1 um: no public scan of that size is at hand),
 * on 2 threads. Prints; never fails. SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ggx/ggx_fit.h"
#include "microsurface.h"
#include "predict.h"
#include "surface.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void one(const char *name, const double *h, size_t nx, size_t ny, double dx)
{
    double t0 = now();
    ggx_shape fit;
    ggx_heightfield_options ho = {0, 0};
    ggx_fit_options fo = {0};
    fo.threads = 2;
    if (ggx_fit_heightfield(&fit, h, nx, ny, dx, dx, &ho, &fo, NULL) != GGX_OK) {
        printf("%-34s the fit failed\n", name);
        return;
    }
    double t1 = now();
    predict_spec sp = {0};
    const double th[5] = {0, 20, 40, 60, 75};
    sp.h = h, sp.nx = nx, sp.ny = ny, sp.dx = dx, sp.model = &fit, sp.n_theta = 5, sp.n_phi = 4, sp.res = 127;
    for (int i = 0; i < 5; i++) sp.theta[i] = th[i] * 3.14159265358979323846 / 180;
    sp.rays = 1000000, sp.bounces = 100, sp.threads = 2;
    predict_result r;
    char err[300];
    double tt[2];
    for (int wave = 0; wave < 2; wave++) {
        sp.wave = wave;
        double a = now();
        if (predict_run(&sp, &r, err, sizeof err) != 0) {
            printf("%-34s %s\n", name, err);
            return;
        }
        tt[wave] = now() - a;
        if (wave)
            printf("%-34s %8.2f %10.2f %10.2f %10.2f %12.1f\n", name, t1 - t0, tt[0], tt[1] - tt[0], t1 - t0 + tt[1],
                   (double)r.rays / tt[0] * 1e-6);
        predict_free(&r);
    }
}

int main(void)
{
    printf("libggx prediction benchmark (ggx predict's defaults, 2 threads)\n\n");
    printf("%-34s %8s %10s %10s %10s %12s\n", "surface", "fit, s", "trace, s", "wave, s", "total, s", "M rays/s");
    surface s;
    surface_read_options ro = {SURFACE_HEIGHTS, 0};
    char err[300];
    const char *scan = "tests/data/x3p/KautschukInfiniteFocus.x3p";
    if (surface_read(scan, &ro, &s, err, sizeof err) == 0) {
        for (size_t i = 0; i < s.nx * s.ny; i++) s.h[i] *= s.z_scale * 1e6; /* micrometres */
        one("rubber scan, 860 x 634", s.h, s.nx, s.ny, s.dx * 1e6);
        surface_free(&s);
    } else printf("%-34s %s (run from the source tree)\n", "rubber scan", err);
    size_t n = 2048, nx = 1197, ny = 940;
    double *g = malloc(n * n * sizeof *g), *h = malloc(nx * ny * sizeof *h);
    ms_gauss_spec gs = {n, 0.2, 0.2, 0.0, 16, 3};
    if (g && h && ms_gauss(&gs, g, NULL, err, sizeof err) == 0) {
        for (size_t y = 0; y < ny; y++)
            for (size_t x = 0; x < nx; x++) h[y * nx + x] = g[(y + 300) * n + x + 200];
        one("generated field, 1197 x 940", h, nx, ny, 1.0);
    } else printf("%-34s %s\n", "generated field", g && h ? err : "out of memory");
    free(g), free(h);
    return 0;
}
