/* The readers of measured surfaces (libs/surface): every format written and read back, the normal maps'
 * conventions, and every malformed case refused with a reason and nothing left allocated. SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ggx/ggx_fit.h"
#include "surface.h"
#include "testlib.h"

#if __has_include(<png.h>)
#include <png.h>
#define HAVE_PNG 1
#endif
#if __has_include(<zip.h>)
#include <zip.h>
#define HAVE_ZIP 1
#endif

static char dir[64];

static const char *tmp(const char *name)
{
    static char p[128];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return p;
}

/* A 7 x 5 height field with rough values, spacing 2e-6 x 3e-6 m, heights in metres. */
static surface heights(void)
{
    surface s;
    memset(&s, 0, sizeof s);
    s.kind = SURFACE_HEIGHTS, s.nx = 7, s.ny = 5, s.dx = 2e-6, s.dy = 3e-6, s.z_scale = 1.0;
    s.h = malloc(35 * sizeof *s.h);
    rng r = {5};
    for (int i = 0; i < 35; i++) s.h[i] = 1e-7 * rng_range(&r, -1.0, 1.0) + 3e-7 * i;
    return s;
}

static surface normals(size_t nx, size_t ny)
{
    surface s;
    memset(&s, 0, sizeof s);
    s.kind = SURFACE_NORMALS, s.nx = nx, s.ny = ny;
    s.m = malloc(nx * ny * sizeof *s.m);
    rng r = {6};
    for (size_t i = 0; i < nx * ny; i++) {
        double x = rng_range(&r, -0.6, 0.6), y = rng_range(&r, -0.6, 0.6), l = sqrt(1 + x * x + y * y);
        s.m[i] = (ggx_vec3){x / l, y / l, 1 / l};
    }
    return s;
}

static void read_ok(const char *path, surface_kind want, surface *s, int y_down)
{
    surface_read_options o = {want, y_down};
    char err[512] = "";
    int rc = surface_read(path, &o, s, err, sizeof err);
    CHECK(rc == 0, "%s: %s", path, err);
}

/* Heights through every height format: text exactly (%.17g), gsf to float, x3p exactly, PNG to half a level of
 * 16 bits; spacing and units come back where the format has them. */
static void height_round_trips(void **state)
{
    (void)state;
    surface s = heights();
    const struct {
        surface_format f;
        const char *name;
        double tol; /* relative to the range of heights */
        int spacing;
    } cases[] = {{SURFACE_ASCII, "h.txt", 1e-15, 1},      {SURFACE_XYZ, "h.xyz", 1e-15, 1},
                 {SURFACE_GSF, "h.gsf", 1e-6, 1},         {SURFACE_X3P, "h.x3p", 0.0, 1},
                 {SURFACE_PNG, "h.png", 0.51 / 65535, 0}, {SURFACE_EXR, "h.exr", 1e-6, 1}};
    for (unsigned c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char err[256] = "";
        double zs = 0.0;
        int rc = surface_write(tmp(cases[c].name), cases[c].f, &s, 16, &zs, err, sizeof err);
        CHECK(rc == 0, "write %s: %s", cases[c].name, err);
        surface b;
        read_ok(tmp(cases[c].name), SURFACE_HEIGHTS, &b, 0);
        CHECK(b.nx == 7 && b.ny == 5, "%s: %zu x %zu", cases[c].name, b.nx, b.ny);
        double lo = HUGE_VAL, hi = -HUGE_VAL, worst = 0.0;
        for (int i = 0; i < 35; i++) lo = fmin(lo, s.h[i]), hi = fmax(hi, s.h[i]);
        for (int i = 0; i < 35; i++) {
            double got = cases[c].f == SURFACE_PNG ? lo + b.h[i] * zs : b.h[i] * b.z_scale;
            worst = fmax(worst, fabs(got - s.h[i]) / (hi - lo));
        }
        CHECK(worst <= cases[c].tol + 1e-16, "%s: heights off by %g of the range", cases[c].name, worst);
        if (cases[c].spacing) {
            CHECK_CLOSE(b.dx, 2e-6, 1e-12, 0.0, "%s dx", cases[c].name);
            CHECK_CLOSE(b.dy, 3e-6, 1e-12, 0.0, "%s dy", cases[c].name);
            CHECK(b.z_scale > 0, "%s: no height unit", cases[c].name);
        } else {
            CHECK(b.dx == 0 && b.z_scale == 0 && b.bits == (cases[c].f == SURFACE_PNG ? 16 : 0),
                  "%s: spacing or units invented", cases[c].name);
        }
        printf("heights %s: largest error %.3g of the range\n", cases[c].name, worst);
        surface_free(&b);
    }
    surface_free(&s);
}

