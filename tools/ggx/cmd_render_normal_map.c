/* ggx render --normal-map: a plane textured with a normal map's filtered chain at one level beside the full-resolution
 * map supersampled (the ground truth), for our filter and the engines' (libs/verify/mip_compare.h), with the
 * difference images and the RMSE of every level. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cmd_render.h"
#include "mip_compare.h"
#include "surface.h"

static void paint_grey(cairo_t *cr, double x, double y, double scale, const float *img, size_t w, size_t h, double k,
                       int clip_w, int clip_h)
{
    float *rgb = malloc(w * h * 3 * sizeof *rgb);
    if (!rgb) die("out of memory");
    for (size_t i = 0; i < w * h; i++) rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = (float)(img[i] / (img[i] + k));
    cairo_save(cr);
    cairo_rectangle(cr, x, y, clip_w, clip_h);
    cairo_clip(cr);
    paint_linear_rgb(cr, x, y, scale, rgb, (int)w, (int)h, 0.0);
    cairo_restore(cr);
    free(rgb);
}

static void paint_diff(cairo_t *cr, double x, double y, double scale, const float *img, const float *truth, size_t w,
                       size_t h, double vmax, int clip_w, int clip_h)
{
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, (int)w, (int)h);
    unsigned char *d = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    cairo_surface_flush(s);
    for (size_t j = 0; j < h; j++)
        for (size_t i = 0; i < w; i++) {
            double c[3];
            colormap(fabs((double)img[j * w + i] - (double)truth[j * w + i]) / vmax, c);
            uint32_t px = (uint32_t)lround(255 * c[0]) << 16 | (uint32_t)lround(255 * c[1]) << 8 |
                          (uint32_t)lround(255 * c[2]);
            memcpy(d + j * (size_t)stride + 4 * i, &px, 4);
        }
    cairo_save(cr);
    cairo_rectangle(cr, x, y, clip_w, clip_h);
    cairo_clip(cr);
    paint_image(cr, s, x, y, scale);
    cairo_restore(cr);
}

static void render_normal_map_help(void)
{
    printf("usage: ggx render --normal-map FILE (--alpha A | --roughness-map FILE [--perceptual]) [--y-down]\n"
           "                  [--level K] [--light point:THETA,PHI[,E]] [--view THETA,PHI] [--threads N] [--out "
           "FIG.png]\n\n"
           "A plane textured with the normal map's mip chain (ggx mipmap's, exact and fast) at level K, lit by a\n"
           "distant light (--light as ggx render takes it; default 45, 180 degrees) and seen from a distant eye "
           "(default 45, 0: the mirror\n"
           "direction), beside the ground truth: the full-resolution map supersampled, each level-K texel the\n"
           "mean radiance f(wi, wo) wi.z (F = 1) of its base texels, each the skewed ellipsoid of its normal and\n"
           "roughness. Beside ours, the engines' filters, each a shading normal (the renormalised mean normal)\n"
           "with an unskewed lobe: no filtering, Toksvig, variance widening (Tokuyoshi-Kaplanyan, clamped at\n"
           "0.18) and ours without skew. Row 1: the truth and each method; row 2: the map at full resolution and\n"
           "each method's |difference| from the truth at this light and eye. Prints for every level and method\n"
           "the relative RMS error sqrt(sum (value - truth)^2 / sum truth^2) over the level's texels and the 37\n"
           "standard light-eye pairs (lights at 25, 50, 75 degrees in four azimuths, eyes at 0, 45, 70, and the\n"
           "mirror pair at 45), or the given pair alone when --light or --view is given; against the truth, and\n"
           "against the engines' own truth (each base texel GGX about its normal as a shading normal). Default\n"
           "level: 3 (8 x 8 base texels per texel), or the last.\n");
}

static const command_spec RENDER_NORMAL_MAP_SPEC = {
    "normal-map,alpha,roughness-map,perceptual,y-down,level,light,view,threads,out", render_normal_map_help, 0};

int render_normal_map(int argc, char **argv)
{
    options o;
    if (!command_options(&RENDER_NORMAL_MAP_SPEC, argc, argv, 2, &o)) return 0;
    if (!o.normal_map) die("--normal-map FILE is required");
    if (o.have_alpha == !!o.roughness_map) die("give the base roughness as one of --alpha A or --roughness-map FILE");
    if (o.have_alpha && o.alpha[0] != o.alpha[1]) die("--alpha: the comparison takes an isotropic A");
    if (o.perceptual && !o.roughness_map) die("--perceptual applies to --roughness-map");
    mc_view given = {direction_deg(45, 180), direction_deg(45, 0)}; /* mc_standard_views' first */
    if (o.light) {
        double v[3];
        parse_light_point(o.light, &given.wi, v); /* E scales the truth and the levels alike: no error changes */
        if (!(given.wi.z > 1e-9))
            die("--light '%s': the light must be above the plane (theta below 90 degrees)", o.light);
    }
    if (o.have_view) {
        if (!(o.view.z > 1e-9)) die("--view: the eye must be above the plane (theta below 90 degrees)");
        given.wo = o.view;
    }
    mc_view views[MC_VIEWS];
    mc_standard_views(views);
    views[0] = given;
    int nviews = o.light || o.have_view ? 1 : MC_VIEWS;
    const char *path = o.out ? o.out : "normal-map.png";
    int to_stdout = strcmp(path, "-") == 0;
    if (!to_stdout && !path_is_stream(path) && !path_has_ext(path, ".png"))
        die("--out '%s': give a .png name (or - for standard output)", path);
    surface_read_options ro = {SURFACE_NORMALS, o.y_down};
    surface s;
    char err[512];
    if (surface_read(o.normal_map, &ro, &s, err, sizeof err) != 0) die("%s", err);
    if (s.ny < 1 || s.nx < 1 || (s.ny == 1 && s.format == SURFACE_CSV)) die("%s: not a normal map", o.normal_map);
    if (s.nx > 4096 || s.ny > 4096)
        die("%s: %zu x %zu texels; the comparison takes up to 4096 x 4096", o.normal_map, s.nx, s.ny);
    size_t w = s.nx, h = s.ny;
    double *alpha = NULL;
    if (o.roughness_map) {
        alpha = roughness_map_read(&o, w, h);
    } else if (!(o.alpha[0] > 0.0 && o.alpha[0] <= GGX_ALPHA_MAX)) {
        die("--alpha: %g is not a roughness in (0, %g]", o.alpha[0], GGX_ALPHA_MAX);
    }
    int nl = mc_level_count(w, h), K = o.level >= 0 ? o.level : (nl - 1 < 3 ? nl - 1 : 3);
    if (K >= nl) die("--level %d: the chain of a %zu x %zu map has levels 0 to %d", K, w, h, nl - 1);
    size_t wk = w, hk = h;
    for (int k = 0; k < K; k++) wk = (wk + 1) / 2, hk = (hk + 1) / 2;
    mc_level *levels = malloc((size_t)nl * sizeof *levels);
    float *img = malloc((size_t)(1 + MC_METHODS) * wk * hk * sizeof *img);
    float *full = malloc(w * h * sizeof *full);
    if (!levels || !img || !full) die("out of memory");
    int threads = o.threads > 0 ? o.threads : 1;
    if (mc_compare(w, h, s.m, alpha, o.alpha[0], views, nviews, threads, levels, K, img, full, err, sizeof err) != 0)
        die("%s", err);
    char rough[600];
    if (o.roughness_map)
        snprintf(rough, sizeof rough, "roughness %s%s", o.roughness_map, o.perceptual ? " (perceptual)" : "");
    else snprintf(rough, sizeof rough, "alpha %g", o.alpha[0]);
    FILE *tab = to_stdout ? stderr : stdout; /* the figure on standard output: the table beside it */
    fprintf(tab, "ggx render --normal-map: %s, %zu x %zu texels, %s; relative RMSE against the truth, %s\n\n",
            o.normal_map, w, h, rough,
            nviews == 1 ? "at the given light and eye" : "pooled over the 37 standard light-eye pairs");
    for (int table = 0; table < 2; table++) {
        if (table)
            fprintf(tab,
                    "\nagainst the engines' own truth (each base texel GGX about its normal as a shading normal):\n\n");
        fprintf(tab, "| level | size |");
        for (int k = 0; k < MC_METHODS; k++) fprintf(tab, " %s |", mc_name[k]);
        fprintf(tab, "\n|---|---|");
        for (int k = 0; k < MC_METHODS; k++) fprintf(tab, "---|");
        fprintf(tab, "\n");
        for (int l = 0; l < nl; l++) {
            fprintf(tab, "| %d | %zu x %zu |", l, levels[l].w, levels[l].h);
            for (int k = 0; k < MC_METHODS; k++)
                fprintf(tab, " %.4f |", table ? levels[l].rmse_engine[k] : levels[l].rmse[k]);
            fprintf(tab, "\n");
        }
    }
    /* the figure: panels of the map's size at a scale of at least 160 pixels */
    int s0 = (int)ceil(160.0 / (double)(w > h ? w : h));
    if (s0 < 1) s0 = 1;
    int pw = (int)w * s0, ph = (int)h * s0, gap = 8, top = 34, label = 30, cols = 1 + MC_METHODS, bar = 70;
    int W = gap + cols * (pw + gap) + bar, H = top + 2 * (ph + label) + gap + 16;
    double peak = 0.0, dmax = 0.0, mean = 0.0;
    for (size_t i = 0; i < wk * hk; i++) peak = fmax(peak, img[i]), mean += img[i] / (double)(wk * hk);
    for (int k = 1; k <= MC_METHODS; k++)
        for (size_t i = 0; i < wk * hk; i++) dmax = fmax(dmax, fabs((double)img[(size_t)k * wk * hk + i] - img[i]));
    if (!(peak > 0.0)) peak = mean = 1.0;
    if (!(dmax > 0.0)) dmax = peak;
    canvas c;
    canvas_open_file(&c, path, FMT_PNG, W, H, 0);
    canvas_clear(&c);
    cairo_t *cr = c.cr;
    set_rgb(cr, c.th->fg);
    text_font(cr, 12, 1);
    char line[1200];
    snprintf(line, sizeof line, "%s, %zu x %zu, %s: level %d (%zu x %zu), light θ %.0f°, eye θ %.0f°, F = 1",
             o.normal_map, w, h, rough, K, wk, hk, acos(given.wi.z) / DEG, acos(given.wo.z) / DEG);
    text_at(cr, gap, 14, 0, 0.5, line);
    text_font(cr, 10, 0);
    double lv_scale = (double)s0 * ldexp(1.0, K);
    for (int col = 0; col < cols; col++) {
        double x = gap + col * (pw + gap), y1 = top, y2 = top + ph + label;
        const float *p = img + (size_t)col * wk * hk;
        paint_grey(cr, x, y1, lv_scale, p, wk, hk, mean, pw, ph);
        set_rgb(cr, c.th->fg);
        text_at(cr, x, y1 + ph + 12, 0, 0.5, col == 0 ? "truth (supersampled)" : mc_name[col - 1]);
        if (col == 0) {
            paint_grey(cr, x, y2, s0, full, w, h, mean, pw, ph);
            set_rgb(cr, c.th->fg);
            text_at(cr, x, y2 + ph + 12, 0, 0.5, "the map at level 0");
        } else {
            paint_diff(cr, x, y2, lv_scale, p, img, wk, hk, dmax, pw, ph);
            set_rgb(cr, c.th->fg);
            snprintf(line, sizeof line, "|difference|, RMSE %.1f %%", 100.0 * levels[K].rmse_first[col - 1]);
            text_at(cr, x, y2 + ph + 12, 0, 0.5, line);
        }
    }
    colour_bar(cr, c.th, gap + cols * (pw + gap), top + ph + label, 10, ph, dmax / peak, 0, 0, "of the truth's peak",
               9);
    canvas_close_file(&c);
    free(levels), free(img), free(full), free(alpha);
    surface_free(&s);
    return 0;
}
