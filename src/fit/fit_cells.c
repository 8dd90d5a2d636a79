/* ggx_fit_normal_cells: normals known only to a square cell of their (n_x, n_y) components, the texels of a quantised
 * normal map, fitted by the likelihood of the cells (docs/design/fit.md, "Quantised normal maps").
 * SPDX-License-Identifier: MIT */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "common/gauss.h"
#include "fit.h"

enum { CELL_Q = 8 }; /* CELL_Q x CELL_Q Gauss-Legendre points per cell */
_Static_assert(CELL_Q *CELL_Q == FIT_CELL_POINTS && FIT_PIECE % FIT_CELL_POINTS == 0 &&
                   FIT_CHUNK % FIT_CELL_POINTS == 0,
               "a cell's points fill whole pieces and chunks");

/* The distinct cells: centres (u, v) of half-width hq, summed weights; the quadrature's nodes and weights on
 * [-1, 1]. */
typedef struct cell_set {
    size_t n;
    double *u, *v, *wt;
    double hq;
    double node[CELL_Q], gw[CELL_Q];
} cell_set;

/* The quadrature points of cell c: slopes x~ = -(n_x, n_y) / n_z of the points (u + hq xi_i, v + hq xi_j) of the
 * cell, and their area weights in slope space, hq^2 w_i w_j / n_z^4 (dx~ dy~ = dn_x dn_y / n_z^4); 0, with slope 0,
 * for a point outside the unit disk (no normal) or so near its rim that n_z^4 could underflow. */
static void cell_points(const cell_set *cs, size_t c, double *x, double *y, double *a)
{
    for (int i = 0; i < CELL_Q; i++)
        for (int j = 0; j < CELL_Q; j++) {
            int k = i * CELL_Q + j;
            double nx = cs->u[c] + cs->hq * cs->node[i], ny = cs->v[c] + cs->hq * cs->node[j];
            double z2 = 1.0 - nx * nx - ny * ny;
            int in = z2 > 1e-12;
            double nz = sqrt(in ? z2 : 1.0);
            x[k] = in ? -nx / nz : 0.0, y[k] = in ? -ny / nz : 0.0;
            a[k] = in ? cs->hq * cs->hq * cs->gw[i] * cs->gw[j] / (z2 * z2) : 0.0;
        }
}

/* fit_source's fill for cells (fit.h, "censored"): the points of cells [i0 / 64, (i0 + k) / 64), weighted by the
 * cell's weight times their shares a_k f_k / sum a f of its probability under the density at `at`; returns
 * L = sum_c n_c log sum_k a_k f_k. The Gaussian's f is taken relative to the cell's largest, so that no share
 * underflows to 0 / 0. */
static double fill_cells(const void *ctx, const fit_point *at, size_t i0, size_t k, double *x, double *y, double *w)
{
    const cell_set *cs = ctx;
    const double t0 = at->t[0], t1 = at->t[1], p0 = at->p[0], p1 = at->p[1], p2 = at->p[2];
    double L = 0.0;
    for (size_t s = 0; s < k; s += FIT_CELL_POINTS) {
        size_t c = (i0 + s) / FIT_CELL_POINTS;
        double *xs = x + s, *ys = y + s, *ws = w + s, f[FIT_CELL_POINTS], a[FIT_CELL_POINTS];
        cell_points(cs, c, xs, ys, a);
        double big = -HUGE_VAL;
        for (int j = 0; j < FIT_CELL_POINTS; j++) {
            double rx = xs[j] - t0, ry = ys[j] - t1, delta = p0 * rx * rx + 2.0 * p1 * rx * ry + p2 * ry * ry;
            f[j] = at->gaussian ? -0.5 * delta : 1.0 / ((1.0 + delta) * (1.0 + delta));
            if (a[j] > 0.0 && f[j] > big) big = f[j];
        }
        if (at->gaussian) /* a point outside the disk (a = 0) may lie far above the cell's largest */
            for (int j = 0; j < FIT_CELL_POINTS; j++) f[j] = a[j] > 0.0 ? exp(f[j] - big) : 0.0;
        double sum = 0.0;
        for (int j = 0; j < FIT_CELL_POINTS; j++) sum += a[j] * f[j];
        /* sum > 0: every cell kept has a point inside the disk (cells_build), whose share is positive */
        double scale = cs->wt[c] / sum;
        for (int j = 0; j < FIT_CELL_POINTS; j++) ws[j] = a[j] * f[j] * scale;
        L += cs->wt[c] * (log(sum) + (at->gaussian ? big : 0.0));
    }
    return L;
}

static uint64_t hash_pair(double u, double v)
{
    uint64_t a, b;
    memcpy(&a, &u, sizeof a);
    memcpy(&b, &v, sizeof b);
    uint64_t h = a * 0x9e3779b97f4a7c15u ^ (b + 0x632be59bd9b4e019u + (a << 6) + (a >> 2));
    h ^= h >> 31;
    h *= 0xbf58476d1ce4e5b9u;
    return h ^ (h >> 29);
}

/* The distinct cells of the texels, in the order of their first texel, by a hash of the centres' bits; each texel
 * used or counted into info by why not (a cell with no point inside the disk: the horizon). GGX_ERR_RANGE for a
 * negative weight (the other texels counted); GGX_ERR_MEMORY. */
