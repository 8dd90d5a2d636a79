/* What the sheet of a prediction shows, from the prediction (figure_predict.h): its lines of text, slices and rows,
 * and its spheres rendered under one distant light. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "figure_predict.h"
#include "kirchhoff.h"
#include "render.h"

static ggx_vec3 polar(double theta, double phi)
{
    ggx_vec3 w = {sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)};
    return w;
}

void figure_predict_fill(figure_predict_data *d, const predict_spec *s, const predict_result *r, const ggx_shape *fit,
                         const ggx_fit_info *info, const char *name, const char *no_wave)
{
    snprintf(d->title, sizeof d->title, "ggx predict: %s", name);
    snprintf(d->lines[0], sizeof d->lines[0],
             "%zu x %zu heights, spacing %.4g um, RMS height %.4g um (levelled), %.2f %% missing", s->nx, s->ny, s->dx,
             r->sigma_h, 100 * r->missing);
    double ax, ay, tx, ty, tz;
    ggx_shape_ellipsoid_params(fit, &ax, &ay, &tx, &ty, &tz);
    char tails[96] = "";
    if (isfinite(info->tails.nu) && isfinite(info->tails.nu_std_error))
        snprintf(tails, sizeof tails, "; slope tails: Student t of nu %.3g +- %.2g (GGX: 2)", info->tails.nu,
                 info->tails.nu_std_error);
    snprintf(d->lines[1], sizeof d->lines[1], "fitted: --alpha %.4g,%.4g --skew %.4g,%.4g --rotate %.4g%s", ax, ay,
             tx / DEG + 0.0, ty / DEG + 0.0, tz / DEG + 0.0, tails); /* + 0.0: no "-0" */
    char untraced[96] = "";
    if (r->untraced)
        snprintf(untraced, sizeof untraced, "; %d incidences too grazing for the patch's band of heights", r->untraced);
    snprintf(d->lines[2], sizeof d->lines[2],
             "traced: %ld rays, every bounce followed (%.2g %% left the patch's side, %.2g %% fell through holes)%s",
             r->rays, 100.0 * (double)r->left / (double)(r->rays ? r->rays : 1),
             100.0 * (double)r->lost / (double)(r->rays ? r->rays : 1), untraced);
    if (s->wave)
        snprintf(d->lines[3], sizeof d->lines[3],
                 "wave optics: 630, 532, 465 nm on %zu x %zu heights (%.0f x %.0f um) upsampled %d x, %.1f %% aliased",
                 r->wave_window[2], r->wave_window[3], (double)r->wave_window[2] * s->dx,
                 (double)r->wave_window[3] * s->dx, r->upsample, 100 * r->aliased);
    else snprintf(d->lines[3], sizeof d->lines[3], "wave optics: not computed (%s)", no_wave);
    d->slices = s->n_theta < FIGURE_PREDICT_SLICES ? s->n_theta : FIGURE_PREDICT_SLICES, d->slice_phi = 0;
    for (int c = 0; c < 3; c++) d->wavelength[c] = s->wave ? ms_kirchhoff_rgb_um[c] : 0;
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    for (int k = 0; k < d->slices; k++) {
        d->slice_theta[k] = s->theta[k] / DEG;
        ggx_vec3 wi = polar(s->theta[k], 0);
        for (int i = 0; i < FIGURE_PREDICT_POINTS; i++) {
            double t = (i - 89.0) *
                       DEG; /* negative: towards the light (phi 0), positive: the mirror's side (phi 180) */
            ggx_vec3 wo = polar(fabs(t), t < 0 ? 0 : GGX_PI);
            double f[3];
            brdf_table_eval(&r->traced, wi, wo, f);
            d->traced[k][i] = f[0];
            d->model[k][i] = ggx_brdf_eval(fit, &one, wi, wo);
            if (s->wave) brdf_table_eval(&r->wave, wi, wo, f);
            for (int c = 0; c < 3; c++) d->wave[k][c][i] = s->wave ? f[c] : NAN;
        }
    }
    d->rows = s->n_theta < FIGURE_PREDICT_ROWS ? s->n_theta : FIGURE_PREDICT_ROWS;
    for (int it = 0; it < d->rows; it++) {
        d->row_theta[it] = s->theta[it] / DEG;
        d->albedo_traced[it] = predict_row_albedo(&r->traced, it, 0);
        d->albedo_model[it] = predict_row_albedo(&r->model, it, 0);
        d->l2_model_traced[it] = predict_row_l2(&r->model, 0, &r->traced, 0, it);
        d->albedo_wave[it] = s->wave ? predict_row_albedo(&r->wave, it, 1) : NAN;
        d->l2_model_wave[it] = s->wave ? predict_row_l2(&r->model, 0, &r->wave, 1, it) : NAN;
        d->l2_traced_wave[it] = s->wave ? predict_row_l2(&r->traced, 0, &r->wave, 1, it) : NAN;
    }
}

