/* The subcommands of the ggx command. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "audit.h"
#include "chi2.h"
#include "cli.h"


const sampler_info SAMPLERS[] = {
    {"stretch", 0, ggx_sample_ndf_stretch, NULL, NULL, "NDF: cosine hemisphere + elliptic stretch (Engstad)"},
    {"ellipse", 0, ggx_sample_ndf_ellipse, NULL, NULL, "NDF: projected ellipse lifted to the ellipsoid (blog Part 2)"},
    {"inversion", 0, ggx_sample_ndf_inversion, NULL, NULL, "NDF: closed-form theta, phi (unskewed shapes only)"},
    {"visible", 0, ggx_sample_ndf_visible, NULL, NULL, "NDF: visible-normal sampling from n (any shape)"},
    {"caps", 1, NULL, ggx_sample_vndf_caps, NULL, "VNDF: spherical caps (default)"},
    {"crescent", 1, NULL, ggx_sample_vndf_crescent, NULL, "VNDF: Walter version 3, concentric disk"},
    {"crescent-polar", 1, NULL, ggx_sample_vndf_crescent_polar, NULL, "VNDF: Walter version 3, polar disk"},
    {"heitz", 1, NULL, ggx_sample_vndf_heitz, NULL, "VNDF: Heitz / Engstad five steps"},
    {"walter-v1", 2, NULL, NULL, ggx_sample_vndf_walter_v1, "VNDF: Walter version 1 (rejection, bounding sphere)"},
    {"walter-v2", 2, NULL, NULL, ggx_sample_vndf_walter_v2, "VNDF: Walter version 2 (rejection, sphere space)"},
    {"brdf", 3, NULL, NULL, NULL, "directions: reflection sampling (eq 47-50), view = wi"},
    {"bsdf", 4, NULL, NULL, NULL, "directions: rough dielectric (Walter 2007), view = known direction, --eta"},
    {"wrong-s", 1, NULL, verify_crescent_blog_s, NULL, "deliberately WRONG VNDF sampler (blog's s from A^-T n), to test ggx check"},
};
const int NSAMPLERS = sizeof SAMPLERS / sizeof SAMPLERS[0];

const sampler_info *find_sampler(const char *name)
{
    for (int i = 0; i < NSAMPLERS; i++)
        if (strcmp(SAMPLERS[i].name, name) == 0) return &SAMPLERS[i];
    die("unknown sampler '%s' (see ggx sample --help)", name);
}

static void print_samplers(FILE *f)
{
    fprintf(f, "samplers:\n");
    for (int i = 0; i < NSAMPLERS; i++) fprintf(f, "  %-15s %s\n", SAMPLERS[i].name, SAMPLERS[i].help);
}

static const char SHAPE_HELP[] =
    "shape (one syntax for every subcommand):\n"
    "  --alpha AX[,AY]       roughness (default 0.15,0.5); one value for isotropic\n"
    "  --skew TX,TY          skew angles theta_x, theta_y in degrees (default 0,0)\n"
    "  --rotate TZ           rotation of the anisotropy in the tangent plane, degrees (default 0)\n"
    "  --matrix a,b,c,d,e,f,g,h,i   any invertible A, row-major (replaces the three above)\n"
    "directions are THETA,PHI in degrees or X,Y,Z (normalised); n = +z, pointing away from the surface\n";

#define SHAPE_OPTS "alpha,skew,rotate,matrix"

static double uniform_cb(void *st) { return rng_uniform((rng *)st); }

/* ---------------------------------------------------------------- eval */

