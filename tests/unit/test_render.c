/* The renderer (libs/render) as a proof: the white furnace with and without compensation against the
 * library's albedos, for the glass sphere too; light, BSDF and MIS sampling converge to one image; a distant light on
 * the plane equals the BRDF; the environment's sampling distribution; the image is the same for any thread count;
 * radiance files round-trip. Arguments and measured margins: docs/design/render.md. SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "render.h"
#include "surface.h"
#include "testlib.h"
#include "chi2.h"
#include "verify.h"

#ifdef GGX_HAVE_STB
#include <stb_image_write.h>
#endif

#define DEG (GGX_PI / 180)

typedef struct image {
    int w, h;
    float *rgb, *var;
} image;

static image render(const render_spec *r)
{
    image im = {r->width, r->height, NULL, NULL};
    size_t n = (size_t)r->width * (size_t)r->height * 3;
    im.rgb = malloc(n * sizeof *im.rgb), im.var = malloc(n * sizeof *im.var);
    CHECK(im.rgb && im.var, "memory");
    render_image(r, im.rgb, im.var);
    return im;
}
static void image_free(image *im) { free(im->rgb), free(im->var); }

static void prepare(render_spec *r)
{
    char err[300] = "";
    CHECK(render_prepare(r, err, sizeof err) == 0, "render_prepare: %s", err);
}

/* The compensated reflector with F = 1 in the white furnace: every pixel is 1 (the environment's radiance) within its
 * Monte Carlo error and the albedo table's 1e-3 (views to 89 degrees; 2e-3 beyond, where the table is not promised);
 * the image's mean over the sphere within 1e-3. */
static void furnace_compensated(void **state)
{
    (void)state;
    render_env env;
    char err[200];
    CHECK(render_env_white(&env, 1.0, err, sizeof err) == 0, "%s", err);
    render_spec r;
    render_spec_defaults(&r);
    ggx_shape_ellipsoid(&r.shape, 0.3, 0.6, 0, 0, 30 * DEG);
    r.env = &env, r.compensate = 1, r.width = r.height = 32, r.spp = 1024, r.threads = 2;
    prepare(&r);
    image im = render(&r);
    double sum = 0, worst = 0, var = 0;
    double hits = 0;
    for (int y = 0; y < r.height; y++)
        for (int x = 0; x < r.width; x++) {
            render_hit h;
            size_t i = 3 * ((size_t)y * (size_t)r.width + (size_t)x);
            int hit = render_primary(&r, x + 0.5, y + 0.5, &h);
            if (!hit && im.var[i] == 0) { /* no sample met the sphere */
                CHECK(im.rgb[i] == 1.0f, "the furnace's background is 1, got %g", im.rgb[i]);
                continue;
            }
            if (!hit) h.view_local.z = 0; /* the rim crosses the pixel; its centre misses */
            for (int k = 0; k < 3; k++) {
                double d = fabs(im.rgb[i + k] - 1.0), sd = sqrt(im.var[i + k]);
                double table = h.view_local.z >= 0.0175 ? 1e-3 : 2e-3;
                CHECK(d <= 5 * sd + table + 1e-6, "pixel (%d, %d): %.6f, sd %.2g, view z %.3f", x, y, im.rgb[i + k], sd,
                      h.view_local.z);
                if (d - 5 * sd > worst) worst = d - 5 * sd;
            }
            if (hit) sum += im.rgb[i + 1], var += im.var[i + 1], hits++;
        }
    double mean = sum / hits;
    printf("furnace, compensated: %.0f pixels on the sphere, mean %.6f (standard error %.1e), worst |pixel - 1| - 5 sd "
           "%.2g\n",
           hits, mean, sqrt(var) / hits, worst);
    CHECK(fabs(mean - 1) <= 1e-3, "image mean %.6f", mean);
    image_free(&im);
    render_release(&r);
    render_env_free(&env);
}

/* Without compensation every pixel is the albedo ggx_albedo of its view (samples at the pixel's centre), within 5
 * standard errors, for every sampler of the registry that can sample a reflector; a negative control (the image of a
 * rougher shape) must fail the same comparison. */
