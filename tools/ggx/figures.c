/* The seeds' figures: density images (PNG, with a colour bar) and equal-area grids mapped onto the hemisphere
 * (SVG), top and side views. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

figure_kind figure_from_name(const char *name)
{
    static const struct {
        const char *name;
        figure_kind k;
    } names[] = {{"ndf", FIG_NDF},   {"ndf-side", FIG_NDF_SIDE},   {"vndf", FIG_VNDF},
                 {"vndf-side", FIG_VNDF_SIDE}, {"grid", FIG_GRID}, {"grid-side", FIG_GRID_SIDE}};
    for (unsigned i = 0; i < sizeof names / sizeof names[0]; i++)
        if (name && strcmp(name, names[i].name) == 0) return names[i].k;
    die("--figure: unknown figure '%s' (ndf, ndf-side, vndf, vndf-side, grid, grid-side)", name ? name : "");
}

/* The density shown at a point of the view: the hemisphere seen from above (x, y) or from the side (x, z), the
 * visible half facing -y. */
static double density_at(figure_kind k, const ggx_shape *s, ggx_vec3 view, double a, double b, int *inside)
{
    ggx_vec3 m;
    double r2 = a * a + b * b;
    *inside = r2 <= 1.0;
    if (!*inside) return 0.0;
    if (k == FIG_NDF || k == FIG_VNDF) {
        m.x = a, m.y = b, m.z = sqrt(1.0 - r2);
    } else {
        *inside = b >= 0.0;
        m.x = a, m.y = -sqrt(1.0 - r2), m.z = b;
    }
    return (k == FIG_NDF || k == FIG_NDF_SIDE) ? ggx_pdf_ndf(s, m) : ggx_pdf_vndf(s, view, m);
}

static void density_png(figure_kind k, const ggx_shape *s, ggx_vec3 view, int size, int log_scale, const char *title,
                        const char *path)
{
    const int top = 36, bar_w = 24, right = 150;
    int W = size + right, H = size + top + 12;
    double *val = malloc(sizeof(double) * (size_t)size * (size_t)size);
    if (!val) die("out of memory");
    double vmax = 0.0, R = 0.5 * size - 2;
    int side = k == FIG_NDF_SIDE || k == FIG_VNDF_SIDE;
    for (int py = 0; py < size; py++) {
        for (int px = 0; px < size; px++) {
            /* 2 x 2 supersampling of the pixel */
            double sum = 0.0;
            int in = 0;
            for (int q = 0; q < 4; q++) {
                double a = (px + 0.25 + 0.5 * (q & 1) - 0.5 * size) / R;
                double b = side ? (size - 2 - py - 0.25 - 0.5 * (q >> 1)) / R : (0.5 * size - py - 0.25 - 0.5 * (q >> 1)) / R;
                int inside;
                sum += density_at(k, s, view, a, b, &inside);
                in += inside;
            }
            val[(long)py * size + px] = in ? sum / 4 : -1.0;
            if (in && sum / 4 > vmax) vmax = sum / 4;
        }
    }
    image im = image_new(W, H, 24, 24, 28);
    const unsigned char white[3] = {235, 235, 235}, grey[3] = {70, 70, 76};
    double lo = log_scale ? vmax * 1e-4 : 0.0;
    for (int py = 0; py < size; py++) {
        for (int px = 0; px < size; px++) {
            double v = val[(long)py * size + px];
            unsigned char c[3];
            if (v < 0) {
                memcpy(c, grey, 3);
                if (side) continue;
            } else {
                double t = vmax > 0 ? (log_scale ? (v > lo ? log(v / lo) / log(vmax / lo) : 0.0) : v / vmax) : 0.0;
                colormap(t, c);
            }
            image_set(&im, px, py + top, c);
        }
    }
    /* colour bar with five labelled ticks */
    int bx = size + 16, by = top, bh = size;
    for (int y = 0; y < bh; y++) {
        unsigned char c[3];
        colormap(1.0 - (double)y / (bh - 1), c);
        for (int x = 0; x < bar_w; x++) image_set(&im, bx + x, by + y, c);
    }
    for (int t = 0; t <= 4; t++) {
        double f = t / 4.0, v = log_scale ? lo * pow(vmax / lo, f) : vmax * f;
        int y = by + (int)((1.0 - f) * (bh - 1));
        char lab[32];
        snprintf(lab, sizeof lab, "%.3g", v);
        for (int x = 0; x < 6; x++) image_set(&im, bx + bar_w + x, y, white);
        image_text(&im, bx + bar_w + 10, y - 7 < top ? top : (y - 7 > top + bh - 14 ? top + bh - 14 : y - 7), lab, 2, white);
    }
    image_text(&im, 8, 8, title, 2, white);
    image_text(&im, bx - 4, top + bh + 2, log_scale ? "LOG PDF" : "PDF", 1, white);
    write_png(&im, path);
    image_free(&im);
    free(val);
}