int cmd_eval(int argc, char **argv)
{
    options o;
    parse_options(argc, argv, 2, &o, SHAPE_OPTS ",wi,wo,fresnel,eta,format,out");
    if (o.help) {
        printf("usage: ggx eval [shape] [--wi DIR] [--wo DIR]... [--fresnel F] [--eta ETA] [--format csv|json] [--out FILE]\n\n"
               "Evaluates the model for one incident direction wi and one or more outgoing directions wo (defaults:\n"
               "wi = 40,0 and wo = 0,0 40,180 60,180 20,90). Columns: the directions, the half vector h, D(h), G1(wi,h),\n"
               "G1(wo,h), G = G1 G1, the height-correlated G2, Lambda(wi), Lambda(wo), the VNDF pdf of h for wi, the\n"
               "reflection pdf of wo, the BRDF, and with --eta the rough-dielectric BSDF f(wi -> wo) and its pdf.\n"
               "--fresnel one | dielectric:ETA | conductor:ETA,K | schlick:F0 (default one)\n\n%s", SHAPE_HELP);
        return 0;
    }
    ggx_shape s;
    shape_from_options(&o, &s);
    ggx_fresnel f = fresnel_from_options(&o);
    if (!o.have_wi) parse_direction("40,0", &o.wi);
    if (o.nwo == 0) {
        const char *d[] = {"0,0", "40,180", "60,180", "20,90"};
        for (int i = 0; i < 4; i++) parse_direction(d[i], &o.wo[o.nwo++]);
    }
    int json = 0;
    if (o.format && strcmp(o.format, "json") == 0) json = 1;
    else if (o.format && strcmp(o.format, "csv") != 0) die("--format: '%s' is not csv or json", o.format);
    static const char *cols[] = {"wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z", "h_x", "h_y", "h_z", "D", "G1_wi",
                                 "G1_wo", "G", "G2_hc", "lambda_wi", "lambda_wo", "pdf_vndf", "pdf_brdf", "brdf",
                                 "bsdf", "pdf_bsdf"};
    int ncols = o.have_eta ? 21 : 19;
    out_file out;
    out_open(&out, o.out);
    if (json) fprintf(out.f, "[\n");
    else
        for (int c = 0; c < ncols; c++) fprintf(out.f, "%s%s", cols[c], c + 1 < ncols ? "," : "\n");
    for (int k = 0; k < o.nwo; k++) {
        ggx_vec3 wi = o.wi, wo = o.wo[k], h = ggx_half_reflect(wi, wo);
        double v[21] = {wi.x, wi.y, wi.z, wo.x, wo.y, wo.z, h.x, h.y, h.z, ggx_ndf(&s, h), ggx_g1(&s, wi, h),
                        ggx_g1(&s, wo, h), ggx_g2(&s, wi, wo, h), ggx_g2_height_correlated(&s, wi, wo, h),
                        ggx_lambda(&s, wi), ggx_lambda(&s, wo), ggx_pdf_vndf(&s, wi, h), ggx_pdf_brdf(&s, wi, wo),
                        ggx_brdf_eval(&s, &f, wi, wo), 0, 0};
        if (o.have_eta) {
            v[19] = ggx_bsdf_eval(&s, o.eta, wi, wo, GGX_RADIANCE);
            v[20] = ggx_pdf_bsdf(&s, o.eta, wo, wi);
        }
        if (json) fprintf(out.f, "  {");
        for (int c = 0; c < ncols; c++) {
            if (json) fprintf(out.f, "\"%s\": %.17g%s", cols[c], v[c], c + 1 < ncols ? ", " : "");
            else fprintf(out.f, "%.17g%s", v[c], c + 1 < ncols ? "," : "\n");
        }
        if (json) fprintf(out.f, "}%s\n", k + 1 < o.nwo ? "," : "");
    }
    if (json) fprintf(out.f, "]\n");
    out_close(&out);
    return 0;
}

/* ---------------------------------------------------------------- sample */

/* One sample of any sampler: the direction, its pdf and weight (1 for normal samplers). Returns 0 when invalid. */
static int draw_one(const sampler_info *smp, const ggx_shape *s, ggx_vec3 view, const ggx_fresnel *f, double eta,
                    rng *r, ggx_vec3 *w, double *pdf, double *weight)
{
    double u1 = rng_uniform(r), u2 = rng_uniform(r);
    *weight = 1.0;
    if (smp->kind == 3 || smp->kind == 4) {
        ggx_sample x = smp->kind == 3 ? ggx_sample_brdf(s, f, view, u1, u2)
                                      : ggx_sample_bsdf(s, eta, view, u1, u2, rng_uniform(r), GGX_RADIANCE);
        *w = x.w, *pdf = x.pdf, *weight = x.weight;
        return x.event != GGX_EVENT_INVALID;
    }
    if (smp->kind == 0) *w = smp->ndf(s, u1, u2);
    else if (smp->kind == 1) *w = smp->vndf(s, view, u1, u2);
    else {
        unsigned t;
        *w = smp->reject(s, view, uniform_cb, r, &t);
    }
    *pdf = smp->kind == 0 ? ggx_pdf_ndf(s, *w) : ggx_pdf_vndf(s, view, *w);
    if (!(*pdf > 0)) *weight = 0.0;
    return *pdf > 0;
}

