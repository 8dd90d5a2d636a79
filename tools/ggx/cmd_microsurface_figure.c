/* ggx microsurface figure: a microsurface's traced G1 over the views of a plane, beside the model's masking forms
 * (docs/design/microsurface.md). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure_out.h"
#include "cmd_microsurface.h"

static const double PI = 3.14159265358979323846;

/* the view at signed angle a (degrees) in the plane of azimuth phi: a < 0 from the opposite azimuth */
static ggx_vec3 plane_view(double a, double phi)
{
    double th = fabs(a) * PI / 180.0, p = (a < 0 ? phi + 180.0 : phi) * PI / 180.0;
    return (ggx_vec3){sin(th) * cos(p), sin(th) * sin(p), cos(th)};
}

static void microsurface_figure_help(void)
{
    printf("usage: ggx microsurface figure --heightfield FILE [--spacing D] [--z-scale Z] [--downsample K]\n"
           "                               [--tilted | --risers P]\n"
           "                               [--alpha A[,AY] [--skew TX,TY] [--rotate TZ] | --matrix M] [--from PHI]\n"
           "                               [-n RAYS] [--threads N] [--size WxH] [--theme light|dark] --out "
           "FILE.png|svg|pdf\n\n"
           "G1(v) of a height field's facets, traced with RAYS rays (default 100,000) from each view every 5\n"
           "degrees of the plane of azimuth PHI (default: the skew's direction t, else 0), from 85 degrees on\n"
           "the side of PHI + 180 (drawn left) to 85 degrees on the side of PHI (right), as marks, beside the\n"
           "model's forms for the shape fitted to the facets (or given) as curves: for a skewed shape eq 6\n"
           "(ggx_g1), eq 32 without its min (ggx_g1_smith), vertical facets (Walter's remedy with Smith's\n"
           "masking), the tilted base (ggx_g1_tilted) and the sawtooth's (ggx_g1_risers); for an unskewed one\n"
           "Smith's GGX and Smith's Beckmann of the facets' covariance. --tilted and --risers P as for\n"
           "ggx microsurface measure; views below a tilted patch's plane have no mark. A measured scan (not\n"
           "square, missing points, edges that do not wrap) is traced as a patch, as by measure (--downsample K\n"
           "as there); its views too grazing for its heights' band have no mark.\n");
}

static const command_spec MICROSURFACE_FIGURE_SPEC = {"heightfield,spacing,z-scale,downsample,tilted,risers," SHAPE_OPTS
                                                      ",from,n,threads,size,theme,out",
                                                      microsurface_figure_help, 0};

