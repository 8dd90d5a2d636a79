/* The renderer of render.h: the sphere and the plane, the path tracer with light and BSDF sampling combined by the
 * power heuristic, run over the tiles of render_tiles.c. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ggx/ggx_inline.h"
#include "render_tiles.h"
#include "surface.h"


static double uniform_cb(void *st) { return render_uniform(st); }

/* ---- the camera, stated for captions ---- */
void render_camera_words(const render_spec *r, char *buf, size_t n)
{
    if (r->scene == RENDER_SPHERE)
        snprintf(buf, n, "camera 4 units from the unit sphere, 10° up, on −y; 34° field of view");
    else snprintf(buf, n, "camera 3.2 units from the origin, 35° up, azimuth 60°; 50° field of view");
}

/* ---- the surfaces ---- */
static void frame_at(const render_spec *r, ggx_vec3 p, render_hit *h)
{
    h->p = p;
    if (r->scene == RENDER_PLANE) {
        h->t = ggx_k_v3_d(1, 0, 0), h->b = ggx_k_v3_d(0, 1, 0), h->n = ggx_k_v3_d(0, 0, 1);
        return;
    }
    h->n = p;
    double l = hypot(p.x, p.y);
    h->t = l > 1e-12 ? ggx_k_v3_d(-p.y / l, p.x / l, 0) : ggx_k_v3_d(1, 0, 0); /* at the poles: any tangent */
    if (l <= 1e-12) h->t = ggx_k_normalize_d(ggx_k_add_d(h->t, ggx_k_scale_d(h->n, -ggx_k_dot_d(h->t, h->n))));
    h->b = ggx_k_cross_d(h->n, h->t);
}

static ggx_vec3 to_local(const render_hit *h, ggx_vec3 w)
{
    return ggx_k_v3_d(ggx_k_dot_d(w, h->t), ggx_k_dot_d(w, h->b), ggx_k_dot_d(w, h->n));
}
static ggx_vec3 to_world(const render_hit *h, ggx_vec3 w)
{
    return ggx_k_add_d(ggx_k_scale_d(h->t, w.x), ggx_k_add_d(ggx_k_scale_d(h->b, w.y), ggx_k_scale_d(h->n, w.z)));
}

/* A camera ray from o along unit d: the first surface point, 1 if any. */
static int first_hit(const render_spec *r, ggx_vec3 o, ggx_vec3 d, ggx_vec3 *p)
{
    if (r->scene == RENDER_PLANE) {
        if (!(d.z < 0) || !(o.z > 0)) return 0;
        *p = ggx_k_add_d(o, ggx_k_scale_d(d, -o.z / d.z));
        p->z = 0;
        return 1;
    }
    double b = ggx_k_dot_d(o, d), c = ggx_k_dot_d(o, o) - 1, disc = b * b - c;
    if (disc <= 0) return 0;
    double q = sqrt(disc), t = -b - q;
    if (!(t > 0)) return 0;
    *p = ggx_k_normalize_d(ggx_k_add_d(o, ggx_k_scale_d(d, t)));
    return 1;
}

/* ---- the material ---- */
static int is_glass(const render_spec *r) { return r->fresnel.kind == GGX_FRESNEL_DIELECTRIC; }

/* f(wl -> v) in the radiance convention, local directions: wl towards the light, v towards the camera. */
static double bsdf_eval(const render_spec *r, ggx_vec3 wl, ggx_vec3 v)
{
    if (is_glass(r))
        return r->bsdf_energy ? ggx_bsdf_compensated_eval(r->bsdf_energy, wl, v, GGX_RADIANCE)
                              : ggx_bsdf_eval(&r->shape, r->fresnel.eta, wl, v, GGX_RADIANCE);
    return r->energy ? ggx_brdf_compensated_eval(r->energy, &r->fresnel, wl, v)
                     : ggx_brdf_eval(&r->shape, &r->fresnel, wl, v);
}

/* The density with which bsdf_sample draws w from v. */
static double bsdf_pdf(const render_spec *r, ggx_vec3 v, ggx_vec3 w)
{
    if (is_glass(r))
        return r->bsdf_energy ? ggx_pdf_bsdf_compensated(r->bsdf_energy, v, w)
                              : ggx_pdf_bsdf(&r->shape, r->fresnel.eta, v, w);
    if (r->energy) return ggx_pdf_brdf_compensated(r->energy, &r->fresnel, v, w);
    const ggx_sampler_info *smp = r->sampler;
    if (smp->family == GGX_FAMILY_DIRECTION) return smp->pdf_direction(&r->shape, r->fresnel.eta, v, w);
    if (!(v.z > 0) || !(w.z > 0)) return 0;
    ggx_vec3 m = ggx_k_normalize_d(ggx_k_add_d(v, w));
    return smp->pdf(&r->shape, v, m) / (4 * ggx_k_dot_d(v, m));
}