int cmd_sample(int argc, char **argv)
{
    options o;
    parse_options(argc, argv, 2, &o, SHAPE_OPTS ",sampler,view,n,seed,format,out,fresnel,eta");
    if (o.help) {
        printf("usage: ggx sample [shape] [--sampler NAME] [--view DIR] [-n N] [--seed S] [--format csv|f32] [--out FILE]\n\n"
               "Draws N samples (default 1000) with columns x,y,z,pdf,weight. For normal samplers the weight is 1;\n"
               "for brdf and bsdf it is f |w.n| / pdf. Invalid samples are written as 0,0,0,0,0. --format f32 writes\n"
               "5 little-endian float32 per sample. --view is the view / known direction (default 40,0).\n\n");
        print_samplers(stdout);
        printf("\n%s", SHAPE_HELP);
        return 0;
    }
    ggx_shape s;
    shape_from_options(&o, &s);
    const sampler_info *smp = find_sampler(o.sampler ? o.sampler : "caps");
    if (!o.have_view) parse_direction("40,0", &o.view);
    if ((smp->kind >= 1 && smp->kind <= 3) && !(o.view.z > 0))
        die("--view must be above the horizon for sampler '%s'", smp->name);
    if (smp->kind == 4 && o.view.z == 0) die("--view must not lie on the horizon for sampler 'bsdf'");
    ggx_fresnel f = fresnel_from_options(&o);
    int f32 = 0;
    if (o.format && strcmp(o.format, "f32") == 0) f32 = 1;
    else if (o.format && strcmp(o.format, "csv") != 0) die("--format: '%s' is not csv or f32", o.format);
    if (f32 && !o.out) die("--format f32 needs --out FILE");
    long n = o.n > 0 ? o.n : 1000;
    rng r = {o.seed};
    out_file out;
    out_open(&out, o.out);
    if (!f32) fprintf(out.f, "x,y,z,pdf,weight\n");
    for (long i = 0; i < n; i++) {
        ggx_vec3 w;
        double pdf, weight;
        if (!draw_one(smp, &s, o.view, &f, o.eta, &r, &w, &pdf, &weight)) w = t_vec(0, 0, 0), pdf = 0, weight = 0;
        if (f32) {
            float v[5] = {(float)w.x, (float)w.y, (float)w.z, (float)pdf, (float)weight};
            fwrite(v, sizeof v, 1, out.f);
        } else {
            fprintf(out.f, "%.17g,%.17g,%.17g,%.17g,%.17g\n", w.x, w.y, w.z, pdf, weight);
        }
    }
    out_close(&out);
    return 0;
}

/* ---------------------------------------------------------------- plot */

static const char *default_ext(figure_kind k) { return (k == FIG_GRID || k == FIG_GRID_SIDE) ? "svg" : "png"; }

int cmd_plot(int argc, char **argv)
{
    options o;
    parse_options(argc, argv, 2, &o, SHAPE_OPTS ",figure,view,sampler,size,log,out");
    if (o.help) {
        printf("usage: ggx plot [shape] [--figure NAME] [--view DIR] [--sampler NAME] [--size PX] [--log] [--out FILE]\n\n"
               "Figures: ndf, ndf-side (pdf D(m) m.n from above / from the side, PNG with a colour bar), vndf,\n"
               "vndf-side (the visible-normal pdf for --view, default 75,0), grid, grid-side (the 10 x 10 equal-area\n"
               "grid of the unit square mapped onto the hemisphere by --sampler, default stretch, SVG). --log uses a\n"
               "logarithmic colour scale over four decades (for sharp lobes). --size in pixels (default 512).\n"
               "--out defaults to FIGURE.png or FIGURE.svg in the current folder.\n\n%s", SHAPE_HELP);
        return 0;
    }
    ggx_shape s;
    shape_from_options(&o, &s);
    figure_kind k = figure_from_name(o.figure ? o.figure : "ndf");
    if (!o.have_view) parse_direction("75,0", &o.view);
    if ((k == FIG_VNDF || k == FIG_VNDF_SIDE) && !(o.view.z > 0)) die("--view must be above the horizon for a VNDF figure");
    const sampler_info *smp = find_sampler(o.sampler ? o.sampler : "stretch");
    if (smp->kind == 1 && !(o.view.z > 0)) die("--view must be above the horizon for sampler '%s'", smp->name);
    char path[512], title[128];
    if (o.out) snprintf(path, sizeof path, "%s", o.out);
    else snprintf(path, sizeof path, "%s.%s", o.figure ? o.figure : "ndf", default_ext(k));
    const char *want = (k == FIG_GRID || k == FIG_GRID_SIDE) ? ".svg" : ".png";
    size_t pl = strlen(path);
    if (pl < 4 || strcmp(path + pl - 4, want) != 0) die("--out: figure '%s' is written as %s", o.figure ? o.figure : "ndf", want);
    snprintf(title, sizeof title, "%s  alpha %.3g,%.3g", o.figure ? o.figure : "ndf", o.alpha[0], o.alpha[1]);
    draw_figure(k, &s, o.view, smp, o.size, o.log_scale, title, path);
    fprintf(stderr, "ggx: wrote %s\n", path);
    return 0;
}

