/* Direction sampling: chi-square of every DIRECTION sampler of the registry (reflection sampling, Walter eq 47-48;
 * the rough dielectric) against its pdf, the weight bound of eq 52 for reflections, and the consistency of sample,
 * pdf and weight. Directions are keyed by their half vector in the sphere space of the shape (region 0: same side
 * as the known direction, 1: other side). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "samplers.h"

typedef struct dir_ctx {
    const ggx_sampler_info *info; /* a DIRECTION sampler of the registry */
    const ggx_shape *s;
    ggx_fresnel f;  /* for reflection sampling */
    ggx_vec3 v;     /* the known direction */
    double eta;     /* for the rough dielectric */
    int transmits;  /* the sampler's pdf is nonzero on the other side of the surface: keys in 2 regions */
    double max_weight;
    long checked;
} dir_ctx;

/* The BSDF value of a direction sampler's sample, for the check weight = f |w.n| / pdf. The registry has no
 * evaluation function, so a new direction sampler fails here until its evaluation is added. */
static double dir_eval(const dir_ctx *c, ggx_vec3 w)
{
    switch (c->info->id) {
    case GGX_SAMPLER_BRDF: return ggx_brdf_eval(c->s, &c->f, c->v, w);
    case GGX_SAMPLER_BSDF: return ggx_bsdf_eval(c->s, c->eta, w, c->v, GGX_RADIANCE);
    default: CHECK(0, "direction sampler %s: no evaluation known to this test", c->info->name); return 0.0;
    }
}

/* u3 (the choice between reflection and transmission) is drawn only for samplers that transmit, so that reflection
 * sampling uses the random numbers it always did. */
static int dir_draw(void *vc, rng *r, ggx_vec3 *w)
{
    dir_ctx *c = vc;
    double u1 = rng_uniform(r), u2 = rng_uniform(r), u3 = c->transmits ? rng_uniform(r) : 0.5;
    ggx_sample smp = c->info->sample_direction(c->s, &c->f, c->eta, c->v, u1, u2, u3, GGX_RADIANCE);
    if (smp.event == GGX_EVENT_INVALID) {
        CHECK(smp.pdf == 0 && smp.weight == 0 && smp.w.x == 0 && smp.w.y == 0 && smp.w.z == 0, "invalid sample");
        return 0;
    }
    /* Every 16th sample: the reported pdf and weight agree with the registry's pdf and the evaluation. */
    if ((c->checked++ & 15) == 0) {
        double pdf = c->info->pdf_direction(c->s, c->eta, c->v, smp.w), f = dir_eval(c, smp.w);
        CHECK_CLOSE(smp.pdf, pdf, 1e-9, 0, "%s: pdf of w (%g,%g,%g)", c->info->name, smp.w.x, smp.w.y, smp.w.z);
        CHECK_CLOSE(smp.weight, f * fabs(smp.w.z) / smp.pdf, 1e-9, 1e-300, "%s: weight", c->info->name);
        CHECK_CLOSE(t_dot(smp.w, smp.w), 1.0, 1e-12, 0, "%s: unit w", c->info->name);
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
        return c->info->pdf_direction(c->s, c->eta, c->v, w) / ggx_jacobian_reflect(w, h) * jk;
    }
    if (!c->transmits) return 0.0;
    double ev = c->v.z > 0 ? 1.0 : c->eta, et = c->v.z > 0 ? c->eta : 1.0;
    if (!ggx_refract(c->v, h, et / ev, &w) || (w.z > 0) == (c->v.z > 0) || w.z == 0) return 0.0;
    double jr = ggx_jacobian_refract(c->v, w, h, ev, et);
    return jr > 0 ? c->info->pdf_direction(c->s, c->eta, c->v, w) / jr * jk : 0.0;
}

static chi2_result run_dir(dir_ctx *c, const char *name, uint64_t seed, double *min_p)
{
    chi2_problem p = {name, c->transmits ? 2 : 1, dir_draw, dir_key, dir_density, c};
    double alpha = test_chi2_level();
    chi2_result r = chi2_run_scaled(&p, seed, alpha);
    chi2_runs_done++;
    chi2_runs_by[variant_index(VARIANT_EXPORTED)][c->info->id]++;
    CHECK(r.zero_cell_hits == 0, "%s: %ld samples where the pdf is zero", name, r.zero_cell_hits);
    CHECK(r.pvalue >= alpha, "%s: chi2 %.1f, dof %d, p = %.3g", name, r.stat, r.dof, r.pvalue);
    if (r.pvalue < *min_p) *min_p = r.pvalue;
    return r;
}

/* Every direction sampler of reflection (one that does not transmit; those that do run the dielectric sweep below)
 * over the sweep of shapes and views, F = 1 and a conductor in turn; the weight never exceeds 1 (Walter eq 52;
 * 1e-12 for rounding). Seeds 7000 + 100 k + 10 i + j, k the sampler's rank among the registry's reflection
 * samplers. Then, for reflection sampling with F = 1 on unskewed shapes, the weight equals G1(wo, m) (eq 51 holds
 * with equality). */
