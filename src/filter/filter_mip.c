/* One level of a mip chain of lobes (ggx_filter_downsample): each coarser texel the filter of its box of finer
 * texels, rows split over threads. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "common/parallel.h"
#include "filter.h"

typedef struct mip_job {
    double *out, *w_out;
    const double *in, *w_in;
    size_t w, h, w2, h2;
    int shares;
    const filter_rule *rule;
    const filter_settings *f;
} mip_job;

/* share k of the coarser level's rows: rows h2 k / shares to h2 (k + 1) / shares */
static void mip_rows(void *ctx, int k)
{
    const mip_job *j = ctx;
    size_t y0 = j->h2 * (size_t)k / (size_t)j->shares, y1 = j->h2 * (size_t)(k + 1) / (size_t)j->shares;
    for (size_t y = y0; y < y1; y++)
        for (size_t x = 0; x < j->w2; x++) {
            filter_lobe L[4];
            size_t n = 0, xs = 2 * x, ys = 2 * y, nx = xs + 1 < j->w ? 2 : 1, ny = ys + 1 < j->h ? 2 : 1, one = 0;
            double W = 0.0;
            for (size_t dy = 0; dy < ny; dy++)
                for (size_t dx = 0; dx < nx; dx++) W += j->w_in ? j->w_in[(ys + dy) * j->w + xs + dx] : 1.0;
            for (size_t dy = 0; dy < ny; dy++)
                for (size_t dx = 0; dx < nx; dx++) {
                    size_t i = (ys + dy) * j->w + xs + dx;
                    double wi = j->w_in ? j->w_in[i] : 1.0;
                    if (wi == 0.0) continue;
                    const double *c = j->in + GGX_LOBE_PARAMS * i;
                    filter_lobe_set(&L[n++], c, c + 2, wi / W);
                    one = i;
                }
            size_t o_i = y * j->w2 + x;
            double *o = j->out + GGX_LOBE_PARAMS * o_i;
            if (j->w_out) j->w_out[o_i] = W;
            if (n == 0) { /* nothing to filter: the placeholder */
                o[0] = o[1] = o[3] = 0.0, o[2] = o[4] = 1.0;
                continue;
            }
            if (n == 1) {
                memcpy(o, j->in + GGX_LOBE_PARAMS * one, GGX_LOBE_PARAMS * sizeof *o);
                continue;
            }
            int converged;
            filter_em(L, n, j->rule, j->f, o, o + 2, &converged, NULL);
        }
}

GGX_API ggx_status ggx_filter_downsample(double *out, double *w_out, const double *in, const double *w_in, size_t w,
                                         size_t h, const ggx_filter_options *opt)
{
    if (!out || !in) return GGX_ERR_NULL;
    filter_settings f;
    ggx_status st = filter_settings_of(opt, &f);
    if (st != GGX_OK) return st;
    if (w == 0 || h == 0 || w > SIZE_MAX / GGX_LOBE_PARAMS / sizeof(double) / h) return GGX_ERR_RANGE;
    for (size_t i = 0; i < w * h; i++) { /* weights in [0, 1e300]; every texel that counts a shape */
        double wi = w_in ? w_in[i] : 1.0;
        if (!(wi >= 0.0 && wi <= 1e300)) return GGX_ERR_RANGE;
        if (wi == 0.0) continue;
        if (filter_params_check(in + GGX_LOBE_PARAMS * i) != GGX_OK) return GGX_ERR_RANGE;
    }
    filter_rule r;
    if ((st = filter_rule_make(&f, &r)) != GGX_OK) return st;
    size_t w2 = (w + 1) / 2, h2 = (h + 1) / 2;
    int nt = (size_t)f.threads < h2 ? f.threads : (int)h2;
    mip_job job = {out, w_out, in, w_in, w, h, w2, h2, nt, &r, &f};
    ggx_internal_parallel_for(nt, mip_rows, &job);
    filter_rule_free(&r);
    return GGX_OK;
}
