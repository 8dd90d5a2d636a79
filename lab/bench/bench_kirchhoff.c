/* Benchmark of the Kirchhoff BRDF (libs/microsurface/kirchhoff.h): seconds for the setup (the windowed phase field
 * and its FFT, one level, no upsampling) and the binning of n x n patches (n = 1024, 2048) at one wavelength on 1
 * and 2 threads, beside a bare KISS FFT (kiss_fftnd) of the same size on one thread, the floor. Prints; never fails.
 * SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <kiss_fftnd.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "kirchhoff.h"
#include "microsurface.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(void)
{
    printf("libggx Kirchhoff BRDF benchmark: Gaussian fields (alpha 0.2, correlation length 16), spacing 0.1,\n"
           "wavelength 0.5, view (0.3, 0.2), 8 x 16 bins; the best of 3 runs\n\n");
    printf("%-6s %12s %10s %10s %12s %14s\n", "n", "bare FFT, s", "1 thr, s", "2 thr, s", "of it bin, s",
           "2 thr / FFT");
    for (size_t n = 1024; n <= 2048; n *= 2) {
        double *h = malloc(n * n * sizeof *h), share[128];
        char err[300];
        ms_gauss_spec gs = {n, 0.2, 0.2, 0.0, 16, 5};
        if (!h || ms_gauss(&gs, h, NULL, err, sizeof err) != 0) {
            printf("%-6zu %s\n", n, h ? err : "out of memory");
            free(h);
            continue;
        }
        for (size_t i = 0; i < n * n; i++) h[i] *= 0.1; /* heights in the spacing's unit */
        /* the floor: one forward complex 2-D transform of the same size */
        int dims[2] = {(int)n, (int)n};
        kiss_fftnd_cfg cfg = kiss_fftnd_alloc(dims, 2, 0, NULL, NULL);
        kiss_fft_cpx *a = calloc(n * n, sizeof *a), *b = malloc(n * n * sizeof *b);
        double fft = INFINITY, t1 = INFINITY, t2 = INFINITY, tb = INFINITY;
        for (int rep = 0; rep < 3 && cfg && a && b; rep++) {
            for (size_t i = 0; i < n * n; i++) a[i].r = (float)cos(h[i]), a[i].i = (float)sin(h[i]);
            double t0 = now();
            kiss_fftnd(cfg, a, b);
            fft = fmin(fft, now() - t0);
        }
        kiss_fft_free(cfg), free(a), free(b);
        for (int thr = 1; thr <= 2; thr++)
            for (int rep = 0; rep < 3; rep++) {
                ms_kirchhoff_spec s = {h, n, n, 0.1, 0.5, {0.3, 0.2, sqrt(0.87)}, 1, 1, 0, 0, 0, thr};
                ms_kirchhoff k;
                double t0 = now();
                if (ms_kirchhoff_setup(&s, &k, err, sizeof err) != 0) {
                    printf("%-6zu %s\n", n, err);
                    break;
                }
                double ts = now();
                ms_kirchhoff_bin(&k, 8, 16, share);
                double te = now();
                if (thr == 1) t1 = fmin(t1, te - t0);
                else t2 = fmin(t2, te - t0), tb = fmin(tb, te - ts);
                ms_kirchhoff_free(&k);
            }
        printf("%-6zu %12.3f %10.3f %10.3f %12.3f %14.2f\n", n, fft, t1, t2, tb, t2 / fft);
        free(h);
    }
    return 0;
}
