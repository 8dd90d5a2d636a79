/* ggx microsurface: height fields with a chosen NDF (libs/microsurface), written as OpenEXR or x3p for ggx fit and the
 * tracer. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chi2.h"
#include "cli.h"
#include "ggx/ggx_fit.h"
#include "ggx/ggx_samplers.h"
#include "microsurface.h"
#include "cmd_microsurface.h"
#include "surface.h"

static void write_heights(const char *path, double *h, size_t n)
{
    surface s;
    memset(&s, 0, sizeof s);
    s.kind = SURFACE_HEIGHTS, s.nx = n, s.ny = n, s.h = h;
    int x3p = path_has_ext(path, ".x3p");
    /* x3p in metres: a grid of 1 micrometre, heights in the same unit, so slopes are the field's; OpenEXR as is,
     * with its spacing of 1 in its header */
    if (x3p) s.dx = s.dy = 1e-6, s.z_scale = 1e-6;
    else s.dx = s.dy = 1.0, s.z_scale = 1.0;
    if (!x3p && !path_has_ext(path, ".exr")) die("--out '%s': give a .exr or .x3p name", path);
    unsigned char *data;
    size_t bytes;
    char err[400];
    int rc = x3p ? surface_encode_x3p(&s, &data, &bytes, err, sizeof err)
                 : surface_encode_exr(&s, &data, &bytes, err, sizeof err);
    if (rc != 0) die("cannot write '%s': %s", path, err);
    out_write_file(path, data, bytes);
    free(data);
}

static void generate_help(void)
{
    printf("usage: ggx microsurface generate --kind beckmann|ggx|vgroove [--alpha A[,AY]] [--skew TX,TY]\n"
           "                                 [--rotate TZ] [--corr L] [--mix M] [--period P] [--risers P]\n"
           "                                 --size N [--seed S] --out FILE.exr|FILE.x3p\n\n"
           "A periodic height field on an N x N grid of unit spacing (N even, 64 to 4096), whose facets (both\n"
           "triangulations of each cell, as ggx fit reads them) have a chosen NDF:\n"
           "  beckmann  a Gaussian random field: the facets' slopes are Gaussian with covariance\n"
           "            R diag(AX^2, AY^2) R^T / 2 (Beckmann of roughness AX, AY, the axes rotated by TZ degrees;\n"
           "            either triangulation alone is off across by E[D^2] / 4, D the cell's mixed difference),\n"
           "            its autocorrelation Gaussian with correlation length L grid spacings (default 16;\n"
           "            4 to N / 4), by FFT (KISS FFT); --seed S picks the field (default 1)\n"
           "  ggx       GGX slopes of roughness AX, AY rotated by TZ (the shape ggx fit reads back): a Beckmann\n"
           "            field of slope covariance Sigma divided by sqrt(W), W chi-square of 2 degrees of freedom\n"
           "            over the tile's area, varying on the mixing length M (default 8 L, L to N / 4): the\n"
           "            Gaussian scale mixture that GGX's slopes are\n"
           "            --skew TX,TY (degrees): the skewed ellipsoid of ggx_shape_ellipsoid(AX, AY, TX, TY, TZ),\n"
           "            its slopes a Student t of location t and scale Sigma (ggx_shape_slopes): GGX of scale\n"
           "            Sigma on the plane of slope t, t . (x, y) added over the tile. Repeated as it is, that\n"
           "            tile is not periodic: measure it as a tilted patch (measure --tilted). --risers P makes\n"
           "            it a periodic sawtooth: t . (x mod P, y mod P), each ramp of P spacings stepping back\n"
           "            down in one cell, a near-vertical riser (P divides N, at most N / 2)\n"
           "  vgroove   V-grooves along y of period P spacings (even, default 16) and slope AX along x: two\n"
           "            facet normals, each on half the area (Torrance-Sparrow's V-cavities)\n"
           "OpenEXR holds the heights in one float channel Y and the grid spacing 1 in its header attribute\n"
           "spacing; x3p in doubles with a grid of 1e-6 m and heights in metres. Prints the surface's\n"
           "parameters: the heights' standard deviation and the autocorrelation's metric M, C(r) = sigma^2\n"
           "exp(-r^T M r).\n");
}

static const command_spec GENERATE_SPEC = {"kind,alpha,skew,rotate,corr,mix,period,risers,size,seed,out", generate_help,
                                           0};

