/* The fits' passes over a source of slopes: fixed units of samples, each unit's sums kept apart and added in unit
 * order, so that any thread count gives the same bits. SPDX-License-Identifier: MIT */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "common/parallel.h"
#include "fit.h"

static int pass_sums(fit_pass_kind kind, const fit_point *at)
{
    switch (kind) {
    case FIT_PASS_MOMENTS: return FIT_MOMENT_SUMS;
    case FIT_PASS_ESTEP: return FIT_ESTEP_SUMS;
    case FIT_PASS_HESSIAN: return FIT_HESSIAN_SUMS;
    case FIT_PASS_CELLS: return at->cells * at->cells;
    }
    return 0;
}

/* Sum of log q_i for q_i >= 1 (the E-step's 1 + delta): SUM_LANES running products, each multiplied by two samples
 * at a time, whose exponents are taken from the bits and whose mantissas are carried in [1, 2), and one log per call
 * (of the lanes' product), instead of a log per sample. The lanes are independent, so the loop vectorises. The
 * result differs from the sum of logs by rounding only: each step rounds twice (relative 2^-53 each, so 2^-53 in the
 * log), about k rounding errors of at most 2^-53 in the sum of k samples. A call with a q_i at or above 2^500 (a
 * sample near the horizon, where a product could overflow) sums the logs. */
enum { SUM_LANES = 8 };

static inline double sum_log(const double *q, size_t k)
{
    int big = 0;
    for (size_t i = 0; i < k; i++) big += q[i] >= 0x1p500;
    double sum = 0.0;
    if (big) {
        for (size_t i = 0; i < k; i++) sum += log(q[i]);
        return sum;
    }
    double m[SUM_LANES];
    uint64_t e[SUM_LANES]; /* the biased exponents taken out, 1023 per step and lane more than the true ones */
    for (int l = 0; l < SUM_LANES; l++) m[l] = 1.0, e[l] = 0;
    size_t i = 0, steps = 0;
    for (; i + 2 * SUM_LANES <= k; i += 2 * SUM_LANES, steps++)
        for (int l = 0; l < SUM_LANES; l++) {
            double p = m[l] * (q[i + l] * q[i + SUM_LANES + l]); /* in [1, 2^1001) */
            uint64_t b;
            memcpy(&b, &p, sizeof b);
            e[l] += b >> 52; /* p >= 1: no sign bit, no subnormal */
            b = (b & 0x000fffffffffffffu) | 0x3ff0000000000000u;
            memcpy(&m[l], &b, sizeof b);
        }
    for (; i < k; i++) sum += log(q[i]);
    double mp = 1.0; /* below 2^SUM_LANES */
    uint64_t et = 0;
    for (int l = 0; l < SUM_LANES; l++) et += e[l], mp *= m[l];
    return sum + log(mp) + ((double)et - 1023.0 * (double)(steps * SUM_LANES)) * 0.69314718055994530942;
}

/* sum w_i log(1 + d_i): by sum_log of q_i = 1 + w_i d_i when every weight is 0 or 1 (then q_i = (1 + d_i)^w_i),
 * else a log1p per sample. */
static double weighted_log_sum(const double *q, const double *d, const double *w, size_t k, int general)
{
    if (!general) return sum_log(q, k);
    double l = 0.0;
    for (size_t i = 0; i < k; i++) l += w[i] != 0.0 ? w[i] * log1p(d[i]) : 0.0;
    return l;
}

/* The sums of samples [i0, i1) into s (zeroed by the caller). Every loop is free of branches (a skipped sample has
 * w = 0 and finite slopes, so it adds zeros) and vectorises; the x86-64-v3 and x86-64-v4 clones run them 4 and 8
 * wide. */
