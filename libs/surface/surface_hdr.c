/* Radiance RGBE images (.hdr) through stb_image (Debian's libstb): linear RGB radiance, the top row first, as the
 * format stores it (-Y +X); the run-length and flat encodings the library decodes; a file whose pixels end early is refused (stb_image would
 * read the missing bytes as black). SPDX-License-Identifier: MIT */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"

#ifdef GGX_HAVE_STB
#include <stb_image.h>

#define HDR_MAX_SIDE 65536

/* The rows of a w x h image whose pixel data the bytes hold in full, walked as stb_image decodes them: after the
 * header's empty line and the resolution line, flat RGBE pixels (4 bytes each) where w < 8 or w >= 32768, else
 * scanlines that each start 2, 2, w / 256 (< 128), w % 256 and hold four run-length-encoded channels (a byte
 * above 128: a run of it minus 128 of the next byte; else that many bytes), and a scanline that does not start so
 * makes stb_image read the whole image flat from there (4 w h bytes). stb_image reads the bytes a file lacks as
 * zeros: the reader refuses a file whose rows end early. Returns the rows held (h for a complete file), or -1 for a
 * run-length encoding that stb_image refuses itself. */
static long hdr_rows_held(const unsigned char *data, size_t n, int w, int h)
{
    size_t p = 0;
    int empty = 0;
    while (p < n && !empty) { /* the header's lines, to its empty line */
        size_t start = p;
        while (p < n && data[p] != '\n') p++;
        empty = p == start;
        p++;
    }
    while (p < n && data[p] != '\n') p++; /* the resolution line */
    p++;
    if (p > n) return 0;
    size_t row = 4 * (size_t)w;
    if (w < 8 || w >= 32768) return (long)((n - p) / row < (size_t)h ? (n - p) / row : (size_t)h);
    for (long j = 0; j < h; j++) {
        if (n - p < 4) return j;
        if (data[p] != 2 || data[p + 1] != 2 || (data[p + 2] & 0x80)) /* flat from here, from row 0 again */
            return (long)((n - p) / row < (size_t)h ? (n - p) / row : (size_t)h);
        if ((data[p + 2] << 8 | data[p + 3]) != w) return -1;
        p += 4;
        for (int k = 0; k < 4; k++)
            for (int i = 0; i < w;) {
                if (p >= n) return j;
                int c = data[p++];
                if (c > 128) {
                    c -= 128;
                    if (c > w - i) return -1;
                    if (p >= n) return j;
                    p++;
                } else {
                    if (c > w - i) return -1;
                    if ((size_t)c > n - p) return j;
                    p += (size_t)c;
                }
                i += c;
            }
    }
    return h;
}

int surface_parse_hdr(const unsigned char *data, size_t n, surface *s, char *err, size_t errn)
{
    if (!data || n < 6 || n > INT_MAX || !stbi_is_hdr_from_memory(data, (int)n))
        return surface_fail(err, errn, "not a Radiance .hdr file");
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(data, (int)n, &w, &h, &comp) || w < 1 || h < 1)
        return surface_fail(err, errn, "not a readable Radiance .hdr file (corrupt or truncated)");
    if (w > HDR_MAX_SIDE || h > HDR_MAX_SIDE)
        return surface_fail(err, errn, "%d x %d pixels: too large (at most %d a side)", w, h, HDR_MAX_SIDE);
    long rows = hdr_rows_held(data, n, w, h);
    if (rows >= 0 && rows < h)
        return surface_fail(err, errn, "a truncated Radiance .hdr file: its pixels end after %ld of its %d rows", rows,
                            h);
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
