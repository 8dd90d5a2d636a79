/* Energy compensation (Kulla & Conty 2017) for every shape: a per-shape table of the albedo E(v), the
 * multiple-scattering lobe, its sampler and pdf, and the compensated BRDF (docs/energy.md).
 * SPDX-License-Identifier: MIT
 *
 * The table. E = P(v) I(v) (internal.h): P is closed-form and carries E's steep dependence on the view at grazing
 * and the kink of Walter's min through n for skewed shapes; the table holds I at nodes
 *   mu = sin(pi y^2 / 2), y = i / (NM - 1)        (theta = (pi / 2)(1 - y^2): dense towards grazing, and linear in
 *                                                  theta at the pole, where I is smooth in the view's components)
 *   phi = phi0 + 2 pi j / np                      (phi0: the axis of alpha_x for unskewed shapes)
 * and is read by Catmull-Rom interpolation in (y, phi). Across the pole a column continues as the opposite column
 * (the view at (y, phi) beyond y = 1 is the view at (2 - y, phi + pi)), so the pole needs no special case; below
 * y = 0 the rows are extrapolated. Isotropic shapes need one column, unskewed ones a quarter turn (E is even about
 * both tangent axes), skewed ones a full turn.
 *
 * The lobe. f_ms(wi, wo) = F_ms (1 - E(wi)) (1 - E(wo)) / (pi (1 - E_avg)) with E the table's interpolant and
 * E_avg = (1 / pi) int E(w) w.z dw computed from the same interpolant, so that int f_ms(wi, wo) wo.z dwo is exactly
 * 1 - E(wi) (up to the quadrature of the cells below): the compensated albedo is 1 - (E - E_table)(wi) with F = 1.
 * Sampling: the cosine-weighted measure is uniform in (t, phi) with t = mu^2 (w.z dw = dt dphi / 2); each table
 * cell [y_i, y_i+1] x [phi_j, phi_j+1] is a sampling cell with weight int (1 - E) dt dphi (4 x 4 Gauss-Legendre in
 * (y, phi)), drawn from their cumulative sum, and uniform in (t, phi) inside: a piecewise-constant pdf, exact for
 * what it draws, close to the lobe's shape. */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>

#include "../common/gauss.h"
#include "../common/albedo_rows.h"
#include "../common/interp.h"
#include "internal.h"

/* Table size: 33 rows in y, 128 columns on a full turn. E of anisotropic shapes has sharp features in the azimuth
 * at grazing (alpha(phi) changes fast near the axis of the smaller alpha): 64 columns left errors of 1.6e-3 to
 * 3.8e-3 at 89 degrees, 128 columns 1.5e-4 to 4e-4 (docs/energy.md). The nodes are computed to TABLE_TOL, well
 * below the interpolation error. */
enum { NM = 33, NP_FULL = 128, CELL_GL = 4 };
#define TABLE_TOL 1e-4

struct ggx_energy {
    ggx_shape s;
    int np;       /* columns: 1 (isotropic) or NP_FULL */
    double phi0;  /* azimuth of column 0 */
    double e_avg; /* (1 / pi) int E w.z dw of the interpolant */
    double total; /* sum of the cell weights = 2 pi (1 - e_avg) */
    double *tab;  /* NM x np values of I, row-major */
    double *pad;  /* the same with the ghost nodes of node() around it: (NM + 2) x pw, pw = np + 3 (1 if np = 1) */
    int pw;
    double *cdf;  /* (NM - 1) np + 1 cumulative cell weights, cdf[0] = 0 */
};

/* F = 1, for a NULL ggx_fresnel. */
static const ggx_fresnel fresnel_one = {GGX_FRESNEL_ONE, 0, 0, 0};

static double gl_x[16], gl_w[16], cell_x[CELL_GL], cell_w[CELL_GL];
static pthread_once_t once = PTHREAD_ONCE_INIT;
static void init_rules(void)
{
    gq_nodes(16, gl_x, gl_w);
    gq_nodes(CELL_GL, cell_x, cell_w);
}

static double mu_of_y(double y) { return sin(0.5 * GGX_PI * y * y); }

