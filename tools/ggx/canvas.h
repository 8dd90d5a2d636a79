/* Drawing surfaces of the ggx command: cairo over the command's atomic output files. SPDX-License-Identifier: MIT */
#ifndef GGX_CANVAS_H
#define GGX_CANVAS_H

#include <cairo.h>

#include "cli.h"

typedef enum canvas_format { FMT_PNG, FMT_SVG, FMT_PDF } canvas_format;

/* Colours of a theme: background, text and lines, secondary lines, the hemisphere's disk, the grey region. */
typedef struct theme {
    double bg[3], fg[3], faint[3], disk[3], region[3];
} theme;
const theme *theme_get(int dark);
void set_rgb(cairo_t *cr, const double c[3]);

/* The format a file name asks for (.png, .svg, .pdf), else fallback. */
canvas_format format_of_path(const char *path, canvas_format fallback);
const char *format_ext(canvas_format f);
/* 1 for "-" (standard output) and for what is not a regular file (a device, a FIFO): written in any format. */
int path_is_stream(const char *path);
/* The format of a figure's --out: its name's (.png, .svg, .pdf), or deflt for a stream; dies with one line for a
 * file name that ends in none of them. */
canvas_format figure_format_of(const char *path, canvas_format deflt);

/* A surface of w x h pixels (PNG) or points (SVG, PDF; 1 pt = 1/72 in) written to path through out_open: the file
 * appears complete at canvas_close or not at all. canvas_page starts a new page (PDF; the other formats keep one). */
typedef struct canvas {
    cairo_surface_t *surface;
    cairo_t *cr;
    canvas_format format;
    int w, h;
    const theme *th;
    out_file out;
    char path[1024];
} canvas;
void canvas_open(canvas *c, const char *path, canvas_format fmt, int w, int h, int dark);
void canvas_clear(canvas *c);
void canvas_page(canvas *c);
void canvas_close(canvas *c);

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

#endif
