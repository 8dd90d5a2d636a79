/* The figures: the seeds' hemisphere figures (densities and equal-area grids, from above and from the side, with
 * engstad-vndf-proof's grey region) and the line plots (G1, Lambda, NDF slices, furnace and albedo), drawn with cairo.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure.h"
#include "ggx/ggx_inline.h"
#include "common/eig3.h"


/* ---------------------------------------------------------------------------------------------------------------
 * The hemisphere's projection
 * --------------------------------------------------------------------------------------------------------------- */

int hemi_project(const hemi_proj *p, ggx_vec3 m, double *X, double *Y)
{
    if (!p->side) {
        *X = p->cx + p->R * m.x, *Y = p->cy - p->R * m.y;
        return 1;
    }
    *X = p->cx + p->R * ggx_k_dot_d(m, p->right), *Y = p->cy - p->R * m.z;
    return ggx_k_dot_d(m, p->toward) >= -1e-9; /* the silhouette itself is visible */
}

int hemi_unproject(const hemi_proj *p, double X, double Y, ggx_vec3 *m)
{
    double a = (X - p->cx) / p->R, b = (p->cy - Y) / p->R, r2 = a * a + b * b;
    if (r2 > 1.0) return 0;
    if (!p->side) {
        *m = ggx_k_v3_d(a, b, sqrt(1.0 - r2));
        return 1;
    }
    if (b < 0) return 0;
    double c = sqrt(1.0 - r2);
    *m = ggx_k_v3_d(a * p->right.x + c * p->toward.x, a * p->right.y + c * p->toward.y, b);
    return 1;
}

static void hemi_set_from(hemi_proj *p, double from)
{
    p->from = from;
    p->toward = ggx_k_v3_d(cos(from), sin(from), 0);
    p->right = ggx_k_v3_d(-p->toward.y, p->toward.x, 0); /* n x toward */
}

/* ---------------------------------------------------------------------------------------------------------------
 * What the figures show
 * --------------------------------------------------------------------------------------------------------------- */

double figure_density(const figure_spec *f, ggx_vec3 m)
{
    return figure_is_vndf(f->kind) ? ggx_pdf_vndf(f->s, f->view, m) : ggx_pdf_ndf(f->s, m);
}

double figure_peak(const figure_spec *f, ggx_vec3 *where)
{
    /* the hemisphere as the unit disk (a, b) -> (a, b, sqrt(1 - a^2 - b^2)): no singularity at the pole */
    const int N = 240;
    double best = -1, ba = 0, bb = 0;
    for (int i = 0; i <= N; i++)
        for (int j = 0; j <= N; j++) {
            double a = -1 + 2.0 * i / N, b = -1 + 2.0 * j / N, r2 = a * a + b * b;
            if (r2 > 1) continue;
            double d = figure_density(f, ggx_k_v3_d(a, b, sqrt(1 - r2)));
            if (d > best) best = d, ba = a, bb = b;
        }
    for (double step = 2.0 / N; step > 1e-10; step *= 0.5) {
        for (int moved = 1; moved;) {
            moved = 0;
            static const int dirs[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}};
            for (int k = 0; k < 8; k++) {
                double a = ba + step * dirs[k][0], b = bb + step * dirs[k][1], r2 = a * a + b * b;
                if (r2 > 1) continue;
                double d = figure_density(f, ggx_k_v3_d(a, b, sqrt(1 - r2)));
                if (d > best) best = d, ba = a, bb = b, moved = 1;
            }
        }
    }
    if (where) *where = ggx_k_v3_d(ba, bb, sqrt(fmax(0.0, 1 - ba * ba - bb * bb)));
    return best;
}

int figure_grey(ggx_vec3 v, ggx_vec3 m) { return 2.0 * ggx_k_dot_d(m, v) * m.z - v.z > 0; }


/* The grey region's boundary at azimuth phi: the polar angle where 2 (m.v) m.z = v.z (docs/figures.md). */
ggx_vec3 figure_grey_boundary(ggx_vec3 v, double phi)
{
    double st = sqrt(fmax(0.0, 1 - v.z * v.z)), pv = atan2(v.y, v.x);
    double tb = 0.5 * atan2(v.z, -st * cos(phi - pv));
    return ggx_k_v3_d(sin(tb) * cos(phi), sin(tb) * sin(phi), cos(tb));
}

/* The lobe's width seen across a horizontal direction t: ||A' t||, the ellipsoid's extent along t (alpha_x along x
 * for a diagonal A). */
static double lobe_width(const ggx_shape *s, double azimuth)
{
    double t[3] = {cos(azimuth), sin(azimuth), 0}, w = 0;
    for (int i = 0; i < 3; i++) {
        double r = s->a[i][0] * t[0] + s->a[i][1] * t[1];
        w += r * r;
    }
    return w;
}