static void furnace_albedo_every_sampler(void **state)
{
    (void)state;
    render_env env;
    char err[200];
    CHECK(render_env_white(&env, 1.0, err, sizeof err) == 0, "%s", err);
    render_spec r;
    render_spec_defaults(&r);
    ggx_shape_ellipsoid(&r.shape, 0.3, 0.5, 15 * DEG, -10 * DEG, 20 * DEG);
    r.env = &env, r.width = r.height = 20, r.spp = 256, r.threads = 2, r.jitter = 0;
    int n = r.width * r.height;
    double *want = calloc((size_t)n, sizeof *want);
    int *hit = calloc((size_t)n, sizeof *hit);
    for (int i = 0; i < n; i++) {
        render_hit h;
        hit[i] = render_primary(&r, i % r.width + 0.5, i / r.width + 0.5, &h);
        if (hit[i]) want[i] = ggx_albedo(&r.shape, h.view_local);
    }
    int tested = 0;
    for (int id = 0; id <= GGX_SAMPLER_COUNT; id++) {
        render_spec q = r;
        int control = id == GGX_SAMPLER_COUNT;
        q.sampler = ggx_sampler_get(control ? GGX_SAMPLER_BRDF_BOUNDED : (ggx_sampler_id)id);
        if (q.sampler->id == GGX_SAMPLER_BSDF) continue;
        if (q.sampler->domain == GGX_DOMAIN_UNSKEWED) continue; /* the shape is skewed */
        if (control) ggx_shape_ellipsoid(&q.shape, 0.3 * 1.3, 0.5 * 1.3, 15 * DEG, -10 * DEG, 20 * DEG);
        prepare(&q);
        image im = render(&q);
        double zmax = 0;
        for (int i = 0; i < n; i++) {
            if (!hit[i]) continue;
            double sd = sqrt(im.var[3 * i + 1]), z = fabs(im.rgb[3 * i + 1] - want[i]) / (sd + 1e-7);
            if (z > zmax) zmax = z;
        }
        printf("furnace, %-22s largest |pixel - albedo| / sd %.2f\n",
               control ? "control (rougher shape)" : q.sampler->name, zmax);
        if (control) CHECK(zmax > 5, "the negative control passed: z %.2f", zmax);
        else
            CHECK(zmax <= 5, "sampler %s: a pixel %.2f standard errors from ggx_albedo", q.sampler->name, zmax),
                tested++;
        image_free(&im);
    }
    CHECK(tested >= 8, "only %d samplers tested", tested);
    free(want), free(hit);
    render_env_free(&env);
}

/* The compensated rough glass sphere in the white furnace: light goes in and out, and every pixel stays 1 within its
 * error and the tables' errors along the path; without compensation no pixel gains energy. */
static void furnace_glass(void **state)
{
    (void)state;
    render_env env;
    char err[200];
    CHECK(render_env_white(&env, 1.0, err, sizeof err) == 0, "%s", err);
    for (int comp = 1; comp >= 0; comp--) {
        render_spec r;
        render_spec_defaults(&r);
        ggx_shape_iso(&r.shape, 0.3);
        ggx_fresnel_dielectric(&r.fresnel, 1.5);
        r.env = &env, r.compensate = comp, r.width = r.height = 32, r.spp = 256, r.threads = 2, r.depth = 64;
        prepare(&r);
        image im = render(&r);
        double sum = 0, worst = 0, var = 0;
        double hits = 0;
        for (int i = 0; i < r.width * r.height; i++) {
            render_hit h;
            if (!render_primary(&r, i % r.width + 0.5, i / r.width + 0.5, &h)) continue;
            double v = im.rgb[3 * i + 1], sd = sqrt(im.var[3 * i + 1]);
            if (comp) CHECK(fabs(v - 1) <= 5 * sd + 5e-3, "glass pixel %d: %.5f, sd %.2g", i, v, sd);
            else CHECK(v <= 1 + 5 * sd, "uncompensated glass pixel %d gains energy: %.5f, sd %.2g", i, v, sd);
            if (fabs(v - 1) - 5 * sd > worst) worst = fabs(v - 1) - 5 * sd;
            sum += v, var += im.var[3 * i + 1], hits++;
        }
        double se = sqrt(var) / hits;
        printf("glass sphere, %s: mean %.5f (standard error %.1e) over %.0f pixels, worst |pixel - 1| - 5 sd %.2g\n",
               comp ? "compensated" : "uncompensated", sum / hits, se, hits, worst);
        if (comp) CHECK(fabs(sum / hits - 1) <= 2e-3 + 4 * se, "compensated glass: mean %.5f, se %.1e", sum / hits, se);
        else CHECK(sum / hits < 0.99, "uncompensated glass loses energy: mean %.5f", sum / hits);
        image_free(&im);
        render_release(&r);
    }
    render_env_free(&env);
}

