/* Latitude-longitude environments for the renderer: the built-in sky, the furnace, files, and their piecewise-constant
 * sampling distribution (render.h). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "render.h"
#include "surface.h"


static int env_fail(char *err, size_t errn, const char *msg) { return surface_fail(err, errn, "%s", msg); }

void render_env_free(render_env *e)
{
    free(e->texel), free(e->alias);
    memset(e, 0, sizeof *e);
}

static double luminance(const float *c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

int render_env_init(render_env *e, int w, int h, float *rgb, long *negatives, char *err, size_t errn)
{
    memset(e, 0, sizeof *e);
    if (negatives) *negatives = 0;
    if (!rgb || w < 1 || h < 1) {
        free(rgb);
        return env_fail(err, errn, "an environment needs at least 1 x 1 pixels");
    }
    e->w = w, e->h = h;
    size_t count = (size_t)w * (size_t)h;
    long bad = 0, neg = 0;
    for (size_t i = 0; i < 3 * count; i++) {
        if (!isfinite(rgb[i])) bad++;
        else if (rgb[i] < 0) rgb[i] = 0, neg++;
    }
    if (negatives) *negatives = neg;
    if (bad) {
        free(rgb);
        render_env_free(e);
        return surface_fail(err, errn, "%ld values of the environment are NaN or infinite (not radiance)", bad);
    }
    if (count > UINT32_MAX) {
        free(rgb);
        render_env_free(e);
        return env_fail(err, errn, "an environment of more than 2^32 pixels");
    }
    e->texel = malloc(count * sizeof *e->texel);
    e->alias = malloc(count * sizeof *e->alias);
    double *p = malloc(count * sizeof *p);
    uint32_t *work = malloc(count * sizeof *work);
    if (!e->texel || !e->alias || !p || !work) {
        free(p), free(work), free(rgb);
        render_env_free(e);
        return env_fail(err, errn, "out of memory");
    }
    double total = 0;
    for (int i = 0; i < h; i++) {
        double s = sin((i + 0.5) * GGX_PI / h);
        for (int j = 0; j < w; j++) {
            size_t k = (size_t)i * (size_t)w + (size_t)j;
            p[k] = luminance(rgb + 3 * k) * s;
            total += p[k];
        }
    }
    for (size_t k = 0; k < count; k++)
        for (int c = 0; c < 3; c++) e->texel[k].rgb[c] = rgb[3 * k + (size_t)c];
    free(rgb);
    if (!(total > 0) || !isfinite(total)) {
        free(p), free(work);
        render_env_free(e);
        return env_fail(err, errn,
                        total > 0 ? "the environment's radiance sums to more than a double holds"
                                  : "the environment is black everywhere (nothing to light with)");
    }
    /* Vose's alias method: p scaled to mean 1; the small ones (below 1) each take the rest of their column from a
     * large one. work holds the small indices from the front and the large from the back. */
    size_t ns = 0, nl = 0;
    for (size_t k = 0; k < count; k++) {
        e->texel[k].pdf_scale = (float)(p[k] / total * (double)count / (2 * GGX_PI * GGX_PI));
        p[k] *= (double)count / total;
        if (p[k] < 1) work[ns++] = (uint32_t)k;
        else work[count - 1 - nl++] = (uint32_t)k;
    }
    while (ns && nl) {
        uint32_t s = work[--ns], l = work[count - nl];
        e->alias[s].keep = (float)p[s], e->alias[s].other = l;
        p[l] -= 1 - p[s];
        if (p[l] < 1) nl--, work[ns++] = l;
    }
    while (nl) {
        uint32_t l = work[count - nl--];
        e->alias[l].keep = 1, e->alias[l].other = l;
    }
    while (ns) {
        uint32_t s = work[--ns];
        e->alias[s].keep = 1, e->alias[s].other = s;
    } /* rounding's leftovers */
    free(p), free(work);
    return 0;
}

int render_env_white(render_env *e, double L, char *err, size_t errn)
{
    /* 8 x 4 pixels: the distribution is then close to uniform over the sphere, and the radiance exactly L */
    int w = 8, h = 4;
    float *rgb = malloc((size_t)(3 * w * h) * sizeof *rgb);
    if (!rgb) return env_fail(err, errn, "out of memory");
    for (int i = 0; i < 3 * w * h; i++) rgb[i] = (float)L;
    return render_env_init(e, w, h, rgb, NULL, err, errn);
}

static ggx_vec3 dir_of(double theta, double phi)
{
    return (ggx_vec3){sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)};
}

/* The sky without the sun along d (sun: the unit direction to it). */
static void sky_radiance(ggx_vec3 d, ggx_vec3 sun, double out[3])
{
    static const double horizon[3] = {1.05, 1.02, 0.97}, zenith[3] = {0.20, 0.38, 0.80}, ground[3] = {0.30, 0.27, 0.24};
    if (d.z < 0) {
        memcpy(out, ground, sizeof ground);
        return;
    }
    double t = pow(d.z, 0.45), c = d.x * sun.x + d.y * sun.y + d.z * sun.z;
    double glow = 0.5 * exp(-acos(fmax(-1.0, fmin(1.0, c))) / 0.15); /* the aureole around the sun */
    for (int k = 0; k < 3; k++) out[k] = horizon[k] * (1 - t) + zenith[k] * t + glow * (k == 2 ? 0.8 : 1.0);
}