double figure_default_from(const figure_spec *f)
{
    double lobe; /* the azimuth the lobe leans toward */
    if (figure_is_vndf(f->kind) || figure_has_grey(f)) {
        lobe = atan2(f->view.y, f->view.x);
    } else {
        figure_spec nd = *f;
        nd.kind = FIG_NDF;
        ggx_vec3 m;
        figure_peak(&nd, &m);
        lobe = hypot(m.x, m.y) > 1e-2 ? atan2(m.y, m.x) : 0.0;
    }
    /* in profile (from lobe - 90 degrees: the lean in the image plane, pointing right) unless the lobe is narrower
     * across that plane than across the other, where the visible half would be a sliver: then facing it */
    double profile = lobe - GGX_PI / 2;
    return lobe_width(f->s, profile) >= lobe_width(f->s, lobe) ? profile : lobe;
}

/* ---------------------------------------------------------------------------------------------------------------
 * Spherical polygons on the visible half of a side view
 * --------------------------------------------------------------------------------------------------------------- */

/* Appends the great-circle arc from a to b (shorter way, end points excluded) to out. */
static int arc_points(ggx_vec3 a, ggx_vec3 b, ggx_vec3 *out, int n, int max)
{
    double w = acos(fmax(-1.0, fmin(1.0, ggx_k_dot_d(a, b))));
    int k = (int)(w / (2.0 * GGX_PI / 180));
    for (int i = 1; i < k && n < max; i++) {
        double t = (double)i / k, s = sin(w);
        double ca = sin((1 - t) * w) / s, cb = sin(t * w) / s;
        out[n++] = ggx_k_v3_d(ca * a.x + cb * b.x, ca * a.y + cb * b.y, ca * a.z + cb * b.z);
    }
    return n;
}

/* Clips a closed spherical polygon (densely sampled) to the hemisphere m.e >= 0; the cut follows the great circle
 * m.e = 0, the silhouette of a side view. Returns the number of points written to out (0: wholly hidden). */
static int clip_front(const ggx_vec3 *p, int n, ggx_vec3 e, ggx_vec3 *out, int max)
{
    int start = -1;
    for (int i = 0; i < n; i++)
        if (ggx_k_dot_d(p[i], e) >= 0) {
            start = i;
            break;
        }
    if (start < 0) return 0;
    int k = 0;
    ggx_vec3 exit_pt = p[start];
    for (int j = 0; j < n; j++) {
        ggx_vec3 a = p[(start + j) % n], b = p[(start + j + 1) % n];
        double da = ggx_k_dot_d(a, e), db = ggx_k_dot_d(b, e);
        if (da >= 0 && k < max) out[k++] = a;
        if ((da >= 0) != (db >= 0)) {
            double t = da / (da - db);
            ggx_vec3 x = ggx_k_normalize_d(
                ggx_k_v3_d(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)));
            if (da >= 0) {
                exit_pt = x;
                if (k < max) out[k++] = x;
            } else {
                k = arc_points(exit_pt, x, out, k, max);
                if (k < max) out[k++] = x;
            }
        }
    }
    return k;
}

static void path_points(cairo_t *cr, const hemi_proj *hp, const ggx_vec3 *p, int n)
{
    cairo_new_path(cr);
    for (int i = 0; i < n; i++) {
        double X, Y;
        hemi_project(hp, p[i], &X, &Y);
        if (i == 0) cairo_move_to(cr, X, Y);
        else cairo_line_to(cr, X, Y);
    }
    cairo_close_path(cr);
}

/* The grey region as a closed path (visible part only). */
#define GREY_N 720
static void grey_path(cairo_t *cr, const hemi_proj *hp, ggx_vec3 v)
{
    static ggx_vec3 ring[GREY_N], vis[GREY_N * 3];
    for (int i = 0; i < GREY_N; i++) ring[i] = figure_grey_boundary(v, 2 * GGX_PI * i / GREY_N);
    if (!hp->side) path_points(cr, hp, ring, GREY_N);
    else path_points(cr, hp, vis, clip_front(ring, GREY_N, hp->toward, vis, GREY_N * 3));
}

/* The grey region's boundary curve itself, where visible. */
static void grey_contour(cairo_t *cr, const hemi_proj *hp, ggx_vec3 v)
{
    int pen = 0;
    cairo_new_path(cr);
    for (int i = 0; i <= GREY_N; i++) {
        double X, Y;
        int vis = hemi_project(hp, figure_grey_boundary(v, 2 * GGX_PI * i / GREY_N), &X, &Y);
        if (vis && pen) cairo_line_to(cr, X, Y);
        else if (vis) cairo_move_to(cr, X, Y);
        pen = vis;
    }
    cairo_stroke(cr);
}

/* ---------------------------------------------------------------------------------------------------------------
 * Captions and marks
 * --------------------------------------------------------------------------------------------------------------- */

/* Text in the theme's colour on a halo of the background's, readable over the density and off it. */
static void text_halo(cairo_t *cr, const theme *th, double x, double y, double ax, double ay, const char *s)
{
    double size = font_size_of(cr);
    cairo_new_path(cr);
    cairo_move_to(cr, x - ax * text_width(cr, s), y + (1.0 - ay) * 0.72 * size);
    cairo_text_path(cr, s);
    set_rgb(cr, th->bg);
    cairo_set_line_width(cr, 0.25 * size);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_stroke_preserve(cr);
    set_rgb(cr, th->fg);
    cairo_fill(cr);
}

