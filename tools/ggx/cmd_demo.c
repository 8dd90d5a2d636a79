/* ggx demo: the seeds' figures for the seeds' shape and a skewed one, the line plots, figures.pdf with all of them
 * in the seeds' order, then a check of every sampler of normals. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "chi2.h"
#include "cmd_render.h"

/* The samplers the demo checks on a shape: those of normals, where the shape is in their domain. */
static int checked(const ggx_sampler_info *smp, const ggx_shape *s)
{
    return smp->family != GGX_FAMILY_DIRECTION && sampler_applies(smp, s);
}

/* The seeds' figures, in the seeds' order: engstad-stretch's four, engstad-vndf-proof's eight; then the line plots. */
static const struct demo_figure {
    const char *file, *seed, *seed_figure;
    figure_kind kind;
    double phi_v; /* degrees; NAN: no view */
    int vndf_sampler;
} FIGS[] = {
    {"grid-top.svg", "engstad-stretch", "ggx-top: equal area GGX", FIG_GRID, NAN, 0},
    {"grid-side.svg", "engstad-stretch", "ggx-side: GGX equal area from the side", FIG_GRID_SIDE, NAN, 0},
    {"ndf-top.png", "engstad-stretch", "d-top: PDF from top", FIG_NDF, NAN, 0},
    {"ndf-side.png", "engstad-stretch", "d-side: PDF from side", FIG_NDF_SIDE, NAN, 0},
    {"vndf-75-0-grid-top.svg", "engstad-vndf-proof", "figure 1: equal area from top", FIG_GRID, 0, 1},
    {"vndf-75-0-grid-side.svg", "engstad-vndf-proof", "figure 2: equal area from side", FIG_GRID_SIDE, 0, 1},
    {"vndf-75-0-top.png", "engstad-vndf-proof", "figure 3: PDF from top", FIG_VNDF, 0, 0},
    {"vndf-75-0-side.png", "engstad-vndf-proof", "figure 4: PDF from side", FIG_VNDF_SIDE, 0, 0},
    {"vndf-75-90-grid-top.svg", "engstad-vndf-proof", "figure 5: equal area from top", FIG_GRID, 90, 1},
    {"vndf-75-90-grid-side.svg", "engstad-vndf-proof", "figure 6: equal area from side", FIG_GRID_SIDE, 90, 1},
    {"vndf-75-90-top.png", "engstad-vndf-proof", "figure 7: PDF from top", FIG_VNDF, 90, 0},
    {"vndf-75-90-side.png", "engstad-vndf-proof", "figure 8: PDF from side", FIG_VNDF_SIDE, 90, 0},
    {"g1.svg", NULL, "masking G1", FIG_G1, NAN, 0},
    {"lambda.svg", NULL, "Smith Lambda", FIG_LAMBDA, NAN, 0},
    {"ndf-slice.svg", NULL, "NDF slices", FIG_NDF_SLICE, NAN, 0},
    {"furnace.svg", NULL, "furnace and albedo", FIG_FURNACE, NAN, 0},
};
enum { NFIGS = sizeof FIGS / sizeof FIGS[0] };

static const struct demo_shape {
    const char *prefix;
    double tx, ty; /* degrees */
} SHAPES[2] = {{"", 0, 0}, {"skewed-", 15, -10}};

static figure_spec demo_spec(const struct demo_figure *d, const ggx_shape *s, int k, int dark)
{
    figure_spec f = {d->kind, s, {0, 0, 1}, ggx_sampler_get(GGX_SAMPLER_STRETCH), 0, dark, NAN, "", "", 0.0, 0.0};
    if (!isnan(d->phi_v)) /* theta_v = 75 degrees */
        f.view = (ggx_vec3){sin(75 * DEG) * cos(d->phi_v * DEG), sin(75 * DEG) * sin(d->phi_v * DEG), cos(75 * DEG)};
    if (d->vndf_sampler) f.sampler = ggx_sampler_get(GGX_SAMPLER_HEITZ);
    figure_shape_caption(f.shape_text, sizeof f.shape_text, 0.15, 0.5, SHAPES[k].tx, SHAPES[k].ty, 0);
    if (d->seed)
        snprintf(f.note, sizeof f.note, "%s: seed %s, %s", k ? "skewed version of" : "reproduces", d->seed,
                 d->seed_figure);
    return f;
}

/* The row of lit spheres: the seeds' shape, the same skewed, the same rotated; a conductor under the built-in sky. */
enum { NSPHERES = 3 };
static const struct demo_sphere {
    double tx, ty, tz; /* degrees */
    const char *label;
} SPHERES[NSPHERES] = {
    {0, 0, 0, "the seeds' shape"}, {15, -10, 0, "skewed θx 15°, θy −10°"}, {0, 0, 45, "rotated θz 45°"}};

