/* The Portable Float Map: "PF" (three channels) or "Pf" (one), then the width and height, then a scale whose sign is
 * the byte order (negative: little-endian) and whose magnitude is not applied, one whitespace byte, then 32-bit floats
 * row by row from the bottom row up. Read as radiance ("PF") or heights ("Pf"), the top row first as everywhere in
 * surface; written likewise, little-endian. SPDX-License-Identifier: MIT */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"

#define PFM_MAX_SIDE 65536

static int is_space(unsigned char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/* The next whitespace-separated token of the header, at most 63 bytes, into tok; 0 when there is none. */
static int pfm_token(const unsigned char *d, size_t n, size_t *at, char tok[64])
{
    size_t i = *at, k = 0;
    while (i < n && is_space(d[i])) i++;
    while (i < n && !is_space(d[i]) && k < 63) tok[k++] = (char)d[i++];
    tok[k] = '\0';
    if (k == 0 || (i < n && !is_space(d[i]))) return 0;
    *at = i;
    return 1;
}

static float pfm_float(const unsigned char *p, int little)
{
    uint32_t u = little ? (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24
                        : (uint32_t)p[3] | (uint32_t)p[2] << 8 | (uint32_t)p[1] << 16 | (uint32_t)p[0] << 24;
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

int surface_parse_pfm(const unsigned char *data, size_t n, surface *s, char *err, size_t errn)
{
    char tok[64];
    size_t at = 0;
    if (!data || !pfm_token(data, n, &at, tok) || (strcmp(tok, "PF") != 0 && strcmp(tok, "Pf") != 0))
        return surface_fail(err, errn, "not a PFM file (it starts with PF or Pf)");
    int ch = tok[1] == 'F' ? 3 : 1;
    double v[3];
    for (int k = 0; k < 3; k++) {
        char *end;
        if (!pfm_token(data, n, &at, tok)) return surface_fail(err, errn, "a PFM header cut short");
        errno = 0;
        v[k] = strtod(tok, &end);
        if (*end || errno || !isfinite(v[k]))
            return surface_fail(err, errn, "a PFM header value '%s' is not a number", tok);
    }
    if (v[0] != floor(v[0]) || v[1] != floor(v[1]) || v[0] < 1 || v[1] < 1 || v[2] == 0)
        return surface_fail(err, errn, "a PFM header of %g x %g pixels, scale %g: not an image", v[0], v[1], v[2]);
    if (v[0] > PFM_MAX_SIDE || v[1] > PFM_MAX_SIDE)
        return surface_fail(err, errn, "%g x %g pixels: too large (at most %d a side)", v[0], v[1], PFM_MAX_SIDE);
    if (ch == 1 && (v[0] < 2 || v[1] < 2))
        return surface_fail(err, errn, "%g x %g pixels: a height field needs at least 2 x 2", v[0], v[1]);
    at++; /* the single whitespace byte before the data */
    size_t w = (size_t)v[0], h = (size_t)v[1], count = w * h * (size_t)ch;
    if (at > n || (n - at) / 4 < count)
        return surface_fail(err, errn, "a PFM file of %zu x %zu pixels cut short (%zu bytes of %zu)", w, h,
                            at > n ? 0 : n - at, count * 4);
    int little = v[2] < 0;
    float *p = malloc(count * sizeof *p);
    double *hts = ch == 1 ? malloc(w * h * sizeof *hts) : NULL;
    if (!p || (ch == 1 && !hts)) {
        free(p), free(hts);
        return surface_fail(err, errn, "out of memory");
    }
    for (size_t y = 0; y < h; y++) /* the file's first row is the image's bottom */
        for (size_t i = 0; i < w * (size_t)ch; i++)
            p[(h - 1 - y) * w * (size_t)ch + i] = pfm_float(data + at + 4 * (y * w * (size_t)ch + i), little);
    if (ch == 3) {
        s->kind = SURFACE_RADIANCE, s->rgb = p;
    } else {
        for (size_t i = 0; i < w * h; i++) hts[i] = p[i];
        free(p);
        s->kind = SURFACE_HEIGHTS, s->h = hts;
    }
    s->nx = w, s->ny = h;
    return 0;
}

int surface_encode_pfm(const surface *s, unsigned char **data, size_t *n, char *err, size_t errn)
{
    *data = NULL, *n = 0;
    int ch = s->kind == SURFACE_RADIANCE ? 3 : 1;
    if (s->kind == SURFACE_NORMALS || (ch == 3 ? !s->rgb : !s->h) || s->nx < 1 || s->ny < 1 || s->nx > PFM_MAX_SIDE ||
        s->ny > PFM_MAX_SIDE)
        return surface_fail(err, errn, "PFM holds radiance or heights of at most %d pixels a side", PFM_MAX_SIDE);
    char head[64];
    int hn = snprintf(head, sizeof head, "%s\n%zu %zu\n-1.0\n", ch == 3 ? "PF" : "Pf", s->nx, s->ny);
    size_t count = s->nx * s->ny * (size_t)ch, total = (size_t)hn + 4 * count;
    unsigned char *d = malloc(total);
    if (!d) return surface_fail(err, errn, "out of memory");
    memcpy(d, head, (size_t)hn);
    unsigned char *q = d + hn;
    for (size_t y = s->ny; y-- > 0;)
        for (size_t i = 0; i < s->nx * (size_t)ch; i++) {
            size_t k = y * s->nx * (size_t)ch + i;
            float f = ch == 3 ? s->rgb[k] : (float)s->h[k];
            uint32_t u;
            memcpy(&u, &f, sizeof u);
            for (int b = 0; b < 4; b++) *q++ = (unsigned char)(u >> (8 * b));
        }
    *data = d, *n = total;
    return 0;
}

int surface_write_pfm(const char *path, const surface *s, char *err, size_t errn)
{
    unsigned char *data;
    size_t n;
    char why[160];
    if (surface_encode_pfm(s, &data, &n, why, sizeof why) != 0)
        return surface_fail(err, errn, "cannot write '%s' (%s)", path, why);
    return surface_write_bytes(path, data, n, err, errn);
}