static int generate(int argc, char **argv)
{
    options o;
    if (!command_options(&GENERATE_SPEC, argc, argv, 3, &o)) return 0;
    if (!o.kind) die("--kind beckmann|ggx|vgroove is required");
    if (!o.size) die("--size N is required");
    if (!o.out) die("--out FILE.exr|FILE.x3p is required");
    size_t n = (size_t)o.size;
    if (o.size_h && o.size_h != o.size) die("--size: a square grid, N");
    if (n % 2 != 0) die("--size %zu: an even size", n);
    double *h = malloc(n * n * sizeof *h);
    if (!h) die("out of memory for %zu x %zu heights", n, n);
    char err[400];
    if ((o.have_skew || o.risers) && strcmp(o.kind, "ggx") != 0) {
        free(h);
        die("--skew and --risers apply to --kind ggx");
    }
    if (o.risers && !o.have_skew) {
        free(h);
        die("--risers: give the skew (--skew TX,TY) whose ramps they step down from");
    }
    if (o.risers && ((size_t)o.risers > n / 2 || n % (size_t)o.risers != 0)) {
        free(h);
        die("--risers %d: a period that divides the size %zu and is at most half of it", o.risers, n);
    }
    if (strcmp(o.kind, "beckmann") == 0) {
        if (o.period) die("--period applies to --kind vgroove");
        if (o.mix > 0) die("--mix applies to --kind ggx");
        ms_gauss_spec sp = {
            n, o.alpha[0], o.alpha[1], o.rotate * 3.14159265358979323846 / 180.0, o.corr > 0 ? o.corr : 16.0, o.seed};
        if (!o.have_alpha) sp.alpha_x = sp.alpha_y = 0.3;
        ms_gauss_info info;
        if (ms_gauss(&sp, h, &info, err, sizeof err) != 0) {
            free(h); /* (die exits: nothing left to the leak checkers) */
            die("%s", err);
        }
        write_heights(o.out, h, n);
        printf("ggx microsurface: %s, %zu x %zu, Beckmann alpha %g, %g rotated %g degrees, correlation length %g: "
               "heights' sigma %.6g, M = [%.6g %.6g; %.6g %.6g], seed %llu\n",
               o.out, n, n, sp.alpha_x, sp.alpha_y, o.rotate, sp.corr_len, info.sigma, info.metric[0], info.metric[1],
               info.metric[1], info.metric[2], (unsigned long long)o.seed);
    } else if (strcmp(o.kind, "ggx") == 0) {
        if (o.period) die("--period applies to --kind vgroove");
        ms_ggx_spec sp = {
            n,     o.alpha[0], o.alpha[1], o.rotate * 3.14159265358979323846 / 180.0, o.corr > 0 ? o.corr : 8.0,
            o.mix, o.seed};
        if (!o.have_alpha) sp.alpha_x = sp.alpha_y = 0.3;
        double t[2] = {0.0, 0.0};
        int rc;
        if (o.have_alpha && !(o.alpha[0] >= 1e-3 && o.alpha[0] <= 7.0 && o.alpha[1] >= 1e-3 && o.alpha[1] <= 7.0)) {
            free(h);
            die("--alpha: a GGX surface takes alphas in [0.001, 7]");
        }
        if (o.have_skew) {
            ggx_shape skewed;
            options so = o;
            if (!so.have_alpha) so.alpha[0] = so.alpha[1] = 0.3;
            shape_from_options(&so, &skewed);
            rc = ms_ggx_skewed(&skewed, &sp, (size_t)o.risers, h, t, err, sizeof err);
        } else {
            rc = ms_ggx(&sp, h, err, sizeof err);
        }
        if (rc != 0) {
            free(h); /* (die exits: nothing left to the leak checkers) */
            die("%s", err);
        }
        write_heights(o.out, h, n);
        printf("ggx microsurface: %s, %zu x %zu, GGX alpha %g, %g rotated %g degrees, correlation length %g, mixing "
               "length %g, seed %llu\n",
               o.out, n, n, sp.alpha_x, sp.alpha_y, sp.phi * 180.0 / 3.14159265358979323846 + 0.0, sp.corr_len,
               sp.mix_len > 0 ? sp.mix_len : 8.0 * sp.corr_len, (unsigned long long)o.seed);
        if (o.have_skew)
            printf("skewed %g, %g degrees: slopes of location t = (%.6g, %.6g) on %s\n", o.skew[0], o.skew[1],
                   t[0] + 0.0, t[1] + 0.0,
                   o.risers ? "a sawtooth of ramps stepping down on risers" : "a tilted patch (measure --tilted)");
        if (o.risers)
            printf("sawtooth period %d: risers in the columns and rows %d mod %d\n", o.risers, o.risers - 1, o.risers);
    } else if (strcmp(o.kind, "vgroove") == 0) {
        if (o.corr > 0 || o.have_rotate || o.mix > 0)
            die("--corr, --mix and --rotate apply to --kind beckmann and ggx");
        if (o.have_alpha && o.alpha[0] != o.alpha[1]) die("--alpha: a V-groove has one slope");
        double slope = o.have_alpha ? o.alpha[0] : 0.5;
        size_t p = o.period ? (size_t)o.period : 16;
        if (ms_vgroove(n, p, slope, h, err, sizeof err) != 0) {
            free(h); /* (die exits: nothing left to the leak checkers) */
            die("%s", err);
        }
        write_heights(o.out, h, n);
        printf("ggx microsurface: %s, %zu x %zu, V-grooves of period %zu and slope %g (facet normals at %.6g "
               "degrees)\n",
               o.out, n, n, p, slope, atan(slope) * 180.0 / 3.14159265358979323846);
    } else {
        die("--kind: unknown kind '%s' (beckmann, ggx, vgroove)", o.kind);
    }
    free(h);
    return 0;
}

