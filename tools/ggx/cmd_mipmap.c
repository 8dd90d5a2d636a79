/* ggx mipmap: a tangent-space normal map filtered into a chain of per-texel ellipsoids (ggx_filter.h), one OpenEXR
 * file per level holding each texel's slope location t, scale Sigma and weight. SPDX-License-Identifier: MIT */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "ggx/ggx_filter.h"
#include "surface.h"

static const char *const CHANNELS[GGX_LOBE_PARAMS + 1] = {"t.x", "t.y", "sigma.xx", "sigma.xy", "sigma.yy", "weight"};

/* The level's summary: the weighted mean slope location and the weighted mean of det(Sigma)^(1/4), the alpha of the
 * isotropic lobe of the same spread. */
static void summary(const double *lobes, const double *w, size_t count, double t[2], double *alpha)
{
    double W = 0.0;
    t[0] = t[1] = *alpha = 0.0;
    for (size_t i = 0; i < count; i++) {
        const double *c = lobes + GGX_LOBE_PARAMS * i;
        if (w[i] == 0.0) continue;
        W += w[i], t[0] += w[i] * c[0], t[1] += w[i] * c[1];
        *alpha += w[i] * sqrt(sqrt(c[2] * c[4] - c[3] * c[3]));
    }
    if (W > 0.0) t[0] /= W, t[1] /= W, *alpha /= W;
}

static void write_level(const char *path, const double *lobes, const double *w, size_t nx, size_t ny)
{
    size_t count = nx * ny;
    float *plane[GGX_LOBE_PARAMS + 1];
    for (int k = 0; k <= GGX_LOBE_PARAMS; k++)
        if (!(plane[k] = malloc(count * sizeof(float)))) die("out of memory");
    for (size_t i = 0; i < count; i++) {
        for (int k = 0; k < GGX_LOBE_PARAMS; k++) plane[k][i] = (float)lobes[GGX_LOBE_PARAMS * i + k];
        plane[GGX_LOBE_PARAMS][i] = (float)w[i];
    }
    unsigned char *data;
    size_t n;
    char err[256];
    if (surface_encode_exr_channels(nx, ny, GGX_LOBE_PARAMS + 1, CHANNELS, plane, &data, &n, err, sizeof err) != 0)
        die("cannot write '%s': %s", path, err);
    for (int k = 0; k <= GGX_LOBE_PARAMS; k++) free(plane[k]);
    out_write_file(path, data, n);
    free(data);
}

/* The level as two 16-bit PNGs (docs/cli.md states the encoding): the mean normal n = (-t.x, -t.y, 1) / |.| as
 * (n + 1) / 2 in RGB; sqrt(Sigma_xx) / 4, sqrt(Sigma_yy) / 4, (rho + 1) / 2 with rho = Sigma_xy / sqrt(Sigma_xx
 * Sigma_yy), and the weight over the level's box of base texels (4^level) in RGBA. */
static void write_level_png(const char *dir, int level, const double *lobes, const double *w, size_t nx, size_t ny)
{
    size_t count = nx * ny;
    double *pl[7];
    for (int k = 0; k < 7; k++)
        if (!(pl[k] = malloc(count * sizeof(double)))) die("out of memory");
    double box = ldexp(1.0, 2 * level);
    for (size_t i = 0; i < count; i++) {
        const double *c = lobes + GGX_LOBE_PARAMS * i;
        double l = sqrt(1.0 + c[0] * c[0] + c[1] * c[1]), sx = sqrt(c[2]), sy = sqrt(c[4]);
        pl[0][i] = 0.5 * (1.0 - c[0] / l), pl[1][i] = 0.5 * (1.0 - c[1] / l), pl[2][i] = 0.5 * (1.0 + 1.0 / l);
        pl[3][i] = sx / 4.0, pl[4][i] = sy / 4.0, pl[5][i] = 0.5 * (1.0 + c[3] / (sx * sy)), pl[6][i] = w[i] / box;
    }
    char err[256];
    for (int part = 0; part < 2; part++) {
        char *path = alloc_printf("%s/level-%d-%s.png", dir, level, part ? "sigma" : "normal");
        out_file out;
        out_open(&out, path);
        const double *const *planes = (const double *const *)(pl + (part ? 3 : 0));
        if (surface_write_png_channels(out.f, nx, ny, part ? 4 : 3, planes, err, sizeof err) != 0)
            die("cannot write '%s': %s", path, err);
        out_close(&out);
        free(path);
    }
    for (int k = 0; k < 7; k++) free(pl[k]);
}