static void draw_marks(cairo_t *cr, const theme *th, const hemi_proj *hp, const figure_spec *f, double F, int show_view)
{
    double cx = hp->cx, cy = hp->cy, R = hp->R;
    cairo_set_line_width(cr, fmax(0.6, 0.07 * F));
    set_rgb(cr, th->fg);
    text_font(cr, 0.9 * F, 0);
    char name[32];
    if (!hp->side) {
        cairo_new_path(cr);
        cairo_arc(cr, cx, cy, R, 0, 2 * GGX_PI);
        cairo_stroke(cr);
        arrow(cr, cx + R, cy, cx + R + 1.1 * F, cy, 0.45 * F);
        text_at(cr, cx + R + 0.6 * F, cy - 0.55 * F, 0.5, 1, "x");
        arrow(cr, cx, cy - R, cx, cy - R - 1.1 * F, 0.45 * F);
        text_at(cr, cx - 0.45 * F, cy - R - 0.8 * F, 1, 0.5, "y");
        /* n points at the viewer, at the centre: said beside the disk, not drawn over the density's peak */
        set_rgb(cr, th->faint);
        text_font(cr, 0.8 * F, 0);
        text_at(cr, cx - R - 0.2 * F, cy + R, 0, 1, "n: centre");
    } else {
        cairo_new_path(cr);
        cairo_arc(cr, cx, cy, R, GGX_PI, 2 * GGX_PI);
        cairo_stroke(cr);
        cairo_move_to(cr, cx - R - 0.3 * F, cy);
        cairo_line_to(cr, cx + R, cy);
        cairo_stroke(cr);
        arrow(cr, cx + R, cy, cx + R + 1.1 * F, cy, 0.45 * F);
        figure_direction_name(hp->right, name, sizeof name);
        text_at(cr, cx + R + 0.15 * F, cy - 0.55 * F, 0, 1, name);
        arrow(cr, cx, cy - R, cx, cy - R - 1.1 * F, 0.45 * F);
        text_at(cr, cx + 0.45 * F, cy - R - 0.8 * F, 0, 0.5, "n");
    }
    if (show_view) {
        double X, Y;
        int vis = hemi_project(hp, f->view, &X, &Y);
        double dash[] = {0.25 * F, 0.2 * F};
        cairo_set_source_rgb(cr, 1, 1, 1);
        cairo_set_line_width(cr, fmax(1.0, 0.16 * F));
        if (!vis) cairo_set_dash(cr, dash, 2, 0);
        cairo_new_path(cr);
        cairo_arc(cr, X, Y, 0.42 * F, 0, 2 * GGX_PI);
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_set_line_width(cr, fmax(0.6, 0.07 * F));
        cairo_new_path(cr);
        cairo_arc(cr, X, Y, 0.55 * F, 0, 2 * GGX_PI);
        cairo_stroke(cr);
        cairo_set_dash(cr, NULL, 0, 0);
        /* the label below right of the mark, clear of the axis labels (above the x arrow, left of the y / n one) */
        text_font(cr, 0.95 * F, 1);
        text_halo(cr, th, X + 0.75 * F, Y + 0.75 * F, 0, 0, "v");
    }
}

/* ---------------------------------------------------------------------------------------------------------------
 * Hemisphere figures
 * --------------------------------------------------------------------------------------------------------------- */

/* The colour of a density value, linear or over four decades. */
static void density_colour(double d, double vmax, int log_scale, double rgb[3])
{
    double t = log_scale ? (d > vmax * 1e-4 ? log(d / (vmax * 1e-4)) / log(1e4) : 0.0) : d / vmax;
    colormap(t, rgb);
}

/* The density image: each pixel the mean colour of 3 x 3 samples inside the projected hemisphere, its alpha the
 * covered fraction; the grey region hatched in dark lines (the colours elsewhere untouched, so the brightest pixel
 * stays the density's peak). One pixel per unit on image surfaces, two on vector ones. */
static void draw_density(cairo_t *cr, const hemi_proj *hp, const figure_spec *f, double vmax, double F)
{
    int vector = cairo_surface_get_type(cairo_get_target(cr)) != CAIRO_SURFACE_TYPE_IMAGE;
    double scale = vector ? 2.0 : 1.0;
    double x0 = floor(hp->cx - hp->R - 1), y0 = floor(hp->cy - hp->R - 1);
    double x1 = ceil(hp->cx + hp->R + 1), y1 = ceil(hp->side ? hp->cy + 1 : hp->cy + hp->R + 1);
    int W = (int)((x1 - x0) * scale), H = (int)((y1 - y0) * scale);
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, W, H);
    unsigned char *data = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img), grey = figure_has_grey(f);
    double period = fmax(4.0, 0.55 * F), width = fmax(1.0, 0.09 * F);
    const int ss = 3;
    cairo_surface_flush(img);
    for (int j = 0; j < H; j++) {
        unsigned int *row = (unsigned int *)(data + (long)j * stride);
        for (int i = 0; i < W; i++) {
            double acc[3] = {0, 0, 0};
            int in = 0;
            for (int q = 0; q < ss * ss; q++) {
                double X = x0 + (i + (q % ss + 0.5) / ss) / scale, Y = y0 + (j + (q / ss + 0.5) / ss) / scale;
                ggx_vec3 m;
                if (!hemi_unproject(hp, X, Y, &m)) continue;
                double rgb[3], d = figure_density(f, m);
                if (f->log_scale && !(d > 0)) continue; /* zero has no place on a log scale: left blank */
                density_colour(d, vmax, f->log_scale, rgb);
                if (grey && figure_grey(f->view, m) && fmod(X + Y, period) < width)
                    for (int k = 0; k < 3; k++) rgb[k] = 0.3 * rgb[k] + 0.7 * 0.5;
                for (int k = 0; k < 3; k++) acc[k] += rgb[k];
                in++;
            }
            unsigned int px = 0;
            if (in) {
                double a = (double)in / (ss * ss);
                px = (unsigned)(a * 255 + 0.5) << 24;
                for (int k = 0; k < 3; k++) px |= (unsigned)(acc[k] / in * a * 255 + 0.5) << (16 - 8 * k);
            }
            row[i] = px;
        }
    }
    cairo_surface_mark_dirty(img);
    cairo_save(cr);
    cairo_translate(cr, x0, y0);
    cairo_scale(cr, 1 / scale, 1 / scale);
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), vector ? CAIRO_FILTER_GOOD : CAIRO_FILTER_NEAREST);
    cairo_paint(cr);
    cairo_restore(cr);
    cairo_surface_destroy(img);
}