/* Normals: CSV exactly (with and without weights); PNG normal maps of 8 and 16 bits within half a level per
 * component; y_down negates y; a map whose blue is 0 rebuilds z. */
static void normal_round_trips(void **state)
{
    (void)state;
    surface s = normals(9, 1);
    char err[256] = "";
    CHECK(surface_write(tmp("n.csv"), SURFACE_CSV, &s, 0, NULL, err, sizeof err) == 0, "%s", err);
    surface b;
    read_ok(tmp("n.csv"), SURFACE_NORMALS, &b, 0);
    CHECK(b.nx == 9 && b.ny == 1 && !b.w && memcmp(b.m, s.m, 9 * sizeof *s.m) == 0, "CSV normals differ");
    surface_free(&b);
    s.w = malloc(9 * sizeof *s.w);
    for (int i = 0; i < 9; i++) s.w[i] = 0.5 + i;
    CHECK(surface_write(tmp("nw.csv"), SURFACE_CSV, &s, 0, NULL, err, sizeof err) == 0, "%s", err);
    read_ok(tmp("nw.csv"), SURFACE_NORMALS, &b, 0);
    CHECK(b.w && memcmp(b.w, s.w, 9 * sizeof *s.w) == 0, "CSV weights differ");
    surface_free(&b);
    surface_free(&s);

    s = normals(6, 4);
    for (int bits = 8; bits <= 16; bits += 8) {
        const char *name = bits == 8 ? "n8.png" : "n16.png";
        CHECK(surface_write(tmp(name), SURFACE_PNG, &s, bits, NULL, err, sizeof err) == 0, "%s", err);
        double level = 2.0 / (bits == 8 ? 255.0 : 65535.0);
        for (int mode = 0; mode < 2; mode++) { /* y up, y down */
            read_ok(tmp(name), SURFACE_NORMALS, &b, mode == 1);
            CHECK(b.nx == 6 && b.ny == 4 && b.channels == 3 && b.bits == bits, "%s: %zu x %zu", name, b.nx, b.ny);
            double worst = 0.0;
            for (int i = 0; i < 24; i++) {
                /* the stored components were (n + 1) / 2 of the unit normal; read back, normalised again */
                double y = mode == 1 ? -b.m[i].y : b.m[i].y;
                worst = fmax(worst, fmax(fabs(b.m[i].x - s.m[i].x), fabs(y - s.m[i].y)));
            }
            double tol = 0.5 * level * 2.5; /* half a level per component, then normalised */
            CHECK(worst <= tol, "%s mode %d: off by %g (tolerance %g)", name, mode, worst, tol);
            surface_free(&b);
        }
    }
    /* OpenEXR normal maps: float components, y down too. */
    CHECK(surface_write(tmp("n.exr"), SURFACE_EXR, &s, 0, NULL, err, sizeof err) == 0, "%s", err);
    for (int mode = 0; mode < 2; mode++) {
        read_ok(tmp("n.exr"), SURFACE_NORMALS, &b, mode);
        CHECK(b.nx == 6 && b.ny == 4 && b.channels == 3 && b.bits == 0, "n.exr: %zu x %zu", b.nx, b.ny);
        for (int i = 0; i < 24; i++) {
            CHECK_CLOSE(b.m[i].x, s.m[i].x, 0.0, 1e-7, "exr normal %d x", i);
            CHECK_CLOSE(mode ? -b.m[i].y : b.m[i].y, s.m[i].y, 0.0, 1e-7, "exr normal %d y", i);
        }
        surface_free(&b);
    }
    /* Two channels: blue 0 everywhere, z rebuilt from x and y. */
    surface two = normals(6, 4);
    for (int i = 0; i < 24; i++) two.m[i].z = -1.0; /* (z + 1) / 2 = 0: blue 0 */
    CHECK(surface_write(tmp("n2.png"), SURFACE_PNG, &two, 16, NULL, err, sizeof err) == 0, "%s", err);
    read_ok(tmp("n2.png"), SURFACE_NORMALS, &b, 0);
    CHECK(b.channels == 2, "two channels not recognised: %d", b.channels);
    for (int i = 0; i < 24; i++)
        CHECK_CLOSE(b.m[i].z, sqrt(1 - s.m[i].x * s.m[i].x - s.m[i].y * s.m[i].y), 0.0, 1e-4, "rebuilt z %d", i);
    surface_free(&b);
    surface_free(&two);
    /* A normal map read as heights, and heights read as a normal map: refused with a reason. */
    surface_read_options ho = {SURFACE_HEIGHTS, 0};
    CHECK(surface_read(tmp("n8.png"), &ho, &b, err, sizeof err) != 0 && strstr(err, "colour"), "%s", err);
    surface_read_options no = {SURFACE_NORMALS, 0};
    CHECK(surface_read(tmp("h.gsf"), &no, &b, err, sizeof err) != 0 && strstr(err, "heights"), "%s", err);
    surface_free(&s);
}

