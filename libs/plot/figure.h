/* The figures of the model: the seeds' hemisphere figures and the line plots researchers make of the model, drawn
 * with cairo into any rectangle of a canvas (a file of its own, or a page of a PDF).
 * SPDX-License-Identifier: MIT */
#ifndef GGX_PLOT_FIGURE_H
#define GGX_PLOT_FIGURE_H

#include "canvas.h"
#include "ggx/ggx_samplers.h"

typedef enum figure_kind {
    FIG_NDF,
    FIG_NDF_SIDE,
    FIG_VNDF,
    FIG_VNDF_SIDE,
    FIG_GRID,
    FIG_GRID_SIDE, /* the seeds' hemisphere figures */
    FIG_G1,
    FIG_LAMBDA,
    FIG_NDF_SLICE,
    FIG_FURNACE,
    FIG_POLAR,
    FIG_SLICE, /* line plots, the polar plot, the slice */
    FIG_COUNT
} figure_kind;
/* The figure's name ("ndf", "vndf-side", ...: the names of ggx plot --figure) and its inverse, -1 for no figure. */
const char *figure_name(figure_kind k);
int figure_kind_of(const char *name);
/* The kinds' families: seen from the side, equal-area grids, VNDF densities, line plots (and the polar plot and
 * the slice). */
static inline int figure_is_side(figure_kind k)
{
    return k == FIG_NDF_SIDE || k == FIG_VNDF_SIDE || k == FIG_GRID_SIDE;
}
static inline int figure_is_grid(figure_kind k) { return k == FIG_GRID || k == FIG_GRID_SIDE; }
static inline int figure_is_vndf(figure_kind k) { return k == FIG_VNDF || k == FIG_VNDF_SIDE; }
static inline int figure_is_line(figure_kind k) { return k >= FIG_G1; }

/* What a figure shows. */
typedef struct figure_spec {
    figure_kind kind;
    const ggx_shape *s;
    ggx_vec3 view;                   /* VNDF figures and VNDF samplers' grids; above the horizon */
    const ggx_sampler_info *sampler; /* grids: the map of the unit square */
    int log_scale, dark;
    double from;          /* side views: the azimuth of the viewer (radians); NAN: the default */
    char shape_text[192]; /* the caption's shape, e.g. "αx 0.15, αy 0.5, θx 0°, θy 0°, θz 0°" */
    char note[192];       /* one more caption line (the seed figure reproduced), or "" */
    double eta;           /* polar: 0 for the BRDF, else the BSDF's relative index of refraction */
    double phi_d;         /* slice: the difference angle phi_d (radians) */
} figure_spec;

/* The hemisphere's projection in a figure: from above (x right, y up) or from the side, seen from the horizontal
 * direction toward (azimuth `from`) with right = n x toward pointing right and n up. */
typedef struct hemi_proj {
    int side;
    double cx, cy, R; /* the projected centre of the hemisphere (the origin) and its radius, in canvas units */
    ggx_vec3 right, toward;
    double from;
} hemi_proj;

/* Projects a unit direction; returns 0 when it is hidden (side views: behind the hemisphere, m.toward < 0). */
int hemi_project(const hemi_proj *p, ggx_vec3 m, double *X, double *Y);
/* The visible unit direction under a canvas point; 0 when the point is outside the projected hemisphere. */
int hemi_unproject(const hemi_proj *p, double X, double Y, ggx_vec3 *m);

/* The density a hemisphere figure shows: D(m) m.n for NDF figures, the VNDF pdf for the view for VNDF figures. */
double figure_density(const figure_spec *f, ggx_vec3 m);
/* The density's largest value and where it is (a dense search of the hemisphere refined by pattern search on the
 * function itself, not on the image): the colour scale's top and the peak the tests find in the image. */
double figure_peak(const figure_spec *f, ggx_vec3 *where);
/* The grey region of engstad-vndf-proof: 1 when the view reflected about m, 2 (m.v) m - v, lies above the horizon. Its
 * boundary is theta_b(phi) = atan2(cos theta_v, -sin theta_v cos(phi - phi_v)) / 2 (derived in docs/figures.md). */