/* The grid: each of the 10 x 10 cells of the unit square, its boundary traced through the sampler's map, filled in a
 * checkerboard; on side views only the visible half is drawn (clipped on the silhouette). */
/* Appends the map of the segment from (a1, a2) to (b1, b2) of the unit square (start point excluded), subdividing
 * where the map turns fast: near a point where the sampler's Jacobian is singular (the caps map at the cap's rim
 * opposite the view) one step of the square sweeps a long arc of the hemisphere. */
static int trace_edge(const figure_spec *f, double a1, double a2, ggx_vec3 ma, double b1, double b2, ggx_vec3 *out,
                      int n, int max, int depth)
{
    /* u = 1 itself is outside the samplers' domain; 1 - 1e-7 keeps the map away from the rounding of its singular point */
    ggx_vec3 mb = f->sampler->sample(f->s, f->view, fmin(b1, 1.0 - 1e-7), fmin(b2, 1.0 - 1e-7));
    if (depth < 14 && ggx_k_dot_d(ma, mb) < cos(1.0 * DEG)) {
        double c1 = 0.5 * (a1 + b1), c2 = 0.5 * (a2 + b2);
        n = trace_edge(f, a1, a2, ma, c1, c2, out, n, max, depth + 1);
        ggx_vec3 mc = n > 0 ? out[n - 1] : ma;
        return trace_edge(f, c1, c2, mc, b1, b2, out, n, max, depth + 1);
    }
    /* still a jump: the segment crosses the singular point, whose image is the arc of the great circle m.v = 0
     * between the two limits (the boundary of the visible normals) */
    if (ggx_k_dot_d(ma, mb) < cos(1.0 * DEG)) n = arc_points(ma, mb, out, n, max);
    if (n < max) out[n++] = mb;
    return n;
}

/* The grid: each of the 10 x 10 cells of the unit square, its boundary traced through the sampler's map, filled in a
 * checkerboard; on side views only the visible half is drawn (clipped on the silhouette). */
static void draw_grid(cairo_t *cr, const theme *th, const hemi_proj *hp, const figure_spec *f, double F)
{
    enum { CELLS = 10, STEPS = 40, NP = 4096 };
    static ggx_vec3 poly[NP], vis[NP * 2];
    static const double colours[2][3] = {{0.23, 0.32, 0.55}, {0.99, 0.72, 0.30}};
    for (int i = 0; i < CELLS; i++)
        for (int j = 0; j < CELLS; j++) {
            const double c1[5] = {(double)i / CELLS, (i + 1.0) / CELLS, (i + 1.0) / CELLS, (double)i / CELLS,
                                  (double)i / CELLS};
            const double c2[5] = {(double)j / CELLS, (double)j / CELLS, (j + 1.0) / CELLS, (j + 1.0) / CELLS,
                                  (double)j / CELLS};
            int n = 0;
            ggx_vec3 prev = f->sampler->sample(f->s, f->view, c1[0], c2[0]);
            for (int e = 0; e < 4; e++)
                for (int t = 1; t <= STEPS; t++) {
                    double g0 = (t - 1.0) / STEPS, g = (double)t / STEPS;
                    n = trace_edge(f, c1[e] + g0 * (c1[e + 1] - c1[e]), c2[e] + g0 * (c2[e + 1] - c2[e]), prev,
                                   c1[e] + g * (c1[e + 1] - c1[e]), c2[e] + g * (c2[e + 1] - c2[e]), poly, n, NP, 0);
                    prev = poly[n - 1];
                }
            const ggx_vec3 *p = poly;
            if (hp->side) {
                n = clip_front(poly, n, hp->toward, vis, NP * 2);
                p = vis;
            }
            if (n < 3) continue;
            path_points(cr, hp, p, n);
            const double *c = colours[(i + j) % 2];
            cairo_set_source_rgba(cr, c[0], c[1], c[2], 0.55);
            cairo_fill_preserve(cr);
            set_rgb(cr, th->fg);
            cairo_set_line_width(cr, fmax(0.4, 0.05 * F));
            cairo_stroke(cr);
        }
}

