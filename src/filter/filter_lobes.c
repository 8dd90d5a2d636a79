/* The ellipsoid closest to a mixture of lobes (ggx_filter.h): EM for the Student t over each lobe's quadrature
 * nodes, the texel's lobe, and the KL divergence of a shape from the mixture (docs/design/filter.md).
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/gauss.h"
#include "filter.h"

ggx_status filter_settings_of(const ggx_filter_options *opt, filter_settings *f)
{
    ggx_filter_options o;
    if (opt) o = *opt;
    else memset(&o, 0, sizeof o);
    if (o.max_iterations < 0 || o.radial_nodes < 0 || o.angular_nodes < 0 || !(o.tolerance >= 0.0) || o.threads < 0 ||
        o.threads > FILTER_MAX_THREADS || o.radial_nodes > FILTER_MAX_RADIAL || o.angular_nodes > FILTER_MAX_ANGULAR ||
        o.angular_nodes % 2 != 0 || o.radial_nodes == 1 || o.angular_nodes == 2)
        return GGX_ERR_RANGE;
    f->max_iterations = o.max_iterations ? o.max_iterations : 500;
    f->tolerance = o.tolerance > 0.0 ? o.tolerance : 1e-10;
    f->radial = o.radial_nodes ? o.radial_nodes : 8;
    f->angular = o.angular_nodes ? o.angular_nodes : 16;
    f->threads = o.threads ? o.threads : 1;
    return GGX_OK;
}

GGX_API ggx_status ggx_filter_options_fast(ggx_filter_options *o)
{
    if (!o) return GGX_ERR_NULL;
    o->radial_nodes = 2, o->angular_nodes = 4, o->max_iterations = 1;
    return GGX_OK;
}

ggx_status filter_rule_make(const filter_settings *f, filter_rule *r)
{
    int nr = f->radial, na = f->angular;
    r->n = nr * na;
    r->zx = malloc(3 * (size_t)r->n * sizeof *r->zx);
    double *xs = malloc(2 * (size_t)nr * sizeof *xs);
    if (!r->zx || !xs) {
        free(r->zx), free(xs);
        return GGX_ERR_MEMORY;
    }
    r->zy = r->zx + r->n, r->q = r->zy + r->n;
    double *ws = xs + nr;
    gq_nodes(nr, xs, ws);
    for (int j = 0; j < nr; j++) {
        double s = 0.5 * (1.0 + xs[j]), om = 1.0 - s; /* 1 - s, exact for s >= 1/2 and the rule's s below it */
        double rho = sqrt(s * (2.0 - s)) / om;
        double wq = 0.5 * ws[j] * 2.0 * om / na;
        for (int k = 0; k < na; k++) {
            double c, sn;
            ggx_k_sincos_turn_d((k + 0.5) / na, &c, &sn);
            r->zx[j * na + k] = rho * c, r->zy[j * na + k] = rho * sn, r->q[j * na + k] = wq;
        }
    }
    free(xs);
    return GGX_OK;
}

void filter_rule_free(filter_rule *r) { free(r->zx); }

void filter_lobe_set(filter_lobe *b, const double t[2], const double sigma[3], double w)
{
    b->t[0] = t[0], b->t[1] = t[1];
    memcpy(b->sigma, sigma, sizeof b->sigma);
    b->l[0] = sqrt(sigma[0]);
    b->l[1] = sigma[1] / b->l[0];
    b->l[2] = sqrt(fmax(sigma[2] - b->l[1] * b->l[1], 0.0));
    fit_inverse(sigma, b->p);
    b->w = w;
    b->log_norm = log(GGX_PI) + 0.5 * fit_log_det(sigma);
}

/* The lobes of the shapes with their shares of the weights, and the rule of f: what ggx_filter_lobes and
 * ggx_filter_kl work on (free both with filter_release). */