GGX_HOT_WIDE static void unit_sums(const fit_source *src, fit_pass_kind kind, const fit_point *at, size_t i0, size_t i1,
                                   double *s)
{
    double x[FIT_CHUNK], y[FIT_CHUNK], w[FIT_CHUNK], q[FIT_CHUNK], dl[FIT_CHUNK], cb[FIT_CHUNK];
    const double t0 = at->t[0], t1 = at->t[1], p0 = at->p[0], p1 = at->p[1], p2 = at->p[2];
    for (size_t at0 = i0; at0 < i1; at0 += FIT_CHUNK) {
        size_t k = i1 - at0 < FIT_CHUNK ? i1 - at0 : FIT_CHUNK;
        double own = src->fill(src->ctx, at, at0, k, x, y, w); /* censored sources: their log term */
        if (kind == FIT_PASS_MOMENTS) {
            /* log cos theta = -log(1 + |x~|^2) / 2, summed through sum_log (a log per chunk) when asked */
            double a0 = 0, a1 = 0, a2 = 0, a3 = 0, a4 = 0, a5 = 0, a7 = 0, unit = 0;
#pragma omp simd reduction(+ : a0, a1, a2, a3, a4, a5, a7, unit)
            for (size_t i = 0; i < k; i++) {
                double wi = w[i], rx = x[i] - t0, ry = y[i] - t1;
                a0 += wi, a1 += wi * rx, a2 += wi * ry;
                a3 += wi * rx * rx, a4 += wi * rx * ry, a5 += wi * ry * ry;
                a7 += wi * wi;
                dl[i] = x[i] * x[i] + y[i] * y[i];
                q[i] = 1.0 + wi * dl[i];
                unit += wi != 0.0 && wi != 1.0;
            }
            double a6 = src->censored ? own : at->cells == 1 ? -0.5 * weighted_log_sum(q, dl, w, k, unit != 0.0) : 0.0;
            s[0] += a0, s[1] += a1, s[2] += a2, s[3] += a3, s[4] += a4, s[5] += a5, s[6] += a6, s[7] += a7;
        } else if (kind == FIT_PASS_ESTEP) {
            double a0 = 0, a1 = 0, a2 = 0, a3 = 0, a4 = 0, a5 = 0, a6 = 0, unit = 0;
#pragma omp simd reduction(+ : a0, a1, a2, a3, a4, a5, a6, unit)
            for (size_t i = 0; i < k; i++) {
                double wi = w[i], rx = x[i] - t0, ry = y[i] - t1;
                double delta = p0 * rx * rx + 2.0 * p1 * rx * ry + p2 * ry * ry, wc = wi / (1.0 + delta);
                a0 += wi, a1 += wc, a2 += wc * rx, a3 += wc * ry;
                a4 += wc * rx * rx, a5 += wc * rx * ry, a6 += wc * ry * ry;
                dl[i] = delta;
                q[i] = 1.0 + wi * delta;        /* (1 + delta)^w for w in {0, 1} */
                unit += wi != 0.0 && wi != 1.0; /* a weight other than 0 and 1 */
            }
            double lsum = src->censored ? -0.5 * own : weighted_log_sum(q, dl, w, k, unit != 0.0);
            s[0] += a0, s[1] += a1, s[2] += a2, s[3] += a3, s[4] += a4, s[5] += a5, s[6] += a6, s[7] += lsum;
        } else if (kind == FIT_PASS_HESSIAN) {
            /* With q = P r, c = 1 / (1 + delta) and e = (qx^2, 2 qx qy, qy^2): W, sum w c, sum w c q (2),
             * sum w c q q^T (3), sum w c^2 q q^T (3), sum w c^2 q e^T (2 x 3), sum w c^2 e e^T (6), sum w log(1 + delta). */
            /* three loops of at most nine sums each (one loop of 22 spilled them): the first keeps c, the others
             * make q again */
            double a0 = 0, a1 = 0, a2 = 0, a3 = 0, a4 = 0, a5 = 0, a6 = 0, unit = 0;
#pragma omp simd reduction(+ : a0, a1, a2, a3, a4, a5, a6, unit)
            for (size_t i = 0; i < k; i++) {
                double wi = w[i], rx = x[i] - t0, ry = y[i] - t1;
                double qx = p0 * rx + p1 * ry, qy = p1 * rx + p2 * ry, delta = qx * rx + qy * ry;
                double c = 1.0 / (1.0 + delta), wc = wi * c;
                a0 += wi, a1 += wc, a2 += wc * qx, a3 += wc * qy;
                a4 += wc * qx * qx, a5 += wc * qx * qy, a6 += wc * qy * qy;
                cb[i] = c;
                dl[i] = delta;
                q[i] = 1.0 + wi * delta;
                unit += wi != 0.0 && wi != 1.0;
            }
            double b0 = 0, b1 = 0, b2 = 0, b3 = 0, b4 = 0, b5 = 0, b6 = 0, b7 = 0, b8 = 0;
#pragma omp simd reduction(+ : b0, b1, b2, b3, b4, b5, b6, b7, b8)
            for (size_t i = 0; i < k; i++) {
                double rx = x[i] - t0, ry = y[i] - t1, qx = p0 * rx + p1 * ry, qy = p1 * rx + p2 * ry;
                double wc2 = w[i] * cb[i] * cb[i], e0 = qx * qx, e1 = 2.0 * qx * qy, e2 = qy * qy;
                b0 += wc2 * e0, b1 += wc2 * qx * qy, b2 += wc2 * e2;
                b3 += wc2 * qx * e0, b4 += wc2 * qx * e1, b5 += wc2 * qx * e2;
                b6 += wc2 * qy * e0, b7 += wc2 * qy * e1, b8 += wc2 * qy * e2;
            }
            double c0 = 0, c1 = 0, c2 = 0, c3 = 0, c4 = 0, c5 = 0;
#pragma omp simd reduction(+ : c0, c1, c2, c3, c4, c5)
            for (size_t i = 0; i < k; i++) {
                double rx = x[i] - t0, ry = y[i] - t1, qx = p0 * rx + p1 * ry, qy = p1 * rx + p2 * ry;
                double wc2 = w[i] * cb[i] * cb[i], e0 = qx * qx, e1 = 2.0 * qx * qy, e2 = qy * qy;
                c0 += wc2 * e0 * e0, c1 += wc2 * e0 * e1, c2 += wc2 * e0 * e2;
                c3 += wc2 * e1 * e1, c4 += wc2 * e1 * e2, c5 += wc2 * e2 * e2;
            }
            const double a[FIT_HESSIAN_SUMS - 1] = {a0, a1, a2, a3, a4, a5, a6, b0, b1, b2, b3,
                                                    b4, b5, b6, b7, b8, c0, c1, c2, c3, c4, c5};
            for (int j = 0; j < FIT_HESSIAN_SUMS - 1; j++) s[j] += a[j];
            s[FIT_HESSIAN_SUMS - 1] += src->censored ? -0.5 * own : weighted_log_sum(q, dl, w, k, unit != 0.0);
        } else {
            /* the cell of z = L^-1 r: the u band floor(K u) and the angle band floor(K (atan2(z1, z0) / 2 pi + 1/2))
             * (both clamped to K - 1), the latter counted without atan2: the band is the number of the boundaries
             * phi_b = -pi + 2 pi b / K (b = 1 .. K - 1) at or below the angle, and for z in the upper half plane
             * (z1 >= 0) every boundary below 0 is, and one at or above 0 exactly when cross(u_b, z) >= 0; in the
             * lower half plane no boundary at or above 0 is, and one below 0 exactly when cross(u_b, z) >= 0 (the
             * angles then differ by less than pi). */
            const int K = at->cells;
            const double l0 = at->linv[0], l1 = at->linv[1], l2 = at->linv[2];
            double bc[FIT_MAX_CELLS], bs[FIT_MAX_CELLS];
            int below[FIT_MAX_CELLS], cell[FIT_CHUNK];
            for (int b = 1; b < K; b++) {
                double phi = -GGX_PI + 2.0 * GGX_PI * b / K;
                bc[b] = cos(phi), bs[b] = sin(phi), below[b] = 2 * b < K;
            }
            double *z0 = q, *z1 = dl; /* the buffers of the logs, free in this pass */
#pragma omp simd
            for (size_t i = 0; i < k; i++) {
                double rx = x[i] - t0, ry = y[i] - t1;
                z0[i] = l0 * rx, z1[i] = l1 * rx + l2 * ry;
                double r2 = z0[i] * z0[i] + z1[i] * z1[i], u = r2 < 1e300 ? r2 / (1.0 + r2) : 1.0;
                int iu = (int)(u * K);
                cell[i] = (iu < K ? iu : K - 1) * K;
            }
            for (int b = 1; b < K; b++) {
                const double c = bc[b], sn = bs[b];
                const int lo = below[b];
#pragma omp simd
                for (size_t i = 0; i < k; i++) {
                    int ccw = c * z1[i] - sn * z0[i] >= 0.0;
                    cell[i] += z1[i] >= 0.0 ? (lo | ccw) : (lo & ccw);
                }
            }
            /* four histograms in turn, so that neighbouring samples in one cell do not wait on each other's sums; a
             * skipped sample adds its weight 0 */
            double h4[4][FIT_MAX_CELLS * FIT_MAX_CELLS];
            memset(h4, 0, sizeof h4);
            size_t i = 0;
            for (; i + 4 <= k; i += 4)
                for (int j = 0; j < 4; j++) h4[j][cell[i + j]] += w[i + j];
            for (; i < k; i++) h4[0][cell[i]] += w[i];
            for (int c = 0; c < K * K; c++) s[c] += (h4[0][c] + h4[1][c]) + (h4[2][c] + h4[3][c]);
        }
    }
}