/* The tiles' means and the variances of those means, channel 1 (green). */
static void tile_stats(const image *im, int t, double *mean, double *var)
{
    int tx = t % (im->w / 8), ty = t / (im->w / 8);
    double s = 0, v = 0;
    for (int y = 8 * ty; y < 8 * ty + 8; y++)
        for (int x = 8 * tx; x < 8 * tx + 8; x++) {
            size_t i = 3 * ((size_t)y * (size_t)im->w + (size_t)x) + 1;
            s += im->rgb[i], v += im->var[i];
        }
    *mean = s / 64, *var = v / (64.0 * 64.0);
}

/* The largest |z| over tiles between two images. */
static double tile_zmax(const image *a, const image *b)
{
    double zmax = 0;
    for (int t = 0; t < (a->w / 8) * (a->h / 8); t++) {
        double ma, va, mb, vb;
        tile_stats(a, t, &ma, &va);
        tile_stats(b, t, &mb, &vb);
        double z = fabs(ma - mb) / sqrt(va + vb + 1e-30);
        if (z > zmax) zmax = z;
    }
    return zmax;
}

/* Light samples only, BSDF samples only and MIS give the same image under a sky with a small bright sun: per 8 x 8
 * tile, z-tests of each pair with a Bonferroni bound for a family-wise level of 1e-3; the image of a rougher shape
 * must be told apart. */
static void strategies_agree(void **state)
{
    (void)state;
    render_env env;
    char err[200];
    CHECK(render_env_sky(&env, 256, 128, 40 * DEG, -100 * DEG, 8 * DEG, 6.0, err, sizeof err) == 0, "%s", err);
    render_spec r;
    render_spec_defaults(&r);
    ggx_shape_ellipsoid(&r.shape, 0.25, 0.5, 10 * DEG, 0, 30 * DEG);
    ggx_fresnel_conductor(&r.fresnel, 1.0, 6.7);
    r.env = &env, r.width = r.height = 32, r.spp = 256, r.threads = 2;
    prepare(&r);
    image im[3];
    for (int s = 0; s < 3; s++) {
        render_spec q = r;
        /* BSDF samples find the sun rarely: their variance estimate needs more of them */
        q.strategy = (render_strategy)s, q.seed = 13 + (unsigned)s, q.spp = s == RENDER_BSDF_ONLY ? 4 * r.spp : r.spp;
        im[s] = render(&q);
    }
    render_spec q = r;
    ggx_shape_ellipsoid(&q.shape, 0.25 * 1.15, 0.5 * 1.15, 10 * DEG, 0, 30 * DEG);
    q.seed = 99;
    image rough = render(&q);
    int tests = 3 * (r.width / 8) * (r.height / 8);
    double zc = 4.6; /* two-sided normal quantile at 1e-3 / 48 is 4.1; 4.6 leaves room for the variances' own error */
    (void)tests;
    static const char *const names[3] = {"MIS", "light only", "BSDF only"};
    for (int a = 0; a < 3; a++)
        for (int b = a + 1; b < 3; b++) {
            double z = tile_zmax(&im[a], &im[b]);
            printf("strategies: %s against %s, largest tile |z| %.2f\n", names[a], names[b], z);
            CHECK(z <= zc, "%s and %s differ: tile z %.2f", names[a], names[b], z);
        }
    double zr = tile_zmax(&im[0], &rough);
    printf("strategies: MIS against a 15%% rougher shape (negative control), largest tile |z| %.2f\n", zr);
    CHECK(zr > zc, "the rougher shape was not told apart: z %.2f", zr);
    /* MIS is never much noisier than the better of the two */
    double v[3] = {0, 0, 0};
    for (int s = 0; s < 3; s++)
        for (int i = 0; i < r.width * r.height; i++) v[s] += im[s].var[3 * i + 1];
    printf("strategies: summed variance MIS %.3g, light %.3g, BSDF %.3g\n", v[0], v[1], v[2]);
    CHECK(v[0] <= 1.5 * fmin(v[1], v[2]), "MIS variance %.3g against %.3g and %.3g", v[0], v[1], v[2]);
    for (int s = 0; s < 3; s++) image_free(&im[s]);
    image_free(&rough);
    render_env_free(&env);
}

