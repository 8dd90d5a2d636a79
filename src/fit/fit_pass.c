/* The fits' passes over a source of slopes: fixed units of samples, each unit's sums kept apart and added in unit
 * order, so that any thread count gives the same bits. SPDX-License-Identifier: MIT */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

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

/* The sums of samples [i0, i1) into s (zeroed by the caller). */
static void unit_sums(const fit_source *src, fit_pass_kind kind, const fit_point *at, size_t i0, size_t i1, double *s)
{
    double x[FIT_CHUNK], y[FIT_CHUNK], w[FIT_CHUNK], lc[FIT_CHUNK];
    const double t0 = at->t[0], t1 = at->t[1], p0 = at->p[0], p1 = at->p[1], p2 = at->p[2];
    for (size_t at0 = i0; at0 < i1; at0 += FIT_CHUNK) {
        size_t k = i1 - at0 < FIT_CHUNK ? i1 - at0 : FIT_CHUNK;
        src->fill(src->ctx, at0, k, x, y, w, kind == FIT_PASS_MOMENTS ? lc : NULL);
        if (kind == FIT_PASS_MOMENTS) {
            double a[FIT_MOMENT_SUMS] = {0};
            for (size_t i = 0; i < k; i++) {
                double wi = w[i], rx = x[i] - t0, ry = y[i] - t1;
                if (wi == 0.0) continue;
                a[0] += wi, a[1] += wi * rx, a[2] += wi * ry;
                a[3] += wi * rx * rx, a[4] += wi * rx * ry, a[5] += wi * ry * ry;
                a[6] += wi * lc[i], a[7] += wi * wi;
            }
            for (int j = 0; j < FIT_MOMENT_SUMS; j++) s[j] += a[j];
        } else if (kind == FIT_PASS_ESTEP) {
            double a[FIT_ESTEP_SUMS] = {0};
            for (size_t i = 0; i < k; i++) {
                double wi = w[i], rx = x[i] - t0, ry = y[i] - t1;
                if (wi == 0.0) continue;
                double delta = p0 * rx * rx + 2.0 * p1 * rx * ry + p2 * ry * ry, wc = wi / (1.0 + delta);
                a[0] += wi, a[1] += wc, a[2] += wc * rx, a[3] += wc * ry;
                a[4] += wc * rx * rx, a[5] += wc * rx * ry, a[6] += wc * ry * ry;
                a[7] += wi * log1p(delta);
            }
            for (int j = 0; j < FIT_ESTEP_SUMS; j++) s[j] += a[j];
        } else if (kind == FIT_PASS_HESSIAN) {
            /* With q = P r, c = 1 / (1 + delta) and e = (qx^2, 2 qx qy, qy^2): W, sum w c, sum w c q (2),
             * sum w c q q^T (3), sum w c^2 q q^T (3), sum w c^2 q e^T (2 x 3), sum w c^2 e e^T (6), sum w log(1 + delta). */
            double a[FIT_HESSIAN_SUMS] = {0};
            for (size_t i = 0; i < k; i++) {
                double wi = w[i], rx = x[i] - t0, ry = y[i] - t1;
                if (wi == 0.0) continue;
                double qx = p0 * rx + p1 * ry, qy = p1 * rx + p2 * ry, delta = qx * rx + qy * ry;
                double c = 1.0 / (1.0 + delta), wc = wi * c, wc2 = wc * c;
                double e0 = qx * qx, e1 = 2.0 * qx * qy, e2 = qy * qy;
                a[0] += wi, a[1] += wc, a[2] += wc * qx, a[3] += wc * qy;
                a[4] += wc * e0, a[5] += wc * qx * qy, a[6] += wc * e2;
                a[7] += wc2 * e0, a[8] += wc2 * qx * qy, a[9] += wc2 * e2;
                a[10] += wc2 * qx * e0, a[11] += wc2 * qx * e1, a[12] += wc2 * qx * e2;
                a[13] += wc2 * qy * e0, a[14] += wc2 * qy * e1, a[15] += wc2 * qy * e2;
                a[16] += wc2 * e0 * e0, a[17] += wc2 * e0 * e1, a[18] += wc2 * e0 * e2;
                a[19] += wc2 * e1 * e1, a[20] += wc2 * e1 * e2, a[21] += wc2 * e2 * e2;
                a[22] += wi * log1p(delta);
            }
            for (int j = 0; j < FIT_HESSIAN_SUMS; j++) s[j] += a[j];
        } else {
            const int K = at->cells;
            const double l0 = at->linv[0], l1 = at->linv[1], l2 = at->linv[2];
            for (size_t i = 0; i < k; i++) {
                double wi = w[i], rx = x[i] - t0, ry = y[i] - t1;
                if (wi == 0.0) continue;
                double z0 = l0 * rx, z1 = l1 * rx + l2 * ry, r2 = z0 * z0 + z1 * z1;
                double u = r2 / (1.0 + r2), ang = atan2(z1, z0) * (0.5 / GGX_PI) + 0.5;
                int iu = (int)(u * K), ia = (int)(ang * K);
                iu = iu < 0 ? 0 : iu >= K ? K - 1 : iu;
                ia = ia < 0 ? 0 : ia >= K ? K - 1 : ia;
                s[iu * K + ia] += wi;
            }
        }
    }
}

typedef struct pass_job {
    const fit_source *src;
    fit_pass_kind kind;
    const fit_point *at;
    double *unit;
    int nsums, first, stride;
    size_t units;
} pass_job;

static void *pass_thread(void *arg)
{
    const pass_job *j = arg;
    for (size_t u = (size_t)j->first; u < j->units; u += (size_t)j->stride) {
        size_t i0 = u * FIT_UNIT, i1 = i0 + FIT_UNIT < j->src->n ? i0 + FIT_UNIT : j->src->n;
        unit_sums(j->src, j->kind, j->at, i0, i1, j->unit + u * (size_t)j->nsums);
    }
    return NULL;
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
    pass_job jobs[256];
    pthread_t tid[256];
    int started[256] = {0};
    for (int i = 0; i < t; i++) jobs[i] = (pass_job){src, kind, at, unit, ns, i, t, units};
    for (int i = 1; i < t; i++) started[i] = pthread_create(&tid[i], NULL, pass_thread, &jobs[i]) == 0;
    pass_thread(&jobs[0]);
    for (int i = 1; i < t; i++) {
        if (started[i])
            pthread_join(tid[i], NULL);
        else
            pass_thread(&jobs[i]); /* a thread that could not start: its units run here */
    }
    for (size_t u = 0; u < units; u++)
        for (int j = 0; j < ns; j++) sums[j] += unit[u * (size_t)ns + j];
    free(unit);
    return GGX_OK;
}