/* The spheres' materials: the model's BRDF and a table's. */
static void sphere_model(const void *ctx, ggx_vec3 wl, ggx_vec3 v, double f[3])
{
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    f[0] = f[1] = f[2] = ggx_brdf_eval(ctx, &one, wl, v);
}
static void sphere_table(const void *ctx, ggx_vec3 wl, ggx_vec3 v, double f[3]) { brdf_table_eval(ctx, wl, v, f); }

/* The exposure (stops) that puts the image's 99.5th percentile of its channels' largest at 1 (a histogram of 4096
 * steps up to its top). */
static double exposure_of(const float *rgb, size_t pixels)
{
    double top = 0;
    for (size_t i = 0; i < 3 * pixels; i++) top = fmax(top, rgb[i]);
    long hist[4096] = {0}, lit = 0;
    for (size_t i = 0; i < 3 * pixels; i += 3) {
        double v = fmax(rgb[i], fmax(rgb[i + 1], rgb[i + 2]));
        if (v > 0) hist[v >= top ? 4095 : (int)(v / top * 4096)]++, lit++;
    }
    long c = 0;
    int b = 4095;
    while (b > 0 && (c += hist[b]) < lit / 200) b--;
    return -log2(top > 0 ? (b + 1) * top / 4096 : 1);
}

int figure_predict_spheres(figure_predict_data *d, const predict_spec *s, const predict_result *r, const ggx_shape *fit,
                           int size, const double *exposure, float *sphere[3])
{
    render_spec rs;
    render_spec_defaults(&rs);
    rs.light = RENDER_LIGHT_DIRECTIONAL;
    rs.light_dir = polar(55 * DEG, -130 * DEG), rs.light_irradiance = 1;
    rs.width = rs.height = size, rs.spp = 4, rs.threads = s->threads;
    size_t pixels = (size_t)size * (size_t)size;
    const void *ctx[3] = {fit, &r->all, &r->wave};
    render_brdf_fn fn[3] = {sphere_model, sphere_table, sphere_table};
    static const char *label[3] = {"the fitted model", "traced, every bounce", "wave optics (R, G, B)"};
    for (int k = 0; k < 3; k++) {
        sphere[k] = NULL;
        if (k == 2 && !s->wave) continue;
        if (!(sphere[k] = malloc(3 * pixels * sizeof(float)))) return -1;
        render_direct(&rs, fn[k], ctx[k], sphere[k]);
    }
    for (int k = 0; k < 3; k++) {
        d->sphere[k] = sphere[k];
        snprintf(d->sphere_label[k], sizeof d->sphere_label[k], "%s", label[k]);
    }
    d->exposure = exposure ? *exposure : exposure_of(sphere[0], pixels), d->size = size;
    snprintf(d->light_words, sizeof d->light_words,
             "spheres under one distant light (theta 55, phi -130 degrees), F = 1, exposure %+.2f stops", d->exposure);
    return 0;
}