static ggx_vec3 view_at(double y, double phi)
{
    double th = rows_theta_of_y(y), st = sin(th);
    ggx_vec3 v = {st * cos(phi), st * sin(phi), cos(th)};
    return v;
}

static double node(const ggx_energy *e, int i, int j)
{
    int np = e->np;
    if (i >= NM) { /* across the pole */
        i = 2 * (NM - 1) - i;
        j += np / 2;
    }
    j %= np;
    if (j < 0) j += np;
    if (i < 0) return 2.0 * e->tab[j] - e->tab[(size_t)np + j]; /* linear extrapolation below grazing */
    return e->tab[(size_t)i * np + j];
}

/* The table cell of a unit w with w.z > 0: row i (y in [i, i + 1] / (NM - 1)) and column j, and the fractions
 * fy, fp inside it. Used by the lookup and by the lobe's pdf, whose cells are the table's. */
static void table_cell(const ggx_energy *e, ggx_vec3 w, int *i, double *fy, int *j, double *fp)
{
    double st = sqrt(w.x * w.x + w.y * w.y), th = atan2(st, w.z);
    double y = rows_y_of_theta(th) * (NM - 1);
    *i = (int)y;
    if (*i > NM - 2) *i = NM - 2;
    if (*i < 0) *i = 0;
    *fy = y - *i;
    *j = 0;
    *fp = 0.0;
    if (e->np == 1) return;
    double p = (atan2(w.y, w.x) - e->phi0) * (e->np / (2.0 * GGX_PI));
    p -= e->np * floor(p / e->np);
    *j = (int)p;
    if (*j > e->np - 1) *j = e->np - 1;
    if (*j < 0) *j = 0;
    *fp = p - *j;
}

/* E of the table at the unit view v (v.z > 0), in [0, 1]: Catmull-Rom over the padded nodes around the cell. */
static double table_albedo(const ggx_energy *e, ggx_vec3 v)
{
    int i, j;
    double fy, fp, r;
    table_cell(e, v, &i, &fy, &j, &fp);
    const double *r0 = e->pad + (size_t)i * e->pw; /* row i - 1 */
    if (e->np == 1) {
        double p[4] = {r0[0], r0[1], r0[2], r0[3]};
        r = catmull_rom(p, fy);
    } else {
        double col[4];
        for (int dj = 0; dj < 4; dj++) {
            const double *c = r0 + j + dj; /* column j - 1 + dj */
            double p[4] = {c[0], c[e->pw], c[2 * e->pw], c[3 * e->pw]};
            col[dj] = catmull_rom(p, fy);
        }
        r = catmull_rom(col, fp);
    }
    r *= ggx_internal_albedo_scale(&e->s, v);
    return r > 0 ? (r < 1 ? r : 1) : 0;
}

/* A unit direction with z > 0, or 0 for a zero, non-finite or lower-hemisphere one. */
static int unit_up(ggx_vec3 w, ggx_vec3 *out)
{
    double l = sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
    if (!(l > 0 && l <= 1e300)) return 0;
    out->x = w.x / l;
    out->y = w.y / l;
    out->z = w.z / l;
    return out->z > 0;
}

