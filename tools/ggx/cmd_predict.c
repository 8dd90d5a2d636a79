/* ggx predict: a measured surface's appearance predicted from its heights beside its fitted model: the fit, the BRDF
 * traced (geometric optics) and by wave optics over a grid of incidences, their distances from the model, lit
 * spheres, on one sheet (libs/predict, docs/design/predict.md). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cmd_microsurface.h"
#include "figure_out.h"
#include "figure_predict.h"
#include "ggx/ggx_fit.h"
#include "kirchhoff.h"
#include "predict.h"
#include "render.h"

void predict_help(void)
{
    printf("usage: ggx predict --heightfield FILE [--spacing D] [--z-scale Z] [-n RAYS] [--bounces K]\n"
           "                   [--no-wave] [--size PX] [--exposure STOPS] [--threads N] [--out DIR]\n\n"
           "What a measured surface's heights predict for its appearance, beside the GGX ellipsoid fitted to\n"
           "them (ggx fit): the BRDF with F = 1 traced over the heights as a patch (geometric optics, every\n"
           "bounce followed; ggx microsurface measure) and by scalar wave optics (the Kirchhoff BRDF at 630,\n"
           "532 and 465 nm; ggx microsurface wave), at the incidences theta_i 0, 20, 40, 60 and 75 degrees\n"
           "times 4 azimuths, each tabulated over 127 x 127 cells of the outgoing directions' projection.\n"
           "Writes into DIR (default predict/): sheet.pdf and sheet.png (the fit, the BRDF in the plane of\n"
           "incidence at theta_i 0, 20, 40 and 60 degrees traced, wave and fitted, the albedos and the relative\n"
           "L2 of the fitted model against each prediction per incidence, and spheres under one distant light\n"
           "in the fitted model, the traced BRDF and the wave BRDF), spheres.png (the three spheres), predict.csv\n"
           "(one row per incidence) and predict.json (all of it). Prints the table of the sheet.\n\n"
           "  --heightfield FILE   a measured height field (x3p, gsf, OpenEXR, 16-bit PNG, PFM, text; see ggx fit);\n"
           "                       a file's own spacing is read as metres; --spacing D in micrometres (the\n"
           "                       heights then in D's unit), --z-scale Z micrometres per height unit; equal\n"
           "                       spacings along x and y\n"
           "  -n RAYS              traced rays per incidence (default 1,000,000)\n"
           "  --bounces K          the most reflections of a traced ray (default 100)\n"
           "  --size PX            the spheres' size in pixels (default 256)\n"
           "  --exposure STOPS     the spheres' exposure (default: the fitted model's sphere at 1 in its\n"
           "                       99.5th percentile)\n"
           "  --no-wave            no wave optics (its share of the time: most of it)\n");
}

/* the incidences: polar angles (degrees) times azimuths; the sheet's slices at the first four */
static const double THETAS[] = {0, 20, 40, 60, 75};
enum { N_THETA = sizeof THETAS / sizeof THETAS[0], N_PHI = 4, RES = 127 }; /* odd: the normal is a cell's centre */

static void show(void *ctx, long done, long total)
{
    if (*(int *)ctx) progress_show("predict", done, total);
}

/* The spheres' materials: the model's BRDF and a table's. */
static void sphere_model(const void *ctx, ggx_vec3 wl, ggx_vec3 v, double f[3])
{
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    f[0] = f[1] = f[2] = ggx_brdf_eval(ctx, &one, wl, v);
}
static void sphere_table(const void *ctx, ggx_vec3 wl, ggx_vec3 v, double f[3]) { brdf_table_eval(ctx, wl, v, f); }

typedef struct prediction {
    const options *o;
    size_t nx, ny;
    double dx;
    ggx_shape fit;
    ggx_fit_info info;
    predict_spec spec;
    predict_result res;
    figure_predict_data sheet;
    float *sphere[3];
    int size;
} prediction;