/* The visible normals' chi-square: the tracer as a sampler of normals (the first facet hit from v, from a random
 * origin over the tile), against ggx_pdf_vndf of a shape, through the suite's harness (libs/verify/chi2.h). */
typedef struct vndf_ctx {
    normal_keys nk; /* first: the harness's keys and density */
    const ms_tracer *t;
    const size_t *risers;
    size_t size;
    double d[3], w[4], z; /* origins uniform over [w0, w2] x [w1, w3] at height z: the tile, or a patch's window */
    int patch;
} vndf_ctx;

static int vndf_draw(void *p, rng *r, ggx_vec3 *w)
{
    vndf_ctx *c = p;
    ms_hit hit;
    /* the first facet hit off a sawtooth's risers (the facets of D); on a patch, of the rays that hit (not through a
     * hole, not out of its side) */
    for (int tries = 0;; tries++) {
        double o[3] = {c->w[0] + rng_uniform(r) * (c->w[2] - c->w[0]), c->w[1] + rng_uniform(r) * (c->w[3] - c->w[1]),
                       c->z};
        int k = ms_trace(c->t, o, c->d, &hit);
        if (tries == 1000 || (k != 1 && !c->patch)) return 0;
        if (k == 1 && !ms_riser_cell(c->risers, c->size, hit.cell)) break;
    }
    *w = (ggx_vec3){hit.m[0], hit.m[1], hit.m[2]};
    return 1;
}

static double vndf_pdf(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m) { return ggx_pdf_vndf(s, v, m); }

