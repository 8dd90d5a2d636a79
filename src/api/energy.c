/* Energy compensation (Kulla & Conty 2017) for every shape: the per-shape table of the albedo E(v) of ggx_brdf_eval
 * (src/api/energy_table.c), the multiple-scattering lobe, its sampler and pdf, and the compensated BRDF
 * (docs/design/energy.md). SPDX-License-Identifier: MIT
 *
 * The lobe. f_ms(wi, wo) = F_ms (1 - E(wi)) (1 - E(wo)) / (pi (1 - E_avg)) with E the table's interpolant and
 * E_avg = (1 / pi) int E(w) w.z dw computed from the same interpolant, so that int f_ms(wi, wo) wo.z dwo is exactly
 * 1 - E(wi) (up to the quadrature of the table's cells): the compensated albedo is 1 + (E - E_table)(wi) with
 * F = 1. */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>

#include "common/albedo_rows.h"
#include "common/gauss.h"
#include "energy_table.h"

/* Table size. Shapes whose nodes come from a shipped table take its rows: isotropic ones 65 rows and one column,
 * unskewed anisotropic ones 33 rows (y = i / 32, the anisotropic table's) and 128 columns on a full turn (E of
 * anisotropic shapes has sharp features in the azimuth at grazing: 64 columns left errors of 1.6e-3 to 3.8e-3 at
 * 89 degrees, 128 columns 1.5e-4 to 4e-4; docs/design/energy.md). The others (skewed shapes, roughnesses or anisotropy
 * outside the shipped tables) compute their nodes by quadrature, to TABLE_TOL, on 65 rows (with 33, skewed lobes of
 * alpha 0.05 erred by 1e-2 near grazing, with 65 by 1.6e-3) and 128 columns, and are guarded where the interpolation
 * falls below E (energy_table.c). */
#define TABLE_TOL 1e-4
enum { ROWS = 33, FINE_ROWS = 65, COLUMNS = 128 };
struct ggx_energy {
    ggx_shape s;
    energy_table t;
};

static double gl_x[16], gl_w[16];
static pthread_once_t once = PTHREAD_ONCE_INIT;
static void init_rules(void) { gq_nodes(16, gl_x, gl_w); }

/* A node of the table: I = E / P of ggx_albedo, or for a shape in a shipped table's range that table's value at the
 * node instead of a quadrature: the isotropic table's row (the same rows), or the anisotropic table's
 * node (the per-shape table's rows and its columns 0 to 32 are that table's), interpolated in the roughnesses. */
typedef struct brdf_nodes {
    const ggx_shape *s;
    int shipped; /* 1: the isotropic table, 2: the anisotropic table */
} brdf_nodes;

static double brdf_node(void *vc, ggx_vec3 v, double y)
{
    const brdf_nodes *c = vc;
    const ggx_shape *s = c->s;
    double i_value;
    if (c->shipped == 1 && ggx_internal_iso_table_i(s->alpha_x, y, &i_value)) return i_value;
    if (c->shipped == 2) {
        double x = s->tangent_cos * v.x + s->tangent_sin * v.y, yy = s->tangent_cos * v.y - s->tangent_sin * v.x;
        if (ggx_internal_aniso_table_i(s->alpha_x, s->alpha_y, y, cols_psi_of_xy(fabs(x), fabs(yy), COLS_WARP_K),
                                       &i_value))
            return i_value;
    }
    return ggx_internal_albedo(s, v, 0, TABLE_TOL) / ggx_internal_albedo_scale(s, v);
}

/* A table of s with rows x columns, its nodes from the shipped tables (shipped 1 or 2) or by quadrature (0, and
 * then checked); NULL when out of memory. */
static ggx_energy *build(const ggx_shape *s, int shipped, int rows, int columns)
{
    ggx_energy *e = malloc(sizeof *e + sizeof(double) * ggx_internal_etab_size(s, rows, columns));
    if (!e) return NULL;
    e->s = *s;
    brdf_nodes c = {&e->s, shipped};
    ggx_internal_etab_build(&e->t, &e->s, rows, columns, COLS_WARP_K, shipped == 0, (double *)(e + 1), brdf_node, &c);
    return e;
}

GGX_API ggx_status ggx_energy_create(const ggx_shape *s, ggx_energy **out)
{
    if (!out) return GGX_ERR_NULL;
    *out = NULL;
    if (!s) return GGX_ERR_NULL;
    double probe;
    int iso = ggx_internal_is_isotropic(s), shipped = 0;
    if (iso && ggx_internal_iso_table_i(s->alpha_x, 1.0, &probe)) shipped = 1;
    else if (s->kind != GGX_SHAPE_SKEWED && ggx_internal_aniso_table_serves(s->alpha_x, s->alpha_y)) shipped = 2;
    ggx_energy *e = build(s, shipped, shipped == 2 ? ROWS : FINE_ROWS, COLUMNS);
    if (!e) return GGX_ERR_MEMORY;
    *out = e;
    return GGX_OK;
}

