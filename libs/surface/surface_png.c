/* PNG surfaces through libpng: grey height maps (8 or 16 bit, raw levels) and tangent-space normal maps (RGB or RGBA;
 * an RGB map whose blue is 0 everywhere, or grey + alpha, as two channels with z rebuilt). Grey of 1, 2 or 4 bits
 * reads as its levels too. SPDX-License-Identifier: MIT */
#include <math.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"

#ifdef GGX_HAVE_PNG
#include <png.h>

typedef struct mem {
    const unsigned char *p;
    size_t n, at;
} mem;

static void mem_read(png_structp png, png_bytep out, png_size_t len)
{
    mem *m = png_get_io_ptr(png);
    if (len > m->n - m->at) png_error(png, "truncated");
    memcpy(out, m->p + m->at, len);
    m->at += len;
}

static void quiet(png_structp png, png_const_charp msg) { (void)png, (void)msg; }
/* libpng's errors end in its jump buffer without printing (the caller says what failed, in one line) */
static void fail_jump(png_structp png, png_const_charp msg)
{
    (void)msg;
    png_longjmp(png, 1);
}

int surface_parse_png(const unsigned char *data, size_t n, const surface_read_options *o, surface *s, char *err,
                      size_t errn)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, fail_jump, quiet);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        return surface_fail(err, errn, "out of memory");
    }
    mem m = {data, n, 0};
    unsigned char *volatile pixels = NULL;
    png_bytep *volatile rows = NULL;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        free(pixels), free(rows);
        free(s->h), free(s->m);
        s->h = NULL, s->m = NULL;
        return surface_fail(err, errn, "not a readable PNG (corrupt or truncated)");
    }
    png_set_read_fn(png, &m, mem_read);
    png_set_user_limits(png, 65536, 65536);
    png_read_info(png, info);
    png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    int depth = png_get_bit_depth(png, info), type = png_get_color_type(png, info);
    /* grey of 1, 2 or 4 bits is expanded to 8 by libpng's scaling (levels times 255, 85 or 17): undone below, so
     * heights are the file's own levels */
    const int grey_bits = type == PNG_COLOR_TYPE_GRAY && depth < 8 ? depth : 0;
    if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (type == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    png_read_update_info(png, info);
    depth = png_get_bit_depth(png, info);
    int ch = png_get_channels(png, info);
    size_t stride = png_get_rowbytes(png, info);
    if ((w < 2 || h < 2) && (o->want == SURFACE_HEIGHTS || ch == 1)) { /* a normal map may be one texel */
        png_destroy_read_struct(&png, &info, NULL);
        return surface_fail(err, errn, "%u x %u pixels: a height field needs at least 2 x 2", (unsigned)w, (unsigned)h);
    }
    pixels = malloc(stride * h);
    rows = malloc(h * sizeof *rows);
    if (!pixels || !rows) png_error(png, "memory");
    for (png_uint_32 y = 0; y < h; y++) rows[y] = pixels + y * stride;
    png_read_image(png, rows);
    png_read_end(png, NULL);
    png_destroy_read_struct(&png, &info, NULL);
    size_t count = (size_t)w * h;
    const double max = depth == 16 ? 65535.0 : 255.0;
#define LEVEL(i, c)                                                                                                    \
    (depth == 16 ? (double)(pixels[2 * ((i)*ch + (c))] << 8 | pixels[2 * ((i)*ch + (c)) + 1])                          \
                 : (double)pixels[(i)*ch + (c)])
    /* rows have no padding beyond ch * depth / 8 bytes per pixel: stride = w * ch * depth / 8 */
    int rc = 0;
    s->nx = w, s->ny = h, s->bits = grey_bits ? grey_bits : depth;
    const double unscale = grey_bits ? 255.0 / (double)((1 << grey_bits) - 1) : 1.0;
    if (o->want == SURFACE_HEIGHTS || ch == 1) {
        if (ch > 2) {
            rc = surface_fail(err, errn, "a colour PNG is not a height map (give a grey PNG)");
        } else if (!(s->h = malloc(count * sizeof *s->h))) {
            rc = surface_fail(err, errn, "out of memory");
        } else {
            for (size_t i = 0; i < count; i++) s->h[i] = LEVEL(i, 0) / unscale;
            s->kind = SURFACE_HEIGHTS;
        }
    } else {
        int two = ch == 2;
        if (!two) { /* an RGB map with blue 0 everywhere carries x and y only */
            two = 1;
            for (size_t i = 0; i < count && two; i++) two = LEVEL(i, 2) == 0.0;
        }
        s->channels = two ? 2 : 3;
        if (!(s->m = malloc(count * sizeof *s->m)) || !(s->uv = malloc(2 * count * sizeof *s->uv))) {
            rc = surface_fail(err, errn, "out of memory");
        } else {
            for (size_t i = 0; i < count; i++) {
                double c[3];
                for (int k = 0; k < s->channels; k++) {
                    c[k] = 2.0 * LEVEL(i, k) / max - 1.0;
                }
                s->m[i] = surface_texel_normal(c, s->channels, o->y_down);
                s->uv[2 * i] = c[0], s->uv[2 * i + 1] = o->y_down ? -c[1] : c[1];
            }
            s->kind = SURFACE_NORMALS;
        }
    }
#undef LEVEL
    free(pixels), free(rows);
    return rc;
}

