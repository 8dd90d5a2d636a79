/* Radiance RGBE images (.hdr) through stb_image (Debian's libstb): linear RGB radiance, the top row first, as the
 * format stores it (-Y +X); the run-length and flat encodings the library decodes. SPDX-License-Identifier: MIT */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"

#ifdef GGX_HAVE_STB
#include <stb_image.h>

#define HDR_MAX_SIDE 65536

int surface_parse_hdr(const unsigned char *data, size_t n, surface *s, char *err, size_t errn)
{
    if (!data || n < 6 || n > INT_MAX || !stbi_is_hdr_from_memory(data, (int)n))
        return surface_fail(err, errn, "not a Radiance .hdr file");
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(data, (int)n, &w, &h, &comp) || w < 1 || h < 1)
        return surface_fail(err, errn, "not a readable Radiance .hdr file (corrupt or truncated)");
    if (w > HDR_MAX_SIDE || h > HDR_MAX_SIDE)
        return surface_fail(err, errn, "%d x %d pixels: too large (at most %d a side)", w, h, HDR_MAX_SIDE);
    float *px = stbi_loadf_from_memory(data, (int)n, &w, &h, &comp, 3);
    if (!px) return surface_fail(err, errn, "not a readable Radiance .hdr file (%s)", stbi_failure_reason());
    size_t count = (size_t)w * (size_t)h * 3;
    s->rgb = malloc(count * sizeof *s->rgb);
    if (!s->rgb) {
        stbi_image_free(px);
        return surface_fail(err, errn, "out of memory");
    }
    memcpy(s->rgb, px, count * sizeof *s->rgb);
    stbi_image_free(px);
    s->kind = SURFACE_RADIANCE;
    s->nx = (size_t)w, s->ny = (size_t)h;
    return 0;
}
#else
int surface_parse_hdr(const unsigned char *data, size_t n, surface *s, char *err, size_t errn)
{
    (void)data, (void)n, (void)s;
    return surface_fail(err, errn,
                        "Radiance .hdr support was not built (stb_image missing: apt-get install libstb-dev)");
}
#endif
