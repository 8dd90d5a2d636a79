/* The sheet of a prediction (figure_predict.c): what a measured surface's geometry predicts beside its fitted model,
 * on one page. SPDX-License-Identifier: MIT */
#ifndef GGX_PLOT_FIGURE_PREDICT_H
#define GGX_PLOT_FIGURE_PREDICT_H

#include "canvas.h"
#include "ggx/ggx_fit.h"
#include "predict.h"

/* The canvas's size, in canvas units; the slices (incidences), their points (theta_o from -89 to 89 degrees, one a
 * degree), the table's rows and the spheres. */
enum {
    FIGURE_PREDICT_W = 1200,
    FIGURE_PREDICT_H = 1560,
    FIGURE_PREDICT_SLICES = 4,
    FIGURE_PREDICT_POINTS = 179,
    FIGURE_PREDICT_ROWS = 12,
    FIGURE_PREDICT_SPHERES = 3
};

typedef struct figure_predict_data {
    char title[256];    /* the first line: the file */
    char lines[4][256]; /* the lines under it: the scan, the fit, the tails, the predictions' settings ("" none) */
    int slices;         /* 1 to FIGURE_PREDICT_SLICES */
    double slice_theta[FIGURE_PREDICT_SLICES]; /* each slice's incidence: polar angle, degrees */
    double slice_phi;                          /* their azimuth (degrees): the plane of the slices */
    /* the BRDF (F = 1) in the plane of incidence at theta_o = -89 + i degrees (negative: towards the light's side),
     * per slice: traced, wave optics (three wavelengths, red, green, blue) and the fitted model; NaN: not known */
    double traced[FIGURE_PREDICT_SLICES][FIGURE_PREDICT_POINTS];
    double wave[FIGURE_PREDICT_SLICES][3][FIGURE_PREDICT_POINTS];
    double model[FIGURE_PREDICT_SLICES][FIGURE_PREDICT_POINTS];
    double wavelength[3]; /* micrometres; 0: no wave optics */
    /* the table: per polar angle of incidence (means over its azimuths) the albedos and the relative L2 errors */
    int rows;
    double row_theta[FIGURE_PREDICT_ROWS];
    double albedo_traced[FIGURE_PREDICT_ROWS], albedo_wave[FIGURE_PREDICT_ROWS], albedo_model[FIGURE_PREDICT_ROWS];
    double l2_model_traced[FIGURE_PREDICT_ROWS], l2_model_wave[FIGURE_PREDICT_ROWS],
        l2_traced_wave[FIGURE_PREDICT_ROWS];
    /* the lit spheres: size x size linear RGB each (NULL: not drawn), their captions, and the exposure in stops
     * (paint_linear_rgb's) */
    int size;
    const float *sphere[FIGURE_PREDICT_SPHERES];
    char sphere_label[FIGURE_PREDICT_SPHERES][96];
    char light_words[160];
    double exposure;
} figure_predict_data;

/* The sheet's text, slices (the first four polar angles of s, at azimuth 0) and rows (s's polar angles) from the
 * prediction r of s and the model fit with its fit's info (tails), for the file name; no_wave says why there is no
 * wave optics where s->wave is 0. The spheres are figure_predict_spheres'. */
void figure_predict_fill(figure_predict_data *d, const predict_spec *s, const predict_result *r, const ggx_shape *fit,
                         const ggx_fit_info *info, const char *name, const char *no_wave);
/* The three spheres (size x size pixels each, 4 jittered samples a pixel; sphere[k] malloc'd, the caller frees them,
 * NULL for the wave optics where s->wave is 0) under one distant light (theta 55, phi -130 degrees, irradiance 1;
 * render_direct, ggx render's sphere camera): the model exactly, r's every-bounce trace and r's wave optics by
 * brdf_table_eval; into d, with their captions and the exposure (stops; NULL: the model's sphere at 1 in its 99.5th
 * percentile). Returns 0, or -1 when out of memory. */
int figure_predict_spheres(figure_predict_data *d, const predict_spec *s, const predict_result *r, const ggx_shape *fit,
                           int size, const double *exposure, float *sphere[3]);

/* Draws the sheet onto c, a canvas of FIGURE_PREDICT_W x FIGURE_PREDICT_H: the lines of text, the slices on a log
 * scale, the table and the spheres. */
void figure_predict_draw(canvas *c, const figure_predict_data *d);

#endif