GGX_API void ggx_energy_free(ggx_energy *e) { free(e); }

GGX_API const ggx_shape *ggx_energy_shape(const ggx_energy *e) { return e ? &e->s : NULL; }

GGX_API double ggx_energy_albedo(const ggx_energy *e, ggx_vec3 v)
{
    ggx_vec3 u;
    if (!e || !ggx_internal_unit_up(v, &u)) return 0.0;
    return ggx_internal_etab_albedo(&e->t, u);
}

GGX_API double ggx_energy_albedo_avg(const ggx_energy *e) { return e ? e->t.e_avg : 0.0; }

GGX_API double ggx_fresnel_avg(const ggx_fresnel *f)
{
    if (!f) return 1.0;
    pthread_once(&once, init_rules);
    switch (f->kind) {
    case GGX_FRESNEL_ONE: return 1.0;
    case GGX_FRESNEL_SCHLICK: return f->f0 + (1.0 - f->f0) / 21.0; /* 2 int (1 - mu)^5 mu dmu = 1 / 21 */
    case GGX_FRESNEL_DIELECTRIC:
        if (f->eta < 1.0 && f->eta > 0.0) {
            /* Total internal reflection below mu_c = sqrt(1 - eta^2); above it F is smooth in the transmitted
             * cosine c (mu^2 = mu_c^2 + eta^2 c^2, mu dmu = eta^2 c dc, c from 0 to 1), not in mu. */
            double sum = 0.0;
            for (int i = 0; i < 16; i++) {
                double c = 0.5 + 0.5 * gl_x[i];
                double mu = sqrt((1.0 - f->eta * f->eta) + f->eta * f->eta * c * c);
                sum += gl_w[i] * ggx_fresnel_eval_d(f, mu) * c;
            }
            return (1.0 - f->eta * f->eta) + f->eta * f->eta * sum; /* 2 x (half-width 1/2) */
        }
        break;
    default: break;
    }
    double sum = 0.0;
    for (int i = 0; i < 16; i++) {
        double mu = 0.5 + 0.5 * gl_x[i];
        sum += gl_w[i] * ggx_fresnel_eval_d(f, mu) * mu;
    }
    return sum; /* 2 x (half-width 1/2) */
}

/* F_avg of f, remembered per thread for the last few Fresnel terms: a renderer evaluates the same few (one per colour
 * channel) again and again, and the quadrature of a conductor's or dielectric's F costs far more than a lookup. Fields compare
 * by value (a NaN never matches, and is recomputed). */
static double fresnel_avg_cached(const ggx_fresnel *f)
{
    enum { SLOTS = 4 };
    static _Thread_local struct {
        ggx_fresnel f;
        double avg;
        int used;
    } cache[SLOTS];
    static _Thread_local int next;
    if (f->kind == GGX_FRESNEL_ONE || f->kind == GGX_FRESNEL_SCHLICK) return ggx_fresnel_avg(f); /* closed forms */
    for (int i = 0; i < SLOTS; i++)
        if (cache[i].used && cache[i].f.kind == f->kind && cache[i].f.eta == f->eta && cache[i].f.k == f->k &&
            cache[i].f.f0 == f->f0)
            return cache[i].avg;
    double a = ggx_fresnel_avg(f);
    cache[next].f = *f;
    cache[next].avg = a;
    cache[next].used = 1;
    next = (next + 1) % SLOTS;
    return a;
}

/* Kulla & Conty's factor for the energy that leaves after more than one bounce with Fresnel F_avg per bounce,
 * relative to F = 1: F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) (1 for F = 1). */
static double ms_fresnel_of(const ggx_energy *e, double fa)
{
    double den = 1.0 - fa * (1.0 - e->t.e_avg);
    return den > 0 ? fa * fa * e->t.e_avg / den : 0.0;
}

static double ms_fresnel(const ggx_energy *e, const ggx_fresnel *f) { return ms_fresnel_of(e, fresnel_avg_cached(f)); }

/* f_ms given E(wi) (ew) and the factor F_ms. */
static double ms_lobe_e(const ggx_energy *e, double fms, double ew, ggx_vec3 wo)
{
    double loss = 1.0 - e->t.e_avg;
    if (!(loss > 1e-12)) return 0.0;
    return fms * (1.0 - ew) * (1.0 - ggx_internal_etab_albedo(&e->t, wo)) / (GGX_PI * loss);
}

static double ms_lobe(const ggx_energy *e, double fms, ggx_vec3 wi, ggx_vec3 wo)
{
    return ms_lobe_e(e, fms, ggx_internal_etab_albedo(&e->t, wi), wo);
}

