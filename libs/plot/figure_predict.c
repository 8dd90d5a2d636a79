/* The sheet of a prediction (figure_predict.h). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "figure.h"
#include "figure_predict.h"

/* One slice: the traced BRDF as marks, the wave optics' three wavelengths and the model as lines. */
static void draw_slice(cairo_t *cr, const theme *th, double x, double y, double w, double h,
                       const figure_predict_data *d, int s)
{
    static plot_series sr[5]; /* (large: LINE_MAX_POINTS each) */
    int ns = 0;
    memset(sr, 0, sizeof sr);
    const char *colour[3] = {"red", "green", "blue"};
    snprintf(sr[ns].label, sizeof sr[ns].label, "fitted model");
    for (int i = 0; i < FIGURE_PREDICT_POINTS; i++)
        if (d->model[s][i] > 0) sr[ns].x[sr[ns].n] = i - 89, sr[ns].y[sr[ns].n++] = d->model[s][i];
    ns++;
    if (d->wavelength[0] > 0)
        for (int c = 0; c < 3; c++) {
            snprintf(sr[ns].label, sizeof sr[ns].label, "wave, %.0f nm (%s)", 1000 * d->wavelength[c], colour[c]);
            for (int i = 0; i < FIGURE_PREDICT_POINTS; i++)
                if (d->wave[s][c][i] > 0) sr[ns].x[sr[ns].n] = i - 89, sr[ns].y[sr[ns].n++] = d->wave[s][c][i];
            ns++;
        }
    snprintf(sr[ns].label, sizeof sr[ns].label, "traced");
    sr[ns].marks = 1;
    for (int i = 0; i < FIGURE_PREDICT_POINTS; i += 2)
        if (d->traced[s][i] > 0) sr[ns].x[sr[ns].n] = i - 89, sr[ns].y[sr[ns].n++] = d->traced[s][i];
    ns++;
    plot_axes ax = {
        "theta_o in the plane of incidence (degrees; negative: the light's side)", "BRDF (F = 1)", 1, 1, 1, 90.0};
    plot_draw(cr, th, x, y + 18, w, h - 18, 13, sr, ns, &ax);
    char line[128];
    snprintf(line, sizeof line, "incidence theta_i %.0f, phi_i %.0f degrees", d->slice_theta[s], d->slice_phi);
    set_rgb(cr, th->fg);
    text_font(cr, 14, 1);
    text_at(cr, x + 60, y + 6, 0.0, 0.5, line);
}

static void draw_table(cairo_t *cr, const theme *th, double x, double y, const figure_predict_data *d)
{
    const char *head[7] = {"theta_i", "albedo traced", "wave", "model", "L2 model/traced", "model/wave", "traced/wave"};
    const double col[7] = {0, 90, 220, 310, 400, 560, 680};
    text_font(cr, 13, 1);
    set_rgb(cr, th->fg);
    for (int k = 0; k < 7; k++) text_at(cr, x + col[k], y, 0.0, 0.5, head[k]);
    text_font(cr, 13, 0);
    for (int r = 0; r < d->rows; r++) {
        double v[7] = {d->row_theta[r],       d->albedo_traced[r], d->albedo_wave[r],   d->albedo_model[r],
                       d->l2_model_traced[r], d->l2_model_wave[r], d->l2_traced_wave[r]};
        for (int k = 0; k < 7; k++) {
            char cell[32];
            if (!isfinite(v[k])) snprintf(cell, sizeof cell, "-");
            else if (k == 0) snprintf(cell, sizeof cell, "%.0f", v[k]);
            else snprintf(cell, sizeof cell, "%.3f", v[k]);
            text_at(cr, x + col[k], y + 20 * (r + 1), 0.0, 0.5, cell);
        }
    }
}

void figure_predict_draw(canvas *c, const figure_predict_data *d)
{
    const int W = FIGURE_PREDICT_W;
    cairo_t *cr = c->cr;
    const theme *th = c->th;
    set_rgb(cr, th->fg);
    text_font(cr, 20, 1);
    text_at(cr, W / 2.0, 28, 0.5, 0.5, d->title);
    text_font(cr, 14, 0);
    for (int k = 0; k < 4; k++)
        if (d->lines[k][0]) text_at(cr, W / 2.0, 56 + 22 * k, 0.5, 0.5, d->lines[k]);
    const double Y0 = 150, PW = 590, PH = 330;
    for (int s = 0; s < d->slices; s++)
        draw_slice(cr, th, 10 + (s % 2) * (PW + 10), Y0 + (s / 2) * (PH + 16), PW, PH, d, s);
    double Y1 = Y0 + 2 * (PH + 16) + 10;
    text_font(cr, 15, 1);
    text_at(cr, 60, Y1, 0.0, 0.5,
            "per incidence (means over its azimuths): directional albedo and the relative L2 of the BRDF over the "
            "outgoing directions");
    draw_table(cr, th, 80, Y1 + 26, d);
    double Y2 = Y1 + 26 + 20 * (d->rows + 1) + 24, side = 360;
    text_font(cr, 15, 1);
    text_at(cr, 60, Y2, 0.0, 0.5, d->light_words);
    for (int k = 0; k < FIGURE_PREDICT_SPHERES; k++) {
        if (!d->sphere[k]) continue;
        double x = 30 + k * (side + 30);
        paint_linear_rgb(cr, x, Y2 + 20, side / d->size, d->sphere[k], d->size, d->size, d->exposure);
        set_rgb(cr, th->fg);
        text_font(cr, 14, 0);
        text_at(cr, x + side / 2, Y2 + 20 + side + 16, 0.5, 0.5, d->sphere_label[k]);
    }
}
