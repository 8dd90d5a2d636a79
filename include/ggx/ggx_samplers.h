/*
 * libggx: the registry of samplers. SPDX-License-Identifier: MIT
 *
 * One list, GGX_SAMPLER_LIST, names every sampler of the library once. The run-time table (ggx_sampler_get,
 * ggx_sampler_find), the batch kernels, the ggx command's --sampler option, the test sweeps, the fuzz target, the
 * benchmark and the seed audit are all generated from it or iterate the table. Adding a sampler is one kernel (for a
 * sphere-space sampler, one case of k_lune_point in kernel/lune.inc) and one line here.
 */
#ifndef GGX_GGX_SAMPLERS_H
#define GGX_GGX_SAMPLERS_H

#include "ggx/ggx.h"

#ifdef __cplusplus
extern "C" {
#endif

/* X(ID, name, stem, family, domain, inverse, batch, help)
 * - ID: the suffix of GGX_SAMPLER_<ID>; name: the ggx command's --sampler name;
 * - stem: the double API function is ggx_<stem> (and ggx_<stem>_inv when inverse is 1), the inline kernels are
 *   ggx_<stem>_f and ggx_<stem>_d;
 * - family: NDF (m with pdf D(m) m.n), VNDF (m with pdf eq 33 for the view v), REJECTION (VNDF by rejection, with a
 *   source of random numbers), DIRECTION (a direction w with pdf and weight);
 * - domain: ANY shape, or UNSKEWED shapes only (a skewed shape gives the zero vector);
 * - batch: 1 when the float batch API has it (ggx_batch_sample_normals for NDF and VNDF, ggx_batch_sample_directions
 *   for DIRECTION). */
#define GGX_SAMPLER_LIST(X)                                                                                            \
    X(STRETCH, "stretch", sample_ndf_stretch, NDF, ANY, 1, 1, "NDF: cosine hemisphere + elliptic stretch (Engstad)")   \
    X(ELLIPSE, "ellipse", sample_ndf_ellipse, NDF, ANY, 0, 0,                                                          \
      "NDF: projected ellipse lifted to the ellipsoid (blog Part 2)")                                                  \
    X(INVERSION, "inversion", sample_ndf_inversion, NDF, UNSKEWED, 0, 0,                                               \
      "NDF: closed-form theta, phi (unskewed shapes only)")                                                            \
    X(VISIBLE, "visible", sample_ndf_visible, NDF, ANY, 0, 1, "NDF: visible-normal sampling from n (any shape)")       \
    X(CAPS, "caps", sample_vndf_caps, VNDF, ANY, 1, 1, "VNDF: spherical caps (default)")                               \
    X(CRESCENT, "crescent", sample_vndf_crescent, VNDF, ANY, 1, 1, "VNDF: Walter version 3, concentric disk")          \
    X(CRESCENT_POLAR, "crescent-polar", sample_vndf_crescent_polar, VNDF, ANY, 1, 1,                                   \
      "VNDF: Walter version 3, polar disk")                                                                            \
    X(HEITZ, "heitz", sample_vndf_heitz, VNDF, ANY, 1, 1, "VNDF: Heitz / Engstad five steps")                          \
    X(WALTER_V1, "walter-v1", sample_vndf_walter_v1, REJECTION, ANY, 0, 0,                                             \
      "VNDF: Walter version 1 (rejection, bounding sphere)")                                                           \
    X(WALTER_V2, "walter-v2", sample_vndf_walter_v2, REJECTION, ANY, 0, 0,                                             \
      "VNDF: Walter version 2 (rejection, sphere space)")                                                              \
    X(BRDF, "brdf", sample_brdf, DIRECTION, ANY, 0, 1, "directions: reflection sampling (eq 47-50), view = wi")        \
    X(BRDF_BOUNDED, "brdf-bounded", sample_brdf_bounded, DIRECTION, ANY, 0, 1,                                         \
      "directions: bounded reflection sampling (caps from the horizon bound), view = wi")                              \
    X(BRDF_BOUNDED_AZIMUTH, "brdf-bounded-azimuth", sample_brdf_bounded_azimuth, DIRECTION, ANY, 0, 0,                 \
      "directions: bounded reflection sampling, bound per azimuth of the cap point, view = wi")                        \
    X(BSDF, "bsdf", sample_bsdf, DIRECTION, ANY, 0, 0,                                                                 \
      "directions: rough dielectric (Walter 2007), view = known direction, --eta")

typedef enum ggx_sampler_id {
#define GGX_SAMPLER_ENUM_(ID, name, stem, family, domain, inverse, batch, help) GGX_SAMPLER_##ID,
    GGX_SAMPLER_LIST(GGX_SAMPLER_ENUM_)
#undef GGX_SAMPLER_ENUM_
        GGX_SAMPLER_COUNT
} ggx_sampler_id;

typedef enum ggx_sampler_family {
    GGX_FAMILY_NDF = 0,
    GGX_FAMILY_VNDF = 1,
    GGX_FAMILY_REJECTION = 2,
    GGX_FAMILY_DIRECTION = 3
} ggx_sampler_family;

typedef enum ggx_sampler_domain { GGX_DOMAIN_ANY = 0, GGX_DOMAIN_UNSKEWED = 1 } ggx_sampler_domain;

/* One sampler, with its functions in signatures shared by the family (NULL where the family has none). */
typedef struct ggx_sampler_info {
    ggx_sampler_id id;
    const char *name;
    const char *help;
    ggx_sampler_family family;
    ggx_sampler_domain domain;
    int batch; /* the float batch API has it */
    /* NDF and VNDF: the normal for (u1, u2) and view v (NDF samplers ignore v). */
    ggx_vec3 (*sample)(const ggx_shape *s, ggx_vec3 v, double u1, double u2);
    /* The (u1, u2) that give m, or NULL. */
    ggx_vec2 (*inverse)(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);
    /* NDF, VNDF, REJECTION: the pdf the sampler has (ggx_pdf_ndf, ignoring v, or ggx_pdf_vndf). */
    double (*pdf)(const ggx_shape *s, ggx_vec3 v, ggx_vec3 m);
    /* REJECTION: as ggx_sample_vndf_walter_v1. */
    ggx_vec3 (*sample_reject)(const ggx_shape *s, ggx_vec3 v, ggx_uniform_fn next, void *state, unsigned *trials);
    /* DIRECTION: a direction from the known direction v (f for reflection, eta for the dielectric). */
    ggx_sample (*sample_direction)(const ggx_shape *s, const ggx_fresnel *f, double eta, ggx_vec3 v, double u1,
                                   double u2, double u3, ggx_transport mode);
    /* DIRECTION: the pdf of sample_direction giving w from v. */
    double (*pdf_direction)(const ggx_shape *s, double eta, ggx_vec3 v, ggx_vec3 w);
    /* The name of its double API function, "ggx_<stem>" (its inverse is that name + "_inv"), for bindings and tools
     * that call the named function. (Entries are only reached through pointers, so fields are added at the end.) */
    const char *function;
} ggx_sampler_info;

/* The entry of a sampler; NULL for an id outside [0, GGX_SAMPLER_COUNT). */
const ggx_sampler_info *ggx_sampler_get(ggx_sampler_id id);
/* The entry with that --sampler name; NULL when there is none (or name is NULL). */
const ggx_sampler_info *ggx_sampler_find(const char *name);

#ifdef __cplusplus
}
#endif

#endif /* GGX_GGX_SAMPLERS_H */
