/* ggx check: normalisation, chi-square and Jacobian checks of samplers of normals. SPDX-License-Identifier: MIT */
#include <math.h>

#include "chi2.h"
#include "cli.h"

typedef struct check_ctx {
    normal_keys keys; /* first: the chi-square key and density come from normal_keys_* */
    const ggx_sampler_info *smp;
    long drawn, total;
    int progress;
} check_ctx;

static int check_draw(void *vc, rng *r, ggx_vec3 *m)
{
    check_ctx *c = vc;
    double pdf, w;
    int ok = draw_sample(c->smp, c->keys.s, c->keys.v, NULL, 0, r, m, &pdf, &w);
    if (c->progress && (++c->drawn & 0xFFFF) == 0) progress_show(c->smp->name, c->drawn, c->total);
    return ok || t_dot(*m, *m) > 0.5; /* a normal with pdf 0 is still a sample: the harness flags it */
}

static double check_integrand(ggx_vec3 m, void *vc)
{
    const normal_keys *k = vc;
    return k->pdf(k->s, k->v, m);
}

void require_check_n(long n)
{
    if (n < CHECK_MIN_N) die("-n: the chi-square test needs at least %d samples (%ld given)", CHECK_MIN_N, n);
}

check_result run_check(const ggx_shape *s, ggx_vec3 view, const ggx_sampler_info *smp, long n, unsigned long long seed,
                       double alpha, int progress)
{
    check_result res = {0, 1, NAN, 0, 0};
    check_ctx c = {{s, view, smp->pdf}, smp, 0, n, progress};
    /* normalisation of the pdf the sampler claims; a visible-normal pdf lives on the half facing the view */
    int ndf = smp->family == GGX_FAMILY_NDF;
    res.norm_error = fabs(quad_hemisphere(s, check_integrand, &c, ndf ? NULL : &view, ndf ? 0 : 1, 1e-10, NULL) - 1.0);
    /* chi-square */
    chi2_problem p = {smp->name, 1, check_draw, normal_keys_key, normal_keys_density, &c};
    /* 100 x 200 cells for 10^6 samples; fewer for smaller n, so that cells expect about 50 samples */
    int nt = (int)fmin(100.0, fmax(4.0, floor(sqrt((double)n / 100.0))));
    chi2_result r = chi2_run_quiet(&p, n, nt, 2 * nt, seed, alpha); /* ggx check reports in its table */
    if (progress) progress_end(smp->name, n);
    res.pvalue = r.pvalue;
    res.zero_hits = r.zero_cell_hits;
    /* Jacobian |dm/du| = 1 / pdf by central differences at 200 points away from the edges and seams, for the
     * samplers that map the unit square (rejection samplers do not) */
    if (smp->sample) {
        rng g = {seed ^ 0x5bd1e995ull};
        double worst = 0.0;
        int done = 0;
        for (int i = 0; i < 2000 && done < 200; i++) {
            double u1 = 0.02 + 0.96 * rng_uniform(&g), u2 = 0.02 + 0.96 * rng_uniform(&g), h = 1e-6;
            if (fabs(fabs(2 * u1 - 1) - fabs(2 * u2 - 1)) < 0.02 || fabs(2 * u1 - 1) < 0.02 || fabs(2 * u2 - 1) < 0.02)
                continue;
#define MAP(a, b) smp->sample(s, view, a, b)
            ggx_vec3 m = MAP(u1, u2);
            double pdf = c.keys.pdf(s, view, m);
            if (m.z < 0.035 || (!ndf && t_dot(m, view) < 0.035) || !(pdf > 0)) continue;
            ggx_vec3 da = t_add(MAP(u1 + h, u2), t_scale(MAP(u1 - h, u2), -1));
            ggx_vec3 db = t_add(MAP(u1, u2 + h), t_scale(MAP(u1, u2 - h), -1));
#undef MAP
            ggx_vec3 cr = t_cross(da, db);
            worst = fmax(worst, fabs(sqrt(t_dot(cr, cr)) / (4 * h * h) * pdf - 1));
            done++;
        }
        res.jac_error = done > 0 ? worst : INFINITY; /* INFINITY: no point was away from the edges */
    }
    res.pass = res.pvalue >= alpha && res.zero_hits == 0 && res.norm_error < 1e-6 &&
               (isnan(res.jac_error) || isinf(res.jac_error) || res.jac_error < 1e-4);
    return res;
}