static ggx_status lobes_make(const ggx_shape *lobes, const double *weight, size_t n, const filter_settings *f,
                             filter_lobe **out, filter_rule *r)
{
    if (n == 0) return GGX_ERR_RANGE;
    double W = 0.0;
    for (size_t i = 0; i < n; i++) {
        double w = weight ? weight[i] : 1.0;
        if (!(w >= 0.0) || !isfinite(w)) return GGX_ERR_RANGE;
        W += w;
    }
    if (!(W > 0.0) || !isfinite(W)) return GGX_ERR_RANGE;
    filter_lobe *L = malloc(n * sizeof *L);
    if (!L) return GGX_ERR_MEMORY;
    for (size_t i = 0; i < n; i++) {
        double t[2], sg[3];
        ggx_shape_slopes(&lobes[i], t, sg);
        filter_lobe_set(&L[i], t, sg, (weight ? weight[i] : 1.0) / W);
    }
    ggx_status st = filter_rule_make(f, r);
    if (st != GGX_OK) {
        free(L);
        return st;
    }
    *out = L;
    return GGX_OK;
}

static void filter_release(filter_lobe *L, filter_rule *r)
{
    free(L);
    filter_rule_free(r);
}

/* (x, y) P (x, y)^T for a symmetric P = (p_xx, p_xy, p_yy): delta of a slope offset against Sigma^-1 = P. */
static inline double quad_form(const double p[3], double x, double y)
{
    return p[0] * x * x + 2.0 * p[1] * x * y + p[2] * y * y;
}

/* log P22 of lobe b at slope (x, y), plus log of its share. */
static inline double lobe_log_density(const filter_lobe *b, double x, double y)
{
    return log(b->w) - b->log_norm - 2.0 * log1p(quad_form(b->p, x - b->t[0], y - b->t[1]));
}

/* The node k of lobe b, about c: r = t_b - c + L_b z_k. */
static inline void node(const filter_lobe *b, const filter_rule *r, int k, const double c[2], double *rx, double *ry)
{
    *rx = b->t[0] - c[0] + b->l[0] * r->zx[k];
    *ry = b->t[1] - c[1] + b->l[1] * r->zx[k] + b->l[2] * r->zy[k];
}

/* The E step at (t, Sigma^-1 = p) over every lobe's nodes, in the layout of fit_mstep (W = 1); the sum of
 * w log(1 + delta), for the log-likelihood, only when want_ll is set. */
static void estep(const filter_lobe *L, size_t n, const filter_rule *r, const double t[2], const double p[3],
                  int want_ll, double a[FIT_ESTEP_SUMS])
{
    memset(a, 0, FIT_ESTEP_SUMS * sizeof *a);
    for (size_t i = 0; i < n; i++) {
        if (L[i].w == 0.0) continue;
        double s[FIT_ESTEP_SUMS] = {0};
        for (int k = 0; k < r->n; k++) {
            double x, y;
            node(&L[i], r, k, t, &x, &y);
            double d = quad_form(p, x, y), q = r->q[k], c = q / (1.0 + d);
            s[1] += c, s[2] += c * x, s[3] += c * y;
            s[4] += c * x * x, s[5] += c * x * y, s[6] += c * y * y;
            if (want_ll) s[7] += q * log1p(d);
        }
        a[0] += L[i].w;
        for (int j = 1; j < FIT_ESTEP_SUMS; j++) a[j] += L[i].w * s[j];
    }
}

static double log_likelihood(const double sigma[3], const double a[FIT_ESTEP_SUMS])
{
    return -log(GGX_PI) - 0.5 * fit_log_det(sigma) - 2.0 * a[7] / a[0];
}