GGX_API ggx_status ggx_energy_create(const ggx_shape *s, ggx_energy **out)
{
    if (!out) return GGX_ERR_NULL;
    *out = NULL;
    if (!s) return GGX_ERR_NULL;
    pthread_once(&once, init_rules);
    int iso = ggx_internal_is_isotropic(s);
    int np = iso ? 1 : NP_FULL, ncell = (NM - 1) * np;
    int pw = np == 1 ? 1 : np + 3;
    ggx_energy *e = malloc(sizeof *e + sizeof(double) * ((size_t)NM * np + (size_t)(NM + 2) * pw + ncell + 1));
    if (!e) return GGX_ERR_MEMORY;
    e->s = *s;
    e->np = np;
    e->phi0 = s->kind == GGX_SHAPE_SKEWED ? 0.0 : atan2(s->tangent_sin, s->tangent_cos);
    e->tab = (double *)(e + 1);
    e->pad = e->tab + (size_t)NM * np;
    e->pw = pw;
    e->cdf = e->pad + (size_t)(NM + 2) * pw;

    /* Nodes. Unskewed: E(phi0 + d) = E(phi0 - d) = E(phi0 + pi - d), so columns 0..np/4 determine the rest. */
    int jmax = s->kind == GGX_SHAPE_SKEWED ? np - 1 : np / 4;
    /* Isotropic shapes in the shipped table's range read their rows from it (its rows include these: y = i / 32 is
     * its row 2 i), instead of 32 quadratures. */
    double probe;
    int shipped = iso && ggx_internal_iso_table_i(s->alpha_x, 1.0, &probe);
    for (int i = 1; i < NM && shipped; i++) ggx_internal_iso_table_i(s->alpha_x, (double)i / (NM - 1), &e->tab[i]);
    for (int i = 1; i < NM && !shipped; i++) {
        double y = (double)i / (NM - 1);
        for (int j = 0; j <= jmax; j++) {
            ggx_vec3 v = view_at(y, e->phi0 + 2.0 * GGX_PI * j / np);
            if (i == NM - 1) v.x = v.y = 0.0, v.z = 1.0; /* the pole, every column the same */
            double val = (i == NM - 1 && j > 0) ? e->tab[(size_t)i * np]
                                                 : ggx_internal_albedo(s, v, 0, TABLE_TOL) /
                                                       ggx_internal_albedo_scale(s, v);
            e->tab[(size_t)i * np + j] = val;
        }
        if (s->kind != GGX_SHAPE_SKEWED && np > 1)
            for (int j = 0; j <= jmax; j++) {
                double val = e->tab[(size_t)i * np + j];
                e->tab[(size_t)i * np + (np - j) % np] = val;
                e->tab[(size_t)i * np + np / 2 - j] = val;
                e->tab[(size_t)i * np + (np / 2 + j) % np] = val;
            }
    }
    for (int j = 0; j < np; j++) /* grazing row: quadratic extrapolation (E needs v.z > 0) */
        e->tab[j] = 3.0 * e->tab[np + j] - 3.0 * e->tab[2 * np + j] + e->tab[3 * np + j];

    /* The padded copy that interp reads: row r is node row r - 1 (the columns of the isotropic table are rows). */
    for (int r = 0; r < NM + 2; r++) {
        if (np == 1) {
            e->pad[r] = node(e, r - 1, 0);
            continue;
        }
        for (int c = 0; c < pw; c++) e->pad[(size_t)r * pw + c] = node(e, r - 1, c - 1);
    }

    /* Cell weights int (1 - E) dt dphi, t = mu^2: dt = 2 mu mu'(y) dy. */
    double dphi = 2.0 * GGX_PI / np, sum = 0.0;
    e->cdf[0] = 0.0;
    for (int i = 0; i < NM - 1; i++)
        for (int j = 0; j < np; j++) {
            double w = 0.0;
            for (int a = 0; a < CELL_GL; a++) {
                double y = (i + 0.5 + 0.5 * cell_x[a]) / (NM - 1);
                double mu = mu_of_y(y), dmu = cos(0.5 * GGX_PI * y * y) * GGX_PI * y;
                for (int b = 0; b < CELL_GL; b++) {
                    double phi = e->phi0 + dphi * (j + 0.5 + 0.5 * cell_x[b]);
                    double ev = mu > 0 ? table_albedo(e, view_at(y, phi)) : 0.0;
                    w += cell_w[a] * cell_w[b] * (1.0 - ev) * 2.0 * mu * dmu;
                }
            }
            w *= 0.25 * dphi / (NM - 1); /* the two half-widths of the Gauss-Legendre rule */
            if (!(w > 0)) w = 0.0;
            sum += w;
            e->cdf[i * np + j + 1] = sum;
        }
    e->total = sum;
    e->e_avg = 1.0 - sum / (2.0 * GGX_PI);
    if (e->e_avg < 0) e->e_avg = 0;
    if (e->e_avg > 1) e->e_avg = 1;
    *out = e;
    return GGX_OK;
}

GGX_API void ggx_energy_free(ggx_energy *e) { free(e); }