static void measure_help(void)
{
    printf("usage: ggx microsurface measure --heightfield FILE [--spacing D] [--z-scale Z] [--downsample K]\n"
           "                                [--tilted | --risers P]\n"
           "                                [--alpha A[,AY] [--skew TX,TY] [--rotate TZ] | --matrix M]\n"
           "                                --view THETA,PHI [-n RAYS] [--bounces K] [--threads N] [--seed S]\n"
           "                                [--format md|json] [--out FILE]\n\n"
           "Traces a periodic height field (ggx microsurface generate's, or any square tile whose edges wrap)\n"
           "from the view v with RAYS rays (default 1e6) on a jittered grid of origins and reports the masking\n"
           "against the model: G1(v) of the facets (exact for a height field: the footprint's projected area\n"
           "over the facets'), Smith's G1 for Beckmann slopes of the facets' covariance and for GGX of the\n"
           "ellipsoid fitted to the facets (ggx_fit_heightfield), and per normal bin (4 rings of equal\n"
           "sin^2(theta_m) times 8 azimuth sectors) the traced G1(v, m), the visible share of the bin's\n"
           "projected area, against G1(v): Smith's masking makes them equal. Then the visible normals: the\n"
           "first facets hit by up to 200,000 rays from random origins (--seed S), chi-square against\n"
           "ggx_pdf_vndf of the fitted shape (eq 33) on 16 x 16 cells of its sphere space. Then the BRDF with\n"
           "F = 1 and the light at the view: RAYS rays reflected from facet to facet until they escape (at most\n"
           "K times, default 100; the rest are counted as still bouncing), binned in 8 x 16 outgoing bins of\n"
           "equal projected solid angle; single scattering against ggx_brdf_eval of the fitted shape and the\n"
           "same with the height-correlated G2 in place of eq 5's (its albedo against ggx_albedo and\n"
           "ggx_albedo_height_correlated), all bounces against\n"
           "ggx_brdf_compensated_eval of the fitted scale without its skew (the white furnace: albedo 1).\n"
           "The model's shape is the fit, or the shape given (--alpha, --skew, --rotate or --matrix).\n\n"
           "Measured scans: a surface that is not square, has missing points, or whose edges do not wrap\n"
           "(differences across them 3 times the inner ones in RMS) is traced as a finite patch, levelled: rays\n"
           "start over an inner window (the patch less the heights' band times tan(theta) where the rays go;\n"
           "for the BRDF more, on every side), cells with a missing corner are absent and the rays through them\n"
           "counted as fallen through holes, rays that leave the patch's side counted as left; the report says\n"
           "so. Spacings must be equal (to 1e-3); --downsample K averages K x K blocks first (default: none).\n\n"
           "Skewed surfaces (generate --skew): --tilted traces the tile as an infinite tilted patch, each copy\n"
           "raised by the tile's mean slope (its inner differences' mean) times N; --risers P as the sawtooth of\n"
           "generate --risers P, whose risers (the cells of the columns and rows P - 1 mod P along an axis where\n"
           "they step by more than 1) are counted apart. G1 of the other facets, traced, is then set beside\n"
           "Walter's eq 6 (ggx_g1, with its min), the Smith form of eq 32 without it (ggx_g1_smith), vertical\n"
           "facets (Walter's remedy with Smith's masking), the tilted base (ggx_g1_tilted: Smith's masking\n"
           "about the plane of slope t) and the sawtooth's (ggx_g1_risers); and the risers' own visible share. A\n"
           "tilted patch's BRDF is not measured (its directions are the tilted plane's).\n");
}

static const command_spec MEASURE_SPEC = {"heightfield,spacing,z-scale,downsample,tilted,risers," SHAPE_OPTS
                                          ",view,n,bounces,threads,seed,format,out",
                                          measure_help, 0};

/* What ggx microsurface measure found, for its report. */
typedef struct measured {
    const options *o;
    size_t n;
    microsurface_patch pt;
    char no_brdf[400]; /* why the BRDF was not measured */
    double v[3], theta, phi, tilt[2], ts[2];
    ms_g1 r;
    ms_brdf br;
    int given, skewed, brdf, bounces;
    long vrays;
    chi2_result cr;
    double g_b, g_ggx, g_eq6, g_vf, g_tb, g_saw, g_riser, g1v;
    double e_single, e_all, e_model, e_hc, l2_single, l2_all, l2_hc;
} measured;

enum { BR = 8, BS = 16 }; /* the BRDF's bins: rings of equal sin^2 theta times sectors */