static void draw_hemisphere(cairo_t *cr, const theme *th, double x, double y, double w, double h, const figure_spec *f,
                            hemi_proj *out)
{
    double F = figure_font(w, h);
    /* a small figure (an icon, a thumbnail) keeps the picture, its marks and the title; the rest would be unreadable */
    int compact = w < 300 || h < 200;
    double cap = figure_draw_caption(cr, th, x, y, w, F, f, compact ? 1 : FIGURE_CAPTION_LINES);
    int density = !figure_is_grid(f->kind);
    double band = density && !compact ? 7.4 * F : 0.0, margin = 1.8 * F;
    double bx = x, by = y + cap, bw = w - band, bh = h - cap - 0.4 * F;
    hemi_proj hp = {0};
    hp.side = figure_is_side(f->kind);
    hemi_set_from(&hp, isnan(f->from) ? -GGX_PI / 2 : f->from);
    if (!hp.side) {
        hp.R = fmax(1.0, 0.5 * fmin(bw - 2 * margin, bh - 2 * margin));
        hp.cx = bx + 0.5 * bw, hp.cy = by + 0.5 * bh;
    } else {
        hp.R = fmax(1.0, fmin(0.5 * bw - margin - 2.6 * F, bh - margin - 1.6 * F));
        hp.cx = bx + 0.5 * bw, hp.cy = by + margin + hp.R + 0.5 * (bh - margin - 1.6 * F - hp.R);
    }
    /* the hemisphere's disk */
    set_rgb(cr, th->disk);
    cairo_new_path(cr);
    if (hp.side) cairo_arc(cr, hp.cx, hp.cy, hp.R, GGX_PI, 2 * GGX_PI);
    else cairo_arc(cr, hp.cx, hp.cy, hp.R, 0, 2 * GGX_PI);
    cairo_close_path(cr);
    cairo_fill(cr);
    double vmax = 0;
    if (density) {
        vmax = figure_peak(f, NULL);
        draw_density(cr, &hp, f, vmax, F);
    } else {
        if (figure_has_grey(f)) {
            grey_path(cr, &hp, f->view);
            set_rgb(cr, th->region);
            cairo_fill(cr);
        }
        draw_grid(cr, th, &hp, f, F);
    }
    /* rings of polar angle 30 and 60 degrees (top view) */
    if (!hp.side) {
        double dash[] = {0.3 * F, 0.3 * F};
        cairo_set_dash(cr, dash, 2, 0);
        cairo_set_line_width(cr, fmax(0.4, 0.05 * F));
        cairo_set_source_rgba(cr, 0.5, 0.5, 0.55, 0.8);
        for (int r = 30; r <= 60; r += 30) {
            cairo_new_path(cr);
            cairo_arc(cr, hp.cx, hp.cy, hp.R * sin(r * DEG), 0, 2 * GGX_PI);
            cairo_stroke(cr);
        }
        cairo_set_dash(cr, NULL, 0, 0);
    }
    if (figure_has_grey(f)) {
        cairo_set_line_width(cr, fmax(0.8, 0.12 * F));
        cairo_set_source_rgba(cr, th->fg[0], th->fg[1], th->fg[2], 0.75);
        grey_contour(cr, &hp, f->view);
    }
    draw_marks(cr, th, &hp, f, F, figure_is_vndf(f->kind) || figure_has_grey(f));
    if (hp.side && !compact) {
        set_rgb(cr, th->faint);
        text_font(cr, 0.8 * F, 0);
        char seen[96];
        snprintf(seen, sizeof seen, "seen from φ %.4g°", figure_azimuth_deg(hp.from));
        text_at(cr, hp.cx, hp.cy + 0.6 * F, 0.5, 0, seen);
    }
    if (band > 0) {
        double bar_h = hp.side ? hp.R : 2 * hp.R, bar_y = hp.cy - hp.R;
        colour_bar(cr, th, x + w - band + 1.2 * F, bar_y, 1.1 * F, bar_h, vmax, vmax * 1e-4, f->log_scale,
                   f->log_scale ? "pdf (sr⁻¹, log scale)" : "pdf (sr⁻¹)", 0.8 * F);
    }
    if (out) *out = hp;
}

/* ---------------------------------------------------------------------------------------------------------------
 * Line plots
 * --------------------------------------------------------------------------------------------------------------- */

typedef plot_series series;

static ggx_vec3 dir_deg(double theta, double phi)
{
    return ggx_k_v3_d(sin(theta * DEG) * cos(phi * DEG), sin(theta * DEG) * sin(phi * DEG), cos(theta * DEG));
}

/* The azimuths the direction plots sample: the principal ones of an unskewed shape, the four quadrants otherwise. */
static int plot_azimuths(const ggx_shape *s, double *phi)
{
    if (s->kind != GGX_SHAPE_SKEWED) {
        double p0 = atan2(s->tangent_sin, s->tangent_cos) / DEG;
        phi[0] = p0, phi[1] = p0 + 45, phi[2] = p0 + 90;
        return 3;
    }
    for (int i = 0; i < 4; i++) phi[i] = 90.0 * i;
    return 4;
}