int filter_em(const filter_lobe *L, size_t n, const filter_rule *r, const filter_settings *f, double t[2], double s[3],
              int *converged, double *ll)
{
    /* the start: the lobes' mean location and their mean scale plus the locations' spread */
    t[0] = t[1] = 0.0, s[0] = s[1] = s[2] = 0.0;
    for (size_t i = 0; i < n; i++) t[0] += L[i].w * L[i].t[0], t[1] += L[i].w * L[i].t[1];
    for (size_t i = 0; i < n; i++) {
        double dx = L[i].t[0] - t[0], dy = L[i].t[1] - t[1];
        s[0] += L[i].w * (L[i].sigma[0] + dx * dx);
        s[1] += L[i].w * (L[i].sigma[1] + dx * dy);
        s[2] += L[i].w * (L[i].sigma[2] + dy * dy);
    }
    /* Sigma's eigenvalues held in [GGX_ALPHA_MIN^2, GGX_ALPHA_MAX^2]: the constrained M step (docs/design/fit.md);
     * the top 1e-14 below it, so that Sigma rebuilt from its clamped eigenvalues, a few ulp off, stays a shape */
    const double lo = GGX_ALPHA_MIN * GGX_ALPHA_MIN, hi = GGX_ALPHA_MAX * GGX_ALPHA_MAX * (1.0 - 1e-14);
    fit_clamp_sigma_range(s, lo, hi);
    int it = 0;
    double a[FIT_ESTEP_SUMS], p[3];
    *converged = 0;
    while (it < f->max_iterations) {
        fit_inverse(s, p);
        estep(L, n, r, t, p, 0, a);
        double tn[2], sn[3];
        fit_mstep(a, t, GGX_FIT_ELLIPSOID, tn, sn);
        fit_clamp_sigma_range(sn, lo, hi);
        double ch = fit_change(t, s, tn, sn);
        memcpy(t, tn, 2 * sizeof *t), memcpy(s, sn, 3 * sizeof *s);
        it++;
        if (!(ch > f->tolerance)) {
            *converged = ch <= f->tolerance;
            break;
        }
    }
    if (ll) {
        fit_inverse(s, p);
        estep(L, n, r, t, p, 1, a);
        *ll = log_likelihood(s, a);
    }
    return it;
}

GGX_API ggx_status ggx_filter_lobes(ggx_shape *out, const ggx_shape *lobes, const double *weight, size_t n,
                                    const ggx_filter_options *opt, ggx_filter_info *info)
{
    if (!out || !lobes) return GGX_ERR_NULL;
    filter_settings f;
    ggx_status st = filter_settings_of(opt, &f);
    if (st != GGX_OK) return st;
    filter_lobe *L;
    filter_rule r;
    if ((st = lobes_make(lobes, weight, n, &f, &L, &r)) != GGX_OK) return st;
    double t[2], s[3], ll;
    int converged, it = filter_em(L, n, &r, &f, t, s, &converged, &ll);
    filter_release(L, &r);
    ggx_shape res;
    st = ggx_shape_from_slopes(&res, t[0], t[1], s[0], s[1], s[2]);
    if (st != GGX_OK) return st;
    *out = res;
    if (info) info->iterations = it, info->converged = converged, info->log_likelihood = ll;
    return GGX_OK;
}