static void render_spheres(prediction *p)
{
    render_spec r;
    render_spec_defaults(&r);
    r.light = RENDER_LIGHT_DIRECTIONAL;
    r.light_dir = direction_deg(55, -130), r.light_irradiance = 1;
    r.width = r.height = p->size, r.spp = 4, r.threads = p->spec.threads;
    size_t n = (size_t)p->size * (size_t)p->size * 3;
    const void *ctx[3] = {&p->fit, &p->res.all, &p->res.wave};
    render_brdf_fn fn[3] = {sphere_model, sphere_table, sphere_table};
    for (int k = 0; k < 3; k++) {
        if (k == 2 && !p->spec.wave) continue;
        p->sphere[k] = malloc(n * sizeof(float));
        if (!p->sphere[k]) die("out of memory for the spheres");
        render_direct(&r, fn[k], ctx[k], p->sphere[k]);
    }
    /* the exposure: the model's sphere at 1 in its 99.5th percentile (by a histogram of 4096 steps of its max) */
    double e = p->o->exposure, top = 0;
    int automatic = !p->o->have_exposure;
    if (automatic) {
        for (size_t i = 0; i < n; i++) top = fmax(top, p->sphere[0][i]);
        long hist[4096] = {0}, lit = 0;
        for (size_t i = 0; i < n; i += 3) {
            double v = fmax(p->sphere[0][i], fmax(p->sphere[0][i + 1], p->sphere[0][i + 2]));
            if (v > 0) hist[v >= top ? 4095 : (int)(v / top * 4096)]++, lit++;
        }
        long c = 0;
        int b = 4095;
        while (b > 0 && (c += hist[b]) < lit / 200) b--;
        double p995 = top > 0 ? (b + 1) * top / 4096 : 1;
        e = -log2(p995);
    }
    p->sheet.exposure = e, p->sheet.size = p->size;
    snprintf(p->sheet.light_words, sizeof p->sheet.light_words,
             "spheres under one distant light (theta 55, phi -130 degrees), F = 1, exposure %+.2f stops", e);
    static const char *label[3] = {"the fitted model", "traced, every bounce", "wave optics (R, G, B)"};
    for (int k = 0; k < 3; k++) {
        p->sheet.sphere[k] = p->sphere[k];
        snprintf(p->sheet.sphere_label[k], sizeof p->sheet.sphere_label[k], "%s", label[k]);
    }
}

