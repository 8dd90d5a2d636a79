/* Direction sampling: chi-square of reflection sampling (Walter eq 47-48) and rough-dielectric sampling against
 * their pdfs, the weight bound of eq 52, and the consistency of sample, pdf and weight. Directions are keyed by
 * their half vector in the sphere space of the shape (region 0: same side as the known direction, 1: other side).
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "samplers.h"

typedef struct dir_ctx {
    const ggx_shape *s;
    ggx_fresnel f;
    ggx_vec3 v; /* the known direction */
    double eta; /* 0: BRDF */
    double max_weight;
    long checked;
} dir_ctx;

static int dir_draw(void *vc, rng *r, ggx_vec3 *w)
{
    dir_ctx *c = vc;
    double u1 = rng_uniform(r), u2 = rng_uniform(r);
    ggx_sample smp;
    if (c->eta == 0.0) {
        smp = ggx_sample_brdf(c->s, &c->f, c->v, u1, u2);
    } else {
        smp = ggx_sample_bsdf(c->s, c->eta, c->v, u1, u2, rng_uniform(r), GGX_RADIANCE);
    }
    if (smp.event == GGX_EVENT_INVALID) {
        CHECK(smp.pdf == 0 && smp.weight == 0 && smp.w.x == 0 && smp.w.y == 0 && smp.w.z == 0, "invalid sample");
        return 0;
    }
    /* Every 16th sample: the reported pdf and weight agree with the public pdf and eval functions. */
    if ((c->checked++ & 15) == 0) {
        double pdf = c->eta == 0.0 ? ggx_pdf_brdf(c->s, c->v, smp.w) : ggx_pdf_bsdf(c->s, c->eta, c->v, smp.w);
        double f = c->eta == 0.0 ? ggx_brdf_eval(c->s, &c->f, c->v, smp.w)
                                 : ggx_bsdf_eval(c->s, c->eta, smp.w, c->v, GGX_RADIANCE);
        CHECK_CLOSE(smp.pdf, pdf, 1e-9, 0, "pdf of w (%g,%g,%g)", smp.w.x, smp.w.y, smp.w.z);
        CHECK_CLOSE(smp.weight, f * fabs(smp.w.z) / smp.pdf, 1e-9, 1e-300, "weight");
        CHECK_CLOSE(t_dot(smp.w, smp.w), 1.0, 1e-12, 0, "unit w");
    }
    if (smp.weight > c->max_weight) c->max_weight = smp.weight;
    *w = smp.w;
    return 1;
}

static ggx_vec3 half_of(const dir_ctx *c, ggx_vec3 w, int *region)
{
    *region = (w.z > 0) == (c->v.z > 0) ? 0 : 1;
    if (*region == 0) return ggx_half_reflect(c->v, w);
    double ev = c->v.z > 0 ? 1.0 : c->eta, ew = w.z > 0 ? 1.0 : c->eta;
    return ggx_half_refract(c->v, w, ev, ew);
}

static int dir_key(void *vc, ggx_vec3 w, int *region, ggx_vec3 *k)
{
    dir_ctx *c = vc;
    ggx_vec3 h = half_of(c, w, region);
    if (!(t_dot(h, h) > 0.5)) return 0;
    *k = key_of_normal(c->s, h);
    return 1;
}

/* Density of keys: pdf(w(h)) |d omega_w / d omega_h| |d omega_h / d omega_k|. */
static double dir_density(void *vc, int region, ggx_vec3 k)
{
    dir_ctx *c = vc;
    double jk;
    ggx_vec3 h = normal_of_key(c->s, k, &jk), w;
    if (!(h.z > 0)) return 0.0;
    if (region == 0) {
        w = ggx_reflect(c->v, h);
        if (!((w.z > 0) == (c->v.z > 0)) || w.z == 0 || t_dot(c->v, h) * (c->v.z > 0 ? 1 : -1) <= 0) return 0.0;
        double pdf = c->eta == 0.0 ? ggx_pdf_brdf(c->s, c->v, w) : ggx_pdf_bsdf(c->s, c->eta, c->v, w);
        return pdf / ggx_jacobian_reflect(w, h) * jk;
    }
    if (c->eta == 0.0) return 0.0;
    double ev = c->v.z > 0 ? 1.0 : c->eta, et = c->v.z > 0 ? c->eta : 1.0;
    if (!ggx_refract(c->v, h, et / ev, &w) || (w.z > 0) == (c->v.z > 0) || w.z == 0) return 0.0;
    double jr = ggx_jacobian_refract(c->v, w, h, ev, et);
    return jr > 0 ? ggx_pdf_bsdf(c->s, c->eta, c->v, w) / jr * jk : 0.0;
}