/* A distant light: each pixel is f_r(wl, view) wl.z E from ggx_brdf_eval at the pixel's centre, to float precision,
 * on the plane and on the sphere (whose shadowed side is 0). */
static void distant_light(void **state)
{
    (void)state;
    for (int scene = 0; scene < 2; scene++) {
        render_spec r;
        render_spec_defaults(&r);
        ggx_shape_ellipsoid(&r.shape, 0.2, 0.45, 12 * DEG, 5 * DEG, 40 * DEG);
        ggx_fresnel_conductor(&r.fresnel, 0.2, 3.5);
        r.scene = scene ? RENDER_SPHERE : RENDER_PLANE;
        r.light = RENDER_LIGHT_DIRECTIONAL;
        r.light_dir = t_dir(50 * DEG, -140 * DEG), r.light_irradiance = 2.5;
        r.width = 40, r.height = 30, r.spp = 1, r.jitter = 0, r.threads = 2;
        prepare(&r);
        image im = render(&r);
        double worst = 0;
        int lit = 0;
        for (int i = 0; i < r.width * r.height; i++) {
            render_hit h;
            double want = 0;
            if (render_primary(&r, i % r.width + 0.5, i / r.width + 0.5, &h)) {
                ggx_vec3 l = {t_dot(r.light_dir, h.t), t_dot(r.light_dir, h.b), t_dot(r.light_dir, h.n)};
                if (l.z > 0) want = ggx_brdf_eval(&r.shape, &r.fresnel, l, h.view_local) * l.z * r.light_irradiance;
            }
            double got = im.rgb[3 * i], e = fabs(got - want) / fmax(want, 1e-30);
            lit += want > 0;
            if (want > 0 && e > worst) worst = e;
            CHECK(fabs(got - want) <= 1e-6 * want + 1e-30, "%s pixel %d: %.9g, want %.9g", scene ? "sphere" : "plane",
                  i, got, want);
        }
        printf("distant light on the %s: %d lit pixels, largest relative error %.2g\n", scene ? "sphere" : "plane", lit,
               worst);
        CHECK(lit > r.width * r.height / 4, "only %d pixels lit", lit);
        image_free(&im);
    }
}

/* render_direct with the model as the caller's function: the path tracer's image at depth 1 under a distant light
 * (the same pixel points: jittered, 3 samples each), to float rounding; each channel the function's own. */
typedef struct direct_model {
    const render_spec *r;
    double scale[3];
} direct_model;
static void direct_model_f(const void *ctx, ggx_vec3 wl, ggx_vec3 v, double f[3])
{
    const direct_model *m = ctx;
    double x = ggx_brdf_eval(&m->r->shape, &m->r->fresnel, wl, v);
    for (int k = 0; k < 3; k++) f[k] = m->scale[k] * x;
}
static void direct_light_function(void **state)
{
    (void)state;
    render_spec r;
    render_spec_defaults(&r);
    ggx_shape_ellipsoid(&r.shape, 0.15, 0.3, 10 * DEG, -5 * DEG, 25 * DEG);
    ggx_fresnel_conductor(&r.fresnel, 0.25, 3.1);
    r.light = RENDER_LIGHT_DIRECTIONAL;
    r.light_dir = t_dir(40 * DEG, -110 * DEG), r.light_irradiance = 3;
    r.width = 36, r.height = 28, r.spp = 3, r.depth = 1, r.threads = 2;
    prepare(&r);
    image im = render(&r);
    direct_model m = {&r, {1, 0.5, 2}};
    float *d = malloc((size_t)r.width * (size_t)r.height * 3 * sizeof *d);
    CHECK(d, "memory");
    CHECK(render_direct(&r, direct_model_f, &m, d) == 0, "values beyond float");
    int lit = 0;
    for (int i = 0; i < r.width * r.height; i++) {
        double want = im.rgb[3 * i];
        lit += want > 0;
        for (int k = 0; k < 3; k++)
            CHECK(fabs(d[3 * i + k] - m.scale[k] * want) <= 1e-6 * m.scale[k] * want + 1e-30,
                  "pixel %d channel %d: %.9g, want %.9g", i, k, d[3 * i + k], m.scale[k] * want);
    }
    CHECK(lit > r.width * r.height / 4, "only %d pixels lit", lit);
    free(d);
    image_free(&im);
}