/* A direction w from v: 1 with its pdf and weight f(w -> v) |w.z| / pdf, or 0. */
static int bsdf_sample(const render_spec *r, ggx_vec3 v, render_stream *rs, ggx_vec3 *w, double *pdf, double *weight)
{
    double u1 = render_uniform(rs), u2 = render_uniform(rs), u3 = render_uniform(rs);
    ggx_sample x;
    if (is_glass(r))
        x = r->bsdf_energy ? ggx_sample_bsdf_compensated(r->bsdf_energy, v, u1, u2, u3, GGX_RADIANCE)
                           : ggx_sample_bsdf(&r->shape, r->fresnel.eta, v, u1, u2, u3, GGX_RADIANCE);
    else if (r->energy) x = ggx_sample_brdf_compensated(r->energy, &r->fresnel, v, u1, u2, u3);
    else if (r->sampler->family == GGX_FAMILY_DIRECTION)
        x = r->sampler->sample_direction(&r->shape, &r->fresnel, r->fresnel.eta, v, u1, u2, u3, GGX_RADIANCE);
    else {
        /* a sampler of normals: the mirror direction of its normal */
        const ggx_sampler_info *smp = r->sampler;
        unsigned trials;
        ggx_vec3 m = smp->family == GGX_FAMILY_REJECTION ? smp->sample_reject(&r->shape, v, uniform_cb, rs, &trials)
                                                         : smp->sample(&r->shape, v, u1, u2);
        double vm = ggx_k_dot_d(v, m);
        if (!(vm > 0)) return 0;
        ggx_vec3 o = ggx_reflect(v, m);
        double pm = smp->pdf(&r->shape, v, m);
        if (!(o.z > 0) || !(pm > 0)) return 0;
        *w = o, *pdf = pm / (4 * vm), *weight = bsdf_eval(r, o, v) * o.z / *pdf;
        return isfinite(*weight);
    }
    if (x.event == GGX_EVENT_INVALID || !(x.pdf > 0) || !isfinite(x.weight)) return 0;
    *w = x.w, *pdf = x.pdf, *weight = x.weight;
    return 1;
}

/* Whether light arriving from world direction d reaches point h unobstructed: the sphere is convex, so from its
 * surface every direction on the outer side leaves it; the plane's lower side has no far side to light it. */
static int unoccluded(const render_spec *r, const render_hit *h, ggx_vec3 d)
{
    return r->scene == RENDER_PLANE ? d.z > 0 : ggx_k_dot_d(d, h->n) > 0;
}

/* The radiance along one camera path; out[3] += it. */
static void trace(const render_spec *r, const render_camera *cam, double x, double y, render_stream *rs, double out[3])
{
    ggx_vec3 d = render_camera_dir(r, cam, x, y), p;
    int env = r->light == RENDER_LIGHT_ENV;
    double Le[3];
    if (!first_hit(r, cam->pos, d, &p)) {
        if (env) {
            render_env_radiance(r->env, d, Le);
            for (int k = 0; k < 3; k++) out[k] += Le[k];
        }
        return;
    }
    double beta = 1;
    for (int depth = 0; depth < r->depth; depth++) {
        render_hit h;
        frame_at(r, p, &h);
        ggx_vec3 v = to_local(&h, ggx_k_scale_d(d, -1));
        /* the light's sample */
        if (!env) {
            ggx_vec3 wl = r->light_dir;
            if (unoccluded(r, &h, wl)) {
                ggx_vec3 l = to_local(&h, wl);
                double c = beta * bsdf_eval(r, l, v) * fabs(l.z) * r->light_irradiance;
                for (int k = 0; k < 3; k++) out[k] += c;
            }
        } else if (r->strategy != RENDER_BSDF_ONLY) {
            double pl, u1 = render_uniform(rs), u2 = render_uniform(rs);
            ggx_vec3 wl = render_env_sample(r->env, u1, u2, &pl, Le);
            if (pl > 0 && unoccluded(r, &h, wl)) {
                ggx_vec3 l = to_local(&h, wl);
                double f = bsdf_eval(r, l, v);
                if (f > 0) {
                    double mis = r->strategy == RENDER_MIS ? render_power_heuristic(pl, bsdf_pdf(r, v, l)) : 1;
                    double c = beta * f * fabs(l.z) * mis / pl;
                    for (int k = 0; k < 3; k++) out[k] += c * Le[k];
                }
            }
        }
        /* the BSDF's sample */
        ggx_vec3 w;
        double pdf, weight;
        if (!bsdf_sample(r, v, rs, &w, &pdf, &weight)) return;
        beta *= weight;
        if (!(beta > 0)) return;
        ggx_vec3 wd = to_world(&h, w);
        if (unoccluded(r, &h, wd) || r->scene == RENDER_PLANE) {
            /* it leaves the scene (below the plane: into its inside, which gives nothing) */
            if (!env || r->strategy == RENDER_LIGHT_ONLY || !unoccluded(r, &h, wd)) return;
            double pe = render_env_lookup(r->env, wd, Le);
            double mis = r->strategy == RENDER_MIS ? render_power_heuristic(pdf, pe) : 1;
            for (int k = 0; k < 3; k++) out[k] += beta * mis * Le[k];
            return;
        }
        /* inside the sphere: to its far side, the chord from p along wd */
        p = ggx_k_normalize_d(ggx_k_add_d(p, ggx_k_scale_d(wd, -2 * ggx_k_dot_d(p, wd))));
        d = wd;
    }
}