static void grid_svg(figure_kind k, const ggx_shape *s, ggx_vec3 view, const ggx_sampler_info *smp, int size,
                     const char *title, const char *path)
{
    if (!smp->sample) die("sampler '%s' is not a map of the unit square; grids need one", smp->name);
    int side = k == FIG_GRID_SIDE;
    double R = 0.5 * size - 10, cx = 0.5 * size, cy = side ? size - 20.0 : 0.5 * size + 20;
    int H = side ? size / 2 + 40 : size + 40;
    if (side) cy = H - 10.0;
    out_file o;
    out_open(&o, path);
    FILE *f = o.f;
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\">\n", size, H, size, H);
    fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"#18181c\"/>\n");
    fprintf(f, "<text x=\"8\" y=\"18\" font-family=\"sans-serif\" font-size=\"14\" fill=\"#ebebeb\">%s</text>\n", title);
    if (side)
        fprintf(f, "<path d=\"M %.2f %.2f A %.2f %.2f 0 0 1 %.2f %.2f Z\" fill=\"#2a2a30\" stroke=\"#888\"/>\n", cx - R, cy, R, R, cx + R, cy);
    else
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"#2a2a30\" stroke=\"#888\"/>\n", cx, cy, R);
    const int cells = 10, steps = 24;
    /* Checkerboard of the 10 x 10 equal-area cells, each cell's boundary traced through the map. */
    for (int i = 0; i < cells; i++) {
        for (int j = 0; j < cells; j++) {
            fprintf(f, "<polygon fill=\"%s\" fill-opacity=\"0.55\" stroke=\"#ebebeb\" stroke-width=\"0.6\" points=\"",
                    (i + j) % 2 ? "#e0783a" : "#5a2d8c");
            for (int e = 0; e < 4; e++) {
                for (int t = 0; t < steps; t++) {
                    double f0 = (double)t / steps, u1, u2;
                    if (e == 0) u1 = (i + f0) / cells, u2 = (double)j / cells;
                    else if (e == 1) u1 = (i + 1.0) / cells, u2 = (j + f0) / cells;
                    else if (e == 2) u1 = (i + 1.0 - f0) / cells, u2 = (j + 1.0) / cells;
                    else u1 = (double)i / cells, u2 = (j + 1.0 - f0) / cells;
                    if (u1 > 1.0 - 1e-9) u1 = 1.0 - 1e-9;
                    if (u2 > 1.0 - 1e-9) u2 = 1.0 - 1e-9;
                    ggx_vec3 m = smp->sample(s, view, u1, u2);
                    double X = cx + R * m.x, Y = side ? cy - R * m.z : cy - R * m.y;
                    fprintf(f, "%.2f,%.2f ", X, Y);
                }
            }
            fprintf(f, "\"/>\n");
        }
    }
    fprintf(f, "</svg>\n");
    out_close(&o);
}

void draw_figure(figure_kind k, const ggx_shape *s, ggx_vec3 view, const ggx_sampler_info *sampler, int size,
                 int log_scale, const char *title, const char *path)
{
    if (k == FIG_GRID || k == FIG_GRID_SIDE) grid_svg(k, s, view, sampler, size, title, path);
    else density_png(k, s, view, size, log_scale, title, path);
}
