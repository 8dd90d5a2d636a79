/* The medium of flakes (libs/render/render_volume.c) as a proof: the white furnace (albedo 1 in a uniform
 * environment L: every pixel's expectation is L, whatever the flakes, since L everywhere solves the transport
 * equation when nothing is absorbed) for both phase functions, skewed and rotated flakes, thin to thick media, with
 * two negative controls that must fail it; the transmittance alone (albedo 0) against exp(-rho sigma(d) chord) per
 * pixel; single scattering by isotropic flakes against an independent quadrature of its closed form; the image is the
 * same for any thread count. Arguments and measured numbers: docs/design/sggx.md. SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "render.h"
#include "testlib.h"

#define DEG (GGX_PI / 180)

typedef struct image {
    int n;
    float *rgb, *var;
} image;

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static image render(const render_spec *r, render_volume *v)
{
    char err[300] = "";
    CHECK(render_volume_prepare(v, r, err, sizeof err) == 0, "render_volume_prepare: %s", err);
    image im = {r->width * r->height, NULL, NULL};
    im.rgb = malloc((size_t)im.n * 3 * sizeof *im.rgb), im.var = malloc((size_t)im.n * 3 * sizeof *im.var);
    CHECK(im.rgb && im.var, "memory");
    CHECK(render_volume_image(r, v, im.rgb, im.var) == 0, "values beyond the largest float");
    return im;
}
static void image_free(image *im) { free(im->rgb), free(im->var); }

/* The image's mean (green channel) and its standard error, from the pixels' variances. */
static void image_mean(const image *im, double *mean, double *se)
{
    double sum = 0, var = 0;
    for (int i = 0; i < im->n; i++) sum += im->rgb[3 * i + 1], var += im->var[3 * i + 1];
    *mean = sum / im->n, *se = sqrt(var) / im->n;
}

static render_spec furnace_spec(const render_env *env, int size, int spp)
{
    render_spec r;
    render_spec_defaults(&r);
    ggx_shape_ellipsoid(&r.shape, 0.2, 0.6, 25 * DEG, -15 * DEG, 30 * DEG); /* skewed and rotated flakes */
    r.env = env, r.width = r.height = size, r.spp = spp, r.threads = 2;
    return r;
}

/* Albedo 1, L = 0.7: the image's mean is L within 4 standard errors, for both phase functions, densities from thin to
 * thick and the three strategies (the path ends only by leaving the medium: no scattering limit that could lose
 * energy). The phase's samples alone have no variance here: every path leaves with weight 1 and brings L. */
static void furnace(void **state)
{
    (void)state;
    const double L = 0.7;
    render_env env;
    char err[200];
    CHECK(render_env_white(&env, L, err, sizeof err) == 0, "%s", err);
    static const struct {
        render_phase phase;
        double rho;
        int spp, quick;
        render_strategy strategy;
    } cases[] = {
        {RENDER_PHASE_SPECULAR, 0.5, 1024, 1, RENDER_MIS}, {RENDER_PHASE_SPECULAR, 3, 1024, 0, RENDER_MIS},
        {RENDER_PHASE_SPECULAR, 20, 512, 1, RENDER_MIS},   {RENDER_PHASE_SPECULAR, 3, 512, 0, RENDER_BSDF_ONLY},
        {RENDER_PHASE_DIFFUSE, 0.5, 512, 1, RENDER_MIS},   {RENDER_PHASE_DIFFUSE, 3, 256, 0, RENDER_MIS},
        {RENDER_PHASE_DIFFUSE, 20, 128, 1, RENDER_MIS},    {RENDER_PHASE_DIFFUSE, 3, 128, 1, RENDER_LIGHT_ONLY},
    };
    static const char *strategy[] = {"MIS", "light", "phase"};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        if (test_quick() && !cases[c].quick) continue;
        int spp = (int)fmax(2, round(cases[c].spp * test_scale()));
        render_spec r = furnace_spec(&env, 24, spp);
        r.strategy = cases[c].strategy;
        render_volume v;
        render_volume_defaults(&v);
        v.density = cases[c].rho, v.phase = cases[c].phase, v.scatter = 1 << 20;
        double t0 = seconds();
        image im = render(&r, &v);
        double mean, se;
        image_mean(&im, &mean, &se);
        printf(
            "furnace, %s flakes, rho %4.1f, %-5s: mean %.5f, L %.1f, standard error %.1e, z %+.2f (%d spp, %.2f s)\n",
            cases[c].phase == RENDER_PHASE_DIFFUSE ? "diffuse " : "specular", v.density, strategy[cases[c].strategy],
            mean, L, se, se > 0 ? (mean - L) / se : 0.0, spp, seconds() - t0);
        CHECK(fabs(mean - L) <= 4 * se + 1e-6, "furnace mean %.6f, L %g, se %.2g", mean, L, se);
        image_free(&im);
    }
    render_env_free(&env);
}