static void report_json(FILE *f, const measured *m)
{
    fprintf(f, "{\n  \"input\": \"%s\", \"size\": %zu, \"view_deg\": [%.6g, %.6g], \"rays\": %ld, \"missed\": %ld,\n",
            m->o->heightfield, m->n, m->theta, m->phi, m->r.rays, m->r.missed);
    fprintf(f,
            "  \"slope_cov\": [%.10g, %.10g, %.10g],\n  \"g1\": {\"facets\": %.10g, \"smith_beckmann\": %s, "
            "\"smith_ggx_fit\": %s},\n",
            m->r.slope_cov[0], m->r.slope_cov[1], m->r.slope_cov[2], m->r.g1, json_number(m->g_b),
            json_number(m->g_ggx));
    fprintf(f,
            "  \"tilt\": [%.10g, %.10g], \"risers\": [%zu, %zu], \"slope_mean\": [%.10g, %.10g], "
            "\"t\": [%s, %s],\n",
            m->tilt[0], m->tilt[1], m->r.risers[0], m->r.risers[1], m->r.slope_mean[0], m->r.slope_mean[1],
            json_number(m->ts[0]), json_number(m->ts[1]));
    fprintf(f,
            "  \"skewed_g1\": {\"traced\": %.10g, \"eq6\": %s, \"smith\": %s, \"vertical_facets\": %s, "
            "\"tilted_base\": %s, \"sawtooth\": %s, \"risers_area\": %.10g, \"risers_visible\": %s},\n",
            m->g1v, json_number(m->g_eq6), json_number(m->g_ggx), json_number(m->g_vf), json_number(m->g_tb),
            json_number(m->g_saw), m->r.riser_area, json_number(m->g_riser));
    fprintf(f, "  \"vndf_chi2\": {\"rays\": %ld, \"stat\": %s, \"dof\": %d, \"pvalue\": %s, \"invalid\": %ld},\n",
            m->vrays, json_number(m->cr.stat), m->cr.dof, json_number(m->cr.pvalue), m->cr.invalid);
    if (m->brdf) {
        fprintf(f,
                "  \"brdf\": {\"rays\": %ld, \"lost\": %ld, \"capped\": %ld, \"albedo_single\": %.8g, "
                "\"albedo_model\": %s, \"albedo_model_height_correlated\": %s, \"albedo_all\": %.8g, "
                "\"l2_single\": %s, \"l2_single_height_correlated\": %s, \"l2_all\": %s,\n",
                m->br.rays, m->br.lost, m->br.capped, m->e_single, json_number(m->e_model), json_number(m->e_hc),
                m->e_all, json_number(m->l2_single), json_number(m->l2_hc), json_number(m->l2_all));
        /* the shares per outgoing bin (ring-major, BR x BS), for comparing runs */
        for (int k = 0; k < 2; k++) {
            const double *x = k ? m->br.all : m->br.single;
            fprintf(f, "    \"%s\": [", k ? "all" : "single");
            for (int b = 0; b < BR * BS; b++) fprintf(f, "%s%.8g", b ? ", " : "", x[b]);
            fprintf(f, "]%s\n", k ? "}," : ",");
        }
    } else fprintf(f, "  \"brdf\": null,\n");
    if (m->pt.on)
        fprintf(f,
                "  \"patch\": {\"why\": \"%s\", \"nx\": %zu, \"ny\": %zu, \"downsample\": %d, \"edge\": "
                "\"window\", \"window\": [%.6g, %.6g, %.6g, %.6g], \"left\": %ld, \"holes\": %ld, "
                "\"brdf_left\": %ld, \"missing_points\": %zu, \"absent_cells\": %zu, \"levelled\": [%.6g, %.6g]},\n",
                m->pt.why, m->pt.nx, m->pt.ny, m->pt.downsample, m->r.window[0], m->r.window[1], m->r.window[2],
                m->r.window[3], m->r.left, m->r.holes, m->br.left, m->pt.missing, m->pt.absent, m->pt.plane[0],
                m->pt.plane[1]);
    else fprintf(f, "  \"patch\": null,\n");
    fprintf(f, "  \"bins\": [");
}

/* a patch's lines of the report: why it is one, its edge treatment and what its rays met */
static void report_patch_md(FILE *f, const measured *m)
{
    fprintf(f,
            "traced as a patch (%s), %zu x %zu heights%s, levelled (the plane of slopes %.4g, %.4g taken off): no "
            "wrap; rays start over the window [%.5g, %.5g] x [%.5g, "
            "%.5g] (the patch less the band's fall times tan(theta) downstream), %ld left its side and %ld fell "
            "through missing regions (%zu missing points, %zu absent cells)\n\n",
            m->pt.why, m->pt.nx, m->pt.ny, m->pt.downsample > 1 ? " after --downsample" : "", m->pt.plane[0],
            m->pt.plane[1], m->r.window[0], m->r.window[2], m->r.window[1], m->r.window[3], m->r.left, m->r.holes,
            m->pt.missing, m->pt.absent);
}

