/* The rendered ground truth of a filtered normal map (mip_compare.h). SPDX-License-Identifier: MIT */
#include "mip_compare.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ggx/ggx_filter.h"

const char *const mc_name[MC_METHODS] = {"ours",    "ours, fast mode",   "no filtering",
                                         "Toksvig", "variance widening", "ours without skew"};

static ggx_vec3 polar(double theta_deg, double phi_deg)
{
    double t = theta_deg * GGX_PI / 180.0, p = phi_deg * GGX_PI / 180.0;
    ggx_vec3 d = {sin(t) * cos(p), sin(t) * sin(p), cos(t)};
    return d;
}

void mc_standard_views(mc_view v[MC_VIEWS])
{
    static const double eye[3] = {0.0, 45.0, 70.0}, light[3] = {25.0, 50.0, 75.0};
    v[0].wi = polar(45, 180), v[0].wo = polar(45, 0);
    int k = 1;
    for (int e = 0; e < 3; e++)
        for (int l = 0; l < 3; l++)
            for (int a = 0; a < 4; a++, k++) v[k].wi = polar(light[l], 90.0 * a), v[k].wo = polar(eye[e], 0.0);
}

int mc_level_count(size_t w, size_t h)
{
    int n = 1;
    while (w > 1 || h > 1) w = (w + 1) / 2, h = (h + 1) / 2, n++;
    return n;
}

static int fail(char *err, size_t errn, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errn, fmt, ap);
    va_end(ap);
    return -1;
}

/* The sums a level keeps per texel: weight, weight x (unit normal, alpha^2, the truth and the engines' truth per
 * view). */
enum { S_W, S_N, S_A2 = S_N + 3, S_TRUTH };
#define SUMS(nv) (S_TRUTH + 2 * (nv))

/* The next level's sums: the boxes of ggx_filter_downsample (2 x 2 from (2x, 2y), cut at an odd last row or column). */
static void sums_down(const double *in, size_t w, size_t h, int k, double *out)
{
    size_t w2 = (w + 1) / 2, h2 = (h + 1) / 2;
    for (size_t y = 0; y < h2; y++)
        for (size_t x = 0; x < w2; x++) {
            double *o = out + (y * w2 + x) * (size_t)k;
            memset(o, 0, (size_t)k * sizeof *o);
            for (size_t dy = 0; dy < 2 && 2 * y + dy < h; dy++)
                for (size_t dx = 0; dx < 2 && 2 * x + dx < w; dx++) {
                    const double *c = in + ((2 * y + dy) * w + 2 * x + dx) * (size_t)k;
                    for (int j = 0; j < k; j++) o[j] += c[j];
                }
        }
}

static double lobe_radiance(const double *c, const ggx_fresnel *f, const mc_view *v)
{
    ggx_shape s;
    if (ggx_shape_from_slopes(&s, c[0], c[1], c[2], c[3], c[4]) != GGX_OK) return NAN;
    return ggx_brdf_eval(&s, f, v->wi, v->wo) * v->wi.z;
}

