/* Images of a material: a unit sphere or an infinite plane made of one shape of the library, lit by a
 * latitude-longitude environment or a distant light, path traced with the library's own BSDFs, samplers and pdfs
 * (ggx render, ggx demo, the Python package). Needs only the library; the environment files come through surface.h.
 * Derivations and the tests' arguments: docs/design/render.md. SPDX-License-Identifier: MIT
 *
 * Conventions. World z is up (the environment's zenith); directions point away from the surface. The sphere is
 * |p| = 1 at the origin, its tangent frame at p: x (the shape's x axis) along the parallel, eastward,
 * t = normalize(-p.y, p.x, 0); y along the meridian towards the north pole, b = p x t; n = p. The plane is z = 0,
 * its frame the world's (x, y, z); the half-space below it is the material's inside and has no far side. A shape
 * rotated by theta_z turns its x axis from t towards b. */
#ifndef GGX_TOOL_RENDER_H
#define GGX_TOOL_RENDER_H

#include <stddef.h>
#include <stdint.h>

#include "ggx/ggx.h"
#include "ggx/ggx_samplers.h"

/* ---- environments ----
 * w x h pixels of linear RGB radiance, row 0 at the zenith: pixel (i, j) is constant over theta in
 * [i, i + 1) pi / h and phi in [j, j + 1) 2 pi / w, phi measured from +x towards +y. Sampled by a piecewise-constant
 * 2D distribution: a pixel with probability p_ij proportional to its luminance (Rec. 709: 0.2126 R + 0.7152 G +
 * 0.0722 B) times sin theta at its centre, drawn in constant time from an alias table (Walker, Vose), then uniformly
 * in (theta, phi) within it; pdf per solid angle p_ij w h / (2 pi^2 sin theta). */
typedef struct render_texel {
    float rgb[3];
    float pdf_scale; /* p_ij w h / (2 pi^2): the pdf times sin theta (radiance and pdf in one cache line) */
} render_texel;
typedef struct render_alias {
    float keep;     /* the probability of keeping pixel k ... */
    uint32_t other; /* ... and the pixel taken otherwise */
} render_alias;
typedef struct render_env {
    int w, h;
    render_texel *texel; /* w h, row-major, the top row first */
    render_alias *alias; /* w h */
} render_env;

/* Takes rgb (malloc'd, 3 w h floats; freed by render_env_free, also on failure). Refuses (returns -1 with a one-line
 * reason in err) NaN or infinite values, and an environment of zero luminance everywhere (nothing to sample);
 * negative values are set to 0 and counted in *negatives (may be NULL). */
int render_env_init(render_env *e, int w, int h, float *rgb, long *negatives, char *err, size_t errn);
void render_env_free(render_env *e);
/* A uniform environment of radiance L in every channel (the furnace). */
int render_env_white(render_env *e, double L, char *err, size_t errn);
/* The built-in sky: w x h pixels (even w, h >= 2) of an analytic clear sky (a gradient from a white horizon to a blue
 * zenith, a grey ground below the horizon) and a sun: a disc of angular radius sun_radius (radians) at elevation
 * sun_elev and azimuth sun_az, uniform radiance giving irradiance sun_irradiance at normal incidence (pixels the
 * disc's rim crosses are covered by 8 x 8 subsamples). */
int render_env_sky(render_env *e, int w, int h, double sun_elev, double sun_az, double sun_radius,
                   double sun_irradiance, char *err, size_t errn);
/* The defaults of `ggx render`'s sky: 512 x 256 pixels, the sun at 35 degrees elevation, azimuth -120 degrees, of
 * radius 1.5 degrees and irradiance 6 (the sky adds about 2.6 on a horizontal plane). */
int render_env_default_sky(render_env *e, char *err, size_t errn);
/* Radiance along unit d, written to rgb[3]; with the pdf of render_env_sample for d (0 at the poles) as the return
 * value. */
double render_env_lookup(const render_env *e, ggx_vec3 d, double rgb[3]);
void render_env_radiance(const render_env *e, ggx_vec3 d, double rgb[3]);
double render_env_pdf(const render_env *e, ggx_vec3 d);
/* A direction drawn from the distribution by (u1, u2) in [0, 1)^2, its pdf per solid angle in *pdf (0: invalid) and
 * its radiance in rgb[3]. */
ggx_vec3 render_env_sample(const render_env *e, double u1, double u2, double *pdf, double rgb[3]);

