/* SPDX-License-Identifier: MIT */
#include "samplers.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const sweep_shape SWEEP_SHAPES[] = {
    {"iso 0.05", {0.05, 0.05, 0, 0, 0}},
    {"iso 0.3", {0.3, 0.3, 0, 0, 0}},
    {"iso 1", {1.0, 1.0, 0, 0, 0}},
    {"iso 2", {2.0, 2.0, 0, 0, 0}},
    {"aniso 0.05:0.5", {0.05, 0.5, 0, 0, 0}},
    {"aniso 1:0.1 rot", {1.0, 0.1, 0, 0, 0.7}},
    {"skew 0.3:1", {0.3, 1.0, 0.5, -0.3, 0.4}},
    {"skew 0.05:0.3", {0.05, 0.3, -0.5, 0.5, 1.2}},
    {"skew 2:0.2", {2.0, 0.2, 0.3, 0.5, -0.8}},
};
const int SWEEP_NSHAPES = sizeof SWEEP_SHAPES / sizeof SWEEP_SHAPES[0];
const double SWEEP_VIEWS_DEG[] = {0.0, 30.0, 80.0, 89.5};
const int SWEEP_NVIEWS = sizeof SWEEP_VIEWS_DEG / sizeof SWEEP_VIEWS_DEG[0];
int chi2_runs_by[VARIANT_COUNT][GGX_SAMPLER_COUNT];

ggx_vec3 sweep_view(double theta_deg)
{
    if (theta_deg == 0.0) return t_vec(0, 0, 1);
    return t_dir(theta_deg * GGX_PI / 180.0, 0.7);
}

normal_ctx normal_ctx_of(const variant *var, ggx_sampler_id id, const ggx_shape *s, ggx_vec3 v)
{
    normal_ctx c;
    memset(&c, 0, sizeof c);
    c.s = s, c.v = v, c.var = var, c.id = id;
    return c;
}

static double uniform_cb(void *state) { return rng_uniform((rng *)state); }

/* Samplers of normals run in blocks of NORMAL_BLOCK with the random numbers drawn in the same order as one at a
 * time (u1, u2 of sample 0, then of sample 1, ...), so blocks change no result; rejection samplers and custom
 * samplers run one at a time. */
static int normal_draw(void *vc, rng *r, ggx_vec3 *m)
{
    normal_ctx *c = vc;
    c->draws++;
    if (c->custom) {
        double u1 = rng_uniform(r), u2 = rng_uniform(r);
        *m = c->custom(c->s, c->v, u1, u2);
    } else if (c->var->has(c->var, c->id) == 2) {
        unsigned t;
        *m = c->var->sample_reject(c->var, c->id, c->s, c->v, uniform_cb, r, &t);
        c->trials += t;
    } else {
        if (c->next == c->filled) {
            double u1[NORMAL_BLOCK], u2[NORMAL_BLOCK];
            ggx_vec3 v[NORMAL_BLOCK];
            for (int i = 0; i < NORMAL_BLOCK; i++) u1[i] = rng_uniform(r), u2[i] = rng_uniform(r), v[i] = c->v;
            c->var->sample(c->var, c->id, c->s, NORMAL_BLOCK, v, u1, u2, c->block);
            c->next = 0, c->filled = NORMAL_BLOCK;
        }
        *m = c->block[c->next++];
    }
    return t_dot(*m, *m) > 0.5;
}

static int normal_key(void *vc, ggx_vec3 m, int *region, ggx_vec3 *k)
{
    *region = 0;
    *k = key_of_normal(((const normal_ctx *)vc)->s, m);
    return 1;
}

/* The density of keys k = normalize(A^{-T} m): pdf(m(k)) d omega_m / d omega_k. */
static double normal_density(void *vc, int region, ggx_vec3 k)
{
    (void)region;
    const normal_ctx *c = vc;
    double j, pdf;
    ggx_vec3 m = normal_of_key(c->s, k, &j);
    if (c->pdf) pdf = c->pdf(c, m);
    else c->var->sampler_pdf(c->var, c->id, c->s, 1, &c->v, &m, &pdf);
    return pdf * j;
}

chi2_result chi2_run_scaled(const chi2_problem *p, uint64_t seed, double alpha)
{
    long n = chi2_samples();
    int nt, np;
    chi2_grid(n, &nt, &np);
    return chi2_run(p, n, nt, np, seed, alpha);
}