/* The NDF's principal axes: D(m) = c / (m^T B m)^2 with B = A'^{-1} A'^{-T}, by the library's 3x3 eigen-solver. */
static void principal_axes(const ggx_shape *s, ggx_vec3 axes[3], double eig[3])
{
    double B[3][3], V[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            B[i][j] = 0;
            for (int k = 0; k < 3; k++) B[i][j] += s->ainv_t[k][i] * s->ainv_t[k][j];
        }
    ggx_eig3(B, V);
    for (int i = 0; i < 3; i++) eig[i] = B[i][i], axes[i] = ggx_k_v3_d(V[i][0], V[i][1], V[i][2]);
}

static int line_series(const figure_spec *f, series *sr, const char **xlabel, const char **ylabel, int *logy)
{
    double phi[4];
    int na = plot_azimuths(f->s, phi), ns = 0;
    ggx_vec3 n = ggx_k_v3_d(0, 0, 1);
    *xlabel = "view polar angle θ (degrees)";
    *logy = 0;
    if (f->kind == FIG_G1 || f->kind == FIG_LAMBDA) {
        *ylabel = f->kind == FIG_G1 ? "G1(v)" : "Λ(v)";
        for (int a = 0; a < na; a++, ns++) {
            series *s = &sr[ns];
            s->n = 0;
            snprintf(s->label, sizeof s->label, "φ %.4g°", figure_azimuth_deg(phi[a] * DEG));
            for (int i = 0; i <= 179; i++) {
                double th = fmin(0.5 * i, 89.9);
                ggx_vec3 v = dir_deg(th, phi[a]);
                s->x[s->n] = th;
                s->y[s->n++] = f->kind == FIG_G1 ? ggx_g1(f->s, v, n) : ggx_lambda(f->s, v);
            }
        }
    } else if (f->kind == FIG_NDF_SLICE) {
        *xlabel = "angle from the peak in the plane (degrees)";
        *ylabel = "D(m) (sr⁻¹)";
        *logy = 1;
        ggx_vec3 ax[3];
        double eig[3];
        principal_axes(f->s, ax, eig);
        int top = 0; /* the peak: the axis of the smallest eigenvalue of B, turned to the upper side */
        for (int i = 1; i < 3; i++)
            if (eig[i] < eig[top]) top = i;
        ggx_vec3 pk = ax[top].z < 0 ? ggx_k_v3_d(-ax[top].x, -ax[top].y, -ax[top].z) : ax[top];
        for (int i = 0; i < 3; i++) {
            if (i == top) continue;
            series *s = &sr[ns++];
            s->n = 0;
            ggx_vec3 t = ax[i];
            if (t.x + 1e-9 * t.y < 0) t = ggx_k_v3_d(-t.x, -t.y, -t.z);
            double alpha = sqrt(eig[top] / eig[i]);
            snprintf(s->label, sizeof s->label, "toward φ %.4g° (α %.3g)", figure_azimuth_deg(atan2(t.y, t.x)), alpha);
            for (int k = 0; k <= 358; k++) {
                double g = (-89.5 + 0.5 * k) * DEG;
                ggx_vec3 m = ggx_k_v3_d(cos(g) * pk.x + sin(g) * t.x, cos(g) * pk.y + sin(g) * t.y,
                                        cos(g) * pk.z + sin(g) * t.z);
                double d = ggx_ndf(f->s, m);
                if (d > 0) s->x[s->n] = g / DEG, s->y[s->n++] = d;
            }
        }
    } else {
        *ylabel = "fraction of energy";
        for (int a = 0; a < 2; a++) {
            double p = phi[a == 0 ? 0 : 2]; /* unskewed: the principal axes; skewed: 0 and 180 degrees */
            series *w = &sr[ns++], *e = &sr[ns++];
            w->n = e->n = 0;
            snprintf(w->label, sizeof w->label, "weak furnace, φ %.4g°", figure_azimuth_deg(p * DEG));
            snprintf(e->label, sizeof e->label, "albedo E(v), φ %.4g°", figure_azimuth_deg(p * DEG));
            for (int i = 0; i <= 179; i++) {
                double th = fmin(0.5 * i, 89.9);
                ggx_vec3 v = dir_deg(th, p);
                /* int G1(v) D(m) (m.v)+ / (v.n) dm = G1(v) (1 + Lambda(v)): the lune's area over the footprint */
                w->x[w->n] = th, w->y[w->n++] = ggx_g1(f->s, v, n) * (1 + ggx_lambda(f->s, v));
                if (i % 4 == 0 || i == 179) e->x[e->n] = th, e->y[e->n++] = ggx_albedo(f->s, v);
            }
        }
        /* an anisotropic shape: the isotropic E at sqrt(alpha_x alpha_y), which renderers use in its place */
        const ggx_shape *s = f->s;
        if (s->kind != GGX_SHAPE_SKEWED && fabs(s->alpha_x - s->alpha_y) > 1e-12 * s->alpha_y) {
            double a = sqrt(s->alpha_x * s->alpha_y);
            series *r = &sr[ns++];
            r->n = 0;
            snprintf(r->label, sizeof r->label, "isotropic E at √(αx αy) = %.3g", a);
            for (int i = 0; i <= 179; i++) {
                double th = fmin(0.5 * i, 89.9);
                r->x[r->n] = th, r->y[r->n++] = ggx_albedo_iso_table(a, cos(th * DEG), GGX_MASKING_SEPARABLE);
            }
        }
    }
    return ns;
}