GGX_API ggx_status ggx_filter_kl(const ggx_shape *sh, const ggx_shape *lobes, const double *weight, size_t n,
                                 const ggx_filter_options *opt, double *kl)
{
    if (!sh || !lobes || !kl) return GGX_ERR_NULL;
    filter_settings f;
    ggx_status st = filter_settings_of(opt, &f);
    if (st != GGX_OK) return st;
    /* its own default rule, finer than the filter's: the log of the mixture is harder to integrate than the E step */
    if (!opt || !opt->radial_nodes) f.radial = 32;
    if (!opt || !opt->angular_nodes) f.angular = 64;
    filter_lobe *L;
    filter_rule r;
    if ((st = lobes_make(lobes, weight, n, &f, &L, &r)) != GGX_OK) return st;
    double ts[2], ss[3];
    ggx_shape_slopes(sh, ts, ss);
    filter_lobe S; /* the shape, as a lobe of share 1 */
    filter_lobe_set(&S, ts, ss, 1.0);
    const double zero[2] = {0.0, 0.0};
    double total = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (L[i].w == 0.0) continue;
        double sum = 0.0;
        for (int k = 0; k < r.n; k++) {
            double x, y;
            node(&L[i], &r, k, zero, &x, &y); /* the slope itself */
            /* log mix(x) by log-sum-exp over the lobes, about the largest term */
            double top = -HUGE_VAL, acc = 0.0;
            for (size_t j = 0; j < n; j++) {
                if (L[j].w == 0.0) continue;
                double lj = lobe_log_density(&L[j], x, y);
                if (lj > top) acc = acc * exp(top - lj) + 1.0, top = lj;
                else acc += exp(lj - top);
            }
            sum += r.q[k] * (top + log(acc) - lobe_log_density(&S, x, y));
        }
        total += L[i].w * sum;
    }
    filter_release(L, &r);
    *kl = total;
    return GGX_OK;
}

/* The slope parameters of a texel's lobe (ggx_texel_lobe's checks, in its order). */
static ggx_status texel_params(ggx_vec3 nrm, double alpha_x, double alpha_y, double phi, double c[GGX_LOBE_PARAMS])
{
    if (!isfinite(alpha_x) || !isfinite(alpha_y) || !isfinite(phi)) return GGX_ERR_NONFINITE;
    if (!(alpha_x > 0.0 && alpha_y > 0.0 && alpha_x <= GGX_ALPHA_MAX && alpha_y <= GGX_ALPHA_MAX)) return GGX_ERR_ALPHA;
    if (!isfinite(nrm.x) || !isfinite(nrm.y) || !isfinite(nrm.z)) return GGX_ERR_NONFINITE;
    if (!(nrm.z > 0.0)) return GGX_ERR_RANGE;
    double tx = -nrm.x / nrm.z, ty = -nrm.y / nrm.z;
    if (!(fabs(tx) <= GGX_MATRIX_SCALE_MAX && fabs(ty) <= GGX_MATRIX_SCALE_MAX)) return GGX_ERR_RANGE;
    double ax = fmax(alpha_x, GGX_ALPHA_MIN), ay = fmax(alpha_y, GGX_ALPHA_MIN), co = cos(phi), si = sin(phi);
    double lx = ax * ax, ly = ay * ay;
    c[0] = tx, c[1] = ty;
    c[2] = lx * co * co + ly * si * si, c[3] = (lx - ly) * co * si, c[4] = lx * si * si + ly * co * co;
    return GGX_OK;
}

ggx_status filter_params_check(const double c[GGX_LOBE_PARAMS])
{
    /* Clearly inside: every entry finite, Sigma positive definite with room for rounding, its eigenvalues (below the
     * trace tr) under GGX_ALPHA_MAX^2 / 2, and A = [Sigma^(1/2) 0; -t^T 1] (|det A| >= sqrt(det Sigma), ||A||_F^2 <=
     * tr + 2 GGX_ALPHA_MIN^2 + |t|^2 + 1) conditioned and scaled 4 times inside ggx_shape_matrix's bounds. */
    double tx = c[0], ty = c[1], sxx = c[2], sxy = c[3], syy = c[4], tr = sxx + syy, d = sxx * syy - sxy * sxy;
    double f2 = tr + 2.0 * GGX_ALPHA_MIN * GGX_ALPHA_MIN + tx * tx + ty * ty + 1.0;
    if (sxx > 0.0 && syy > 0.0 && d > 1e-6 * sxx * syy && tr <= 0.5 * GGX_ALPHA_MAX * GGX_ALPHA_MAX &&
        f2 <= 1e-2 * GGX_MATRIX_SCALE_MAX * GGX_MATRIX_SCALE_MAX && sqrt(d) > 4.0 * GGX_SINGULAR_TOL * f2 * sqrt(f2))
        return GGX_OK; /* false for NaN; an infinite entry makes f2 or d infinite or NaN */
    ggx_shape s;
    return ggx_shape_from_slopes(&s, tx, ty, sxx, sxy, syy);
}