/* The sheet's slices, table and lines of text. */
static void fill_sheet(prediction *p)
{
    figure_predict_data *d = &p->sheet;
    const predict_result *r = &p->res;
    snprintf(d->title, sizeof d->title, "ggx predict: %s", p->o->heightfield);
    snprintf(d->lines[0], sizeof d->lines[0],
             "%zu x %zu heights, spacing %.4g um, RMS height %.4g um (levelled), %.2f %% missing", p->nx, p->ny, p->dx,
             r->sigma_h, 100 * r->missing);
    double ax, ay, tx, ty, tz;
    ggx_shape_ellipsoid_params(&p->fit, &ax, &ay, &tx, &ty, &tz);
    char tails[96] = "";
    if (isfinite(p->info.tails.nu) && isfinite(p->info.tails.nu_std_error))
        snprintf(tails, sizeof tails, "; slope tails: Student t of nu %.3g +- %.2g (GGX: 2)", p->info.tails.nu,
                 p->info.tails.nu_std_error);
    snprintf(d->lines[1], sizeof d->lines[1], "fitted: --alpha %.4g,%.4g --skew %.4g,%.4g --rotate %.4g%s", ax, ay,
             tx / DEG + 0.0, ty / DEG + 0.0, tz / DEG + 0.0, tails);
    char untraced[96] = "";
    if (r->untraced)
        snprintf(untraced, sizeof untraced, "; %d incidences too grazing for the patch's band of heights", r->untraced);
    snprintf(d->lines[2], sizeof d->lines[2],
             "traced: %ld rays, every bounce followed (%.2g %% left the patch's side, %.2g %% fell through holes)%s",
             r->rays, 100.0 * (double)r->left / (double)(r->rays ? r->rays : 1),
             100.0 * (double)r->lost / (double)(r->rays ? r->rays : 1), untraced);
    if (p->spec.wave)
        snprintf(d->lines[3], sizeof d->lines[3],
                 "wave optics: 630, 532, 465 nm on %zu x %zu heights (%.0f x %.0f um) upsampled %d x, %.1f %% aliased",
                 r->wave_window[2], r->wave_window[3], (double)r->wave_window[2] * p->dx,
                 (double)r->wave_window[3] * p->dx, r->upsample, 100 * r->aliased);
    else
        snprintf(d->lines[3], sizeof d->lines[3], "wave optics: not computed (%s)",
                 p->o->no_wave ? "--no-wave" : "KISS FFT not built");
    d->slices = FIGURE_PREDICT_SLICES, d->slice_phi = 0;
    for (int c = 0; c < 3; c++) d->wavelength[c] = p->spec.wave ? ms_kirchhoff_rgb_um[c] : 0;
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    for (int s = 0; s < d->slices; s++) {
        d->slice_theta[s] = THETAS[s];
        ggx_vec3 wi = direction_deg(THETAS[s], 0);
        for (int i = 0; i < FIGURE_PREDICT_POINTS; i++) {
            double t = i - 89.0; /* negative: towards the light (phi 0), positive: the mirror's side (phi 180) */
            ggx_vec3 wo = direction_deg(fabs(t), t < 0 ? 0 : 180);
            double f[3];
            brdf_table_eval(&r->traced, wi, wo, f);
            d->traced[s][i] = f[0];
            d->model[s][i] = ggx_brdf_eval(&p->fit, &one, wi, wo);
            if (p->spec.wave) brdf_table_eval(&r->wave, wi, wo, f);
            for (int c = 0; c < 3; c++) d->wave[s][c][i] = p->spec.wave ? f[c] : NAN;
        }
    }
    d->rows = N_THETA;
    for (int it = 0; it < N_THETA; it++) {
        d->row_theta[it] = THETAS[it];
        d->albedo_traced[it] = predict_row_albedo(&r->traced, it, 0);
        d->albedo_model[it] = predict_row_albedo(&r->model, it, 0);
        d->l2_model_traced[it] = predict_row_l2(&r->model, 0, &r->traced, 0, it);
        d->albedo_wave[it] = p->spec.wave ? predict_row_albedo(&r->wave, it, 1) : NAN;
        d->l2_model_wave[it] = p->spec.wave ? predict_row_l2(&r->model, 0, &r->wave, 1, it) : NAN;
        d->l2_traced_wave[it] = p->spec.wave ? predict_row_l2(&r->traced, 0, &r->wave, 1, it) : NAN;
    }
}

static void write_table(FILE *f, const prediction *p, int csv)
{
    const predict_result *r = &p->res;
    if (csv)
        fprintf(f, "theta_i,phi_i,albedo_traced,albedo_traced_all,albedo_wave_r,albedo_wave_g,albedo_wave_b,"
                   "albedo_model,l2_model_traced,l2_model_wave_g,l2_traced_wave_g\n");
    else
        fprintf(f, "| theta_i | albedo traced (all bounces) | wave (532 nm) | model | L2 model/traced | model/wave | "
                   "traced/wave |\n|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < brdf_table_count(&r->traced); k++) {
        int it = k / N_PHI;
        if (!csv) {
            if (k % N_PHI) continue;
            const figure_predict_data *d = &p->sheet;
            fprintf(f, "| %.0f | %.4f (%.4f) | %.4f | %.4f | %.4f | %.4f | %.4f |\n", THETAS[it], d->albedo_traced[it],
                    predict_row_albedo(&r->all, it, 0), d->albedo_wave[it], d->albedo_model[it], d->l2_model_traced[it],
                    d->l2_model_wave[it], d->l2_traced_wave[it]);
            continue;
        }
        predict_incidence q = predict_incidence_of(r, k);
        fprintf(f, "%.6g,%.6g,%.8g,%.8g,%.8g,%.8g,%.8g,%.8g,%.8g,%.8g,%.8g\n", THETAS[it], 360.0 * (k % N_PHI) / N_PHI,
                q.albedo_traced, q.albedo_all, q.albedo_wave[0], q.albedo_wave[1], q.albedo_wave[2], q.albedo_model,
                q.l2_model_traced, q.l2_model_wave, q.l2_traced_wave);
    }
}

