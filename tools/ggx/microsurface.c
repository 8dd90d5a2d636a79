/* ggx microsurface: height fields with a chosen NDF (lab/microsurface), written as OpenEXR or x3p for ggx fit and the
 * tracer. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "microsurface.h"
#include "surface.h"

static void write_heights(const char *path, double *h, size_t n)
{
    surface s;
    memset(&s, 0, sizeof s);
    s.kind = SURFACE_HEIGHTS, s.nx = n, s.ny = n, s.h = h;
    size_t len = strlen(path);
    int x3p = len >= 4 && strcmp(path + len - 4, ".x3p") == 0;
    /* x3p in metres: a grid of 1 micrometre, heights in the same unit, so slopes are the field's; OpenEXR as is */
    if (x3p) s.dx = s.dy = 1e-6, s.z_scale = 1e-6;
    if (!x3p && !(len >= 4 && strcmp(path + len - 4, ".exr") == 0)) die("--out '%s': give a .exr or .x3p name", path);
    unsigned char *data;
    size_t bytes;
    char err[400];
    int rc = x3p ? surface_encode_x3p(&s, &data, &bytes, err, sizeof err)
                 : surface_encode_exr(&s, &data, &bytes, err, sizeof err);
    if (rc != 0) die("cannot write '%s': %s", path, err);
    out_file f;
    out_open(&f, path);
    if (fwrite(data, 1, bytes, f.f) != bytes) out_check(&f);
    out_close(&f);
    free(data);
}

static int generate(int argc, char **argv)
{
    options o;
    parse_options(argc, argv, 3, &o, "kind,alpha,rotate,corr,period,size,seed,out");
    if (o.help) {
        printf("usage: ggx microsurface generate --kind beckmann|vgroove [--alpha A[,AY]] [--rotate TZ] [--corr L]\n"
               "                                 [--period P] --size N [--seed S] --out FILE.exr|FILE.x3p\n\n"
               "A periodic height field on an N x N grid of unit spacing (N even, 64 to 4096), whose facets (both\n"
               "triangulations of each cell, as ggx fit reads them) have a chosen NDF:\n"
               "  beckmann  a Gaussian random field: every facet's slope is Gaussian with covariance\n"
               "            R diag(AX^2, AY^2) R^T / 2 (Beckmann of roughness AX, AY, the axes rotated by TZ degrees),\n"
               "            its autocorrelation Gaussian with correlation length L grid spacings (default 16;\n"
               "            4 to N / 4), by FFT (KISS FFT); --seed S picks the field (default 1)\n"
               "  vgroove   V-grooves along y of period P spacings (even, default 16) and slope AX along x: two\n"
               "            facet normals, each on half the area (Torrance-Sparrow's V-cavities)\n"
               "OpenEXR holds the heights in one float channel Y (ggx fit --heightfield needs --spacing 1 --z-scale\n"
               "1 for it); x3p in doubles with a grid of 1e-6 m and heights in metres. Prints the surface's\n"
               "parameters: the heights' standard deviation and the autocorrelation's metric M, C(r) = sigma^2\n"
               "exp(-r^T M r).\n");
        return 0;
    }
    if (!o.kind) die("--kind beckmann|vgroove is required");
    if (!o.size) die("--size N is required");
    if (!o.out) die("--out FILE.exr|FILE.x3p is required");
    size_t n = (size_t)o.size;
    if (o.size_h && o.size_h != o.size) die("--size: a square grid, N");
    if (n % 2 != 0) die("--size %zu: an even size", n);
    double *h = malloc(n * n * sizeof *h);
    if (!h) die("out of memory for %zu x %zu heights", n, n);
    char err[400];
    if (strcmp(o.kind, "beckmann") == 0) {
        if (o.period) die("--period applies to --kind vgroove");
        ms_gauss_spec sp = {n, o.alpha[0], o.alpha[1], o.rotate * 3.14159265358979323846 / 180.0,
                            o.corr > 0 ? o.corr : 16.0, o.seed};
        if (!o.have_alpha) sp.alpha_x = sp.alpha_y = 0.3;
        ms_gauss_info info;
        if (ms_gauss(&sp, h, &info, err, sizeof err) != 0) die("%s", err);
        write_heights(o.out, h, n);
        printf("ggx microsurface: %s, %zu x %zu, Beckmann alpha %g, %g rotated %g degrees, correlation length %g: "
               "heights' sigma %.6g, M = [%.6g %.6g; %.6g %.6g], seed %llu\n",
               o.out, n, n, sp.alpha_x, sp.alpha_y, o.rotate, sp.corr_len, info.sigma, info.metric[0],
               info.metric[1], info.metric[1], info.metric[2], (unsigned long long)o.seed);
    } else if (strcmp(o.kind, "vgroove") == 0) {
        if (o.corr > 0 || o.have_rotate) die("--corr and --rotate apply to --kind beckmann");
        if (o.have_alpha && o.alpha[0] != o.alpha[1]) die("--alpha: a V-groove has one slope");
        double slope = o.have_alpha ? o.alpha[0] : 0.5;
        size_t p = o.period ? (size_t)o.period : 16;
        if (ms_vgroove(n, p, slope, h, err, sizeof err) != 0) die("%s", err);
        write_heights(o.out, h, n);
        printf("ggx microsurface: %s, %zu x %zu, V-grooves of period %zu and slope %g (facet normals at %.6g "
               "degrees)\n", o.out, n, n, p, slope, atan(slope) * 180.0 / 3.14159265358979323846);
    } else {
        die("--kind: unknown kind '%s' (beckmann, vgroove)", o.kind);
    }
    free(h);
    return 0;
}

int cmd_microsurface(int argc, char **argv)
{
    if (argc < 3 || strcmp(argv[2], "--help") == 0 || strcmp(argv[2], "-h") == 0) {
        printf("usage: ggx microsurface generate [options]   (ggx microsurface generate --help)\n\n"
               "Microsurfaces with a chosen NDF, to check the model against geometry: generate writes a periodic\n"
               "height field (a Gaussian random field of Beckmann facets, or V-grooves) as OpenEXR or x3p, which\n"
               "ggx fit reads.\n");
        if (argc < 3) die("give a subcommand: generate");
        return 0;
    }
    if (strcmp(argv[2], "generate") == 0) return generate(argc, argv);
    die("microsurface: unknown subcommand '%s' (generate)", argv[2]);
    return 2;
}