static void report_md(FILE *f, const measured *m)
{
    fprintf(f, "# ggx microsurface measure: %s, %zu x %zu, view theta %.4g, phi %.4g degrees\n\n", m->o->heightfield,
            m->pt.on ? m->pt.nx : m->n, m->pt.on ? m->pt.ny : m->n, m->theta, m->phi);
    if (m->pt.on) report_patch_md(f, m);
    fprintf(f, "%ld rays, %ld missed; the facets' slope covariance %.6g, %.6g, %.6g\n\n", m->r.rays, m->r.missed,
            m->r.slope_cov[0], m->r.slope_cov[1], m->r.slope_cov[2]);
    fprintf(f,
            "| G1(v) | value |\n|---|---|\n| the facets (exact) | %.6f |\n| Smith, Beckmann of the facets' "
            "covariance | %.6f |\n| Smith, GGX %s (ggx_g1_smith) | %.6f |\n\n",
            m->r.g1, m->g_b, m->given ? "given" : "fitted", m->g_ggx);
    if (m->skewed) {
        fprintf(f,
                "skewed: %s; the facets off the risers have the mean slope %.6g, %.6g; the model's t = %.6g, "
                "%.6g\n\n",
                m->o->tilted   ? "a tilted patch"
                : m->o->risers ? "a sawtooth"
                               : "periodic",
                m->r.slope_mean[0], m->r.slope_mean[1], m->ts[0], m->ts[1]);
        fprintf(f,
                "| G1(v) of the facets off the risers | value |\n|---|---|\n| traced | %.6f |\n"
                "| eq 6 with its min (ggx_g1) | %.6f |\n| Smith form of eq 32 (ggx_g1_smith) | %.6f |\n"
                "| vertical facets (Walter's remedy, Smith's masking) | %.6f |\n"
                "| tilted base (ggx_g1_tilted) | %.6f |\n"
                "| sawtooth (ggx_g1_risers) | %.6f |\n",
                m->g1v, m->g_eq6, m->g_ggx, m->g_vf, m->g_tb, m->g_saw);
        if (m->r.riser_area > 0.0)
            fprintf(f, "| the risers' visible share (projected area %.6f) | %.6f |\n", m->r.riser_area, m->g_riser);
        fprintf(f, "\n");
    }
    if (m->cr.dof > 0)
        fprintf(f,
                "visible normals of %ld rays against ggx_pdf_vndf of the %s shape (eq 33): chi-square %.6g on %d "
                "degrees of freedom (%.3g per degree), p = %.3g\n\n",
                m->vrays, m->given ? "given" : "fitted", m->cr.stat, m->cr.dof, m->cr.stat / m->cr.dof, m->cr.pvalue);
    else fprintf(f, "visible normals of %ld rays: too few for a chi-square against ggx_pdf_vndf\n\n", m->vrays);
    if (!m->brdf) fprintf(f, "the BRDF is not measured: %s\n\n", m->no_brdf);
    else
        fprintf(f,
                "the BRDF with F = 1 from the light at the view, %ld rays (%ld lost, %ld still bouncing "
                "after %d), "
                "%d x %d bins:\n\n| | traced | model | relative L2 of the BRDF over the bins |\n|---|---|---|---|\n"
                "| single scattering: albedo | %.5f | %.5f (ggx_albedo; height-correlated: %.5f) | %.4f "
                "(ggx_brdf_eval; with the height-correlated G2: %.4f) |\n"
                "| all bounces: albedo | %.5f | 1 (F = 1) | %.4f (ggx_brdf_compensated_eval) |\n\n",
                m->br.rays, m->br.lost, m->br.capped, m->bounces, BR, BS, m->e_single, m->e_model, m->e_hc,
                m->l2_single, m->l2_hc, m->e_all, m->l2_all);
    fprintf(f,
            "| sin^2 theta_m | phi_m, degrees | projected area | traced G1(v, m) | / G1(v) |\n|---|---|---|---|---|\n");
}

/* the normal bins with enough of the projected area: traced G1(v, m) */
static void report_bins(FILE *f, const measured *m, int json)
{
    int first = 1;
    for (int b = 0; b < m->r.rings * m->r.sectors; b++) {
        if (!(m->r.area[b] > 1e-4 * m->v[2])) continue; /* bins with under 1e-4 of the projected area: too few rays */
        int ring = b / m->r.sectors, sec = b % m->r.sectors;
        double g = m->r.visible[b] / m->r.area[b];
        if (json)
            fprintf(f, "%s\n    {\"ring\": %d, \"sector\": %d, \"area\": %.8g, \"g1\": %.8g}", first ? "" : ",", ring,
                    sec, m->r.area[b], g);
        else
            fprintf(f, "| %.2f-%.2f | %.0f-%.0f | %.5f | %.5f | %.4f |\n", (double)ring / m->r.rings,
                    (double)(ring + 1) / m->r.rings, 360.0 * sec / m->r.sectors, 360.0 * (sec + 1) / m->r.sectors,
                    m->r.area[b], g, g / m->g1v);
        first = 0;
    }
}

/* The BRDF with F = 1 from the light at the view: the traced albedos, and the relative L2 over the bins of the traced
 * single scattering against ggx_brdf_eval of the shape (and with the height-correlated G2), and of all bounces against
 * the energy-compensated BRDF of the shape's scale without its (small) skew. fit NULL: no shape to compare with. */