static void render_spheres(int px, float *img[NSPHERES])
{
    render_env env;
    char err[300];
    if (render_env_default_sky(&env, err, sizeof err) != 0) die("demo sky: %s", err);
    for (int k = 0; k < NSPHERES; k++) {
        render_spec r;
        render_spec_defaults(&r);
        if (ggx_shape_ellipsoid(&r.shape, 0.15, 0.5, SPHERES[k].tx * DEG, SPHERES[k].ty * DEG, SPHERES[k].tz * DEG) !=
            GGX_OK)
            die("demo sphere shape");
        ggx_fresnel_conductor(&r.fresnel, 1.0, 6.7);
        r.env = &env, r.width = r.height = px, r.spp = 32;
        long cpus = sysconf(_SC_NPROCESSORS_ONLN);
        r.threads = cpus >= 1 && cpus <= 256 ? (int)cpus : 1;
        if (render_prepare(&r, err, sizeof err) != 0) die("demo sphere: %s", err);
        img[k] = malloc((size_t)px * (size_t)px * 3 * sizeof(float));
        if (!img[k]) die("demo sphere: out of memory");
        render_image(&r, img[k], NULL);
    }
    render_env_free(&env);
}

/* The spheres side by side in (x, y, w), each labelled below; returns the height used. */
static double draw_spheres(cairo_t *cr, const theme *th, double x, double y, double w, float *img[NSPHERES], int px)
{
    double gap = 0.02 * w, cell = (w - (NSPHERES - 1) * gap) / NSPHERES, sc = cell / px, font = fmax(8.0, cell / 22);
    set_rgb(cr, th->fg);
    text_font(cr, font, 0);
    for (int k = 0; k < NSPHERES; k++) {
        double cx = x + k * (cell + gap);
        paint_linear_rgb(cr, cx, y, sc, img[k], px, px, 0);
        text_at(cr, cx + 0.5 * cell, y + cell + 1.4 * font, 0.5, 0.5, SPHERES[k].label);
    }
    return cell + 2.4 * font;
}

static const char *const SPHERES_NOTE[2] = {
    "αx 0.15, αy 0.5, conductor η 1, k 6.7, built-in sky (sun at 35°, azimuth −120°), 32 spp; the shape's x along "
    "the parallels (east).",
    "The skew moves the highlight off the mirror direction of the sun; θz turns the streak."};

static void write_spheres(const char *path, float *img[NSPHERES], int px, int width)
{
    canvas c;
    double h = (width - 24) / (double)NSPHERES + 2.4 * fmax(8.0, (width - 24) / (double)NSPHERES / 22) + 20;
    canvas_open_file(&c, path, FMT_PNG, width, (int)ceil(h), 0);
    draw_spheres(c.cr, c.th, 12, 12, width - 24, img, px);
    canvas_close_file(&c);
}

/* figures.pdf: one page per figure, the seeds' shape at the left and the skewed one at the right; then the spheres. */
static void write_pdf(const char *path, ggx_shape sh[2], float *img[NSPHERES], int px)
{
    const double W = 842, H = 595; /* A4 landscape, points */
    canvas c;
    canvas_open_file(&c, path, FMT_PDF, (int)W, (int)H, 0);
    for (int i = 0; i < NFIGS; i++) {
        if (i) canvas_page(&c);
        const struct demo_figure *d = &FIGS[i];
        set_rgb(c.cr, c.th->fg);
        text_font(c.cr, 13, 1);
        char head[256];
        if (d->seed) snprintf(head, sizeof head, "Seed %s, %s", d->seed, d->seed_figure);
        else snprintf(head, sizeof head, "Beyond the seeds: %s", d->seed_figure);
        text_at(c.cr, 28, 26, 0, 0, head);
        text_font(c.cr, 10, 0);
        text_at(c.cr, 28, 46, 0, 0,
                "left: the seeds' shape αx 0.15, αy 0.5 (θv 75° where there is a view); "
                "right: the same shape skewed by θx 15°, θy −10°, which the seeds do not show");
        double pw = 0.5 * (W - 56), ph = fmin(H - 90, pw * figure_aspect(d->kind) * 1.1);
        for (int k = 0; k < 2; k++) {
            figure_spec f = demo_spec(d, &sh[k], k, 0);
            figure_draw(c.cr, c.th, 28 + k * pw, 66 + 0.5 * (H - 90 - ph), pw, ph, &f, NULL);
        }
    }
    canvas_page(&c);
    set_rgb(c.cr, c.th->fg);
    text_font(c.cr, 13, 1);
    text_at(c.cr, 28, 26, 0, 0, "Beyond the seeds: the material, lit (ggx render)");
    text_font(c.cr, 10, 0);
    for (int i = 0; i < 2; i++) text_at(c.cr, 28, 46 + 14 * i, 0, 0, SPHERES_NOTE[i]);
    draw_spheres(c.cr, c.th, 28, 90, W - 56, img, px);
    canvas_close_file(&c);
}