static ggx_status cells_build(cell_set *cs, const double *uv, const double *weight, size_t n, double *w2_sum,
                              ggx_fit_info *info)
{
    double wmax = 0.0;
    int negative = 0;
    for (size_t i = 0; i < n; i++) {
        double wi = weight ? weight[i] : 1.0;
        if (!isfinite(uv[2 * i]) || !isfinite(uv[2 * i + 1]) || !isfinite(wi)) continue; /* non-finite first */
        if (wi > wmax) wmax = wi;
        negative |= wi < 0.0;
    }
    double wscale = wmax > 0.0 ? 1.0 / wmax : 1.0;
    if (!(wscale < HUGE_VAL)) wscale = 0x1p1000; /* a subnormal largest weight */
    size_t cap = 1024, *slot = NULL;             /* slot: cell index + 1, 0 empty */
    size_t have = 0;
    *w2_sum = 0.0;
    ggx_status st = GGX_OK;
    if (!(slot = calloc(cap, sizeof *slot))) return GGX_ERR_MEMORY;
    double px[FIT_CELL_POINTS], py[FIT_CELL_POINTS], pa[FIT_CELL_POINTS];
    for (size_t i = 0; i < n && st == GGX_OK; i++) {
        double u = uv[2 * i], v = uv[2 * i + 1], wi = weight ? weight[i] : 1.0;
        if (!isfinite(u) || !isfinite(v) || !isfinite(wi)) {
            info->ignored_nonfinite++;
            continue;
        }
        if (wi <= 0.0) {
            if (wi == 0.0) info->ignored_weight++; /* a negative weight: an error, after the others are counted */
            continue;
        }
        u += 0.0, v += 0.0; /* -0 and 0: one cell */
        uint64_t h = hash_pair(u, v);
        size_t at = (size_t)h & (cap - 1);
        while (slot[at] && !(cs->u[slot[at] - 1] == u && cs->v[slot[at] - 1] == v)) at = (at + 1) & (cap - 1);
        size_t c;
        if (slot[at]) {
            c = slot[at] - 1;
        } else { /* a new cell: kept when part of it lies inside the disk */
            if (cs->n == have) {
                size_t nh = have ? 2 * have : 256;
                double *nu = realloc(cs->u, nh * sizeof *nu);
                if (nu) cs->u = nu;
                double *nv = nu ? realloc(cs->v, nh * sizeof *nv) : NULL;
                if (nv) cs->v = nv;
                double *nw = nv ? realloc(cs->wt, nh * sizeof *nw) : NULL;
                if (nw) cs->wt = nw;
                if (!nw) {
                    st = GGX_ERR_MEMORY;
                    break;
                }
                have = nh;
            }
            c = cs->n;
            cs->u[c] = u, cs->v[c] = v, cs->wt[c] = 0.0;
            cell_points(cs, c, px, py, pa);
            double area = 0.0;
            for (int j = 0; j < FIT_CELL_POINTS; j++) area += pa[j];
            if (!(area > 0.0)) {
                info->ignored_horizon++;
                continue; /* not entered: every such texel is counted again */
            }
            cs->n++;
            slot[at] = c + 1;
            if (2 * cs->n > cap) { /* grow the table, entries again in cell order */
                size_t ncap = 2 * cap, *ns = calloc(ncap, sizeof *ns);
                if (!ns) {
                    st = GGX_ERR_MEMORY;
                    break;
                }
                for (size_t e = 0; e < cs->n; e++) {
                    size_t b = (size_t)hash_pair(cs->u[e], cs->v[e]) & (ncap - 1);
                    while (ns[b]) b = (b + 1) & (ncap - 1);
                    ns[b] = e + 1;
                }
                free(slot);
                slot = ns, cap = ncap;
            }
        }
        double ws = wi * wscale;
        cs->wt[c] += ws;
        *w2_sum += ws * ws;
        info->used++;
    }
    free(slot);
    return st == GGX_OK && negative ? GGX_ERR_RANGE : st;
}

GGX_API ggx_status ggx_fit_normal_cells(ggx_shape *out, const double *uv, const double *weight, size_t n, double q,
                                        const ggx_fit_options *opt, ggx_fit_info *info)
{
    ggx_fit_info local;
    ggx_fit_info *inf = info ? info : &local;
    memset(inf, 0, sizeof *inf);
    if (!out || (!uv && n > 0)) return GGX_ERR_NULL;
    if (!isfinite(q)) return GGX_ERR_NONFINITE;
    if (!(q > 0.0) || q > 2.0) return GGX_ERR_RANGE;
    fit_data check;
    ggx_fit_model model;
    ggx_status st = fit_settings(opt, &check, &model);
    if (st != GGX_OK) return st;
    cell_set cs;
    memset(&cs, 0, sizeof cs);
    cs.hq = 0.5 * q;
    gq_nodes(CELL_Q, cs.node, cs.gw);
    double w2 = 0.0;
    st = cells_build(&cs, uv, weight, n, &w2, inf);
    if (st == GGX_OK && inf->used < 5) st = GGX_ERR_DATA;
    if (st == GGX_OK) {
        double W = 0.0;
        for (size_t c = 0; c < cs.n; c++) W += cs.wt[c];
        fit_source src = {fill_cells, &cs, cs.n * FIT_CELL_POINTS, 0, 1, W * W / w2, 0.64 * cs.hq * cs.hq};
        ggx_shape s;
        st = fit_run(&src, opt, &s, inf);
        if (st == GGX_OK) *out = s;
    }
    if (st != GGX_OK) {
        ggx_fit_info keep = *inf;
        memset(inf, 0, sizeof *inf);
        inf->used = keep.used, inf->ignored_horizon = keep.ignored_horizon;
        inf->ignored_nonfinite = keep.ignored_nonfinite, inf->ignored_weight = keep.ignored_weight;
    }
    free(cs.u), free(cs.v), free(cs.wt);
    return st;
}