GGX_API double ggx_brdf_ms_eval(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo)
{
    f = GGX_FRESNEL_OR_ONE(f);
    ggx_vec3 a, b;
    if (!e || !ggx_internal_unit_up(wi, &a) || !ggx_internal_unit_up(wo, &b)) return 0.0;
    return ms_lobe(e, ms_fresnel(e, f), a, b);
}

GGX_API double ggx_pdf_brdf_ms(const ggx_energy *e, ggx_vec3 wi, ggx_vec3 wo)
{
    ggx_vec3 a, b;
    if (!e || !ggx_internal_unit_up(wi, &a) || !ggx_internal_unit_up(wo, &b)) return 0.0;
    return ggx_internal_etab_pdf(&e->t, b);
}

GGX_API ggx_sample ggx_sample_brdf_ms(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, double u1, double u2)
{
    f = GGX_FRESNEL_OR_ONE(f);
    ggx_vec3 a;
    if (!e || !ggx_internal_unit_up(wi, &a)) return ggx_internal_invalid_sample();
    ggx_vec3 w = ggx_internal_etab_sample(&e->t, u1, u2);
    if (!(w.z > 0)) return ggx_internal_invalid_sample();
    double pdf = ggx_internal_etab_pdf(&e->t, w);
    if (!(pdf > 0)) return ggx_internal_invalid_sample();
    ggx_sample r = {w, pdf, ms_lobe(e, ms_fresnel(e, f), a, w) * w.z / pdf, GGX_EVENT_REFLECT};
    return r;
}

/* Probability of drawing the single-scattering lobe: its albedo estimate F_avg E(wi) against the multiple-
 * scattering lobe's F_ms (1 - E(wi)). Writes E(wi) and F_ms for the caller. */
static double ss_share(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, double *ew, double *fms)
{
    double fa = fresnel_avg_cached(f);
    *ew = ggx_internal_etab_albedo(&e->t, wi);
    *fms = ms_fresnel_of(e, fa);
    double ss = fa * *ew, ms = (1.0 - e->t.e_avg > 1e-12) ? *fms * (1.0 - *ew) : 0.0, tot = ss + ms;
    return tot > 0 ? ss / tot : 1.0;
}

GGX_API double ggx_brdf_compensated_eval(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo)
{
    f = GGX_FRESNEL_OR_ONE(f);
    ggx_vec3 a, b;
    if (!e || !ggx_internal_unit_up(wi, &a) || !ggx_internal_unit_up(wo, &b)) return 0.0;
    return ggx_brdf_eval_d(&e->s, f, a, b) + ms_lobe(e, ms_fresnel(e, f), a, b);
}

GGX_API double ggx_pdf_brdf_compensated(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo)
{
    f = GGX_FRESNEL_OR_ONE(f);
    ggx_vec3 a, b;
    if (!e || !ggx_internal_unit_up(wi, &a) || !ggx_internal_unit_up(wo, &b)) return 0.0;
    double ew, fms, p = ss_share(e, f, a, &ew, &fms);
    return p * ggx_pdf_brdf_bounded_d(&e->s, a, b) + (1.0 - p) * ggx_internal_etab_pdf(&e->t, b);
}

GGX_API ggx_sample ggx_sample_brdf_compensated(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, double u1,
                                               double u2, double u3)
{
    f = GGX_FRESNEL_OR_ONE(f);
    ggx_vec3 a;
    if (!e || !ggx_internal_unit_up(wi, &a)) return ggx_internal_invalid_sample();
    double ew, fms, p = ss_share(e, f, a, &ew, &fms);
    ggx_vec3 w;
    double pdf_ss;
    if (ggx_internal_clamp01(u3) < p) { /* the sample carries its own pdf, ggx_pdf_brdf_bounded's */
        ggx_sample ss = ggx_sample_brdf_bounded_d(&e->s, f, a, u1, u2);
        if (ss.event != GGX_EVENT_REFLECT) return ggx_internal_invalid_sample();
        w = ss.w;
        pdf_ss = ss.pdf;
    } else {
        w = ggx_internal_etab_sample(&e->t, u1, u2);
        pdf_ss = ggx_pdf_brdf_bounded_d(&e->s, a, w); /* 0 for w.z <= 0, which is refused below */
    }
    if (!(w.z > 0)) return ggx_internal_invalid_sample();
    double pdf = p * pdf_ss + (1.0 - p) * ggx_internal_etab_pdf(&e->t, w);
    if (!(pdf > 0)) return ggx_internal_invalid_sample();
    double fr = ggx_brdf_eval_d(&e->s, f, a, w) + ms_lobe_e(e, fms, ew, w);
    ggx_sample r = {w, pdf, fr * w.z / pdf, GGX_EVENT_REFLECT};
    return r;
}