/* ---------------------------------------------------------------- check */

typedef struct check_ctx {
    normal_keys keys; /* first: the chi-square key and density come from normal_keys_* */
    const sampler_info *smp;
    long drawn, total;
    int progress;
} check_ctx;

static void progress_bar(check_ctx *c)
{
    int width = 40, filled = (int)(width * c->drawn / c->total);
    fprintf(stderr, "\r  %-14s [", c->smp->name);
    for (int i = 0; i < width; i++) fputc(i < filled ? '#' : '.', stderr);
    fprintf(stderr, "] %3d%%", (int)(100 * c->drawn / c->total));
    fflush(stderr);
}


static int check_draw(void *vc, rng *r, ggx_vec3 *m)
{
    check_ctx *c = vc;
    double pdf, w;
    int ok = draw_one(c->smp, c->keys.s, c->keys.v, NULL, 0, r, m, &pdf, &w);
    if (c->progress && (++c->drawn & 0xFFFF) == 0) progress_bar(c);
    return ok || t_dot(*m, *m) > 0.5; /* a normal with pdf 0 is still a sample: the harness flags it */
}

static double check_integrand(ggx_vec3 m, void *vc)
{
    const normal_keys *k = vc;
    return k->pdf(k->s, k->v, m);
}

check_result run_check(const ggx_shape *s, ggx_vec3 view, const sampler_info *smp, long n, unsigned long long seed,
                       double alpha, int progress)
{
    check_result res = {0, 1, NAN, 0, 0};
    check_ctx c = {{s, view, smp->kind == 0 ? verify_pdf_ndf : ggx_pdf_vndf}, smp, 0, n, progress};
    /* normalisation of the pdf the sampler claims */
    res.norm_error = fabs(quad_hemisphere(s, check_integrand, &c, smp->kind == 0 ? NULL : &view, smp->kind == 0 ? 0 : 1,
                                          1e-10, NULL) - 1.0);
    /* chi-square */
    chi2_problem p = {smp->name, 1, check_draw, normal_keys_key, normal_keys_density, &c};
    /* 100 x 200 cells for 10^6 samples; fewer for smaller n, so that cells expect about 50 samples */
    int nt = (int)fmin(100.0, fmax(4.0, floor(sqrt((double)n / 100.0))));
    chi2_result r = chi2_run_quiet(&p, n, nt, 2 * nt, seed, alpha); /* ggx check reports in its table */
    if (progress) {
        c.drawn = n;
        progress_bar(&c);
        fputc('\n', stderr);
    }
    res.pvalue = r.pvalue;
    res.zero_hits = r.zero_cell_hits;
    /* Jacobian |dm/du| = 1 / pdf by central differences at 200 points away from the edges and seams */
    if (smp->kind <= 1) {
        rng g = {seed ^ 0x5bd1e995ull};
        double worst = 0.0;
        for (int i = 0, done = 0; i < 2000 && done < 200; i++) {
            double u1 = 0.02 + 0.96 * rng_uniform(&g), u2 = 0.02 + 0.96 * rng_uniform(&g), h = 1e-6;
            if (fabs(fabs(2 * u1 - 1) - fabs(2 * u2 - 1)) < 0.02 || fabs(2 * u1 - 1) < 0.02 || fabs(2 * u2 - 1) < 0.02) continue;
#define MAP(a, b) (smp->kind == 0 ? smp->ndf(s, a, b) : smp->vndf(s, view, a, b))
            ggx_vec3 m = MAP(u1, u2);
            double pdf = c.keys.pdf(s, view, m);
            if (m.z < 0.035 || (smp->kind == 1 && t_dot(m, view) < 0.035) || !(pdf > 0)) continue;
            ggx_vec3 da = t_add(MAP(u1 + h, u2), t_scale(MAP(u1 - h, u2), -1));
            ggx_vec3 db = t_add(MAP(u1, u2 + h), t_scale(MAP(u1, u2 - h), -1));
#undef MAP
            ggx_vec3 cr = t_cross(da, db);
            worst = fmax(worst, fabs(sqrt(t_dot(cr, cr)) / (4 * h * h) * pdf - 1));
            done++;
        }
        res.jac_error = worst;
    }
    res.pass = res.pvalue >= alpha && res.zero_hits == 0 && res.norm_error < 1e-6 &&
               (isnan(res.jac_error) || res.jac_error < 1e-4);
    return res;
}

