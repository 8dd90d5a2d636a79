/* Direct lighting of the scene by one distant light with a material the caller gives as a function (render.h):
 * the images of tabulated BRDFs (traced or wave-optics predictions) beside the model's, made by the same camera and
 * pixel loop as render_image. SPDX-License-Identifier: MIT */
#include <math.h>

#include "ggx/ggx_inline.h"
#include "render.h"
#include "render_tiles.h"

typedef struct direct_ctx {
    const render_spec *r;
    render_brdf_fn f;
    const void *fctx;
} direct_ctx;

/* One camera sample: f(l, v) cos(theta_l) E at the surface point the ray sees first (the sphere is convex and the
 * plane open: nothing shadows the light), nothing where it misses. */
static void direct_sample(const void *ctx, const render_camera *cam, double x, double y, render_stream *rs,
                          double out[3])
{
    (void)cam, (void)rs;
    const direct_ctx *c = ctx;
    render_hit h;
    if (!render_primary(c->r, x, y, &h)) return;
    ggx_vec3 wl = c->r->light_dir;
    ggx_vec3 l = {ggx_k_dot_d(wl, h.t), ggx_k_dot_d(wl, h.b), ggx_k_dot_d(wl, h.n)};
    if (!(l.z > 0) || !(h.view_local.z > 0)) return;
    double f[3] = {0, 0, 0};
    c->f(c->fctx, l, h.view_local, f);
    for (int k = 0; k < 3; k++) out[k] += f[k] * l.z * c->r->light_irradiance;
}

long render_direct(const render_spec *r, render_brdf_fn f, const void *ctx, float *rgb)
{
    direct_ctx c = {r, f, ctx};
    return render_tiles(r, direct_sample, &c, rgb, NULL);
}
