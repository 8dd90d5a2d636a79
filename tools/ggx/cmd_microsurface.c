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
    size_t len = strlen(path);
    int x3p = len >= 4 && strcmp(path + len - 4, ".x3p") == 0;
    /* x3p in metres: a grid of 1 micrometre, heights in the same unit, so slopes are the field's; OpenEXR as is */
    if (x3p) s.dx = s.dy = 1e-6, s.z_scale = 1e-6;
    if (!x3p && !(len >= 4 && strcmp(path + len - 4, ".exr") == 0)) die("--out '%s': give a .exr or .x3p name", path);
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
           "  beckmann  a Gaussian random field: every facet's slope is Gaussian with covariance\n"
           "            R diag(AX^2, AY^2) R^T / 2 (Beckmann of roughness AX, AY, the axes rotated by TZ degrees),\n"
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
           "OpenEXR holds the heights in one float channel Y (ggx fit --heightfield needs --spacing 1 --z-scale\n"
           "1 for it); x3p in doubles with a grid of 1e-6 m and heights in metres. Prints the surface's\n"
           "parameters: the heights' standard deviation and the autocorrelation's metric M, C(r) = sigma^2\n"
           "exp(-r^T M r).\n");
}

static const command_spec GENERATE_SPEC = {"kind,alpha,skew,rotate,corr,mix,period,risers,size,seed,out",
                                           generate_help};

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
    double d[3], n, zmax;
} vndf_ctx;

static int vndf_draw(void *p, rng *r, ggx_vec3 *w)
{
    vndf_ctx *c = p;
    ms_hit hit;
    for (int tries = 0;; tries++) { /* the first facet hit off a sawtooth's risers (the facets of D) */
        double o[3] = {rng_uniform(r) * c->n, rng_uniform(r) * c->n, c->zmax + 1.0};
        if (ms_trace(c->t, o, c->d, &hit) != 1 || tries == 1000) return 0;
        if (!ms_riser_cell(c->risers, c->size, hit.cell)) break;
    }
    *w = (ggx_vec3){hit.m[0], hit.m[1], hit.m[2]};
    return 1;
}

static double vndf_pdf(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m) { return ggx_pdf_vndf(s, v, m); }

/* a JSON number, or null for NaN and infinities (JSON has neither) */
static const char *jnum(char buf[32], double x)
{
    if (isfinite(x)) snprintf(buf, 32, "%.10g", x);
    else snprintf(buf, 32, "null");
    return buf;
}

static void measure_help(void)
{
    printf("usage: ggx microsurface measure --heightfield FILE [--spacing D] [--z-scale Z] [--tilted | --risers P]\n"
           "                                [--alpha A[,AY] [--skew TX,TY] [--rotate TZ] | --matrix M]\n"
           "                                --view THETA,PHI [-n RAYS] [--bounces K] [--threads N] [--seed S]\n"
           "                                [--format md|json] [--out FILE]\n\n"
           "Traces a periodic height field (ggx microsurface generate's, or any square tile whose edges wrap)\n"
           "from the view v with RAYS rays (default 1e6) on a jittered grid of origins and reports the masking\n"
           "against the model: G1(v) of the facets (exact for a height field: the footprint's projected area\n"
           "over the facets'), Smith's G1 for Beckmann slopes of the facets' covariance and for GGX of the\n"
           "ellipsoid fitted to the facets (ggx_fit_heightfield), and per normal bin (4 rings of equal\n"
           "sin^2(theta_m) times 8 azimuth sectors) the traced G1(v, m), the visible share of the bin's\n"
           "projected area, against G1(v): Smith's masking makes them equal. A tile whose edges do not wrap\n"
           "(differences across them 3 times the inner ones in RMS) is refused. Then the visible normals: the\n"
           "first facets hit by up to 200,000 rays from random origins (--seed S), chi-square against\n"
           "ggx_pdf_vndf of the fitted shape (eq 33) on 16 x 16 cells of its sphere space. Then the BRDF with\n"
           "F = 1 and the light at the view: RAYS rays reflected from facet to facet until they escape (at most\n"
           "K times, default 100; the rest are counted as still bouncing), binned in 8 x 16 outgoing bins of\n"
           "equal projected solid angle; single scattering against ggx_brdf_eval of the fitted shape and the\n"
           "same with the height-correlated G2 in place of eq 5's (its albedo against ggx_albedo and\n"
           "ggx_albedo_height_correlated), all bounces against\n"
           "ggx_brdf_compensated_eval of the fitted scale without its skew (the white furnace: albedo 1).\n"
           "The model's shape is the fit, or the shape given (--alpha, --skew, --rotate or --matrix).\n\n"
           "Skewed surfaces (generate --skew): --tilted traces the tile as an infinite tilted patch, each copy\n"
           "raised by the tile's mean slope (its inner differences' mean) times N; --risers P as the sawtooth of\n"
           "generate --risers P, whose risers (the cells of the columns and rows P - 1 mod P along an axis where\n"
           "they step by more than 1) are counted apart. G1 of the other facets, traced, is then set beside\n"
           "Walter's eq 6 (ggx_g1, with its min), the Smith form of eq 32 without it (ggx_g1_smith), vertical\n"
           "facets (Walter's remedy with Smith's masking), the tilted base (ggx_g1_tilted: Smith's masking\n"
           "about the plane of slope t) and the sawtooth's (ggx_g1_risers); and the risers' own visible share. A\n"
           "tilted patch's BRDF is not measured (its directions are the tilted plane's).\n");
}