/* The same image, bit for bit, for 1, 2 and 5 threads, on a size that is no multiple of the tiles. */
static void thread_invariance(void **state)
{
    (void)state;
    render_env env;
    char err[200];
    CHECK(render_env_sky(&env, 128, 64, 35 * DEG, -120 * DEG, 2 * DEG, 6.0, err, sizeof err) == 0, "%s", err);
    render_spec r;
    render_spec_defaults(&r);
    ggx_shape_ellipsoid(&r.shape, 0.15, 0.5, 0, 0, 0);
    ggx_fresnel_dielectric(&r.fresnel, 1.5);
    r.env = &env, r.width = 37, r.height = 21, r.spp = 4, r.seed = 5;
    prepare(&r);
    image ref = render(&r);
    for (int t = 2; t <= 5; t += 3) {
        r.threads = t;
        image im = render(&r);
        size_t n = (size_t)r.width * (size_t)r.height * 3 * sizeof(float);
        CHECK(memcmp(im.rgb, ref.rgb, n) == 0 && memcmp(im.var, ref.var, n) == 0, "%d threads give another image", t);
        image_free(&im);
    }
    r.seed = 6;
    image other = render(&r);
    CHECK(memcmp(other.rgb, ref.rgb, (size_t)r.width * (size_t)r.height * 3 * sizeof(float)) != 0,
          "another seed gives the same image");
    image_free(&other), image_free(&ref);
    render_env_free(&env);
}

/* The environment's distribution: the pdf of each sample is render_env_pdf of its direction, the pdf integrates to 1,
 * pixels are hit in proportion to luminance x sin theta (chi-square), a black pixel never; and what is refused. */
