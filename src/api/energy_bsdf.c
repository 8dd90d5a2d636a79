/* Energy compensation of the rough dielectric ggx_bsdf_eval (Kulla & Conty 2017, "Revisiting Physically Based
 * Shading at Imageworks", the dielectric part), for every shape: the albedo tables of both sides, the multiple-
 * scattering lobes on both sides, their sampler and pdf, and the compensated BSDF (docs/design/energy.md has the
 * derivation). SPDX-License-Identifier: MIT
 *
 * Side 0 is above the surface (index 1), side 1 below it (index eta). E_a(u) is the single-scattering albedo R + T
 * of light arriving from side a along u (ggx_bsdf_albedo), tabulated at u' = sgn(u.z) u in the upper hemisphere,
 * L_a = pi (1 - E_avg,a) the cosine-weighted loss. The lobe, in the radiance convention, for wi on side a and wo on
 * side b:
 *   f_ms(wi, wo) = c_ab (1 - E_a(wi)) (1 - E_b(wo)),
 *   c_aa = (1 - x_a) / L_a,  c_01 = x_0 / L_1,  c_10 = x_1 / L_0,
 * so that light from side a gets back its loss 1 - E_a(wi), the share x_a of it on the other side. Reciprocity
 * f(wi, wo) / eta_o^2 = f(wo, wi) / eta_i^2 asks c_01 / eta^2 = c_10 = t, i.e. x_0 L_0 = eta^2 x_1 L_1, or
 * x_0 = eta^2 t L_1 and x_1 = t L_0: one free number t. Kulla & Conty split the loss by the average Fresnel term;
 * here t is the largest value for which no side transmits more than its Fresnel share, x_a <= 1 - F_avg,a:
 *   t = min((1 - F_avg,0) / (eta^2 L_1), (1 - F_avg,1) / L_0),
 * and since 1 - F_avg,0 = eta^2 (1 - F_avg,1) (the transmittance of a smooth interface, from both sides), that is
 * t = (1 - F_avg,1) / max(L_0, L_1): the side that loses more transmits exactly its Fresnel share, the other less. */
#include <math.h>
#include <stdlib.h>

#include "common/parallel.h"
#include "tables/bsdf_grid.h"
#include "energy_table.h"

/* The nodes are computed to TABLE_TOL; the lookup's error is dominated by the interpolation (docs/design/energy.md). */
#define TABLE_TOL 1e-4
/* 65 rows: with 33 (the conductor's) the lookup erred by up to 1.6e-3 near the critical angle from the denser side,
 * where E dips over a width ~alpha; 128 columns: with 64 it erred by 3.9e-3 at grazing for alpha (0.1, 1)
 * (docs/design/energy.md). */
enum { ROWS = 65, COLUMNS = 128 };
/* the rows of the shipped isotropic table are these rows (bsdf_node reads them) */
_Static_assert((int)ROWS == (int)BSDF_NY, "the per-shape tables and the shipped table share their rows");

struct ggx_bsdf_energy {
    ggx_shape s;
    double eta;
    energy_table side[2]; /* E of light from above (0) and from below (1), at u' = sgn(u.z) u */
    double c[2][2];       /* c_ab, radiance convention */
    double x[2];          /* x_a: the share of side a's loss that the lobe transmits */
};

typedef struct bsdf_nodes {
    ggx_bsdf_energy *e;
    double sgn; /* 1: light from above, -1: from below */
    double *storage;
    int shipped; /* isotropic, with (alpha, eta) in the shipped table's range: its rows are read instead */
} bsdf_nodes;

/* A node: I = E / P of ggx_bsdf_albedo's R + T, or for an isotropic shape in the shipped table's range its value at
 * the same row (the tables share their rows), interpolated in alpha and eta. */
static double bsdf_node(void *vc, ggx_vec3 v, double y)
{
    const bsdf_nodes *c = vc;
    double i_value, eta_r = c->sgn > 0 ? c->e->eta : 1.0 / c->e->eta;
    if (c->shipped && ggx_internal_bsdf_iso_table_i(c->e->s.alpha_x, eta_r, y, &i_value)) return i_value;
    ggx_vec3 u = {c->sgn * v.x, c->sgn * v.y, c->sgn * v.z};
    return ggx_internal_bsdf_albedo(&c->e->s, c->e->eta, u, TABLE_TOL) / ggx_internal_albedo_scale(&c->e->s, v);
}

