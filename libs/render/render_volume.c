/* The medium of flakes of render.h: a path tracer of the unit sphere filled with a homogeneous SGGX medium, the
 * environment gathered at each scattering event by its own sample and by the phase function's, run over the tiles
 * of render_tiles.c. The flakes' sigma, phase functions and samplers are the library's (ggx_sggx.h).
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <string.h>

#include "ggx/ggx_inline.h"
#include "render_tiles.h"
#include "surface.h"

/* Russian roulette starts after this many scattering events: the first ones carry most of the image */
#define RR_AFTER 3

typedef struct volume_job {
    const render_spec *r;
    const render_volume *v;
} volume_job;

/* The distance from p (|p| <= 1) along unit d to the unit sphere: the positive root of |p + s d| = 1. For a point on
 * the sphere leaving outwards the root is c / (b + q), not q - b, which would cancel. */
static double exit_distance(ggx_vec3 p, ggx_vec3 d)
{
    double b = ggx_k_dot_d(p, d), c = 1 - ggx_k_dot_d(p, p), q = sqrt(fmax(0.0, b * b + c));
    return b > 0 ? fmax(0.0, c) / (b + q) : q - b;
}

static double phase_eval(const render_volume *v, ggx_vec3 wi, ggx_vec3 wo)
{
    return v->phase == RENDER_PHASE_DIFFUSE ? ggx_sggx_phase_diffuse(&v->flakes, wi, wo)
                                            : ggx_sggx_phase_specular(&v->flakes, wi, wo);
}

/* A direction drawn from f(wi, .) exactly (weight 1); the zero vector where the sampler gives none. */
static ggx_vec3 phase_sample(const render_volume *v, ggx_vec3 wi, render_stream *rs)
{
    double u1 = render_uniform(rs), u2 = render_uniform(rs);
    if (v->phase == RENDER_PHASE_SPECULAR) return ggx_sggx_sample_specular(&v->flakes, wi, u1, u2);
    double u3 = render_uniform(rs), u4 = render_uniform(rs);
    return ggx_sggx_sample_diffuse(&v->flakes, wi, u1, u2, u3, u4);
}

static void add_scaled(double out[3], const double beta[3], double c, const double L[3])
{
    for (int k = 0; k < 3; k++) out[k] += beta[k] * c * L[k];
}

/* The light's sample at collision point p of a ray along d: the environment from l, attenuated to the sphere's
 * boundary along l, through the phase function f(-d, l). */
static void gather_light(const render_spec *r, const render_volume *v, ggx_vec3 p, ggx_vec3 d, const double beta[3],
                         render_stream *rs, double out[3])
{
    double pl, Le[3], u1 = render_uniform(rs), u2 = render_uniform(rs);
    ggx_vec3 l = render_env_sample(r->env, u1, u2, &pl, Le);
    if (!(pl > 0)) return;
    double f = phase_eval(v, ggx_k_scale_d(d, -1), l);
    if (!(f > 0)) return;
    ggx_vec3 along = v->fault == RENDER_FAULT_SIGMA_DIRECTION ? d : l;
    double T = exp(-v->density * ggx_sggx_sigma(&v->flakes, along) * exit_distance(p, l));
    double mis = r->strategy == RENDER_MIS ? render_power_heuristic(pl, f) : 1;
    double scale = v->fault == RENDER_FAULT_NEE_PHASE ? 1.1 : 1;
    add_scaled(out, beta, scale * f * T * mis / pl, Le);
}

