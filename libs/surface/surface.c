/* Measured surfaces: format detection, file reading, dispatch to the parsers and writers. SPDX-License-Identifier: MIT */
#include "surface.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char *ext_of(const char *name)
{
    const char *dot = name ? strrchr(name, '.') : NULL, *slash = name ? strrchr(name, '/') : NULL;
    return dot && (!slash || dot > slash) ? dot + 1 : "";
}

surface_format surface_format_of(const char *name, const unsigned char *data, size_t n)
{
    if (n >= 8 && memcmp(data, "\x89PNG\r\n\x1a\n", 8) == 0) return SURFACE_PNG;
    if (n >= 4 && memcmp(data, "\x76\x2f\x31\x01", 4) == 0) return SURFACE_EXR;
    if (n >= 4 && memcmp(data, "PK\x03\x04", 4) == 0) return SURFACE_X3P;
    if (n >= 21 && memcmp(data, "Gwyddion Simple Field", 21) == 0) return SURFACE_GSF;
    if ((n >= 10 && memcmp(data, "#?RADIANCE", 10) == 0) || (n >= 6 && memcmp(data, "#?RGBE", 6) == 0))
        return SURFACE_HDR;
    if (n >= 3 && data[0] == 'P' && (data[1] == 'F' || data[1] == 'f') && (data[2] == '\n' || data[2] == ' '))
        return SURFACE_PFM;
    const char *e = ext_of(name);
    if (strcasecmp(e, "csv") == 0) return SURFACE_CSV;
    if (strcasecmp(e, "xyz") == 0) return SURFACE_XYZ;
    if (strcasecmp(e, "txt") == 0 || strcasecmp(e, "asc") == 0 || strcasecmp(e, "dat") == 0) return SURFACE_ASCII;
    if (strcasecmp(e, "gsf") == 0) return SURFACE_GSF;
    if (strcasecmp(e, "png") == 0) return SURFACE_PNG;
    if (strcasecmp(e, "exr") == 0) return SURFACE_EXR;
    if (strcasecmp(e, "x3p") == 0) return SURFACE_X3P;
    if (strcasecmp(e, "hdr") == 0 || strcasecmp(e, "pic") == 0) return SURFACE_HDR;
    if (strcasecmp(e, "pfm") == 0) return SURFACE_PFM;
    return SURFACE_UNKNOWN;
}

const char *surface_format_name(surface_format f)
{
    static const char *const names[] = {"CSV normals", "ASCII matrix", "XYZ text",      "Gwyddion .gsf", "PNG",
                                        "OpenEXR",     "x3p",          "Radiance .hdr", "PFM",           "unknown"};
    return names[f <= SURFACE_UNKNOWN ? f : SURFACE_UNKNOWN];
}

int surface_parse(surface_format f, const unsigned char *data, size_t n, const surface_read_options *o, surface *s,
                  char *err, size_t errn)
{
    surface_read_options d = {SURFACE_HEIGHTS, 0};
    if (!o) o = &d;
    memset(s, 0, sizeof *s);
    int rc;
    switch (f) {
    case SURFACE_CSV:
    case SURFACE_ASCII:
    case SURFACE_XYZ: rc = surface_parse_text(f, data, n, s, err, errn); break;
    case SURFACE_GSF: rc = surface_parse_gsf(data, n, s, err, errn); break;
    case SURFACE_PNG: rc = surface_parse_png(data, n, o, s, err, errn); break;
    case SURFACE_EXR: rc = surface_parse_exr(data, n, o, s, err, errn); break;
    case SURFACE_X3P: rc = surface_parse_x3p(data, n, s, err, errn); break;
    case SURFACE_HDR: rc = surface_parse_hdr(data, n, s, err, errn); break;
    case SURFACE_PFM: rc = surface_parse_pfm(data, n, s, err, errn); break;
    default:
        return surface_fail(err, errn,
                            o->want == SURFACE_RADIANCE
                                ? "unknown format (give .exr, .hdr or .pfm)"
                                : "unknown format (give .csv, .txt/.asc, .xyz, .gsf, .png, .exr or .x3p)");
    }
    if (rc != 0) {
        surface_free(s);
        return -1;
    }
    s->format = f;
    /* a one-channel float image (PFM "Pf") is radiance in grey where radiance is wanted */
    if (o->want == SURFACE_RADIANCE && s->kind == SURFACE_HEIGHTS && f == SURFACE_PFM) {
        size_t count = s->nx * s->ny;
        s->rgb = malloc(count * 3 * sizeof *s->rgb);
        if (!s->rgb) {
            surface_free(s);
            return surface_fail(err, errn, "out of memory");
        }
        for (size_t i = 0; i < count; i++) s->rgb[3 * i] = s->rgb[3 * i + 1] = s->rgb[3 * i + 2] = (float)s->h[i];
        free(s->h);
        s->h = NULL;
        s->kind = SURFACE_RADIANCE;
    }
    if (s->kind != o->want) {
        static const char *const what[] = {"heights", "normals", "radiance"};
        static const char *const wanted[] = {"a height field", "normals", "an image of radiance"};
        surface_kind had = s->kind;
        surface_free(s);
        return surface_fail(err, errn, "the file holds %s, not %s", what[had], wanted[o->want]);
    }
    return 0;
}

int surface_read(const char *path, const surface_read_options *o, surface *s, char *err, size_t errn)
{
    memset(s, 0, sizeof *s);
    FILE *f = fopen(path, "rb");
    if (!f) return surface_fail(err, errn, "cannot read '%s': %s", path, strerror(errno));
    size_t cap = 1 << 16, n = 0;
    unsigned char *buf = malloc(cap);
    for (;;) {
        if (!buf) {
            fclose(f);
            return surface_fail(err, errn, "'%s': out of memory", path);
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (n < cap) break;
        unsigned char *nb = cap > SIZE_MAX / 2 ? NULL : realloc(buf, cap * 2);
        if (!nb) free(buf);
        buf = nb, cap *= 2;
    }
    int bad = ferror(f), why_bad = errno;
    fclose(f);
    if (bad) {
        free(buf);
        return surface_fail(err, errn, "cannot read '%s': %s", path, strerror(why_bad));
    }
    if (n == 0) {
        free(buf);
        return surface_fail(err, errn, "'%s' is empty", path);
    }
    char why[240];
    surface_format fmt = surface_format_of(path, buf, n);
    int rc = surface_parse(fmt, buf, n, o, s, why, sizeof why);
    free(buf);
    if (rc != 0) {
        for (char *c = why; *c; c++) /* one line, whatever a reason quotes from the file */
            if ((unsigned char)*c < 0x20 || *c == 0x7f) *c = ' ';
        return surface_fail(err, errn, "'%s' (%s): %s", path, surface_format_name(fmt), why);
    }
    return 0;
}

int surface_write(const char *path, surface_format f, const surface *s, int bits, double *z_scale, char *err,
                  size_t errn)
{
    switch (f) {
    case SURFACE_CSV:
    case SURFACE_ASCII:
    case SURFACE_XYZ: return surface_write_text(path, f, s, err, errn);
    case SURFACE_GSF: return surface_write_gsf(path, s, err, errn);
    case SURFACE_PNG: return surface_write_png(path, s, bits, z_scale, err, errn);
    case SURFACE_EXR: return surface_write_exr(path, s, err, errn);
    case SURFACE_X3P: return surface_write_x3p(path, s, err, errn);
    case SURFACE_PFM: return surface_write_pfm(path, s, err, errn);
    default: return surface_fail(err, errn, "unknown format");
    }
}