/* side k of the table: k = 0 from above (c[0]), 1 from below (c[1]) */
static void build_side(void *vc, int k)
{
    bsdf_nodes *c = (bsdf_nodes *)vc + k;
    /* uniform azimuths: the warp that serves the conductor (denser at the axes) left 4.0e-3 here from below, for
     * (0.1, 1) rotated, eta 1.5, at 86 degrees, where the uniform columns leave 3.9e-4 */
    ggx_internal_etab_build(&c->e->side[c->sgn > 0 ? 0 : 1], &c->e->s, ROWS, COLUMNS, 1.0, !c->shipped, c->storage,
                            bsdf_node, c);
}

static double transmittance_avg(double eta_rel)
{
    ggx_fresnel f;
    ggx_fresnel_dielectric(&f, eta_rel);
    return 1.0 - ggx_fresnel_avg(&f);
}

GGX_API ggx_status ggx_bsdf_energy_create(const ggx_shape *s, double eta, ggx_bsdf_energy **out)
{
    if (!out) return GGX_ERR_NULL;
    *out = NULL;
    if (!s) return GGX_ERR_NULL;
    if (!isfinite(eta)) return GGX_ERR_NONFINITE;
    /* eta = 1: the transmission is a delta that ggx_bsdf_eval does not represent, so no lobe can complete it */
    if (!(eta > 0) || eta == 1.0 || eta > 1e300) return GGX_ERR_ETA;
    size_t n = ggx_internal_etab_size(s, ROWS, COLUMNS);
    ggx_bsdf_energy *e = malloc(sizeof *e + sizeof(double) * 2 * n);
    if (!e) return GGX_ERR_MEMORY;
    e->s = *s;
    e->eta = eta;
    /* The two sides on two threads (in turn where no thread can be started): they share nothing but the shape. */
    /* the shipped table from alpha 0.025, where it keeps within 1e-3 (below, near the critical angle, it erred by
     * up to 1.2e-3, and per-shape tables built from it with it) */
    double probe;
    int shipped = ggx_internal_is_isotropic(s) && s->alpha_x >= BSDF_PROMISE_AMIN &&
                  ggx_internal_bsdf_iso_table_i(s->alpha_x, eta, 1.0, &probe);
    bsdf_nodes c[2] = {{e, 1.0, (double *)(e + 1), shipped}, {e, -1.0, (double *)(e + 1) + n, shipped}};
    /* a second thread only when there are quadratures to share */
    ggx_internal_parallel_for(shipped ? 1 : 2, build_side, c);
    if (shipped) build_side(c, 1);
    double l0 = 0.5 * e->side[0].total, l1 = 0.5 * e->side[1].total; /* pi (1 - E_avg) */
    double t0 = transmittance_avg(eta), t1 = transmittance_avg(1.0 / eta);
    double lmax = l0 > l1 ? l0 : l1, t = 0.0;
    if (lmax > 0) {
        t = t0 / (eta * eta * lmax);
        if (t1 / lmax < t) t = t1 / lmax;
    }
    e->c[0][1] = eta * eta * t;
    e->c[1][0] = t;
    e->x[0] = e->c[0][1] * l1;
    e->x[1] = t * l0;
    e->c[0][0] = l0 > 0 ? (1.0 - e->x[0]) / l0 : 0.0;
    e->c[1][1] = l1 > 0 ? (1.0 - e->x[1]) / l1 : 0.0;
    *out = e;
    return GGX_OK;
}

GGX_API void ggx_bsdf_energy_free(ggx_bsdf_energy *e) { free(e); }

GGX_API const ggx_shape *ggx_bsdf_energy_shape(const ggx_bsdf_energy *e) { return e ? &e->s : NULL; }

GGX_API double ggx_bsdf_energy_eta(const ggx_bsdf_energy *e) { return e ? e->eta : 0.0; }