int figure_curve(const figure_spec *f, int k, double *x, double *y, int max, char *label, size_t n)
{
    static series sr[8];
    const char *xlabel, *ylabel;
    int logy;
    if (f->kind < FIG_G1) return -1;
    if (f->kind == FIG_POLAR) return polar_curve(f, k, x, y, max, label, n);
    if (f->kind == FIG_SLICE) return -1;
    int ns = line_series(f, sr, &xlabel, &ylabel, &logy);
    if (k < 0 || k >= ns) return -1;
    int m = sr[k].n < max ? sr[k].n : max;
    for (int i = 0; i < m; i++) x[i] = sr[k].x[i], y[i] = sr[k].y[i];
    if (label && n) snprintf(label, n, "%s", sr[k].label);
    return m;
}

static void draw_lines(cairo_t *cr, const theme *th, double x, double y, double w, double h, const figure_spec *f)
{
    static series sr[8];
    plot_axes ax = {0};
    int ns = line_series(f, sr, &ax.xlabel, &ax.ylabel, &ax.logy);
    double F = figure_font(w, h);
    double cap = figure_draw_caption(cr, th, x, y, w, F, f, FIGURE_CAPTION_LINES);
    ax.slice = f->kind == FIG_NDF_SLICE;
    ax.range_x_max = f->kind == FIG_LAMBDA ? 85 : INFINITY; /* the scale of the curve; the asymptote leaves the box */
    ax.free_top = f->kind == FIG_LAMBDA;
    plot_draw(cr, th, x, y + cap, w, h - cap, F, sr, ns, &ax);
}