/* Malformed input: every case returns -1 with a reason and leaves s empty. */
static void refuse(surface_format f, const char *data, size_t n, surface_kind want, const char *expect)
{
    surface s;
    surface_read_options o = {want, 0};
    char err[256] = "";
    int rc = surface_parse(f, (const unsigned char *)data, n, &o, &s, err, sizeof err);
    CHECK(rc == -1, "%s accepted: %.60s", surface_format_name(f), data);
    CHECK(strstr(err, expect) != NULL, "%s: reason '%s', expected '%s'", surface_format_name(f), err, expect);
    CHECK(s.h == NULL && s.m == NULL && s.w == NULL, "memory left after a refusal");
}

static char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    *n = 0;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)len + 1);
    *n = fread(b, 1, (size_t)len, f);
    fclose(f);
    return b;
}

static void malformed(void **state)
{
    (void)state;
    const surface_kind H = SURFACE_HEIGHTS, N = SURFACE_NORMALS;
    refuse(SURFACE_CSV, "x,y,z\n0.1,0.2\n", 14, N, "not x,y,z");
    refuse(SURFACE_CSV, "", 0, N, "no normals");
    refuse(SURFACE_CSV, "0,0,1\n0,0,nan\n", 14, N, "not a finite number");
    refuse(SURFACE_CSV, "0,0,1\n0,0,1,2\n", 14, N, "weight on some lines");
    refuse(SURFACE_ASCII, "1 2 3\n4 5\n", 10, H, "the first row has 3");
    refuse(SURFACE_ASCII, "1\n", 2, H, "at least 2 x 2");
    refuse(SURFACE_ASCII, "1 2\n3 inf\n", 10, H, "not a finite number");
    refuse(SURFACE_ASCII, "1 2\n3 4\0", 8, H, "NUL byte");
    refuse(SURFACE_XYZ, "0 0 1\n1 0 2\n0 1 3\n", 18, H, "not a regular grid");
    refuse(SURFACE_XYZ, "0 0 1\n1 0 2\n0 1 3\n1 1\n", 22, H, "not x y z");
    refuse(SURFACE_XYZ, "0 0 1\n1 0 2\n0 1 3\n3 1 4\n", 24, H, "not a regular grid");
    refuse(SURFACE_GSF, "Gwyddion Simple Field 1.0\nXRes = 2\nYRes = 2\n", 44, H, "does not end");
    refuse(SURFACE_GSF, "Gwyddion Simple Field 1.0\nXRes = 1\nYRes = 2\n\0\0\0", 47, H, "from 2 to");
    refuse(SURFACE_GSF, "Gwyddion Simple Field 1.0\nXRes = 2\nYRes = 2\nXReal = 0\n\0\0", 55, H, "positive");
    refuse(SURFACE_GSF, "Gwyddion Simple Field 1.0\nXRes = 2\nYRes = 2\n\0\0\0\0\0\0\0", 51, H, "truncated");
    refuse(SURFACE_GSF, "Gwyddion", 8, H, "header");
    refuse(SURFACE_PNG, "\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16, H, "PNG");
    refuse(SURFACE_X3P, "PK\x05\x06\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0", 22, H, "main.xml"); /* an empty zip */
    refuse(SURFACE_X3P, "PK\x03\x04garbage", 11, H, "zip");
    refuse(SURFACE_EXR, "\x76\x2f\x31\x01\x02\0\0\0garbage", 15, H, "OpenEXR");
    refuse(SURFACE_UNKNOWN, "abc", 3, H, "unknown format");
    /* A PNG of 1 x 1 pixel, a truncated PNG, x3p with bad XML and with short data. */
    surface s = heights();
    s.nx = 1, s.ny = 1;
    char err[256];
    CHECK(surface_write(tmp("one.png"), SURFACE_PNG, &s, 8, NULL, err, sizeof err) == 0, "%s", err);
    size_t n = 0;
    char *b = slurp(tmp("one.png"), &n);
    refuse(SURFACE_PNG, b, n, H, "at least 2 x 2");
    free(b);
    s.nx = 7, s.ny = 5;
    CHECK(surface_write(tmp("t.png"), SURFACE_PNG, &s, 16, NULL, err, sizeof err) == 0, "%s", err);
    b = slurp(tmp("t.png"), &n);
    refuse(SURFACE_PNG, b, n - 20, H, "corrupt or truncated");
    free(b);
    CHECK(surface_write(tmp("t.exr"), SURFACE_EXR, &s, 0, NULL, err, sizeof err) == 0, "%s", err);
    b = slurp(tmp("t.exr"), &n);
    refuse(SURFACE_EXR, b, n - 20, H, "corrupt or truncated");
    refuse(SURFACE_EXR, b, n / 2, H, "corrupt or truncated");
    free(b);
    CHECK(surface_write(tmp("t.x3p"), SURFACE_X3P, &s, 0, NULL, err, sizeof err) == 0, "%s", err);
    b = slurp(tmp("t.x3p"), &n);
    refuse(SURFACE_X3P, b, n - 30, H, "zip");
    free(b);
    surface_free(&s);
    /* empty and missing files */
    FILE *f = fopen(tmp("empty.gsf"), "w");
    fclose(f);
    surface_read_options o = {H, 0};
    CHECK(surface_read(tmp("empty.gsf"), &o, &s, err, sizeof err) != 0 && strstr(err, "empty"), "%s", err);
    CHECK(surface_read(tmp("missing.gsf"), &o, &s, err, sizeof err) != 0 && strstr(err, "cannot read"), "%s", err);
}

/* Gwyddion's text export header: widths and the value unit give spacing in metres and heights' scale. */
static void gwyddion_text_header(void **state)
{
    (void)state;
    const char *t = "# Channel: Height\n# Width: 4.000 \xc2\xb5m\n# Height: 2.000 \xc2\xb5m\n# Value units: nm\n"
                    "1 2 3 4\n5 6 7 8\n";
    surface s;
    surface_read_options o = {SURFACE_HEIGHTS, 0};
    char err[128];
    CHECK(surface_parse(SURFACE_ASCII, (const unsigned char *)t, strlen(t), &o, &s, err, sizeof err) == 0, "%s", err);
    CHECK_CLOSE(s.dx, 1e-6, 1e-12, 0.0, "dx");
    CHECK_CLOSE(s.dy, 1e-6, 1e-12, 0.0, "dy");
    CHECK_CLOSE(s.z_scale, 1e-9, 1e-12, 0.0, "nm heights");
    surface_free(&s);
}

/* The quantisation of normal maps, measured: texels of isotropic shapes drawn by the NDF sampler, written at 8 and
 * 16 bits and fitted at their levels, against the fit of the same normals in double. 16 bits: within 0.05 % for
 * alpha down to 0.005. 8 bits: within 0.5 % for alpha >= 0.05; at alpha 0.01 the levels (2 / 255 apart) inflate
 * alpha by more than 3 %; the 8-bit texels fitted as cells (ggx_fit_normal_cells, as ggx fit does) stay within 1 %
 * at every alpha (docs/design/fit.md). */
static void quantisation(void **state)
{
    (void)state;
    const double alphas[] = {0.005, 0.01, 0.02, 0.05, 0.1, 0.3};
    for (int k = 0; k < 6; k++) {
        ggx_shape sh;
        assert_int_equal(ggx_shape_iso(&sh, alphas[k]), GGX_OK);
        rng r = {(uint64_t)k + 1};
        surface m;
        memset(&m, 0, sizeof m);
        m.kind = SURFACE_NORMALS, m.nx = m.ny = 256;
        m.m = malloc(65536 * sizeof *m.m);
        for (int i = 0; i < 65536; i++) m.m[i] = ggx_sample_ndf(&sh, rng_uniform(&r), rng_uniform(&r));
        ggx_fit_options o = {GGX_FIT_ISOTROPIC, 0, 0, 0, NULL, NULL, 0};
        ggx_shape f;
        ggx_fit_info info;
        assert_int_equal(ggx_fit_normals(&f, m.m, NULL, 65536, &o, &info), GGX_OK);
        double a0 = sqrt(info.sigma[0]), rel[2], cells = 0.0;
        for (int b = 0; b < 2; b++) {
            char err[200];
            CHECK(surface_write(tmp("q.png"), SURFACE_PNG, &m, b ? 16 : 8, NULL, err, sizeof err) == 0, "%s", err);
            surface q;
            read_ok(tmp("q.png"), SURFACE_NORMALS, &q, 0);
            assert_int_equal(ggx_fit_normals(&f, q.m, NULL, 65536, &o, &info), GGX_OK);
            rel[b] = sqrt(info.sigma[0]) / a0 - 1.0;
            if (b == 0) { /* the same 8-bit texels as cells */
                CHECK(q.uv != NULL, "no decoded levels");
                assert_int_equal(ggx_fit_normal_cells(&f, q.uv, NULL, 65536, 2.0 / 255.0, &o, &info), GGX_OK);
                cells = sqrt(info.sigma[0]) / a0 - 1.0;
            }
            surface_free(&q);
        }
        printf("quantisation: alpha %.3g: 8-bit %+.3f %% (as cells %+.3f %%), 16-bit %+.4f %%\n", alphas[k],
               100 * rel[0], 100 * cells, 100 * rel[1]);
        CHECK(fabs(rel[1]) <= 5e-4, "16 bits at alpha %g: %g", alphas[k], rel[1]);
        if (alphas[k] >= 0.05) CHECK(fabs(rel[0]) <= 5e-3, "8 bits at alpha %g: %g", alphas[k], rel[0]);
        if (alphas[k] == 0.01) CHECK(rel[0] > 0.03, "8 bits at alpha 0.01: %g (the documented inflation)", rel[0]);
        /* as cells: within 1 % of the fit in double at every alpha (the standard error of alpha is about 0.2 %) */
        CHECK(fabs(cells) <= 0.01, "8 bits as cells at alpha %g: %g", alphas[k], cells);
        surface_free(&m);
    }
}

#ifdef HAVE_PNG
/* Grey PNGs of 1, 2, 4, 8 and 16 bits read as their own levels (not libpng's expansion to 8 bits), W x 1 and 1 x H
 * refused alike as heights. */
static void png_grey_depths(void **state)
{
    (void)state;
    static const int depths[5] = {1, 2, 4, 8, 16};
    for (int d = 0; d < 5; d++) {
        int bits = depths[d];
        unsigned top = (1u << bits) - 1;
        for (int shape = 0; shape < 3; shape++) {
            png_uint_32 w = shape == 1 ? 1 : 4, h = shape == 2 ? 1 : 3;
            FILE *f = fopen(tmp("grey.png"), "wb");
            png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
            png_infop info = png_create_info_struct(png);
            png_init_io(png, f);
            png_set_IHDR(png, info, w, h, bits, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                         PNG_FILTER_TYPE_DEFAULT);
            png_write_info(png, info);
            if (bits < 8) png_set_packing(png);
            unsigned char row[8];
            for (png_uint_32 y = 0; y < h; y++) {
                for (png_uint_32 x = 0; x < w; x++) {
                    unsigned v = (x + y * w) % (top + 1);
                    if (bits == 16) row[2 * x] = (unsigned char)(v >> 8), row[2 * x + 1] = (unsigned char)v;
                    else row[x] = (unsigned char)v;
                }
                png_write_row(png, row);
            }
            png_write_end(png, NULL);
            png_destroy_write_struct(&png, &info);
            fclose(f);
            surface s;
            surface_read_options o = {SURFACE_HEIGHTS, 0};
            char err[512] = "";
            int rc = surface_read(tmp("grey.png"), &o, &s, err, sizeof err);
            if (shape) {
                CHECK(rc != 0 && strstr(err, "at least 2 x 2"), "%d-bit %u x %u: %s", bits, (unsigned)w, (unsigned)h,
                      err);
                continue;
            }
            CHECK(rc == 0 && s.bits == bits, "%d-bit grey: %s", bits, err);
            for (size_t i = 0; i < 12; i++)
                CHECK(s.h[i] == (double)(i % (top + 1)), "%d-bit grey: level %zu read as %g", bits, i, s.h[i]);
            surface_free(&s);
        }
    }
}
#endif

/* One absurd finite height (1e308) among ordinary ones: left out of the levelling and its facets, the fit as
 * without it (rather than every slope overflowing). */
static void absurd_height(void **state)
{
    (void)state;
    size_t nx = 40, ny = 40;
    double *h = malloc(nx * ny * sizeof *h);
    rng r = {9};
    for (size_t i = 0; i < nx * ny; i++) h[i] = rng_range(&r, -1.0, 1.0) + 0.01 * (double)(i % nx);
    ggx_shape a, b;
    ggx_fit_info ia, ib;
    CHECK(ggx_fit_heightfield(&a, h, nx, ny, 1.0, 1.0, NULL, NULL, &ia) == GGX_OK, "the ordinary field");
    h[20 * nx + 20] = 1e308;
    ggx_status st = ggx_fit_heightfield(&b, h, nx, ny, 1.0, 1.0, NULL, NULL, &ib);
    CHECK(st == GGX_OK && ib.used == ia.used - 16 && ib.ignored_nonfinite == 16, "one absurd height: %s, used %zu",
          ggx_status_str(st), ib.used);
    CHECK(fabs(ib.sigma[0] / ia.sigma[0] - 1) < 0.02 && fabs(ib.t[0] - ia.t[0]) < 0.02, "sigma %g against %g",
          ib.sigma[0], ia.sigma[0]);
    free(h);
}

#ifndef GGX_SOURCE_DIR
#define GGX_SOURCE_DIR "."
#endif

/* The public x3p files of tests/data/x3p (README.md there names their sources): each read with its size, spacing and
 * missing points, and fitted; the point cloud and the file whose main.xml no longer matches its checksum refused. */
static void x3p_public(void **state)
{
    (void)state;
    static const struct {
        const char *file;
        size_t nx, ny, missing;
        double dx, dy, h0; /* h0: the first height */
        const char *refused;
    } files[] = {
        {"ISO5436-sample1.x3p", 4, 4, 1, 1.6016e-2, 1.6016e-2, 4.86219120804151e-1, NULL},
        {"ISO5436-sample1_bin.x3p", 4, 4, 1, 1.6016e-2, 1.6016e-2, 4.86219120804151e-1, NULL},
        {"ISO5436-sample3.x3p", 4, 4, 1, 1.6016e-2, 2.0, 2.0 + 4.86219120804151e-1, NULL},
        {"ISO5436-sample4.x3p", 4, 4, 1, 1.6016e-2, 1.6016e-2, -0.5 + 986 * 0.001, NULL},
        {"ISO5436-sample4_bin.x3p", 4, 4, 1, 1.6016e-2, 1.6016e-2, -0.5 + 986 * 0.001, NULL},
        {"KautschukInfiniteFocus.x3p", 860, 634, 5296, 2.279984215e-6, 2.279794519e-6, NAN, NULL},
        {"sample-land.x3p", 918, 256, 25292, 2.58e-6, 2.58e-6, NAN, NULL},
        {"pyramid.x3p", 5, 5, 0, 1.0, 1.0, NAN, NULL},
        {"testing.x3p", 30, 20, 0, 0.0274999996026357, 0.0274999996026357, NAN, NULL},
        {"ISO5436-sample2.x3p", 0, 0, 0, 0, 0, 0, "point cloud"},
        {"csafe-logo.x3p", 0, 0, 0, 0, 0, 0, "main.xml's MD5 is"},
    };
    for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
        char path[512], err[512] = "";
        snprintf(path, sizeof path, "%s/tests/data/x3p/%s", GGX_SOURCE_DIR, files[f].file);
        surface s;
        surface_read_options o = {SURFACE_HEIGHTS, 0};
        int rc = surface_read(path, &o, &s, err, sizeof err);
        if (files[f].refused) {
            CHECK(rc != 0 && strstr(err, files[f].refused) && !strchr(err, '\n'), "%s: '%s'", files[f].file, err);
            continue;
        }
        CHECK(rc == 0, "%s: %s", files[f].file, err);
        if (rc != 0) continue;
        size_t missing = 0;
        for (size_t i = 0; i < s.nx * s.ny; i++) missing += !isfinite(s.h[i]);
        CHECK(s.nx == files[f].nx && s.ny == files[f].ny && missing == files[f].missing, "%s: %zu x %zu, %zu missing",
              files[f].file, s.nx, s.ny, missing);
        CHECK(fabs(s.dx / files[f].dx - 1) < 1e-9 && fabs(s.dy / files[f].dy - 1) < 1e-9, "%s: spacing %g x %g",
              files[f].file, s.dx, s.dy);
        if (isfinite(files[f].h0)) CHECK(fabs(s.h[0] - files[f].h0) < 1e-12, "%s: h[0] = %.17g", files[f].file, s.h[0]);
        ggx_shape out;
        ggx_fit_info info;
        ggx_status st = ggx_fit_heightfield(&out, s.h, s.nx, s.ny, s.dx / s.z_scale, s.dy / s.z_scale, NULL, NULL,
                                            &info);
        CHECK(st == GGX_OK && info.used > 0, "%s: fit: %s", files[f].file, ggx_status_str(st));
        surface_free(&s);
    }
}