GGX_API const ggx_shape *ggx_energy_shape(const ggx_energy *e) { return e ? &e->s : NULL; }

GGX_API double ggx_energy_albedo(const ggx_energy *e, ggx_vec3 v)
{
    ggx_vec3 u;
    if (!e || !unit_up(v, &u)) return 0.0;
    return table_albedo(e, u);
}

GGX_API double ggx_energy_albedo_avg(const ggx_energy *e) { return e ? e->e_avg : 0.0; }

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
 * channel) again and again, and the quadrature of a conductor's or dielectric's F costs about 200 ns. Fields compare
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
    double den = 1.0 - fa * (1.0 - e->e_avg);
    return den > 0 ? fa * fa * e->e_avg / den : 0.0;
}

static double ms_fresnel(const ggx_energy *e, const ggx_fresnel *f) { return ms_fresnel_of(e, fresnel_avg_cached(f)); }

/* f_ms given E(wi) (ew) and the factor F_ms. */
static double ms_lobe_e(const ggx_energy *e, double fms, double ew, ggx_vec3 wo)
{
    double loss = 1.0 - e->e_avg;
    if (!(loss > 1e-12)) return 0.0;
    return fms * (1.0 - ew) * (1.0 - table_albedo(e, wo)) / (GGX_PI * loss);
}

static double ms_lobe(const ggx_energy *e, double fms, ggx_vec3 wi, ggx_vec3 wo)
{
    return ms_lobe_e(e, fms, table_albedo(e, wi), wo);
}

GGX_API double ggx_brdf_ms_eval(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo)
{
    if (!f) f = &fresnel_one;
    ggx_vec3 a, b;
    if (!e || !unit_up(wi, &a) || !unit_up(wo, &b)) return 0.0;
    return ms_lobe(e, ms_fresnel(e, f), a, b);
}

/* The cell of a unit w with w.z > 0: row i, column j, and its (t, phi) area. */
static int cell_of(const ggx_energy *e, ggx_vec3 w, double *area)
{
    int i, j;
    double fy, fp;
    table_cell(e, w, &i, &fy, &j, &fp);
    double m0 = mu_of_y((double)i / (NM - 1)), m1 = mu_of_y((double)(i + 1) / (NM - 1));
    *area = (m1 * m1 - m0 * m0) * (2.0 * GGX_PI / e->np);
    return i * e->np + j;
}

static double ms_pdf(const ggx_energy *e, ggx_vec3 w)
{
    if (!(e->total > 0)) return 0.0;
    double area;
    int c = cell_of(e, w, &area);
    double wc = e->cdf[c + 1] - e->cdf[c];
    return area > 0 ? wc / (e->total * area) * 2.0 * w.z : 0.0;
}

GGX_API double ggx_pdf_brdf_ms(const ggx_energy *e, ggx_vec3 wi, ggx_vec3 wo)
{
    ggx_vec3 a, b;
    if (!e || !unit_up(wi, &a) || !unit_up(wo, &b)) return 0.0;
    return ms_pdf(e, b);
}

static double clamp01(double u) { return u >= 0 ? (u < 1 ? u : 0x1.fffffffffffffp-1) : 0.0; }

