/* Benchmark of the normal-map filter (include/ggx/ggx_filter.h): ggx_filter_lobes on a 2 x 2 footprint of a bump map
 * (the box of one mip level) for several rules and tolerances, the lobes filtered per second, what a 4096 x 4096
 * map's chain would take at that rate (each level from the one above, 4096^2 / 3 footprints), and each setting's
 * error against 64 x 128 nodes at 1e-12; then a 512 x 512 map's whole chain by ggx_filter_downsample on 1 and 2
 * threads. Prints; never fails. SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ggx/ggx_filter.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The largest change between two shapes' (t, Sigma) in the second's scale, as the filter's tolerance measures. */
static double change(const ggx_shape *a, const ggx_shape *b)
{
    double ta[2], sa[3], tb[2], sb[3];
    ggx_shape_slopes(a, ta, sa), ggx_shape_slopes(b, tb, sb);
    double e = fmax(fabs(ta[0] - tb[0]) / sqrt(sb[0]), fabs(ta[1] - tb[1]) / sqrt(sb[2]));
    e = fmax(e, fmax(fabs(sa[0] - sb[0]) / sb[0], fabs(sa[2] - sb[2]) / sb[2]));
    return fmax(e, fabs(sa[1] - sb[1]) / sqrt(sb[0] * sb[2]));
}

int main(void)
{
    enum { FOOTPRINTS = 64 };
    ggx_shape lobes[FOOTPRINTS][4];
    for (int f = 0; f < FOOTPRINTS; f++) /* 2 x 2 texels of waves, alpha from 0.05 to 0.5 */
        for (int i = 0; i < 4; i++) {
            double x = f * 2 + i % 2, y = i / 2, gx = 0.2 * cos(0.7 * x + 1.3 * y), gy = 0.2 * sin(1.1 * x - 0.4 * y);
            ggx_vec3 n = {-gx, -gy, 1};
            ggx_texel_lobe(&lobes[f][i], n, 0.05 + 0.45 * f / (FOOTPRINTS - 1), 0.05 + 0.45 * f / (FOOTPRINTS - 1), 0);
        }
    ggx_shape ref[FOOTPRINTS];
    ggx_filter_options fine = {0};
    fine.radial_nodes = 64, fine.angular_nodes = 128, fine.tolerance = 1e-12;
    for (int f = 0; f < FOOTPRINTS; f++) ggx_filter_lobes(&ref[f], lobes[f], NULL, 4, &fine, NULL);
    const struct {
        int radial, angular;
        double tol;
        int iterations;
    } settings[] = {{8, 16, 0, 0},  {8, 16, 1e-6, 0}, {4, 8, 1e-4, 0}, {2, 4, 1e-3, 0},
                    {16, 32, 0, 0}, {4, 8, 0, 1},     {2, 4, 0, 1},    {2, 4, 0, 2}};
    printf("libggx filter benchmark: ggx_filter_lobes of 2 x 2 texels (alpha 0.05 to 0.5), one thread\n\n");
    printf("%-8s %9s %12s %10s %14s %16s %14s\n", "rule", "tolerance", "iterations", "us/call", "lobes/s",
           "4096^2 chain, s", "error");
    for (size_t k = 0; k < sizeof settings / sizeof settings[0]; k++) {
        ggx_filter_options o = {0};
        o.radial_nodes = settings[k].radial, o.angular_nodes = settings[k].angular, o.tolerance = settings[k].tol;
        o.max_iterations = settings[k].iterations;
        double best = 1e30, err = 0.0;
        long its = 0;
        for (int rep = 0; rep < 5; rep++) {
            double t0 = now();
            its = 0;
            for (int f = 0; f < FOOTPRINTS; f++) {
                ggx_shape out;
                ggx_filter_info info;
                ggx_filter_lobes(&out, lobes[f], NULL, 4, &o, &info);
                its += info.iterations;
                if (rep == 0) err = fmax(err, change(&out, &ref[f]));
            }
            best = fmin(best, (now() - t0) / FOOTPRINTS);
        }
        printf("%3dx%-4d %9.0e %12.1f %10.2f %14.3g %16.1f %14.2e\n", settings[k].radial, settings[k].angular,
               settings[k].tol > 0 ? settings[k].tol : 1e-10, (double)its / FOOTPRINTS, best * 1e6, 4.0 / best,
               4096.0 * 4096.0 / 3.0 * best, err);
    }
    /* whole chains: the default rule on 512 x 512 (times 64 for 4096^2), the fast mode on 4096 x 4096 itself */
    printf("\nwhole chains of a map of waves (alpha 0.1), level 0 by ggx_texel_lobes, the rest by "
           "ggx_filter_downsample:\n");
    printf("%-34s %8s %14s %14s %18s\n", "settings", "threads", "level 0, s", "the rest, s", "4096^2 chain, s");
    const struct {
        const char *name;
        int side, radial, angular, iterations;
    } chains[] = {{"default (8x16, 1e-10), 512^2", 512, 0, 0, 0}, {"fast (2x4, 1 iteration), 4096^2", 4096, 2, 4, 1}};
    for (size_t c = 0; c < sizeof chains / sizeof chains[0]; c++) {
        size_t side = (size_t)chains[c].side, count = side * side;
        double *lv = malloc(count * GGX_LOBE_PARAMS * sizeof *lv), *wv = malloc(count * sizeof *wv);
        double *nx = malloc(count * GGX_LOBE_PARAMS * sizeof *nx),
               *wn = malloc(count * sizeof *wn); /* either may hold level 0 */
        ggx_vec3 *nm = malloc(count * sizeof *nm);
        /* written before the clock starts (not with zeros, which the compiler may turn into calloc): the kernel's
         * zeroing of fresh pages is not the filter's time */
        memset(lv, 1, count * GGX_LOBE_PARAMS * sizeof *lv), memset(nx, 1, count * GGX_LOBE_PARAMS * sizeof *nx);
        memset(wv, 1, count * sizeof *wv), memset(wn, 1, count * sizeof *wn);
        for (size_t i = 0; i < count; i++) {
            double x = (double)(i % side), y = (double)(i / side);
            nm[i] = (ggx_vec3){-0.2 * cos(0.3 * x + 0.5 * y), -0.2 * sin(0.4 * x - 0.2 * y), 1};
        }
        for (int threads = 1; threads <= 2; threads++) {
            double t0 = now();
            ggx_texel_lobes(lv, wv, nm, count, 0.1, 0.1, 0.0, NULL);
            double t1 = now();
            ggx_filter_options o = {0};
            o.threads = threads, o.radial_nodes = chains[c].radial, o.angular_nodes = chains[c].angular;
            o.max_iterations = chains[c].iterations;
            size_t w = side, h = side;
            while (w > 1 || h > 1) {
                ggx_filter_downsample(nx, wn, lv, wv, w, h, &o);
                w = (w + 1) / 2, h = (h + 1) / 2;
                double *tl = lv, *tw = wv;
                lv = nx, wv = wn, nx = tl, wn = tw;
            }
            double t2 = now(), scale = 4096.0 * 4096.0 / (double)count;
            printf("%-34s %8d %14.2f %14.2f %18.1f\n", chains[c].name, threads, t1 - t0, t2 - t1, (t2 - t0) * scale);
        }
        free(lv), free(wv), free(nx), free(wn), free(nm);
    }
    return 0;
}
