/* Measured surfaces for ggx fit: height fields and normals read from the formats of surface metrology and texture
 * tools, each parsed from bytes in memory (so the fuzz target feeds the same code), and written back for round trips.
 * SPDX-License-Identifier: MIT */
#ifndef GGX_TOOL_SURFACE_H
#define GGX_TOOL_SURFACE_H

#include <stddef.h>
#include <stdio.h>

#include "ggx/ggx.h"

/* What a file is read as: heights, unit normals, or linear RGB radiance (environment maps and rendered images, in
 * surface.rgb, never normalised). */
typedef enum surface_kind { SURFACE_HEIGHTS, SURFACE_NORMALS, SURFACE_RADIANCE } surface_kind;

typedef enum surface_format {
    SURFACE_CSV,   /* normals: x,y,z[,weight] per line, an optional header line of names */
    SURFACE_ASCII, /* heights: a matrix of numbers, one row per line (Gwyddion's and MountainsMap's text export) */
    SURFACE_XYZ,   /* heights: x y z per line on a regular grid, in any order */
    SURFACE_GSF,   /* heights: Gwyddion Simple Field (.gsf) */
    SURFACE_PNG,   /* heights (grey) or a tangent-space normal map (RGB, or grey + alpha / two channels), 8 or 16 bit */
    SURFACE_EXR,   /* heights (one channel: Y, Z or the first) or a normal map (R, G[, B]) in float */
    SURFACE_X3P,   /* heights: ISO 25178-72 / ISO 5436-2 .x3p (a zip of main.xml and the binary points) */
    SURFACE_HDR,   /* radiance: Radiance RGBE (.hdr), read through stb_image */
    SURFACE_PFM,   /* radiance (PF, 3 channels) or heights (Pf, 1 channel): the Portable Float Map */
    SURFACE_UNKNOWN
} surface_format;

typedef struct surface {
    surface_kind kind;
    size_t nx, ny;  /* the grid (heights and normal maps); a list of normals has ny = 1 */
    double *h;      /* heights, nx * ny, x fastest; NaN where the file marks a point invalid */
    ggx_vec3 *m;    /* normals, nx * ny */
    float *rgb;     /* radiance (SURFACE_RADIANCE): R, G, B per pixel, nx * ny pixels, the top row first */
    double *w;      /* the normals' weights (CSV), or NULL */
    double *uv;     /* normal maps of integer levels (PNG): each texel's decoded red and green, 2 level / (2^bits - 1)
                     * - 1 (green negated with y_down), the centre of its cell of normals (ggx_fit_normal_cells,
                     * q = 2 / (2^bits - 1)), 2 per texel; else NULL */
    double dx, dy;  /* spacing from the file (x3p, gsf, XYZ, a Gwyddion text header, OpenEXR's "spacing"), 0 where
                     * it has none */
    double z_scale; /* what brings a height into the unit of dx, dy where the file says both (x3p, gsf, XYZ and a
                     * text header with units: 1e-6 for heights in micrometres beside metres), else 0 */
    int bits;       /* 8 or 16 for PNG (1, 2 or 4 for grey of those depths), 0 for float data */
    int channels;   /* channels of a normal map: 2 (z rebuilt) or 3; of an OpenEXR height field, the file's count */
    surface_format format; /* what the file was read as */
} surface;

typedef struct surface_read_options {
    surface_kind want; /* heights or normals */
    int y_down;        /* normal maps: the green channel points down (DirectX), so y is negated */
} surface_read_options;

/* The format of a file from its first bytes (PNG, EXR, zip, "Gwyddion Simple Field") or else its name's extension. */
surface_format surface_format_of(const char *name, const unsigned char *data, size_t n);
const char *surface_format_name(surface_format f);

/* Parses data (n bytes) in the given format into s. Returns 0 on success; on failure frees what it allocated, writes
 * a one-line reason to err and returns -1. Formats not built in (no libpng, OpenEXR, libzip + libxml2) fail with
 * a reason that says so. */
int surface_parse(surface_format f, const unsigned char *data, size_t n, const surface_read_options *o, surface *s,
                  char *err, size_t errn);