/* quiet: chi2_run_quiet, which writes no table (a negative control's rejection is its expected answer). */
static chi2_result run_normal(normal_ctx *c, const char *name, uint64_t seed, double alpha, int quiet)
{
    chi2_problem p = {name, 1, normal_draw, normal_key, normal_density, c};
    long n = chi2_samples();
    int nt, np;
    chi2_grid(n, &nt, &np);
    chi2_result r = quiet ? chi2_run_quiet(&p, n, nt, np, seed, alpha) : chi2_run(&p, n, nt, np, seed, alpha);
    if (!c->custom) chi2_runs_by[variant_index(c->var)][c->id]++;
    return r;
}

chi2_result run_normal_chi2_unchecked(normal_ctx *c, const char *name, uint64_t seed)
{
    return run_normal(c, name, seed, test_chi2_level(), 1);
}

chi2_result run_normal_chi2(normal_ctx *c, const char *name, uint64_t seed, double *min_p)
{
    double alpha = test_chi2_level();
    chi2_result r = run_normal(c, name, seed, alpha, 0);
    CHECK(r.zero_cell_hits == 0, "%s: %ld samples where the pdf is zero", name, r.zero_cell_hits);
    CHECK(chi2_accepts(r.pvalue), "%s: chi2 %.1f, dof %d, p = %.3g < %.3g (histogram in chi2_*.csv)", name, r.stat,
          r.dof, r.pvalue, alpha);
    if (min_p && r.pvalue < *min_p) *min_p = r.pvalue;
    return r;
}

/* One sample of sampler id of var at (u1, u2) (a rejection sampler: from a fixed stream). */
static ggx_vec3 sample_once(const variant *var, ggx_sampler_id id, const ggx_shape *s, ggx_vec3 v, double u1, double u2)
{
    ggx_vec3 m;
    if (var->has(var, id) == 2) {
        rng r = {1};
        unsigned t;
        return var->sample_reject(var, id, s, v, uniform_cb, &r, &t);
    }
    var->sample(var, id, s, 1, &v, &u1, &u2, &m);
    return m;
}

int chi2_sweep(const variant *var, unsigned families, const int *shapes, int nshapes, const int *views, int nviews,
               uint64_t seed_base, double *min_p)
{
    int runs = 0, k = -1;
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *info = ggx_sampler_get((ggx_sampler_id)id);
        if (!(families & FAMILY_BIT(info->family))) continue;
        k++;
        if (!var->has(var, (ggx_sampler_id)id)) continue;
        int ndf = info->family == GGX_FAMILY_NDF;
        double acc_sum = 0.0;
        int acc_n = 0;
        for (int a = 0; a < nshapes; a++) {
            const int i = shapes[a];
            ggx_shape s;
            make_shape(&s, SWEEP_SHAPES[i].p);
            if (info->domain == GGX_DOMAIN_UNSKEWED && s.kind == GGX_SHAPE_SKEWED) {
                /* Outside its domain the sampler returns the zero vector (pdf 0). */
                ggx_vec3 m = sample_once(var, (ggx_sampler_id)id, &s, sweep_view(30.0), 0.3, 0.6);
                CHECK(m.x == 0 && m.y == 0 && m.z == 0, "%s %s on the skewed shape %s must return 0", var->name,
                      info->name, SWEEP_SHAPES[i].name);
                continue;
            }
            for (int b = 0; b < (ndf ? 1 : nviews); b++) {
                const int j = ndf ? 0 : views[b];
                normal_ctx c = normal_ctx_of(var, (ggx_sampler_id)id, &s, sweep_view(SWEEP_VIEWS_DEG[j]));
                char name[160];
                if (ndf) snprintf(name, sizeof name, "%s ndf %s, %s", var->name, info->name, SWEEP_SHAPES[i].name);
                else
                    snprintf(name, sizeof name, "%s vndf %s, %s, view %g", var->name, info->name, SWEEP_SHAPES[i].name,
                             SWEEP_VIEWS_DEG[j]);
                uint64_t seed = seed_base + 100 * (uint64_t)k + (uint64_t)(ndf ? i : 10 * i + j);
                run_normal_chi2(&c, name, seed, min_p);
                runs++;
                if (c.trials) acc_sum += (double)c.draws / (double)c.trials, acc_n++;
            }
        }
        if (acc_n)
            printf("%s %s: mean acceptance rate %.3f over %d shape/view pairs\n", var->name, info->name,
                   acc_sum / acc_n, acc_n);
    }
    return runs;
}

int sampler_transmits(const ggx_sampler_info *info)
{
    ggx_shape s;
    make_shape(&s, SWEEP_SHAPES[1].p);
    ggx_vec3 v = sweep_view(30.0), w;
    CHECK(ggx_refract(v, t_vec(0, 0, 1), 1.5, &w), "refraction through n");
    return info->pdf_direction(&s, 1.5, v, w) > 0;
}