int figure_grey(ggx_vec3 v, ggx_vec3 m);
/* The point of the grey region's boundary at azimuth phi (radians), for a view v above the horizon. */
ggx_vec3 figure_grey_boundary(ggx_vec3 v, double phi);
/* 1 when the figure shades the grey region (VNDF densities, grids of a VNDF sampler). */
int figure_has_grey(const figure_spec *f);
/* The default azimuth a side view is seen from. The lobe leans toward the view's azimuth (VNDF figures and VNDF
 * samplers' grids) or the NDF peak's (0 when the peak is at n). The view is from that azimuth - 90 degrees (the lean
 * in profile, pointing right, as in the seeds: from -y for phi_v = 0) when the lobe is at least as wide across that
 * plane (||A' t|| for t toward the viewer) as across the lean; else from the lobe's azimuth, facing it, so that the
 * visible half is not a sliver (phi_v = 90 on the seeds' shape, narrow along x). */
double figure_default_from(const figure_spec *f);

/* A line plot's series: points joined by a line in the palette's colour and dashes, or (marks) measured points
 * drawn as open circles in the text's colour. */
#define LINE_MAX_POINTS 360
typedef struct plot_series {
    double x[LINE_MAX_POINTS], y[LINE_MAX_POINTS];
    int n, marks;
    char label[96];
} plot_series;
/* Its axes: labels, a log scale for y, x over [-90, 90] (slice) or [0, 90], the points beyond range_x_max left out
 * of the y range, and the y range's top at 1.05 times the highest point (free_top) or at least 1.05. */
typedef struct plot_axes {
    const char *xlabel, *ylabel;
    int logy, slice, free_top;
    double range_x_max;
} plot_axes;
/* Draws the series into (x, y, w, h) of cr with font size F, a legend at the right. */
void plot_draw(cairo_t *cr, const theme *th, double x, double y, double w, double h, double F, const plot_series *sr,
               int ns, const plot_axes *ax);

/* Curve k of a line figure (FIG_G1 and after): its first max points into x, y and its legend into label (n bytes);
 * returns the number of points written, or -1 when the figure has no curve k. Not thread-safe. */
int figure_curve(const figure_spec *f, int k, double *x, double *y, int max, char *label, size_t n);

/* What the figures share (figure_common.c): the caption (returns its height; at most max_lines lines, of at most
 * FIGURE_CAPTION_LINES: title, shape and view, grey region, log scale, seed note), the font size for a rectangle,
 * the curves' colour-blind-safe palette, an azimuth (radians) in degrees in (-180, 180], and a horizontal
 * direction's name ("x", "-y", or its azimuth). */
enum { FIGURE_CAPTION_LINES = 5 };
double figure_azimuth_deg(double rad);
void figure_direction_name(ggx_vec3 d, char *buf, size_t n);
double figure_draw_caption(cairo_t *cr, const theme *th, double x, double y, double w, double F, const figure_spec *f,
                           int max_lines);
double figure_font(double w, double h);
extern const double FIGURE_PALETTE[6][3];

/* The polar figure (figure_polar.c): its curves, as figure_curve, and its drawing. */
int polar_curve(const figure_spec *f, int k, double *x, double *y, int max, char *label, size_t n);
void polar_draw(cairo_t *cr, const theme *th, double x, double y, double w, double h, const figure_spec *f);

/* The slice figure (figure_slice.c): f_r (F = 1) over the half-vector angle theta_h and the difference angle
 * theta_d (Rusinkiewicz's coordinates, the half vector at phi_h = 0) at f->phi_d; 0 where wi or wo is below the
 * horizon. slice_dirs gives the directions of a point. */
double slice_value(const figure_spec *f, double theta_h, double theta_d);
void slice_dirs(double theta_h, double theta_d, double phi_d, ggx_vec3 *wi, ggx_vec3 *wo);
void slice_draw(cairo_t *cr, const theme *th, double x, double y, double w, double h, const figure_spec *f);

/* Draws the figure into the rectangle (x, y, w, h) of cr; *proj (may be NULL) receives the hemisphere's
 * projection (hemisphere figures). */
void figure_draw(cairo_t *cr, const theme *th, double x, double y, double w, double h, const figure_spec *f,
                 hemi_proj *proj);
/* The figure's natural aspect, height / width, and the height of a file of a given width with it. */
double figure_aspect(figure_kind k);
int figure_height(figure_kind k, int width);
/* The captions' words for a shape given by its alphas and angles (degrees). */
void figure_shape_caption(char *buf, size_t n, double ax, double ay, double tx, double ty, double tz);

#endif
