/* Drawing surfaces for the figures (canvas.h): PNG, SVG and PDF through a caller's writer, the themes, text, the
 * colour map and the colour bar. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cairo-pdf.h>
#include <cairo-svg.h>

#include "canvas.h"

static const double VIRIDIS[256][3] = {
#include "viridis.inc"
};

void colormap(double t, double rgb[3])
{
    if (!(t > 0)) t = 0; /* NaN too */
    if (t > 1) t = 1;
    double x = t * 255.0;
    int i = (int)x;
    if (i > 254) i = 254;
    double f = x - i;
    for (int k = 0; k < 3; k++) rgb[k] = (1 - f) * VIRIDIS[i][k] + f * VIRIDIS[i + 1][k];
}

static const theme LIGHT = {{1, 1, 1}, {0.08, 0.08, 0.1}, {0.45, 0.45, 0.5}, {0.93, 0.93, 0.94}, {0.55, 0.55, 0.58}};
static const theme DARK = {
    {0.09, 0.09, 0.11}, {0.92, 0.92, 0.93}, {0.6, 0.6, 0.65}, {0.16, 0.16, 0.19}, {0.45, 0.45, 0.5}};
const theme *theme_get(int dark) { return dark ? &DARK : &LIGHT; }

void set_rgb(cairo_t *cr, const double c[3]) { cairo_set_source_rgb(cr, c[0], c[1], c[2]); }

const char *format_ext(canvas_format f) { return f == FMT_PNG ? ".png" : f == FMT_SVG ? ".svg" : ".pdf"; }

/* cairo's writer: into the caller's, remembering a refusal (canvas_close reports it). */
static cairo_status_t write_out(void *closure, const unsigned char *data, unsigned int length)
{
    canvas *c = closure;
    if (c->write(c->closure, data, length) == 0) return CAIRO_STATUS_SUCCESS;
    c->write_failed = 1;
    return CAIRO_STATUS_WRITE_ERROR;
}

static int canvas_error(canvas *c, cairo_status_t st)
{
    snprintf(c->error, sizeof c->error, "%s", cairo_status_to_string(st));
    return -1;
}

int canvas_open(canvas *c, canvas_format fmt, int w, int h, int dark, canvas_write_fn write, void *closure)
{
    memset(c, 0, sizeof *c);
    c->format = fmt, c->w = w, c->h = h, c->th = theme_get(dark), c->write = write, c->closure = closure;
    if (fmt == FMT_PNG) c->surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    else if (fmt == FMT_SVG) c->surface = cairo_svg_surface_create_for_stream(write_out, c, w, h);
    else c->surface = cairo_pdf_surface_create_for_stream(write_out, c, w, h);
    if (fmt == FMT_PDF) cairo_pdf_surface_set_metadata(c->surface, CAIRO_PDF_METADATA_CREATOR, "ggx (libggx)");
    c->cr = cairo_create(c->surface);
    if (cairo_status(c->cr) != CAIRO_STATUS_SUCCESS) {
        cairo_status_t st = cairo_status(c->cr);
        cairo_destroy(c->cr);
        cairo_surface_destroy(c->surface);
        c->cr = NULL, c->surface = NULL;
        return canvas_error(c, st);
    }
    canvas_clear(c);
    return 0;
}

void canvas_clear(canvas *c)
{
    set_rgb(c->cr, c->th->bg);
    cairo_paint(c->cr);
}

void canvas_page(canvas *c)
{
    cairo_show_page(c->cr);
    canvas_clear(c);
}

int canvas_close(canvas *c)
{
    cairo_destroy(c->cr);
    cairo_status_t st;
    if (c->format == FMT_PNG) {
        cairo_surface_flush(c->surface);
        st = cairo_surface_write_to_png_stream(c->surface, write_out, c);
    } else {
        cairo_surface_finish(c->surface);
        st = cairo_surface_status(c->surface);
    }
    cairo_surface_destroy(c->surface);
    c->cr = NULL, c->surface = NULL;
    return st == CAIRO_STATUS_SUCCESS ? 0 : canvas_error(c, st);
}