int render_env_sky(render_env *e, int w, int h, double sun_elev, double sun_az, double sun_radius,
                   double sun_irradiance, char *err, size_t errn)
{
    if (w < 2 || h < 2 || !(sun_radius > 0 && sun_radius < 0.5) || !(sun_irradiance >= 0))
        return env_fail(err, errn, "a sky needs at least 2 x 2 pixels and a sun radius in (0, 0.5) rad");
    float *rgb = malloc((size_t)w * (size_t)h * 3 * sizeof *rgb);
    if (!rgb) return env_fail(err, errn, "out of memory");
    ggx_vec3 sun = dir_of(GGX_PI / 2 - sun_elev, sun_az);
    static const double sun_colour[3] = {1.0, 0.95, 0.88};
    /* radiance of a uniform disc giving sun_irradiance at normal incidence: E = L pi sin^2(r) */
    double Ls = sun_irradiance / (GGX_PI * sin(sun_radius) * sin(sun_radius)), cos_r = cos(sun_radius);
    double pix = fmax(GGX_PI / h, 2 * GGX_PI / w); /* a pixel's largest angular side */
    for (int i = 0; i < h; i++)
        for (int j = 0; j < w; j++) {
            double th = (i + 0.5) * GGX_PI / h, ph = (j + 0.5) * 2 * GGX_PI / w, c[3];
            ggx_vec3 d = dir_of(th, ph);
            sky_radiance(d, sun, c);
            double cs = d.x * sun.x + d.y * sun.y + d.z * sun.z, ang = acos(fmax(-1.0, fmin(1.0, cs)));
            double cover = 0;
            if (ang < sun_radius + 1.5 * pix) { /* near the disc: its share of the pixel by 8 x 8 subsamples */
                int in = 0;
                for (int a = 0; a < 8; a++)
                    for (int b = 0; b < 8; b++) {
                        ggx_vec3 q = dir_of((i + (a + 0.5) / 8) * GGX_PI / h, (j + (b + 0.5) / 8) * 2 * GGX_PI / w);
                        in += q.x * sun.x + q.y * sun.y + q.z * sun.z >= cos_r;
                    }
                cover = in / 64.0;
            }
            float *o = rgb + 3 * ((size_t)i * (size_t)w + (size_t)j);
            for (int k = 0; k < 3; k++) o[k] = (float)(c[k] * (1 - cover) + Ls * sun_colour[k] * cover);
        }
    return render_env_init(e, w, h, rgb, NULL, err, errn);
}

int render_env_default_sky(render_env *e, char *err, size_t errn)
{
    double deg = GGX_PI / 180;
    return render_env_sky(e, 512, 256, 35 * deg, -120 * deg, 1.5 * deg, 6.0, err, errn);
}

/* The pixel of direction d and sin theta there. */
static size_t env_pixel(const render_env *e, ggx_vec3 d, double *sin_theta)
{
    /* theta and sin theta from the components, not from z: 1 - z^2 loses sin theta's digits near the poles */
    double rho = hypot(d.x, d.y), th = atan2(rho, d.z), ph = atan2(d.y, d.x);
    if (ph < 0) ph += 2 * GGX_PI;
    int i = (int)(th / GGX_PI * e->h), j = (int)(ph / (2 * GGX_PI) * e->w);
    if (i >= e->h) i = e->h - 1;
    if (j >= e->w) j = e->w - 1;
    if (i < 0) i = 0;
    if (j < 0) j = 0;
    *sin_theta = rho / hypot(rho, d.z);
    return (size_t)i * (size_t)e->w + (size_t)j;
}

double render_env_lookup(const render_env *e, ggx_vec3 d, double rgb[3])
{
    double s;
    const render_texel *t = e->texel + env_pixel(e, d, &s);
    rgb[0] = t->rgb[0], rgb[1] = t->rgb[1], rgb[2] = t->rgb[2];
    return s > 0 ? t->pdf_scale / s : 0;
}

void render_env_radiance(const render_env *e, ggx_vec3 d, double rgb[3]) { render_env_lookup(e, d, rgb); }

double render_env_pdf(const render_env *e, ggx_vec3 d)
{
    double rgb[3];
    return render_env_lookup(e, d, rgb);
}

ggx_vec3 render_env_sample(const render_env *e, double u1, double u2, double *pdf, double rgb[3])
{
    size_t count = (size_t)e->w * (size_t)e->h;
    double x = fmin(fmax(u1, 0.0), 1.0) * (double)count, f;
    size_t k = (size_t)x;
    if (k >= count) k = count - 1;
    f = x - (double)k;
    render_alias a = e->alias[k];
    if (f < a.keep) f = f / a.keep; /* the fraction of the kept part, uniform again: theta within the pixel */
    else f = (f - a.keep) / (1 - a.keep), k = a.other;
    f = fmin(fmax(f, 0.0), 1.0);
    size_t i = k / (size_t)e->w, j = k % (size_t)e->w;
    double th = ((double)i + f) * GGX_PI / e->h, ph = ((double)j + fmin(fmax(u2, 0.0), 1.0)) * 2 * GGX_PI / e->w;
    double s = sin(th);
    const render_texel *t = e->texel + k;
    rgb[0] = t->rgb[0], rgb[1] = t->rgb[1], rgb[2] = t->rgb[2];
    *pdf = s > 0 ? t->pdf_scale / s : 0;
    return dir_of(th, ph);
}