static void write_json(FILE *f, const prediction *p)
{
    const predict_result *r = &p->res;
    double ax, ay, tx, ty, tz;
    ggx_shape_ellipsoid_params(&p->fit, &ax, &ay, &tx, &ty, &tz);
    fprintf(f, "{\n  \"heightfield\": \"%s\",\n  \"points\": [%zu, %zu],\n  \"spacing_um\": %.9g,\n", p->o->heightfield,
            p->nx, p->ny, p->dx);
    fprintf(f, "  \"sigma_h_um\": %s,\n  \"missing_share\": %.9g,\n", json_number(r->sigma_h), r->missing);
    fprintf(f,
            "  \"fit\": {\"alpha\": [%.9g, %.9g], \"skew_deg\": [%.9g, %.9g], \"rotate_deg\": %.9g, \"t\": [%.9g, "
            "%.9g], \"sigma\": [%.9g, %.9g, %.9g], \"nu\": %s, \"nu_std_error\": %s},\n",
            ax, ay, tx / DEG, ty / DEG, tz / DEG, p->info.t[0], p->info.t[1], p->info.sigma[0], p->info.sigma[1],
            p->info.sigma[2], json_number(p->info.tails.nu), json_number(p->info.tails.nu_std_error));
    fprintf(f,
            "  \"traced\": {\"rays\": %ld, \"left\": %ld, \"lost\": %ld, \"capped\": %ld, \"bounces\": %d, "
            "\"window\": [%.9g, %.9g, %.9g, %.9g], \"untraced_incidences\": %d},\n",
            r->rays, r->left, r->lost, r->capped, p->spec.bounces, r->window[0], r->window[1], r->window[2],
            r->window[3], r->untraced);
    if (p->spec.wave)
        fprintf(f, "  \"wave\": {\"wavelengths_um\": [%.6g, %.6g, %.6g], \"aliased_share\": %.9g, \"upsample\": %d},\n",
                ms_kirchhoff_rgb_um[0], ms_kirchhoff_rgb_um[1], ms_kirchhoff_rgb_um[2], r->aliased, r->upsample);
    else fprintf(f, "  \"wave\": null,\n");
    fprintf(f, "  \"incidences\": [");
    for (int k = 0; k < brdf_table_count(&r->traced); k++) {
        predict_incidence q = predict_incidence_of(r, k);
        fprintf(f,
                "%s\n    {\"theta_i\": %.6g, \"phi_i\": %.6g, \"albedo_traced\": %s, \"albedo_traced_all\": %s, "
                "\"albedo_wave\": [%s, %s, %s], \"albedo_model\": %s, \"l2_model_traced\": %s, "
                "\"l2_model_wave\": %s, \"l2_traced_wave\": %s}",
                k ? "," : "", THETAS[k / N_PHI], 360.0 * (k % N_PHI) / N_PHI, json_number(q.albedo_traced),
                json_number(q.albedo_all), json_number(q.albedo_wave[0]), json_number(q.albedo_wave[1]),
                json_number(q.albedo_wave[2]), json_number(q.albedo_model), json_number(q.l2_model_traced),
                json_number(q.l2_model_wave), json_number(q.l2_traced_wave));
    }
    fprintf(f, "\n  ]\n}\n");
}