/* ---- what to render ---- */
typedef enum render_scene { RENDER_SPHERE, RENDER_PLANE } render_scene;
typedef enum render_light { RENDER_LIGHT_ENV, RENDER_LIGHT_DIRECTIONAL } render_light;
/* How each path vertex gathers light: the light's sample and the BSDF's, combined by multiple importance sampling
 * with the power heuristic; the light's sample alone; the BSDF's sample alone. A distant light is always gathered by
 * its own sample (the BSDF cannot hit it). All three converge to the same image. */
typedef enum render_strategy { RENDER_MIS, RENDER_LIGHT_ONLY, RENDER_BSDF_ONLY } render_strategy;

typedef struct render_spec {
    ggx_shape shape;
    /* The material: a reflector with this Fresnel term (GGX_FRESNEL_ONE, CONDUCTOR, SCHLICK), or, for a
     * GGX_FRESNEL_DIELECTRIC term, the rough glass of ggx_bsdf_eval with eta = fresnel.eta (inside / outside). */
    ggx_fresnel fresnel;
    /* The sampler of a reflector: any registry entry but GGX_SAMPLER_BSDF (normals samplers give wo = reflect(wi,
     * m), pdf D_v(m) / (4 |wi.m|) or the NDF's D(m) m.n / (4 |wi.m|)); the glass always samples by ggx_sample_bsdf.
     * NULL: GGX_SAMPLER_BRDF_BOUNDED. With compensation, reflectors sample by ggx_sample_brdf_compensated and
     * glass by ggx_sample_bsdf_compensated, and sampler must be NULL or GGX_SAMPLER_BRDF_BOUNDED. */
    const ggx_sampler_info *sampler;
    int compensate; /* add the library's multiple-scattering lobes (ggx_energy / ggx_bsdf_energy) */
    render_scene scene;
    render_light light;
    const render_env *env;   /* RENDER_LIGHT_ENV */
    ggx_vec3 light_dir;      /* RENDER_LIGHT_DIRECTIONAL: unit, towards the light, world frame */
    double light_irradiance; /* RENDER_LIGHT_DIRECTIONAL: at normal incidence, every channel */
    render_strategy strategy;
    int width, height, spp; /* >= 1 each */
    int depth;              /* the most surface interactions a path has (>= 1; the glass sphere needs 2 to pass) */
    uint64_t seed;
    int threads; /* >= 1; the image does not depend on it */
    int jitter;  /* 1: each sample at a uniform point of its pixel; 0: every sample at the centre */
    /* Called from the calling thread with the pixels done so far (may be NULL). */
    void (*progress)(void *ctx, long done, long total);
    void *progress_ctx;
    /* Filled by render_prepare (NULL where not compensated). */
    ggx_energy *energy;
    ggx_bsdf_energy *bsdf_energy;
} render_spec;

/* The defaults: isotropic alpha 0.2, F = 1, the bounded sampler, no compensation, the sphere, an environment light
 * (env to be set), MIS, 256 x 256 pixels, 64 spp, depth 32, seed 1, 1 thread, jitter on. */
void render_spec_defaults(render_spec *r);
/* Checks r and builds what it needs (the energy tables when compensating: seconds for anisotropic and skewed
 * shapes). Returns 0, or -1 with a one-line reason. */
int render_prepare(render_spec *r, char *err, size_t errn);
void render_release(render_spec *r);

/* The image: rgb (3 width height floats, the top row first) of each pixel's mean radiance over its spp samples;
 * var, when not NULL, the variance of that mean per channel (the samples' variance / spp; 0 for spp = 1). Each
 * pixel's samples come from its own stream of random numbers (from seed and the pixel's index), so the image is the
 * same bit for bit for any number of threads (threads that cannot be started leave their tiles to the others).
 * The means are computed in double; returns the number of values (of rgb and var) beyond the largest float, which
 * are stored as infinity (a light bright enough that the image does not fit single precision): 0 for an image of
 * finite values only. */
long render_image(const render_spec *r, float *rgb, float *var);