static void print_check_header(FILE *f)
{
    fprintf(f, "%-15s %14s %12s %14s  %s\n", "sampler", "|norm - 1|", "chi2 p", "max|J pdf-1|", "verdict");
}
static void print_check_row(FILE *f, const char *name, check_result r)
{
    char jac[32];
    if (isnan(r.jac_error)) snprintf(jac, sizeof jac, "%14s", "(rejection)");
    else snprintf(jac, sizeof jac, "%14.2e", r.jac_error);
    fprintf(f, "%-15s %14.2e %12.4g %s  %s%s\n", name, r.norm_error, r.pvalue, jac, r.pass ? "pass" : "FAIL",
            r.zero_hits ? " (samples where the pdf is 0)" : "");
}

int cmd_check(int argc, char **argv)
{
    options o;
    parse_options(argc, argv, 2, &o, SHAPE_OPTS ",sampler,view,n,seed,progress,no-progress");
    if (o.help) {
        printf("usage: ggx check [shape] [--sampler NAME] [--view DIR] [-n N] [--seed S] [--progress|--no-progress]\n\n"
               "Checks samplers of normals against their pdfs for your parameters: the pdf's normalisation by adaptive\n"
               "quadrature, a chi-square goodness-of-fit test with N samples (default 10^6) on 100 x 200 equal-area\n"
               "cells in sphere space (Sidak-corrected level 0.01 over the samplers checked), and the Jacobian\n"
               "|dm/du| = 1/pdf by finite differences. Without --sampler every normal sampler that applies is checked.\n"
               "Exit status 0 only if all pass (1 otherwise, 2 for bad input). A progress bar is shown on a terminal.\n\n");
        print_samplers(stdout);
        printf("\n%s", SHAPE_HELP);
        return 0;
    }
    ggx_shape s;
    shape_from_options(&o, &s);
    if (!o.have_view) parse_direction("40,0", &o.view);
    const sampler_info *list[32];
    int nl = 0;
    if (o.sampler) {
        list[nl++] = find_sampler(o.sampler);
        if (list[0]->kind > 2) die("ggx check checks samplers of normals; '%s' samples directions", o.sampler);
    } else {
        for (int i = 0; i < NSAMPLERS; i++)
            if (SAMPLERS[i].kind <= 2 && strcmp(SAMPLERS[i].name, "wrong-s") != 0 &&
                !(SAMPLERS[i].ndf == ggx_sample_ndf_inversion && s.kind == GGX_SHAPE_SKEWED))
                list[nl++] = &SAMPLERS[i];
    }
    for (int i = 0; i < nl; i++)
        if (list[i]->kind >= 1 && !(o.view.z > 0)) die("--view must be above the horizon for sampler '%s'", list[i]->name);
    int progress = o.progress >= 0 ? o.progress : isatty(2);
    long n = o.n > 0 ? o.n : 1000000;
    double alpha = chi2_sidak(nl);
    print_check_header(stdout);
    int all = 1;
    for (int i = 0; i < nl; i++) {
        check_result r = run_check(&s, o.view, list[i], n, o.seed + (unsigned long long)i, alpha, progress);
        print_check_row(stdout, list[i]->name, r);
        fflush(stdout);
        all &= r.pass;
    }
    printf("%s: %d sampler%s checked at level %.3g each\n", all ? "all pass" : "FAILED", nl, nl == 1 ? "" : "s", alpha);
    return all ? 0 : 1;
}

