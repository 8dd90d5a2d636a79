/* The captions of rendered images in the command's figures (cmd_render.h), shared by ggx
 * render, ggx render --normal-map and ggx demo. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "cmd_render.h"

void render_material_words(const render_spec *r, char *buf, size_t n)
{
    const ggx_fresnel *f = &r->fresnel;
    const char *ms = r->compensate ? ", energy compensated" : "";
    if (f->kind == GGX_FRESNEL_DIELECTRIC) snprintf(buf, n, "rough glass, η %g%s", f->eta, ms);
    else if (f->kind == GGX_FRESNEL_CONDUCTOR) snprintf(buf, n, "conductor η %g, k %g%s", f->eta, f->k, ms);
    else if (f->kind == GGX_FRESNEL_SCHLICK) snprintf(buf, n, "Schlick F0 %g%s", f->f0, ms);
    else snprintf(buf, n, "F = 1%s", ms);
}

const char *render_frame_words(render_scene scene)
{
    return scene == RENDER_SPHERE
               ? "sphere: the shape's x along the parallels (east), y to the north pole; θz turns x to y"
               : "plane z = 0: the shape's x along world x, y along world y";
}
