/* Rendered images in the command's figures (cmd_render.h): the sRGB paint and the captions' words, shared by ggx
 * render, ggx render --normal-map and ggx demo. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>

#include "cmd_render.h"

static unsigned char srgb8(double v)
{
    v = isfinite(v) ? fmin(fmax(v, 0.0), 1.0) : 0.0;
    v = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
    return (unsigned char)lrint(255 * v);
}

void render_paint(cairo_t *cr, double x, double y, double scale, const float *rgb, int w, int h, double exposure)
{
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    unsigned char *data = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img);
    double k = exp2(exposure);
    for (int j = 0; j < h; j++) {
        uint32_t *row = (uint32_t *)(data + (size_t)j * (size_t)stride);
        for (int i = 0; i < w; i++) {
            const float *c = rgb + 3 * ((size_t)j * (size_t)w + (size_t)i);
            row[i] = (uint32_t)srgb8(k * c[0]) << 16 | (uint32_t)srgb8(k * c[1]) << 8 | srgb8(k * c[2]);
        }
    }
    paint_image(cr, img, x, y, scale);
}

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