double *roughness_map_read(const options *o, size_t nx, size_t ny)
{
    surface_read_options rr = {SURFACE_HEIGHTS, 0};
    surface r;
    char err[512];
    if (surface_read(o->roughness_map, &rr, &r, err, sizeof err) != 0) die("--roughness-map: %s", err);
    if (r.format == SURFACE_EXR && r.channels > 1)
        die("--roughness-map %s: %d channels: give a one-channel OpenEXR or a grey PNG", o->roughness_map, r.channels);
    if (r.nx != nx || r.ny != ny)
        die("--roughness-map %s: %zu x %zu texels, the normal map %zu x %zu", o->roughness_map, r.nx, r.ny, nx, ny);
    double scale = r.bits ? 1.0 / (ldexp(1.0, r.bits) - 1.0) : 1.0; /* PNG levels to [0, 1] */
    for (size_t i = 0; i < nx * ny; i++) {
        double v = r.h[i] * scale;
        r.h[i] = o->perceptual && v >= 0.0 ? v * v : v; /* a negative value stays negative: rejected */
    }
    double *alpha = r.h;
    r.h = NULL;
    surface_free(&r);
    return alpha;
}

/* The file names of the chain's levels in format png16 or exr: "level-K" then each suffix. */
static const char *const PNG16_SUFFIXES[] = {"-normal.png", "-sigma.png", NULL};
static const char *const EXR_SUFFIXES[] = {".exr", NULL};

/* The level K of a name of the chain's pattern ("level-K" in decimal without leading zeros, then one of the
 * suffixes, exactly as the command writes them), else -1. */
static long level_of_name(const char *name, const char *const *suffixes)
{
    if (strncmp(name, "level-", 6) != 0) return -1;
    const char *d = name + 6;
    size_t digits = strspn(d, "0123456789");
    if (digits == 0 || digits > 9 || (d[0] == '0' && digits > 1)) return -1;
    for (int i = 0; suffixes[i]; i++)
        if (strcmp(d + digits, suffixes[i]) == 0) return strtol(d, NULL, 10);
    return -1;
}

/* Removes from dir the files of the chain's own names (suffixes) at levels from levels on: what an earlier, longer
 * chain left, which would otherwise read as part of this one. Files of other names, and of the other format, stay.
 * Returns how many it removed; dies when one cannot be removed. */
static int remove_stale_levels(const char *dir, int levels, const char *const *suffixes)
{
    DIR *d = opendir(dir);
    if (!d) die("cannot read output folder '%s': %s", dir, strerror(errno));
    int removed = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (level_of_name(e->d_name, suffixes) < levels) continue;
        char *path = alloc_printf("%s/%s", dir, e->d_name);
        struct stat st;
        if (lstat(path, &st) == 0 && (S_ISREG(st.st_mode) || S_ISLNK(st.st_mode))) {
            if (unlink(path) != 0) die("cannot remove '%s' of an earlier chain: %s", path, strerror(errno));
            removed++;
        }
        free(path);
    }
    closedir(d);
    return removed;
}