/* ---- a medium of flakes ----
 * The unit sphere filled with a homogeneous SGGX medium (ggx_sggx.h): flakes of density rho whose distribution is the
 * ellipsoid of the spec's shape, S = A^T A (ggx_sggx_from_shape), in world coordinates: the shape's x, y, z are the
 * world's, so an unskewed shape's mean flake normal is the zenith (its flakes lie like a surface facing up) and
 * theta_z turns its x axis from world x towards world y. A ray along d is attenuated by sigma_t(d) = rho sigma(d)
 * (ggx_sggx_sigma): constant along the straight ray, so the free-flight distance is drawn exactly, t = -log(1 - u) /
 * sigma_t(d), and the medium's boundary is crossed with probability exp(-sigma_t(d) s), s the chord. At a collision the
 * particle scatters with the single-scattering albedo (per channel; the rest is absorbed) by the specular or the diffuse
 * flakes' phase function f(wi, wo) with wi = -d. The light: the environment (RENDER_LIGHT_ENV), gathered at each
 * scattering event by its own sample, transmittance exp(-rho sigma(l) s_exit(l)) times f(-d, l), and by the phase
 * function's sample when its free flight leaves the sphere, combined as r->strategy says (the power heuristic for
 * RENDER_MIS; phase samples are the BSDF's). Russian roulette after the third event keeps the estimate unbiased (a
 * path's throughput is never raised above 1 by it). Derivation and the furnace test: docs/design/sggx.md. */
typedef enum render_phase { RENDER_PHASE_SPECULAR, RENDER_PHASE_DIFFUSE } render_phase;
/* Mistakes a test switches on to show that its check catches them (negative controls); RENDER_FAULT_NONE otherwise:
 * the light's sample weighted by 1.1 f instead of f, or its transmittance computed with sigma of the ray's own
 * direction d instead of sigma(l). */
typedef enum render_fault { RENDER_FAULT_NONE, RENDER_FAULT_NEE_PHASE, RENDER_FAULT_SIGMA_DIRECTION } render_fault;
typedef struct render_volume {
    double density;   /* rho >= 0, flakes per unit volume (their area scaled as sigma states) */
    double albedo[3]; /* in [0, 1] per channel; 1: no absorption */
    render_phase phase;
    int scatter; /* the most scattering events of a path (>= 1; 1: single scattering); default 256 */
    render_fault fault;
    ggx_sggx flakes; /* filled by render_volume_prepare from the spec's shape */
} render_volume;

/* Density 1, albedo 1, specular flakes, at most 256 scattering events, no fault. */
void render_volume_defaults(render_volume *v);
/* Checks v and what render_volume_image reads of r (size, spp, threads >= 1; the sphere scene; an environment light)
 * and builds the flakes of r's shape. Returns 0, or -1 with a one-line reason in err (a shape too ill-conditioned for
 * SGGX among them). */
int render_volume_prepare(render_volume *v, const render_spec *r, char *err, size_t errn);
/* The image of the medium seen by the sphere scene's camera, as render_image makes it (rgb, var, the deterministic
 * streams per pixel and the return value alike). Of r it reads the environment, strategy, size, spp, seed, jitter,
 * threads and progress; its material (Fresnel term, sampler, compensation, depth) has no part. The pixel's
 * expectation is the radiance scattered at most v->scatter times. */
long render_volume_image(const render_spec *r, const render_volume *v, float *rgb, float *var);

/* The camera ray through image point (x, y) (pixels; (0, 0) the top-left corner) and what it sees first: returns 1
 * when it hits the surface, with the hit point, the tangent frame (t, b, n) and the view (towards the camera) in
 * that frame in *view_local; 0 when it misses (the environment is seen), with the ray's direction in *dir. */
typedef struct render_hit {
    ggx_vec3 p, t, b, n, view_local, dir;
} render_hit;
int render_primary(const render_spec *r, double x, double y, render_hit *hit);

/* ---- a material given as a function ----
 * f(wl -> v) per channel (F included) at local directions: wl towards the light, v towards the camera, both above
 * the surface; written to f[3]. Called from many threads at once with the same ctx. */
typedef void (*render_brdf_fn)(const void *ctx, ggx_vec3 wl, ggx_vec3 v, double f[3]);
/* The scene of r lit by its distant light alone (r->light_dir, r->light_irradiance; the environment is not read), in
 * the material f: each pixel the mean over its spp samples of f(l, v) cos(theta_l) E where the camera ray meets the
 * surface, 0 where it misses or where the light or the view is below the surface's tangent plane. Nothing shadows
 * the light (the sphere is convex and the plane open). The same camera, pixel points and thread invariance as
 * render_image, whose image of a reflector with depth 1 under a distant light it equals for f = ggx_brdf_eval of
 * r's shape and Fresnel term; r's shape, Fresnel term and sampler are not read. Returns as render_image. */
long render_direct(const render_spec *r, render_brdf_fn f, const void *ctx, float *rgb);

/* The camera, stated for captions: where it is and what it looks at. */
void render_camera_words(const render_spec *r, char *buf, size_t n);

#endif