/* The negative controls: the light's sample weighted by 1.1 f, and its transmittance taken with sigma of the ray's
 * own direction, must each move the furnace's mean beyond 6 standard errors. */
static void furnace_controls(void **state)
{
    (void)state;
    const double L = 0.7;
    render_env env;
    char err[200];
    CHECK(render_env_white(&env, L, err, sizeof err) == 0, "%s", err);
    static const render_fault faults[] = {RENDER_FAULT_NEE_PHASE, RENDER_FAULT_SIGMA_DIRECTION};
    double z[2];
    for (int f = 0; f < 2; f++) {
        render_spec r = furnace_spec(&env, 24, (int)fmax(4, round(1024 * test_scale())));
        ggx_shape_ellipsoid(&r.shape, 0.05, 0.3, 25 * DEG, -15 * DEG, 30 * DEG);
        render_volume v;
        render_volume_defaults(&v);
        v.density = 1, v.phase = RENDER_PHASE_DIFFUSE, v.scatter = 1 << 20, v.fault = faults[f];
        image im = render(&r, &v);
        double mean, se;
        image_mean(&im, &mean, &se);
        printf("furnace, control %s: mean %.5f, L %.1f, z %+.2f\n",
               f == 0 ? "(light's sample through 1.1 f)   " : "(transmittance with sigma(d))", mean, L,
               (mean - L) / se);
        z[f] = fabs(mean - L) / se;
        image_free(&im);
    }
    for (int f = 0; f < 2; f++) CHECK(z[f] > 6, "negative control %d passed: z %.2f", f, z[f]);
    render_env_free(&env);
}

/* Albedo 0 under L = 1, every sample at its pixel's centre: each sample is 1 when the camera ray crosses the medium
 * unscattered, 0 otherwise, so a pixel's mean is binomial with p = T = exp(-rho sigma(d) chord), d and the chord from
 * render_primary and sigma from the flakes of the shape. Every pixel within 5 of its exact standard deviations; the
 * squared z over the pixels averages 1 (within 5 standard errors of that mean). */
static void transmittance(void **state)
{
    (void)state;
    render_env env;
    char err[200];
    CHECK(render_env_white(&env, 1.0, err, sizeof err) == 0, "%s", err);
    render_spec r = furnace_spec(&env, 20, (int)fmax(64, round(1024 * test_scale())));
    r.jitter = 0;
    render_volume v;
    render_volume_defaults(&v);
    v.density = 2, v.albedo[0] = v.albedo[1] = v.albedo[2] = 0;
    image im = render(&r, &v);
    ggx_sggx flakes;
    CHECK(ggx_sggx_from_shape(&flakes, &r.shape) == GGX_OK, "flakes");
    double zmax = 0, z2 = 0, tmin = 1;
    int hits = 0;
    for (int i = 0; i < im.n; i++) {
        render_hit h;
        double T = 1;
        if (render_primary(&r, i % r.width + 0.5, i / r.width + 0.5, &h)) {
            double chord = -2 * (h.p.x * h.dir.x + h.p.y * h.dir.y + h.p.z * h.dir.z);
            T = exp(-v.density * ggx_sggx_sigma(&flakes, h.dir) * chord);
            tmin = fmin(tmin, T), hits++;
        }
        double sd = sqrt(T * (1 - T) / r.spp), d = fabs(im.rgb[3 * i + 1] - T);
        CHECK(d <= 5 * sd + 1e-6, "pixel %d: %.6f, T %.6f, sd %.2g", i, im.rgb[3 * i + 1], T, sd);
        if (sd > 0) zmax = fmax(zmax, d / sd), z2 += d * d / (sd * sd);
    }
    z2 /= hits;
    printf("transmittance: %d pixels on the sphere, T down to %.3f, largest |z| %.2f, mean z^2 %.3f\n", hits, tmin,
           zmax, z2);
    CHECK(fabs(z2 - 1) <= 5 * sqrt(2.0 / hits), "mean squared z %.3f over %d pixels", z2, hits);
    image_free(&im);
    render_env_free(&env);
}

/* The probability that a particle leaving point p of radius |p| = rad inside the unit sphere of isotropic extinction
 * rho in a uniform direction escapes: (1/2) of the integral over mu = cos(angle to p) of exp(-rho s(mu)), with
 * s = -rad mu + sqrt(1 - rad^2 (1 - mu^2)) the distance to the sphere (Simpson's rule). */