void text_font(cairo_t *cr, double size, int bold)
{
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

/* The typographic minus: a hyphen that starts a number ("-10°", "φ -90°", a negative tick) becomes U+2212; hyphens
 * inside words (sampler names such as walter-v1) stay. */
static const char *typeset(const char *s, char *out, size_t n)
{
    size_t k = 0;
    for (const char *p = s; *p && k + 4 < n; p++) {
        int number = p[0] == '-' && (p[1] >= '0' && p[1] <= '9') &&
                     (p == s || p[-1] == ' ' || p[-1] == '(' || p[-1] == ',');
        if (number) out[k++] = '\xe2', out[k++] = '\x88', out[k++] = '\x92';
        else out[k++] = *p;
    }
    out[k] = '\0';
    return out;
}

double text_width(cairo_t *cr, const char *s)
{
    char t[512];
    cairo_text_extents_t e;
    cairo_text_extents(cr, typeset(s, t, sizeof t), &e);
    return e.x_advance;
}

void text_at(cairo_t *cr, double x, double y, double ax, double ay, const char *s)
{
    /* ay: 0 puts the top of capitals at y, 0.5 centres them, 1 puts the baseline at y */
    char t[512];
    double cap = 0.72 * font_size_of(cr);
    cairo_move_to(cr, x - ax * text_width(cr, s), y + (1.0 - ay) * cap);
    cairo_show_text(cr, typeset(s, t, sizeof t));
}

double font_size_of(cairo_t *cr)
{
    cairo_matrix_t m;
    cairo_get_font_matrix(cr, &m);
    return m.yy;
}

void text_vertical(cairo_t *cr, double x, double y, const char *s)
{
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_rotate(cr, -GGX_PI / 2);
    text_at(cr, 0, 0, 0.5, 0.5, s);
    cairo_restore(cr);
}

/* Tick values that are round numbers: 1, 2 or 5 times a power of ten, about `want` of them over [lo, hi]. */
int nice_ticks(double lo, double hi, int want, double *ticks, int max)
{
    if (!(hi > lo)) return 0;
    double raw = (hi - lo) / want, p = pow(10.0, floor(log10(raw))), step = p;
    if (raw / p > 5) step = 10 * p;
    else if (raw / p > 2) step = 5 * p;
    else if (raw / p > 1) step = 2 * p;
    int n = 0;
    for (double t = ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step && n < max; t += step)
        ticks[n++] = fabs(t) < 1e-12 * step ? 0.0 : t;
    return n;
}

void format_tick(double v, char *buf, size_t n)
{
    if (v != 0 && (fabs(v) >= 1e5 || fabs(v) < 1e-3)) snprintf(buf, n, "%.0e", v);
    else snprintf(buf, n, "%g", v);
}

void colour_bar(cairo_t *cr, const theme *th, double x, double y, double w, double h, double vmax, double vmin_log,
                int log_scale, const char *label, double font)
{
    int steps = (int)ceil(h);
    for (int i = 0; i < steps; i++) {
        double rgb[3];
        colormap(1.0 - (i + 0.5) / steps, rgb);
        set_rgb(cr, rgb);
        cairo_rectangle(cr, x, y + h * i / steps, w, h / steps + 0.6);
        cairo_fill(cr);
    }
    set_rgb(cr, th->fg);
    cairo_set_line_width(cr, 0.8);
    cairo_rectangle(cr, x, y, w, h);
    cairo_stroke(cr);
    text_font(cr, font, 0);
    double ticks[32];
    int nt;
    if (log_scale) {
        nt = 0;
        for (double d = ceil(log10(vmin_log) - 1e-9); d <= log10(vmax) + 1e-9 && nt < 32; d += 1)
            ticks[nt++] = pow(10, d);
    } else {
        nt = nice_ticks(0, vmax, 5, ticks, 32);
    }
    for (int i = 0; i < nt; i++) {
        double f = log_scale ? log(ticks[i] / vmin_log) / log(vmax / vmin_log) : ticks[i] / vmax;
        double ty = y + h * (1 - f);
        cairo_move_to(cr, x + w, ty);
        cairo_line_to(cr, x + w + 0.25 * font, ty);
        cairo_stroke(cr);
        char buf[32];
        format_tick(ticks[i], buf, sizeof buf);
        text_at(cr, x + w + 0.4 * font, ty, 0, 0.5, buf);
    }
    /* the top of the scale, the density's peak, said above the bar */
    char top[48];
    snprintf(top, sizeof top, "max %.4g", vmax);
    text_at(cr, x, y - 0.5 * font, 0, 1, top);
    text_vertical(cr, x + w + 3.3 * font, y + 0.5 * h, label);
}

void arrow(cairo_t *cr, double x0, double y0, double x1, double y1, double head)
{
    double dx = x1 - x0, dy = y1 - y0, L = hypot(dx, dy);
    if (!(L > 0)) return;
    dx /= L, dy /= L;
    cairo_move_to(cr, x0, y0);
    cairo_line_to(cr, x1 - 0.6 * head * dx, y1 - 0.6 * head * dy);
    cairo_stroke(cr);
    cairo_move_to(cr, x1, y1);
    cairo_line_to(cr, x1 - head * dx - 0.45 * head * dy, y1 - head * dy + 0.45 * head * dx);
    cairo_line_to(cr, x1 - head * dx + 0.45 * head * dy, y1 - head * dy - 0.45 * head * dx);
    cairo_close_path(cr);
    cairo_fill(cr);
}

void paint_image(cairo_t *cr, cairo_surface_t *img, double x, double y, double scale)
{
    cairo_surface_mark_dirty(img);
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, scale, scale);
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_paint(cr);
    cairo_restore(cr);
    cairo_surface_destroy(img);
}

static unsigned char srgb8(double v)
{
    v = isfinite(v) ? fmin(fmax(v, 0.0), 1.0) : 0.0;
    v = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
    return (unsigned char)lrint(255 * v);
}

void paint_linear_rgb(cairo_t *cr, double x, double y, double scale, const float *rgb, int w, int h, double exposure)
{
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    unsigned char *data = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img);
    double k = exp2(exposure);
    for (int j = 0; j < h; j++) {
        uint32_t *row = (uint32_t *)(data + (size_t)j * (size_t)stride);
        for (int i = 0; i < w; i++) {
            const float *c = rgb + 3 * ((size_t)j * (size_t)w + (size_t)i);
            row[i] = (uint32_t)srgb8(k * c[0]) << 16 | (uint32_t)srgb8(k * c[1]) << 8 | srgb8(k * c[2]);
        }
    }
    paint_image(cr, img, x, y, scale);
}