typedef struct pass_job {
    const fit_source *src;
    fit_pass_kind kind;
    const fit_point *at;
    double *unit;
    int nsums, stride;
    size_t units;
} pass_job;

/* share k of the pass: units k, k + stride, ... (each unit's sums in its own row, combined in unit order) */
static void pass_share(void *ctx, int k)
{
    const pass_job *j = ctx;
    for (size_t u = (size_t)k; u < j->units; u += (size_t)j->stride) {
        size_t i0 = u * FIT_UNIT, i1 = i0 + FIT_UNIT < j->src->n ? i0 + FIT_UNIT : j->src->n;
        unit_sums(j->src, j->kind, j->at, i0, i1, j->unit + u * (size_t)j->nsums);
    }
}

ggx_status fit_pass(const fit_source *src, int threads, fit_pass_kind kind, const fit_point *at, double *sums)
{
    int ns = pass_sums(kind, at);
    size_t units = (src->n + FIT_UNIT - 1) / FIT_UNIT;
    memset(sums, 0, sizeof(double) * (size_t)ns);
    if (units == 0) return GGX_OK;
    double *unit = calloc(units * (size_t)ns, sizeof(double));
    if (!unit) return GGX_ERR_MEMORY;
    int t = threads < 1 ? 1 : threads;
    if ((size_t)t > units) t = (int)units;
    pass_job job = {src, kind, at, unit, ns, t, units};
    ggx_internal_parallel_for(t, pass_share, &job);
    for (size_t u = 0; u < units; u++)
        for (int j = 0; j < ns; j++) sums[j] += unit[u * (size_t)ns + j];
    free(unit);
    return GGX_OK;
}