static void brdf_against_model(measured *m, const ggx_shape *fit)
{
    double d1 = 0.0, n1 = 0.0, d2 = 0.0, n2 = 0.0, d3 = 0.0, n3 = 0.0;
    ggx_energy *en = NULL;
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    m->e_model = m->e_hc = NAN;
    if (fit) {
        double ts[2], ss[3];
        ggx_shape flat;
        ggx_shape_slopes(fit, ts, ss);
        if (ggx_shape_from_slopes(&flat, 0.0, 0.0, ss[0], ss[1], ss[2]) == GGX_OK) ggx_energy_create(&flat, &en);
        m->e_model = ggx_albedo(fit, m->o->view), m->e_hc = ggx_albedo_height_correlated(fit, m->o->view);
    }
    for (int b = 0; b < BR * BS; b++) {
        double f1 = m->br.single[b] * BR * BS / 3.14159265358979323846,
               fa = m->br.all[b] * BR * BS / 3.14159265358979323846;
        m->e_single += m->br.single[b], m->e_all += m->br.all[b];
        if (!fit) continue;
        /* the model's mean over the bin (uniform in sin^2 theta and phi: uniform in projected solid angle) */
        double m1 = 0.0, ma = 0.0, mh = 0.0;
        int ring = b / BS, sec = b % BS;
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 4; k++) {
                double u = ((double)ring + (i + 0.5) / 4.0) / BR,
                       ph = 2.0 * 3.14159265358979323846 * ((double)sec + (k + 0.5) / 4.0) / BS;
                ggx_vec3 wo = {sqrt(u) * cos(ph), sqrt(u) * sin(ph), sqrt(1.0 - u)};
                double f = ggx_brdf_eval(fit, &one, m->o->view, wo) / 16.0;
                /* the height-correlated G2 in place of eq 5's: the same BRDF times their ratio at the half vector */
                ggx_vec3 hv = ggx_half_reflect(m->o->view, wo);
                double g2 = ggx_g2(fit, m->o->view, wo, hv);
                m1 += f, mh += g2 > 0.0 ? f * ggx_g2_height_correlated(fit, m->o->view, wo, hv) / g2 : 0.0;
                if (en) ma += ggx_brdf_compensated_eval(en, &one, m->o->view, wo) / 16.0;
            }
        d1 += (f1 - m1) * (f1 - m1), n1 += m1 * m1, d2 += (fa - ma) * (fa - ma), n2 += ma * ma;
        d3 += (f1 - mh) * (f1 - mh), n3 += mh * mh;
    }
    m->l2_single = sqrt(d1 / n1), m->l2_all = en ? sqrt(d2 / n2) : NAN, m->l2_hc = sqrt(d3 / n3);
    ggx_energy_free(en);
}

