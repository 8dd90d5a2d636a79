/* A measured surface's appearance predicted from its heights (docs/design/predict.md): the BRDF by geometric optics
 * (the heights traced as a patch, every bounce followed) and by wave optics (the Kirchhoff BRDF at three
 * wavelengths), each tabulated over a grid of incidences beside the fitted model's, with the albedos and the
 * distances between them per incidence. SPDX-License-Identifier: MIT */
#ifndef GGX_PREDICT_PREDICT_H
#define GGX_PREDICT_PREDICT_H

#include <stddef.h>
#include <stdint.h>

#include "brdf_table.h"
#include "ggx/ggx.h"

typedef struct predict_spec {
    const double *h;        /* nx ny heights in micrometres, h[y nx + x]; NaN marks a missing point */
    size_t nx, ny;          /* at least 3 x 3 */
    double dx;              /* the grid's spacing in micrometres, equal along x and y */
    const ggx_shape *model; /* the model set beside the predictions (the fit of the same heights) */
    int n_theta;            /* the incidences: polar angles theta (radians, increasing, below 90 degrees) times */
    double theta[BRDF_TABLE_MAX_THETA];
    int n_phi; /* n_phi azimuths 2 pi j / n_phi */
    int res;   /* the tables' cells a side over the projected outgoing directions */
    long rays; /* traced rays per incidence */
    int bounces;
    int wave;           /* 1: the wave optics too, at ms_kirchhoff_rgb_um */
    size_t wave_points; /* the most FFT points of one wave-optics setup (ms_kirchhoff_spec's max_points, on the
                           * largest centred window that fits the upsampling chosen: its crop); 0: 2^22 */
    int threads;        /* >= 1; the results do not depend on it */
    /* Called from the calling thread after each incidence's trace and wave optics (may be NULL). */
    void (*progress)(void *ctx, long done, long total);
    void *progress_ctx;
} predict_spec;

typedef struct predict_result {
    brdf_table traced; /* single scattering, traced (one channel): each cell's share of the rays whose way is known
                        * (not fallen through a missing region, not left the patch's side) */
    brdf_table all;    /* every bounce, traced (one channel) */
    brdf_table wave;   /* wave optics, red, green, blue (three channels; no incidences where spec->wave is 0) */
    brdf_table model;  /* the model (one channel): each cell's share of ggx_sample_brdf's weights on a jittered 512^2
                        * grid, the cell's mean of f in expectation however narrow the lobe */
    long rays, left, lost, capped; /* summed over the incidences: traced, left the patch's side, fell through a
                                    * missing region, still bouncing after spec->bounces */
    double window[4];              /* the normal incidence's window of ray origins, in grid spacings */
    int untraced;                  /* incidences too grazing for the patch (ms_patch_window finds no window for
                                    * the band of its heights): not known in traced and all */
    double missing;                /* the share of missing points */
    double sigma_h;                /* the RMS height after levelling, micrometres */
    double aliased;                /* the wave optics' largest aliased share over its setups */
    int upsample;                  /* the wave optics' upsampling at normal incidence, blue */
    size_t wave_window[4];         /* and its window of the heights: first x, first y, points along x and y */
} predict_result;

/* Traces and (with spec->wave) computes the wave optics of each incidence into r (predict_free releases it; on
 * failure nothing is left to free). The heights are levelled first (ms_level). An incidence the patch cannot trace
 * (ms_patch_window finds no window) is unknown in every table. Returns 0, or -1 with a one-line
 * reason in err (the tracer's or the wave optics' refusal, a bad grid, no memory). */
int predict_run(const predict_spec *spec, predict_result *r, char *err, size_t errn);
void predict_free(predict_result *r);

/* One incidence's figures: the albedos (traced single scattering and every bounce, wave optics red, green, blue, the
 * model) and the relative L2 distances of the model from the trace and from the green wave, and of the trace from
 * the green wave (brdf_table_l2: ||a - b|| / ||b||, b the second); NaN where not known (no wave optics: its five). */
typedef struct predict_incidence {
    double albedo_traced, albedo_all, albedo_wave[3], albedo_model;
    double l2_model_traced, l2_model_wave, l2_traced_wave;
} predict_incidence;
predict_incidence predict_incidence_of(const predict_result *r, int k);

/* The rows of a sheet: for polar angle row it, channel ch, the mean over its known azimuths of a table's albedo, or
 * of the relative L2 of a (channel ca) against b (channel cb); NaN where none is known. */
double predict_row_albedo(const brdf_table *t, int it, int ch);
double predict_row_l2(const brdf_table *a, int ca, const brdf_table *b, int cb, int it);

#endif