static void write_outputs(prediction *p, const char *dir)
{
    out_begin_set(); /* every file or none, the table on standard output included */
    char *path = alloc_printf("%s/sheet.pdf", dir);
    for (int fmt = 0; fmt < 2; fmt++) {
        canvas c;
        snprintf(path + strlen(path) - 3, 4, "%s", fmt ? "png" : "pdf");
        canvas_open_file(&c, path, fmt ? FMT_PNG : FMT_PDF, FIGURE_PREDICT_W, FIGURE_PREDICT_H, 0);
        canvas_clear(&c);
        figure_predict_draw(&c, &p->sheet);
        canvas_close_file(&c);
    }
    free(path);
    path = alloc_printf("%s/spheres.png", dir);
    canvas c;
    canvas_open_file(&c, path, FMT_PNG, 3 * p->size, p->size, 0);
    canvas_clear(&c);
    for (int k = 0; k < 3; k++)
        if (p->sphere[k]) paint_linear_rgb(c.cr, k * p->size, 0, 1, p->sphere[k], p->size, p->size, p->sheet.exposure);
    canvas_close_file(&c);
    free(path);
    out_file f;
    path = alloc_printf("%s/predict.csv", dir);
    out_open(&f, path);
    write_table(f.f, p, 1);
    out_close(&f);
    free(path);
    path = alloc_printf("%s/predict.json", dir);
    out_open(&f, path);
    write_json(f.f, p);
    out_close(&f);
    free(path);
    write_table(stdout, p, 0);
    out_flush_stdout();
    out_commit_set();
    out_keep_dirs();
}

int cmd_predict(options *o, const ggx_shape *s)
{
    (void)s;
    if (!o->heightfield) die("--heightfield FILE is required");
    if (o->size_h) die("--size: one number, the spheres' side in pixels");
    const char *dir = o->out ? o->out : "predict";
    ensure_dir(dir); /* before the work: a folder that cannot be made fails at once (and one made goes on failure) */
    prediction *p = calloc(1, sizeof *p);
    if (!p) die("out of memory");
    p->o = o;
    size_t missing;
    double *h = microsurface_heights_um(o, &p->nx, &p->ny, &p->dx, &missing);
    /* the fit of the same heights (levelled as the predictions are) */
    ggx_heightfield_options ho = {0, 0};
    ggx_fit_options fo = {0};
    fo.threads = o->threads > 0 ? o->threads : 2;
    ggx_status st = ggx_fit_heightfield(&p->fit, h, p->nx, p->ny, p->dx, p->dx, &ho, &fo, &p->info);
    if (st != GGX_OK) {
        free(h);
        die("%s: the fit failed: %s", o->heightfield, ggx_status_str(st));
    }
    predict_spec *sp = &p->spec;
    sp->h = h, sp->nx = p->nx, sp->ny = p->ny, sp->dx = p->dx, sp->model = &p->fit;
    sp->n_theta = N_THETA, sp->n_phi = N_PHI, sp->res = RES;
    for (int i = 0; i < N_THETA; i++) sp->theta[i] = THETAS[i] * DEG;
    sp->rays = o->n > 0 ? o->n : 1000000, sp->bounces = o->bounces > 0 ? o->bounces : 100;
    sp->threads = o->threads > 0 ? o->threads : 2;
    sp->wave = !o->no_wave && ms_kirchhoff_built();
    int bar = progress_wanted(o->progress);
    sp->progress = show, sp->progress_ctx = &bar;
    char err[512];
    if (predict_run(sp, &p->res, err, sizeof err) != 0) {
        free(h);
        die("%s: %s", o->heightfield, err);
    }
    if (bar) progress_end("predict", brdf_table_count(&p->res.traced));
    free(h);
    p->size = o->size > 0 ? o->size : 256;
    render_spheres(p);
    fill_sheet(p);
    if (p->spec.wave && p->res.aliased > 0.2)
        fprintf(stderr,
                "ggx: warning: the wave optics misplaces %.0f %% of the light at some incidence (the scan's spacing "
                "against the wavelength: docs/design/predict.md)\n",
                100 * p->res.aliased);
    write_outputs(p, dir);
    predict_free(&p->res);
    for (int k = 0; k < 3; k++) free(p->sphere[k]);
    free(p);
    return 0;
}