static void environment(void **state)
{
    (void)state;
    int w = 16, h = 8;
    float *rgb = malloc((size_t)(3 * w * h) * sizeof *rgb);
    rng g = {3};
    for (int i = 0; i < 3 * w * h; i++) rgb[i] = (float)rng_range(&g, 0.0, 2.0);
    for (int k = 0; k < 3; k++) rgb[3 * 37 + k] = 0; /* one black pixel */
    rgb[3 * 16 + 2] = -0.5f;                         /* one negative value, read as 0 */
    render_env e;
    char err[200];
    long neg = 0;
    CHECK(render_env_init(&e, w, h, rgb, &neg, err, sizeof err) == 0, "%s", err);
    CHECK(neg == 1 && e.texel[16].rgb[2] == 0, "negatives %ld", neg);
    long n = (long)(200000 * test_scale()) + 20000, *count = calloc((size_t)(w * h), sizeof *count);
    double worst = 0;
    for (long s = 0; s < n; s++) {
        double pdf;
        double c[3], c2[3];
        ggx_vec3 d = render_env_sample(&e, rng_uniform(&g), rng_uniform(&g), &pdf, c);
        render_env_radiance(&e, d, c2);
        if (pdf > 0) CHECK(c[0] == c2[0] && c[1] == c2[1] && c[2] == c2[2], "the sample's radiance is its pixel's");
        double p2 = render_env_pdf(&e, d);
        if (pdf > 0 && fabs(pdf - p2) / pdf > worst) worst = fabs(pdf - p2) / pdf;
        int i = (int)(acos(d.z) / GGX_PI * h),
            j = (int)(fmod(atan2(d.y, d.x) + 2 * GGX_PI, 2 * GGX_PI) / (2 * GGX_PI) * w);
        count[(i < h ? i : h - 1) * w + (j < w ? j : w - 1)]++;
    }
    CHECK(worst < 1e-5, "sample pdf and render_env_pdf differ by %.2g", worst);
    CHECK(count[37] == 0, "the black pixel was hit %ld times", count[37]);
    /* expected counts: p_ij = pdf_scale sin theta_c x the pixel's solid-angle factor 2 pi^2 / (w h) */
    double chi2 = 0, integral = 0;
    int cells = 0;
    for (int k = 0; k < w * h; k++) {
        double p = e.texel[k].pdf_scale * 2 * GGX_PI * GGX_PI / (w * h);
        integral += p;
        if (k == 37) continue;
        double ex = p * (double)n;
        chi2 += ((double)count[k] - ex) * ((double)count[k] - ex) / ex, cells++;
    }
    double pv = chi2_pvalue(chi2, cells - 1);
    printf("environment: %ld samples, chi-square %.1f on %d cells, p %.3f\n", n, chi2, cells - 1, pv);
    CHECK(fabs(integral - 1) < 1e-6, "the pixels' probabilities sum to %.9f", integral);
    CHECK(chi2_accepts(pv), "pixel counts off the distribution: p %.2g", pv);
    free(count);
    render_env_free(&e);
    /* refusals: NaN, infinity, black everywhere */
    float *bad = calloc(12, sizeof *bad);
    bad[4] = NAN;
    CHECK(render_env_init(&e, 2, 2, bad, NULL, err, sizeof err) == -1 && strstr(err, "NaN"), "NaN accepted: %s", err);
    bad = calloc(12, sizeof *bad);
    bad[0] = INFINITY;
    CHECK(render_env_init(&e, 2, 2, bad, NULL, err, sizeof err) == -1 && strstr(err, "infinite"), "inf accepted");
    bad = calloc(12, sizeof *bad);
    CHECK(render_env_init(&e, 2, 2, bad, NULL, err, sizeof err) == -1 && strstr(err, "black"), "black accepted");
}

/* A light bright enough that the image's values pass the largest float: render_image counts them; an infinite
 * irradiance is refused. */
static void overflowing_light(void **state)
{
    (void)state;
    render_spec r;
    render_spec_defaults(&r);
    r.light = RENDER_LIGHT_DIRECTIONAL, r.light_irradiance = 3e38, r.width = r.height = 16, r.spp = 1;
    prepare(&r);
    size_t n = (size_t)r.width * (size_t)r.height * 3;
    float *rgb = malloc(n * sizeof *rgb), *var = malloc(n * sizeof *var);
    CHECK(rgb && var, "memory");
    long over = render_image(&r, rgb, var), inf = 0;
    for (size_t i = 0; i < n; i++) inf += !isfinite(rgb[i]) + !isfinite(var[i]);
    CHECK(over > 0 && over == inf, "irradiance 3e38: %ld values over the largest float counted, %ld infinite", over,
          inf);
    r.light_irradiance = 1;
    CHECK(render_image(&r, rgb, var) == 0, "irradiance 1 overflows");
    r.light_irradiance = INFINITY;
    char err[200] = "";
    CHECK(render_prepare(&r, err, sizeof err) == -1 && strstr(err, "finite"), "an infinite irradiance accepted: %s",
          err);
    free(rgb), free(var);
}

/* Radiance files: PFM and OpenEXR written and read back exactly, Radiance .hdr (written here by stb_image_write) to
 * its 8-bit mantissas; a truncated file is refused with a reason. */
