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
    if (figure_predict_spheres(&p->sheet, &p->spec, &p->res, &p->fit, p->size, o->have_exposure ? &o->exposure : NULL,
                               p->sphere) != 0)
        die("out of memory for the spheres");
    figure_predict_fill(&p->sheet, &p->spec, &p->res, &p->fit, &p->info, o->heightfield,
                        o->no_wave ? "--no-wave" : "KISS FFT not built");
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