static int measure(int argc, char **argv)
{
    options o;
    if (!command_options(&MEASURE_SPEC, argc, argv, 3, &o)) return 0;
    if (!o.heightfield) die("--heightfield FILE is required");
    if (!o.have_view) die("--view THETA,PHI is required");
    if (!(o.view.z > 1e-9)) die("--view: the view must be above the plane");
    measured m;
    memset(&m, 0, sizeof m);
    m.o = &o;
    double *h;
    size_t risers[2];
    ms_tracer *t = microsurface_open(&o, &h, &m.n, m.tilt, risers, &m.pt);
    char err[400];
    m.v[0] = o.view.x, m.v[1] = o.view.y, m.v[2] = o.view.z;
    long rays = o.n > 0 ? o.n : 1000000;
    int threads = o.threads > 0 ? o.threads : 1;
    if (ms_measure_g1(t, h, m.n, m.v, rays, 4, 8, risers, threads, &m.r, err, sizeof err) != 0) die("%s", err);
    ggx_shape fit;
    ggx_status st = microsurface_model(&o, h, &m.pt, m.n, risers, &fit, &m.given);
    m.g_ggx = st == GGX_OK ? ggx_g1_smith(&fit, o.view) : NAN, m.g_b = ms_beckmann_g1(m.r.slope_cov, m.v);
    /* the visible normals against eq 33 for the fitted shape, 16 x 16 cells of its sphere space */
    m.vrays = rays < 200000 ? rays : 200000;
    if (st == GGX_OK) {
        double zmin, zmax;
        ms_tracer_bounds(t, &zmin, &zmax);
        vndf_ctx c = {{&fit, o.view, vndf_pdf},
                      t,
                      risers,
                      m.n,
                      {-m.v[0], -m.v[1], -m.v[2]},
                      {0.0, 0.0, (double)m.n, (double)m.n},
                      zmax + 1.0,
                      m.pt.on};
        if (m.pt.on) memcpy(c.w, m.r.window, sizeof c.w), c.z = ms_patch_top(t);
        chi2_problem p = {"traced visible normals", 1, vndf_draw, normal_keys_key, normal_keys_density, &c};
        m.cr = chi2_run_quiet(&p, m.vrays, 16, 16, o.seed, 0.01);
    }
    m.bounces = o.bounces > 0 ? o.bounces : 100, m.brdf = !o.tilted;
    m.e_model = m.e_hc = m.l2_single = m.l2_all = m.l2_hc = NAN;
    snprintf(m.no_brdf, sizeof m.no_brdf, "a tilted patch's directions are the tilted plane's");
    double bw[4];
    /* a patch too small for the BRDF's margins at this view: G1 is reported, the BRDF not */
    if (m.pt.on && ms_patch_window(t, m.v, 1, bw, m.no_brdf, sizeof m.no_brdf) != 0) m.brdf = 0;
    if (m.brdf) {
        if (ms_measure_brdf(t, m.n, m.v, rays, BR, BS, m.bounces, threads, &m.br, err, sizeof err) != 0) die("%s", err);
        brdf_against_model(&m, st == GGX_OK ? &fit : NULL);
    }
    /* skewed surfaces: the facets off the risers against the masking forms (microsurface.h, skew.c) */
    double ss[3];
    if (st == GGX_OK) ggx_shape_slopes(&fit, m.ts, ss);
    m.g_eq6 = st == GGX_OK ? ggx_g1(&fit, o.view, o.view) : NAN;
    m.g_vf = st == GGX_OK ? ms_g1_vertical_facets(&fit, m.v) : NAN;
    m.g_tb = st == GGX_OK ? ggx_g1_tilted(&fit, o.view, o.view) : NAN;
    m.g_saw = st == GGX_OK ? ggx_g1_risers(&fit, o.view, o.view) : NAN;
    m.g_riser = m.r.riser_area > 0.0 ? m.r.riser_visible / m.r.riser_area : NAN;
    /* a periodic tile has no mean slope */
    m.skewed = o.tilted || o.risers || (m.given && hypot(m.ts[0], m.ts[1]) > 1e-9);
    m.g1v = risers[0] || risers[1] ? m.r.g1_off_risers : m.r.g1;
    int json = o.format && strcmp(o.format, "json") == 0;
    if (o.format && !json && strcmp(o.format, "md") != 0) die("--format: '%s' is not md or json", o.format);
    out_file f;
    out_open(&f, o.out ? o.out : "-");
    m.theta = acos(m.v[2]) * 180.0 / 3.14159265358979323846;
    m.phi = atan2(m.v[1], m.v[0]) * 180.0 / 3.14159265358979323846;
    if (json) report_json(f.f, &m);
    else report_md(f.f, &m);
    report_bins(f.f, &m, json);
    if (json) fprintf(f.f, "\n  ]\n}\n");
    out_close(&f);
    ms_g1_free(&m.r);
    ms_brdf_free(&m.br);
    ms_tracer_free(t);
    free(h);
    return 0;
}

int cmd_microsurface(int argc, char **argv)
{
    if (argc < 3 || strcmp(argv[2], "--help") == 0 || strcmp(argv[2], "-h") == 0) {
        printf("usage: ggx microsurface generate|measure|figure|wave [options]   (ggx microsurface generate --help, "
               "...)\n\n"
               "Microsurfaces with a chosen NDF, to check the model against geometry: generate writes a periodic\n"
               "height field (Beckmann or GGX facets, skewed ones, V-grooves) as OpenEXR or x3p, which\n"
               "ggx fit reads; measure traces one and reports its masking, visible normals and BRDF against the\n"
               "model's; figure draws its traced G1 over the views of a plane beside the model's forms.\n");
        if (argc < 3) die("give a subcommand: generate, measure or figure");
        return 0;
    }
    if (strcmp(argv[2], "generate") == 0) return generate(argc, argv);
    if (strcmp(argv[2], "measure") == 0) return measure(argc, argv);
    if (strcmp(argv[2], "figure") == 0) return microsurface_figure(argc, argv);
    if (strcmp(argv[2], "wave") == 0) return microsurface_wave(argc, argv);
    die("microsurface: unknown subcommand '%s' (generate, measure, figure, wave)", argv[2]);
    return 2;
}