void check_chi2_coverage(const variant *var, unsigned families)
{
    int vi = variant_index(var), covered = 0;
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *info = ggx_sampler_get((ggx_sampler_id)id);
        if (!(families & FAMILY_BIT(info->family))) continue;
        /* the exported API has every registered sampler: the registry gives its functions */
        if (var == VARIANT_EXPORTED)
            CHECK(var->has(var, (ggx_sampler_id)id), "registry sampler %s has no function in the exported table",
                  info->name);
        if (!var->has(var, (ggx_sampler_id)id)) continue;
        CHECK(chi2_runs_by[vi][id] > 0, "%s: registry sampler %s (family %d) got no chi-square run", var->name,
              info->name, (int)info->family);
        covered++;
    }
    printf("%s: %d registry samplers covered by chi-square runs\n", var->name, covered);
}

enum { BT = 50, BP = 32, ST = 100, SP = 8 };
double binned_chi2(const binned_problem *p, uint64_t seed, int *dof)
{
    static _Thread_local double obs[2 * BT * BP], ex[2 * BT * BP];
    int nb = p->sides * BT * BP;
    long n = chi2_samples();
    for (int b = 0; b < nb; b++) obs[b] = ex[b] = 0;
    rng r = {seed};
    for (long k = 0; k < n; k++) {
        ggx_vec3 w;
        if (!p->draw(p->ctx, &r, &w)) continue;
        int side = w.z < 0 && p->sides == 2;
        double t = w.z * w.z, phi = atan2(w.y, w.x) + GGX_PI;
        int bt = (int)(t * BT), bp = (int)(phi / (2 * GGX_PI) * BP);
        bt = bt < BT ? bt : BT - 1;
        bp = bp < BP ? bp : BP - 1;
        obs[(side * BT + bt) * BP + bp]++;
    }
    for (int side = 0; side < p->sides; side++)
        for (int bt = 0; bt < BT; bt++)
            for (int bp = 0; bp < BP; bp++) {
                double sum = 0;
                for (int i = 0; i < ST; i++) {
                    double t = (bt + (i + 0.5) / ST) / BT, mu = sqrt(t), st = sqrt(1 - t);
                    for (int j = 0; j < SP; j++) {
                        double phi = (bp + (j + 0.5) / SP) / BP * 2 * GGX_PI - GGX_PI;
                        ggx_vec3 w = t_vec(st * cos(phi), st * sin(phi), side ? -mu : mu);
                        sum += p->pdf(p->ctx, w) / (2 * mu); /* dw = dt dphi / (2 mu) */
                    }
                }
                ex[(side * BT + bt) * BP + bp] = (double)n * sum / (ST * SP) * (1.0 / BT) * (2 * GGX_PI / BP);
            }
    double stat = 0, po = 0, pe = 0;
    int bins = 0;
    for (int b = 0; b < nb; b++) {
        if (ex[b] < 5) {
            po += obs[b];
            pe += ex[b];
            continue;
        }
        stat += (obs[b] - ex[b]) * (obs[b] - ex[b]) / ex[b];
        bins++;
    }
    if (pe >= 5) {
        stat += (po - pe) * (po - pe) / pe;
        bins++;
    } else {
        CHECK(po <= pe + 5 * sqrt(pe) + 5, "pooled bins: %g observed, %g expected", po, pe);
    }
    *dof = bins - 1;
    return chi2_pvalue(stat, *dof);
}

typedef struct hemi_ctx {
    double (*f)(ggx_vec3 w, void *ctx);
    void *ctx;
    double theta;
    int below;
} hemi_ctx;

static double hemi_phi(double phi, void *vc)
{
    hemi_ctx *c = vc;
    ggx_vec3 w = t_dir(c->theta, phi);
    if (c->below) w.z = -w.z;
    return c->f(w, c->ctx) * cos(c->theta) * sin(c->theta);
}

static double hemi_theta(double theta, void *vc)
{
    hemi_ctx *c = vc;
    c->theta = theta;
    double sum = 0;
    for (int k = 0; k < 8; k++) sum += quad_adapt(hemi_phi, c, k * GGX_PI / 4, (k + 1) * GGX_PI / 4, 1e-9);
    return sum;
}

double hemisphere_cos_quad(double (*f)(ggx_vec3 w, void *ctx), void *ctx, int below)
{
    hemi_ctx c = {f, ctx, 0, below};
    double sum = 0;
    for (int k = 0; k < 8; k++) sum += quad_adapt(hemi_theta, &c, k * GGX_PI / 16, (k + 1) * GGX_PI / 16, 1e-8);
    return sum;
}