/* texel_params, and the lobe is a shape (ggx_shape_from_slopes accepts it) */
static ggx_status texel_shape(ggx_vec3 nrm, double alpha_x, double alpha_y, double phi, double c[GGX_LOBE_PARAMS],
                              ggx_shape *s)
{
    ggx_status st = texel_params(nrm, alpha_x, alpha_y, phi, c);
    return st != GGX_OK ? st : ggx_shape_from_slopes(s, c[0], c[1], c[2], c[3], c[4]);
}

GGX_API ggx_status ggx_texel_lobe(ggx_shape *out, ggx_vec3 nrm, double alpha_x, double alpha_y, double phi)
{
    if (!out) return GGX_ERR_NULL;
    double c[GGX_LOBE_PARAMS];
    ggx_shape res;
    ggx_status st = texel_shape(nrm, alpha_x, alpha_y, phi, c, &res);
    if (st != GGX_OK) return st;
    *out = res;
    return GGX_OK;
}

/* The lobes of n texels of roughness (ax[i] or ax0, ay[i] or ay0), rejected ones as ggx_texel_lobes says; returns
 * how many were rejected. Map roughness in [0, GGX_ALPHA_MIN) is raised to GGX_ALPHA_MIN (texel_params refuses 0). */
static size_t lobes_fill(double *lobes, double *weight, const ggx_vec3 *normals, size_t n, const double *ax,
                         const double *ay, double ax0, double ay0, double phi)
{
    size_t bad = 0;
    for (size_t i = 0; i < n; i++) {
        double *c = lobes + GGX_LOBE_PARAMS * i;
        double x = ax ? ax[i] : ax0, y = ay ? ay[i] : ax ? x : ay0;
        if (x >= 0.0 && x < GGX_ALPHA_MIN) x = GGX_ALPHA_MIN;
        if (y >= 0.0 && y < GGX_ALPHA_MIN) y = GGX_ALPHA_MIN;
        ggx_status ti = texel_params(normals[i], x, y, phi, c);
        weight[i] = ti == GGX_OK && filter_params_check(c) == GGX_OK;
        if (weight[i] == 0.0) bad++, c[0] = c[1] = c[3] = 0.0, c[2] = c[4] = 1.0;
    }
    return bad;
}

GGX_API ggx_status ggx_texel_lobes(double *lobes, double *weight, const ggx_vec3 *normals, size_t n, double alpha_x,
                                   double alpha_y, double phi, size_t *rejected)
{
    if (!lobes || !weight || !normals) return GGX_ERR_NULL;
    ggx_vec3 up = {0.0, 0.0, 1.0};
    double probe[GGX_LOBE_PARAMS];
    ggx_shape s;
    ggx_status st = texel_shape(up, alpha_x, alpha_y, phi, probe, &s); /* the roughness, before anything is written */
    if (st != GGX_OK) return st;
    size_t bad = lobes_fill(lobes, weight, normals, n, NULL, NULL, alpha_x, alpha_y, phi);
    if (rejected) *rejected = bad;
    return GGX_OK;
}

GGX_API ggx_status ggx_texel_lobes_roughness(double *lobes, double *weight, const ggx_vec3 *normals,
                                             const double *alpha_x, const double *alpha_y, size_t n, double phi,
                                             size_t *rejected)
{
    if (!lobes || !weight || !normals || !alpha_x) return GGX_ERR_NULL;
    if (!isfinite(phi)) return GGX_ERR_NONFINITE;
    size_t bad = lobes_fill(lobes, weight, normals, n, alpha_x, alpha_y, 0.0, 0.0, phi);
    if (rejected) *rejected = bad;
    return GGX_OK;
}