int render_primary(const render_spec *r, double x, double y, render_hit *hit)
{
    render_camera cam = render_camera_make(r);
    memset(hit, 0, sizeof *hit);
    ggx_vec3 d = render_camera_dir(r, &cam, x, y), p;
    hit->dir = d;
    if (!first_hit(r, cam.pos, d, &p)) return 0;
    frame_at(r, p, hit);
    hit->view_local = to_local(hit, ggx_k_scale_d(d, -1));
    hit->dir = d;
    return 1;
}

/* ---- setup ---- */
void render_spec_defaults(render_spec *r)
{
    memset(r, 0, sizeof *r);
    ggx_shape_iso(&r->shape, 0.2);
    ggx_fresnel_one(&r->fresnel);
    r->scene = RENDER_SPHERE;
    r->light = RENDER_LIGHT_ENV;
    r->strategy = RENDER_MIS;
    r->width = r->height = 256;
    r->spp = 64;
    r->depth = 32;
    r->seed = 1;
    r->threads = 1;
    r->jitter = 1;
    r->light_dir = ggx_k_v3_d(0, 0, 1);
    r->light_irradiance = 1;
}

int render_prepare(render_spec *r, char *err, size_t errn)
{
    r->energy = NULL, r->bsdf_energy = NULL;
    if (r->width < 1 || r->height < 1 || r->spp < 1 || r->depth < 1 || r->threads < 1)
        return surface_fail(err, errn, "an image needs a size, samples, a depth and threads of at least 1");
    if (r->light == RENDER_LIGHT_ENV && !r->env) return surface_fail(err, errn, "no environment to light with");
    if (r->light == RENDER_LIGHT_DIRECTIONAL && !(fabs(ggx_k_dot_d(r->light_dir, r->light_dir) - 1) < 1e-9 &&
                                                  r->light_irradiance >= 0 && isfinite(r->light_irradiance)))
        return surface_fail(err, errn, "a distant light needs a unit direction and a finite, non-negative irradiance");
    const ggx_sampler_info *bounded = ggx_sampler_get(GGX_SAMPLER_BRDF_BOUNDED);
    if (is_glass(r)) {
        if (r->sampler && r->sampler->id != GGX_SAMPLER_BSDF)
            return surface_fail(err, errn, "the rough glass samples by its own sampler, bsdf (not %s)",
                                r->sampler->name);
        r->sampler = ggx_sampler_get(GGX_SAMPLER_BSDF);
    } else {
        if (!r->sampler) r->sampler = bounded;
        if (r->sampler->id == GGX_SAMPLER_BSDF)
            return surface_fail(err, errn, "sampler bsdf is the rough glass's: a reflector takes any other");
        if (r->sampler->domain == GGX_DOMAIN_UNSKEWED && r->shape.kind == GGX_SHAPE_SKEWED)
            return surface_fail(err, errn, "sampler '%s' is for unskewed shapes only; this shape is skewed",
                                r->sampler->name);
    }
    if (r->compensate && !is_glass(r) && r->sampler != bounded)
        return surface_fail(err, errn,
                            "with compensation a reflector samples by ggx_sample_brdf_compensated, whose "
                            "single-scattering lobe is brdf-bounded (not %s)",
                            r->sampler->name);
    if (!r->compensate) return 0;
    ggx_status st = is_glass(r) ? ggx_bsdf_energy_create(&r->shape, r->fresnel.eta, &r->bsdf_energy)
                                : ggx_energy_create(&r->shape, &r->energy);
    if (st != GGX_OK)
        return surface_fail(err, errn, "no energy compensation for this %s: %s",
                            is_glass(r) ? "shape and eta" : "shape", ggx_status_str(st));
    return 0;
}

void render_release(render_spec *r)
{
    ggx_energy_free(r->energy);
    ggx_bsdf_energy_free(r->bsdf_energy);
    r->energy = NULL, r->bsdf_energy = NULL;
}

/* ---- the image ---- */
static void trace_sample(const void *ctx, const render_camera *cam, double x, double y, render_stream *rs,
                         double out[3])
{
    trace(ctx, cam, x, y, rs, out);
}

long render_image(const render_spec *r, float *rgb, float *var) { return render_tiles(r, trace_sample, r, rgb, var); }