void demo_help(void)
{
    printf("usage: ggx demo [--out DIR] [-n N] [--size W] [--theme light|dark]\n\n"
           "Draws the seeds' figures for alpha = (0.15, 0.5) and for the same shape skewed by theta_x = 15,\n"
           "theta_y = -10 degrees into DIR (default out/), the skewed ones prefixed skewed-:\n"
           "  engstad-stretch: grid-top.svg, grid-side.svg (the 10 x 10 equal-area grid mapped by\n"
           "    NDF sampling), ndf-top.png, ndf-side.png (the NDF pdf);\n"
           "  engstad-vndf-proof (visible normals, theta_v = 75, phi_v = P for P = 0 and 90): "
           "vndf-75-P-grid-top.svg,\n"
           "    vndf-75-P-grid-side.svg (the grid mapped by the five-step VNDF sampler), vndf-75-P-top.png,\n"
           "    vndf-75-P-side.png (the VNDF pdf), each with the grey region of normals that reflect the view\n"
           "    above the horizon;\n"
           "  line plots: g1.svg, lambda.svg, ndf-slice.svg, furnace.svg;\n"
           "  spheres.png: spheres of the material under the built-in sky (ggx render): the seeds' shape, the same\n"
           "    skewed, the same rotated by theta_z = 45;\n"
           "  figures.pdf: every figure, one page each in the seeds' order, the seed's shape beside the skewed one;\n"
           "    the spheres on the last page.\n"
           "Then checks every sampler for these shapes (N samples each, default 10^6) and prints the table.\n"
           "--size: the figures' width (default 640; heights follow each figure's aspect). The figures are\n"
           "written all or none.\n");
}

int cmd_demo(options *o, const ggx_shape *no_shape)
{
    (void)no_shape;
    if (o->n > 0) require_check_n(o->n); /* before any figure is drawn */
    if (o->size_h) die("--size: the demo takes a width only (each figure keeps its own aspect)");
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    const char *dir = o->out ? o->out : "out";
    ensure_dir(dir);
    int size = o->size ? o->size : 640;
    ggx_vec3 v0;
    parse_direction("75,0", &v0);
    char *path;
    ggx_shape sh[2];
    for (int k = 0; k < 2; k++)
        if (ggx_shape_ellipsoid(&sh[k], 0.15, 0.5, SHAPES[k].tx * DEG, SHAPES[k].ty * DEG, 0) != GGX_OK)
            die("demo shape");
    printf("ggx demo: figures in %s/\n", dir);
    out_begin_set(); /* all figures or none */
    for (int k = 0; k < 2; k++) {
        for (int i = 0; i < NFIGS; i++) {
            path = alloc_printf("%s/%s%s", dir, SHAPES[k].prefix, FIGS[i].file);
            figure_spec f = demo_spec(&FIGS[i], &sh[k], k, o->dark);
            figure_write(&f, path, format_of_name(path, FMT_PNG), size, figure_height(f.kind, size));
            printf("  %s\n", path);
            free(path);
            out_flush_stdout();
        }
    }
    int px = size * 2 / 5;
    float *img[NSPHERES];
    render_spheres(px, img);
    path = alloc_printf("%s/spheres.png", dir);
    write_spheres(path, img, px, size);
    printf("  %s\n", path);
    free(path);
    path = alloc_printf("%s/figures.pdf", dir);
    write_pdf(path, sh, img, px);
    for (int k = 0; k < NSPHERES; k++) free(img[k]);
    printf("  %s (%d pages)\n", path, NFIGS + 1);
    free(path);
    out_commit_set();
    out_keep_dirs(); /* the figures are complete: a folder made for them stays */
    clock_gettime(CLOCK_MONOTONIC, &t1);
    printf("figures drawn in %.1f s\n", (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
    long n = o->n > 0 ? o->n : 1000000;
    /* every sampler of normals of the library, on each shape in its domain */
    int runs = 0;
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < GGX_SAMPLER_COUNT; i++) runs += checked(ggx_sampler_get((ggx_sampler_id)i), &sh[k]);
    double alpha = chi2_sidak(runs);
    printf("\nchecks (%ld samples each; VNDF for theta_v = 75, phi_v = 0; level %.2g per run):\n", n, alpha);
    int all = 1;
    for (int k = 0; k < 2; k++) {
        printf("%s\n", k ? "skewed 15,-10" : "alpha 0.15,0.5");
        print_check_header(stdout);
        for (int i = 0; i < GGX_SAMPLER_COUNT; i++) {
            const ggx_sampler_info *smp = ggx_sampler_get((ggx_sampler_id)i);
            if (!checked(smp, &sh[k])) continue;
            check_result r = run_check(&sh[k], v0, smp, n, 100 + (unsigned long long)i, alpha, 0);
            print_check_row(stdout, smp->name, r);
            out_flush_stdout();
            all &= r.pass;
        }
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    printf("\n%s in %.1f s. Figures: %s/\n", all ? "all checks pass" : "SOME CHECKS FAILED",
           (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec), dir);
    return all ? 0 : 1;
}