void print_check_header(FILE *f)
{
    fprintf(f, "%-15s %14s %12s %14s  %s\n", "sampler", "|norm - 1|", "chi2 p", "max|J pdf-1|", "verdict");
}
void print_check_row(FILE *f, const char *name, check_result r)
{
    char jac[32];
    if (isnan(r.jac_error)) snprintf(jac, sizeof jac, "%14s", "(rejection)");
    else if (isinf(r.jac_error)) snprintf(jac, sizeof jac, "%14s", "(no point)");
    else snprintf(jac, sizeof jac, "%14.2e", r.jac_error);
    fprintf(f, "%-15s %14.2e %12.4g %s  %s%s\n", name, r.norm_error, r.pvalue, jac, r.pass ? "pass" : "FAIL",
            r.zero_hits ? " (samples where the pdf is 0)" : "");
}

void check_help(void)
{
    printf("usage: ggx check [shape] [--sampler NAME] [--view DIR] [-n N] [--seed S] [--progress|--no-progress]\n\n"
           "Checks samplers of normals against their pdfs for your parameters: the pdf's normalisation by adaptive\n"
           "quadrature, a chi-square goodness-of-fit test with N samples (default 10^6) on 100 x 200 equal-area\n"
           "cells in sphere space (Sidak-corrected level 0.01 over the samplers checked), and the Jacobian\n"
           "|dm/du| = 1/pdf by finite differences. Without --sampler every normal sampler that applies is checked.\n"
           "Exit status 0 only if all pass (1 otherwise, 2 for bad input). A progress bar is shown on a "
           "terminal.\n\n");
    print_samplers(stdout);
    printf("\n");
}

int cmd_check(options *o, const ggx_shape *s)
{
    if (!o->have_view) parse_direction("40,0", &o->view);
    const ggx_sampler_info *list[GGX_SAMPLER_COUNT + 1];
    int nl = 0;
    if (o->sampler) {
        list[nl++] = find_sampler(o->sampler);
        if (list[0]->family == GGX_FAMILY_DIRECTION)
            die("ggx check checks samplers of normals; '%s' samples directions", o->sampler);
        require_domain(list[0], s);
    } else { /* the library's samplers of normals that apply to the shape (wrong-s only when asked for) */
        for (int i = 0; i < GGX_SAMPLER_COUNT; i++) {
            const ggx_sampler_info *smp = ggx_sampler_get((ggx_sampler_id)i);
            if (smp->family != GGX_FAMILY_DIRECTION && sampler_applies(smp, s)) list[nl++] = smp;
        }
    }
    for (int i = 0; i < nl; i++) require_view(list[i], o->view);
    int progress = progress_wanted(o->progress);
    long n = o->n > 0 ? o->n : 1000000;
    require_check_n(n);
    double alpha = chi2_sidak(nl);
    print_check_header(stdout);
    int all = 1, no_jac = 0;
    for (int i = 0; i < nl; i++) {
        check_result r = run_check(s, o->view, list[i], n, o->seed + (unsigned long long)i, alpha, progress);
        print_check_row(stdout, list[i]->name, r);
        out_flush_stdout(); /* a reader that has gone stops the run */
        all &= r.pass;
        no_jac |= isinf(r.jac_error);
    }
    printf("%s: %d sampler%s checked at level %.3g each\n", all ? "all pass" : "FAILED", nl, nl == 1 ? "" : "s", alpha);
    if (no_jac)
        printf("(no point): the Jacobian was not checked, every sampled normal being within 2 degrees of the horizon\n"
               "or of the view's silhouette, where finite differences do not resolve it\n");
    return all ? 0 : 1;
}