void mipmap_help(void)
{
    printf("usage: ggx mipmap --normal-map FILE (--alpha A[,AY] | --roughness-map FILE [--perceptual]) [--fast]\n"
           "                  [--y-down] [--threads N] [--out DIR] [--format exr|png16]\n\n"
           "Filters a tangent-space normal map (PNG 8 or 16 bit, RGB or two channels with z rebuilt; OpenEXR R,\n"
           "G[, B]) of base roughness A (or AX along x, AY along y), or of a roughness per texel from a grey PNG\n"
           "(level / (2^bits - 1)) or a one-channel OpenEXR of the normal map's size (--perceptual: the map holds\n"
           "r and alpha = r^2, as glTF and Disney maps do; 0 is raised to 1e-4; a negative or NaN value rejects\n"
           "its texel), into a mip chain of ellipsoids, with no\n"
           "shading normal left: each texel of level 0 is the GGX lobe of A translated to its normal's slope (a\n"
           "skewed ellipsoid, exactly), and each texel of a coarser level the ellipsoid closest (least KL\n"
           "divergence) to the mixture of its 2 x 2 texels above, by ggx_filter_downsample (odd sizes: the last\n"
           "column or row filters 2 x 1, 1 x 2 or 1 x 1 boxes). A texel whose normal is NaN, zero or not above\n"
           "the tangent plane is rejected: weight 0, counted nowhere (an RGB PNG whose blue is 0 everywhere is\n"
           "read as two channels, z rebuilt); a map of rejected texels only is an error. --y-down: the green\n"
           "channel points down\n"
           "(DirectX maps). Writes DIR/level-K.exr (default DIR: mipmap) for K = 0 to the 1 x 1 level, each\n"
           "with the float channels t.x, t.y (the slope location: the mean normal is (-t.x, -t.y, 1)\n"
           "normalised), sigma.xx, sigma.xy, sigma.yy (the slope scale, as ggx_shape_from_slopes takes them)\n"
           "and weight (the texels behind the texel), all files or none. --format png16 writes instead\n"
           "DIR/level-K-normal.png (RGB: the mean normal n = (-t.x, -t.y, 1) normalised, as (n + 1) / 2) and\n"
           "DIR/level-K-sigma.png (RGBA: sqrt(sigma.xx) / 4, sqrt(sigma.yy) / 4, (rho + 1) / 2 with rho =\n"
           "sigma.xy / sqrt(sigma.xx sigma.yy), weight / 4^K), 16 bits each (widths above 4 saturate). Prints per\n"
           "level its size, the mean slope location, the mean det(Sigma)^(1/4) (the alpha of an isotropic\n"
           "lobe as wide) and the time. --fast: one EM step over 2 x 4 nodes per lobe (ggx_filter.h's fast mode:\n"
           "30 to 80 times faster, at most about 0.005 nats of KL given up on the tests' footprints).\n"
           "A folder DIR that the command makes is removed again if the run fails or is ended by a signal. In the\n"
           "folder of an earlier, longer chain, that chain's deeper levels in the format written (the command's\n"
           "own names only) are removed once the new chain is complete.\n");
}

