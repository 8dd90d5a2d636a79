/* The rendered ground truth of a filtered normal map: a plane textured with a chain's level K, lit by a distant light
 * and seen from a distant eye, against the full-resolution map supersampled (each level-K texel the mean of its base
 * texels' radiance), for our filter (exact and fast) and each baseline of normal_filters.h. Used by ggx render
 * --normal-map, its test and make bench; docs/design/filter.md. SPDX-License-Identifier: MIT */
#ifndef GGX_LAB_MIP_COMPARE_H
#define GGX_LAB_MIP_COMPARE_H

#include <stddef.h>

#include "ggx/ggx.h"
#include "normal_filters.h"

enum { MC_OURS, MC_FAST, MC_BASELINE, MC_METHODS = MC_BASELINE + NF_BASELINES };
extern const char *const mc_name[MC_METHODS];

typedef struct mc_view {
    ggx_vec3 wi, wo; /* the light's and the eye's unit directions, tangent frame */
} mc_view;

typedef struct mc_level {
    size_t w, h;
    double mean;             /* the truth's mean radiance over the level's texels of nonzero weight, all views */
    double rmse[MC_METHODS]; /* the relative RMS error: sqrt(sum w (value - truth)^2 / sum w truth^2), the sums over
                              * the level's texels (w their weights) and the views */
    double rmse_engine[MC_METHODS]; /* the same against the engines' truth: every base texel an unskewed lobe of its
                                     * alpha about its own normal as a shading normal (no filtering's convention) */
    double rmse_first[MC_METHODS];  /* rmse for views[0] alone */
} mc_level;

/* The standard views, MC_VIEWS light-eye pairs: lights at theta 25, 50 and 75 degrees and phi 0, 90, 180 and 270,
 * eyes at theta 0, 45 and 70 degrees and phi 0; the first is the mirror pair at 45 degrees (light 45, 180). */
enum { MC_VIEWS = 37 };
void mc_standard_views(mc_view v[MC_VIEWS]);

/* The number of levels of a w x h chain (down to 1 x 1). */
int mc_level_count(size_t w, size_t h);

/* Base texel i: normal normals[i] (any length) and roughness alpha[i] (alpha NULL: alpha0), its lobe ggx_texel_lobe's
 * (ggx_texel_lobes_roughness'); the truth of a texel its radiance f(wi, wo) wi.z with F = 1 (ggx_brdf_eval of the
 * lobe, on the geometric plane), a level-K texel's the weighted mean over its box of base texels. Fills levels[0 ..
 * mc_level_count - 1]; where images is not NULL, writes the level image_level for views[0] as 1 + MC_METHODS float
 * images of that level's size, row-major: the truth, then each method (0 where a texel has no weight), and where
 * truth0 is not NULL the truth of level 0 for views[0] (w x h). threads for the filter. Returns 0, or -1 with a
 * one-line reason in err. */
int mc_compare(size_t w, size_t h, const ggx_vec3 *normals, const double *alpha, double alpha0, const mc_view *views,
               int nviews, int threads, mc_level *levels, int image_level, float *images, float *truth0, char *err,
               size_t errn);

#endif