int microsurface_figure(int argc, char **argv)
{
    options o;
    if (!command_options(&MICROSURFACE_FIGURE_SPEC, argc, argv, 3, &o)) return 0;
    if (!o.heightfield) die("--heightfield FILE is required");
    if (!o.out) die("--out FILE.png|svg|pdf is required");
    canvas_format fmt = figure_format_of("--out", o.out, FMT_PNG);
    size_t n, risers[2];
    double tilt[2], *h;
    microsurface_patch pt;
    ms_tracer *t = microsurface_open(&o, &h, &n, tilt, risers, &pt);
    char err[400];
    long rays = o.n > 0 ? o.n : 100000;
    int threads = o.threads > 0 ? o.threads : 1;
    /* the model's shape: fitted to the facets off the risers, or given */
    ggx_shape fit;
    int given;
    if (microsurface_model(&o, h, &pt, n, risers, &fit, &given) != GGX_OK)
        die("%s: no shape fits its facets", o.heightfield);
    double ts[2], ss[3];
    ggx_shape_slopes(&fit, ts, ss);
    /* (a periodic tile has no mean slope: a fit's small t there is the sampling's) */
    int skewed = o.tilted || o.risers || (given && hypot(ts[0], ts[1]) > 1e-9);
    double phi = isfinite(o.from) ? o.from : skewed ? atan2(ts[1], ts[0]) * 180.0 / PI : 0.0;
    enum { CURVES = 5 };
    static plot_series sr[CURVES + 1];
    int nc = skewed ? CURVES : 2;
    /* the traced marks, after the curves; the facets' slope covariance (the same at every view) for Beckmann's */
    plot_series *m = &sr[nc];
    m->n = 0, m->marks = 1;
    snprintf(m->label, sizeof m->label, "traced (%ld rays a view)", rays);
    double cov[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i <= 34; i++) {
        double a = -85.0 + 5.0 * i;
        ggx_vec3 v = plane_view(a, phi);
        double vv[3] = {v.x, v.y, v.z};
        if (!ms_view_clear(o.tilted ? tilt : NULL, vv)) continue; /* below (or along) the tilted plane */
        double w[4];
        if (pt.on && ms_patch_window(t, vv, 0, w, err, sizeof err) != 0) continue; /* too grazing for the patch */
        ms_g1 r;
        if (ms_measure_g1(t, h, n, vv, rays, 1, 1, risers, threads, &r, err, sizeof err) != 0) die("%s", err);
        m->x[m->n] = a, m->y[m->n++] = r.g1_off_risers;
        memcpy(cov, r.slope_cov, sizeof cov);
        ms_g1_free(&r);
    }
    /* the curves, every half degree */
    const char *names[CURVES] = {"eq 6 (ggx_g1)", "eq 32 without min", "vertical facets", "tilted base (ggx_g1_tilted)",
                                 "sawtooth (ggx_g1_risers)"};
    for (int c = 0; c < nc; c++) {
        plot_series *s = &sr[c];
        s->n = 0, s->marks = 0;
        snprintf(s->label, sizeof s->label, "%s", skewed ? names[c] : c == 0 ? "Smith, GGX" : "Smith, Beckmann");
        for (int i = 0; i <= 340; i++) {
            double a = -85.0 + 0.5 * i;
            ggx_vec3 v = plane_view(a, phi);
            double vv[3] = {v.x, v.y, v.z}, g;
            if (!skewed) g = c == 0 ? ggx_g1_smith(&fit, v) : ms_beckmann_g1(cov, vv);
            else if (c == 0) g = ggx_g1(&fit, v, v);
            else if (c == 1) g = ggx_g1_smith(&fit, v);
            else if (c == 2) g = ms_g1_vertical_facets(&fit, vv);
            else if (c == 3) g = ggx_g1_tilted(&fit, v, v);
            else g = ggx_g1_risers(&fit, v, v);
            s->x[s->n] = a, s->y[s->n++] = g;
        }
    }
    ms_tracer_free(t);
    free(h);
    /* the figure */
    int W = o.size ? o.size : 900, H = o.size_h ? o.size_h : (int)lround(W * 0.6);
    canvas c;
    canvas_open_file(&c, o.out, fmt, W, H, o.dark);
    cairo_t *cr = c.cr;
    double F = figure_font(W, H);
    char l1[200], l2[400], l3[300];
    double back = phi + 180.0 > 180.0 ? phi - 180.0 : phi + 180.0;
    snprintf(l1, sizeof l1, "Masking traced on a microsurface against the model's forms");
    /* the surface and the views on one line, the shape on the next: a scan's path is long */
    snprintf(l2, sizeof l2, "%s, %zu × %zu%s; views at azimuth %.4g° (right) and %.4g° (left)", o.heightfield,
             pt.on ? pt.nx : n, pt.on ? pt.ny : n,
             o.tilted   ? ", a tilted patch"
             : o.risers ? ", a sawtooth"
             : pt.on    ? ", a measured patch"
                        : "",
             phi + 0.0, back + 0.0);
    snprintf(l3, sizeof l3, "the %s GGX shape's slopes: t = (%.3g, %.3g), Σ = (%.3g, %.3g, %.3g)",
             given ? "given" : "fitted", ts[0] + 0.0, ts[1] + 0.0, ss[0], ss[1], ss[2]);
    set_rgb(cr, c.th->fg);
    text_font(cr, 1.0 * F, 1);
    text_at(cr, 0.4 * F, 0.5 * F, 0, 0, l1);
    text_font(cr, 0.75 * F, 0);
    text_at(cr, 0.4 * F, 2.0 * F, 0, 0, l2);
    text_at(cr, 0.4 * F, 3.1 * F, 0, 0, l3);
    plot_axes ax = {"view polar angle in the plane (degrees; left: the opposite azimuth)",
                    o.risers ? "G1(v) of the facets off the risers" : "G1(v)",
                    0,
                    1,
                    0,
                    INFINITY};
    plot_draw(cr, c.th, 0, 4.2 * F, W, H - 4.2 * F, F, sr, nc + 1, &ax);
    canvas_close_file(&c);
    if (strcmp(o.out, "-") != 0) fprintf(stderr, "ggx: wrote %s (%d x %d)\n", o.out, W, H);
    return 0;
}