#ifdef HAVE_ZIP
/* An archive of named members (name, bytes, length; a NULL name ends the list) as a file; its bytes in *n. */
static unsigned char *zip_members(const char *path, const char *const *names, const char *const *data,
                                  const size_t *len, size_t *n)
{
    remove(path);
    int e;
    zip_t *z = zip_open(path, ZIP_CREATE | ZIP_TRUNCATE, &e);
    for (int k = 0; names[k]; k++) {
        zip_source_t *src = zip_source_buffer(z, data[k], len[k] ? len[k] : strlen(data[k]), 0);
        zip_file_add(z, names[k], src, ZIP_FL_ENC_UTF_8);
    }
    zip_close(z);
    return (unsigned char *)slurp(path, n);
}

/* main.xml with the given axes and Record3 body, of an areal surface. */
static void x3p_xml(char *out, size_t n, const char *feature, const char *cx, const char *cy, const char *cz,
                    const char *record3)
{
    snprintf(out, n,
             "<?xml version=\"1.0\"?><p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\"><Record1>"
             "<Revision>ISO5436 - 2000</Revision><FeatureType>%s</FeatureType><Axes><CX>%s</CX><CY>%s</CY>"
             "<CZ>%s</CZ></Axes></Record1><Record3>%s</Record3></p:ISO5436_2>",
             feature, cx, cy, cz, record3);
}