static void radiance_files(void **state)
{
    (void)state;
    char dir[] = "/tmp/ggx-render-XXXXXX", path[96];
    CHECK(mkdtemp(dir) != NULL, "mkdtemp");
    surface s;
    memset(&s, 0, sizeof s);
    s.kind = SURFACE_RADIANCE, s.nx = 9, s.ny = 5;
    s.rgb = malloc(9 * 5 * 3 * sizeof *s.rgb);
    rng g = {8};
    for (int i = 0; i < 9 * 5 * 3; i++) s.rgb[i] = (float)(rng_range(&g, 0.0, 50.0) * (i % 7 == 0 ? 100 : 1));
    surface_read_options ro = {SURFACE_RADIANCE, 0};
    char err[300];
    for (int f = 0; f < 2; f++) {
        snprintf(path, sizeof path, "%s/e.%s", dir, f ? "exr" : "pfm");
        int rc = surface_write(path, f ? SURFACE_EXR : SURFACE_PFM, &s, 0, NULL, err, sizeof err);
#ifndef GGX_HAVE_EXR
        if (f) continue;
#endif
        CHECK(rc == 0, "%s", err);
        surface t;
        CHECK(surface_read(path, &ro, &t, err, sizeof err) == 0, "%s", err);
        CHECK(t.nx == 9 && t.ny == 5 && memcmp(t.rgb, s.rgb, 9 * 5 * 3 * sizeof(float)) == 0, "%s round trip", path);
        surface_free(&t);
    }
    /* a truncated PFM */
    unsigned char *data;
    size_t n;
    CHECK(surface_encode_pfm(&s, &data, &n, err, sizeof err) == 0, "%s", err);
    surface t;
    CHECK(surface_parse(SURFACE_PFM, data, n - 7, &ro, &t, err, sizeof err) == -1 && strstr(err, "cut short"),
          "a truncated PFM: %s", err);
    free(data);
#ifdef GGX_HAVE_STB
    snprintf(path, sizeof path, "%s/e.hdr", dir);
    CHECK(stbi_write_hdr(path, 9, 5, 3, s.rgb) != 0, "stbi_write_hdr");
    CHECK(surface_read(path, &ro, &t, err, sizeof err) == 0, "%s", err);
    double worst = 0;
    for (int i = 0; i < 9 * 5 * 3; i++) {
        double mx = fmax(s.rgb[i - i % 3], fmax(s.rgb[i - i % 3 + 1], s.rgb[i - i % 3 + 2]));
        worst = fmax(worst, fabs(t.rgb[i] - s.rgb[i]) / mx);
    }
    printf("radiance files: .hdr within %.2g of each pixel's largest channel\n", worst);
    CHECK(t.nx == 9 && t.ny == 5 && worst <= 1.0 / 128, ".hdr round trip off by %.3g", worst);
    surface_free(&t);
    /* cut to half its pixels, run-length encoded (9 pixels a row) and flat (4), it is refused; whole, it is read */
    for (int w = 9; w >= 4; w -= 5) {
        snprintf(path, sizeof path, "%s/w%d.hdr", dir, w);
        CHECK(stbi_write_hdr(path, w, 5, 3, s.rgb) != 0, "stbi_write_hdr");
        FILE *f = fopen(path, "rb");
        CHECK(f != NULL, "%s", path);
        unsigned char buf[4096];
        size_t len = fread(buf, 1, sizeof buf, f);
        fclose(f);
        CHECK(surface_parse(SURFACE_HDR, buf, len, &ro, &t, err, sizeof err) == 0, "%s: %s", path, err);
        surface_free(&t);
        size_t header = 0;
        while (header + 1 < len && !(buf[header] == '\n' && buf[header + 1] == '\n')) header++;
        while (++header < len && buf[header] != '\n') continue; /* the resolution line */
        size_t half = header + 1 + (len - header - 1) / 2;
        memset(&t, 0, sizeof t);
        CHECK(surface_parse(SURFACE_HDR, buf, half, &ro, &t, err, sizeof err) == -1 && strstr(err, "truncated"),
              "a .hdr of width %d cut to half its pixels accepted (%s)", w, err);
    }
#endif
    surface_free(&s);
    char cmd[96];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0, "rm");
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(environment),           cmocka_unit_test(radiance_files),
        cmocka_unit_test(overflowing_light),     cmocka_unit_test(distant_light),
        cmocka_unit_test(direct_light_function), cmocka_unit_test(thread_invariance),
        cmocka_unit_test(furnace_compensated),   cmocka_unit_test(furnace_albedo_every_sampler),
        cmocka_unit_test(furnace_glass),         cmocka_unit_test(strategies_agree),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    return rc | chi2_budget_end("render", argc, argv);
}