int mc_compare(size_t w, size_t h, const ggx_vec3 *normals, const double *alpha, double alpha0, const mc_view *views,
               int nviews, int threads, mc_level *levels, int image_level, float *images, float *truth0, char *err,
               size_t errn)
{
    if (w == 0 || h == 0 || nviews < 1) return fail(err, errn, "nothing to compare");
    for (int v = 0; v < nviews; v++)
        if (!(views[v].wi.z > 0.0 && views[v].wo.z > 0.0)) return fail(err, errn, "a view or light below the horizon");
    size_t n = w * h;
    const int K = SUMS(nviews);
    double *exact = malloc(n * GGX_LOBE_PARAMS * sizeof *exact), *fast = malloc(n * GGX_LOBE_PARAMS * sizeof *fast);
    double *next = malloc(n * GGX_LOBE_PARAMS * sizeof *next), *wt = malloc(n * sizeof *wt);
    double *sums = malloc(n * (size_t)K * sizeof *sums), *sums2 = malloc(n * (size_t)K * sizeof *sums2);
    if (!exact || !fast || !next || !wt || !sums || !sums2) {
        free(exact), free(fast), free(next), free(wt), free(sums), free(sums2);
        return fail(err, errn, "out of memory for a %zu x %zu map", w, h);
    }
    ggx_status st = alpha ? ggx_texel_lobes_roughness(exact, wt, normals, alpha, NULL, n, 0.0, NULL)
                          : ggx_texel_lobes(exact, wt, normals, n, alpha0, alpha0, 0.0, NULL);
    int rc = 0;
    if (st != GGX_OK) {
        rc = fail(err, errn, "the base roughness: %s", ggx_status_str(st));
        goto done;
    }
    memcpy(fast, exact, n * GGX_LOBE_PARAMS * sizeof *fast);
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    for (size_t i = 0; i < n; i++) { /* level 0's sums */
        double *s = sums + i * (size_t)K, wi = wt[i];
        memset(s, 0, (size_t)K * sizeof *s);
        if (wi == 0.0) continue;
        ggx_vec3 m = normals[i];
        double l = sqrt(m.x * m.x + m.y * m.y + m.z * m.z), a = alpha ? fmax(alpha[i], GGX_ALPHA_MIN) : alpha0;
        m.x /= l, m.y /= l, m.z /= l;
        nf_lobe e;
        if (nf_baseline(NF_NONE, m, a * a, NULL, &e) != 0) {
            rc = fail(err, errn, "texel %zu: GGX of alpha %g about its normal is not a shape", i, a);
            goto done;
        }
        s[S_W] = wi, s[S_N] = wi * m.x, s[S_N + 1] = wi * m.y, s[S_N + 2] = wi * m.z, s[S_A2] = wi * a * a;
        for (int v = 0; v < nviews; v++) {
            s[S_TRUTH + 2 * v] = wi * lobe_radiance(exact + GGX_LOBE_PARAMS * i, &one, &views[v]);
            s[S_TRUTH + 2 * v + 1] = wi * nf_radiance(&e, &one, views[v].wi, views[v].wo);
        }
    }
    ggx_filter_options oe = {0}, of = {0};
    oe.threads = of.threads = threads;
    ggx_filter_options_fast(&of);
    double *nw = malloc(n * sizeof *nw); /* the next level's weights */
    if (!nw) {
        rc = fail(err, errn, "out of memory");
        goto done;
    }
    for (int L = 0;; L++) {
        mc_level *lv = &levels[L];
        memset(lv, 0, sizeof *lv);
        lv->w = w, lv->h = h;
        double sq[MC_METHODS] = {0}, sqe[MC_METHODS] = {0}, sq1[MC_METHODS] = {0}, tot = 0.0, W = 0.0, t2 = 0.0,
               te2 = 0.0, t21 = 0.0;
        for (size_t i = 0; i < w * h; i++) {
            const double *s = sums + i * (size_t)K;
            if (s[S_W] == 0.0) {
                if (truth0 && L == 0) truth0[i] = 0.0f;
                if (images && L == image_level)
                    for (int k = 0; k <= MC_METHODS; k++) images[(size_t)k * w * h + i] = 0.0f;
                continue;
            }
            double sw = s[S_W];
            ggx_vec3 m = {s[S_N] / sw, s[S_N + 1] / sw, s[S_N + 2] / sw};
            const double *ce = exact + GGX_LOBE_PARAMS * i, *cf = fast + GGX_LOBE_PARAMS * i;
            nf_lobe b[NF_BASELINES];
            for (int k = 0; k < NF_BASELINES; k++)
                if (nf_baseline((nf_kind)k, m, s[S_A2] / sw, ce + 2, &b[k]) != 0) {
                    rc = fail(err, errn, "level %d texel %zu: %s is not a shape (mean alpha^2 %g)", L, i, nf_name[k],
                              s[S_A2] / sw);
                    free(nw);
                    goto done;
                }
            for (int v = 0; v < nviews; v++) {
                double truth = s[S_TRUTH + 2 * v] / sw, truth_e = s[S_TRUTH + 2 * v + 1] / sw, val[MC_METHODS];
                val[MC_OURS] = lobe_radiance(ce, &one, &views[v]);
                val[MC_FAST] = lobe_radiance(cf, &one, &views[v]);
                for (int k = 0; k < NF_BASELINES; k++)
                    val[MC_BASELINE + k] = nf_radiance(&b[k], &one, views[v].wi, views[v].wo);
                for (int k = 0; k < MC_METHODS; k++) {
                    sq[k] += sw * (val[k] - truth) * (val[k] - truth);
                    sqe[k] += sw * (val[k] - truth_e) * (val[k] - truth_e);
                    if (v == 0) sq1[k] += sw * (val[k] - truth) * (val[k] - truth);
                }
                tot += sw * truth, W += sw, t2 += sw * truth * truth, te2 += sw * truth_e * truth_e;
                if (v == 0) t21 += sw * truth * truth;
                if (truth0 && L == 0 && v == 0) truth0[i] = (float)truth;
                if (images && L == image_level && v == 0) {
                    images[i] = (float)truth;
                    for (int k = 0; k < MC_METHODS; k++) images[(size_t)(k + 1) * w * h + i] = (float)val[k];
                }
            }
        }
        lv->mean = W > 0.0 ? tot / W : 0.0;
        for (int k = 0; k < MC_METHODS; k++) {
            lv->rmse[k] = t2 > 0.0 ? sqrt(sq[k] / t2) : 0.0;
            lv->rmse_engine[k] = te2 > 0.0 ? sqrt(sqe[k] / te2) : 0.0;
            lv->rmse_first[k] = t21 > 0.0 ? sqrt(sq1[k] / t21) : 0.0;
        }
        if (w == 1 && h == 1) break;
        /* the next level: both chains from this one's lobes and weights, the sums by the same boxes */
        if (ggx_filter_downsample(next, nw, exact, wt, w, h, &oe) != GGX_OK) {
            free(nw);
            rc = fail(err, errn, "level %d: the filter failed", L + 1);
            goto done;
        }
        memcpy(exact, next, ((w + 1) / 2) * ((h + 1) / 2) * GGX_LOBE_PARAMS * sizeof *next);
        if (ggx_filter_downsample(next, NULL, fast, wt, w, h, &of) != GGX_OK) {
            free(nw);
            rc = fail(err, errn, "level %d: the fast filter failed", L + 1);
            goto done;
        }
        memcpy(fast, next, ((w + 1) / 2) * ((h + 1) / 2) * GGX_LOBE_PARAMS * sizeof *next);
        memcpy(wt, nw, ((w + 1) / 2) * ((h + 1) / 2) * sizeof *nw);
        sums_down(sums, w, h, K, sums2);
        double *t = sums;
        sums = sums2, sums2 = t;
        w = (w + 1) / 2, h = (h + 1) / 2;
    }
    free(nw);
done:
    free(exact), free(fast), free(next), free(wt), free(sums), free(sums2);
    return rc;
}
