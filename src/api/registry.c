/* The run-time table of samplers, generated from GGX_SAMPLER_LIST (ggx_samplers.h): each family's functions are
 * adapted to the table's shared signatures. SPDX-License-Identifier: MIT */
#include <string.h>

#include "internal.h"

/* NDF samplers ignore the view. */
#define ADAPT_NDF(ID, stem)                                                                                            \
    static ggx_vec3 draw_##ID(const ggx_shape *s, ggx_vec3 v, double u1, double u2)                                    \
    {                                                                                                                  \
        (void)v;                                                                                                       \
        return ggx_##stem(s, u1, u2);                                                                                  \
    }
#define ADAPT_VNDF(ID, stem)
#define ADAPT_REJECTION(ID, stem)
#define ADAPT_DIRECTION(ID, stem)
#define ADAPT_INV_NDF_1(ID, stem)                                                                                      \
    static ggx_vec2 inv_##ID(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)                                               \
    {                                                                                                                  \
        (void)v;                                                                                                       \
        return ggx_##stem##_inv(s, m);                                                                                 \
    }
#define ADAPT_INV_NDF_0(ID, stem)
#define ADAPT_INV_VNDF_1(ID, stem)
#define ADAPT_INV_VNDF_0(ID, stem)
#define ADAPT_INV_REJECTION_0(ID, stem)
#define ADAPT_INV_DIRECTION_0(ID, stem)
#define ADAPT(ID, name, stem, family, domain, inverse, batch, help)                                                    \
    ADAPT_##family(ID, stem) ADAPT_INV_##family##_##inverse(ID, stem)
GGX_SAMPLER_LIST(ADAPT)

static double pdf_ndf(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m)
{
    (void)v;
    return ggx_pdf_ndf(s, m);
}

/* The direction samplers in the table's signature: reflection (name: ggx_sample_X with pdf ggx_pdf_X) uses f, the
 * dielectric eta, u3 and the mode. */
#define DIR_REFLECTION(x)                                                                                              \
    static ggx_sample dir_sample_##x(const ggx_shape *s, const ggx_fresnel *f, double eta, ggx_vec3 v, double u1,      \
                                     double u2, double u3, ggx_transport mode)                                         \
    {                                                                                                                  \
        (void)eta, (void)u3, (void)mode;                                                                               \
        return ggx_sample_##x(s, f, v, u1, u2);                                                                        \
    }                                                                                                                  \
    static double pdf_sample_##x(const ggx_shape *s, double eta, ggx_vec3 v, ggx_vec3 w)                               \
    {                                                                                                                  \
        (void)eta;                                                                                                     \
        return ggx_pdf_##x(s, v, w);                                                                                   \
    }
DIR_REFLECTION(brdf)
DIR_REFLECTION(brdf_bounded)
DIR_REFLECTION(brdf_bounded_azimuth)
static ggx_sample dir_sample_bsdf(const ggx_shape *s, const ggx_fresnel *f, double eta, ggx_vec3 v, double u1,
                                  double u2, double u3, ggx_transport mode)
{
    (void)f;
    return ggx_sample_bsdf(s, eta, v, u1, u2, u3, mode);
}
static double pdf_sample_bsdf(const ggx_shape *s, double eta, ggx_vec3 v, ggx_vec3 w)
{
    return ggx_pdf_bsdf(s, eta, v, w);
}

/* Per family: the sample field, and the pdf, sample_reject, sample_direction and pdf_direction fields. */
#define SAMPLE_NDF(ID, stem) draw_##ID
#define SAMPLE_VNDF(ID, stem) ggx_##stem
#define SAMPLE_REJECTION(ID, stem) NULL
#define SAMPLE_DIRECTION(ID, stem) NULL
#define REST_NDF(ID, stem) pdf_ndf, NULL, NULL, NULL
#define REST_VNDF(ID, stem) ggx_pdf_vndf, NULL, NULL, NULL
#define REST_REJECTION(ID, stem) ggx_pdf_vndf, ggx_##stem, NULL, NULL
#define REST_DIRECTION(ID, stem) NULL, NULL, dir_##stem, pdf_##stem
#define INV_NDF_1(ID, stem) inv_##ID
#define INV_VNDF_1(ID, stem) ggx_##stem##_inv
#define INV_NDF_0(ID, stem) NULL
#define INV_VNDF_0(ID, stem) NULL
#define INV_REJECTION_0(ID, stem) NULL
#define INV_DIRECTION_0(ID, stem) NULL
#define ENTRY(ID, name, stem, family, domain, inverse, batch, help)                                                    \
    {GGX_SAMPLER_##ID,                                                                                                 \
     name,                                                                                                             \
     help,                                                                                                             \
     GGX_FAMILY_##family,                                                                                              \
     GGX_DOMAIN_##domain,                                                                                              \
     batch,                                                                                                            \
     SAMPLE_##family(ID, stem),                                                                                        \
     INV_##family##_##inverse(ID, stem),                                                                               \
     REST_##family(ID, stem),                                                                                          \
     "ggx_" #stem},
static const ggx_sampler_info table[GGX_SAMPLER_COUNT] = {GGX_SAMPLER_LIST(ENTRY)};

GGX_API const ggx_sampler_info *ggx_sampler_get(ggx_sampler_id id)
{
    return (id >= 0 && id < GGX_SAMPLER_COUNT) ? &table[id] : NULL;
}

GGX_API const ggx_sampler_info *ggx_sampler_find(const char *name)
{
    for (int i = 0; name && i < GGX_SAMPLER_COUNT; i++)
        if (strcmp(table[i].name, name) == 0) return &table[i];
    return NULL;
}
