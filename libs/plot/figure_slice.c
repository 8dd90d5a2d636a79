/* The slice figure (ggx plot --figure slice): the BRDF (F = 1) over Rusinkiewicz's half-vector angle theta_h and
 * difference angle theta_d at one phi_d, as BRDF Explorer's image slice, on a logarithmic colour scale.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "figure.h"

enum { SLICE_CELLS = 180 }; /* cells per axis over [0, 90) degrees */

/* Rusinkiewicz's directions: h at (theta_h, phi_h = 0), the difference vector d at (theta_d, phi_d) in the frame
 * that carries n to h (a rotation by theta_h about y), wi = that rotation of d, wo = wi reflected about h. */
void slice_dirs(double theta_h, double theta_d, double phi_d, ggx_vec3 *wi, ggx_vec3 *wo)
{
    double dx = sin(theta_d) * cos(phi_d), dy = sin(theta_d) * sin(phi_d), dz = cos(theta_d);
    double ch = cos(theta_h), sh = sin(theta_h);
    ggx_vec3 h = {sh, 0.0, ch};
    *wi = (ggx_vec3){ch * dx + sh * dz, dy, -sh * dx + ch * dz};
    double k = 2.0 * (wi->x * h.x + wi->y * h.y + wi->z * h.z);
    *wo = (ggx_vec3){k * h.x - wi->x, k * h.y - wi->y, k * h.z - wi->z};
}

double slice_value(const figure_spec *f, double theta_h, double theta_d)
{
    ggx_vec3 wi, wo;
    slice_dirs(theta_h, theta_d, f->phi_d, &wi, &wo);
    if (!(wi.z > 0) || !(wo.z > 0)) return 0.0;
    return ggx_brdf_eval(f->s, NULL, wi, wo);
}

void slice_draw(cairo_t *cr, const theme *th, double x, double y, double w, double h, const figure_spec *f)
{
    static double v[SLICE_CELLS][SLICE_CELLS];
    double vmax = 0.0;
    for (int j = 0; j < SLICE_CELLS; j++)
        for (int i = 0; i < SLICE_CELLS; i++) {
            double a = (i + 0.5) * 90.0 / SLICE_CELLS * DEG, b = (j + 0.5) * 90.0 / SLICE_CELLS * DEG;
            v[j][i] = slice_value(f, a, b);
            if (isfinite(v[j][i]) && v[j][i] > vmax) vmax = v[j][i];
        }
    if (!(vmax > 0)) vmax = 1.0;
    const double vmin = vmax * 1e-4; /* four decades */
    double F = figure_font(w, h);
    double cap = figure_draw_caption(cr, th, x, y, w, F, f, 3);
    double band = 7.0 * F; /* the colour bar and its labels */
    double side = fmin(w - band - 5.0 * F, h - cap - 4.0 * F);
    double px = x + 4.2 * F, py = y + cap + 0.6 * F;
    /* the image: one pixel per cell, scaled without smoothing; blank where f_r is 0 (a direction below the horizon) */
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, SLICE_CELLS, SLICE_CELLS);
    unsigned char *data = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img);
    cairo_surface_flush(img);
    for (int j = 0; j < SLICE_CELLS; j++) {
        unsigned int *row = (unsigned int *)(data + (long)(SLICE_CELLS - 1 - j) * stride); /* theta_d up */
        for (int i = 0; i < SLICE_CELLS; i++) {
            double d = v[j][i], rgb[3];
            if (!(d > 0)) {
                row[i] = 0;
                continue;
            }
            colormap(log(fmax(d, vmin) / vmin) / log(vmax / vmin), rgb);
            row[i] = 0xff000000u | (unsigned)lround(255 * rgb[0]) << 16 | (unsigned)lround(255 * rgb[1]) << 8 |
                     (unsigned)lround(255 * rgb[2]);
        }
    }
    paint_image(cr, img, px, py, side / SLICE_CELLS);
    /* frame, ticks every 15 degrees, axis labels */
    set_rgb(cr, th->fg);
    cairo_set_line_width(cr, fmax(0.6, 0.07 * F));
    cairo_rectangle(cr, px, py, side, side);
    cairo_stroke(cr);
    text_font(cr, 0.8 * F, 0);
    for (int t = 0; t <= 90; t += 15) {
        char b[16];
        snprintf(b, sizeof b, "%d", t);
        double X = px + side * t / 90.0, Y = py + side * (1.0 - t / 90.0);
        cairo_move_to(cr, X, py + side), cairo_line_to(cr, X, py + side + 0.3 * F), cairo_stroke(cr);
        text_at(cr, X, py + side + 0.5 * F, 0.5, 0, b);
        cairo_move_to(cr, px, Y), cairo_line_to(cr, px - 0.3 * F, Y), cairo_stroke(cr);
        text_at(cr, px - 0.5 * F, Y, 1, 0.5, b);
    }
    text_font(cr, 0.85 * F, 0);
    text_at(cr, px + 0.5 * side, py + side + 1.9 * F, 0.5, 0, "half-vector angle θh (degrees)");
    text_vertical(cr, x + 1.0 * F, py + 0.5 * side, "difference angle θd (degrees)");
    colour_bar(cr, th, px + side + 1.2 * F, py, 1.1 * F, side, vmax, vmin, 1, "f_r (sr⁻¹)", 0.75 * F);
}
