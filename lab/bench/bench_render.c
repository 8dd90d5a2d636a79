/* Benchmark of the renderer (libs/render/render.h): the time of a 512 x 512 conductor sphere under the built-in sky at
 * 64 samples per pixel on 1 and 2 threads, and the noise of the reflection samplers in a picture: the RMSE of 64-spp
 * images against a 4096-spp reference, and the efficiency 1 / (RMSE^2 x seconds), for brdf (VNDF reflection) against
 * the bounded samplers. Prints; never fails. SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "render.h"

#define DEG (GGX_PI / 180)

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double rmse(const float *a, const float *b, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++) s += ((double)a[i] - b[i]) * ((double)a[i] - b[i]);
    return sqrt(s / (double)n);
}

int main(int argc, char **argv)
{
    int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
    render_env sky;
    char err[300];
    double t0 = now();
    if (render_env_default_sky(&sky, err, sizeof err) != 0) return fprintf(stderr, "%s\n", err), 0;
    printf("libggx render benchmark (%s)\n\nthe built-in sky (512 x 256, alias table): %.3f s\n\n",
           quick ? "quick" : "full", now() - t0);
    render_spec r;
    render_spec_defaults(&r);
    ggx_shape_ellipsoid(&r.shape, 0.15, 0.5, 0, 0, 0);
    ggx_fresnel_conductor(&r.fresnel, 1.0, 6.7);
    r.env = &sky, r.width = r.height = quick ? 256 : 512, r.spp = 64;
    printf("%d x %d conductor sphere (alpha 0.15, 0.5), 64 spp, MIS, brdf-bounded:\n", r.width, r.height);
    printf("%-8s %10s %14s\n", "threads", "seconds", "ns per path");
    size_t n = (size_t)r.width * (size_t)r.height * 3;
    float *img = malloc(n * sizeof *img);
    for (int t = 1; t <= 2; t++) {
        r.threads = t;
        render_prepare(&r, err, sizeof err);
        double best = 1e30;
        for (int k = 0; k < 2; k++) {
            t0 = now();
            render_image(&r, img, NULL);
            best = fmin(best, now() - t0);
        }
        printf("%-8d %10.3f %14.1f\n", t, best, best * t / ((double)r.width * r.height * r.spp) * 1e9);
    }
    free(img);
    /* the samplers' noise: a rough anisotropic sphere, whose grazing views waste VNDF reflection samples, under the
     * sky without its sun (a sun's noise is the light sample's business, and would hide the samplers') */
    render_env soft;
    if (render_env_sky(&soft, 512, 256, 35 * DEG, -120 * DEG, 1.5 * DEG, 0.0, err, sizeof err) != 0)
        return fprintf(stderr, "%s\n", err), 0;
    render_spec q;
    render_spec_defaults(&q);
    ggx_shape_ellipsoid(&q.shape, 0.5, 0.9, 0, 0, 30 * DEG);
    ggx_fresnel_conductor(&q.fresnel, 1.0, 6.7);
    q.env = &soft, q.width = q.height = 128, q.threads = 2, q.spp = quick ? 1024 : 4096, q.seed = 1000;
    n = (size_t)q.width * (size_t)q.height * 3;
    float *ref = malloc(n * sizeof *ref), *im = malloc(n * sizeof *im);
    render_prepare(&q, err, sizeof err);
    t0 = now();
    render_image(&q, ref, NULL);
    printf("\nnoise of 64-spp images against a %d-spp reference (MIS, %.1f s), 128 x 128, alpha 0.5, 0.9, theta_z "
           "30,\nunder the sky without its sun:\n",
           q.spp, now() - t0);
    printf("%-22s %-10s %10s %10s %14s %12s\n", "sampler", "strategy", "seconds", "RMSE", "1/(RMSE^2 s)", "vs brdf");
    const int ids[] = {GGX_SAMPLER_BRDF, GGX_SAMPLER_BRDF_BOUNDED, GGX_SAMPLER_BRDF_BOUNDED_AZIMUTH, GGX_SAMPLER_CAPS};
    for (int st = 0; st < 2; st++) {
        double base = 0;
        for (int k = 0; k < 4; k++) {
            render_spec s = q;
            s.sampler = ggx_sampler_get((ggx_sampler_id)ids[k]);
            s.spp = 64, s.seed = 7, s.strategy = st ? RENDER_BSDF_ONLY : RENDER_MIS;
            render_prepare(&s, err, sizeof err);
            double best = 1e30;
            for (int rep = 0; rep < 2; rep++) {
                t0 = now();
                render_image(&s, im, NULL);
                best = fmin(best, now() - t0);
            }
            double e = rmse(im, ref, n), eff = 1 / (e * e * best);
            if (k == 0) base = eff;
            printf("%-22s %-10s %10.3f %10.5f %14.0f %11.2fx\n", s.sampler->name, st ? "BSDF only" : "MIS", best, e,
                   eff, eff / base);
        }
    }
    free(ref), free(im);
    render_env_free(&sky);
    render_env_free(&soft);
    return 0;
}
