/* Benchmark of the fits (include/ggx/ggx_fit.h): EM throughput in samples per second per pass over the data, and the
 * time of a 4096 x 4096 height field's fit, on 1 and 2 threads. Prints; never fails. SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ggx/ggx_fit.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double rnd(uint64_t *s)
{
    *s = *s * 6364136223846793005u + 1442695040888963407u;
    return (double)(*s >> 11) * 0x1p-53;
}

/* Passes over the data of one ggx_fit_* of at most 2^22 samples (EM on all of them): the moments (1), the Gaussian's
 * two, per Student-t model its iterations and at least one information pass, the tails' passes, and the goodness of
 * fit's cells (1): a lower bound, so the throughput below is too. */
static int passes(const ggx_fit_info *info)
{
    int p = 4 + info->tails.iterations;
    for (int k = 0; k < 3; k++) p += info->models[k].iterations + 1;
    return p;
}

int main(int argc, char **argv)
{
    int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
    size_t n = quick ? 1u << 20 : 1u << 22;
    uint64_t seed = 1;
    ggx_shape s;
    ggx_shape_ellipsoid(&s, 0.3, 0.1, 0.4, -0.2, 0.7);
    ggx_vec3 *m = malloc(n * sizeof *m);
    for (size_t i = 0; i < n; i++) m[i] = ggx_sample_ndf(&s, rnd(&seed), rnd(&seed));
    printf("libggx fit benchmark (%s)\n\n", quick ? "quick" : "full");
    printf("ggx_fit_normals, %zu normals of a skewed shape (alpha 0.3, 0.1):\n", n);
    printf("%-8s %10s %8s %14s %16s\n", "threads", "seconds", "passes", "ns per sample", "M samples/s/pass");
    for (int t = 1; t <= 2; t++) {
        ggx_fit_options o;
        memset(&o, 0, sizeof o);
        o.threads = t;
        ggx_shape f;
        ggx_fit_info info;
        double best = 1e30;
        for (int r = 0; r < 3; r++) {
            double t0 = now();
            ggx_fit_normals(&f, m, NULL, n, &o, &info);
            best = fmin(best, now() - t0);
        }
        int p = passes(&info);
        printf("%-8d %10.3f %8d %14.2f %16.1f\n", t, best, p, 1e9 * best / ((double)n * p), (double)n * p / best / 1e6);
    }
    free(m);

    /* A 4096^2 height field: separable random walks, so slopes are Gaussian (the fit's four models all run). */
    size_t nx = quick ? 1024 : 4096, ny = nx;
    double *h = malloc(nx * ny * sizeof *h), *F = malloc(nx * sizeof *F), *G = malloc(ny * sizeof *G);
    F[0] = G[0] = 0.0;
    for (size_t i = 1; i < nx; i++) F[i] = F[i - 1] + 0.2 * (rnd(&seed) - 0.5);
    for (size_t j = 1; j < ny; j++) G[j] = G[j - 1] + 0.1 * (rnd(&seed) - 0.5);
    for (size_t j = 0; j < ny; j++)
        for (size_t i = 0; i < nx; i++) h[j * nx + i] = F[i] + G[j];
    printf(
        "\nggx_fit_heightfield, %zu x %zu heights (%zu facets; above 2^22 samples: EM on 2^20, then steps on all):\n",
        nx, ny, 4 * (nx - 1) * (ny - 1));
    printf("%-8s %10s %14s\n", "threads", "seconds", "ns per facet");
    for (int t = 1; t <= 2; t++) {
        ggx_fit_options o;
        memset(&o, 0, sizeof o);
        o.threads = t;
        ggx_shape f;
        ggx_fit_info info;
        double t0 = now();
        ggx_fit_heightfield(&f, h, nx, ny, 1.0, 1.0, NULL, &o, &info);
        double dt = now() - t0;
        printf("%-8d %10.3f %14.2f\n", t, dt, 1e9 * dt / (double)info.used);
    }
    free(h), free(F), free(G);
    return 0;
}
