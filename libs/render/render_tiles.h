/* What the renderers of this folder share, internal to it: the counter-based random stream of each (seed, pixel,
 * sample), the camera of each scene, and the image loop that runs one renderer's estimator over tiles taken by
 * threads in turn. The surfaces' path tracer (render.c) and the medium of flakes (render_volume.c) are two
 * estimators over this one loop, so their images are deterministic per pixel in the same way.
 * SPDX-License-Identifier: MIT */
#ifndef GGX_RENDER_TILES_H
#define GGX_RENDER_TILES_H

#include <stdint.h>

#include "render.h"

/* ---- random numbers: a counter-based stream per (seed, pixel, sample) ---- */
typedef struct render_stream {
    uint64_t s;
} render_stream;

/* splitmix64's finaliser (Steele, Lea, Flood): a bijection of 64 bits that scatters consecutive counters */
static inline uint64_t render_mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}
/* The next number of the stream, uniform on the 2^53 doubles k 2^-53 of [0, 1). */
static inline double render_uniform(render_stream *r)
{
    r->s += 0x9e3779b97f4a7c15ULL;
    return (double)(render_mix64(r->s) >> 11) * 0x1.0p-53;
}

/* Veach's power heuristic (exponent 2): the weight of a sample drawn with density a where another strategy would draw
 * it with density b. */
static inline double render_power_heuristic(double a, double b) { return a * a / (a * a + b * b); }

/* ---- the camera of r's scene ---- */
typedef struct render_camera {
    ggx_vec3 pos, fwd, right, up;
    double tan_half;
} render_camera;

render_camera render_camera_make(const render_spec *r);
/* The unit direction of the camera ray through image point (x, y) (pixels; (0, 0) the top-left corner). */
ggx_vec3 render_camera_dir(const render_spec *r, const render_camera *c, double x, double y);

/* ---- the image ---- */
/* One camera sample: adds the radiance of one path through image point (x, y) to out[3], drawing its random numbers
 * from rs. ctx is the estimator's own (read-only: every thread shares it). */
typedef void (*render_estimator)(const void *ctx, const render_camera *cam, double x, double y, render_stream *rs,
                                 double out[3]);

/* The image of r's size, spp, seed, jitter, threads and progress, each sample estimated by est, as render_image
 * states it (rgb, var and the return value mean what they mean there). */
long render_tiles(const render_spec *r, render_estimator est, const void *ctx, float *rgb, float *var);

#endif