/* planes[k] in [0, 1] (clamped; NaN as 0) as the levels of 8 or 16 bits, rounded to the nearest */
static int write_png_levels(FILE *f, size_t nx, size_t ny, int nch, int bits, const double *const *planes, char *err,
                            size_t errn)
{
    static const int types[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                 PNG_COLOR_TYPE_RGB_ALPHA};
    if (nch < 1 || nch > 4 || nx < 1 || ny < 1 || nx > 0x7fffffff || ny > 0x7fffffff)
        return surface_fail(err, errn, "no image for PNG");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, fail_jump, quiet);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    unsigned char *volatile row = NULL;
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        free(row);
        return surface_fail(err, errn, "PNG encoding failed");
    }
    png_init_io(png, f);
    int bpc = bits == 16 ? 2 : 1;
    double max = bits == 16 ? 65535.0 : 255.0;
    png_set_IHDR(png, info, (png_uint_32)nx, (png_uint_32)ny, bits == 16 ? 16 : 8, types[nch], PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    row = malloc(nx * (size_t)nch * (size_t)bpc);
    if (!row) png_error(png, "memory");
    for (size_t y = 0; y < ny; y++) {
        for (size_t x = 0; x < nx; x++)
            for (int k = 0; k < nch; k++) {
                double v = planes[k][y * nx + x];
                unsigned l = (unsigned)lround(fmin(fmax(isnan(v) ? 0.0 : v, 0.0), 1.0) * max);
                unsigned char *p = row + (x * (size_t)nch + (size_t)k) * (size_t)bpc;
                if (bpc == 2) p[0] = (unsigned char)(l >> 8), p[1] = (unsigned char)l;
                else p[0] = (unsigned char)l;
            }
        png_write_row(png, row);
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(row);
    return 0;
}

int surface_write_png_channels(FILE *f, size_t nx, size_t ny, int nch, const double *const *planes, char *err,
                               size_t errn)
{
    return write_png_levels(f, nx, ny, nch, 16, planes, err, errn);
}

int surface_write_png(const char *path, const surface *s, int bits, double *z_scale, char *err, size_t errn)
{
    int heights = s->kind == SURFACE_HEIGHTS, ch = heights ? 1 : 3;
    size_t n = s->nx * s->ny;
    double *v = malloc(n * (size_t)ch * sizeof *v), lo = 0.0, hi = 1.0;
    if (!v) return surface_fail(err, errn, "cannot write '%s': out of memory", path);
    if (heights) { /* the heights' range over the levels; z_scale, the height of one level */
        lo = HUGE_VAL, hi = -HUGE_VAL;
        for (size_t i = 0; i < n; i++) lo = fmin(lo, s->h[i]), hi = fmax(hi, s->h[i]);
        if (!(hi > lo)) hi = lo + 1.0;
        if (z_scale) *z_scale = (hi - lo) / (bits == 16 ? 65535.0 : 255.0);
    }
    for (size_t i = 0; i < n; i++) {
        if (heights) v[i] = (s->h[i] - lo) / (hi - lo);
        else { /* a tangent-space normal map: 0.5 (c + 1) per channel */ v[i] = s->m ? 0.5 * (s->m[i].x + 1.0) : 0.5;
            v[n + i] = s->m ? 0.5 * (s->m[i].y + 1.0) : 0.5;
            v[2 * n + i] = s->m ? 0.5 * (s->m[i].z + 1.0) : 0.5;
        }
    }
    const double *planes[3] = {v, v + n, v + 2 * n};
    FILE *f = fopen(path, "wb");
    int rc = f ? write_png_levels(f, s->nx, s->ny, ch, bits, planes, err, errn) : -1;
    if (f && fclose(f) != 0) rc = -1;
    free(v);
    if (rc != 0) {
        if (f) remove(path);
        return surface_fail(err, errn, "cannot write '%s'", path);
    }
    return 0;
}
#else
int surface_write_png_channels(FILE *f, size_t nx, size_t ny, int nch, const double *const *planes, char *err,
                               size_t errn)
{
    (void)f, (void)nx, (void)ny, (void)nch, (void)planes;
    return surface_fail(err, errn, "PNG support was not built (libpng missing: apt-get install libpng-dev)");
}
int surface_parse_png(const unsigned char *data, size_t n, const surface_read_options *o, surface *s, char *err,
                      size_t errn)
{
    (void)data, (void)n, (void)o, (void)s;
    return surface_fail(err, errn, "PNG support was not built (libpng missing: apt-get install libpng-dev)");
}
int surface_write_png(const char *path, const surface *s, int bits, double *z_scale, char *err, size_t errn)
{
    (void)path, (void)s, (void)bits, (void)z_scale;
    return surface_fail(err, errn, "PNG support was not built (libpng missing: apt-get install libpng-dev)");
}
#endif
