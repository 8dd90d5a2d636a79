/* Gwyddion Simple Field (.gsf): a text header "Gwyddion Simple Field 1.0" of "Key = value" lines (XRes, YRes,
 * XReal, YReal, XYUnits, ZUnits), NUL padding to a multiple of 4 bytes (at least one NUL), then XRes * YRes
 * little-endian float32 heights, x fastest (Gwyddion's documentation of the format). SPDX-License-Identifier: MIT */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"

/* The factor of a unit name into metres (1 for "m"); 0 when not a length unit. */
static double unit_factor(const char *u)
{
    static const struct {
        const char *u;
        double f;
    } units[] = {{"m", 1.0},   {"mm", 1e-3},  {"um", 1e-6}, {"\xc2\xb5m", 1e-6},
                 {"nm", 1e-9}, {"pm", 1e-12}, {"A", 1e-10}};
    for (unsigned i = 0; i < sizeof units / sizeof units[0]; i++)
        if (strcmp(u, units[i].u) == 0) return units[i].f;
    return 0.0;
}

int surface_parse_gsf(const unsigned char *data, size_t n, surface *s, char *err, size_t errn)
{
    const char magic[] = "Gwyddion Simple Field 1.0\n";
    if (n < sizeof magic - 1 || memcmp(data, magic, sizeof magic - 1) != 0)
        return surface_fail(err, errn, "no 'Gwyddion Simple Field 1.0' header");
    const unsigned char *nul = memchr(data, '\0', n);
    if (!nul) return surface_fail(err, errn, "the header does not end (no NUL padding)");
    size_t hlen = (size_t)(nul - data), start = (hlen + 4) & ~(size_t)3; /* padded to 4, at least one NUL */
    char *hdr = malloc(hlen + 1);
    if (!hdr) return surface_fail(err, errn, "out of memory");
    memcpy(hdr, data, hlen);
    hdr[hlen] = '\0';
    double xres = 0, yres = 0, xreal = 1.0, yreal = 1.0;
    char xyu[32] = "", zu[32] = "";
    for (char *line = strchr(hdr, '\n'); line; line = strchr(line, '\n')) {
        line++;
        char key[32], val[64];
        if (sscanf(line, " %31[A-Za-z] = %63[^\n]", key, val) != 2) continue;
        if (strcmp(key, "XRes") == 0) xres = strtod(val, NULL);
        else if (strcmp(key, "YRes") == 0) yres = strtod(val, NULL);
        else if (strcmp(key, "XReal") == 0) xreal = strtod(val, NULL);
        else if (strcmp(key, "YReal") == 0) yreal = strtod(val, NULL);
        else if (strcmp(key, "XYUnits") == 0) snprintf(xyu, sizeof xyu, "%.31s", val);
        else if (strcmp(key, "ZUnits") == 0) snprintf(zu, sizeof zu, "%.31s", val);
    }
    free(hdr);
    if (!(xres >= 2 && yres >= 2 && xres <= 1e6 && yres <= 1e6) || xres != floor(xres) || yres != floor(yres))
        return surface_fail(err, errn, "XRes and YRes must be whole numbers from 2 to 10^6 (%g x %g given)", xres,
                            yres);
    if (!(xreal > 0 && yreal > 0 && isfinite(xreal) && isfinite(yreal)))
        return surface_fail(err, errn, "XReal and YReal must be positive (%g, %g given)", xreal, yreal);
    size_t nx = (size_t)xres, ny = (size_t)yres, count = nx * ny;
    for (size_t i = hlen; i < start && i < n; i++)
        if (data[i] != '\0') return surface_fail(err, errn, "the header's padding is not NUL bytes");
    if (start > n || n - start < 4 * count)
        return surface_fail(err, errn, "truncated: %zu x %zu heights need %zu bytes after the header, %zu there", nx,
                            ny, 4 * count, start > n ? 0 : n - start);
    s->h = malloc(count * sizeof *s->h);
    if (!s->h) return surface_fail(err, errn, "out of memory");
    for (size_t i = 0; i < count; i++) {
        const unsigned char *b = data + start + 4 * i;
        uint32_t u = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
        float f;
        memcpy(&f, &u, 4);
        s->h[i] = f;
    }
    s->kind = SURFACE_HEIGHTS, s->nx = nx, s->ny = ny;
    s->dx = xreal / xres, s->dy = yreal / yres;
    double fxy = xyu[0] ? unit_factor(xyu) : 1.0, fz = zu[0] ? unit_factor(zu) : 1.0;
    s->z_scale = fxy > 0 && fz > 0 ? fz / fxy : 0.0;
    return 0;
}

int surface_write_gsf(const char *path, const surface *s, char *err, size_t errn)
{
    FILE *o = fopen(path, "wb");
    if (!o) return surface_fail(err, errn, "cannot write '%s': %s", path, strerror(errno));
    char hdr[512];
    int len = snprintf(hdr, sizeof hdr,
                       "Gwyddion Simple Field 1.0\nXRes = %zu\nYRes = %zu\nXReal = %.17g\nYReal = %.17g\n"
                       "XYUnits = m\nZUnits = m\nTitle = ggx\n",
                       s->nx, s->ny, s->dx * (double)s->nx, s->dy * (double)s->ny);
    fwrite(hdr, 1, (size_t)len, o);
    static const char zeros[4] = {0};
    fwrite(zeros, 1, 4 - ((size_t)len & 3), o);
    for (size_t i = 0; i < s->nx * s->ny; i++) {
        float f = (float)(s->h[i] * (s->z_scale > 0 ? s->z_scale : 1.0));
        uint32_t u;
        memcpy(&u, &f, 4);
        unsigned char b[4] = {(unsigned char)u, (unsigned char)(u >> 8), (unsigned char)(u >> 16),
                              (unsigned char)(u >> 24)};
        fwrite(b, 1, 4, o);
    }
    if (fclose(o) != 0) return surface_fail(err, errn, "cannot write '%s'", path);
    return 0;
}