void plot_draw(cairo_t *cr, const theme *th, double x, double y, double w, double h, double F, const plot_series *sr,
               int ns, const plot_axes *ax)
{
    int logy = ax->logy;
    double legend_w = 0;
    text_font(cr, 0.8 * F, 0);
    for (int i = 0; i < ns; i++) legend_w = fmax(legend_w, text_width(cr, sr[i].label));
    legend_w += 3.6 * F;
    double px = x + 5.0 * F, py = y + 0.6 * F, pw = w - 5.0 * F - legend_w - 0.8 * F, ph = h - 4.2 * F;
    double xlo = 1e300, xhi = -1e300, ylo = 1e300, yhi = -1e300;
    for (int i = 0; i < ns; i++)
        for (int k = 0; k < sr[i].n; k++) {
            if (sr[i].x[k] > ax->range_x_max) continue;
            xlo = fmin(xlo, sr[i].x[k]), xhi = fmax(xhi, sr[i].x[k]);
            double v = logy ? log10(sr[i].y[k]) : sr[i].y[k];
            if (isfinite(v)) ylo = fmin(ylo, v), yhi = fmax(yhi, v);
        }
    if (ax->slice) xlo = -90, xhi = 90;
    else xlo = 0, xhi = 90;
    if (logy) ylo = floor(fmax(ylo, yhi - 6)), yhi = ceil(yhi);
    else ylo = fmin(0.0, ylo), yhi = ax->free_top ? yhi * 1.05 : fmax(1.0, yhi) * 1.05;
    if (!logy && ylo < 0)
        ylo -= 0.05 * (yhi - ylo); /* a negative curve (Lambda of a skewed shape) clear of the frame */
    if (!(yhi > ylo)) yhi = ylo + 1;
#define MAPX(v) (px + pw * ((v)-xlo) / (xhi - xlo))
#define MAPY(v) (py + ph * (1 - ((v)-ylo) / (yhi - ylo)))
    /* axes, grid lines and ticks */
    double ticks[64];
    cairo_set_line_width(cr, fmax(0.4, 0.05 * F));
    text_font(cr, 0.8 * F, 0);
    int nt = 7; /* every 15 degrees over [0, 90], every 30 over [-90, 90] */
    for (int i = 0; i < nt; i++) ticks[i] = ax->slice ? -90 + 30 * i : 15 * i;
    for (int i = 0; i < nt; i++) {
        double X = MAPX(ticks[i]);
        cairo_set_source_rgba(cr, th->faint[0], th->faint[1], th->faint[2], 0.35);
        cairo_move_to(cr, X, py), cairo_line_to(cr, X, py + ph), cairo_stroke(cr);
        set_rgb(cr, th->fg);
        char b[32];
        format_tick(ticks[i], b, sizeof b);
        text_at(cr, X, py + ph + 0.45 * F, 0.5, 0, b);
    }
    nt = logy ? 0 : nice_ticks(ylo, yhi, 6, ticks, 64);
    if (logy)
        for (double d = ylo; d <= yhi + 1e-9; d += 1) ticks[nt++] = d;
    for (int i = 0; i < nt; i++) {
        double Y = MAPY(ticks[i]);
        cairo_set_source_rgba(cr, th->faint[0], th->faint[1], th->faint[2], 0.35);
        cairo_move_to(cr, px, Y), cairo_line_to(cr, px + pw, Y), cairo_stroke(cr);
        set_rgb(cr, th->fg);
        char b[32];
        format_tick(logy ? pow(10, ticks[i]) : ticks[i], b, sizeof b);
        text_at(cr, px - 0.4 * F, Y, 1, 0.5, b);
    }
    set_rgb(cr, th->fg);
    cairo_set_line_width(cr, fmax(0.6, 0.07 * F));
    cairo_rectangle(cr, px, py, pw, ph);
    cairo_stroke(cr);
    text_font(cr, 0.85 * F, 0);
    text_at(cr, px + 0.5 * pw, py + ph + 2.0 * F, 0.5, 0, ax->xlabel);
    text_vertical(cr, x + 1.0 * F, py + 0.5 * ph, ax->ylabel);
    /* the curves, clipped to the box; a series of marks as open circles */
    cairo_save(cr);
    cairo_rectangle(cr, px, py, pw, ph);
    cairo_clip(cr);
    cairo_set_line_width(cr, fmax(1.0, 0.14 * F));
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (int i = 0; i < ns; i++) {
        double dashes[2] = {0.7 * F * (i % 3), 0.35 * F};
        set_rgb(cr, sr[i].marks ? th->fg : FIGURE_PALETTE[i % 6]);
        cairo_set_dash(cr, dashes, i % 3 && !sr[i].marks ? 2 : 0, 0);
        for (int k = 0; k < sr[i].n; k++) {
            double Y = MAPY(logy ? log10(sr[i].y[k]) : sr[i].y[k]);
            if (sr[i].marks) {
                cairo_new_sub_path(cr);
                cairo_arc(cr, MAPX(sr[i].x[k]), Y, 0.3 * F, 0, 2 * 3.14159265358979323846);
            } else if (k == 0) {
                cairo_move_to(cr, MAPX(sr[i].x[k]), Y);
            } else {
                cairo_line_to(cr, MAPX(sr[i].x[k]), Y);
            }
        }
        cairo_stroke(cr);
    }
    cairo_restore(cr);
    /* legend, at the right of the box */
    text_font(cr, 0.8 * F, 0);
    for (int i = 0; i < ns; i++) {
        double lx = px + pw + 0.8 * F, ly = py + 0.6 * F + 1.4 * F * i;
        double dashes[2] = {0.7 * F * (i % 3), 0.35 * F};
        set_rgb(cr, sr[i].marks ? th->fg : FIGURE_PALETTE[i % 6]);
        cairo_set_line_width(cr, fmax(1.0, 0.14 * F));
        if (sr[i].marks) {
            cairo_new_sub_path(cr);
            cairo_arc(cr, lx + 1.2 * F, ly, 0.3 * F, 0, 2 * 3.14159265358979323846);
            cairo_stroke(cr);
        } else {
            cairo_set_dash(cr, dashes, i % 3 ? 2 : 0, 0);
            cairo_move_to(cr, lx, ly), cairo_line_to(cr, lx + 2.4 * F, ly), cairo_stroke(cr);
            cairo_set_dash(cr, NULL, 0, 0);
        }
        set_rgb(cr, th->fg);
        text_at(cr, lx + 2.9 * F, ly, 0, 0.5, sr[i].label);
    }
#undef MAPX
#undef MAPY
}

/* ---------------------------------------------------------------------------------------------------------------
 * Entry points
 * --------------------------------------------------------------------------------------------------------------- */

void figure_draw(cairo_t *cr, const theme *th, double x, double y, double w, double h, const figure_spec *fin,
                 hemi_proj *proj)
{
    figure_spec f = *fin;
    if (figure_is_side(f.kind) && isnan(f.from)) f.from = figure_default_from(&f);
    cairo_save(cr);
    cairo_rectangle(cr, x, y, w, h);
    cairo_clip(cr);
    if (f.kind == FIG_POLAR) polar_draw(cr, th, x, y, w, h, &f);
    else if (f.kind == FIG_SLICE) slice_draw(cr, th, x, y, w, h, &f);
    else if (figure_is_line(f.kind)) draw_lines(cr, th, x, y, w, h, &f);
    else draw_hemisphere(cr, th, x, y, w, h, &f, proj);
    cairo_restore(cr);
}

double figure_aspect(figure_kind k)
{
    if (k == FIG_POLAR) return 0.7;
    if (k == FIG_SLICE) return 0.82;
    if (figure_is_line(k)) return 0.62;
    if (figure_is_side(k)) return figure_is_grid(k) ? 0.68 : 0.62;
    return figure_is_grid(k) ? 1.0 : 0.86;
}

int figure_height(figure_kind k, int width) { return (int)lround(width * figure_aspect(k)); }

void figure_shape_caption(char *buf, size_t n, double ax, double ay, double tx, double ty, double tz)
{
    snprintf(buf, n, "αx %.4g, αy %.4g  ·  θx %.4g°, θy %.4g°, θz %.4g°", ax, ay, tx, ty, tz);
}