static int parse_x3p_bytes(const unsigned char *b, size_t n, surface *s, char *err, size_t errn)
{
    surface_read_options o = {SURFACE_HEIGHTS, 0};
    return surface_parse(SURFACE_X3P, b, n, &o, s, err, errn);
}

/* The layouts the standard allows, and every damaged or lying archive refused with its reason. */
static void x3p_variants(void **state)
{
    (void)state;
    const char *inc = "<AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment><Offset>0</Offset>";
    char xml[4096], err[512];
    size_t n;
    surface s;
    /* inline heights of every DataType, an empty Datum a missing point */
    static const char *const types[4] = {"I", "L", "F", "D"};
    for (int t = 0; t < 4; t++) {
        char cz[200];
        snprintf(cz, sizeof cz,
                 "<AxisType>A</AxisType><DataType>%s</DataType><Increment>%s</Increment>"
                 "<Offset>1</Offset>",
                 types[t], t < 2 ? "0.5" : "1");
        x3p_xml(xml, sizeof xml, "SUR", inc, inc, cz,
                "<MatrixDimension><SizeX>3</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataList>"
                "<Datum>1</Datum><Datum>-2</Datum><Datum/><Datum>4</Datum><Datum> 5 </Datum><Datum>6</Datum>"
                "</DataList>");
        unsigned char *b = zip_members(tmp("inline.x3p"), (const char *[]){"main.xml", NULL}, (const char *[]){xml},
                                       (size_t[]){0}, &n);
        CHECK(parse_x3p_bytes(b, n, &s, err, sizeof err) == 0, "DataType %s inline: %s", types[t], err);
        double k = t < 2 ? 0.5 : 1.0;
        CHECK(s.nx == 3 && s.ny == 2 && s.h[0] == 1 + k && s.h[1] == 1 - 2 * k && isnan(s.h[2]) && s.h[5] == 1 + 6 * k,
              "DataType %s inline: %g %g %g", types[t], s.h[0], s.h[1], s.h[2]);
        surface_free(&s);
        free(b);
    }
    /* an integer out of its type's range, and a Datum of two values where one is due */
    x3p_xml(xml, sizeof xml, "SUR", inc, inc, "<AxisType>A</AxisType><DataType>I</DataType>",
            "<MatrixDimension><SizeX>2</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataList>"
            "<Datum>1</Datum><Datum>40000</Datum><Datum>1</Datum><Datum>1</Datum></DataList>");
    unsigned char *b = zip_members(tmp("bad.x3p"), (const char *[]){"main.xml", NULL}, (const char *[]){xml},
                                   (size_t[]){0}, &n);
    refuse(SURFACE_X3P, (const char *)b, n, SURFACE_HEIGHTS, "Datum 2 is not 1 value");
    free(b);
    /* an absolute x axis: regular (decreasing, so mirrored) read, irregular refused; main.xml in a folder */
    const char *absx = "<AxisType>A</AxisType><DataType>D</DataType><Offset>0</Offset>";
    const char *zd = "<AxisType>A</AxisType><DataType>D</DataType>";
    x3p_xml(xml, sizeof xml, "SUR", absx, inc, zd,
            "<MatrixDimension><SizeX>3</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataList>"
            "<Datum>4e-6;1</Datum><Datum>2e-6;2</Datum><Datum>0;3</Datum><Datum>4e-6;4</Datum><Datum/>"
            "<Datum>0;6</Datum></DataList>");
    b = zip_members(tmp("absx.x3p"), (const char *[]){"scan/main.xml", NULL}, (const char *[]){xml}, (size_t[]){0}, &n);
    CHECK(parse_x3p_bytes(b, n, &s, err, sizeof err) == 0, "absolute x: %s", err);
    CHECK(fabs(s.dx - 2e-6) < 1e-18 && s.h[0] == 3 && s.h[2] == 1 && s.h[3] == 6 && isnan(s.h[4]),
          "absolute x: dx %g, %g %g %g", s.dx, s.h[0], s.h[2], s.h[3]);
    surface_free(&s);
    free(b);
    x3p_xml(xml, sizeof xml, "SUR", absx, inc, zd,
            "<MatrixDimension><SizeX>3</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataList>"
            "<Datum>0;1</Datum><Datum>1e-6;2</Datum><Datum>3e-6;3</Datum><Datum>0;4</Datum><Datum>1e-6;5</Datum>"
            "<Datum>3e-6;6</Datum></DataList>");
    b = zip_members(tmp("irr.x3p"), (const char *[]){"main.xml", NULL}, (const char *[]){xml}, (size_t[]){0}, &n);
    refuse(SURFACE_X3P, (const char *)b, n, SURFACE_HEIGHTS, "absolute CX axis is irregular");
    free(b);
    /* main.xml in two folders, a profile, a list */
    b = zip_members(tmp("two.x3p"), (const char *[]){"a/main.xml", "b/main.xml", NULL}, (const char *[]){xml, xml},
                    (size_t[]){0, 0}, &n);
    refuse(SURFACE_X3P, (const char *)b, n, SURFACE_HEIGHTS, "more than one folder");
    free(b);
    x3p_xml(xml, sizeof xml, "PRF", inc, inc, zd,
            "<MatrixDimension><SizeX>3</SizeX><SizeY>1</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataList>"
            "<Datum>1</Datum><Datum>2</Datum><Datum>3</Datum></DataList>");
    b = zip_members(tmp("prf.x3p"), (const char *[]){"main.xml", NULL}, (const char *[]){xml}, (size_t[]){0}, &n);
    refuse(SURFACE_X3P, (const char *)b, n, SURFACE_HEIGHTS, "FeatureType PRF is a profile");
    free(b);
    /* binary data: XML lying about the size, and wrong MD5s */
    double pts[6] = {1, 2, 3, 4, 5, 6};
    x3p_xml(xml, sizeof xml, "SUR", inc, inc, zd,
            "<MatrixDimension><SizeX>3</SizeX><SizeY>3</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataLink>"
            "<PointDataLink>bindata/data.bin</PointDataLink></DataLink>");
    b = zip_members(tmp("lie.x3p"), (const char *[]){"main.xml", "bindata/data.bin", NULL},
                    (const char *[]){xml, (const char *)pts}, (size_t[]){0, sizeof pts}, &n);
    refuse(SURFACE_X3P, (const char *)b, n, SURFACE_HEIGHTS, "holds 48 bytes, not the 72");
    free(b);
    x3p_xml(xml, sizeof xml, "SUR", inc, inc, zd,
            "<MatrixDimension><SizeX>3</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataLink>"
            "<PointDataLink>bindata/data.bin</PointDataLink>"
            "<MD5ChecksumPointData>00000000000000000000000000000000</MD5ChecksumPointData></DataLink>");
    b = zip_members(tmp("md5d.x3p"), (const char *[]){"main.xml", "bindata/data.bin", NULL},
                    (const char *[]){xml, (const char *)pts}, (size_t[]){0, sizeof pts}, &n);
    refuse(SURFACE_X3P, (const char *)b, n, SURFACE_HEIGHTS, "MD5ChecksumPointData");
    free(b);
    b = zip_members(tmp("md5x.x3p"), (const char *[]){"main.xml", "md5checksum.hex", NULL},
                    (const char *[]){xml, "0123456789abcdef0123456789abcdef *main.xml\n"}, (size_t[]){0, 0}, &n);
    refuse(SURFACE_X3P, (const char *)b, n, SURFACE_HEIGHTS, "main.xml's MD5 is");
    free(b);
    /* a written archive with main.xml's CRC flipped, in its local header and the central directory alike */
    surface h = heights();
    CHECK(surface_write(tmp("crc.x3p"), SURFACE_X3P, &h, 0, NULL, err, sizeof err) == 0, "%s", err);
    surface_free(&h);
    char *c = slurp(tmp("crc.x3p"), &n);
    CHECK(parse_x3p_bytes((unsigned char *)c, n, &s, err, sizeof err) == 0, "written x3p: %s", err);
    surface_free(&s);
    int flipped = 0;
    for (size_t i = 0; i + 46 < n; i++) {
        if (memcmp(c + i, "PK\x03\x04", 4) == 0 && memcmp(c + i + 30, "main.xml", 8) == 0) c[i + 14] ^= 1, flipped++;
        if (memcmp(c + i, "PK\x01\x02", 4) == 0 && memcmp(c + i + 46, "main.xml", 8) == 0) c[i + 16] ^= 1, flipped++;
    }
    CHECK(flipped == 2, "main.xml's headers: %d", flipped);
    refuse(SURFACE_X3P, c, n, SURFACE_HEIGHTS, "CRC");
    free(c);
}
#endif

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/ggx-surface-XXXXXX");
    if (!mkdtemp(dir)) return 1;
    const struct CMUnitTest tests[] = {cmocka_unit_test(height_round_trips), cmocka_unit_test(normal_round_trips),
                                       cmocka_unit_test(malformed),          cmocka_unit_test(gwyddion_text_header),
                                       cmocka_unit_test(quantisation),       cmocka_unit_test(x3p_public),
                                       cmocka_unit_test(absurd_height),
#ifdef HAVE_PNG
                                       cmocka_unit_test(png_grey_depths),
#endif
#ifdef HAVE_ZIP
                                       cmocka_unit_test(x3p_variants)
#endif
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    char cmd[96];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) rc = 1;
    return rc;
}