/* The radiance along one camera path; out[3] += it. */
static void trace_volume(const void *ctx, const render_camera *cam, double x, double y, render_stream *rs,
                         double out[3])
{
    const volume_job *j = ctx;
    const render_spec *r = j->r;
    const render_volume *v = j->v;
    ggx_vec3 d = render_camera_dir(r, cam, x, y), o = cam->pos;
    double Le[3], beta[3] = {1, 1, 1};
    /* the camera is outside the sphere: the ray enters at the nearer root of |o + t d| = 1, if it meets it */
    double b = ggx_k_dot_d(o, d), disc = b * b - (ggx_k_dot_d(o, o) - 1);
    if (!(disc > 0) || b >= 0) {
        render_env_radiance(r->env, d, Le);
        add_scaled(out, beta, 1, Le);
        return;
    }
    double q = sqrt(disc), s = 2 * q;
    ggx_vec3 p = ggx_k_add_d(o, ggx_k_scale_d(d, -b - q)), wi = d;
    for (int events = 0;; events++) {
        /* the free flight: exact, since sigma_t(d) is constant along the ray (a NaN for density 0 escapes too) */
        double t = -log1p(-render_uniform(rs)) / (v->density * ggx_sggx_sigma(&v->flakes, d));
        if (!(t < s)) {
            /* it leaves the sphere: the environment along d, seen directly or reached by the phase's sample, whose
             * density f(wi, d) the light's sample's weight needs (evaluated here only: most samples scatter again) */
            if (events > 0 && r->strategy == RENDER_LIGHT_ONLY) return;
            double pe = render_env_lookup(r->env, d, Le);
            double mis = events > 0 && r->strategy == RENDER_MIS && pe > 0
                             ? render_power_heuristic(phase_eval(v, wi, d), pe)
                             : 1;
            add_scaled(out, beta, mis, Le);
            return;
        }
        if (events == v->scatter) return;
        p = ggx_k_add_d(p, ggx_k_scale_d(d, t));
        double most = 0;
        for (int k = 0; k < 3; k++) beta[k] *= v->albedo[k], most = fmax(most, beta[k]);
        if (!(most > 0)) return;
        if (events + 1 > RR_AFTER && most < 1) {
            /* survive with probability most, the weight divided by it: unbiased, and the weight stays <= 1 */
            if (render_uniform(rs) >= most) return;
            for (int k = 0; k < 3; k++) beta[k] /= most;
        }
        if (r->strategy != RENDER_BSDF_ONLY) gather_light(r, v, p, d, beta, rs, out);
        wi = ggx_k_scale_d(d, -1);
        d = phase_sample(v, wi, rs);
        if (!(ggx_k_dot_d(d, d) > 0)) return;
        s = exit_distance(p, d);
    }
}

void render_volume_defaults(render_volume *v)
{
    memset(v, 0, sizeof *v);
    v->density = 1;
    v->albedo[0] = v->albedo[1] = v->albedo[2] = 1;
    v->phase = RENDER_PHASE_SPECULAR;
    v->scatter = 256;
    v->fault = RENDER_FAULT_NONE;
}

int render_volume_prepare(render_volume *v, const render_spec *r, char *err, size_t errn)
{
    if (r->width < 1 || r->height < 1 || r->spp < 1 || r->threads < 1)
        return surface_fail(err, errn, "an image needs a size, samples and threads of at least 1");
    if (r->scene != RENDER_SPHERE) return surface_fail(err, errn, "the medium of flakes fills the sphere scene only");
    if (r->light != RENDER_LIGHT_ENV || !r->env)
        return surface_fail(err, errn, "the medium of flakes is lit by an environment (a distant light is not one)");
    if (!(v->density >= 0 && v->density <= 1e6))
        return surface_fail(err, errn, "the flakes' density must be in [0, 1e6] (%g given)", v->density);
    for (int k = 0; k < 3; k++)
        if (!(v->albedo[k] >= 0 && v->albedo[k] <= 1))
            return surface_fail(err, errn, "the albedo must be in [0, 1] per channel (%g given)", v->albedo[k]);
    if (v->scatter < 1) return surface_fail(err, errn, "a path needs at least one scattering event");
    ggx_status st = ggx_sggx_from_shape(&v->flakes, &r->shape);
    if (st != GGX_OK) return surface_fail(err, errn, "no flakes of this shape: %s", ggx_status_str(st));
    return 0;
}

long render_volume_image(const render_spec *r, const render_volume *v, float *rgb, float *var)
{
    volume_job j = {r, v};
    return render_tiles(r, trace_volume, &j, rgb, var);
}