/* ---------------------------------------------------------------- demo */

int cmd_demo(int argc, char **argv)
{
    options o;
    parse_options(argc, argv, 2, &o, "out,n,size");
    if (o.help) {
        printf("usage: ggx demo [--out DIR] [-n N] [--size PX]\n\n"
               "Draws the seeds' figures for alpha = (0.15, 0.5) and for the same shape skewed by theta_x = 15,\n"
               "theta_y = -10 degrees into DIR (default out/): the equal-area grid mapped by NDF sampling (top and\n"
               "side), the NDF pdf (top and side), the VNDF pdf for theta_v = 75 with phi_v = 0 and 90. Then checks\n"
               "every sampler for these shapes (N samples each, default 10^6) and prints the table.\n");
        return 0;
    }
    clock_t c0 = clock();
    const char *dir = o.out ? o.out : "out";
    ensure_dir(dir);
    int size = o.size == 512 ? 384 : o.size;
    struct {
        const char *prefix, *label;
        double tx, ty;
    } shapes[2] = {{"", "alpha 0.15,0.5", 0, 0}, {"skewed-", "skewed 15,-10", 15, -10}};
    ggx_vec3 v0, v90;
    parse_direction("75,0", &v0);
    parse_direction("75,90", &v90);
    char path[1024], title[128];
    const sampler_info *stretch = find_sampler("stretch");
    static const struct {
        figure_kind k;
        const char *name;
        int view;
    } figs[] = {{FIG_GRID, "grid-top.svg", 0},        {FIG_GRID_SIDE, "grid-side.svg", 0},
                {FIG_NDF, "ndf-top.png", 0},          {FIG_NDF_SIDE, "ndf-side.png", 0},
                {FIG_VNDF, "vndf-75-0.png", 0},       {FIG_VNDF, "vndf-75-90.png", 90}};
    printf("ggx demo: figures in %s/\n", dir);
    for (int k = 0; k < 2; k++) {
        ggx_shape s;
        if (ggx_shape_ellipsoid(&s, 0.15, 0.5, shapes[k].tx * DEG, shapes[k].ty * DEG, 0) != GGX_OK) die("demo shape");
        for (unsigned f = 0; f < sizeof figs / sizeof figs[0]; f++) {
            snprintf(path, sizeof path, "%s/%s%s", dir, shapes[k].prefix, figs[f].name);
            snprintf(title, sizeof title, "%s %s", shapes[k].label, figs[f].name);
            *strrchr(title, '.') = '\0';
            draw_figure(figs[f].k, &s, figs[f].view ? v90 : v0, stretch, size, 0, title, path);
            printf("  %s\n", path);
        }
    }
    long n = o.n > 0 ? o.n : 1000000;
    const char *names[] = {"stretch", "ellipse", "inversion", "visible", "caps", "crescent", "crescent-polar", "heitz", "walter-v2"};
    int nn = sizeof names / sizeof names[0], runs = 2 * nn - 1;
    double alpha = chi2_sidak(runs);
    printf("\nchecks (%ld samples each; VNDF for theta_v = 75, phi_v = 0; level %.2g per run):\n", n, alpha);
    int all = 1;
    for (int k = 0; k < 2; k++) {
        ggx_shape s;
        if (ggx_shape_ellipsoid(&s, 0.15, 0.5, shapes[k].tx * DEG, shapes[k].ty * DEG, 0) != GGX_OK) die("demo shape");
        printf("%s\n", shapes[k].label);
        print_check_header(stdout);
        for (int i = 0; i < nn; i++) {
            const sampler_info *smp = find_sampler(names[i]);
            if (smp->ndf == ggx_sample_ndf_inversion && s.kind == GGX_SHAPE_SKEWED) continue;
            check_result r = run_check(&s, v0, smp, n, 100 + (unsigned long long)i, alpha, 0);
            print_check_row(stdout, smp->name, r);
            fflush(stdout);
            all &= r.pass;
        }
    }
    printf("\n%s in %.1f s. Figures: %s/\n", all ? "all checks pass" : "SOME CHECKS FAILED",
           (double)(clock() - c0) / CLOCKS_PER_SEC, dir);
    return all ? 0 : 1;
}