/* Reads a whole file and parses it (the format from surface_format_of); -1 with err on failure. */
int surface_read(const char *path, const surface_read_options *o, surface *s, char *err, size_t errn);
void surface_free(surface *s);

/* Writers, for round trips (tests) and for surfaces the command makes: heights (kind HEIGHTS) or normals. PNG
 * heights are scaled to the full range of `bits` (the scale returned in *z_scale, height per level); normals are
 * encoded as (n + 1) / 2. Return 0, or -1 with err. */
int surface_write(const char *path, surface_format f, const surface *s, int bits, double *z_scale, char *err,
                  size_t errn);

/* Per format, in its own file. */
int surface_parse_text(surface_format f, const unsigned char *data, size_t n, surface *s, char *err, size_t errn);
int surface_parse_gsf(const unsigned char *data, size_t n, surface *s, char *err, size_t errn);
int surface_parse_png(const unsigned char *data, size_t n, const surface_read_options *o, surface *s, char *err,
                      size_t errn);
int surface_parse_exr(const unsigned char *data, size_t n, const surface_read_options *o, surface *s, char *err,
                      size_t errn);
int surface_parse_x3p(const unsigned char *data, size_t n, surface *s, char *err, size_t errn);
int surface_write_text(const char *path, surface_format f, const surface *s, char *err, size_t errn);
int surface_write_gsf(const char *path, const surface *s, char *err, size_t errn);
int surface_write_png(const char *path, const surface *s, int bits, double *z_scale, char *err, size_t errn);
int surface_write_exr(const char *path, const surface *s, char *err, size_t errn);
int surface_write_x3p(const char *path, const surface *s, char *err, size_t errn);
int surface_parse_hdr(const unsigned char *data, size_t n, surface *s, char *err, size_t errn);
int surface_parse_pfm(const unsigned char *data, size_t n, surface *s, char *err, size_t errn);
int surface_write_pfm(const char *path, const surface *s, char *err, size_t errn);
/* The bytes of an OpenEXR file (surface_write_exr's) in *data (malloc'd, *n bytes), for callers that write them
 * through their own output; 0, or -1 with err. Radiance is written as R, G, B in FLOAT; heights as Y, times z_scale
 * where it is set, and where dx and dy are set the header attribute "spacing" (dx, dy) that the reader returns. */
int surface_encode_exr(const surface *s, unsigned char **data, size_t *n, char *err, size_t errn);
/* Heights as an x3p archive in memory (malloc'd), for writers that must put the file in place atomically. */
int surface_encode_x3p(const surface *s, unsigned char **data, size_t *n, char *err, size_t errn);
/* nch (1 to 4: grey, grey + alpha, RGB, RGBA) channels of nx x ny pixels from planes[k] (row-major, the top row
 * first), each value in [0, 1] (clamped; NaN as 0) rounded to 16-bit levels, as a PNG written to f. */
int surface_write_png_channels(FILE *f, size_t nx, size_t ny, int nch, const double *const *planes, char *err,
                               size_t errn);
/* Any nch FLOAT channels of nx x ny pixels, named names[k], from planes[k] (row-major, the top row first), as an
 * OpenEXR file's bytes (ZIP, scanlines). */
int surface_encode_exr_channels(size_t nx, size_t ny, int nch, const char *const *names, float *const *planes,
                                unsigned char **data, size_t *n, char *err, size_t errn);
/* The same for PFM: "PF" (radiance) or "Pf" (heights), little-endian, the bottom row first as the format says. */
int surface_encode_pfm(const surface *s, unsigned char **data, size_t *n, char *err, size_t errn);

/* Shared by the parsers: a formatted reason into err (returns -1), and the normal of a map's texel. */
int surface_fail(char *err, size_t errn, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* Writes the n bytes of an encoded file (malloc'd; freed here) to path: 0, or -1 with "cannot write" in err and no
 * partial file left. */
int surface_write_bytes(const char *path, unsigned char *data, size_t n, char *err, size_t errn);
/* The normal of a texel whose components are c[0..channels) in [-1, 1]: two channels rebuild z = sqrt(1 - x^2 - y^2)
 * (clamped at 0); y negated for y_down. Returns the zero vector (ignored by the fit) for NaN or zero-length. */
ggx_vec3 surface_texel_normal(const double *c, int channels, int y_down);

#endif