static const command_spec MEASURE_SPEC = {
    "heightfield,spacing,z-scale,tilted,risers," SHAPE_OPTS ",view,n,bounces,threads,seed,format,out", measure_help};

static int measure(int argc, char **argv)
{
    options o;
    if (!command_options(&MEASURE_SPEC, argc, argv, 3, &o)) return 0;
    if (!o.heightfield) die("--heightfield FILE is required");
    if (!o.have_view) die("--view THETA,PHI is required");
    if (!(o.view.z > 1e-9)) die("--view: the view must be above the plane");
    size_t n;
    double tilt[2], *h;
    size_t risers[2];
    ms_tracer *t = microsurface_open(&o, &h, &n, tilt, risers);
    char err[400];
    double v[3] = {o.view.x, o.view.y, o.view.z};
    long rays = o.n > 0 ? o.n : 1000000;
    int threads = o.threads > 0 ? o.threads : 1;
    ms_g1 r;
    if (ms_measure_g1(t, h, n, v, rays, 4, 8, risers, threads, &r, err, sizeof err) != 0) die("%s", err);
    ggx_shape fit;
    int given;
    ggx_status st = microsurface_model(&o, h, n, risers, &fit, &given);
    double g_ggx = st == GGX_OK ? ggx_g1_smith(&fit, o.view) : NAN, g_b = ms_beckmann_g1(r.slope_cov, v);
    /* the visible normals against eq 33 for the fitted shape, 16 x 16 cells of its sphere space */
    chi2_result cr = {0};
    long vrays = rays < 200000 ? rays : 200000;
    if (st == GGX_OK) {
        double zmin, zmax;
        ms_tracer_bounds(t, &zmin, &zmax);
        vndf_ctx c = {{&fit, o.view, vndf_pdf}, t, risers, n, {-v[0], -v[1], -v[2]}, (double)n, zmax};
        chi2_problem p = {"traced visible normals", 1, vndf_draw, normal_keys_key, normal_keys_density, &c};
        cr = chi2_run_quiet(&p, vrays, 16, 16, o.seed, 0.01);
    }
    /* the BRDF with F = 1 from the light v: traced single and all bounces against ggx_brdf_eval of the fitted shape
     * and the energy-compensated BRDF of the fitted scale without its (small) skew */
    enum { BR = 8, BS = 16 };
    ms_brdf br;
    memset(&br, 0, sizeof br);
    int bounces = o.bounces > 0 ? o.bounces : 100, brdf = !o.tilted;
    if (brdf && ms_measure_brdf(t, n, v, rays, BR, BS, bounces, threads, &br, err, sizeof err) != 0) die("%s", err);
    double e_single = 0.0, e_all = 0.0, d1 = 0.0, n1 = 0.0, d2 = 0.0, n2 = 0.0, d3 = 0.0, n3 = 0.0;
    double e_model = NAN, e_hc = NAN;
    ggx_energy *en = NULL;
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    if (st == GGX_OK && brdf) {
        double ts[2], ss[3];
        ggx_shape flat;
        ggx_shape_slopes(&fit, ts, ss);
        if (ggx_shape_from_slopes(&flat, 0.0, 0.0, ss[0], ss[1], ss[2]) == GGX_OK) ggx_energy_create(&flat, &en);
        e_model = ggx_albedo(&fit, o.view), e_hc = ggx_albedo_height_correlated(&fit, o.view);
    }
    for (int b = 0; brdf && b < BR * BS; b++) {
        double f1 = br.single[b] * BR * BS / 3.14159265358979323846, fa = br.all[b] * BR * BS / 3.14159265358979323846;
        e_single += br.single[b], e_all += br.all[b];
        if (st != GGX_OK) continue;
        /* the model's mean over the bin (uniform in sin^2 theta and phi: uniform in projected solid angle) */
        double m1 = 0.0, ma = 0.0, mh = 0.0;
        int ring = b / BS, sec = b % BS;
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 4; k++) {
                double u = ((double)ring + (i + 0.5) / 4.0) / BR,
                       ph = 2.0 * 3.14159265358979323846 * ((double)sec + (k + 0.5) / 4.0) / BS;
                ggx_vec3 wo = {sqrt(u) * cos(ph), sqrt(u) * sin(ph), sqrt(1.0 - u)};
                double f = ggx_brdf_eval(&fit, &one, o.view, wo) / 16.0;
                /* the height-correlated G2 in place of eq 5's: the same BRDF times their ratio at the half vector */
                ggx_vec3 hv = ggx_half_reflect(o.view, wo);
                double g2 = ggx_g2(&fit, o.view, wo, hv);
                m1 += f, mh += g2 > 0.0 ? f * ggx_g2_height_correlated(&fit, o.view, wo, hv) / g2 : 0.0;
                if (en) ma += ggx_brdf_compensated_eval(en, &one, o.view, wo) / 16.0;
            }
        d1 += (f1 - m1) * (f1 - m1), n1 += m1 * m1, d2 += (fa - ma) * (fa - ma), n2 += ma * ma;
        d3 += (f1 - mh) * (f1 - mh), n3 += mh * mh;
    }
    double l2_single = brdf ? sqrt(d1 / n1) : NAN, l2_all = en ? sqrt(d2 / n2) : NAN,
           l2_hc = brdf ? sqrt(d3 / n3) : NAN;
    ggx_energy_free(en);
    /* skewed surfaces: the facets off the risers against the masking forms (microsurface.h, skew.c) */
    double ts[2] = {0.0, 0.0}, ss[3];
    if (st == GGX_OK) ggx_shape_slopes(&fit, ts, ss);
    double g_eq6 = st == GGX_OK ? ggx_g1(&fit, o.view, o.view) : NAN;
    double g_vf = st == GGX_OK ? ms_g1_vertical_facets(&fit, v) : NAN;
    double g_tb = st == GGX_OK ? ggx_g1_tilted(&fit, o.view, o.view) : NAN;
    double g_saw = st == GGX_OK ? ggx_g1_risers(&fit, o.view, o.view) : NAN;
    double g_riser = r.riser_area > 0.0 ? r.riser_visible / r.riser_area : NAN;
    int skewed = o.tilted || o.risers || (given && hypot(ts[0], ts[1]) > 1e-9); /* a periodic tile has no mean slope */
    double g1v = risers[0] || risers[1] ? r.g1_off_risers : r.g1;
    int json = o.format && strcmp(o.format, "json") == 0;
    if (o.format && !json && strcmp(o.format, "md") != 0) die("--format: '%s' is not md or json", o.format);
    out_file f;
    out_open(&f, o.out ? o.out : "-");
    double theta = acos(v[2]) * 180.0 / 3.14159265358979323846,
           phi = atan2(v[1], v[0]) * 180.0 / 3.14159265358979323846;
    if (json) {
        fprintf(f.f,
                "{\n  \"input\": \"%s\", \"size\": %zu, \"view_deg\": [%.6g, %.6g], \"rays\": %ld, \"missed\": %ld,\n",
                o.heightfield, n, theta, phi, r.rays, r.missed);
        char b1[32], b2[32], b3[32], b4[32], b5[32];
        fprintf(f.f,
                "  \"slope_cov\": [%.10g, %.10g, %.10g],\n  \"g1\": {\"facets\": %.10g, \"smith_beckmann\": %s, "
                "\"smith_ggx_fit\": %s},\n",
                r.slope_cov[0], r.slope_cov[1], r.slope_cov[2], r.g1, jnum(b1, g_b), jnum(b2, g_ggx));
        fprintf(f.f,
                "  \"tilt\": [%.10g, %.10g], \"risers\": [%zu, %zu], \"slope_mean\": [%.10g, %.10g], "
                "\"t\": [%s, %s],\n",
                tilt[0], tilt[1], r.risers[0], r.risers[1], r.slope_mean[0], r.slope_mean[1], jnum(b1, ts[0]),
                jnum(b2, ts[1]));
        char b6[32];
        fprintf(f.f,
                "  \"skewed_g1\": {\"traced\": %.10g, \"eq6\": %s, \"smith\": %s, \"vertical_facets\": %s, "
                "\"tilted_base\": %s, \"sawtooth\": %s, \"risers_area\": %.10g, \"risers_visible\": %s},\n",
                g1v, jnum(b1, g_eq6), jnum(b2, g_ggx), jnum(b3, g_vf), jnum(b4, g_tb), jnum(b5, g_saw), r.riser_area,
                jnum(b6, g_riser));
        fprintf(f.f, "  \"vndf_chi2\": {\"rays\": %ld, \"stat\": %s, \"dof\": %d, \"pvalue\": %s, \"invalid\": %ld},\n",
                vrays, jnum(b1, cr.stat), cr.dof, jnum(b2, cr.pvalue), cr.invalid);
        if (brdf)
            fprintf(f.f,
                    "  \"brdf\": {\"rays\": %ld, \"lost\": %ld, \"capped\": %ld, \"albedo_single\": %.8g, "
                    "\"albedo_model\": %s, \"albedo_model_height_correlated\": %s, \"albedo_all\": %.8g, "
                    "\"l2_single\": %s, \"l2_single_height_correlated\": %s, \"l2_all\": %s},\n",
                    br.rays, br.lost, br.capped, e_single, jnum(b3, e_model), jnum(b1, e_hc), e_all,
                    jnum(b4, l2_single), jnum(b6, l2_hc), jnum(b5, l2_all));
        else fprintf(f.f, "  \"brdf\": null,\n");
        fprintf(f.f, "  \"bins\": [");
    } else {
        fprintf(f.f, "# ggx microsurface measure: %s, %zu x %zu, view theta %.4g, phi %.4g degrees\n\n", o.heightfield,
                n, n, theta, phi);
        fprintf(f.f, "%ld rays, %ld missed; the facets' slope covariance %.6g, %.6g, %.6g\n\n", r.rays, r.missed,
                r.slope_cov[0], r.slope_cov[1], r.slope_cov[2]);
        fprintf(f.f,
                "| G1(v) | value |\n|---|---|\n| the facets (exact) | %.6f |\n| Smith, Beckmann of the facets' "
                "covariance | %.6f |\n| Smith, GGX %s (ggx_g1_smith) | %.6f |\n\n",
                r.g1, g_b, given ? "given" : "fitted", g_ggx);
        if (skewed) {
            fprintf(f.f,
                    "skewed: %s; the facets off the risers have the mean slope %.6g, %.6g; the model's t = %.6g, "
                    "%.6g\n\n",
                    o.tilted   ? "a tilted patch"
                    : o.risers ? "a sawtooth"
                               : "periodic",
                    r.slope_mean[0], r.slope_mean[1], ts[0], ts[1]);
            fprintf(f.f,
                    "| G1(v) of the facets off the risers | value |\n|---|---|\n| traced | %.6f |\n"
                    "| eq 6 with its min (ggx_g1) | %.6f |\n| Smith form of eq 32 (ggx_g1_smith) | %.6f |\n"
                    "| vertical facets (Walter's remedy, Smith's masking) | %.6f |\n"
                    "| tilted base (ggx_g1_tilted) | %.6f |\n"
                    "| sawtooth (ggx_g1_risers) | %.6f |\n",
                    g1v, g_eq6, g_ggx, g_vf, g_tb, g_saw);
            if (r.riser_area > 0.0)
                fprintf(f.f, "| the risers' visible share (projected area %.6f) | %.6f |\n", r.riser_area, g_riser);
            fprintf(f.f, "\n");
        }
        if (cr.dof > 0)
            fprintf(f.f,
                    "visible normals of %ld rays against ggx_pdf_vndf of the %s shape (eq 33): chi-square %.6g on %d "
                    "degrees of freedom (%.3g per degree), p = %.3g\n\n",
                    vrays, given ? "given" : "fitted", cr.stat, cr.dof, cr.stat / cr.dof, cr.pvalue);
        else fprintf(f.f, "visible normals of %ld rays: too few for a chi-square against ggx_pdf_vndf\n\n", vrays);
        if (!brdf) fprintf(f.f, "the BRDF is not measured on a tilted patch\n\n");
        else
            fprintf(f.f,
                    "the BRDF with F = 1 from the light at the view, %ld rays (%ld lost, %ld still bouncing "
                    "after %d), "
                    "%d x %d bins:\n\n| | traced | model | relative L2 of the BRDF over the bins |\n|---|---|---|---|\n"
                    "| single scattering: albedo | %.5f | %.5f (ggx_albedo; height-correlated: %.5f) | %.4f "
                    "(ggx_brdf_eval; with the height-correlated G2: %.4f) |\n"
                    "| all bounces: albedo | %.5f | 1 (F = 1) | %.4f (ggx_brdf_compensated_eval) |\n\n",
                    br.rays, br.lost, br.capped, bounces, BR, BS, e_single, e_model, e_hc, l2_single, l2_hc, e_all,
                    l2_all);
        fprintf(
            f.f,
            "| sin^2 theta_m | phi_m, degrees | projected area | traced G1(v, m) | / G1(v) |\n|---|---|---|---|---|\n");
    }
    int first = 1;
    for (int b = 0; b < r.rings * r.sectors; b++) {
        if (!(r.area[b] > 1e-4 * v[2])) continue; /* bins with under 1e-4 of the projected area: too few rays */
        int ring = b / r.sectors, sec = b % r.sectors;
        double g = r.visible[b] / r.area[b];
        if (json)
            fprintf(f.f, "%s\n    {\"ring\": %d, \"sector\": %d, \"area\": %.8g, \"g1\": %.8g}", first ? "" : ",", ring,
                    sec, r.area[b], g);
        else
            fprintf(f.f, "| %.2f-%.2f | %.0f-%.0f | %.5f | %.5f | %.4f |\n", (double)ring / r.rings,
                    (double)(ring + 1) / r.rings, 360.0 * sec / r.sectors, 360.0 * (sec + 1) / r.sectors, r.area[b], g,
                    g / g1v);
        first = 0;
    }
    if (json) fprintf(f.f, "\n  ]\n}\n");
    out_close(&f);
    ms_g1_free(&r);
    ms_brdf_free(&br);
    ms_tracer_free(t);
    free(h);
    return 0;
}

int cmd_microsurface(int argc, char **argv)
{
    if (argc < 3 || strcmp(argv[2], "--help") == 0 || strcmp(argv[2], "-h") == 0) {
        printf("usage: ggx microsurface generate|measure|figure [options]   (ggx microsurface generate --help, ...)\n\n"
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
    die("microsurface: unknown subcommand '%s' (generate, measure, figure)", argv[2]);
    return 2;
}