int cmd_mipmap(options *o, const ggx_shape *no_shape)
{
    (void)no_shape;
    if (!o->normal_map) die("--normal-map FILE is required");
    if (o->have_alpha == !!o->roughness_map)
        die("give the base roughness as one of --alpha A[,AY] or --roughness-map FILE");
    if (o->perceptual && !o->roughness_map) die("--perceptual applies to --roughness-map");
    int png16 = o->format && strcmp(o->format, "png16") == 0;
    if (o->format && !png16 && strcmp(o->format, "exr") != 0) die("--format: '%s' is not exr or png16", o->format);
    double none_d[GGX_LOBE_PARAMS];
    ggx_vec3 none_v = {0.0, 0.0, 1.0};
    ggx_status st = GGX_OK;
    if (o->have_alpha) st = ggx_texel_lobes(none_d, none_d, &none_v, 0, o->alpha[0], o->alpha[1], 0.0, NULL);
    if (st != GGX_OK) die("--alpha: %s", ggx_status_str(st)); /* before the map is read */
    surface_read_options ro = {SURFACE_NORMALS, o->y_down};
    surface s;
    char err[512];
    if (surface_read(o->normal_map, &ro, &s, err, sizeof err) != 0) die("%s", err);
    if (s.ny < 1 || s.nx < 1 || (s.ny == 1 && s.format == SURFACE_CSV)) die("%s: not a normal map", o->normal_map);
    size_t nx = s.nx, ny = s.ny, count = nx * ny;
    double *lobes = malloc(count * GGX_LOBE_PARAMS * sizeof *lobes), *w = malloc(count * sizeof *w);
    double *next = malloc(((nx + 1) / 2) * ((ny + 1) / 2) * GGX_LOBE_PARAMS * sizeof *next);
    double *wn = malloc(((nx + 1) / 2) * ((ny + 1) / 2) * sizeof *wn);
    if (!lobes || !w || !next || !wn) die("out of memory");
    size_t rejected;
    if (o->roughness_map) {
        double *alpha = roughness_map_read(o, nx, ny);
        st = ggx_texel_lobes_roughness(lobes, w, s.m, alpha, NULL, count, 0.0, &rejected);
        free(alpha);
    } else {
        st = ggx_texel_lobes(lobes, w, s.m, count, o->alpha[0], o->alpha[1], 0.0, &rejected);
    }
    if (st != GGX_OK || rejected == count) /* the buffers freed first: a leak checker sees none on this way out */
        free(lobes), free(w), free(next), free(wn), surface_free(&s);
    if (st != GGX_OK) die("--alpha: %s", ggx_status_str(st));
    if (rejected == count)
        die("%s: every texel is rejected (its normal NaN, zero or not above the tangent plane%s): no chain to filter",
            o->normal_map, o->roughness_map ? ", or its roughness negative or NaN" : "");
    surface_free(&s);
    const char *dir = o->out ? o->out : "mipmap";
    ensure_dir(dir); /* a folder it makes goes again, when empty, on an error or a signal before the chain is whole */
    ggx_filter_options fo = {0};
    fo.threads = o->threads > 0 ? o->threads : 1;
    if (o->fast) ggx_filter_options_fast(&fo);
    char rough[600];
    if (o->roughness_map)
        snprintf(rough, sizeof rough, "roughness %s%s", o->roughness_map, o->perceptual ? " (perceptual)" : "");
    else snprintf(rough, sizeof rough, "alpha %g, %g", o->alpha[0], o->alpha[1]);
    printf("ggx mipmap: %s, %zu x %zu texels (%zu rejected), %s%s, into %s/\n", o->normal_map, nx, ny, rejected, rough,
           o->fast ? ", fast mode" : "", dir);
    printf("| level | size | mean t | mean det(Sigma)^(1/4) | seconds to the next |\n|---|---|---|---|---|\n");
    out_begin_set(); /* every level or none */
    int levels = 0;
    for (int level = 0;; level++) {
        levels++;
        if (png16) {
            write_level_png(dir, level, lobes, w, nx, ny);
        } else {
            char *path = alloc_printf("%s/level-%d.exr", dir, level);
            write_level(path, lobes, w, nx, ny);
            free(path);
        }
        double t[2], alpha;
        summary(lobes, w, nx * ny, t, &alpha);
        printf("| %d | %zu x %zu | %.6g, %.6g | %.6g | ", level, nx, ny, t[0], t[1], alpha);
        if (nx == 1 && ny == 1) {
            printf("|\n");
            break;
        }
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        st = ggx_filter_downsample(next, wn, lobes, w, nx, ny, &fo);
        if (st != GGX_OK) die("level %d: %s", level + 1, ggx_status_str(st));
        clock_gettime(CLOCK_MONOTONIC, &t1);
        printf("%.3f |\n", (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
        out_flush_stdout();
        nx = (nx + 1) / 2, ny = (ny + 1) / 2;
        /* the new level becomes the one to filter: both buffers hold any level below the first */
        double *tl = lobes, *tw = w;
        lobes = next, w = wn, next = tl, wn = tw;
    }
    out_commit_set();
    out_keep_dirs(); /* complete: the folder stays */
    int stale = remove_stale_levels(dir, levels, png16 ? PNG16_SUFFIXES : EXR_SUFFIXES);
    if (stale)
        fprintf(stderr,
                "ggx: note: removed %d file%s of levels %d and beyond, left in %s/ by an earlier, longer chain\n",
                stale, stale == 1 ? "" : "s", levels, dir);
    free(lobes), free(w), free(next), free(wn);
    return 0;
}
