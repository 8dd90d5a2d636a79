/* The engines' normal-map filters, the baselines that ggx_filter_lobes is measured against (tests/unit/test_filter.c, the
 * rendered comparison of libs/verify/mip_compare.c, ggx render --normal-map). Each keeps a shading normal: the
 * renormalised mean n = m / |m| of a footprint's unit normals (m their weighted mean), and an unskewed GGX lobe in the
 * frame of n, evaluated there with the cosine about n as engines do. docs/design/filter.md states them and their
 * sources. SPDX-License-Identifier: MIT */
#ifndef GGX_LAB_NORMAL_FILTERS_H
#define GGX_LAB_NORMAL_FILTERS_H

#include "ggx/ggx.h"

typedef enum nf_kind {
    NF_NONE,     /* no filtering: alpha^2 unchanged */
    NF_TOKSVIG,  /* Toksvig: the Blinn-Phong exponent s = 2 / alpha^2 - 2 scaled by |m| / (|m| + s (1 - |m|)) */
    NF_VARIANCE, /* variance widening as Tokuyoshi and Kaplanyan ship it: alpha^2 + min(2 sigma^2, 0.18), at most 1,
                  * sigma^2 = 1 / kappa the per-axis variance of the von Mises-Fisher lobe of mean length |m|,
                  * kappa = (3 |m| - |m|^3) / (1 - |m|^2) */
    NF_UNSKEWED, /* our filtered lobe's scale Sigma without its location, about n: what an engine does with our shapes */
    /* (Toksvig and variance widening leave a base alpha of 1 or more as it is: both assume alpha <= 1) */
    NF_BASELINES
} nf_kind;
extern const char *const nf_name[NF_BASELINES];

typedef struct nf_lobe {
    double frame[3][3]; /* rows: the shading frame's tangent, bitangent and normal n (the least rotation of z to n) */
    ggx_shape s;        /* the unskewed lobe in that frame */
} nf_lobe;

/* The baseline of kind k for a footprint whose unit normals have weighted mean m (|m| in (0, 1]) and whose texels'
 * alpha^2 have weighted mean alpha2; sigma (Sigma_xx, Sigma_xy, Sigma_yy) is our filter's scale, read by NF_UNSKEWED
 * only (may be NULL otherwise). Returns 0, or -1 where m is zero, not finite or below the horizon. */
int nf_baseline(nf_kind k, ggx_vec3 m, double alpha2, const double sigma[3], nf_lobe *out);

/* f(wi, wo) (n . wi)+ of the baseline for tangent-frame directions: the reflectance times the cosine about its
 * shading normal, ggx_brdf_eval in the shading frame. */
double nf_radiance(const nf_lobe *b, const ggx_fresnel *f, ggx_vec3 wi, ggx_vec3 wo);

/* The baseline's lobe as a shape of the tangent frame (its ellipsoid rotated from the shading frame: A F, F the
 * frame), for KL divergences from a mixture of texel lobes. Returns ggx_shape_matrix's status. */
ggx_status nf_tangent_shape(const nf_lobe *b, ggx_shape *out);

#endif