static void reflection_sweep(void **state)
{
    (void)state;
    int k = -1;
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *info = ggx_sampler_get((ggx_sampler_id)id);
        if (info->family != GGX_FAMILY_DIRECTION || sampler_transmits(info)) continue;
        k++;
        double min_p = 1.0, max_w = 0.0, invalid_frac = 0.0;
        int runs = 0;
        for (int i = 0; i < SWEEP_NSHAPES; i++) {
            ggx_shape s;
            make_shape(&s, SWEEP_SHAPES[i].p);
            for (int j = 0; j < SWEEP_NVIEWS; j++) {
                ggx_vec3 v = sweep_view(SWEEP_VIEWS_DEG[j]);
                dir_ctx c = {info, &s, {GGX_FRESNEL_ONE, 0, 0, 0}, v, 1.5, 0, 0.0, 0};
                if (j % 2) ggx_fresnel_conductor(&c.f, 0.2, 3.9);
                char name[128];
                snprintf(name, sizeof name, "%s %s, view %g", info->name, SWEEP_SHAPES[i].name, SWEEP_VIEWS_DEG[j]);
                chi2_result r = run_dir(&c, name, 7000 + 100 * (uint64_t)k + 10 * (uint64_t)i + (uint64_t)j, &min_p);
                runs++;
                CHECK(c.max_weight <= 1.0 + 1e-12, "%s: weight %.17g > 1 (eq 52)", name, c.max_weight);
                if (c.max_weight > max_w) max_w = c.max_weight;
                if ((double)r.invalid / 1e6 > invalid_frac) invalid_frac = (double)r.invalid / 1e6;
            }
        }
        printf("%s: %d chi-square runs, smallest p %.4g, largest weight %.15f, most samples invalid %.4f\n",
               info->name, runs, min_p, max_w, invalid_frac);
    }
    CHECK(k >= 0, "no direction sampler reflects only: the reflection sweep tested nothing");
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
}

/* Every direction sampler that transmits, as a rough dielectric: eta = 1.5 and 1/1.5, from outside and from
 * inside, including total internal reflection (from inside glass at 60 degrees, beyond the critical angle of 41.8
 * degrees). Seeds 9000 + 1000 t + 100 i + 10 j + e, t the sampler's rank among those that transmit. */
static void dielectric_sweep(void **state)
{
    (void)state;
    const int shapes[] = {1, 4, 5, 6, 8};
    const double views[][2] = {{30, 1}, {80, 1}, {30, -1}, {60, -1}};
    const double etas[] = {1.5, 1 / 1.5};
    int t = -1;
    for (int id = 0; id < GGX_SAMPLER_COUNT; id++) {
        const ggx_sampler_info *info = ggx_sampler_get((ggx_sampler_id)id);
        if (info->family != GGX_FAMILY_DIRECTION || !sampler_transmits(info)) continue;
        t++;
        double min_p = 1.0;
        int runs = 0;
        for (unsigned i = 0; i < sizeof shapes / sizeof shapes[0]; i++) {
            ggx_shape s;
            make_shape(&s, SWEEP_SHAPES[shapes[i]].p);
            for (unsigned j = 0; j < sizeof views / sizeof views[0]; j++) {
                for (unsigned e = 0; e < 2; e++) {
                    ggx_vec3 v = sweep_view(views[j][0]);
                    v.z *= views[j][1];
                    dir_ctx c = {info, &s, {GGX_FRESNEL_ONE, 0, 0, 0}, v, etas[e], 1, 0.0, 0};
                    char name[128];
                    snprintf(name, sizeof name, "%s %s, view %g%s, eta %.3f", info->name, SWEEP_SHAPES[shapes[i]].name,
                             views[j][0], views[j][1] < 0 ? " inside" : "", etas[e]);
                    run_dir(&c, name, 9000 + 1000 * (uint64_t)t + 100 * i + 10 * j + e, &min_p);
                    runs++;
                }
            }
        }
        printf("%s as a dielectric: %d chi-square runs, smallest p %.4g\n", info->name, runs, min_p);
    }
    CHECK(t >= 0, "no direction sampler transmits: the dielectric sweep tested nothing");
}

/* Every registered direction sampler got chi-square runs. */
static void dir_coverage(void **state)
{
    (void)state;
    check_chi2_coverage(VARIANT_EXPORTED, FAMILY_BIT(GGX_FAMILY_DIRECTION));
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(reflection_sweep), cmocka_unit_test(dielectric_sweep),
                                       cmocka_unit_test(dir_coverage)};
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    printf("chi-square runs in this program: %d\n", chi2_runs_done);
    return rc;
}