/* A direction of the lobe's sampling distribution (wi does not matter for it). */
static ggx_vec3 ms_direction(const ggx_energy *e, double u1, double u2)
{
    ggx_vec3 zero = {0, 0, 0};
    if (!(e->total > 0)) return zero;
    int ncell = (NM - 1) * e->np;
    double x = clamp01(u1) * e->total;
    int lo = 0, hi = ncell; /* the cell c with cdf[c] <= x < cdf[c + 1], skipping empty cells */
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (e->cdf[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    double wc = e->cdf[lo + 1] - e->cdf[lo];
    double f = wc > 0 ? (x - e->cdf[lo]) / wc : 0.5;
    f = f >= 0 ? (f <= 1 ? f : 1) : 0;
    int i = lo / e->np, j = lo % e->np;
    double m0 = mu_of_y((double)i / (NM - 1)), m1 = mu_of_y((double)(i + 1) / (NM - 1));
    double t = m0 * m0 + f * (m1 * m1 - m0 * m0);
    double phi = e->phi0 + (j + clamp01(u2)) * (2.0 * GGX_PI / e->np);
    double st = sqrt(fmax(0.0, 1.0 - t));
    ggx_vec3 w = {st * cos(phi), st * sin(phi), sqrt(t)};
    return w;
}

static ggx_sample invalid(void)
{
    ggx_sample r = {{0, 0, 0}, 0.0, 0.0, GGX_EVENT_INVALID};
    return r;
}

GGX_API ggx_sample ggx_sample_brdf_ms(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, double u1, double u2)
{
    if (!f) f = &fresnel_one;
    ggx_vec3 a;
    if (!e || !unit_up(wi, &a)) return invalid();
    ggx_vec3 w = ms_direction(e, u1, u2);
    if (!(w.z > 0)) return invalid();
    double pdf = ms_pdf(e, w);
    if (!(pdf > 0)) return invalid();
    ggx_sample r = {w, pdf, ms_lobe(e, ms_fresnel(e, f), a, w) * w.z / pdf, GGX_EVENT_REFLECT};
    return r;
}

/* Probability of drawing the single-scattering lobe: its albedo estimate F_avg E(wi) against the multiple-
 * scattering lobe's F_ms (1 - E(wi)). Writes E(wi) and F_ms for the caller. */
static double ss_share(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, double *ew, double *fms)
{
    double fa = fresnel_avg_cached(f);
    *ew = table_albedo(e, wi);
    *fms = ms_fresnel_of(e, fa);
    double ss = fa * *ew, ms = (1.0 - e->e_avg > 1e-12) ? *fms * (1.0 - *ew) : 0.0, tot = ss + ms;
    return tot > 0 ? ss / tot : 1.0;
}

GGX_API double ggx_brdf_compensated_eval(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo)
{
    if (!f) f = &fresnel_one;
    ggx_vec3 a, b;
    if (!e || !unit_up(wi, &a) || !unit_up(wo, &b)) return 0.0;
    return ggx_brdf_eval_d(&e->s, f, a, b) + ms_lobe(e, ms_fresnel(e, f), a, b);
}

GGX_API double ggx_pdf_brdf_compensated(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo)
{
    if (!f) f = &fresnel_one;
    ggx_vec3 a, b;
    if (!e || !unit_up(wi, &a) || !unit_up(wo, &b)) return 0.0;
    double ew, fms, p = ss_share(e, f, a, &ew, &fms);
    return p * ggx_pdf_brdf_bounded_d(&e->s, a, b) + (1.0 - p) * ms_pdf(e, b);
}

GGX_API ggx_sample ggx_sample_brdf_compensated(const ggx_energy *e, const ggx_fresnel *f, ggx_vec3 wi, double u1,
                                               double u2, double u3)
{
    if (!f) f = &fresnel_one;
    ggx_vec3 a;
    if (!e || !unit_up(wi, &a)) return invalid();
    double ew, fms, p = ss_share(e, f, a, &ew, &fms);
    ggx_vec3 w;
    double pdf_ss;
    if (clamp01(u3) < p) { /* the sample carries its own pdf, ggx_pdf_brdf_bounded's */
        ggx_sample ss = ggx_sample_brdf_bounded_d(&e->s, f, a, u1, u2);
        if (ss.event != GGX_EVENT_REFLECT) return invalid();
        w = ss.w;
        pdf_ss = ss.pdf;
    } else {
        w = ms_direction(e, u1, u2);
        pdf_ss = ggx_pdf_brdf_bounded_d(&e->s, a, w); /* 0 for w.z <= 0, which is refused below */
    }
    if (!(w.z > 0)) return invalid();
    double pdf = p * pdf_ss + (1.0 - p) * ms_pdf(e, w);
    if (!(pdf > 0)) return invalid();
    double fr = ggx_brdf_eval_d(&e->s, f, a, w) + ms_lobe_e(e, fms, ew, w);
    ggx_sample r = {w, pdf, fr * w.z / pdf, GGX_EVENT_REFLECT};
    return r;
}
