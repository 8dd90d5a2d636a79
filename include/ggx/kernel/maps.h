/* libggx kernels: the constructions of the lune samplers (kernel/lune.inc), for every precision.
 * SPDX-License-Identifier: MIT */
#ifndef GGX_KERNEL_MAPS_H
#define GGX_KERNEL_MAPS_H

/* The map that draws a sphere-space lune point from (u1, u2): the argument map of ggx_k_lune_* (a compile-time
 * constant in every caller, so that the branches on it fold). */
typedef enum ggx_k_map {
    GGX_K_MAP_CAPS = 0,           /* spherical caps: c uniform on the cap c.z >= -vs.z, p = vs + c */
    GGX_K_MAP_STRETCH = 1,        /* the cosine hemisphere about z (the view is n) */
    GGX_K_MAP_CRESCENT = 2,       /* Walter's version 3 on the concentric disk */
    GGX_K_MAP_CRESCENT_POLAR = 3, /* Walter's version 3 on the polar disk */
    GGX_K_MAP_HEITZ = 4,          /* Heitz's squished polar disk */
    /* The map of each lune sampler, by the stem of its function (the stem column of the registry,
     * ggx_samplers.h): code generated from the registry names a sampler's map as ggx_k_map_<stem>, so that a
     * sampler of normals that reaches a generated loop without a map here does not compile. */
    ggx_k_map_sample_ndf_stretch = GGX_K_MAP_STRETCH,
    ggx_k_map_sample_ndf_visible = GGX_K_MAP_CAPS, /* the caps for the view n */
    ggx_k_map_sample_vndf_caps = GGX_K_MAP_CAPS,
    ggx_k_map_sample_vndf_crescent = GGX_K_MAP_CRESCENT,
    ggx_k_map_sample_vndf_crescent_polar = GGX_K_MAP_CRESCENT_POLAR,
    ggx_k_map_sample_vndf_heitz = GGX_K_MAP_HEITZ
} ggx_k_map;

#endif /* GGX_KERNEL_MAPS_H */