static double escape_isotropic(double rho, double rad)
{
    const int n = 400;
    double sum = 0;
    for (int k = 0; k <= n; k++) {
        double mu = -1 + 2.0 * k / n, s = -rad * mu + sqrt(1 - rad * rad * (1 - mu * mu));
        sum += (k == 0 || k == n ? 1 : k % 2 ? 4 : 2) * exp(-rho * s);
    }
    return sum * (2.0 / n) / 3 / 2;
}

/* Single scattering by the flakes of S = I (alpha 1: sigma = 1 in every direction and the specular phase function
 * 1/(4 pi)), albedo a, L = 1: a pixel whose ray has chord c sees exp(-rho c) + a times the integral over the chord of
 * rho exp(-rho t) escape(p(t)) dt (Simpson's rule), independent of the renderer's estimator. The mean over the sphere's
 * pixels of (pixel - expected) within 4 standard errors, every pixel within 5. */
static void single_scattering(void **state)
{
    (void)state;
    render_env env;
    char err[200];
    CHECK(render_env_white(&env, 1.0, err, sizeof err) == 0, "%s", err);
    render_spec r = furnace_spec(&env, 12, (int)fmax(64, round(512 * test_scale())));
    ggx_shape_iso(&r.shape, 1.0);
    r.jitter = 0;
    render_volume v;
    render_volume_defaults(&v);
    v.density = 1.5, v.scatter = 1, v.albedo[0] = v.albedo[1] = v.albedo[2] = 0.8;
    image im = render(&r, &v);
    double diff = 0, var = 0, zmax = 0;
    int hits = 0;
    for (int i = 0; i < im.n; i++) {
        render_hit h;
        if (!render_primary(&r, i % r.width + 0.5, i / r.width + 0.5, &h)) continue;
        double dp = h.p.x * h.dir.x + h.p.y * h.dir.y + h.p.z * h.dir.z, c = -2 * dp;
        const int n = 200;
        double sum = 0;
        for (int k = 0; k <= n; k++) {
            double t = c * k / n, p2 = 1 + 2 * t * dp + t * t; /* |p + t d|^2 */
            sum += (k == 0 || k == n ? 1
                    : k % 2          ? 4
                                     : 2) *
                   v.density * exp(-v.density * t) * escape_isotropic(v.density, sqrt(fmax(0.0, fmin(1.0, p2))));
        }
        double want = exp(-v.density * c) + v.albedo[1] * sum * (c / n) / 3;
        double got = im.rgb[3 * i + 1], sd = sqrt(im.var[3 * i + 1]);
        CHECK(fabs(got - want) <= 5 * sd + 1e-6, "pixel %d: %.6f, expected %.6f, sd %.2g", i, got, want, sd);
        zmax = fmax(zmax, fabs(got - want) / sd);
        diff += got - want, var += im.var[3 * i + 1], hits++;
    }
    printf("single scattering: %d pixels, mean of pixel - closed form %+.2e (standard error %.1e), largest |z| %.2f\n",
           hits, diff / hits, sqrt(var) / hits, zmax);
    CHECK(fabs(diff) <= 4 * sqrt(var), "single scattering off by %.3g (se %.2g)", diff / hits, sqrt(var) / hits);
    image_free(&im);
    render_env_free(&env);
}

/* The sky: the image with 1 thread and with 3 is the same bit for bit (each pixel's own stream). */
static void thread_invariance(void **state)
{
    (void)state;
    render_env env;
    char err[200];
    CHECK(render_env_default_sky(&env, err, sizeof err) == 0, "%s", err);
    render_spec r = furnace_spec(&env, 20, 4);
    render_volume v;
    render_volume_defaults(&v);
    v.density = 4, v.phase = RENDER_PHASE_DIFFUSE, v.albedo[2] = 0.5;
    r.threads = 1;
    image a = render(&r, &v);
    r.threads = 3;
    image b = render(&r, &v);
    for (int i = 0; i < 3 * a.n; i++)
        CHECK(a.rgb[i] == b.rgb[i] && a.var[i] == b.var[i], "value %d: %g with 1 thread, %g with 3", i, a.rgb[i],
              b.rgb[i]);
    image_free(&a), image_free(&b);
    render_env_free(&env);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(furnace),           cmocka_unit_test(furnace_controls),  cmocka_unit_test(transmittance),
        cmocka_unit_test(single_scattering), cmocka_unit_test(thread_invariance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