/* The unit direction w, its side (0 above, 1 below) and u' = sgn(w.z) w; 0 for a zero, non-finite or horizontal w. */
static int side_of(ggx_vec3 w, ggx_vec3 *unit, int *side, ggx_vec3 *up)
{
    ggx_vec3 f = {-w.x, -w.y, -w.z};
    if (ggx_internal_unit_up(w, up)) {
        *side = 0;
        *unit = *up;
        return 1;
    }
    if (!ggx_internal_unit_up(f, up)) return 0;
    *side = 1;
    unit->x = -up->x, unit->y = -up->y, unit->z = -up->z;
    return 1;
}

GGX_API double ggx_bsdf_energy_albedo(const ggx_bsdf_energy *e, ggx_vec3 v)
{
    ggx_vec3 w, u;
    int a;
    if (!e || !side_of(v, &w, &a, &u)) return 0.0;
    return ggx_internal_etab_albedo(&e->side[a], u);
}

GGX_API double ggx_bsdf_energy_albedo_avg(const ggx_bsdf_energy *e, int below)
{
    return e ? e->side[below ? 1 : 0].e_avg : 0.0;
}

/* f_ms(wi -> wo) in the radiance convention, for unit directions on sides a, b (u': their upper-hemisphere forms). */
static double ms_lobe(const ggx_bsdf_energy *e, int a, ggx_vec3 ui, int b, ggx_vec3 uo)
{
    return e->c[a][b] * (1.0 - ggx_internal_etab_albedo(&e->side[a], ui)) *
           (1.0 - ggx_internal_etab_albedo(&e->side[b], uo));
}

/* The lobe for a transport mode: the adjoint swaps the directions. */
static double ms_mode(const ggx_bsdf_energy *e, int a, ggx_vec3 ua, int b, ggx_vec3 ub, ggx_transport mode)
{
    return mode == GGX_IMPORTANCE ? ms_lobe(e, b, ub, a, ua) : ms_lobe(e, a, ua, b, ub);
}

GGX_API double ggx_bsdf_ms_eval(const ggx_bsdf_energy *e, ggx_vec3 wi, ggx_vec3 wo, ggx_transport mode)
{
    ggx_vec3 a, b, ua, ub;
    int sa, sb;
    if (!e || !side_of(wi, &a, &sa, &ua) || !side_of(wo, &b, &sb, &ub)) return 0.0;
    return ms_mode(e, sa, ua, sb, ub, mode);
}

GGX_API double ggx_bsdf_compensated_eval(const ggx_bsdf_energy *e, ggx_vec3 wi, ggx_vec3 wo, ggx_transport mode)
{
    ggx_vec3 a, b, ua, ub;
    int sa, sb;
    if (!e || !side_of(wi, &a, &sa, &ua) || !side_of(wo, &b, &sb, &ub)) return 0.0;
    return ggx_bsdf_eval_d(&e->s, e->eta, a, b, mode) + ms_mode(e, sa, ua, sb, ub, mode);
}

/* The lobe's density of w (side b, u' = ub) from a view on side a: side b chosen with probability x_a or 1 - x_a,
 * then the table's cell distribution. */
static double ms_pdf(const ggx_bsdf_energy *e, int a, int b, ggx_vec3 ub)
{
    double pick = a == b ? 1.0 - e->x[a] : e->x[a];
    return pick > 0 ? pick * ggx_internal_etab_pdf(&e->side[b], ub) : 0.0;
}

/* A direction of the lobe from a view on side a: its side by u3, then the table's cells by u1, u2. */
static ggx_vec3 ms_direction(const ggx_bsdf_energy *e, int a, double u1, double u2, double u3)
{
    int b = ggx_internal_clamp01(u3) < e->x[a] ? 1 - a : a;
    ggx_vec3 w = ggx_internal_etab_sample(&e->side[b], u1, u2);
    if (b == 1) w.x = -w.x, w.y = -w.y, w.z = -w.z;
    return w;
}

/* The sample of a unit direction w drawn from a view on side a, with its pdf, its weight f |w.z| / pdf and its
 * event; invalid when w is not a direction or the pdf vanishes. */