static chi2_result run_dir(dir_ctx *c, const char *name, uint64_t seed, double *min_p)
{
    chi2_problem p = {name, c->eta == 0.0 ? 1 : 2, dir_draw, dir_key, dir_density, c};
    double alpha = chi2_sidak(CHI2_SUITE_RUNS);
    chi2_result r = chi2_run_scaled(&p, seed, alpha);
    chi2_runs_done++;
    CHECK(r.zero_cell_hits == 0, "%s: %ld samples where the pdf is zero", name, r.zero_cell_hits);
    CHECK(r.pvalue >= alpha, "%s: chi2 %.1f, dof %d, p = %.3g", name, r.stat, r.dof, r.pvalue);
    if (r.pvalue < *min_p) *min_p = r.pvalue;
    return r;
}

/* Reflection sampling over the sweep; the weight never exceeds 1 (Walter eq 52) with F = 1 and with a conductor,
 * and equals G1(wo, m) F for unskewed shapes (eq 51 holds with equality). */
static void brdf_sampling(void **state)
{
    (void)state;
    double min_p = 1.0, max_w = 0.0, invalid_frac = 0.0;
    int runs = 0;
    for (int i = 0; i < SWEEP_NSHAPES; i++) {
        ggx_shape s;
        make_shape(&s, SWEEP_SHAPES[i].p);
        for (int j = 0; j < SWEEP_NVIEWS; j++) {
            dir_ctx c = {&s, {GGX_FRESNEL_ONE, 0, 0, 0}, sweep_view(SWEEP_VIEWS_DEG[j]), 0.0, 0.0, 0};
            if (j % 2) ggx_fresnel_conductor(&c.f, 0.2, 3.9);
            char name[128];
            snprintf(name, sizeof name, "brdf %s, view %g", SWEEP_SHAPES[i].name, SWEEP_VIEWS_DEG[j]);
            chi2_result r = run_dir(&c, name, 7000 + 10 * i + j, &min_p);
            runs++;
            CHECK(c.max_weight <= 1.0 + 1e-12, "%s: weight %.17g > 1 (eq 52)", name, c.max_weight);
            if (c.max_weight > max_w) max_w = c.max_weight;
            if ((double)r.invalid / 1e6 > invalid_frac) invalid_frac = (double)r.invalid / 1e6;
        }
    }
    rng r = {8};
    for (int i = 0; i < 20000; i++) {
        ggx_shape s;
        make_shape(&s, random_shape(&r, 0.0));
        ggx_fresnel one = {GGX_FRESNEL_ONE, 0, 0, 0};
        ggx_vec3 wi = random_view(&r);
        ggx_sample smp = ggx_sample_brdf(&s, &one, wi, rng_uniform(&r), rng_uniform(&r));
        if (smp.event == GGX_EVENT_INVALID) continue;
        ggx_vec3 m = ggx_half_reflect(wi, smp.w);
        CHECK_CLOSE(smp.weight, ggx_g1(&s, smp.w, m), 1e-9, 1e-15, "eq 51 equality when unskewed");
    }
    printf("brdf: %d chi-square runs, smallest p %.4g, largest weight %.15f, most samples below the horizon %.4f\n",
           runs, min_p, max_w, invalid_frac);
}

/* Rough dielectric: eta = 1.5 and 1/1.5, from outside and from inside, including total internal reflection
 * (from inside glass at 60 degrees, beyond the critical angle of 41.8 degrees). */
static void bsdf_sampling(void **state)
{
    (void)state;
    double min_p = 1.0;
    int runs = 0;
    const int shapes[] = {1, 4, 5, 6, 8};
    const double views[][2] = {{30, 1}, {80, 1}, {30, -1}, {60, -1}};
    const double etas[] = {1.5, 1 / 1.5};
    for (unsigned i = 0; i < sizeof shapes / sizeof shapes[0]; i++) {
        ggx_shape s;
        make_shape(&s, SWEEP_SHAPES[shapes[i]].p);
        for (unsigned j = 0; j < sizeof views / sizeof views[0]; j++) {
            for (unsigned e = 0; e < 2; e++) {
                ggx_vec3 v = sweep_view(views[j][0]);
                v.z *= views[j][1];
                dir_ctx c = {&s, {GGX_FRESNEL_ONE, 0, 0, 0}, v, etas[e], 0.0, 0};
                char name[128];
                snprintf(name, sizeof name, "bsdf %s, view %g%s, eta %.3f", SWEEP_SHAPES[shapes[i]].name, views[j][0],
                         views[j][1] < 0 ? " inside" : "", etas[e]);
                run_dir(&c, name, 9000 + 100 * i + 10 * j + e, &min_p);
                runs++;
            }
        }
    }
    printf("bsdf: %d chi-square runs, smallest p %.4g\n", runs, min_p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(brdf_sampling), cmocka_unit_test(bsdf_sampling)};
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    printf("chi-square runs in this program: %d\n", chi2_runs_done);
    return rc;
}
