/* The samplers of the ggx command: the library's registry, walked in its order, and wrong-s. Everything the
 * command does with a sampler (its name, help line, view and domain checks, drawing) goes through the registry's
 * family, domain and function pointers, so a sampler added to the library is on the command line without an edit
 * here. SPDX-License-Identifier: MIT */
#include <string.h>

#include "audit.h"
#include "cli.h"

/* The blog's crescent factor, right for unskewed shapes only: the negative control of `ggx check`, which must
 * reject it on a skewed shape. It is not a library sampler, so it lives here, after the registry's entries; its id
 * is GGX_SAMPLER_COUNT, no registry id. */
static const ggx_sampler_info WRONG_S = {
    .id = GGX_SAMPLER_COUNT,
    .name = "wrong-s",
    .help = "deliberately WRONG VNDF sampler (blog's s from A^-T n), to test ggx check",
    .family = GGX_FAMILY_VNDF,
    .domain = GGX_DOMAIN_ANY,
    .sample = verify_crescent_blog_s,
    .pdf = ggx_pdf_vndf,
};

int cli_sampler_count(void) { return GGX_SAMPLER_COUNT + 1; }

const ggx_sampler_info *cli_sampler(int i)
{
    return i < GGX_SAMPLER_COUNT ? ggx_sampler_get((ggx_sampler_id)i) : &WRONG_S;
}

const ggx_sampler_info *find_sampler(const char *name)
{
    for (int i = 0; i < cli_sampler_count(); i++)
        if (strcmp(cli_sampler(i)->name, name) == 0) return cli_sampler(i);
    die("unknown sampler '%s' (see ggx sample --help)", name);
}

void print_samplers(FILE *f)
{
    int w = 15; /* the column fits the longest name, with two spaces after it */
    for (int i = 0; i < cli_sampler_count(); i++)
        if ((int)strlen(cli_sampler(i)->name) > w) w = (int)strlen(cli_sampler(i)->name);
    fprintf(f, "samplers:\n");
    for (int i = 0; i < cli_sampler_count(); i++)
        fprintf(f, "  %-*s  %s\n", w, cli_sampler(i)->name, cli_sampler(i)->help);
}

int sampler_applies(const ggx_sampler_info *smp, const ggx_shape *s)
{
    return !(smp->domain == GGX_DOMAIN_UNSKEWED && s->kind == GGX_SHAPE_SKEWED);
}

void require_domain(const ggx_sampler_info *smp, const ggx_shape *s)
{
    /* Outside its domain a sampler returns only zero vectors: asked for by name, that is a mistake to report, not
     * a file of zeros to write. */
    if (!sampler_applies(smp, s)) die("sampler '%s' is for unskewed shapes only; this shape is skewed", smp->name);
}

/* The registry does not say from which side of the surface a direction sampler takes its known direction (a
 * reflection model from above only, a dielectric from both): one sample from straight below tells. */
static int takes_views_from_below(const ggx_sampler_info *smp)
{
    ggx_shape s;
    ggx_fresnel one;
    ggx_shape_iso(&s, 0.5);
    ggx_fresnel_one(&one);
    ggx_sample x = smp->sample_direction(&s, &one, 1.5, t_vec(0, 0, -1), 0.5, 0.5, 0.5, GGX_RADIANCE);
    return x.event != GGX_EVENT_INVALID;
}

void require_view(const ggx_sampler_info *smp, ggx_vec3 view)
{
    if (smp->family == GGX_FAMILY_NDF) return; /* samplers of D(m)(m.n) have no view */
    if (!(view.z > 0) && (smp->family != GGX_FAMILY_DIRECTION || !takes_views_from_below(smp)))
        die("--view must be above the horizon for sampler '%s'", smp->name);
    if (view.z == 0) die("--view must not lie on the horizon for sampler '%s'", smp->name);
}

static double uniform_cb(void *st) { return rng_uniform((rng *)st); }

int draw_sample(const ggx_sampler_info *smp, const ggx_shape *s, ggx_vec3 view, const ggx_fresnel *f, double eta,
                rng *r, ggx_vec3 *w, double *pdf, double *weight)
{
    /* u1, u2 come first for every family (rejection samplers draw theirs after them), which keeps the samples of a
     * seed what they were when each family had its own branch. */
    double u1 = rng_uniform(r), u2 = rng_uniform(r);
    *weight = 1.0;
    if (smp->family == GGX_FAMILY_DIRECTION) {
        ggx_sample x = smp->sample_direction(s, f, eta, view, u1, u2, rng_uniform(r), GGX_RADIANCE);
        *w = x.w, *pdf = x.pdf, *weight = x.weight;
        return x.event != GGX_EVENT_INVALID;
    }
    if (smp->family == GGX_FAMILY_REJECTION) {
        unsigned t;
        *w = smp->sample_reject(s, view, uniform_cb, r, &t);
    } else {
        *w = smp->sample(s, view, u1, u2);
    }
    *pdf = smp->pdf(s, view, *w);
    if (!(*pdf > 0)) *weight = 0.0;
    return *pdf > 0;
}
