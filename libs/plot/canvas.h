/* Drawing surfaces for the figures: cairo surfaces (PNG, SVG, PDF) whose encoded bytes go to a writer the caller
 * gives (a file, memory), the themes, text, the colour map and the colour bar. SPDX-License-Identifier: MIT */
#ifndef GGX_PLOT_CANVAS_H
#define GGX_PLOT_CANVAS_H

#include <cairo.h>
#include <stddef.h>

#include "ggx/ggx.h"

/* Degrees to radians: the figures' angles are in degrees. */
#define DEG (GGX_PI / 180.0)

typedef enum canvas_format { FMT_PNG, FMT_SVG, FMT_PDF } canvas_format;

/* Colours of a theme: background, text and lines, secondary lines, the hemisphere's disk, the grey region. */
typedef struct theme {
    double bg[3], fg[3], faint[3], disk[3], region[3];
} theme;
const theme *theme_get(int dark);
void set_rgb(cairo_t *cr, const double c[3]);

/* The extension of a format, with the dot (".png", ".svg", ".pdf"). */
const char *format_ext(canvas_format f);

/* Where a canvas's encoded bytes go, in order: returns 0 when all n bytes were taken, else nonzero. */
typedef int (*canvas_write_fn)(void *closure, const unsigned char *data, size_t n);

/* A surface of w x h pixels (PNG) or points (SVG, PDF; 1 pt = 1/72 in) whose bytes go to write(closure, ...): SVG
 * and PDF as they are drawn, PNG at canvas_close. canvas_page starts a new page (PDF; the other formats keep one).
 * canvas_open and canvas_close return 0, or -1 with cairo's reason in error (canvas_close: write_failed set when
 * the writer refused bytes); canvas_close frees the surface either way. */
typedef struct canvas {
    cairo_surface_t *surface;
    cairo_t *cr;
    canvas_format format;
    int w, h;
    const theme *th;
    canvas_write_fn write;
    void *closure;
    int write_failed;
    char error[128];
} canvas;
int canvas_open(canvas *c, canvas_format fmt, int w, int h, int dark, canvas_write_fn write, void *closure);
void canvas_clear(canvas *c);
void canvas_page(canvas *c);
int canvas_close(canvas *c);

/* viridis at t in [0, 1] (clamped; NaN gives its darkest colour) */
void colormap(double t, double rgb[3]);

/* Text in DejaVu Sans: text_at anchors the string at (x, y) by the fractions ax (0 left, 1 right) and ay (0 top of
 * the capitals, 0.5 their middle, 1 baseline). */
void text_font(cairo_t *cr, double size, int bold);
double font_size_of(cairo_t *cr);
double text_width(cairo_t *cr, const char *s);
void text_at(cairo_t *cr, double x, double y, double ax, double ay, const char *s);
void text_vertical(cairo_t *cr, double x, double y, const char *s); /* centred, reading upwards */
int nice_ticks(double lo, double hi, int want, double *ticks, int max);
void format_tick(double v, char *buf, size_t n);
/* A vertical colour bar at (x, y, w, h) from 0 (or vmin_log on a log scale) to vmax, ticks and a label at its right. */
void colour_bar(cairo_t *cr, const theme *th, double x, double y, double w, double h, double vmax, double vmin_log,
                int log_scale, const char *label, double font);
void arrow(cairo_t *cr, double x0, double y0, double x1, double y1, double head);
/* Paints img (marked dirty here) with its top left at (x, y), each of its pixels scale canvas units wide, without
 * smoothing (a cell stays a cell), and destroys it. */
void paint_image(cairo_t *cr, cairo_surface_t *img, double x, double y, double scale);
/* Paints a linear RGB image (w x h floats times 3, the top row first) at (x, y), each pixel scale units wide, as 8-bit
 * sRGB of min(1, 2^exposure L) per channel (NaN and negative values black). */
void paint_linear_rgb(cairo_t *cr, double x, double y, double scale, const float *rgb, int w, int h, double exposure);

#endif
