/* What every reader and writer of measured surfaces shares (surface.h): the error message, freeing a surface, a
 * normal map's texel as a unit normal, an encoded file written out. The dispatch over the formats (surface.c) sits above the formats' files,
 * which call down into this one only. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"

int surface_fail(char *err, size_t errn, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (err && errn) vsnprintf(err, errn, fmt, ap);
    va_end(ap);
    return -1;
}

void surface_free(surface *s)
{
    free(s->h);
    free(s->m);
    free(s->w);
    free(s->uv);
    free(s->rgb);
    memset(s, 0, sizeof *s);
}

ggx_vec3 surface_texel_normal(const double *c, int channels, int y_down)
{
    ggx_vec3 z = {0.0, 0.0, 0.0};
    double x = c[0], y = y_down ? -c[1] : c[1], w;
    if (channels >= 3) w = c[2];
    else w = sqrt(fmax(0.0, 1.0 - x * x - y * y));
    if (!isfinite(x) || !isfinite(y) || !isfinite(w)) return z;
    double l = sqrt(x * x + y * y + w * w);
    if (!(l > 0.0)) return z;
    return (ggx_vec3){x / l, y / l, w / l};
}

int surface_write_bytes(const char *path, unsigned char *data, size_t n, char *err, size_t errn)
{
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(data, 1, n, f) == n;
    if (f && fclose(f) != 0) ok = 0;
    free(data);
    if (!ok) {
        if (f) remove(path);
        return surface_fail(err, errn, "cannot write '%s'", path);
    }
    return 0;
}