static ggx_sample finish(int a, ggx_vec3 w, double pdf, double f)
{
    ggx_vec3 unit, u;
    int b;
    if (!side_of(w, &unit, &b, &u) || !(pdf > 0) || !(pdf <= 1e300)) return ggx_internal_invalid_sample();
    ggx_sample r = {w, pdf, f * fabs(w.z) / pdf, a == b ? GGX_EVENT_REFLECT : GGX_EVENT_TRANSMIT};
    if (!(r.weight >= 0 && r.weight <= 1e300)) return ggx_internal_invalid_sample();
    return r;
}

GGX_API double ggx_pdf_bsdf_ms(const ggx_bsdf_energy *e, ggx_vec3 v, ggx_vec3 w)
{
    ggx_vec3 a, b, ua, ub;
    int sa, sb;
    if (!e || !side_of(v, &a, &sa, &ua) || !side_of(w, &b, &sb, &ub)) return 0.0;
    return ms_pdf(e, sa, sb, ub);
}

GGX_API ggx_sample ggx_sample_bsdf_ms(const ggx_bsdf_energy *e, ggx_vec3 v, double u1, double u2, double u3,
                                      ggx_transport mode)
{
    ggx_vec3 a, ua;
    int sa;
    if (!e || !side_of(v, &a, &sa, &ua)) return ggx_internal_invalid_sample();
    ggx_vec3 w = ms_direction(e, sa, u1, u2, u3), uw, ub;
    int sb;
    if (!side_of(w, &uw, &sb, &ub)) return ggx_internal_invalid_sample();
    return finish(sa, w, ms_pdf(e, sa, sb, ub), ms_mode(e, sb, ub, sa, ua, mode));
}

/* The probability of the single-scattering lobe: its albedo E_a(v) (the lobes' albedos add up to 1). */
static double ss_share(const ggx_bsdf_energy *e, int a, ggx_vec3 ua)
{
    return ggx_internal_etab_albedo(&e->side[a], ua);
}

static double pdf_compensated(const ggx_bsdf_energy *e, ggx_vec3 v, int a, double p, ggx_vec3 w, int b, ggx_vec3 ub)
{
    return p * ggx_pdf_bsdf_d(&e->s, e->eta, v, w) + (1.0 - p) * ms_pdf(e, a, b, ub);
}

GGX_API double ggx_pdf_bsdf_compensated(const ggx_bsdf_energy *e, ggx_vec3 v, ggx_vec3 w)
{
    ggx_vec3 a, b, ua, ub;
    int sa, sb;
    if (!e || !side_of(v, &a, &sa, &ua) || !side_of(w, &b, &sb, &ub)) return 0.0;
    return pdf_compensated(e, a, sa, ss_share(e, sa, ua), b, sb, ub);
}

GGX_API ggx_sample ggx_sample_bsdf_compensated(const ggx_bsdf_energy *e, ggx_vec3 v, double u1, double u2, double u3,
                                               ggx_transport mode)
{
    ggx_vec3 a, ua;
    int sa;
    if (!e || !side_of(v, &a, &sa, &ua)) return ggx_internal_invalid_sample();
    double p = ss_share(e, sa, ua), u = ggx_internal_clamp01(u3);
    ggx_vec3 w;
    if (u < p) { /* u3 rescaled to [0, 1) picks reflection or refraction inside ggx_sample_bsdf */
        ggx_sample ss = ggx_sample_bsdf_d(&e->s, e->eta, a, u1, u2, u / p, mode);
        if (ss.event == GGX_EVENT_INVALID) return ggx_internal_invalid_sample();
        w = ss.w;
    } else {
        w = ms_direction(e, sa, u1, u2, (u - p) / (1.0 - p));
    }
    ggx_vec3 uw, ub;
    int sb;
    if (!side_of(w, &uw, &sb, &ub)) return ggx_internal_invalid_sample();
    double f = ggx_bsdf_eval_d(&e->s, e->eta, uw, a, mode) + ms_mode(e, sb, ub, sa, ua, mode);
    return finish(sa, uw, pdf_compensated(e, a, sa, p, uw, sb, ub), f);
}
